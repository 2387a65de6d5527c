//! A scene with a tip that is not a sphere (docs/PHYSICS.md section 12): its pull-offs, and at
//! each load the contact and zone radii, the approach and the simplest adequate model for that
//! shape (Sneddon's adhesion-free punch, the DMT-type and JKR-type closed forms, or the exact
//! Maugis-Dugdale law).

use super::{checked_tolerance, scene_loads, SceneInput};
use crate::error::Message;
use crate::law::{Drive, Tip};
use crate::physics::params::ParamError;
use crate::physics::tip::{Shape, TipInput, TipUnits};
use crate::solver::Status;
use serde::Serialize;

/// A tip scene's state at one load.
#[derive(Clone, Debug, Serialize)]
pub struct TipLoadResult {
    /// The load (N, compressive positive).
    pub load_n: f64,
    /// The load in the tip's force unit.
    pub load_normalised: f64,
    /// Whether the state was found (no contact below the load-controlled pull-off).
    pub status: Status,
    /// The contact radius (m).
    pub contact_radius_m: Option<f64>,
    /// The Dugdale zone's outer radius (m).
    pub zone_radius_m: Option<f64>,
    /// The approach (m).
    pub approach_m: Option<f64>,
    /// Sneddon's (adhesion-free) contact radius error relative to Maugis-Dugdale's.
    pub err_hertz: Option<f64>,
    /// The DMT-type radius's error (Sneddon's punch under the load plus the rigid tip's force).
    pub err_dmt: Option<f64>,
    /// The JKR-type radius's error (the energy balance of the punch).
    pub err_jkr: Option<f64>,
    /// The simplest adequate model at this load, for this shape.
    pub model: &'static str,
    /// Why, in words.
    pub why: String,
}

/// A tip scene solved.
#[derive(Clone, Debug, Serialize)]
#[allow(non_snake_case)] // the JSON keys name their unit: ..._N
pub struct TipSceneResult {
    /// The scene's name.
    pub name: String,
    /// The tip as given.
    pub tip: TipInput,
    /// For a pyramid: the half-angle of the cone of the same area function it is solved as.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub equivalent_cone_half_angle_deg: Option<f64>,
    /// Reduced modulus E* (Pa).
    pub e_star_pa: f64,
    /// Work of adhesion (J/m^2).
    pub work_of_adhesion_j_m2: f64,
    /// Dugdale stress (Pa).
    pub s0_pa: f64,
    /// The shape's normalised units and its Maugis parameter.
    pub units: TipUnits,
    /// The shape's Maugis parameter `(3/2) s0 l / (E* d)`.
    pub lambda: f64,
    /// The tolerance a simpler model must meet.
    pub tolerance: f64,
    /// Pull-off force under load control (N, tensile negative).
    pub pulloff_force_load_control_N: f64,
    /// Pull-off force under displacement control (N).
    pub pulloff_force_displacement_control_N: f64,
    /// Contact radius at the load-controlled pull-off (m; 0 where contact is lost at zero
    /// radius).
    pub pulloff_contact_radius_load_control_m: f64,
    /// The simplest model adequate over the scene's loads.
    pub recommended_model: &'static str,
    /// The pull-off (jump-out) force under the scene's control (N); with a cantilever, where
    /// its stiffness equals the contact's force gradient on the retract (`tabor cycle --tip`).
    pub pulloff_force_under_control_N: f64,
    /// The control of the experiment, in words.
    pub control: String,
    /// The state at each load.
    pub loads: Vec<TipLoadResult>,
    /// For a measured profile: the error its interpolation may bring to the results (relative;
    /// an upper estimate from the table at every other point).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub profile_error: Option<f64>,
    /// Where the idealisation is stretched.
    pub warnings: Vec<String>,
    /// Where the values came from.
    pub source: Option<String>,
}

/// The tip scene's material pair: E*, w and s0 (the force range's reduction needs no radius).
fn materials(s: &SceneInput) -> Result<(f64, f64, f64), ParamError> {
    if s.radius_m.is_some() || s.body1.is_some() || s.body2.is_some() {
        return Err(ParamError::Missing(
            "a scene with a tip takes e_star_pa and the tip, not radius_m or bodies (give a sphere as \"tip\": {\"shape\": \"sphere\", \"radius_m\": R})",
        ));
    }
    for (given, key) in [
        (s.humidity.is_some(), "humidity"),
        (s.shear_strength_pa.is_some(), "shear_strength_pa"),
        (s.atomic_spacing_m.is_some(), "atomic_spacing_m"),
    ] {
        if given {
            return Err(ParamError::Conflict(format!(
                "{key} is not available for a tip other than a sphere: leave it out (or give the sphere's radius_m)"
            ).into()));
        }
    }
    let probe = SceneInput {
        radius_m: Some(1.0),
        tip: None,
        ..s.clone()
    };
    let c = super::contact_of(&probe)?;
    Ok((c.e_star, c.work, c.s0))
}

