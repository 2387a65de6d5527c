// f64 refinement of the f32 kernels' states, for adapters with SHADER_F64 (a separate module:
// the f32 kernels must run where f64 does not exist). Each point starts from its f32 state
// and takes safeguarded Newton steps in mu on the f64 curve of shaders/curve64.wgsl.

// Twin of kernel::layout::Lambda64 (56 bytes).
struct Lambda64 {
    lambda: f64,
    // The branch end of the residual's quantity: Pbar_c (+ 2 for small lambda), Dbar_min.
    load_end: f64,
    disp_end: f64,
    // mu at the end of each interior branch: the stable side is mu < mu_end.
    mu_load: f64,
    mu_disp: f64,
    small: u32,
    disp_at_zero: u32,
    invalid: u32,
    pad0: u32,
}

// Twin of kernel::layout::Point64 (24 bytes): the value (load or approach, or with ROWS_ARE_GAPS
// its distance above the branch end), the lambda index, and the f32 kernel's status code and
// m - 1.
struct Point64 {
    value: f64,
    ci: u32,
    code: u32,
    m_minus_1: f32,
    pad0: u32,
}

// Twin of kernel::layout::Out64 (32 bytes).
struct Out64 {
    a: f64,
    other: f64,
    m_minus_1: f64,
    code: u32,
    pad0: u32,
}

override CONTROL: u32 = 0u; // 0 load control, 1 displacement control
override ROWS_ARE_GAPS: bool = false; // values are distances above the branch end

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> lambdas: array<Lambda64>;
@group(0) @binding(2) var<storage, read> input: array<Point64>;
@group(0) @binding(3) var<storage, read_write> out: array<Out64>;

const STATUS_OK: u32 = 0u;
const STATUS_NOT_CONVERGED: u32 = 2u;
@compute @workgroup_size(WORKGROUP)
fn polish(@builtin(global_invocation_id) gid: vec3<u32>) {
    let local = gid.x;
    if local >= params.count {
        return;
    }
    let pt = input[local];
    let status = pt.code & 0xffu;
    // No contact, invalid input, or the zero-radius end: the f32 kernel's answer stands.
    if (status != STATUS_OK && status != STATUS_NOT_CONVERGED) || !(pt.m_minus_1 < 3.0e38) {
        out[local] = Out64(0.0, 0.0, 0.0, pt.code, 0u);
        return;
    }
    let c = lambdas[pt.ci];
    let small = c.small == 1u;
    // Q - goal = (Q - end) - gap with the gap exact, as the f64 CPU solver does it; given a
    // load, goal = load (+ 2 where Q is Pbar + 2).
    var goal = pt.value;
    var end = c.disp_end;
    var mu_end = c.mu_disp;
    var interior = c.disp_at_zero == 0u;
    if CONTROL == 0u {
        goal = select(pt.value, pt.value + 2.0, small);
        end = c.load_end;
        mu_end = c.mu_load;
        interior = true;
    }
    let mm1 = f64(pt.m_minus_1);
    var mu = sqrt(mm1 * (mm1 + 2.0));
    var max_iter = select(params.max_iter, 8u, params.max_iter == 0u);
    var done = false;
    var steps = 0u;
    var r_prev: f64 = 1.0e300;
    for (var it = 1u; it <= max_iter; it++) {
        steps = it;
        let p = curve_point64(c.lambda, mu);
        var q = select(p.load, p.load_plus_2, small);
        var dq = p.dload;
        if CONTROL == 1u {
            q = p.approach;
            dq = p.dapproach;
        }
        var res = q - goal;
        if ROWS_ARE_GAPS {
            res = (q - end) - pt.value;
        }
        let r = abs(res);
        // Near pull-off dQ/dmu -> 0 and the steps stay at the noise of Q / dQ: once |Q - goal|
        // has stopped falling and is at rounding level, it is as good as f64 gets.
        if it > 2u && r >= 0.5 * r_prev && r <= 1e-13 * max(abs(q), 1.0) {
            done = true;
            break;
        }
        r_prev = r;
        let step = -res / dq;
        var next = mu + step;
        // Stay on the stable branch (mu < mu_end on an interior branch) and at mu > 0.
        if interior && next >= mu_end {
            next = 0.5 * (mu + mu_end);
        }
        if !(next > 0.0) {
            next = 0.5 * mu;
        }
        let moved = abs(next - mu);
        mu = next;
        // Newton converges quadratically: after a step of 1e-13 the next would be at the noise level.
        if moved <= 1e-13 * mu {
            done = true;
            break;
        }
    }
    let p = curve_point64(c.lambda, mu);
    let other = select(p.approach, p.load, CONTROL == 1u);
    var code = pt.code & 0xffu;
    if !done || !(abs(p.a) < 1.0e300) {
        code = STATUS_NOT_CONVERGED;
    }
    out[local] = Out64(p.a, other, p.m_minus_1, code | (steps << 8u), 0u);
}
