//! The per-lambda context: pull-offs computed once, then many loads or approaches solved cheaply.

use super::{Control, SolveError, State, Status};
use crate::numeric::root::{bisect_sign, secant_bracketed, Stop};
use crate::physics::md::{
    curve_point, point, zero_radius_end, CurvePoint, ZeroRadiusEnd, LAMBDA_D,
};
use crate::physics::real::{Dd, Real};
use crate::physics::tolerances::carries_load_plus_2;

/// Newton tolerance on x = ln(mu), relative; the residual's rounding noise stops it earlier.
const X_TOL: f64 = 1e-15;
const MAX_ITER: u32 = 100;
/// Width of the search bracket in x below the pull-off: enough for loads up to 1e12 at every
/// lambda in 1e-26..1e26 (measured against the oracle table, tests/suite/domain.rs).
const BRACKET: f64 = 60.0;
pub use crate::physics::tolerances::TABLE_NODES;
/// The first table node's distance from the pull-off in x; node k lies at TABLE_DX0 2^k.
pub const TABLE_DX0: f64 = 0.01 * BRACKET / 81.92;

/// A state given by its contact radius: load, approach and m - 1 from the curve, and whether it
/// is stable under load control (dPbar/dA > 0) and displacement control (dDbar/dA > 0).
#[derive(Clone, Copy, Debug)]
pub struct RadiusState {
    /// The Maugis parameter.
    pub lambda: f64,
    /// Contact radius A.
    pub a: f64,
    /// Pbar.
    pub load: f64,
    /// Dbar.
    pub approach: f64,
    /// m - 1, m = C/A (carried apart: m -> 1 on the JKR side).
    pub m_minus_1: f64,
    /// Stable under load control (before the load-controlled pull-off).
    pub load_stable: bool,
    /// Stable under displacement control (before its jump-out).
    pub displacement_stable: bool,
    /// Whether the state was found.
    pub status: Status,
}

impl RadiusState {
    /// A state that could not be computed: empty fields and `status`.
    pub fn failed(lambda: f64, a: f64, status: Status) -> RadiusState {
        RadiusState {
            lambda,
            a,
            load: f64::NAN,
            approach: f64::NAN,
            m_minus_1: f64::NAN,
            load_stable: false,
            displacement_stable: false,
            status,
        }
    }
}

/// The state at contact radius `a` (A > 0): the curve point there, with its stability under
/// both controls. A falls strictly with mu, so A fixes the state; the only search is the
/// bisection for mu, to the last bit. Stability compares A with the pull-off radii (exact),
/// not the sign of the slopes, which rounding decides near A = 0.
pub fn solve_radius(lambda: f64, a: f64) -> RadiusState {
    match LambdaContext::new(lambda) {
        Ok(ctx) => ctx.solve_radius(a),
        Err(_) => RadiusState::failed(lambda, a, Status::InvalidInput),
    }
}

fn solve_radius_in(ctx: &LambdaContext, a: f64) -> RadiusState {
    let lambda = ctx.lambda;
    if super::domain::check_radius(a).is_err() {
        return RadiusState::failed(lambda, a, Status::InvalidInput);
    }
    let mut x = x_at_radius(lambda, a);
    if x >= 80.0 {
        // A below the usual bracket's end (about 1e-35): mu up to e^700 reaches A ~ 1e-300.
        x = bisect_sign(|x| a - point(lambda, x).a, 80.0, 700.0);
    }
    let p = point(lambda, x);
    let ok = [p.load, p.approach, p.m_minus_1]
        .iter()
        .all(|v| v.is_finite())
        && (p.a / a - 1.0).abs() < 1e-12;
    if !ok {
        // A state that was not found carries no numbers.
        return RadiusState::failed(lambda, a, Status::NotConverged);
    }
    // Load control is stable from the load pull-off on (dPbar/dA > 0 there); displacement
    // control from the displacement jump-out on, which is A = 0 for lambda <= lambda_D.
    let disp_a = if lambda <= LAMBDA_D {
        0.0
    } else {
        ctx.disp_pulloff().a
    };
    RadiusState {
        lambda,
        a,
        load: p.load,
        approach: p.approach,
        m_minus_1: p.m_minus_1,
        load_stable: a >= ctx.load_pulloff.a,
        displacement_stable: a >= disp_a,
        status: Status::Ok,
    }
}

/// Where a stable branch ends: the jump-out (pull-off) point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PullOff {
    /// ln(mu) there; `+inf` when the contact is lost at zero radius.
    pub x: f64,
    /// Pbar at the pull-off.
    pub load: f64,
    /// Contact radius A there.
    pub a: f64,
    /// Dbar there.
    pub approach: f64,
    /// m - 1 there (`inf` at zero radius).
    pub m_minus_1: f64,
}

impl PullOff {
    /// The pull-off is the A -> 0 end of the curve (displacement control, lambda <= lambda_D).
    pub fn at_zero_radius(&self) -> bool {
        self.x == f64::INFINITY
    }
}

