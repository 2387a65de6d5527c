//! Wet rough surfaces (docs/PHYSICS.md section 10.1): Greenwood-Williamson summits whose
//! cohesive law is the two-zone law of section 10 (the solid's Dugdale zone and a water
//! meniscus), each under the separation of a rigid flat with its own history.
//!
//! A summit's complete equilibrium path (free, the longer zone's disc alone, both discs, the
//! contact curve) is cut into its stretches where the approach rises along the path: the stable
//! states under displacement control. On the approach a summit follows its stretch to the
//! stretch's upper end and jumps to the next stretch holding that approach; on the retract it
//! follows it back to the lower end and jumps to the previous one holding it (or to the free
//! branch). Each stretch's load is evaluated exactly at a given approach (a bracketed root in the
//! path's parameter on the non-contact stretches, the solver's displacement-controlled state on
//! the contact curve); the sampled path only locates the folds, which are then refined.
//!
//! Units are section 10's, built on the total work of adhesion `w = w1 + w2`: loads per summit
//! in `pi w R`, separations and sigma in `(pi^2 w^2 R / K^2)^(1/3)`.

use super::{domain, integrate, upper_tail, Leg, Mean, Rough, RoughCycle, RoughError};
use super::{SummitBranch, SummitLaw, Z_CUT};
use crate::error::Message;
use crate::law::{ContactLaw, Md, TwoZones};
use crate::physics::two_zone::{non_contact_both, non_contact_single, Shape, Zones};
use crate::solver::two_zone::TwoZoneContext;
use crate::solver::Status;
use std::cell::Cell;
use std::f64::consts::PI;

/// Absolute error aimed at for each piece of one summit's loop (pi w R times the approach unit).
const LOOP_TOL: f64 = 1e-11;
/// Samples of each non-contact stretch of the path used to locate its folds.
const SAMPLES: usize = 2000;

/// The part of the path a stretch lies on, with its parameter's interval.
#[derive(Clone, Copy, Debug)]
enum Part {
    Free,
    /// The longer zone's disc alone, parametrised by its radius.
    Single(f64, f64),
    /// Both discs, parametrised by the shorter zone's radius.
    Both(f64, f64),
    Contact,
}

/// A stretch of the equilibrium path on which the approach rises: stable under rigid grips for
/// approaches in `[lo, hi]`.
#[derive(Clone, Copy, Debug)]
pub struct Stretch {
    part: Part,
    /// The lowest and highest approach of the stretch (-inf, +inf at the path's ends).
    pub lo: f64,
    /// The highest approach of the stretch.
    pub hi: f64,
}

impl Stretch {
    /// The branch a summit on this stretch is on.
    pub fn branch(&self) -> SummitBranch {
        match self.part {
            Part::Free => SummitBranch::Free,
            Part::Single(..) | Part::Both(..) => SummitBranch::NonContact,
            Part::Contact => SummitBranch::Contact,
        }
    }
}

/// One wet summit (two zones of different ranges) and its stable stretches under rigid grips.
pub struct WetSummit {
    /// The summit's two-zone law.
    pub ctx: TwoZoneContext,
    /// The stretches in the order of the path (free first, contact last).
    pub stretches: Vec<Stretch>,
    /// The stable contact curve tabulated in the contact radius (None: exact everywhere).
    table: Option<ContactTable>,
}

/// Radii of the contact table.
const TABLE: usize = 3000;

/// The stable contact curve at radii from its fold (or near A = 0) up to a largest approach:
/// approach and load against A, interpolated by 4-point Lagrange cubics in A (smooth there, also
/// at the fold where the load against the approach has a square-root end). The interpolation
/// error is measured in `tests/suite/rough_wet.rs` against the solver's state at the approach.
struct ContactTable {
    a: Vec<f64>,
    d: Vec<f64>,
    p: Vec<f64>,
}

