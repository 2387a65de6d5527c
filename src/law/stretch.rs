//! A law's stretches under displacement control (docs/PHYSICS.md sections 10.1 and 11): the
//! runs of its equilibrium path on which the approach rises along the path, each stable under
//! rigid grips between its ends, in the order of the path (the free branch first, the open
//! contact stretch last), and the jumps between them: on the approach from a stretch's top to
//! the next stretch of the path holding it, on the retract from its bottom to the previous one
//! holding it (or free). Found from the law's own states: each piece probed, each fold (a sign
//! change of the approach's slope along the path) refined by bisection to the last bit.

use super::path::Branch;
use super::{Law, Piece};
use crate::numeric::root::{bisect_sign, newton_bracketed};
use crate::physics::domain::short;

/// Probes per piece of the path that locate its folds (each fold then refined to the last bit).
const PROBES: usize = 2048;

/// Why a law's stretches could not be found.
#[derive(Debug, thiserror::Error)]
pub enum StretchError {
    /// A piece of the path had no finite states, or the path did not end in an open contact
    /// stretch reaching the overlap asked for.
    #[error("the {} piece of the law's path could not be followed (up to overlap {}, lambda = {})", .0.name(), short(*.1), short(*.2))]
    Path(Branch, f64, f64),
}

/// A stretch of the path on which the approach rises: stable under rigid grips for overlaps in
/// `[lo, hi]`.
#[derive(Debug)]
pub struct Stretch {
    /// Its kind: free, non-contact or contact.
    pub branch: Branch,
    /// The piece of the path it lies on.
    pub piece: Piece,
    /// The path parameter at the low and the high end (the approach rises from the first).
    pub t: (f64, f64),
    /// The low overlap (-inf for the free branch).
    pub lo: f64,
    /// The top overlap (+inf for the open contact stretch).
    pub hi: f64,
    /// The approach at `t.1` (`hi` where the stretch is bounded; the path's end for the open
    /// contact stretch).
    pub top: f64,
    /// Whether the low and the high end are folds (vertical in overlap and load).
    pub fold: (bool, bool),
    /// `lo` widened by rounding (1e-12 relative): a jump that lands within rounding of a
    /// stretch's end (the stretches it joins agree to a few ulps) stays there.
    pub floor: f64,
    /// `hi` widened by rounding.
    pub ceil: f64,
    /// The stretch the approach jumps to from `hi`.
    pub up: usize,
    /// The stretch the retract jumps to from `lo`.
    pub down: usize,
}

/// A law's stretches, free first, with the contact piece's least load.
#[derive(Debug)]
pub struct Stretches {
    /// The stretches in the order of the path.
    pub list: Vec<Stretch>,
    /// The load-controlled pull-off: the contact piece's least load.
    pub load_pulloff: f64,
}

/// A run of the path where the approach rises, before it is a stretch.
struct Run {
    piece: Piece,
    t: (f64, f64),
    fold: (bool, bool),
    /// It starts where the previous piece's last run ends (the path is continuous there).
    joined: bool,
    open: bool,
}

/// The runs of rising approach of every piece after the free one, in the order of the path, and
/// the contact piece's least load (the load-controlled pull-off) with the path's end.
fn runs<L: Law + ?Sized>(law: &L, overlap_max: f64) -> Result<(Vec<Run>, f64), StretchError> {
    let lambda = law.lambda().unwrap_or(f64::NAN);
    let failed = |b: Branch, d: f64| StretchError::Path(b, d, lambda);
    // The contact piece must reach beyond the overlap asked for (a table's last node lies two
    // graded steps past it).
    let reach = overlap_max.max(0.0) * 1.05 + 1.0;
    let mut a_max = reach.sqrt() + 2.0;
    for _ in 0..80 {
        let p = law.state(Piece::Contact, law.t_of_radius(a_max));
        if p.approach >= reach {
            break;
        }
        a_max *= 1.5;
    }
    let mut out: Vec<Run> = Vec::new();
    let mut least = f64::INFINITY;
    // Whether the previous piece's last run reached its end (the path runs on into this one).
    let mut continues = false;
    for (piece, t0, t1) in law.pieces(a_max) {
        let branch = if piece == Piece::Contact {
            Branch::Contact
        } else {
            Branch::NonContact
        };
        if !(t0.is_finite() && t1.is_finite() && t0 != t1) {
            return Err(failed(branch, f64::NAN));
        }
        let probed = Probed::of(law, piece, t0, t1).ok_or(failed(branch, f64::NAN))?;
        continues = probed.runs(continues, &mut out);
        if piece == Piece::Contact {
            least = least_load(law, &probed.ts, &probed.st);
        }
    }
    // The last run must be the open contact branch.
    if !out.last().is_some_and(|r| r.open) {
        return Err(failed(Branch::Contact, overlap_max));
    }
    Ok((out, least))
}

