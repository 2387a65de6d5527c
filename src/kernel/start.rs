//! The dense start of the load branch ([`crate::solver::start`]) in the kernels' form, and its
//! f32 lookup as `shaders/md.wgsl` (`start_x`) does it.
//!
//! Each lambda with a start gets one block of u32 words, appended to the grid kernel's input
//! after its rows; `GpuLambda::start_at` is the block's word offset (0: none):
//! `[nodes, buckets, t0, per_t, guide[buckets], (t, dx, dx/dt)[nodes]]`, numbers as f32 bits.
//! dx = ln(mu / mu_ref) with the f32 mu_ref the kernel multiplies by, so that the start is
//! relative to what the kernel iterates on.

use super::layout::GpuLambda;
use crate::solver::LambdaContext;

/// Words before the guide.
const HEADER: usize = 4;

/// The blocks of a grid's lambdas: `at[i]` is lambda i's block offset within `words`, if any.
#[derive(Clone, Debug, Default)]
pub struct Starts {
    /// Every block, one after another.
    pub words: Vec<u32>,
    /// Lambda i's block offset within `words`, if it has one.
    pub at: Vec<Option<u32>>,
}

impl Starts {
    /// The blocks of the contexts that have a dense start (see [`crate::solver::with_starts`]).
    pub fn new(ctx: &[Option<LambdaContext>], prepared: &[GpuLambda]) -> Starts {
        let mut s = Starts::default();
        for (c, g) in ctx.iter().zip(prepared) {
            let block = c.as_ref().and_then(|c| {
                let start = c.start.as_ref()?;
                // Only the shipped load branch: the kernel offsets x by its f32 mu_ref.
                (g.invalid == 0).then(|| encode(start, g.load.mu_ref))
            });
            s.at.push(block.map(|b| {
                let at = s.words.len() as u32;
                s.words.extend(b);
                at
            }));
        }
        s
    }

    /// `lambdas` with `start_at` set for blocks placed at word `base` of the kernel's input.
    pub fn placed(&self, lambdas: &[GpuLambda], base: usize) -> Vec<GpuLambda> {
        lambdas
            .iter()
            .enumerate()
            .map(|(i, g)| GpuLambda {
                start_at: self
                    .at
                    .get(i)
                    .copied()
                    .flatten()
                    .map_or(0, |a| base as u32 + a),
                ..*g
            })
            .collect()
    }

    /// Lambda i's block, for the CPU mirror.
    pub fn block(&self, i: usize) -> Option<&[u32]> {
        let at = self.at.get(i).copied().flatten()? as usize;
        Some(&self.words[at..])
    }
}

/// One lambda's block.
fn encode(start: &crate::solver::start::LoadStart, mu_ref: f32) -> Vec<u32> {
    let (nodes, guide, per_t) = start.parts();
    let x_ref = (mu_ref as f64).ln();
    let mut w = vec![
        nodes.len() as u32,
        guide.len() as u32,
        (nodes[0][0] as f32).to_bits(),
        (per_t as f32).to_bits(),
    ];
    w.extend_from_slice(guide);
    for &[t, x, dx_dt] in nodes {
        w.extend([t as f32, (x - x_ref) as f32, dx_dt as f32].map(f32::to_bits));
    }
    w
}

