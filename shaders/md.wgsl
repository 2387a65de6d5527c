// Maugis-Dugdale states in f32: the shared functions of every tabor kernel.
// Read side by side with src/solver/mirror.rs (the CPU mirror) and src/physics/md.rs.
// No built-in transcendental is trusted (lavapipe's inverse trigonometry is off by 1.6e-4 and
// the Vulkan exp bound is 3 + 2|x| ulp): atan, exp and ln below are written out, with the error
// bounds measured in tests/gpu.rs and src/solver/mirror.rs.

// Twin of gpu::layout::Branch (40 x 4 bytes).
struct Branch {
    mu_ref: f32,
    end_hi: f32,
    end_lo: f32,
    s_max: f32,
    cheb: array<f32, 8>,
    t: array<f32, 14>,
    dx: array<f32, 14>,
}

// Twin of gpu::layout::GpuLambda (88 x 4 bytes).
struct Lambda {
    lambda: f32,
    small: u32,
    disp_at_zero: u32,
    invalid: u32,
    end_load: f32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
    load: Branch,
    disp: Branch,
}

// Twin of gpu::layout::Params.
struct Params {
    nx: u32,
    offset: u32,
    count: u32,
    control: u32,
    rows_are_gaps: u32,
    flags: u32,
    pad0: u32,
    pad1: u32,
}