/// One piece of a law's path at its probes.
struct Probed<'a, L: Law + ?Sized> {
    law: &'a L,
    piece: Piece,
    /// +1 where the parameter rises along the path, -1 where it falls.
    sign: f64,
    breaks: Vec<f64>,
    ts: Vec<f64>,
    st: Vec<super::Pt>,
}

impl<'a, L: Law + ?Sized> Probed<'a, L> {
    /// The piece from `t0` to `t1` probed ([`probes`]); None where a state is not finite.
    fn of(law: &'a L, piece: Piece, t0: f64, t1: f64) -> Option<Probed<'a, L>> {
        let breaks = law.breaks(piece);
        let ts = probes(t0, t1, &breaks);
        let st: Vec<_> = ts.iter().map(|&t| law.state(piece, t)).collect();
        st.iter()
            .all(|p| p.approach.is_finite() && p.load.is_finite())
            .then_some(Probed {
                law,
                piece,
                sign: (t1 - t0).signum(),
                breaks,
                ts,
                st,
            })
    }

    fn rising(&self, i: usize) -> bool {
        self.sign * self.st[i].dapproach > 0.0
    }

    /// The fold between probes i and i + 1, where the approach's slope along the path changes
    /// sign: bisection on that slope, signed to be negative at the smaller t.
    fn fold_at(&self, i: usize) -> f64 {
        let (a, b) = (self.ts[i], self.ts[i + 1]);
        let flip = if (a < b) == self.rising(i) {
            -self.sign
        } else {
            self.sign
        };
        let (law, piece) = (self.law, self.piece);
        bisect_sign(|t| flip * law.state(piece, t).dapproach, a.min(b), a.max(b))
    }

    /// The lowest approach of probes i..=j.
    fn lowest(&self, i: usize, j: usize) -> f64 {
        self.st[i..=j]
            .iter()
            .map(|p| p.approach)
            .fold(f64::INFINITY, f64::min)
    }

    /// The approach at the fold between probes i and i + 1 (the probes only bracket it).
    fn refined(&self, i: usize) -> f64 {
        self.law.state(self.piece, self.fold_at(i)).approach
    }

    /// Whether the approach falls from probe i to the lowest of probes i..=j by no more than
    /// rounding.
    fn flat(&self, i: usize, j: usize) -> bool {
        rounding(self.st[i].approach, self.lowest(i, j))
    }

    /// Whether the fall from the top after probe `top` to the bottom before probe `bottom` is
    /// rounding, measured between its refined ends.
    fn shallow(&self, top: usize, bottom: usize) -> bool {
        rounding(self.refined(top), self.refined(bottom - 1))
    }

    /// Whether the fall from the piece's start to the bottom before probe `bottom` is rounding,
    /// the bottom refined.
    fn shallow_from_start(&self, bottom: usize) -> bool {
        rounding(self.st[0].approach, self.refined(bottom - 1))
    }

    /// Whether the fall from the top after probe `top` to the piece's lowest approach after it
    /// is rounding, the top refined.
    fn shallow_to_end(&self, top: usize) -> bool {
        rounding(self.refined(top), self.lowest(top, self.st.len() - 1))
    }

    /// Whether `t` is one of the piece's breaks (to rounding).
    fn at_break(&self, t: f64) -> bool {
        self.breaks
            .iter()
            .any(|&b| (t - b).abs() <= 1e-12 * (1.0 + b.abs()))
    }

    /// The piece's rising runs appended to `out` (`continues`: the previous piece's last run
    /// reached its end, so the path runs on into this one); whether its last run reaches the
    /// piece's end.
    fn runs(&self, continues: bool, out: &mut Vec<Run>) -> bool {
        let n = self.ts.len();
        // The rising runs as probe ranges; a fall between two of them (or before the first)
        // within rounding of the approach is noise where the path is flat (near A -> 0), not a
        // pair of folds: the runs are merged across it.
        let mut spans: Vec<(usize, usize)> = Vec::new();
        let mut i = 0;
        while i < n {
            if !self.rising(i) {
                i += 1;
                continue;
            }
            let mut j = i;
            while j + 1 < n && self.rising(j + 1) {
                j += 1;
            }
            match spans.last_mut() {
                Some(last) if self.flat(last.1, i) && self.shallow(last.1, i) => last.1 = j,
                None if i > 0 && self.flat(0, i) && self.shallow_from_start(i) => {
                    spans.push((0, j))
                }
                _ => spans.push((i, j)),
            }
            i = j + 1;
        }
        // A fall to the piece's end within rounding: the run reaches the end.
        if let Some(last) = spans.last_mut() {
            if last.1 + 1 < n && self.flat(last.1, n - 1) && self.shallow_to_end(last.1) {
                last.1 = n - 1;
            }
        }
        let reaches_end = spans.last().is_some_and(|l| l.1 == n - 1);
        for (i, j) in spans {
            let ta = if i > 0 {
                self.fold_at(i - 1)
            } else {
                self.ts[0]
            };
            let tb = if j + 1 < n {
                self.fold_at(j)
            } else {
                self.ts[n - 1]
            };
            // Where the path turns back at a break, the load's slope in the overlap is the same
            // on both sides: a turn, not a fold (the stiffness stays finite there).
            let start_fold = i > 0 && !self.at_break(ta);
            let end_fold = j + 1 < n && !self.at_break(tb);
            out.push(Run {
                piece: self.piece,
                t: (ta, tb),
                fold: (start_fold, end_fold),
                // The path runs on from the previous piece's end (the pieces are consecutive).
                joined: i == 0 && continues,
                open: self.piece == Piece::Contact && j + 1 == n,
            });
        }
        reaches_end
    }
}

/// Whether a fall of the approach from `top` to `bottom` is rounding (the path flat, near A -> 0).
fn rounding(top: f64, bottom: f64) -> bool {
    top - bottom <= 1e-10 * (1.0 + top.abs())
}

/// The probes of a piece from `t0` to `t1` (in the path's order): [`PROBES`] evenly spread, and
/// at each break the break itself with probes closing in on it geometrically from both sides,
/// down to a thousandth of the probe spacing, so that a turn of the path next to it is seen.
/// (Nearer probes would add nothing: the two-zone law's slopes there are differences over
/// `1e-6 (1 + |t|)`, about a thousandth of the spacing.)
fn probes(t0: f64, t1: f64, breaks: &[f64]) -> Vec<f64> {
    let mut ts: Vec<f64> = (0..PROBES)
        .map(|i| t0 + (t1 - t0) * i as f64 / (PROBES - 1) as f64)
        .collect();
    let step = (t1 - t0) / (PROBES - 1) as f64;
    let (lo, hi) = (t0.min(t1), t0.max(t1));
    for &b in breaks.iter().filter(|&&b| b > lo && b < hi) {
        ts.push(b);
        for k in 1..=24 {
            let d = step.abs() * 10f64.powf(-(k as f64) / 8.0);
            ts.extend([b - d, b + d].into_iter().filter(|&t| t > lo && t < hi));
        }
    }
    ts.sort_by(|a, b| a.total_cmp(b));
    ts.dedup();
    if t1 < t0 {
        ts.reverse();
    }
    ts
}

/// The contact piece's least load from its probes `ts` and states `st`, refined where the
/// load's slope in t changes sign.
fn least_load<L: Law + ?Sized>(law: &L, ts: &[f64], st: &[super::Pt]) -> f64 {
    let n = ts.len();
    let k = (0..n)
        .min_by(|&i, &j| st[i].load.total_cmp(&st[j].load))
        .unwrap_or(0);
    if k > 0 && k + 1 < n {
        let (a, b) = (ts[k - 1].min(ts[k + 1]), ts[k - 1].max(ts[k + 1]));
        let t = bisect_sign(|t| law.state(Piece::Contact, t).dload, a, b);
        law.state(Piece::Contact, t).load.min(st[k].load)
    } else {
        st[k].load
    }
}

impl Stretches {
    /// The stretches of `law`, the contact stretch followed beyond the overlap `overlap_max`.
    pub fn of<L: Law + ?Sized>(law: &L, overlap_max: f64) -> Result<Stretches, StretchError> {
        let (runs, load_pulloff) = runs(law, overlap_max)?;
        let free_end = law.free_end();
        let mut stretches = vec![Stretch {
            branch: Branch::Free,
            piece: Piece::Free,
            t: (f64::NEG_INFINITY, free_end),
            lo: f64::NEG_INFINITY,
            hi: free_end,
            top: free_end,
            fold: (false, false),
            floor: f64::NEG_INFINITY,
            ceil: widen(free_end, 1.0),
            up: 0,
            down: 0,
        }];
        let mut joined = vec![false];
        let mut dropped = false;
        for r in &runs {
            let lo = law.state(r.piece, r.t.0).approach;
            let top = law.state(r.piece, r.t.1).approach;
            // A stretch narrower than rounding holds no state a contact could keep.
            let was_dropped = std::mem::replace(&mut dropped, false);
            if !r.open && !(top - lo > 1e-13 * (1.0 + lo.abs())) {
                dropped = true;
                continue;
            }
            stretches.push(Stretch {
                branch: if r.piece == Piece::Contact {
                    Branch::Contact
                } else {
                    Branch::NonContact
                },
                piece: r.piece,
                t: r.t,
                lo,
                hi: if r.open { f64::INFINITY } else { top },
                top,
                fold: r.fold,
                floor: widen(lo, -1.0),
                ceil: if r.open {
                    f64::INFINITY
                } else {
                    widen(top, 1.0)
                },
                up: 0,
                down: 0,
            });
            joined.push(r.joined && !was_dropped);
        }
        link(&mut stretches, &joined);
        Ok(Stretches {
            list: stretches,
            load_pulloff,
        })
    }

