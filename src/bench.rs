//! `tabor bench`: every solver variant on one workload, timed in one run and measured against
//! the f64 reference, charted as throughput against error.

use crate::gpu::Gpu;
use crate::kernel::cpu::md::{solve_f32, KernelFlags};
use crate::kernel::layout::{GpuLambda, Lambda64, Out, Out64};
use crate::kernel::prepare::{prepare64, prepare_ctx, split};
use crate::physics::closed::{cos_radius, dmt_radius, hertz_radius, jkr_radius};
use crate::solver::{naive, Control, LambdaContext, Status};
use rayon::prelude::*;
use serde::Serialize;
use std::time::Instant;

/// The points of a benchmark: a grid of lambda 1e-4..1e4 by gaps above the load-controlled
/// pull-off (1e-6..1e3), plus the 300 reference states, each with its reference A.
pub struct Workload {
    /// The lambdas of the grid, then those of the reference states.
    pub lambdas: Vec<f64>,
    /// Each lambda's f64 solver.
    pub contexts: Vec<LambdaContext>,
    /// (lambda index, load, gap above pull-off (NaN: given by the load), reference A).
    pub points: Vec<(usize, f64, f64, f64)>,
}

const REFERENCE_POINTS: &str = include_str!("../data/points.csv");

impl Workload {
    /// A grid of `n_lambda` by `n_load` points plus the 300 reference states.
    pub fn new(n_lambda: usize, n_load: usize) -> Workload {
        let mut lambdas: Vec<f64> = crate::numeric::grid::axis(1e-4, 1e4, n_lambda, true);
        let grid_n = lambdas.len();
        let mut rdr = csv::Reader::from_reader(REFERENCE_POINTS.as_bytes());
        let table: Vec<(f64, f64, f64)> = rdr
            .records()
            .map(|r| {
                let r = r.expect("embedded table");
                (
                    r[2].parse().unwrap(),
                    r[3].parse().unwrap(),
                    r[4].parse().unwrap(),
                )
            })
            .collect();
        lambdas.extend(table.iter().map(|t| t.0));
        let contexts: Vec<LambdaContext> = lambdas
            .par_iter()
            .map(|&l| LambdaContext::new(l).expect("lambda in range"))
            .collect();
        let gaps = crate::numeric::grid::axis(1e-6, 1e3, n_load, true);
        let grid: Vec<(usize, f64)> = (0..grid_n)
            .flat_map(|i| gaps.iter().map(move |&g| (i, g)))
            .collect();
        let mut points: Vec<(usize, f64, f64, f64)> = grid
            .par_iter()
            .map(|&(i, g)| {
                let c = &contexts[i];
                let load = c.load_pulloff.load + g;
                (i, load, g, c.solve_load_gap(g, load).a)
            })
            .collect();
        // The reference states are given by their load (gap NaN): solved as a user's input is.
        for (k, t) in table.iter().enumerate() {
            points.push((grid_n + k, t.1, f64::NAN, t.2));
        }
        Workload {
            lambdas,
            contexts,
            points,
        }
    }
}

#[derive(Clone, Debug, Serialize, serde::Deserialize)]
/// One variant's speed and accuracy.
pub struct VariantResult {
    /// Its name (`gpu_f32`, `cpu_f64`, ...).
    pub name: String,
    /// What it is.
    pub description: String,
    /// Points solved.
    pub points: usize,
    /// Wall time (s).
    pub seconds: f64,
    /// Throughput.
    pub points_per_second: f64,
    /// The largest relative error of A against the reference.
    pub max_rel_err: f64,
    /// The median relative error of A.
    pub median_rel_err: f64,
    /// The 99th percentile of the relative error of A.
    pub p99_rel_err: f64,
    /// Max error over the points at least 1e-4 |Pbar_c| above pull-off (the f32 contract).
    pub max_rel_err_away: f64,
    /// No answer, NaN, a failed status, or an answer off by more than 50% (wrong branch).
    pub failures: usize,
    /// f64 solvers: curve evaluations per state, their tables included.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub evals_per_state: Option<f64>,
}

