//! CPU mirrors of the WGSL kernels, one file per kernel.

pub mod md;