/// The start's dx = ln(mu / mu_ref) and dF/dx = dt/dx at ln(gap) = t, or None outside it:
/// the shader's `start_x`, operation for operation.
pub fn start_x(block: &[u32], t: f32) -> Option<(f32, f32)> {
    let f = |i: usize| f32::from_bits(block[i]);
    let (n, nb) = (block[0] as usize, block[1] as usize);
    let (t0, per_t) = (f(2), f(3));
    let nodes = HEADER + nb;
    if !(t >= t0 && t <= f(nodes + 3 * (n - 1))) {
        return None;
    }
    let b = (((t - t0) * per_t) as usize).min(nb - 1);
    let mut k = block[HEADER + b] as usize;
    while k + 2 < n && f(nodes + 3 * (k + 1)) <= t {
        k += 1;
    }
    let i = nodes + 3 * k;
    let (ta, xa, sa, tb, xb, sb) = (f(i), f(i + 1), f(i + 2), f(i + 3), f(i + 4), f(i + 5));
    let w = tb - ta;
    let s = (t - ta) / w;
    let u = 1.0 - s;
    let x = (1.0 + 2.0 * s) * u * u * xa
        + s * u * u * w * sa
        + s * s * (3.0 - 2.0 * s) * xb
        + s * s * (s - 1.0) * w * sb;
    Some((x, 1.0 / (sa + s * (sb - sa))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::cpu::md::{solve_f32, solve_f32_started, KernelFlags};
    use crate::kernel::prepare::{prepare_ctx, split};
    use crate::solver::{with_starts, Control, Status};

    /// On the map's classic grid the started f32 solve agrees with the f64 solver as the
    /// unstarted one does, and needs far fewer iterations.
    #[test]
    fn the_started_kernel_iterates_less_with_the_same_accuracy() {
        let axis = crate::numeric::grid::axis(1e-3, 1e3, 400, true);
        let ctx: Vec<Option<LambdaContext>> =
            axis.iter().map(|&l| LambdaContext::new(l).ok()).collect();
        let started = with_starts(&ctx, &axis, Control::Load);
        let prepared: Vec<GpuLambda> = started.iter().flatten().map(prepare_ctx).collect();
        let starts = Starts::new(&started, &prepared);
        assert!(
            starts.at.iter().all(Option::is_some),
            "a lambda without a start"
        );
        let (mut plain, mut fast, mut n, mut worst) = (0u32, 0u32, 0u32, 0f64);
        for (i, (c, g)) in started.iter().flatten().zip(&prepared).enumerate() {
            for &load in &axis {
                let (h, l) = split(load);
                let f = KernelFlags::SHIPPED;
                let a = solve_f32(g, h, l, Control::Load, false, f);
                let b = solve_f32_started(g, starts.block(i), h, l, Control::Load, false, f);
                assert_eq!(b.status(), Status::Ok, "lambda {}, load {load}", c.lambda);
                assert_eq!(a.status(), b.status());
                let exact = c.solve_load(load).a;
                worst = worst.max((b.a as f64 / exact - 1.0).abs());
                plain += a.iterations();
                fast += b.iterations();
                n += 1;
            }
        }
        let (plain, fast) = (plain as f64 / n as f64, fast as f64 / n as f64);
        eprintln!("f32 kernel: {plain:.2} iterations a state, {fast:.2} with the start; worst A error {worst:.1e}");
        assert!(
            worst < crate::physics::tolerances::F32_TOLERANCE,
            "{worst:e}"
        );
        assert!(fast < 0.5 * plain, "{fast} against {plain}");
    }

    /// The lookup reproduces the f64 table's x at its nodes and between them.
    #[test]
    fn start_x_follows_the_f64_start() {
        let mut c = LambdaContext::new(0.7).unwrap();
        c.add_start(-1.0, 100.0, 1 << 16);
        let g = prepare_ctx(&c);
        let starts = Starts::new(&[Some(c.clone())], &[g]);
        let block = starts.block(0).unwrap();
        let x_ref = (g.load.mu_ref as f64).ln();
        let start = c.start.as_ref().unwrap();
        let (nodes, _, _) = start.parts();
        let mut worst = 0f64;
        for pair in nodes.windows(2) {
            let t = 0.5 * (pair[0][0] + pair[1][0]);
            let x = start.x(t).unwrap() - x_ref;
            let (x32, slope) = start_x(block, t as f32).unwrap();
            assert!(slope < 0.0, "dt/dx {slope}: the gap grows as x falls");
            worst = worst.max((x32 as f64 - x).abs() / x.abs().max(1.0));
        }
        assert!(worst < 1e-6, "{worst:e}");
        assert!(start_x(block, nodes[0][0] as f32 - 1.0).is_none());
    }
}