fn summarize(
    name: &str,
    description: &str,
    w: &Workload,
    seconds: f64,
    a: &[Option<f64>],
) -> VariantResult {
    let mut errs = Vec::with_capacity(a.len());
    let mut failures = 0;
    let mut away = 0f64;
    for (p, v) in w.points.iter().zip(a) {
        match v {
            Some(x) if x.is_finite() => {
                let e = ((x - p.3) / p.3).abs();
                if e > 0.5 {
                    failures += 1;
                } else {
                    errs.push(e);
                    let pc = w.contexts[p.0].load_pulloff.load;
                    if p.1 - pc >= crate::physics::tolerances::NEAR_PULLOFF * pc.abs() {
                        away = away.max(e);
                    }
                }
            }
            _ => failures += 1,
        }
    }
    errs.sort_by(|a, b| a.total_cmp(b));
    let q = |f: f64| {
        errs.get(((errs.len() as f64 - 1.0) * f).round() as usize)
            .copied()
            .unwrap_or(f64::NAN)
    };
    VariantResult {
        name: name.into(),
        description: description.into(),
        points: a.len(),
        seconds,
        points_per_second: a.len() as f64 / seconds,
        max_rel_err: errs.last().copied().unwrap_or(f64::NAN),
        median_rel_err: q(0.5),
        p99_rel_err: q(0.99),
        max_rel_err_away: away,
        failures,
        evals_per_state: None,
    }
}

fn f64_solve(w: &Workload, p: &(usize, f64, f64, f64)) -> f64 {
    f64_state(&w.contexts[p.0], p).a
}

fn f64_state(c: &LambdaContext, p: &(usize, f64, f64, f64)) -> crate::solver::State {
    if p.2.is_nan() {
        c.solve_load(p.1)
    } else {
        c.solve_load_gap(p.2, p.1)
    }
}

/// Curve evaluations per state of the solve without a dense start.
fn search_evals(w: &Workload) -> f64 {
    let n: u64 = w
        .points
        .par_iter()
        .map(|p| f64_state(&w.contexts[p.0], p).iterations as u64)
        .sum();
    n as f64 / w.points.len() as f64
}

fn out_a(o: &Out, capped: bool) -> Option<f64> {
    let ok = o.status() == Status::Ok || (capped && o.status() == Status::NotConverged);
    ok.then_some(o.a as f64)
}

/// Runs every variant; `progress` gets one line per finished variant.
pub fn run(
    w: &Workload,
    gpu: Option<&Gpu>,
    progress: &mut dyn FnMut(&VariantResult),
) -> Vec<VariantResult> {
    let mut results = Vec::new();
    {
        let mut push = |r: VariantResult| {
            progress(&r);
            results.push(r);
        };
        cpu_f64_variants(w, &mut push);
        let prepared: Vec<GpuLambda> = w.contexts.par_iter().map(prepare_ctx).collect();
        // Without a GPU, the iteration caps are traced on the mirror.
        mirror_variants(w, &prepared, gpu.is_none(), &mut push);
        if let Some(g) = gpu {
            gpu_variants(w, g, &prepared, &mut push);
        }
        reference_variants(w, &mut push);
    }
    results
}

