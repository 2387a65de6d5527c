//! Scenes: one real contact in SI units. Which model it needs (the simplest within the
//! tolerance, point by point), and what an experimenter wants: radii, approaches, pull-off forces,
//! warnings where continuum or small-strain theory breaks down, friction. The inverse problems
//! (`infer`: w from a pull-off force; `fit`: w and E* from load and radius pairs) and the
//! built-in scenes (`presets`, from `data/presets.json`) are beside it.

mod fit;
pub mod humidity;
mod infer;
mod input;
mod presets;
pub mod tip;

pub use fit::{fit_pairs, PairsFit};
pub use infer::{infer, infer_wet, wet_options, Inference, WetInference};
pub use input::{contact_of, SceneControl, SceneInput};
pub use presets::{preset, preset_names};

use crate::map::{classify, criteria, Region};
use crate::physics::model::ContactModel;
use crate::physics::params::{Contact, ParamError};
use crate::solver::{LambdaContext, Status};
use serde::Serialize;

/// The state of a scene at one load.
#[derive(Clone, Debug, Serialize)]
pub struct LoadResult {
    /// The load (N, compressive positive).
    pub load_n: f64,
    /// The load in units of pi w R.
    pub load_normalised: f64,
    /// Whether the state was found.
    pub status: Status,
    /// The contact radius (m).
    pub contact_radius_m: Option<f64>,
    /// The approach (m).
    pub approach_m: Option<f64>,
    /// Hertz peak pressure for this contact radius, 2 E* a / (pi R) (Pa): the pressure scale.
    pub pressure_scale_pa: Option<f64>,
    /// The contact radius over the sphere's radius.
    pub a_over_r: Option<f64>,
    /// Hertz's contact radius error relative to MD's.
    pub err_hertz: Option<f64>,
    /// DMT's contact radius error relative to MD's.
    pub err_dmt: Option<f64>,
    /// JKR's contact radius error relative to MD's.
    pub err_jkr: Option<f64>,
    /// The deformation over the force's range (small: rigid spheres, Bradley).
    pub rigid_measure: Option<f64>,
    /// The simplest adequate model at this load.
    pub model: &'static str,
    /// Why, in words.
    pub why: String,
    /// The friction estimate tau0 pi a^2 (N), with a shear strength.
    pub friction_n: Option<f64>,
    /// Where the model is stretched at this load.
    pub warnings: Vec<String>,
}

/// A scene solved: its parameters, pull-offs, the recommended model and each load's state.
#[derive(Clone, Debug, Serialize)]
#[allow(non_snake_case)] // the JSON keys name their unit: ..._N
pub struct SceneResult {
    /// The scene's name.
    pub name: String,
    /// Effective modulus E* (Pa).
    pub e_star_pa: f64,
    /// K = 4 E* / 3 (Pa).
    pub k_pa: f64,
    /// Effective radius (m).
    pub radius_m: f64,
    /// Work of adhesion (J/m^2).
    pub work_of_adhesion_j_m2: f64,
    /// Dugdale stress (Pa).
    pub s0_pa: f64,
    /// Maugis parameter.
    pub lambda: f64,
    /// Tabor parameter.
    pub tabor_parameter: f64,
    /// The tolerance a simpler model must meet.
    pub tolerance: f64,
    /// Pull-off force under load control (N, tensile negative).
    pub pulloff_force_load_control_N: f64,
    /// Pull-off force under displacement control (N).
    pub pulloff_force_displacement_control_N: f64,
    /// Contact radius at the load-controlled pull-off (m).
    pub pulloff_contact_radius_load_control_m: f64,
    /// Contact radius at zero load (m).
    pub zero_load_contact_radius_m: f64,
    /// The simplest model adequate over the scene's loads.
    pub recommended_model: ContactModel,
    /// Why, in words.
    pub recommendation: String,
    /// The pull-off (jump-out) force under the scene's control (N); with a cantilever, where its
    /// stiffness equals the contact's force gradient (see `tabor cycle`).
    pub pulloff_force_under_control_N: f64,
    /// The control of the experiment, in words.
    pub control: String,
    /// The state at each load.
    pub loads: Vec<LoadResult>,
    /// Where the values came from.
    pub source: Option<String>,
    /// With humidity: the meniscus, and every force, radius and approach above is for the solid
    /// plus the meniscus.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub meniscus: Option<humidity::Meniscus>,
    #[serde(skip_serializing_if = "Option::is_none")]
    /// The relative humidity, where there is a meniscus.
    pub relative_humidity: Option<f64>,
    /// The dry contact's pull-offs (N), for comparison, where there is a meniscus.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dry_pulloff_force_load_control_N: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    /// The dry contact's displacement-controlled pull-off (N).
    pub dry_pulloff_force_displacement_control_N: Option<f64>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    /// Where the meniscus model is stretched or does not apply.
    pub meniscus_warnings: Vec<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    /// With a humidity but no meniscus: why, in words (the results are the dry contact's).
    pub no_meniscus: Option<String>,
}

