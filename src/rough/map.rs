//! The rough adhesion map (`tabor rough-map`): over lambda and sigma, the pull-off per summit of
//! a Greenwood-Williamson surface of exact Maugis-Dugdale summits relative to the smooth
//! summit's, and the simplest summit model (Hertz, Bradley, DMT, JKR, else MD) whose rough
//! pull-off and retract curve are within a tolerance of the exact ones (docs/PHYSICS.md
//! section 9).
//!
//! Per lambda the summit's contact branch is tabulated once (exact f64 solves, cubic
//! interpolation with its error measured at every interval's midpoint); every sigma of that
//! column then only integrates the table against the Gaussian (piecewise Gauss-Legendre).

use super::{Leg, Rough, RoughError, Summit};
use crate::engine::{CheckReport, Engine};
use crate::error::Message;
use crate::map::Region;
use crate::numeric::legendre::{gauss_legendre, Order};
use crate::physics::closed::{jkr_approach, jkr_load};
use crate::physics::domain::short;
use crate::solver::{Control, Status};
use rayon::prelude::*;
use serde::Serialize;
use std::f64::consts::PI;

/// The Gaussian's mass beyond this many sigma (2.6e-12) is dropped in the map's quadrature.
const Z_MAP: f64 = 7.0;
/// Widest quadrature piece, in sigma, and its Gauss-Legendre nodes: over the 256 x 256
/// gallery map the pull-offs agree with 20 nodes on pieces of 1 sigma within 7.6e-7 of
/// max(|pull-off|, 1e-3 |Pbar_c|), the same largest difference as with pieces of 6 sigma
/// (0.8 of the time) and 3e-6 with 12 nodes on 2 sigma; pieces of 14 sigma miss by 1.2e-4
/// (measured as in README's rough-map section).
const PIECE: f64 = 8.0;
const GL_N: usize = 20;
/// Samples of each retract curve (the curves are compared there; the pull-off is refined from
/// the smallest).
pub const CURVE_SAMPLES: usize = 20;
/// Half-width, in sigma, of the window sampled around each jump-out (see `jump_windows`): the
/// Gaussian's weight beyond it is 3e-5 of its peak.
const JUMP_WINDOW: f64 = 4.0;
/// Interpolation error the table aims at; intervals next to the fold that miss it (near
/// lambda_D the branch turns within a tiny range of approaches) are solved exactly instead.
const TABLE_TARGET: f64 = 1e-6;
/// The exactly solved stretch may reach up to this v (u about 2.5).
const EXACT_V_MAX: f64 = 2.0;
/// How much finer the table of that stretch is ([`BranchTable::refine_fold`]).
const FOLD_REFINE: usize = 16;
/// Table step in the graded variable v (u = v + v^2 / (2 U_S), u = sqrt(delta - delta_out)).
pub(crate) const TABLE_H: f64 = 0.025;
/// 1 / TABLE_H: the quadrature's inner loop multiplies rather than divides.
pub(crate) const TABLE_INV_H: f64 = 40.0;
pub(crate) const U_S: f64 = 4.0;
/// The ratio contours drawn and exported.
pub const CONTOURS: [f64; 3] = [0.5, 0.1, 0.01];

/// What `tabor rough-map` computes.
#[derive(Clone, Debug, Serialize)]
pub struct RoughMapSpec {
    /// The smallest lambda (log axis).
    pub lambda_min: f64,
    /// The largest lambda.
    pub lambda_max: f64,
    /// Columns (lambda).
    pub nx: usize,
    /// The smallest roughness sigma (approach units, log axis).
    pub sigma_min: f64,
    /// The largest roughness.
    pub sigma_max: f64,
    /// Rows (sigma).
    pub ny: usize,
    /// Largest pull-off error (relative to the smooth summit's pull-off) and retract-curve error
    /// (relative to the curve's largest |load|) a simpler summit model may have.
    pub tolerance: f64,
    /// The flat is pressed to `-press_sigmas * sigma` before the retract.
    pub press_sigmas: f64,
}

impl RoughMapSpec {
    /// One clear line for a bad value.
    pub fn validate(&self) -> Result<(), RoughError> {
        let bad = |m: Message| Err(RoughError::Scene(m));
        crate::physics::domain::check_lambda_range(self.lambda_min, self.lambda_max)
            .map_err(RoughError::Scene)?;
        super::check_roughness_range(self.sigma_min, self.sigma_max).or_else(bad)?;
        if !(2..=4096).contains(&self.nx) || !(2..=4096).contains(&self.ny) {
            return bad(Message::new()
                .key("nx")
                .text(" and ")
                .key("ny")
                .text(format!(
                    " must be in 2..=4096, got {} and {}",
                    self.nx, self.ny
                )));
        }
        if !(self.tolerance > 0.0 && self.tolerance < 1.0) {
            return bad(Message::new()
                .key("tolerance")
                .text(format!(" must be in (0, 1), got {}", short(self.tolerance))));
        }
        super::check_press_sigmas(self.press_sigmas).or_else(bad)
    }
}

/// The summit's stable contact branch tabulated in v, where `u = v + v^2 / (2 U_S)` and
/// `u = sqrt(delta - delta_out)`: the square root takes the fold's `sqrt(delta - delta_out)`
/// singularity out of the table, and the grading spaces the nodes wider where the load is
/// nearly Hertz's. The interpolant is the not-a-knot cubic spline through the nodes: twice
/// continuously differentiable, so that the quadrature over it converges as over a smooth
/// function (a piecewise Lagrange cubic has a kink at every node).
#[derive(Clone, Debug)]
pub struct BranchTable {
    delta0: f64,
    /// Per interval in v, the cubic's coefficients in `s = v / TABLE_H - k`, lowest first;
    /// from [`spline`] only, so never empty (the unchecked indexing of [`spline_at`] and the
    /// quadrature relies on it).
    coef: Vec<[f64; 4]>,
    /// The largest difference, at the midpoints of all intervals, between the interpolant and
    /// the exact load, divided by max(1, |load|), outside the exactly solved stretch.
    pub error: f64,
    /// Below this v the load is solved exactly, not interpolated (0: nowhere).
    pub exact_below: f64,
    /// A finer table of the stretch next to the fold that this table misses the target in
    /// (from `exact_below` up to its end), where that one meets it.
    fold: Option<FoldTable>,
}

/// The stretch `v < end` next to the fold, tabulated at [`FOLD_REFINE`] times the main step
/// (the cubic's coefficients in `s = v / h - k`).
#[derive(Clone, Debug)]
struct FoldTable {
    inv_h: f64,
    end: f64,
    coef: Vec<[f64; 4]>,
}

impl FoldTable {
    #[inline]
    fn at_v(&self, v: f64) -> f64 {
        let x = v * self.inv_h;
        spline_at(&self.coef, x)
    }
}

pub(crate) fn u_of_v(v: f64) -> f64 {
    v + v * v / (2.0 * U_S)
}

#[inline]
pub(crate) fn v_of_u(u: f64) -> f64 {
    // The positive root of v^2 / (2 U_S) + v - u = 0, written without cancellation.
    2.0 * u / (1.0 + (1.0 + u * (2.0 / U_S)).sqrt())
}

impl BranchTable {
    /// Tabulates `load(delta)` for `delta` in `[delta0, delta_hi]`; `None` where it fails.
    pub fn new(delta0: f64, delta_hi: f64, load: impl Fn(f64) -> Option<f64>) -> Option<Self> {
        let loads: Vec<f64> = Self::approaches(delta0, delta_hi)
            .into_iter()
            .map(&load)
            .collect::<Option<_>>()?;
        Self::from_loads(delta0, &loads)
    }

