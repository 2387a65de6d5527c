//! Force-overlap laws for particle (discrete-element) codes: the exact Maugis-Dugdale sphere
//! under displacement control, with its hysteresis, as a table that a DEM code evaluates per
//! contact and time step (docs/PHYSICS.md section 11).
//!
//! A contact's history is one [`Branch`]: far apart ([`Branch::Free`]), joined by the Dugdale
//! zone alone across a gap ([`Branch::NonContact`]), or in contact ([`Branch::Contact`]). The
//! overlap decides the next branch from the last one ([`DemLaw::next_branch`]): on the approach
//! a pair feels the attraction from `-h0`, lands on the non-contact branch where it is stable
//! (lambda below lambda_D) and enters contact at `delta_in`; on the retract it stays in contact
//! down to the fold under rigid grips, `delta_out`, then drops to the non-contact branch (down
//! to its own end, `delta_nc`) or comes free. The loop between the two paths is the energy a
//! slow collision loses ([`DemLaw::loop_area`]), the area of `tabor cycle`'s rigid-grip loop.
//!
//! The contact branch is a not-a-knot cubic spline in the graded variable `v` of
//! `u = sqrt(delta - delta_out)` (which takes the fold's square root out), with a step halved
//! until the error measured against exact solves at every interval's midpoint is within
//! [`TARGET`] of max(|Pbar_c|, |load|); the non-contact branch is its closed form. An
//! evaluation is two square roots and a cubic: no allocation, no solve, and a law is shared
//! read-only between threads (each contact keeps its own [`Branch`]).

use crate::physics::domain::{short, DomainError};
use crate::physics::params::Contact;
use crate::rough::map::{spline, u_of_v, v_of_u, TABLE_H};
use crate::rough::Summit;
use serde::Serialize;
use std::f64::consts::PI;

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

/// The branch a contact is on: its whole history as far as the law is concerned.
#[repr(u8)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Branch {
    /// Apart, beyond the force's reach (or released from it).
    #[default]
    Free = 0,
    /// Joined across a gap by the Dugdale zone alone (no contact, A = 0).
    NonContact = 1,
    /// In contact.
    Contact = 2,
}

impl Branch {
    /// The branch of a stored code (0, 1, 2), None for any other.
    pub fn from_code(code: u8) -> Option<Branch> {
        match code {
            0 => Some(Branch::Free),
            1 => Some(Branch::NonContact),
            2 => Some(Branch::Contact),
            _ => None,
        }
    }

    /// The name used in tables: `free`, `non_contact`, `contact`.
    pub fn name(self) -> &'static str {
        match self {
            Branch::Free => "free",
            Branch::NonContact => "non_contact",
            Branch::Contact => "contact",
        }
    }
}

/// One evaluation: the load and its slope along the branch the contact is on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Eval {
    /// The load (normalised `Pbar`, positive repulsive).
    pub load: f64,
    /// d load / d overlap on the branch (infinite at the contact branch's fold, where the
    /// branch is vertical; zero on the free branch).
    pub stiffness: f64,
    /// The branch after this overlap.
    pub branch: Branch,
    /// The overlap lies beyond the table (the last cubic is extrapolated).
    pub beyond_table: bool,
}

/// Why a law could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DemError {
    /// An input outside its domain.
    #[error(transparent)]
    Domain(#[from] DomainError),
    /// The pair's scene refused.
    #[error("{0}")]
    Scene(String),
    /// An exact solve of the contact branch failed (no table is built from a guess).
    #[error("the exact solver failed on the contact branch at overlap {} (lambda = {}): no table is built", short(*.0), short(*.1))]
    Failed(f64, f64),
    /// The table missed its target even at its finest step.
    #[error("the table of lambda = {} misses its 1e-6 target (error {}) at its finest step: no table is built", short(*.0), short(*.1))]
    Target(f64, f64),
}