#[derive(Clone, Debug)]
/// One lambda's solver: both pull-offs and the coarse table that starts every state.
pub struct LambdaContext {
    /// The Maugis parameter.
    pub lambda: f64,
    /// Load-controlled pull-off: the minimum of Pbar along the curve.
    pub load_pulloff: PullOff,
    /// Displacement-controlled jump-out: the minimum of Dbar (at A = 0 for lambda <= lambda_D).
    /// Computed on first use (a minimum search that load-controlled solves never need).
    disp: std::sync::OnceLock<(PullOff, f64)>,
    /// The A -> 0 end of the curve.
    pub end: ZeroRadiusEnd,
    /// Pbar + 2 at the load pull-off, evaluated without cancellation.
    pub load_plus_2_c: f64,
    /// The stable load branch tabulated at x_k = xc - TABLE_DX0 2^k: ln(Pbar - Pbar_c) per node,
    /// for a first guess and a bracket (a bisection over the nodes, then Newton steps). Each node
    /// is evaluated on first use: a single state needs about four of them, and with every
    /// state its own lambda the fourteen made up half of a context's cost.
    load_table: [std::sync::OnceLock<f64>; TABLE_NODES],
    /// The dense start of the load-controlled branch, where built ([`LambdaContext::add_start`]).
    pub start: Option<std::sync::Arc<super::start::LoadStart>>,
}

/// A lambda with at least this many load-controlled states may get a dense start (where its
/// nodes are fewer than half the states: each state then saves about four evaluations).
pub const START_MIN_STATES: usize = 16;
/// A Newton solve stops where its correction of x is at most this (less near the pull-off) and
/// carries that correction by the slopes: the second-order term it leaves out is below 1e-14.
const ONE_STEP_DX: f64 = 1e-7;

/// x = ln(mu) at which the contact radius equals `a` (A falls strictly with mu).
pub fn x_at_radius(lambda: f64, a: f64) -> f64 {
    bisect_sign(|x| a - point(lambda, x).a, -80.0, 80.0)
}

/// [`x_at_radius`] by Newton steps on ln A (d ln A/dx = mu A'(mu) / A), kept inside the bracket
/// that the residual's signs shrink: the same root within a few ulp in about six curve points,
/// where bisection to the last bit takes sixty. The fits' spring paths need it at every lambda
/// a fit tries.
pub fn x_at_radius_newton(lambda: f64, a: f64) -> f64 {
    let (mut lo, mut hi) = (-80.0f64, 80.0f64);
    let target = a.ln();
    let mut x = 0.0;
    for _ in 0..200 {
        let p = point(lambda, x);
        // ln A falls with x: positive residuals lie left of the root (a NaN, as bisection
        // took it, right of it).
        let r = p.a.ln() - target;
        if r == 0.0 {
            return x;
        } else if r > 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let slope = p.mu * p.da_dmu / p.a;
        let newton = x - r / slope;
        let next = if slope < 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - x).abs() <= 2.0 * f64::EPSILON * x.abs().max(1.0) || !(hi > lo) {
            return next;
        }
        x = next;
    }
    x
}

fn dload_dx_dd(lambda: f64, x: f64) -> f64 {
    let mu = x.exp();
    let p = curve_point(Dd::of(lambda), Dd::of(mu));
    p.dload_dmu.to_f64() * mu
}

fn dapproach_dx_dd(lambda: f64, x: f64) -> f64 {
    let mu = x.exp();
    let p = curve_point(Dd::of(lambda), Dd::of(mu));
    p.dapproach_dmu.to_f64() * mu
}

/// Brackets the sign change of `slope` (negative on the stable side) within `half` of `x_est`,
/// widening by steps of 2 where it is not there, and closes in on it.
/// Returns `None` if no positive slope is found to the right (the minimum is at x = inf).
fn minimum_of(slope: impl Fn(f64) -> f64, x_est: f64, half: f64) -> Option<f64> {
    let (mut lo, mut hi) = (x_est - half, x_est + half);
    let mut n = 0;
    let mut s_lo = slope(lo);
    while s_lo >= 0.0 {
        hi = lo;
        lo -= 2.0;
        s_lo = slope(lo);
        n += 1;
        if n > 40 {
            return None;
        }
    }
    n = 0;
    let mut s_hi = slope(hi);
    while s_hi <= 0.0 {
        (lo, s_lo) = (hi, s_hi);
        hi += 2.0;
        s_hi = slope(hi);
        n += 1;
        if n > 20 {
            return None;
        }
    }
    // The bracketed secant (bisection where a step misbehaves): about ten slopes where plain
    // bisection takes sixty, which made the context the cost of scattered states.
    let x0 = if x_est > lo && x_est < hi {
        x_est
    } else {
        0.5 * (lo + hi)
    };
    let r = secant_bracketed(|x| -slope(x), (lo, -s_lo), (hi, -s_hi), x0, 1e-15, 200);
    Some(r.x)
}

