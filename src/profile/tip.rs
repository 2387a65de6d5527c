//! A tip's pressure and gap (docs/PHYSICS.md section 12): the shape's adhesion-free pressure and
//! gap at the contact radius plus Maugis's adhesive field, which depends on (A, C, lambda) alone
//! and is section 8's Maugis-Dugdale field less its Hertz part. Units of section 12 (radii in l,
//! gaps in d, pressure in `pi w / d`, so that the Dugdale stress is lambda/2 and
//! `Pbar = 2 pi int p r dr`).

use super::{radii, Given, ProfileStatus, MAX_PROFILE_POINTS};
use crate::law::tip::{self, Tip};
use crate::law::Given as State;
use crate::physics::fields::{hertz_gap, hertz_pressure, MdGeometry};
use crate::solver::Status;
use serde::Serialize;
use std::f64::consts::PI;

/// A tip state's pressure and gap.
#[derive(Clone, Debug, Serialize)]
pub struct TipProfile {
    /// The tip's Maugis parameter.
    pub lambda: f64,
    /// The shape, in a sentence.
    pub tip: String,
    /// Always `normalised` (section 12's units).
    pub units: &'static str,
    /// The Dugdale range h0 = 2/(pi lambda) in the gap's unit.
    pub dugdale_range: f64,
    /// The Dugdale stress lambda/2 in the pressure's unit.
    pub dugdale_stress: f64,
    /// `ok`, or `no_contact` below the pull-off of the control (empty arrays).
    pub status: ProfileStatus,
    /// The contact radius.
    pub a: Option<f64>,
    /// The Dugdale zone's outer radius.
    pub c: Option<f64>,
    /// The load.
    pub load: Option<f64>,
    /// The approach.
    pub approach: Option<f64>,
    /// The sampling radii (clustered at a and c).
    pub r: Vec<f64>,
    /// Compressive positive; null at a cone's apex (logarithmically infinite).
    pub pressure: Vec<Option<f64>>,
    /// The surface gap (0 inside the contact).
    pub gap: Vec<f64>,
    /// The J-integral through the Dugdale zone over w, `(pi lambda/2) gap(C)`: 1 at equilibrium.
    pub energy_release_rate_over_w: Option<f64>,
}

impl crate::error::Named for TipProfileError {
    fn named(&self, names: crate::error::Names) -> String {
        match self {
            TipProfileError::Points(n) => {
                format!(
                    "{} = {n}: give 16 to 100000 sampling points",
                    names("points").unwrap_or("points")
                )
            }
            TipProfileError::Law(e) => e.named(names),
            e => e.to_string(),
        }
    }
}

/// Why a tip's profile was not computed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TipProfileError {
    /// The number of points is out of range.
    #[error("points = {0}: give 16 to 100000 sampling points")]
    Points(usize),
    /// The law's own refusal.
    #[error(transparent)]
    Law(#[from] crate::law::LawError),
    /// The value given is not a finite number (or a radius not above 0).
    #[error("{0} = {1}: give a finite number (a radius above 0)")]
    Value(&'static str, f64),
}

/// The profile of `law`'s state fixed by `given`, at about `points` radii.
pub fn tip_profile(law: Tip, given: Given, points: usize) -> Result<TipProfile, TipProfileError> {
    if !(16..=MAX_PROFILE_POINTS).contains(&points) {
        return Err(TipProfileError::Points(points));
    }
    let law = Tip::new(law.shape, law.lambda)?;
    let (g, value, name) = match given {
        Given::Load(p) => (State::Load, p, "load"),
        Given::Approach(d) => (State::Approach, d, "approach"),
        Given::Radius(a) => (State::Radius, a, "radius"),
    };
    let lambda = law.lambda;
    let mut out = TipProfile {
        lambda,
        tip: law.shape.label(),
        units: "normalised",
        dugdale_range: 2.0 / (PI * lambda),
        dugdale_stress: 0.5 * lambda,
        status: ProfileStatus::NoContact,
        a: None,
        c: None,
        load: None,
        approach: None,
        r: Vec::new(),
        pressure: Vec::new(),
        gap: Vec::new(),
        energy_release_rate_over_w: None,
    };
    let (status, point) = tip::solve(law.shape, lambda, g, value);
    let p = match (status, point) {
        (Status::Ok, Some(p)) => p,
        (Status::InvalidInput, _) => return Err(TipProfileError::Value(name, value)),
        _ => return Ok(out),
    };
    let (a, c) = (p.a, p.c);
    let adhesive = MdGeometry {
        lambda,
        a,
        mu: ((c - a) * (c + a)).sqrt() / a,
    };
    let shape = law.shape;
    let gap = |r: f64| shape.hertz_gap(a, r) + adhesive.gap(r) - hertz_gap(a, r);
    out.r = radii(2.0 * c, points, &[a, c]);
    out.pressure = out
        .r
        .iter()
        .map(|&r| {
            shape
                .hertz_pressure(a, r)
                .map(|h| h + adhesive.pressure(r) - hertz_pressure(a, r))
        })
        .collect();
    out.gap = out.r.iter().map(|&r| gap(r)).collect();
    out.energy_release_rate_over_w = Some(0.5 * PI * lambda * gap(c));
    out.status = ProfileStatus::Ok;
    (out.a, out.c, out.load, out.approach) = (Some(a), Some(c), Some(p.load), Some(p.approach));
    Ok(out)
}
