//! Scenes: one real contact in SI units. Which model it needs (the simplest within the
//! tolerance, point by point), and what an experimenter wants: radii, approaches, pull-off forces,
//! warnings where continuum or small-strain theory breaks down, friction; and the inverse problem
//! from a measured pull-off force.

use crate::map::{classify, criteria, Region};
use crate::physics::params::{
    effective_radius, reduced_modulus, Body, Contact, ForceRange, ParamError,
};
use crate::solver::{LambdaContext, Status};
use serde::{Deserialize, Serialize};

/// The scene file (JSON). Units are SI and named in every key.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SceneInput {
    pub name: Option<String>,
    pub body1: Option<Body>,
    pub body2: Option<Body>,
    /// The reduced modulus and effective radius, instead of two bodies.
    pub e_star_pa: Option<f64>,
    pub radius_m: Option<f64>,
    pub work_of_adhesion_j_m2: Option<f64>,
    /// Dupre: w = g1 + g2 - g12 (J/m^2).
    pub surface_energies_j_m2: Option<[f64; 3]>,
    pub z0_m: Option<f64>,
    pub s0_pa: Option<f64>,
    pub h0_m: Option<f64>,
    pub loads_n: Option<Vec<f64>>,
    /// [min, max, count], linear.
    pub load_range_n: Option<(f64, f64, usize)>,
    pub tolerance: Option<f64>,
    /// Lattice spacing for the continuum check (default 0.25 nm).
    pub atomic_spacing_m: Option<f64>,
    /// Interfacial shear strength tau0 for the friction estimate F = tau0 pi a^2.
    pub shear_strength_pa: Option<f64>,
    /// The control of the experiment: "load", "displacement", or {"cantilever_n_m": k}.
    pub control: Option<SceneControl>,
    /// Source of the values, for the record.
    pub source: Option<String>,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SceneControl {
    Load,
    Displacement,
    /// An AFM cantilever (a spring in series) of stiffness k (N/m).
    CantileverNM(f64),
}

#[derive(Clone, Debug, Serialize)]
pub struct LoadResult {
    pub load_n: f64,
    pub load_normalised: f64,
    pub status: Status,
    pub contact_radius_m: Option<f64>,
    pub approach_m: Option<f64>,
    /// Hertz peak pressure for this contact radius, 2 E* a / (pi R) (Pa): the pressure scale.
    pub pressure_scale_pa: Option<f64>,
    pub a_over_r: Option<f64>,
    pub err_hertz: Option<f64>,
    pub err_dmt: Option<f64>,
    pub err_jkr: Option<f64>,
    pub rigid_measure: Option<f64>,
    pub model: &'static str,
    pub why: String,
    pub friction_n: Option<f64>,
    pub warnings: Vec<String>,
}

#[derive(Clone, Debug, Serialize)]
#[allow(non_snake_case)] // the JSON keys name their unit: ..._N
pub struct SceneResult {
    pub name: String,
    pub e_star_pa: f64,
    pub k_pa: f64,
    pub radius_m: f64,
    pub work_of_adhesion_j_m2: f64,
    pub s0_pa: f64,
    pub lambda: f64,
    pub tabor_parameter: f64,
    pub tolerance: f64,
    pub pulloff_force_load_control_N: f64,
    pub pulloff_force_displacement_control_N: f64,
    pub pulloff_contact_radius_load_control_m: f64,
    pub zero_load_contact_radius_m: f64,
    pub recommended_model: &'static str,
    pub recommendation: String,
    /// The pull-off (jump-out) force under the scene's control (N); with a cantilever, where its
    /// stiffness equals the contact's force gradient (see `tabor cycle`).
    pub pulloff_force_under_control_N: f64,
    pub control: String,
    pub loads: Vec<LoadResult>,
    pub source: Option<String>,
}

