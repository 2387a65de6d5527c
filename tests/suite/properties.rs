//! Property tests across and beyond the domain (physics::domain): a state marked `ok` has every
//! field finite and satisfies the Maugis-Dugdale equations to the contract; anything else has a
//! failure status and empty fields. The same for pull-offs, curves and cycles.

// `!(x <= max)` is deliberate: a NaN must count as outside.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use proptest::prelude::*;
use tabor::cycle::{cycle, Drive};
use tabor::physics::domain::{self, Method, LAMBDA_MAX, LAMBDA_MIN, LOAD_MAX, RADIUS_MAX};
use tabor::physics::md::curve_point;
use tabor::physics::md::point;
use tabor::solver::context::x_at_radius;
use tabor::solver::{solve_one, Control, LambdaContext, State, Status};

/// lambda log-uniform over 1e-30..1e30 (the exact solver's domain is 1e-26..1e26, the limits
/// answer beyond it), now and then exactly on a limit or outside every method.
fn lambda() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => (-30.0f64..30.0).prop_map(|e| 10f64.powf(e)),
        1 => Just(LAMBDA_MIN),
        1 => Just(LAMBDA_MAX),
        1 => prop::sample::select(vec![1e-301, 1e-310, 1e160, 1e300, -1.0, 0.0, f64::NAN, f64::INFINITY]),
    ]
}

/// A signed value with magnitude log-uniform over 1e-10..10^max_exp, or a special value.
fn signed(max_exp: f64) -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => ((-10.0f64..max_exp), any::<bool>()).prop_map(|(e, neg)| if neg { -10f64.powf(e) } else { 10f64.powf(e) }),
        1 => prop::sample::select(vec![0.0, -2.0, 1e300, -1e300, f64::NAN, f64::INFINITY]),
    ]
}

/// The state reproduces what was given: from its m - 1 the curve gives back its A and its load
/// (load control) or approach (displacement control).
fn check_state(s: &State, lambda: f64, value: f64, control: Control) -> Result<(), TestCaseError> {
    if s.status != Status::Ok {
        prop_assert!(s.a.is_nan() || s.status == Status::NotConverged, "{s:?}");
        return Ok(());
    }
    for v in [s.load, s.approach, s.a, s.m_minus_1] {
        prop_assert!(v.is_finite(), "{s:?}");
    }
    prop_assert!(s.a > 0.0 && s.m_minus_1 > 0.0, "{s:?}");
    let mu = (s.m_minus_1 * (s.m_minus_1 + 2.0)).sqrt();
    let p = curve_point(lambda, mu);
    prop_assert!(
        (p.a / s.a - 1.0).abs() < 1e-12,
        "A {} vs {}: {s:?}",
        p.a,
        s.a
    );
    match control {
        Control::Load => {
            prop_assert_eq!(s.load, value);
            let tol = 1e-9 * value.abs().max(2.0);
            prop_assert!(
                (p.load - value).abs() <= tol,
                "load {} vs {value}: {s:?}",
                p.load
            );
            prop_assert!((p.approach - s.approach).abs() <= 1e-9 * s.approach.abs().max(1.0));
        }
        Control::Displacement => {
            prop_assert_eq!(s.approach, value);
            let tol = 1e-9 * value.abs().max(1.0);
            prop_assert!(
                (p.approach - value).abs() <= tol,
                "approach {} vs {value}: {s:?}",
                p.approach
            );
            prop_assert!((p.load - s.load).abs() <= 1e-9 * s.load.abs().max(2.0));
        }
    }
    Ok(())
}

