//! A curve fitted in humid air: the solid's work of adhesion with the water meniscus taken out.
//!
//! The curve's shape is fitted with one Dugdale zone (Maugis-Dugdale: E*, w, lambda). That
//! zone's load-controlled pull-off, `Pbar_c(lambda) pi w R`, is then read as the pull-off of the
//! solid's zone and the meniscus beside it (the two-zone law, docs/PHYSICS.md section 10): the
//! solid's w is the one that, with the meniscus of the humidity given and the fitted E* and
//! Lennard-Jones range z0, pulls off at that force, the same exact inversion as
//! [`crate::scene::infer_wet`] (`tabor infer --relative-humidity`).

use super::CurveFit;
use crate::physics::params::{Contact, ForceRange, LJ_STRESS};
use crate::scene::humidity::{HumidityInput, Meniscus};
use crate::solver::LambdaContext;
use serde::Serialize;
use std::f64::consts::PI;

/// The humidity of a fitted curve and the solid's w it leaves (SI units).
#[derive(Clone, Debug, Serialize)]
pub struct FitHumidity {
    /// Relative humidity, 0..1.
    pub relative_humidity: f64,
    /// Contact angle of water on the surfaces (degrees).
    pub contact_angle_deg: f64,
    /// Surface tension of the liquid (N/m), the default filled in.
    pub surface_tension_n_m: f64,
    /// Molar volume of the liquid (m^3/mol), the default filled in.
    pub molar_volume_m3_mol: f64,
    /// Temperature (K), the default filled in.
    pub temperature_k: f64,
    /// The meniscus as a Dugdale zone; null where none forms (a contact angle of 90 degrees or
    /// more).
    pub meniscus: Option<Meniscus>,
    /// The fitted Maugis-Dugdale model's load-controlled pull-off, `Pbar_c(lambda) pi w R` with
    /// the fitted E*, w, lambda and the curve's tip radius (N, its magnitude): the force the
    /// meniscus is taken out of.
    pub pulloff_force_load_control_n: f64,
    /// The Lennard-Jones range of the solid's zone, held while its w is found (the fit's z0, m).
    pub z0_m: f64,
    /// The load-controlled pull-off of the meniscus alone (N, its magnitude).
    pub meniscus_only_pulloff_n: Option<f64>,
    /// The solid's w with the meniscus taken out (J/m^2): the fitted w where no meniscus
    /// forms; null where the meniscus alone pulls off harder than the fitted model (`note`
    /// says so).
    pub solid_work_of_adhesion_j_m2: Option<f64>,
    /// The solid's Maugis parameter with that w and z0.
    pub solid_lambda: Option<f64>,
    /// The fraction of the fitted pull-off that the meniscus adds: 1 - (the solid's own
    /// Maugis-Dugdale pull-off with its w) / (the fitted pull-off); 0 without a meniscus.
    pub meniscus_share: Option<f64>,
    /// The meniscus' range 2 r_K cos(theta) against the fitted zone's Dugdale range w / s0.
    pub meniscus_range_over_fitted_range: Option<f64>,
    /// Whether the reading is fair: the meniscus reaches no farther than the fitted Dugdale
    /// zone, or its work is at most a tenth of the fitted w (see `note`).
    pub fair_reading: bool,
    /// What was found, and how far to trust it, in words.
    pub note: String,
}

/// Where the meniscus' work is at most this fraction of the fitted w, the meniscus is small
/// and the reading fair whatever its range.
pub const SMALL_MENISCUS: f64 = 0.1;