fn lagrange(x: &[f64], y: &[f64], t: f64) -> f64 {
    let mut s = 0.0;
    for i in 0..x.len() {
        let mut l = 1.0;
        for j in 0..x.len() {
            if j != i {
                l *= (t - x[j]) / (x[i] - x[j]);
            }
        }
        s += l * y[i];
    }
    s
}

impl ContactTable {
    fn new(ctx: &TwoZoneContext, top: f64) -> Option<ContactTable> {
        use rayon::prelude::*;
        let hi = ctx.state_at_approach(top);
        if hi.status != Status::Ok {
            return None;
        }
        let fold = ctx.disp_pulloff;
        let a_lo = if fold.at_zero_radius() {
            1e-5 * hi.a
        } else {
            fold.a
        };
        let a: Vec<f64> = (0..TABLE)
            .map(|i| a_lo + (hi.a - a_lo) * (i as f64 / (TABLE - 1) as f64).powi(2))
            .collect();
        let st: Vec<(f64, f64)> = a
            .par_iter()
            .map(|&r| {
                let s = ctx.state_at_radius(r);
                if s.status == Status::Ok {
                    (s.approach, s.load)
                } else {
                    (f64::NAN, f64::NAN)
                }
            })
            .collect();
        let (d, p): (Vec<f64>, Vec<f64>) = st.into_iter().unzip();
        // Monotone, finite approaches only; otherwise the exact solver everywhere.
        let ok = d.iter().chain(&p).all(|v| v.is_finite()) && d.windows(2).all(|w| w[1] > w[0]);
        ok.then_some(ContactTable { a, d, p })
    }

    /// The load and the contact radius at approach `delta`, None outside the table.
    fn state(&self, delta: f64) -> Option<(f64, f64)> {
        let n = self.d.len();
        if !(delta >= self.d[0] && delta <= self.d[n - 1]) {
            return None;
        }
        let i = self.d.partition_point(|&x| x <= delta).clamp(1, n - 1) - 1;
        let j0 = i.saturating_sub(1).min(n - 4);
        let (xa, xd, xp) = (
            &self.a[j0..j0 + 4],
            &self.d[j0..j0 + 4],
            &self.p[j0..j0 + 4],
        );
        // The radius where the cubic approach equals delta, by bisection in [a_i, a_i+1].
        let (mut lo, mut hi) = (self.a[i], self.a[i + 1]);
        for _ in 0..100 {
            let m = 0.5 * (lo + hi);
            if lagrange(xa, xd, m) < delta {
                lo = m;
            } else {
                hi = m;
            }
            if hi - lo <= 1e-16 * hi {
                break;
            }
        }
        let a = 0.5 * (lo + hi);
        Some((lagrange(xa, xp, a), a))
    }
}

fn approach_of(z: &Zones, part: Part, p: f64) -> f64 {
    match part {
        Part::Single(..) => non_contact_single(z, p).approach,
        Part::Both(..) => non_contact_both(z, p).map_or(f64::NAN, |q| q.approach),
        _ => f64::NAN,
    }
}

fn zones_failed(e: impl Into<Message>) -> RoughError {
    RoughError::Scene(Message::from("the wet summit could not be solved: ").then(e.into()))
}

