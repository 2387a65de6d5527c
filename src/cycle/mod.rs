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

use crate::physics::md::{curve_point, non_contact_point, zero_radius_end};
use crate::solver::context::x_at_radius;
use crate::solver::LambdaContext;
use serde::Serialize;

pub mod two_zone;

/// How the cycle is driven: the base held by rigid grips, a dead load, or a spring between them.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Drive {
    /// Displacement control.
    RigidGrips,
    /// Load control.
    DeadLoad,
    /// A spring of normalised stiffness kbar in series.
    Spring(f64),
}

/// Which part of the equilibrium path a point is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Branch {
    /// No force: the surfaces farther apart than the force range.
    Free,
    /// The Dugdale zone alone (A = 0).
    NonContact,
    /// In contact: the Maugis-Dugdale curve.
    Contact,
}

impl Branch {
    /// The branch's name in tables and JSON (`free`, `non_contact`, `contact`).
    pub fn name(self) -> &'static str {
        match self {
            Branch::Free => "free",
            Branch::NonContact => "non_contact",
            Branch::Contact => "contact",
        }
    }
}

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

/// One equilibrium state on the path (normalised units).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct PathPoint {
    /// The branch it is on.
    pub branch: Branch,
    /// The approach (normalised).
    pub approach: f64,
    /// The load (normalised, compressive positive).
    pub load: f64,
    /// The contact radius (0 off contact).
    pub a: f64,
    /// Normalised radius of the cohesive zone: C on the non-contact branch, m A in contact.
    pub c: f64,
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

fn control_of(p: &PathPoint, drive: Drive) -> f64 {
    match drive {
        Drive::RigidGrips => p.approach,
        Drive::DeadLoad => p.load,
        Drive::Spring(k) => p.approach + p.load / k,
    }
}

