//! The one path follower: the equilibrium path of a contact law followed under a drive on the
//! way in or out, evaluated exactly at any value of the drive's control (normalised units,
//! docs/PHYSICS.md sections 1 and 4). A spring of normalised stiffness kbar (the force a
//! cantilever measures: the fits) controls the base displacement `Delta = Dbar + Pbar/kbar`;
//! rigid grips are kbar = infinity (Delta the approach), a dead load kbar = 0 (the control the
//! load itself). The cycles take their folds, jumps and landings from it.
//!
//! The path is cut into pieces (the law's, [`Law::pieces`], which holds every law-specific
//! equation), each parametrised by t with the state an explicit function of t:
//! the free piece (no force, t = Dbar), the non-contact piece (t = C) and the contact piece
//! (t = -ln mu for Maugis-Dugdale, t = A for the closed forms). A state is stable while
//! `dDelta/dt > 0`. Retracting, the state goes down the contact piece until a fold
//! (`dDelta/dt = 0`) or the piece's end, then jumps at constant Delta to the next stable stretch
//! below; approaching, the same upwards. Each followed stretch is a segment on which Delta rises
//! with t, so a given Delta maps to one state, found by a safeguarded Newton iteration on the
//! exact curve: the nodes only bracket it.

use super::{nodes, ContactLaw, Law, Piece, Pt};
use serde::{Deserialize, Serialize};

/// Which way the base moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    /// Towards the sample (the base height decreasing).
    Approach,
    /// Away from the sample.
    Retract,
}

impl Direction {
    /// The name in files (CSV `segment` columns, JSON): `approach` or `retract`.
    pub fn name(self) -> &'static str {
        match self {
            Direction::Approach => "approach",
            Direction::Retract => "retract",
        }
    }
}

impl Pt {
    /// The state a small step `dt` along the piece, to first order (the slopes are not moved):
    /// its error is about half the second derivative times dt^2, 1e-16 of the parameter's scale
    /// squared where dt is below 1e-8 of it.
    fn moved(&self, dt: f64) -> Pt {
        Pt {
            load: self.load + self.dload * dt,
            approach: self.approach + self.dapproach * dt,
            a: self.a + self.da * dt,
            ..*self
        }
    }
}

/// A state on the followed path.
#[derive(Clone, Copy, Debug)]
pub struct PathState {
    /// The piece the state is on.
    pub piece: Piece,
    /// Its parameter on that piece.
    pub t: f64,
    /// The load Pbar (normalised).
    pub load: f64,
    /// The contact radius A (normalised; 0 apart).
    pub a: f64,
    /// The approach Dbar (normalised).
    pub approach: f64,
    /// Held at the end of its stretch (a point the data puts on the other side of a jump).
    pub clamped: bool,
    /// The slopes of the load and the approach with respect to t there (the Jacobian of a fit
    /// reads them instead of evaluating the state again).
    pub(crate) dload: f64,
    pub(crate) dapproach: f64,
}

impl PathState {
    fn on(piece: Piece, t: f64, p: &Pt, clamped: bool) -> PathState {
        PathState {
            piece,
            t,
            load: p.load,
            a: p.a,
            approach: p.approach,
            clamped,
            dload: p.dload,
            dapproach: p.dapproach,
        }
    }
}

/// Which side of the first jump a measured point is on, as the data says: the model then
/// evaluates it on that side's branch, held at the branch's end (or continued along it) where the
/// model's own jump lies elsewhere. The misfit is then continuous in the parameters, so the fit
/// can move the model's jump onto the measured one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// Not told by the data: the followed path decides.
    Any,
    /// Before the first jump of its direction (retract: still in contact).
    BeforeJump,
    /// After it.
    AfterJump,
}

#[derive(Clone, Copy, Debug)]
struct Node {
    t: f64,
    delta: f64,
    slope: f64,
}

/// A slope in t of Delta, or of its terms, below this is rounding (Delta is O(1) in these
/// units). A genuine fold's bracket between nodes has a slope far above it at one end at least.
const SLOPE_ROUNDING: f64 = 1e-13;

