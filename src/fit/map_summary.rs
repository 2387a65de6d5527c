//! A force map at a glance: how many pixels each status and each adequate model holds, and each
//! quantity's distribution over the fitted pixels (quantiles and a histogram), for a figure or
//! the JSON beside the maps.

use super::{CurveFit, FitStatus, Model, MAP_QUANTITIES};
use serde::Serialize;
use std::collections::BTreeMap;

/// Every status a pixel can have: a fit's, or `no_curve` where the map holds no curve.
pub const PIXEL_STATUSES: [&str; 5] = [
    "ok",
    "invalid_input",
    "no_contact",
    "not_converged",
    "no_curve",
];

/// A pixel's status, as in [`PIXEL_STATUSES`] (its index is the status map's value).
pub fn pixel_status(fit: Option<&CurveFit>) -> usize {
    match fit.map(|r| r.status) {
        Some(FitStatus::Ok) => 0,
        Some(FitStatus::InvalidInput) => 1,
        Some(FitStatus::NoContact) => 2,
        Some(FitStatus::NotConverged) => 3,
        None => 4,
    }
}

/// The summary of a force map (`--maps PREFIX` writes it as PREFIX_summary.json; [`summarize_map`]).
#[derive(Clone, Debug, Serialize)]
pub struct MapSummary {
    /// Pixels across.
    pub nx: usize,
    /// Pixels down.
    pub ny: usize,
    /// Pixels of each status ([`PIXEL_STATUSES`]; every one is listed, zero included).
    pub status: BTreeMap<&'static str, usize>,
    /// Fitted (`ok`) pixels of each adequate model (`none` where no model was adequate).
    pub adequate_model: BTreeMap<&'static str, usize>,
    /// Each map quantity over the fitted pixels.
    pub quantities: Vec<QuantitySummary>,
}

/// One quantity over a map's fitted pixels.
#[derive(Clone, Debug, Serialize)]
pub struct QuantitySummary {
    /// The quantity's name (its map is `PREFIX_<name>.npy`).
    pub name: &'static str,
    /// Its SI unit (empty for a number).
    pub unit: &'static str,
    /// Pixels with a value (for lambda: where it is determined).
    pub count: usize,
    /// Fitted pixels without one (lambda: not determined).
    pub missing: usize,
    /// Whether the histogram's bins are even in log10 (the quantity spans decades).
    pub log_bins: bool,
    /// Smallest, 5%, 25%, 50%, 75%, 95% and largest (absent without a value).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub quantiles: Option<Quantiles>,
    /// The bins' edges (count + 1 of them; empty without a value).
    pub edges: Vec<f64>,
    /// Pixels in each bin (the last bin holds its upper edge).
    pub counts: Vec<usize>,
}

/// Order statistics of a quantity (linear interpolation between ranks).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Quantiles {
    /// The smallest value.
    pub min: f64,
    /// The 5% quantile.
    pub q05: f64,
    /// The lower quartile.
    pub q25: f64,
    /// The median.
    pub median: f64,
    /// The upper quartile.
    pub q75: f64,
    /// The 95% quantile.
    pub q95: f64,
    /// The largest value.
    pub max: f64,
}

impl Quantiles {
    fn of(sorted: &[f64]) -> Self {
        let q = |p: f64| {
            let x = p * (sorted.len() - 1) as f64;
            let (i, f) = (x.floor() as usize, x - x.floor());
            let hi = sorted[(i + 1).min(sorted.len() - 1)];
            sorted[i] + f * (hi - sorted[i])
        };
        Quantiles {
            min: sorted[0],
            q05: q(0.05),
            q25: q(0.25),
            median: q(0.5),
            q75: q(0.75),
            q95: q(0.95),
            max: sorted[sorted.len() - 1],
        }
    }
}

