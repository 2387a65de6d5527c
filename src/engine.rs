//! Where the work runs: the GPU kernels (f32) or the CPU reference (f64), chosen once, with a
//! one-line reason, and the cross-check of GPU results against the CPU.

use crate::gpu::Gpu;
/// What can go wrong on an engine (only the GPU backend fails).
pub use crate::gpu::GpuError as EngineError;
use crate::kernel::kernel_lambda;
use crate::kernel::layout::{KernelFlags, Lambda64, Out, Out64};
use crate::kernel::prepare::{prepare64, split};
use crate::kernel::start::Starts;
use crate::solver::{self, Control, LambdaContext, State, Status};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::HashMap;
use EngineError as GpuError;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
/// Which backend solves: chosen by the user, resolved by [`Engine::select`].
pub enum Backend {
    /// A hardware GPU, else the CPU (a software adapter only when named with `--adapter`).
    Auto,
    /// The WGSL kernels (f32) on a GPU adapter; an error if there is none.
    Gpu,
    /// The f64 reference solver on all CPU cores.
    Cpu,
}

/// The GPU's arithmetic: the f32 kernels, or their states refined by Newton steps in f64 on the
/// GPU (adapters with SHADER_F64). The CPU path is f64 either way.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Precision {
    /// The f32 kernels alone.
    F32,
    /// The f32 kernels' states refined by Newton steps in f64 on the GPU.
    F64,
}

/// The backend that solves: the f64 solver on the CPU, or a GPU device with its kernels.
pub enum Engine {
    /// The f64 solver on all CPU cores.
    Cpu,
    /// A GPU device with the WGSL kernels.
    Gpu(Box<Gpu>),
}

impl Engine {
    /// Chooses the engine; the string says which and why, in one line.
    pub fn select(backend: Backend, adapter: Option<&str>) -> Result<(Engine, String), GpuError> {
        let cpu_line = || {
            format!(
                "CPU f64 reference solver on {} threads",
                rayon::current_num_threads()
            )
        };
        let on_gpu = |g: Gpu, how: &str| {
            let line = format!(
                "backend: GPU f32 kernels on {} ({}, {}{how})",
                g.adapter.name,
                g.adapter.backend,
                kind(&g)
            );
            (Engine::Gpu(Box::new(g)), line)
        };
        match backend {
            Backend::Cpu => Ok((
                Engine::Cpu,
                format!("backend: {} (backend cpu)", cpu_line()),
            )),
            Backend::Gpu => Ok(on_gpu(Gpu::new(adapter)?, "")),
            // The adapter is looked at before a device is made: choosing the CPU makes no
            // device and compiles no shader.
            Backend::Auto => {
                let fallback = |e: GpuError| {
                    let line = format!("backend: {} (backend auto: {e})", cpu_line());
                    Ok((Engine::Cpu, line))
                };
                match crate::gpu::choose_summary(adapter) {
                    // An adapter asked for by name that is not there is an error, not a fallback.
                    Err(e @ GpuError::NoMatch { .. }) => Err(e),
                    Err(e) => fallback(e),
                    // A software adapter (lavapipe, SwiftShader) runs the shaders on the same
                    // cores as the CPU solver, which is exact and faster there (cargo bench
                    // --bench grid: 1.16e7 f64 states/s against 1.09e7 f32 on lavapipe, two
                    // cores). Named with --adapter, it is used as asked.
                    Ok(s) if s.software && adapter.is_none() => Ok((
                        Engine::Cpu,
                        format!(
                            "backend: {} (backend auto: the only adapter, {}, is a software one on the same cores, where the exact solver is faster; the gpu backend uses it)",
                            cpu_line(),
                            s.name
                        ),
                    )),
                    Ok(_) => match Gpu::new(adapter) {
                        Ok(g) => Ok(on_gpu(g, "; chosen by backend auto")),
                        Err(e @ GpuError::NoMatch { .. }) => Err(e),
                        Err(e) => fallback(e),
                    },
                }
            }
        }
    }

    /// The one place that dispatches on the backend.
    fn solver(&self) -> &dyn Solve {
        match self {
            Engine::Cpu => &CpuSolver,
            Engine::Gpu(g) => g.as_ref(),
        }
    }