/// The minimum of a curve quantity: bisection on the f64 slope, then secant steps on the
/// double-double slope where f64 is too coarse (`precise_below`: f64 cannot even bracket it).
fn minimum_polished(
    fast: impl Fn(f64) -> f64,
    precise: impl Fn(f64) -> f64,
    (x_est, half): (f64, f64),
    polish: bool,
    precise_only: bool,
) -> Option<f64> {
    if precise_only {
        return minimum_of(precise, x_est, half);
    }
    // From the fitted guess the precise secant needs no f64 search first: two or three
    // double-double slopes instead of about eight f64 ones and three precise ones.
    if polish && half < 1e-5 {
        if let Some(x) = secant_from_guess(&precise, x_est, half) {
            return Some(x);
        }
    }
    let x = minimum_of(&fast, x_est, half)?;
    if !polish {
        return Some(x);
    }
    let (mut x0, mut x1) = (x, x + 1e-7 * x.abs().max(1.0));
    let (mut f0, mut f1) = (precise(x0), precise(x1));
    for _ in 0..10 {
        if f1 == f0 {
            break;
        }
        let step = -f1 * (x1 - x0) / (f1 - f0);
        (x0, f0) = (x1, f1);
        x1 += step;
        if !(step.abs() > 1e-16 * x1.abs().max(1.0)) {
            break;
        }
        f1 = precise(x1);
    }
    // The polish only moves within the f64 noise; anything else means it went astray.
    if (x1 - x).abs() < 1e-2 {
        Some(x1)
    } else {
        minimum_of(precise, x_est, 2.0)
    }
}

/// The zero of `slope` by secant steps from `x_est` (within `half` of it), stopped when the next
/// error, about the product of the last two steps over x's scale, is far below x's rounding:
/// None where the steps leave `half` or do not settle in four.
fn secant_from_guess(slope: impl Fn(f64) -> f64, x_est: f64, half: f64) -> Option<f64> {
    let scale = x_est.abs().max(1.0);
    let (mut x0, mut x1) = (x_est, x_est + 1e-9 * scale);
    let (mut f0, mut f1) = (slope(x0), slope(x1));
    let mut prev = f64::NAN;
    for _ in 0..4 {
        if f1 == f0 {
            return None;
        }
        let step = -f1 * (x1 - x0) / (f1 - f0);
        (x0, f0) = (x1, f1);
        x1 += step;
        if !((x1 - x_est).abs() < half) {
            return None;
        }
        // Before a previous step, the first one stands for the guess's error.
        let last = if prev.is_nan() { step } else { prev };
        if (step * last).abs() <= 1e-17 * scale * scale {
            return Some(x1);
        }
        prev = step;
        f1 = slope(x1);
    }
    None
}

/// x = ln(mu) of the load pull-off, the minimum of Pbar along the curve, searched from `guess`
/// (and how far the first bracket reaches). The slope of Pbar at its minimum is a difference of
/// terms larger by ~lambda^-3 (PHYSICS.md section 5): below lambda = 0.5 it is polished in
/// double-double, below 1e-3 searched in double-double alone.
fn load_pulloff_x(lambda: f64, guess: (f64, f64)) -> Option<f64> {
    let slope = |x: f64| {
        let p = point(lambda, x);
        p.dload_dmu * p.mu
    };
    let slope_dd = |x: f64| dload_dx_dd(lambda, x);
    minimum_polished(slope, slope_dd, guess, lambda < 0.5, lambda < 1e-3)
}

/// Below this lambda the load pull-off's radius comes from its series, not from the zero of the
/// slope: that slope is a difference of terms larger by lambda^-3, so even in double-double its
/// zero moves A_c by about 1.5e-33 lambda^-3 (1.5e-9 at lambda = 1e-8, measured against the
/// 50-digit oracle), while the series' next term is O(lambda^3).
pub const PULLOFF_SERIES_BELOW: f64 = 1e-6;

/// The contact radius of the load pull-off as lambda -> 0 (docs/PHYSICS.md section 5.1):
/// `Pbar + 2 = 1.7175 lambda^1.5 - pi lambda (1 + 0.16144 lambda^1.5) A^2 + (1 + sqrt(pi)
/// lambda^1.5) A^3 + ...`, whose minimum is at `A_c = (2 pi lambda / 3) (1 - (4 (pi - 1) /
/// (3 sqrt(pi))) lambda^1.5 + O(lambda^3))`.
pub fn pulloff_radius_series(lambda: f64) -> f64 {
    use std::f64::consts::PI;
    let c = 4.0 * (PI - 1.0) / (3.0 * PI.sqrt());
    (2.0 * PI * lambda / 3.0) * (1.0 - c * lambda * lambda.sqrt())
}