impl WetSummit {
    /// The summit of the zones `zones` (two different ranges: `Shape::Two`), its contact curve
    /// tabulated up to the approach `top` (beyond it, and with `top` None, solved exactly).
    pub fn new(zones: Zones, top: Option<f64>) -> Result<WetSummit, RoughError> {
        let ctx = TwoZoneContext::new(zones).map_err(|s| {
            zones_failed(format!(
                "the two-zone contact curve failed (status {}): try ratios closer to 1",
                s.name()
            ))
        })?;
        let (c1, c2) = crate::law::two_zone::non_contact_ends_of(&ctx).map_err(zones_failed)?;
        let z = &ctx.zones;
        let long = match z.shape() {
            Shape::Two { long } => long,
            Shape::Single { .. } => return Err(zones_failed("one range: use the dry model")),
        };
        let h_long = z.range[long];
        let mut stretches = vec![Stretch {
            part: Part::Free,
            lo: f64::NEG_INFINITY,
            hi: -h_long,
        }];
        // Each non-contact part sampled in its parameter; its rising runs, their interior ends
        // (folds of the approach) refined by golden section. The two parts meet continuously
        // (c_S = 0 of both discs is the single disc's last point).
        for (single, end) in [(true, c1), (false, c2)] {
            let part = |p0: f64, p1: f64| {
                if single {
                    Part::Single(p0, p1)
                } else {
                    Part::Both(p0, p1)
                }
            };
            let probe = part(0.0, end);
            let ps: Vec<f64> = (0..SAMPLES)
                .map(|i| end * i as f64 / (SAMPLES - 1) as f64)
                .collect();
            let ds: Vec<f64> = ps.iter().map(|&p| approach_of(z, probe, p)).collect();
            if ds.iter().any(|d| !d.is_finite()) {
                return Err(zones_failed(
                    "the non-contact branch has no finite approach",
                ));
            }
            let n = ps.len();
            let refine = |i: usize, sign: f64| -> (f64, f64) {
                if i == 0 || i + 1 >= n {
                    return (ps[i], ds[i]);
                }
                let q =
                    super::GOLDEN.argmin(|x| sign * approach_of(z, probe, x), ps[i - 1], ps[i + 1]);
                let dq = approach_of(z, probe, q);
                if sign * dq < sign * ds[i] {
                    (q, dq)
                } else {
                    (ps[i], ds[i])
                }
            };
            let mut i = 0;
            while i + 1 < n {
                if !(ds[i + 1] > ds[i]) {
                    i += 1;
                    continue;
                }
                let mut j = i;
                while j + 1 < n && ds[j + 1] > ds[j] {
                    j += 1;
                }
                let (p0, d0) = refine(i, 1.0);
                let (p1, d1) = refine(j, -1.0);
                stretches.push(Stretch {
                    part: part(p0, p1),
                    lo: d0,
                    hi: d1,
                });
                i = j;
            }
        }
        let out = ctx.disp_pulloff;
        stretches.push(Stretch {
            part: Part::Contact,
            lo: out.approach,
            hi: f64::INFINITY,
        });
        let table = top.and_then(|t| ContactTable::new(&ctx, t));
        Ok(WetSummit {
            ctx,
            stretches,
            table,
        })
    }

    /// Whether stretch `j` holds the approach `level` (within rounding: where two stretches meet
    /// at the A -> 0 end their ends agree to a few ulps).
    fn holds(&self, j: usize, level: f64) -> bool {
        let s = self.stretches[j];
        let tol = 1e-12 * (1.0 + level.abs());
        s.lo - tol <= level && level <= s.hi + tol
    }

    /// The stretch on the approach at approach `delta` (coming from far away).
    pub fn approach_stretch(&self, delta: f64) -> usize {
        let mut k = 0;
        while delta > self.stretches[k].hi {
            let level = self.stretches[k].hi;
            match (k + 1..self.stretches.len()).find(|&j| self.holds(j, level)) {
                Some(j) => k = j,
                None => return self.stretches.len() - 1,
            }
        }
        k
    }

    /// The stretch on the retract at approach `delta` after the deepest approach `delta_max`.
    pub fn retract_stretch(&self, delta: f64, delta_max: f64) -> usize {
        let mut k = self.approach_stretch(delta_max);
        while delta < self.stretches[k].lo {
            let level = self.stretches[k].lo;
            match (0..k).rev().find(|&j| self.holds(j, level)) {
                Some(j) => k = j,
                None => return 0,
            }
        }
        k
    }

    /// The exact load on the contact stretch at approach `delta` (the solver's state there).
    pub fn contact_exact(&self, delta: f64) -> Option<f64> {
        let s = self.ctx.state_at_approach(delta);
        (s.status == Status::Ok).then_some(s.load)
    }