/// One followed stretch: Delta rises with t over [t_lo, t_hi] of its piece (the free piece's
/// parameter is the approach; infinite ends: the stretch goes on).
#[derive(Clone, Copy, Debug)]
pub struct Segment {
    /// The piece.
    pub piece: Piece,
    /// Its parameter where the stretch starts.
    pub t_lo: f64,
    /// Where it ends.
    pub t_hi: f64,
    /// Delta at `t_lo`.
    pub delta_lo: f64,
    /// Delta at `t_hi`.
    pub delta_hi: f64,
}

/// The drive's control at a state and its slope in t: the base `Delta = Dbar + Pbar/kbar`
/// under a spring (kbar = infinity: rigid grips, Delta the approach), the load itself under a
/// dead load (kbar = 0).
fn control(kbar: f64, p: &Pt) -> (f64, f64) {
    if kbar == 0.0 {
        (p.load, p.dload)
    } else {
        (p.approach + p.load / kbar, p.dapproach + p.dload / kbar)
    }
}

/// The sizes of the terms the control and its slope are sums of: their rounding's scale.
fn control_terms(kbar: f64, p: &Pt) -> (f64, f64) {
    if kbar == 0.0 {
        (p.load.abs(), p.dload.abs())
    } else {
        (
            p.approach.abs() + (p.load / kbar).abs(),
            p.dapproach.abs() + (p.dload / kbar).abs(),
        )
    }
}

/// The path of one law under one drive, up to base displacement `delta_max`: a spring of
/// normalised stiffness kbar (the fits, a cantilever's cycle), rigid grips (kbar = infinity) or a
/// dead load (kbar = 0, Delta the load).
#[derive(Clone, Debug)]
pub struct DrivenPath<L = ContactLaw> {
    /// The law followed.
    pub law: L,
    /// The normalised spring stiffness kbar (infinity: rigid grips; 0: a dead load).
    pub kbar: f64,
    pieces: Vec<(Piece, Vec<Node>)>,
    /// Retract segments from the top down, and the retract's first jump (the last segment
    /// before it).
    retract: (Vec<Segment>, Option<usize>),
    /// The same for the approach, from the bottom up: followed when first asked for (a fit of
    /// retract data, the default, never needs it).
    approach: std::cell::OnceCell<(Vec<Segment>, Option<usize>)>,
}

impl<L: Law + Clone> DrivenPath<L> {
    /// The path of `law` (a lambda in the solver's domain) under a spring of normalised
    /// stiffness `kbar > 0`, up to the largest base displacement it must reach.
    pub fn of(law: L, kbar: f64, delta_max: f64) -> DrivenPath<L> {
        let delta_of = |piece, t| control(kbar, &law.state(piece, t)).0;
        // The contact piece's top: the radius whose Delta passes delta_max (doubling).
        let mut a_max = 2.0;
        while delta_of(Piece::Contact, law.t_of_radius(a_max)) < delta_max.max(1.0) * 1.05
            && a_max < 1e5
        {
            a_max *= 2.0;
        }
        DrivenPath::to_radius(law, kbar, a_max)
    }

    /// The path of `law` under the drive of stiffness `kbar` (infinity: rigid grips; 0: a dead
    /// load), its contact piece followed up to radius `a_max`.
    pub fn to_radius(law: L, kbar: f64, a_max: f64) -> DrivenPath<L> {
        // The states at the nodes do not depend on the spring: a fit of a one-zone law at
        // fixed lambda (the profile, the intervals) evaluates them once and only rescales
        // Delta with kbar (the two-zone law's nodes move with E* and w).
        let node = |t: f64, p: &Pt| {
            let (delta, slope) = control(kbar, p);
            Node { t, delta, slope }
        };
        let nodes = |piece, t0: f64, t1: f64| -> Vec<Node> {
            let mut n: Vec<Node> = nodes(&law, piece, t0, t1)
                .iter()
                .map(|(t, p)| node(*t, p))
                .collect();
            // Where the piece's formula changes (a law's breaks) its slope may jump: a node on
            // either side, so that no window between nodes straddles the jump (its end slopes
            // would hide a crossing inside it, and a fold there is the break).
            let breaks = law.breaks(piece);
            if breaks.is_empty() {
                return n;
            }
            for b in breaks.into_iter().filter(|&b| b > t0 && b < t1) {
                let after = (b + 1e-9 * b.abs().max(1.0)).min(t1);
                n.push(node(b, &law.state(piece, b)));
                n.push(node(after, &law.state(piece, after)));
            }
            n.sort_by(|x, y| x.t.total_cmp(&y.t));
            n.dedup_by(|x, y| x.t == y.t);
            n
        };
        let pieces = law
            .pieces(a_max)
            .into_iter()
            .map(|(piece, t0, t1)| (piece, nodes(piece, t0, t1)))
            .collect();
        let mut path = DrivenPath {
            law,
            kbar,
            pieces,
            retract: (Vec::new(), None),
            approach: std::cell::OnceCell::new(),
        };
        let segs = path.follow(Direction::Retract);
        let jump = path.find_first_jump(&segs, Direction::Retract);
        path.retract = (segs, jump);
        path
    }

