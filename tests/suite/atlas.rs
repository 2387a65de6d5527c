//! Stability where methods fail, pinned from both sides: the shipped solvers hold their bounds
//! over the extreme ranges (a dense sweep), and the naive methods really do fail where
//! PHYSICS.md says they do, so a regression in either direction is caught.

use crate::common;
use common::logspace;
use tabor::kernel::cpu::md::{solve_f32, KernelFlags};
use tabor::kernel::prepare::{prepare, split};
use tabor::physics::closed::{dmt_radius, jkr_radius};
use tabor::solver::{naive, Control, LambdaContext, Status};

#[test]
fn shipped_f32_algorithm_holds_over_the_extreme_ranges() {
    // The kernel's arithmetic on the CPU (no GPU needed), lambda 1e-6..1e6, gaps 1e-8..1e6.
    let mut worst = 0f64;
    for &l in &logspace(-6.0, 6.0, 49) {
        let c = LambdaContext::new(l).unwrap();
        let g = prepare(l);
        for &gap in &logspace(-8.0, 6.0, 57) {
            let load = c.load_pulloff.load + gap;
            let (h, lo) = split(load);
            let o = solve_f32(&g, h, lo, Control::Load, false, KernelFlags::SHIPPED);
            assert_eq!(o.status(), Status::Ok, "lambda {l} gap {gap}");
            assert!(o.a.is_finite() && o.other.is_finite() && o.m_minus_1.is_finite());
            let e = (o.a as f64 / c.solve_load_gap(gap, load).a - 1.0).abs();
            assert!(e < 1e-3, "lambda {l} gap {gap}: {e:e}");
            if (1e-4..=1e4).contains(&l) && gap >= 1e-4 * c.load_pulloff.load.abs() {
                assert!(e <= 1e-5, "lambda {l} gap {gap}: {e:e}");
                worst = worst.max(e);
            }
        }
    }
    eprintln!("shipped f32 (CPU mirror): max rel. error of A {worst:.2e}");
}

#[test]
fn displacement_kernel_holds_its_contract_where_it_certifies() {
    // The kernel's arithmetic (CPU mirror) under rigid grips, lambda 1e-4..1e4 on both sides of
    // lambda_D, approaches from 1e-10 to 1e2 of max(|Dbar_c|, 1) above the end: wherever
    // `kernel_certifies` leaves a state to the kernel, its status is the f64 solver's and its A
    // within 1e-5. Closer to the end the kernel really is off (which is why the engine re-solves
    // those states in f64): pinned too, so that the cut cannot silently become too loose.
    let (mut worst, mut worst_inside) = (0f64, 0f64);
    for &l in &logspace(-4.0, 4.0, 81) {
        let c = LambdaContext::new(l).unwrap();
        let g = prepare(l);
        let end = c.disp_pulloff().approach;
        for &r in &logspace(-10.0, 2.0, 241) {
            let d = end + r * end.abs().max(1.0);
            let reference = c.solve_approach(d);
            assert_eq!(reference.status, Status::Ok);
            let (h, lo) = split(d);
            let o = solve_f32(
                &g,
                h,
                lo,
                Control::Displacement,
                false,
                KernelFlags::SHIPPED,
            );
            let e = if o.status() == Status::Ok {
                (o.a as f64 / reference.a - 1.0).abs()
            } else {
                f64::INFINITY
            };
            if tabor::engine::kernel_certifies(&c, d, Control::Displacement) {
                assert!(
                    e <= 1e-5,
                    "lambda {l} approach {d} ({r:e} above the end): {e:e}"
                );
                worst = worst.max(e);
            } else {
                worst_inside = worst_inside.max(e);
            }
        }
    }
    eprintln!("displacement control (CPU mirror): max rel. error of A {worst:.2e} where certified, {worst_inside:.2e} nearer the end");
    assert!(
        worst_inside > 1e-5,
        "the cut could be tightened: {worst_inside:e}"
    );
}

fn naive32_err(l: f64, gap: f64) -> f64 {
    let c = LambdaContext::new(l).unwrap();
    let load = c.load_pulloff.load + gap;
    let (h, lo) = split(load);
    let o = solve_f32(&prepare(l), h, lo, Control::Load, false, KernelFlags::NAIVE);
    (o.a as f64 / c.solve_load_gap(gap, load).a - 1.0).abs()
}