fn second_derivative(slope: impl Fn(f64) -> f64, x: f64) -> f64 {
    let h = 1e-3;
    (slope(x + h) - slope(x - h)) / (2.0 * h)
}

fn pulloff_at(lambda: f64, x: f64) -> PullOff {
    let p = point(lambda, x);
    PullOff {
        x,
        load: p.load,
        a: p.a,
        approach: p.approach,
        m_minus_1: p.m_minus_1,
    }
}

/// The first guess of the load pull-off's x = ln(mu), from a fit over lambda, so that its
/// search brackets it at once and takes a few secant steps, the double-double ones included
/// (with every state its own lambda, that search is most of the cost).
mod pulloff_fit {
    use std::sync::OnceLock;

    /// log10(lambda) covered: 1e-8..1e8 (beyond it the search starts from the asymptotes).
    const U_LO: f64 = -8.0;
    const PIECES: usize = 16;
    /// Chebyshev points per decade: the interpolant is within 1.2e-8 of x_c (measured at 4000
    /// points), so the first bracket is 1e-6 wide; the search widens it where it must.
    const N: usize = 14;
    const HALF: f64 = 1e-6;

    /// The JKR (mu ~ 1.14/lambda) and DMT (mu ~ 0.54 lambda^-1.5) asymptotes.
    pub(super) fn asymptotic(lambda: f64) -> f64 {
        (1.1447 / lambda + 0.54 * lambda.powf(-1.5)).ln()
    }

    /// Per decade, the Chebyshev coefficients of x_c - asymptotic, from full searches at the
    /// Chebyshev points (224 of them, once per process). On this thread: a parallel build
    /// inside `get_or_init` deadlocks when a worker that waits for it steals a task that
    /// needs the fit too.
    fn table() -> &'static [[f64; N]; PIECES] {
        static FIT: OnceLock<[[f64; N]; PIECES]> = OnceLock::new();
        FIT.get_or_init(|| {
            let node = |j: usize| (std::f64::consts::PI * (j as f64 + 0.5) / N as f64).cos();
            let values: Vec<f64> = (0..PIECES * N)
                .map(|i| {
                    let lambda = 10f64.powf(U_LO + (i / N) as f64 + 0.5 * (1.0 + node(i % N)));
                    let x_est = asymptotic(lambda);
                    super::load_pulloff_x(lambda, (x_est, 2.0)).map_or(0.0, |x| x - x_est)
                })
                .collect();
            std::array::from_fn(|p| {
                let f = &values[p * N..(p + 1) * N];
                std::array::from_fn(|k| {
                    let s: f64 = (0..N)
                        .map(|j| {
                            let angle = std::f64::consts::PI * k as f64 * (j as f64 + 0.5);
                            f[j] * (angle / N as f64).cos()
                        })
                        .sum();
                    s * 2.0 / N as f64 * if k == 0 { 0.5 } else { 1.0 }
                })
            })
        })
    }

    /// The guessed x_c and how far the first bracket reaches on either side of it.
    pub fn guess(lambda: f64) -> (f64, f64) {
        let x_est = asymptotic(lambda);
        let u = lambda.log10() - U_LO;
        if !(0.0..=PIECES as f64).contains(&u) {
            return (x_est, 2.0);
        }
        let p = (u as usize).min(PIECES - 1);
        let v = 2.0 * (u - p as f64) - 1.0;
        let c = &table()[p];
        let (mut b1, mut b2) = (0.0, 0.0);
        for &ck in c[1..].iter().rev() {
            (b1, b2) = (2.0 * v * b1 - b2 + ck, b1);
        }
        let x = x_est + v * b1 - b2 + c[0];
        if x.is_finite() {
            (x, HALF)
        } else {
            (x_est, 2.0)
        }
    }
}

impl LambdaContext {
    /// Solves both pull-offs and builds the start table; lambda in the exact domain.
    pub fn new(lambda: f64) -> Result<Self, SolveError> {
        Self::new_uncertified(super::domain::check_lambda(lambda)?)
    }

    /// As [`LambdaContext::new`] for any finite lambda > 0, outside the certified domain too:
    /// for measuring where the solver stops (`examples/domain_probe.rs`), never for answers.
    #[doc(hidden)]
    pub fn new_uncertified(lambda: f64) -> Result<Self, SolveError> {
        if !(lambda.is_finite() && lambda > 0.0) {
            return Err(super::domain::check_lambda(f64::NAN).unwrap_err().into());
        }
        let xc = if lambda < PULLOFF_SERIES_BELOW {
            // The radius of the minimum from its series, x from the radius (well conditioned).
            // mu_c ~ 0.54 lambda^-1.5 passes e^80 below lambda ~ 1e-23.
            let a = pulloff_radius_series(lambda);
            bisect_sign(|x| a - point(lambda, x).a, -80.0, 200.0)
        } else {
            load_pulloff_x(lambda, pulloff_fit::guess(lambda))
                .ok_or(SolveError::NoPullOff(lambda))?
        };
        let p = point(lambda, xc);
        let load_pulloff = PullOff {
            x: xc,
            load: p.load,
            a: p.a,
            approach: p.approach,
            m_minus_1: p.m_minus_1,
        };
        let load_plus_2_c = p.load_plus_2;
        let end = zero_radius_end(lambda);

        Ok(Self {
            lambda,
            load_pulloff,
            disp: std::sync::OnceLock::new(),
            end,
            load_plus_2_c,
            load_table: Default::default(),
            start: None,
        })
    }

