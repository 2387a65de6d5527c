//! CPU mirrors of the WGSL kernels, one file per kernel.

pub mod classify;
pub mod ensemble64;
pub mod md;
pub mod polish64;
