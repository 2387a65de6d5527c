//! Approach-retract cycles (PHYSICS.md section 4): the complete equilibrium path (free, the
//! non-contact branch with a cohesive zone only, the Maugis-Dugdale contact branch) and the path
//! actually followed under rigid grips, dead load or a spring in series (an AFM cantilever).
//!
//! With the spring's stiffness k normalised as `kbar = k (pi^2 w^2 R / K^2)^(1/3) / (pi w R)`,
//! the controlled variable is the base displacement `Delta = Dbar + Pbar / kbar` (rigid grips:
//! kbar -> infinity, Delta = Dbar; dead load: kbar -> 0, the load itself). Parametrise the path by
//! s (C growing on the non-contact branch, then A growing on the contact branch): a state is
//! stable while `dDelta/ds > 0`, i.e. until `dPbar/dDbar = -kbar` (the contact's force gradient
//! reaches the spring's stiffness; under rigid grips `dDbar/ds = 0`, under dead load
//! `dPbar/ds = 0`). There the system jumps at constant Delta to the next stable state. The energy
//! lost per cycle is the loop's area `W = closed integral of Pbar dDelta = closed integral of
//! Pbar dDbar` (the spring's stored energy is a state function), in units of pi w R times the
//! approach unit.
//!
//! The drive's path is the fits' follower's ([`DrivenPath`]: folds, jumps and landings exact);
//! the law's sampled path is what a figure draws and where the steps between them lie.

use crate::law::follow::{Direction, DrivenPath, Segment};
use crate::law::md::CYCLE_POINTS;
use crate::law::path::{control_of, free_before};
use crate::law::stretch::Stretches;
use crate::law::{Law, LawError, Md, Piece};
use serde::Serialize;

pub use crate::law::{Branch, Drive, PathPoint};

/// The half of a cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Phase {
    /// The surfaces move together.
    Approach,
    /// The surfaces move apart.
    Retract,
}

impl std::fmt::Display for Phase {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Phase::Approach => "approach",
            Phase::Retract => "retract",
        })
    }
}

/// One step of the cycle: the state the drive holds at one value of its control.
#[derive(Clone, Debug, Serialize)]
pub struct Step {
    /// Approach or retract.
    pub phase: Phase,
    /// The state.
    pub point: PathPoint,
    /// The controlled variable (Delta, or the load under dead load).
    pub control: f64,
    /// true at the first point after a jump.
    pub jump: bool,
}

/// A jump: where the followed branch ends and the state the drive lands on.
#[derive(Clone, Debug, Serialize)]
pub struct Jump {
    /// Approach or retract.
    pub phase: Phase,
    /// The state at the end of the branch left.
    pub from: PathPoint,
    /// None: under dead load the surfaces separate for good.
    pub to: Option<PathPoint>,
}

/// An approach-retract cycle: the equilibrium path, the steps the drive takes on it, its jumps and the energy lost.
#[derive(Clone, Debug, Serialize)]
pub struct Cycle {
    /// The Maugis parameter (the solid's, for two zones).
    pub lambda: f64,
    /// The drive.
    pub drive: Drive,
    /// The complete equilibrium path, stable and unstable parts.
    pub path: Vec<PathPoint>,
    /// For each path point: stable under this drive (the control rises along the path there).
    pub stable: Vec<bool>,
    /// The steps, approach then retract.
    pub steps: Vec<Step>,
    /// The jumps, in the order met.
    pub jumps: Vec<Jump>,
    /// Energy lost per cycle (normalised); None where the loop does not close (dead load).
    pub hysteresis: Option<f64>,
}

/// The Maugis-Dugdale cycle up to the load `max_load` (0 < max_load <= 1e12) for lambda in the
/// solver's domain ([`run`] of [`Md`]).
pub fn cycle(lambda: f64, drive: Drive, max_load: f64) -> Result<Cycle, CycleError> {
    run(&Md { lambda }, drive, max_load)
}