    /// Displacement-controlled jump-out: the minimum of Dbar (at A = 0 for lambda <= lambda_D).
    pub fn disp_pulloff(&self) -> PullOff {
        self.disp().0
    }

    /// d2Dbar/dx2 at an interior displacement jump-out (NaN at zero radius).
    pub fn disp_curvature(&self) -> f64 {
        self.disp().1
    }

    fn disp(&self) -> (PullOff, f64) {
        *self.disp.get_or_init(|| {
            let (lambda, end) = (self.lambda, self.end);
            let xc = self.load_pulloff.x;
            let zero_radius = PullOff {
                x: f64::INFINITY,
                load: end.load,
                a: 0.0,
                approach: end.approach,
                m_minus_1: f64::INFINITY,
            };
            let (disp_pulloff, disp_curvature) = if lambda <= LAMBDA_D {
                (zero_radius, f64::NAN)
            } else {
                let disp_slope = |x: f64| {
                    let p = point(lambda, x);
                    p.dapproach_dmu * p.mu
                };
                let disp_slope_dd = |x: f64| dapproach_dx_dd(lambda, x);
                // JKR jump-out under rigid grips: A = 6^(-1/3), mu ~ 1.65/lambda.
                let x_est = (1.65 / lambda).ln().min(xc + 2.0);
                // Just above lambda_D the minimum sits at tiny A, where the f64 slope cancels.
                let near_d = lambda < 1.2;
                let guess = (x_est, 2.0);
                match minimum_polished(disp_slope, disp_slope_dd, guess, lambda < 4.0, near_d) {
                    Some(xd) => (pulloff_at(lambda, xd), second_derivative(disp_slope, xd)),
                    None => (zero_radius, f64::NAN),
                }
            };
            (disp_pulloff, disp_curvature)
        })
    }

    /// Builds the dense start of the load-controlled branch (see [`super::start`]) for loads
    /// from `load_lo` to `load_hi`, where it costs fewer curve evaluations than half of the
    /// `states` to solve: afterwards such a state usually costs one curve evaluation.
    pub fn add_start(&mut self, load_lo: f64, load_hi: f64, states: usize) {
        let pc = self.load_pulloff.load;
        let (gap_lo, gap_hi) = ((load_lo - pc).max(0.0), load_hi - pc);
        if self.start.is_some() || !(gap_hi > 0.0 && gap_hi.is_finite()) {
            return;
        }
        let (lambda, p2c, xc) = (self.lambda, self.load_plus_2_c, self.load_pulloff.x);
        let small = carries_load_plus_2(lambda);
        let gap = move |p: &CurvePoint<f64>| {
            if small {
                p.load_plus_2 - p2c
            } else {
                p.load - pc
            }
        };
        // Start a little below the smallest load, from the coarse table's guess.
        let (_, _, x_lo) = self.load_guess(gap_lo.max(f64::MIN_POSITIVE).ln());
        let y_lo = (xc - x_lo).ln() - 0.5;
        self.start = super::start::LoadStart::new(lambda, xc, gap, y_lo, gap_hi.ln(), states / 2)
            .map(Into::into);
    }

