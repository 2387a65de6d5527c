//! Inside the contact: pressure and gap profiles of one state under Maugis-Dugdale and, at the
//! same load, Hertz, DMT and JKR; the stress intensity and energy release rate at the contact
//! edge; the largest tensile stress. Units as in [`crate::physics::fields`], or SI for a scene.

use crate::physics::closed::{dmt_radius, hertz_radius, jkr_approach, jkr_radius};
use crate::physics::fields::{
    energy_release_over_w, hertz_gap, hertz_pressure, jkr_gap, jkr_pressure, jkr_stress_intensity,
    MdGeometry,
};
use crate::physics::model::ContactModel;
use crate::physics::params::Contact;
use crate::solver::{LambdaContext, SolveError, Status};
use serde::Serialize;

pub mod spec;
pub mod tip;
pub mod two_zone;

/// What fixes the Maugis-Dugdale state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Given {
    /// The load Pbar (the stable branch under load control).
    Load(f64),
    /// The approach Dbar (the stable branch under displacement control).
    Approach(f64),
    /// The contact radius A (any point of the curve).
    Radius(f64),
}

impl Given {
    /// What it fixes and its value.
    pub fn split(self) -> (crate::law::Given, f64) {
        match self {
            Given::Load(p) => (crate::law::Given::Load, p),
            Given::Approach(d) => (crate::law::Given::Approach, d),
            Given::Radius(a) => (crate::law::Given::Radius, a),
        }
    }
}

/// Whether a model of a profile has a state at its load.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ProfileStatus {
    /// The model has a state: the arrays are filled.
    Ok,
    /// The load is below this model's pull-off: no contact, empty arrays.
    NoContact,
}

/// The profile of one model.
#[derive(Clone, Debug, Serialize)]
pub struct ModelProfile {
    /// The model: Maugis-Dugdale, the two-zone law ([`ContactModel::SolidAndMeniscus`]), Hertz,
    /// DMT or JKR. Written as [`ModelProfile::model_name`].
    #[serde(serialize_with = "serialize_model")]
    pub model: ContactModel,
    /// `ok`, or `no_contact` where the load is below this model's pull-off (empty arrays).
    pub status: ProfileStatus,
    /// Contact radius.
    pub a: Option<f64>,
    /// Outer radius of the zone where the surface forces act (MD: the Dugdale zone; Hertz and
    /// JKR: the contact radius; DMT: unbounded, null).
    pub c: Option<f64>,
    /// The load of the state.
    pub load: f64,
    /// The approach of the state (null where the model has none at that load).
    pub approach: Option<f64>,
    /// The sampling radii (clustered at the edges).
    pub r: Vec<f64>,
    /// Compressive positive; null where the stress is singular (JKR at r = a).
    pub pressure: Vec<Option<f64>>,
    /// The surface gap at each radius (0 inside the contact).
    pub gap: Vec<f64>,
    /// The largest tensile stress and the radii where it acts; null where it is unbounded.
    pub max_tension: Option<f64>,
    /// The radii (inner, outer) of the largest tension.
    pub max_tension_at: Option<(f64, f64)>,
    /// Stress intensity factor at r = a (0 where the stress is bounded, as in MD).
    pub stress_intensity: Option<f64>,
    /// Energy release rate at the contact edge over w (JKR: from K_I; MD: the J-integral through
    /// the Dugdale zone, Dugdale stress times the gap at r = c). 1 at equilibrium.
    pub energy_release_rate_over_w: Option<f64>,
    /// Where the model is stretched at this state.
    pub notes: Vec<String>,
}

/// A profile's model by its name in JSON and CSV.
fn serialize_model<S: serde::Serializer>(m: &ContactModel, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(profile_model_name(*m))
}

/// The name of a profile's model: [`ContactModel::name`], except `two_zone` for the two-zone
/// law (the name profiles have always written).
fn profile_model_name(m: ContactModel) -> &'static str {
    match m {
        ContactModel::SolidAndMeniscus => "two_zone",
        m => m.name(),
    }
}

