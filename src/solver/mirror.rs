//! The shaders' f32 arithmetic, on the CPU: read it side by side with `shaders/md.wgsl`.

/// `(atan(mu), mu - atan(mu))` in f32 from the half-angle reduction and the Maclaurin series
/// only (no built-in atan: lavapipe's inverse trigonometric built-ins are off by up to 1.6e-4).
/// For mu > 1, `atan(mu) = pi/2 - atan(1/mu)`. Max relative error about 3 ulp (measured by the
/// tests below against f64).
pub fn atan_parts_f32(mu: f32) -> (f32, f32) {
    let big = mu > 1.0;
    let t0 = if big { 1.0 / mu } else { mu };
    let mut t = t0;
    let mut weight = 1.0f32;
    let mut acc = 0.0f32;
    while t > 0.1 {
        let onem = 1.0 + (1.0 + t * t).sqrt();
        acc += weight * t * t * t / (onem * onem);
        t /= onem;
        weight *= 2.0;
    }
    let z = t * t;
    let series = t * z * (1.0 / 3.0 - z * (1.0 / 5.0 - z * (1.0 / 7.0 - z * (1.0 / 9.0))));
    let d0 = acc + weight * series; // t0 - atan(t0)
    if big {
        let at = std::f32::consts::FRAC_PI_2 - (t0 - d0);
        (at, mu - at)
    } else {
        (mu - d0, d0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn f32_atan_parts_are_accurate_over_the_whole_range() {
        let (mut worst_at, mut worst_d) = (0.0f64, 0.0f64);
        for i in 0..20001 {
            let mu = 10f32.powf(-9.0 + 19.0 * i as f32 / 20000.0);
            let (at, d) = atan_parts_f32(mu);
            let m = mu as f64;
            let at64 = m.atan();
            let (_, d64) = crate::physics::real::Real::atan_parts(m);
            worst_at = worst_at.max((at as f64 / at64 - 1.0).abs());
            worst_d = worst_d.max((d as f64 / d64 - 1.0).abs());
        }
        assert!(worst_at < 3.0e-7, "atan: {worst_at:e}");
        assert!(worst_d < 6.0e-7, "mu - atan: {worst_d:e}");
    }
}

use crate::gpu::layout::{Branch, GpuLambda, Out, TABLE_NODES};
use crate::gpu::prepare::cheb_eval;
use crate::physics::md::curve_point;
use crate::solver::{Control, Status};

const LN2_HI: f32 = 0.693_145_75;
const LN2_LO: f32 = 1.428_606_8e-6;
const LOG2E: f32 = std::f32::consts::LOG2_E;

/// 2^n for integer n in the normal range (WGSL: `ldexp`).
fn ldexp(x: f32, n: i32) -> f32 {
    x * f32::from_bits(((n + 127).clamp(1, 254) as u32) << 23)
}

/// exp with Cody-Waite reduction and a degree-7 Taylor polynomial: within 2 ulp for all
/// |x| < 87 (the Vulkan built-in is allowed 3 + 2|x| ulp).
pub fn exp_f32(x: f32) -> f32 {
    let x = x.clamp(-87.0, 88.0);
    let n = (x * LOG2E).round();
    let r = (x - n * LN2_HI) - n * LN2_LO;
    let p = 1.0
        + r * (1.0
            + r * (0.5
                + r * (1.0 / 6.0
                    + r * (1.0 / 24.0
                        + r * (1.0 / 120.0 + r * (1.0 / 720.0 + r * (1.0 / 5040.0)))))));
    let n = n as i32;
    // Two steps so that 2^n never overflows on its own.
    ldexp(ldexp(p, n / 2), n - n / 2)
}

/// ln y for y > 0 from the exponent and 2 atanh((m-1)/(m+1)), m in [sqrt(1/2), sqrt(2)).
pub fn ln_f32(y: f32) -> f32 {
    if y <= 0.0 {
        return f32::NEG_INFINITY;
    }
    if !y.is_finite() {
        return f32::INFINITY;
    }
    // frexp for normal numbers (WGSL: `frexp`).
    let bits = y.to_bits();
    let mut e = ((bits >> 23) & 0xff) as i32 - 126;
    let mut m = f32::from_bits((bits & 0x807f_ffff) | (126 << 23));
    if m < std::f32::consts::FRAC_1_SQRT_2 {
        m *= 2.0;
        e -= 1;
    }
    let u = (m - 1.0) / (m + 1.0);
    let z = u * u;
    let series = 2.0
        * u
        * (1.0
            + z * (1.0 / 3.0
                + z * (1.0 / 5.0 + z * (1.0 / 7.0 + z * (1.0 / 9.0 + z * (1.0 / 11.0))))));
    e as f32 * LN2_HI + (e as f32 * LN2_LO + series)
}

/// ln(1 + q), accurate for small q (the residual near convergence).
pub fn log1p_f32(q: f32) -> f32 {
    if q.abs() < 0.25 {
        let u = q / (2.0 + q);
        let z = u * u;
        2.0 * u * (1.0 + z * (1.0 / 3.0 + z * (1.0 / 5.0 + z * (1.0 / 7.0 + z * (1.0 / 9.0)))))
    } else {
        ln_f32(1.0 + q)
    }
}

fn branch(g: &GpuLambda, control: Control) -> &Branch {
    match control {
        Control::Load => &g.load,
        Control::Displacement => &g.disp,
    }
}

/// Variant switch (bit 0 of `flags`): the textbook formulas, to show what the shipped ones avoid.
pub const FLAG_NAIVE: u32 = 1;

/// The curve point from the formulas as printed: `(m^2 - 2) arcsec m + mu` and `m - 1` by
/// subtraction, which cancel as m -> 1 (the JKR side). Same atan as the shipped kernel.
pub fn curve_point_naive(lambda: f32, mu: f32) -> crate::physics::md::CurvePoint<f32> {
    let (at, _) = atan_parts_f32(mu);
    let m = (1.0 + mu * mu).sqrt();
    let m_minus_1 = m - 1.0;
    let f1 = (m * m - 2.0) * at + mu;
    let f2 = mu * at - m_minus_1;
    let alpha = 0.5 * lambda * f1;
    let beta = 4.0 / 3.0 * lambda * lambda * f2;
    let a = (-beta + (beta * beta + 4.0 * alpha).sqrt()) / (2.0 * alpha);
    let load = a * a * a - lambda * a * a * (mu + m * m * at);
    let approach = a * a - 4.0 / 3.0 * lambda * a * mu;
    crate::physics::md::CurvePoint {
        mu,
        a,
        m_minus_1,
        load_plus_2: load + 2.0,
        load,
        approach,
        dload_dmu: f32::NAN,
        dapproach_dmu: f32::NAN,
    }
}

fn point_f32(g: &GpuLambda, mu: f32, naive: bool) -> crate::physics::md::CurvePoint<f32> {
    if naive {
        curve_point_naive(g.lambda, mu)
    } else {
        curve_point(g.lambda, mu)
    }
}

/// The residual's quantity: Pbar + 2 (small lambda) or Pbar, or Dbar.
fn quantity(g: &GpuLambda, control: Control, mu: f32, naive: bool) -> f32 {
    let p = point_f32(g, mu, naive);
    match control {
        Control::Load if g.small == 1 && !naive => p.load_plus_2,
        Control::Load => p.load,
        Control::Displacement => p.approach,
    }
}

/// F = ln(gap(mu) / gap): zero at the root, positive farther from the branch end. The naive
/// variant subtracts one f32 branch end.
fn residual(g: &GpuLambda, control: Control, mu: f32, gap: f32, naive: bool) -> f32 {
    let b = branch(g, control);
    let r = if naive {
        (quantity(g, control, mu, true) - naive_end(g, control)) - gap
    } else {
        ((quantity(g, control, mu, false) - b.end_hi) - b.end_lo) - gap
    };
    let q = r / gap;
    if q <= -1.0 {
        f32::NEG_INFINITY
    } else {
        log1p_f32(q)
    }
}

/// The branch end as one f32 in the residual's naive units (Pbar, not Pbar + 2).
fn naive_end(g: &GpuLambda, control: Control) -> f32 {
    let b = branch(g, control);
    let shift = if control == Control::Load && g.small == 1 {
        2.0
    } else {
        0.0
    };
    ((b.end_hi as f64 + b.end_lo as f64) - shift) as f32
}

/// The f32 solve of one point, exactly as `shaders/md.wgsl` does it. The load (approach) comes
/// as an unevaluated pair `hi + lo` (about 48 bits), so that its distance from the branch end is
/// exact: an f32 load near Pbar_c = -2 is already off by 1e-4 of a gap of 1e-3. With `is_gap`
/// the pair is that distance itself. `flags` as the kernels' Params: bit 0 [`FLAG_NAIVE`], bits
/// 8..15 an iteration limit (0: the default, 32).
pub fn solve_f32(
    g: &GpuLambda,
    hi: f32,
    lo: f32,
    control: Control,
    is_gap: bool,
    flags: u32,
) -> Out {
    let value = hi;
    let naive = flags & FLAG_NAIVE != 0;
    let max_iter = (flags >> 8) & 0xff;
    let fail = |st: Status| Out {
        a: f32::NAN,
        other: f32::NAN,
        m_minus_1: f32::NAN,
        code: st as u32,
    };
    if g.invalid == 1 || !value.is_finite() {
        return fail(Status::InvalidInput);
    }
    let b = branch(g, control);
    let zero_end = control == Control::Displacement && g.disp_at_zero == 1;
    let shift = if control == Control::Load && g.small == 1 {
        2.0
    } else {
        0.0
    };
    // hi + shift - end_hi is exact where it matters (Sterbenz), then the low parts are added.
    let gap = if naive {
        if is_gap {
            hi
        } else {
            hi - naive_end(g, control)
        }
    } else if is_gap {
        hi + lo
    } else {
        ((hi + shift) - b.end_hi) + (lo - b.end_lo)
    };
    if gap < 0.0 {
        return fail(Status::NoContact);
    }
    let mut iterations = 0u32;
    let mut status = Status::Ok;
    let mu;
    if gap == 0.0 {
        if zero_end {
            let load = g.end_load;
            return Out {
                a: 0.0,
                other: load,
                m_minus_1: f32::INFINITY,
                code: 0,
            };
        }
        mu = b.mu_ref;
    } else if !naive && gap.sqrt() < b.s_max {
        let s = gap.sqrt();
        let dx = s * cheb_eval(&b.cheb, 2.0 * s / b.s_max - 1.0);
        mu = b.mu_ref * exp_f32(dx);
    } else {
        let t = ln_f32(gap);
        let n = TABLE_NODES;
        // First node with t_k >= t (the shader's binary search gives the same k).
        let k = b.t.partition_point(|&tk| tk < t);
        // Bracket one node wider than the interval, in case a node's f32 mu sits on the root.
        let end_dx = if zero_end { b.dx[0] + 60.0 } else { 0.0 };
        let (mut hi, mut f_hi) = if k >= 2 {
            (b.dx[k - 2], b.t[k - 2] - t)
        } else {
            (end_dx, f32::NEG_INFINITY)
        };
        let (mut lo, mut f_lo) = if k + 1 < n {
            (b.dx[k + 1], b.t[k + 1] - t)
        } else {
            (b.dx[n - 1] - 120.0, f32::INFINITY)
        };
        // First guess: linear in (t, ln|dx|) for an interior end (exact near it), else in (t, dx).
        let mut x = if k == 0 {
            if zero_end {
                b.dx[0] + 1.0
            } else {
                b.dx[0] * exp_f32(0.5 * (t - b.t[0]))
            }
        } else if k == n {
            b.dx[n - 1] - 1.0
        } else {
            let w = (t - b.t[k - 1]) / (b.t[k] - b.t[k - 1]);
            if zero_end {
                b.dx[k - 1] + w * (b.dx[k] - b.dx[k - 1])
            } else {
                -exp_f32(ln_f32(-b.dx[k - 1]) + w * (ln_f32(-b.dx[k]) - ln_f32(-b.dx[k - 1])))
            }
        };
        if !(x > lo && x < hi) {
            x = 0.5 * (lo + hi);
        }
        // Secant in x = ln(mu/mu_ref) with a bisection safeguard; mu is carried separately and
        // updated multiplicatively, since an f32 x near 14 resolves mu only to 1e-6.
        let max_iter = if max_iter == 0 { 32 } else { max_iter };
        let mut m = b.mu_ref * exp_f32(x);
        let (mut f_prev, mut l_prev) = (f32::NAN, 0.0f32);
        let mut dx_old = hi - lo;
        let mut done = false;
        // The best iterate so far: what an iteration cap returns (a safeguard bisection can be
        // the last step taken).
        let (mut best_f, mut best_m) = (f32::INFINITY, m);
        for it in 1..=max_iter {
            iterations = it;
            let fx = residual(g, control, m, gap, naive);
            if fx.abs() < best_f {
                (best_f, best_m) = (fx.abs(), m);
            }
            // |F| at the f32 noise level (a relative error of the gap of 8e-7): done. Below it
            // the secant slope is noise.
            if fx.abs() <= 8e-7 {
                done = true;
                break;
            }
            if fx > 0.0 {
                (lo, f_lo) = (x, fx);
            } else {
                (hi, f_hi) = (x, fx);
            }
            if hi - lo <= 4e-7 * x.abs().max(1.0) {
                done = true;
                break;
            }
            let slope = if f_prev.is_finite() && l_prev != 0.0 {
                (fx - f_prev) / l_prev
            } else if fx > 0.0 {
                (f_hi - fx) / (hi - x)
            } else {
                (f_lo - fx) / (lo - x)
            };
            let step = -fx / slope;
            // The last step is applied, so stopping at the noise level of F still lands within
            // a few ulp of mu.
            if step.is_finite() && step.abs() <= 2.5e-7 {
                m *= exp_f32(step);
                done = true;
                break;
            }
            let next = x + step;
            f_prev = fx;
            // Non-strict: a step below the ulp of x still moves mu, which is carried apart.
            if step.is_finite() && next >= lo && next <= hi && step.abs() < 0.5 * dx_old.abs() {
                m *= exp_f32(step);
                l_prev = step;
                dx_old = step;
                x = next;
            } else {
                let mid = 0.5 * (lo + hi);
                let m_new = b.mu_ref * exp_f32(mid);
                l_prev = ln_f32(m_new / m);
                dx_old = mid - x;
                x = mid;
                m = m_new;
            }
        }
        if !done {
            status = Status::NotConverged;
            m = best_m;
        }
        mu = m;
    }
    let p = point_f32(g, mu, naive);
    let other = match control {
        Control::Load => p.approach,
        Control::Displacement => p.load,
    };
    Out {
        a: p.a,
        other,
        m_minus_1: p.m_minus_1,
        code: status as u32 | (iterations << 8),
    }
}

#[cfg(test)]
mod solver_tests {
    use super::*;

    #[test]
    fn own_exp_and_ln_are_within_a_few_ulp() {
        let (mut we, mut wl) = (0.0f64, 0.0f64);
        for i in 0..20001 {
            let x = -80.0 + 160.0 * i as f32 / 20000.0;
            we = we.max((exp_f32(x) as f64 / (x as f64).exp() - 1.0).abs());
            let y = 10f32.powf(-30.0 + 60.0 * i as f32 / 20000.0);
            let l = (y as f64).ln();
            wl = wl.max((ln_f32(y) as f64 - l).abs() / l.abs().max(1.0));
        }
        assert!(we < 2.5e-7, "exp {we:e}");
        assert!(wl < 2.5e-7, "ln {wl:e}");
        for &q in &[1e-7f32, -1e-5, 0.1, -0.2, 0.3, 5.0] {
            assert!(
                (log1p_f32(q) as f64 / (q as f64).ln_1p() - 1.0).abs() < 3e-7,
                "log1p({q})"
            );
        }
    }
}