    /// The state at `Pbar - Pbar_c = gap` by Newton steps on F = ln(1 + r/gap) from `x0`
    /// (one curve evaluation each, at most `max_evals`) until the correction of x is at most
    /// `ONE_STEP_DX` (less near the pull-off), then that last correction carried to A, Dbar and
    /// m - 1 by their slopes (its second-order error in x is below 1e-14). Every iterate stays strictly inside `(lo, hi)`. None
    /// (the caller searches) where a step leaves the bracket, the steps do not settle, or the
    /// evaluation does not certify the state.
    fn solve_load_newton(
        &self,
        x0: f64,
        (lo, hi): (f64, f64),
        max_evals: u32,
        gap: f64,
        load: f64,
    ) -> Option<State> {
        let small = carries_load_plus_2(self.lambda);
        let (mut x, mut mu) = (x0, x0.exp());
        for evals in 1..=max_evals {
            let p = curve_point(self.lambda, mu);
            let r = if small {
                (p.load_plus_2 - self.load_plus_2_c) - gap
            } else {
                (p.load - self.load_pulloff.load) - gap
            };
            // F' = P'(x) / (gap + r). ln(1 + z) by its series where z is small (as it is near
            // the root): a libm call saved per state, the step's relative error z^4/4.
            let z = r / gap;
            let f = if z.abs() < 1e-3 {
                z * (1.0 - z * (0.5 - z / 3.0))
            } else {
                z.ln_1p()
            };
            let dx = -f * (gap + r) / (p.dload_dmu * p.mu);
            if !(dx.is_finite() && x + dx > lo && x + dx < hi) {
                return None;
            }
            // Near the pull-off F bends like 2 ln(xc - x): the carried step's error in x is
            // about dx^2 / (xc - x), held to ONE_STEP_DX^2 = 1e-14 there too.
            if dx * dx > ONE_STEP_DX * ONE_STEP_DX * (self.load_pulloff.x - x).min(1.0) {
                x += dx;
                mu *= dx.exp();
                continue;
            }
            let noise = 1e-13 * load.abs().max(2.0);
            if r.abs() > 1e-6 * gap + noise {
                return None;
            }
            let m = 1.0 + p.m_minus_1;
            let s = State {
                lambda: self.lambda,
                load,
                approach: p.approach + p.dapproach_dmu * p.mu * dx,
                a: p.a + p.da_dmu * p.mu * dx,
                m_minus_1: p.m_minus_1 + p.mu * p.mu / m * dx,
                status: Status::Ok,
                iterations: evals,
            };
            let ok = [s.approach, s.a, s.m_minus_1].iter().all(|v| v.is_finite())
                && s.a > 0.0
                && s.m_minus_1 > 0.0;
            return ok.then_some(s);
        }
        None
    }

    /// The state at x from one curve evaluation: the controlled quantity as given, the other
    /// (approach under load control, load under displacement control) from the curve.
    ///
    /// The same evaluation certifies it: a state is `ok` only if every field is finite, A > 0,
    /// and the controlled quantity is reproduced (`gap` is its distance from the pull-off); a
    /// search that ended anywhere else is `not_converged`, never a number marked ok.
    fn state(
        &self,
        x: f64,
        given: f64,
        gap: f64,
        control: Control,
        iterations: u32,
        stop: Stop,
    ) -> State {
        let p = point(self.lambda, x);
        let (load, approach, other, residual) = match control {
            Control::Load => {
                let r = if carries_load_plus_2(self.lambda) {
                    (p.load_plus_2 - self.load_plus_2_c) - gap
                } else {
                    (p.load - self.load_pulloff.load) - gap
                };
                (given, p.approach, p.approach, r)
            }
            Control::Displacement => (p.load, given, p.load, p.approach - given),
        };
        // Rounding noise of the curve is ~1e-16 of the larger of the value and the pull-off.
        let noise = 1e-13 * given.abs().max(2.0);
        let certified = [other, p.a, p.m_minus_1].iter().all(|v| v.is_finite())
            && p.a > 0.0
            && p.m_minus_1 > 0.0
            && residual.abs() <= 1e-6 * gap.abs() + noise;
        State {
            lambda: self.lambda,
            load,
            approach,
            a: p.a,
            m_minus_1: p.m_minus_1,
            status: match stop {
                Stop::Converged if certified => Status::Ok,
                _ => Status::NotConverged,
            },
            iterations,
        }
    }

    /// The state at load `load` (Pbar) on the load-controlled stable branch.
    pub fn solve_load(&self, load: f64) -> State {
        let lambda = self.lambda;
        if super::domain::check_load(load).is_err() {
            return State::failed(lambda, load, f64::NAN, Status::InvalidInput);
        }
        let pc = self.load_pulloff;
        if load < pc.load {
            return State::failed(lambda, load, f64::NAN, Status::NoContact);
        }
        // The residual is written as a difference from the pull-off so that its relative
        // accuracy does not degrade as the load approaches Pbar_c. On the DMT side the load is
        // carried as Pbar + 2 (exact in floating point near -2).
        let small = carries_load_plus_2(lambda);
        let gap = if small {
            (load + 2.0) - self.load_plus_2_c
        } else {
            load - pc.load
        };
        self.solve_load_gap(gap, load)
    }

    /// The state at `Pbar - Pbar_c = gap` (exact, however small); `load` is what is reported.
    pub fn solve_load_gap(&self, gap: f64, load: f64) -> State {
        if !(gap.is_finite() && gap > 0.0) {
            return self.solve_load_search(gap, load);
        }
        let t = gap.ln();
        // The dense start's x is within about 1e-8: one evaluation, rarely more.
        if let Some(x0) = self.start.as_ref().and_then(|s| s.x(t)) {
            let bracket = (x0 - 1e-2, (x0 + 1e-2).min(self.load_pulloff.x));
            if let Some(s) = self.solve_load_newton(x0, bracket, 4, gap, load) {
                return s;
            }
        }
        // Else the coarse table's bracket and guess: Newton (about three evaluations, where
        // the secant takes six and one more for the state), the secant where it fails.
        let (lo, hi, x0) = self.load_guess(t);
        if let Some(s) = self.solve_load_newton(x0, (lo.0, hi.0), 8, gap, load) {
            return s;
        }
        self.solve_load_search(gap, load)
    }