/// The Maugis-Dugdale force-overlap law of one lambda, normalised (load `Pbar = P/(pi w R)`,
/// overlap `Dbar` in approach units `(pi^2 w^2 R / K^2)^(1/3)`).
#[derive(Debug)]
pub struct DemLaw {
    /// The Maugis parameter.
    pub lambda: f64,
    /// The Dugdale range, 2 / (pi lambda): the attraction starts at overlap `-h0`.
    pub h0: f64,
    /// The overlap where the approach enters contact.
    pub delta_in: f64,
    /// The contact branch's fold under rigid grips: the retract leaves contact below it.
    pub delta_out: f64,
    /// The non-contact branch's end on the retract (None above lambda_D: no stable branch).
    pub delta_nc: Option<f64>,
    /// The pull-off under load control, Pbar_c (the most tensile contact state).
    pub load_pulloff: f64,
    /// The load at the fold under rigid grips (where the retract leaves contact).
    pub disp_pulloff: f64,
    /// The largest overlap of the table.
    pub overlap_max: f64,
    /// The table's largest measured error, relative to max(|Pbar_c|, |load|).
    pub error: f64,
    /// The table's step in the graded variable.
    pub step: f64,
    /// The table's nodes.
    pub nodes: usize,
    c_star: f64,
    c_end: f64,
    table: Table,
    summit: Summit,
}

/// The contact branch's spline in the graded variable `v` of `u = sqrt(delta - delta_out)`.
#[derive(Debug)]
struct Table {
    delta_out: f64,
    inv_h: f64,
    coef: Vec<[f64; 4]>,
}

impl Table {
    /// The load and d load / d overlap at `delta`.
    #[inline(always)]
    fn at(&self, delta: f64) -> (f64, f64) {
        let u = (delta - self.delta_out).max(0.0).sqrt();
        let v = 2.0 * u / (1.0 + (1.0 + u * (2.0 / U_S)).sqrt());
        let x = v * self.inv_h;
        let last = self.coef.len() - 1;
        // x >= 0 here; the last interval's cubic beyond the table.
        let k = (x as usize).min(last);
        let s = x - k as f64;
        let c = &self.coef[k];
        let load = ((c[3] * s + c[2]) * s + c[1]) * s + c[0];
        let dload_dv = ((3.0 * c[3] * s + 2.0 * c[2]) * s + c[1]) * self.inv_h;
        // u = v + v^2 / (2 U_S), delta = delta_out + u^2.
        let stiffness = dload_dv / ((1.0 + v / U_S) * 2.0 * u);
        (load, stiffness)
    }
}

impl DemLaw {
    /// The law of `lambda`, its contact branch tabulated up to `overlap_max` (approach units).
    pub fn new(lambda: f64, overlap_max: f64) -> Result<DemLaw, DemError> {
        let summit = Summit::new(lambda).map_err(|e| DemError::Scene(e.to_string()))?;
        if !(overlap_max.is_finite()
            && overlap_max > summit.delta_out
            && overlap_max <= OVERLAP_MAX)
        {
            return Err(DomainError {
                name: "overlap_max",
                value: overlap_max,
                range: "(delta_out, 1e4] approach units",
                hint: "give a largest overlap above the contact branch's fold and at most 1e4 approach units",
            }
            .into());
        }
        let pc = summit.smooth_pulloff();
        let v_max = v_of_u((overlap_max - summit.delta_out).sqrt());
        let at = |v: f64| {
            let u = u_of_v(v);
            summit.delta_out + u * u
        };
        let exact = |d: f64| -> Result<f64, DemError> {
            summit
                .contact(d)
                .map(|c| c.0)
                .filter(|p| p.is_finite())
                .ok_or(DemError::Failed(d, lambda))
        };
        let mut h = TABLE_H;
        for halving in 0..=MAX_HALVINGS {
            // At least five nodes (the spline's minimum), one interval past the end.
            let n = ((v_max / h).ceil() as usize + 2).max(5);
            let vals = (0..n)
                .map(|k| exact(at(k as f64 * h)))
                .collect::<Result<Vec<_>, _>>()?;
            let table = Table {
                delta_out: summit.delta_out,
                inv_h: 1.0 / h,
                coef: spline(&vals),
            };
            // The error at every interval's midpoint.
            let mut err = 0.0f64;
            for k in 0..n - 1 {
                let d = at((k as f64 + 0.5) * h);
                let want = exact(d)?;
                let e = (table.at(d).0 - want).abs() / pc.abs().max(want.abs());
                // NaN compares false: a failed interpolation is a miss.
                err = if e.is_nan() {
                    f64::INFINITY
                } else {
                    err.max(e)
                };
            }
            if err <= TARGET {
                return Ok(DemLaw {
                    lambda,
                    h0: summit.h0,
                    delta_in: summit.delta_in,
                    delta_out: summit.delta_out,
                    delta_nc: summit.delta_nc,
                    load_pulloff: pc,
                    disp_pulloff: vals[0],
                    overlap_max,
                    error: err,
                    step: h,
                    nodes: n,
                    c_star: summit.c_star,
                    c_end: summit.c_end,
                    table,
                    summit,
                });
            }
            if halving == MAX_HALVINGS {
                return Err(DemError::Target(lambda, err));
            }
            h *= 0.5;
        }
        unreachable!("the loop returns at its last halving")
    }

