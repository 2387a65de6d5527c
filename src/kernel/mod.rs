//! The kernels' host side that needs no GPU: the byte layout shared with the WGSL structs
//! (`layout`), the per-lambda preparation in f64 (`prepare`), and a CPU mirror of each WGSL
//! kernel (`cpu`), as vello's `vello_shaders/src/cpu/`. Tests and benchmarks run the kernels'
//! arithmetic here without an adapter; `gpu` runs the same layouts on one.

pub mod cpu;
pub mod layout;
pub mod prepare;
pub mod start;

/// The WGSL source of the f32 kernels: the host's prelude of shared constants, the shared
/// functions, then the entry points.
pub fn shader_source() -> String {
    crate::physics::tolerances::wgsl_prelude()
        + include_str!("../../shaders/md.wgsl")
        + "\n"
        + include_str!("../../shaders/solve.wgsl")
}

/// The WGSL source of the f64 refinement (a separate module: it needs SHADER_F64), after the
/// same prelude.
pub fn polish64_source() -> String {
    crate::physics::tolerances::wgsl_prelude()
        + include_str!("../../shaders/curve64.wgsl")
        + "\n"
        + include_str!("../../shaders/polish64.wgsl")
}

/// The WGSL source of the force-map states (`shaders/fit_states.wgsl`, f64 like the refinement,
/// whose curve point it shares), after the same prelude.
pub fn fit_states_source() -> String {
    crate::physics::tolerances::wgsl_prelude()
        + include_str!("../../shaders/curve64.wgsl")
        + "\n"
        + include_str!("../../shaders/fit_states.wgsl")
}