fn opt(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

pub fn contact_of(s: &SceneInput) -> Result<Contact, ParamError> {
    let (e_star, radius) = match (&s.body1, &s.body2) {
        (Some(b1), Some(b2)) => (reduced_modulus(b1, b2)?, effective_radius(b1, b2)?),
        (Some(_), None) | (None, Some(_)) => {
            return Err(ParamError::Missing(
                "give both body1 and body2, or e_star_pa and radius_m",
            ))
        }
        (None, None) => (
            s.e_star_pa.ok_or(ParamError::Missing(
                "missing e_star_pa (or body1 and body2)",
            ))?,
            s.radius_m
                .ok_or(ParamError::Missing("missing radius_m (or body1 and body2)"))?,
        ),
    };
    let w = match (s.work_of_adhesion_j_m2, s.surface_energies_j_m2) {
        (Some(w), None) => w,
        (None, Some([g1, g2, g12])) => g1 + g2 - g12,
        (Some(_), Some(_)) => {
            return Err(ParamError::Missing(
                "give work_of_adhesion_j_m2 or surface_energies_j_m2, not both",
            ))
        }
        (None, None) => {
            return Err(ParamError::Missing(
                "missing work_of_adhesion_j_m2 (or surface_energies_j_m2 = [g1, g2, g12])",
            ))
        }
    };
    let range = match (s.z0_m, s.s0_pa, s.h0_m) {
        (Some(z), None, None) => ForceRange::LennardJones(z),
        (None, Some(s0), None) => ForceRange::DugdaleStress(s0),
        (None, None, Some(h)) => ForceRange::DugdaleRange(h),
        (None, None, None) => {
            return Err(ParamError::Missing(
                "missing the force range: z0_m (Lennard-Jones), s0_pa or h0_m (Dugdale)",
            ))
        }
        _ => return Err(ParamError::Missing("give one of z0_m, s0_pa, h0_m")),
    };
    Contact::new(radius, e_star, w, range)
}

fn why(region: Region, c: &crate::map::Criteria, tol: f64) -> String {
    let pct = |e: f64| format!("{:.1}%", 100.0 * e);
    match region {
        Region::Hertz => format!(
            "Hertz is within {} of the exact radius ({})",
            pct(tol),
            pct(c.err_hertz)
        ),
        Region::Rigid => format!(
            "the deformation is {:.1}% of the force range: rigid (Bradley) spheres",
            100.0 * c.rigid
        ),
        Region::Dmt => format!(
            "Hertz is off by {}, but DMT is within {} ({})",
            pct(c.err_hertz.min(9.99)),
            pct(tol),
            pct(c.err_dmt)
        ),
        Region::Jkr => format!(
            "DMT is off by {}, JKR is within {} ({})",
            pct(c.err_dmt.min(9.99)),
            pct(tol),
            pct(c.err_jkr)
        ),
        Region::Md => format!(
            "no closed form is within {}: DMT off by {}, JKR off by {}",
            pct(tol),
            pct(c.err_dmt.min(9.99)),
            pct(c.err_jkr.min(9.99))
        ),
        Region::NoContact => "the load is below the pull-off: no contact".into(),
        Region::Failed => "the solver did not converge".into(),
    }
}

/// Most loads one scene solves (its report is kept in memory).
pub const MAX_SCENE_LOADS: usize = 100_000;

pub fn solve_scene(s: &SceneInput) -> Result<SceneResult, ParamError> {
    let c = contact_of(s)?;
    let tol = s.tolerance.unwrap_or(0.05);
    if !(tol > 0.0 && tol < 1.0) {
        return Err(ParamError::OutOfRange {
            field: "tolerance",
            value: tol,
            allowed: "in (0, 1)",
        });
    }
    let spacing = s.atomic_spacing_m.unwrap_or(0.25e-9);
    let lambda = c.lambda();
    let ctx = LambdaContext::new(lambda).map_err(|_| ParamError::OutOfRange {
        field: "the Maugis parameter lambda of these inputs",
        value: lambda,
        allowed:
            "in 1e-8..1e8, the solver's domain (check the units of E*, R, w and the force range)",
    })?;
    let (fs, rs, ds) = (c.force_scale(), c.radius_scale(), c.approach_scale());
    if let Some(t) = s.shear_strength_pa {
        if !(t.is_finite() && t >= 0.0) {
            return Err(ParamError::OutOfRange {
                field: "shear_strength_pa",
                value: t,
                allowed: ">= 0 (Pa)",
            });
        }
    }
    let count = s.loads_n.as_ref().map_or(0, Vec::len) + s.load_range_n.map_or(0, |r| r.2);
    if count > MAX_SCENE_LOADS {
        return Err(ParamError::OutOfRange {
            field: "the number of loads (loads_n or load_range_n)",
            value: count as f64,
            allowed: "at most 100000; for more use `tabor solve` on a file",
        });
    }
    let loads: Vec<f64> = match (&s.loads_n, s.load_range_n) {
        (Some(l), None) => l.clone(),
        (None, Some((a, b, n))) if n >= 2 => (0..n)
            .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
            .collect(),
        (None, None) => vec![0.0],
        _ => {
            return Err(ParamError::Missing(
                "give loads_n or load_range_n = [min, max, count >= 2], not both",
            ))
        }
    };
    let mut results = Vec::new();
    let mut counts = std::collections::BTreeMap::new();
    for &p in &loads {
        if !p.is_finite() {
            return Err(ParamError::OutOfRange {
                field: "loads_n",
                value: p,
                allowed: "finite (N)",
            });
        }
        crate::solver::domain::check_load(p / fs).map_err(|_| ParamError::OutOfRange {
            field: "loads_n",
            value: p,
            allowed: "a load whose normalised value P / (pi w R) is within -1e12..1e12",
        })?;
        let st = ctx.solve_load(p / fs);
        let region = classify(&st, tol);
        *counts.entry(region as u8).or_insert(0usize) += 1;
        let ok = st.status == Status::Ok;
        let cr = criteria(lambda, st.load, st.a, st.approach);
        let a = st.a * rs;
        let mut warnings = Vec::new();
        if ok && a / c.radius > 0.1 {
            warnings.push(format!(
                "a/R = {:.2} > 0.1: small-strain (half-space) theory breaks down",
                a / c.radius
            ));
        }
        // A 1.35 nm contact on a 0.25 nm lattice is only about 5 atoms across (the AFM example).
        if ok && a < 10.0 * spacing {
            warnings.push(format!("the contact radius is {:.1} atomic spacings: continuum theory is questionable here", a / spacing));
        }
        results.push(LoadResult {
            load_n: p,
            load_normalised: st.load,
            status: st.status,
            contact_radius_m: ok.then_some(a),
            approach_m: ok.then_some(st.approach * ds),
            pressure_scale_pa: ok.then_some(2.0 * c.e_star * a / (std::f64::consts::PI * c.radius)),
            a_over_r: ok.then_some(a / c.radius),
            err_hertz: if ok { opt(cr.err_hertz) } else { None },
            err_dmt: if ok { opt(cr.err_dmt) } else { None },
            err_jkr: if ok { opt(cr.err_jkr) } else { None },
            rigid_measure: ok.then_some(cr.rigid),
            model: region.name(),
            why: why(region, &cr, tol),
            friction_n: s
                .shear_strength_pa
                .filter(|_| ok)
                .map(|t| t * std::f64::consts::PI * a * a),
            warnings,
        });
    }
    // The simplest model adequate at every load of the scene, in the map's order.
    let order = [
        Region::Hertz,
        Region::Rigid,
        Region::Dmt,
        Region::Jkr,
        Region::Md,
    ];
    let contact: Vec<&LoadResult> = results.iter().filter(|r| r.status == Status::Ok).collect();
    let rec = order
        .iter()
        .copied()
        .find(|&m| {
            !contact.is_empty()
                && contact.iter().all(|r| {
                    let e = match m {
                        Region::Hertz => r.err_hertz,
                        Region::Rigid => r.rigid_measure,
                        Region::Dmt => r.err_dmt,
                        Region::Jkr => r.err_jkr,
                        _ => Some(0.0),
                    };
                    e.is_some_and(|e| e <= tol)
                })
        })
        .unwrap_or(Region::Md);
    let recommendation = if contact.is_empty() {
        "no load of the scene is above the pull-off".to_string()
    } else if rec == Region::Md {
        format!("no closed form is within {}% at every load in contact: use Maugis-Dugdale (lambda = {:.3}, Tabor parameter {:.3})", 100.0 * tol, lambda, c.tabor())
    } else {
        format!(
            "{} is within {}% at all {} loads in contact (lambda = {:.3}, Tabor parameter {:.3})",
            rec.label(),
            100.0 * tol,
            contact.len(),
            lambda,
            c.tabor()
        )
    };
    let zero = ctx.solve_load(0.0);
    let (pulloff_control, control_name) = match &s.control {
        None | Some(SceneControl::Load) => (ctx.load_pulloff.load * fs, "load".to_string()),
        Some(SceneControl::Displacement) => {
            (ctx.disp_pulloff.load * fs, "displacement".to_string())
        }
        Some(SceneControl::CantileverNM(k)) => {
            if !(*k > 0.0 && k.is_finite()) {
                return Err(ParamError::OutOfRange {
                    field: "control.cantilever_n_m",
                    value: *k,
                    allowed: "> 0 (N/m)",
                });
            }
            let kbar = crate::cycle::normalised_stiffness(*k, &c);
            let cyc = crate::cycle::cycle(lambda, crate::cycle::Drive::Spring(kbar), 1.0).map_err(
                |_| ParamError::OutOfRange {
                    field: "control.cantilever_n_m",
                    value: *k,
                    allowed: "a stiffness whose normalised value is positive and finite",
                },
            )?;
            let out = cyc
                .jumps
                .iter()
                .find(|j| j.phase == crate::cycle::Phase::Retract)
                .map_or(ctx.disp_pulloff.load, |j| j.from.load);
            (
                out * fs,
                format!("cantilever k = {k} N/m (normalised {kbar:.4e})"),
            )
        }
    };
    Ok(SceneResult {
        pulloff_force_under_control_N: pulloff_control,
        control: control_name,
        name: s.name.clone().unwrap_or_else(|| "scene".into()),
        e_star_pa: c.e_star,
        k_pa: c.k(),
        radius_m: c.radius,
        work_of_adhesion_j_m2: c.work,
        s0_pa: c.s0,
        lambda,
        tabor_parameter: c.tabor(),
        tolerance: tol,
        pulloff_force_load_control_N: ctx.load_pulloff.load * fs,
        pulloff_force_displacement_control_N: ctx.disp_pulloff.load * fs,
        pulloff_contact_radius_load_control_m: ctx.load_pulloff.a * rs,
        zero_load_contact_radius_m: zero.a * rs,
        recommended_model: rec.name(),
        recommendation,
        loads: results,
        source: s.source.clone(),
    })
}

/// Built-in scenes. The AFM geometry and lattice spacing are those of the classic AFM example
/// (a 20 nm tip on a 0.25 nm lattice); the material values are representative handbook values,
/// stated as such.
pub fn preset(name: &str) -> Option<SceneInput> {
    let body = |e: f64, nu: f64, r: Option<f64>| {
        Some(Body {
            youngs_modulus_pa: e,
            poisson_ratio: nu,
            radius_m: r,
        })
    };
    let base = |name: &str,
                b1,
                b2,
                w: f64,
                z0: f64,
                range: (f64, f64, usize),
                tau: Option<f64>,
                source: &str| SceneInput {
        name: Some(name.into()),
        body1: b1,
        body2: b2,
        e_star_pa: None,
        radius_m: None,
        work_of_adhesion_j_m2: Some(w),
        surface_energies_j_m2: None,
        z0_m: Some(z0),
        s0_pa: None,
        h0_m: None,
        loads_n: None,
        load_range_n: Some(range),
        tolerance: None,
        atomic_spacing_m: Some(0.25e-9),
        shear_strength_pa: tau,
        control: None,
        source: Some(source.into()),
    };
    Some(match name {
        "afm-si" => base("AFM silicon tip (R = 20 nm) on silicon", body(169e9, 0.27, Some(20e-9)), body(169e9, 0.27, None), 0.1, 0.3e-9, (0.0, 20e-9, 5), Some(1e9),
            "R = 20 nm and the 0.25 nm lattice spacing of the classic AFM example; Si E = 169 GPa, nu = 0.27 (handbook value for Si <110>); w = 0.1 J/m^2 and z0 = 0.3 nm representative of a dry oxide-covered Si contact; tau0 = 1 GPa representative of nanoscale friction"),
        "pdms-glass" => base("PDMS sphere (R = 2 mm) on glass", body(1.8e6, 0.5, Some(2e-3)), body(70e9, 0.22, None), 0.044, 0.3e-9, (-0.5e-3, 5e-3, 12), None,
            "PDMS E = 1.8 MPa, nu = 0.5 (typical Sylgard 184); glass E = 70 GPa, nu = 0.22 (handbook); w = 44 mJ/m^2, twice the PDMS surface energy of about 22 mJ/m^2; z0 = 0.3 nm"),
        "mica-sfa" => base("Mica surfaces in a surface force apparatus (R = 1 cm)", body(34.5e9, 0.25, Some(1e-2)), body(34.5e9, 0.25, None), 0.1, 0.3e-9, (-1e-3, 10e-3, 12), None,
            "R = 1 cm (typical SFA cylinders); mica E = 34.5 GPa, nu = 0.25 (handbook; the glue under the sheets, ignored here, lowers the effective modulus); w = 0.1 J/m^2 representative of mica in dry air; z0 = 0.3 nm"),
        "graphene-mems" => base("Graphene-coated MEMS asperity (R = 1 um)", body(160e9, 0.22, Some(1e-6)), body(160e9, 0.22, None), 0.37, 0.34e-9, (0.0, 1e-6, 6), Some(50e6),
            "polysilicon E = 160 GPa, nu = 0.22 (handbook); w = 0.37 J/m^2, the graphite interlayer adhesion energy; z0 = 0.34 nm, the graphene interlayer spacing; asperity radius 1 um representative"),
        "hydrogel-titanium" => base("Hydrogel sphere (R = 1 mm) on titanium", body(50e3, 0.45, Some(1e-3)), body(110e9, 0.34, None), 0.01, 1e-9, (-10e-6, 100e-6, 12), None,
            "hydrogel E = 50 kPa, nu = 0.45 (soft gel); titanium E = 110 GPa, nu = 0.34 (handbook); w = 10 mJ/m^2 and z0 = 1 nm representative of adhesion in a biological fluid"),
        _ => return None,
    })
}

pub const PRESETS: [&str; 5] = [
    "afm-si",
    "pdms-glass",
    "mica-sfa",
    "graphene-mems",
    "hydrogel-titanium",
];

/// What a measured pull-off force says about the work of adhesion under each model.
#[derive(Clone, Debug, Serialize)]
pub struct Inference {
    pub pulloff_force_n: f64,
    pub w_jkr_j_m2: f64,
    pub tabor_if_jkr: f64,
    pub w_dmt_j_m2: f64,
    pub tabor_if_dmt: f64,
    pub w_md_j_m2: Option<f64>,
    pub lambda_md: Option<f64>,
    pub verdict: String,
}

/// From a pull-off force (N, positive or negative), R, E* and the LJ range z0: w under JKR
/// (Fc = 3/2 pi w R), DMT (Fc = 2 pi w R) and the exact MD (w and lambda together), and the
/// usual self-consistency check: a model is to be trusted if the Tabor parameter computed
/// with its own w agrees with its own assumption (JKR: muT > 5, DMT: muT < 0.1).
pub fn infer(pulloff_n: f64, radius: f64, e_star: f64, z0: f64) -> Result<Inference, ParamError> {
    let f = pulloff_n.abs();
    if !(f > 0.0 && f.is_finite()) {
        return Err(ParamError::OutOfRange {
            field: "pulloff_force_n",
            value: pulloff_n,
            allowed: "non-zero and finite (N)",
        });
    }
    let pi = std::f64::consts::PI;
    let tabor =
        |w: f64| Contact::new(radius, e_star, w, ForceRange::LennardJones(z0)).map(|c| c.tabor());
    let w_jkr = f / (1.5 * pi * radius);
    let w_dmt = f / (2.0 * pi * radius);
    let (mt_j, mt_d) = (tabor(w_jkr)?, tabor(w_dmt)?);
    // Every w between the DMT and JKR values must give a lambda the solver can certify.
    for w in [w_dmt, w_jkr] {
        let l = Contact::new(radius, e_star, w, ForceRange::LennardJones(z0))?.lambda();
        if crate::solver::domain::check_lambda(l).is_err() {
            return Err(ParamError::OutOfRange {
                field: "pulloff_force_n",
                value: pulloff_n,
                allowed: "a force whose work of adhesion gives a Maugis parameter in 1e-8..1e8 with this R, E* and z0 (check the units)",
            });
        }
    }
    // MD: find w with -Pbar_c(lambda(w)) pi w R = f; the left side grows with w.
    let g = |w: f64| -> f64 {
        let c = Contact::new(radius, e_star, w, ForceRange::LennardJones(z0)).expect("validated");
        LambdaContext::new(c.lambda())
            .map_or(f64::NAN, |ctx| -ctx.load_pulloff.load * pi * w * radius - f)
    };
    let w_md =
        crate::solver::root::bisect_sign(|lw| g(lw.exp()), w_dmt.ln() - 1e-9, w_jkr.ln() + 1e-9)
            .exp();
    let ok = g(w_md).abs() < 1e-9 * f;
    let lam = Contact::new(radius, e_star, w_md, ForceRange::LennardJones(z0))?.lambda();
    let off = |w: f64| {
        if ok {
            format!(
                " (it differs from the exact Maugis-Dugdale w by {:.1}%)",
                100.0 * (w / w_md - 1.0)
            )
        } else {
            String::new()
        }
    };
    let verdict = match (mt_j > 5.0, mt_d < 0.1) {
        (true, false) => format!("JKR is self-consistent (Tabor parameter {mt_j:.2} > 5 with its own w); DMT is not ({mt_d:.2}). Trust w = {w_jkr:.4e} J/m^2{}.", off(w_jkr)),
        (false, true) => format!("DMT is self-consistent (Tabor parameter {mt_d:.3} < 0.1 with its own w); JKR is not ({mt_j:.2}). Trust w = {w_dmt:.4e} J/m^2{}.", off(w_dmt)),
        _ => format!("neither closed form is self-consistent (Tabor parameter {mt_d:.3} with the DMT w, {mt_j:.3} with the JKR w): use the Maugis-Dugdale value w = {w_md:.4e} J/m^2 (lambda = {lam:.3})."),
    };
    Ok(Inference {
        pulloff_force_n: f,
        w_jkr_j_m2: w_jkr,
        tabor_if_jkr: mt_j,
        w_dmt_j_m2: w_dmt,
        tabor_if_dmt: mt_d,
        w_md_j_m2: ok.then_some(w_md),
        lambda_md: ok.then_some(lam),
        verdict,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_solve_and_afm_is_questioned() {
        for p in PRESETS {
            let r = solve_scene(&preset(p).unwrap()).unwrap();
            assert!(r.pulloff_force_load_control_N < 0.0, "{p}");
        }
        let afm = solve_scene(&preset("afm-si").unwrap()).unwrap();
        assert!(
            afm.lambda < 0.5,
            "the AFM tip is on the DMT side: {}",
            afm.lambda
        );
        assert!(afm
            .loads
            .iter()
            .any(|l| l.warnings.iter().any(|w| w.contains("continuum"))));
        let pdms = solve_scene(&preset("pdms-glass").unwrap()).unwrap();
        assert!(
            pdms.lambda > 100.0 && pdms.recommended_model == "jkr",
            "{} {}",
            pdms.lambda,
            pdms.recommended_model
        );
    }

    #[test]
    fn cantilever_pulloff_lies_between_the_controls() {
        let mut s = preset("afm-si").unwrap();
        s.control = Some(SceneControl::CantileverNM(0.2));
        let r = solve_scene(&s).unwrap();
        let (lc, dc, k) = (
            r.pulloff_force_load_control_N,
            r.pulloff_force_displacement_control_N,
            r.pulloff_force_under_control_N,
        );
        assert!(
            k >= lc.min(dc) - 1e-12 && k <= lc.max(dc) + 1e-12,
            "{lc} {dc} {k}"
        );
    }

    #[test]
    fn pulloff_force_in_newtons_matches_jkr_and_dmt_limits() {
        // JKR side: Fc = 3/2 pi w R.
        let pdms = solve_scene(&preset("pdms-glass").unwrap()).unwrap();
        let fc = 1.5 * std::f64::consts::PI * 0.044 * 2e-3;
        assert!((-pdms.pulloff_force_load_control_N / fc - 1.0).abs() < 1e-3);
    }

    #[test]
    fn inference_recovers_w() {
        // A synthetic AFM measurement made with the exact MD model.
        let (r, e, z0, w) = (20e-9, 90e9, 0.3e-9, 0.1);
        let c = Contact::new(r, e, w, ForceRange::LennardJones(z0)).unwrap();
        let f = -LambdaContext::new(c.lambda()).unwrap().load_pulloff.load * c.force_scale();
        let inf = infer(f, r, e, z0).unwrap();
        assert!((inf.w_md_j_m2.unwrap() / w - 1.0).abs() < 1e-9);
        assert!(inf.w_dmt_j_m2 < w && inf.w_jkr_j_m2 > w);
    }

    #[test]
    fn bad_scene_inputs_name_the_field() {
        let mut s = preset("pdms-glass").unwrap();
        s.body1.as_mut().unwrap().poisson_ratio = 0.7;
        assert!(solve_scene(&s)
            .unwrap_err()
            .to_string()
            .contains("poisson_ratio"));
        let mut s = preset("pdms-glass").unwrap();
        s.work_of_adhesion_j_m2 = None;
        assert!(solve_scene(&s)
            .unwrap_err()
            .to_string()
            .contains("work_of_adhesion"));
    }
}

/// A fit of w and E* to measured (load, contact radius) pairs with the exact MD model.
#[derive(Clone, Debug, Serialize)]
pub struct PairsFit {
    pub work_of_adhesion_j_m2: f64,
    pub e_star_pa: f64,
    pub lambda: f64,
    pub tabor_parameter: f64,
    /// (a_model - a_measured) / a_measured for each pair.
    pub relative_residuals: Vec<f64>,
    pub rms_relative_residual: f64,
}

/// Least squares on the relative contact-radius residuals over (ln w, ln E*): a coarse grid, then
/// a compass search to a step of 1e-9. `pairs` are (load in N, contact radius in m).
pub fn fit_pairs(pairs: &[(f64, f64)], radius: f64, z0: f64) -> Result<PairsFit, ParamError> {
    if pairs.len() < 2 {
        return Err(ParamError::Missing(
            "give at least two (load, contact radius) pairs",
        ));
    }
    for &(p, a) in pairs {
        if !(p.is_finite() && a.is_finite() && a > 0.0) {
            return Err(ParamError::OutOfRange {
                field: "pairs",
                value: if a > 0.0 { p } else { a },
                allowed: "finite loads (N) and positive contact radii (m)",
            });
        }
    }
    // Two parameters need two distinct loads, and an elastic contact grows with the load.
    let mut sorted = pairs.to_vec();
    sorted.sort_by(|x, y| x.0.total_cmp(&y.0));
    sorted.dedup_by(|x, y| x.0 == y.0 && x.1 == y.1);
    if sorted.windows(2).filter(|w| w[1].0 > w[0].0).count() < 1 {
        return Err(ParamError::Missing(
            "the pairs need at least two different loads to determine both w and E*",
        ));
    }
    if let Some(w) = sorted
        .windows(2)
        .find(|w| w[1].0 > w[0].0 && !(w[1].1 > w[0].1))
    {
        return Err(ParamError::OutOfRange {
            field: "contact_radius_m",
            value: w[1].1,
            allowed: "larger at a larger load (the contact radius of an elastic sphere grows with the load); check the columns",
        });
    }
    let residuals = |lw: f64, le: f64| -> Option<Vec<f64>> {
        let c = Contact::new(radius, le.exp(), lw.exp(), ForceRange::LennardJones(z0)).ok()?;
        let ctx = LambdaContext::new(c.lambda()).ok()?;
        let (fs, rs) = (c.force_scale(), c.radius_scale());
        Some(
            pairs
                .iter()
                .map(|&(p, a)| {
                    let s = ctx.solve_load(p / fs);
                    if s.status == Status::Ok {
                        s.a * rs / a - 1.0
                    } else {
                        1.0
                    }
                })
                .collect(),
        )
    };
    let cost = |lw: f64, le: f64| {
        residuals(lw, le).map_or(f64::INFINITY, |r| r.iter().map(|x| x * x).sum::<f64>())
    };
    let mut best = (f64::INFINITY, 0.0, 0.0);
    for i in 0..=24 {
        for j in 0..=24 {
            let (lw, le) = (
                (1e-4f64).ln() + i as f64 * (1e5f64).ln() / 24.0,
                (1e3f64).ln() + j as f64 * (1e9f64).ln() / 24.0,
            );
            let c = cost(lw, le);
            if c < best.0 {
                best = (c, lw, le);
            }
        }
    }
    let (mut f, mut lw, mut le) = best;
    let mut step = 0.5;
    while step > 1e-9 {
        let mut moved = false;
        for (dw, de) in [
            (step, 0.0),
            (-step, 0.0),
            (0.0, step),
            (0.0, -step),
            (step, step),
            (-step, -step),
            (step, -step),
            (-step, step),
        ] {
            let c = cost(lw + dw, le + de);
            if c < f {
                (f, lw, le) = (c, lw + dw, le + de);
                moved = true;
            }
        }
        if !moved {
            step *= 0.5;
        }
    }
    let r = residuals(lw, le).ok_or(ParamError::Missing("the fit left the valid range"))?;
    // A minimum on the edge of the searched box, or pairs the model leaves out of contact, mean
    // the data do not determine the parameters: no number is better than a wrong one.
    let (lw_lo, lw_hi) = ((1e-4f64).ln(), (1e1f64).ln());
    let (le_lo, le_hi) = ((1e3f64).ln(), (1e12f64).ln());
    if !(lw > lw_lo + 0.5 && lw < lw_hi - 0.5 && le > le_lo + 0.5 && le < le_hi - 0.5) {
        return Err(ParamError::Missing(
            "the pairs do not determine w and E*: the best fit runs to the edge of w in 1e-4..10 J/m^2 and E* in 1e3..1e12 Pa (check the units and that the radii grow with the load)",
        ));
    }
    if r.contains(&1.0) {
        return Err(ParamError::Missing(
            "some loads lie below the fitted model's pull-off: the pairs are not consistent with one Maugis-Dugdale contact",
        ));
    }
    let c = Contact::new(radius, le.exp(), lw.exp(), ForceRange::LennardJones(z0))?;
    let rms = (r.iter().map(|x| x * x).sum::<f64>() / r.len() as f64).sqrt();
    Ok(PairsFit {
        work_of_adhesion_j_m2: c.work,
        e_star_pa: c.e_star,
        lambda: c.lambda(),
        tabor_parameter: c.tabor(),
        relative_residuals: r,
        rms_relative_residual: rms,
    })
}

#[cfg(test)]
mod fit_tests {
    use super::*;

    #[test]
    fn pairs_fit_recovers_w_and_e_star() {
        // Synthetic JKR-like test: PDMS-like sphere, exact MD radii at six loads.
        let (r, e, w, z0) = (2e-3, 2.4e6, 0.044, 0.3e-9);
        let c = Contact::new(r, e, w, ForceRange::LennardJones(z0)).unwrap();
        let ctx = LambdaContext::new(c.lambda()).unwrap();
        let pairs: Vec<(f64, f64)> = [-2e-4, 0.0, 5e-4, 1e-3, 2e-3, 4e-3]
            .iter()
            .map(|&p| (p, ctx.solve_load(p / c.force_scale()).a * c.radius_scale()))
            .collect();
        let fit = fit_pairs(&pairs, r, z0).unwrap();
        assert!(
            (fit.work_of_adhesion_j_m2 / w - 1.0).abs() < 1e-5,
            "{}",
            fit.work_of_adhesion_j_m2
        );
        assert!((fit.e_star_pa / e - 1.0).abs() < 1e-5, "{}", fit.e_star_pa);
        assert!(fit.rms_relative_residual < 1e-6);
    }
}
