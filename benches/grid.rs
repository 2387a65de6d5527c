//! Throughput of the solvers on a lambda x load grid. Run: `cargo bench --bench grid`.
//! Not a test: it measures, it asserts nothing. Variants are timed in one run and compared as
//! ratios, since the machine may be shared; each figure is the median of seven runs. GPU
//! timings include preparing the per-lambda data and reading every result back.

use rayon::prelude::*;
use std::time::Instant;
use tabor::engine::{Engine, Precision};
use tabor::gpu::Gpu;
use tabor::solver::{solve_grid, Control, LambdaContext, State};

fn logspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| 10f64.powf(a + (b - a) * i as f64 / (n - 1) as f64))
        .collect()
}

/// Median wall time of `REPS` runs (the first also pays for page faults; the machine may be
/// shared), and the last run's result.
fn timed<T>(mut f: impl FnMut() -> T) -> (f64, T) {
    const REPS: usize = 7;
    let mut secs = Vec::with_capacity(REPS);
    let mut out = None;
    for _ in 0..REPS {
        let t = Instant::now();
        out = Some(f());
        secs.push(t.elapsed().as_secs_f64());
    }
    secs.sort_by(f64::total_cmp);
    (secs[REPS / 2], out.unwrap())
}

fn rate(points: usize, secs: f64) -> String {
    format!("{:>10.3e} solves/s ({secs:.3} s)", points as f64 / secs)
}

fn main() {
    let n = 1000;
    let lambdas = logspace(-3.0, 3.0, n);
    let loads = logspace(-3.0, 3.0, n);
    let _ = solve_grid(&lambdas[..10], &loads[..10], Control::Load); // warm-up
    let threads = rayon::current_num_threads();
    // Before: the bracketed secant search from the coarse table (contexts without a start).
    let search = |lambdas: &[f64], loads: &[f64]| -> Vec<State> {
        let ctx: Vec<Option<LambdaContext>> = lambdas
            .par_iter()
            .map(|&l| LambdaContext::new(l).ok())
            .collect();
        loads
            .par_iter()
            .flat_map_iter(|&p| ctx.iter().map(move |c| c.as_ref().unwrap().solve_load(p)))
            .collect()
    };
    let (search_all, before) = timed(|| search(&lambdas, &loads));
    // After: what solve_grid does, the dense start of each lambda over the loads asked for.
    let (cpu_all, states) = timed(|| solve_grid(&lambdas, &loads, Control::Load));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let (cpu_one, _) = timed(|| pool.install(|| solve_grid(&lambdas, &loads, Control::Load)));
    let (search_one, _) = timed(|| pool.install(|| search(&lambdas, &loads)));
    // Curve evaluations: the search's iterations plus the final state; the start's Newton
    // evaluations plus its table nodes.
    let evals_before: u64 = before.iter().map(|s| s.iterations as u64 + 1).sum();
    let evals_after: u64 = states.iter().map(|s| s.iterations as u64).sum();
    let nodes: usize = lambdas
        .par_iter()
        .map(|&l| {
            let mut c = LambdaContext::new(l).unwrap();
            c.add_start(loads[0], loads[n - 1], n);
            c.start.map(|s| s.nodes()).unwrap_or(0)
        })
        .sum();
    let one = states.iter().filter(|s| s.iterations == 1).count();
    let worst = before
        .iter()
        .zip(&states)
        .map(|(a, b)| (a.a / b.a - 1.0).abs())
        .fold(0.0, f64::max);
    let per = |e: u64| e as f64 / (n * n) as f64;
    println!("grid {n}x{n}: lambda 1e-3..1e3 x load 1e-3..1e3, load control, contexts included");
    println!(
        "  cpu f64 search, {threads} threads  : {}  ({:.2} curve evaluations per state)",
        rate(n * n, search_all),
        per(evals_before)
    );
    println!("  cpu f64 search, 1 thread   : {}", rate(n * n, search_one));
    println!(
        "  cpu f64 start, {threads} threads   : {}  = {:.2}x the search ({:.2} evaluations per state + {:.2} for the tables; {:.1}% in one evaluation)",
        rate(n * n, cpu_all),
        search_all / cpu_all,
        per(evals_after),
        nodes as f64 / (n * n) as f64,
        100.0 * one as f64 / (n * n) as f64
    );
    println!(
        "  cpu f64 start, 1 thread    : {}  = {:.2}x the search",
        rate(n * n, cpu_one),
        search_one / cpu_one
    );
    println!("  largest difference of A between the two: {worst:.1e}");

    let gpu = match Gpu::new(std::env::var("TABOR_ADAPTER").ok().as_deref()) {
        Ok(g) => g,
        Err(e) => {
            println!("  gpu: skipped ({e})");
            return;
        }
    };
    let name = format!("{} ({})", gpu.adapter.name, gpu.adapter.device_type);
    let engine = Engine::Gpu(Box::new(gpu));
    let _ = engine
        .solve_grid(&lambdas[..64], &loads[..64], Control::Load)
        .unwrap(); // warm-up
    let (g1, _) = timed(|| engine.solve_grid(&lambdas, &loads, Control::Load).unwrap());
    println!(
        "  gpu f32 on {name}: {}  = {:.2}x the cpu (all threads)",
        rate(n * n, g1),
        cpu_all / g1
    );
    // The same grid with every state refined by Newton steps in f64 on the GPU.
    let mut engine = engine;
    if engine.set_precision(Precision::F64).is_ok() {
        let _ = engine
            .solve_grid(&lambdas[..64], &loads[..64], Control::Load)
            .unwrap(); // warm-up (the f64 pipeline)
        let (g64, _) = timed(|| engine.solve_grid(&lambdas, &loads, Control::Load).unwrap());
        println!(
            "  gpu f32 + f64 Newton  : {}  = {:.2}x the cpu f64 (all threads)",
            rate(n * n, g64),
            cpu_all / g64
        );
        engine.set_precision(Precision::F32).unwrap();
    } else {
        println!("  gpu f64: skipped (no SHADER_F64 on this adapter)");
    }
    let big = 4096;
    let (bl, bp) = (logspace(-3.0, 3.0, big), logspace(-3.0, 3.0, big));
    let t = Instant::now();
    let _ = engine.solve_grid(&bl, &bp, Control::Load).unwrap();
    let g16 = t.elapsed().as_secs_f64();
    println!(
        "  gpu f32, grid {big}x{big} (16.8M points): {}",
        rate(big * big, g16)
    );
}
