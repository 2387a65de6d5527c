//! Every threshold of the accuracy contract and of the solvers' branching, named once (as
//! statrs' `prec.rs`), so that the solver, the kernels' host side, the cross-check, the tests
//! and the benchmarks cannot drift apart.

/// The relative error of A the f32 GPU kernels are held to (see `NEAR_PULLOFF`).
pub const F32_TOLERANCE: f64 = 1e-5;

/// Under load control, states closer than this times |Pbar_c| to the pull-off are outside the
/// f32 contract (the kernel's residual cannot resolve the gap there); the cross-check reports
/// them apart.
pub const NEAR_PULLOFF: f64 = 1e-4;

/// Below this lambda the load is carried as Pbar + 2 (exact near the DMT value -2, where
/// Pbar = A^3 - lambda A^2 g cancels), in the f64 solver and in the kernels.
pub const SMALL_LAMBDA: f64 = 1.0;

/// Whether the load of this lambda is carried as Pbar + 2.
#[inline]
pub fn carries_load_plus_2(lambda: f64) -> bool {
    lambda < SMALL_LAMBDA
}

/// Threads per workgroup of every compute kernel (`@workgroup_size` in `shaders/*.wgsl`;
/// tests/shaders.rs reads it back from the WGSL through naga).
pub const WORKGROUP_SIZE: usize = 256;
