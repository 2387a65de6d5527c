//! Bracketed root finding: a safeguarded secant iteration that says why it stopped, Newton's
//! method kept in its bracket, and bisection on a sign to the last bit.

/// Why a root search ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// The step fell below the tolerance, the bracket closed, or the residual was exactly zero.
    Converged,
    /// The iteration limit was reached; the best bracketed estimate is returned.
    MaxIterations,
}

#[derive(Clone, Copy, Debug)]
/// A root found by a bracketed search.
pub struct Root {
    /// The root.
    pub x: f64,
    /// Iterations used.
    pub iterations: u32,
    /// Why the search stopped.
    pub stop: Stop,
}

/// Finds `x` in `[lo, hi]` with `f(x) = 0`, given `f(lo) > 0 > f(hi)` (values may be
/// infinite). Secant steps through the latest point and the opposite bracket end, or the previous
/// point; a step that leaves the bracket or fails to halve the previous one becomes a bisection,
/// so the iteration cannot jump to another branch. Derivative-free on purpose: along the DMT side
/// the slope of the load is a difference of terms larger by lambda^-3, while the residual itself
/// is computed without cancellation.
pub fn secant_bracketed(
    mut f: impl FnMut(f64) -> f64,
    (mut lo, mut f_lo): (f64, f64),
    (mut hi, mut f_hi): (f64, f64),
    x0: f64,
    rel_tol: f64,
    max_iter: u32,
) -> Root {
    let mut x = if x0 > lo && x0 < hi {
        x0
    } else {
        0.5 * (lo + hi)
    };
    let (mut x_prev, mut f_prev) = (f64::NAN, f64::NAN);
    let mut dx_old = hi - lo;
    for it in 1..=max_iter {
        let fx = f(x);
        if fx == 0.0 {
            return Root {
                x,
                iterations: it,
                stop: Stop::Converged,
            };
        }
        if fx > 0.0 {
            (lo, f_lo) = (x, fx);
        } else {
            (hi, f_hi) = (x, fx);
        }
        // Secant through the previous iterate if it exists, else through the bracket end on the
        // other side of the root.
        let (xa, fa) = if f_prev.is_finite() {
            (x_prev, f_prev)
        } else if fx > 0.0 {
            (hi, f_hi)
        } else {
            (lo, f_lo)
        };
        // A partner with an infinite residual (at the pull-off itself) gives no slope.
        let step = if fa.is_finite() {
            -fx * (x - xa) / (fx - fa)
        } else {
            f64::NAN
        };
        let tol = rel_tol * x.abs().max(1.0);
        // Test convergence before the bracket: a step below one ulp rounds onto the bracket end.
        if step.abs() <= tol {
            return Root {
                x: x + step,
                iterations: it,
                stop: Stop::Converged,
            };
        }
        let next = x + step;
        let ok = step.is_finite() && next > lo && next < hi && step.abs() < 0.5 * dx_old.abs();
        let next = if ok { next } else { 0.5 * (lo + hi) };
        dx_old = next - x;
        (x_prev, f_prev) = (x, fx);
        if hi - lo <= tol {
            return Root {
                x: next,
                iterations: it,
                stop: Stop::Converged,
            };
        }
        x = next;
    }
    Root {
        x,
        iterations: max_iter,
        stop: Stop::MaxIterations,
    }
}

/// The root of an increasing `f` in `[lo, hi]` (`f(lo) < 0 <= f(hi)`) by Newton's method from
/// `x0`, `f` giving the value and the slope: each step narrows the bracket, and a step that
/// would leave it is a bisection. Stops when a step, or the bracket, is within 4 ulp.
pub fn newton_bracketed(
    mut f: impl FnMut(f64) -> (f64, f64),
    mut lo: f64,
    mut hi: f64,
    x0: f64,
) -> f64 {
    let close =
        |a: f64, b: f64, scale: f64| (a - b).abs() <= 4.0 * f64::EPSILON * scale.abs().max(1.0);
    let mut x = x0;
    for _ in 0..200 {
        let (r, d) = f(x);
        if r < 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let newton = x - r / d;
        let next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if close(next, x, x) || close(hi, lo, hi) {
            return next;
        }
        x = next;
    }
    x
}

/// Bisection on the sign of `s(x)`, with `s(lo) < 0 < s(hi)`, to the last representable bit.
pub fn bisect_sign(mut s: impl FnMut(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if s(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn secant_finds_cube_root_and_counts_iterations() {
        let r = secant_bracketed(
            |x| 8.0 - x * x * x,
            (0.0, 8.0),
            (10.0, -992.0),
            5.0,
            1e-15,
            100,
        );
        assert_eq!(r.stop, Stop::Converged);
        assert!((r.x - 2.0).abs() < 1e-14);
        assert!(r.iterations < 20);
    }

    #[test]
    fn secant_reports_iteration_limit() {
        let r = secant_bracketed(
            |x| 8.0 - x * x * x,
            (0.0, 8.0),
            (10.0, -992.0),
            5.0,
            1e-15,
            2,
        );
        assert_eq!(r.stop, Stop::MaxIterations);
    }

    #[test]
    fn bisect_sign_reaches_last_bit() {
        let x = bisect_sign(|x| x * x - 2.0, 0.0, 2.0);
        assert!((x - 2f64.sqrt()).abs() <= 4.5e-16);
    }
}