    /// The approaches a table of `[delta0, delta_hi]` is solved at: its nodes, then the
    /// midpoints of its intervals (where its error is measured).
    pub fn approaches(delta0: f64, delta_hi: f64) -> Vec<f64> {
        let v_max = v_of_u((delta_hi - delta0).max(1.0).sqrt());
        let n = (v_max / TABLE_H).ceil() as usize + 4;
        let at = |v: f64| {
            let u = u_of_v(v);
            delta0 + u * u
        };
        (0..n)
            .map(|k| at(k as f64 * TABLE_H))
            .chain((0..n - 1).map(|k| at((k as f64 + 0.5) * TABLE_H)))
            .collect()
    }

    /// The table from the loads at [`BranchTable::approaches`] (solved by any backend); `None`
    /// where one is not finite.
    pub fn from_loads(delta0: f64, loads: &[f64]) -> Option<Self> {
        if loads.iter().any(|l| !l.is_finite()) {
            return None;
        }
        let n = loads.len().div_ceil(2);
        let (vals, mids) = loads.split_at(n);
        let mut t = BranchTable {
            delta0,
            coef: spline(vals),
            error: 0.0,
            exact_below: 0.0,
            fold: None,
        };
        let errs: Vec<f64> = mids
            .iter()
            .enumerate()
            .map(|(k, &exact)| {
                let v = (k as f64 + 0.5) * TABLE_H;
                (t.at_v(v) - exact).abs() / exact.abs().max(1.0)
            })
            .collect();
        // The intervals near the fold that miss the target are left to exact solves.
        let bad = (0..errs.len())
            .take_while(|&k| (k as f64) * TABLE_H < EXACT_V_MAX)
            .filter(|&k| errs[k] > TABLE_TARGET)
            .last();
        let first = match bad {
            Some(k) => {
                t.exact_below = (k + 1) as f64 * TABLE_H;
                k + 1
            }
            None => 0,
        };
        t.error = errs[first..].iter().fold(0.0, |a, &b| a.max(b));
        Some(t)
    }

    /// Tabulates the stretch left to exact solves at 16 times the resolution, solving `load`
    /// (exact) at the finer nodes and midpoints: where that table meets the 1e-6 target the
    /// quadrature interpolates it (its error joins [`BranchTable::error`]),
    /// and only the intervals next to the fold that still miss it are solved exactly. One
    /// exact solve costs as much as a hundred interpolations: near lambda_D, where the branch
    /// turns within a tiny range of approaches, those solves were an eighth of a map's time.
    pub fn refine_fold(&mut self, load: impl Fn(f64) -> Option<f64>) {
        if self.exact_below <= 0.0 {
            return;
        }
        let h = TABLE_H / FOLD_REFINE as f64;
        let n = (self.exact_below / TABLE_H).round() as usize * FOLD_REFINE;
        let delta = |v: f64| {
            let u = u_of_v(v);
            self.delta0 + u * u
        };
        let Some(vals) = (0..=n)
            .map(|k| load(delta(k as f64 * h)))
            .collect::<Option<Vec<_>>>()
        else {
            return;
        };
        let coef = spline(&vals);
        let fine = FoldTable {
            inv_h: 1.0 / h,
            end: self.exact_below,
            coef,
        };
        let mut errs = Vec::with_capacity(n);
        for k in 0..n {
            let v = (k as f64 + 0.5) * h;
            let Some(exact) = load(delta(v)) else { return };
            errs.push((fine.at_v(v) - exact).abs() / exact.abs().max(1.0));
        }
        let first = errs
            .iter()
            .rposition(|&e| !(e <= TABLE_TARGET))
            .map_or(0, |k| k + 1);
        if first == n {
            return;
        }
        self.error = errs[first..].iter().fold(self.error, |a, &b| a.max(b));
        self.exact_below = first as f64 * h;
        self.fold = Some(fine);
    }

    /// The cubic's coefficients per interval in `s = v / TABLE_H - k`, lowest first.
    pub(crate) fn coef(&self) -> &[[f64; 4]] {
        &self.coef
    }

    /// The spline at `v` (the last interval's cubic beyond the table).
    #[inline]
    pub(crate) fn at_v(&self, v: f64) -> f64 {
        let x = v * TABLE_INV_H;
        spline_at(&self.coef, x)
    }

    /// The interpolated load; where `v` is below [`BranchTable::exact_below`] the caller solves
    /// exactly instead ([`BranchTable::load_or`]).
    #[inline]
    pub fn load(&self, delta: f64) -> f64 {
        self.load_or(delta, None)
    }

    /// The load: interpolated, or from `exact` in the exactly solved stretch (NaN where that
    /// fails).
    #[inline]
    pub fn load_or(&self, delta: f64, exact: Option<&Summit>) -> f64 {
        let v = v_of_u((delta - self.delta0).max(0.0).sqrt());
        match (exact, &self.fold) {
            (Some(s), _) if v < self.exact_below => s.contact(delta).map_or(f64::NAN, |c| c.0),
            (_, Some(f)) if v < f.end => f.at_v(v),
            _ => self.at_v(v),
        }
    }
}

/// The spline of [`spline`] at `x` in units of its spacing from the first node (the last
/// interval's cubic beyond it).
#[inline(always)]
pub(crate) fn spline_at(coef: &[[f64; 4]], x: f64) -> f64 {
    // The interval's index from x clamped to the last one (a NaN x takes the last one and gives
    // NaN): in range, so the plain conversion needs none of `as`'s saturating checks.
    let last = coef.len() - 1;
    let xk = x.min(last as f64).max(0.0);
    // SAFETY: xk is finite and within 0..=last, which fits usize.
    let k = unsafe { xk.to_int_unchecked::<usize>() };
    let s = x - k as f64;
    // SAFETY: k <= last.
    let c = unsafe { coef.get_unchecked(k) };
    ((c[3] * s + c[2]) * s + c[1]) * s + c[0]
}

/// The not-a-knot cubic spline through `y` at unit spacing, as per-interval coefficients in the
/// local variable `s` in [0, 1]. Not-a-knot at uniform spacing makes the second derivatives `M`
/// linear over the first and last three nodes (`M0 = 2 M1 - M2`), so the first and last
/// equations give `M1` and `M(n-2)` directly and the rest is tridiagonal (Thomas algorithm).
pub(crate) fn spline(y: &[f64]) -> Vec<[f64; 4]> {
    let n = y.len();
    assert!(n >= 5, "a spline table needs at least five nodes");
    // r_i = 6 (y[i-1] - 2 y[i] + y[i+1]) = M[i-1] + 4 M[i] + M[i+1] for 1 <= i <= n-2.
    let r = |i: usize| 6.0 * (y[i - 1] - 2.0 * y[i] + y[i + 1]);
    let mut m = vec![0.0; n];
    m[1] = r(1) / 6.0;
    m[n - 2] = r(n - 2) / 6.0;
    // Rows 2..=n-3: M[i-1] + 4 M[i] + M[i+1] = r(i), with M[1] and M[n-2] known.
    let inner = n.saturating_sub(4);
    if inner > 0 {
        let (mut c, mut d) = (vec![0.0; inner], vec![0.0; inner]);
        for j in 0..inner {
            let i = j + 2;
            let mut rhs = r(i);
            if j == 0 {
                rhs -= m[1];
            }
            if j == inner - 1 {
                rhs -= m[n - 2];
            }
            let (cp, dp) = if j == 0 {
                (0.0, 0.0)
            } else {
                (c[j - 1], d[j - 1])
            };
            let den = 4.0 - cp;
            c[j] = 1.0 / den;
            d[j] = (rhs - dp) / den;
        }
        for j in (0..inner).rev() {
            let next = if j + 1 < inner { m[j + 3] } else { 0.0 };
            m[j + 2] = d[j] - c[j] * next;
        }
    }
    m[0] = 2.0 * m[1] - m[2];
    m[n - 1] = 2.0 * m[n - 2] - m[n - 3];
    (0..n - 1)
        .map(|k| {
            let (y0, y1, m0, m1) = (y[k], y[k + 1], m[k], m[k + 1]);
            [
                y0,
                (y1 - y0) - (2.0 * m0 + m1) / 6.0,
                0.5 * m0,
                (m1 - m0) / 6.0,
            ]
        })
        .collect()
}

