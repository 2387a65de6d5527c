//! The non-contact branch against the reference tables and its limits.

use crate::common;
use common::*;
use tabor::physics::md::non_contact_point;

#[test]
fn non_contact_branch_meets_the_curve_end_in_the_tables() {
    for row in table("pulloff.csv") {
        let lambda = num(&row, "lambda");
        let (p, d) = non_contact_point(lambda, num(&row, "C_A0"));
        assert!(rel(p, num(&row, "Pbar_A0")) < 1e-13, "lambda {lambda}: {p}");
        // Dbar = C^2/2 - (8 lambda / 3 pi) C - 2 / (pi lambda) cancels terms of size 2/(pi lambda).
        let dr = num(&row, "Dbar_A0");
        let tol = 4e-16 * 2.0 / (std::f64::consts::PI * lambda) + 1e-13;
        assert!((d - dr).abs() < tol, "lambda {lambda}: {d} vs {dr}");
    }
}

#[test]
fn rigid_dugdale_law_for_small_lambda() {
    // Pbar = -2 - pi lambda Dbar on the non-contact branch as lambda -> 0; substituting Dbar, the
    // difference is exactly -(8/3) lambda^2 C, the elastic stretch under the cohesive stress.
    for lambda in [1e-4, 1e-3] {
        let c_end = tabor::physics::md::zero_radius_end(lambda).c;
        for i in 1..=20 {
            let c = c_end * i as f64 / 20.0;
            let (p, d) = non_contact_point(lambda, c);
            let rigid = -2.0 - std::f64::consts::PI * lambda * d;
            let expected = -8.0 / 3.0 * lambda * lambda * c;
            assert!(
                (p - rigid - expected).abs() < 1e-12,
                "lambda {lambda} C {c}: {p} vs {rigid}"
            );
            // ... which vanishes against the pull-off force 2 as lambda -> 0.
            assert!(expected.abs() < 0.2 * lambda);
        }
    }
}

/// Under rigid grips the retract leaves the zone alone (the non-contact branch,
/// `Dbar = fbar(C) - 8 lambda C / (3 pi) - 2/(pi lambda)`) at its fold, `fbar'(C) = 8 lambda / (3 pi)`, for the
/// load `-(pi lambda / 2) C^2`: the sphere's `C = 8 lambda / (3 pi)` below lambda_D, and the
/// cubic tip's `C^2 = 8 k_3 lambda / (9 pi)` (`-pi/3` at lambda = 1). The cycle's samples only
/// bracket it (8% off in load at lambda 0.1 before it was refined).
#[test]
fn the_retract_leaves_the_zone_alone_at_its_exact_fold() {
    use std::f64::consts::PI;
    use tabor::cycle::{run, Phase};
    use tabor::law::{Branch, ContactLaw, Drive, Tip};
    use tabor::physics::tip::Shape;
    let out = |law: &ContactLaw| {
        let c = run(law, Drive::RigidGrips, 2.0).unwrap();
        let j = c
            .jumps
            .iter()
            .rev()
            .find(|j| j.phase == Phase::Retract)
            .expect("a jump off the zone")
            .clone();
        assert_eq!(j.from.branch, Branch::NonContact, "{law:?}");
        assert_eq!(j.to.map(|t| t.load), Some(0.0), "{law:?}");
        assert!(
            (j.to.unwrap().approach - j.from.approach).abs() <= 1e-15,
            "{law:?}: the landing holds the approach"
        );
        j.from
    };
    for lambda in [0.05, 0.1, 0.3, 0.6] {
        let p = out(&ContactLaw::md(lambda));
        let c = 8.0 * lambda / (3.0 * PI);
        assert!(
            rel(p.c, c) < 1e-12,
            "lambda {lambda}: C {} against {c}",
            p.c
        );
        let load = -PI * lambda / 2.0 * c * c;
        assert!(
            rel(p.load, load) < 1e-12,
            "lambda {lambda}: {} against {load}",
            p.load
        );
    }
    let cubic = Tip::new(Shape::Power { exponent: 3.0 }, 1.0).unwrap();
    let p = out(&ContactLaw::Tip(cubic));
    assert!(rel(p.load, -PI / 3.0) < 1e-12, "{}", p.load);
    assert!(rel(p.c, (2.0f64 / 3.0).sqrt()) < 1e-12, "{}", p.c);
}
