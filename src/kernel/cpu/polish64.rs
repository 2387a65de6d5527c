//! The CPU mirror of `shaders/polish64.wgsl` and of the curve point it shares with the other f64
//! module (`shaders/curve64.wgsl`): the f64 refinement of one f32 state, as the kernel does it
//! (its own atan: three half-angle steps and a series, since WGSL has no f64 transcendentals).
//! Read it side by side with the shaders.

use crate::kernel::layout::{Lambda64, Out, Out64, Point64};
use crate::solver::{Control, Status};

/// `(atan(mu), mu - atan(mu))` in f64 as the shader computes them: three half-angle steps to
/// t <= tan(pi/64) (t0 - 2 t = t0 t^2 exactly, so every term of t0 - atan t0 is positive), then
/// eight terms of the series.
pub fn atan_parts64(mu: f64) -> (f64, f64) {
    let big = mu > 1.0;
    let t0 = if big { 1.0 / mu } else { mu };
    let t1 = t0 / (1.0 + (1.0 + t0 * t0).sqrt());
    let t2 = t1 / (1.0 + (1.0 + t1 * t1).sqrt());
    let t3 = t2 / (1.0 + (1.0 + t2 * t2).sqrt());
    let z = t3 * t3;
    let mut s = 1.0 / 17.0;
    for k in [15.0, 13.0, 11.0, 9.0, 7.0, 5.0, 3.0] {
        s = 1.0 / k - z * s;
    }
    let d3 = t3 * z * s;
    let d0 = t0 * t1 * t1 + 2.0 * (t1 * t2 * t2 + 2.0 * (t2 * z + 2.0 * d3));
    if big {
        let at = std::f64::consts::FRAC_PI_2 - (t0 - d0);
        (at, mu - at)
    } else {
        (mu - d0, d0)
    }
}

/// The shader's curve point (`shaders/curve64.wgsl`): A, Pbar, Pbar + 2, Dbar, m - 1 and the
/// slopes in mu.
pub(crate) struct Point {
    pub(crate) a: f64,
    pub(crate) load: f64,
    pub(crate) load_plus_2: f64,
    pub(crate) approach: f64,
    pub(crate) m_minus_1: f64,
    pub(crate) dload: f64,
    pub(crate) dapproach: f64,
}

pub(crate) fn curve_point64(lambda: f64, mu: f64) -> Point {
    let four_thirds = 4.0 / 3.0;
    let (at, mu_minus_at) = atan_parts64(mu);
    let mu2 = mu * mu;
    let m = (1.0 + mu2).sqrt();
    let m_minus_1 = mu2 / (1.0 + m);
    let f1 = mu2 * at + mu_minus_at;
    let f2 = mu * at - m_minus_1;
    let alpha = 0.5 * lambda * f1;
    let beta = four_thirds * lambda * lambda * f2;
    let a = 2.0 / (beta + (beta * beta + 4.0 * alpha).sqrt());
    let g = mu + (1.0 + mu2) * at;
    let m2 = 1.0 + mu2;
    let df1 = 2.0 * mu * at + 2.0 * mu2 / m2;
    let df2 = at - mu * mu2 / ((1.0 + m) * m2);
    let dalpha = 0.5 * lambda * df1;
    let dbeta = four_thirds * lambda * lambda * df2;
    let da = -(a * (dalpha * a + dbeta)) / (2.0 * alpha * a + beta);
    let dg = 2.0 + 2.0 * mu * at;
    Point {
        a,
        load: a * a * (a - lambda * g),
        load_plus_2: a * (a * a + (8.0 / 3.0) * lambda * lambda * f2) - 2.0 * lambda * a * a * at,
        approach: a * (a - four_thirds * lambda * mu),
        m_minus_1,
        dload: da * (3.0 * a * a - 2.0 * lambda * a * g) - lambda * a * a * dg,
        dapproach: da * (2.0 * a - four_thirds * lambda * mu) - four_thirds * lambda * a,
    }
}