/// The exact f64 solver on all threads and on one.
fn cpu_f64_variants(w: &Workload, push: &mut dyn FnMut(VariantResult)) {
    let pts = &w.points;
    let t = Instant::now();
    let a: Vec<Option<f64>> = pts.par_iter().map(|p| Some(f64_solve(w, p))).collect();
    let s = t.elapsed().as_secs_f64();
    let evals = search_evals(w);
    push(VariantResult {
        evals_per_state: Some(evals),
        ..summarize(
            "cpu-f64",
            &format!(
                "exact solver, f64, coarse table and Newton (bracketed secant where it fails), {} threads (the reference for the grid)",
                rayon::current_num_threads()
            ),
            w,
            s,
            &a,
        )
    });
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("thread pool");
    let t = Instant::now();
    let a: Vec<Option<f64>> = pool.install(|| pts.iter().map(|p| Some(f64_solve(w, p))).collect());
    push(VariantResult {
        evals_per_state: Some(evals),
        ..summarize(
            "cpu-f64-1t",
            "exact solver, f64, coarse table and Newton, 1 thread",
            w,
            t.elapsed().as_secs_f64(),
            &a,
        )
    });
    // The dense start over each lambda's loads (their range known, as solve_grid knows its
    // values), built inside the timing.
    let mut range = vec![(f64::INFINITY, f64::NEG_INFINITY, 0usize); w.contexts.len()];
    for p in pts {
        let r = &mut range[p.0];
        *r = (r.0.min(p.1), r.1.max(p.1), r.2 + 1);
    }
    let t = Instant::now();
    let started: Vec<LambdaContext> = w
        .contexts
        .par_iter()
        .zip(&range)
        .map(|(c, &(lo, hi, n))| {
            let mut c = c.clone();
            if n >= crate::solver::context::START_MIN_STATES {
                c.add_start(lo, hi, n);
            }
            c
        })
        .collect();
    let states: Vec<crate::solver::State> = pts
        .par_iter()
        .map(|p| f64_state(&started[p.0], p))
        .collect();
    let s = t.elapsed().as_secs_f64();
    let nodes: usize = started
        .iter()
        .map(|c| c.start.as_ref().map_or(0, |s| s.nodes()))
        .sum();
    let evals: u64 = states.iter().map(|s| s.iterations as u64).sum();
    let a: Vec<Option<f64>> = states.iter().map(|s| Some(s.a)).collect();
    push(VariantResult {
        evals_per_state: Some((evals + nodes as u64) as f64 / pts.len() as f64),
        ..summarize(
            "cpu-f64-start",
            &format!(
                "exact solver, f64, dense start and one Newton correction, {} threads (tables timed)",
                rayon::current_num_threads()
            ),
            w,
            s,
            &a,
        )
    });
}

/// The kernels' f32 arithmetic on the CPU (the mirror), shipped and naive, and with iteration
/// caps when `trace_caps`.
fn mirror_variants(
    w: &Workload,
    prepared: &[GpuLambda],
    trace_caps: bool,
    push: &mut dyn FnMut(VariantResult),
) {
    let pts = &w.points;
    // The kernel's f32 arithmetic on the CPU (the mirror), all threads; `capped` counts
    // not-converged answers from an iteration cap.
    let mirror = |flags: KernelFlags, capped: bool| -> (f64, Vec<Option<f64>>) {
        let t = Instant::now();
        let a = pts
            .par_iter()
            .map(|p| {
                let (h, l) = split(p.1);
                out_a(
                    &solve_f32(&prepared[p.0], h, l, Control::Load, false, flags),
                    capped,
                )
            })
            .collect();
        (t.elapsed().as_secs_f64(), a)
    };
    for (name, flags, desc) in [
        (
            "cpu-f32",
            KernelFlags::SHIPPED,
            "the GPU kernel's f32 algorithm on the CPU (all threads)",
        ),
        (
            "cpu-f32-naive",
            KernelFlags::NAIVE,
            "f32, textbook formulas (no series, one f32 load)",
        ),
    ] {
        let (secs, a) = mirror(flags, false);
        push(summarize(name, desc, w, secs, &a));
    }
    // Without a GPU, the iteration caps are traced on the mirror.
    if trace_caps {
        for k in [1u32, 2, 3, 4, 6] {
            let (secs, a) = mirror(KernelFlags::capped(k), true);
            let desc = format!("the f32 algorithm stopped after {k} iteration(s)");
            push(summarize(&format!("cpu-f32-iter{k}"), &desc, w, secs, &a));
        }
    }
}

