//! Maugis-Dugdale (docs/PHYSICS.md sections 1 to 4): one Dugdale zone of stress `s0` over the
//! range `h0`. Its path: the free piece, the non-contact piece (the zone alone, t = C, a
//! quadratic in C), the contact piece (t = -ln mu, mu = m - 1 + ... by `physics::md`).

use super::path::{check_drive, contact_radii, non_contact_ts, point_of, Branch, Drive, PathPoint};
use super::{cache, Law, LawError, LawKey, Piece, Pt, A_START};
use crate::physics::md::{curve_point, curve_point_dlambda, non_contact_point, zero_radius_end};
use crate::physics::model::ContactModel;
use crate::solver::context::{x_at_radius, x_at_radius_newton};
use crate::solver::LambdaContext;
use serde::Serialize;
use std::f64::consts::PI;

/// Maugis-Dugdale at its Maugis parameter (in the solver's domain, checked by the operations).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Md {
    /// The Maugis parameter.
    pub lambda: f64,
}

/// Points per stretch of a cycle's sampled path.
pub(crate) const CYCLE_POINTS: usize = 400;

impl Law for Md {
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
                let (load, approach) = non_contact_point(lambda, t);
                Pt {
                    load,
                    approach,
                    a: 0.0,
                    dload: -PI * lambda * t,
                    dapproach: t - 8.0 * lambda / (3.0 * PI),
                    da: 0.0,
                }
            }
            Piece::Contact => {
                let mu = (-t).exp();
                let c = curve_point(lambda, mu);
                Pt {
                    load: c.load,
                    approach: c.approach,
                    a: c.a,
                    dload: -mu * c.dload_dmu,
                    dapproach: -mu * c.dapproach_dmu,
                    da: -mu * c.da_dmu,
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
                let (_, dload, dapproach) = curve_point_dlambda(lambda, (-t).exp());
                (dload, dapproach)
            }
        }
    }
    /// The Dugdale zone's reach.
    fn free_end(&self) -> f64 {
        -2.0 / (PI * self.lambda)
    }
    /// A Newton search in x = ln mu, kept per thread (a fit at fixed lambda asks for the same
    /// radii again).
    fn t_of_radius(&self, a: f64) -> f64 {
        -cache::radius(self.key(), a, || x_at_radius_newton(self.lambda, a))
    }
    fn pieces(&self, a_max: f64) -> Vec<(Piece, f64, f64)> {
        let contact = (
            Piece::Contact,
            self.t_of_radius(A_START),
            self.t_of_radius(a_max),
        );
        let c_end = zero_radius_end(self.lambda).c;
        vec![(Piece::NonContact, 0.0, c_end), contact]
    }
    fn pulloff(&self) -> f64 {
        crate::physics::closed::cos_pulloff(self.lambda).abs()
    }
    /// The non-contact piece is a quadratic in C: one fold at most.
    fn node_count(&self, piece: Piece) -> usize {
        if piece == Piece::NonContact {
            64
        } else {
            super::NODES
        }
    }
    fn key(&self) -> LawKey {
        (ContactModel::Md, [self.lambda.to_bits(), 0, 0, 0])
    }
    /// The contact piece's zone radius is m A.
    fn point(&self, piece: Piece, t: f64) -> PathPoint {
        if piece != Piece::Contact {
            return point_of(piece, t, &self.state(piece, t));
        }
        contact_at_mu(self.lambda, (-t).exp())
    }
    fn cycle_path(&self, drive: Drive, max_load: f64) -> Result<Vec<(Piece, f64)>, LawError> {
        crate::solver::domain::check_lambda(self.lambda)
            .map_err(crate::solver::SolveError::from)?;
        check_drive(drive, max_load)?;
        Ok(cycle_samples(self.lambda, max_load, CYCLE_POINTS))
    }
    fn check(&self) -> Result<(), LawError> {
        crate::solver::domain::check_lambda(self.lambda)
            .map_err(crate::solver::SolveError::from)?;
        Ok(())
    }
    /// The retract's fold of the contact branch, to the solver's precision: the pull-offs of
    /// the solver's context, or under a spring a bisection in A around the sampled fold.
    fn fold(&self, drive: Drive, near: &PathPoint) -> Option<PathPoint> {
        let lambda = self.lambda;
        let ctx = LambdaContext::new(lambda).ok()?;
        let exact = match drive {
            Drive::RigidGrips => ctx.disp_pulloff(),
            Drive::DeadLoad => ctx.load_pulloff,
            Drive::Spring(k) => {
                // Where the control's slope along the curve changes sign (the control rises
                // with A on the stable side).
                let slope = |a: f64| {
                    let p = curve_point(lambda, x_at_radius(lambda, a).exp());
                    p.dapproach_dmu + p.dload_dmu / k
                };
                let (mut lo, mut hi) = (0.8 * near.a, 1.25 * near.a + 1e-300);
                if (slope(lo) > 0.0) == (slope(hi) > 0.0) {
                    return None;
                }
                for _ in 0..200 {
                    let m = 0.5 * (lo + hi);
                    if (slope(m) > 0.0) == (slope(lo) > 0.0) {
                        lo = m;
                    } else {
                        hi = m;
                    }
                }
                return Some(contact_point(lambda, 0.5 * (lo + hi)));
            }
        };
        (exact.a > 0.0).then(|| contact_point(lambda, exact.a))
    }
}

/// The contact branch's state at radius `a`.
fn contact_point(lambda: f64, a: f64) -> PathPoint {
    contact_at_mu(lambda, x_at_radius(lambda, a).exp())
}

/// The contact branch's state at `mu`.
fn contact_at_mu(lambda: f64, mu: f64) -> PathPoint {
    let p = curve_point(lambda, mu);
    PathPoint {
        branch: Branch::Contact,
        approach: p.approach,
        load: p.load,
        a: p.a,
        c: (p.m_minus_1 + 1.0) * p.a,
    }
}

/// Where a cycle samples the path up to load `max_load`, `n` points per stretch: the
/// non-contact piece evenly in C, the contact piece at `contact_radii`. `lambda` must be in
/// the solver's domain.
pub fn cycle_samples(lambda: f64, max_load: f64, n: usize) -> Vec<(Piece, f64)> {
    let end = zero_radius_end(lambda);
    let mut path = non_contact_ts(end.c, n);
    let Ok(ctx) = LambdaContext::new(lambda) else {
        return Vec::new();
    };
    let a_max = ctx.solve_load(max_load).a;
    let a_mid = a_max.min(ctx.solve_load(10.0).a);
    path.extend(
        contact_radii(a_mid, a_max, n)
            .into_iter()
            .map(|a| (Piece::Contact, -x_at_radius(lambda, a))),
    );
    path
}
