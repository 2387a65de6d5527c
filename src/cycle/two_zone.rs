//! The approach-retract cycle of the two-zone law (the solid's Dugdale zone plus a water
//! meniscus, docs/PHYSICS.md section 10), through the same stability, jump and loop-area code as
//! the MD cycle: only the equilibrium path differs. In the total-w units of section 10: free until
//! the approach reaches `-H_L` (the longer range), the longer zone's disc alone until the axis gap
//! is the shorter range, both discs until the axis gap closes, then the contact curve.
//! A single zone, or two zones of one range, is MD itself and gives MD's cycle.

use super::{check_drive, control_of, run, Branch, Cycle, Drive, Jump, Md, PathLaw};
use super::{PathPoint, Phase};
use crate::physics::two_zone::Zones;
use crate::physics::two_zone::{
    non_contact_both, non_contact_ends, non_contact_single, NonContactPoint, Shape,
};
use crate::solver::two_zone::{TwoZoneContext, TwoZoneState, ZonesError};
use crate::solver::Status;

/// Points per stretch of the path, as for MD.
const N: usize = 400;

/// The cycle of the solid (Maugis parameter `lambda_s`) with a second zone of stress ratio `rho`
/// and range ratio `eta`, up to the load `max_load` (total-w units). `Cycle::lambda` is the
/// solid's; `PathPoint::c` is the outer radius of the longer-range zone.
pub fn cycle(
    lambda_s: f64,
    rho: f64,
    eta: f64,
    drive: Drive,
    max_load: f64,
) -> Result<Cycle, ZonesError> {
    let err = |e: crate::solver::SolveError| ZonesError(e.to_string());
    let zones = Zones::from_ratios(lambda_s, rho, eta)?;
    crate::solver::domain::check_lambda(lambda_s).map_err(|e| err(e.into()))?;
    check_drive(drive, max_load).map_err(err)?;
    match zones.shape() {
        // One zone, or two of one range: MD itself, reported with the solid's lambda.
        Shape::Single { lambda } => {
            crate::solver::domain::check_lambda(lambda).map_err(|e| err(e.into()))?;
            let Ok(mut c) = run(&Md(lambda), drive, max_load);
            c.lambda = lambda_s;
            Ok(c)
        }
        Shape::Two { long } => {
            let ctx = TwoZoneContext::new(zones).map_err(|s| failed("its pull-offs", s))?;
            run(
                &TwoZones {
                    lambda_s,
                    ctx,
                    long,
                },
                drive,
                max_load,
            )
        }
    }
}

/// The two-zone law with both zones; `long` is the longer-range zone.
struct TwoZones {
    lambda_s: f64,
    ctx: TwoZoneContext,
    long: usize,
}

impl PathLaw for TwoZones {
    type Error = ZonesError;
    fn lambda(&self) -> f64 {
        self.lambda_s
    }
    fn path(&self, max_load: f64) -> Result<Vec<PathPoint>, ZonesError> {
        two_zone_path(&self.ctx, self.long, max_load)
    }
    fn refine_jumps(&self, drive: Drive, jumps: &mut [Jump]) {
        refine_two_zone(&self.ctx, self.long, drive, jumps)
    }
}

fn failed(what: &str, s: Status) -> ZonesError {
    ZonesError(format!(
        "the two-zone contact curve could not be solved for {what} (status {}): try ratios \
         closer to 1 or a lambda nearer 1",
        s.name()
    ))
}

fn nc_point(p: &NonContactPoint, long: usize) -> PathPoint {
    PathPoint {
        branch: Branch::NonContact,
        approach: p.approach,
        load: p.load,
        a: 0.0,
        c: p.c[long],
    }
}

fn contact_point(s: &TwoZoneState, long: usize) -> PathPoint {
    PathPoint {
        branch: Branch::Contact,
        approach: s.approach,
        load: s.load,
        a: s.a,
        c: s.c[long],
    }
}

/// The ends of the non-contact branch's two stretches ([`non_contact_ends`] of its zones).
pub(crate) fn non_contact_ends_of(ctx: &TwoZoneContext) -> Result<(f64, f64), ZonesError> {
    non_contact_ends(&ctx.zones).ok_or_else(|| failed("the discs", Status::NotConverged))
}

