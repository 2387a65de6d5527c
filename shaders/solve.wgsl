// Entry points. The host prepends md.wgsl (WGSL has no include).
//   grid:   a lambda x load grid; lambdas[ix] per column, the load pair of each row in `input`
//           (2 words per row: hi, lo). Nothing is uploaded per point.
//   points: a list; `input` holds 4 words per point: lambda index, load hi, load lo, unused.

@compute @workgroup_size(WORKGROUP)
fn grid(@builtin(global_invocation_id) gid: vec3<u32>) {
    let local = gid.x;
    if local >= params.count {
        return;
    }
    let i = params.offset + local;
    let ix = i % params.nx;
    let iy = i / params.nx;
    let hi = bitcast<f32>(input[2u * iy]);
    let lo = bitcast<f32>(input[2u * iy + 1u]);
    out[local] = solve(ix, hi, lo, params.max_iter);
}

@compute @workgroup_size(WORKGROUP)
fn points(@builtin(global_invocation_id) gid: vec3<u32>) {
    let local = gid.x;
    if local >= params.count {
        return;
    }
    let c = input[4u * local];
    let hi = bitcast<f32>(input[4u * local + 1u]);
    let lo = bitcast<f32>(input[4u * local + 2u]);
    out[local] = solve(c, hi, lo, params.max_iter);
}

// Measures the functions the kernels rely on, on this adapter: input = f32 arguments;
// out = (own atan, own mu - atan, own exp(-x/4), bits of the built-in atan) - tests/gpu.rs
// compares them with f64.
@compute @workgroup_size(WORKGROUP)
fn probe(@builtin(global_invocation_id) gid: vec3<u32>) {
    let local = gid.x;
    if local >= params.count {
        return;
    }
    let x = bitcast<f32>(input[local]);
    let ap = atan_parts(x);
    out[local] = Out(ap.x, ap.y, exp_f(-0.25 * x), bitcast<u32>(atan(x)));
}
