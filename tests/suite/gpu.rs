//! The WGSL kernels on whatever adapter exists, against the reference tables and the f64 solver.
//! Without an adapter these tests skip with a printed reason; with TABOR_REQUIRE_GPU=1 (set by
//! .ci/run, which installs Mesa's software Vulkan driver) a missing adapter fails them.

use crate::common;
use common::*;
use tabor::engine::{Backend, Engine, Precision};
use tabor::gpu::Gpu;
use tabor::kernel::cpu::md::{solve_f32, KernelFlags};
use tabor::kernel::prepare::{prepare, prepare_all, split};
use tabor::solver::{solve_grid, Control, LambdaContext, Status};

/// The f32 kernels' contract: relative error of A away from pull-off.
const F32_TOL: f64 = tabor::physics::tolerances::F32_TOLERANCE;
/// On another adapter the kernel and its CPU mirror agree to this many ulps of A, with the same
/// statuses: its compiler may contract a multiply and an add into one fused operation (WGSL
/// allows it, the mirror does not), so the Newton corrections round differently and the stop
/// test can fall an iteration or more earlier or later; the counts are printed, not asserted
/// (lavapipe holds them exactly). Measured on an NVIDIA H200 (Vulkan): 39 ulp, 292 of 300
/// counts equal (at most 2 apart) on the reference points; 19 ulp, 82% equal (at most 4 apart)
/// on the started grid.
const MIRROR_ULPS: u64 = 64;

/// Mesa's lavapipe (the CI adapter) must give exactly the mirror's bits: its compiler does not
/// fuse, and the shaders are written so that its algebraic rewrites (factoring `a b + a c`,
/// simplifying `(1 + q) - 1`) find nothing to change.
fn bit_exact(g: &Gpu) -> bool {
    g.adapter.name.contains("llvmpipe")
}

/// Kernel against mirror over `n` states: `same` equal iteration counts, the largest difference
/// of the counts, and the largest difference of A in ulps.
struct Mirrored {
    n: usize,
    same: usize,
    iter_diff: u32,
    ulps: u64,
}

impl Mirrored {
    fn new() -> Self {
        Mirrored {
            n: 0,
            same: 0,
            iter_diff: 0,
            ulps: 0,
        }
    }
    fn add(&mut self, gpu_iters: u32, mirror_iters: u32, ulps: Option<u64>) {
        self.n += 1;
        self.same += (gpu_iters == mirror_iters) as usize;
        self.iter_diff = self.iter_diff.max(gpu_iters.abs_diff(mirror_iters));
        self.ulps = self.ulps.max(ulps.unwrap_or(0));
    }
    fn assert(&self, g: &Gpu, what: &str) {
        let Mirrored {
            n,
            same,
            iter_diff,
            ulps,
        } = *self;
        eprintln!(
            "{what}: kernel against its CPU mirror: {same} of {n} with the same iteration count (at most {iter_diff} apart), A within {ulps} ulp"
        );
        if bit_exact(g) {
            assert_eq!(same, n, "{what}: iteration counts differ from the mirror's");
            assert_eq!(ulps, 0, "{what}: A differs from the mirror's by {ulps} ulp");
        } else {
            assert!(ulps <= MIRROR_ULPS, "{what}: {ulps} ulp");
        }
    }
}

fn ulps(a: f32, b: f32) -> u64 {
    (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs()
}

fn gpu() -> Option<Gpu> {
    match Gpu::new(std::env::var("TABOR_ADAPTER").ok().as_deref()) {
        Ok(g) => {
            eprintln!(
                "GPU tests on {} ({}, {})",
                g.adapter.name, g.adapter.backend, g.adapter.device_type
            );
            Some(g)
        }
        Err(e) => {
            if std::env::var("TABOR_REQUIRE_GPU").is_ok_and(|v| v == "1") {
                panic!("TABOR_REQUIRE_GPU=1 but no GPU adapter: {e}");
            }
            eprintln!(
                "SKIPPED: no GPU adapter ({e}); set TABOR_REQUIRE_GPU=1 to make this a failure"
            );
            None
        }
    }
}

#[test]
fn own_functions_are_accurate_on_this_adapter() {
    let Some(g) = gpu() else { return };
    let xs: Vec<f32> = (0..20001)
        .map(|i| 10f32.powf(-9.0 + 19.0 * i as f32 / 20000.0))
        .collect();
    let out = g.probe(&xs).unwrap();
    let (mut e_at, mut e_d, mut e_exp, mut e_builtin) = (0f64, 0f64, 0f64, 0f64);
    for (x, o) in xs.iter().zip(&out) {
        let x = *x as f64;
        let (at, d) = tabor::physics::real::Real::atan_parts(x);
        e_at = e_at.max((o[0] as f64 / at - 1.0).abs());
        e_d = e_d.max((o[1] as f64 / d - 1.0).abs());
        e_builtin = e_builtin.max((o[3] as f64 / at - 1.0).abs());
        let xe = (-0.25 * x).max(-87.0);
        if xe > -80.0 {
            e_exp = e_exp.max((o[2] as f64 / xe.exp() - 1.0).abs());
        }
    }
    eprintln!("max rel. error: own atan {e_at:.2e}, own mu-atan {e_d:.2e}, own exp {e_exp:.2e}; built-in atan {e_builtin:.2e}");
    assert!(
        e_at < 5e-7 && e_d < 1e-6 && e_exp < 5e-7,
        "atan {e_at:e} mu-atan {e_d:e} exp {e_exp:e}"
    );
}

#[test]
fn reference_points_on_the_gpu() {
    let Some(g) = gpu() else { return };
    let rows = table("points.csv");
    let lambdas: Vec<f64> = rows.iter().map(|r| num(r, "lambda")).collect();
    let prepared = prepare_all(&lambdas);
    let pts: Vec<(u32, f32, f32)> = rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let (h, l) = split(num(r, "Pbar"));
            (i as u32, h, l)
        })
        .collect();
    let out = g
        .points(&prepared, &pts, Control::Load, KernelFlags::SHIPPED)
        .unwrap();
    let mut worst_far = 0f64;
    let mut mirrored = Mirrored::new();
    for (i, (r, o)) in rows.iter().zip(&out).enumerate() {
        assert_eq!(o.status(), Status::Ok, "id {i}");
        let e = rel(o.a as f64, num(r, "A"));
        let (load, pc) = (num(r, "Pbar"), num(r, "Pbar_pulloff_load"));
        assert!(e.is_finite());
        if load - pc >= 1e-4 * pc.abs() {
            assert!(e <= F32_TOL, "id {i}: {e:e}");
            worst_far = worst_far.max(e);
        } else {
            assert!(e < 1e-4, "id {i} near pull-off: {e:e}");
        }
        // The CPU mirror computes the same thing.
        let m = solve_f32(
            &prepared[i],
            pts[i].1,
            pts[i].2,
            Control::Load,
            false,
            KernelFlags::SHIPPED,
        );
        assert_eq!(o.status(), m.status(), "id {i}");
        mirrored.add(o.iterations(), m.iterations(), Some(ulps(o.a, m.a)));
    }
    eprintln!("reference points: max rel. error of A (gap >= 1e-4 |Pc|) {worst_far:.2e}");
    mirrored.assert(&g, "reference points");
}