/// The WGSL kernels on the adapter: shipped, naive, capped, and refined in f64.
fn gpu_variants(
    w: &Workload,
    g: &Gpu,
    prepared: &[GpuLambda],
    push: &mut dyn FnMut(VariantResult),
) {
    let pts = &w.points;
    let gp: Vec<(u32, f32, f32)> = pts
        .iter()
        .map(|p| {
            let (h, l) = split(p.1);
            (p.0 as u32, h, l)
        })
        .collect();
    // Warm-up: each variant's pipeline is compiled on first use.
    for flags in [KernelFlags::SHIPPED, KernelFlags::NAIVE] {
        let _ = g.points(prepared, &gp[..gp.len().min(1024)], Control::Load, flags);
    }
    let mut variants: Vec<(String, KernelFlags, String)> = vec![
        (
            "gpu-f32".into(),
            KernelFlags::SHIPPED,
            format!("shipped WGSL kernel on {}", g.adapter.name),
        ),
        (
            "gpu-f32-naive".into(),
            KernelFlags::NAIVE,
            "WGSL kernel with the textbook formulas".into(),
        ),
    ];
    for k in [1u32, 2, 3, 4, 6] {
        variants.push((
            format!("gpu-f32-iter{k}"),
            KernelFlags::capped(k),
            format!("shipped kernel stopped after {k} iteration(s)"),
        ));
    }
    for (name, flags, desc) in variants {
        let t = Instant::now();
        match g.points(prepared, &gp, Control::Load, flags) {
            Ok(out) => {
                let s = t.elapsed().as_secs_f64();
                let a: Vec<Option<f64>> =
                    out.iter().map(|o| out_a(o, flags.max_iter != 0)).collect();
                push(summarize(&name, &desc, w, s, &a));
            }
            Err(e) => eprintln!("{name}: {e}"),
        }
    }
    // The f32 kernel's states refined by Newton steps in f64 on the GPU (SHADER_F64).
    if g.f64 {
        let l64: Vec<Lambda64> = w
            .contexts
            .iter()
            .map(|c| prepare64(Some(c), c.lambda))
            .collect();
        // Grid points are refined from their exact gap, the reference states from their load
        // (as the f64 solver is given them).
        let n_grid = pts.iter().filter(|p| p.2.is_finite()).count();
        let idx: Vec<(u32, f64)> = pts
            .iter()
            .map(|p| (p.0 as u32, if p.2.is_finite() { p.2 } else { p.1 }))
            .collect();
        let refine = |o: Vec<Out>| -> Result<(Vec<Out64>, Vec<Out>), crate::gpu::GpuError> {
            let (og, ot) = o.split_at(n_grid.min(o.len()));
            let (ig, it) = idx[..o.len()].split_at(og.len());
            let mut r = g.polish_f64(&l64, ig, og, Control::Load, true, 0)?;
            r.extend(g.polish_f64(&l64, it, ot, Control::Load, false, 0)?);
            Ok((r, o))
        };
        // Warm-up: both pipelines of the refinement.
        let _ = g
            .points(prepared, &gp[..16], Control::Load, KernelFlags::SHIPPED)
            .and_then(|o| {
                g.polish_f64(&l64, &idx[..16], &o, Control::Load, true, 0)?;
                g.polish_f64(&l64, &idx[..16], &o, Control::Load, false, 0)
            });
        let t = Instant::now();
        match g
            .points(prepared, &gp, Control::Load, KernelFlags::SHIPPED)
            .and_then(&refine)
        {
            Ok((r, o)) => {
                let s = t.elapsed().as_secs_f64();
                let a: Vec<Option<f64>> = r
                    .iter()
                    .zip(&o)
                    .map(|(r, o)| {
                        let s = crate::engine::to_state64(0.0, 0.0, o, r, Control::Load);
                        (s.status == Status::Ok).then_some(s.a)
                    })
                    .collect();
                let desc = "shipped kernel, then Newton steps in f64 on the GPU";
                push(summarize("gpu-f64", desc, w, s, &a));
            }
            Err(e) => eprintln!("gpu-f64: {e}"),
        }
    }
}

/// The public Python reference's naive f64 method and the closed forms as stand-ins for MD.
fn reference_variants(w: &Workload, push: &mut dyn FnMut(VariantResult)) {
    let pts = &w.points;
    // The naive f64 method of the public Python reference, on a subsample (it is slow).
    let step = (pts.len() / 4000).max(1);
    let sub = Workload {
        lambdas: w.lambdas.clone(),
        contexts: w.contexts.clone(),
        points: pts.iter().step_by(step).copied().collect(),
    };
    let t = Instant::now();
    let a: Vec<Option<f64>> = sub
        .points
        .par_iter()
        .map(|p| naive::solve_load(&sub.contexts[p.0], p.1))
        .collect();
    push(summarize("naive-f64-fixed-bracket", "f64 textbook formulas, Brent on m in [1, 1e12] (the public Python method), every n-th point", &sub, t.elapsed().as_secs_f64(), &a));

    // Closed forms as stand-ins for MD.
    let closed: [ClosedForm; 4] = [
        ("hertz", "Hertz contact radius", |_, p| hertz_radius(p)),
        ("dmt", "DMT contact radius", |_, p| dmt_radius(p)),
        ("jkr", "JKR contact radius", |_, p| jkr_radius(p)),
        (
            "cos",
            "Carpick-Ogletree-Salmeron transition fit",
            cos_radius,
        ),
    ];
    for (name, desc, f) in closed {
        let t = Instant::now();
        let a: Vec<Option<f64>> = pts.par_iter().map(|p| f(w.lambdas[p.0], p.1)).collect();
        push(summarize(name, desc, w, t.elapsed().as_secs_f64(), &a));
    }
}