/// The units of a scene's tip (its E*, w and s0): its shape in them, with its Maugis
/// parameter.
pub fn units_of(s: &SceneInput) -> Result<TipUnits, ParamError> {
    let tip = s.tip.as_ref().ok_or(ParamError::Missing(
        "the scene has no \"tip\": give one (a sphere's scene has no shape beyond the paraboloid)",
    ))?;
    let (e_star, w, s0) = materials(s)?;
    tip.units(e_star, w, s0)
}

/// A tip in its normalised units as the command line and Python give it: a shape (`cone`,
/// `sphere`, `power:N`, `capped-cone:R_OVER_L:HALF_ANGLE_DEG`), or a scene as JSON text whose
/// tip is taken in the units of its E* and w ([`units_of`]): any tip given in SI units, a
/// measured profile among them, whose shape in the units depends on E* and w.
pub fn shape_of(text: &str) -> Result<Shape, Message> {
    if !text.trim_start().starts_with('{') {
        return text.parse();
    }
    let scene: SceneInput = serde_json::from_str(text).map_err(|e| {
        Message::new()
            .key("tip")
            .text(format!(": not a valid scene: {e}"))
    })?;
    units_of(&scene)
        .map(|u| u.shape)
        .map_err(|e| Message::new().key("tip").text(format!(" (a scene): {e}")))
}

/// Solves a scene whose `tip` is given.
pub fn solve_tip_scene(s: &SceneInput, tip: &TipInput) -> Result<TipSceneResult, ParamError> {
    let (e_star, w, s0) = materials(s)?;
    let tol = checked_tolerance(s)?;
    let u = tip.units(e_star, w, s0)?;
    let law = Tip::new(u.shape, u.lambda).map_err(|_| ParamError::OutOfRange {
        field: "the tip's Maugis parameter lambda of these inputs",
        value: u.lambda,
        allowed: "in 1e-3..1e3 (check the units of E*, w and the force range)",
    })?;
    let dead = law.pulloff_state(Drive::DeadLoad);
    let grips = law.pulloff_state(Drive::RigidGrips);
    let f0 = u.shape.rigid_force(u.lambda);
    // The stable piece's start, found once for every load.
    let t0 = law.stable_from(Drive::DeadLoad);
    let loads = scene_loads(s)?
        .into_iter()
        .map(|p| load_result(&law, t0, &u, f0, tol, p))
        .collect::<Result<Vec<_>, _>>()?;
    let order = ["hertz", "dmt", "jkr", "md"];
    let recommended_model = loads
        .iter()
        .filter(|l| l.status == Status::Ok)
        .map(|l| order.iter().position(|m| *m == l.model).unwrap_or(3))
        .max()
        .map_or("none", |i| order[i]);
    let (under, control) = under_control(s, &law, &u, grips.load)?;
    let mut warnings = tip.warnings();
    let mut profile_error = None;
    if let crate::physics::tip::Shape::Measured(p) = u.shape {
        let last_m = p.largest_radius() * u.length_m;
        // The radii the states rest on: the least contact radius above 0, the widest zone.
        let narrowest = loads
            .iter()
            .filter_map(|l| l.contact_radius_m)
            .chain([dead.a * u.length_m, grips.a * u.length_m])
            .filter(|&a| a > 0.0)
            .fold(f64::INFINITY, f64::min);
        let widest = loads
            .iter()
            .filter_map(|l| l.zone_radius_m)
            .fold(dead.c.max(grips.c) * u.length_m, f64::max);
        let e = p.error_between(narrowest.min(widest) / u.length_m, widest / u.length_m);
        profile_error = Some(e);
        warnings.push(format!(
            "the measured profile ({} points to r = {} m) gives these results within {:.1e} (relative; an upper estimate: over the radii they rest on, its interpolant's Abel transform differs by that from that of every other point)",
            p.points(),
            crate::physics::domain::short(last_m),
            e
        ));
        if widest > last_m {
            warnings.push(format!(
                "the Dugdale zone reaches r = {} m, beyond the measured profile's last radius {} m: the tip is continued there by its tangent",
                crate::physics::domain::short(widest),
                crate::physics::domain::short(last_m)
            ));
        }
    }
    Ok(TipSceneResult {
        name: s.name.clone().unwrap_or_else(|| "scene".into()),
        tip: tip.clone(),
        equivalent_cone_half_angle_deg: tip.equivalent_cone_deg(),
        e_star_pa: e_star,
        work_of_adhesion_j_m2: w,
        s0_pa: s0,
        units: u,
        lambda: u.lambda,
        tolerance: tol,
        pulloff_force_load_control_N: dead.load * u.force_n,
        pulloff_force_displacement_control_N: grips.load * u.force_n,
        pulloff_contact_radius_load_control_m: dead.a * u.length_m,
        recommended_model,
        pulloff_force_under_control_N: under,
        control,
        loads,
        profile_error,
        warnings,
        source: s.source.clone(),
    })
}

