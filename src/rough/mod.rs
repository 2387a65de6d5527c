//! Rough surfaces (docs/PHYSICS.md section 9): Greenwood-Williamson summits of Gaussian height,
//! each under the separation of a rigid flat with its own history (free, the non-contact
//! branch, contact) through an approach and a retract. One model ([`Rough`]) sums any summit
//! law ([`SummitLaw`]): the exact Maugis-Dugdale sphere ([`Summit`]) here, the two-zone summit
//! of section 10 in [`wet`].
//!
//! Units are one summit's (Johnson and Greenwood): loads per summit in `pi w R`, separations and
//! sigma in the approach unit `(pi^2 w^2 R / K^2)^(1/3)`.

pub mod ensemble;
pub mod lambda_table;
pub mod map;
pub mod scene;
pub mod wet;

use crate::error::Message;
use crate::numeric::golden::{Golden, Ties, Width};
use crate::physics::domain::{short, DomainError};
use crate::physics::md::{zero_radius_end, LAMBDA_D};
use crate::solver::{LambdaContext, SolveError, Status};
use serde::Serialize;
use std::cell::Cell;
use std::f64::consts::PI;

/// The Gaussian's mass beyond this many sigma (4e-33) is dropped.
pub(crate) const Z_CUT: f64 = 12.0;
/// The default largest separation: beyond `Z_FREE` sigma above the Dugdale range the summits
/// that still feel the flat carry a fraction 1e-17 of them.
pub(crate) const Z_FREE: f64 = 8.5;
/// Relative error each quadrature piece must reach (its estimate).
const QUAD_TOL: f64 = 1e-13;
/// Most points of a separation sweep, as for an explicit ensemble: a few thousand separations
/// draw and tabulate any cycle, and each costs about 3 ms (dry) to 7 ms (wet) of CPU time, so
/// this bound keeps a run within about a minute on two cores (100000 took minutes).
pub const POINTS_MAX: usize = 10_000;
/// The deepest press of the flat, in sigma (either way) about the mean summit plane: pressed 6
/// sigma below it, all but 1e-9 of the summits have touched, so a deeper press changes the
/// retract by less than that (a summit's retract depends on whether it touched, not on how
/// deep); the rough map's quadrature keeps heights to 7 sigma. One range for `rough-pulloff`
/// and `rough-map`.
pub const PRESS_SIGMAS_MAX: f64 = 6.0;
/// Largest separation of a cycle (approach units).
pub const SEPARATION_MAX: f64 = 1e6;
/// Largest sigma of a rough surface (approach units).
pub const SIGMA_MAX: f64 = 1e4;

/// Which branch a summit is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SummitBranch {
    /// Not touching, out of the force's reach.
    Free,
    /// The Dugdale zone alone (A = 0).
    NonContact,
    /// In contact.
    Contact,
}

/// One summit's branches and the approaches where it jumps between them (section 9).
#[derive(Debug)]
pub struct Summit {
    /// The summit's Maugis parameter.
    pub lambda: f64,
    ctx: LambdaContext,
    /// The Dugdale range, 2 / (pi lambda).
    pub h0: f64,
    /// The non-contact branch's lowest approach is at C = C* = 8 lambda / (3 pi).
    pub c_star: f64,
    /// The A -> 0 end of the contact branch: C there, and its approach.
    pub c_end: f64,
    /// The approach of the contact branch's A -> 0 end.
    pub delta_a0: f64,
    /// Entry into contact on the approach.
    pub delta_in: f64,
    /// The contact branch's lowest approach (rigid-grip jump-out).
    pub delta_out: f64,
    /// The stable non-contact branch's lowest approach (None above lambda_D: no stable branch).
    pub delta_nc: Option<f64>,
}

impl Summit {
    /// The summit of Maugis parameter `lambda`: its context and the approaches where it jumps.
    pub fn new(lambda: f64) -> Result<Summit, SolveError> {
        let ctx = LambdaContext::new(lambda)?;
        let end = zero_radius_end(lambda);
        let h0 = 2.0 / (PI * lambda);
        let c_star = 8.0 * lambda / (3.0 * PI);
        let delta_out = ctx.disp_pulloff().approach;
        let stable_nc = lambda < LAMBDA_D && c_star < end.c;
        Ok(Summit {
            lambda,
            h0,
            c_star,
            c_end: end.c,
            delta_a0: end.approach,
            delta_in: if stable_nc {
                end.approach.max(-h0)
            } else {
                -h0
            },
            delta_out,
            delta_nc: stable_nc.then(|| -h0 - 0.5 * c_star * c_star),
            ctx,
        })
    }

    /// The load on the stable contact branch at approach `delta >= delta_out`, and A there.
    pub fn contact(&self, delta: f64) -> Option<(f64, f64)> {
        let s = self.ctx.solve_approach(delta.max(self.delta_out));
        (s.status == Status::Ok).then_some((s.load, s.a))
    }

    /// The load on the stable non-contact branch at approach `delta >= delta_nc`.
    pub fn non_contact(&self, delta: f64) -> f64 {
        let root = (self.c_star * self.c_star + 2.0 * (delta + self.h0)).max(0.0);
        let c = (self.c_star + root.sqrt()).min(self.c_end);
        -(PI * self.lambda / 2.0) * c * c
    }

