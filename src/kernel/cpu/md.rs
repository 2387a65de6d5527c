//! The CPU mirror of `shaders/md.wgsl`: the f32 solve of one point, line by line as the kernel
//! does it. Read it side by side with the shader.

use crate::kernel::layout::{Branch, GpuLambda, Out, TABLE_NODES};
use crate::kernel::prepare::cheb_eval;
use crate::physics::f32math::{atan_parts_f32, exp_f32, ln_f32, log1p_f32};
use crate::physics::md::{curve_point, CurvePoint};
use crate::solver::{Control, Status};

// The iteration's thresholds, shared with the shader through its prelude.
pub use crate::physics::tolerances::{
    BRACKET_ABOVE, BRACKET_BELOW, BRACKET_CLOSED, F_NOISE, MAX_ITER, SUB_ULP_STEP,
};

fn branch(g: &GpuLambda, control: Control) -> &Branch {
    match control {
        Control::Load => &g.load,
        Control::Displacement => &g.disp,
    }
}

pub use crate::kernel::layout::KernelFlags;

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
        da_dmu: f32::NAN,
    }
}

fn point_f32(g: &GpuLambda, mu: f32, naive: bool) -> crate::physics::md::CurvePoint<f32> {
    if naive {
        curve_point_naive(g.lambda, mu)
    } else {
        curve_point(g.lambda, mu)
    }
}

/// The residual's quantity: Dbar under displacement control, else Pbar + 2 (small lambda) or Pbar.
fn quantity(p: &CurvePoint<f32>, g: &GpuLambda, control: Control, naive: bool) -> f32 {
    match control {
        Control::Displacement => p.approach,
        Control::Load if g.small == 1 && !naive => p.load_plus_2,
        Control::Load => p.load,
    }
}

/// F = ln(gap(mu) / gap): zero at the root, positive farther from the branch end. The naive
/// variant subtracts the branch end as one f32 in Pbar (not Pbar + 2).
fn residual(p: &CurvePoint<f32>, g: &GpuLambda, control: Control, gap: f32, naive: bool) -> f32 {
    let b = branch(g, control);
    let r = if naive {
        (quantity(p, g, control, true) - naive_end(g, control)) - gap
    } else {
        ((quantity(p, g, control, false) - b.end_hi) - b.end_lo) - gap
    };
    log1p_f32(r / gap)
}

/// The branch end as one f32 in the residual's naive units (Pbar, not Pbar + 2).
fn naive_end(g: &GpuLambda, control: Control) -> f32 {
    let b = branch(g, control);
    (b.end_hi - shift(g, control)) + b.end_lo
}

/// 2 where the load residual is written as Pbar + 2 (small lambda).
fn shift(g: &GpuLambda, control: Control) -> f32 {
    if control == Control::Load && g.small == 1 {
        2.0
    } else {
        0.0
    }
}

/// `p + c (p - q)` field by field: the state moved along the last secant.
fn lerp_point(p: &CurvePoint<f32>, q: &CurvePoint<f32>, c: f32) -> CurvePoint<f32> {
    let l = |a: f32, b: f32| a + c * (a - b);
    CurvePoint {
        mu: l(p.mu, q.mu),
        a: l(p.a, q.a),
        m_minus_1: l(p.m_minus_1, q.m_minus_1),
        load_plus_2: l(p.load_plus_2, q.load_plus_2),
        load: l(p.load, q.load),
        approach: l(p.approach, q.approach),
        dload_dmu: f32::NAN,
        dapproach_dmu: f32::NAN,
        da_dmu: f32::NAN,
    }
}

/// The f32 solve of one point, exactly as `shaders/md.wgsl` does it. The load (approach) comes
/// as an unevaluated pair `hi + lo` (about 48 bits), so that its distance from the branch end is
/// exact: an f32 load near Pbar_c = -2 is already off by 1e-4 of a gap of 1e-3. With `is_gap`
/// the pair is that distance itself. `flags`: the textbook formulas, and an iteration cap (0:
/// iterate to convergence, at most [`MAX_ITER`]).
pub fn solve_f32(
    g: &GpuLambda,
    hi: f32,
    lo: f32,
    control: Control,
    is_gap: bool,
    flags: KernelFlags,
) -> Out {
    solve_f32_started(g, None, hi, lo, control, is_gap, flags)
}

