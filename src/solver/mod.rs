//! Solvers: the exact f64 reference (per-lambda context, batches on all cores). The f32 mirror
//! of the shaders is the kernel layer's (`kernel::cpu`), above this one.

pub mod context;
pub mod curve;
pub mod limits;
pub mod naive;
pub mod start;
pub mod two_zone;

pub use crate::physics::domain;
pub use context::{LambdaContext, PullOff, RadiusState};

use rayon::prelude::*;
use serde::Serialize;

/// What a solve is given: the load (dead load) or the approach (rigid grips).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Control {
    /// Load control (dead load): the load is given.
    Load,
    /// Displacement control (rigid grips): the approach is given.
    Displacement,
}

impl Control {
    /// The name in JSON and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Control::Load => "load",
            Control::Displacement => "displacement",
        }
    }
}

/// Outcome of one state. The numeric codes are the ones the shaders write.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
#[repr(u32)]
pub enum Status {
    /// A state was found.
    Ok = 0,
    /// The load is below the pull-off, or the approach below the jump-out: no contact.
    NoContact = 1,
    /// The iteration limit was reached; the numbers are the best bracketed estimate.
    NotConverged = 2,
    /// lambda or the load is not a finite number in range.
    InvalidInput = 3,
}

impl Status {
    /// The name in JSON and CSV.
    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::NoContact => "no_contact",
            Status::NotConverged => "not_converged",
            Status::InvalidInput => "invalid_input",
        }
    }
    /// The status of a kernel's code (its low byte).
    pub fn from_code(code: u32) -> Status {
        match code {
            0 => Status::Ok,
            1 => Status::NoContact,
            2 => Status::NotConverged,
            _ => Status::InvalidInput,
        }
    }
}

/// A contact state in the Johnson-Greenwood normalisation. Fields that could not be computed
/// (no contact, bad input) are NaN and are written as empty fields, never as numbers.
#[derive(Clone, Copy, Debug)]
pub struct State {
    /// The Maugis parameter.
    pub lambda: f64,
    /// Pbar.
    pub load: f64,
    /// Dbar.
    pub approach: f64,
    /// Contact radius A.
    pub a: f64,
    /// m - 1 (c/a - 1), full relative precision.
    pub m_minus_1: f64,
    /// Whether the state was found; the numbers are NaN otherwise.
    pub status: Status,
    /// Curve evaluations spent on this state (its context's and tables' not counted).
    pub iterations: u32,
}

impl State {
    /// A state that was not found: the inputs and the status, NaN for the rest.
    pub fn failed(lambda: f64, load: f64, approach: f64, status: Status) -> State {
        State {
            lambda,
            load,
            approach,
            a: f64::NAN,
            m_minus_1: f64::NAN,
            status,
            iterations: 0,
        }
    }
}

