//! A dense start for the load-controlled solve of one lambda: y = ln(xc - x) tabulated against
//! t = ln(Pbar - Pbar_c) with its slope at every node, so that a cubic Hermite interpolant gives
//! x to about 1e-9 and one curve evaluation with one Newton correction gives the state to full
//! precision. It covers only the loads asked for, and is built only where its nodes are fewer
//! than half the states of the lambda (grids, maps); scattered states keep the bracketed
//! secant search.

use super::context::point;

/// Node spacing in y = ln(xc - x): the Hermite error is about h^4 / 384 times the fourth
/// derivative of y(t), below 1e-8 here.
const H: f64 = 1.0 / 32.0;
/// No node closer to the pull-off than this in y (xc - x = e^-20 = 2e-9); below, the secant.
const Y_FIRST: f64 = -20.0;

/// The tabulated branch: strictly increasing t, with y and dy/dt at each node.
#[derive(Clone, Debug)]
pub struct LoadStart {
    t: Vec<f64>,
    y: Vec<f64>,
    dy_dt: Vec<f64>,
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
        let mut s = LoadStart {
            t: Vec::new(),
            y: Vec::new(),
            dy_dt: Vec::new(),
        };
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
                || s.t.last().is_some_and(|&last| t <= last)
            {
                s.t.clear();
                s.y.clear();
                s.dy_dt.clear();
                continue;
            }
            s.t.push(t);
            s.y.push(y);
            s.dy_dt.push(1.0 / dt_dy);
            if t > t_hi {
                return (s.t.len() >= 2).then_some(s);
            }
        }
        None
    }

    /// x for ln(Pbar - Pbar_c) = t, or None outside the table.
    #[inline]
    pub fn x(&self, t: f64, xc: f64) -> Option<f64> {
        let n = self.t.len();
        if !(t >= self.t[0] && t <= self.t[n - 1]) {
            return None;
        }
        let k = self.t.partition_point(|&tk| tk <= t).clamp(1, n - 1) - 1;
        let (t0, t1) = (self.t[k], self.t[k + 1]);
        let w = t1 - t0;
        let s = (t - t0) / w;
        // Cubic Hermite on [t0, t1] with the slopes at both ends.
        let (h00, h10) = (
            (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s),
            s * (1.0 - s) * (1.0 - s),
        );
        let (h01, h11) = (s * s * (3.0 - 2.0 * s), s * s * (s - 1.0));
        let y = h00 * self.y[k]
            + h10 * w * self.dy_dt[k]
            + h01 * self.y[k + 1]
            + h11 * w * self.dy_dt[k + 1];
        Some(xc - y.exp())
    }

    /// Curve evaluations spent on the table.
    pub fn nodes(&self) -> usize {
        self.t.len()
    }
}