    /// The backend's name in JSON (`cpu`, `gpu`).
    pub fn name(&self) -> &'static str {
        self.solver().name()
    }

    /// The arithmetic of the states it returns (`f64`, `f32`).
    pub fn precision(&self) -> &'static str {
        self.solver().precision()
    }

    /// Sets the GPU's arithmetic; f64 needs an adapter with SHADER_F64 (the CPU is f64 anyway).
    pub fn set_precision(&mut self, p: Precision) -> Result<(), GpuError> {
        if let Engine::Gpu(g) = self {
            if p == Precision::F64 && !g.f64 {
                return Err(GpuError::NoF64(g.adapter.name.clone()));
            }
            g.refine_f64 = p == Precision::F64;
        }
        Ok(())
    }

    /// The GPU adapter, if the engine has one.
    pub fn adapter(&self) -> Option<&crate::gpu::AdapterSummary> {
        self.solver().adapter()
    }

    /// Solves a list of (lambda, value) points.
    pub fn solve_points(
        &self,
        points: &[(f64, f64)],
        control: Control,
    ) -> Result<Vec<State>, GpuError> {
        self.solver().solve_points(points, control)
    }

    /// As [`Engine::solve_points`], and on a GPU `checks` of the states (spread over the
    /// points) re-solved by the CPU f64 solver: the one chunk step of every streaming front end.
    pub fn solve_points_checked(
        &self,
        points: &[(f64, f64)],
        control: Control,
        checks: usize,
    ) -> Result<(Vec<State>, Option<CheckReport>), GpuError> {
        let states = self.solve_points(points, control)?;
        let check = matches!(self, Engine::Gpu(_))
            .then(|| cross_check(points, &states, control, checks, GPU_TOLERANCE));
        Ok((states, check))
    }

    /// Solves the grid lambdas x gaps, load = Pbar_c(lambda) + gap (row-major, one row per gap):
    /// the tensile range down to the pull-off, with the gap exact however small.
    pub fn solve_grid_gaps(&self, lambdas: &[f64], gaps: &[f64]) -> Result<Vec<State>, GpuError> {
        self.solve_grid_gaps_with(&contexts(lambdas), lambdas, gaps)
    }

    /// As [`Engine::solve_grid_gaps`], with the per-lambda contexts already built.
    pub fn solve_grid_gaps_with(
        &self,
        ctx: &[Option<LambdaContext>],
        lambdas: &[f64],
        gaps: &[f64],
    ) -> Result<Vec<State>, GpuError> {
        self.solver().solve_grid_gaps_with(ctx, lambdas, gaps)
    }

    /// Solves the grid lambdas x values (row-major, one row per value).
    pub fn solve_grid(
        &self,
        lambdas: &[f64],
        values: &[f64],
        control: Control,
    ) -> Result<Vec<State>, GpuError> {
        self.solve_grid_with(&contexts(lambdas), lambdas, values, control)
    }

    /// As [`Engine::solve_grid`], with the per-lambda contexts already built.
    pub fn solve_grid_with(
        &self,
        ctx: &[Option<LambdaContext>],
        lambdas: &[f64],
        values: &[f64],
        control: Control,
    ) -> Result<Vec<State>, GpuError> {
        self.solver().solve_grid_with(ctx, lambdas, values, control)
    }

    /// The GPU where it runs f64 shaders (an explicit ensemble's stepping needs them).
    pub fn gpu_f64(&self) -> Option<&Gpu> {
        match self {
            Engine::Gpu(g) if g.f64 => Some(g),
            _ => None,
        }
    }

    /// Whether [`Engine::classify_grid`] runs here: a GPU with the f32 kernels alone (with the
    /// f64 refinement the states come back whole), f64 shaders (the classification is the
    /// host's, in f64) and the bindings it needs.
    pub fn classifies(&self) -> bool {
        matches!(self, Engine::Gpu(g) if g.classifies && !g.refine_f64)
    }

    /// Solves the grid lambdas x loads (row-major, one row per load) and classifies it on the
    /// device with tolerance `tol` (see `shaders/classify.wgsl`): a byte a point, and the whole
    /// states of the points `picks` (ascending). Only where [`Engine::classifies`].
    pub fn classify_grid(
        &self,
        ctx: &[Option<LambdaContext>],
        lambdas: &[f64],
        loads: &[f64],
        tol: f64,
        picks: &[usize],
    ) -> Result<ClassifiedGrid, GpuError> {
        match self {
            Engine::Gpu(g) if self.classifies() => {
                classify_on_gpu(g, ctx, lambdas, loads, tol, picks)
            }
            _ => Err(GpuError::Runtime(
                "classify_grid needs a GPU engine with the f32 kernels and f64 shaders".into(),
            )),
        }
    }
}

