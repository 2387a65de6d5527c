//! Maugis-Dugdale for an axisymmetric tip (docs/PHYSICS.md section 12): a power law (cone,
//! sphere, blunt tips; pyramids as their equivalent cone) or a capped cone, in the shape's
//! normalised units. Its path: the free piece, the non-contact piece (the zone alone, t = C),
//! the contact piece (t = ln A, mu the root of equation (1t) at each A).

use super::path::{check_drive, contact_radii, non_contact_ts, point_of, Branch, Drive, PathPoint};
use super::{Given, Law, LawError, LawKey, Piece, Pt, A_START};
use crate::numeric::root::{bisect_sign, newton_bracketed};
use crate::physics::model::ContactModel;
use crate::physics::tip::Shape;
use crate::solver::Status;
use serde::Serialize;
use std::f64::consts::PI;

/// Maugis-Dugdale on a tip of shape `shape` at its Maugis parameter.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Tip {
    /// The tip in its normalised units.
    #[serde(flatten)]
    pub shape: Shape,
    /// The shape's Maugis parameter `(3/2) s0 l / (E* d)` (section 12).
    pub lambda: f64,
}

/// The lambda a tip is solved over (the sphere's is wider: section 5.1).
pub const LAMBDA_RANGE: (f64, f64) = (1e-3, 1e3);

/// A contact state at radius A with its slopes in A (dA/dA = 1) and in lambda.
#[derive(Clone, Copy, Debug)]
struct Contact {
    a: f64,
    m: f64,
    load: f64,
    approach: f64,
    dload: f64,
    dapproach: f64,
    /// The sizes of the terms the slopes are differences of: their rounding is ~1e-16 of
    /// these (near A = 0 the terms grow like 1/A while the slopes fall).
    dload_terms: f64,
    dapproach_terms: f64,
    dload_dlambda: f64,
    dapproach_dlambda: f64,
}

impl Tip {
    /// The tip's law, after the checks of its numbers.
    pub fn new(shape: Shape, lambda: f64) -> Result<Tip, LawError> {
        let (lo, hi) = LAMBDA_RANGE;
        if !(lambda >= lo && lambda <= hi) {
            return Err(
                crate::solver::SolveError::from(crate::solver::domain::DomainError {
                    name: "the tip's Maugis parameter lambda",
                    value: lambda,
                    range: "[1e-3, 1e3]",
                    hint: "a tip is solved for lambda from 1e-3 to 1e3 (change s0 or h0)",
                })
                .into(),
            );
        }
        Ok(Tip { shape, lambda })
    }

    /// `K(mu) = mu atan mu - (m - 1)` of equation (1t) and its slope.
    fn k(mu: f64, m: f64) -> (f64, f64) {
        let at = mu.atan();
        (
            mu * at - mu * mu / (1.0 + m),
            at + mu / (1.0 + mu * mu) - mu / m,
        )
    }

    /// ln mu at contact radius `a`: (1t) at fixed A rises with mu (`dJbar/dmu > 0`, K rising),
    /// so one root, by Newton's method safeguarded in a bracket (for any profile; at fixed mu
    /// (1t) may have several roots in A where `Fbar'` is not monotone, as at a capped cone's
    /// joint, so the contact piece is parametrised by A).
    fn ln_mu_at(&self, a: f64) -> f64 {
        let lambda = self.lambda;
        let h = |x: f64| {
            let mu = x.exp();
            let m = mu.hypot(1.0);
            let (j, _, jmu) = self.shape.gap(a, mu);
            let (k, dk) = Self::k(mu, m);
            (
                lambda * j + 4.0 / 3.0 * lambda * lambda * k * a - 1.0,
                mu * (lambda * jmu + 4.0 / 3.0 * lambda * lambda * dk * a),
            )
        };
        // A start from the sphere's DMT-side scale: C ~ a few units.
        let x0 = (2.0 / a.max(1e-300)).ln().clamp(-60.0, 60.0);
        newton_bracketed(h, -60.0, 60.0, x0)
    }

