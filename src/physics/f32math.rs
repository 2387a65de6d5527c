//! The shaders' f32 arithmetic on the CPU: transcendental functions written out as the WGSL
//! kernels compute them (no built-ins: lavapipe's are off by up to 1.6e-4). Read side by side
//! with `shaders/md.wgsl`; `physics::real` uses them for its `f32` number type.

/// `(atan(mu), mu - atan(mu))` in f32 from one half-angle step and a polynomial, with no loop
/// (no built-in atan: lavapipe's inverse trigonometric built-ins are off by up to 1.6e-4).
/// For mu > 1, `atan(mu) = pi/2 - atan(1/mu)`. Max relative error about 3 ulp (measured by the
/// tests below against f64).
pub fn atan_parts_f32(mu: f32) -> (f32, f32) {
    let big = mu > 1.0;
    let t0 = if big { 1.0 / mu } else { mu };
    // atan t0 = 2 atan t, t <= tan(pi/8); t0 - 2 t = t0 t^2 exactly, so there is no cancellation.
    let t = t0 / (1.0 + (1.0 + t0 * t0).sqrt());
    let z = t * t;
    // (t - atan t) / t^3 on z in [0, tan^2(pi/8)]: degree-5 Chebyshev fit, relative error 1.6e-9.
    let g = 0.333_333_34
        + z * (-0.199_999_78
            + z * (0.142_841_52 + z * (-0.110_713_65 + z * (0.086_246_76 + z * -0.050_481_386))));
    let d0 = z * (t0 + 2.0 * t * g); // t0 - atan(t0)
    if big {
        let at = std::f32::consts::FRAC_PI_2 - (t0 - d0);
        (at, mu - at)
    } else {
        (mu - d0, d0)
    }
}

const LN2_HI: f32 = 0.693_145_75;
const LN2_LO: f32 = 1.428_606_8e-6;
const LOG2E: f32 = std::f32::consts::LOG2_E;

/// 2^n for integer n in the normal range (WGSL: `ldexp`).
fn ldexp(x: f32, n: i32) -> f32 {
    x * f32::from_bits(((n + 127).clamp(1, 254) as u32) << 23)
}

/// exp with Cody-Waite reduction and a degree-7 Taylor polynomial: within 2 ulp for all
/// |x| < 87 (the Vulkan built-in is allowed 3 + 2|x| ulp).
pub fn exp_f32(x: f32) -> f32 {
    let x = x.clamp(-87.0, 88.0);
    let n = (x * LOG2E).round();
    let r = (x - n * LN2_HI) - n * LN2_LO;
    let p = 1.0
        + r * (1.0
            + r * (0.5
                + r * (1.0 / 6.0
                    + r * (1.0 / 24.0
                        + r * (1.0 / 120.0 + r * (1.0 / 720.0 + r * (1.0 / 5040.0)))))));
    let n = n as i32;
    // Two steps so that 2^n never overflows on its own.
    ldexp(ldexp(p, n / 2), n - n / 2)
}

/// ln y for y > 0 from the exponent and 2 atanh((m-1)/(m+1)), m in [sqrt(1/2), sqrt(2)).
pub fn ln_f32(y: f32) -> f32 {
    if y <= 0.0 {
        return f32::NEG_INFINITY;
    }
    if !y.is_finite() {
        return f32::INFINITY;
    }
    // frexp for normal numbers (WGSL: `frexp`).
    let bits = y.to_bits();
    let mut e = ((bits >> 23) & 0xff) as i32 - 126;
    let mut m = f32::from_bits((bits & 0x807f_ffff) | (126 << 23));
    if m < std::f32::consts::FRAC_1_SQRT_2 {
        m *= 2.0;
        e -= 1;
    }
    let u = (m - 1.0) / (m + 1.0);
    let z = u * u;
    let series = 2.0
        * u
        * (1.0
            + z * (1.0 / 3.0
                + z * (1.0 / 5.0 + z * (1.0 / 7.0 + z * (1.0 / 9.0 + z * (1.0 / 11.0))))));
    e as f32 * LN2_HI + (e as f32 * LN2_LO + series)
}

/// ln(1 + q), accurate for small q (the residual near convergence): 2 atanh(s) with
/// s = q / (2 + q) by its series for |q| < 0.1 (truncation below 1e-11), else ln(1 + q).
/// Not Goldberg's ln(u) q / (u - 1) with u = 1 + q: a driver may simplify (1 + q) - 1 to q
/// (Mesa's NIR does), which silently undoes the correction and parts the GPU from this mirror.
pub fn log1p_f32(q: f32) -> f32 {
    let s = q / (2.0 + q);
    let z = s * s;
    let series = 2.0 * s * (1.0 + z * (1.0 / 3.0 + z * (1.0 / 5.0 + z * (1.0 / 7.0))));
    if q.abs() < 0.1 {
        series
    } else {
        ln_f32(1.0 + q)
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