/// A grid classified on the device ([`Engine::classify_grid`]).
pub struct ClassifiedGrid {
    /// The kernel's byte of each point: the region in bits 0-2, the adequate models above.
    /// Points in `on_cpu` have no byte of the kernel's (their slot holds 6, failed).
    pub marks: Vec<u8>,
    /// The states of the picked points, in the order asked.
    pub picked: Vec<State>,
    /// Points outside the kernels' lambda domain, solved on the CPU in f64: (index, state).
    pub on_cpu: Vec<(usize, State)>,
}

fn classify_on_gpu(
    g: &Gpu,
    ctx: &[Option<LambdaContext>],
    lambdas: &[f64],
    loads: &[f64],
    tol: f64,
    picks: &[usize],
) -> Result<ClassifiedGrid, GpuError> {
    let t0 = std::time::Instant::now();
    let (rows, prepared, starts) = kernel_grid(g, ctx, lambdas, loads, Control::Load, false);
    let t_starts = t0.elapsed().as_secs_f64();
    let c = g.grid_classified(&prepared, &starts, &rows, (lambdas, loads), tol, picks)?;
    let nx = lambdas.len();
    // Lambdas outside the kernels' domain are solved on the CPU in f64, as `finish` does.
    let cpu = |i: usize| {
        let (l, p) = (lambdas[i % nx], loads[i / nx]);
        match &ctx[i % nx] {
            Some(c) => solver::solve_with(c, p, Control::Load),
            None => solver::solve_one(l, p, Control::Load),
        }
    };
    let outside: Vec<usize> = (0..nx).filter(|&ix| !kernel_lambda(lambdas[ix])).collect();
    let on_cpu = (0..loads.len())
        .flat_map(|iy| outside.iter().map(move |&ix| iy * nx + ix))
        .collect::<Vec<_>>()
        .into_par_iter()
        .map(|i| (i, cpu(i)))
        .collect();
    let picked = picks
        .par_iter()
        .zip(&c.picked)
        .map(|(&i, o)| match kernel_lambda(lambdas[i % nx]) {
            true => to_state(lambdas[i % nx], loads[i / nx], o, Control::Load),
            false => cpu(i),
        })
        .collect();
    if crate::gpu::device::trace() {
        eprintln!(
            "gpu trace: grid classified, {} points: starts and contexts {t_starts:.4} s, all {:.4} s",
            c.marks.len(),
            t0.elapsed().as_secs_f64()
        );
    }
    Ok(ClassifiedGrid {
        marks: c.marks,
        picked,
        on_cpu,
    })
}

/// What a backend does; [`Engine`] dispatches to one of its two implementations.
trait Solve {
    fn name(&self) -> &'static str;
    fn precision(&self) -> &'static str;
    fn adapter(&self) -> Option<&crate::gpu::AdapterSummary>;
    fn solve_points(&self, points: &[(f64, f64)], control: Control)
        -> Result<Vec<State>, GpuError>;
    fn solve_grid_gaps_with(
        &self,
        ctx: &[Option<LambdaContext>],
        lambdas: &[f64],
        gaps: &[f64],
    ) -> Result<Vec<State>, GpuError>;
    fn solve_grid_with(
        &self,
        ctx: &[Option<LambdaContext>],
        lambdas: &[f64],
        values: &[f64],
        control: Control,
    ) -> Result<Vec<State>, GpuError>;
}

/// The f64 reference solver on all cores.
struct CpuSolver;

