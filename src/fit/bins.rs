//! A long curve in bins: runs of neighbouring points that lie on a straight line within the
//! noise, each replaced by its mean and weighted by its count, for the search of the fit.
//!
//! A measured curve holds thousands of points, most of them on stretches (the baseline, the
//! slow rise of the contact) where the model is a straight line over many points. The fit's
//! cost grows with the points (each evaluation follows every point, each Jacobian's QR is
//! m x 5), while its answer depends only on the sums the points make. Over a bin where the model
//! is linear, `sum_i (F_i - m_i)^2 = k (Fbar - mbar)^2 + sum_i ((F_i - Fbar) - (m_i - mbar))^2`:
//! the first term is the bin's mean weighted by k, the second the scatter inside it, the same
//! for every parameter to within the model's curvature over the bin. A bin grows while its
//! points' scatter about their own straight line stays within [`LINE_Z`] standard deviations
//! of what the baseline's noise gives: where the force bends (the contact point, the dip before
//! a jump), bins end. The points before a jump (their residual is their distance to the fold)
//! stay single points, and a curve without measurable noise is never binned. What bending
//! stays hidden in the noise still moves a bin's mean from the model's mean over it: bins are
//! kept short (16 points) and the line test strict (one standard deviation), which keeps the
//! 95% intervals' coverage over long synthetic curves (`fit::binned_long_curves_keep_their_
//! coverage`), and each fit found on the bins is finished on the points, its intervals moved
//! from the bins' minimum to it (`interval::recentre`).

use super::Prepared;

/// How far above its expectation (in its standard deviations) the scatter of a bin's points
/// about their straight line may go before the bin ends.
pub const LINE_Z: f64 = 1.0;
/// The most points in one bin.
pub const MAX_BIN: usize = 16;
/// A curve is binned only where bins take it below this share of its points.
const WORTH: f64 = 0.7;
/// Curves with fewer points are fitted on their points: their fits are fast, and bins would
/// only move their answers by their curvature.
pub const MIN_TO_BIN: usize = 1000;

impl Prepared {
    /// The curve in bins (see the module's text), or None where binning would not pay: a
    /// noise-free or short curve, or one with few points to merge.
    pub fn binned(&self) -> Option<Prepared> {
        let n = self.force.len();
        // A curve without measurable noise (a model's own curve) keeps its points.
        if n < MIN_TO_BIN
            || !(self.noise > 1e-6 * self.scales.0)
            || self.weight.iter().any(|&w| w != 1.0)
        {
            return None;
        }
        // Runs of one direction and side, the points before a jump alone.
        let breaks = |i: usize| {
            i == 0
                || self.dir[i] != self.dir[i - 1]
                || self.side[i] != self.side[i - 1]
                || self.at_jump[i]
                || self.at_jump[i - 1]
        };
        let mut runs = Vec::new();
        let mut start = 0;
        for i in 1..=n {
            if i == n || breaks(i) {
                runs.push(start..i);
                start = i;
            }
        }
        let s2 = self.noise * self.noise;
        let mut bins: Vec<std::ops::Range<usize>> = Vec::new();
        for run in runs {
            let mut i = run.start;
            while i < run.end {
                let mut line = Line::default();
                line.add(self.height[i], self.force[i]);
                let mut j = i + 1;
                while j < run.end && j - i < MAX_BIN {
                    let mut next = line;
                    next.add(self.height[j], self.force[j]);
                    // The points about their straight line: within the noise's spread, or the
                    // force bends inside the bin.
                    let dof = next.n - 2.0;
                    if next.scatter() > s2 * (dof + LINE_Z * (2.0 * dof).sqrt()) {
                        break;
                    }
                    line = next;
                    j += 1;
                }
                bins.push(i..j);
                i = j;
            }
        }
        if (bins.len() as f64) > WORTH * n as f64 {
            return None;
        }
        let mut out = Prepared {
            height: Vec::with_capacity(bins.len()),
            force: Vec::with_capacity(bins.len()),
            dir: Vec::with_capacity(bins.len()),
            side: Vec::with_capacity(bins.len()),
            at_jump: Vec::with_capacity(bins.len()),
            weight: Vec::with_capacity(bins.len()),
            within: 0.0,
            ..self.clone()
        };
        for b in bins {
            let k = b.len() as f64;
            let (h, f) = (&self.height[b.clone()], &self.force[b.clone()]);
            let (hm, fm) = (h.iter().sum::<f64>() / k, f.iter().sum::<f64>() / k);
            out.height.push(hm);
            out.force.push(fm);
            out.dir.push(self.dir[b.start]);
            out.side.push(self.side[b.start]);
            out.at_jump.push(self.at_jump[b.start]);
            out.weight.push(k);
            out.within += scatter(h, f, hm, fm);
        }
        Some(out)
    }
}