#[test]
fn grid_512_agrees_with_cpu_on_every_status() {
    let Some(g) = gpu() else { return };
    let lambdas = logspace(-3.0, 3.0, 512);
    let mut loads = logspace(-3.0, 3.0, 512);
    loads[0] = -1.7; // rows below some pull-offs too
    loads[1] = -1.5;
    let engine = Engine::Gpu(Box::new(g));
    let gs = engine.solve_grid(&lambdas, &loads, Control::Load).unwrap();
    let cs = solve_grid(&lambdas, &loads, Control::Load);
    let mut worst = 0f64;
    for (i, (a, b)) in gs.iter().zip(&cs).enumerate() {
        assert_eq!(
            a.status, b.status,
            "point {i}: lambda {} load {}",
            b.lambda, b.load
        );
        if b.status == Status::Ok {
            let e = rel(a.a, b.a);
            let pc = LambdaContext::new(b.lambda).unwrap().load_pulloff.load;
            if b.load - pc >= 1e-4 * pc.abs() {
                worst = worst.max(e);
            }
        }
    }
    eprintln!("512x512 grid: statuses identical; max rel. error of A {worst:.2e}");
    assert!(worst <= F32_TOL);
}

/// The grid kernel with the dense starts against its CPU mirror: the same statuses, A as the
/// mirror's (see `Mirrored::assert`), and far fewer iterations than without: under half on
/// lavapipe (1.26 against 3.77), under 0.6 where multiply-adds fuse (1.82 on an H200).
#[test]
fn started_grid_matches_its_mirror() {
    use tabor::kernel::cpu::md::solve_f32_started;
    use tabor::kernel::prepare::prepare_ctx;
    use tabor::kernel::start::Starts;
    let Some(g) = gpu() else { return };
    let lambdas = logspace(-3.0, 3.0, 64);
    let mut loads = logspace(-3.0, 3.0, 400);
    loads[0] = -1.5; // below some pull-offs
    let ctx: Vec<Option<LambdaContext>> = lambdas
        .iter()
        .map(|&l| LambdaContext::new(l).ok())
        .collect();
    let started = tabor::solver::with_starts(&ctx, &loads, Control::Load);
    let prepared: Vec<_> = started.iter().flatten().map(prepare_ctx).collect();
    let starts = Starts::new(&started, &prepared);
    // Where the rows reach down to the pull-off the start would cost too many nodes.
    let with = starts.at.iter().filter(|a| a.is_some()).count();
    assert!(with * 2 >= lambdas.len(), "{with} starts");
    let rows: Vec<(f32, f32)> = loads.iter().map(|&v| split(v)).collect();
    let f = KernelFlags::SHIPPED;
    let out = g
        .grid_started(&prepared, &starts, &rows, Control::Load, false, f)
        .unwrap();
    let plain = g.grid(&prepared, &rows, Control::Load, false, f).unwrap();
    let mut mirrored = Mirrored::new();
    let (mut iters, mut iters_plain) = (0u32, 0u32);
    for (i, (o, p)) in out.iter().zip(&plain).enumerate() {
        let (ix, (h, l)) = (i % lambdas.len(), rows[i / lambdas.len()]);
        let m = solve_f32_started(
            &prepared[ix],
            starts.block(ix),
            h,
            l,
            Control::Load,
            false,
            f,
        );
        assert_eq!(
            o.status(),
            m.status(),
            "lambda {}, load {}",
            lambdas[ix],
            loads[i / 64]
        );
        assert_eq!(o.status(), p.status());
        let ok = o.status() == Status::Ok;
        mirrored.add(o.iterations(), m.iterations(), ok.then(|| ulps(o.a, m.a)));
        iters += o.iterations();
        iters_plain += p.iterations();
    }
    let n = out.len() as f64;
    eprintln!(
        "started grid: {:.2} iterations a state, {:.2} without the start",
        iters as f64 / n,
        iters_plain as f64 / n
    );
    mirrored.assert(&g, "started grid");
    let share = if bit_exact(&g) { 0.5 } else { 0.6 };
    assert!((iters as f64) < share * iters_plain as f64);
}