/// One summit's load on a branch of a summit model.
#[derive(Clone, Copy, Debug)]
enum Law<'a> {
    /// MD contact branch (table; the summit solves its exactly solved stretch).
    Table(&'a BranchTable, Option<&'a Summit>),
    /// MD non-contact branch: -(pi lambda / 2) C^2, C = C* + sqrt(C*^2 + 2 (delta + h0)).
    NonContact { lambda: f64, h0: f64, c_star: f64 },
    /// Hertz: delta^(3/2).
    Hertz,
    /// DMT in contact: delta^(3/2) - 2.
    DmtContact,
    /// Rigid sphere in contact (Bradley): -2.
    Rigid,
    /// A rigid sphere's Dugdale attraction at a gap: -2 (1 + delta / h0).
    Attract { h0: f64 },
}

impl Law<'_> {
    /// `sum over k of wt[k] * load(delta[k])`, in node order: one loop per law, so that the
    /// law's match and constants stay out of the node loop.
    #[inline(always)]
    fn weighted_sum<const FUSED: bool>(self, wt: &[f64; GL_N], delta: &[f64; GL_N]) -> f64 {
        #[inline(always)]
        fn sum(wt: &[f64; GL_N], delta: &[f64; GL_N], f: impl Fn(f64) -> f64) -> f64 {
            let mut s = 0.0;
            for k in 0..GL_N {
                s += wt[k] * f(delta[k]);
            }
            s
        }
        match self {
            Law::Table(t, Some(s)) if t.exact_below > 0.0 || t.fold.is_some() => {
                sum(wt, delta, |x| t.load_or(x, Some(s)))
            }
            Law::Table(t, _) => {
                // The graded variable of every node first (square roots and a division, which
                // vectorise), then the spline.
                // Then each node's interval and local variable (a vector conversion), and the
                // cubics apart from the sum, so that no chain of one node waits on another's;
                // fused multiply-adds (compiled for FMA, see `Quad::retract`) shorten the
                // Horner chain and differ from `spline_at` by rounding only.
                debug_assert!(!t.coef.is_empty() && t.coef.len() < u32::MAX as usize);
                let last = (t.coef.len() - 1) as f64;
                let (mut at, mut s) = ([0u32; GL_N], [0.0; GL_N]);
                for k in 0..GL_N {
                    let x = v_of_u((delta[k] - t.delta0).max(0.0).sqrt()) * TABLE_INV_H;
                    let xk = x.min(last).max(0.0);
                    // SAFETY: xk is finite and within 0..=last, far below u32::MAX.
                    at[k] = unsafe { xk.to_int_unchecked::<u32>() };
                    s[k] = x - at[k] as f64;
                }
                let mut f = [0.0; GL_N];
                for k in 0..GL_N {
                    // SAFETY: at[k] <= last.
                    let c = unsafe { t.coef.get_unchecked(at[k] as usize) };
                    let m = |a, b| madd::<FUSED>(a, s[k], b);
                    f[k] = m(m(m(c[3], c[2]), c[1]), c[0]);
                }
                sum(wt, &f, |f| f)
            }
            Law::NonContact { lambda, h0, c_star } => {
                let f = PI * lambda / 2.0;
                sum(wt, delta, |x| {
                    let c = c_star + (c_star * c_star + 2.0 * (x + h0)).max(0.0).sqrt();
                    -f * c * c
                })
            }
            Law::Hertz => sum(wt, delta, |x| {
                let x = x.max(0.0);
                x * x.sqrt()
            }),
            Law::DmtContact => sum(wt, delta, |x| {
                let x = x.max(0.0);
                x * x.sqrt() - 2.0
            }),
            Law::Rigid => sum(wt, delta, |_| -2.0),
            Law::Attract { h0 } => sum(wt, delta, |x| -2.0 * (1.0 + x / h0)),
        }
    }
}

