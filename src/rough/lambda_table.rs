//! The summits' contact branch tabulated over a range of lambda, for explicit ensembles whose
//! summits each have their own radius and so their own lambda (docs/PHYSICS.md section 9,
//! explicit ensembles).
//!
//! Node tables sit on a uniform grid in ln(lambda), each a [`BranchTable`] of the load and one of
//! the contact radius A in the same graded variable v of `u = sqrt(delta - delta_out)`. Measured
//! from each lambda's own fold, the branch is smooth in (ln lambda, u), so a summit's state is
//! the 4-point Lagrange combination in ln(lambda) of the node tables at its own v: two cubic
//! evaluations per node instead of a root search. The summit's fold, entry and non-contact branch
//! stay exact (its own [`Summit`]); within the stretch next to the fold where a node table misses
//! its target, its states are solved exactly.
//!
//! The error is measured, not assumed: every node table's at its intervals' midpoints in v, and
//! the interpolation in ln(lambda) against tables solved exactly at the grid's midpoints (where a
//! uniform 4-point Lagrange cubic errs most). The grid is halved until that meets the target.

use super::map::{v_of_u, BranchTable, TABLE_H};
use super::{RoughError, Summit};
use crate::engine::{CheckReport, Engine};
use crate::solver::{Control, Status};

/// The grid step in ln(lambda) tried first (20 nodes per decade), and the finest allowed.
const LN_STEP: f64 = std::f64::consts::LN_10 / 20.0;
const LN_STEP_MIN: f64 = LN_STEP / 16.0;
/// The interpolation error aimed at, relative to max(1, |value|) (loads in pi w R, A in the
/// radius unit).
pub const TARGET: f64 = 1e-6;
/// Table states of a GPU's tables re-solved by the CPU f64 solver for its cross-check.
const GPU_CHECKS: usize = 1000;

/// A summit's place on the grid: the first of its four nodes and their Lagrange weights.
#[derive(Clone, Copy, Debug)]
pub struct Stencil {
    pub(crate) first: usize,
    pub(crate) w: [f64; 4],
}

/// Contact-branch tables (load and A) over a range of lambda.
#[derive(Debug)]
pub struct LambdaTables {
    /// ln(lambda) of node 0, and the step.
    x0: f64,
    step: f64,
    pub(crate) load: Vec<BranchTable>,
    pub(crate) area: Vec<BranchTable>,
    /// Below this v a state is solved exactly (the widest exact stretch of the node tables).
    pub exact_below: f64,
    /// The largest interpolation error measured (in v and in ln lambda), relative to
    /// max(1, |value|).
    pub error: f64,
    /// Nodes of the grid in ln(lambda).
    pub nodes: usize,
    /// Which backend solved the tables (`cpu f64`, `gpu f32`, `gpu f64`).
    pub backend: String,
    /// A GPU's table states against the CPU f64 solver on a sample (None on the CPU).
    pub check: Option<CheckReport>,
}

/// The 4-point Lagrange weights at t in [0, 1) between the middle two of four uniform nodes.
fn weights(t: f64) -> [f64; 4] {
    [
        -t * (t - 1.0) * (t - 2.0) / 6.0,
        (t + 1.0) * (t - 1.0) * (t - 2.0) / 2.0,
        -(t + 1.0) * t * (t - 2.0) / 2.0,
        (t + 1.0) * t * (t - 1.0) / 6.0,
    ]
}

/// Per table (node or midpoint lambda): its summit and the approaches it is solved at.
struct Plan {
    summits: Vec<Summit>,
    approaches: Vec<Vec<f64>>,
}

impl Plan {
    /// Tables up to approach `delta_max` for every summit between the nodes: one span for all,
    /// from the lowest fold of the nodes (so that all tables share the v grid).
    fn new(lambdas: &[f64], delta_max: f64) -> Result<Plan, RoughError> {
        use rayon::prelude::*;
        let summits: Vec<Summit> = lambdas
            .par_iter()
            .map(|&l| Summit::new(l))
            .collect::<Result<_, _>>()?;
        let lowest = summits
            .iter()
            .map(|s| s.delta_out)
            .fold(f64::INFINITY, f64::min);
        let span = delta_max - lowest + 1.0;
        let approaches = summits
            .iter()
            .map(|s| BranchTable::approaches(s.delta_out, s.delta_out + span))
            .collect();
        Ok(Plan {
            summits,
            approaches,
        })
    }
}

/// Solves every table's approaches on `engine`: (load, A) per approach, NaN where a state
/// failed; a GPU's states are cross-checked on a sample against the CPU f64 solver.
/// Per table, (load, A) at each of its approaches.
type Solved = Vec<Vec<(f64, f64)>>;