fn in_domain(lambda: f64) -> bool {
    (LAMBDA_MIN..=LAMBDA_MAX).contains(&lambda)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn load_control_states_are_certified_or_failed(l in lambda(), load in signed(13.0)) {
        let s = solve_one(l, load, Control::Load);
        let method = domain::method(l);
        if method.is_none() || !(load.abs() <= LOAD_MAX) {
            prop_assert_eq!(s.status, Status::InvalidInput);
            prop_assert!(s.a.is_nan());
        } else if method == Some(Method::Md) {
            prop_assert!(s.status != Status::InvalidInput && s.status != Status::NotConverged, "{s:?}");
        } else {
            // A limit refuses (invalid_input) where it is not certified, never fails to converge.
            prop_assert!(s.status != Status::NotConverged, "{s:?}");
        }
        check_state(&s, l, load, Control::Load)?;
    }

    #[test]
    fn states_near_the_pulloff_are_certified(l in (-8.0f64..8.0).prop_map(|e| 10f64.powf(e)), e in -15.0f64..1.0) {
        let c = LambdaContext::new(l).unwrap();
        let load = c.load_pulloff.load + 10f64.powf(e);
        let s = c.solve_load(load);
        prop_assert_eq!(s.status, Status::Ok);
        check_state(&s, l, load, Control::Load)?;
    }

    #[test]
    fn displacement_control_states_are_certified_or_failed(l in lambda(), d in signed(9.0)) {
        let s = solve_one(l, d, Control::Displacement);
        let method = domain::method(l);
        if method.is_none() || !(d.abs() <= 1e8) {
            prop_assert_eq!(s.status, Status::InvalidInput);
        } else if method == Some(Method::Md) {
            prop_assert!(s.status == Status::Ok || s.status == Status::NoContact, "{s:?}");
        } else {
            prop_assert!(s.status != Status::NotConverged, "{s:?}");
        }
        check_state(&s, l, d, Control::Displacement)?;
    }

    #[test]
    fn pulloffs_exist_exactly_in_the_domain(l in lambda()) {
        match LambdaContext::new(l) {
            Ok(c) => {
                prop_assert!(in_domain(l));
                let (p, d) = (c.load_pulloff, c.disp_pulloff());
                prop_assert!(p.load >= -2.0 - 1e-12 && p.load <= -1.5 + 1e-12, "{p:?}");
                prop_assert!(p.a.is_finite() && p.a > 0.0 && p.approach.is_finite());
                // Rigid grips hold on to smaller loads than dead load.
                prop_assert!(d.load.is_finite() && d.load >= p.load - 1e-12, "{d:?} {p:?}");
                prop_assert!(d.approach.is_finite() && d.a >= 0.0);
            }
            Err(e) => {
                prop_assert!(!in_domain(l));
                prop_assert!(e.to_string().contains("1e-26..1e26"), "{e}");
            }
        }
    }

    #[test]
    fn curve_points_at_a_given_radius_are_on_the_curve(l in (-8.0f64..8.0).prop_map(|e| 10f64.powf(e)), e in -6.0f64..4.0) {
        let a = 10f64.powf(e).min(RADIUS_MAX);
        let p = point(l, x_at_radius(l, a));
        prop_assert!((p.a / a - 1.0).abs() < 1e-12, "{} vs {a}", p.a);
        for v in [p.load, p.approach, p.m_minus_1] {
            prop_assert!(v.is_finite());
        }
    }

    #[test]
    fn cycles_are_finite_or_refused(l in lambda(), max in signed(13.0), k in prop_oneof![Just(None), (-3.0f64..3.0).prop_map(|e| Some(10f64.powf(e)))]) {
        let drive = k.map_or(Drive::RigidGrips, Drive::Spring);
        match cycle(l, drive, max) {
            Ok(c) => {
                prop_assert!(in_domain(l) && max > 0.0 && max <= LOAD_MAX);
                for p in &c.path {
                    prop_assert!(p.load.is_finite() && p.approach.is_finite() && p.a.is_finite(), "{p:?}");
                }
                if let Some(w) = c.hysteresis {
                    prop_assert!(w.is_finite() && w >= 0.0);
                }
            }
            Err(_) => prop_assert!(!(in_domain(l) && max > 0.0 && max <= LOAD_MAX)),
        }
    }
}
