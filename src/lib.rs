//! tabor: adhesion maps for elastic spheres in contact.
//!
//! Layout: [`physics`] (equations), [`solver`] (f64 reference and f32 mirror), `gpu` (wgpu host
//! code for the WGSL kernels in `shaders/`), `map` (classification), `render` (figures) and the
//! command line in `src/cli`.

// `!(x <= tol)` and the like are deliberate: a NaN must land on the failure side.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod bench;
#[cfg(feature = "cli")]
pub mod cli;
pub mod cycle;
pub mod engine;
pub mod export;
pub mod gpu;
pub mod io;
pub mod kernel;
pub mod map;
pub mod physics;
pub mod profile;
pub mod progress;
pub mod render;
pub mod scene;
pub mod solver;