/// The bin's scatter about its own straight line, scaled to the k - 1 degrees of freedom that
/// its points have about its mean (the model's slope over the bin is not noise): the part of a
/// fit's residual sum that its mean does not carry.
fn scatter(h: &[f64], f: &[f64], hm: f64, fm: f64) -> f64 {
    let k = h.len();
    if k < 2 {
        return 0.0;
    }
    let sxx: f64 = h.iter().map(|x| (x - hm).powi(2)).sum();
    let sxy: f64 = h.iter().zip(f).map(|(x, y)| (x - hm) * (y - fm)).sum();
    let syy: f64 = f.iter().map(|y| (y - fm).powi(2)).sum();
    if k == 2 || !(sxx > 0.0) {
        return syy;
    }
    let line = (syy - sxy * sxy / sxx).max(0.0);
    line * (k - 1) as f64 / (k - 2) as f64
}

/// The running sums of a straight-line fit.
#[derive(Clone, Copy, Default)]
struct Line {
    n: f64,
    h: f64,
    f: f64,
    hh: f64,
    hf: f64,
    ff: f64,
    /// The first point's height and force, subtracted so that the sums do not cancel.
    origin: Option<(f64, f64)>,
}

impl Line {
    fn add(&mut self, h: f64, f: f64) {
        let (h0, f0) = *self.origin.get_or_insert((h, f));
        let (x, y) = (h - h0, f - f0);
        self.n += 1.0;
        self.h += x;
        self.f += y;
        self.hh += x * x;
        self.hf += x * y;
        self.ff += y * y;
    }

    /// The sum of squares of the points about their least-squares line.
    fn scatter(&self) -> f64 {
        let sxx = self.hh - self.h * self.h / self.n;
        let sxy = self.hf - self.h * self.f / self.n;
        let syy = self.ff - self.f * self.f / self.n;
        if sxx > 0.0 {
            (syy - sxy * sxy / sxx).max(0.0)
        } else {
            syy.max(0.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::{prepare, synthetic, FitOptions, Model, Params};

    fn synthetic_truth() -> Params {
        Params {
            e_star: 1.5e9,
            w: 0.05,
            lambda: 0.8,
            zc: 40e-9,
            f0: 0.0,
        }
    }

    fn curve(noise: f64, points: usize) -> Prepared {
        let s = synthetic::Synthetic {
            model: Model::Md,
            params: synthetic_truth(),
            radius: 20e-9,
            spring: 2.0,
            points,
            depth: 6.0,
            noise,
            seed: 11,
        };
        let opt = FitOptions {
            radius: 20e-9,
            spring: 2.0,
            ..FitOptions::default()
        };
        prepare(&synthetic::synthetic(&s), &opt).unwrap()
    }

    #[test]
    fn bins_keep_the_sums_and_a_noise_free_curve_is_not_binned() {
        assert!(curve(0.0, 4000).binned().is_none());
        let d = curve(1e-10, 4000);
        let b = d.binned().expect("a long noisy curve is binned");
        assert!(b.force.len() < d.force.len() / 2, "{} bins", b.force.len());
        // The counts and the force sum are the curve's.
        assert_eq!(b.weight.iter().sum::<f64>(), d.force.len() as f64);
        let sum: f64 = d.force.iter().sum();
        let bsum: f64 = b.force.iter().zip(&b.weight).map(|(f, w)| f * w).sum();
        assert!((sum - bsum).abs() <= 1e-9 * d.force.iter().map(|f| f.abs()).sum::<f64>());
        // Every point before a jump is alone in its bin, and kept.
        let jumps = d.at_jump.iter().filter(|&&j| j).count();
        assert!(jumps > 0);
        assert_eq!(
            (0..b.force.len())
                .filter(|&i| b.at_jump[i] && b.weight[i] == 1.0)
                .count(),
            jumps
        );
        // At the truth, each bin's mean against the model at its mean height, and against
        // the model's mean over its points: the same weighted sums within a Delta chi^2 of 1
        // (0.19 measured, against 4000 for the points' sum): the model is a straight line
        // over each bin.
        let t = synthetic_truth();
        let model = |c: &Prepared| {
            crate::fit::model_forces(Model::Md, &t, 20e-9, 2.0, &c.height, &c.dir, Some(&c.side))
                .unwrap()
                .0
        };
        let (fb, fd) = (model(&b), model(&d));
        let (mut at_mean, mut mean_of, mut start) = (0.0, 0.0, 0);
        for (i, w) in b.weight.iter().enumerate() {
            let k = *w as usize;
            let m = fd[start..start + k].iter().sum::<f64>() / *w;
            at_mean += w * (b.force[i] - fb[i]).powi(2);
            mean_of += w * (b.force[i] - m).powi(2);
            start += k;
        }
        let s2 = 1e-20;
        assert!(
            (at_mean - mean_of).abs() < s2,
            "{} against {}",
            at_mean / s2,
            mean_of / s2
        );
    }
}