#[test]
fn naive_f32_fails_on_the_jkr_side() {
    // PHYSICS.md section 5: evaluated naively, f32 is off by 9% at lambda = 1000, or has no
    // answer (NaN: m - 1 rounds to 0).
    for gap in [1e-6, 1e-2, 1.0] {
        let e = naive32_err(1e3, gap);
        assert!(e.is_nan() || e > 1e-2, "gap {gap}: {e:e}");
    }
    // Beyond it there is no answer at all.
    assert!(naive32_err(1e4, 1.0).is_nan());
    // ... while at moderate lambda and load it is fine.
    assert!(naive32_err(1.0, 1.0) < 1e-5);
}

#[test]
fn naive_f64_with_a_fixed_bracket_loses_digits_then_answers() {
    let err = |l: f64, gap: f64| {
        let c = LambdaContext::new(l).unwrap();
        let load = c.load_pulloff.load + gap;
        naive::solve_load(&c, load).map(|a| (a / c.solve_load_gap(gap, load).a - 1.0).abs())
    };
    // Digits lost from lambda ~ 1e5 ...
    assert!(err(1e5, 1.0).unwrap() > 1e-8);
    // ... no answer or a wrong one by lambda ~ 1e6 ...
    assert!(err(1e6, 1.0).is_none_or(|e| e > 1e-2));
    assert!(err(3e5, 1e-2).is_none_or(|e| e > 1e-2));
    // ... and fine at lambda = 1.
    assert!(err(1.0, 1.0).unwrap() < 1e-10);
    // The shipped f64 solver at the same points: full precision.
    let c = LambdaContext::new(1e6).unwrap();
    let s = c.solve_load(c.load_pulloff.load + 1.0);
    let p = tabor::physics::md::curve_point(1e6, (s.m_minus_1 * (s.m_minus_1 + 2.0)).sqrt());
    assert!((p.load - (c.load_pulloff.load + 1.0)).abs() < 1e-12);
}

#[test]
fn closed_forms_leave_their_range_where_documented() {
    // PHYSICS.md section 6: JKR within 5% in A for all loads 0..1e3 only when lambda >= 1.88;
    // DMT only when lambda <= 0.085.
    let worst = |l: f64, f: fn(f64) -> Option<f64>| {
        let c = LambdaContext::new(l).unwrap();
        logspace(-3.0, 3.0, 200)
            .iter()
            .map(|&p| (f(p).unwrap() / c.solve_load(p).a - 1.0).abs())
            .fold(0.0, f64::max)
    };
    assert!(worst(1.95, jkr_radius) <= 0.05);
    assert!(worst(1.8, jkr_radius) > 0.05);
    assert!(worst(0.08, dmt_radius) <= 0.05);
    assert!(worst(0.09, dmt_radius) > 0.05);
}

/// The f64 refinement's arithmetic on the CPU (the mirror of polish64.wgsl), started from the
/// f32 kernel's mirror: the 300 reference states meet the f64 solver's own bound, without a GPU.
#[test]
fn f64_refinement_mirror_meets_the_f64_contract() {
    use tabor::kernel::cpu::polish64::{point64, polish_f64};
    use tabor::kernel::prepare::prepare64;
    let mut worst = 0f64;
    for r in common::table("points.csv") {
        let (l, load) = (common::num(&r, "lambda"), common::num(&r, "Pbar"));
        let c = LambdaContext::new(l).unwrap();
        let (h, lo) = split(load);
        let o = solve_f32(
            &prepare(l),
            h,
            lo,
            Control::Load,
            false,
            KernelFlags::SHIPPED,
        );
        let p = polish_f64(
            &prepare64(Some(&c), l),
            &point64(0, load, &o),
            Control::Load,
            false,
            0,
        );
        assert_eq!(p.status(), Status::Ok, "lambda {l} load {load}");
        let b = common::bound(load, common::num(&r, "Pbar_pulloff_load"));
        let e = common::rel(p.a, common::num(&r, "A"));
        assert!(e <= b, "lambda {l} load {load}: {e:e} > {b:e}");
        worst = worst.max(e / b);
    }
    eprintln!("f64 refinement (CPU mirror), reference states: worst error/bound {worst:.2}");
}