    /// The contact radius on the stable contact curve at approach `delta` (at least its fold's).
    pub fn contact_radius(&self, delta: f64) -> Option<f64> {
        let delta = delta.max(self.ctx.disp_pulloff.approach);
        if let Some((_, a)) = self.table.as_ref().and_then(|t| t.state(delta)) {
            return Some(a);
        }
        let s = self.ctx.state_at_approach(delta);
        (s.status == Status::Ok).then_some(s.a)
    }

    /// The load on stretch `k` at approach `delta` (clamped into the stretch); None where the
    /// solver failed.
    pub fn load(&self, k: usize, delta: f64) -> Option<f64> {
        let st = self.stretches[k];
        let z = &self.ctx.zones;
        let delta = delta.clamp(st.lo, st.hi);
        let (p0, p1) = match st.part {
            Part::Free => return Some(0.0),
            Part::Contact => {
                if let Some((p, _)) = self.table.as_ref().and_then(|t| t.state(delta)) {
                    return Some(p);
                }
                let s = self.ctx.state_at_approach(delta);
                return (s.status == Status::Ok).then_some(s.load);
            }
            Part::Single(a, b) | Part::Both(a, b) => (a, b),
        };
        // The parameter where the approach equals delta: bracketed Illinois steps.
        let f = |p: f64| approach_of(z, st.part, p) - delta;
        let (mut a, mut b) = (p0, p1);
        let (mut fa, mut fb) = (st.lo - delta, st.hi - delta);
        let mut p = if fa == 0.0 { a } else { b };
        if fa != 0.0 && fb != 0.0 {
            let mut side = 0;
            for _ in 0..200 {
                p = (a * fb - b * fa) / (fb - fa);
                if !(p > a.min(b) && p < a.max(b)) {
                    p = 0.5 * (a + b);
                }
                let fp = f(p);
                if !fp.is_finite() {
                    return None;
                }
                if fp == 0.0 {
                    break;
                }
                if (fp < 0.0) == (fa < 0.0) {
                    (a, fa) = (p, fp);
                    if side == -1 {
                        fb *= 0.5;
                    }
                    side = -1;
                } else {
                    (b, fb) = (p, fp);
                    if side == 1 {
                        fa *= 0.5;
                    }
                    side = 1;
                }
                if (b - a).abs() <= 1e-15 * (1.0 + p.abs()) {
                    break;
                }
            }
        }
        let load = match st.part {
            Part::Single(..) => non_contact_single(z, p).load,
            _ => non_contact_both(z, p)?.load,
        };
        load.is_finite().then_some(load)
    }

    /// The approach where a summit coming from far away enters contact.
    pub fn approach_enter(&self) -> f64 {
        let last = self.stretches.len() - 1;
        // The upper end of the stretch from which the approach jumps (or runs) into contact.
        let mut k = 0;
        loop {
            let level = self.stretches[k].hi;
            match (k + 1..self.stretches.len()).find(|&j| self.holds(j, level)) {
                Some(j) if j == last => return level,
                Some(j) => k = j,
                None => return level,
            }
        }
    }

    /// The work lost by one summit whose approach runs from `lo` up to `hi` and back:
    /// the integral of its approach load less its retract load over `[lo, hi]` (each stretch
    /// smooth between the marks), and the error estimate; None where a load failed.
    fn loop_area(&self, lo: f64, hi: f64) -> Option<(f64, f64)> {
        let failed = Cell::new(false);
        let f = |delta: f64| {
            let up = self.load(self.approach_stretch(delta), delta);
            let down = self.load(self.retract_stretch(delta, hi), delta);
            match (up, down) {
                (Some(u), Some(d)) => u - d,
                _ => {
                    failed.set(true);
                    0.0
                }
            }
        };
        let mut cuts: Vec<f64> = self.marks();
        cuts.extend([lo, hi]);
        cuts.retain(|c| (lo..=hi).contains(c));
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let (mut area, mut error) = (0.0, 0.0);
        for w in cuts.windows(2) {
            // Up and down one stretch enclose nothing: no quadrature of rounding noise.
            let mid = 0.5 * (w[0] + w[1]);
            if self.approach_stretch(mid) == self.retract_stretch(mid, hi) {
                continue;
            }
            // An absolute tolerance (loads and approaches are of order one): a relative one
            // chases rounding where approach and retract nearly agree (small lambda).
            let o = quadrature::double_exponential::integrate(&f, w[0], w[1], LOOP_TOL);
            area += o.integral;
            error += o.error_estimate;
        }
        (!failed.get()).then_some((area, error))
    }