    /// The branch on the approach at approach `delta` (coming from far away).
    pub fn approach_branch(&self, delta: f64) -> SummitBranch {
        if delta >= self.delta_in {
            SummitBranch::Contact
        } else if delta >= -self.h0 {
            SummitBranch::NonContact
        } else {
            SummitBranch::Free
        }
    }

    /// The branch on the retract at approach `delta`, after the largest approach `delta_max`.
    pub fn retract_branch(&self, delta: f64, delta_max: f64) -> SummitBranch {
        if delta_max >= self.delta_in && delta >= self.delta_out {
            return SummitBranch::Contact;
        }
        match self.delta_nc {
            Some(lo) if delta_max >= -self.h0 && delta >= lo => SummitBranch::NonContact,
            _ => SummitBranch::Free,
        }
    }

    /// The load on `branch` at approach `delta` (None where the solver failed).
    pub fn load(&self, branch: SummitBranch, delta: f64) -> Option<f64> {
        match branch {
            SummitBranch::Free => Some(0.0),
            SummitBranch::NonContact => Some(self.non_contact(delta)),
            SummitBranch::Contact => self.contact(delta).map(|c| c.0),
        }
    }

    /// The single summit's load-controlled pull-off (Pbar_c).
    pub fn smooth_pulloff(&self) -> f64 {
        self.ctx.load_pulloff.load
    }

    /// The approaches where a summit's load jumps or has a fold.
    fn marks(&self) -> Vec<f64> {
        let mut m = vec![-self.h0, self.delta_in, self.delta_out, self.delta_a0];
        m.extend(self.delta_nc);
        m
    }
}

/// A summit's law as the rough model reads it (docs/PHYSICS.md sections 9 and 10.1): where a
/// summit is on its path under rigid grips (a state: its branch, or its stretch) on the approach
/// and on the retract, its load there, and the approaches where the load jumps or folds. One
/// rough model ([`Rough`]) sums any such law over the heights: the dry Maugis-Dugdale summit
/// ([`Summit`]) and the wet one of two zones ([`wet::WetSummit`]).
pub trait SummitLaw: Sync {
    /// Where a summit is on its path.
    type State: Copy;
    /// The Maugis parameter a failure is reported with.
    fn lambda(&self) -> f64;
    /// The state on the approach at approach `delta` (coming from far away).
    fn approach_state(&self, delta: f64) -> Self::State;
    /// The state on the retract at approach `delta`, after the deepest approach `delta_max`.
    fn retract_state(&self, delta: f64, delta_max: f64) -> Self::State;
    /// The branch of a state.
    fn branch_of(&self, s: Self::State) -> SummitBranch;
    /// The load in state `s` at approach `delta` (None where the solver failed).
    fn load_in(&self, s: Self::State, delta: f64) -> Option<f64>;
    /// The approaches where the load jumps or folds (placed at the flat's separation).
    fn marks(&self) -> Vec<f64>;
    /// The approaches where the retract's state changes with the deepest approach (placed at
    /// the smallest separation).
    fn retract_marks(&self) -> Vec<f64>;
    /// How far beyond its height a summit feels the flat, on the approach or the retract.
    fn reach(&self) -> f64;
    /// The single summit's load-controlled pull-off.
    fn smooth_pulloff(&self) -> f64;
    /// The mean of A^2 over all summits of heights N(0, sigma^2) at separation `d`.
    fn mean_area(&self, sigma: f64, leg: Leg, d: f64) -> Result<f64, RoughError>;
    /// The energy lost per summit in a cycle from `d_max` down to `d_min` and back.
    fn hysteresis(&self, sigma: f64, d_min: f64, d_max: f64) -> Result<f64, RoughError>;
}

impl SummitLaw for Summit {
    type State = SummitBranch;

    fn lambda(&self) -> f64 {
        self.lambda
    }

    fn approach_state(&self, delta: f64) -> SummitBranch {
        self.approach_branch(delta)
    }

    fn retract_state(&self, delta: f64, delta_max: f64) -> SummitBranch {
        self.retract_branch(delta, delta_max)
    }

    fn branch_of(&self, s: SummitBranch) -> SummitBranch {
        s
    }

    fn load_in(&self, s: SummitBranch, delta: f64) -> Option<f64> {
        self.load(s, delta)
    }

    fn marks(&self) -> Vec<f64> {
        Summit::marks(self)
    }

    fn retract_marks(&self) -> Vec<f64> {
        vec![self.delta_in, -self.h0]
    }

    fn reach(&self) -> f64 {
        [self.h0, -self.delta_out, -self.delta_nc.unwrap_or(0.0)]
            .into_iter()
            .fold(0.0, f64::max)
    }

    fn smooth_pulloff(&self) -> f64 {
        Summit::smooth_pulloff(self)
    }

    fn mean_area(&self, sigma: f64, leg: Leg, d: f64) -> Result<f64, RoughError> {
        let s = sigma;
        let failed = Cell::new(false);
        let mut total = 0.0;
        for w in cuts(self, sigma, leg, d).windows(2) {
            let (t0, t1) = (w[0], w[1]);
            if state_at(self, leg, 0.5 * (t0 + t1) * s, d) != SummitBranch::Contact {
                continue;
            }
            let f = |t: f64| {
                let g = (-0.5 * t * t).exp() / (2.0 * PI).sqrt();
                match self.contact(t * s - d) {
                    Some((_, a)) => g * a * a,
                    None => {
                        failed.set(true);
                        0.0
                    }
                }
            };
            total += integrate(&f, t0, t1).0;
        }
        if failed.get() {
            return Err(RoughError::Failed(d, self.lambda));
        }
        Ok(total)
    }

