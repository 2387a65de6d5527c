// Maugis-Dugdale states in f32: the shared functions of every tabor kernel.
// Read side by side with src/kernel/cpu/md.rs (the CPU mirror) and src/physics/md.rs.
// No built-in transcendental is trusted (lavapipe's inverse trigonometry is off by 1.6e-4 and
// the Vulkan exp bound is 3 + 2|x| ulp): atan, exp and ln below are written out, with the error
// bounds measured in tests/gpu.rs and src/kernel/cpu/md.rs.

// Twin of kernel::layout::Branch (40 x 4 bytes).
struct Branch {
    mu_ref: f32,
    end_hi: f32,
    end_lo: f32,
    s_max: f32,
    cheb: array<f32, CHEB_TERMS>,
    t: array<f32, TABLE_NODES>,
    dx: array<f32, TABLE_NODES>,
}

// Twin of kernel::layout::GpuLambda (88 x 4 bytes).
struct Lambda {
    lambda: f32,
    small: u32,
    disp_at_zero: u32,
    invalid: u32,
    end_load: f32,
    start_at: u32,
    pad1: u32,
    pad2: u32,
    load: Branch,
    disp: Branch,
}

// Twin of kernel::layout::Params.
struct Params {
    nx: u32,
    offset: u32,
    count: u32,
    // An iteration cap for benchmarks (0: iterate to convergence).
    max_iter: u32,
}

// Pipeline constants: each variant is its own pipeline. A software adapter runs both sides of
// every branch under a lane mask, so a variant chosen at run time would cost all the others too.
override CONTROL: u32 = 0u; // 0 load control, 1 displacement control
override ROWS_ARE_GAPS: bool = false; // grid rows hold the distance above the branch end
override NAIVE: bool = false; // the textbook formulas, for benchmarks

// Twin of kernel::layout::Out. code = status | iterations << 8.
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

// Fields of the branch in use (CONTROL) of lambdas[i], read in place: copying the 352-byte
// struct into every invocation costs more than the whole root search.
fn br_mu_ref(i: u32) -> f32 {
    if CONTROL == 1u {
        return lambdas[i].disp.mu_ref;
    }
    return lambdas[i].load.mu_ref;
}
fn br_end(i: u32) -> vec2<f32> {
    if CONTROL == 1u {
        return vec2<f32>(lambdas[i].disp.end_hi, lambdas[i].disp.end_lo);
    }
    return vec2<f32>(lambdas[i].load.end_hi, lambdas[i].load.end_lo);
}
fn br_s_max(i: u32) -> f32 {
    if CONTROL == 1u {
        return lambdas[i].disp.s_max;
    }
    return lambdas[i].load.s_max;
}
fn br_cheb(i: u32, k: i32) -> f32 {
    if CONTROL == 1u {
        return lambdas[i].disp.cheb[k];
    }
    return lambdas[i].load.cheb[k];
}
fn br_t(i: u32, k: u32) -> f32 {
    if CONTROL == 1u {
        return lambdas[i].disp.t[k];
    }
    return lambdas[i].load.t[k];
}
fn br_dx(i: u32, k: u32) -> f32 {
    if CONTROL == 1u {
        return lambdas[i].disp.dx[k];
    }
    return lambdas[i].load.dx[k];
}

const STATUS_OK: u32 = 0u;
const STATUS_NO_CONTACT: u32 = 1u;
const STATUS_NOT_CONVERGED: u32 = 2u;
const STATUS_INVALID: u32 = 3u;
const HALF_PI: f32 = 1.5707963267948966;
const LN2_HI: f32 = 0.69314575;
const LN2_LO: f32 = 1.4286068e-6;
const LN2: f32 = 0.6931472;
const LOG2E: f32 = 1.4426950408889634;
const INF: f32 = 3.0e38;
// TABLE_NODES, CHEB_TERMS and the iteration's thresholds (F_NOISE, BRACKET_CLOSED,
// SUB_ULP_STEP, BRACKET_BELOW, BRACKET_ABOVE, MAX_ITER) come from the host's prelude
// (kernel::prelude::wgsl_prelude), shared with the CPU mirror.