/// A summit model on the retract: the summits that touched (`delta_max >= touched_from`) follow
/// `touched`, those that only reached `reached_from` follow `reached`; each a list of
/// `(delta_lo, delta_hi, law)` (zero elsewhere; a fold's square root sits at a `delta_lo`).
struct Model<'a> {
    touched_from: f64,
    touched: Vec<(f64, f64, Law<'a>)>,
    reached_from: f64,
    reached: Vec<(f64, f64, Law<'a>)>,
}

/// `a b + c`, fused into one rounding where `FUSED` (the quadrature's node loops on CPUs with
/// FMA, where the multiply-add chains' latency bounds the loops), else two; the two differ by
/// rounding only (about 1e-16 relative).
#[inline(always)]
fn madd<const FUSED: bool>(a: f64, b: f64, c: f64) -> f64 {
    if FUSED {
        a.mul_add(b, c)
    } else {
        a * b + c
    }
}

/// Entries of [`ExpTable`].
const EXP_N: usize = 64;

/// `2^(j / EXP_N)` for `j < EXP_N`: the table of [`exp_nonpositive`].
struct ExpTable([f64; EXP_N]);

impl ExpTable {
    fn new() -> ExpTable {
        ExpTable(std::array::from_fn(|j| (j as f64 / EXP_N as f64).exp2()))
    }
}

/// `exp(x)` for `x <= 0` (the Gaussian at the quadrature's nodes) within about 1.5 ulp of
/// `f64::exp`, written without calls or branches so that a loop of them vectorises:
/// `x = (k / 64) ln2 + r` with `|r| <= ln2 / 128` (ln2 in two parts, the first with trailing
/// zeros so that `k ln2_hi / 64` is exact), `exp(r)` by its Taylor series to `r^5` (the rest
/// below 4e-17), `2^(k / 64)` from the table times a power of two put into the exponent's
/// bits. Below -708 (where that power leaves the normal range) it returns `exp(-708)`.
#[inline(always)]
fn exp_nonpositive<const FUSED: bool>(x: f64, table: &ExpTable) -> f64 {
    const LN2_HI: f64 = 0.693_147_180_369_123_8 / EXP_N as f64;
    const LN2_LO: f64 = 1.908_214_929_270_587_7e-10 / EXP_N as f64;
    // 1.5 * 2^52: adding it rounds to an integer, which is left in the low bits.
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    // k + 1023 * 64 >= 0 for x >= -708: logical shifts give 2^(k / 64)'s parts.
    const BIAS: u64 = 1023 * EXP_N as u64;
    let x = x.max(-708.0);
    let z = x * (EXP_N as f64 * std::f64::consts::LOG2_E) + SHIFT;
    let kf = z - SHIFT;
    let kb = z.to_bits().wrapping_sub(SHIFT.to_bits()).wrapping_add(BIAS);
    let m = madd::<FUSED>;
    let r = m(-kf, LN2_LO, m(-kf, LN2_HI, x));
    let p = m(
        m(
            m(m(m(r, 1.0 / 120.0, 1.0 / 24.0), r, 1.0 / 6.0), r, 0.5),
            r,
            1.0,
        ),
        r,
        1.0,
    );
    let two_m = f64::from_bits((kb / EXP_N as u64) << 52);
    table.0[(kb % EXP_N as u64) as usize] * two_m * p
}

/// `G(h) = integral over [h, Z_MAP] of phi(t) (t - h)^(3/2) dt`, the Gaussian moment behind
/// every Hertzian summit population (Greenwood and Williamson's F_3/2, truncated where the map
/// truncates): a not-a-knot spline on a uniform grid of h, its nodes computed with t = h + u^2
/// (which leaves the smooth integrand 2 u^4 phi(h + u^2)) by composite Gauss-Legendre. G is
/// smooth in h (G(-7) = 18.6 at most), and the table is within 1e-12 of G at every midpoint
/// (the tests; 4e-12 with half the nodes).
struct HertzTail {
    coef: Vec<[f64; 4]>,
}

/// Nodes of [`HertzTail`] per unit of h.
const HERTZ_TAIL_PER_UNIT: f64 = 256.0;

impl HertzTail {
    fn new(nodes: &[(f64, f64)]) -> HertzTail {
        let n = (2.0 * Z_MAP * HERTZ_TAIL_PER_UNIT) as usize + 1;
        let y: Vec<f64> = (0..n)
            .map(|k| Self::exact(nodes, -Z_MAP + k as f64 / HERTZ_TAIL_PER_UNIT))
            .collect();
        HertzTail { coef: spline(&y) }
    }

    /// G(h) by quadrature: eight pieces of 20 Gauss-Legendre nodes in u = sqrt(t - h).
    fn exact(nodes: &[(f64, f64)], h: f64) -> f64 {
        let u_max = (Z_MAP - h).max(0.0).sqrt();
        let w = u_max / 8.0;
        let mut total = 0.0;
        for p in 0..8 {
            for &(x, wx) in nodes {
                let u = w * (p as f64 + x);
                let t = h + u * u;
                total += wx * w * 2.0 * u.powi(4) * (-0.5 * t * t).exp();
            }
        }
        total / (2.0 * PI).sqrt()
    }

    /// G(h) for `-Z_MAP <= h`: interpolated (zero from `Z_MAP` up).
    #[inline]
    fn at(&self, h: f64) -> f64 {
        if h >= Z_MAP {
            return 0.0;
        }
        let x = (h + Z_MAP) * HERTZ_TAIL_PER_UNIT;
        spline_at(&self.coef, x)
    }
}

struct Quad {
    nodes: [(f64, f64); GL_N],
    hertz: HertzTail,
    /// The CPU has AVX2 and FMA: the node loops run four wide, their multiply-adds fused. An
    /// x86-64 CPU without them rounds each product and sum apart (the same results to about
    /// 1e-16 relative); other architectures fuse.
    avx2: bool,
    exp: ExpTable,
}

impl Quad {
    fn new() -> Quad {
        let mut nodes = [(0.0, 0.0); GL_N];
        nodes.copy_from_slice(&gauss_legendre(GL_N, Order::FromZero));
        #[cfg(target_arch = "x86_64")]
        let avx2 = std::arch::is_x86_feature_detected!("avx2")
            && std::arch::is_x86_feature_detected!("fma");
        #[cfg(not(target_arch = "x86_64"))]
        let avx2 = false;
        Quad {
            hertz: HertzTail::new(&nodes),
            nodes,
            avx2,
            exp: ExpTable::new(),
        }
    }

    /// The mean retract load per summit at separation `d` after pressing to `d_min`.
    fn retract(&self, m: &Model, sigma: f64, d_min: f64, d: f64) -> f64 {
        #[cfg(target_arch = "x86_64")]
        {
            if self.avx2 {
                // SAFETY: the CPU has AVX2 and FMA (checked in `Quad::new`).
                return unsafe { self.retract_avx2(m, sigma, d_min, d) };
            }
            // Without FMA a fused multiply-add is a slow library call: two roundings instead.
            self.retract_any::<false>(m, sigma, d_min, d)
        }
        #[cfg(not(target_arch = "x86_64"))]
        self.retract_any::<true>(m, sigma, d_min, d)
    }

    /// [`Quad::retract`] compiled for AVX2 and FMA.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn retract_avx2(&self, m: &Model, sigma: f64, d_min: f64, d: f64) -> f64 {
        self.retract_any::<true>(m, sigma, d_min, d)
    }

    /// Integral of phi(t) law(sigma t - d) over [t0, t1]; with `fold` the substitution
    /// t = t0 + (t1 - t0) s^2 takes out a square root at t0.
    #[inline(always)]
    fn piece<const FUSED: bool>(
        &self,
        law: Law,
        sigma: f64,
        d: f64,
        t0: f64,
        t1: f64,
        fold: bool,
    ) -> f64 {
        let w = t1 - t0;
        // Node by node in separate loops without calls, which the compiler vectorises.
        let (mut t, mut jac) = ([0.0; GL_N], [0.0; GL_N]);
        if fold {
            for k in 0..GL_N {
                let s = self.nodes[k].0;
                (t[k], jac[k]) = (t0 + w * s * s, 2.0 * w * s);
            }
        } else {
            for k in 0..GL_N {
                (t[k], jac[k]) = (t0 + w * self.nodes[k].0, w);
            }
        }
        let (mut wt, mut delta) = ([0.0; GL_N], [0.0; GL_N]);
        for k in 0..GL_N {
            wt[k] =
                self.nodes[k].1 * jac[k] * exp_nonpositive::<FUSED>(-0.5 * t[k] * t[k], &self.exp);
            delta[k] = sigma * t[k] - d;
        }
        law.weighted_sum::<FUSED>(&wt, &delta) / (2.0 * PI).sqrt()
    }

    /// The mean load of the summits from height `h` (sigma) up, all in contact, where the law
    /// is Hertz's, DMT's or the rigid summits': closed forms in the tail mass and `G(h)`.
    #[inline(always)]
    fn moment(&self, law: Law, sigma: f64, h: f64) -> Option<f64> {
        let mass = || super::upper_tail(h) - super::upper_tail(Z_MAP);
        let hertz = || sigma * sigma.sqrt() * self.hertz.at(h);
        match law {
            Law::Hertz => Some(hertz()),
            Law::DmtContact => Some(hertz() - 2.0 * mass()),
            Law::Rigid => Some(-2.0 * mass()),
            _ => None,
        }
    }

    /// [`Quad::retract`] for any CPU.
    #[inline(always)]
    fn retract_any<const FUSED: bool>(&self, m: &Model, sigma: f64, d_min: f64, d: f64) -> f64 {
        let mut total = 0.0;
        // Heights (in sigma) of each history class.
        let t_touch = (d_min + m.touched_from) / sigma;
        let t_reach = (d_min + m.reached_from) / sigma;
        let classes = [
            (t_touch, Z_MAP, &m.touched),
            (t_reach, t_touch.min(Z_MAP), &m.reached),
        ];
        for (lo, hi, segs) in classes {
            for &(dl, dh, law) in segs.iter() {
                let s0 = (d + dl) / sigma;
                let a = s0.max(lo).max(-Z_MAP);
                let b = ((d + dh) / sigma).min(hi);
                if !(b > a) {
                    continue;
                }
                // The Hertzian and rigid laws over the whole population in contact (from the
                // summits just touching up to the truncation) are Gaussian moments in closed
                // form: sigma^(3/2) G(h) and the tail mass, no nodes.
                if dl == 0.0 && a == s0 && b == Z_MAP {
                    if let Some(v) = self.moment(law, sigma, a) {
                        total += v;
                        continue;
                    }
                }
                // Mostly one piece: no divisions then (the same numbers as with them).
                let (pieces, w) = if b - a <= PIECE {
                    (1, b - a)
                } else {
                    let n = ((b - a) / PIECE).ceil();
                    (n as usize, (b - a) / n)
                };
                for k in 0..pieces {
                    let t0 = a + w * k as f64;
                    let fold = k == 0 && a == s0;
                    total += self.piece::<FUSED>(law, sigma, d, t0, t0 + w, fold);
                }
            }
        }
        total
    }
}

/// The summit models of one lambda, in the order tried, and exact MD last.
struct Models<'a> {
    list: [Model<'a>; 5],
}

/// JKR's stable branch under grips (lambda-independent), from its closed forms.
pub fn jkr_table(delta_hi: f64) -> BranchTable {
    let a_out = 6f64.powf(-1.0 / 3.0);
    let d_out = jkr_approach(a_out);
    let load = |delta: f64| {
        // jkr_approach rises with A above a_out: bisection then a Newton polish.
        let (mut lo, mut hi) = (a_out, 2.0 + delta.max(0.0).sqrt() * 1.5);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if jkr_approach(mid) < delta {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo <= 1e-15 * hi {
                break;
            }
        }
        Some(jkr_load(0.5 * (lo + hi)))
    };
    BranchTable::new(d_out, delta_hi, load).expect("closed forms do not fail")
}