    /// The energy lost per summit in a cycle from `d_max` down to `d_min` and back, heights
    /// N(0, sigma^2): the order of integration swapped (docs/PHYSICS.md section 10.1), the mean
    /// over the heights of each summit's own loop over its window of approaches
    /// `[z - d_max, z - d_min]`. Where the window starts below every mark (the summit comes from
    /// free), the loop depends only on the stretch its top reaches (up and down one stretch
    /// enclose nothing), so it is constant between the heights where the top crosses a mark: one
    /// loop times the Gaussian mass there. Elsewhere the heights' integral is taken by
    /// quadrature. A loss that is zero within rounding is reported as 0, never below.
    fn hysteresis(&self, sigma: f64, d_min: f64, d_max: f64) -> Result<f64, RoughError> {
        let marks = self.marks();
        let (Some(&m_lo), true) = (marks.first(), d_max > d_min) else {
            return Ok(0.0);
        };
        let mut cuts: Vec<f64> = marks
            .iter()
            .flat_map(|m| [(d_min + m) / sigma, (d_max + m) / sigma])
            .collect();
        cuts.extend([-Z_CUT, Z_CUT]);
        cuts.retain(|x| x.is_finite() && x.abs() <= Z_CUT);
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        // Each piece of heights on its own core; (loss, error estimate), None where a load failed.
        let piece = |t0: f64, t1: f64| -> Option<(f64, f64)> {
            if t1 * sigma - d_min <= m_lo {
                return Some((0.0, 0.0)); // never reaches a mark: free throughout
            }
            if t1 * sigma - d_max <= m_lo {
                let z = 0.5 * (t0 + t1) * sigma;
                let (a, e) = self.loop_area(z - d_max, z - d_min)?;
                let mass = upper_tail(t0) - upper_tail(t1);
                return Some((a * mass, e * mass));
            }
            let failed = Cell::new(false);
            let g = |t: f64| {
                let z = t * sigma;
                match self.loop_area(z - d_max, z - d_min) {
                    Some((a, _)) => (-0.5 * t * t).exp() / (2.0 * PI).sqrt() * a,
                    None => {
                        failed.set(true);
                        0.0
                    }
                }
            };
            let v = integrate(&g, t0, t1);
            (!failed.get()).then_some(v)
        };
        use rayon::prelude::*;
        let parts: Option<Vec<(f64, f64)>> =
            cuts.par_windows(2).map(|w| piece(w[0], w[1])).collect();
        let Some(parts) = parts else {
            return Err(RoughError::Failed(d_min, self.ctx.zones.lambda[0]));
        };
        let (mut total, error) = parts
            .iter()
            .fold((0.0, 0.0), |(v, e), p| (v + p.0, e + p.1));
        // Each summit's loop encloses a non-negative area: a negative sum is rounding.
        if total < 0.0 && total >= -(error + 1e-12 * self.ctx.load_pulloff.load.abs() * sigma) {
            total = 0.0;
        }
        Ok(total)
    }

    /// The approaches where a summit's load jumps, folds or changes stretch.
    fn marks(&self) -> Vec<f64> {
        crate::law::stretch::marks(self.stretches.iter().map(|s| (s.lo, s.hi)))
    }
}

