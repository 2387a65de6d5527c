//! GPU host code: adapter choice, the reusable compute context, chunked dispatches and readback.
//! The byte layouts, the per-lambda preparation and the shader sources live in `kernel`.

pub mod device;
pub use device::{
    choose_summary, list_adapters, AdapterSummary, EnsembleSums, Gpu, GpuError, SummitBuffers,
};