    fn hysteresis(&self, sigma: f64, d_min: f64, d_max: f64) -> Result<f64, RoughError> {
        dry_hysteresis(self, sigma, d_min, d_max)
    }
}

/// The state of the summit of height `z` at separation `d`.
fn state_at<S: SummitLaw>(summit: &S, leg: Leg, z: f64, d: f64) -> S::State {
    match leg {
        Leg::Approach => summit.approach_state(z - d),
        Leg::Retract { d_min } => summit.retract_state(z - d, z - d_min),
    }
}

/// The heights (in sigma) where the summits' load at separation `d` jumps or folds, within
/// the Gaussian's kept range, sorted.
fn cuts<S: SummitLaw>(summit: &S, sigma: f64, leg: Leg, d: f64) -> Vec<f64> {
    let s = sigma;
    let mut z: Vec<f64> = summit.marks().iter().map(|m| (d + m) / s).collect();
    if let Leg::Retract { d_min } = leg {
        z.extend(summit.retract_marks().iter().map(|m| (d_min + m) / s));
    }
    z.push(-Z_CUT);
    z.push(Z_CUT);
    z.retain(|x| x.is_finite() && x.abs() <= Z_CUT);
    z.sort_by(f64::total_cmp);
    z.dedup();
    z
}

/// Standard normal upper tail, to full relative precision far out.
pub(crate) fn upper_tail(x: f64) -> f64 {
    0.5 * libm::erfc(x / std::f64::consts::SQRT_2)
}

/// A rough surface: one law for every summit (by default the dry Maugis-Dugdale summit of one
/// lambda), summit heights N(0, sigma^2).
pub struct Rough<S = Summit> {
    /// Every summit's law and branches.
    pub summit: S,
    /// The heights' standard deviation (approach units).
    pub sigma: f64,
}

/// Which half of a cycle a load is asked for: the approach, or the retract after `d_min`.
#[derive(Clone, Copy, Debug)]
pub enum Leg {
    /// The approach from far away.
    Approach,
    /// The retract after pressing to the separation `d_min`.
    Retract {
        /// The smallest separation reached.
        d_min: f64,
    },
}

/// The mean state of the summits at one separation.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Mean {
    /// The separation of the flat from the mean summit plane (approach units).
    pub separation: f64,
    /// Load per summit.
    pub load: f64,
    /// Fraction of summits in contact.
    pub contact_fraction: f64,
    /// Fraction of summits on the non-contact (cohesive zone only) branch.
    pub noncontact_fraction: f64,
    /// The part of the load per summit carried by the summits in contact (with their Dugdale
    /// zones): `load = contact_load + noncontact_load`.
    pub contact_load: f64,
    /// The part carried by the summits on the non-contact branch (cohesive zone only, always
    /// tensile).
    pub noncontact_load: f64,
    /// The quadrature's error estimate of the load.
    #[serde(skip)]
    pub quadrature_error: f64,
}

