//! The kernels' host side that needs no GPU: the byte layout shared with the WGSL structs
//! (`layout`), the per-lambda preparation in f64 (`prepare`), and a CPU mirror of each WGSL
//! kernel (`cpu`), as vello's `vello_shaders/src/cpu/`. Tests and benchmarks run the kernels'
//! arithmetic here without an adapter; `gpu` runs the same layouts on one.

pub mod cpu;
pub mod layout;
pub mod prepare;

/// The WGSL source of the f32 kernels: the shared functions, then the entry points.
pub fn shader_source() -> String {
    concat!(
        include_str!("../../shaders/md.wgsl"),
        "\n",
        include_str!("../../shaders/solve.wgsl")
    )
    .to_string()
}

/// The WGSL source of the f64 refinement (a separate module: it needs SHADER_F64).
pub fn polish64_source() -> &'static str {
    include_str!("../../shaders/polish64.wgsl")
}
