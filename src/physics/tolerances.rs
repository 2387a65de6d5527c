// Every threshold of the accuracy contract and of the solvers' branching, named once (as
// statrs' `prec.rs`), so that the solver, the kernels, their CPU mirror, the cross-check, the
// tests and the benchmarks cannot drift apart. The WGSL kernels get theirs from the prelude
// that `kernel::prelude` generates (build.rs includes both files to validate the shaders with
// the same prelude). No inner doc comments: this file is `include!`d.

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

/// Nodes of the per-lambda bracket table (f64 solver and kernels).
pub const TABLE_NODES: usize = 14;

/// Terms of the kernels' Chebyshev fit of the state near the branch end.
pub const CHEB_TERMS: usize = 8;

/// The f32 kernel's iteration: |F| at the f32 noise level is done.
pub const F_NOISE: f32 = 8e-7;
/// The bracket closed to this relative width is done.
pub const BRACKET_CLOSED: f32 = 4e-7;
/// A step below this relative size (4 ulp) is taken along the last secant, not evaluated.
pub const SUB_ULP_STEP: f32 = 2.5e-7;
/// How far the search bracket reaches below the table's last node.
pub const BRACKET_BELOW: f32 = 120.0;
/// How far it reaches above the first node (zero-radius end).
pub const BRACKET_ABOVE: f32 = 60.0;
/// The iteration limit when no cap is given.
pub const MAX_ITER: u32 = 32;