// Twin of gpu::layout::Out. code = status | iterations << 8.
struct Out {
    a: f32,
    other: f32,
    m_minus_1: f32,
    code: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> lambdas: array<Lambda>;
@group(0) @binding(2) var<storage, read> input: array<u32>;
@group(0) @binding(3) var<storage, read_write> out: array<Out>;

// Fields of one branch (control 0: load, 1: displacement) of lambdas[i], read in place: copying
// the 352-byte struct into every invocation costs more than the whole root search.
fn br_mu_ref(i: u32, control: u32) -> f32 {
    if control == 1u {
        return lambdas[i].disp.mu_ref;
    }
    return lambdas[i].load.mu_ref;
}
fn br_end(i: u32, control: u32) -> vec2<f32> {
    if control == 1u {
        return vec2<f32>(lambdas[i].disp.end_hi, lambdas[i].disp.end_lo);
    }
    return vec2<f32>(lambdas[i].load.end_hi, lambdas[i].load.end_lo);
}
fn br_s_max(i: u32, control: u32) -> f32 {
    if control == 1u {
        return lambdas[i].disp.s_max;
    }
    return lambdas[i].load.s_max;
}
fn br_cheb(i: u32, control: u32, k: i32) -> f32 {
    if control == 1u {
        return lambdas[i].disp.cheb[k];
    }
    return lambdas[i].load.cheb[k];
}
fn br_t(i: u32, control: u32, k: u32) -> f32 {
    if control == 1u {
        return lambdas[i].disp.t[k];
    }
    return lambdas[i].load.t[k];
}
fn br_dx(i: u32, control: u32, k: u32) -> f32 {
    if control == 1u {
        return lambdas[i].disp.dx[k];
    }
    return lambdas[i].load.dx[k];
}

const STATUS_OK: u32 = 0u;
const STATUS_NO_CONTACT: u32 = 1u;
const STATUS_NOT_CONVERGED: u32 = 2u;
const STATUS_INVALID: u32 = 3u;
const TABLE_NODES: u32 = 14u;
const HALF_PI: f32 = 1.5707963267948966;
const LN2_HI: f32 = 0.69314575;
const LN2_LO: f32 = 1.4286068e-6;
const LOG2E: f32 = 1.4426950408889634;
const INF: f32 = 3.0e38;

// (atan(mu), mu - atan(mu)) from the half-angle reduction and the Maclaurin series only.
fn atan_parts(mu: f32) -> vec2<f32> {
    let big = mu > 1.0;
    var t0 = mu;
    if big {
        t0 = 1.0 / mu;
    }
    var t = t0;
    var weight = 1.0;
    var acc = 0.0;
    for (var i = 0; i < 8 && t > 0.1; i++) {
        let onem = 1.0 + sqrt(1.0 + t * t);
        acc += weight * t * t * t / (onem * onem);
        t = t / onem;
        weight *= 2.0;
    }
    let z = t * t;
    let series = t * z * (1.0 / 3.0 - z * (1.0 / 5.0 - z * (1.0 / 7.0 - z * (1.0 / 9.0))));
    let d0 = acc + weight * series;
    if big {
        let at = HALF_PI - (t0 - d0);
        return vec2<f32>(at, mu - at);
    }
    return vec2<f32>(mu - d0, d0);
}

fn exp_f(x_in: f32) -> f32 {
    let x = clamp(x_in, -87.0, 88.0);
    let n = round(x * LOG2E);
    let r = (x - n * LN2_HI) - n * LN2_LO;
    let p = 1.0 + r * (1.0 + r * (0.5 + r * (1.0 / 6.0 + r * (1.0 / 24.0 + r * (1.0 / 120.0 + r * (1.0 / 720.0 + r * (1.0 / 5040.0)))))));
    let ni = i32(n);
    return ldexp(ldexp(p, ni / 2), ni - ni / 2);
}

fn ln_f(y: f32) -> f32 {
    if y <= 0.0 {
        return -INF;
    }
    if y > 3.0e38 {
        return INF;
    }
    let fr = frexp(y);
    var m = fr.fract;
    var e = fr.exp;
    if m < 0.70710678 {
        m *= 2.0;
        e -= 1;
    }
    let u = (m - 1.0) / (m + 1.0);
    let z = u * u;
    let series = 2.0 * u * (1.0 + z * (1.0 / 3.0 + z * (1.0 / 5.0 + z * (1.0 / 7.0 + z * (1.0 / 9.0 + z * (1.0 / 11.0))))));
    return f32(e) * LN2_HI + (f32(e) * LN2_LO + series);
}

fn log1p_f(q: f32) -> f32 {
    if abs(q) < 0.25 {
        let u = q / (2.0 + q);
        let z = u * u;
        return 2.0 * u * (1.0 + z * (1.0 / 3.0 + z * (1.0 / 5.0 + z * (1.0 / 7.0 + z * (1.0 / 9.0)))));
    }
    return ln_f(1.0 + q);
}

// A curve point: A, Pbar, Pbar + 2, Dbar, m - 1 (src/physics/md.rs, curve_point).
struct Point {
    a: f32,
    load: f32,
    load_plus_2: f32,
    approach: f32,
    m_minus_1: f32,
}

// Variant switch for benchmarks (Params.flags bit 0): the textbook formulas, which cancel as
// m -> 1 (src/solver/mirror.rs, curve_point_naive).
fn naive() -> bool {
    return (params.flags & 1u) != 0u;
}

fn curve_point_naive(lambda: f32, mu: f32) -> Point {
    let at = atan_parts(mu).x;
    let m = sqrt(1.0 + mu * mu);
    let m_minus_1 = m - 1.0;
    let f1 = (m * m - 2.0) * at + mu;
    let f2 = mu * at - m_minus_1;
    let alpha = 0.5 * lambda * f1;
    let beta = (4.0 / 3.0) * lambda * lambda * f2;
    let a = (-beta + sqrt(beta * beta + 4.0 * alpha)) / (2.0 * alpha);
    var p: Point;
    p.a = a;
    p.load = a * a * a - lambda * a * a * (mu + m * m * at);
    p.load_plus_2 = p.load + 2.0;
    p.approach = a * a - (4.0 / 3.0) * lambda * a * mu;
    p.m_minus_1 = m_minus_1;
    return p;
}

fn curve_point(lambda: f32, mu: f32) -> Point {
    if naive() {
        return curve_point_naive(lambda, mu);
    }
    let ap = atan_parts(mu);
    let at = ap.x;
    let mu2 = mu * mu;
    let m = sqrt(1.0 + mu2);
    let m_minus_1 = mu2 / (1.0 + m);
    let f1 = mu2 * at + ap.y;
    let f2 = mu * at - m_minus_1;
    let alpha = 0.5 * lambda * f1;
    let beta = (4.0 / 3.0) * lambda * lambda * f2;
    let a = 2.0 / (beta + sqrt(beta * beta + 4.0 * alpha));
    let g = mu + (1.0 + mu2) * at;
    var p: Point;
    p.a = a;
    p.load = a * a * (a - lambda * g);
    p.load_plus_2 = a * a * a + (8.0 / 3.0) * lambda * lambda * f2 * a - 2.0 * lambda * a * a * at;
    p.approach = a * (a - (4.0 / 3.0) * lambda * mu);
    p.m_minus_1 = m_minus_1;
    return p;
}

// The residual's quantity: Pbar + 2 (small lambda) or Pbar under load control, Dbar else.
fn quantity(lambda: f32, small: bool, control: u32, mu: f32) -> f32 {
    let p = curve_point(lambda, mu);
    if control == 1u {
        return p.approach;
    }
    if small && !naive() {
        return p.load_plus_2;
    }
    return p.load;
}

// The branch end as one f32 in naive units (Pbar, not Pbar + 2).
fn naive_end(end: vec2<f32>, small: bool, control: u32) -> f32 {
    var shift = 0.0;
    if control == 0u && small {
        shift = 2.0;
    }
    return (end.x - shift) + end.y;
}

fn residual(lambda: f32, small: bool, end: vec2<f32>, control: u32, mu: f32, gap: f32) -> f32 {
    var r = ((quantity(lambda, small, control, mu) - end.x) - end.y) - gap;
    if naive() {
        r = (quantity(lambda, small, control, mu) - naive_end(end, small, control)) - gap;
    }
    let q = r / gap;
    if q <= -1.0 {
        return -INF;
    }
    return log1p_f(q);
}

fn cheb_eval(i: u32, control: u32, u: f32) -> f32 {
    var b1 = 0.0;
    var b2 = 0.0;
    for (var k = 7; k >= 1; k--) {
        let b0 = 2.0 * u * b1 - b2 + br_cheb(i, control, k);
        b2 = b1;
        b1 = b0;
    }
    return u * b1 - b2 + br_cheb(i, control, 0);
}

fn failed(status: u32) -> Out {
    // NaN is not portable in WGSL constants: the host reads the status and ignores the numbers.
    return Out(0.0, 0.0, 0.0, status);
}

// One point, as src/solver/mirror.rs solve_f32: the load (approach) is the pair hi + lo, or the
// distance above the branch end if is_gap.
fn solve(ci: u32, hi: f32, lo: f32, control: u32, is_gap: bool, max_iter_in: u32) -> Out {
    if lambdas[ci].invalid == 1u || !(abs(hi) < INF) {
        return failed(STATUS_INVALID);
    }
    let lambda = lambdas[ci].lambda;
    let small = lambdas[ci].small == 1u;
    let end = br_end(ci, control);
    let mu_ref = br_mu_ref(ci, control);
    let s_max = br_s_max(ci, control);
    let zero_end = control == 1u && lambdas[ci].disp_at_zero == 1u;
    var shift = 0.0;
    if control == 0u && small {
        shift = 2.0;
    }
    var gap = hi + lo;
    if !is_gap {
        gap = ((hi + shift) - end.x) + (lo - end.y);
    }
    if naive() {
        gap = hi;
        if !is_gap {
            gap = hi - naive_end(end, small, control);
        }
    }
    if gap < 0.0 {
        return failed(STATUS_NO_CONTACT);
    }
    var iterations = 0u;
    var status = STATUS_OK;
    var mu = mu_ref;
    if gap == 0.0 {
        if zero_end {
            return Out(0.0, lambdas[ci].end_load, INF, STATUS_OK);
        }
    } else if !naive() && sqrt(gap) < s_max {
        let s = sqrt(gap);
        let dx = s * cheb_eval(ci, control, 2.0 * s / s_max - 1.0);
        mu = mu_ref * exp_f(dx);
    } else {
        let t = ln_f(gap);
        let n = TABLE_NODES;
        // First node with t_k >= t (binary search: the same k as a scan, in 4 steps).
        var k = 0u;
        var k_hi = n;
        while k < k_hi {
            let mid = (k + k_hi) / 2u;
            if br_t(ci, control, mid) < t {
                k = mid + 1u;
            } else {
                k_hi = mid;
            }
        }
        var end_dx = 0.0;
        if zero_end {
            end_dx = br_dx(ci, control, 0) + 60.0;
        }
        var hi_x = end_dx;
        var f_hi = -INF;
        if k >= 2u {
            hi_x = br_dx(ci, control, k - 2u);
            f_hi = br_t(ci, control, k - 2u) - t;
        }
        var lo_x = br_dx(ci, control, n - 1u) - 120.0;
        var f_lo = INF;
        if k + 1u < n {
            lo_x = br_dx(ci, control, k + 1u);
            f_lo = br_t(ci, control, k + 1u) - t;
        }
        var x: f32;
        if k == 0u {
            if zero_end {
                x = br_dx(ci, control, 0) + 1.0;
            } else {
                x = br_dx(ci, control, 0) * exp_f(0.5 * (t - br_t(ci, control, 0)));
            }
        } else if k == n {
            x = br_dx(ci, control, n - 1u) - 1.0;
        } else {
            let w = (t - br_t(ci, control, k - 1u)) / (br_t(ci, control, k) - br_t(ci, control, k - 1u));
            if zero_end {
                x = br_dx(ci, control, k - 1u) + w * (br_dx(ci, control, k) - br_dx(ci, control, k - 1u));
            } else {
                let l0 = ln_f(-br_dx(ci, control, k - 1u));
                x = -exp_f(l0 + w * (ln_f(-br_dx(ci, control, k)) - l0));
            }
        }
        if !(x > lo_x && x < hi_x) {
            x = 0.5 * (lo_x + hi_x);
        }
        var max_iter = max_iter_in;
        if max_iter == 0u {
            max_iter = 32u;
        }
        var m = mu_ref * exp_f(x);
        var have_prev = false;
        var f_prev = 0.0;
        var l_prev = 0.0;
        var dx_old = hi_x - lo_x;
        var done = false;
        // The best iterate so far: what an iteration cap returns.
        var best_f = INF;
        var best_m = m;
        for (var it = 1u; it <= max_iter; it++) {
            iterations = it;
            let fx = residual(lambda, small, end, control, m, gap);
            if abs(fx) < best_f {
                best_f = abs(fx);
                best_m = m;
            }
            // |F| at the f32 noise level: done (below it the secant slope is noise).
            if abs(fx) <= 8e-7 {
                done = true;
                break;
            }
            if fx > 0.0 {
                lo_x = x;
                f_lo = fx;
            } else {
                hi_x = x;
                f_hi = fx;
            }
            if hi_x - lo_x <= 4e-7 * max(abs(x), 1.0) {
                done = true;
                break;
            }
            var slope: f32;
            if have_prev && abs(f_prev) < INF && l_prev != 0.0 {
                slope = (fx - f_prev) / l_prev;
            } else if fx > 0.0 {
                slope = (f_hi - fx) / (hi_x - x);
            } else {
                slope = (f_lo - fx) / (lo_x - x);
            }
            let step = -fx / slope;
            let finite = abs(step) < INF;
            if finite && abs(step) <= 2.5e-7 {
                m *= exp_f(step);
                done = true;
                break;
            }
            let next = x + step;
            f_prev = fx;
            have_prev = true;
            if finite && next >= lo_x && next <= hi_x && abs(step) < 0.5 * abs(dx_old) {
                m *= exp_f(step);
                l_prev = step;
                dx_old = step;
                x = next;
            } else {
                let mid = 0.5 * (lo_x + hi_x);
                let m_new = mu_ref * exp_f(mid);
                l_prev = ln_f(m_new / m);
                dx_old = mid - x;
                x = mid;
                m = m_new;
            }
        }
        if !done {
            status = STATUS_NOT_CONVERGED;
            m = best_m;
        }
        mu = m;
    }
    let p = curve_point(lambda, mu);
    var other = p.approach;
    if control == 1u {
        other = p.load;
    }
    return Out(p.a, other, p.m_minus_1, status | (iterations << 8u));
}