fn models<'a>(s: &'a Summit, md: &'a BranchTable, jkr: &'a BranchTable) -> Models<'a> {
    let inf = f64::INFINITY;
    let h0 = s.h0;
    let nc = Law::NonContact {
        lambda: s.lambda,
        h0,
        c_star: s.c_star,
    };
    // The quadrature's pieces must not straddle the kink where the non-contact branch's C
    // reaches the contact branch's A -> 0 end.
    let contact = vec![(s.delta_out, inf, Law::Table(md, Some(s)))];
    let nc_kink = 0.5 * ((s.c_end - s.c_star).powi(2) - s.c_star * s.c_star) - h0;
    let split = |lo: f64, hi: f64| {
        if lo < nc_kink && nc_kink < hi {
            vec![(lo, nc_kink, nc), (nc_kink, hi, nc)]
        } else {
            vec![(lo, hi, nc)]
        }
    };
    let md_model = match s.delta_nc {
        Some(lo) => Model {
            touched_from: s.delta_in,
            touched: [contact, split(lo, s.delta_out)].concat(),
            reached_from: -h0,
            reached: split(lo, inf),
        },
        None => Model {
            touched_from: s.delta_in,
            touched: contact,
            reached_from: s.delta_in,
            reached: vec![],
        },
    };
    let attract = Law::Attract { h0 };
    let none = || (inf, vec![]);
    let plain = |segs: Vec<(f64, f64, Law<'a>)>, from: f64| {
        let (reached_from, reached) = none();
        Model {
            touched_from: from,
            touched: segs,
            reached_from,
            reached,
        }
    };
    Models {
        list: [
            plain(vec![(0.0, inf, Law::Hertz)], 0.0),
            plain(vec![(-h0, 0.0, attract), (0.0, inf, Law::Rigid)], -h0),
            plain(vec![(-h0, 0.0, attract), (0.0, inf, Law::DmtContact)], -h0),
            plain(
                vec![(
                    jkr_approach(6f64.powf(-1.0 / 3.0)),
                    inf,
                    Law::Table(jkr, None),
                )],
                0.0,
            ),
            md_model,
        ],
    }
}

/// The pull-off and retract curve of one model at one roughness.
struct Retract {
    /// Loads at the sample separations.
    curve: Vec<f64>,
    pulloff: f64,
    separation: f64,
}

fn retract(q: &Quad, m: &Model, sigma: f64, d_min: f64, seps: &[f64], refine: bool) -> Retract {
    let curve: Vec<f64> = seps
        .iter()
        .map(|&d| q.retract(m, sigma, d_min, d))
        .collect();
    refined(q, m, sigma, d_min, seps, curve, refine)
}

/// The samples in the order a simpler model's curve is compared with MD's: MD's pull-off
/// sample, the deepest press, then the rest; a model fails at its first sample off by more
/// than the tolerance, mostly one of the first two.
fn sample_order(md: &[f64]) -> Vec<usize> {
    let i = (0..md.len())
        .min_by(|&a, &b| md[a].total_cmp(&md[b]))
        .unwrap_or(0);
    let mut order = vec![i];
    order.extend((0..md.len()).filter(|&k| k != i));
    order
}

/// A model's curve at the samples, or, at its first sample further than `limit` from MD's,
/// the largest difference seen so far (a lower bound of the curve's error).
fn curve_within(
    q: &Quad,
    m: &Model,
    (sigma, d_min): (f64, f64),
    seps: &[f64],
    md: &[f64],
    order: &[usize],
    limit: f64,
) -> Result<Vec<f64>, f64> {
    let mut curve = vec![0.0; seps.len()];
    let mut worst = 0.0f64;
    for &k in order {
        curve[k] = q.retract(m, sigma, d_min, seps[k]);
        let e = (curve[k] - md[k]).abs();
        // NaN compares false: a failed sample is not a pass.
        if !(e <= limit) {
            return Err(worst.max(e));
        }
        worst = worst.max(e);
    }
    Ok(curve)
}

/// The pull-off from the sampled curve: the smallest sample, refined between its neighbours.
fn refined(
    q: &Quad,
    m: &Model,
    sigma: f64,
    d_min: f64,
    seps: &[f64],
    curve: Vec<f64>,
    refine: bool,
) -> Retract {
    let load = |d: f64| q.retract(m, sigma, d_min, d);
    let i = (0..curve.len())
        .min_by(|&a, &b| curve[a].total_cmp(&curve[b]))
        .unwrap_or(0);
    let (mut best_d, mut best) = (seps[i], curve[i]);
    // Every sample compressive and the last, where the summits come free, the smallest: the load
    // falls to zero from above and there is no tensile minimum; Brent would only walk to the
    // end of the bracket (about 28 loads, a fifth of the map's points at large sigma).
    let falling_to_free = i + 1 == seps.len() && best > 0.0;
    if refine && !falling_to_free {
        let (lo, hi) = (i.saturating_sub(1), (i + 1).min(seps.len() - 1));
        let (a, b) = (seps[lo], seps[hi]);
        // The pull-off is the value at a smooth minimum (smooth on the scale sigma, the
        // Gaussian's width): an abscissa to 1e-6 sigma gives it to about 1e-12. Where the
        // smallest sample lies inside, Brent starts from it and its neighbours.
        let tol = 1e-6 * sigma.min((b - a).abs());
        let start =
            (lo < i && i < hi).then(|| [(seps[i], curve[i]), (a, curve[lo]), (b, curve[hi])]);
        let (x, f) = brent_min(&load, a, b, start, tol);
        if f < best {
            (best_d, best) = (x, f);
        }
    }
    Retract {
        curve,
        // No tensile load at all: the pull-off is zero (NaN stays NaN: a failed solve).
        pulloff: if best > 0.0 { 0.0 } else { best },
        separation: best_d,
    }
}

