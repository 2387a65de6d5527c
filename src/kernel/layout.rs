//! The data the kernels read, byte for byte: each struct has a twin in `shaders/md.wgsl`
//! (checked by `tests/suite/shaders.rs`).

use bytemuck::{Pod, Zeroable};

pub use crate::physics::tolerances::{CHEB_TERMS, TABLE_NODES};

/// One stable branch (load control or displacement control) of one lambda, prepared in f64 on
/// the host. WGSL twin: `struct Branch`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct Branch {
    /// mu at the end of the branch (the jump-out); mu = mu_ref exp(dx).
    pub mu_ref: f32,
    /// The branch-end value of the residual's quantity (Pbar_c, Pbar_c + 2 or Dbar_min) as an
    /// unevaluated f32 pair hi + lo, so that value - end is exact near the end.
    pub end_hi: f32,
    /// The low part of the branch end.
    pub end_lo: f32,
    /// Below gap = s_max^2 the state comes from the Chebyshev fit, not the iteration.
    pub s_max: f32,
    /// dx(s) = s * sum c_k T_k(2 s / s_max - 1), s = sqrt(gap).
    pub cheb: [f32; CHEB_TERMS],
    /// ln(gap) at the table nodes, increasing.
    pub t: [f32; TABLE_NODES],
    /// dx = ln(mu / mu_ref) at the table nodes.
    pub dx: [f32; TABLE_NODES],
}

/// Everything the kernels need for one lambda. WGSL twin: `struct Lambda`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuLambda {
    /// The Maugis parameter.
    pub lambda: f32,
    /// 1: the load residual is written as Pbar + 2 (DMT side, lambda < 1).
    pub small: u32,
    /// 1: the displacement branch ends at A = 0 (lambda <= lambda_D): its table is linear in dx.
    pub disp_at_zero: u32,
    /// 1: this lambda is invalid; every point gets status invalid_input.
    pub invalid: u32,
    /// Pbar at the A -> 0 end of the curve (where a zero-radius displacement branch ends).
    pub end_load: f32,
    /// Word offset of this lambda's dense start in the grid kernel's input (0: none); see
    /// `kernel::start`.
    pub start_at: u32,
    /// Padding to the WGSL alignment.
    pub _pad: [u32; 2],
    /// The load-controlled branch.
    pub load: Branch,
    /// The displacement-controlled branch.
    pub disp: Branch,
}

/// Per-dispatch parameters. WGSL twin: `struct Params`. The variant (control, rows as gaps,
/// naive formulas) is a pipeline constant, not a parameter: see `Variant`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct Params {
    /// Grid columns (lambdas); unused by the point kernel.
    pub nx: u32,
    /// First point of this dispatch.
    pub offset: u32,
    /// Points in this dispatch.
    pub count: u32,
    /// An iteration cap for benchmarks (0 = iterate to convergence).
    pub max_iter: u32,
}

/// Per-dispatch parameters of the map's classification (`shaders/classify.wgsl`). WGSL twin:
/// `struct Params` there.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct ClassifyParams {
    /// (1 - tol)^3.
    pub cube_lo: f64,
    /// (1 + tol)^3.
    pub cube_hi: f64,
    /// The tolerance.
    pub tol: f64,
    /// Grid columns.
    pub nx: u32,
    /// The dispatch's first point.
    pub offset: u32,
    /// Points in this dispatch.
    pub count: u32,
    /// Results to copy out whole.
    pub picks: u32,
    /// Words of marks in the output; the picked results follow.
    pub marks_words: u32,
    /// Padding to 16 bytes.
    pub _pad: u32,
}

/// One summit of an explicit ensemble for `shaders/ensemble64.wgsl`: what its stepping needs,
/// prepared in f64 on the host (its own context gives the approaches where it jumps). WGSL twin:
/// `struct Summit` there.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct SummitRec {
    /// Height above the reference plane (m).
    pub height_m: f64,
    /// The approach unit (m): delta = (height - separation) / unit.
    pub unit: f64,
    /// The force unit pi w R (N).
    pub force: f64,
    /// The contact radius unit (m).
    pub radius: f64,
    /// pi lambda / 2 (the non-contact branch's load factor).
    pub half_pi_lambda: f64,
    /// The Dugdale range 2 / (pi lambda).
    pub h0: f64,
    /// C* = 8 lambda / (3 pi).
    pub c_star: f64,
    /// C at the contact branch's A -> 0 end.
    pub c_end: f64,
    /// Entry into contact on the approach.
    pub delta_in: f64,
    /// The contact branch's lowest approach (the fold).
    pub delta_out: f64,
    /// The stable non-contact branch's lowest approach (used where `has_nc` is 1).
    pub delta_nc: f64,
    /// The deepest approach of the cycle.
    pub delta_max: f64,
    /// The Lagrange weights of its four table nodes.
    pub w: [f64; 4],
    /// The first of its four table nodes.
    pub first: u32,
    /// 1: the summit has a stable non-contact branch.
    pub has_nc: u32,
}