/// The cycle of any law under `drive` up to the load `max_load`, after the law's and the
/// drive's checks (each one line naming the value): the law's path sampled for drawing, and the
/// path the drive follows on it, exactly ([`DrivenPath`], the fits' follower: rigid grips at
/// kbar = infinity, a dead load at kbar = 0), its jumps from the exact folds to the exact
/// landings. The steps are the samples on the followed stretches and the stretches' ends. Under
/// rigid grips the loop is the exact one of the law's stretches ([`Stretches::loop_area`], the
/// DEM law's); otherwise the trapezoids over the steps.
pub fn run<L: Law + Clone>(law: &L, drive: Drive, max_load: f64) -> Result<Cycle, CycleError> {
    let mut ts = law.cycle_path(drive, max_load)?;
    let mut path: Vec<PathPoint> = ts.iter().map(|&(p, t)| law.point(p, t)).collect();
    let (Some(first), Some(top)) = (path.first().copied(), path.last().copied()) else {
        return Err(LawError::Unsupported {
            model: law.model(),
            what: "sampled path for this cycle",
        });
    };
    let free = free_before(&path, first.approach, CYCLE_POINTS);
    ts.splice(0..0, free.iter().map(|p| (Piece::Free, p.approach)));
    path.splice(0..0, free);
    let follower = DrivenPath::to_radius(law.clone(), drive.kbar(), top.a);
    let walk = Walk {
        law,
        drive,
        ts: &ts,
        path: &path,
    };
    let mut steps = Vec::new();
    let mut jumps = Vec::new();
    walk.approach(
        follower.segments(Direction::Approach),
        &mut steps,
        &mut jumps,
    );
    let separated = walk.retract(
        follower.segments(Direction::Retract),
        &mut steps,
        &mut jumps,
    );
    let hysteresis = (!separated).then(|| match drive {
        Drive::RigidGrips => Stretches::of(law, top.approach)
            .ok()
            .and_then(|s| s.loop_area(law, top.approach))
            .map_or_else(|| trapezoid_loop(&steps), |w| w.max(0.0)),
        _ => trapezoid_loop(&steps),
    });
    let u: Vec<f64> = path.iter().map(|p| control_of(p, drive)).collect();
    let n = path.len();
    let stable = (0..n)
        .map(|i| {
            if i + 1 < n {
                u[i + 1] >= u[i]
            } else {
                u[i] >= u[i - 1]
            }
        })
        .collect();
    Ok(Cycle {
        lambda: law.lambda().unwrap_or(f64::NAN),
        drive,
        path,
        stable,
        steps,
        jumps,
        hysteresis,
    })
}

/// A stretch's end as a step, unless it is the state before it to rounding: near the contact
/// piece's A -> 0 end its control is flat to rounding, and the follower's stretches there end at
/// folds of noise.
fn push_end(steps: &mut Vec<Step>, s: Step) {
    let same = |x: f64, y: f64| (x - y).abs() <= 1e-12 * (1.0 + x.abs());
    if let Some(last) = steps.last() {
        if last.phase == s.phase
            && last.point.branch == s.point.branch
            && same(last.point.load, s.point.load)
            && same(last.point.approach, s.point.approach)
        {
            return;
        }
    }
    steps.push(s);
}

/// The followed stretches turned into a cycle's steps and jumps: the path's samples on each
/// stretch, and its exact ends.
struct Walk<'a, L: Law + ?Sized> {
    law: &'a L,
    drive: Drive,
    /// Each sample's piece and parameter.
    ts: &'a [(Piece, f64)],
    path: &'a [PathPoint],
}