/// The solid's w of a fitted curve (`r`, status ok) in the humidity `h`, with the curve's tip
/// radius. `h` has been checked ([`HumidityInput::validate`]). Never fails: where the meniscus
/// cannot be taken out, the solid's w is null and `note` says why.
pub fn solid_work(r: &CurveFit, radius: f64, h: &HumidityInput) -> Option<FitHumidity> {
    let (e_star, w, lambda, z0) = (r.e_star_pa?, r.work_of_adhesion_j_m2?, r.lambda?, r.z0_m?);
    let mut out = FitHumidity {
        relative_humidity: h.relative_humidity,
        contact_angle_deg: h.contact_angle_deg,
        surface_tension_n_m: h.surface_tension(),
        molar_volume_m3_mol: h.molar_volume(),
        temperature_k: h.temperature(),
        meniscus: None,
        pulloff_force_load_control_n: f64::NAN,
        z0_m: z0,
        meniscus_only_pulloff_n: None,
        solid_work_of_adhesion_j_m2: None,
        solid_lambda: None,
        meniscus_share: None,
        meniscus_range_over_fitted_range: None,
        fair_reading: false,
        note: String::new(),
    };
    let fail = |mut out: FitHumidity, why: String| {
        out.note = format!("the meniscus could not be taken out of this fit: {why}");
        Some(out)
    };
    let ctx = match LambdaContext::new(lambda) {
        Ok(c) => c,
        Err(e) => return fail(out, e.to_string()),
    };
    let f = -ctx.load_pulloff.load * PI * w * radius;
    if !(f.is_finite() && f > 0.0) {
        return fail(out, format!("the fitted pull-off {f:e} N is not a force"));
    }
    out.pulloff_force_load_control_n = f;
    let contact = match Contact::new(radius, e_star, w, ForceRange::LennardJones(z0)) {
        Ok(c) => c,
        Err(e) => return fail(out, e.to_string()),
    };
    let meniscus = match h.meniscus(&contact) {
        Ok(m) => m,
        Err(e) => return fail(out, e.to_string()),
    };
    let Some(m) = meniscus else {
        out.solid_work_of_adhesion_j_m2 = Some(w);
        out.solid_lambda = Some(lambda);
        out.meniscus_share = Some(0.0);
        out.fair_reading = true;
        out.note = format!(
            "no meniscus forms at a contact angle of {} degrees (90 or more): the solid's w is the fitted w",
            crate::physics::domain::short(h.contact_angle_deg)
        );
        return Some(out);
    };
    out.meniscus = Some(m);
    // The fitted zone's Dugdale range w / s0, s0 = LJ_STRESS w / z0.
    let ratio = m.range_m / (z0 / LJ_STRESS);
    out.meniscus_range_over_fitted_range = Some(ratio);
    let small = m.work_of_adhesion_j_m2 <= SMALL_MENISCUS * w;
    out.fair_reading = ratio <= 1.0 || small;
    let fairness = fairness(ratio, small, m.work_of_adhesion_j_m2, w);
    let inf = match crate::scene::infer_wet(f, radius, e_star, z0, h) {
        Ok(i) => i,
        Err(e) => return fail(out, e.to_string()),
    };
    out.meniscus_only_pulloff_n = Some(inf.meniscus_only_pulloff_n);
    match (inf.solid_work_of_adhesion_j_m2, inf.solid_lambda) {
        (Some(ws), Some(ls)) => {
            out.solid_work_of_adhesion_j_m2 = Some(ws);
            out.solid_lambda = Some(ls);
            let alone = LambdaContext::new(ls)
                .map(|c| -c.load_pulloff.load * PI * ws * radius)
                .ok();
            out.meniscus_share = alone.map(|a| 1.0 - a / f);
            out.note = format!(
                "solid w = {ws:.4e} J/m^2 (lambda = {ls:.3}): with the meniscus (w = {:.4e} J/m^2) it pulls off at the fitted {f:.4e} N; the fitted w = {w:.4e} J/m^2 holds both; {fairness}",
                m.work_of_adhesion_j_m2
            );
        }
        _ if inf.meniscus_only_pulloff_n >= f => {
            out.note = format!(
                "no solid w: the meniscus alone pulls off at {:.4e} N, more than the fitted model's {f:.4e} N (a larger contact angle or a lower humidity than given, or a meniscus not in equilibrium)",
                inf.meniscus_only_pulloff_n
            );
        }
        _ => {
            out.note = format!(
                "no solid w: the two-zone pull-off was not matched to 1e-9 of the fitted {f:.4e} N"
            );
        }
    }
    Some(out)
}

/// Whether one Dugdale zone fairly describes a curve with this meniscus, in words: its range
/// against the fitted zone's (`ratio`), or its work small against the fitted w.
fn fairness(ratio: f64, small: bool, meniscus_w: f64, w: f64) -> String {
    if ratio <= 1.0 {
        format!(
            "a fair reading: the meniscus reaches {ratio:.2} of the fitted zone's range, so one Dugdale zone describes the curve's shape with the meniscus in it"
        )
    } else if small {
        format!(
            "a fair reading: the meniscus reaches {ratio:.2} times the fitted zone's range, but its work is at most a tenth of the fitted w"
        )
    } else {
        format!(
            "a doubtful reading: the meniscus reaches {ratio:.2} times the fitted zone's range with a work {:.2} times the fitted w, so the curve's shape is not one Dugdale zone's and the fitted lambda (and the z0 held here) mixes solid and meniscus",
            meniscus_w / w
        )
    }
}