// (atan(mu), mu - atan(mu)) from one half-angle step and a polynomial, without loops (a
// masked loop runs as long as its slowest lane). For mu > 1, atan(mu) = pi/2 - atan(1/mu).
fn atan_parts(mu: f32) -> vec2<f32> {
    let big = mu > 1.0;
    let t0 = select(mu, 1.0 / mu, big);
    // atan t0 = 2 atan t with t = t0 / (1 + sqrt(1 + t0^2)) <= tan(pi/8), and t0 - 2 t = t0 t^2
    // exactly, so t0 - atan t0 = t0 t^2 + 2 (t - atan t) has no cancellation.
    let t = t0 / (1.0 + sqrt(1.0 + t0 * t0));
    let z = t * t;
    // (t - atan t) / t^3 for z in [0, tan^2(pi/8)]: degree-5 fit, relative error 1.6e-9.
    let g = 0.33333334 + z * (-0.19999978 + z * (0.14284152 + z * (-0.11071365 + z * (0.08624676 + z * -0.050481386))));
    let d0 = z * (t0 + 2.0 * t * g);
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

// ln(1 + q), accurate for small q; -INF for q <= -1 (as physics::f32math::log1p_f32).
fn log1p_f(q: f32) -> f32 {
    // Small q (the residual near convergence): 2 atanh(s), s = q / (2 + q), by its series
    // (truncation below 1e-11 for |q| < 0.1). Goldberg's q / ((1 + q) - 1) correction is not
    // used: a compiler may simplify (1 + q) - 1 to q (Mesa's NIR does), which undoes it.
    let s = q / (2.0 + q);
    let z = s * s;
    let series = 2.0 * s * (1.0 + z * (1.0 / 3.0 + z * (1.0 / 5.0 + z * (1.0 / 7.0))));
    return select(ln_f(1.0 + q), series, abs(q) < 0.1);
}

// A curve point: A, Pbar, Pbar + 2, Dbar, m - 1 (src/physics/md.rs, curve_point).
struct Point {
    a: f32,
    load: f32,
    load_plus_2: f32,
    approach: f32,
    m_minus_1: f32,
}

// The NAIVE variant: the textbook formulas, which cancel as m -> 1 (src/kernel/cpu/md.rs,
// curve_point_naive).
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
    if NAIVE {
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
    p.load_plus_2 = a * (a * a + (8.0 / 3.0) * lambda * lambda * f2) - 2.0 * lambda * a * a * at;
    p.approach = a * (a - (4.0 / 3.0) * lambda * mu);
    p.m_minus_1 = m_minus_1;
    return p;
}

// The residual's quantity: Dbar under displacement control, else Pbar + 2 (small lambda) or Pbar.
fn quantity(p: Point, small: bool) -> f32 {
    if CONTROL == 1u {
        return p.approach;
    }
    return select(p.load, p.load_plus_2, small && !NAIVE);
}

// F = ln(gap(mu) / gap): zero at the root, positive farther from the branch end. The NAIVE
// variant subtracts the branch end as one f32 in Pbar (not Pbar + 2).
fn residual(p: Point, small: bool, end: vec2<f32>, shift: f32, gap: f32) -> f32 {
    var r = ((quantity(p, small) - end.x) - end.y) - gap;
    if NAIVE {
        r = (quantity(p, small) - ((end.x - shift) + end.y)) - gap;
    }
    return log1p_f(r / gap);
}

fn cheb_eval(i: u32, u: f32) -> f32 {
    var b1 = 0.0;
    var b2 = 0.0;
    for (var k = 7; k >= 1; k--) {
        let b0 = 2.0 * u * b1 - b2 + br_cheb(i, k);
        b2 = b1;
        b1 = b0;
    }
    return u * b1 - b2 + br_cheb(i, 0);
}

// The dense start of lambda `ci`'s load branch, from its block in `input` at word `sa` (see
// src/kernel/start.rs, whose start_x is this, operation for operation): x = ln(mu / mu_ref) by a
// cubic Hermite in t = ln(gap), and dF/dx = dt/dx; slope 0 where t is outside the table.
fn start_x(sa: u32, t: f32) -> vec2<f32> {
    let n = input[sa];
    let nb = input[sa + 1u];
    let t0 = bitcast<f32>(input[sa + 2u]);
    let per_t = bitcast<f32>(input[sa + 3u]);
    let nodes = sa + 4u + nb;
    if !(t >= t0 && t <= bitcast<f32>(input[nodes + 3u * (n - 1u)])) {
        return vec2<f32>(0.0, 0.0);
    }
    let b = min(u32((t - t0) * per_t), nb - 1u);
    var k = input[sa + 4u + b];
    while k + 2u < n && bitcast<f32>(input[nodes + 3u * (k + 1u)]) <= t {
        k += 1u;
    }
    let i = nodes + 3u * k;
    let ta = bitcast<f32>(input[i]);
    let xa = bitcast<f32>(input[i + 1u]);
    let sa_ = bitcast<f32>(input[i + 2u]);
    let tb = bitcast<f32>(input[i + 3u]);
    let xb = bitcast<f32>(input[i + 4u]);
    let sb = bitcast<f32>(input[i + 5u]);
    let w = tb - ta;
    let s = (t - ta) / w;
    let u = 1.0 - s;
    let x = (1.0 + 2.0 * s) * u * u * xa + s * u * u * w * sa_ + s * s * (3.0 - 2.0 * s) * xb + s * s * (s - 1.0) * w * sb;
    return vec2<f32>(x, 1.0 / (sa_ + s * (sb - sa_)));
}

fn failed(status: u32) -> Out {
    // NaN is not portable in WGSL constants: the host reads the status and ignores the numbers.
    return Out(0.0, 0.0, 0.0, status);
}

fn lerp_point(p: Point, q: Point, c: f32) -> Point {
    return Point(p.a + c * (p.a - q.a), p.load + c * (p.load - q.load), p.load_plus_2 + c * (p.load_plus_2 - q.load_plus_2), p.approach + c * (p.approach - q.approach), p.m_minus_1 + c * (p.m_minus_1 - q.m_minus_1));
}

// The root search's first x = ln(mu / mu_ref), the slope dF/dx for its first step, and the
// bracket around it (src/kernel/cpu/md.rs, first_guess). Near the branch end the Chebyshev fit
// gives x directly (one evaluation); elsewhere the table brackets the root and gives the first
// guess, or the lambda's dense start where the grid has one (load control only).
struct Guess {
    direct: bool,
    x: f32,
    slope0: f32,
    lo_x: f32,
    f_lo: f32,
    hi_x: f32,
    f_hi: f32,
}

fn first_guess(ci: u32, gap: f32, zero_end: bool) -> Guess {
    let s = sqrt(gap);
    let s_max = br_s_max(ci);
    let direct = gap == 0.0 || (!NAIVE && s < s_max);
    let n = TABLE_NODES;
    var x = 0.0;
    var slope0 = 0.0;
    var lo_x = br_dx(ci, n - 1u) - BRACKET_BELOW;
    var f_lo = INF;
    var hi_x = select(0.0, br_dx(ci, 0u) + BRACKET_ABOVE, zero_end);
    var f_hi = -INF;
    if direct {
        x = select(s * cheb_eval(ci, 2.0 * s / s_max - 1.0), 0.0, gap == 0.0);
    } else {
        let t = ln_f(gap);
        // First node with t_k >= t (binary search: the same k as a scan, in 4 steps).
        var k = 0u;
        var k_hi = n;
        while k < k_hi {
            let mid = (k + k_hi) / 2u;
            if br_t(ci, mid) < t {
                k = mid + 1u;
            } else {
                k_hi = mid;
            }
        }
        // Bracket one node wider than the interval, in case a node's f32 mu sits on the root.
        if k >= 2u {
            hi_x = br_dx(ci, k - 2u);
            f_hi = br_t(ci, k - 2u) - t;
        }
        if k + 1u < n {
            lo_x = br_dx(ci, k + 1u);
            f_lo = br_t(ci, k + 1u) - t;
        }
        x = br_dx(ci, n - 1u) - 1.0;
        if k < n {
            let k1 = max(k, 1u);
            let d0 = br_dx(ci, k1 - 1u);
            let w = (t - br_t(ci, k1 - 1u)) / (br_t(ci, k1) - br_t(ci, k1 - 1u));
            if zero_end {
                x = select(d0 + w * (br_dx(ci, k1) - d0), br_dx(ci, 0u) + 1.0, k == 0u);
            } else {
                // Interior nodes double (dx_k = dx_0 2^k), so ln|dx| is linear in k between
                // nodes; before the first node the gap is quadratic in dx.
                x = d0 * exp_f(select(w * LN2, 0.5 * (t - br_t(ci, 0u)), k == 0u));
            }
        }
        // The first step's slope dF/dx = dt/dx: the table's chord around the guess.
        let kc = clamp(k, 1u, n - 1u);
        slope0 = (br_t(ci, kc) - br_t(ci, kc - 1u)) / (br_dx(ci, kc) - br_dx(ci, kc - 1u));
        // The dense start, where the grid has one (load control only): x to about f32
        // precision and its own slope, so that the first evaluation is usually the answer.
        let sa = lambdas[ci].start_at;
        if CONTROL == 0u && !NAIVE && sa != 0u {
            let st = start_x(sa, t);
            if st.y != 0.0 {
                x = st.x;
                slope0 = st.y;
            }
        }
        if !(x > lo_x && x < hi_x) {
            x = 0.5 * (lo_x + hi_x);
        }
    }
    return Guess(direct, x, slope0, lo_x, f_lo, hi_x, f_hi);
}

// One point, as src/kernel/cpu/md.rs solve_f32: the load (approach) is the pair hi + lo, or the
// distance above the branch end if ROWS_ARE_GAPS. max_iter_in: 0, or a cap for benchmarks.
fn solve(ci: u32, hi: f32, lo: f32, max_iter_in: u32) -> Out {
    if lambdas[ci].invalid == 1u || !(abs(hi) < INF) {
        return failed(STATUS_INVALID);
    }
    let lambda = lambdas[ci].lambda;
    let small = lambdas[ci].small == 1u;
    let end = br_end(ci);
    let mu_ref = br_mu_ref(ci);
    let zero_end = CONTROL == 1u && lambdas[ci].disp_at_zero == 1u;
    let shift = select(0.0, 2.0, CONTROL == 0u && small);
    // hi + shift - end.x is exact where it matters (Sterbenz), then the low parts are added.
    var gap = select(((hi + shift) - end.x) + (lo - end.y), hi + lo, ROWS_ARE_GAPS);
    if NAIVE {
        gap = select(hi - ((end.x - shift) + end.y), hi, ROWS_ARE_GAPS);
    }
    if gap < 0.0 {
        return failed(STATUS_NO_CONTACT);
    }
    if gap == 0.0 && zero_end {
        return Out(0.0, lambdas[ci].end_load, INF, STATUS_OK);
    }
    let g = first_guess(ci, gap, zero_end);
    let direct = g.direct;
    let slope0 = g.slope0;
    var x = g.x;
    var lo_x = g.lo_x;
    var f_lo = g.f_lo;
    var hi_x = g.hi_x;
    var f_hi = g.f_hi;
    // Secant in x with a bisection safeguard; mu is carried apart and updated multiplicatively,
    // since an f32 x near 14 resolves mu only to 1e-6.
    var max_iter = select(max_iter_in, MAX_ITER, max_iter_in == 0u);
    var m = mu_ref * exp_f(x);
    var p: Point;
    var p_prev: Point;
    var have_prev = false;
    var f_prev = 0.0;
    var l_prev = 0.0;
    var dx_old = hi_x - lo_x;
    var rf_last = false;
    var done = false;
    var iterations = 0u;
    // The best iterate so far: what an iteration cap returns.
    var best_f = INF;
    var best: Point;
    for (var it = 1u; it <= max_iter; it++) {
        iterations = it;
        p = curve_point(lambda, m);
        let fx = residual(p, small, end, shift, gap);
        if abs(fx) < best_f {
            best_f = abs(fx);
            best = p;
        }
        // The direct start is the answer; |F| at the f32 noise level is done (below it the
        // secant slope is noise).
        if direct || abs(fx) <= F_NOISE {
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
        if hi_x - lo_x <= BRACKET_CLOSED * max(abs(x), 1.0) {
            done = true;
            break;
        }
        // Secant slope; before there is one, the table's; without either, the chord to the
        // bracket end on the other side.
        var slope = slope0;
        if have_prev && abs(f_prev) < INF && l_prev != 0.0 {
            slope = (fx - f_prev) / l_prev;
        } else if have_prev && fx > 0.0 {
            slope = (f_hi - fx) / (hi_x - x);
        } else if have_prev {
            slope = (f_lo - fx) / (lo_x - x);
        }
        let step = -fx / slope;
        // A zero step from an infinite slope is no step: bisect.
        let finite = abs(step) < INF && step != 0.0;
        // A step below 4 ulp of x: the state there is this one moved along the last secant
        // (the error is second order in the step), not one more evaluation.
        if finite && abs(step) <= SUB_ULP_STEP * max(abs(x), 1.0) && have_prev && l_prev != 0.0 {
            p = lerp_point(p, p_prev, step / l_prev);
            done = true;
            break;
        }
        let next = x + step;
        let take = finite && next >= lo_x && next <= hi_x && abs(step) < 0.5 * abs(dx_old);
        // Else regula falsi on the bracket, which lands next to an end whose F is already at
        // the noise level (bisection would walk back from the far end), but never twice in a
        // row, so that the bracket at least halves every other step.
        let rf = lo_x - f_lo * (hi_x - lo_x) / (f_hi - f_lo);
        let use_rf = !take && !rf_last && rf > lo_x && rf < hi_x;
        rf_last = use_rf;
        let to = select(0.5 * (lo_x + hi_x), rf, use_rf);
        let d = select(to - x, step, take);
        m *= exp_f(d);
        x = select(to, next, take);
        f_prev = fx;
        p_prev = p;
        have_prev = true;
        l_prev = d;
        dx_old = d;
    }
    return finish(p, done, best, iterations);
}

// The answer: the converged point, or the best iterate where the cap was reached (status not
// converged), with the iterations in the code's high bits (src/kernel/cpu/md.rs, finish).
fn finish(p_in: Point, done: bool, best: Point, iterations: u32) -> Out {
    var p = p_in;
    var status = STATUS_OK;
    if !done {
        status = STATUS_NOT_CONVERGED;
        p = best;
    }
    let other = select(p.approach, p.load, CONTROL == 1u);
    // Only the NAIVE formulas can produce a non-number (0/0 where m - 1 rounds to 0): say so.
    if !(abs(p.a) < INF && abs(other) < INF) {
        status = STATUS_NOT_CONVERGED;
    }
    return Out(p.a, other, p.m_minus_1, status | (iterations << 8u));
}
