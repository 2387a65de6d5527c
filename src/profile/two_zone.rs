//! The pressure and gap of a two-zone state (the solid's Dugdale zone and a second one, e.g. a
//! water meniscus; docs/PHYSICS.md section 10), beside Hertz, DMT and JKR of the total w at the
//! same load. Units built on the total w, as in [`crate::solver::two_zone`].

use crate::law::two_zone::{self, ContextError, TwoZones};
use crate::physics::model::ContactModel;
use crate::profile::{
    closed_form_models, radii, Given, ModelProfile, ProfileStatus, MAX_PROFILE_POINTS,
};
use crate::solver::two_zone::TwoZoneState;
use crate::solver::Status;
use serde::Serialize;
use std::f64::consts::PI;

/// The profile of one two-zone state, and the closed forms of the total w at its load.
#[derive(Clone, Debug, Serialize)]
pub struct TwoZoneProfile {
    /// The solid's Maugis parameter (on its own w1), and the second zone's stress and range
    /// over the solid's.
    pub lambda: f64,
    /// The second zone's Dugdale stress over the solid's.
    pub stress_ratio: f64,
    /// The second zone's range over the solid's.
    pub range_ratio: f64,
    /// `normalised` (units of the total w) or `SI`.
    pub units: &'static str,
    /// Each zone's Dugdale stress (pressure unit) and range (gap unit): solid, second zone.
    pub zone_stress: [f64; 2],
    /// Each zone's range (gap unit): solid, second zone.
    pub zone_range: [f64; 2],
    /// w1/w and w2/w.
    pub work_share: [f64; 2],
    /// The zones' outer radii c1 (solid) and c2, where the gap equals each range.
    pub zone_edges: [f64; 2],
    /// Whether the state is stable under load control.
    pub load_stable: bool,
    /// Whether the state is stable under displacement control.
    pub displacement_stable: bool,
    /// The J-integral through both zones over w1 + w2, sum of stress times the gap at each
    /// zone's edge: 1 at equilibrium.
    pub energy_release_rate_over_w: f64,
    /// `two_zone` (its c is the outer of c1, c2), then Hertz, DMT and JKR of the total w.
    pub models: Vec<ModelProfile>,
    /// Where the model is stretched at this state.
    pub warnings: Vec<String>,
}

/// Why a two-zone profile could not be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TwoZoneProfileError {
    #[error("{0}")]
    /// The zones' parameters are refused.
    Zones(crate::error::Message),
    #[error("the two-zone curve could not be computed (`{}`)", .0.name())]
    /// The two-zone curve could not be computed.
    Curve(Status),
    #[error("the two-zone state is `{}`: no contact there, so no profile (give a load above the pull-off, an approach above the jump-out, or a radius > 0)", .0.name())]
    /// No contact at the given state.
    NoState(Status),
    #[error("points {0} is out of range: give 16..=100000 sampling radii")]
    /// A sampling count out of range.
    Points(usize),
}

impl crate::error::Named for TwoZoneProfileError {
    fn named(&self, names: crate::error::Names) -> String {
        match self {
            TwoZoneProfileError::Zones(m) => m.named(names),
            TwoZoneProfileError::Points(n) => format!(
                "{} {n} is out of range: give 16..=100000 sampling radii",
                names("points").unwrap_or("points")
            ),
            e => e.to_string(),
        }
    }
}