impl Solve for CpuSolver {
    fn name(&self) -> &'static str {
        "cpu"
    }
    fn precision(&self) -> &'static str {
        "f64"
    }
    fn adapter(&self) -> Option<&crate::gpu::AdapterSummary> {
        None
    }
    fn solve_points(
        &self,
        points: &[(f64, f64)],
        control: Control,
    ) -> Result<Vec<State>, GpuError> {
        Ok(solver::solve_points(points, control))
    }
    fn solve_grid_gaps_with(
        &self,
        ctx: &[Option<LambdaContext>],
        lambdas: &[f64],
        gaps: &[f64],
    ) -> Result<Vec<State>, GpuError> {
        Ok(solver::solve_grid_gaps_with(ctx, lambdas, gaps))
    }
    fn solve_grid_with(
        &self,
        ctx: &[Option<LambdaContext>],
        lambdas: &[f64],
        values: &[f64],
        control: Control,
    ) -> Result<Vec<State>, GpuError> {
        Ok(solver::solve_grid_with(ctx, lambdas, values, control))
    }
}

/// The f32 WGSL kernels (and the f64 refinement) on an adapter.
impl Solve for Gpu {
    fn name(&self) -> &'static str {
        "gpu"
    }
    fn precision(&self) -> &'static str {
        if self.refine_f64 {
            "f64 (f32 kernel, then f64 Newton steps on the GPU)"
        } else {
            "f32"
        }
    }
    fn adapter(&self) -> Option<&crate::gpu::AdapterSummary> {
        Some(&self.adapter)
    }
    fn solve_points(
        &self,
        points: &[(f64, f64)],
        control: Control,
    ) -> Result<Vec<State>, GpuError> {
        let g = self;
        let mut index: HashMap<u64, u32> = HashMap::new();
        let mut lambdas = Vec::new();
        let pts: Vec<(u32, f32, f32)> = points
            .iter()
            .map(|&(l, v)| {
                let i = *index.entry(l.to_bits()).or_insert_with(|| {
                    lambdas.push(l);
                    (lambdas.len() - 1) as u32
                });
                let (h, lo) = split(v);
                (i, h, lo)
            })
            .collect();
        let ctx = contexts(&lambdas);
        let out = g.points(
            &prepare_contexts(&ctx, &lambdas),
            &pts,
            control,
            KernelFlags::SHIPPED,
        )?;
        let idx: Vec<(u32, f64)> = pts
            .iter()
            .zip(points)
            .map(|(p, &(_, v))| (p.0, v))
            .collect();
        finish(g, &ctx, &lambdas, &idx, &out, control, false)
    }
    fn solve_grid_gaps_with(
        &self,
        ctx: &[Option<LambdaContext>],
        lambdas: &[f64],
        gaps: &[f64],
    ) -> Result<Vec<State>, GpuError> {
        grid_on_gpu(self, ctx, lambdas, gaps, Control::Load, true)
    }
    fn solve_grid_with(
        &self,
        ctx: &[Option<LambdaContext>],
        lambdas: &[f64],
        values: &[f64],
        control: Control,
    ) -> Result<Vec<State>, GpuError> {
        grid_on_gpu(self, ctx, lambdas, values, control, false)
    }
}

/// The grid kernel's input for `lambdas x values`: the rows as hi/lo pairs, the lambdas'
/// preparation and their dense starts.
fn kernel_grid(
    g: &Gpu,
    ctx: &[Option<LambdaContext>],
    lambdas: &[f64],
    values: &[f64],
    control: Control,
    gaps: bool,
) -> (
    Vec<(f32, f32)>,
    std::sync::Arc<Vec<crate::kernel::layout::GpuLambda>>,
    Starts,
) {
    let rows = values.iter().map(|&v| split(v)).collect();
    // The dense starts, as on the CPU: the kernel then mostly stops at its first evaluation.
    // Only a software adapter wants them (see `wants_starts`).
    let started = match (wants_starts(g), gaps) {
        (false, _) => std::borrow::Cow::Borrowed(ctx),
        (true, true) => solver::with_gap_starts(ctx, values),
        (true, false) => solver::with_starts(ctx, values, control),
    };
    // Preparing a lambda does not use its start: the bands of a map share one preparation.
    let prepared = g.prepared_for(lambdas, || prepare_contexts(ctx, lambdas));
    let starts = Starts::new(&started, &prepared);
    (rows, prepared, starts)
}