    /// The contact state at radius `a` (equations (1t) to (3t)) with its slopes in A and in
    /// lambda.
    fn contact_at(&self, a: f64) -> Contact {
        let lambda = self.lambda;
        let mu = self.ln_mu_at(a).exp();
        let m = mu.hypot(1.0);
        let (j, ja, jmu) = self.shape.gap(a, mu);
        let (k, dk) = Self::k(mu, m);
        // (1t) is G(A, mu) = 0: dmu/dA and dmu/dlambda by implicit differentiation.
        let g_a = lambda * ja + 4.0 / 3.0 * lambda * lambda * k;
        let g_mu = lambda * jmu + 4.0 / 3.0 * lambda * lambda * dk * a;
        let dmu = -g_a / g_mu;
        let dmu_dlambda = -(j + 8.0 / 3.0 * lambda * k * a) / g_mu;
        let (q, dq) = self.shape.load(a);
        let (f, df) = self.shape.abel(a);
        let s = mu + m * m * mu.atan();
        let ds = 2.0 + 2.0 * mu * mu.atan();
        Contact {
            a,
            m,
            load: q - lambda * a * a * s,
            approach: f - 4.0 / 3.0 * lambda * a * mu,
            dload: dq - 2.0 * lambda * a * s - lambda * a * a * ds * dmu,
            dapproach: df - 4.0 / 3.0 * lambda * (mu + a * dmu),
            dload_terms: dq.abs() + 2.0 * lambda * a * s.abs() + (lambda * a * a * ds * dmu).abs(),
            dapproach_terms: df.abs() + 4.0 / 3.0 * lambda * (mu.abs() + (a * dmu).abs()),
            dload_dlambda: -a * a * s - lambda * a * a * ds * dmu_dlambda,
            dapproach_dlambda: -4.0 / 3.0 * a * (mu + lambda * dmu_dlambda),
        }
    }

    /// The non-contact piece's end, the contact piece's A -> 0 limit: the root C of
    /// `(pi lambda/2) fbar(C) + (2 (pi - 2) lambda^2/3) C = 1`.
    pub fn zone_end(&self) -> f64 {
        let lambda = self.lambda;
        let qb = 2.0 * (PI - 2.0) * lambda * lambda / 3.0;
        let h = |c: f64| PI * lambda / 2.0 * self.shape.profile(c).0 + qb * c - 1.0;
        bisect_sign(h, 0.0, 1.0 / qb)
    }

    /// The contact branch's state at radius `a`, with its zone radius.
    pub fn at_radius(&self, a: f64) -> PathPoint {
        self.contact_point(a.ln())
    }

    /// The contact branch's point at parameter t = ln A.
    fn contact_point(&self, t: f64) -> PathPoint {
        let c = self.contact_at(t.exp());
        PathPoint {
            branch: Branch::Contact,
            approach: c.approach,
            load: c.load,
            a: c.a,
            c: c.m * c.a,
        }
    }

    /// The control's slope along the contact piece under `drive` (per unit A), and the size of
    /// the terms it is a difference of.
    fn control_slope(&self, drive: Drive, t: f64) -> (f64, f64) {
        let c = self.contact_at(t.exp());
        match drive {
            Drive::RigidGrips => (c.dapproach, c.dapproach_terms),
            Drive::DeadLoad => (c.dload, c.dload_terms),
            Drive::Spring(k) => (
                c.dapproach + c.dload / k,
                c.dapproach_terms + c.dload_terms / k.abs(),
            ),
        }
    }

    /// The fold a retract under `drive` leaves the contact piece from: coming down from large
    /// radii, the first t where the control stops rising; None where it rises all the way from
    /// the A -> 0 end (the pull-off is at that end).
    fn extreme(&self, drive: Drive) -> Option<f64> {
        let t0 = self.t_of_radius(A_START);
        let t1 = self.t_of_radius(1e3);
        let n = 400;
        let mut above = t1;
        for i in (0..n).rev() {
            let t = t0 + (t1 - t0) * i as f64 / n as f64;
            // A fold only where the slope falls clearly below zero: near A = 0 a rising
            // control's slope tends to zero under a rounding noise that can cross it.
            let (slope, terms) = self.control_slope(drive, t);
            if slope <= -1e-13 * terms {
                return Some(bisect_sign(|t| self.control_slope(drive, t).0, t, above));
            }
            above = t;
        }
        None
    }