/// A rough surface of wet summits, or (one range: `rho = 0`, `eta = 0` or `eta = 1`) the dry
/// model of section 9 with the single zone's lambda: the one rough model ([`Rough`]) over
/// either summit law.
pub enum WetRough {
    /// One zone: the dry model.
    Dry(Rough),
    /// Two zones of different ranges.
    Wet(Rough<WetSummit>),
}

impl SummitLaw for WetSummit {
    type State = usize;

    fn lambda(&self) -> f64 {
        self.ctx.zones.lambda[0]
    }

    fn approach_state(&self, delta: f64) -> usize {
        self.approach_stretch(delta)
    }

    fn retract_state(&self, delta: f64, delta_max: f64) -> usize {
        self.retract_stretch(delta, delta_max)
    }

    fn branch_of(&self, k: usize) -> SummitBranch {
        self.stretches[k].branch()
    }

    fn load_in(&self, k: usize, delta: f64) -> Option<f64> {
        self.load(k, delta)
    }

    fn marks(&self) -> Vec<f64> {
        WetSummit::marks(self)
    }

    fn retract_marks(&self) -> Vec<f64> {
        WetSummit::marks(self)
    }

    fn reach(&self) -> f64 {
        self.stretches
            .iter()
            .flat_map(|s| [-s.lo, -s.hi])
            .filter(|x| x.is_finite())
            .fold(0.0, f64::max)
    }

    fn smooth_pulloff(&self) -> f64 {
        self.ctx.load_pulloff.load
    }

    fn mean_area(&self, s: f64, leg: Leg, d: f64) -> Result<f64, RoughError> {
        let last = self.stretches.len() - 1;
        let lo = self.stretches[last].lo;
        // Summits in contact: on the approach above the jump into it, on the retract those whose
        // deepest approach reached it and that have not left it.
        let t_in = (d + self.approach_enter()) / s;
        let t0 = match leg {
            Leg::Approach => t_in,
            Leg::Retract { d_min } => {
                // Heights whose deepest approach z - d_min reached contact, still above lo.
                ((d_min + self.approach_enter()) / s).max((d + lo) / s)
            }
        }
        .max(-Z_CUT);
        if t0 >= Z_CUT {
            return Ok(0.0);
        }
        let failed = Cell::new(false);
        let f = |t: f64| {
            let g = (-0.5 * t * t).exp() / (2.0 * PI).sqrt();
            match self.contact_radius(t * s - d) {
                Some(a) => g * a * a,
                None => {
                    failed.set(true);
                    0.0
                }
            }
        };
        let v = integrate(&f, t0, Z_CUT).0;
        if failed.get() {
            return Err(RoughError::Failed(d, self.ctx.zones.lambda[0]));
        }
        Ok(v)
    }

    fn hysteresis(&self, sigma: f64, d_min: f64, d_max: f64) -> Result<f64, RoughError> {
        WetSummit::hysteresis(self, sigma, d_min, d_max)
    }
}

impl WetRough {
    /// Summits of the contact law `law` (MD, or the solid with its meniscus), heights N(0,
    /// sigma^2) in the law's approach unit: the one entry of the command line and Python.
    pub fn of_law(law: ContactLaw, sigma: f64) -> Result<WetRough, RoughError> {
        match law {
            ContactLaw::Md(Md { lambda }) => Ok(WetRough::Dry(Rough::new(lambda, sigma)?)),
            ContactLaw::SolidAndMeniscus(TwoZones {
                lambda,
                stress_ratio,
                range_ratio,
            }) => WetRough::new(lambda, stress_ratio, range_ratio, sigma),
            closed => Err(RoughError::Scene(
                format!(
                "rough summits of the {} law are not modelled: give md summits (a lambda), or a \
                 meniscus",
                closed.model().label()
            )
                .into(),
            )),
        }
    }