/// The complete equilibrium path up to load `max_load`: free, non-contact, contact.
/// `lambda` must be in the solver's domain (see [`cycle`]).
pub fn equilibrium_path(lambda: f64, max_load: f64, n: usize) -> Vec<PathPoint> {
    let end = zero_radius_end(lambda);
    let (_, d0) = non_contact_point(lambda, 0.0);
    let mut path = Vec::with_capacity(3 * n);
    for i in 0..n {
        let c = end.c * i as f64 / (n - 1) as f64;
        let (p, d) = non_contact_point(lambda, c);
        path.push(PathPoint {
            branch: Branch::NonContact,
            approach: d,
            load: p,
            a: 0.0,
            c,
        });
    }
    let Ok(ctx) = LambdaContext::new(lambda) else {
        return Vec::new();
    };
    let a_max = ctx.solve_load(max_load).a;
    // The jumps happen at loads of order one: the branch up to the radius at load 10 gets 2n
    // points however large `max_load` is, and beyond it n more, spaced geometrically.
    let a_mid = a_max.min(ctx.solve_load(10.0).a);
    let mut radii: Vec<f64> = (1..=2 * n)
        .map(|i| a_mid * (i as f64 / (2 * n) as f64).powf(1.5))
        .collect();
    if a_max > a_mid {
        radii.extend((1..=n).map(|i| a_mid * (a_max / a_mid).powf(i as f64 / n as f64)));
    }
    for a in radii {
        // Dense near A = 0, where the contact branch leaves the non-contact one.
        let mu = x_at_radius(lambda, a).exp();
        let p = curve_point(lambda, mu);
        path.push(PathPoint {
            branch: Branch::Contact,
            approach: p.approach,
            load: p.load,
            a: p.a,
            c: (p.m_minus_1 + 1.0) * p.a,
        });
    }
    // The free segment before first contact of the force zones (no force), long enough for any
    // spring jump to land on.
    let lowest = path
        .iter()
        .map(|p| p.approach + p.load.min(0.0) * 1e3)
        .fold(d0, f64::min);
    let free: Vec<PathPoint> = (0..n)
        .map(|i| {
            let d = lowest - 1.0 + (d0 - lowest + 1.0) * i as f64 / n as f64;
            PathPoint {
                branch: Branch::Free,
                approach: d,
                load: 0.0,
                a: 0.0,
                c: 0.0,
            }
        })
        .collect();
    free.into_iter().chain(path).collect()
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

/// The checks every law's cycle shares: the final load and the spring.
fn check_drive(drive: Drive, max_load: f64) -> Result<(), crate::solver::SolveError> {
    if !(max_load > 0.0 && max_load <= 1e12) {
        return Err(crate::solver::domain::DomainError {
            name: "the largest load of the approach",
            value: max_load,
            range: "(0, 1e12]",
            hint: "the approach must end in compression",
        }
        .into());
    }
    if let Drive::Spring(k) = drive {
        if !(k > 0.0 && k.is_finite()) {
            return Err(crate::solver::domain::DomainError {
                name: "the spring stiffness kbar",
                value: k,
                range: "(0, inf)",
                hint: "give a positive, finite stiffness",
            }
            .into());
        }
    }
    Ok(())
}

/// The cycle up to the load `max_load` (0 < max_load <= 1e12) for lambda in the solver's
/// domain.
pub fn cycle(lambda: f64, drive: Drive, max_load: f64) -> Result<Cycle, crate::solver::SolveError> {
    crate::solver::domain::check_lambda(lambda)?;
    check_drive(drive, max_load)?;
    let Ok(c) = run(&Md(lambda), drive, max_load);
    Ok(c)
}

/// What a cycle needs of a contact law: its complete equilibrium path up to a load, and its
/// exact jump-outs (the path's samples only bracket them). The drive, the stability, the jumps
/// and the loop's area are the same for every law (`run`); a law implements this in its own
/// module (MD here, the two-zone law in `two_zone.rs`).
pub(crate) trait PathLaw {
    /// Why the law's path could not be solved.
    type Error;
    /// The Maugis parameter reported with the cycle (the solid's).
    fn lambda(&self) -> f64;
    /// The path from free to `max_load`, its parameter rising along it.
    fn path(&self, max_load: f64) -> Result<Vec<PathPoint>, Self::Error>;
    /// Puts the jump-outs where the law's folds are.
    fn refine_jumps(&self, drive: Drive, jumps: &mut [Jump]);
}

/// The Maugis-Dugdale law at this lambda (checked by the caller).
struct Md(f64);

impl PathLaw for Md {
    type Error = std::convert::Infallible;
    fn lambda(&self) -> f64 {
        self.0
    }
    fn path(&self, max_load: f64) -> Result<Vec<PathPoint>, Self::Error> {
        Ok(equilibrium_path(self.0, max_load, 400))
    }
    fn refine_jumps(&self, drive: Drive, jumps: &mut [Jump]) {
        refine_jump_outs(self.0, drive, jumps)
    }
}

/// The cycle of any law under `drive` (law and drive checked).
fn run<L: PathLaw>(law: &L, drive: Drive, max_load: f64) -> Result<Cycle, L::Error> {
    let path = law.path(max_load)?;
    let f = follow(&path, drive);
    let mut jumps = f.jumps;
    law.refine_jumps(drive, &mut jumps);
    Ok(Cycle {
        lambda: law.lambda(),
        drive,
        path,
        stable: f.stable,
        steps: f.steps,
        jumps,
        hysteresis: f.hysteresis,
    })
}

/// Why a cycle was not computed: a bad law, drive or load (the message names the quantity, the
/// value and what to give), or a two-zone curve that could not be solved.
#[derive(Debug, thiserror::Error)]
pub enum CycleError {
    /// The MD law or the drive.
    #[error(transparent)]
    Solve(#[from] crate::solver::SolveError),
    /// The two-zone law.
    #[error(transparent)]
    Zones(#[from] crate::solver::two_zone::ZonesError),
}

/// An approach-retract cycle to compute: the options of `tabor cycle` and `tabor.cycle`, checked
/// here for both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CycleSpec {
    /// The contact law.
    pub law: crate::physics::model::ContactLaw,
    /// How the base is driven.
    pub drive: Drive,
    /// The load the approach ends at (0 < max_load <= 1e12; the two-zone law's in total-w
    /// units).
    pub max_load: f64,
}

impl CycleSpec {
    /// The cycle, after the law's and the drive's checks (each one line naming the value).
    pub fn run(&self) -> Result<Cycle, CycleError> {
        use crate::physics::model::ContactLaw;
        Ok(match self.law {
            ContactLaw::Md { lambda } => cycle(lambda, self.drive, self.max_load)?,
            ContactLaw::SolidAndMeniscus {
                lambda,
                stress_ratio,
                range_ratio,
            } => two_zone::cycle(lambda, stress_ratio, range_ratio, self.drive, self.max_load)?,
        })
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

/// The loop area, integral of P dD along approach then retract (trapezoids).
/// The stretches followed both ways cancel exactly, but at large loads their terms dwarf the
/// loop (1e17 against 0.5 at a final load of 1e10): Neumaier's compensated sum keeps it.
fn loop_area(steps: &[Step]) -> f64 {
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
    let hysteresis = (!separated).then(|| loop_area(&steps));
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

/// The retract's jump from the contact branch is a fold of the exact curve: under rigid grips
/// the minimum of the approach, under dead load the minimum of the load (the pull-offs of the
/// solver's context), and under a spring where `dPbar/dDbar = -kbar`. The path's samples only
/// bracket it; this puts the jump where it is, to the solver's precision (the landing on the
/// free branch moves with it).
fn refine_jump_outs(lambda: f64, drive: Drive, jumps: &mut [Jump]) {
    let Ok(ctx) = LambdaContext::new(lambda) else {
        return;
    };
    let at = |a: f64| {
        let p = curve_point(lambda, x_at_radius(lambda, a).exp());
        PathPoint {
            branch: Branch::Contact,
            approach: p.approach,
            load: p.load,
            a: p.a,
            c: (p.m_minus_1 + 1.0) * p.a,
        }
    };
    for j in jumps
        .iter_mut()
        .filter(|j| j.phase == Phase::Retract && j.from.branch == Branch::Contact)
    {
        let exact = match drive {
            Drive::RigidGrips => ctx.disp_pulloff(),
            Drive::DeadLoad => ctx.load_pulloff,
            Drive::Spring(k) => {
                // Where the control's slope along the curve changes sign, by bisection in A
                // around the sampled fold (the control rises with A on the stable side).
                let slope = |a: f64| {
                    let p = curve_point(lambda, x_at_radius(lambda, a).exp());
                    p.dapproach_dmu + p.dload_dmu / k
                };
                let (mut lo, mut hi) = (0.8 * j.from.a, 1.25 * j.from.a + 1e-300);
                if (slope(lo) > 0.0) == (slope(hi) > 0.0) {
                    continue;
                }
                for _ in 0..200 {
                    let m = 0.5 * (lo + hi);
                    if (slope(m) > 0.0) == (slope(lo) > 0.0) {
                        lo = m;
                    } else {
                        hi = m;
                    }
                }
                let p = at(0.5 * (lo + hi));
                j.from = p;
                if let Some(to) = j.to.as_mut().filter(|t| t.branch == Branch::Free) {
                    to.approach = p.approach + p.load / k;
                }
                continue;
            }
        };
        if exact.a > 0.0 {
            let p = at(exact.a);
            if let Some(to) = j.to.as_mut().filter(|t| t.branch == Branch::Free) {
                to.approach = p.approach;
            }
            j.from = p;
        }
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