    /// The pull-off under `drive` (dead load or rigid grips): the state at the fold of the
    /// contact branch, or its A -> 0 end where the branch has no fold.
    pub fn pulloff_state(&self, drive: Drive) -> PathPoint {
        match self.extreme(drive) {
            Some(t) => self.contact_point(t),
            None => {
                let c = self.zone_end();
                let (load, approach) = (
                    -PI * self.lambda / 2.0 * c * c,
                    -4.0 / 3.0 * self.lambda * c,
                );
                PathPoint {
                    branch: Branch::Contact,
                    approach,
                    load,
                    a: 0.0,
                    c,
                }
            }
        }
    }

    /// Where the contact piece is stable under `drive` (a dead load or rigid grips): from its
    /// fold up, or all of it where the control rises from the A -> 0 end on.
    pub fn stable_from(&self, drive: Drive) -> f64 {
        self.extreme(drive)
            .unwrap_or_else(|| self.t_of_radius(A_START))
    }

    /// The contact state stable under `drive` at `value` of its control (the load under a dead
    /// load, the approach under rigid grips), the stable piece starting at `t0`
    /// ([`Tip::stable_from`]); None below the control's pull-off (no contact) or beyond
    /// A = e^60.
    pub fn stable_at(&self, drive: Drive, t0: f64, value: f64) -> Option<PathPoint> {
        let f = |t: f64| {
            let s = self.state(Piece::Contact, t);
            match drive {
                Drive::RigidGrips => (s.approach - value, s.dapproach),
                _ => (s.load - value, s.dload),
            }
        };
        if !(f(t0).0 <= 0.0) {
            return None;
        }
        let (mut lo, mut hi) = (t0, t0 + 1.0);
        while f(hi).0 < 0.0 {
            lo = hi;
            hi += 1.0;
            if hi > 60.0 {
                return None;
            }
        }
        let t = newton_bracketed(f, lo, hi, 0.5 * (lo + hi));
        Some(self.contact_point(t))
    }

    /// The state stable under `drive` at `value` of its control ([`Tip::stable_at`] from that
    /// drive's fold).
    pub fn state_under(&self, drive: Drive, value: f64) -> Option<PathPoint> {
        self.stable_at(drive, self.stable_from(drive), value)
    }

    /// The stable state under a dead load `p` ([`Tip::stable_at`]).
    pub fn at_load_above(&self, t0: f64, p: f64) -> Option<PathPoint> {
        self.stable_at(Drive::DeadLoad, t0, p)
    }

    /// The state at approach `dbar` on the way in under rigid grips, following the path
    /// without a jump as a quasi-static indentation does: the free surfaces while the gap
    /// exceeds the range (`dbar` below [`Law::free_end`]), the zone alone (the non-contact
    /// piece, where its approach rises) up to its end at A -> 0, then the contact piece's
    /// stable part (where the contact piece folds, large lambda, its stable part from the
    /// fold). None beyond A = e^60.
    pub fn approach_state(&self, dbar: f64) -> Option<PathPoint> {
        if dbar < self.free_end() {
            return Some(PathPoint {
                branch: Branch::Free,
                approach: dbar,
                load: 0.0,
                a: 0.0,
                c: 0.0,
            });
        }
        // The zone's end and the grips' stable start, once per law and thread (a curve's
        // points share them).
        let (c_end, t0) = super::cache::ends(self.key(), || {
            (self.zone_end(), self.stable_from(Drive::RigidGrips))
        });
        let zone = |c: f64| self.state(Piece::NonContact, c);
        if dbar >= zone(c_end).approach {
            // Between the zone's end and the contact piece's first node (A = 1e-9): its start.
            return self.stable_at(Drive::RigidGrips, t0, dbar).or_else(|| {
                (dbar < self.contact_point(t0).approach).then(|| self.contact_point(t0))
            });
        }
        // The non-contact piece's approach falls from the free end while fbar' < 8 lambda /
        // (3 pi), then rises to its end: the root on the rising part.
        let lowest = if zone(0.0).dapproach < 0.0 {
            bisect_sign(|c| zone(c).dapproach, 0.0, c_end)
        } else {
            0.0
        };
        let c = bisect_sign(|c| zone(c).approach - dbar, lowest, c_end);
        let p = zone(c);
        Some(PathPoint {
            branch: Branch::NonContact,
            approach: p.approach,
            load: p.load,
            a: 0.0,
            c,
        })
    }

