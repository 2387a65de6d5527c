// An explicit ensemble's summits stepped through a cycle on the device, in f64 (adapters with
// SHADER_F64): every summit's branch, load and contact area at every separation, summed. CPU
// mirror: src/kernel/cpu/ensemble64.rs; the host's own stepping: rough::ensemble::add_summit.
//   sum_chunks: one thread per (chunk of summits, separation) adds up its chunk's summits in
//               order: 8 sums (approach: force, area, contacts, non-contacts; the retract's).
//   reduce:     one thread per (separation, sum) adds the chunks' sums in order.
// A contact state next to its fold (v below `exact_below`) is not interpolated: the thread
// flags it (summit, separation and leg) and the host adds its exact state.

// Twin of kernel::layout::SummitRec (136 bytes).
struct Summit {
    height_m: f64,
    unit: f64,
    force: f64,
    radius: f64,
    half_pi_lambda: f64,
    h0: f64,
    c_star: f64,
    c_end: f64,
    delta_in: f64,
    delta_out: f64,
    delta_nc: f64,
    delta_max: f64,
    w0: f64,
    w1: f64,
    w2: f64,
    w3: f64,
    first: u32,
    has_nc: u32,
}

// Twin of kernel::layout::EnsembleParams (48 bytes).
struct Params {
    exact_below: f64,
    inv_h: f64,
    two_over_us: f64,
    summits: u32,
    seps: u32,
    chunk: u32,
    chunks: u32,
    retract_only: u32,
    flag_cap: u32,
}

struct Flags {
    count: atomic<u32>,
    // 1 once a state found no room: the host then steps the summits itself.
    over: atomic<u32>,
    // (summit, separation | leg << 31), leg 1 the retract.
    entries: array<vec2<u32>>,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> summits: array<Summit>;
// The node tables' cubic coefficients (lowest first), all nodes' load tables then area tables.
@group(0) @binding(2) var<storage, read> coefs: array<vec4<f64>>;
// Per node: (first coefficient, intervals) of its load table, then of its area table.
@group(0) @binding(3) var<storage, read> nodes: array<vec4<u32>>;
@group(0) @binding(4) var<storage, read> seps: array<f64>;
@group(0) @binding(5) var<storage, read_write> partials: array<f64>;
@group(0) @binding(6) var<storage, read_write> flags: Flags;
@group(0) @binding(7) var<storage, read_write> sums: array<f64>;

const PI: f64 = 3.141592653589793;

// rough::map::spline_at: the interval's cubic at x (in steps from the first node), the last
// interval's beyond the table.
fn spline_at(first: u32, intervals: u32, x: f64) -> f64 {
    let last = intervals - 1u;
    let xk = max(min(x, f64(last)), 0.0);
    let k = u32(xk);
    let s = x - f64(k);
    let c = coefs[first + k];
    return ((c.w * s + c.z) * s + c.y) * s + c.x;
}

// rough::map::v_of_u.
fn v_of_u(u: f64) -> f64 {
    return 2.0 * u / (1.0 + sqrt(1.0 + u * params.two_over_us));
}

// Adds one leg's state (0 approach, 1 retract) of summit i at separation k into acc[4 leg..].
// Branches: 0 free, 1 non-contact, 2 contact.
fn add_state(acc: ptr<function, array<f64, 8>>, s: Summit, i: u32, k: u32, leg: u32, delta: f64, branch: u32) {
    let o = 4u * leg;
    if branch == 1u {
        let root = max(s.c_star * s.c_star + 2.0 * (delta + s.h0), 0.0);
        let c = min(s.c_star + sqrt(root), s.c_end);
        (*acc)[o] += -(s.half_pi_lambda * c * c) * s.force;
        (*acc)[o + 3u] += 1.0;
    } else if branch == 2u {
        let v = v_of_u(sqrt(max(delta - s.delta_out, 0.0)));
        if v < params.exact_below {
            let at = atomicAdd(&flags.count, 1u);
            if at < params.flag_cap {
                flags.entries[at] = vec2<u32>(i, k | (leg << 31u));
            } else {
                atomicMax(&flags.over, 1u);
            }
            return;
        }
        let x = v * params.inv_h;
        let w = array<f64, 4>(s.w0, s.w1, s.w2, s.w3);
        var p: f64 = 0.0;
        var a: f64 = 0.0;
        for (var j = 0u; j < 4u; j++) {
            let n = nodes[s.first + j];
            p += w[j] * spline_at(n.x, n.y, x);
            a += w[j] * spline_at(n.z, n.w, x);
        }
        let ar = a * s.radius;
        (*acc)[o] += p * s.force;
        // pi a^2 in the order lavapipe's compiler gives PI * (ar * ar) anyway (the mirror's).
        (*acc)[o + 1u] += (PI * ar) * ar;
        (*acc)[o + 2u] += 1.0;
    }
}

@compute @workgroup_size(WORKGROUP)
fn sum_chunks(@builtin(global_invocation_id) gid: vec3<u32>) {
    let t = gid.x;
    if t >= params.chunks * params.seps {
        return;
    }
    let k = t % params.seps;
    let c = t / params.seps;
    let d = seps[k];
    var acc: array<f64, 8>;
    for (var q = 0u; q < 8u; q++) {
        acc[q] = 0.0;
    }
    let end = min((c + 1u) * params.chunk, params.summits);
    for (var i = c * params.chunk; i < end; i++) {
        let s = summits[i];
        let delta = (s.height_m - d) / s.unit;
        if params.retract_only == 0u {
            var b = 0u;
            if delta >= s.delta_in {
                b = 2u;
            } else if delta >= -s.h0 {
                b = 1u;
            }
            add_state(&acc, s, i, k, 0u, delta, b);
        }
        var r = 0u;
        if s.delta_max >= s.delta_in && delta >= s.delta_out {
            r = 2u;
        } else if s.has_nc == 1u && s.delta_max >= -s.h0 && delta >= s.delta_nc {
            r = 1u;
        }
        add_state(&acc, s, i, k, 1u, delta, r);
    }
    for (var q = 0u; q < 8u; q++) {
        partials[8u * t + q] = acc[q];
    }
}

@compute @workgroup_size(WORKGROUP)
fn reduce(@builtin(global_invocation_id) gid: vec3<u32>) {
    let t = gid.x;
    if t >= 8u * params.seps {
        return;
    }
    let k = t / 8u;
    let q = t % 8u;
    var total: f64 = 0.0;
    for (var c = 0u; c < params.chunks; c++) {
        total += partials[8u * (c * params.seps + k) + q];
    }
    sums[t] = total;
}