/// The grid `lambdas x values` (row-major, one row per value) by the grid kernel: the values
/// are loads, approaches, or with `gaps` distances above the pull-off (load control).
fn grid_on_gpu(
    g: &Gpu,
    ctx: &[Option<LambdaContext>],
    lambdas: &[f64],
    values: &[f64],
    control: Control,
    gaps: bool,
) -> Result<Vec<State>, GpuError> {
    let t0 = std::time::Instant::now();
    let (rows, prepared, starts) = kernel_grid(g, ctx, lambdas, values, control, gaps);
    let t_starts = t0.elapsed().as_secs_f64();
    let out = g.grid_started(
        &prepared,
        &starts,
        &rows,
        control,
        gaps,
        KernelFlags::SHIPPED,
    )?;
    let t_gpu = t0.elapsed().as_secs_f64() - t_starts;
    let nx = lambdas.len();
    let idx: Vec<(u32, f64)> = (0..out.len())
        .map(|i| ((i % nx) as u32, values[i / nx]))
        .collect();
    let states = finish(g, ctx, lambdas, &idx, &out, control, gaps);
    if crate::gpu::device::trace() {
        eprintln!(
            "gpu trace: grid of {} states: starts and contexts {t_starts:.4} s, gpu {t_gpu:.4} s, states on the CPU {:.4} s",
            out.len(),
            t0.elapsed().as_secs_f64() - t_starts - t_gpu
        );
    }
    states
}

/// The per-lambda contexts of a lambda axis, in parallel (None for an invalid lambda).
pub fn contexts(lambdas: &[f64]) -> Vec<Option<LambdaContext>> {
    lambdas
        .par_iter()
        .map(|&l| LambdaContext::new(l).ok())
        .collect()
}

fn prepare_contexts(
    ctx: &[Option<LambdaContext>],
    lambdas: &[f64],
) -> Vec<crate::kernel::layout::GpuLambda> {
    ctx.par_iter()
        .zip(lambdas)
        .map(|(c, &l)| {
            c.as_ref().map_or_else(
                || crate::kernel::prepare::prepare(l),
                crate::kernel::prepare::prepare_ctx,
            )
        })
        .collect()
}

/// Whether a grid on this adapter gets the CPU-built dense starts. They halve the kernel's
/// iterations (3.77 to 1.82 a state on an H200), which pays on a software adapter sharing the
/// CPU's cores; a hardware GPU solves a million states in about a millisecond without them,
/// while building them per band costs the CPU more than that (README, Speed).
fn wants_starts(g: &Gpu) -> bool {
    g.adapter.software
}

fn kind(g: &Gpu) -> &'static str {
    if g.adapter.software {
        "software adapter"
    } else {
        "hardware"
    }
}

/// The states of kernel results for points `(lambda index, value)`, refined in f64 on the GPU
/// if the engine is set to f64. With `gaps` the values are distances above the pull-off: the
/// refinement works from the exact gap, the states carry the load Pbar_c + gap.
fn finish(
    g: &Gpu,
    ctx: &[Option<LambdaContext>],
    lambdas: &[f64],
    idx: &[(u32, f64)],
    out: &[Out],
    control: Control,
    gaps: bool,
) -> Result<Vec<State>, GpuError> {
    let value = |i: u32, v: f64| match (gaps, &ctx[i as usize]) {
        (false, _) => v,
        (true, Some(c)) => c.load_pulloff.load + v,
        (true, None) => f64::NAN,
    };
    // Displacement-controlled states near the end of their branch are beyond what the kernel
    // can certify: the CPU solves them in f64 (see `kernel_certifies`); so are the lambdas
    // outside the kernels' own domain (see `kernel_lambda`).
    let near_end = |i: u32, v: f64| -> Option<State> {
        let lambda = lambdas[i as usize];
        if !kernel_lambda(lambda) {
            return Some(match (&ctx[i as usize], gaps) {
                (Some(c), true) => c.solve_load_gap(v, c.load_pulloff.load + v),
                (Some(c), false) => solver::solve_with(c, v, control),
                (None, true) => State::failed(lambda, f64::NAN, f64::NAN, Status::InvalidInput),
                (None, false) => solver::solve_one(lambda, v, control),
            });
        }
        let c = ctx[i as usize].as_ref()?;
        (!gaps && !kernel_certifies(c, v, control)).then(|| c.solve_approach(v))
    };
    if !g.refine_f64 {
        return Ok(idx
            .par_iter()
            .zip(out)
            .map(|(&(i, v), o)| {
                near_end(i, v)
                    .unwrap_or_else(|| to_state(lambdas[i as usize], value(i, v), o, control))
            })
            .collect());
    }
    let l64: Vec<Lambda64> = ctx
        .iter()
        .zip(lambdas)
        .map(|(c, &l)| prepare64(c.as_ref(), l))
        .collect();
    let r = g.polish_f64(&l64, idx, out, control, gaps, 0)?;
    Ok(idx
        .par_iter()
        .zip(out)
        .zip(&r)
        .map(|((&(i, v), o), r)| {
            near_end(i, v)
                .unwrap_or_else(|| to_state64(lambdas[i as usize], value(i, v), o, r, control))
        })
        .collect())
}