    /// The segments followed in a direction and the first jump's index.
    fn followed(&self, dir: Direction) -> &(Vec<Segment>, Option<usize>) {
        match dir {
            Direction::Retract => &self.retract,
            Direction::Approach => self.approach.get_or_init(|| {
                let segs = self.follow(Direction::Approach);
                let jump = self.find_first_jump(&segs, Direction::Approach);
                (segs, jump)
            }),
        }
    }

    fn eval(&self, piece: Piece, t: f64) -> (Pt, f64, f64) {
        let p = self.law.state(piece, t);
        let (delta, slope) = control(self.kbar, &p);
        (p, delta, slope)
    }

    fn slope(&self, piece: Piece, t: f64) -> f64 {
        self.eval(piece, t).2
    }

    fn delta(&self, piece: Piece, t: f64) -> f64 {
        self.eval(piece, t).1
    }

    /// The fold between two nodes where the slope changes sign: the bracketed secant on the
    /// slope (about five evaluations where bisection takes fifty), with the slopes at the ends
    /// where they are known (a node's).
    fn fold(
        &self,
        piece: Piece,
        (lo, s_lo): (f64, Option<f64>),
        (hi, s_hi): (f64, Option<f64>),
    ) -> f64 {
        let s_lo = s_lo.unwrap_or_else(|| self.slope(piece, lo));
        let s_hi = s_hi.unwrap_or_else(|| self.slope(piece, hi));
        // Where the slopes are rounding, and so are both of their terms (the contact piece's
        // far end, A -> 0 as t -> -inf, where the curve's slopes in t vanish), Delta is flat to
        // rounding across the bracket and any point of it is the fold: the secant would bisect
        // noise to the last bit.
        let terms = |t: f64| control_terms(self.kbar, &self.eval(piece, t).0).1;
        if s_lo.abs().max(s_hi.abs()) <= SLOPE_ROUNDING
            && terms(lo).max(terms(hi)) <= SLOPE_ROUNDING
        {
            return 0.5 * (lo + hi);
        }
        // secant_bracketed wants f(lo) > 0 > f(hi).
        let sign = if s_lo > 0.0 { 1.0 } else { -1.0 };
        if !(sign * s_hi < 0.0) {
            return if s_lo > 0.0 { lo } else { hi };
        }
        let r = crate::numeric::root::secant_bracketed(
            |t| sign * self.slope(piece, t),
            (lo, sign * s_lo),
            (hi, sign * s_hi),
            0.5 * (lo + hi),
            1e-15,
            200,
        );
        r.x.clamp(lo, hi)
    }

    /// Where `solve_between` starts: Delta's cubic Hermite interpolant between two nodes, else
    /// the secant between the bracket's ends.
    fn start_between(
        &self,
        piece: Piece,
        target: f64,
        (lo, n_lo): (f64, Option<(f64, f64)>),
        (hi, n_hi): (f64, Option<(f64, f64)>),
    ) -> f64 {
        let d_lo = n_lo.map_or_else(|| self.delta(piece, lo), |n| n.0);
        let d_hi = n_hi.map_or_else(|| self.delta(piece, hi), |n| n.0);
        let t = if d_hi > d_lo {
            lo + (hi - lo) * ((target - d_lo) / (d_hi - d_lo)).clamp(0.0, 1.0)
        } else {
            0.5 * (lo + hi)
        };
        if let (Some((_, m0)), Some((_, m1)), true) = (n_lo, n_hi, d_hi > d_lo) {
            // Between two nodes, Delta's cubic Hermite interpolant (values and slopes) puts
            // the start within the cube of the node spacing: two Newton steps on it.
            return hermite_root(lo, hi, (d_lo, m0), (d_hi, m1), target, t);
        }
        t
    }