    /// As [`LambdaContext::solve_load_gap`] by the bracketed secant search alone, from the
    /// coarse table, the state certified by one more evaluation: what the Newton solves fall
    /// back on, and their independent check in the tests.
    pub fn solve_load_search(&self, gap: f64, load: f64) -> State {
        let lambda = self.lambda;
        let pc = self.load_pulloff;
        let small = carries_load_plus_2(lambda);
        if !gap.is_finite() {
            return State::failed(lambda, load, f64::NAN, Status::InvalidInput);
        }
        if gap <= 0.0 {
            return self.state(pc.x, load, 0.0, Control::Load, 0, Stop::Converged);
        }
        let residual = |x: f64| {
            let p = point(lambda, x);
            let r = if small {
                (p.load_plus_2 - self.load_plus_2_c) - gap
            } else {
                (p.load - pc.load) - gap
            };
            // F = ln((P - Pc) / (P_target - Pc)): nearly linear in x far from the pull-off and
            // like 2 ln(xc - x) near it, so the secant converges in a few steps everywhere.
            let f = (r / gap).ln_1p();
            if f.is_nan() {
                f64::NEG_INFINITY
            } else {
                f
            }
        };
        let (lo, hi, x0) = self.load_guess(gap.ln());
        let root = secant_bracketed(residual, lo, hi, x0, X_TOL, MAX_ITER);
        self.state(
            root.x,
            load,
            gap,
            Control::Load,
            root.iterations + 1,
            root.stop,
        )
    }

    /// x of table node k.
    fn table_x(&self, k: usize) -> f64 {
        self.load_pulloff.x - TABLE_DX0 * 2f64.powi(k as i32)
    }

    /// ln(Pbar - Pbar_c) at table node k, evaluated on first use.
    fn table_t(&self, k: usize) -> f64 {
        *self.load_table[k].get_or_init(|| {
            let p = point(self.lambda, self.table_x(k));
            let gap = if carries_load_plus_2(self.lambda) {
                p.load_plus_2 - self.load_plus_2_c
            } else {
                p.load - self.load_pulloff.load
            };
            // Below lambda ~ 3e-9 the nearest nodes' gap, ~6e-4 lambda^3, is under the f64
            // noise of Pbar + 2 (~1e-16 lambda^1.5) and may come out <= 0: such a node is below
            // every load (-inf), not NaN, which would break the bisection over the nodes.
            if gap > 0.0 {
                gap.ln()
            } else {
                f64::NEG_INFINITY
            }
        })
    }

    /// Bracket (with residuals) and first guess for ln(Pbar - Pbar_c) = t from the table: linear
    /// in (t, ln(xc - x)), which is exact near the pull-off, where P - Pc ~ (xc - x)^2.
    #[allow(clippy::type_complexity)]
    fn load_guess(&self, t: f64) -> ((f64, f64), (f64, f64), f64) {
        let xc = self.load_pulloff.x;
        let tab = |k: usize| (self.table_t(k), self.table_x(k));
        // The first node with t_k >= t, by bisection over the nodes (t_k increases with k).
        let (mut k, mut k_hi) = (0, TABLE_NODES);
        while k < k_hi {
            let mid = (k + k_hi) / 2;
            if self.table_t(mid) < t {
                k = mid + 1;
            } else {
                k_hi = mid;
            }
        }
        if k == 0 {
            let (t0, x0) = tab(0);
            return (
                (x0, t0 - t),
                (xc, f64::NEG_INFINITY),
                xc - (xc - x0) * ((t - t0) / 2.0).exp(),
            );
        }
        if k == TABLE_NODES {
            let (t1, x1) = tab(k - 1);
            return ((xc - 4.0 * BRACKET, f64::INFINITY), (x1, t1 - t), x1 - 1.0);
        }
        let ((t0, x0), (t1, x1)) = (tab(k - 1), tab(k));
        if t0 == f64::NEG_INFINITY {
            // A node below the noise: no interpolation, the bracket's middle.
            return ((x1, t1 - t), (x0, f64::NEG_INFINITY), 0.5 * (x0 + x1));
        }
        let w = (t - t0) / (t1 - t0);
        let y = (xc - x0).ln() * (1.0 - w) + (xc - x1).ln() * w;
        ((x1, t1 - t), (x0, t0 - t), xc - y.exp())
    }