/// The refinement of one point (`polish` in the shader): safeguarded Newton steps in mu from the
/// f32 state; `max_steps` 0 means the default, 8.
pub fn polish_f64(
    c: &Lambda64,
    pt: &Point64,
    control: Control,
    rows_are_gaps: bool,
    max_steps: u32,
) -> Out64 {
    let status = pt.code & 0xff;
    let (ok, not_converged) = (Status::Ok as u32, Status::NotConverged as u32);
    // No contact, invalid input, or the zero-radius end: the f32 kernel's answer stands.
    if (status != ok && status != not_converged) || !(pt.m_minus_1 < 3.0e38) {
        return Out64 {
            code: pt.code,
            ..Default::default()
        };
    }
    let small = c.small == 1;
    let (goal, end, mu_end, interior) = match control {
        Control::Load => (
            if small { pt.value + 2.0 } else { pt.value },
            c.load_end,
            c.mu_load,
            true,
        ),
        Control::Displacement => (pt.value, c.disp_end, c.mu_disp, c.disp_at_zero == 0),
    };
    let mm1 = pt.m_minus_1 as f64;
    let mut mu = (mm1 * (mm1 + 2.0)).sqrt();
    let max_iter = if max_steps == 0 { 8 } else { max_steps };
    let (mut done, mut steps, mut r_prev) = (false, 0u32, 1.0e300f64);
    for it in 1..=max_iter {
        steps = it;
        let p = curve_point64(c.lambda, mu);
        let (q, dq) = match control {
            Control::Load => (if small { p.load_plus_2 } else { p.load }, p.dload),
            Control::Displacement => (p.approach, p.dapproach),
        };
        let res = if rows_are_gaps {
            (q - end) - pt.value
        } else {
            q - goal
        };
        let r = res.abs();
        // Near pull-off dQ/dmu -> 0 and the steps stay at the noise of Q / dQ: once |Q - goal|
        // has stopped falling and is at rounding level, it is as good as f64 gets.
        if it > 2 && r >= 0.5 * r_prev && r <= 1e-13 * q.abs().max(1.0) {
            done = true;
            break;
        }
        r_prev = r;
        let mut next = mu - res / dq;
        // Stay on the stable branch (mu < mu_end on an interior branch) and at mu > 0.
        if interior && next >= mu_end {
            next = 0.5 * (mu + mu_end);
        }
        if !(next > 0.0) {
            next = 0.5 * mu;
        }
        let moved = (next - mu).abs();
        mu = next;
        // Newton converges quadratically: after a step of 1e-13 the next would be at the noise
        // level.
        if moved <= 1e-13 * mu {
            done = true;
            break;
        }
    }
    let p = curve_point64(c.lambda, mu);
    let other = match control {
        Control::Load => p.approach,
        Control::Displacement => p.load,
    };
    let code = if !done || !(p.a.abs() < 1.0e300) {
        not_converged
    } else {
        status
    };
    Out64 {
        a: p.a,
        other,
        m_minus_1: p.m_minus_1,
        code: code | (steps << 8),
        _pad: 0,
    }
}

/// The input of the refinement for a kernel result: the value, the lambda index and the f32
/// state (as the host uploads it).
pub fn point64(ci: u32, value: f64, o: &Out) -> Point64 {
    Point64 {
        value,
        ci,
        code: o.code,
        m_minus_1: o.m_minus_1,
        _pad: 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atan_parts_match_the_f64_reference() {
        for i in 0..2001 {
            let mu = 10f64.powf(-8.0 + 16.0 * i as f64 / 2000.0);
            let (at, d) = atan_parts64(mu);
            let (at_ref, d_ref) = crate::physics::real::Real::atan_parts(mu);
            assert!((at / at_ref - 1.0).abs() < 4e-16, "{mu}");
            assert!((d / d_ref - 1.0).abs() < 2e-14, "{mu}");
        }
    }
}