/// The minimum of `f` on [a, b]: Brent's method (golden section with parabolic steps), to
/// `abs_tol` in the abscissa; it stops without Brent's closing probes where a parabola through
/// close points puts the minimum within the tolerance. `start`, where given, is three known points: the best inside
/// the bracket, and the bracket's ends; the first step is then the parabola through them.
fn brent_min(
    f: &dyn Fn(f64) -> f64,
    a: f64,
    b: f64,
    start: Option<[(f64, f64); 3]>,
    abs_tol: f64,
) -> (f64, f64) {
    const C: f64 = 0.381_966_011_250_105_1;
    let (mut a, mut b) = (a.min(b), a.max(b));
    let (mut x, mut fx, mut w, mut fw, mut v, mut fv, mut e) = match start {
        Some([(x, fx), p, q]) => {
            let (w, v) = if p.1 <= q.1 { (p, q) } else { (q, p) };
            // e as if the last steps had been as wide as the bracket: a parabolic step may
            // come first.
            (x, fx, w.0, w.1, v.0, v.1, b - a)
        }
        None => {
            let x = a + C * (b - a);
            let fx = f(x);
            (x, fx, x, fx, x, fx, 0.0)
        }
    };
    // The step before: as wide as the bracket where a start was given, so that parabolic
    // steps may follow one another from the first.
    let mut d: f64 = if start.is_some() { b - a } else { 0.0 };
    for _ in 0..100 {
        let m = 0.5 * (a + b);
        let tol1 = 1e-10 * x.abs() + abs_tol;
        let tol2 = 2.0 * tol1;
        if (x - m).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol1 {
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            let e_old = e;
            e = d;
            if p.abs() < (0.5 * q * e_old).abs() && p > q * (a - x) && p < q * (b - x) {
                d = p / q;
                // The vertex of a parabola through points within 1e3 tol1 of x lies within tol1
                // of x: x is the minimum to about tol1 (parabolas converge superlinearly on a
                // smooth minimum), and the closing probes at x +- tol1, two loads, are skipped.
                if d.abs() < tol1 && (x - w).abs().max((x - v).abs()) < 1e3 * tol1 {
                    break;
                }
                let u = x + d;
                if u - a < tol2 || b - u < tol2 {
                    d = if m >= x { tol1 } else { -tol1 };
                }
                golden = false;
            }
        }
        if golden {
            e = if x >= m { a - x } else { b - x };
            d = C * e;
        }
        let u = if d.abs() >= tol1 {
            x + d
        } else {
            x + tol1.copysign(d)
        };
        let fu = f(u);
        if fu <= fx {
            if u >= x {
                a = x;
            } else {
                b = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    (x, fx)
}

/// The result of the map.
#[derive(Clone, Debug)]
pub struct RoughMap {
    /// What was computed.
    pub spec: RoughMapSpec,
    /// The lambda axis.
    pub lambdas: Vec<f64>,
    /// The sigma axis.
    pub sigmas: Vec<f64>,
    /// Per column: the smooth summit's pull-off (Pbar_c) and the table's interpolation error.
    pub smooth_pulloff: Vec<f64>,
    /// Per column: the table's interpolation error (relative to max(1, |load|)).
    pub table_error: Vec<f64>,
    /// Per point (row-major, row = sigma): pull-off per summit, its separation, relative to the
    /// smooth summit's, the region, and each simpler model's error (the larger of its pull-off
    /// and curve errors; Hertz, Bradley, DMT, JKR). The models are tried in that order and
    /// stop at the first adequate one (NaN after it); a model is rejected at its first sample
    /// beyond the tolerance (Hertz on its pull-off alone where that misses), so a rejected
    /// model's error is a lower bound, above the tolerance.
    pub pulloff: Vec<f64>,
    /// Per point: the separation of the pull-off.
    pub pulloff_separation: Vec<f64>,
    /// Per point: the pull-off over the smooth summit's.
    pub relative_pulloff: Vec<f64>,
    /// Per point: the simplest adequate summit model.
    pub regions: Vec<Region>,
    /// Per point: the errors of Hertz, Bradley, DMT and JKR.
    pub model_error: Vec<[f64; 4]>,
    /// The map's pull-offs against the adaptive quadrature of `tabor rough` at sample points.
    pub check: Check,
    /// Which backend solved the tables (`cpu f64`, `gpu f32`, `gpu f64`).
    pub table_backend: String,
    /// A GPU's table states against the CPU f64 solver on a sample (None on the CPU).
    pub table_check: Option<CheckReport>,
    /// Seconds the map took.
    pub seconds: f64,
}

/// The map's pull-off loads recomputed at sample points by [`Rough::mean`] (tanh-sinh, exact
/// solver at every node) at the separation the map found.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Check {
    /// Points checked.
    pub points: usize,
    /// Largest |map - exact| / max(|exact|, 1e-3 |Pbar_c|).
    pub max_relative_difference: f64,
}

/// The models tried, in order; region codes as in [`crate::map::Region`].
pub const MODEL_REGIONS: [Region; 4] = [Region::Hertz, Region::Rigid, Region::Dmt, Region::Jkr];

/// The most points of a map re-solved exactly to check it (each is a summit ensemble's
/// pull-off search).
pub const MAX_CHECK: usize = 100_000;

/// The number of points to re-solve, checked (at most [`MAX_CHECK`]).
pub fn check_checks(checks: usize) -> Result<(), RoughError> {
    if checks > MAX_CHECK {
        return Err(RoughError::Scene(Message::new().key("check").text(
            format!(" {checks}: give at most {MAX_CHECK} points to re-solve"),
        )));
    }
    Ok(())
}

/// Computes the map on all cores: per lambda one table, then every sigma.
pub fn compute(spec: &RoughMapSpec, checks: usize) -> Result<RoughMap, RoughError> {
    compute_with(spec, checks, &Engine::Cpu)
}

/// States of the tables solved on a GPU at once, at most (a chunk of columns).
const GPU_TABLE_CHUNK: usize = 1 << 20;
/// Table states of a GPU map re-solved by the CPU f64 solver for its cross-check.
const GPU_TABLE_CHECKS: usize = 1000;

/// The summits' contact-branch tables: on the CPU by the exact solver, summit by summit; on a
/// GPU every column's nodes and midpoints at once in chunks (the f32 kernels, refined in f64
/// with `Precision::F64`), with a sample re-solved by the CPU f64 solver.
fn tables(
    summits: &[Summit],
    delta_hi: f64,
    engine: &Engine,
) -> Result<(Vec<BranchTable>, Option<CheckReport>), RoughError> {
    let failed = |s: &Summit| RoughError::Failed(f64::NAN, s.lambda);
    if matches!(engine, Engine::Cpu) {
        let t = summits
            .par_iter()
            .map(|s| {
                crate::interrupt::checkpoint();
                BranchTable::new(s.delta_out, delta_hi, |d| s.contact(d).map(|c| c.0))
                    .ok_or_else(|| failed(s))
            })
            .collect::<Result<_, _>>()?;
        return Ok((t, None));
    }
    let per: Vec<Vec<f64>> = summits
        .iter()
        .map(|s| BranchTable::approaches(s.delta_out, delta_hi))
        .collect();
    let total: usize = per.iter().map(Vec::len).sum();
    let every = (total / GPU_TABLE_CHECKS).max(1);
    let mut check = CheckReport::empty(crate::engine::GPU_TOLERANCE);
    let mut out = Vec::with_capacity(summits.len());
    let mut first = 0;
    while first < summits.len() {
        let (mut last, mut len) = (first, 0);
        while last < summits.len() && (last == first || len + per[last].len() <= GPU_TABLE_CHUNK) {
            len += per[last].len();
            last += 1;
        }
        let points: Vec<(f64, f64)> = (first..last)
            .flat_map(|i| per[i].iter().map(move |&d| (summits[i].lambda, d)))
            .collect();
        let states = engine
            .solve_points(&points, Control::Displacement)
            .map_err(|e| RoughError::Scene(e.to_string().into()))?;
        let sample: Vec<usize> = (0..points.len()).step_by(every).collect();
        check.merge(crate::engine::cross_check(
            &sample.iter().map(|&i| points[i]).collect::<Vec<_>>(),
            &sample.iter().map(|&i| states[i]).collect::<Vec<_>>(),
            Control::Displacement,
            sample.len(),
            crate::engine::GPU_TOLERANCE,
        ));
        let mut at = 0;
        for i in first..last {
            let loads: Vec<f64> = states[at..at + per[i].len()]
                .iter()
                .map(|st| {
                    if st.status == Status::Ok {
                        st.load
                    } else {
                        f64::NAN
                    }
                })
                .collect();
            at += per[i].len();
            let s = &summits[i];
            out.push(BranchTable::from_loads(s.delta_out, &loads).ok_or_else(|| failed(s))?);
        }
        first = last;
    }
    Ok((out, Some(check)))
}

/// As [`compute`], the summits' tables solved on `engine` (a GPU's states are cross-checked
/// against the CPU f64 solver on a sample: [`RoughMap::table_check`]).
pub fn compute_with(
    spec: &RoughMapSpec,
    checks: usize,
    engine: &Engine,
) -> Result<RoughMap, RoughError> {
    spec.validate()?;
    check_checks(checks)?;
    let t0 = std::time::Instant::now();
    let (nx, ny) = (spec.nx, spec.ny);
    let lambdas = crate::numeric::grid::axis(spec.lambda_min, spec.lambda_max, nx, true);
    let sigmas = crate::numeric::grid::axis(spec.sigma_min, spec.sigma_max, ny, true);
    let p = spec.press_sigmas;
    // The approaches the quadrature reaches: heights up to Z_MAP sigma above separations down
    // to -press sigma.
    let delta_hi = (Z_MAP + p.max(0.0)) * spec.sigma_max + 1.0;
    let jkr = jkr_table(delta_hi);
    let quad = Quad::new();
    let summits: Vec<Summit> = lambdas
        .par_iter()
        .map(|&l| Summit::new(l))
        .collect::<Result<_, _>>()?;
    let (mut tables, table_check) = tables(&summits, delta_hi, engine)?;
    // The stretches next to the fold that the tables miss the target in, finer (exact f64
    // solves on the CPU, whatever the backend: a few columns near lambda_D).
    tables
        .par_iter_mut()
        .zip(&summits)
        .for_each(|(t, s)| t.refine_fold(|d| s.contact(d).map(|c| c.0)));
    type Column = (f64, f64, Vec<(f64, f64, Region, [f64; 4])>);
    let columns: Vec<Column> = summits
        .par_iter()
        .zip(&tables)
        .map(|(s, table)| -> Result<Column, RoughError> {
            let smooth = s.ctx.load_pulloff.load;
            let ms = models(s, table, &jkr);
            let reach = [s.h0, -s.delta_out, -s.delta_nc.unwrap_or(0.0)]
                .into_iter()
                .fold(0.0, f64::max);
            let col = sigmas
                .par_iter()
                .map(|&sigma| point(&quad, &ms, smooth, reach, sigma, spec))
                .collect();
            Ok((smooth, table.error.max(jkr.error), col))
        })
        .collect::<Result<_, _>>()?;
    let n = nx * ny;
    let mut m = RoughMap {
        spec: spec.clone(),
        smooth_pulloff: columns.iter().map(|c| c.0).collect(),
        table_error: columns.iter().map(|c| c.1).collect(),
        pulloff: vec![0.0; n],
        pulloff_separation: vec![0.0; n],
        relative_pulloff: vec![0.0; n],
        regions: vec![Region::Failed; n],
        model_error: vec![[f64::NAN; 4]; n],
        lambdas,
        sigmas,
        check: Check::default(),
        table_backend: format!("{} {}", engine.name(), engine.precision()),
        table_check,
        seconds: 0.0,
    };
    for (ix, (smooth, _, col)) in columns.iter().enumerate() {
        for (iy, &(pc, sep, region, errs)) in col.iter().enumerate() {
            let i = iy * nx + ix;
            m.pulloff[i] = pc;
            m.pulloff_separation[i] = sep;
            m.relative_pulloff[i] = (pc / smooth).abs();
            // A failed exact solve in the fold's stretch leaves NaN: no number, no region.
            m.regions[i] = if pc.is_finite() {
                region
            } else {
                Region::Failed
            };
            m.model_error[i] = errs;
        }
    }
    m.check = check(&m, checks)?;
    m.seconds = t0.elapsed().as_secs_f64();
    Ok(m)
}

/// Separations, half a sigma apart, within `JUMP_WINDOW` sigma of where either model's
/// touched summits jump out (a contact branch ending at `delta_lo`: the summits at height
/// `d + delta_lo` leave it, so the load steps there, smoothed by the Gaussian over a few sigma).
/// None where the uniform samples are already that dense.
fn jump_windows<'m>(
    md: &'m Model,
    m: &'m Model,
    sigma: f64,
    (d_min, d_max): (f64, f64),
    seps: &[f64],
) -> impl Iterator<Item = f64> + 'm {
    let spacing = seps.get(1).map_or(0.0, |s1| s1 - seps[0]);
    let dense = spacing <= 0.5 * sigma;
    let steps = (2.0 * JUMP_WINDOW) as i32;
    [md, m]
        .into_iter()
        .flat_map(|model| model.touched.iter())
        .filter(move |(lo, _, law)| !dense && lo.is_finite() && matches!(law, Law::Table(..)))
        .flat_map(move |&(lo, _, _)| {
            (-steps..=steps)
                .map(move |i| -lo + 0.5 * sigma * f64::from(i))
                .filter(move |&d| d_min <= d && d <= d_max)
        })
}