/// The root search's first x = ln(mu / mu_ref), the slope dF/dx for its first step, and the
/// bracket around it (the shader's `first_guess`).
struct Guess {
    /// x is the answer: no search (the Chebyshev fit near the branch end).
    direct: bool,
    x: f32,
    slope0: f32,
    lo_x: f32,
    f_lo: f32,
    hi_x: f32,
    f_hi: f32,
}

/// Near the branch end the Chebyshev fit gives x directly (one evaluation); elsewhere the
/// table brackets the root and gives the first guess, or the lambda's dense start where the
/// grid has one (load control only).
fn first_guess(
    b: &Branch,
    start: Option<&[u32]>,
    gap: f32,
    control: Control,
    naive: bool,
    zero_end: bool,
) -> Guess {
    let s = gap.sqrt();
    let direct = gap == 0.0 || (!naive && s < b.s_max);
    let start = start.filter(|_| control == Control::Load && !naive);
    let n = TABLE_NODES;
    let (mut lo_x, mut f_lo) = (b.dx[n - 1] - BRACKET_BELOW, f32::INFINITY);
    let end_dx = if zero_end {
        b.dx[0] + BRACKET_ABOVE
    } else {
        0.0
    };
    let (mut hi_x, mut f_hi) = (end_dx, f32::NEG_INFINITY);
    if direct {
        let x = if gap == 0.0 {
            0.0
        } else {
            s * cheb_eval(&b.cheb, 2.0 * s / b.s_max - 1.0)
        };
        return Guess {
            direct,
            x,
            slope0: 0.0,
            lo_x,
            f_lo,
            hi_x,
            f_hi,
        };
    }
    let t = ln_f32(gap);
    // First node with t_k >= t (the shader's binary search gives the same k).
    let k = b.t.partition_point(|&tk| tk < t);
    // Bracket one node wider than the interval, in case a node's f32 mu sits on the root.
    if k >= 2 {
        (hi_x, f_hi) = (b.dx[k - 2], b.t[k - 2] - t);
    }
    if k + 1 < n {
        (lo_x, f_lo) = (b.dx[k + 1], b.t[k + 1] - t);
    }
    let mut x = b.dx[n - 1] - 1.0;
    if k < n {
        let k1 = k.max(1);
        let d0 = b.dx[k1 - 1];
        let w = (t - b.t[k1 - 1]) / (b.t[k1] - b.t[k1 - 1]);
        x = if zero_end {
            if k == 0 {
                b.dx[0] + 1.0
            } else {
                d0 + w * (b.dx[k1] - d0)
            }
        } else {
            // Interior nodes double (dx_k = dx_0 2^k), so ln|dx| is linear in k between
            // nodes; before the first node the gap is quadratic in dx.
            let e = if k == 0 {
                0.5 * (t - b.t[0])
            } else {
                w * std::f32::consts::LN_2
            };
            d0 * exp_f32(e)
        };
    }
    // The first step's slope dF/dx = dt/dx: the table's chord around the guess.
    let kc = k.clamp(1, n - 1);
    let mut slope0 = (b.t[kc] - b.t[kc - 1]) / (b.dx[kc] - b.dx[kc - 1]);
    // The dense start: x to about f32 precision and its own slope, so that the first
    // evaluation is usually the answer.
    if let Some((xs, ss)) = start.and_then(|blk| crate::kernel::start::start_x(blk, t)) {
        x = xs;
        slope0 = ss;
    }
    if !(x > lo_x && x < hi_x) {
        x = 0.5 * (lo_x + hi_x);
    }
    Guess {
        direct,
        x,
        slope0,
        lo_x,
        f_lo,
        hi_x,
        f_hi,
    }
}

