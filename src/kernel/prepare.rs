//! Host-side preparation of the per-lambda data, in f64: the branch ends, the bracket table and
//! the Chebyshev fit of the state near the jump-out, where f32 cannot evaluate the residual
//! accurately enough (dA/dP is infinite there).

use super::layout::{Branch, GpuLambda, Lambda64, CHEB_TERMS, TABLE_NODES};
use crate::physics::md::{curve_point, point, CurvePoint};
use crate::solver::LambdaContext;
use rayon::prelude::*;

/// Splits an f64 into an f32 pair whose sum carries ~48 bits.
pub fn split(x: f64) -> (f32, f32) {
    let hi = x as f32;
    (hi, (x - hi as f64) as f32)
}

/// f32 relative rounding error.
const EPS32: f64 = 6.0e-8;
/// The estimated f32 error of the iterated solution below which the iteration is trusted.
const TRUST: f64 = 1e-6;
/// The fitted region never reaches past this table node (|dx| ~ 0.94): beyond it g(s) is not
/// polynomial enough for 8 terms.
const FIT_NODE_MAX: usize = 7;

/// Fits g(s) = dx / s on Chebyshev-Gauss nodes of [0, s_max].
fn cheb_fit(s_max: f64, dx_of_gap: &impl Fn(f64) -> f64) -> [f32; CHEB_TERMS] {
    let n = CHEB_TERMS;
    let g: Vec<f64> = (0..n)
        .map(|j| {
            let th = std::f64::consts::PI * (j as f64 + 0.5) / n as f64;
            let s = 0.5 * s_max * (1.0 + th.cos());
            dx_of_gap(s * s) / s
        })
        .collect();
    std::array::from_fn(|k| {
        let sum: f64 = (0..n)
            .map(|j| g[j] * (std::f64::consts::PI * k as f64 * (j as f64 + 0.5) / n as f64).cos())
            .sum();
        (sum * 2.0 / n as f64 * if k == 0 { 0.5 } else { 1.0 }) as f32
    })
}

/// The Chebyshev sum `sum c_k T_k(u)` (Clenshaw), as the shader evaluates it.
pub fn cheb_eval(c: &[f32; CHEB_TERMS], u: f32) -> f32 {
    // Clenshaw recurrence, the same as the shader's.
    let (mut b1, mut b2) = (0.0f32, 0.0f32);
    for k in (1..CHEB_TERMS).rev() {
        let b0 = 2.0 * u * b1 - b2 + c[k];
        b2 = b1;
        b1 = b0;
    }
    u * b1 - b2 + c[0]
}

/// Builds one interior branch (a quadratic minimum at x_end): `value(p) - end` is the gap.
fn interior_branch(
    lambda: f64,
    x_end: f64,
    end: f64,
    value: impl Fn(&CurvePoint<f64>) -> f64 + Copy,
    value32: impl Fn(&CurvePoint<f32>) -> f32 + Copy,
    dx_of_gap: impl Fn(f64) -> f64,
) -> Branch {
    let mut t = [0f32; TABLE_NODES];
    let mut dxs = [0f32; TABLE_NODES];
    let mut s_max = 0.0;
    let mut prev: Option<(f64, f64)> = None;
    for k in 0..TABLE_NODES {
        let dx = -crate::solver::context::TABLE_DX0 * 2f64.powi(k as i32);
        let p = point(lambda, x_end + dx);
        let gap = value(&p) - end;
        t[k] = gap.max(1e-37).ln() as f32;
        dxs[k] = dx as f32;
        // The f32 iteration's error here, measured: the f32 residual's error at a few mu near
        // the node, turned into an error of x by the slope and of A by |dlnA/dx| <= 2.
        if let Some((gp, dxp)) = prev {
            let slope = (gap - gp) / (dx - dxp);
            let dv = (0..4)
                .map(|i| {
                    let mu = ((x_end + dx).exp() * (1.0 + 1e-3 * i as f64)) as f32;
                    let v32 = value32(&curve_point(lambda as f32, mu));
                    (v32 as f64 - value(&curve_point(lambda, mu as f64))).abs()
                })
                .fold(0.0, f64::max);
            let err = 2.0 * (dv + EPS32 * end.abs()) / slope.abs();
            if s_max == 0.0 && (err < TRUST || k == FIT_NODE_MAX) {
                s_max = gp.sqrt();
            }
        }
        prev = Some((gap, dx));
    }
    // Shrink the fitted interval until the fit reproduces the f64 solver to ~f32 precision.
    let mut cheb = [0f32; CHEB_TERMS];
    for _ in 0..12 {
        cheb = cheb_fit(s_max, &dx_of_gap);
        let worst = (1..16)
            .map(|i| {
                let s = s_max * i as f64 / 16.0;
                let fit = s as f32 * cheb_eval(&cheb, (2.0 * s / s_max - 1.0) as f32);
                (fit as f64 - dx_of_gap(s * s)).abs()
            })
            .fold(0.0, f64::max);
        if worst < 1e-7 {
            break;
        }
        s_max *= 0.6;
    }
    let (end_hi, end_lo) = split(end);
    Branch {
        mu_ref: x_end.exp() as f32,
        end_hi,
        end_lo,
        s_max: s_max as f32,
        cheb,
        t,
        dx: dxs,
    }
}