/// One point of the map: the exact summits' pull-off and its separation, the region (the first
/// simpler model within the tolerance, else MD) and each model's error (NaN after the adequate
/// one; a lower bound for a rejected model).
fn point(
    quad: &Quad,
    ms: &Models,
    smooth: f64,
    reach: f64,
    sigma: f64,
    spec: &RoughMapSpec,
) -> (f64, f64, Region, [f64; 4]) {
    crate::interrupt::checkpoint();
    let d_min = -spec.press_sigmas * sigma;
    let d_max = 6.0 * sigma + reach;
    let seps: Vec<f64> = (0..CURVE_SAMPLES)
        .map(|k| d_min + (d_max - d_min) * k as f64 / (CURVE_SAMPLES - 1) as f64)
        .collect();
    let md = retract(quad, &ms.list[4], sigma, d_min, &seps, true);
    // The largest |load| of MD's curve, its pull-off included (a sample may miss a narrow dip).
    let scale = md
        .curve
        .iter()
        .fold(md.pulloff.abs(), |m, v| m.max(v.abs()));
    let scale = scale.max(f64::MIN_POSITIVE);
    let order = sample_order(&md.curve);
    let mut errs = [f64::NAN; 4];
    for (k, m) in ms.list[..4].iter().enumerate() {
        // Hertz's pull-off is zero: where that alone misses, its curve is not needed.
        let hertz_miss = md.pulloff.abs() / smooth.abs();
        if k == 0 && hertz_miss > spec.tolerance {
            errs[k] = hertz_miss;
            continue;
        }
        let limit = spec.tolerance * scale;
        let curve = match curve_within(quad, m, (sigma, d_min), &seps, &md.curve, &order, limit) {
            Ok(c) => c,
            Err(worst) => {
                errs[k] = worst / scale;
                continue;
            }
        };
        let curve_err = curve
            .iter()
            .zip(&md.curve)
            .fold(0.0f64, |e, (a, b)| e.max((a - b).abs()))
            / scale;
        // The pull-off is refined only where the curve passes (Hertz's is zero, no refinement
        // needed).
        let r = refined(quad, m, sigma, d_min, &seps, curve, k > 0);
        let pull_err = (r.pulloff - md.pulloff).abs() / smooth.abs();
        // The curves also where they rise steeply: at small sigma a summit model's retract
        // rises within a few sigma of its summits' jump-out (`d = -delta_out`, away from the
        // pull-off), a stretch the uniform samples hit or miss as lambda moves their grid
        // (which drew the MD/JKR border as one-pixel spikes). There both curves are sampled at
        // half a sigma, on which scale they are smooth.
        let across = jump_windows(&ms.list[4], m, sigma, (d_min, d_max), &seps)
            .map(|d| {
                (quad.retract(m, sigma, d_min, d) - quad.retract(&ms.list[4], sigma, d_min, d))
                    .abs()
            })
            .fold(0.0f64, f64::max)
            / scale;
        errs[k] = curve_err.max(pull_err).max(across);
        if errs[k] <= spec.tolerance {
            return (md.pulloff, md.separation, MODEL_REGIONS[k], errs);
        }
    }
    (md.pulloff, md.separation, Region::Md, errs)
}

/// Recomputes the load at the map's pull-off separation at `count` evenly spread points with
/// the adaptive quadrature and exact solves of `tabor rough`.
fn check(m: &RoughMap, count: usize) -> Result<Check, RoughError> {
    let n = m.pulloff.len();
    let count = count.min(n);
    let worst = (0..count)
        .into_par_iter()
        .map(|k| -> Result<f64, RoughError> {
            let i = ((2 * k + 1) * n / (2 * count)).min(n - 1);
            let (ix, iy) = (i % m.spec.nx, i / m.spec.nx);
            let sigma = m.sigmas[iy];
            let r = Rough::new(m.lambdas[ix], sigma)?;
            let d_min = -m.spec.press_sigmas * sigma;
            let exact = r
                .mean(Leg::Retract { d_min }, m.pulloff_separation[i])?
                .load
                .min(0.0);
            let floor = 1e-3 * m.smooth_pulloff[ix].abs();
            Ok((m.pulloff[i] - exact).abs() / exact.abs().max(floor))
        })
        .collect::<Result<Vec<f64>, _>>()?
        .into_iter()
        .fold(0.0, f64::max);
    Ok(Check {
        points: count,
        max_relative_difference: worst,
    })
}

