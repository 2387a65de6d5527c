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