impl ModelProfile {
    /// The model's name in JSON and CSV: `md`, `two_zone`, `hertz`, `dmt` or `jkr`.
    pub fn model_name(&self) -> &'static str {
        profile_model_name(self.model)
    }

    /// Into SI units: lengths by `fr`, forces by `ff`, approaches and gaps by `fd`, stresses by
    /// `fp` (the stress intensity by `fp sqrt(fr)`).
    pub(crate) fn scale(&mut self, fr: f64, ff: f64, fd: f64, fp: f64) {
        self.a = self.a.map(|x| x * fr);
        self.c = self.c.map(|x| x * fr);
        self.load *= ff;
        self.approach = self.approach.map(|x| x * fd);
        self.r.iter_mut().for_each(|x| *x *= fr);
        self.pressure.iter_mut().flatten().for_each(|x| *x *= fp);
        self.gap.iter_mut().for_each(|x| *x *= fd);
        self.max_tension = self.max_tension.map(|x| x * fp);
        self.max_tension_at = self.max_tension_at.map(|(a, b)| (a * fr, b * fr));
        self.stress_intensity = self.stress_intensity.map(|x| x * fp * fr.sqrt());
    }
}

/// A state's pressure and gap for Maugis-Dugdale beside Hertz, DMT and JKR at the same load.
#[derive(Clone, Debug, Serialize)]
pub struct Profile {
    /// The Maugis parameter.
    pub lambda: f64,
    /// `normalised` (Johnson-Greenwood units) or `SI` (m, Pa, N).
    pub units: &'static str,
    /// Dugdale range h0 = 2/(pi lambda) in the gap's unit.
    pub dugdale_range: f64,
    /// Dugdale stress lambda/2 in the pressure's unit.
    pub dugdale_stress: f64,
    /// The models' profiles, Maugis-Dugdale first.
    pub models: Vec<ModelProfile>,
    /// Where the state is outside what the models assume (SI profiles: a/R above 0.1).
    pub warnings: Vec<String>,
}

const EDGE_PER_DECADE: i32 = 12;

/// The sampling radii: `n` uniform points to `r_max`, and clusters on both sides of every
/// radius in `edges`, where the fields change fastest.
pub(crate) fn radii(r_max: f64, n: usize, edges: &[f64]) -> Vec<f64> {
    let mut r: Vec<f64> = (0..n).map(|i| r_max * i as f64 / (n - 1) as f64).collect();
    for &e in edges
        .iter()
        .filter(|e| e.is_finite() && **e > 0.0 && **e < r_max)
    {
        r.push(e);
        // Geometric steps, EDGE_PER_DECADE a decade from 1e-1 to 1e-9 of the radius: the
        // pressure rises like a square root from the contact edge, and a trapezoid over the
        // printed profile then recovers the load to 1e-4 of the cohesive zone's force.
        for k in EDGE_PER_DECADE..=9 * EDGE_PER_DECADE {
            let d = 10f64.powf(-(k as f64) / EDGE_PER_DECADE as f64);
            r.push(e * (1.0 - d));
            if e * (1.0 + d) < r_max {
                r.push(e * (1.0 + d));
            }
        }
    }
    r.sort_by(|a, b| a.total_cmp(b));
    r.dedup();
    r
}

fn no_contact(model: ContactModel, load: f64, why: &str) -> ModelProfile {
    ModelProfile {
        model,
        status: ProfileStatus::NoContact,
        a: None,
        c: None,
        load,
        approach: None,
        r: Vec::new(),
        pressure: Vec::new(),
        gap: Vec::new(),
        max_tension: None,
        max_tension_at: None,
        stress_intensity: None,
        energy_release_rate_over_w: None,
        notes: vec![why.to_string()],
    }
}

/// The most points a profile samples per model.
pub const MAX_PROFILE_POINTS: usize = 100_000;