    /// The stretch after overlap `delta`, coming from `k` (the history's one rule).
    #[inline(always)]
    pub fn next(&self, mut k: usize, delta: f64) -> usize {
        let s = &self.list;
        if delta > s[k].ceil {
            while delta > s[k].ceil {
                k = s[k].up;
            }
        } else {
            while delta < s[k].floor {
                k = s[k].down;
            }
        }
        k
    }

    /// The overlap where a contact coming from apart enters contact: the top of the last
    /// stretch the approach follows before one in contact.
    pub fn entry(&self) -> f64 {
        let s = &self.list;
        let mut k = 0;
        loop {
            let j = s[k].up;
            if s[j].branch == Branch::Contact || j == s.len() - 1 {
                return s[k].hi;
            }
            k = j;
        }
    }

    /// The retract from the contact stretch down to free: the stretch on which it leaves
    /// contact (the last in contact it follows), and where it comes free if that is after
    /// crossing the gap on a non-contact stretch (None: at the jump out of contact).
    pub fn exit(&self) -> (usize, Option<f64>) {
        let s = &self.list;
        let (mut k, mut out) = (s.len() - 1, s.len() - 1);
        loop {
            let j = s[k].down;
            if j == 0 {
                let free_from = (s[k].branch == Branch::NonContact).then_some(s[k].lo);
                return (out, free_from);
            }
            if s[j].branch == Branch::Contact {
                out = j;
            }
            k = j;
        }
    }