    /// Delta(t) = target on [lo, hi], where Delta rises: safeguarded Newton, with Delta and its
    /// slope at either end where they are known (a node's).
    fn solve_between(
        &self,
        piece: Piece,
        target: f64,
        (mut lo, n_lo): (f64, Option<(f64, f64)>),
        (mut hi, n_hi): (f64, Option<(f64, f64)>),
    ) -> (Pt, f64) {
        if piece == Piece::Free {
            return (self.law.state(piece, target), target);
        }
        let mut t = self.start_between(piece, target, (lo, n_lo), (hi, n_hi));
        for _ in 0..100 {
            let (p, d, s) = self.eval(piece, t);
            let r = d - target;
            let tol = 1e-15 * control_terms(self.kbar, &p).0.max(1.0);
            if r.abs() <= tol {
                return (p, t);
            }
            if r < 0.0 {
                lo = t;
            } else {
                hi = t;
            }
            let newton = t - r / s;
            let next = if s > 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if next == t || !(hi > lo) {
                return (p, t);
            }
            t = next;
        }
        (self.law.state(piece, t), t)
    }

    /// The segments followed in one direction.
    fn follow(&self, dir: Direction) -> Vec<Segment> {
        match dir {
            Direction::Retract => self.follow_retract(),
            Direction::Approach => self.follow_approach(),
        }
    }

    /// The retract: from the top of the contact piece down, each stable stretch to its fold or
    /// its piece's end, a jump at constant Delta to the highest stable crossing below, and the
    /// free piece last.
    fn follow_retract(&self) -> Vec<Segment> {
        let mut segs = Vec::new();
        // From the top of the contact piece down.
        let mut k = self.pieces.len() - 1;
        let mut t_hi = self.pieces[k].1.last().unwrap().t;
        let mut delta_hi = f64::INFINITY;
        loop {
            let (piece, nodes) = (&self.pieces[k].0, &self.pieces[k].1);
            // The highest unstable node below t_hi.
            let unstable = nodes.iter().rposition(|n| n.t < t_hi && !(n.slope > 0.0));
            let t_lo = match unstable {
                Some(j) => {
                    let above = match nodes.get(j + 1) {
                        Some(n) if n.t <= t_hi => (n.t, Some(n.slope)),
                        _ => (t_hi, None),
                    };
                    self.fold(*piece, (nodes[j].t, Some(nodes[j].slope)), above)
                }
                None => nodes[0].t,
            };
            let delta_lo = self.delta(*piece, t_lo);
            segs.push(Segment {
                piece: *piece,
                t_lo,
                t_hi,
                delta_lo,
                delta_hi,
            });
            // Land below: the highest stable crossing of delta_lo under t_lo.
            match self.land(delta_lo, k, t_lo, Direction::Retract) {
                Some((kk, t)) => {
                    k = kk;
                    t_hi = t;
                    delta_hi = delta_lo;
                }
                None => {
                    segs.push(Segment {
                        piece: Piece::Free,
                        t_lo: f64::NEG_INFINITY,
                        t_hi: delta_lo.min(self.law.free_end()),
                        delta_lo: f64::NEG_INFINITY,
                        delta_hi: delta_lo,
                    });
                    return segs;
                }
            }
        }
    }