/// Prepares one lambda for the kernels.
pub fn prepare(lambda: f64) -> GpuLambda {
    // Outside the kernels' domain the lambda is marked invalid (the engine solves it on the CPU).
    let ctx = LambdaContext::new(lambda)
        .ok()
        .filter(|_| super::kernel_lambda(lambda));
    let Some(ctx) = ctx else {
        return GpuLambda {
            lambda: lambda as f32,
            invalid: 1,
            ..bytemuck::Zeroable::zeroed()
        };
    };
    prepare_ctx(&ctx)
}

/// The kernels' data for one lambda, from its f64 context.
pub fn prepare_ctx(ctx: &LambdaContext) -> GpuLambda {
    let lambda = ctx.lambda;
    if !super::kernel_lambda(lambda) {
        return prepare(lambda);
    }
    let small = crate::physics::tolerances::carries_load_plus_2(lambda);
    let xc = ctx.load_pulloff.x;
    let load_end = if small {
        ctx.load_plus_2_c
    } else {
        ctx.load_pulloff.load
    };
    let load = interior_branch(
        lambda,
        xc,
        load_end,
        move |p| if small { p.load_plus_2 } else { p.load },
        move |p| if small { p.load_plus_2 } else { p.load },
        |gap| {
            let s = ctx.solve_load_gap(gap, f64::NAN);
            (s.m_minus_1 * (s.m_minus_1 + 2.0)).sqrt().ln() - xc
        },
    );
    let jo = ctx.disp_pulloff();
    let disp = if jo.at_zero_radius() {
        // The branch runs to A = 0 at x = inf; ln(D - D_end) is nearly linear in x at both ends.
        let mut t = [0f32; TABLE_NODES];
        let mut dxs = [0f32; TABLE_NODES];
        for k in 0..TABLE_NODES {
            let dx = 40.0 - 65.0 * k as f64 / (TABLE_NODES - 1) as f64;
            let gap = point(lambda, xc + dx).approach - jo.approach;
            t[k] = gap.max(1e-37).ln() as f32;
            dxs[k] = dx as f32;
        }
        let (end_hi, end_lo) = split(jo.approach);
        Branch {
            mu_ref: xc.exp() as f32,
            end_hi,
            end_lo,
            s_max: 0.0,
            cheb: [0.0; CHEB_TERMS],
            t,
            dx: dxs,
        }
    } else {
        let xd = jo.x;
        interior_branch(
            lambda,
            xd,
            jo.approach,
            |p| p.approach,
            |p| p.approach,
            |gap| {
                let s = ctx.solve_approach(jo.approach + gap);
                (s.m_minus_1 * (s.m_minus_1 + 2.0)).sqrt().ln() - xd
            },
        )
    };
    GpuLambda {
        lambda: lambda as f32,
        small: small as u32,
        disp_at_zero: jo.at_zero_radius() as u32,
        invalid: 0,
        end_load: ctx.end.load as f32,
        start_at: 0,
        _pad: [0; 2],
        load,
        disp,
    }
}

/// Prepares one lambda for the f64 refinement (`shaders/polish64.wgsl`).
pub fn prepare64(ctx: Option<&LambdaContext>, lambda: f64) -> Lambda64 {
    let Some(ctx) = ctx.filter(|c| super::kernel_lambda(c.lambda)) else {
        return Lambda64 {
            lambda,
            invalid: 1,
            ..bytemuck::Zeroable::zeroed()
        };
    };
    let small = crate::physics::tolerances::carries_load_plus_2(ctx.lambda);
    let jo = ctx.disp_pulloff();
    Lambda64 {
        lambda: ctx.lambda,
        load_end: if small {
            ctx.load_plus_2_c
        } else {
            ctx.load_pulloff.load
        },
        disp_end: jo.approach,
        mu_load: ctx.load_pulloff.x.exp(),
        mu_disp: if jo.at_zero_radius() { 0.0 } else { jo.x.exp() },
        small: small as u32,
        disp_at_zero: jo.at_zero_radius() as u32,
        invalid: 0,
        _pad: 0,
    }
}

/// Prepares many lambdas in parallel; also returns the f64 contexts for cross-checks.
pub fn prepare_all(lambdas: &[f64]) -> Vec<GpuLambda> {
    lambdas.par_iter().map(|&l| prepare(l)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The kernels' first guess interpolates ln|dx| linearly in the node index: interior
    /// branch nodes must double exactly.
    #[test]
    fn interior_table_nodes_double() {
        for &l in &[1e-4, 0.3, 1.0, 7.0, 1e4] {
            let g = prepare(l);
            let mut branches = vec![&g.load];
            if g.disp_at_zero == 0 {
                branches.push(&g.disp);
            }
            for b in branches {
                for k in 1..TABLE_NODES {
                    assert_eq!(b.dx[k], 2.0 * b.dx[k - 1], "lambda {l} node {k}");
                    assert!(b.t[k] > b.t[k - 1], "lambda {l} node {k}");
                }
            }
        }
    }
}