    /// The smallest overlap where any force acts on the retract: where it comes free, or the
    /// attraction's start.
    pub fn lowest(&self) -> f64 {
        let (out, free_from) = self.exit();
        free_from.unwrap_or(self.list[out].lo).min(self.list[0].hi)
    }

    /// The exact load at `delta` on stretch `k` (clamped into it): the law's state where the
    /// approach equals `delta`, by a bracketed Newton search in the path parameter.
    pub fn exact<L: Law + ?Sized>(&self, law: &L, k: usize, delta: f64) -> Option<f64> {
        let s = self.list.get(k)?;
        if s.branch == Branch::Free {
            return Some(0.0);
        }
        let d = delta.clamp(s.lo, s.top);
        let (t0, t1) = s.t;
        let sign = (t1 - t0).signum();
        // Increasing in the search variable x = sign t.
        let f = |x: f64| {
            let p = law.state(s.piece, sign * x);
            (p.approach - d, sign * p.dapproach)
        };
        let (a, b) = (sign * t0, sign * t1);
        let guess = a + (b - a) * ((d - s.lo) / (s.top - s.lo)).clamp(0.0, 1.0);
        let t = if d <= s.lo {
            t0
        } else if d >= s.top {
            t1
        } else {
            sign * newton_bracketed(f, a, b, guess)
        };
        let p = law.state(s.piece, t);
        p.load.is_finite().then_some(p.load)
    }

