//! The kernels' host side that needs no GPU: the byte layout shared with the WGSL structs
//! (`layout`), the per-lambda preparation in f64 (`prepare`), and a CPU mirror of each WGSL
//! kernel (`cpu`), as vello's `vello_shaders/src/cpu/`. Tests and benchmarks run the kernels'
//! arithmetic here without an adapter; `gpu` runs the same layouts on one.

pub mod cpu;
pub mod layout;
/// The kernels' launch shape and the WGSL prelude of shared constants.
pub mod prelude;
pub mod prepare;
pub mod start;

/// The f32 kernels' lambda domain, narrower than the exact solver's: their tables, fits and
/// f32 residuals were measured and tested over lambda 1e-8..1e8 only (README, Accuracy).
pub const KERNEL_LAMBDA_MIN: f64 = 1e-8;
/// See [`KERNEL_LAMBDA_MIN`].
pub const KERNEL_LAMBDA_MAX: f64 = 1e8;

/// Whether the kernels take this lambda; the engine solves the others on the CPU in f64 (by
/// the exact solver, or the closed-form limits beyond its domain).
pub fn kernel_lambda(lambda: f64) -> bool {
    (KERNEL_LAMBDA_MIN..=KERNEL_LAMBDA_MAX).contains(&lambda)
}

/// The WGSL source of the f32 kernels: the host's prelude of shared constants, the shared
/// functions, then the entry points.
pub fn shader_source() -> String {
    prelude::wgsl_prelude()
        + include_str!("../../shaders/md.wgsl")
        + "\n"
        + include_str!("../../shaders/solve.wgsl")
}

/// The WGSL source of a map's classification on the device (its own module: its bindings are
/// not the solvers').
pub fn classify_source() -> String {
    prelude::wgsl_prelude() + include_str!("../../shaders/classify.wgsl")
}

/// The WGSL source of an explicit ensemble's stepping in f64 (`shaders/ensemble64.wgsl`; its
/// own module, for adapters with SHADER_F64).
pub fn ensemble64_source() -> String {
    prelude::wgsl_prelude() + include_str!("../../shaders/ensemble64.wgsl")
}

/// The WGSL source of the f64 refinement (a separate module: it needs SHADER_F64), after the
/// same prelude.
pub fn polish64_source() -> String {
    prelude::wgsl_prelude()
        + include_str!("../../shaders/curve64.wgsl")
        + "\n"
        + include_str!("../../shaders/polish64.wgsl")
}
