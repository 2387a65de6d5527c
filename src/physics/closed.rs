//! Closed-form contact models in the Johnson-Greenwood normalisation (PHYSICS.md section 3),
//! and the Carpick-Ogletree-Salmeron transition fit (section 6).

/// Hertz (no adhesion): `Pbar = A^3`, `Dbar = A^2`. Defined for `Pbar >= 0`.
pub fn hertz_radius(load: f64) -> Option<f64> {
    (load >= 0.0).then(|| load.cbrt())
}

/// DMT: `Pbar = A^3 - 2`, `Dbar = A^2`. Defined for `Pbar >= -2`.
pub fn dmt_radius(load: f64) -> Option<f64> {
    (load >= -2.0).then(|| (load + 2.0).cbrt())
}

/// DMT's pull-off load, `-2` (in `pi w R`), under either control.
pub const DMT_PULLOFF: f64 = -2.0;
/// Bradley's rigid spheres: pull-off -2, no deformation.
pub const BRADLEY_PULLOFF: f64 = -2.0;
/// JKR's load-controlled pull-off, `-3/2`.
pub const JKR_PULLOFF_LOAD: f64 = -1.5;
/// JKR's displacement-controlled pull-off load, `-5/6`.
pub const JKR_PULLOFF_DISPLACEMENT: f64 = -5.0 / 6.0;

/// JKR on its load-stable branch: `A^3 = Pbar + 3 + sqrt(9 + 6 Pbar)`, for `Pbar >= -3/2`.
pub fn jkr_radius(load: f64) -> Option<f64> {
    (load >= -1.5).then(|| (load + 3.0 + (9.0 + 6.0 * load).max(0.0).sqrt()).cbrt())
}

/// JKR load at contact radius A: `A^3 - sqrt(6 A^3)`.
pub fn jkr_load(a: f64) -> f64 {
    a * a * a - (6.0 * a * a * a).sqrt()
}

/// JKR approach at contact radius A: `A^2 - (2/3) sqrt(6 A)`.
pub fn jkr_approach(a: f64) -> f64 {
    a * a - (2.0 / 3.0) * (6.0 * a).sqrt()
}

/// The Carpick-Ogletree-Salmeron transition equation with the Johnson-Greenwood fits for its
/// parameters, in the normalisation used here. `None` where it has no answer (below its
/// pull-off).
pub fn cos_radius(lambda: f64, load: f64) -> Option<f64> {
    let alpha = (1.0 - (-lambda / 0.924).exp()) / 1.02;
    let l13 = 2.28 * lambda.powf(1.3);
    let a0 = 1.54 + 0.279 * (l13 - 1.0) / (l13 + 1.0);
    let pc = cos_pulloff(lambda);
    let s = 1.0 - load / pc;
    (s >= 0.0).then(|| a0 * ((alpha + s.sqrt()) / (1.0 + alpha)).powf(2.0 / 3.0))
}

/// The Johnson-Greenwood fit of the load-controlled pull-off (exponent 1.4; PHYSICS.md
/// section 7 of docs/PHYSICS.md: an exponent of 1/4 would be off by 15%).
pub fn cos_pulloff(lambda: f64) -> f64 {
    let l14 = 4.04 * lambda.powf(1.4);
    -1.75 + 0.25 * (l14 - 1.0) / (l14 + 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jkr_inverse_and_pulloffs() {
        for &p in &[-1.5, -1.0, 0.0, 1.0, 100.0] {
            let a = jkr_radius(p).unwrap();
            assert!((jkr_load(a) - p).abs() < 1e-12 * p.abs().max(1.0));
        }
        // Load-controlled pull-off at A = (3/2)^(1/3).
        assert!((jkr_radius(-1.5).unwrap() - 1.5f64.cbrt()).abs() < 1e-15);
        // Displacement-controlled jump-out: minimum of the approach at A = 6^(-1/3).
        let a = 6f64.powf(-1.0 / 3.0);
        assert!((jkr_approach(a) + 3.0 * 6f64.powf(-2.0 / 3.0)).abs() < 1e-15);
        let h = 1e-6;
        assert!((jkr_approach(a + h) - jkr_approach(a - h)).abs() < 1e-11);
        assert!((jkr_load(a) - JKR_PULLOFF_DISPLACEMENT).abs() < 1e-15);
        assert!(jkr_radius(-1.6).is_none());
    }

    #[test]
    fn cos_limits() {
        assert!((cos_pulloff(1e-6) + 2.0).abs() < 1e-6);
        assert!((cos_pulloff(1e6) + 1.5).abs() < 1e-6);
        assert!((cos_radius(1e6, 0.0).unwrap() - 1.819).abs() < 2e-3);
    }
}
