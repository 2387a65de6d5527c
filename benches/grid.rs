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
    // Without a dense start, contexts built inside the timing: the bracketed secant search
    // from the coarse table, and Newton from the same table (what a single state now takes).
    let unstarted = |lambdas: &[f64], loads: &[f64], newton: bool| -> Vec<State> {
        let ctx: Vec<LambdaContext> = lambdas
            .par_iter()
            .map(|&l| LambdaContext::new(l).unwrap())
            .collect();
        loads
            .par_iter()
            .flat_map_iter(|&p| {
                ctx.iter().map(move |c| {
                    let gap = p - c.load_pulloff.load;
                    if newton {
                        c.solve_load_gap(gap, p)
                    } else {
                        c.solve_load_search(gap, p)
                    }
                })
            })
            .collect()
    };
    let (search_all, search) = timed(|| unstarted(&lambdas, &loads, false));
    let (coarse_all, coarse) = timed(|| unstarted(&lambdas, &loads, true));
    // What solve_grid does: the dense start of each lambda over the loads asked for.
    let (cpu_all, states) = timed(|| solve_grid(&lambdas, &loads, Control::Load));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let (cpu_one, _) = timed(|| pool.install(|| solve_grid(&lambdas, &loads, Control::Load)));
    let (search_one, _) = timed(|| pool.install(|| unstarted(&lambdas, &loads, false)));
    let evals =
        |s: &[State]| s.iter().map(|s| s.iterations as u64).sum::<u64>() as f64 / (n * n) as f64;
    let nodes: usize = lambdas
        .par_iter()
        .map(|&l| {
            let mut c = LambdaContext::new(l).unwrap();
            c.add_start(loads[0], loads[n - 1], n);
            c.start.map(|s| s.nodes()).unwrap_or(0)
        })
        .sum();
    let one = states.iter().filter(|s| s.iterations == 1).count();
    let worst = |other: &[State]| {
        other
            .iter()
            .zip(&search)
            .map(|(a, b)| (a.a / b.a - 1.0).abs())
            .fold(0.0, f64::max)
    };
    println!("grid {n}x{n}: lambda 1e-3..1e3 x load 1e-3..1e3, load control, contexts included");
    println!(
        "  cpu f64 search, {threads} threads  : {}  ({:.2} curve evaluations per state)",
        rate(n * n, search_all),
        evals(&search)
    );
    println!(
        "  cpu f64 Newton, {threads} threads  : {}  = {:.2}x the search ({:.2} evaluations per state; A within {:.1e} of the search)",
        rate(n * n, coarse_all),
        search_all / coarse_all,
        evals(&coarse),
        worst(&coarse)
    );
    println!(
        "  cpu f64 start, {threads} threads   : {}  = {:.2}x the search ({:.2} evaluations per state + {:.2} for the tables; {:.1}% in one evaluation; A within {:.1e} of the search)",
        rate(n * n, cpu_all),
        search_all / cpu_all,
        evals(&states),
        nodes as f64 / (n * n) as f64,
        100.0 * one as f64 / (n * n) as f64,
        worst(&states)
    );
    println!("  cpu f64 search, 1 thread   : {}", rate(n * n, search_one));
    println!(
        "  cpu f64 start, 1 thread    : {}  = {:.2}x the search",
        rate(n * n, cpu_one),
        search_one / cpu_one
    );

    // Scattered states: every point its own lambda (a file of measurements), so every state
    // builds its own context (the pull-off search) and solves from the coarse table.
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut uniform = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let m = 1_000_000;
    let points: Vec<(f64, f64)> = (0..m)
        .map(|_| {
            (
                10f64.powf(-3.0 + 6.0 * uniform()),
                10f64.powf(-3.0 + 6.0 * uniform()),
            )
        })
        .collect();
    let (scattered, solved) = timed(|| tabor::solver::solve_points(&points, Control::Load));
    let (contexts, _) = timed(|| {
        points
            .par_iter()
            .map(|p| LambdaContext::new(p.0).map_or(0.0, |c| c.load_pulloff.x))
            .sum::<f64>()
    });
    let ok = solved
        .iter()
        .filter(|s| s.status == tabor::solver::Status::Ok)
        .count();
    println!(
        "scattered: {m} points, lambda and load log-uniform in 1e-3..1e3, each its own lambda ({ok} ok)"
    );
    println!(
        "  cpu f64, {threads} threads       : {}  (of which contexts alone {:.3} s: {:.2} us each on one thread)",
        rate(m, scattered),
        contexts,
        contexts * threads as f64 / m as f64 * 1e6
    );

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
    let (g1, gs) = timed(|| engine.solve_grid(&lambdas, &loads, Control::Load).unwrap());
    let worst32 = gs
        .iter()
        .zip(&states)
        .map(|(a, b)| (a.a / b.a - 1.0).abs())
        .fold(0.0, f64::max);
    println!(
        "  gpu f32 on {name}: {}  = {:.2}x the cpu (all threads); {:.2} iterations a state, A within {worst32:.1e} of the f64 solver",
        rate(n * n, g1),
        cpu_all / g1,
        evals(&gs)
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