    /// The approach: free up to its end, then each jump up to the nearest stable crossing above
    /// and along it to its fold, up to the top of the contact piece.
    fn follow_approach(&self) -> Vec<Segment> {
        let mut segs = Vec::new();
        // Free up to its end, then jump up.
        // The free piece's control at its end: its approach (a spring, rigid grips), or no load.
        let mut delta_lo = self.delta(Piece::Free, self.law.free_end());
        segs.push(Segment {
            piece: Piece::Free,
            t_lo: f64::NEG_INFINITY,
            t_hi: self.law.free_end(),
            delta_lo: f64::NEG_INFINITY,
            delta_hi: delta_lo,
        });
        let (mut k, mut t_from) = (0usize, f64::NEG_INFINITY);
        loop {
            let Some((kk, t_lo)) = self.land(delta_lo, k, t_from, Direction::Approach) else {
                // No stable state at this Delta above: follow the last piece (cannot
                // happen for these models; kept so the path always reaches the top).
                let (piece, nodes) = self.pieces.last().unwrap();
                let t_lo = nodes[0].t;
                segs.push(Segment {
                    piece: *piece,
                    t_lo,
                    t_hi: nodes.last().unwrap().t,
                    delta_lo: self.delta(*piece, t_lo),
                    delta_hi: f64::INFINITY,
                });
                return segs;
            };
            let (piece, nodes) = (&self.pieces[kk].0, &self.pieces[kk].1);
            let unstable = nodes.iter().position(|n| n.t > t_lo && !(n.slope > 0.0));
            let t_hi = match unstable {
                Some(j) => {
                    let below = match j.checked_sub(1).map(|i| &nodes[i]) {
                        Some(n) if n.t >= t_lo => (n.t, Some(n.slope)),
                        _ => (t_lo, None),
                    };
                    self.fold(*piece, below, (nodes[j].t, Some(nodes[j].slope)))
                }
                None => nodes.last().unwrap().t,
            };
            let top = kk == self.pieces.len() - 1 && unstable.is_none();
            let delta_hi = if top {
                f64::INFINITY
            } else {
                self.delta(*piece, t_hi)
            };
            segs.push(Segment {
                piece: *piece,
                t_lo,
                t_hi,
                delta_lo,
                delta_hi,
            });
            if top {
                return segs;
            }
            delta_lo = delta_hi;
            k = kk;
            t_from = t_hi;
        }
    }

    /// Where a jump at `delta` from piece `k` at `t_from` lands: on a stable stretch, the
    /// nearest crossing below (retract) or above (approach). None: the free piece (retract).
    fn land(&self, delta: f64, k: usize, t_from: f64, dir: Direction) -> Option<(usize, f64)> {
        let tol = 1e-9 * delta.abs().max(1.0);
        let crosses = |piece: Piece, a: &Node, b: &Node| -> Option<f64> {
            // A window with a fold inside (end slopes of both signs) is searched on its stable
            // part: from the fold up to the stable node above, or from the stable node below
            // up to the fold. (Small lambda: Maugis-Dugdale's snap onto the zone alone lands
            // in the non-contact piece's first window, which also holds its fold.)
            let node = |n: &Node| (n.t, Some((n.delta, n.slope)));
            let fold = || self.fold(piece, (a.t, Some(a.slope)), (b.t, Some(b.slope)));
            let (lo, hi) = match (a.slope > 0.0, b.slope > 0.0) {
                (true, true) => (node(a), node(b)),
                (false, true) => ((fold(), None), node(b)),
                (true, false) => (node(a), (fold(), None)),
                (false, false) => return None,
            };
            let delta_at =
                |(t, n): (f64, Option<(f64, f64)>)| n.map_or_else(|| self.delta(piece, t), |n| n.0);
            let (d_lo, d_hi) = (delta_at(lo), delta_at(hi));
            if d_lo <= delta && delta <= d_hi {
                Some(self.solve_between(piece, delta, lo, hi).1)
            } else if (d_lo - delta).abs() <= tol {
                Some(lo.0)
            } else if (d_hi - delta).abs() <= tol {
                Some(hi.0)
            } else {
                None
            }
        };
        match dir {
            Direction::Retract => {
                for kk in (0..=k).rev() {
                    let (piece, nodes) = (self.pieces[kk].0, &self.pieces[kk].1);
                    for w in nodes.windows(2).rev() {
                        // Below t_from on its own piece; every node of a piece below it (each
                        // piece has its own parameter).
                        if kk == k && w[1].t >= t_from {
                            continue;
                        }
                        if let Some(t) = crosses(piece, &w[0], &w[1]) {
                            return Some((kk, t));
                        }
                    }
                }
                None
            }
            Direction::Approach => {
                for kk in k..self.pieces.len() {
                    let (piece, nodes) = (self.pieces[kk].0, &self.pieces[kk].1);
                    for w in nodes.windows(2) {
                        if kk == k && w[0].t <= t_from {
                            continue;
                        }
                        if let Some(t) = crosses(piece, &w[0], &w[1]) {
                            return Some((kk, t));
                        }
                    }
                }
                None
            }
        }
    }