    /// The approaches where the load jumps, folds or changes stretch.
    pub fn marks(&self) -> Vec<f64> {
        marks(self.list.iter().map(|s| (s.lo, s.hi)))
    }

    /// The energy lost in one slow cycle from apart to `overlap_max` and back (normalised by
    /// `pi w R` times the approach unit): the area between the approach and the retract, from
    /// the exact stretches by double-exponential quadrature between the marks. Zero where the
    /// cycle does not reach the attraction; None for a largest overlap that is not finite.
    pub fn loop_area<L: Law + ?Sized>(&self, law: &L, overlap_max: f64) -> Option<f64> {
        if !overlap_max.is_finite() {
            return None;
        }
        let app = |d: f64| self.next(0, d);
        let reached = app(overlap_max);
        let ret = |d: f64| self.next(reached, d);
        let mut cuts = self.marks();
        cuts.push(self.lowest());
        cuts.retain(|&c| c < overlap_max);
        cuts.push(overlap_max);
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let failed = std::cell::Cell::new(false);
        let mut area = 0.0;
        for w in cuts.windows(2) {
            let mid = 0.5 * (w[0] + w[1]);
            let (ka, kr) = (app(mid), ret(mid));
            if ka == kr {
                continue;
            }
            let f = |d: f64| match (self.exact(law, ka, d), self.exact(law, kr, d)) {
                (Some(a), Some(r)) => a - r,
                _ => {
                    failed.set(true);
                    0.0
                }
            };
            area += quadrature::double_exponential::integrate(f, w[0], w[1], 1e-12).integral;
        }
        (!failed.get()).then_some(area)
    }
}

/// The finite ends of stretches given as `(lo, hi)`, sorted, each once: where a load jumps,
/// folds or changes stretch.
pub(crate) fn marks(ends: impl Iterator<Item = (f64, f64)>) -> Vec<f64> {
    let mut m: Vec<f64> = ends
        .flat_map(|(lo, hi)| [lo, hi])
        .filter(|x| x.is_finite())
        .collect();
    m.sort_by(f64::total_cmp);
    m.dedup();
    m
}

/// `x` moved by rounding (1e-12 relative) in the direction `dir`.
fn widen(x: f64, dir: f64) -> f64 {
    x + dir * 1e-12 * (1.0 + x.abs())
}

/// Whether stretch `s` holds the overlap `level` (within rounding: where two stretches meet at
/// a piece's end their ends agree to a few ulps).
fn holds(s: &Stretch, level: f64) -> bool {
    s.floor <= level && level <= s.ceil
}

/// The jumps: from a stretch's top on the approach to the first later stretch holding it (the
/// next one where the path runs on across a piece's end; the contact branch where none holds
/// it), from its bottom on the retract to the last earlier one holding it (the free branch
/// where none does).
fn link(s: &mut [Stretch], joined: &[bool]) {
    let n = s.len();
    for k in 0..n {
        let up = if k + 1 < n && joined[k + 1] {
            k + 1
        } else {
            (k + 1..n).find(|&j| holds(&s[j], s[k].hi)).unwrap_or(n - 1)
        };
        let down = if k == 0 {
            0
        } else if joined[k] {
            k - 1
        } else {
            (0..k).rev().find(|&j| holds(&s[j], s[k].lo)).unwrap_or(0)
        };
        s[k].up = up;
        s[k].down = down;
    }
}