#[derive(Debug, thiserror::Error)]
/// Why a lambda's solver could not be built.
#[non_exhaustive]
pub enum SolveError {
    #[error(transparent)]
    /// lambda outside the domain.
    Domain(#[from] domain::DomainError),
    #[error("no load-controlled pull-off found for lambda = {}", domain::short(*.0))]
    /// The pull-off search failed at this lambda.
    NoPullOff(f64),
}

impl SolveError {
    /// The message, naming the quantity by its key.
    pub fn message(&self) -> crate::error::Message {
        match self {
            SolveError::Domain(d) => d.message(),
            SolveError::NoPullOff(l) => crate::error::Message::new()
                .text("no load-controlled pull-off found for ")
                .key("lambda")
                .text(format!(" = {}", domain::short(*l))),
        }
    }
}

impl crate::error::Named for SolveError {
    fn named(&self, names: crate::error::Names) -> String {
        self.message().named(names)
    }
}

/// The state of one (lambda, value) point; `value` is the load or the approach.
/// Inside the exact solver's domain by MD; beyond it by the closed-form limit where that is
/// certified (`domain::method` says which), else `invalid_input`.
pub fn solve_one(lambda: f64, value: f64, control: Control) -> State {
    match LambdaContext::new(lambda) {
        Ok(ctx) => solve_with(&ctx, value, control),
        Err(_) => beyond(lambda, value, control),
    }
}

/// A state outside the exact solver's domain: the limit's, or `invalid_input`.
fn beyond(lambda: f64, value: f64, control: Control) -> State {
    limits::solve_limit(lambda, value, control).unwrap_or_else(|| invalid(lambda, value, control))
}

fn invalid(lambda: f64, value: f64, control: Control) -> State {
    match control {
        Control::Load => State::failed(lambda, value, f64::NAN, Status::InvalidInput),
        Control::Displacement => State::failed(lambda, f64::NAN, value, Status::InvalidInput),
    }
}

#[inline]
/// One state of a prepared lambda at a load or approach.
pub fn solve_with(ctx: &LambdaContext, value: f64, control: Control) -> State {
    match control {
        Control::Load => ctx.solve_load(value),
        Control::Displacement => ctx.solve_approach(value),
    }
}

/// Solves a list of (lambda, value) points on all cores (beyond the exact solver's domain by
/// the limits, as [`solve_one`]), one context per distinct lambda: the
/// points are grouped by lambda (a sort, not a map of contexts), each group builds its context
/// (with a dense start where it has enough load-controlled states to pay for it), solves its
/// points and drops it, so memory is the points and their states whatever the mix.
pub fn solve_points(points: &[(f64, f64)], control: Control) -> Vec<State> {
    let mut order: Vec<u32> = (0..points.len() as u32).collect();
    order.par_sort_unstable_by_key(|&i| points[i as usize].0.to_bits());
    let groups: Vec<&[u32]> = order
        .chunk_by(|&a, &b| points[a as usize].0.to_bits() == points[b as usize].0.to_bits())
        .collect();
    let solved: Vec<Vec<(u32, State)>> = groups
        .par_iter()
        .map(|g| {
            let lambda = points[g[0] as usize].0;
            let Ok(mut ctx) = LambdaContext::new(lambda) else {
                return g
                    .iter()
                    .map(|&i| (i, beyond(lambda, points[i as usize].1, control)))
                    .collect();
            };
            if control == Control::Load && g.len() >= context::START_MIN_STATES {
                let (lo, hi) = g
                    .iter()
                    .map(|&i| points[i as usize].1)
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                        (a.min(v), b.max(v))
                    });
                ctx.add_start(lo, hi, g.len());
            }
            g.iter()
                .map(|&i| (i, solve_with(&ctx, points[i as usize].1, control)))
                .collect()
        })
        .collect();
    let mut out = vec![State::failed(0.0, 0.0, 0.0, Status::InvalidInput); points.len()];
    for (i, s) in solved.into_iter().flatten() {
        out[i as usize] = s;
    }
    out
}

/// The states at the contact radii of a list of (lambda, A) points, on all cores.
pub fn solve_radius_points(points: &[(f64, f64)]) -> Vec<RadiusState> {
    // One context (its pull-off radii decide the stability) per distinct lambda.
    let mut lambdas: Vec<u64> = points.iter().map(|p| p.0.to_bits()).collect();
    lambdas.sort_unstable();
    lambdas.dedup();
    let ctxs: std::collections::HashMap<u64, Option<LambdaContext>> = lambdas
        .par_iter()
        .map(|&b| (b, LambdaContext::new(f64::from_bits(b)).ok()))
        .collect();
    points
        .par_iter()
        .map(|&(lambda, a)| match &ctxs[&lambda.to_bits()] {
            Some(ctx) => ctx.solve_radius(a),
            None => RadiusState::failed(lambda, a, Status::InvalidInput),
        })
        .collect()
}

/// Solves the grid `lambdas x values` (row-major: one row per value, `lambdas.len()` columns),
/// on all cores.
pub fn solve_grid(lambdas: &[f64], values: &[f64], control: Control) -> Vec<State> {
    let ctx: Vec<Option<LambdaContext>> = lambdas
        .par_iter()
        .map(|&l| LambdaContext::new(l).ok())
        .collect();
    solve_grid_with(&ctx, lambdas, values, control)
}