    /// The state at base displacement `delta` on the way in or out (a spring or rigid grips,
    /// kbar > 0: under a dead load the free piece's control, no load, does not fix its state).
    pub fn at(&self, delta: f64, dir: Direction) -> PathState {
        self.at_side_from(delta, dir, Side::Any, None)
    }

    /// The stretches followed in a direction, in the order met (approach: from the free piece
    /// up; retract: from the top down), each ending in a fold, a jump or a piece's end.
    pub fn segments(&self, dir: Direction) -> &[Segment] {
        &self.followed(dir).0
    }

    fn first_jump(&self, dir: Direction) -> Option<usize> {
        self.followed(dir).1
    }

    /// The index of the last of `segs` (followed in `dir`) before the first jump (a change of
    /// load), if any.
    fn find_first_jump(&self, segs: &[Segment], dir: Direction) -> Option<usize> {
        (0..segs.len().saturating_sub(1)).find(|&j| {
            let (a, b) = (&segs[j], &segs[j + 1]);
            let (ta, tb) = match dir {
                Direction::Retract => (a.t_lo, b.t_hi),
                Direction::Approach => (a.t_hi, b.t_lo),
            };
            let la = self.eval(a.piece, ta).0.load;
            let lb = self.eval(b.piece, tb).0.load;
            (la - lb).abs() > 1e-6 * la.abs().max(lb.abs()).max(1e-3)
        })
    }

    fn state_at(&self, seg: &Segment, t: f64, clamped: bool) -> PathState {
        PathState::on(seg.piece, t, &self.law.state(seg.piece, t), clamped)
    }

    /// The state at base displacement `delta` on the side of the first jump the data says.
    pub fn at_side(&self, delta: f64, dir: Direction, side: Side) -> PathState {
        self.at_side_from(delta, dir, side, None)
    }

    /// The same, Newton steps from `hint` (the point's state at nearby parameters, as in the
    /// trial steps of a fit) where it lies on the right stretch: two or three evaluations
    /// instead of a search from the nodes.
    pub fn at_side_from(
        &self,
        delta: f64,
        dir: Direction,
        side: Side,
        hint: Option<&PathState>,
    ) -> PathState {
        let Some(j) = self.first_jump(dir).filter(|_| side != Side::Any) else {
            let segs = self.segments(dir);
            let seg = containing(segs, delta)
                .or_else(|| segs.last())
                .expect("a path has segments");
            return self.at_in_from(seg, delta, hint);
        };
        let segs = self.segments(dir);
        let (run, first) = match side {
            Side::BeforeJump => (&segs[..=j], false),
            _ => (&segs[j + 1..], true),
        };
        if let Some(seg) = containing(run, delta) {
            return self.at_in_from(seg, delta, hint);
        }
        // Beyond the run: before the jump, held at the fold; after it, the landing branch
        // continued (held at the landing where it cannot be).
        let retract = dir == Direction::Retract;
        if !first {
            let seg = &run[run.len() - 1];
            let t = if retract { seg.t_lo } else { seg.t_hi };
            if seg.piece == Piece::Free {
                return self.at_in(seg, delta.min(seg.t_hi));
            }
            return self.state_at(seg, t, true);
        }
        let seg = &run[0];
        if seg.piece == Piece::Free {
            let mut s = self.at_in(seg, delta);
            s.load = 0.0;
            return s;
        }
        let t = if retract { seg.t_hi } else { seg.t_lo };
        near(&self.law, self.kbar, delta, seg.piece, t)
            .unwrap_or_else(|| self.state_at(seg, t, true))
    }

    fn at_in_from(&self, seg: &Segment, delta: f64, hint: Option<&PathState>) -> PathState {
        if let Some(h) = hint {
            if seg.piece != Piece::Free
                && h.piece == seg.piece
                && !h.clamped
                && h.t >= seg.t_lo
                && h.t <= seg.t_hi
            {
                if let Some(s) = near(&self.law, self.kbar, delta, seg.piece, h.t) {
                    if s.t >= seg.t_lo && s.t <= seg.t_hi {
                        return s;
                    }
                }
            }
        }
        self.at_in(seg, delta)
    }

    fn at_in(&self, seg: &Segment, delta: f64) -> PathState {
        let (lo, hi) = if seg.piece == Piece::Free {
            ((seg.t_lo, None), (seg.t_hi, None))
        } else {
            self.bracket(seg, delta)
        };
        let (p, t) = self.solve_between(seg.piece, delta, lo, hi);
        PathState::on(seg.piece, t, &p, false)
    }

