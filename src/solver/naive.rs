//! The naive f64 method of the public Python reference (the package `adhesion`), for comparison:
//! equation (1) solved for m at a given contact radius with Brent's method on the fixed bracket
//! m in [1, 1e12] (absolute tolerance 2e-12, scipy's default), the textbook formulas with
//! arccos(1/m), and the load-to-state problem solved by a second Brent search on A around that
//! forward map.

use super::LambdaContext;
use crate::physics::closed::{dmt_radius, jkr_radius};
use roots::{find_root_brent, SimpleConvergency};

/// m at contact radius `a`, or None if the fixed bracket holds no root.
pub fn m_of_a(lambda: f64, a: f64) -> Option<f64> {
    let f = |m: f64| {
        let s = (m * m - 1.0).max(0.0).sqrt();
        let asec = (1.0 / m).acos();
        lambda * a * a / 2.0 * ((m * m - 2.0) * asec + s)
            + 4.0 * lambda * lambda * a / 3.0 * (s * asec - m + 1.0)
            - 1.0
    };
    let mut conv = SimpleConvergency {
        eps: 2e-12f64,
        max_iter: 100,
    };
    find_root_brent(1.0, 1e12, f, &mut conv).ok()
}

/// Pbar at contact radius `a` through the forward map.
pub fn load_of_a(lambda: f64, a: f64) -> Option<f64> {
    let m = m_of_a(lambda, a)?;
    let s = (m * m - 1.0).max(0.0).sqrt();
    Some(a * a * a - lambda * a * a * (s + m * m * (1.0 / m).acos()))
}

/// The contact radius at load `load` on the stable branch (A above the exact pull-off radius),
/// or None where the searches fail.
pub fn solve_load(ctx: &LambdaContext, load: f64) -> Option<f64> {
    let lambda = ctx.lambda;
    let a_lo = ctx.load_pulloff.a;
    let mut a_hi = jkr_radius(load)
        .or(dmt_radius(load))
        .unwrap_or(a_lo)
        .max(a_lo)
        * 1.1
        + 0.1;
    for _ in 0..60 {
        if load_of_a(lambda, a_hi)? > load {
            break;
        }
        a_hi *= 2.0;
    }
    let mut conv = SimpleConvergency {
        eps: 2e-12f64,
        max_iter: 200,
    };
    find_root_brent(
        a_lo,
        a_hi,
        |a| load_of_a(lambda, a).unwrap_or(f64::NAN) - load,
        &mut conv,
    )
    .ok()
}
