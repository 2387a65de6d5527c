//! GPU host code: adapter choice, the reusable compute context, chunked dispatches and readback.

pub mod layout;
pub mod prepare;