/// As [`solve_f32`], with the lambda's dense start (its block, `kernel::start`) where it has
/// one: the grid kernel's solve.
pub fn solve_f32_started(
    g: &GpuLambda,
    start: Option<&[u32]>,
    hi: f32,
    lo: f32,
    control: Control,
    is_gap: bool,
    flags: KernelFlags,
) -> Out {
    let (naive, max_iter) = (flags.naive, flags.max_iter);
    let b = branch(g, control);
    let zero_end = control == Control::Displacement && g.disp_at_zero == 1;
    let gap = match gap_above_end(g, hi, lo, control, is_gap, naive) {
        Ok(gap) => gap,
        Err(out) => return out,
    };
    let Guess {
        direct,
        mut x,
        slope0,
        mut lo_x,
        mut f_lo,
        mut hi_x,
        mut f_hi,
    } = first_guess(b, start, gap, control, naive, zero_end);
    // Secant in x with a bisection safeguard; mu is carried apart and updated multiplicatively,
    // since an f32 x near 14 resolves mu only to 1e-6.
    let max_iter = if max_iter == 0 { MAX_ITER } else { max_iter };
    let mut m = b.mu_ref * exp_f32(x);
    let mut p = CurvePoint::<f32>::default();
    let mut prev: Option<(CurvePoint<f32>, f32, f32)> = None; // point, F, ln step to the next
    let mut dx_old = hi_x - lo_x;
    let mut rf_last = false;
    let mut done = false;
    let mut iterations = 0;
    // The best iterate so far: what an iteration cap returns.
    let (mut best_f, mut best) = (f32::INFINITY, p);
    for it in 1..=max_iter {
        iterations = it;
        p = point_f32(g, m, naive);
        let fx = residual(&p, g, control, gap, naive);
        if fx.abs() < best_f {
            (best_f, best) = (fx.abs(), p);
        }
        // The direct start is the answer; |F| at the f32 noise level (a relative error of the
        // gap of 8e-7) is done: below it the secant slope is noise.
        if direct || fx.abs() <= F_NOISE {
            done = true;
            break;
        }
        if fx > 0.0 {
            (lo_x, f_lo) = (x, fx);
        } else {
            (hi_x, f_hi) = (x, fx);
        }
        if hi_x - lo_x <= BRACKET_CLOSED * x.abs().max(1.0) {
            done = true;
            break;
        }
        // Secant slope; before there is one, the table's; without either, the chord to the
        // bracket end on the other side.
        let slope = match prev {
            None => slope0,
            Some((_, f_prev, l_prev)) if f_prev.is_finite() && l_prev != 0.0 => {
                (fx - f_prev) / l_prev
            }
            Some(_) if fx > 0.0 => (f_hi - fx) / (hi_x - x),
            Some(_) => (f_lo - fx) / (lo_x - x),
        };
        let step = -fx / slope;
        // A zero step from an infinite slope is no step: bisect.
        let finite = step.is_finite() && step != 0.0;
        // A step below 4 ulp of x: the state there is this one moved along the last secant
        // (the error is second order in the step), not one more evaluation.
        if let Some((q, _, l_prev)) = prev.filter(|&(_, _, l)| {
            finite && step.abs() <= SUB_ULP_STEP * x.abs().max(1.0) && l != 0.0
        }) {
            p = lerp_point(&p, &q, step / l_prev);
            done = true;
            break;
        }
        let next = x + step;
        // Non-strict: a step below the ulp of x still moves mu, which is carried apart.
        let take = finite && next >= lo_x && next <= hi_x && step.abs() < 0.5 * dx_old.abs();
        // Else regula falsi on the bracket, which lands next to an end whose F is already at
        // the noise level (bisection would walk back from the far end), but never twice in a
        // row, so that the bracket at least halves every other step.
        let rf = lo_x - f_lo * (hi_x - lo_x) / (f_hi - f_lo);
        let use_rf = !take && !rf_last && rf > lo_x && rf < hi_x;
        rf_last = use_rf;
        let target = if use_rf { rf } else { 0.5 * (lo_x + hi_x) };
        let d = if take { step } else { target - x };
        m *= exp_f32(d);
        x = if take { next } else { target };
        prev = Some((p, fx, d));
        dx_old = d;
    }
    finish(if done { Some(p) } else { None }, best, control, iterations)
}