/// The variants on the Pareto front: among those with no failure, none is both faster and more
/// accurate (max error).
pub fn pareto(results: &[VariantResult]) -> Vec<usize> {
    let ok: Vec<usize> = (0..results.len())
        .filter(|&i| results[i].max_rel_err.is_finite() && results[i].failures == 0)
        .collect();
    let mut front: Vec<usize> = ok
        .iter()
        .copied()
        .filter(|&i| {
            !ok.iter().any(|&j| {
                let (a, b) = (&results[j], &results[i]);
                j != i
                    && a.max_rel_err <= b.max_rel_err
                    && a.points_per_second >= b.points_per_second
                    && a.failures <= b.failures
                    && (a.max_rel_err < b.max_rel_err || a.points_per_second > b.points_per_second)
            })
        })
        .collect();
    front.sort_by(|&a, &b| results[a].max_rel_err.total_cmp(&results[b].max_rel_err));
    front
}

/// The results as a text table with its legend.
pub fn table(results: &[VariantResult]) -> String {
    let mut t = format!(
        "{:<26} {:>12} {:>10} {:>10} {:>10} {:>12} {:>9} {:>6}\n",
        "variant", "points/s", "max err", "p99 err", "median", "max (>=1e-4)", "failures", "evals"
    );
    for r in results {
        t += &format!(
            "{:<26} {:>12.3e} {:>10.2e} {:>10.2e} {:>10.2e} {:>12.2e} {:>9} {:>6}\n",
            r.name,
            r.points_per_second,
            r.max_rel_err,
            r.p99_rel_err,
            r.median_rel_err,
            r.max_rel_err_away,
            r.failures,
            r.evals_per_state
                .map_or(String::new(), |e| format!("{e:.2}"))
        );
    }
    t += "errors: relative error of A against the f64 solver (grid) and the 50-digit table (300 states);\n";
    t += "max (>=1e-4): over points at least 1e-4 |Pbar_c| above pull-off; failures: no answer, NaN, failed status or off by > 50%\n";
    t += "evals: curve evaluations per state of the f64 solvers, their tables included\n";
    t
}

/// One method's error over the atlas grid: relative error of A (NaN: failed).
pub struct AtlasMap {
    /// The file name (without extension).
    pub name: &'static str,
    /// The figure's title.
    pub title: String,
    /// Each grid point's relative error of A (NaN: failed).
    pub err: Vec<f64>,
}

/// A closed form as a stand-in for MD: name, description, A from (lambda, load) if defined.
type ClosedForm = (&'static str, &'static str, fn(f64, f64) -> Option<f64>);

/// The atlas: the lambda axis, the gap axis and one error map per method.
pub type Atlas = (Vec<f64>, Vec<f64>, Vec<AtlasMap>);

/// An answer's relative error against the reference radius, NaN where it failed (no answer,
/// not finite, or more than 50% off: another branch).
fn atlas_error(a: Option<f64>, reference: f64) -> f64 {
    match a {
        Some(x) if x.is_finite() => {
            let e = ((x - reference) / reference).abs();
            if e > 0.5 {
                f64::NAN
            } else {
                e
            }
        }
        _ => f64::NAN,
    }
}

/// The atlas maps of the closed forms used as stand-ins for MD. `reference[i]` is point i's
/// (load, radius); `rel` its relative error.
fn closed_form_maps(
    lambdas: &[f64],
    reference: &[(f64, f64)],
    rel: &(dyn Fn(Option<f64>, usize) -> f64 + Sync),
) -> Vec<AtlasMap> {
    let nx = lambdas.len();
    let closed: [ClosedForm; 3] = [
        ("jkr", "JKR closed form as a stand-in for MD", |_, p| {
            jkr_radius(p)
        }),
        ("dmt", "DMT closed form as a stand-in for MD", |_, p| {
            dmt_radius(p)
        }),
        (
            "cos",
            "Carpick-Ogletree-Salmeron fit as a stand-in for MD",
            cos_radius,
        ),
    ];
    closed
        .into_iter()
        .map(|(name, title, f)| AtlasMap {
            name,
            title: title.into(),
            err: (0..reference.len())
                .into_par_iter()
                .map(|i| rel(f(lambdas[i % nx], reference[i].0), i))
                .collect(),
        })
        .collect()
}

