//! The work of adhesion from a measured pull-off force under JKR, DMT and exact MD.

use crate::error::Message;
use crate::physics::params::{Contact, ForceRange, ParamError};
use crate::solver::LambdaContext;
use serde::Serialize;

/// What a measured pull-off says of w under each model.
#[derive(Clone, Debug, Serialize)]
pub struct Inference {
    /// The measured pull-off force (N, positive).
    pub pulloff_force_n: f64,
    /// w if the contact is JKR's (J/m^2).
    pub w_jkr_j_m2: f64,
    /// The Tabor parameter with that w.
    pub tabor_if_jkr: f64,
    /// w if the contact is DMT's (J/m^2).
    pub w_dmt_j_m2: f64,
    /// The Tabor parameter with that w.
    pub tabor_if_dmt: f64,
    /// w from the exact MD pull-off with the given range (J/m^2).
    pub w_md_j_m2: Option<f64>,
    /// The Maugis parameter with that w.
    pub lambda_md: Option<f64>,
    /// Which model the data support, in words.
    pub verdict: String,
    /// A w outside physical sense (the plausible ranges of `tabor fit`).
    pub warnings: Vec<String>,
}

/// A w (J/m^2) outside physical sense beside E* (Pa), as `tabor fit` bounds them, in words.
fn implausible_w(w: f64, e_star: f64) -> Option<String> {
    let (ok, values) = crate::physics::params::plausibility(e_star, w);
    (!ok).then(|| {
        format!("{values}: outside physical sense; check the units of the force (N), the radius (m) and E* (Pa)")
    })
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
                allowed: "a force whose work of adhesion gives a Maugis parameter in 1e-26..1e26 with this R, E* and z0 (check the units)",
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
        crate::numeric::root::bisect_sign(|lw| g(lw.exp()), w_dmt.ln() - 1e-9, w_jkr.ln() + 1e-9)
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
    let trusted = match (mt_j > 5.0, mt_d < 0.1) {
        (true, false) => w_jkr,
        (false, true) => w_dmt,
        _ => w_md,
    };
    let warnings: Vec<String> = implausible_w(trusted, e_star).into_iter().collect();
    let verdict = match (mt_j > 5.0, mt_d < 0.1) {
        _ if !warnings.is_empty() => format!("no w to trust: {}", warnings[0]),
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
        warnings,
    })
}

/// The humidity of a pull-off inference from its options (water at `contact_angle_deg`,
/// default 0): none without a relative humidity, where a contact angle alone is refused rather
/// than ignored.
pub fn wet_options(
    relative_humidity: Option<f64>,
    contact_angle_deg: Option<f64>,
) -> Result<Option<super::humidity::HumidityInput>, ParamError> {
    match (relative_humidity, contact_angle_deg) {
        (None, None) => Ok(None),
        (None, Some(_)) => Err(ParamError::Conflict(
            Message::new()
                .key("humidity.contact_angle_deg")
                .text(" is given without ")
                .key("humidity.relative_humidity")
                .text(", and would be ignored: give the relative humidity the pull-off was measured in, or leave the contact angle out"),
        )),
        (Some(rh), t) => Ok(Some(super::humidity::HumidityInput::water(
            rh,
            t.unwrap_or(0.0),
        ))),
    }
}

/// The solid's work of adhesion from a pull-off force measured in humid air.
#[derive(Clone, Debug, Serialize)]
pub struct WetInference {
    /// The measured pull-off force (N, its magnitude).
    pub pulloff_force_n: f64,
    /// The solid's w with the meniscus taken out (J/m^2); None where the meniscus alone pulls
    /// off harder than measured.
    pub solid_work_of_adhesion_j_m2: Option<f64>,
    /// The solid's Maugis parameter with that w.
    pub solid_lambda: Option<f64>,
    /// The meniscus of the humidity given; null where none forms (a contact angle of 90
    /// degrees or more, or a Kelvin radius below one molecule: the solid's w is then the dry
    /// one, and `no_meniscus` says why).
    pub meniscus: Option<super::humidity::Meniscus>,
    /// The load-controlled pull-off of the meniscus alone (N, its magnitude; 0 without one).
    pub meniscus_only_pulloff_n: f64,
    /// The w a dry analysis (exact MD) would report for the same force (J/m^2).
    pub dry_md_work_of_adhesion_j_m2: Option<f64>,
    /// What to conclude, in one sentence.
    pub verdict: String,
    /// Why no meniscus forms, where none does.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub no_meniscus: Option<String>,
    /// Where the meniscus model is stretched or does not apply, and an implausible w.
    pub warnings: Vec<String>,
}