fn solve(plan: &Plan, engine: &Engine) -> Result<(Solved, Option<CheckReport>), RoughError> {
    let points: Vec<(f64, f64)> = plan
        .summits
        .iter()
        .zip(&plan.approaches)
        .flat_map(|(s, ds)| ds.iter().map(move |&d| (s.lambda, d)))
        .collect();
    let states = engine
        .solve_points(&points, Control::Displacement)
        .map_err(|e| RoughError::Scene(e.to_string().into()))?;
    let check = (!matches!(engine, Engine::Cpu)).then(|| {
        crate::engine::cross_check(
            &points,
            &states,
            Control::Displacement,
            GPU_CHECKS,
            crate::engine::GPU_TOLERANCE,
        )
    });
    let mut at = 0;
    let out = plan
        .approaches
        .iter()
        .map(|ds| {
            let v = states[at..at + ds.len()]
                .iter()
                .map(|st| match st.status {
                    Status::Ok => (st.load, st.a),
                    _ => (f64::NAN, f64::NAN),
                })
                .collect();
            at += ds.len();
            v
        })
        .collect();
    Ok((out, check))
}

impl LambdaTables {
    /// Tables for summits of lambda in `[lambda_lo, lambda_hi]` whose approaches reach up to
    /// `delta_max`, solved on `engine`; the grid is refined until its measured
    /// error meets [`TARGET`] (or reaches its finest step, and reports what it measured).
    pub fn new(
        lambda_lo: f64,
        lambda_hi: f64,
        delta_max: f64,
        engine: &Engine,
    ) -> Result<LambdaTables, RoughError> {
        let mut step = LN_STEP;
        loop {
            let t = Self::with_step(lambda_lo, lambda_hi, delta_max, step, engine)?;
            if t.error <= TARGET || step <= LN_STEP_MIN {
                return Ok(t);
            }
            step /= 2.0;
        }
    }

    fn with_step(
        lambda_lo: f64,
        lambda_hi: f64,
        delta_max: f64,
        step: f64,
        engine: &Engine,
    ) -> Result<LambdaTables, RoughError> {
        let failed = |l: f64| RoughError::Failed(f64::NAN, l);
        // One node below the smallest lambda and two above the largest: every summit has the
        // four nodes of its stencil, with its lambda between the middle two.
        // At least four nodes: one lambda (every summit of one radius, the plain
        // Greenwood-Williamson ensemble) has x = 1 up to rounding, which may floor to 0.
        let x0 = lambda_lo.ln() - step;
        let nodes = (((lambda_hi.ln() - x0) / step).floor() as usize + 3).max(4);
        let node_l: Vec<f64> = (0..nodes).map(|k| (x0 + k as f64 * step).exp()).collect();
        // Midpoints between nodes k and k+1 with a full stencil: k in 1..=nodes-3.
        let mid_l: Vec<f64> = (1..nodes - 2)
            .map(|k| (x0 + (k as f64 + 0.5) * step).exp())
            .collect();
        let lambdas: Vec<f64> = node_l.iter().chain(&mid_l).copied().collect();
        let plan = Plan::new(&lambdas, delta_max)?;
        let (solved, check) = solve(&plan, engine)?;
        let table = |i: usize, f: fn(&(f64, f64)) -> f64| {
            let v: Vec<f64> = solved[i].iter().map(f).collect();
            BranchTable::from_loads(plan.summits[i].delta_out, &v).ok_or(failed(lambdas[i]))
        };
        let load = (0..nodes)
            .map(|i| table(i, |s| s.0))
            .collect::<Result<Vec<_>, _>>()?;
        let area = (0..nodes)
            .map(|i| table(i, |s| s.1))
            .collect::<Result<Vec<_>, _>>()?;
        let exact_below = load
            .iter()
            .chain(&area)
            .map(|t| t.exact_below)
            .fold(0.0, f64::max);
        let mut error = load
            .iter()
            .chain(&area)
            .map(|t| t.error)
            .fold(0.0, f64::max);
        // The interpolation in ln(lambda) at the midpoints, at every v node beyond the exact
        // stretch: node values are exact solves, so this is that interpolation's error alone.
        let w = weights(0.5);
        let nv = solved[0].len().div_ceil(2);
        for (m, k) in (1..nodes - 2).enumerate() {
            let exact = &solved[nodes + m];
            for (i, e) in exact.iter().enumerate().take(nv) {
                if (i as f64) * TABLE_H < exact_below {
                    continue;
                }
                let (mut p, mut a) = (0.0, 0.0);
                for j in 0..4 {
                    let s = solved[k - 1 + j][i];
                    p += w[j] * s.0;
                    a += w[j] * s.1;
                }
                let ep = (p - e.0).abs() / e.0.abs().max(1.0);
                let ea = (a - e.1).abs() / e.1.abs().max(1.0);
                if !(ep.is_finite() && ea.is_finite()) {
                    return Err(failed(lambdas[nodes + m]));
                }
                error = error.max(ep).max(ea);
            }
        }
        Ok(LambdaTables {
            x0,
            step,
            load,
            area,
            exact_below,
            error,
            nodes,
            backend: engine.name().to_string() + " " + engine.precision(),
            check,
        })
    }