    /// Summits of solid Maugis parameter `lambda_s` with a second zone of stress ratio `rho` and
    /// range ratio `eta` (section 10), heights N(0, sigma^2) in the total-w approach unit.
    pub fn new(lambda_s: f64, rho: f64, eta: f64, sigma: f64) -> Result<WetRough, RoughError> {
        crate::physics::domain::check_lambda(lambda_s)?;
        for (name, v) in [
            ("the stress ratio rho = s2/s1", rho),
            ("the range ratio eta = h2/h1", eta),
        ] {
            if !(v.is_finite() && (0.0..=1e6).contains(&v)) {
                return Err(domain(
                    name,
                    v,
                    "0..1e6",
                    "give a finite ratio >= 0 (0: no meniscus)",
                )
                .into());
            }
        }
        let zones = Zones::from_ratios(lambda_s, rho, eta).map_err(zones_failed)?;
        match zones.shape() {
            Shape::Single { lambda } => Ok(WetRough::Dry(Rough::new(lambda, sigma)?)),
            Shape::Two { .. } => {
                // The roughness's check first, as for the dry model.
                let _ = Rough::new(lambda_s, sigma)?;
                Ok(WetRough::Wet(Rough {
                    summit: WetSummit::new(zones, Some(15.0 * sigma + 5.0))?,
                    sigma,
                }))
            }
        }
    }

    /// The single summit's load-controlled pull-off.
    pub fn smooth_pulloff(&self) -> f64 {
        match self {
            WetRough::Dry(r) => r.summit.smooth_pulloff(),
            WetRough::Wet(r) => r.summit.smooth_pulloff(),
        }
    }

    /// The mean load and branch fractions at separation `d`.
    pub fn mean(&self, leg: Leg, d: f64) -> Result<Mean, RoughError> {
        match self {
            WetRough::Dry(r) => r.mean(leg, d),
            WetRough::Wet(r) => r.mean(leg, d),
        }
    }

    /// The mean of A^2 over all summits (those not in contact count 0) at separation `d`.
    pub fn mean_area(&self, leg: Leg, d: f64) -> Result<f64, RoughError> {
        match self {
            WetRough::Dry(r) => r.mean_area(leg, d),
            WetRough::Wet(r) => r.mean_area(leg, d),
        }
    }

    /// The separation beyond which no summit within the kept range feels the flat.
    pub fn free_separation(&self) -> f64 {
        match self {
            WetRough::Dry(r) => r.free_separation(),
            WetRough::Wet(r) => r.free_separation(),
        }
    }

    /// The mean load of an explicit ensemble of summits of heights `z` at separation `d`, each
    /// on its own stretch.
    pub fn ensemble_load(&self, leg: Leg, z: &[f64], d: f64) -> Result<f64, RoughError> {
        Ok(match self {
            WetRough::Dry(r) => r.ensemble_mean(leg, z, d)?,
            WetRough::Wet(r) => r.ensemble_mean(leg, z, d)?,
        }
        .load)
    }

    /// The cycle from `d_max` (default [`WetRough::free_separation`]) down to `d_min` and back,
    /// reported with the solid's lambda `lambda_s`; its pull-off and energy loss are found
    /// exactly, whatever the number of separations.
    pub fn cycle(
        &self,
        lambda_s: f64,
        d_min: f64,
        d_max: Option<f64>,
        points: usize,
    ) -> Result<RoughCycle, RoughError> {
        let mut c = match self {
            WetRough::Dry(r) => r.cycle(d_min, d_max, points)?,
            WetRough::Wet(r) => r.cycle(d_min, d_max, points)?,
        };
        c.lambda = lambda_s;
        Ok(c)
    }

    /// The pull-off per summit after pressing to `d_min`: the retract sampled at `samples`
    /// separations up to where every summit is free again, then refined.
    pub fn pulloff_after(&self, d_min: f64, samples: usize) -> Result<(f64, f64), RoughError> {
        match self {
            WetRough::Dry(r) => r.pulloff_after(d_min, samples),
            WetRough::Wet(r) => r.pulloff_after(d_min, samples),
        }
    }
}
