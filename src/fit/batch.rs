//! A force map's curve points evaluated together on a GPU with f64 shaders
//! (`shaders/fit_states.wgsl`, its CPU mirror `kernel::cpu::fit_states`). The host follows each
//! curve's path under its spring (the folds and jumps, [`SpringPath`]) and finds each retract
//! point's bracket and start on the Maugis-Dugdale contact piece, as [`SpringPath::at`] does;
//! the GPU then takes every such point's Newton steps at once. `bench/fit_gpu.sh` measures it
//! against the CPU on the force-map benchmark's curves; the fits themselves stay on the CPU
//! (README, "The GPU and fits", says why with those figures).

use crate::kernel::layout::{FitCurve64, FitPoint64};
use crate::law::follow::SpringPath;
use rayon::prelude::*;

/// The points of many curves on their contact pieces, ready for `Gpu::fit_states`.
#[derive(Clone, Debug, Default)]
pub struct Batch {
    /// Each curve's lambda and normalised spring.
    pub curves: Vec<FitCurve64>,
    /// The points on a contact piece, curve by curve.
    pub points: Vec<FitPoint64>,
    /// Each of `points`' curve and its index in that curve's base displacements.
    pub index: Vec<(u32, u32)>,
}

/// The batch of the retract points at base displacements `deltas[c]` (normalised) on the paths
/// `paths[c]` (Maugis-Dugdale; other models' points stay on the CPU). The paths are taken
/// mutably only so that threads can share them out (a path's lazily followed approach is not
/// shareable); nothing in them changes.
pub fn pack(paths: &mut [SpringPath], deltas: &[Vec<f64>]) -> Batch {
    let curves = paths
        .iter()
        .map(|p| FitCurve64 {
            lambda: p.law.lambda().unwrap_or(f64::NAN),
            kbar: p.kbar,
        })
        .collect();
    let (points, index) = paths
        .par_iter_mut()
        .zip(deltas)
        .enumerate()
        .flat_map_iter(|(c, (path, ds))| {
            ds.iter().enumerate().filter_map(move |(i, &delta)| {
                let [mu_lo, mu_hi, mu_start] = path.contact_bracket(delta)?;
                let p = FitPoint64 {
                    delta,
                    mu_lo,
                    mu_hi,
                    mu_start,
                    curve: c as u32,
                    _pad: 0,
                };
                Some((p, (c as u32, i as u32)))
            })
        })
        .unzip();
    Batch {
        curves,
        points,
        index,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::{Direction, Model};
    use crate::kernel::cpu::fit_states::fit_state;

    /// The kernel's arithmetic (its CPU mirror) from the packed brackets reaches the fit path's
    /// own states; points off the contact piece (free, jumped, beyond the path) are left out.
    #[test]
    fn the_batchs_states_are_the_paths() {
        for (lambda, kbar) in [
            (0.05, 0.3),
            (0.7, 0.33),
            (1.0, 40.0),
            (9.5, 2.0),
            (50.0, 0.05),
        ] {
            let mut paths = vec![SpringPath::of(Model::Md.law(lambda), kbar, 8.0)];
            let low = paths[0].force_reach().min(0.0) - 1.0;
            let deltas = vec![(0..400)
                .map(|k| low + (9.0 - low) * k as f64 / 399.0)
                .collect::<Vec<f64>>()];
            let b = pack(&mut paths, &deltas);
            assert!(b.points.len() > 100, "lambda {lambda}: {}", b.points.len());
            for (p, &(_, i)) in b.points.iter().zip(&b.index) {
                let o = fit_state(&b.curves[0], p);
                let s = paths[0].at(deltas[0][i as usize], Direction::Retract);
                assert!(o.converged(), "lambda {lambda}, Delta {}", p.delta);
                let err = (o.load - s.load).abs() / s.load.abs().max(1.0);
                assert!(err <= 1e-13, "lambda {lambda}, Delta {}: {err:e}", p.delta);
                assert!((o.mu.ln() + s.t).abs() <= 1e-9 * s.t.abs().max(1.0));
            }
            // Every point left out is one the CPU puts elsewhere than on the contact piece.
            let batched: std::collections::HashSet<u32> = b.index.iter().map(|x| x.1).collect();
            for (i, &d) in deltas[0].iter().enumerate() {
                if !batched.contains(&(i as u32)) {
                    let s = paths[0].at(d, Direction::Retract);
                    assert!(s.a == 0.0 || s.clamped, "lambda {lambda}, Delta {d}");
                }
            }
        }
    }
}
