//! A dense start for the load-controlled solve of one lambda: x = ln(mu) tabulated against
//! t = ln(Pbar - Pbar_c) with its slope at every node (nodes evenly spaced in y = ln(xc - x),
//! which crowds them towards the pull-off), so that a cubic Hermite interpolant gives x to about
//! 1e-9 and one curve evaluation with one Newton correction gives the state to full precision.
//! It covers only the loads asked for, and is built only where its nodes are fewer than half
//! the states of the lambda (grids, maps); scattered states keep the bracketed secant search.

use crate::physics::md::point;

/// Node spacing in y = ln(xc - x): the Hermite error in x stays below about 1e-8 (95% of the
/// states of `cargo bench --bench grid` need no second evaluation).
const H: f64 = 1.0 / 32.0;
/// No node closer to the pull-off than this in y (xc - x = e^-20 = 2e-9); below, the secant.
const Y_FIRST: f64 = -20.0;

/// The tabulated branch: strictly increasing t, with x and dx/dt at each node (x rather than
/// y: one exponential fewer a state, and fewer second evaluations than mu itself), and a guide
/// from uniform buckets of t to the node at or below each bucket's start, so that a lookup is
/// one index and a short walk instead of a binary search.
#[derive(Clone, Debug)]
pub struct LoadStart {
    /// (t, x, dx/dt) per node, together so that a lookup touches one or two cache lines.
    nodes: Vec<[f64; 3]>,
    guide: Vec<u32>,
    /// Buckets per unit of t.
    per_t: f64,
}

impl LoadStart {
    /// Tabulates the branch of `lambda` below the pull-off at `xc` from y = `y_lo` up to
    /// ln(Pbar - Pbar_c) = `t_hi`, with at most `max_nodes` curve evaluations; `gap(p)` is
    /// Pbar - Pbar_c of a curve point in the context's cancellation-free form. None where the
    /// range needs more nodes, or the curve does not give a clean monotone table (the solve
    /// then keeps its secant search).
    pub fn new(
        lambda: f64,
        xc: f64,
        gap: impl Fn(&crate::physics::md::CurvePoint<f64>) -> f64,
        y_lo: f64,
        t_hi: f64,
        max_nodes: usize,
    ) -> Option<LoadStart> {
        let y_lo = y_lo.max(Y_FIRST);
        let mut nodes: Vec<[f64; 3]> = Vec::new();
        for k in 0..max_nodes {
            let y = y_lo + H * k as f64;
            let d = y.exp();
            let x = xc - d;
            let p = point(lambda, x);
            let g = gap(&p);
            // dt/dy = (dP/dx / gap) (dx/dy), with dx/dy = -(xc - x).
            let dt_dy = -(p.dload_dmu * p.mu) * d / g;
            let t = g.ln();
            // Closest to the pull-off the gap is a few ulps and its log is noise: the table
            // starts after the last node that is not clean (states below it take the search).
            if !(g > 0.0 && dt_dy.is_finite() && dt_dy > 0.0)
                || nodes.last().is_some_and(|last| t <= last[0])
            {
                nodes.clear();
                continue;
            }
            // dx/dt = (dx/dy) / (dt/dy).
            nodes.push([t, x, -d / dt_dy]);
            if t > t_hi {
                return (nodes.len() >= 2).then(|| Self::guided(nodes));
            }
        }
        None
    }

    /// Adds the guide: twice as many buckets as intervals.
    fn guided(nodes: Vec<[f64; 3]>) -> LoadStart {
        let n = nodes.len();
        let (t0, t1) = (nodes[0][0], nodes[n - 1][0]);
        let buckets = 2 * (n - 1);
        let per_t = buckets as f64 / (t1 - t0);
        let mut k = 0;
        let guide = (0..buckets)
            .map(|b| {
                let tb = t0 + b as f64 / per_t;
                while k + 2 < n && nodes[k + 1][0] <= tb {
                    k += 1;
                }
                k as u32
            })
            .collect();
        LoadStart {
            nodes,
            guide,
            per_t,
        }
    }

    /// x for ln(Pbar - Pbar_c) = t, or None outside the table.
    #[inline]
    pub fn x(&self, t: f64) -> Option<f64> {
        let nodes = &self.nodes;
        let n = nodes.len();
        if !(t >= nodes[0][0] && t <= nodes[n - 1][0]) {
            return None;
        }
        let b = (((t - nodes[0][0]) * self.per_t) as usize).min(self.guide.len() - 1);
        let mut k = self.guide[b] as usize;
        while k + 2 < n && nodes[k + 1][0] <= t {
            k += 1;
        }
        let ([t0, x0, s0], [t1, x1, s1]) = (nodes[k], nodes[k + 1]);
        let w = t1 - t0;
        let s = (t - t0) / w;
        // Cubic Hermite on [t0, t1] with the slopes at both ends.
        let (h00, h10) = (
            (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s),
            s * (1.0 - s) * (1.0 - s),
        );
        let (h01, h11) = (s * s * (3.0 - 2.0 * s), s * s * (s - 1.0));
        Some(h00 * x0 + h10 * w * s0 + h01 * x1 + h11 * w * s1)
    }

    /// The nodes (t, x, dx/dt), the guide (a node index per bucket) and the buckets per unit
    /// of t: what the kernels' copy of the table is made of (`kernel::start`).
    pub fn parts(&self) -> (&[[f64; 3]], &[u32], f64) {
        (&self.nodes, &self.guide, self.per_t)
    }

    /// Curve evaluations spent on the table.
    pub fn nodes(&self) -> usize {
        self.nodes.len()
    }
}