impl<L: Law + ?Sized> Walk<'_, L> {
    fn step(&self, phase: Phase, point: PathPoint, jump: bool) -> Step {
        Step {
            phase,
            point,
            control: control_of(&point, self.drive),
            jump,
        }
    }

    /// The samples strictly inside (lo, hi) of `piece`, in the path's order.
    fn inside(
        &self,
        piece: Piece,
        lo: f64,
        hi: f64,
    ) -> impl DoubleEndedIterator<Item = usize> + '_ {
        (0..self.ts.len())
            .filter(move |&i| self.ts[i].0 == piece && self.ts[i].1 > lo && self.ts[i].1 < hi)
    }

    /// A jump from `from` to the start of the next stretch `to`, or a continuation: a piece's
    /// end meeting the next piece's start, the same state (the pieces join within 1e-4 in the
    /// approach: the contact piece starts at A = 1e-9). A jump changes the load (rigid grips,
    /// a spring) or the approach (a dead load) by far more. A continuation onto another branch
    /// is a step, so that the branch changes between equal states.
    fn joins(
        &self,
        phase: Phase,
        from: PathPoint,
        to: PathPoint,
        steps: &mut Vec<Step>,
        jumps: &mut Vec<Jump>,
    ) {
        let load_scale = from.load.abs().max(to.load.abs()).max(1e-3);
        let jumped = (from.load - to.load).abs() > 1e-6 * load_scale
            || (from.approach - to.approach).abs() > 1e-3 * (1.0 + from.approach.abs());
        if jumped {
            jumps.push(Jump {
                phase,
                from,
                to: Some(to),
            });
        }
        if jumped || from.branch != to.branch {
            steps.push(self.step(phase, to, jumped));
        }
    }

    /// The approach: from the first sample up each stretch to its fold, a jump to the next,
    /// up to the top sample.
    fn approach(&self, segs: &[Segment], steps: &mut Vec<Step>, jumps: &mut Vec<Jump>) {
        let phase = Phase::Approach;
        let (top_i, top) = (self.ts.len() - 1, self.ts[self.ts.len() - 1].1);
        let mut last: Option<PathPoint> = None;
        for (k, seg) in segs.iter().enumerate() {
            if let Some(from) = last {
                self.joins(
                    phase,
                    from,
                    self.law.point(seg.piece, seg.t_lo),
                    steps,
                    jumps,
                );
            }
            let end = k + 1 == segs.len() || (seg.piece == Piece::Contact && seg.t_hi >= top);
            let hi = if end { top } else { seg.t_hi };
            for i in self.inside(seg.piece, seg.t_lo, hi) {
                steps.push(self.step(phase, self.path[i], false));
            }
            if end {
                steps.push(self.step(phase, self.path[top_i], false));
                return;
            }
            let p = self.law.point(seg.piece, seg.t_hi);
            push_end(steps, self.step(phase, p, false));
            last = Some(p);
        }
    }

    /// The retract: from the top sample down each stretch to its fold, a jump to the next,
    /// down to the first sample; under a dead load a jump onto the free piece separates the
    /// surfaces for good. Returns whether they separated.
    fn retract(&self, segs: &[Segment], steps: &mut Vec<Step>, jumps: &mut Vec<Jump>) -> bool {
        let phase = Phase::Retract;
        let top = self.ts[self.ts.len() - 1].1;
        steps.push(self.step(phase, self.path[self.ts.len() - 1], false));
        let mut last: Option<PathPoint> = None;
        for (k, seg) in segs.iter().enumerate() {
            if let Some(from) = last {
                if seg.piece == Piece::Free && self.drive == Drive::DeadLoad && from.load != 0.0 {
                    jumps.push(Jump {
                        phase,
                        from,
                        to: None,
                    });
                    return true;
                }
                self.joins(
                    phase,
                    from,
                    self.law.point(seg.piece, seg.t_hi),
                    steps,
                    jumps,
                );
            }
            let hi = if k == 0 { top } else { seg.t_hi };
            for i in self.inside(seg.piece, seg.t_lo, hi).rev() {
                steps.push(self.step(phase, self.path[i], false));
            }
            if !seg.t_lo.is_finite() {
                return false;
            }
            let p = self.law.point(seg.piece, seg.t_lo);
            push_end(steps, self.step(phase, p, false));
            last = Some(p);
        }
        false
    }
}

/// Why a cycle was not computed: a bad law, drive or load (the message names the quantity, the
/// value and what to give), or a two-zone curve that could not be solved.
pub type CycleError = LawError;

/// An approach-retract cycle to compute: the options of `tabor cycle` and `tabor.cycle`, checked
/// here for both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CycleSpec {
    /// The contact law.
    pub law: crate::law::ContactLaw,
    /// How the base is driven.
    pub drive: Drive,
    /// The load the approach ends at (0 < max_load <= 1e12; the two-zone law's in total-w
    /// units).
    pub max_load: f64,
}

impl CycleSpec {
    /// The cycle, after the law's and the drive's checks (each one line naming the value).
    pub fn run(&self) -> Result<Cycle, CycleError> {
        run(&self.law, self.drive, self.max_load)
    }
}

/// The loop area, integral of P dD along approach then retract (trapezoids over the samples;
/// under rigid grips [`run`] replaces it by the exact stretches' loop, which this measures
/// independently). The stretches followed both ways cancel exactly, but at large loads their
/// terms dwarf the loop (1e17 against 0.5 at a final load of 1e10): Neumaier's compensated sum
/// keeps it.
pub fn trapezoid_loop(steps: &[Step]) -> f64 {
    let (mut sum, mut comp) = (0.0f64, 0.0f64);
    for s in steps.windows(2) {
        let t =
            0.5 * (s[0].point.load + s[1].point.load) * (s[1].point.approach - s[0].point.approach);
        let next = sum + t;
        comp += if sum.abs() >= t.abs() {
            (sum - next) + t
        } else {
            (t - next) + sum
        };
        sum = next;
    }
    (sum + comp).max(0.0)
}

/// The normalised spring stiffness: k (N/m) times the approach unit over the force unit.
pub fn normalised_stiffness(k: f64, c: &crate::physics::params::Contact) -> f64 {
    k * c.approach_scale() / c.force_scale()
}

