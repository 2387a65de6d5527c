//! Throughput of the solvers on a lambda x load grid. Run: `cargo bench --bench grid`.
//! Not a test: it measures, it asserts nothing. Variants are timed in one run and compared as
//! ratios, since the machine is shared.

use std::time::Instant;
use tabor::solver::{solve_grid, Control};

fn logspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| 10f64.powf(a + (b - a) * i as f64 / (n - 1) as f64))
        .collect()
}

fn main() {
    let n = 1000;
    let lambdas = logspace(-3.0, 3.0, n);
    let loads = logspace(-3.0, 3.0, n);
    let _ = solve_grid(&lambdas[..10], &loads[..10], Control::Load); // warm-up
    let threads = rayon::current_num_threads();
    let t = Instant::now();
    let states = solve_grid(&lambdas, &loads, Control::Load);
    let all = t.elapsed().as_secs_f64();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let t = Instant::now();
    let _ = pool.install(|| solve_grid(&lambdas, &loads, Control::Load));
    let one = t.elapsed().as_secs_f64();
    let iters: u64 = states.iter().map(|s| s.iterations as u64).sum();
    let pts = (n * n) as f64;
    println!("cpu-f64 grid {n}x{n} (lambda 1e-3..1e3, load 1e-3..1e3, load control)");
    println!(
        "  all {threads} threads : {:>10.3e} solves/s ({all:.3} s)",
        pts / all
    );
    println!(
        "  1 thread          : {:>10.3e} solves/s ({one:.3} s)",
        pts / one
    );
    println!(
        "  speed-up          : {:.2}x; mean iterations {:.2}",
        one / all,
        iters as f64 / pts
    );
}
