//! GPU host code: adapter choice, the reusable compute context, chunked dispatches and readback.

pub mod layout;
pub mod prepare;

/// The WGSL source of the kernels: the shared functions, then the entry points.
pub fn shader_source() -> String {
    concat!(
        include_str!("../../shaders/md.wgsl"),
        "\n",
        include_str!("../../shaders/solve.wgsl")
    )
    .to_string()
}

pub mod device;
pub use device::{list_adapters, AdapterSummary, Gpu, GpuError};