    /// The state at approach `approach` (Dbar) on the displacement-controlled stable branch.
    pub fn solve_approach(&self, approach: f64) -> State {
        let lambda = self.lambda;
        if super::domain::check_approach(approach).is_err() {
            return State::failed(lambda, f64::NAN, approach, Status::InvalidInput);
        }
        let jo = self.disp_pulloff();
        if approach < jo.approach {
            return State::failed(lambda, f64::NAN, approach, Status::NoContact);
        }
        let gap = approach - jo.approach;
        if gap == 0.0 {
            return self.zero_gap_disp_state(approach);
        }
        let residual = |x: f64| {
            let r = point(lambda, x).approach - approach;
            let f = (r / gap).ln_1p();
            if f.is_nan() {
                f64::NEG_INFINITY
            } else {
                f
            }
        };
        let (lo, hi, x0) = if jo.at_zero_radius() {
            let xc = self.load_pulloff.x;
            (xc - BRACKET, xc + BRACKET, xc)
        } else {
            let x0 = jo.x - (2.0 * gap / self.disp_curvature()).sqrt();
            (
                jo.x - BRACKET,
                jo.x,
                if x0.is_finite() { x0 } else { jo.x - 1.0 },
            )
        };
        let mut f_lo = residual(lo);
        let mut lo = lo;
        while f_lo <= 0.0 && lo > -1e3 {
            lo -= BRACKET;
            f_lo = residual(lo);
        }
        let f_hi = if jo.at_zero_radius() {
            residual(hi).min(0.0)
        } else {
            f64::NEG_INFINITY
        };
        let root = secant_bracketed(residual, (lo, f_lo), (hi, f_hi), x0, X_TOL, MAX_ITER);
        self.state(
            root.x,
            approach,
            gap,
            Control::Displacement,
            root.iterations,
            root.stop,
        )
    }

    /// The state at contact radius `a`; see [`solve_radius`].
    pub fn solve_radius(&self, a: f64) -> RadiusState {
        solve_radius_in(self, a)
    }

    fn zero_gap_disp_state(&self, approach: f64) -> State {
        let jo = self.disp_pulloff();
        State {
            lambda: self.lambda,
            load: jo.load,
            approach,
            a: jo.a,
            m_minus_1: jo.m_minus_1,
            status: Status::Ok,
            iterations: 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Where the pull-off is polished in double-double (1e-3 <= lambda < 0.5), the secant from
    /// the fitted guess lands within a few ulps of the bracketed search from the asymptotes, in
    /// about two precise slopes.
    #[test]
    fn polish_from_the_guess_matches_the_bracketed_search() {
        let (mut worst, mut evals) = (0f64, 0usize);
        let n = 2000;
        for i in 0..n {
            let lambda = 1e-3 * 500f64.powf((i as f64 + 0.5) / n as f64);
            let fast = |x: f64| {
                let p = point(lambda, x);
                p.dload_dmu * p.mu
            };
            let full = load_pulloff_x(lambda, (pulloff_fit::asymptotic(lambda), 2.0)).unwrap();
            let count = std::cell::Cell::new(0);
            let counted = |x: f64| {
                count.set(count.get() + 1);
                dload_dx_dd(lambda, x)
            };
            let guess = pulloff_fit::guess(lambda);
            let x = minimum_polished(fast, counted, guess, true, false).unwrap();
            evals += count.get();
            worst = worst.max((x - full).abs() / (f64::EPSILON * full.abs().max(1.0)));
        }
        let per = evals as f64 / n as f64;
        eprintln!("polish from the guess: within {worst:.1} ulp, {per:.2} precise slopes");
        assert!(worst <= 4.0, "{worst} ulp");
        assert!(per < 2.5, "{per} precise slopes a context");
    }

    /// The fitted guess is within a twentieth of its bracket of the pull-off that the search
    /// converges to, at points between the fit's nodes across the whole domain.
    #[test]
    fn pulloff_fit_guesses_within_its_bracket() {
        let mut worst = 0f64;
        for i in 0..400 {
            let lambda = 10f64.powf(-8.0 + 16.0 * (i as f64 + 0.31) / 400.0);
            let (guess, half) = pulloff_fit::guess(lambda);
            assert!(half < 1e-5, "lambda {lambda}: no fit");
            let x = LambdaContext::new(lambda).unwrap().load_pulloff.x;
            worst = worst.max((guess - x).abs() / half);
        }
        assert!(worst < 0.05, "worst |guess - x_c| / bracket = {worst:.3}");
    }

    #[test]
    fn newtons_radius_root_is_bisections() {
        let mut worst: f64 = 0.0;
        for &lambda in &[0.01, 0.1, 0.7, 3.0, 40.0, 1000.0] {
            for &a in &[1e-9, 1e-4, 0.05, 0.5, 1.0, 2.0, 16.0, 1024.0, 1e5] {
                let (n, b) = (x_at_radius_newton(lambda, a), x_at_radius(lambda, a));
                let err = (n - b).abs() / b.abs().max(1.0);
                worst = worst.max(err);
                assert!(err <= 1e-13, "lambda {lambda}, A {a}: {n} against {b}");
                assert!((point(lambda, n).a / a - 1.0).abs() <= 1e-14);
            }
        }
        eprintln!("worst relative difference {worst:e}");
    }
}