impl RoughMap {
    /// How many points each region holds (the regions present).
    pub fn region_counts(&self) -> Vec<(Region, usize)> {
        Region::ALL
            .iter()
            .map(|&r| (r, self.regions.iter().filter(|&&x| x == r).count()))
            .filter(|&(_, n)| n > 0)
            .collect()
    }

    /// The largest table error over the columns.
    pub fn table_error_max(&self) -> f64 {
        self.table_error.iter().fold(0.0, |a, &b| a.max(b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A not-a-knot spline reproduces any cubic exactly, ends included, and interpolates its
    /// nodes.
    #[test]
    fn spline_reproduces_cubics_and_its_nodes() {
        let f = |x: f64| 0.3 - 1.7 * x + 0.25 * x * x - 0.02 * x * x * x;
        let y: Vec<f64> = (0..40).map(|k| f(k as f64)).collect();
        let c = spline(&y);
        for (k, ck) in c.iter().enumerate() {
            for s in [0.0, 0.13, 0.5, 0.91, 1.0] {
                let v = ((ck[3] * s + ck[2]) * s + ck[1]) * s + ck[0];
                let x = k as f64 + s;
                assert!((v - f(x)).abs() < 1e-12 * f(x).abs().max(1.0), "{x}: {v}");
            }
        }
        // A function that is not a cubic: nodes exact, midpoints within the O(h^4) bound.
        let g = |x: f64| (0.3 * x).sin();
        let y: Vec<f64> = (0..60).map(|k| g(k as f64)).collect();
        let c = spline(&y);
        for (k, ck) in c.iter().enumerate() {
            assert!((ck[0] - y[k]).abs() < 1e-15);
            let mid = ((ck[3] * 0.5 + ck[2]) * 0.5 + ck[1]) * 0.5 + ck[0];
            // 5/384 h^4 max|g''''| = 5/384 0.3^4 for the clamped spline; the not-a-knot ends
            // are allowed ten times that.
            assert!((mid - g(k as f64 + 0.5)).abs() < 10.0 * 5.0 / 384.0 * 0.3f64.powi(4));
        }
    }

    /// The quadrature's exp agrees with the library's to about 1.5 ulp over the Gaussian's range
    /// and beyond, and is exp(-708) below -708.
    #[test]
    fn hertz_tail_table_is_the_moment() {
        let q = Quad::new();
        // Between the nodes, against the quadrature that made them (absolute: loads are
        // sigma^(3/2) G against a scale of sigma^(3/2) G(-press)).
        let mut worst = 0.0f64;
        for k in 0..(14.0 * HERTZ_TAIL_PER_UNIT) as usize {
            let h = -Z_MAP + (k as f64 + 0.5) / HERTZ_TAIL_PER_UNIT;
            let g = HertzTail::exact(&q.nodes, h);
            worst = worst.max((q.hertz.at(h) - g).abs());
        }
        assert!(worst < 1e-12, "table error {worst:e}");
        // Independent values: G(0) = E[t^(3/2); t > 0] = 2^(3/4) Gamma(5/4) / (2 sqrt(pi)) less
        // the 5.6e-11 of it beyond the truncation at 7, and G(-7) against a plain midpoint sum.
        let g0 = 2f64.powf(0.75) * 0.906_402_477_055_477 / (2.0 * PI.sqrt());
        assert!((q.hertz.at(0.0) / g0 - 1.0).abs() < 1e-10);
        let n = 2_400_000;
        let dt = 24.0 / n as f64;
        let m: f64 = (0..n)
            .map(|i| {
                let t = -12.0 + (i as f64 + 0.5) * dt;
                if t > -7.0 && t < 7.0 {
                    (t + 7.0).powf(1.5) * (-0.5 * t * t).exp()
                } else {
                    0.0
                }
            })
            .sum::<f64>()
            * dt
            / (2.0 * PI).sqrt();
        assert!(
            (q.hertz.at(-7.0) / m - 1.0).abs() < 1e-9,
            "{} {}",
            q.hertz.at(-7.0),
            m
        );
        assert_eq!(q.hertz.at(7.5), 0.0);
    }

    #[test]
    fn exp_nonpositive_matches_exp() {
        let t = ExpTable::new();
        // Both roundings of the multiply-adds: the fused one of CPUs with FMA, and two apart.
        check_exp(|x| super::exp_nonpositive::<true>(x, &t));
        check_exp(|x| super::exp_nonpositive::<false>(x, &t));
    }

    fn check_exp(exp_nonpositive: impl Fn(f64) -> f64) {
        let mut worst = 0.0f64;
        for i in 0..=200_000 {
            let x = -30.0 * i as f64 / 200_000.0 - 1e-9 * (i % 7) as f64;
            let (a, b) = (exp_nonpositive(x), x.exp());
            worst = worst.max((a - b).abs() / b);
        }
        assert!(worst < 4e-16, "{worst:e}");
        for x in [-100.0, -500.0, -707.9] {
            assert!((exp_nonpositive(x) / f64::exp(x) - 1.0).abs() < 1e-15);
        }
        assert_eq!(exp_nonpositive(0.0), 1.0);
        assert_eq!(exp_nonpositive(-1e4), exp_nonpositive(-708.0));
    }

    /// Stopping at a parabola's vertex, without Brent's closing probes, finds the minimum of a
    /// smooth function as a search to machine precision does: the value to 1e-12, the abscissa
    /// to the tolerance; from scratch and from three samples as the map starts it.
    #[test]
    fn brent_stopping_early_finds_the_minimum() {
        for (k, &c) in [0.31, 0.7, 1.37, 1.9].iter().enumerate() {
            let f = |x: f64| 0.1 * k as f64 - (-4.0 * (x - c).powi(2)).exp() * (1.0 + 0.3 * x);
            // Golden section to the resolution of f64.
            let (mut a, mut b) = (c - 1.0, c + 1.0);
            while b - a > 1e-15 {
                let (p, q) = (b - 0.618 * (b - a), a + 0.618 * (b - a));
                if f(p) < f(q) {
                    b = q;
                } else {
                    a = p;
                }
            }
            let (x_ref, f_ref) = (0.5 * (a + b), f(0.5 * (a + b)));
            let tol = 1e-6;
            let h = 0.37;
            let i = c - 0.11;
            let starts = [
                None,
                Some([(i, f(i)), (i - h, f(i - h)), (i + h, f(i + h))]),
            ];
            for (start, (lo, hi)) in starts.into_iter().zip([(c - 1.0, c + 1.3), (i - h, i + h)]) {
                let (x, fx) = brent_min(&f, lo, hi, start, tol);
                assert!((x - x_ref).abs() < 3.0 * tol, "{c}: {x} against {x_ref}");
                assert!(
                    (fx - f_ref).abs() < 1e-12 * f_ref.abs(),
                    "{c}: {fx} against {f_ref}"
                );
            }
        }
    }

    /// Brent's minimum from three known points equals the one from scratch.
    #[test]
    fn brent_from_known_points_finds_the_same_minimum() {
        let f = |x: f64| (x - 0.7).powi(2) * (1.0 + x * x) - 3.0;
        let (a, b) = (0.0, 2.0);
        let plain = brent_min(&f, a, b, None, 1e-10);
        let started = brent_min(&f, a, b, Some([(0.9, f(0.9)), (a, f(a)), (b, f(b))]), 1e-10);
        assert!((plain.0 - 0.7).abs() < 1e-8 && (started.0 - 0.7).abs() < 1e-8);
        assert!((plain.1 + 3.0).abs() < 1e-15 && (started.1 + 3.0).abs() < 1e-15);
    }
}
