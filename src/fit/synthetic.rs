//! Synthetic force curves from a model with known parameters, with Gaussian noise in the force:
//! what the fitter's recovery test, its benchmark and the gallery example are made of.

use super::data::Curve;
use super::problem::{forces_on, law_units};
use super::Model;
use super::{Geometry, Params, SyntheticError};
use crate::law::follow::{Direction, DrivenPath};
use crate::law::ContactLaw;
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

/// What a synthetic curve is made from (SI units).
#[derive(Clone, Debug)]
pub struct Synthetic {
    /// The model whose path under the cantilever gives the forces.
    pub model: Model,
    /// Its parameters (E*, w, lambda, contact point, force offset).
    pub params: Params,
    /// Tip radius R (m).
    pub radius: f64,
    /// Cantilever spring constant k (N/m).
    pub spring: f64,
    /// Points per segment (approach, then retract).
    pub points: usize,
    /// Deepest base displacement past the contact point, in approach units.
    pub depth: f64,
    /// Standard deviation of the force noise (N).
    pub noise: f64,
    /// The noise generator's seed (the curve's id is `synthetic-<seed>`).
    pub seed: u64,
}

/// Curve `i` of `curves` in the synthetic force map of the fitting example and benchmark
/// (`examples/synthetic_curves.rs`, `bench/fit_map.sh`): a 20 nm tip on a polymer-like sample,
/// w 0.04..0.07 J/m^2 and lambda 0.3..9.5 varying along the map, seeded by its index.
pub fn map_curve(i: usize, curves: usize, points: usize, spring: f64, noise: f64) -> Synthetic {
    let t = i as f64 / curves.max(2) as f64;
    Synthetic {
        model: Model::Md,
        params: Params {
            e_star: 2e9,
            w: 0.04 + 0.03 * t,
            lambda: 0.3 * 10f64.powf(1.5 * t),
            zc: 50e-9,
            f0: 0.0,
        },
        radius: 20e-9,
        spring,
        points,
        depth: 8.0,
        noise,
        seed: i as u64 + 1,
    }
}

/// The curve: the base goes from far away to `depth` past the contact point and back, the far
/// 40% of each segment beyond the last force (jump-out included), so a baseline can be taken.
///
/// Panics where the parameters are outside the model's domain: the generator of tests and
/// examples; [`try_synthetic`] returns the reason instead.
pub fn synthetic(s: &Synthetic) -> Curve {
    try_synthetic(s).unwrap_or_else(|e| panic!("synthetic curve: {e}"))
}

/// [`synthetic`], or why the parameters give no curve.
pub fn try_synthetic(s: &Synthetic) -> Result<Curve, SyntheticError> {
    made(s, None, Geometry::Sphere(s.radius))
}

/// [`try_synthetic`] on the tip `tip` (its `radius` ignored): the curve of the tip's law of
/// `s.model` (Sneddon's punch for Hertz, the JKR-type law, its Maugis-Dugdale).
pub fn try_synthetic_on(s: &Synthetic, tip: Geometry) -> Result<Curve, SyntheticError> {
    made(s, None, tip)
}

/// A curve of the two-zone law (`s.model` [`Model::SolidAndMeniscus`], `s.params` the solid's
/// E*, w and lambda) in a meniscus of stress `s2` (Pa) and range `h2` (m): what the two-zone
/// shape fit is tested on.
pub fn try_synthetic_wet(s: &Synthetic, meniscus: (f64, f64)) -> Result<Curve, SyntheticError> {
    if s.model != Model::SolidAndMeniscus {
        return Err(SyntheticError::WetModel(s.model.name()));
    }
    made(s, Some(meniscus), Geometry::Sphere(s.radius))
}

/// The curve of `s` (with the two-zone law's `meniscus`), or why its numbers give none.
fn made(
    s: &Synthetic,
    meniscus: Option<(f64, f64)>,
    tip: Geometry,
) -> Result<Curve, SyntheticError> {
    let p = s.params;
    let radius = tip.radius().unwrap_or(1.0);
    let finite = [
        p.e_star, p.w, p.lambda, p.zc, p.f0, radius, s.spring, s.depth,
    ];
    let positive = [p.e_star, p.w, radius, s.spring, s.depth];
    if !(finite.iter().all(|v| v.is_finite()) && positive.iter().all(|&v| v > 0.0)) {
        return Err(SyntheticError::Numbers {
            e_star: p.e_star,
            w: p.w,
            radius: s.radius,
            spring: s.spring,
            depth: s.depth,
        });
    }
    if !(s.noise >= 0.0 && s.noise.is_finite()) {
        return Err(SyntheticError::Noise(s.noise));
    }
    if !tip.fits(s.model) {
        return Err(SyntheticError::TipLaw(s.model.name()));
    }
    if s.model.has_lambda() && !tip.admits_lambda(p.lambda) {
        return Err(SyntheticError::Lambda(p.lambda));
    }
    let (law, u) = law_units(s.model, &p, tip, s.spring, meniscus);
    noisy(s, law, &u)
}

/// The curve of `s` on the path of `law` in its units `u`, with its noise.
fn noisy(s: &Synthetic, law: ContactLaw, u: &super::Units) -> Result<Curve, SyntheticError> {
    let p = s.params;
    let path = DrivenPath::of(law, u.kbar, s.depth);
    let reach = path.force_reach().min(0.0);
    // Delta from `low` (free) to `depth`: the force begins at `reach`.
    let span = s.depth - reach;
    let low = reach - span * 0.4 / 0.6;
    let n = s.points.max(2);
    let deltas: Vec<f64> = (0..n)
        .map(|i| low + (s.depth - low) * i as f64 / (n - 1) as f64)
        .collect();
    // Approach: Delta rises (the height falls); retract: back.
    let mut height: Vec<f64> = deltas.iter().map(|d| p.zc - d * u.approach).collect();
    height.extend(deltas.iter().rev().map(|d| p.zc - d * u.approach));
    let mut segment = vec![Direction::Approach; n];
    segment.extend(vec![Direction::Retract; n]);
    let (f, _, _, _) = forces_on(law, u, p.zc, &height, &segment, None, None)
        .ok_or(SyntheticError::Lambda(p.lambda))?;
    if let Some(i) = f.iter().position(|f| !f.is_finite()) {
        return Err(SyntheticError::Unsolved {
            model: s.model.label(),
            lambda: p.lambda,
            point: i,
        });
    }
    let mut rng = rand::rngs::StdRng::seed_from_u64(s.seed);
    let normal = Normal::new(0.0, s.noise).map_err(|_| SyntheticError::Noise(s.noise))?;
    let force = f
        .iter()
        .map(|f| {
            f + p.f0
                + if s.noise > 0.0 {
                    normal.sample(&mut rng)
                } else {
                    0.0
                }
        })
        .collect();
    Ok(Curve {
        id: format!("synthetic-{}", s.seed),
        x: None,
        y: None,
        segment,
        height,
        force,
        ..Curve::default()
    })
}
