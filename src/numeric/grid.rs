//! Grids of sample points.

/// `n` points from `min` to `max`, log-spaced if `log`, with the ends exact.
pub fn axis(min: f64, max: f64, n: usize, log: bool) -> Vec<f64> {
    (0..n)
        .map(|i| {
            let t = if n == 1 {
                0.0
            } else {
                i as f64 / (n - 1) as f64
            };
            if log {
                10f64.powf(min.log10() + t * (max.log10() - min.log10()))
            } else {
                min + t * (max - min)
            }
        })
        .collect()
}