    /// Whether the contact piece at radius `a` is stable under `drive` (its control rises).
    pub fn stable_under(&self, drive: Drive, a: f64) -> bool {
        self.control_slope(drive, self.t_of_radius(a)).0 > 0.0
    }
}

/// A shape's identity in a law's cache key: its kind and its numbers' bits.
pub(super) fn shape_bits(shape: &Shape) -> [u64; 3] {
    match *shape {
        Shape::Power { exponent } => [1, exponent.to_bits(), 0],
        Shape::CappedCone { rho, half_angle } => [2, rho.to_bits(), half_angle.to_bits()],
        // A measured table is one leaked allocation: its address is its identity, and its
        // length unit gives the height unit.
        Shape::Measured(p) => [3, p.table_address(), p.length().to_bits()],
    }
}

/// The state of `shape` at `lambda` given by `value` of `given`, with its status: `NoContact`
/// below the pull-off of the control, `InvalidInput` for a lambda outside [`LAMBDA_RANGE`], a
/// value that is not finite or a radius not above zero (the point then None).
pub fn solve(shape: Shape, lambda: f64, given: Given, value: f64) -> (Status, Option<PathPoint>) {
    let Ok(tip) = Tip::new(shape, lambda) else {
        return (Status::InvalidInput, None);
    };
    if !value.is_finite() || (given == Given::Radius && !(value > 0.0)) {
        return (Status::InvalidInput, None);
    }
    let point = match given {
        Given::Radius => Some(tip.at_radius(value)),
        Given::Load => tip.state_under(Drive::DeadLoad, value),
        Given::Approach => tip.state_under(Drive::RigidGrips, value),
    };
    match point {
        Some(p) => (Status::Ok, Some(p)),
        None => (Status::NoContact, None),
    }
}

/// [`Tip::approach_state`] of `shape` at `lambda`, with its status as [`solve`]'s (`Ok` on every
/// branch, the free one included; `NoContact` beyond A = e^60).
pub fn approach_in(shape: Shape, lambda: f64, value: f64) -> (Status, Option<PathPoint>) {
    let Ok(tip) = Tip::new(shape, lambda) else {
        return (Status::InvalidInput, None);
    };
    if !value.is_finite() {
        return (Status::InvalidInput, None);
    }
    match tip.approach_state(value) {
        Some(p) => (Status::Ok, Some(p)),
        None => (Status::NoContact, None),
    }
}

