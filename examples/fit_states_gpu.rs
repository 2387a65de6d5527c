//! One evaluation round of a whole force map on the CPU and batched on a GPU with f64 shaders:
//! the force-map benchmark's curves (`bench/fit_map.sh`: 500 retract points a curve, a 40 N/m
//! cantilever, lambda 0.3..9.5 across the map) at their true parameters, every retract point's
//! state on its curve's path. CPU: `SpringPath::at` on all cores. GPU: the paths followed and
//! the points bracketed on the CPU (`fit::batch::pack`), the contact piece's Newton steps in
//! `shaders/fit_states.wgsl`. Each stage is timed (the least of the repeats) and the GPU's loads
//! are compared with the CPU's. `bench/fit_gpu.sh` runs it.
//!   cargo run --release --example fit_states_gpu -- [side: 64] [repeats: 5] [adapter name]
use rayon::prelude::*;
use std::time::Instant;
use tabor::fit::synthetic::map_curve;
use tabor::fit::{batch, units, Direction, Model, SpringPath};
use tabor::kernel::cpu::fit_states::fit_state;

/// The least wall time of `reps` runs of `f`, and its last result.
fn timed<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..reps.max(1) {
        let t = Instant::now();
        let v = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(v);
    }
    (best, out.unwrap())
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let side: usize = args.first().map_or(64, |s| s.parse().expect("side"));
    let reps: usize = args.get(1).map_or(5, |s| s.parse().expect("repeats"));
    let adapter = args.get(2).map(String::as_str);
    let (curves, points) = (side * side, 500);
    // Each curve's lambda, spring, depth and base displacements, as the synthetic curves have
    // them.
    let specs: Vec<(f64, f64, f64, Vec<f64>)> = (0..curves)
        .into_par_iter()
        .map(|i| {
            let s = map_curve(i, curves, points, 40.0, 2e-11);
            let u = units(&s.params, s.radius, s.spring);
            let path = SpringPath::of(Model::Md.law(s.params.lambda), u.kbar, s.depth);
            let reach = path.force_reach().min(0.0);
            let low = reach - (s.depth - reach) * 0.4 / 0.6;
            let ds = (0..points)
                .map(|k| low + (s.depth - low) * k as f64 / (points - 1) as f64)
                .collect();
            (s.params.lambda, u.kbar, s.depth, ds)
        })
        .collect();
    let deltas: Vec<Vec<f64>> = specs.iter().map(|s| s.3.clone()).collect();
    let (t_paths, mut paths) = timed(reps, || {
        specs
            .par_iter()
            .map(|&(l, k, depth, _)| SpringPath::of(Model::Md.law(l), k, depth))
            .collect::<Vec<SpringPath>>()
    });
    let (t_cpu, cpu) = timed(reps, || {
        paths
            .par_iter_mut()
            .zip(&deltas)
            .map(|(p, ds)| {
                ds.iter()
                    .map(|&d| p.at(d, Direction::Retract).load)
                    .collect::<Vec<f64>>()
            })
            .collect::<Vec<Vec<f64>>>()
    });
    let (t_pack, b) = timed(reps, || batch::pack(&mut paths, &deltas));
    let (t_mirror, mirror) = timed(reps, || {
        b.points
            .par_iter()
            .map(|p| fit_state(&b.curves[p.curve as usize], p))
            .collect::<Vec<_>>()
    });
    println!(
        "force map {side} x {side}: {} retract points at the true parameters, {} of them on a contact piece (batched); {} CPU threads",
        curves * points,
        b.points.len(),
        rayon::current_num_threads()
    );
    println!("CPU: paths {t_paths:.4} s, every point's state (SpringPath::at) {t_cpu:.4} s");
    println!(
        "CPU: the batch's brackets (fit::batch::pack) {t_pack:.4} s, the kernel's CPU mirror {t_mirror:.4} s"
    );
    let worst = |outs: &[tabor::kernel::layout::FitOut64]| {
        b.index
            .iter()
            .zip(outs)
            .map(|(&(c, i), o)| {
                let l = cpu[c as usize][i as usize];
                (o.load - l).abs() / l.abs().max(1.0)
            })
            .fold(0.0f64, f64::max)
    };
    let evals = mirror.iter().map(|o| o.iterations() as f64).sum::<f64>() / mirror.len() as f64;
    println!(
        "mirror: max |load - CPU's| / max(|load|, 1) {:.2e}, {} of {} converged, {evals:.2} curve points a state",
        worst(&mirror),
        mirror.iter().filter(|o| o.converged()).count(),
        mirror.len()
    );
    let gpu = match tabor::gpu::Gpu::new(adapter) {
        Ok(g) => g,
        Err(e) => {
            println!("GPU: none ({e}); the CPU figures above stand alone");
            return;
        }
    };
    let t = Instant::now();
    let first = gpu.fit_states(&b.curves, &b.points);
    let t_first = t.elapsed().as_secs_f64();
    if let Err(e) = first {
        println!("GPU {}: {e}", gpu.adapter.name);
        return;
    }
    let (t_gpu, out) = timed(reps, || gpu.fit_states(&b.curves, &b.points).unwrap());
    let same = out.iter().zip(&mirror).filter(|(g, m)| g == m).count();
    println!(
        "GPU {} ({}{}): fit_states {t_gpu:.4} s with upload and read-back (first call, pipeline built: {t_first:.4} s)",
        gpu.adapter.name,
        gpu.adapter.backend,
        if gpu.adapter.software { ", software" } else { "" }
    );
    println!(
        "GPU: max |load - CPU's| / max(|load|, 1) {:.2e}, {} of {} converged, {same} bit-identical to the mirror",
        worst(&out),
        out.iter().filter(|o| o.converged()).count(),
        out.len()
    );
    let (cpu_round, gpu_round) = (t_paths + t_cpu, t_paths + t_pack + t_gpu);
    println!(
        "one round: CPU {cpu_round:.4} s (paths and states), GPU batch {gpu_round:.4} s (paths, brackets, kernel; the points off the contact piece left out): {:.2}x",
        cpu_round / gpu_round
    );
}