fn opt(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
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

/// A scene solved: a sphere's report, or a tip's.
#[derive(Clone, Debug, Serialize)]
#[serde(untagged)]
pub enum Solved {
    /// A sphere (radius_m, bodies, or a spherical tip).
    Sphere(Box<SceneResult>),
    /// Another tip (docs/PHYSICS.md section 12).
    Tip(Box<tip::TipSceneResult>),
}

/// Solves a scene of any tip: a sphere's (`radius_m`, the bodies or `"tip": {"shape":
/// "sphere"}`) by [`solve_scene`], any other by [`tip::solve_tip_scene`].
pub fn solve(s: &SceneInput) -> Result<Solved, ParamError> {
    match &s.tip {
        None | Some(crate::physics::tip::TipInput::Sphere { .. }) => {
            Ok(Solved::Sphere(Box::new(solve_scene(s)?)))
        }
        Some(t) => Ok(Solved::Tip(Box::new(tip::solve_tip_scene(s, t)?))),
    }
}

/// Solves a sphere's scene: its contact, pull-offs, the state at each load and the recommended
/// model.
pub fn solve_scene(s: &SceneInput) -> Result<SceneResult, ParamError> {
    let c = contact_of(s)?;
    let tol = checked_tolerance(s)?;
    let lambda = c.lambda();
    let ctx = LambdaContext::new(lambda).map_err(|_| ParamError::OutOfRange {
        field: "the Maugis parameter lambda of these inputs",
        value: lambda,
        allowed:
            "in 1e-26..1e26, the solver's domain (check the units of E*, R, w and the force range)",
    })?;
    let loads = scene_loads(s)?;
    let results = loads
        .iter()
        .map(|&p| load_result(s, &c, &ctx, tol, p))
        .collect::<Result<Vec<_>, _>>()?;
    let (rec, recommendation) = recommend(&results, tol, lambda, c.tabor());
    let (pulloff_control, control_name) = pulloff_under_control(s, &c, &ctx)?;
    let (fs, rs) = (c.force_scale(), c.radius_scale());
    let dry = SceneResult {
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
        pulloff_force_displacement_control_N: ctx.disp_pulloff().load * fs,
        pulloff_contact_radius_load_control_m: ctx.load_pulloff.a * rs,
        zero_load_contact_radius_m: ctx.solve_load(0.0).a * rs,
        recommended_model: rec,
        recommendation,
        loads: results,
        source: s.source.clone(),
        meniscus: None,
        relative_humidity: None,
        dry_pulloff_force_load_control_N: None,
        dry_pulloff_force_displacement_control_N: None,
        meniscus_warnings: Vec::new(),
        no_meniscus: None,
    };
    let Some(h) = &s.humidity else {
        return Ok(dry);
    };
    // The limits of the meniscus model, checked once for every front end.
    let meniscus_warnings = h.warnings(c.radius);
    let r = match h.meniscus(&c)? {
        None => SceneResult {
            relative_humidity: Some(h.relative_humidity),
            no_meniscus: h.no_meniscus(),
            ..dry
        },
        Some(m) => wet_scene(s, &c, m, h.relative_humidity, dry)?,
    };
    Ok(SceneResult {
        meniscus_warnings,
        ..r
    })
}

/// The pull-off (normalised, total w) of solid and meniscus under a cantilever of `k` N/m: the
/// retract's jump off the contact curve in the two-zone cycle (`no_jump`, the displacement-
/// controlled pull-off, where the contact is lost at zero radius without one).
fn wet_cantilever_pulloff(
    c: &Contact,
    m: &humidity::Meniscus,
    k: f64,
    no_jump: f64,
) -> Result<(f64, f64), ParamError> {
    if !(k > 0.0 && k.is_finite()) {
        return Err(ParamError::OutOfRange {
            field: "control.cantilever_n_m",
            value: k,
            allowed: "> 0 (N/m)",
        });
    }
    let (rho, eta, u) = humidity::wet_ratios(c, m)?;
    let kbar = k * u.approach / u.load;
    let cyc = crate::cycle::run(
        &crate::law::TwoZones {
            lambda: c.lambda(),
            stress_ratio: rho,
            range_ratio: eta,
        },
        crate::cycle::Drive::Spring(kbar),
        1.0,
    )
    .map_err(|_| ParamError::OutOfRange {
        field: "control.cantilever_n_m",
        value: k,
        allowed: "a stiffness the two-zone cycle can follow (normalised value positive and finite)",
    })?;
    // As for the dry scene: the load where the retract leaves the contact curve by a jump.
    let out = cyc
        .jumps
        .iter()
        .find(|j| {
            j.phase == crate::cycle::Phase::Retract
                && j.from.branch == crate::cycle::Branch::Contact
        })
        .map_or(no_jump, |j| j.from.load);
    Ok((out, kbar))
}

/// The scene's results for the solid plus the meniscus (the two-zone law), the dry pull-offs
/// kept for comparison.
fn wet_scene(
    s: &SceneInput,
    c: &Contact,
    m: humidity::Meniscus,
    rh: f64,
    dry: SceneResult,
) -> Result<SceneResult, ParamError> {
    let (ctx, u) = humidity::wet_context(c, &m)?;
    let (fs, rs, ds) = (u.load, u.radius, u.approach);
    let mut loads = dry.loads.clone();
    for l in loads.iter_mut() {
        let st = ctx.state_at_load(l.load_n / fs);
        let ok = st.status == Status::Ok;
        let a = st.a * rs;
        l.load_normalised = l.load_n / fs;
        l.status = st.status;
        l.contact_radius_m = ok.then_some(a);
        l.approach_m = ok.then_some(st.approach * ds);
        l.pressure_scale_pa = ok.then_some(2.0 * c.e_star * a / (std::f64::consts::PI * c.radius));
        l.a_over_r = ok.then_some(a / c.radius);
        (l.err_hertz, l.err_dmt, l.err_jkr, l.rigid_measure) = (None, None, None, None);
        l.model = if ok {
            "solid_and_meniscus"
        } else {
            "no_contact"
        };
        l.why = if ok {
            "solid and meniscus: two Dugdale zones (docs/PHYSICS.md section 10)".into()
        } else {
            "the load is below the pull-off of solid and meniscus: no contact".into()
        };
        l.friction_n = s
            .shear_strength_pa
            .filter(|_| ok)
            .map(|t| t * std::f64::consts::PI * a * a);
        l.warnings
            .retain(|w| !w.starts_with("a/R") && !w.contains("atomic spacings"));
        let spacing = s.atomic_spacing_m.unwrap_or(0.25e-9);
        if ok && a / c.radius > 0.1 {
            l.warnings.push(format!(
                "a/R = {:.2} > 0.1: small-strain (half-space) theory breaks down",
                a / c.radius
            ));
        }
        if ok && a < 10.0 * spacing {
            l.warnings.push(format!(
                "the contact radius is {:.1} atomic spacings: continuum theory is questionable here",
                a / spacing
            ));
        }
    }
    let (under, control) = match &s.control {
        None | Some(SceneControl::Load) => (ctx.load_pulloff.load * fs, dry.control.clone()),
        Some(SceneControl::Displacement) => (ctx.disp_pulloff.load * fs, dry.control.clone()),
        Some(SceneControl::CantileverNM(k)) => {
            let (p, kbar) = wet_cantilever_pulloff(c, &m, *k, ctx.disp_pulloff.load)?;
            (p * fs, cantilever_text(*k, kbar, true))
        }
    };
    let zero = ctx.state_at_load(0.0);
    Ok(SceneResult {
        pulloff_force_load_control_N: ctx.load_pulloff.load * fs,
        pulloff_force_displacement_control_N: ctx.disp_pulloff.load * fs,
        pulloff_contact_radius_load_control_m: ctx.load_pulloff.a * rs,
        zero_load_contact_radius_m: zero.a * rs,
        pulloff_force_under_control_N: under,
        recommended_model: ContactModel::SolidAndMeniscus,
        recommendation: format!(
            "solid and water meniscus together: two Dugdale zones (solid lambda = {:.3}, meniscus lambda = {:.3}, meniscus share of w = {:.0}%)",
            dry.lambda,
            m.lambda,
            100.0 * m.work_of_adhesion_j_m2 / (m.work_of_adhesion_j_m2 + c.work)
        ),
        loads,
        meniscus: Some(m),
        relative_humidity: Some(rh),
        dry_pulloff_force_load_control_N: Some(dry.pulloff_force_load_control_N),
        dry_pulloff_force_displacement_control_N: Some(dry.pulloff_force_displacement_control_N),
        control,
        ..dry
    })
}

/// The scene's tolerance (default 0.05) and shear strength, checked.
fn checked_tolerance(s: &SceneInput) -> Result<f64, ParamError> {
    let tol = s
        .tolerance
        .unwrap_or(crate::physics::model::DEFAULT_TOLERANCE);
    if !(tol > 0.0 && tol < 1.0) {
        return Err(ParamError::OutOfRange {
            field: "tolerance",
            value: tol,
            allowed: "in (0, 1)",
        });
    }
    if let Some(t) = s.shear_strength_pa {
        if !(t.is_finite() && t >= 0.0) {
            return Err(ParamError::OutOfRange {
                field: "shear_strength_pa",
                value: t,
                allowed: ">= 0 (Pa)",
            });
        }
    }
    Ok(tol)
}

/// The loads of the scene (N): `loads_n`, or `load_range_n` spaced linearly, or zero.
fn scene_loads(s: &SceneInput) -> Result<Vec<f64>, ParamError> {
    let count = s.loads_n.as_ref().map_or(0, Vec::len) + s.load_range_n.map_or(0, |r| r.2);
    if count > MAX_SCENE_LOADS {
        return Err(ParamError::OutOfRange {
            field: "the number of loads (loads_n or load_range_n)",
            value: count as f64,
            allowed: "at most 100000; for more use `tabor solve` on a file",
        });
    }
    match (&s.loads_n, s.load_range_n) {
        (Some(l), None) if l.is_empty() => Err(ParamError::OutOfRange {
            field: "the number of loads in loads_n",
            value: 0.0,
            allowed: "at least one load (N); leave loads_n out for zero load",
        }),
        (Some(l), None) => Ok(l.clone()),
        (None, Some((a, b, n))) if n >= 2 => Ok((0..n)
            .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
            .collect()),
        (None, Some((_, _, n))) => Err(ParamError::OutOfRange {
            field: "the count of load_range_n = [min, max, count]",
            value: n as f64,
            allowed: "at least 2 (for one load use loads_n = [P])",
        }),
        (None, None) => Ok(vec![0.0]),
        (Some(_), Some(_)) => Err(ParamError::Missing(
            "give loads_n or load_range_n = [min, max, count >= 2], not both",
        )),
    }
}

/// One load of the scene: the MD state in SI units, the model it needs and why, warnings.
fn load_result(
    s: &SceneInput,
    c: &Contact,
    ctx: &LambdaContext,
    tol: f64,
    p: f64,
) -> Result<LoadResult, ParamError> {
    let (fs, rs, ds) = (c.force_scale(), c.radius_scale(), c.approach_scale());
    let spacing = s.atomic_spacing_m.unwrap_or(0.25e-9);
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
    let ok = st.status == Status::Ok;
    let cr = criteria(ctx.lambda, st.load, st.a, st.approach);
    let a = st.a * rs;
    let mut warnings = Vec::new();
    if let Some(w) = ok
        .then(|| crate::physics::params::small_strain_warning(a / c.radius))
        .flatten()
    {
        warnings.push(w);
    }
    // A 1.35 nm contact on a 0.25 nm lattice is only about 5 atoms across (the AFM example).
    if ok && a < 10.0 * spacing {
        warnings.push(format!(
            "the contact radius is {:.1} atomic spacings: continuum theory is questionable here",
            a / spacing
        ));
    }
    Ok(LoadResult {
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
    })
}

/// The simplest model adequate at every load of the scene in contact, in the map's order, and
/// the sentence that says so.
fn recommend(results: &[LoadResult], tol: f64, lambda: f64, tabor: f64) -> (ContactModel, String) {
    use ContactModel as M;
    let order = [M::Hertz, M::Rigid, M::Dmt, M::Jkr, M::Md];
    let contact: Vec<&LoadResult> = results.iter().filter(|r| r.status == Status::Ok).collect();
    let rec = order
        .iter()
        .copied()
        .find(|&m| {
            !contact.is_empty()
                && contact.iter().all(|r| {
                    let e = match m {
                        M::Hertz => r.err_hertz,
                        M::Rigid => r.rigid_measure,
                        M::Dmt => r.err_dmt,
                        M::Jkr => r.err_jkr,
                        _ => Some(0.0),
                    };
                    e.is_some_and(|e| e <= tol)
                })
        })
        .unwrap_or(M::Md);
    let recommendation = if contact.is_empty() {
        "no load of the scene is above the pull-off".to_string()
    } else if rec == ContactModel::Md {
        format!("no closed form is within {}% at every load in contact: use Maugis-Dugdale (lambda = {:.3}, Tabor parameter {:.3})", 100.0 * tol, lambda, tabor)
    } else {
        format!(
            "{} is within {}% at all {} loads in contact (lambda = {:.3}, Tabor parameter {:.3})",
            rec.label(),
            100.0 * tol,
            contact.len(),
            lambda,
            tabor
        )
    };
    (rec, recommendation)
}

/// The pull-off force (N) under the scene's control, and the control's description.
fn pulloff_under_control(
    s: &SceneInput,
    c: &Contact,
    ctx: &LambdaContext,
) -> Result<(f64, String), ParamError> {
    let fs = c.force_scale();
    Ok(match &s.control {
        None | Some(SceneControl::Load) => (ctx.load_pulloff.load * fs, "load".to_string()),
        Some(SceneControl::Displacement) => {
            (ctx.disp_pulloff().load * fs, "displacement".to_string())
        }
        Some(SceneControl::CantileverNM(k)) => {
            if !(*k > 0.0 && k.is_finite()) {
                return Err(ParamError::OutOfRange {
                    field: "control.cantilever_n_m",
                    value: *k,
                    allowed: "> 0 (N/m)",
                });
            }
            let kbar = crate::cycle::normalised_stiffness(*k, c);
            let cyc = crate::cycle::cycle(ctx.lambda, crate::cycle::Drive::Spring(kbar), 1.0)
                .map_err(|_| ParamError::OutOfRange {
                    field: "control.cantilever_n_m",
                    value: *k,
                    allowed: "a stiffness whose normalised value is positive and finite",
                })?;
            let out = cyc
                .jumps
                .iter()
                .find(|j| j.phase == crate::cycle::Phase::Retract)
                .map_or(ctx.disp_pulloff().load, |j| j.from.load);
            (out * fs, cantilever_text(*k, kbar, false))
        }
    })
}

/// The scene's cantilever in words: k and its normalised value, with the w it is built on.
fn cantilever_text(k: f64, kbar: f64, wet: bool) -> String {
    format!(
        "cantilever k = {} N/m, {}",
        crate::physics::domain::short(k),
        crate::cycle::kbar_text(kbar, wet)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_solve_and_afm_is_questioned() {
        for p in preset_names() {
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
            pdms.lambda > 100.0 && pdms.recommended_model == ContactModel::Jkr,
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
        let c = Contact::new(
            r,
            e,
            w,
            crate::physics::params::ForceRange::LennardJones(z0),
        )
        .unwrap();
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