/// The error of a rough-surface computation.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RoughError {
    #[error(transparent)]
    /// An input outside its domain.
    Domain(#[from] DomainError),
    #[error(transparent)]
    /// The solver refused a summit.
    Solve(#[from] SolveError),
    #[error("{0}")]
    /// A scene or an option refused, in words naming its keys.
    Scene(Message),
    #[error("the summit solver failed at separation {} (lambda = {}): no number is reported", short(*.0), short(*.1))]
    /// A summit's state that could not be solved (separation, lambda).
    Failed(f64, f64),
}

impl crate::error::Named for RoughError {
    fn named(&self, names: crate::error::Names) -> String {
        match self {
            RoughError::Scene(m) => m.named(names),
            RoughError::Domain(e) => e.named(names),
            RoughError::Solve(e) => e.named(names),
            e => e.to_string(),
        }
    }
}

/// The separations of a cycle, from `d_max` down to `d_min` (approach units), checked.
pub(crate) fn separations(d_min: f64, d_max: f64, points: usize) -> Result<Vec<f64>, RoughError> {
    if !d_min.is_finite() || d_min.abs() > SEPARATION_MAX {
        return Err(domain(
            "the smallest separation",
            d_min,
            "-1e6..1e6 approach units",
            "give a finite separation",
        )
        .into());
    }
    if !(d_max.is_finite() && d_max > d_min && d_max <= SEPARATION_MAX) {
        return Err(domain(
            "the largest separation",
            d_max,
            "above the smallest separation, at most 1e6 approach units",
            "give a largest separation above the smallest",
        )
        .into());
    }
    if !(2..=POINTS_MAX).contains(&points) {
        return Err(domain(
            "the number of separations",
            points as f64,
            "2..10000",
            "give 2..10000 points (more only cost time: a few thousand draw any cycle)",
        )
        .into());
    }
    Ok((0..points)
        .map(|i| d_max + (d_min - d_max) * i as f64 / (points - 1) as f64)
        .collect())
}

/// The default largest separation: `free`, where no summit feels the flat (the user gave
/// none), checked against the sweep's bound and the smallest separation `d_min` with messages
/// that say which of them is at fault.
pub(crate) fn free_d_max(free: f64, d_min: f64) -> Result<f64, RoughError> {
    if free > SEPARATION_MAX {
        return Err(RoughError::Scene(format!(
            "the summits feel the flat out to {} approach units (their force range, 2/(pi lambda) for a dry summit, plus {Z_FREE} sigma), beyond the largest separation a cycle takes ({SEPARATION_MAX:e}): give a larger lambda or a smaller sigma",
            short(free)
        ).into()));
    }
    if d_min >= free {
        return Err(RoughError::Scene(
            Message::new()
                .key("min_separation")
                .text(format!(
                    " = {} is beyond the summits' reach ({} approach units: no summit feels the flat there), so nothing would touch: give a smaller ",
                    short(d_min),
                    short(free)
                ))
                .key("min_separation"),
        ));
    }
    Ok(free)
}

/// The press depth `press_sigmas` (in sigma below the mean summit plane) within
/// +-[`PRESS_SIGMAS_MAX`].
/// A roughness axis: `0 < sigma_min < sigma_max <= 1e4` approach units.
pub(crate) fn check_roughness_range(sigma_min: f64, sigma_max: f64) -> Result<(), Message> {
    if sigma_min > 0.0 && sigma_max > sigma_min && sigma_max <= 1e4 {
        return Ok(());
    }
    Err(Message::new()
        .key("sigma_min")
        .text(format!(" {} and ", short(sigma_min)))
        .key("sigma_max")
        .text(format!(
            " {} are not a roughness range: give 0 < ",
            short(sigma_max)
        ))
        .key("sigma_min")
        .text(" < ")
        .key("sigma_max")
        .text(" <= 1e4 (approach units)"))
}

pub(crate) fn check_press_sigmas(press_sigmas: f64) -> Result<(), Message> {
    if press_sigmas.is_finite() && press_sigmas.abs() <= PRESS_SIGMAS_MAX {
        return Ok(());
    }
    Err(Message::new().key("press_sigmas").text(format!(
        " = {} is not valid: give how many sigma below the mean summit plane the flat was pressed, -{m}..{m} (pressed {m} sigma, all but 1e-9 of the summits have touched: a deeper press changes nothing more)",
        short(press_sigmas),
        m = short(PRESS_SIGMAS_MAX)
    )))
}

/// The mean state at every separation on the approach (down) and on the retract after `d_min`
/// (back up), on all cores.
pub(crate) fn legs(
    seps: &[f64],
    d_min: f64,
    mean: impl Fn(Leg, f64) -> Result<Mean, RoughError> + Sync,
) -> Result<(Vec<Mean>, Vec<Mean>), RoughError> {
    use rayon::prelude::*;
    let approach = seps
        .par_iter()
        .map(|&d| mean(Leg::Approach, d))
        .collect::<Result<_, _>>()?;
    let retract = seps
        .par_iter()
        .rev()
        .map(|&d| mean(Leg::Retract { d_min }, d))
        .collect::<Result<_, _>>()?;
    Ok((approach, retract))
}

/// A separation given by the caller: finite, within 1e6 approach units (as a cycle's).
pub(crate) fn separation_in_range(name: &'static str, d: f64) -> Result<(), RoughError> {
    if d.is_finite() && d.abs() <= 1e6 {
        return Ok(());
    }
    Err(domain(
        name,
        d,
        "-1e6..1e6 approach units",
        "give a finite separation",
    )
    .into())
}

pub(crate) fn domain(
    name: &'static str,
    value: f64,
    range: &'static str,
    hint: &'static str,
) -> DomainError {
    DomainError {
        name,
        value,
        range,
        hint,
    }
}

impl Rough<Summit> {
    /// A rough surface of summit parameter `lambda` and height spread `sigma` (> 0, at most 1e4
    /// approach units).
    pub fn new(lambda: f64, sigma: f64) -> Result<Rough, RoughError> {
        if !(sigma > 0.0 && sigma <= SIGMA_MAX) {
            return Err(domain(
                "sigma (the summit heights' standard deviation)",
                sigma,
                "(0, 1e4] approach units",
                "give a positive, finite roughness",
            )
            .into());
        }
        Ok(Rough {
            summit: Summit::new(lambda)?,
            sigma,
        })
    }
}

impl<S: SummitLaw> Rough<S> {
    /// The mean state of an explicit ensemble of summits of heights `z` (approach units), all of
    /// this surface's law, at separation `d`: each summit on its own branch.
    pub fn ensemble_mean(&self, leg: Leg, z: &[f64], d: f64) -> Result<Mean, RoughError> {
        crate::interrupt::checkpoint();
        // A NaN separation would leave every summit free: a load of 0, not an answer.
        separation_in_range("the separation", d)?;
        if let Leg::Retract { d_min } = leg {
            separation_in_range("the smallest separation", d_min)?;
        }
        let (mut load, mut contact, mut noncontact) = (0.0, 0.0, 0.0);
        let (mut contact_load, mut noncontact_load) = (0.0, 0.0);
        for &zi in z {
            let k = state_at(&self.summit, leg, zi, d);
            let p = self
                .summit
                .load_in(k, zi - d)
                .ok_or(RoughError::Failed(d, self.summit.lambda()))?;
            load += p;
            match self.summit.branch_of(k) {
                SummitBranch::Contact => {
                    (contact, contact_load) = (contact + 1.0, contact_load + p)
                }
                SummitBranch::NonContact => {
                    (noncontact, noncontact_load) = (noncontact + 1.0, noncontact_load + p)
                }
                SummitBranch::Free => {}
            }
        }
        let n = z.len().max(1) as f64;
        Ok(Mean {
            separation: d,
            load: load / n,
            contact_fraction: contact / n,
            noncontact_fraction: noncontact / n,
            contact_load: contact_load / n,
            noncontact_load: noncontact_load / n,
            quadrature_error: 0.0,
        })
    }

    /// The mean of A^2 over all summits (those not in contact count 0) at separation `d`: the
    /// real contact area per summit is pi times it in units of the summit's radius unit squared.
    pub fn mean_area(&self, leg: Leg, d: f64) -> Result<f64, RoughError> {
        self.summit.mean_area(self.sigma, leg, d)
    }

    /// The mean load and branch fractions at separation `d`.
    pub fn mean(&self, leg: Leg, d: f64) -> Result<Mean, RoughError> {
        crate::interrupt::checkpoint();
        let s = self.sigma;
        let cuts = cuts(&self.summit, s, leg, d);
        let failed = Cell::new(false);
        let (mut load, mut contact, mut noncontact, mut error) = (0.0, 0.0, 0.0, 0.0);
        let (mut contact_load, mut noncontact_load) = (0.0, 0.0);
        for w in cuts.windows(2) {
            let (t0, t1) = (w[0], w[1]);
            let k = state_at(&self.summit, leg, 0.5 * (t0 + t1) * s, d);
            let branch = self.summit.branch_of(k);
            let mass = upper_tail(t0) - upper_tail(t1);
            match branch {
                SummitBranch::Free => continue,
                SummitBranch::Contact => contact += mass,
                SummitBranch::NonContact => noncontact += mass,
            }
            // The load integrand in t = z / sigma: the density times the summit's load.
            let f = |t: f64| {
                let g = (-0.5 * t * t).exp() / (2.0 * PI).sqrt();
                match self.summit.load_in(k, t * s - d) {
                    Some(p) => g * p,
                    None => {
                        failed.set(true);
                        0.0
                    }
                }
            };
            let (v, e) = integrate(&f, t0, t1);
            load += v;
            error += e;
            match branch {
                SummitBranch::Contact => contact_load += v,
                _ => noncontact_load += v,
            }
        }
        if failed.get() {
            return Err(RoughError::Failed(d, self.summit.lambda()));
        }
        Ok(Mean {
            separation: d,
            load,
            contact_fraction: contact,
            noncontact_fraction: noncontact,
            contact_load,
            noncontact_load,
            quadrature_error: error,
        })
    }
}

/// Integral of `f` over `[a, b]` by double-exponential quadrature, halving the interval (at most
/// six times) where the error estimate is above [`QUAD_TOL`] of the integrand's scale; returns the
/// integral and the sum of the error estimates of its parts.
pub(crate) fn integrate(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    fn go(f: &dyn Fn(f64) -> f64, a: f64, b: f64, scale: f64, depth: u32) -> (f64, f64) {
        let o = quadrature::double_exponential::integrate(f, a, b, QUAD_TOL * scale);
        if o.error_estimate <= QUAD_TOL * scale || depth == 0 {
            return (o.integral, o.error_estimate);
        }
        let m = 0.5 * (a + b);
        let (l, r) = (go(f, a, m, scale, depth - 1), go(f, m, b, scale, depth - 1));
        (l.0 + r.0, l.1 + r.1)
    }
    if !(b > a) {
        return (0.0, 0.0);
    }
    // The integrand's size at a few interior points sets the absolute tolerance.
    let scale = (1..8)
        .map(|k| f(a + (b - a) * k as f64 / 8.0).abs() * (b - a))
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    go(f, a, b, scale, 6)
}

/// The fewest retract separations a cycle's pull-off search starts from: a cycle reported at
/// fewer is sampled at this many more, so that the search brackets the true minimum and not
/// the least of a few samples.
pub(crate) const PULLOFF_SAMPLES: usize = 64;

/// The golden-section search of the pull-off and of the wet summits' folds.
const GOLDEN: Golden = Golden {
    width: Width::Relative(1e-15),
    ties: Ties::Right,
    max_iter: 200,
};

/// The most tensile retract load: the least of the `samples` (and, where they are fewer than
/// `at_least`, of that many uniform samples over `[d_min, d_max]` of `load`), then a
/// golden-section search for the minimum between its neighbours. Returns the separation and
/// the load. One search for every rough model: the statistical ones (dry and wet) and the
/// explicit ensembles.
pub(crate) fn pulloff_search(
    samples: &[Mean],
    d_min: f64,
    d_max: f64,
    at_least: usize,
    load: &dyn Fn(f64) -> Result<f64, RoughError>,
) -> Result<(f64, f64), RoughError> {
    let mut pts: Vec<(f64, f64)> = samples.iter().map(|m| (m.separation, m.load)).collect();
    if pts.len() < at_least && d_max > d_min {
        for i in 0..at_least {
            let d = d_min + (d_max - d_min) * i as f64 / (at_least - 1) as f64;
            pts.push((d, load(d)?));
        }
    }
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let Some(i) = (0..pts.len()).min_by(|&a, &b| pts[a].1.total_cmp(&pts[b].1)) else {
        return Err(RoughError::Scene("the retract has no separation".into()));
    };
    let lo = pts[i.saturating_sub(1)].0;
    let hi = pts[(i + 1).min(pts.len() - 1)].0;
    let p = GOLDEN.search(load, lo, hi)?;
    let best = [p.left, p.right, pts[i]]
        .into_iter()
        .min_by(|x, y| x.1.total_cmp(&y.1))
        .unwrap_or(pts[i]);
    Ok(best)
}

/// The mean over the summits of a statistical model on a leg at a separation.
pub(crate) type MeanOf<'a> = &'a dyn Fn(Leg, f64) -> Result<Mean, RoughError>;

/// The pull-off per summit of a statistical model (dry or wet: its `mean`) after pressing to
/// `d_min`: the retract sampled at `samples` separations up to `free`, where every summit is
/// free again, then refined.
pub(crate) fn pulloff_after(
    free: f64,
    d_min: f64,
    samples: usize,
    mean: MeanOf,
) -> Result<(f64, f64), RoughError> {
    let d_max = free.max(d_min + 1e-9);
    let leg = Leg::Retract { d_min };
    let m = samples.max(3);
    let retract: Vec<Mean> = (0..m)
        .map(|i| mean(leg, d_min + (d_max - d_min) * i as f64 / (m - 1) as f64))
        .collect::<Result<_, _>>()?;
    retract_pulloff(&retract, d_min, d_max, 0, mean)
}

/// The most tensile retract load of a statistical model after pressing to `d_min`, from the
/// samples `retract` (and, where those are fewer than `at_least`, from that many more up to
/// `d_max`).
pub(crate) fn retract_pulloff(
    retract: &[Mean],
    d_min: f64,
    d_max: f64,
    at_least: usize,
    mean: MeanOf,
) -> Result<(f64, f64), RoughError> {
    let leg = Leg::Retract { d_min };
    pulloff_search(retract, d_min, d_max, at_least, &|d| {
        mean(leg, d).map(|m| m.load)
    })
}

/// What a statistical cycle's range and sampling cannot show: summits still held at its largest
/// separation `d_max` (their `reach` is how far beyond a summit's height it feels the flat), a
/// pull-off at that end, and a pull-off that the reported separations miss.
pub(crate) fn cycle_warnings(
    sigma: f64,
    reach: f64,
    d_max: f64,
    retract: &[Mean],
    pulloff: (f64, f64),
) -> Vec<Message> {
    let mut w = Vec::new();
    let held = upper_tail((d_max - reach) / sigma);
    if held > 1e-9 {
        w.push(
            Message::new()
                .text(format!(
                    "the largest separation {} is inside the summits' force range (a fraction {} of them still feel the flat there; all are free beyond {}): the retract ends before the surfaces separate, so its pull-off and energy loss are this partial cycle's; give a larger ",
                    short(d_max),
                    short(held),
                    short(reach + Z_FREE * sigma)
                ))
                .key("max_separation")
                .text(", or none"),
        );
        if (d_max - pulloff.0).abs() <= 1e-9 * (1.0 + d_max.abs()) {
            w.push(Message::from("the most tensile retract load is at the largest separation: the true pull-off lies beyond it"));
        }
    }
    let least = retract.iter().map(|m| m.load).fold(f64::INFINITY, f64::min);
    if pulloff.1 < 0.0 && least > pulloff.1 + 0.01 * pulloff.1.abs() {
        w.push(
            Message::new()
                .text(format!(
                    "the {} reported separations miss the pull-off's dip (their most tensile load, {}, is {}% above the pull-off {}, found between them): give more ",
                    retract.len(),
                    short(least),
                    short(100.0 * (least - pulloff.1) / pulloff.1.abs()),
                    short(pulloff.1)
                ))
                .key("points")
                .text(" to draw it"),
        );
    }
    w
}

/// An approach from `d_max` down to `d_min` and the retract back (`tabor rough`).
#[derive(Clone, Debug, Serialize)]
pub struct RoughCycle {
    /// The summits' Maugis parameter.
    pub lambda: f64,
    /// The heights' standard deviation (approach units).
    pub sigma: f64,
    /// The approach, from the largest separation down.
    pub approach: Vec<Mean>,
    /// The retract, back up.
    pub retract: Vec<Mean>,
    /// The most tensile retract load per summit, to full precision, and its separation.
    pub pulloff_load: f64,
    /// The separation of the pull-off.
    pub pulloff_separation: f64,
    /// Energy lost per summit per cycle, integral of (P_approach - P_retract) over the
    /// separation (pi w R times the approach unit).
    pub hysteresis: f64,
    /// The single summit's pull-off under rigid grips (Pbar_c).
    pub smooth_pulloff: f64,
    /// Fuller and Tabor's adhesion parameter E* sigma^(3/2) / (R^(1/2) w) = (3 pi / 4)
    /// sigma^(3/2).
    pub fuller_tabor_parameter: f64,
    /// The largest error estimate of the quadrature over every reported load, the pull-off's
    /// included (pi w R per summit): the sum over the pieces of the tanh-sinh estimates.
    pub quadrature_error: f64,
    /// What the cycle's range or sampling cannot show (empty when it shows everything).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<Message>,
}

impl<S: SummitLaw> Rough<S> {
    /// The separation beyond which no summit within the kept range feels the flat, on the
    /// approach or on the retract (which holds on beyond the Dugdale range: down to the
    /// jump-out, or to the end of the non-contact branch).
    pub fn free_separation(&self) -> f64 {
        Z_FREE * self.sigma + self.summit.reach()
    }

    /// The cycle from `d_max` (default [`Rough::free_separation`]) down to `d_min` and back,
    /// `points` separations each way.
    pub fn cycle(
        &self,
        d_min: f64,
        d_max: Option<f64>,
        points: usize,
    ) -> Result<RoughCycle, RoughError> {
        let d_max = match d_max {
            Some(d) => d,
            None => free_d_max(self.free_separation(), d_min)?,
        };
        let seps = separations(d_min, d_max, points)?;
        let (approach, retract) = legs(&seps, d_min, |l, d| self.mean(l, d))?;
        let leg = Leg::Retract { d_min };
        let (pulloff_separation, pulloff_load) =
            retract_pulloff(&retract, d_min, d_max, PULLOFF_SAMPLES, &|leg, d| {
                self.mean(leg, d)
            })?;
        let hysteresis = self.summit.hysteresis(self.sigma, d_min, d_max)?;
        let at_pulloff = self.mean(leg, pulloff_separation)?.quadrature_error;
        let quadrature_error = approach
            .iter()
            .chain(&retract)
            .map(|m| m.quadrature_error)
            .fold(at_pulloff, f64::max);
        Ok(RoughCycle {
            lambda: self.summit.lambda(),
            sigma: self.sigma,
            pulloff_load,
            pulloff_separation,
            hysteresis,
            smooth_pulloff: self.summit.smooth_pulloff(),
            fuller_tabor_parameter: 0.75 * PI * self.sigma.powf(1.5),
            quadrature_error,
            warnings: cycle_warnings(
                self.sigma,
                self.free_separation() - Z_FREE * self.sigma,
                d_max,
                &retract,
                (pulloff_separation, pulloff_load),
            ),
            approach,
            retract,
        })
    }

    /// The pull-off per summit after pressing to `d_min`: the retract sampled at `samples`
    /// separations up to where every summit is free again, then refined. Returns the separation
    /// and the load.
    pub fn pulloff_after(&self, d_min: f64, samples: usize) -> Result<(f64, f64), RoughError> {
        pulloff_after(self.free_separation(), d_min, samples, &|leg, d| {
            self.mean(leg, d)
        })
    }
}

/// Integral of P_approach - P_retract over [d_min, d_max]. Swapping the order of integration,
/// it is the Gaussian mean of each summit's own loop area over its window of approaches
/// `[z - d_max, z - d_min]` (docs/PHYSICS.md section 9): a constant for every summit that
/// touched (or, below lambda_D, reached only the non-contact branch) and was free again at
/// d_max, and a single-summit integral clipped at `z - d_max` for the others.
fn dry_hysteresis(sm: &Summit, s: f64, d_min: f64, d_max: f64) -> Result<f64, RoughError> {
    let failed = Cell::new(false);
    let load = |b: SummitBranch, delta: f64| {
        sm.load(b, delta).unwrap_or_else(|| {
            failed.set(true);
            0.0
        })
    };
    // A touched summit's loop: approach minus retract, nonzero only below delta_in.
    let lo_touch = sm.delta_nc.unwrap_or(sm.delta_out).min(sm.delta_out);
    let touched = |from: f64| -> f64 {
        let f = |delta: f64| {
            load(sm.approach_branch(delta), delta)
                - load(sm.retract_branch(delta, f64::INFINITY), delta)
        };
        let mut cuts: Vec<f64> = sm.marks();
        cuts.push(from.max(lo_touch));
        cuts.retain(|c| *c >= from.max(lo_touch) && *c <= sm.delta_in);
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        cuts.windows(2).map(|w| integrate(&f, w[0], w[1]).0).sum()
    };
    // A summit that reached only the non-contact branch: -(its load) over [delta_nc, -h0].
    let reached = |from: f64| -> f64 {
        match sm.delta_nc {
            Some(lo) => integrate(&|delta| -sm.non_contact(delta), from.max(lo), -sm.h0).0,
            None => 0.0,
        }
    };
    let mass = |t0: f64, t1: f64| upper_tail(t0) - upper_tail(t1);
    let clip = |t: f64| t.clamp(-Z_CUT, Z_CUT);
    let mut total = 0.0;
    // (heights from, to, the loop's lower end, its loop area)
    type HistoryClass<'a> = (f64, f64, f64, &'a dyn Fn(f64) -> f64);
    let regions: [HistoryClass; 2] = [
        (d_min + sm.delta_in, f64::INFINITY, lo_touch, &touched),
        (
            d_min - sm.h0,
            d_min + sm.delta_in,
            sm.delta_nc.unwrap_or(0.0),
            &reached,
        ),
    ];
    for (z0, z1, lo, area) in regions {
        if !(z1 > z0) {
            continue;
        }
        // Below z = d_max + lo the whole loop lies in the window: a constant area.
        let split = d_max + lo;
        let (t0, t1, ts) = (clip(z0 / s), clip(z1 / s), clip(split / s));
        if ts > t0 {
            total += area(f64::NEG_INFINITY) * mass(t0, ts.min(t1));
        }
        if t1 > ts.max(t0) {
            let f = |t: f64| (-0.5 * t * t).exp() / (2.0 * PI).sqrt() * area(t * s - d_max);
            total += integrate(&f, ts.max(t0), t1).0;
        }
    }
    if failed.get() {
        return Err(RoughError::Failed(d_min, sm.lambda));
    }
    // Each summit's loop encloses a non-negative area: a negative sum is rounding.
    Ok(
        if total < 0.0 && total >= -1e-12 * sm.ctx.load_pulloff.load.abs() * s {
            0.0
        } else {
            total
        },
    )
}

