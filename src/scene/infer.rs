//! The work of adhesion from a measured pull-off force under JKR, DMT and exact MD.

use crate::physics::params::{Contact, ForceRange, ParamError};
use crate::solver::LambdaContext;
use serde::Serialize;

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