/// Displacement control: approaches closer than this to the end of the branch, relative to
/// max(|Dbar_c|, 1), are solved on the CPU in f64. Closer to the end the f32 kernel cannot
/// resolve the gap (below lambda_D the contact radius goes like sqrt(Dbar - Dbar_c)): measured
/// with the kernel's CPU mirror over lambda 1e-4..1e4, its error of A reaches 3.7e-5 between
/// 1e-3 and 1e-2 of the end and it can even miss the contact closer in, while beyond 1e-2 it
/// stays below 4.4e-6 (`tests/suite/atlas.rs` pins this).
pub const DISP_F32_END_GAP: f64 = 1e-2;

/// Whether the f32 kernel's result for this state is held to its contract ([`GPU_TOLERANCE`]);
/// where not, the engine solves the state on the CPU in f64 instead.
pub fn kernel_certifies(ctx: &LambdaContext, value: f64, control: Control) -> bool {
    match control {
        Control::Load => true,
        Control::Displacement => {
            let end = ctx.disp_pulloff().approach;
            let gap = value - end;
            // Below the end there is no contact: the kernel says so exactly (the gap is exact).
            !(gap >= 0.0 && gap < DISP_F32_END_GAP * end.abs().max(1.0))
        }
    }
}

/// The relative error of A the f32 kernels are held to: away from the load-controlled pull-off
/// (closer than 1e-4 |Pbar_c| the cross-check reports points apart) and everywhere under
/// displacement control (with [`kernel_certifies`]).
pub const GPU_TOLERANCE: f64 = crate::physics::tolerances::F32_TOLERANCE;

/// A refined result as a State: the f64 numbers, or the kernel's where it took no step (no
/// contact, invalid input, the zero-radius end).
pub fn to_state64(lambda: f64, value: f64, o: &Out, r: &Out64, control: Control) -> State {
    if r.steps() == 0 {
        return to_state(lambda, value, o, control);
    }
    let status = r.status();
    let (load, approach) = match control {
        Control::Load => (value, r.other),
        Control::Displacement => (r.other, value),
    };
    State {
        lambda,
        load,
        approach,
        a: r.a,
        m_minus_1: r.m_minus_1,
        status,
        iterations: o.iterations() + r.steps(),
    }
}

/// A kernel result as a State; numbers the kernel could not compute become NaN.
pub fn to_state(lambda: f64, value: f64, o: &Out, control: Control) -> State {
    let status = o.status();
    let ok = status == Status::Ok || status == Status::NotConverged;
    let num = |x: f32| if ok { x as f64 } else { f64::NAN };
    let (load, approach) = match control {
        Control::Load => (value, num(o.other)),
        Control::Displacement => (num(o.other), value),
    };
    State {
        lambda,
        load,
        approach,
        a: num(o.a),
        m_minus_1: num(o.m_minus_1),
        status,
        iterations: o.iterations(),
    }
}

/// Agreement of GPU results with the f64 reference on a sample.
#[derive(Clone, Debug, Default, Serialize)]
pub struct CheckReport {
    /// Points re-solved by the f64 solver.
    pub checked: usize,
    /// The largest relative error of A the contract allows.
    pub tolerance: f64,
    /// The largest relative error of A.
    pub max_rel_err_a: f64,
    /// The median relative error of A.
    pub median_rel_err_a: f64,
    /// Points over the tolerance.
    pub over_tolerance: usize,
    /// Points closer than 1e-4 |Pbar_c| to the pull-off (load control), where the f32 contract
    /// does not apply: their largest error, reported apart.
    pub near_pulloff: usize,
    /// The largest relative error of A near the pull-off.
    pub near_pulloff_max_rel_err_a: f64,
    /// Points whose status differs from the f64 solver's.
    pub status_mismatches: usize,
    /// The errors behind the median, kept to at most `MEDIAN_SAMPLE` by thinning when reports of
    /// many chunks are merged.
    #[serde(skip)]
    errs: Vec<f64>,
}