/// The non-contact branch: the longer zone's disc alone, then both discs.
fn non_contact_path(ctx: &TwoZoneContext, long: usize) -> Result<Vec<PathPoint>, ZonesError> {
    let z = &ctx.zones;
    let (c1, c2) = non_contact_ends_of(ctx)?;
    let mut path: Vec<PathPoint> = (0..N)
        .map(|i| nc_point(&non_contact_single(z, c1 * i as f64 / (N - 1) as f64), long))
        .collect();
    for i in 1..N {
        let p = non_contact_both(z, c2 * i as f64 / (N - 1) as f64)
            .ok_or_else(|| failed("the two discs", Status::NotConverged))?;
        path.push(nc_point(&p, long));
    }
    Ok(path)
}

/// The complete two-zone path (two ranges): free, non-contact, contact up to `max_load`.
fn two_zone_path(
    ctx: &TwoZoneContext,
    long: usize,
    max_load: f64,
) -> Result<Vec<PathPoint>, ZonesError> {
    let mut path = non_contact_path(ctx, long)?;
    let radius_at = |p: f64| {
        let s = ctx.state_at_load(p);
        (s.status == Status::Ok)
            .then_some(s.a)
            .ok_or_else(|| failed(&format!("the load {p}"), s.status))
    };
    let a_max = radius_at(max_load)?;
    // As for MD: 2N radii up to the radius at load 10, N more beyond, spaced geometrically.
    let a_mid = a_max.min(radius_at(10.0)?);
    let mut radii: Vec<f64> = (1..=2 * N)
        .map(|i| a_mid * (i as f64 / (2 * N) as f64).powf(1.5))
        .collect();
    if a_max > a_mid {
        radii.extend((1..=N).map(|i| a_mid * (a_max / a_mid).powf(i as f64 / N as f64)));
    }
    for a in radii {
        let s = ctx.state_at_radius(a);
        if s.status != Status::Ok {
            return Err(failed(&format!("the contact radius {a}"), s.status));
        }
        path.push(contact_point(&s, long));
    }
    let d0 = path[0].approach;
    let lowest = path
        .iter()
        .map(|p| p.approach + p.load.min(0.0) * 1e3)
        .fold(d0, f64::min);
    let free = (0..N).map(|i| PathPoint {
        branch: Branch::Free,
        approach: lowest - 1.0 + (d0 - lowest + 1.0) * i as f64 / N as f64,
        load: 0.0,
        a: 0.0,
        c: 0.0,
    });
    Ok(free.chain(path).collect())
}

/// Puts the retract's jump from the contact branch at the exact fold of the control (rigid
/// grips: the displacement-controlled pull-off, dead load: the load-controlled one, a spring:
/// where `dPbar/dDbar = -kbar`, [`TwoZoneContext::spring_fold`]); the sampled path only
/// brackets it. A landing on the free branch moves with it, as in the MD cycle.
fn refine_two_zone(ctx: &TwoZoneContext, long: usize, drive: Drive, jumps: &mut [Jump]) {
    for j in jumps
        .iter_mut()
        .filter(|j| j.phase == Phase::Retract && j.from.branch == Branch::Contact)
    {
        let exact = match drive {
            Drive::RigidGrips => ctx.disp_pulloff,
            Drive::DeadLoad => ctx.load_pulloff,
            Drive::Spring(k) => match ctx.spring_fold(k, j.from.a) {
                Some(f) => f,
                None => continue,
            },
        };
        if exact.at_zero_radius() {
            continue;
        }
        j.from = PathPoint {
            branch: Branch::Contact,
            approach: exact.approach,
            load: exact.load,
            a: exact.a,
            c: exact.c[long],
        };
        // On the free branch (no load) at the control of the jump: a spring's base, else the
        // approach.
        if let Some(to) = j.to.as_mut().filter(|t| t.branch == Branch::Free) {
            to.approach = match drive {
                Drive::Spring(_) => control_of(&j.from, drive),
                _ => exact.approach,
            };
        }
    }
}
