//! Synthetic force curves from a model with known parameters, with Gaussian noise in the force:
//! what the fitter's recovery test, its benchmark and the gallery example are made of.

use super::data::Curve;
use super::path::{Direction, Model, SpringPath};
use super::{model_forces, units, Params};
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

#[derive(Clone, Debug)]
pub struct Synthetic {
    pub model: Model,
    pub params: Params,
    pub radius: f64,
    pub spring: f64,
    /// Points per segment (approach, then retract).
    pub points: usize,
    /// Deepest base displacement past the contact point, in approach units.
    pub depth: f64,
    /// Standard deviation of the force noise (N).
    pub noise: f64,
    pub seed: u64,
}

/// The curve: the base goes from far away to `depth` past the contact point and back, the far
/// 40% of each segment beyond the last force (jump-out included), so a baseline can be taken.
pub fn synthetic(s: &Synthetic) -> Curve {
    let p = s.params;
    let u = units(&p, s.radius, s.spring);
    let path = SpringPath::new(s.model, p.lambda, u.kbar, s.depth);
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
    let (f, _, _, _) = model_forces(s.model, &p, s.radius, s.spring, &height, &segment, None)
        .expect("valid parameters");
    let mut rng = rand::rngs::StdRng::seed_from_u64(s.seed);
    let normal = Normal::new(0.0, s.noise.max(0.0)).expect("finite noise");
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
    Curve {
        id: format!("synthetic-{}", s.seed),
        x: None,
        y: None,
        segment,
        height,
        force,
    }
}
