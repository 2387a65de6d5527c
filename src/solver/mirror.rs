//! The shaders' f32 arithmetic, on the CPU: read it side by side with `shaders/md.wgsl`.

/// `(atan(mu), mu - atan(mu))` in f32 from the half-angle reduction and the Maclaurin series
/// only (no built-in atan: lavapipe's inverse trigonometric built-ins are off by up to 1.6e-4).
/// For mu > 1, `atan(mu) = pi/2 - atan(1/mu)`. Max relative error about 3 ulp (measured by the
/// tests below against f64).
pub fn atan_parts_f32(mu: f32) -> (f32, f32) {
    let big = mu > 1.0;
    let t0 = if big { 1.0 / mu } else { mu };
    let mut t = t0;
    let mut weight = 1.0f32;
    let mut acc = 0.0f32;
    while t > 0.1 {
        let onem = 1.0 + (1.0 + t * t).sqrt();
        acc += weight * t * t * t / (onem * onem);
        t /= onem;
        weight *= 2.0;
    }
    let z = t * t;
    let series = t * z * (1.0 / 3.0 - z * (1.0 / 5.0 - z * (1.0 / 7.0 - z * (1.0 / 9.0))));
    let d0 = acc + weight * series; // t0 - atan(t0)
    if big {
        let at = std::f32::consts::FRAC_PI_2 - (t0 - d0);
        (at, mu - at)
    } else {
        (mu - d0, d0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn f32_atan_parts_are_accurate_over_the_whole_range() {
        let (mut worst_at, mut worst_d) = (0.0f64, 0.0f64);
        for i in 0..20001 {
            let mu = 10f32.powf(-9.0 + 19.0 * i as f32 / 20000.0);
            let (at, d) = atan_parts_f32(mu);
            let m = mu as f64;
            let at64 = m.atan();
            let (_, d64) = crate::physics::real::Real::atan_parts(m);
            worst_at = worst_at.max((at as f64 / at64 - 1.0).abs());
            worst_d = worst_d.max((d as f64 / d64 - 1.0).abs());
        }
        assert!(worst_at < 3.0e-7, "atan: {worst_at:e}");
        assert!(worst_d < 6.0e-7, "mu - atan: {worst_d:e}");
    }
}
