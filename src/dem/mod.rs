//! Force-overlap laws for particle (discrete-element) codes: any contact law of `crate::law`
//! with a rigid-grip path (Maugis-Dugdale, the solid with a water meniscus, a tip) under
//! displacement control, with its hysteresis, as a table that a DEM code evaluates per contact
//! and time step (docs/PHYSICS.md section 11).
//!
//! The law's equilibrium path is cut into its **stretches**, the runs on which the approach
//! rises along the path: the states stable under displacement control. The first is the free
//! branch, the last the contact branch from its rigid-grip fold up; between them lie the
//! non-contact stretches (the cohesive zone, or the meniscus and the solid's zone, across a gap).
//! A contact's whole history is the stretch it is on ([`History`], one byte). On the approach a
//! contact follows its stretch to the top and jumps, at that overlap, to the next stretch of the
//! path that holds it; on the retract it follows it to the bottom and jumps to the previous one
//! holding it, or comes free. The loop between the two paths is the energy a slow collision
//! loses ([`DemLaw::loop_area`]), the area of `tabor cycle`'s rigid-grip loop.
//!
//! Each stretch is tabulated as a cubic spline in a variable that takes a fold's square root
//! out: the open contact stretch in `u = sqrt(delta - delta_out)`, graded as `u = v + v^2 /
//! (2 U_S)`; a bounded stretch in the angle theta of `delta = lo + (hi - lo)(1 - cos theta)/2`,
//! smooth at a fold at either end. At an end without a fold the spline is given a zero slope in
//! its variable (the stiffness is finite there). The step is halved until the error measured
//! against exact states at every interval's midpoint is within [`TARGET`] of max(|Pbar_c|,
//! |load|). The exact state at an overlap is the law's own: a bracketed Newton search in the
//! stretch's path parameter. An evaluation is a comparison or two, a square root (an arc cosine
//! on a non-contact stretch) and a cubic: no allocation, no solve, and a law is shared read-only
//! between threads (each contact keeps its own [`History`]).

use crate::error::Message;
use crate::law::stretch::{StretchError, Stretches};
use crate::law::{ContactLaw, Law};
use crate::physics::domain::{short, DomainError};
use crate::physics::params::Contact;
use crate::rough::map::{spline, u_of_v, v_of_u, TABLE_H};

/// The table's target: its measured error at the midpoints, relative to max(|Pbar_c|, |load|).
pub const TARGET: f64 = 1e-6;
/// The largest overlap a table may cover (approach units): a contact radius of about 100
/// approach units, far beyond small strain for any real pair.
pub const OVERLAP_MAX: f64 = 1e4;
/// The largest overlap a table covers where none is given (approach units).
pub const DEFAULT_OVERLAP_MAX: f64 = 10.0;
/// The table's step is halved at most this many times (to TABLE_H / 256).
const MAX_HALVINGS: u32 = 8;
/// The graded variable's scale (the rough map's: `u = v + v^2 / (2 U_S)`).
const U_S: f64 = 4.0;
/// The most stretches a law may have (the history is one byte).
const MAX_STRETCHES: usize = 64;

pub use crate::law::Branch;

/// A contact's history: the stretch of its law's path it is on (one byte; 0, free, for a new
/// contact). Made valid for its law by [`DemLaw::history`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct History(u8);

impl History {
    /// A new contact: apart (the free stretch, code 0).
    pub const NEW: History = History(0);

    /// The byte a particle code stores.
    pub fn code(self) -> u8 {
        self.0
    }
}

/// One evaluation: the load and its slope along the stretch the contact is on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Eval {
    /// The load (normalised `Pbar`, positive repulsive).
    pub load: f64,
    /// d load / d overlap on the stretch (infinite at a fold, where the stretch is vertical;
    /// zero on the free branch).
    pub stiffness: f64,
    /// The kind of stretch after this overlap.
    pub branch: Branch,
    /// The overlap lies beyond the table (the last cubic is extrapolated).
    pub beyond_table: bool,
}