/// As [`solve_grid`], with the contexts of `lambdas` already built.
pub fn solve_grid_with(
    ctx: &[Option<LambdaContext>],
    lambdas: &[f64],
    values: &[f64],
    control: Control,
) -> Vec<State> {
    let started = with_starts(ctx, values, control);
    tiled(lambdas.len(), values, |i, v| match &started[i] {
        Some(c) => solve_with(c, v, control),
        None => invalid(lambdas[i], v, control),
    })
}

/// Solves the grid `lambdas x gaps` (row-major), each gap a load above its lambda's pull-off,
/// with the contexts of `lambdas` already built (a dense start added where it pays).
pub fn solve_grid_gaps_with(
    ctx: &[Option<LambdaContext>],
    lambdas: &[f64],
    gaps: &[f64],
) -> Vec<State> {
    let started = with_gap_starts(ctx, gaps);
    tiled(lambdas.len(), gaps, |i, g| match &started[i] {
        Some(c) => c.solve_load_gap(g, c.load_pulloff.load + g),
        None => State::failed(lambdas[i], f64::NAN, f64::NAN, Status::InvalidInput),
    })
}

/// As [`with_starts`] for rows of gaps above each lambda's pull-off.
pub fn with_gap_starts<'a>(
    ctx: &'a [Option<LambdaContext>],
    gaps: &[f64],
) -> std::borrow::Cow<'a, [Option<LambdaContext>]> {
    if gaps.len() < context::START_MIN_STATES {
        return std::borrow::Cow::Borrowed(ctx);
    }
    let (lo, hi) = finite_range(gaps);
    started(ctx, gaps.len(), |c| {
        let pc = c.load_pulloff.load;
        (pc + lo, pc + hi)
    })
}

/// The smallest and largest finite value.
fn finite_range(values: &[f64]) -> (f64, f64) {
    let finite = values.iter().copied().filter(|v| v.is_finite());
    finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    })
}

/// Copies of the contexts, each with a dense start over the loads `range(c)` for `states`
/// states (see [`LambdaContext::add_start`]).
fn started(
    ctx: &[Option<LambdaContext>],
    states: usize,
    range: impl Fn(&LambdaContext) -> (f64, f64) + Sync,
) -> std::borrow::Cow<'_, [Option<LambdaContext>]> {
    std::borrow::Cow::Owned(
        ctx.par_iter()
            .map(|c| {
                c.clone().map(|mut c| {
                    let (lo, hi) = range(&c);
                    c.add_start(lo, hi, states);
                    c
                })
            })
            .collect(),
    )
}

/// The row-major grid of `nx` columns by `rows`, cell (i, v) given by `solve`, on all cores, in
/// tiles of up to 64 rows: each column solves the tile's rows in a row, so that its lambda's
/// tables stay in cache (row by row, every state reads another lambda's table: 1.6x slower on
/// the 1000 x 1000 grid of `cargo bench --bench grid`). At least four tiles a thread.
fn tiled(nx: usize, rows: &[f64], solve: impl Fn(usize, f64) -> State + Sync) -> Vec<State> {
    let mut out = vec![State::failed(0.0, 0.0, 0.0, Status::InvalidInput); nx * rows.len()];
    if nx == 0 {
        return out;
    }
    let tile = (rows.len() / (4 * rayon::current_num_threads())).clamp(1, 64);
    out.par_chunks_mut(nx * tile)
        .zip(rows.par_chunks(tile))
        .for_each(|(cells, vs)| {
            for i in 0..nx {
                for (r, &v) in vs.iter().enumerate() {
                    cells[r * nx + i] = solve(i, v);
                }
            }
        });
    out
}

/// The contexts with a dense start added for `values` (loads) where it pays (see
/// [`LambdaContext::add_start`]); as they are otherwise.
pub fn with_starts<'a>(
    ctx: &'a [Option<LambdaContext>],
    values: &[f64],
    control: Control,
) -> std::borrow::Cow<'a, [Option<LambdaContext>]> {
    let missing = ctx.iter().flatten().any(|c| c.start.is_none());
    if control != Control::Load || values.len() < context::START_MIN_STATES || !missing {
        return std::borrow::Cow::Borrowed(ctx);
    }
    let (lo, hi) = finite_range(values);
    started(ctx, values.len(), |_| (lo, hi))
}
