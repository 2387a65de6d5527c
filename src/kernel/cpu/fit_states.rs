//! The CPU mirror of `shaders/fit_states.wgsl`: one force-map point's state on its curve's
//! Maugis-Dugdale contact piece, by Newton steps in mu inside the host's bracket, as the kernel
//! takes them. Read it side by side with the shader.

use super::polish64::curve_point64;
use crate::kernel::layout::{FitCurve64, FitOut64, FitPoint64};

/// The state of `pt` on curve `c`'s path (`fit_states` in the shader).
pub fn fit_state(c: &FitCurve64, pt: &FitPoint64) -> FitOut64 {
    let (mut lo, mut hi) = (pt.mu_lo, pt.mu_hi);
    // WGSL's clamp for an ordered bracket (the host's always is), without Rust's panic on a
    // reversed one.
    let mut mu = pt.mu_start.max(lo).min(hi);
    let (mut code, mut steps) = (2u32, 0u32);
    let mut p = curve_point64(c.lambda, mu);
    for it in 0..100u32 {
        steps = it + 1;
        let d = p.approach + p.load / c.kbar;
        let r = d - pt.delta;
        let tol = 1e-15 * (p.approach.abs() + (p.load / c.kbar).abs()).max(1.0);
        if r.abs() <= tol {
            code = 0;
            break;
        }
        // Delta falls with mu: above the target, the root lies at larger mu.
        if r > 0.0 {
            lo = mu;
        } else {
            hi = mu;
        }
        let s = p.dapproach + p.dload / c.kbar;
        let newton = mu - r / s;
        let next = if s < 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if next == mu || !(hi > lo) {
            code = 0;
            break;
        }
        mu = next;
        p = curve_point64(c.lambda, mu);
    }
    FitOut64 {
        mu,
        load: p.load,
        approach: p.approach,
        code: code | (steps << 8),
        _pad: 0,
    }
}