/// Pull-off against roughness for one lambda (Fuller and Tabor's figure).
#[derive(Clone, Debug, Serialize)]
pub struct PulloffCurve {
    /// The summits' Maugis parameter.
    pub lambda: f64,
    /// The single summit's pull-off (Pbar_c).
    pub smooth_pulloff: f64,
    /// The roughnesses (approach units).
    pub sigma: Vec<f64>,
    /// Fuller and Tabor's adhesion parameter at each roughness.
    pub fuller_tabor_parameter: Vec<f64>,
    /// Pull-off per summit, and relative to the smooth summit's.
    pub pulloff: Vec<f64>,
    /// The pull-off per summit over the smooth summit's.
    pub relative_pulloff: Vec<f64>,
}

/// The pull-off per summit after pressing to `press` sigma from the mean summit plane (the
/// smallest separation is `press * sigma`), for each lambda over the roughnesses `sigmas`, on
/// all cores.
pub fn pulloff_against_roughness(
    lambdas: &[f64],
    sigmas: &[f64],
    press: f64,
) -> Result<Vec<PulloffCurve>, RoughError> {
    use rayon::prelude::*;
    lambdas
        .iter()
        .map(|&lambda| {
            let smooth = Summit::new(lambda)?.ctx.load_pulloff.load;
            let pulloff: Vec<f64> = sigmas
                .par_iter()
                .map(|&s| Ok(Rough::new(lambda, s)?.pulloff_after(press * s, 48)?.1))
                .collect::<Result<_, RoughError>>()?;
            Ok(PulloffCurve {
                lambda,
                smooth_pulloff: smooth,
                sigma: sigmas.to_vec(),
                fuller_tabor_parameter: sigmas.iter().map(|s| 0.75 * PI * s.powf(1.5)).collect(),
                relative_pulloff: pulloff.iter().map(|p| p / smooth).collect(),
                pulloff,
            })
        })
        .collect()
}