    /// The nodes around `delta` inside a segment, with their Delta and its slope (None at the
    /// segment's ends, which are not nodes).
    #[allow(clippy::type_complexity)]
    fn bracket(
        &self,
        seg: &Segment,
        delta: f64,
    ) -> ((f64, Option<(f64, f64)>), (f64, Option<(f64, f64)>)) {
        let nodes = &self.pieces.iter().find(|p| p.0 == seg.piece).unwrap().1;
        let i = nodes.partition_point(|n| n.t <= seg.t_lo);
        let j = nodes.partition_point(|n| n.t < seg.t_hi);
        let mut lo = (seg.t_lo, None);
        let mut hi = (seg.t_hi, None);
        // Within the segment Delta rises with t: binary search the interior nodes.
        let interior = &nodes[i..j.max(i)];
        let k = interior.partition_point(|n| n.delta < delta);
        if k > 0 {
            lo = (
                interior[k - 1].t,
                Some((interior[k - 1].delta, interior[k - 1].slope)),
            );
        }
        if k < interior.len() {
            hi = (interior[k].t, Some((interior[k].delta, interior[k].slope)));
        }
        (lo, hi)
    }

    /// The lowest base displacement at which either direction feels a force (the retract's
    /// jump-out, or the start of the approach's force zone).
    pub fn force_reach(&self) -> f64 {
        self.retract
            .0
            .iter()
            .chain(self.segments(Direction::Approach))
            .filter(|s| s.piece != Piece::Free)
            .map(|s| s.delta_lo)
            .fold(self.law.free_end(), f64::min)
    }

