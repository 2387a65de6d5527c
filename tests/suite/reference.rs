//! The f64 reference solver against the 50-digit reference tables.

use crate::common;
use common::*;
use tabor::physics::md::LAMBDA_D;
use tabor::solver::{LambdaContext, Status};

#[test]
fn load_to_state_matches_reference_points() {
    reference_points(false);
}

/// The same states through the dense start (one curve evaluation and a Newton correction,
/// as grids and maps solve them), each with a start built over its own load.
#[test]
fn the_dense_start_matches_reference_points() {
    reference_points(true);
}

fn reference_points(start: bool) {
    let mut worst = (0.0f64, String::new());
    let mut one = 0;
    for row in table("points.csv") {
        let lambda = num(&row, "lambda");
        let load = num(&row, "Pbar");
        let mut ctx = LambdaContext::new(lambda).unwrap();
        if start {
            ctx.add_start(load, load, 1 << 20);
        }
        let s = ctx.solve_load(load);
        one += (s.iterations == 1) as usize;
        assert_eq!(s.status, Status::Ok, "id {}", row["id"]);
        let tol = bound(load, num(&row, "Pbar_pulloff_load"));
        let ea = rel(s.a, num(&row, "A"));
        let em = rel(s.m_minus_1, num(&row, "m_minus_1"));
        let d = num(&row, "Dbar");
        let ed = (s.approach - d).abs() / d.abs().max(1.0);
        let e = ea.max(em).max(ed);
        assert!(
            e <= tol,
            "id {} ({}) lambda {lambda} load {load}: A {ea:e} m-1 {em:e} D {ed:e} > {tol:e}",
            row["id"],
            row["category"]
        );
        if e / tol > worst.0 {
            worst = (e / tol, row["id"].clone());
        }
    }
    eprintln!(
        "worst error / bound = {:.3} (id {}); {one} states in one curve evaluation",
        worst.0, worst.1
    );
    if start {
        assert!(one > 150, "the start was used for only {one} states");
    }
}

#[test]
fn pulloff_matches_reference_under_both_controls() {
    for row in table("pulloff.csv") {
        let lambda = num(&row, "lambda");
        let ctx = LambdaContext::new(lambda).unwrap();
        let lp = ctx.load_pulloff;
        let el = rel(lp.load, num(&row, "Pbar_load"));
        let ea = rel(lp.a, num(&row, "A_load"));
        assert!(
            el <= PULLOFF_TOL && ea <= PULLOFF_TOL,
            "load control, lambda {lambda}: P {el:e} A {ea:e}"
        );
        let dp = ctx.disp_pulloff();
        let el = rel(dp.load, num(&row, "Pbar_disp"));
        let at_a0 = num(&row, "disp_at_A0") == 1.0;
        assert_eq!(dp.at_zero_radius(), at_a0, "lambda {lambda}");
        assert_eq!(at_a0, lambda <= LAMBDA_D);
        let ea = if at_a0 {
            dp.a
        } else {
            rel(dp.a, num(&row, "A_disp"))
        };
        assert!(
            el <= PULLOFF_TOL && ea <= PULLOFF_TOL,
            "displacement control, lambda {lambda}: P {el:e} A {ea:e}"
        );
        let ed = rel(dp.approach, num(&row, "Dbar_disp"));
        assert!(
            ed <= PULLOFF_TOL,
            "jump-out approach, lambda {lambda}: {ed:e}"
        );
        // The A -> 0 end of the curve.
        assert!(rel(ctx.end.load, num(&row, "Pbar_A0")) <= 1e-14);
        assert!(rel(ctx.end.approach, num(&row, "Dbar_A0")) <= 1e-14);
        assert!(rel(ctx.end.c, num(&row, "C_A0")) <= 1e-14);
    }
}

#[test]
fn curve_points_and_stability_flags_match_reference_curves() {
    use tabor::physics::md::curve_point;
    for row in table("curves.csv") {
        let lambda = num(&row, "lambda");
        let a_ref = num(&row, "A");
        if a_ref == 0.0 {
            continue;
        }
        let mm1 = num(&row, "m_minus_1");
        let mu = (mm1 * (mm1 + 2.0)).sqrt();
        let p = curve_point(lambda, mu);
        assert!(
            rel(p.a, a_ref) < 1e-13,
            "lambda {lambda} A {a_ref}: {}",
            p.a
        );
        let pr = num(&row, "Pbar");
        assert!((p.load - pr).abs() / pr.abs().max(1.0) < 1e-13);
        let dr = num(&row, "Dbar");
        assert!((p.approach - dr).abs() / dr.abs().max(1.0) < 1e-13);
        // Stable under load control iff dPbar/dA > 0 iff dPbar/dmu < 0 (A falls with mu).
        assert_eq!(
            p.dload_dmu < 0.0,
            num(&row, "load_stable") == 1.0,
            "lambda {lambda} A {a_ref}"
        );
        assert_eq!(
            p.dapproach_dmu < 0.0,
            num(&row, "disp_stable") == 1.0,
            "lambda {lambda} A {a_ref}"
        );
    }
}

/// Displacement control against an independent reference: the stable part of the reference
/// curves under rigid grips, solved from their Dbar. A is held to the f64 contract times the
/// condition number of A given Dbar, `|Dbar| / (A |dDbar/dA|)`, which grows without bound at
/// the jump-out (and like 1/A^2 at the zero-radius end below lambda_D).
#[test]
fn solve_approach_reproduces_the_reference_curves() {
    use tabor::physics::md::curve_point;
    let (mut worst, mut n) = (0f64, 0);
    for row in table("curves.csv") {
        let (l, a) = (num(&row, "lambda"), num(&row, "A"));
        if num(&row, "disp_stable") != 1.0 || a == 0.0 {
            continue;
        }
        let d = num(&row, "Dbar");
        let s = LambdaContext::new(l).unwrap().solve_approach(d);
        assert_eq!(s.status, Status::Ok, "lambda {l} A {a}");
        let mu = (s.m_minus_1 * (s.m_minus_1 + 2.0)).sqrt();
        let (p, q) = (
            curve_point(l, mu * (1.0 - 1e-6)),
            curve_point(l, mu * (1.0 + 1e-6)),
        );
        let cond = d.abs().max(1.0) / (a * ((q.approach - p.approach) / (q.a - p.a)).abs());
        let e = rel(s.a, a);
        assert!(
            e <= F64_TOL * cond.max(1.0),
            "lambda {l} A {a}: {e:e}, condition {cond:.1e}"
        );
        worst = worst.max(e / cond.max(1.0));
        n += 1;
    }
    eprintln!(
        "solve_approach on {n} reference curve points: worst error {worst:.2e} per unit condition"
    );
}