/// Fuller and Tabor's sweep: the pull-off per summit against the roughness for several
/// lambda, after pressing the flat `press_sigmas` sigma below the mean summit plane.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PulloffSweep {
    /// The summits' Maugis parameters (1 to 20 of them).
    pub lambdas: Vec<f64>,
    /// The smallest roughness, in approach units.
    pub sigma_min: f64,
    /// The largest roughness, in approach units (at most 1e4).
    pub sigma_max: f64,
    /// Roughnesses, log-spaced (2 to 1000).
    pub points: usize,
    /// How far the flat was pressed before the retract, in sigma below the mean summit plane.
    pub press_sigmas: f64,
}

impl Default for PulloffSweep {
    /// Lambda from DMT-like to JKR-like summits, sigma 0.01..10 (24 roughnesses), pressed 3
    /// sigma (99.9% of the summits touched).
    fn default() -> PulloffSweep {
        PulloffSweep {
            lambdas: vec![0.01, 0.1, 1.0, 1000.0],
            sigma_min: 0.01,
            sigma_max: 10.0,
            points: 24,
            press_sigmas: 3.0,
        }
    }
}

impl PulloffSweep {
    /// One clear line for a bad value, naming the quantity.
    pub fn validate(&self) -> Result<(), RoughError> {
        let bad = |m: Message| Err(RoughError::Scene(m));
        check_roughness_range(self.sigma_min, self.sigma_max).or_else(bad)?;
        if !(2..=1000).contains(&self.points) {
            return bad(Message::new()
                .key("points")
                .text(format!(" = {}: give 2..1000 roughnesses", self.points)));
        }
        if self.lambdas.is_empty() || self.lambdas.len() > 20 {
            return bad(Message::new()
                .text(format!("{} ", self.lambdas.len()))
                .phrase("lambda_values", "lambda values")
                .text(": give 1..20"));
        }
        for &l in &self.lambdas {
            crate::physics::domain::check_lambda(l)?;
        }
        check_press_sigmas(self.press_sigmas).or_else(bad)?;
        Ok(())
    }