#[test]
fn extreme_lambdas_and_loads() {
    let Some(g) = gpu() else { return };
    // lambda 1e-6..1e6, loads from 1e-8 above pull-off to 1e6: never NaN, never a failure;
    // lambda 1e-4..1e4 from 1e-4 |Pc| above pull-off: within F32_TOL.
    let lambdas = logspace(-6.0, 6.0, 97);
    let ctx: Vec<LambdaContext> = lambdas
        .iter()
        .map(|&l| LambdaContext::new(l).unwrap())
        .collect();
    let prepared: Vec<_> = lambdas.iter().map(|&l| prepare(l)).collect();
    let gaps = logspace(-8.0, 6.0, 57);
    let mut pts = Vec::new();
    let mut refs = Vec::new();
    for (i, c) in ctx.iter().enumerate() {
        for &gap in &gaps {
            let load = c.load_pulloff.load + gap;
            let (h, l) = split(load);
            pts.push((i as u32, h, l));
            refs.push((i, gap, c.solve_load(load)));
        }
    }
    let out = g
        .points(&prepared, &pts, Control::Load, KernelFlags::SHIPPED)
        .unwrap();
    let mut worst = 0f64;
    for (o, (i, gap, r)) in out.iter().zip(&refs) {
        let lambda = lambdas[*i];
        assert_eq!(o.status(), Status::Ok, "lambda {lambda} gap {gap}");
        assert!(
            o.a.is_finite() && o.a > 0.0 && o.other.is_finite() && o.m_minus_1.is_finite(),
            "lambda {lambda} gap {gap}: {o:?}"
        );
        let e = rel(o.a as f64, r.a);
        if (1e-4..=1e4).contains(&lambda) && *gap >= 1e-4 * ctx[*i].load_pulloff.load.abs() {
            assert!(e <= F32_TOL, "lambda {lambda} gap {gap}: {e:e}");
            worst = worst.max(e);
        }
    }
    eprintln!("extreme sweep: max rel. error of A {worst:.2e}");
}

#[test]
fn displacement_control_agrees_with_cpu() {
    let Some(g) = gpu() else { return };
    let lambdas = logspace(-3.0, 3.0, 64);
    let approaches: Vec<f64> = (0..64)
        .map(|k| -1.6 + 0.05 * k as f64)
        .chain(logspace(0.5, 3.0, 16))
        .collect();
    let engine = Engine::Gpu(Box::new(g));
    let gs = engine
        .solve_grid(&lambdas, &approaches, Control::Displacement)
        .unwrap();
    let cs = solve_grid(&lambdas, &approaches, Control::Displacement);
    let mut worst = 0f64;
    let mut mism = 0;
    for (a, b) in gs.iter().zip(&cs) {
        if a.status != b.status {
            mism += 1;
            continue;
        }
        if b.status == Status::Ok && b.a > 1e-3 {
            worst = worst.max(rel(a.a, b.a));
        }
    }
    eprintln!(
        "displacement control: {mism} status mismatches of {}, max rel. error of A {worst:.2e}",
        cs.len()
    );
    assert_eq!(mism, 0);
    assert!(worst <= F32_TOL, "{worst:e}");
}

/// The f32 contract under displacement control, up to the end of the branch on both sides of
/// lambda_D: every state within 1e-5 of the f64 solver, the same status everywhere (states the
/// kernel cannot resolve near the end are solved in f64 by the engine), and the reference
/// curves' Dbar reproduce their A.
#[test]
fn displacement_control_holds_its_contract_up_to_the_end() {
    let Some(g) = gpu() else { return };
    let engine = Engine::Gpu(Box::new(g));
    let mut points = Vec::new();
    for &l in &logspace(-3.0, 3.0, 41) {
        let c = LambdaContext::new(l).unwrap();
        let end = c.disp_pulloff().approach;
        for &r in &logspace(-10.0, 2.0, 49) {
            points.push((l, end + r * end.abs().max(1.0)));
        }
    }
    let gs = engine.solve_points(&points, Control::Displacement).unwrap();
    let cs = tabor::solver::solve_points(&points, Control::Displacement);
    let mut worst = 0f64;
    for ((p, a), b) in points.iter().zip(&gs).zip(&cs) {
        assert_eq!(a.status, b.status, "lambda {} approach {}", p.0, p.1);
        if b.status == Status::Ok && b.a > 0.0 {
            worst = worst.max(rel(a.a, b.a));
        }
    }
    eprintln!("displacement control near the end: max rel. error of A {worst:.2e}");
    assert!(worst <= F32_TOL, "{worst:e}");
    // The reference curves: the stable part under rigid grips.
    let rows: Vec<_> = table("curves.csv")
        .into_iter()
        .filter(|r| num(r, "disp_stable") == 1.0 && num(r, "A") > 0.0)
        .collect();
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (num(r, "lambda"), num(r, "Dbar")))
        .collect();
    let gs = engine.solve_points(&pts, Control::Displacement).unwrap();
    let mut worst = 0f64;
    for (r, s) in rows.iter().zip(&gs) {
        assert_eq!(s.status, Status::Ok, "{r:?}");
        worst = worst.max(rel(s.a, num(r, "A")));
    }
    eprintln!(
        "displacement control, {} reference curve points: max rel. error of A {worst:.2e}",
        rows.len()
    );
    assert!(worst <= F32_TOL, "{worst:e}");
}

#[test]
fn auto_backend_reports_its_choice() {
    if gpu().is_none() {
        return;
    }
    let software = gpu().unwrap().adapter.software;
    let (engine, line) = Engine::select(Backend::Auto, None).unwrap();
    // On a software adapter (lavapipe in CI) the exact CPU solver is faster, and auto says so;
    // on a hardware GPU auto takes the GPU.
    if software {
        assert_eq!(engine.name(), "cpu");
        assert!(line.contains("software one on the same cores"), "{line}");
    } else {
        assert_eq!(engine.name(), "gpu");
        assert!(line.contains("GPU"), "{line}");
    }
}

/// The GPU set to f64 (f32 kernel, then f64 Newton steps), where the adapter has SHADER_F64.
fn gpu_f64() -> Option<Engine> {
    let g = gpu()?;
    if !g.f64 {
        eprintln!("SKIPPED (f64): {} has no SHADER_F64", g.adapter.name);
        return None;
    }
    let mut e = Engine::Gpu(Box::new(g));
    e.set_precision(Precision::F64).unwrap();
    Some(e)
}