/// The profiles of the MD state fixed by `given` and of Hertz, DMT and JKR at its load, sampled
/// at about `points` radii.
pub fn profile(lambda: f64, given: Given, points: usize) -> Result<Profile, ProfileError> {
    if !(16..=MAX_PROFILE_POINTS).contains(&points) {
        return Err(ProfileError::Points(points));
    }
    let ctx = LambdaContext::new(lambda)?;
    let (a, load, approach, m_minus_1, status) = match given {
        Given::Load(p) => {
            crate::physics::domain::check_load(p)?;
            let s = ctx.solve_load(p);
            (s.a, s.load, s.approach, s.m_minus_1, s.status)
        }
        Given::Approach(d) => {
            crate::physics::domain::check_approach(d)?;
            let s = ctx.solve_approach(d);
            (s.a, s.load, s.approach, s.m_minus_1, s.status)
        }
        Given::Radius(a) => {
            crate::physics::domain::check_radius(a)?;
            let s = ctx.solve_radius(a);
            (s.a, s.load, s.approach, s.m_minus_1, s.status)
        }
    };
    if status != Status::Ok {
        if let Given::Radius(a) = given {
            return Err(ProfileError::RadiusNotFound(a));
        }
        return Err(ProfileError::NoState(status));
    }
    let mu = (m_minus_1 * (m_minus_1 + 2.0)).sqrt();
    let md = MdGeometry { lambda, a, mu };
    let c = md.c();
    // A closed form with zero contact radius (Hertz at zero load) has no contact.
    let nonzero = |a: Option<f64>| a.filter(|&a| a > 0.0);
    let (ah, ad, aj) = (
        nonzero(hertz_radius(load)),
        nonzero(dmt_radius(load)),
        nonzero(jkr_radius(load)),
    );
    let r_max = 1.5
        * [Some(c), ah, ad, aj]
            .iter()
            .flatten()
            .fold(0.0f64, |m, &x| m.max(x));
    let edges: Vec<f64> = [Some(a), Some(c), ah, ad, aj]
        .iter()
        .flatten()
        .copied()
        .collect();
    let mut r = radii(r_max, points, &edges);
    // Inside the contact the pressure turns to the Dugdale stress over a - r ~ a mu^2 / 2,
    // sqrt-like beyond: 80 points a decade from two decades below to three above keep the trapezoid of
    // the printed pressure within 1e-4 of the load.
    let d0 = 0.5 * mu * mu;
    r.extend((-160..=240).filter_map(|k| {
        let d = d0 * 10f64.powf(k as f64 / 80.0);
        (d > 1e-12 && d < 1.0).then_some(a * (1.0 - d))
    }));
    // r = a sin(theta), uniform in theta, makes the Hertz-like sqrt(a^2 - r^2) smooth and
    // resolves the 1/sqrt tail of the turn to the Dugdale stress.
    let n_in = 4 * points;
    r.extend((0..n_in).map(|i| a * (0.5 * std::f64::consts::PI * i as f64 / n_in as f64).sin()));
    r.sort_by(|a, b| a.total_cmp(b));
    r.dedup();

    let h0 = 2.0 / (std::f64::consts::PI * lambda);
    // From mu, not the gap at C: C and A are equal in f64 where lambda is large.
    let j = md.energy_release_over_w();
    let md_profile = ModelProfile {
        model: ContactModel::Md,
        status: ProfileStatus::Ok,
        a: Some(a),
        c: Some(c),
        load,
        approach: Some(approach),
        pressure: r.iter().map(|&x| Some(md.pressure(x))).collect(),
        gap: r.iter().map(|&x| md.gap(x)).collect(),
        r: r.clone(),
        max_tension: Some(0.5 * lambda),
        max_tension_at: Some((a, c)),
        stress_intensity: Some(0.0),
        energy_release_rate_over_w: Some(j),
        notes: vec!["the stress is bounded: the Dugdale stress lambda/2 acts on a < r < c".into()],
    };
    let [hertz, dmt, jkr] = closed_form_models(load, &r);
    Ok(Profile {
        lambda,
        units: "normalised",
        dugdale_range: h0,
        dugdale_stress: 0.5 * lambda,
        models: vec![md_profile, hertz, dmt, jkr],
        warnings: Vec::new(),
    })
}