    /// The contact branch at `delta` (from the table): the load and d load / d overlap.
    #[inline(always)]
    pub fn contact_branch(&self, delta: f64) -> (f64, f64) {
        self.table.at(delta)
    }

    /// The non-contact branch at `delta` (closed form, section 9): -(pi lambda / 2) C^2 with
    /// C = C* + sqrt(C*^2 + 2 (delta + h0)), capped at the contact branch's A -> 0 end.
    #[inline(always)]
    pub fn non_contact_branch(&self, delta: f64) -> (f64, f64) {
        let root = (self.c_star * self.c_star + 2.0 * (delta + self.h0)).max(0.0);
        let r = root.sqrt();
        let c = self.c_star + r;
        if c >= self.c_end {
            let c = self.c_end;
            return (-(PI * self.lambda / 2.0) * c * c, 0.0);
        }
        (-(PI * self.lambda / 2.0) * c * c, -PI * self.lambda * c / r)
    }

    /// The branch after overlap `delta`, coming from `prev` (the history's one rule).
    #[inline(always)]
    pub fn next_branch(&self, prev: Branch, delta: f64) -> Branch {
        let nc_from = self.delta_nc.unwrap_or(f64::INFINITY);
        match prev {
            Branch::Free if delta >= self.delta_in => Branch::Contact,
            Branch::Free if delta >= -self.h0 => Branch::NonContact,
            Branch::Free => Branch::Free,
            Branch::NonContact if delta >= self.delta_in => Branch::Contact,
            Branch::NonContact if delta >= nc_from => Branch::NonContact,
            Branch::NonContact => Branch::Free,
            Branch::Contact if delta >= self.delta_out => Branch::Contact,
            Branch::Contact if delta >= nc_from => Branch::NonContact,
            Branch::Contact => Branch::Free,
        }
    }

    /// The load and stiffness at overlap `delta` for a contact whose history is `history`,
    /// which is updated. A NaN overlap gives a NaN load and leaves the history.
    // Inlined into the caller's loop: measured 41 ns per evaluation as a call, about 21 inlined.
    #[inline(always)]
    pub fn eval(&self, delta: f64, history: &mut Branch) -> Eval {
        if delta.is_nan() {
            return Eval {
                load: f64::NAN,
                stiffness: f64::NAN,
                branch: *history,
                beyond_table: false,
            };
        }
        let b = self.next_branch(*history, delta);
        *history = b;
        let (load, stiffness) = match b {
            Branch::Free => (0.0, 0.0),
            Branch::NonContact => self.non_contact_branch(delta),
            Branch::Contact => self.contact_branch(delta),
        };
        Eval {
            load,
            stiffness,
            branch: b,
            beyond_table: b == Branch::Contact && delta > self.overlap_max,
        }
    }

    /// The exact load on `branch` at `delta` (the contact branch solved, not interpolated).
    pub fn exact(&self, branch: Branch, delta: f64) -> Option<f64> {
        match branch {
            Branch::Free => Some(0.0),
            Branch::NonContact => Some(self.non_contact_branch(delta).0),
            Branch::Contact => self.summit.contact(delta).map(|c| c.0),
        }
    }

    /// The smallest overlap where any force acts on the retract: the non-contact branch's end,
    /// or the fold where the pair comes free.
    pub fn lowest_overlap(&self) -> f64 {
        self.delta_nc.unwrap_or(self.delta_out).min(-self.h0)
    }