impl Law for Tip {
    fn model(&self) -> ContactModel {
        ContactModel::Md
    }
    fn lambda(&self) -> Option<f64> {
        Some(self.lambda)
    }
    fn state(&self, piece: Piece, t: f64) -> Pt {
        let lambda = self.lambda;
        match piece {
            Piece::Free => Pt::free(t),
            Piece::NonContact => {
                let (f, df) = self.shape.profile(t);
                Pt {
                    load: -PI * lambda / 2.0 * t * t,
                    approach: f - 8.0 * lambda / (3.0 * PI) * t - 2.0 / (PI * lambda),
                    a: 0.0,
                    dload: -PI * lambda * t,
                    dapproach: df - 8.0 * lambda / (3.0 * PI),
                    da: 0.0,
                }
            }
            Piece::Contact => {
                let a = t.exp();
                let c = self.contact_at(a);
                Pt {
                    load: c.load,
                    approach: c.approach,
                    a: c.a,
                    dload: a * c.dload,
                    dapproach: a * c.dapproach,
                    da: a,
                }
            }
        }
    }
    fn state_dlambda(&self, piece: Piece, t: f64) -> (f64, f64) {
        let lambda = self.lambda;
        match piece {
            Piece::Free => (0.0, 0.0),
            Piece::NonContact => (
                -PI / 2.0 * t * t,
                -8.0 / (3.0 * PI) * t + 2.0 / (PI * lambda * lambda),
            ),
            Piece::Contact => {
                let c = self.contact_at(t.exp());
                (c.dload_dlambda, c.dapproach_dlambda)
            }
        }
    }
    fn free_end(&self) -> f64 {
        -2.0 / (PI * self.lambda)
    }
    /// The contact piece's parameter is ln A.
    fn t_of_radius(&self, a: f64) -> f64 {
        a.ln()
    }
    fn pieces(&self, a_max: f64) -> Vec<(Piece, f64, f64)> {
        vec![
            (Piece::NonContact, 0.0, self.zone_end()),
            (
                Piece::Contact,
                self.t_of_radius(A_START),
                self.t_of_radius(a_max),
            ),
        ]
    }
    fn pulloff(&self) -> f64 {
        self.pulloff_state(Drive::DeadLoad).load.abs()
    }
    fn key(&self) -> LawKey {
        let shape = shape_bits(&self.shape);
        (
            ContactModel::Md,
            [self.lambda.to_bits(), shape[0], shape[1], shape[2]],
        )
    }
    fn check(&self) -> Result<(), LawError> {
        Tip::new(self.shape, self.lambda)?;
        Ok(())
    }
    /// The contact piece's zone radius is m A.
    fn point(&self, piece: Piece, t: f64) -> PathPoint {
        match piece {
            Piece::Contact => self.contact_point(t),
            _ => point_of(piece, t, &self.state(piece, t)),
        }
    }
    fn cycle_path(&self, drive: Drive, max_load: f64) -> Result<Vec<(Piece, f64)>, LawError> {
        Tip::new(self.shape, self.lambda)?;
        check_drive(drive, max_load)?;
        let n = super::md::CYCLE_POINTS;
        let mut path = non_contact_ts(self.zone_end(), n);
        let t0 = self.stable_from(Drive::DeadLoad);
        let radius_at = |p: f64| self.at_load_above(t0, p).map_or(f64::NAN, |s| s.a);
        let a_max = radius_at(max_load);
        let a_mid = a_max.min(radius_at(10.0));
        if !(a_max > 0.0) {
            return Err(LawError::Unsupported {
                model: ContactModel::Md,
                what: "state at the cycle's largest load (raise max_load)",
            });
        }
        path.extend(
            contact_radii(a_mid, a_max, n)
                .into_iter()
                .map(|a| (Piece::Contact, self.t_of_radius(a))),
        );
        Ok(path)
    }
    /// The fold nearest the sampled one: under dead load or rigid grips the retract's fold
    /// ([`Tip::pulloff_state`]'s), under a spring the sign change of its control's slope in the
    /// cell of a fixed grid in t nearest the sampled fold (so the result does not depend on
    /// where in that cell the sample lay).
    fn fold(&self, drive: Drive, near: &PathPoint) -> Option<PathPoint> {
        if near.a <= 0.0 {
            return None;
        }
        if !matches!(drive, Drive::Spring(_)) {
            return self.extreme(drive).map(|t| self.contact_point(t));
        }
        let slope = |t: f64| self.control_slope(drive, t).0;
        let h = 0.01;
        let k0 = (self.t_of_radius(near.a) / h).floor() as i64;
        for d in 0..400 {
            for k in [k0 + d, k0 - d - 1] {
                let (lo, hi) = (k as f64 * h, (k + 1) as f64 * h);
                if slope(lo) < 0.0 && slope(hi) > 0.0 {
                    return Some(self.contact_point(bisect_sign(slope, lo, hi)));
                }
            }
        }
        None
    }
}