#[test]
fn f64_refinement_meets_the_f64_contract_on_reference_states() {
    let Some(engine) = gpu_f64() else { return };
    let rows = table("points.csv");
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (num(r, "lambda"), num(r, "Pbar")))
        .collect();
    let states = engine.solve_points(&pts, Control::Load).unwrap();
    let (mut worst, mut worst_far) = (0f64, 0f64);
    for (i, (r, s)) in rows.iter().zip(&states).enumerate() {
        assert_eq!(s.status, Status::Ok, "id {i}");
        let b = bound(num(r, "Pbar"), num(r, "Pbar_pulloff_load"));
        let e = rel(s.a, num(r, "A")).max(rel(s.m_minus_1, num(r, "m_minus_1")));
        assert!(e <= b, "id {i}: error {e:e}, bound {b:e}");
        worst = worst.max(e / b);
        if num(r, "Pbar") - num(r, "Pbar_pulloff_load") >= 1e-4 {
            worst_far = worst_far.max(rel(s.a, num(r, "A")));
        }
    }
    eprintln!(
        "f64 refinement, reference states: worst error/bound {worst:.2}; max rel. error of A {worst_far:.2e} at gap >= 1e-4"
    );
}

/// The f64 refinement on the GPU against its CPU mirror, from the same f32 states: the same
/// status, and on lavapipe the same step counts and bits; elsewhere mostly the same step count
/// (the stopping test sits at the rounding level, where a fused multiply-add may round
/// differently) and A within the f64 contract's bound.
#[test]
fn f64_refinement_matches_its_mirror() {
    use tabor::kernel::cpu::polish64::{point64, polish_f64};
    use tabor::kernel::prepare::prepare64;
    let Some(g) = gpu() else { return };
    if !g.f64 {
        eprintln!("SKIPPED: {} has no f64 shaders", g.adapter.name);
        return;
    }
    let rows = table("points.csv");
    let lambdas: Vec<f64> = rows.iter().map(|r| num(r, "lambda")).collect();
    let prepared = prepare_all(&lambdas);
    let ctx: Vec<LambdaContext> = lambdas
        .iter()
        .map(|&l| LambdaContext::new(l).unwrap())
        .collect();
    let l64: Vec<_> = ctx.iter().map(|c| prepare64(Some(c), c.lambda)).collect();
    let pts: Vec<(u32, f32, f32)> = rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let (h, l) = split(num(r, "Pbar"));
            (i as u32, h, l)
        })
        .collect();
    let out = g
        .points(&prepared, &pts, Control::Load, KernelFlags::SHIPPED)
        .unwrap();
    let idx: Vec<(u32, f64)> = rows
        .iter()
        .enumerate()
        .map(|(i, r)| (i as u32, num(r, "Pbar")))
        .collect();
    let gpu64 = g
        .polish_f64(&l64, &idx, &out, Control::Load, false, 0)
        .unwrap();
    let (mut worst, mut same_steps, mut ulps) = (0f64, 0usize, 0u64);
    for (i, ((o, r), (ci, v))) in out.iter().zip(&gpu64).zip(&idx).enumerate() {
        let m = polish_f64(
            &l64[*ci as usize],
            &point64(*ci, *v, o),
            Control::Load,
            false,
            0,
        );
        assert_eq!(r.status(), m.status(), "id {i}");
        same_steps += (r.steps() == m.steps()) as usize;
        // Near the pull-off A is ill-conditioned in the load: the two may differ within the
        // f64 contract's bound there, and agree to a few ulp elsewhere.
        let b = bound(num(&rows[i], "Pbar"), num(&rows[i], "Pbar_pulloff_load"));
        worst = worst.max(rel(r.a, m.a) / b);
        ulps = ulps.max((r.a.to_bits() as i64 - m.a.to_bits() as i64).unsigned_abs());
    }
    eprintln!(
        "f64 refinement against its CPU mirror: {same_steps} of {} with the same steps, A within {worst:.3} of the f64 bound",
        idx.len()
    );
    assert!(worst <= 1.0, "{worst}");
    if bit_exact(&g) {
        assert_eq!(
            same_steps,
            idx.len(),
            "step counts differ from the mirror's"
        );
        assert_eq!(ulps, 0, "A differs from the mirror's by {ulps} ulp");
    } else {
        assert!(same_steps * 10 >= idx.len() * 8, "{same_steps}");
    }
}

#[test]
fn f64_refinement_agrees_with_cpu_under_both_controls() {
    let Some(engine) = gpu_f64() else { return };
    let lambdas = logspace(-4.0, 4.0, 96);
    let loads: Vec<f64> = [-1.9, -1.6, -1.0, -0.5]
        .into_iter()
        .chain(logspace(-4.0, 4.0, 60))
        .collect();
    let approaches: Vec<f64> = (0..40).map(|k| -1.6 + 0.07 * k as f64).collect();
    for (control, values) in [(Control::Load, loads), (Control::Displacement, approaches)] {
        let gs = engine.solve_grid(&lambdas, &values, control).unwrap();
        let cs = solve_grid(&lambdas, &values, control);
        let mut worst = 0f64;
        for (g, c) in gs.iter().zip(&cs) {
            assert_eq!(
                g.status, c.status,
                "{control:?} lambda {} value {}",
                c.lambda, c.load
            );
            if c.status == Status::Ok && c.a > 1e-3 {
                worst = worst.max(rel(g.a, c.a));
            }
        }
        eprintln!("f64 refinement vs CPU, {control:?}: max rel. difference of A {worst:.2e}");
        assert!(worst < 1e-11, "{control:?}: {worst:e}");
    }
    // Distances above the pull-off, down to 1e-10: refined from the exact gap.
    let gaps = logspace(-10.0, 3.0, 40);
    let gs = engine.solve_grid_gaps(&lambdas, &gaps).unwrap();
    let cs = Engine::Cpu.solve_grid_gaps(&lambdas, &gaps).unwrap();
    let mut worst = 0f64;
    for (i, (g, c)) in gs.iter().zip(&cs).enumerate() {
        assert_eq!(g.status, c.status);
        assert_eq!(g.load, c.load);
        let b = 2.0 * bound(gaps[i / lambdas.len()], 0.0);
        let e = rel(g.a, c.a);
        assert!(
            e <= b,
            "lambda {} gap {}: {e:e}",
            c.lambda,
            gaps[i / lambdas.len()]
        );
        worst = worst.max(e / b);
    }
    eprintln!("f64 refinement vs CPU above pull-off: worst difference/bound {worst:.2}");
}