    /// The energy lost in one slow cycle from apart to `overlap_max` and back (normalised by
    /// `pi w R` times the approach unit): the area between the approach and the retract, from
    /// the exact branches by double-exponential quadrature between the jumps. Zero where the
    /// cycle does not reach the attraction.
    pub fn loop_area(&self, overlap_max: f64) -> Option<f64> {
        // The approach's and the retract's branch at each overlap of this cycle.
        let app = |d: f64| self.next_branch(Branch::Free, d);
        let reached = app(overlap_max);
        let ret = |d: f64| self.next_branch(reached, d);
        let mut cuts = vec![
            self.lowest_overlap(),
            -self.h0,
            self.delta_in,
            self.delta_out,
        ];
        cuts.extend(self.delta_nc);
        cuts.retain(|&c| c < overlap_max);
        cuts.push(overlap_max);
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let failed = std::cell::Cell::new(false);
        let mut area = 0.0;
        for w in cuts.windows(2) {
            let mid = 0.5 * (w[0] + w[1]);
            let (ba, br) = (app(mid), ret(mid));
            if ba == br {
                continue;
            }
            let f = |d: f64| match (self.exact(ba, d), self.exact(br, d)) {
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

    /// The whole cycle from `overlap_min` (apart: below `-h0`) to `overlap_max` and back, at
    /// `points` overlaps each way: `(approach, retract)`, each a list of (overlap, eval).
    pub fn drive(
        &self,
        overlap_min: f64,
        overlap_max: f64,
        points: usize,
    ) -> (Vec<(f64, Eval)>, Vec<(f64, Eval)>) {
        let mut history = Branch::Free;
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

/// A pair of bodies in SI units: the normalised law and its scales.
#[derive(Debug)]
pub struct Pair {
    /// The contact (effective radius, reduced modulus, w, Dugdale stress).
    pub contact: Contact,
    /// The normalised law.
    pub law: DemLaw,
    /// Newtons per unit of `Pbar`: pi w R.
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
    /// The branch after this overlap.
    pub branch: Branch,
    /// The overlap lies beyond the table.
    pub beyond_table: bool,
}

impl Pair {
    /// The pair of `contact`, tabulated up to `overlap_max_m` (m).
    pub fn new(contact: Contact, overlap_max_m: f64) -> Result<Pair, DemError> {
        let length_scale = contact.approach_scale();
        let force_scale = contact.force_scale();
        if !(overlap_max_m.is_finite() && overlap_max_m > 0.0) {
            return Err(DomainError {
                name: "overlap_max_m",
                value: overlap_max_m,
                range: "above 0 m",
                hint: "give the largest overlap the particles reach, in m",
            }
            .into());
        }
        let law = DemLaw::new(contact.lambda(), overlap_max_m / length_scale).map_err(|e| match e {
            DemError::Domain(d) if d.name == "overlap_max" => DemError::Scene(format!(
                "overlap_max_m = {} m is {} approach units ({} m each), beyond the 1e4 a table covers: give a smaller overlap_max_m",
                short(overlap_max_m),
                short(d.value),
                short(length_scale)
            )),
            e => e,
        })?;
        Ok(Pair {
            contact,
            law,
            force_scale,
            length_scale,
        })
    }

    /// The pair of a scene file (`tabor scene`'s keys: the bodies or E* and R, w, and the range),
    /// tabulated up to `overlap_max_m` (default [`DEFAULT_OVERLAP_MAX`] approach units). Keys
    /// the dry law under displacement control does not use are refused, not ignored.
    pub fn from_scene(
        s: &crate::scene::SceneInput,
        overlap_max_m: Option<f64>,
    ) -> Result<Pair, DemError> {
        let unused = [
            ("humidity", s.humidity.is_some()),
            ("loads_n", s.loads_n.is_some()),
            ("load_range_n", s.load_range_n.is_some()),
            ("control", s.control.is_some()),
            ("tolerance", s.tolerance.is_some()),
            ("shear_strength_pa", s.shear_strength_pa.is_some()),
        ];
        if let Some((key, _)) = unused.iter().find(|k| k.1) {
            return Err(DemError::Scene(format!(
                "`{key}` is not used by the DEM law (a dry pair under displacement control): remove it"
            )));
        }
        let contact = crate::scene::contact_of(s).map_err(|e| DemError::Scene(e.to_string()))?;
        let max = overlap_max_m.unwrap_or(DEFAULT_OVERLAP_MAX * contact.approach_scale());
        Pair::new(contact, max)
    }

    /// The force and stiffness at `overlap_m` (m, positive interpenetrating) for a contact whose
    /// history is `history` (updated).
    #[inline(always)]
    pub fn eval(&self, overlap_m: f64, history: &mut Branch) -> EvalSi {
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