/// The pull-off force (N) under the scene's control and the control in words: the law's
/// pull-offs under a dead load or rigid grips (`grips`: the latter's, normalised), or under a
/// cantilever the retract's jump of the tip's cycle under that spring (in the tip's units,
/// `kbar = k d / (pi w l^2 / d)`).
fn under_control(
    s: &SceneInput,
    law: &Tip,
    u: &TipUnits,
    grips: f64,
) -> Result<(f64, String), ParamError> {
    use super::SceneControl;
    Ok(match &s.control {
        None | Some(SceneControl::Load) => (
            law.pulloff_state(Drive::DeadLoad).load * u.force_n,
            "load".to_string(),
        ),
        Some(SceneControl::Displacement) => (grips * u.force_n, "displacement".to_string()),
        Some(SceneControl::CantileverNM(k)) => {
            let refused = |value: f64| ParamError::OutOfRange {
                field: "control.cantilever_n_m",
                value,
                allowed: "> 0 (N/m), its normalised value positive and finite",
            };
            let kbar = k * u.approach_m / u.force_n;
            if !(*k > 0.0 && kbar.is_finite()) {
                return Err(refused(*k));
            }
            let cyc = crate::cycle::run(law, Drive::Spring(kbar), 1.0).map_err(|e| {
                ParamError::Conflict(format!(
                    "control.cantilever_n_m = {}: the tip's cycle under kbar = {kbar:.4e} was not solved ({e})",
                    crate::physics::domain::short(*k)
                ).into())
            })?;
            let out = cyc
                .jumps
                .iter()
                .find(|j| j.phase == crate::cycle::Phase::Retract)
                .map_or(grips, |j| j.from.load);
            (
                out * u.force_n,
                format!(
                    "cantilever k = {} N/m, kbar = {kbar:.4e} in the tip's units",
                    crate::physics::domain::short(*k)
                ),
            )
        }
    })
}

/// The state of a tip scene at load `p` (N): the stable state above `t0`
/// ([`Tip::stable_from`]), its radii in metres, and the simplest of the shape's closed forms
/// (force `f0` of the rigid tip) within `tol`.
fn load_result(
    law: &Tip,
    t0: f64,
    u: &TipUnits,
    f0: f64,
    tol: f64,
    p: f64,
) -> Result<TipLoadResult, ParamError> {
    if !p.is_finite() {
        return Err(ParamError::OutOfRange {
            field: "loads_n",
            value: p,
            allowed: "finite (N)",
        });
    }
    let pn = p / u.force_n;
    let state = law.at_load_above(t0, pn);
    let radii = u.shape.closed_radii(pn, f0);
    Ok(match state {
        None => TipLoadResult {
            load_n: p,
            load_normalised: pn,
            status: Status::NoContact,
            contact_radius_m: None,
            zone_radius_m: None,
            approach_m: None,
            err_hertz: None,
            err_dmt: None,
            err_jkr: None,
            model: "none",
            why: "the load is below the pull-off: no contact".into(),
        },
        Some(st) => {
            let err = |x: f64| (x.is_finite()).then(|| (x / st.a - 1.0).abs());
            let errs = radii.map(err);
            let names = ["hertz", "dmt", "jkr"];
            let first = errs.iter().position(|e| e.is_some_and(|e| e <= tol));
            let pct = |e: Option<f64>| e.map_or("none".into(), |e| format!("{:.1}%", 100.0 * e));
            let (model, why) = match first {
                Some(i) => (
                    names[i],
                    format!(
                        "the {}-type radius is within {} ({})",
                        ["Sneddon (Hertz)", "DMT", "JKR"][i],
                        pct(Some(tol)),
                        pct(errs[i])
                    ),
                ),
                None => (
                    "md",
                    format!(
                        "no closed form is within {}: DMT-type off by {}, JKR-type off by {}",
                        pct(Some(tol)),
                        pct(errs[1]),
                        pct(errs[2])
                    ),
                ),
            };
            TipLoadResult {
                load_n: p,
                load_normalised: pn,
                status: Status::Ok,
                contact_radius_m: Some(st.a * u.length_m),
                zone_radius_m: Some(st.c * u.length_m),
                approach_m: Some(st.approach * u.approach_m),
                err_hertz: errs[0],
                err_dmt: errs[1],
                err_jkr: errs[2],
                model,
                why,
            }
        }
    })
}
