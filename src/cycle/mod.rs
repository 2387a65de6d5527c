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

use crate::law::path::{control_of, free_landing};
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

/// Where the path first comes back to `level` on a rising stretch, after index `from`.
fn landing_forward(u: &[f64], from: usize, level: f64) -> Option<(usize, f64)> {
    (from + 1..u.len() - 1)
        .find(|&j| u[j] < u[j + 1] && u[j] <= level && level <= u[j + 1])
        .map(|j| (j, (level - u[j]) / (u[j + 1] - u[j])))
}

fn landing_backward(u: &[f64], from: usize, level: f64) -> Option<(usize, f64)> {
    (0..from.saturating_sub(1))
        .rev()
        .find(|&j| u[j] < u[j + 1] && u[j] <= level && level <= u[j + 1])
        .map(|j| (j, (level - u[j]) / (u[j + 1] - u[j])))
}

fn lerp(a: &PathPoint, b: &PathPoint, t: f64) -> PathPoint {
    let l = |x: f64, y: f64| x + (y - x) * t;
    PathPoint {
        branch: if t < 0.5 { a.branch } else { b.branch },
        approach: l(a.approach, b.approach),
        load: l(a.load, b.load),
        a: l(a.a, b.a),
        c: l(a.c, b.c),
    }
}

/// The Maugis-Dugdale cycle up to the load `max_load` (0 < max_load <= 1e12) for lambda in the
/// solver's domain ([`run`] of [`Md`]).
pub fn cycle(lambda: f64, drive: Drive, max_load: f64) -> Result<Cycle, CycleError> {
    run(&Md { lambda }, drive, max_load)
}

/// The cycle of any law under `drive` up to the load `max_load`, after the law's and the
/// drive's checks (each one line naming the value): the drive's steps, jumps and loop on the
/// law's sampled path, each retract jump from the contact branch put at the law's exact fold
/// (the samples only bracket it; a landing on the free branch moves with it). Under rigid grips
/// the loop is the exact one of the law's stretches ([`Stretches::loop_area`], the DEM law's):
/// the samples' trapezoids fall short where a piece bends between them (1.7% for the two-zone
/// law (0.01, 5, 0.3)); the trapezoids stand where the stretches are not found.
pub fn run<L: Law + ?Sized>(law: &L, drive: Drive, max_load: f64) -> Result<Cycle, CycleError> {
    let path = law.cycle_path(drive, max_load)?;
    let f = follow(&path, drive);
    let mut jumps = f.jumps;
    for j in jumps.iter_mut().filter(|j| j.phase == Phase::Retract) {
        // A landing on the free surfaces moves with the fold (off the zone alone the sampled
        // landing there carries no load, whatever its label; a landing elsewhere is left
        // sampled).
        let (exact, lands_free) = match j.from.branch {
            Branch::Contact => (
                law.fold(drive, &j.from),
                j.to.is_some_and(|t| t.branch == Branch::Free),
            ),
            Branch::NonContact if j.to.is_none_or(|t| t.load == 0.0) => {
                (non_contact_fold(law, drive, &j.from), true)
            }
            _ => (None, false),
        };
        if let Some(p) = exact {
            if let Some(to) = j.to.as_mut().filter(|_| lands_free) {
                to.approach = free_landing(&p, drive);
            }
            j.from = p;
        }
    }
    let hysteresis = f.hysteresis.map(|sampled| match (drive, path.last()) {
        (Drive::RigidGrips, Some(top)) => Stretches::of(law, top.approach)
            .ok()
            .and_then(|s| s.loop_area(law, top.approach))
            .map_or(sampled, |w| w.max(0.0)),
        _ => sampled,
    });
    Ok(Cycle {
        lambda: law.lambda().unwrap_or(f64::NAN),
        drive,
        path,
        stable: f.stable,
        steps: f.steps,
        jumps,
        hysteresis,
    })
}

