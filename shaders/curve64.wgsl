// The f64 Maugis-Dugdale curve point of the f64 refinement (polish64.wgsl, which follows it),
// for adapters with SHADER_F64: src/physics/md.rs curve_point with its derivatives. WGSL has no
// f64 transcendentals (SPIR-V's GLSL.std.450 exp, log and atan are 32-bit only); atan below uses
// sqrt, division and a series. CPU mirror: src/kernel/cpu/polish64.rs.

// Twin of kernel::layout::Params (the f32 kernels' parameters).
struct Params {
    nx: u32,
    offset: u32,
    count: u32,
    max_iter: u32,
}

const HALF_PI: f64 = 1.5707963267948966;

// (atan(mu), mu - atan(mu)) in f64: three half-angle steps (t0 - 2 t = t0 t^2 exactly, so
// every term of t0 - atan t0 is positive) to t <= tan(pi/64), then 8 terms of the series.
fn atan_parts64(mu: f64) -> vec2<f64> {
    let big = mu > 1.0;
    let t0 = select(mu, 1.0 / mu, big);
    let t1 = t0 / (1.0 + sqrt(1.0 + t0 * t0));
    let t2 = t1 / (1.0 + sqrt(1.0 + t1 * t1));
    let t3 = t2 / (1.0 + sqrt(1.0 + t2 * t2));
    let z = t3 * t3;
    var s: f64 = 1.0 / 17.0;
    s = 1.0 / 15.0 - z * s;
    s = 1.0 / 13.0 - z * s;
    s = 1.0 / 11.0 - z * s;
    s = 1.0 / 9.0 - z * s;
    s = 1.0 / 7.0 - z * s;
    s = 1.0 / 5.0 - z * s;
    s = 1.0 / 3.0 - z * s;
    let d3 = t3 * z * s;
    let d0 = t0 * t1 * t1 + 2.0 * (t1 * t2 * t2 + 2.0 * (t2 * z + 2.0 * d3));
    if big {
        let at = HALF_PI - (t0 - d0);
        return vec2<f64>(at, mu - at);
    }
    return vec2<f64>(mu - d0, d0);
}

// The residual's quantity and its derivative in mu, plus the outputs: (A, Pbar, Pbar + 2, Dbar,
// m - 1, dPbar/dmu, dDbar/dmu), as src/physics/md.rs curve_point.
struct Point {
    a: f64,
    load: f64,
    load_plus_2: f64,
    approach: f64,
    m_minus_1: f64,
    dload: f64,
    dapproach: f64,
}

fn curve_point64(lambda: f64, mu: f64) -> Point {
    let four_thirds: f64 = 4.0 / 3.0;
    let ap = atan_parts64(mu);
    let at = ap.x;
    let mu2 = mu * mu;
    let m = sqrt(1.0 + mu2);
    let m_minus_1 = mu2 / (1.0 + m);
    let f1 = mu2 * at + ap.y;
    let f2 = mu * at - m_minus_1;
    let alpha = 0.5 * lambda * f1;
    let beta = four_thirds * lambda * lambda * f2;
    let a = 2.0 / (beta + sqrt(beta * beta + 4.0 * alpha));
    let g = mu + (1.0 + mu2) * at;
    var p: Point;
    p.a = a;
    p.load = a * a * (a - lambda * g);
    p.load_plus_2 = a * (a * a + (8.0 / 3.0) * lambda * lambda * f2) - 2.0 * lambda * a * a * at;
    p.approach = a * (a - four_thirds * lambda * mu);
    p.m_minus_1 = m_minus_1;
    let m2 = 1.0 + mu2;
    let df1 = 2.0 * mu * at + 2.0 * mu2 / m2;
    let df2 = at - mu * mu2 / ((1.0 + m) * m2);
    let dalpha = 0.5 * lambda * df1;
    let dbeta = four_thirds * lambda * lambda * df2;
    let da = -(a * (dalpha * a + dbeta)) / (2.0 * alpha * a + beta);
    let dg = 2.0 + 2.0 * mu * at;
    p.dload = da * (3.0 * a * a - 2.0 * lambda * a * g) - lambda * a * a * dg;
    p.dapproach = da * (2.0 * a - four_thirds * lambda * mu) - four_thirds * lambda * a;
    return p;
}

