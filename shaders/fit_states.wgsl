// A force map's curve points at once, for adapters with SHADER_F64: the state of each point on
// the Maugis-Dugdale contact piece of its curve's path under the cantilever (src/fit/path.rs),
// where the base displacement Delta = Dbar + Pbar / kbar equals the point's. The host has
// followed each path and found each point's stretch and bracket; here Newton steps in mu on
// Delta, kept inside the bracket (Delta falls as mu grows on a followed stretch), to the CPU
// path's tolerance. CPU mirror: src/kernel/cpu/fit_states.rs.

// Twin of kernel::layout::FitCurve64 (16 bytes): one curve's Maugis parameter and spring.
struct FitCurve64 {
    lambda: f64,
    kbar: f64,
}

// Twin of kernel::layout::FitPoint64 (40 bytes): the point's Delta, its bracket in mu and the
// start, and its curve's index.
struct FitPoint64 {
    delta: f64,
    mu_lo: f64,
    mu_hi: f64,
    mu_start: f64,
    curve: u32,
    pad0: u32,
}

// Twin of kernel::layout::FitOut64 (32 bytes).
struct FitOut64 {
    mu: f64,
    load: f64,
    approach: f64,
    code: u32,
    pad0: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> curves: array<FitCurve64>;
@group(0) @binding(2) var<storage, read> input: array<FitPoint64>;
@group(0) @binding(3) var<storage, read_write> out: array<FitOut64>;

const FIT_OK: u32 = 0u;
const FIT_NOT_CONVERGED: u32 = 2u;

@compute @workgroup_size(WORKGROUP)
fn fit_states(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if i >= params.count {
        return;
    }
    let pt = input[i];
    let c = curves[pt.curve];
    var lo = pt.mu_lo;
    var hi = pt.mu_hi;
    var mu = clamp(pt.mu_start, lo, hi);
    var code = FIT_NOT_CONVERGED;
    var steps = 0u;
    var p = curve_point64(c.lambda, mu);
    for (var it = 0u; it < 100u; it++) {
        steps = it + 1u;
        let d = p.approach + p.load / c.kbar;
        let r = d - pt.delta;
        let tol = 1e-15 * max(abs(p.approach) + abs(p.load / c.kbar), 1.0);
        if abs(r) <= tol {
            code = FIT_OK;
            break;
        }
        // Delta falls with mu: above the target, the root lies at larger mu.
        if r > 0.0 {
            lo = mu;
        } else {
            hi = mu;
        }
        let s = p.dapproach + p.dload / c.kbar;
        let newton = mu - r / s;
        var next = 0.5 * (lo + hi);
        if s < 0.0 && newton > lo && newton < hi {
            next = newton;
        }
        if next == mu || !(hi > lo) {
            code = FIT_OK;
            break;
        }
        mu = next;
        p = curve_point64(c.lambda, mu);
    }
    out[i] = FitOut64(mu, p.load, p.approach, code | (steps << 8u), 0u);
}