impl AtlasMap {
    /// Appends the largest error and the share of failed points to the title.
    fn summarise(&mut self) {
        let fails = self.err.iter().filter(|e| e.is_nan()).count();
        let max = self
            .err
            .iter()
            .filter(|e| !e.is_nan())
            .cloned()
            .fold(0.0, f64::max);
        self.title = format!(
            "{}: max error {:.1e}, {:.1}% failed",
            self.title,
            max,
            100.0 * fails as f64 / self.err.len() as f64
        );
    }
}

/// The failure atlas: lambda 1e-6..1e6 (nx, log) by the gap above pull-off 1e-8..1e6 (ny, log),
/// against the f64 solver, for the shipped f32 kernel (on the GPU if given, else its CPU
/// mirror), the naive f32 and f64 methods and the closed forms.
pub fn atlas(nx: usize, ny: usize, gpu: Option<&Gpu>) -> Result<Atlas, crate::gpu::GpuError> {
    let lambdas = crate::numeric::grid::axis(1e-6, 1e6, nx, true);
    let gaps = crate::numeric::grid::axis(1e-8, 1e6, ny, true);
    let ctx: Vec<LambdaContext> = lambdas
        .par_iter()
        .map(|&l| LambdaContext::new(l).expect("lambda in range"))
        .collect();
    let n = nx * ny;
    let at = |i: usize| (i % nx, i / nx);
    let reference: Vec<(f64, f64)> = (0..n)
        .into_par_iter()
        .map(|i| {
            let (ix, iy) = at(i);
            let c = &ctx[ix];
            let load = c.load_pulloff.load + gaps[iy];
            (load, c.solve_load_gap(gaps[iy], load).a)
        })
        .collect();
    let rel = |a: Option<f64>, i: usize| atlas_error(a, reference[i].1);
    let prepared: Vec<GpuLambda> = ctx.par_iter().map(prepare_ctx).collect();
    let mut maps = Vec::new();
    let f32_errs = |flags: KernelFlags| -> Result<Vec<f64>, crate::gpu::GpuError> {
        match gpu {
            Some(g) if flags == KernelFlags::SHIPPED => {
                let rows: Vec<(f32, f32)> = gaps.iter().map(|&v| split(v)).collect();
                let out = g.grid(&prepared, &rows, Control::Load, true, KernelFlags::SHIPPED)?;
                Ok(out
                    .iter()
                    .enumerate()
                    .map(|(i, o)| rel(out_a(o, false), i))
                    .collect())
            }
            _ => Ok((0..n)
                .into_par_iter()
                .map(|i| {
                    let (ix, iy) = at(i);
                    let (h, l) = split(reference[i].0);
                    let _ = iy;
                    rel(
                        out_a(
                            &solve_f32(&prepared[ix], h, l, Control::Load, false, flags),
                            false,
                        ),
                        i,
                    )
                })
                .collect()),
        }
    };
    let where_ = gpu.map_or("CPU mirror of the kernel".to_string(), |g| {
        format!("GPU: {}", g.adapter.name)
    });
    maps.push(AtlasMap {
        name: "shipped_f32",
        title: format!("Shipped f32 kernel ({where_})"),
        err: f32_errs(KernelFlags::SHIPPED)?,
    });
    maps.push(AtlasMap {
        name: "naive_f32",
        title: "Naive f32: textbook formulas, one f32 load".into(),
        err: f32_errs(KernelFlags::NAIVE)?,
    });
    let naive64: Vec<f64> = (0..n)
        .into_par_iter()
        .map(|i| rel(naive::solve_load(&ctx[at(i).0], reference[i].0), i))
        .collect();
    maps.push(AtlasMap {
        name: "naive_f64_fixed_bracket",
        title: "Naive f64: Brent on m in [1, 1e12] (the public Python method)".into(),
        err: naive64,
    });
    maps.extend(closed_form_maps(&lambdas, &reference, &rel));
    for m in &mut maps {
        m.summarise();
    }
    Ok((lambdas, gaps, maps))
}
