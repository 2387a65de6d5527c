// A map's classification on the device, after the grid kernel has solved the same points: each
// point's simplest adequate model and the models adequate on their own criterion, as one byte
// (four to a word), and the whole results of the few points the host asks for (the figure's
// contour grid, the cross-check's sample). The map then reads back a byte a point, not 16.
// In f64 (adapters with SHADER_F64), on the f64 lambdas and loads: the same bytes as the host's
// classification of the same f32 states. CPU mirror: src/kernel/cpu/classify.rs. The host
// prepends the prelude (WORKGROUP).
//
// A byte: the region in bits 0-2 (0 no contact, 1 Hertz, 2 rigid, 3 DMT, 4 JKR, 5 MD,
// 6 failed, as `map::Region`) and the adequate models in bits 3-6 (Hertz, rigid, DMT, JKR).

struct Params {
    cube_lo: f64,      // (1 - tol)^3
    cube_hi: f64,      // (1 + tol)^3
    tol: f64,
    nx: u32,           // grid columns
    offset: u32,       // the dispatch's first point
    count: u32,        // points in this dispatch
    picks: u32,        // results to copy out
    marks_words: u32,  // words of marks in `out`; the picked results follow, 4 words each
    _pad0: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
// Each column's lambda and each row's load as the host has them, in f64.
@group(0) @binding(1) var<storage, read> lambdas: array<f64>;
@group(0) @binding(2) var<storage, read> loads: array<f64>;
// The grid kernel's results of this dispatch (a, other, m - 1, code).
@group(0) @binding(3) var<storage, read> states: array<vec4<u32>>;
// The dispatch-local indices of the results to copy out.
@group(0) @binding(4) var<storage, read> pick: array<u32>;
// The marks, then the picked results: one buffer, one copy back.
@group(0) @binding(5) var<storage, read_write> out: array<u32>;

const HALF_PI: f64 = 1.5707963267948966;

// The tests of `map::adequate` on cubes, in f64 on the f32 state as the host classifies it:
// |A_m / A - 1| <= tol exactly when A_m^3 lies in [(1 - tol)^3 A^3, (1 + tol)^3 A^3].
fn mark(local: u32) -> u32 {
    let i = params.offset + local;
    let s = states[local];
    let status = s.w & 0xffu;
    if status == 1u {
        return 0u;
    }
    if status != 0u {
        return 6u;
    }
    let lambda = lambdas[i % params.nx];
    let p = loads[i / params.nx];
    let a = f64(bitcast<f32>(s.x));
    let approach = f64(bitcast<f32>(s.y));
    let a3 = a * a * a;
    let lo = params.cube_lo * a3;
    let hi = params.cube_hi * a3;
    var bits = 0u;
    if p >= 0.0 && p >= lo && p <= hi {
        bits |= 1u;
    }
    if HALF_PI * lambda * max(a * a, abs(approach)) <= params.tol {
        bits |= 2u;
    }
    let dmt = p + 2.0;
    if dmt >= lo && dmt <= hi {
        bits |= 4u;
    }
    if p >= -1.5 {
        let jkr = p + 3.0 + sqrt(max(9.0 + 6.0 * p, 0.0));
        if jkr >= lo && jkr <= hi {
            bits |= 8u;
        }
    }
    let region = select(5u, firstTrailingBit(bits) + 1u, bits != 0u);
    return region | (bits << 3u);
}

@compute @workgroup_size(WORKGROUP)
fn classify(@builtin(global_invocation_id) gid: vec3<u32>) {
    let w = gid.x;
    if w < params.picks {
        let s = states[pick[w]];
        let at = params.marks_words + 4u * w;
        out[at] = s.x;
        out[at + 1u] = s.y;
        out[at + 2u] = s.z;
        out[at + 3u] = s.w;
    }
    let first = 4u * w;
    if first >= params.count {
        return;
    }
    var word = 0u;
    for (var k = 0u; k < 4u; k++) {
        if first + k < params.count {
            word |= mark(first + k) << (8u * k);
        }
    }
    out[w] = word;
}