/// An ensemble run's parameters (`shaders/ensemble64.wgsl`). WGSL twin: `struct Params` there.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct EnsembleParams {
    /// Below this graded v the contact state is solved exactly on the host.
    pub exact_below: f64,
    /// 1 / the tables' step in v.
    pub inv_h: f64,
    /// 2 / U_S of the grading v(u).
    pub two_over_us: f64,
    /// Summits.
    pub summits: u32,
    /// Separations.
    pub seps: u32,
    /// Summits per chunk (one partial sum per chunk and separation).
    pub chunk: u32,
    /// Chunks.
    pub chunks: u32,
    /// 1: the retract alone.
    pub retract_only: u32,
    /// Room for flagged states.
    pub flag_cap: u32,
}

/// The kernel variants that benchmarks compare with the shipped one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct KernelFlags {
    /// The textbook formulas (no series, one f32 load): the WGSL override `NAIVE`.
    pub naive: bool,
    /// A fixed iteration cap; 0 iterates to convergence (`Params.max_iter`).
    pub max_iter: u32,
}

impl KernelFlags {
    /// The shipped kernel.
    pub const SHIPPED: KernelFlags = KernelFlags {
        naive: false,
        max_iter: 0,
    };
    /// The textbook formulas.
    pub const NAIVE: KernelFlags = KernelFlags {
        naive: true,
        max_iter: 0,
    };
    /// The shipped kernel stopped after `n` iterations (the best iterate is returned).
    pub fn capped(n: u32) -> KernelFlags {
        KernelFlags {
            naive: false,
            max_iter: n,
        }
    }
}

/// The WGSL override `CONTROL` of a control.
pub fn control_code(c: crate::solver::Control) -> u32 {
    match c {
        crate::solver::Control::Load => 0,
        crate::solver::Control::Displacement => 1,
    }
}

/// One result. WGSL twin: `struct Out`. `code` = status | iterations << 8.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq, Default)]
pub struct Out {
    /// Contact radius A.
    pub a: f32,
    /// The approach under load control, the load under displacement control.
    pub other: f32,
    /// m - 1.
    pub m_minus_1: f32,
    /// Status in the low byte, iterations above.
    pub code: u32,
}

impl Out {
    /// The status.
    pub fn status(&self) -> crate::solver::Status {
        crate::solver::Status::from_code(self.code & 0xff)
    }
    /// The secant iterations used.
    pub fn iterations(&self) -> u32 {
        self.code >> 8
    }
}

/// Per-lambda data of the f64 refinement (`shaders/polish64.wgsl`). WGSL twin: `struct Lambda64`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct Lambda64 {
    /// The Maugis parameter.
    pub lambda: f64,
    /// Branch end of the load residual's quantity: Pbar_c, or Pbar_c + 2 if `small`.
    pub load_end: f64,
    /// Branch end of the approach: Dbar at the displacement-controlled jump-out.
    pub disp_end: f64,
    /// mu at the load-controlled pull-off (the stable branch has mu below it).
    pub mu_load: f64,
    /// mu at the displacement-controlled jump-out (interior branches only).
    pub mu_disp: f64,
    /// 1: the load residual is written as Pbar + 2 (DMT side).
    pub small: u32,
    /// 1: the displacement branch ends at A = 0.
    pub disp_at_zero: u32,
    /// 1: this lambda is invalid.
    pub invalid: u32,
    /// Padding to the WGSL alignment.
    pub _pad: u32,
}

/// One point for the f64 refinement: its value (load or approach), lambda index and the f32
/// kernel's result. WGSL twin: `struct Point64`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct Point64 {
    /// The load or approach.
    pub value: f64,
    /// Index of the point's lambda.
    pub ci: u32,
    /// The f32 kernel's code.
    pub code: u32,
    /// The f32 kernel's m - 1, the refinement's start.
    pub m_minus_1: f32,
    /// Padding to the WGSL alignment.
    pub _pad: u32,
}

/// One refined result. WGSL twin: `struct Out64`. `code` = status | Newton steps << 8.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq, Default)]
pub struct Out64 {
    /// Contact radius A.
    pub a: f64,
    /// The approach under load control, the load under displacement control.
    pub other: f64,
    /// m - 1.
    pub m_minus_1: f64,
    /// Status in the low byte, Newton steps above.
    pub code: u32,
    /// Padding to the WGSL alignment.
    pub _pad: u32,
}

impl Out64 {
    /// The status.
    pub fn status(&self) -> crate::solver::Status {
        crate::solver::Status::from_code(self.code & 0xff)
    }
    /// The Newton steps used.
    pub fn steps(&self) -> u32 {
        self.code >> 8
    }
}