    /// The stencil of a summit of Maugis parameter `lambda` (within the tables' range).
    pub fn stencil(&self, lambda: f64) -> Stencil {
        let x = (lambda.ln() - self.x0) / self.step;
        let first = ((x.floor() as usize).max(1) - 1).min(self.nodes - 4);
        Stencil {
            first,
            w: weights(x - (first + 1) as f64),
        }
    }

    /// The load and A of summit `s` (at stencil `st`) on its contact branch at approach
    /// `delta`: interpolated, or solved exactly next to the fold; None where that fails.
    #[inline]
    pub fn contact(&self, s: &Summit, st: &Stencil, delta: f64) -> Option<(f64, f64)> {
        let v = v_of_u((delta - s.delta_out).max(0.0).sqrt());
        if v < self.exact_below {
            return s.contact(delta);
        }
        let (mut p, mut a) = (0.0, 0.0);
        for j in 0..4 {
            p += st.w[j] * self.load[st.first + j].at_v(v);
            a += st.w[j] * self.area[st.first + j].at_v(v);
        }
        Some((p, a))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lagrange_weights_reproduce_cubics() {
        for t in [0.0, 0.25, 0.5, 0.9] {
            let w = weights(t);
            for p in 0..4 {
                let f = |x: f64| x.powi(p) - 0.3 * x;
                let got: f64 = (0..4).map(|j| w[j] * f(j as f64 - 1.0)).sum();
                assert!((got - f(t)).abs() < 1e-14, "t {t} p {p}: {got} vs {}", f(t));
            }
        }
    }

    #[test]
    fn interpolated_states_are_the_exact_ones_within_the_stated_error() {
        let t = LambdaTables::new(0.3, 3.0, 30.0, &Engine::Cpu).unwrap();
        assert!(t.error <= TARGET, "measured error {}", t.error);
        let mut worst = 0f64;
        for l in [0.3, 0.41, 0.777, 1.3, 2.2, 3.0] {
            let s = Summit::new(l).unwrap();
            let st = t.stencil(l);
            for k in 0..60 {
                let delta = s.delta_out + 1e-9 + (k as f64 * 0.09).powi(2);
                let (p, a) = t.contact(&s, &st, delta).unwrap();
                let (pe, ae) = s.contact(delta).unwrap();
                worst = worst
                    .max((p - pe).abs() / pe.abs().max(1.0))
                    .max((a - ae).abs() / ae.abs().max(1.0));
            }
        }
        // Between the measured nodes the error may exceed the measured one slightly (the v
        // interpolation and the lambda interpolation add).
        assert!(worst < 2.0 * TARGET, "largest difference {worst}");
        assert!(worst > 0.0, "the interpolant is exercised");
    }

    #[test]
    fn a_table_over_one_lambda_gives_its_states() {
        // Every summit of one radius (the plain Greenwood-Williamson ensemble): the range is a
        // single lambda, for which the node count once floored to three and indexed past the end.
        for l in [0.05, 0.3, 1.0, 7.0, 1.0 / 3.0, std::f64::consts::PI] {
            let t = LambdaTables::new(l, l, 20.0, &Engine::Cpu).unwrap();
            assert!(t.nodes >= 4 && t.error <= TARGET, "lambda {l}: {t:?}");
            let s = Summit::new(l).unwrap();
            let st = t.stencil(l);
            for k in 0..40 {
                let delta = s.delta_out + 1e-9 + (k as f64 * 0.1).powi(2);
                let (p, a) = t.contact(&s, &st, delta).unwrap();
                let (pe, ae) = s.contact(delta).unwrap();
                assert!(
                    (p - pe).abs() <= 2.0 * TARGET * pe.abs().max(1.0)
                        && (a - ae).abs() <= 2.0 * TARGET * ae.abs().max(1.0),
                    "lambda {l}, delta {delta}: ({p}, {a}) against ({pe}, {ae})"
                );
            }
        }
    }
}