const MEDIAN_SAMPLE: usize = 1 << 16;

impl CheckReport {
    /// No point checked yet.
    pub fn empty(tolerance: f64) -> CheckReport {
        CheckReport {
            tolerance,
            ..Default::default()
        }
    }

    /// Adds the report of another chunk of the same run.
    pub fn merge(&mut self, o: CheckReport) {
        self.checked += o.checked;
        self.max_rel_err_a = self.max_rel_err_a.max(o.max_rel_err_a);
        self.over_tolerance += o.over_tolerance;
        self.near_pulloff += o.near_pulloff;
        self.near_pulloff_max_rel_err_a = self
            .near_pulloff_max_rel_err_a
            .max(o.near_pulloff_max_rel_err_a);
        self.status_mismatches += o.status_mismatches;
        self.errs.extend(o.errs);
        self.errs.sort_by(|a, b| a.total_cmp(b));
        while self.errs.len() > MEDIAN_SAMPLE {
            // Every other one of the sorted errors: the median stays where it was.
            self.errs = self.errs.iter().step_by(2).copied().collect();
        }
        self.median_rel_err_a = self.errs.get(self.errs.len() / 2).copied().unwrap_or(0.0);
    }
}

impl std::fmt::Display for CheckReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.checked == 0 {
            return write!(
                f,
                "cross-check against CPU f64: none made (0 points to check)"
            );
        }
        write!(
            f,
            "cross-check against CPU f64 on {} points: max rel. error of A {:.2e}, median {:.2e}, {} over {:.0e}, {} status mismatches",
            self.checked, self.max_rel_err_a, self.median_rel_err_a, self.over_tolerance, self.tolerance, self.status_mismatches
        )?;
        if self.near_pulloff > 0 {
            write!(
                f,
                "; {} points within 1e-4 |Pc| of pull-off (max {:.2e}, not held to the tolerance)",
                self.near_pulloff, self.near_pulloff_max_rel_err_a
            )?;
        }
        Ok(())
    }
}

/// Re-solves `n` evenly spaced points (all if `n >= len`) on the CPU in f64 and compares.
pub fn cross_check(
    points: &[(f64, f64)],
    states: &[State],
    control: Control,
    n: usize,
    tolerance: f64,
) -> CheckReport {
    let len = points.len();
    let n = n.min(len);
    if n == 0 {
        return CheckReport::empty(tolerance);
    }
    let idx: Vec<usize> = (0..n).map(|k| k * len / n).collect();
    let sample: Vec<(f64, f64)> = idx.iter().map(|&i| points[i]).collect();
    let reference = solver::solve_points(&sample, control);
    let mut errs = Vec::with_capacity(n);
    let (mut mism, mut near, mut near_max) = (0, 0, 0f64);
    for (k, &i) in idx.iter().enumerate() {
        let (g, r) = (&states[i], &reference[k]);
        if g.status != r.status {
            mism += 1;
            continue;
        }
        if r.status == Status::Ok && r.a > 0.0 {
            let e = ((g.a - r.a) / r.a).abs();
            let close = control == Control::Load
                && solver::LambdaContext::new(r.lambda).is_ok_and(|c| {
                    r.load - c.load_pulloff.load
                        < crate::physics::tolerances::NEAR_PULLOFF * c.load_pulloff.load.abs()
                });
            if close {
                near += 1;
                near_max = near_max.max(e);
            } else {
                errs.push(e);
            }
        }
    }
    errs.sort_by(|a, b| a.total_cmp(b));
    let over = errs.iter().filter(|&&e| !(e <= tolerance)).count();
    CheckReport {
        checked: n,
        tolerance,
        max_rel_err_a: errs.last().copied().unwrap_or(0.0),
        median_rel_err_a: errs.get(errs.len() / 2).copied().unwrap_or(0.0),
        over_tolerance: over,
        near_pulloff: near,
        near_pulloff_max_rel_err_a: near_max,
        status_mismatches: mism,
        errs,
    }
}