/// The command line on the GPU: f32 results carry the digits f32 supports, `--check 0` says no
/// check was made, and an adapter asked for by name that does not exist is an error, not a
/// silent fallback to the CPU.
#[test]
fn command_line_on_the_gpu() {
    if gpu().is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in.csv");
    std::fs::write(&input, "lambda,load\n1,0.5\n10,-1.4\n").unwrap();
    let tabor = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
            .args(args)
            .env_remove("TABOR_BACKEND")
            .output()
            .unwrap()
    };
    let o = tabor(&[
        "solve",
        "-i",
        input.to_str().unwrap(),
        "--backend",
        "gpu",
        "--check",
        "0",
    ]);
    let (out, err) = (
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    );
    assert!(o.status.success(), "{err}");
    assert!(err.contains("none made (0 points to check)"), "{err}");
    let row: Vec<&str> = out.lines().nth(1).unwrap().split(',').collect();
    // The given numbers keep 17 digits, the computed ones have 9.
    assert_eq!(row[1], "5.0000000000000000e-1");
    assert_eq!(row[2].split('e').next().unwrap().len(), 10, "{}", row[2]);
    let a: f64 = row[2].parse().unwrap();
    assert!(rel(a, 1.7289400402050878) < F32_TOL, "{a}");
    let o = tabor(&[
        "solve",
        "-i",
        input.to_str().unwrap(),
        "--backend",
        "gpu",
        "--format",
        "json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["metadata"]["precision"], "f32");
    assert_eq!(v["metadata"]["significant_digits"], 9);
    assert_eq!(v["metadata"]["cross_check"]["status_mismatches"], 0);
    let png = dir.path().join("m.png");
    let o = tabor(&[
        "map",
        "--nx",
        "4",
        "--ny",
        "4",
        "--adapter",
        "nosuchname",
        "--out",
        png.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("no adapter name contains \"nosuchname\""),
        "{err}"
    );
    assert!(!png.exists());
}

/// Results do not depend on how a run is split into dispatches, nor on other threads using the
/// same Gpu at the same time (each dispatch has its own parameters).
#[test]
fn chunked_and_concurrent_runs_give_the_same_results() {
    let Some(g) = gpu() else { return };
    let lambdas = logspace(-2.0, 2.0, 37);
    let prepared = prepare_all(&lambdas);
    let rows: Vec<(f32, f32)> = logspace(-3.0, 3.0, 53).iter().map(|&v| split(v)).collect();
    let whole = g
        .grid(&prepared, &rows, Control::Load, false, KernelFlags::SHIPPED)
        .unwrap();
    g.limit_dispatch(100); // 37 x 53 = 1961 points: 20 dispatches, the last one partial
    let chunked = g
        .grid(&prepared, &rows, Control::Load, false, KernelFlags::SHIPPED)
        .unwrap();
    assert_eq!(
        bytemuck::cast_slice::<_, u32>(&whole),
        bytemuck::cast_slice::<_, u32>(&chunked)
    );
    // Two threads, different controls and inputs, on one Gpu, many small dispatches each.
    let approaches: Vec<(f32, f32)> = (0..53).map(|k| split(-0.5 + 0.1 * k as f64)).collect();
    let disp_alone = g
        .grid(
            &prepared,
            &approaches,
            Control::Displacement,
            false,
            KernelFlags::SHIPPED,
        )
        .unwrap();
    let (a, b) = std::thread::scope(|s| {
        let ta = s.spawn(|| {
            (0..4)
                .map(|_| {
                    g.grid(&prepared, &rows, Control::Load, false, KernelFlags::SHIPPED)
                        .unwrap()
                })
                .collect::<Vec<_>>()
        });
        let tb = s.spawn(|| {
            (0..4)
                .map(|_| {
                    g.grid(
                        &prepared,
                        &approaches,
                        Control::Displacement,
                        false,
                        KernelFlags::SHIPPED,
                    )
                    .unwrap()
                })
                .collect::<Vec<_>>()
        });
        (ta.join().unwrap(), tb.join().unwrap())
    });
    g.limit_dispatch(0);
    for r in a {
        assert_eq!(
            bytemuck::cast_slice::<_, u32>(&r),
            bytemuck::cast_slice::<_, u32>(&whole)
        );
    }
    for r in b {
        assert_eq!(
            bytemuck::cast_slice::<_, u32>(&r),
            bytemuck::cast_slice::<_, u32>(&disp_alone)
        );
    }
}

/// The rough map with its summits' tables solved on the GPU (f32 kernel, then f64 steps) is the
/// CPU map: every region, and the pull-offs within 1e-12 of max(|P|, 1e-3 |Pbar_c|); the
/// tables' states agree with the f64 solver on the sample within its contract. The f32 tables
/// alone stay within their cross-check's error (1e-5 of A) in the pull-offs.
#[test]
fn rough_map_tables_on_the_gpu_are_the_cpu_tables() {
    use tabor::rough::map::{compute, compute_with, RoughMapSpec};
    let Some(engine) = gpu_f64() else { return };
    let spec = RoughMapSpec {
        lambda_min: 0.05,
        lambda_max: 50.0,
        nx: 12,
        sigma_min: 0.05,
        sigma_max: 5.0,
        ny: 6,
        tolerance: 0.05,
        press_sigmas: 3.0,
    };
    let cpu = compute(&spec, 0).unwrap();
    let gpu = compute_with(&spec, 0, &engine).unwrap();
    assert!(
        gpu.table_backend.starts_with("gpu f64"),
        "{}",
        gpu.table_backend
    );
    let check = gpu
        .table_check
        .as_ref()
        .expect("a GPU map checks its tables");
    assert!(
        check.checked > 500 && check.status_mismatches == 0,
        "{check}"
    );
    assert!(check.max_rel_err_a < 1e-12, "{check}");
    assert_eq!(cpu.regions, gpu.regions);
    for (i, (a, b)) in cpu.pulloff.iter().zip(&gpu.pulloff).enumerate() {
        let floor = 1e-3 * cpu.smooth_pulloff[i % spec.nx].abs();
        assert!(
            (a - b).abs() <= 1e-12 * a.abs().max(floor),
            "point {i}: cpu {a}, gpu {b}"
        );
    }
    let adapter = std::env::var("TABOR_ADAPTER").ok();
    let mut f32_engine = Engine::select(Backend::Gpu, adapter.as_deref()).unwrap().0;
    f32_engine.set_precision(Precision::F32).unwrap();
    let g32 = compute_with(&spec, 0, &f32_engine).unwrap();
    assert_eq!(g32.table_backend, "gpu f32");
    for (i, (a, b)) in cpu.pulloff.iter().zip(&g32.pulloff).enumerate() {
        let floor = 1e-3 * cpu.smooth_pulloff[i % spec.nx].abs();
        assert!(
            (a - b).abs() <= 1e-5 * a.abs().max(floor),
            "point {i}: cpu {a}, f32 {b}"
        );
    }
}

/// An explicit ensemble's summit tables solved on the GPU (f32 kernel, then f64 steps) give
/// the CPU tables' cycle: forces within 1e-12 of the largest, the same branch counts, and the
/// tables' states within the f64 contract on the sample.
#[test]
fn ensemble_tables_on_the_gpu_are_the_cpu_tables() {
    use tabor::physics::params::ForceRange;
    use tabor::rough::ensemble::{cycle_with, Asperity, Materials, SummitSolver};
    let Some(engine) = gpu_f64() else { return };
    let m = Materials {
        e_star_pa: 2.4e6,
        work_of_adhesion_j_m2: 0.044,
        range: ForceRange::LennardJones(0.3e-9),
    };
    let asp: Vec<Asperity> = (0..500)
        .map(|i| Asperity {
            height_m: ((i as f64 * 0.754878) % 1.0 - 0.5) * 0.4e-6,
            radius_m: 2e-6 * 10f64.powf((i as f64 * 0.618034) % 1.0),
        })
        .collect();
    let run =
        |e: &Engine| cycle_with(&asp, &m, -0.2e-6, None, 50, SummitSolver::Tables, e).unwrap();
    let (cpu, gpu) = (run(&Engine::Cpu), run(&engine));
    assert!(
        gpu.summit_solver.contains("gpu f64"),
        "{}",
        gpu.summit_solver
    );
    let check = gpu.table_check.as_ref().expect("GPU tables are checked");
    assert!(
        check.checked > 500 && check.status_mismatches == 0,
        "{check}"
    );
    assert!(check.max_rel_err_a < 1e-12, "{check}");
    let top = cpu.retract.force_n.iter().fold(0f64, |a, f| a.max(f.abs()));
    for (a, b) in [(&cpu.approach, &gpu.approach), (&cpu.retract, &gpu.retract)] {
        assert_eq!(a.contact_fraction, b.contact_fraction);
        for (x, y) in a.force_n.iter().zip(&b.force_n) {
            assert!((x - y).abs() <= 1e-12 * top, "cpu {x}, gpu {y}");
        }
    }
}

/// A map's bands share one preparation of their lambdas (kept by the Gpu); a grid of other
/// lambdas on the same engine is prepared anew: every run gives a fresh engine's states.
#[test]
fn grids_on_one_engine_reuse_only_their_own_preparation() {
    let Some(_) = gpu() else { return };
    let adapter = std::env::var("TABOR_ADAPTER").ok();
    let engine = || Engine::select(Backend::Gpu, adapter.as_deref()).unwrap().0;
    let loads = logspace(-2.0, 2.0, 40);
    let (l1, l2) = (logspace(-2.0, 2.0, 33), logspace(-1.7, 2.3, 33));
    let a = |s: Vec<tabor::solver::State>| s.iter().map(|s| s.a.to_bits()).collect::<Vec<_>>();
    let e = engine();
    let first = a(e.solve_grid(&l1, &loads, Control::Load).unwrap());
    let other = a(e.solve_grid(&l2, &loads, Control::Load).unwrap());
    let again = a(e.solve_grid(&l1, &loads, Control::Load).unwrap());
    let fresh = a(engine().solve_grid(&l2, &loads, Control::Load).unwrap());
    assert_eq!(first, again);
    assert_eq!(other, fresh);
    assert_ne!(first, other);
}

/// A map's classification on the device (`shaders/classify.wgsl`, f64) against its CPU mirror
/// on the kernel's own results: every byte on lavapipe (nearly every one where multiply-adds
/// fuse), the picked results bit for bit, over dispatches split within the grid. The mirror is
/// the host's classification of the same states (`map::mark`), loads a hair below -1.5 too.
#[test]
fn classified_grid_matches_its_mirror() {
    use tabor::kernel::cpu::classify::{mark, params};
    use tabor::kernel::start::Starts;
    let Some(g) = gpu() else { return };
    let lambdas = logspace(-4.0, 4.0, 37);
    let prepared = prepare_all(&lambdas);
    // Loads just below -1.5 round to -1.5 in f32: the JKR form's guard must see the f64 load.
    let loads: Vec<f64> = (0..61)
        .map(|k| -2.0 + 0.2 * k as f64)
        .chain(logspace(-3.0, 3.0, 40))
        .chain([-1.50000003, -1.5 - 1e-12, -1.5])
        .collect();
    let rows: Vec<(f32, f32)> = loads.iter().map(|&v| split(v)).collect();
    let (tol, nx, n) = (0.05, lambdas.len(), lambdas.len() * rows.len());
    let picks: Vec<usize> = (0..n).step_by(7).collect();
    let f = KernelFlags::SHIPPED;
    let plain = g.grid(&prepared, &rows, Control::Load, false, f).unwrap();
    g.limit_dispatch(1000); // 37 x 104 = 3848 points: 4 dispatches, the last one partial
    let c = g
        .grid_classified(
            &prepared,
            &Starts::default(),
            &rows,
            (&lambdas, &loads),
            tol,
            &picks,
        )
        .unwrap();
    g.limit_dispatch(0);
    assert_eq!(c.marks.len(), n);
    let picked: Vec<_> = picks.iter().map(|&i| plain[i]).collect();
    assert_eq!(
        bytemuck::cast_slice::<_, u32>(&c.picked),
        bytemuck::cast_slice::<_, u32>(&picked)
    );
    let p = params(tol);
    let (mut apart, mut host) = (0, 0);
    for (i, (&m, o)) in c.marks.iter().zip(&plain).enumerate() {
        let (ix, iy) = (i % nx, i / nx);
        let mirror = mark(o, lambdas[ix], loads[iy], &p);
        apart += (m != mirror) as usize;
        let s = tabor::engine::to_state(lambdas[ix], loads[iy], o, Control::Load);
        host += (mirror != tabor::map::mark(&s, tol)) as usize;
    }
    eprintln!("classified grid: {apart} of {n} bytes apart from the mirror");
    if bit_exact(&g) {
        assert_eq!(apart, 0);
    } else {
        assert!(apart * 1000 <= n, "{apart} of {n}");
    }
    assert_eq!(host, 0, "the mirror is not the host's classification");
    let regions: std::collections::BTreeSet<u8> = c.marks.iter().map(|m| m & 7).collect();
    assert_eq!(regions.into_iter().collect::<Vec<_>>(), [0, 1, 2, 3, 4, 5]);
}

/// A map classified on the device is the map of the same kernel's states classified on the
/// host: the same regions and thresholds, the same records on the contour grid (every third
/// point here), the same cross-check; the columns below the kernels' lambda domain (1e-8) are
/// solved on the CPU in both.
#[test]
fn a_map_classified_on_the_device_is_the_map_of_its_states() {
    use tabor::map::{compute_with, ComputeOptions, LoadAxis, MapSpec};
    let Some(g) = gpu() else { return };
    let engine = Engine::Gpu(Box::new(g));
    assert!(engine.classifies());
    let spec = MapSpec {
        lambda_min: 1e-9,
        lambda_max: 1e4,
        nx: 1700,
        load_axis: LoadAxis::Linear,
        load_min: -2.0,
        load_max: 10.0,
        ny: 45,
        tolerance: 0.05,
        strength_ratios: vec![],
    };
    let opts = |records| ComputeOptions {
        keep_exact: false,
        check: 300,
        records,
    };
    let host = compute_with(&spec, &engine, opts(true)).unwrap();
    let device = compute_with(&spec, &engine, opts(false)).unwrap();
    assert_eq!(device.points.stride, 3);
    // Loads a hair below -1.5 (f32 rounds them to it) and a log axis: the same regions.
    for s in [
        MapSpec {
            lambda_min: 1e-4,
            nx: 500,
            load_min: -1.50000003,
            ny: 20,
            ..spec.clone()
        },
        MapSpec {
            lambda_min: 1e-3,
            lambda_max: 1e3,
            nx: 900,
            load_axis: LoadAxis::Log,
            load_min: 1e-3,
            load_max: 1e3,
            ny: 300,
            ..spec.clone()
        },
    ] {
        let (h, d) = (
            compute_with(&s, &engine, opts(true)).unwrap(),
            compute_with(&s, &engine, opts(false)).unwrap(),
        );
        assert!(h.regions == d.regions, "{:?}", s.load_axis);
        assert_eq!(h.thresholds(), d.thresholds());
    }
    let apart = host
        .regions
        .iter()
        .zip(&device.regions)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(apart, 0, "{apart} regions apart");
    assert_eq!(host.thresholds(), device.thresholds());
    for iy in (0..spec.ny).step_by(3) {
        for ix in (0..spec.nx).step_by(3) {
            let i = iy * spec.nx + ix;
            let (a, b) = (host.drawn(i), device.drawn(i));
            assert_eq!(
                (a.a.to_bits(), a.status),
                (b.a.to_bits(), b.status),
                "{ix}, {iy}"
            );
        }
    }
    let (h, d) = (host.check.unwrap(), device.check.unwrap());
    assert_eq!((h.checked, h.max_rel_err_a), (d.checked, d.max_rel_err_a));
    assert_eq!(d.over_tolerance, 0);
}

/// An explicit ensemble's stepping on the device (`shaders/ensemble64.wgsl`) against its CPU
/// mirror, on made-up summits and tables whose graded v puts many contact states next to their
/// folds: the same sums (bit for bit on lavapipe) and the same states flagged for the host,
/// over several chunks of summits, for the whole cycle and for the retract alone.
#[test]
fn ensemble_stepping_matches_its_mirror() {
    use tabor::kernel::cpu::ensemble64::sums;
    use tabor::kernel::layout::SummitRec;
    let Some(engine) = gpu_f64() else { return };
    let g = engine.gpu_f64().expect("an f64 GPU");
    let mut seed = 12345u64;
    let mut rnd = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let (nodes_n, intervals) = (12usize, 20usize);
    let coefs: Vec<[f64; 4]> = (0..2 * nodes_n * intervals)
        .map(|_| [rnd() - 0.5, rnd() - 0.5, 0.1 * rnd(), 0.01 * rnd()])
        .collect();
    let nodes: Vec<[u32; 4]> = (0..nodes_n)
        .map(|j| {
            let (l, a) = (2 * j * intervals, (2 * j + 1) * intervals);
            [l, intervals, a, intervals].map(|x| x as u32)
        })
        .collect();
    let d_min = -1.2e-7;
    let recs: Vec<SummitRec> = (0..2500)
        .map(|i| {
            let height_m = (rnd() - 0.5) * 2e-7;
            let w0 = rnd() - 0.3;
            SummitRec {
                height_m,
                unit: 1e-9 * (1.0 + rnd()),
                force: 1e-6,
                radius: 1e-7,
                half_pi_lambda: 0.3 + rnd(),
                h0: 1.0 + rnd(),
                c_star: 0.4 * rnd(),
                c_end: 1.5,
                delta_in: -0.5 - rnd(),
                delta_out: -2.0 - rnd(),
                delta_nc: -3.0 - rnd(),
                delta_max: (height_m - d_min) / 1.5e-9,
                w: [w0, 0.6, 0.5 - w0, -0.1],
                first: (i % (nodes_n - 3)) as u32,
                has_nc: (i % 3 == 0) as u32,
            }
        })
        .collect();
    let seps: Vec<f64> = (0..37)
        .map(|k| -1.2e-7 + 2.4e-7 * k as f64 / 36.0)
        .collect();
    let b = g
        .summit_buffers(&recs, &coefs, &nodes, (0.9, 40.0, 0.5))
        .unwrap();
    for retract_only in [false, true] {
        let r = g.summit_sums(&b, &seps, retract_only).unwrap();
        assert!(r.params.chunks >= 2, "{:?}", r.params);
        let (want, mut flags) = sums(&recs, &coefs, &nodes, &r.params, &seps);
        let mut got_flags = r.flagged.clone();
        got_flags.sort_unstable();
        flags.sort_unstable();
        assert!(flags.len() > 100, "{} states flagged", flags.len());
        assert_eq!(got_flags, flags);
        let top = want.iter().flatten().fold(0f64, |a, x| a.max(x.abs()));
        for (k, (a, w)) in r.sums.iter().zip(&want).enumerate() {
            for q in 0..8 {
                if bit_exact(g) {
                    assert_eq!(a[q].to_bits(), w[q].to_bits(), "separation {k}, sum {q}");
                } else {
                    assert!(
                        (a[q] - w[q]).abs() <= 1e-12 * top,
                        "{k} {q}: {} {}",
                        a[q],
                        w[q]
                    );
                }
            }
            if retract_only {
                assert_eq!(&a[..4], &[0.0; 4]);
            }
        }
        let contacts: f64 = r.sums.iter().map(|s| s[6]).sum();
        eprintln!(
            "ensemble stepping: {} states flagged, {contacts} retract contact states interpolated",
            flags.len()
        );
        assert!(contacts > 1000.0);
    }
    // Every contact state next to its fold: more than the device keeps (65,536 here), which it
    // says (the ensemble then steps the summits on the CPU) rather than lose any.
    let all = g
        .summit_buffers(&recs, &coefs, &nodes, (1e9, 40.0, 0.5))
        .unwrap();
    match g.summit_sums(&all, &seps, false) {
        Err(tabor::gpu::GpuError::TooLarge(m)) => assert!(m.contains("next to their folds"), "{m}"),
        Err(e) => panic!("{e}"),
        Ok(r) => panic!("{} states flagged, none refused", r.flagged.len()),
    }
}

/// The tables' exact stretch next to each fold widened (v below 0.5, where the tables leave
/// the states to the exact solver): the device flags those states, the host solves them, and
/// the cycle is the CPU's with the same tables.
#[test]
fn ensemble_states_next_to_their_folds_are_solved_on_the_host() {
    use tabor::physics::params::{Contact, ForceRange};
    use tabor::rough::ensemble::{cycle_with_tables, Asperity, Materials};
    use tabor::rough::lambda_table::LambdaTables;
    let Some(engine) = gpu_f64() else { return };
    let m = Materials {
        e_star_pa: 2.4e6,
        work_of_adhesion_j_m2: 0.044,
        range: ForceRange::LennardJones(0.3e-9),
    };
    let asp: Vec<Asperity> = (0..300)
        .map(|i| Asperity {
            height_m: ((i as f64 * 0.754878) % 1.0 - 0.5) * 0.4e-6,
            radius_m: 2e-6 * 10f64.powf((i as f64 * 0.618034) % 1.0),
        })
        .collect();
    let d_min = -0.2e-6;
    let (mut lo, mut hi, mut deepest) = (f64::INFINITY, 0f64, f64::NEG_INFINITY);
    for a in &asp {
        let c = Contact::new(a.radius_m, m.e_star_pa, m.work_of_adhesion_j_m2, m.range).unwrap();
        (lo, hi) = (lo.min(c.lambda()), hi.max(c.lambda()));
        deepest = deepest.max((a.height_m - d_min) / c.approach_scale());
    }
    let tables = || {
        let mut t = LambdaTables::new(lo, hi, deepest, &Engine::Cpu).unwrap();
        t.exact_below = 0.5;
        t
    };
    let run = |e: &Engine| cycle_with_tables(&asp, &m, (d_min, None), 50, tables(), e).unwrap();
    let (cpu, gpu) = (run(&Engine::Cpu), run(&engine));
    assert!(
        gpu.summit_solver.contains("stepped on the gpu"),
        "{}",
        gpu.summit_solver
    );
    let top = cpu.retract.force_n.iter().fold(0f64, |a, f| a.max(f.abs()));
    for (a, b) in [(&cpu.approach, &gpu.approach), (&cpu.retract, &gpu.retract)] {
        assert_eq!(a.contact_fraction, b.contact_fraction);
        assert_eq!(a.noncontact_fraction, b.noncontact_fraction);
        for (x, y) in a.force_n.iter().zip(&b.force_n) {
            assert!((x - y).abs() <= 1e-12 * top, "cpu {x}, gpu {y}");
        }
        for (x, y) in a.real_contact_area_m2.iter().zip(&b.real_contact_area_m2) {
            assert!(
                (x - y).abs() <= 1e-12 * x.abs().max(1e-30),
                "cpu {x}, gpu {y}"
            );
        }
    }
    assert!((cpu.pulloff_force_n - gpu.pulloff_force_n).abs() <= 1e-12 * top);
}