/// The distance of the load (approach) `hi + lo` above the branch end, or the point's answer
/// where there is nothing to search: invalid input, no contact, or the zero-radius end itself.
fn gap_above_end(
    g: &GpuLambda,
    hi: f32,
    lo: f32,
    control: Control,
    is_gap: bool,
    naive: bool,
) -> Result<f32, Out> {
    let fail = |st: Status| Out {
        a: f32::NAN,
        other: f32::NAN,
        m_minus_1: f32::NAN,
        code: st as u32,
    };
    if g.invalid == 1 || !hi.is_finite() {
        return Err(fail(Status::InvalidInput));
    }
    let b = branch(g, control);
    let zero_end = control == Control::Displacement && g.disp_at_zero == 1;
    let shift = shift(g, control);
    // hi + shift - end_hi is exact where it matters (Sterbenz), then the low parts are added.
    let gap = match (naive, is_gap) {
        (true, true) => hi,
        (true, false) => hi - naive_end(g, control),
        (false, true) => hi + lo,
        (false, false) => ((hi + shift) - b.end_hi) + (lo - b.end_lo),
    };
    if gap < 0.0 {
        return Err(fail(Status::NoContact));
    }
    if gap == 0.0 && zero_end {
        return Err(Out {
            a: 0.0,
            other: g.end_load,
            m_minus_1: f32::INFINITY,
            code: 0,
        });
    }
    Ok(gap)
}

/// The answer: the converged point, or the best iterate where the cap was reached (status not
/// converged), with the iterations in the code's high bits.
fn finish(
    done: Option<CurvePoint<f32>>,
    best: CurvePoint<f32>,
    control: Control,
    iterations: u32,
) -> Out {
    let (p, mut status) = match done {
        Some(p) => (p, Status::Ok),
        None => (best, Status::NotConverged),
    };
    let other = match control {
        Control::Load => p.approach,
        Control::Displacement => p.load,
    };
    // Only the naive formulas can produce a non-number (0/0 where m - 1 rounds to 0): say so.
    if !(p.a.is_finite() && other.is_finite()) {
        status = Status::NotConverged;
    }
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

#[cfg(test)]
mod convergence_tests {
    use super::*;
    use crate::kernel::prepare::{prepare, split};
    use crate::solver::LambdaContext;

    fn solve(lambda: f64, load: f64) -> (Out, f64) {
        let (h, l) = split(load);
        let o = solve_f32(
            &prepare(lambda),
            h,
            l,
            Control::Load,
            false,
            KernelFlags::SHIPPED,
        );
        let exact = LambdaContext::new(lambda).unwrap().solve_load(load).a;
        (o, (o.a as f64 / exact - 1.0).abs())
    }

    /// Points where the iteration once stalled: an infinite one-sided slope gave a zero step
    /// (lambda 40.7, 7.8e-4 above pull-off), and bisection walked back from the far bracket
    /// end for 17 steps after F had reached its noise level (lambda 0.087).
    #[test]
    fn former_stalls_converge_in_a_few_iterations() {
        for (lambda, load) in [
            (40.67699994427719, -1.4993233551422893),
            (0.08736731189508772, 0.0011140914),
        ] {
            let (o, e) = solve(lambda, load);
            assert_eq!(o.status(), Status::Ok, "lambda {lambda}");
            assert!(o.iterations() <= 5, "lambda {lambda}: {}", o.iterations());
            assert!(e < 5e-6, "lambda {lambda}: {e:e}");
        }
    }

    /// The classic map's grid: every point within a few iterations (a lane that iterates long
    /// holds up its whole SIMD group on a software adapter).
    #[test]
    fn classic_map_points_need_few_iterations() {
        let n = 300;
        let axis = crate::numeric::grid::axis(1e-3, 1e3, n, true);
        let prepared: Vec<GpuLambda> = axis.iter().map(|&l| prepare(l)).collect();
        let (mut total, mut most) = (0u32, 0u32);
        for g in &prepared {
            for &load in &axis {
                let (h, l) = split(load);
                let o = solve_f32(g, h, l, Control::Load, false, KernelFlags::SHIPPED);
                assert_eq!(o.status(), Status::Ok);
                total += o.iterations();
                most = most.max(o.iterations());
            }
        }
        let mean = total as f64 / (n * n) as f64;
        assert!(most <= 8, "max {most} iterations");
        assert!(mean < 4.2, "mean {mean} iterations");
    }
}