/// Hertz, DMT and JKR at `load` (normalised), sampled at the radii `r`.
pub(crate) fn closed_form_models(load: f64, r: &[f64]) -> [ModelProfile; 3] {
    let nonzero = |a: Option<f64>| a.filter(|&a| a > 0.0);
    let (ah, ad, aj) = (
        nonzero(hertz_radius(load)),
        nonzero(dmt_radius(load)),
        nonzero(jkr_radius(load)),
    );
    let hertz = match ah {
        Some(ah) => ModelProfile {
            model: ContactModel::Hertz,
            status: ProfileStatus::Ok,
            a: Some(ah),
            c: Some(ah),
            load,
            approach: Some(ah * ah),
            pressure: r.iter().map(|&x| Some(hertz_pressure(ah, x))).collect(),
            gap: r.iter().map(|&x| hertz_gap(ah, x)).collect(),
            r: r.to_vec(),
            max_tension: Some(0.0),
            max_tension_at: None,
            stress_intensity: Some(0.0),
            energy_release_rate_over_w: Some(0.0),
            notes: vec!["no surface forces: no tension anywhere".into()],
        },
        None => no_contact(
            ContactModel::Hertz,
            load,
            "no compressive load: Hertz has no contact",
        ),
    };
    let dmt = match ad {
        Some(ad) => ModelProfile {
            model: ContactModel::Dmt,
            status: ProfileStatus::Ok,
            a: Some(ad),
            c: None,
            load,
            approach: Some(ad * ad),
            pressure: r.iter().map(|&x| Some(hertz_pressure(ad, x))).collect(),
            gap: r.iter().map(|&x| hertz_gap(ad, x)).collect(),
            r: r.to_vec(),
            max_tension: None,
            max_tension_at: None,
            stress_intensity: Some(0.0),
            energy_release_rate_over_w: None,
            notes: vec![
                "Hertzian pressure and profile under the load plus 2 (the adhesive force 2 pi w R acts outside the contact, its distribution not modelled): pressure outside the contact shown as 0".into(),
            ],
        },
        None => no_contact(ContactModel::Dmt, load, "the load is below the DMT pull-off -2"),
    };
    let jkr = match aj {
        Some(aj) => {
            let k = jkr_stress_intensity(aj);
            ModelProfile {
                model: ContactModel::Jkr,
                status: ProfileStatus::Ok,
                a: Some(aj),
                c: Some(aj),
                load,
                approach: Some(jkr_approach(aj)),
                pressure: r
                    .iter()
                    .map(|&x| Some(jkr_pressure(aj, x)).filter(|p| p.is_finite()))
                    .collect(),
                gap: r.iter().map(|&x| jkr_gap(aj, x)).collect(),
                r: r.to_vec(),
                max_tension: None,
                max_tension_at: Some((aj, aj)),
                stress_intensity: Some(k),
                energy_release_rate_over_w: Some(energy_release_over_w(k)),
                notes: vec![
                    "the tension is singular (infinite) at r = a: pressure there is null; see stress_intensity".into(),
                ],
            }
        }
        None => no_contact(
            ContactModel::Jkr,
            load,
            "the load is below the JKR pull-off -3/2",
        ),
    };
    [hertz, dmt, jkr]
}

impl Profile {
    /// The same profile in SI units for a contact: radii in m, pressure in Pa, gap and approach
    /// in m, load in N; the stress intensity in Pa m^(1/2).
    pub fn to_si(&self, c: &Contact) -> Profile {
        let (fr, fd, ff) = (c.radius_scale(), c.approach_scale(), c.force_scale());
        let fp = ff / (fr * fr);
        let mut p = self.clone();
        p.units = "SI";
        // The same small-strain check as a scene's, on the MD contact radius.
        if let Some(a) = p.models.first().and_then(|m| m.a) {
            p.warnings
                .extend(crate::physics::params::small_strain_warning(
                    a * fr / c.radius,
                ));
        }
        p.dugdale_range *= fd;
        p.dugdale_stress *= fp;
        for m in &mut p.models {
            m.scale(fr, ff, fd, fp);
        }
        p
    }
}

/// Why a profile could not be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ProfileError {
    #[error(transparent)]
    /// The solver refused the state.
    Solve(#[from] SolveError),
    #[error(transparent)]
    /// An input outside its domain.
    Domain(#[from] crate::physics::domain::DomainError),
    #[error("the Maugis-Dugdale state is `{}`: no contact there, so no profile (give a load above the pull-off, an approach above the jump-out)", .0.name())]
    /// No contact at the given state.
    NoState(Status),
    #[error("the Maugis-Dugdale state at contact radius A = {0:e} could not be computed (`not_converged`): f64 resolves the curve down to about A = 1e-150; give a larger radius")]
    /// The state at a contact radius was not found.
    RadiusNotFound(f64),
    #[error("points {0} is out of range: give 16..=100000 sampling radii")]
    /// A sampling count out of range.
    Points(usize),
}

impl crate::error::Named for ProfileError {
    fn named(&self, names: crate::error::Names) -> String {
        match self {
            ProfileError::Points(n) => format!(
                "{} {n} is out of range: give 16..=100000 sampling radii",
                names("points").unwrap_or("points")
            ),
            ProfileError::Solve(e) => e.named(names),
            ProfileError::Domain(e) => e.named(names),
            e => e.to_string(),
        }
    }
}