/// The two-zone state fixed by `given` for the solid's `lambda` and the second zone's stress
/// ratio `rho` and range ratio `eta`, sampled at about `points` radii.
pub fn two_zone_profile(
    lambda: f64,
    rho: f64,
    eta: f64,
    given: Given,
    points: usize,
) -> Result<TwoZoneProfile, TwoZoneProfileError> {
    if !(16..=MAX_PROFILE_POINTS).contains(&points) {
        return Err(TwoZoneProfileError::Points(points));
    }
    let law = TwoZones {
        lambda,
        stress_ratio: rho,
        range_ratio: eta,
    };
    let ctx = law.context().map_err(|e| match e {
        ContextError::Zones(e) => TwoZoneProfileError::Zones(e.0),
        ContextError::Curve(st) => TwoZoneProfileError::Curve(st),
    })?;
    let (given, value) = given.split();
    let mut s = two_zone::state(&ctx, given, value);
    let zones = ctx.zones;
    if s.status != Status::Ok {
        return Err(TwoZoneProfileError::NoState(s.status));
    }
    // Each edge from mu as the MD profile computes it (the same value to rounding), so that
    // rho = 0 gives the MD profile's grid and numbers.
    for i in 0..2 {
        let mm = s.m_minus_1[i];
        if mm > 0.0 {
            s.c[i] = (1.0 + mm * (mm + 2.0)).sqrt() * s.a;
        }
    }
    let r = sample_radii(&s, points);
    let gap_at = |i: usize| {
        if zones.lambda[i] > 0.0 {
            ctx.gap(&s, s.c[i])
        } else {
            0.0
        }
    };
    // J = sum of stress_i h(c_i); w = pi stress_i h_i summed is 1 in these units.
    let j = 0.5 * PI * (zones.lambda[0] * gap_at(0) + zones.lambda[1] * gap_at(1));
    let c_out = s.c[0].max(s.c[1]);
    // Both stresses act out to the inner edge of the zones present.
    let c_in =
        s.c.iter()
            .copied()
            .filter(|&c| c > s.a)
            .fold(c_out, f64::min);
    let tz = ModelProfile {
        model: ContactModel::SolidAndMeniscus,
        status: ProfileStatus::Ok,
        a: Some(s.a),
        c: Some(c_out),
        load: s.load,
        approach: Some(s.approach),
        pressure: r.iter().map(|&x| Some(ctx.pressure(&s, x))).collect(),
        gap: r.iter().map(|&x| ctx.gap(&s, x)).collect(),
        r: r.clone(),
        max_tension: Some(0.5 * (zones.lambda[0] + zones.lambda[1])),
        max_tension_at: Some((s.a, c_in)),
        stress_intensity: Some(0.0),
        energy_release_rate_over_w: Some(j),
        notes: vec![
            "the stress is bounded: each zone's Dugdale stress acts from a to its edge c_i".into(),
        ],
    };
    let [hertz, dmt, jkr] = closed_form_models(s.load, &r);
    Ok(TwoZoneProfile {
        lambda,
        stress_ratio: rho,
        range_ratio: eta,
        units: "normalised",
        zone_stress: zones.lambda.map(|l| 0.5 * l),
        zone_range: zones.range,
        work_share: [zones.work_share(0), zones.work_share(1)],
        zone_edges: s.c,
        load_stable: s.load_stable,
        displacement_stable: s.displacement_stable,
        energy_release_rate_over_w: j,
        models: vec![tz, hertz, dmt, jkr],
        warnings: Vec::new(),
    })
}

/// The MD profile's grid, with both zone edges and the turn of each zone's stress inside the
/// contact resolved.
fn sample_radii(s: &TwoZoneState, points: usize) -> Vec<f64> {
    use crate::physics::closed::{dmt_radius, hertz_radius, jkr_radius};
    let a = s.a;
    let closed = [hertz_radius(s.load), dmt_radius(s.load), jkr_radius(s.load)];
    let mut edges = vec![a, s.c[0], s.c[1]];
    edges.extend(closed.iter().flatten().filter(|&&x| x > 0.0));
    let r_max = 1.5 * edges.iter().fold(0.0f64, |m, &x| m.max(x));
    let mut r = radii(r_max, points, &edges);
    for mm in s.m_minus_1 {
        if mm > 0.0 {
            let d0 = mm * (mm + 2.0) / 2.0;
            r.extend((-160..=240).filter_map(|k| {
                let d = d0 * 10f64.powf(k as f64 / 80.0);
                (d > 1e-12 && d < 1.0).then_some(a * (1.0 - d))
            }));
        }
    }
    let n_in = 4 * points;
    r.extend((0..n_in).map(|i| a * (0.5 * PI * i as f64 / n_in as f64).sin()));
    r.sort_by(|a, b| a.total_cmp(b));
    r.dedup();
    r
}

impl TwoZoneProfile {
    /// The same profile in SI units for the scales `u` of a dimensional two-zone problem:
    /// radii, gaps and approaches in m, pressures in Pa, loads in N.
    pub fn to_si(&self, u: &crate::solver::two_zone::Units) -> TwoZoneProfile {
        let (fr, fd, ff) = (u.radius, u.approach, u.load);
        let fp = ff / (fr * fr);
        let mut p = self.clone();
        p.units = "SI";
        p.zone_stress = p.zone_stress.map(|x| x * fp);
        p.zone_range = p.zone_range.map(|x| x * fd);
        p.zone_edges = p.zone_edges.map(|x| x * fr);
        for m in &mut p.models {
            m.scale(fr, ff, fd, fp);
        }
        p
    }
}
