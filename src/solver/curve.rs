//! The whole Maugis-Dugdale curve of one lambda, stable and unstable parts, with the stability
//! under both controls, ending at the A = 0 end (`tabor curve`).

use super::context::x_at_radius;
use super::{LambdaContext, SolveError};
use crate::physics::domain::{check_radius, DomainError};
use crate::physics::md::point;
use crate::physics::md::LAMBDA_D;
use serde::Serialize;

/// Most points of a curve (its rows are kept in memory).
pub const MAX_CURVE_POINTS: usize = 1_000_000;

#[derive(Clone, Copy, Debug, Serialize)]
/// One point of a curve.
pub struct CurveRow {
    #[serde(rename = "A")]
    /// Contact radius A.
    pub a: f64,
    /// Pbar.
    pub load: f64,
    /// Dbar.
    pub approach: f64,
    /// `inf` at the A = 0 end (written as null in JSON).
    #[serde(serialize_with = "finite_or_null")]
    pub m_minus_1: f64,
    /// dPbar/dA > 0.
    pub load_stable: bool,
    /// dDbar/dA > 0.
    pub displacement_stable: bool,
}

fn finite_or_null<S: serde::Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
    if x.is_finite() {
        s.serialize_f64(*x)
    } else {
        s.serialize_none()
    }
}

#[derive(Clone, Debug, Serialize)]
/// The whole MD curve of one lambda, from large A to the A -> 0 end.
pub struct Curve {
    /// The Maugis parameter.
    pub lambda: f64,
    /// The points, A falling.
    pub points: Vec<CurveRow>,
}

#[derive(Debug, thiserror::Error)]
/// Why a curve was not computed.
pub enum CurveError {
    #[error(transparent)]
    /// The solver failed.
    Solve(#[from] SolveError),
    #[error(transparent)]
    /// An input outside the domain.
    Domain(#[from] DomainError),
    #[error("points = {0} is out of range: give 2..=1000000")]
    /// The number of points is not in 2..=1_000_000.
    Points(usize),
}

/// `points` rows with A uniform from `a_max` down to 0, the last one the A = 0 end.
pub fn curve(lambda: f64, a_max: f64, points: usize) -> Result<Curve, CurveError> {
    let ctx = LambdaContext::new(lambda)?;
    check_radius(a_max)?;
    if !(2..=MAX_CURVE_POINTS).contains(&points) {
        return Err(CurveError::Points(points));
    }
    let mut rows: Vec<CurveRow> = (0..points - 1)
        .map(|i| {
            let a = a_max * (1.0 - i as f64 / (points - 1) as f64);
            let p = point(lambda, x_at_radius(lambda, a));
            CurveRow {
                a: p.a,
                load: p.load,
                approach: p.approach,
                m_minus_1: p.m_minus_1,
                load_stable: p.dload_dmu < 0.0,
                displacement_stable: p.dapproach_dmu < 0.0,
            }
        })
        .collect();
    let e = ctx.end;
    rows.push(CurveRow {
        a: 0.0,
        load: e.load,
        approach: e.approach,
        m_minus_1: f64::INFINITY,
        load_stable: false,
        displacement_stable: lambda <= LAMBDA_D,
    });
    Ok(Curve {
        lambda,
        points: rows,
    })
}