/// The fold of the non-contact piece (the zone alone, t = C) under `drive` near the sampled
/// jump `near`: where the control's slope along the piece changes sign, from negative below to
/// positive above, bracketed outward from the sample and bisected. None where no sign change
/// lies within 25% of its C (the samples are sparse there at small lambda: 4% off at 0.1).
fn non_contact_fold<L: Law + ?Sized>(law: &L, drive: Drive, near: &PathPoint) -> Option<PathPoint> {
    let slope = |t: f64| {
        let p = law.state(Piece::NonContact, t);
        match drive {
            Drive::RigidGrips => p.dapproach,
            Drive::Spring(k) => p.dapproach + p.dload / k,
            Drive::DeadLoad => p.dload,
        }
    };
    let t = near.c;
    if !(t > 0.0) {
        return None;
    }
    let mut h = 1e-4 * t;
    while h <= 0.25 * t {
        let (lo, hi) = ((t - h).max(0.0), t + h);
        if slope(lo) < 0.0 && slope(hi) > 0.0 {
            let c = crate::numeric::root::bisect_sign(slope, lo, hi);
            let p = law.state(Piece::NonContact, c);
            return Some(PathPoint {
                branch: Branch::NonContact,
                approach: p.approach,
                load: p.load,
                a: 0.0,
                c,
            });
        }
        h *= 2.0;
    }
    None
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

/// What a drive makes of an equilibrium path (any contact law's): the steps followed, the jumps
/// at the folds of the control, the loop's area and each point's stability.
struct Followed {
    steps: Vec<Step>,
    jumps: Vec<Jump>,
    hysteresis: Option<f64>,
    stable: Vec<bool>,
}

/// The approach: follow the path while the control rises (flat counts, as on the free segment
/// under dead load); at a fold, jump forward to where the control is reached again.
fn follow_approach(path: &[PathPoint], u: &[f64], steps: &mut Vec<Step>, jumps: &mut Vec<Jump>) {
    let n = path.len();
    let mut i = 0;
    let mut jumped = false;
    loop {
        steps.push(Step {
            phase: Phase::Approach,
            point: path[i],
            control: u[i],
            jump: jumped,
        });
        jumped = false;
        if i + 1 >= n {
            break;
        }
        if u[i + 1] >= u[i] {
            i += 1;
            continue;
        }
        match landing_forward(u, i, u[i]) {
            Some((j, t)) => {
                let to = lerp(&path[j], &path[j + 1], t);
                jumps.push(Jump {
                    phase: Phase::Approach,
                    from: path[i],
                    to: Some(to),
                });
                steps.push(Step {
                    phase: Phase::Approach,
                    point: to,
                    control: u[i],
                    jump: true,
                });
                i = j + 1;
            }
            None => break,
        }
    }
}

/// The retract: back down the path while the control falls; at a fold, jump back. Returns
/// whether the surfaces separated for good.
fn follow_retract(
    path: &[PathPoint],
    u: &[f64],
    steps: &mut Vec<Step>,
    jumps: &mut Vec<Jump>,
) -> bool {
    let mut i = path.len() - 1;
    let mut jumped = false;
    loop {
        steps.push(Step {
            phase: Phase::Retract,
            point: path[i],
            control: u[i],
            jump: jumped,
        });
        jumped = false;
        if i == 0 {
            return false;
        }
        if u[i - 1] <= u[i] {
            i -= 1;
            continue;
        }
        match landing_backward(u, i, u[i]) {
            Some((j, t)) => {
                let to = lerp(&path[j], &path[j + 1], t);
                jumps.push(Jump {
                    phase: Phase::Retract,
                    from: path[i],
                    to: Some(to),
                });
                steps.push(Step {
                    phase: Phase::Retract,
                    point: to,
                    control: u[i],
                    jump: true,
                });
                i = j;
            }
            None => {
                jumps.push(Jump {
                    phase: Phase::Retract,
                    from: path[i],
                    to: None,
                });
                return true;
            }
        }
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

/// The shared part of every law's cycle: the path followed under `drive`.
fn follow(path: &[PathPoint], drive: Drive) -> Followed {
    let u: Vec<f64> = path.iter().map(|p| control_of(p, drive)).collect();
    let n = path.len();
    let mut steps = Vec::new();
    let mut jumps = Vec::new();
    follow_approach(path, &u, &mut steps, &mut jumps);
    let separated = follow_retract(path, &u, &mut steps, &mut jumps);
    let hysteresis = (!separated).then(|| trapezoid_loop(&steps));
    let stable = (0..n)
        .map(|i| {
            if i + 1 < n {
                u[i + 1] >= u[i]
            } else {
                u[i] >= u[i - 1]
            }
        })
        .collect();
    Followed {
        steps,
        jumps,
        hysteresis,
        stable,
    }
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
    use crate::law::md::equilibrium_path;
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
        let path = equilibrium_path(lambda, 1.0, 100);
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