/// From a pull-off force (N) measured in humid air, R, E*, the Lennard-Jones range z0 of the
/// solid and the humidity: the solid's w whose Dugdale zone, with the meniscus beside it (the
/// two-zone law, docs/PHYSICS.md section 10, solved exactly), pulls off under load control at
/// the measured force. The meniscus' own w, 2 gamma cos(theta), does not depend on the solid's;
/// the pull-off grows with the solid's w, so the root is bracketed between a vanishing solid w
/// and the JKR bound F / (1.5 pi R).
pub fn infer_wet(
    pulloff_n: f64,
    radius: f64,
    e_star: f64,
    z0: f64,
    humidity: &super::humidity::HumidityInput,
) -> Result<WetInference, ParamError> {
    use super::humidity::wet_context;
    let f = pulloff_n.abs();
    let dry = infer(pulloff_n, radius, e_star, z0)?;
    let contact = |w: f64| Contact::new(radius, e_star, w, ForceRange::LennardJones(z0));
    let w_hi = f / (1.5 * std::f64::consts::PI * radius);
    if humidity.relative_humidity == 0.0 {
        return Err(ParamError::Conflict(
            Message::new().key("humidity.relative_humidity").text(
                " = 0 is dry air, where no meniscus forms: leave the humidity out for the dry inference",
            ),
        ));
    }
    let mut out = WetInference {
        pulloff_force_n: f,
        solid_work_of_adhesion_j_m2: None,
        solid_lambda: None,
        meniscus: humidity.meniscus(&contact(w_hi)?)?,
        meniscus_only_pulloff_n: 0.0,
        dry_md_work_of_adhesion_j_m2: dry.w_md_j_m2,
        verdict: String::new(),
        no_meniscus: humidity.no_meniscus(),
        warnings: humidity.warnings(radius),
    };
    let Some(meniscus) = out.meniscus else {
        // No meniscus: the solid holds the whole force, as in dry air.
        out.solid_work_of_adhesion_j_m2 = dry.w_md_j_m2;
        out.solid_lambda = dry.lambda_md;
        out.verdict = format!(
            "no meniscus ({}): the solid's w is the dry Maugis-Dugdale w, {}",
            out.no_meniscus.as_deref().unwrap_or("none forms"),
            dry.w_md_j_m2
                .map_or("not found".into(), |d| format!("{d:.4e} J/m^2"))
        );
        out.warnings.extend(dry.warnings);
        return Ok(out);
    };
    let pulloff = |w: f64| -> Result<f64, ParamError> {
        let c = contact(w)?;
        let (ctx, units) = wet_context(&c, &meniscus)?;
        Ok(-ctx.load_pulloff.load * units.load)
    };
    // A solid w a millionth of the JKR bound: the meniscus alone, to the solver's resolution.
    let w_lo = 1e-6 * w_hi;
    let alone = pulloff(w_lo)?;
    let (w, lam, verdict) = if alone >= f {
        let v = format!(
            "the meniscus alone pulls off at {:.4e} N, more than the {f:.4e} N measured: no solid adhesion is left to infer (a larger contact angle or a lower humidity than given, or a meniscus not in equilibrium)",
            alone
        );
        (None, None, v)
    } else {
        let g = |lw: f64| pulloff(lw.exp()).map_or(f64::NAN, |p| p - f);
        let w = crate::numeric::root::bisect_sign(g, w_lo.ln(), w_hi.ln()).exp();
        let ok = (pulloff(w)? - f).abs() <= 1e-9 * f;
        let lam = contact(w)?.lambda();
        let v = format!(
            "solid w = {w:.4e} J/m^2 (lambda = {lam:.3}) with the meniscus (w = {:.4e} J/m^2) taken out; a dry analysis of the same force would report {}",
            meniscus.work_of_adhesion_j_m2,
            dry.w_md_j_m2.map_or("no MD value".into(), |d| format!("{d:.4e} J/m^2"))
        );
        (ok.then_some(w), ok.then_some(lam), v)
    };
    out.warnings
        .extend(w.and_then(|w| implausible_w(w, e_star)));
    Ok(WetInference {
        solid_work_of_adhesion_j_m2: w,
        solid_lambda: lam,
        meniscus_only_pulloff_n: alone,
        verdict,
        ..out
    })
}