impl crate::error::Named for DemError {
    fn named(&self, names: crate::error::Names) -> String {
        match self {
            DemError::Domain(e) => e.named(names),
            DemError::Scene(m) => m.named(names),
            DemError::Law(e) => e.named(names),
            e => e.to_string(),
        }
    }
}

/// Why a law could not be built.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DemError {
    /// An input outside its domain.
    #[error(transparent)]
    Domain(#[from] DomainError),
    /// The contact law refused (its numbers, or a law without a rigid-grip cycle).
    #[error(transparent)]
    Law(#[from] crate::law::LawError),
    /// The law's path could not be cut into its stretches.
    #[error(transparent)]
    Stretch(#[from] StretchError),
    /// The pair's scene refused.
    #[error("{0}")]
    Scene(Message),
    /// An exact state of a stretch failed (no table is built from a guess).
    #[error("the exact {} state at overlap {} failed (lambda = {}): no table is built", .0.name(), short(*.1), short(*.2))]
    Failed(Branch, f64, f64),
    /// The table missed its target even at its finest step.
    #[error("the table of lambda = {} misses its 1e-6 target (error {}) at its finest step: no table is built", short(*.0), short(*.1))]
    Target(f64, f64),
}

/// How a table's spline variable is had from the overlap.
#[derive(Clone, Copy, Debug)]
enum Var {
    /// The open contact stretch: `u = sqrt(delta - origin)` (the fold's square root taken out)
    /// and `v` graded, `u = v + v^2 / (2 U_S)`.
    Root { origin: f64 },
    /// A bounded stretch: the angle `theta` of `delta = lo + width (1 - cos theta) / 2`, which
    /// takes out a fold's square root at either end (`sqrt((delta - lo)(hi - delta))` is
    /// `width sin(theta) / 2`) and keeps an end without a fold smooth.
    Arc { lo: f64, width: f64 },
}

/// A cubic spline of the load at uniform steps of its variable. Where an end is not a fold the
/// load's slope in the variable is zero there (a finite stiffness over a vanishing root): the
/// spline is made with that slope (through the values mirrored about the end), and the
/// stiffness at the end itself is its limit, from the spline's second derivative there.
#[derive(Debug)]
struct Segment {
    var: Var,
    inv_h: f64,
    coef: Vec<[f64; 4]>,
    /// Whether the low and the high end are without a fold (a zero slope in the variable).
    flat: (bool, bool),
}

impl Segment {
    /// The overlap at spline variable `v`.
    fn delta(&self, v: f64) -> f64 {
        match self.var {
            Var::Root { origin } => {
                let u = u_of_v(v);
                origin + u * u
            }
            Var::Arc { lo, width } => lo + width * 0.5 * (1.0 - v.cos()),
        }
    }

    /// The load and d load / d overlap at `delta`.
    #[inline(always)]
    fn at(&self, delta: f64) -> (f64, f64) {
        let (v, dv) = match self.var {
            Var::Root { origin } => {
                let u = (delta - origin).max(0.0).sqrt();
                if u == 0.0 && self.flat.0 {
                    // P = P0 + c2 (v / h)^2 and v -> u = sqrt(delta - origin) at the end.
                    let c = &self.coef[0];
                    return (c[0], c[2] * self.inv_h * self.inv_h);
                }
                let v = 2.0 * u / (1.0 + (1.0 + u * (2.0 / U_S)).sqrt());
                // dv/ddelta = (dv/du) (du/ddelta); infinite at the fold itself.
                (v, 1.0 / ((1.0 + v / U_S) * 2.0 * u))
            }
            Var::Arc { lo, width } => {
                let y = ((delta - lo) / width).clamp(0.0, 1.0);
                let q = (y * (1.0 - y)).sqrt();
                if q == 0.0 {
                    // P = P_end + P''(theta_end) phi^2 / 2 with phi^2 = 4 |delta - end| / width.
                    let h2 = self.inv_h * self.inv_h / width;
                    let (c0, c1) = (&self.coef[0], &self.coef[self.coef.len() - 1]);
                    match y == 0.0 {
                        true if self.flat.0 => return (c0[0], 4.0 * c0[2] * h2),
                        false if self.flat.1 => {
                            let end = c1[0] + c1[1] + c1[2] + c1[3];
                            return (end, -2.0 * (2.0 * c1[2] + 6.0 * c1[3]) * h2);
                        }
                        _ => {}
                    }
                }
                // dtheta/ddelta = 1 / (width sqrt(y (1 - y))): infinite at a fold.
                ((1.0 - 2.0 * y).acos(), 1.0 / (width * q))
            }
        };
        let s = v * self.inv_h;
        let last = self.coef.len() - 1;
        // s >= 0 here; the last interval's cubic beyond the table.
        let k = (s as usize).min(last);
        let s = s - k as f64;
        let c = &self.coef[k];
        let load = ((c[3] * s + c[2]) * s + c[1]) * s + c[0];
        let dload_dv = ((3.0 * c[3] * s + 2.0 * c[2]) * s + c[1]) * self.inv_h;
        (load, dload_dv * dv)
    }
}

/// The not-a-knot spline of `vals`, with a zero slope at each end flagged `zero` (the values
/// mirrored about it, so that the spline is symmetric there): the intervals of `vals` alone.
fn spline_with(vals: &[f64], zero: (bool, bool)) -> Vec<[f64; 4]> {
    let n = vals.len();
    let mut y: Vec<f64> = Vec::with_capacity(3 * n);
    if zero.0 {
        y.extend(vals[1..].iter().rev());
    }
    let first = y.len();
    y.extend_from_slice(vals);
    if zero.1 {
        y.extend(vals[..n - 1].iter().rev());
    }
    spline(&y)[first..first + n - 1].to_vec()
}

/// The force-overlap law of one contact law, normalised (the law's load and approach units:
/// `Pbar = P/(pi w R)`, overlap `Dbar` in `(pi^2 w^2 R / K^2)^(1/3)`, with the total w where a
/// meniscus adds its own).
#[derive(Debug)]
pub struct DemLaw {
    /// The contact law.
    pub law: ContactLaw,
    /// The (solid's) Maugis parameter.
    pub lambda: f64,
    /// The overlap where the attraction starts on the approach (`-h0` for Maugis-Dugdale; the
    /// meniscus's reach with one).
    pub attraction_from: f64,
    /// The overlap where the approach enters contact.
    pub delta_in: f64,
    /// The contact branch's fold under rigid grips: the retract leaves contact below it.
    pub delta_out: f64,
    /// Where the retract, after leaving contact, finally comes free (None: it comes free at the
    /// jump out of contact).
    pub delta_nc: Option<f64>,
    /// The pull-off under load control, Pbar_c (the most tensile contact state).
    pub load_pulloff: f64,
    /// The load at the fold under rigid grips (where the retract leaves contact).
    pub disp_pulloff: f64,
    /// The largest overlap of the table.
    pub overlap_max: f64,
    /// The table's largest measured error, relative to max(|Pbar_c|, |load|).
    pub error: f64,
    /// The contact table's step in its graded variable.
    pub step: f64,
    /// The tables' nodes.
    pub nodes: usize,
    stretches: Stretches,
    /// Each stretch's table (None on the free branch).
    tables: Vec<Option<Segment>>,
}

impl DemLaw {
    /// The Maugis-Dugdale law of `lambda`, tabulated up to `overlap_max` (approach units).
    pub fn new(lambda: f64, overlap_max: f64) -> Result<DemLaw, DemError> {
        DemLaw::of_law(ContactLaw::md(lambda), overlap_max)
    }

    /// The force-overlap law of `law` (a law with a rigid-grip cycle: Maugis-Dugdale, the
    /// two-zone law, a tip), tabulated up to `overlap_max` (its approach units).
    pub fn of_law(law: ContactLaw, overlap_max: f64) -> Result<DemLaw, DemError> {
        // The law's own checks (its numbers; a closed form has no path to follow).
        law.check()?;
        if !(overlap_max.is_finite() && overlap_max <= OVERLAP_MAX) {
            return Err(range_error(overlap_max));
        }
        let lambda = law.lambda().unwrap_or(f64::NAN);
        let stretches = Stretches::of(&law, overlap_max)?;
        if stretches.list.len() > MAX_STRETCHES {
            return Err(DemError::Scene(format!(
                "the law's path has {} stretches, more than the {MAX_STRETCHES} a history byte holds",
                stretches.list.len()
            ).into()));
        }
        let free_end = stretches.list[0].hi;
        let delta_out = stretches.list.last().map_or(f64::NAN, |s| s.lo);
        if !(overlap_max > delta_out) {
            return Err(range_error(overlap_max));
        }
        let pc = stretches.load_pulloff;
        let mut dem = DemLaw {
            law,
            lambda,
            attraction_from: free_end,
            delta_in: f64::NAN,
            delta_out,
            delta_nc: None,
            load_pulloff: pc,
            disp_pulloff: f64::NAN,
            overlap_max,
            error: 0.0,
            step: f64::NAN,
            nodes: 0,
            stretches,
            tables: Vec::new(),
        };
        dem.tabulate()?;
        dem.delta_in = dem.stretches.entry();
        let (out, free_from) = dem.stretches.exit();
        dem.delta_nc = free_from;
        dem.delta_out = dem.stretches.list[out].lo;
        dem.disp_pulloff = dem.exact_on(out, dem.delta_out).ok_or(DemError::Failed(
            Branch::Contact,
            dem.delta_out,
            lambda,
        ))?;
        Ok(dem)
    }

    /// The tables of every stretch but the free one, each halving its step until it meets
    /// [`TARGET`].
    fn tabulate(&mut self) -> Result<(), DemError> {
        let n = self.stretches.list.len();
        let mut tables = vec![None];
        for k in 1..n {
            let (table, err, h) = self.segment(k)?;
            self.error = self.error.max(err);
            self.nodes += table.coef.len() + 1;
            if k == n - 1 {
                self.step = h;
            }
            tables.push(Some(table));
        }
        self.tables = tables;
        Ok(())
    }

    /// Stretch `k` tabulated: its table, the table's measured error and its step.
    fn segment(&self, k: usize) -> Result<(Segment, f64, f64), DemError> {
        use rayon::prelude::*;
        let s = &self.stretches.list[k];
        let scale = self.load_pulloff.abs();
        let exact = |d: f64| {
            self.exact_on(k, d)
                .ok_or(DemError::Failed(s.branch, d, self.lambda))
        };
        let var = if s.hi.is_infinite() {
            Var::Root { origin: s.lo }
        } else {
            Var::Arc {
                lo: s.lo,
                width: s.top - s.lo,
            }
        };
        // An end without a fold: the spline's slope in its variable is zero there.
        let flat = (!s.fold.0, !s.fold.1 && !s.hi.is_infinite());
        let mut h = TABLE_H;
        for halving in 0..=MAX_HALVINGS {
            // The open contact stretch: steps of h in v, one interval past the end. A bounded
            // one: at least four intervals spanning its angle 0..pi exactly.
            let (n, step) = match var {
                Var::Root { origin } => {
                    let v_max = v_of_u((self.overlap_max - origin).max(0.0).sqrt());
                    (((v_max / h).ceil() as usize + 2).max(5), h)
                }
                Var::Arc { .. } => {
                    let n = ((std::f64::consts::PI / h).ceil() as usize).max(4);
                    (n + 1, std::f64::consts::PI / n as f64)
                }
            };
            let mut seg = Segment {
                var,
                inv_h: 1.0 / step,
                coef: Vec::new(),
                flat,
            };
            let vals = (0..n)
                .into_par_iter()
                .map(|i| exact(seg.delta(i as f64 * step)))
                .collect::<Result<Vec<_>, _>>()?;
            seg.coef = spline_with(&vals, flat);
            // The error at every interval's midpoint.
            let errs = (0..n - 1)
                .into_par_iter()
                .map(|i| {
                    let d = seg.delta((i as f64 + 0.5) * step);
                    let want = exact(d)?;
                    let e = (seg.at(d).0 - want).abs() / scale.max(want.abs());
                    // NaN compares false: a failed interpolation is a miss.
                    Ok(if e.is_nan() { f64::INFINITY } else { e })
                })
                .collect::<Result<Vec<f64>, DemError>>()?;
            let err = errs.into_iter().fold(0.0f64, f64::max);
            if err <= TARGET {
                return Ok((seg, err, step));
            }
            if halving == MAX_HALVINGS {
                return Err(DemError::Target(self.lambda, err));
            }
            h *= 0.5;
        }
        unreachable!("the loop returns at its last halving")
    }

    /// The history of a stored code, None where the code names no stretch of this law.
    pub fn history(&self, code: u8) -> Option<History> {
        ((code as usize) < self.stretches.list.len()).then_some(History(code))
    }

    /// The kind of stretch a history is on (free for a history of another law with more
    /// stretches).
    pub fn branch(&self, history: History) -> Branch {
        self.stretches
            .list
            .get(history.0 as usize)
            .map_or(Branch::Free, |s| s.branch)
    }

    /// The overlaps the stretch of `history` holds: its low and high end (-inf and +inf at the
    /// path's ends).
    pub fn stretch_range(&self, history: History) -> (f64, f64) {
        self.stretches
            .list
            .get(history.0 as usize)
            .map_or((f64::NAN, f64::NAN), |s| (s.lo, s.hi))
    }

    /// The number of stretches: every history code is below it.
    pub fn stretch_count(&self) -> usize {
        self.stretches.list.len()
    }

    /// The contact branch at `delta` (from the table): the load and d load / d overlap.
    #[inline(always)]
    pub fn contact_branch(&self, delta: f64) -> (f64, f64) {
        self.at(self.tables.len() - 1, delta)
    }

    /// The load and d load / d overlap on stretch `k`'s table at `delta`.
    #[inline(always)]
    fn at(&self, k: usize, delta: f64) -> (f64, f64) {
        match &self.tables[k] {
            None => (0.0, 0.0),
            Some(t) => t.at(delta),
        }
    }

    /// The history after overlap `delta`, coming from `history` (without evaluating the load).
    pub fn next_history(&self, history: History, delta: f64) -> History {
        History(self.stretches.next(history.0 as usize, delta) as u8)
    }

    /// The load and stiffness at overlap `delta` for a contact whose history is `history`,
    /// which is updated. A NaN or infinite overlap gives a NaN load and leaves the history (an
    /// overlap of -inf is apart).
    // Inlined into the caller's loop: a call costs about twice the evaluation.
    #[inline(always)]
    pub fn eval(&self, delta: f64, history: &mut History) -> Eval {
        // A history of another law, with more stretches, is taken as a new contact's.
        let list = &self.stretches.list;
        let from = match history.0 as usize {
            k if k < list.len() => k,
            _ => 0,
        };
        if delta.is_nan() || delta == f64::INFINITY {
            return Eval {
                load: f64::NAN,
                stiffness: f64::NAN,
                branch: list[from].branch,
                beyond_table: false,
            };
        }
        let k = self.stretches.next(from, delta);
        *history = History(k as u8);
        let (load, stiffness) = self.at(k, delta);
        Eval {
            load,
            stiffness,
            branch: list[k].branch,
            beyond_table: k == list.len() - 1 && delta > self.overlap_max,
        }
    }

    /// The exact load at `delta` on stretch `k` (clamped into it).
    fn exact_on(&self, k: usize, delta: f64) -> Option<f64> {
        self.stretches.exact(&self.law, k, delta)
    }

    /// The exact load on the stretch a contact with history `history` is on at `delta` (no
    /// table): what the table is measured against. None for a history of another law.
    pub fn exact(&self, history: History, delta: f64) -> Option<f64> {
        self.exact_on(history.0 as usize, delta)
    }

    /// The exact load on the contact branch at `delta`.
    pub fn exact_contact(&self, delta: f64) -> Option<f64> {
        self.exact_on(self.stretches.list.len() - 1, delta)
    }

    /// The smallest overlap where any force acts on the retract: where it comes free, or the
    /// attraction's start.
    pub fn lowest_overlap(&self) -> f64 {
        self.stretches.lowest()
    }

    /// The energy lost in one slow cycle from apart to `overlap_max` and back (normalised by
    /// `pi w R` times the approach unit): the area between the approach and the retract, from
    /// the exact stretches by double-exponential quadrature between the marks. Zero where the
    /// cycle does not reach the attraction; None for a largest overlap that is not finite.
    pub fn loop_area(&self, overlap_max: f64) -> Option<f64> {
        self.stretches.loop_area(&self.law, overlap_max)
    }

    /// The whole cycle from `overlap_min` (apart: below the attraction) to `overlap_max` and
    /// back, at `points` overlaps each way: `(approach, retract)`, each a list of (overlap,
    /// eval).
    pub fn drive(
        &self,
        overlap_min: f64,
        overlap_max: f64,
        points: usize,
    ) -> (Vec<(f64, Eval)>, Vec<(f64, Eval)>) {
        let mut history = History::NEW;
        let at =
            |k: usize| overlap_min + (overlap_max - overlap_min) * k as f64 / (points - 1) as f64;
        let approach: Vec<_> = (0..points)
            .map(|k| (at(k), self.eval(at(k), &mut history)))
            .collect();
        let retract: Vec<_> = (0..points)
            .rev()
            .map(|k| (at(k), self.eval(at(k), &mut history)))
            .collect();
        (approach, retract)
    }
}

fn range_error(overlap_max: f64) -> DemError {
    DomainError {
        name: "overlap_max",
        value: overlap_max,
        range: "(delta_out, 1e4] approach units",
        hint:
            "give a largest overlap above the contact branch's fold and at most 1e4 approach units",
    }
    .into()
}

/// A pair of bodies in SI units: the normalised law and its scales.
#[derive(Debug)]
pub struct Pair {
    /// The contact (effective radius, reduced modulus, w, Dugdale stress).
    pub contact: Contact,
    /// The water meniscus between them, where the scene's humidity forms one.
    pub meniscus: Option<crate::scene::humidity::Meniscus>,
    /// The normalised law.
    pub law: DemLaw,
    /// Newtons per unit of `Pbar`: pi w R (w the total with a meniscus).
    pub force_scale: f64,
    /// Metres per approach unit: (pi^2 w^2 R / K^2)^(1/3).
    pub length_scale: f64,
}

/// One evaluation in SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EvalSi {
    /// The normal force (N, positive repulsive).
    pub force_n: f64,
    /// d force / d overlap (N/m).
    pub stiffness_n_m: f64,
    /// The kind of stretch after this overlap.
    pub branch: Branch,
    /// The overlap lies beyond the table.
    pub beyond_table: bool,
}

impl Pair {
    /// The dry pair of `contact`, tabulated up to `overlap_max_m` (m).
    pub fn new(contact: Contact, overlap_max_m: f64) -> Result<Pair, DemError> {
        Pair::with_meniscus(contact, None, Some(overlap_max_m))
    }

    /// The pair of `contact` with the water meniscus `meniscus` (the two-zone law in the units
    /// of the total w) or dry, tabulated up to `overlap_max_m` (m; None: [`DEFAULT_OVERLAP_MAX`]
    /// approach units).
    pub fn with_meniscus(
        contact: Contact,
        meniscus: Option<crate::scene::humidity::Meniscus>,
        overlap_max_m: Option<f64>,
    ) -> Result<Pair, DemError> {
        let (law, force_scale, length_scale) = match &meniscus {
            None => (
                ContactLaw::md(contact.lambda()),
                contact.force_scale(),
                contact.approach_scale(),
            ),
            Some(m) => {
                let (rho, eta, units) = crate::scene::humidity::wet_ratios(&contact, m)
                    .map_err(|e| DemError::Scene(e.to_string().into()))?;
                (
                    ContactLaw::solid_and_meniscus(contact.lambda(), rho, eta),
                    units.load,
                    units.approach,
                )
            }
        };
        let overlap_max_m = overlap_max_m.unwrap_or(DEFAULT_OVERLAP_MAX * length_scale);
        if !(overlap_max_m.is_finite() && overlap_max_m > 0.0) {
            return Err(DomainError {
                name: "overlap_max_m",
                value: overlap_max_m,
                range: "above 0 m",
                hint: "give the largest overlap the particles reach, in m",
            }
            .into());
        }
        let law = DemLaw::of_law(law, overlap_max_m / length_scale).map_err(|e| match e {
            DemError::Domain(d) if d.name == "overlap_max" => DemError::Scene(
                Message::new()
                    .key("overlap_max_m")
                    .text(format!(
                        " = {} m is {} approach units ({} m each), beyond the 1e4 a table covers: give a smaller ",
                        short(overlap_max_m),
                        short(d.value),
                        short(length_scale)
                    ))
                    .key("overlap_max_m"),
            ),
            e => e,
        })?;
        Ok(Pair {
            contact,
            meniscus,
            law,
            force_scale,
            length_scale,
        })
    }

    /// The pair of a scene file (`tabor scene`'s keys: the bodies or E* and R, w, the range, and
    /// a humidity for a meniscus), tabulated up to `overlap_max_m` (default
    /// [`DEFAULT_OVERLAP_MAX`] approach units). Keys the law under displacement control does not
    /// use are refused, not ignored.
    pub fn from_scene(
        s: &crate::scene::SceneInput,
        overlap_max_m: Option<f64>,
    ) -> Result<Pair, DemError> {
        let unused = [
            ("loads_n", s.loads_n.is_some()),
            ("load_range_n", s.load_range_n.is_some()),
            ("control", s.control.is_some()),
            ("tolerance", s.tolerance.is_some()),
            ("shear_strength_pa", s.shear_strength_pa.is_some()),
        ];
        if let Some((key, _)) = unused.iter().find(|k| k.1) {
            return Err(DemError::Scene(
                format!(
                "`{key}` is not used by the DEM law (a pair under displacement control): remove it"
            )
                .into(),
            ));
        }
        let contact =
            crate::scene::contact_of(s).map_err(|e| DemError::Scene(e.to_string().into()))?;
        let meniscus = match &s.humidity {
            None => None,
            Some(h) => h
                .meniscus(&contact)
                .map_err(|e| DemError::Scene(e.to_string().into()))?,
        };
        Pair::with_meniscus(contact, meniscus, overlap_max_m)
    }

    /// The force and stiffness at `overlap_m` (m, positive interpenetrating) for a contact whose
    /// history is `history` (updated).
    #[inline(always)]
    pub fn eval(&self, overlap_m: f64, history: &mut History) -> EvalSi {
        let e = self.law.eval(overlap_m / self.length_scale, history);
        EvalSi {
            force_n: e.load * self.force_scale,
            stiffness_n_m: e.stiffness * self.force_scale / self.length_scale,
            branch: e.branch,
            beyond_table: e.beyond_table,
        }
    }

    /// The energy lost in one slow cycle to `overlap_max_m` and back (J).
    pub fn loop_energy_j(&self, overlap_max_m: f64) -> Option<f64> {
        self.law
            .loop_area(overlap_max_m / self.length_scale)
            .map(|a| a * self.force_scale * self.length_scale)
    }
}