    /// The most tensile load on the path followed in a direction (the pull-off a cantilever
    /// reads on retract) and the Delta where it is reached.
    pub fn min_load(&self, dir: Direction) -> (f64, f64) {
        let segs = self.segments(dir);
        let mut best = (0.0, f64::NAN);
        for s in segs.iter().filter(|s| s.piece != Piece::Free) {
            let nodes = &self.pieces.iter().find(|p| p.0 == s.piece).unwrap().1;
            let mut ts: Vec<f64> = vec![s.t_lo];
            ts.extend(
                nodes
                    .iter()
                    .map(|n| n.t)
                    .filter(|&t| t > s.t_lo && t < s.t_hi),
            );
            if s.t_hi.is_finite() {
                ts.push(s.t_hi);
            }
            let loads: Vec<f64> = ts.iter().map(|&t| self.eval(s.piece, t).0.load).collect();
            let Some(i) = (0..ts.len()).min_by(|&i, &j| loads[i].total_cmp(&loads[j])) else {
                continue;
            };
            // An interior minimum: refine where dP/dt changes sign.
            let t = if i > 0 && i + 1 < ts.len() {
                let (mut lo, mut hi) = (ts[i - 1], ts[i + 1]);
                for _ in 0..100 {
                    let mid = 0.5 * (lo + hi);
                    if !(mid > lo && mid < hi) {
                        break;
                    }
                    if self.eval(s.piece, mid).0.dload < 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                0.5 * (lo + hi)
            } else {
                ts[i]
            };
            let (p, d, _) = self.eval(s.piece, t);
            if p.load < best.0 {
                best = (p.load, d);
            }
        }
        best
    }
}

/// The root of the cubic Hermite interpolant through (t0, d0, slope m0) and (t1, d1, m1) at
/// `target`, by two Newton steps from `t` (kept inside [t0, t1]).
fn hermite_root(
    t0: f64,
    t1: f64,
    (d0, m0): (f64, f64),
    (d1, m1): (f64, f64),
    target: f64,
    t: f64,
) -> f64 {
    let h = t1 - t0;
    let mut s = (t - t0) / h;
    for _ in 0..2 {
        let (s2, s3) = (s * s, s * s * s);
        let v = (2.0 * s3 - 3.0 * s2 + 1.0) * d0
            + (s3 - 2.0 * s2 + s) * h * m0
            + (-2.0 * s3 + 3.0 * s2) * d1
            + (s3 - s2) * h * m1;
        let dv = (6.0 * s2 - 6.0 * s) * d0
            + (3.0 * s2 - 4.0 * s + 1.0) * h * m0
            + (-6.0 * s2 + 6.0 * s) * d1
            + (3.0 * s2 - 2.0 * s) * h * m1;
        if !(dv > 0.0) {
            break;
        }
        s = (s - (v - target) / dv).clamp(0.0, 1.0);
    }
    t0 + s * h
}

/// The segment whose Delta range holds `delta`.
fn containing(segs: &[Segment], delta: f64) -> Option<&Segment> {
    segs.iter()
        .find(|s| s.delta_lo <= delta && delta <= s.delta_hi)
}

/// The state on a given piece near parameter `t`: Newton steps from there. The Jacobian of a fit
/// keeps each point on its branch this way, so that a finite difference never straddles a jump.
pub fn near<L: Law + ?Sized>(
    law: &L,
    kbar: f64,
    delta: f64,
    piece: Piece,
    t: f64,
) -> Option<PathState> {
    if piece == Piece::Free {
        return Some(PathState {
            piece,
            t: delta,
            load: 0.0,
            a: 0.0,
            approach: delta,
            clamped: false,
            dload: 0.0,
            dapproach: 1.0,
        });
    }
    let mut t = t;
    for _ in 0..8 {
        let p = law.state(piece, t);
        let r = p.approach + p.load / kbar - delta;
        if r.abs() <= 1e-14 * delta.abs().max(1.0) {
            return Some(PathState::on(piece, t, &p, false));
        }
        let s = p.dapproach + p.dload / kbar;
        if !(s.abs() > 0.0) {
            return None;
        }
        let step = r / s;
        t -= step;
        if step.abs() <= 1e-8 * t.abs().max(1.0) {
            // Newton converges quadratically: the state after this step differs from its
            // first-order extrapolation by about step^2 (1e-16 of the parameter's scale
            // squared), so it is not evaluated again.
            return Some(PathState::on(piece, t, &p.moved(-step), false));
        }
    }
    None
}

/// The signed distance from a measured point (`delta`, `load`) to a model piece near parameter
/// `t`, in the plane (load, `scale` Delta), and the parameter of the nearest state: Gauss-Newton
/// on t. Near a fold the load is a square root of Delta (its slope infinite there), so the force
/// residual of a point at or beyond the fold is not smooth in the parameters while the distance
/// to the curve, continued past the fold, is. The sign is that of the model's load minus the
/// measured one where Delta rises with t. None where the iteration leaves the piece.
#[allow(clippy::too_many_arguments)]
pub fn fold_distance(
    law: ContactLaw,
    kbar: f64,
    scale: f64,
    piece: Piece,
    t: f64,
    delta: f64,
    load: f64,
) -> Option<(f64, f64)> {
    if piece == Piece::Free {
        return None;
    }
    let valid = |t: f64| law.on_piece(piece, t);
    let mut t = t;
    for _ in 0..200 {
        if !valid(t) {
            return None;
        }
        let p = law.state(piece, t);
        let (ep, ed) = (p.load - load, scale * (p.approach + p.load / kbar - delta));
        let (tp, td) = (p.dload, scale * (p.dapproach + p.dload / kbar));
        let tt = tp * tp + td * td;
        if !(tt > 0.0 && tt.is_finite()) {
            return None;
        }
        // Newton on the stationarity e.T = 0 with the curve's bend (T' by differences):
        // Gauss-Newton alone creeps where the residual is not small against the curve's speed.
        let h = 1e-5 * t.abs().max(1.0);
        let tangent = |t: f64| {
            let q = law.state(piece, t);
            (q.dload, scale * (q.dapproach + q.dload / kbar))
        };
        let (ap, ad) = tangent(t + h);
        let (bp, bd) = tangent(t - h);
        let bend = (ep * (ap - bp) + ed * (ad - bd)) / (2.0 * h);
        let g = ep * tp + ed * td;
        let curv = tt + bend;
        let step = if curv > 0.1 * tt && valid(t + h) && valid(t - h) {
            g / curv
        } else {
            g / tt
        };
        // The distance is stationary in t: an error e in t moves it by about e^2.
        let small = step.abs() <= 1e-12 * t.abs().max(1.0);
        t -= step;
        if small {
            return Some(((ep * td - ed * tp) / tt.sqrt(), t));
        }
    }
    None
}