/// The map's summary from its grid (`map_grid`): statuses over every pixel, models and
/// quantities over the fitted ones, each quantity as its map shows it.
pub fn summarize_map(
    results: &[CurveFit],
    nx: usize,
    ny: usize,
    grid: &[Option<usize>],
) -> MapSummary {
    let fits: Vec<Option<&CurveFit>> = grid.iter().map(|i| i.map(|i| &results[i])).collect();
    let mut status: BTreeMap<&'static str, usize> =
        PIXEL_STATUSES.iter().map(|s| (*s, 0)).collect();
    for f in &fits {
        *status
            .get_mut(PIXEL_STATUSES[pixel_status(*f)])
            .expect("listed") += 1;
    }
    let ok: Vec<&CurveFit> = fits
        .iter()
        .flatten()
        .copied()
        .filter(|r| r.status == FitStatus::Ok)
        .collect();
    let mut adequate_model: BTreeMap<&'static str, usize> = Model::ALL
        .iter()
        .map(|m| (m.name(), 0))
        .chain([("none", 0)])
        .collect();
    for r in &ok {
        *adequate_model
            .get_mut(r.adequate_model.map_or("none", |m| m.name()))
            .expect("listed") += 1;
    }
    let quantities = MAP_QUANTITIES
        .iter()
        .map(|q| {
            let mut v: Vec<f64> = ok
                .iter()
                .filter_map(|r| q.shown(r))
                .filter(|v| v.is_finite() && (!q.log || *v > 0.0))
                .collect();
            v.sort_by(f64::total_cmp);
            let log_bins = q.log && v.first().is_some_and(|lo| v[v.len() - 1] >= 10.0 * lo);
            let (edges, counts) = histogram(&v, log_bins);
            QuantitySummary {
                name: q.name,
                unit: q.unit,
                count: v.len(),
                missing: ok.len() - v.len(),
                log_bins,
                quantiles: (!v.is_empty()).then(|| Quantiles::of(&v)),
                edges,
                counts,
            }
        })
        .collect();
    MapSummary {
        nx,
        ny,
        status,
        adequate_model,
        quantities,
    }
}

/// Bins even in the value (or its log10) from the smallest to the largest, about the square
/// root of the count of them (5 to 40); one bin around a single value.
fn histogram(sorted: &[f64], log: bool) -> (Vec<f64>, Vec<usize>) {
    let Some((&lo, &hi)) = sorted.first().zip(sorted.last()) else {
        return (Vec::new(), Vec::new());
    };
    let (t, back): (fn(f64) -> f64, fn(f64) -> f64) = if log {
        (f64::log10, |x| 10f64.powf(x))
    } else {
        (|x| x, |x| x)
    };
    let (a, b) = (t(lo), t(hi));
    if b <= a {
        let d = if a == 0.0 { 0.5 } else { 0.05 * a.abs() };
        return (vec![back(a - d), back(a + d)], vec![sorted.len()]);
    }
    let n = ((sorted.len() as f64).sqrt().ceil() as usize).clamp(5, 40);
    let edges: Vec<f64> = (0..=n)
        .map(|i| back(a + (b - a) * i as f64 / n as f64))
        .collect();
    let mut counts = vec![0; n];
    for &v in sorted {
        let k = (((t(v) - a) / (b - a)) * n as f64).floor() as usize;
        counts[k.min(n - 1)] += 1;
    }
    (edges, counts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_and_bins_of_known_values() {
        let v: Vec<f64> = (0..=100).map(f64::from).collect();
        let q = Quantiles::of(&v);
        assert_eq!(
            (q.min, q.q05, q.q25, q.median, q.q75, q.q95, q.max),
            (0.0, 5.0, 25.0, 50.0, 75.0, 95.0, 100.0)
        );
        let (edges, counts) = histogram(&v, false);
        assert_eq!(counts.len(), 11);
        assert_eq!(edges.len(), 12);
        assert_eq!(counts.iter().sum::<usize>(), 101);
        // Bins of width 100/11: 0..9.09 holds 0..9 (10 values); the last holds 91..100.
        assert_eq!(counts[0], 10);
        assert_eq!(counts[10], 10);
        // Log bins: 1, 10, 100, 1000 in 5 bins of 0.6 decades, one value a bin but the middle.
        let (edges, counts) = histogram(&[1.0, 10.0, 100.0, 1000.0], true);
        assert!((edges[5] - 1000.0).abs() < 1e-9 && (edges[0] - 1.0).abs() < 1e-12);
        assert_eq!(counts, vec![1, 1, 0, 1, 1]);
        let (edges, counts) = histogram(&[2.0, 2.0], false);
        assert_eq!((edges, counts), (vec![1.9, 2.1], vec![2]));
    }
}