/// A normalised spring stiffness in words, with the w its units are built on: the solid's
/// (`wet` false) or the total w of solid and meniscus (docs/PHYSICS.md section 10), so that a
/// scene and its cycle say the same.
pub fn kbar_text(kbar: f64, wet: bool) -> String {
    format!(
        "kbar = {kbar:.4e} in the units of {}",
        if wet {
            "the total w (solid and meniscus)"
        } else {
            "the solid's w"
        }
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::LambdaContext;

    fn retract_jump(c: &Cycle) -> &Jump {
        c.jumps
            .iter()
            .find(|j| j.phase == Phase::Retract)
            .expect("a jump-out")
    }

    #[test]
    fn rigid_grips_jkr_jump_out_at_minus_five_sixths() {
        let c = cycle(1e3, Drive::RigidGrips, 2.0).unwrap();
        let j = retract_jump(&c);
        assert!((j.from.load + 5.0 / 6.0).abs() < 2e-3, "{}", j.from.load);
        assert!(c.hysteresis.unwrap() > 0.1);
    }

    #[test]
    fn springs_interpolate_between_grips_and_dead_load() {
        let lambda = 2.0;
        let ctx = LambdaContext::new(lambda).unwrap();
        let stiff = cycle(lambda, Drive::Spring(1e6), 2.0).unwrap();
        assert!(
            (retract_jump(&stiff).from.load - ctx.disp_pulloff().load).abs() < 5e-3,
            "{}",
            retract_jump(&stiff).from.load
        );
        let soft = cycle(lambda, Drive::Spring(1e-4), 2.0).unwrap();
        assert!(
            (retract_jump(&soft).from.load - ctx.load_pulloff.load).abs() < 5e-3,
            "{}",
            retract_jump(&soft).from.load
        );
        let dead = cycle(lambda, Drive::DeadLoad, 2.0).unwrap();
        assert!(retract_jump(&dead).to.is_none() && dead.hysteresis.is_none());
        assert!((retract_jump(&dead).from.load - ctx.load_pulloff.load).abs() < 5e-3);
    }

    #[test]
    fn hysteresis_vanishes_as_the_jumps_do() {
        let e = |l: f64, d: Drive| cycle(l, d, 2.0).unwrap().hysteresis.unwrap();
        let (small, mid, large) = (
            e(0.05, Drive::RigidGrips),
            e(1.0, Drive::RigidGrips),
            e(10.0, Drive::RigidGrips),
        );
        assert!(small < 1e-3 * large && mid < large, "{small} {mid} {large}");
        // A stiffer spring loses less than a softer one.
        assert!(e(1.0, Drive::Spring(100.0)) < e(1.0, Drive::Spring(0.5)));
    }

    #[test]
    fn a_large_final_load_keeps_the_loop() {
        // The loop lives at loads of order one: pushing the approach to 1e10 must not thin it out.
        let w = |max: f64| {
            cycle(1.0, Drive::RigidGrips, max)
                .unwrap()
                .hysteresis
                .unwrap()
        };
        let (w2, w10) = (w(2.0), w(1e10));
        assert!(w2 > 0.4 && (w10 / w2 - 1.0).abs() < 0.02, "{w2} {w10}");
        let c = cycle(1.0, Drive::RigidGrips, 1e12).unwrap();
        let j = c.jumps.iter().find(|j| j.phase == Phase::Retract).unwrap();
        let ctx = LambdaContext::new(1.0).unwrap();
        assert!(
            (j.from.load - ctx.disp_pulloff().load).abs() < 5e-3,
            "{}",
            j.from.load
        );
        assert!(cycle(1e-300, Drive::RigidGrips, 2.0).is_err());
        assert!(cycle(1.0, Drive::RigidGrips, 1e20).is_err());
        assert!(cycle(1.0, Drive::RigidGrips, -1.0).is_err());
        assert!(cycle(1.0, Drive::Spring(0.0), 2.0).is_err());
    }

    #[test]
    fn branches_meet_at_zero_radius() {
        let lambda = 0.3;
        let path = cycle(lambda, Drive::RigidGrips, 1.0).unwrap().path;
        let k = path
            .iter()
            .position(|p| p.branch == Branch::Contact)
            .unwrap();
        let (last_nc, first_c) = (path[k - 1], path[k]);
        assert!(
            (last_nc.load - first_c.load).abs() < 1e-3
                && (last_nc.approach - first_c.approach).abs() < 1e-2
        );
    }
}