    /// The roughnesses of the sweep, log-spaced.
    pub fn sigmas(&self) -> Vec<f64> {
        crate::numeric::grid::axis(self.sigma_min, self.sigma_max, self.points, true)
    }

    /// Checks, then one curve per lambda on all cores.
    pub fn compute(&self) -> Result<Vec<PulloffCurve>, RoughError> {
        self.validate()?;
        pulloff_against_roughness(&self.lambdas, &self.sigmas(), -self.press_sigmas)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn branches_follow_section_9() {
        // Above lambda_D: no stable non-contact branch; in at -h0, out at the jump-out.
        let s = Summit::new(2.0).unwrap();
        assert!(s.delta_nc.is_none());
        assert_eq!(s.delta_in, -s.h0);
        assert!(s.delta_out < -s.h0);
        // Below it: the non-contact branch, joined to the contact branch at A = 0.
        let s = Summit::new(0.1).unwrap();
        let lo = s.delta_nc.unwrap();
        assert!(lo < -s.h0 && s.delta_in > -s.h0);
        assert_eq!(s.delta_out, s.delta_a0);
        // The non-contact load at the A = 0 end equals the contact branch's there.
        let (p, a) = s.contact(s.delta_a0 + 1e-9).unwrap();
        assert!(a < 1e-3 && (s.non_contact(s.delta_a0) / p - 1.0).abs() < 1e-5);
        // Gaussian tails.
        assert!((upper_tail(0.0) - 0.5).abs() < 1e-16);
        assert!((upper_tail(10.0) / 7.619853024160527e-24 - 1.0).abs() < 1e-12);
    }
}
