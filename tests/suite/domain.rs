//! The extended lambda domain: the exact solver against the 50-digit oracle
//! (`tests/reference/md_oracle.py` -> `tests/data/md_extended.csv`) over its whole certified
//! range, the closed-form limits beyond it (their asymptotic difference from MD against the
//! oracle, their switch-over from MD), and the refusals elsewhere.

use crate::common;
use common::*;
use tabor::physics::closed::{jkr_approach, jkr_load};
use tabor::physics::domain::{self, Method, DMT_LIMIT_MAX, LAMBDA_MAX, LAMBDA_MIN};
use tabor::physics::md::LAMBDA_D;
use tabor::solver::limits::{DMT_APPROACH_C05, DMT_LOAD_C15};
use tabor::solver::{solve_one, solve_points, Control, LambdaContext, Status};

struct Row {
    lambda: f64,
    kind: String,
    a: f64,
    load: f64,
    approach: f64,
    m_minus_1: f64,
}

fn oracle() -> Vec<Row> {
    let path = format!("{}/tests/data/md_extended.csv", env!("CARGO_MANIFEST_DIR"));
    let mut rdr = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_path(&path)
        .unwrap_or_else(|e| panic!("{path}: {e}"));
    rdr.records()
        .map(|r| {
            let r = r.unwrap();
            let f = |i: usize| -> f64 { r[i].parse().unwrap() };
            Row {
                lambda: f(0),
                kind: r[1].to_string(),
                a: f(2),
                load: f(3),
                approach: f(4),
                m_minus_1: f(5),
            }
        })
        .collect()
}

fn lambdas(rows: &[Row]) -> Vec<f64> {
    let mut l: Vec<f64> = rows.iter().map(|r| r.lambda).collect();
    l.dedup();
    l
}

/// Every lambda of the table (two a decade over the certified range, its ends included): both
/// pull-offs, and the states at given loads (exact doubles) solved from their load, within the
/// f64 contract. A load whose distance from the pull-off is below f64's resolution of it (the
/// oracle's states at 1.1 times the pull-off radius at small lambda) may be either side of it.
#[test]
fn exact_solver_matches_the_oracle_over_the_certified_domain() {
    let rows = oracle();
    let ls = lambdas(&rows);
    assert!(ls.len() >= 105, "{} lambdas", ls.len());
    assert_eq!(ls[0], LAMBDA_MIN);
    assert_eq!(*ls.last().unwrap(), LAMBDA_MAX);
    let (mut worst, mut states) = ((0.0f64, 0.0), 0);
    for &lambda in &ls {
        let ctx = LambdaContext::new(lambda).unwrap();
        assert_eq!(domain::method(lambda), Some(Method::Md));
        let pc = ctx.load_pulloff.load;
        let pc_table = rows
            .iter()
            .find(|r| r.lambda == lambda && r.kind == "pulloff_load")
            .unwrap()
            .load;
        for r in rows.iter().filter(|r| r.lambda == lambda) {
            match r.kind.as_str() {
                "pulloff_load" => {
                    let lp = ctx.load_pulloff;
                    let (el, ea) = (rel(lp.load, r.load), rel(lp.a, r.a));
                    assert!(
                        el <= PULLOFF_TOL && ea <= PULLOFF_TOL,
                        "lambda {lambda}: load pull-off P {el:e} A {ea:e}"
                    );
                }
                "pulloff_displacement" => {
                    let dp = ctx.disp_pulloff();
                    assert_eq!(dp.at_zero_radius(), lambda <= LAMBDA_D, "lambda {lambda}");
                    let el = rel(dp.load, r.load);
                    let ea = if r.a == 0.0 { dp.a } else { rel(dp.a, r.a) };
                    assert!(
                        el <= PULLOFF_TOL && ea <= PULLOFF_TOL,
                        "lambda {lambda}: jump-out P {el:e} A {ea:e}"
                    );
                }
                _ => {
                    let s = ctx.solve_load(r.load);
                    if r.load - pc_table < 1e-14 * pc_table.abs().max(1.0) {
                        assert!(matches!(s.status, Status::Ok | Status::NoContact));
                        continue;
                    }
                    assert_eq!(s.status, Status::Ok, "lambda {lambda} load {}", r.load);
                    let tol = bound(r.load, pc);
                    let e = rel(s.a, r.a)
                        .max(rel(s.m_minus_1, r.m_minus_1))
                        .max((s.approach - r.approach).abs() / r.approach.abs().max(1.0));
                    assert!(
                        e <= tol,
                        "lambda {lambda} A {}: error {e:e} > {tol:e} (A {} m-1 {} D {})",
                        r.a,
                        s.a,
                        s.m_minus_1,
                        s.approach
                    );
                    if e / tol > worst.0 {
                        worst = (e / tol, lambda);
                    }
                    states += 1;
                }
            }
        }
    }
    eprintln!(
        "{states} oracle states over lambda {LAMBDA_MIN:e}..{LAMBDA_MAX:e}: worst error / bound {:.3} (lambda {:e})",
        worst.0, worst.1
    );
}

/// The asymptotic differences MD minus limit that PHYSICS.md section 5 derives, against the
/// oracle where both are resolved: JKR's lambda^-2 terms at lambda 1e3..1e4, DMT's pi lambda A^2
/// and lambda^0.5 terms at lambda 1e-12..1e-10 and the lambda^1.5 pull-off term at 1e-8..1e-7
/// (17 digits of Pbar near -2 resolve it to 1e-4 there).
#[test]
fn limits_differ_from_md_as_derived() {
    let rows = oracle();
    let mut checked = 0;
    for r in rows.iter().filter(|r| r.kind == "state") {
        let (l, a) = (r.lambda, r.a);
        if (1e3..=1e4).contains(&l) && a <= 100.0 {
            let dp = (r.load - jkr_load(a)) * l * l;
            let want = 1.5 * a * a - 13.0 / 8.0 * 1.5f64.sqrt() * a.sqrt();
            assert!(
                (dp - want).abs() <= 1e-4 * want.abs().max(1.0),
                "P at {l} {a}: {dp} vs {want}"
            );
            let dd = (r.approach - jkr_approach(a)) * l * l;
            let want = a - 5.0 / 12.0 * (1.5 / a).sqrt();
            assert!(
                (dd - want).abs() <= 1e-4 * want.abs().max(1.0),
                "D at {l} {a}: {dd} vs {want}"
            );
            let m1 = 0.75 / a / l / l;
            // Its relative correction is O(lambda^-2) too.
            assert!(rel(r.m_minus_1, m1) < 10.0 / (l * l), "m-1 at {l} {a}");
            checked += 1;
        }
        if (1e-12..=1e-10).contains(&l) && (0.5..=3.0).contains(&a) {
            let dp = r.load - (a * a * a - 2.0);
            let want = DMT_LOAD_C15 * l.powf(1.5) - std::f64::consts::PI * l * a * a;
            assert!(
                (dp - want).abs() <= 1e-3 * want.abs(),
                "P at {l} {a}: {dp} vs {want}"
            );
            let dd = r.approach - a * a;
            let want = -DMT_APPROACH_C05 * l.sqrt();
            assert!(
                (dd - want).abs() <= 1e-3 * want.abs(),
                "D at {l} {a}: {dd} vs {want}"
            );
            checked += 1;
        }
    }
    for r in rows.iter().filter(|r| r.kind == "pulloff_load") {
        if (1e-8..=1e-7).contains(&r.lambda) {
            let want = DMT_LOAD_C15 * r.lambda.powf(1.5);
            assert!(rel(r.load + 2.0, want) < 1e-3, "pull-off at {}", r.lambda);
            checked += 1;
        }
        if (1e3..=1e5).contains(&r.lambda) {
            let a = 1.5f64.cbrt();
            let want = (1.5 * a * a - 13.0 / 8.0 * 1.5f64.sqrt() * a.sqrt()) / r.lambda.powi(2);
            assert!(rel(r.load + 1.5, want) < 1e-3, "pull-off at {}", r.lambda);
            checked += 1;
        }
    }
    assert!(checked >= 30, "{checked}");
}

/// Crossing the exact solver's ends: the JKR limit just above LAMBDA_MAX agrees with MD at
/// LAMBDA_MAX, and the DMT limit at its largest lambda with MD at LAMBDA_MIN, each within the
/// difference its leading term predicts across the step (plus the f64 contract).
#[test]
fn limits_switch_over_from_md_continuously() {
    let above = LAMBDA_MAX * (1.0 + 1e-15);
    assert_eq!(domain::method(above), Some(Method::JkrLimit));
    for &load in &[-1.4999, -1.0, 0.0, 1.0, 1e3, 1e9] {
        let md = solve_one(LAMBDA_MAX, load, Control::Load);
        let jkr = solve_one(above, load, Control::Load);
        assert_eq!(
            (md.status, jkr.status),
            (Status::Ok, Status::Ok),
            "load {load}"
        );
        assert!(rel(jkr.a, md.a) < 1e-13, "A at {load}: {} {}", jkr.a, md.a);
        assert!((jkr.approach - md.approach).abs() < 1e-13 * md.approach.abs().max(1.0));
        assert!(rel(jkr.m_minus_1, md.m_minus_1) < 1e-12, "m-1 at {load}");
    }
    for &d in &[-0.9, -0.5, 0.0, 2.0, 1e4] {
        let md = solve_one(LAMBDA_MAX, d, Control::Displacement);
        let jkr = solve_one(above, d, Control::Displacement);
        assert_eq!(md.status, jkr.status, "approach {d}");
        if md.status == Status::Ok {
            assert!(rel(jkr.a, md.a) < 1e-12, "A at D {d}: {} {}", jkr.a, md.a);
            assert!((jkr.load - md.load).abs() < 1e-12 * md.load.abs().max(1.0));
        }
    }
    // Below JKR's pull-off there is no contact in either.
    assert_eq!(
        solve_one(above, -1.5000001, Control::Load).status,
        Status::NoContact
    );
    assert_eq!(
        solve_one(1e100, -0.95, Control::Displacement).status,
        Status::NoContact
    );

    // Just below LAMBDA_MIN the DMT limit against MD at LAMBDA_MIN: A within the estimate
    // (pi lambda / (3 A), ~1e-26), the approach off by MD's 1.5045 lambda^0.5 = 1.5e-13.
    let below = LAMBDA_MIN * (1.0 - 1e-15);
    assert!(below < DMT_LIMIT_MAX);
    assert_eq!(domain::method(below), Some(Method::DmtLimit));
    let shift = DMT_APPROACH_C05 * LAMBDA_MIN.sqrt();
    for &load in &[-1.9, 0.0, 1.0, 1e6] {
        let md = solve_one(LAMBDA_MIN, load, Control::Load);
        let dmt = solve_one(below, load, Control::Load);
        assert_eq!(
            (md.status, dmt.status),
            (Status::Ok, Status::Ok),
            "load {load}"
        );
        assert!(rel(dmt.a, md.a) < 1e-14, "A at {load}: {} {}", dmt.a, md.a);
        let dd = dmt.approach - md.approach;
        assert!(
            (dd - shift).abs() < 0.01 * shift + 4e-16 * md.approach.abs(),
            "D at {load}: {dd:e} vs {shift:e}"
        );
        assert!(rel(dmt.m_minus_1, md.m_minus_1) < 1e-13, "m-1 at {load}");
    }
}

/// The limits answer only where certified; elsewhere (between the DMT limit and the exact
/// solver, beyond the limits, too close to the DMT pull-off) the state is invalid_input.
#[test]
fn refusals_beyond_the_certified_methods() {
    for &l in &[
        1e-301,
        1e151,
        1e300,
        1e-310,
        0.0,
        -1.0,
        f64::NAN,
        f64::INFINITY,
    ] {
        assert_eq!(domain::method(l), None, "lambda {l:e}");
        for c in [Control::Load, Control::Displacement] {
            let s = solve_one(l, 1.0, c);
            assert_eq!(s.status, Status::InvalidInput, "lambda {l:e}");
            assert!(s.a.is_nan() && s.m_minus_1.is_nan());
        }
    }
    // The DMT limit near its pull-off: MD's contact radius there is ~ 2 pi lambda / 3, not 0.
    let l = 1e-30;
    assert_eq!(
        solve_one(l, -2.0, Control::Load).status,
        Status::InvalidInput
    );
    assert_eq!(
        solve_one(l, -2.0 + 1e-30, Control::Load).status,
        Status::InvalidInput
    );
    assert_eq!(solve_one(l, -2.5, Control::Load).status, Status::NoContact);
    let s = solve_one(l, -1.0, Control::Load);
    assert_eq!(s.status, Status::Ok);
    assert!(rel(s.a, 1.0) < 1e-15 && s.approach == 1.0);
    // m = mu = 2 / (A sqrt(pi lambda)) to O(lambda): 1.128e15 here.
    assert!(rel(s.m_minus_1 + 1.0, 2.0 / (std::f64::consts::PI * l).sqrt()) < 1e-12);
    // Under displacement control the DMT approach is off by 1.5045 lambda^0.5: certified only
    // where A^2 is large against it.
    let l = 0.9e-26;
    assert_eq!(
        solve_one(l, 0.1, Control::Displacement).status,
        Status::InvalidInput
    );
    assert_eq!(
        solve_one(l, -0.1, Control::Displacement).status,
        Status::InvalidInput
    );
    let s = solve_one(l, 4.0, Control::Displacement);
    assert_eq!(s.status, Status::Ok);
    assert!(rel(s.a, 2.0) < 1e-15 && rel(s.load, 6.0) < 1e-15);
    // Out-of-range values stay refused under the limits.
    assert_eq!(
        solve_one(1e30, 2e12, Control::Load).status,
        Status::InvalidInput
    );
    assert_eq!(
        solve_one(1e-40, 2e8, Control::Displacement).status,
        Status::InvalidInput
    );
    // A batch mixes the methods point by point.
    let pts = [
        (1e-12, 0.0),
        (1e-301, 0.0),
        (1e-28, 0.0),
        (1e30, 0.0),
        (1.0, 0.0),
    ];
    let st: Vec<Status> = solve_points(&pts, Control::Load)
        .iter()
        .map(|s| s.status)
        .collect();
    assert_eq!(
        st,
        [
            Status::Ok,
            Status::InvalidInput,
            Status::Ok,
            Status::Ok,
            Status::Ok
        ]
    );
}

/// The command line: `solve` reports the method in every format, answers beyond the exact
/// solver's range by the limits, and refuses a DMT-limit state it cannot certify with the reason.
#[test]
fn command_line_reports_the_method() {
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
            .args(args)
            .output()
            .unwrap()
    };
    let o = run(&[
        "solve", "--lambda", "1e30", "--load", "0", "--format", "csv",
    ]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    let row: Vec<&str> = text.lines().nth(1).unwrap().split(',').collect();
    assert_eq!(row[5..], ["ok", "jkr_limit"]);
    let a: f64 = row[2].parse().unwrap();
    assert!(rel(a, 6f64.cbrt()) < 1e-15, "{a}");
    let o = run(&[
        "solve", "--lambda", "1e-12", "--load", "0", "--format", "json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["results"][0]["method"], "md");
    let o = run(&["solve", "--lambda", "1e-30", "--load", "-1"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("dmt_limit"));
    let o = run(&["solve", "--lambda", "1e-30", "--load", "-2"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("DMT limit is not certified") && err.lines().count() == 1,
        "{err}"
    );
}

/// The library's messages name quantities, never command-line flags (the command line adds
/// those): a map's ranges and sizes, a figure's size, a profile's sampling, a fit's segments.
#[test]
fn library_messages_name_quantities_not_flags() {
    use tabor::map::{LoadAxis, MapSpec};
    // A valid spec with one change.
    let with = |f: &dyn Fn(&mut MapSpec)| {
        let mut s = MapSpec {
            lambda_min: 1e-3,
            lambda_max: 1e3,
            nx: 8,
            load_axis: LoadAxis::Log,
            load_min: 1e-3,
            load_max: 1e3,
            ny: 8,
            tolerance: 0.05,
            strength_ratios: vec![],
        };
        f(&mut s);
        s
    };
    let spec = |f: &dyn Fn(&mut MapSpec)| with(f).validate().unwrap_err().to_string();
    let msgs = [
        spec(&|s| s.lambda_min = 1e200),
        spec(&|s| (s.lambda_min, s.lambda_max) = (10.0, 1.0)),
        spec(&|s| s.nx = 1),
        spec(&|s| s.tolerance = 2.0),
        spec(&|s| s.load_min = -1.0),
        tabor::render::Print::new(5.0, 300.0)
            .unwrap_err()
            .to_string(),
        tabor::profile::profile(1.0, tabor::profile::Given::Load(0.0), 3)
            .unwrap_err()
            .to_string(),
        tabor::gpu::GpuError::NoF64("x".into()).to_string(),
    ];
    let names = [
        "lambda_min",
        "lambda_min must be below lambda_max",
        "nx and ny",
        "tolerance",
        "load_min > 0",
        "width_mm 5",
        "points 3",
        "f32 precision",
    ];
    for (m, name) in msgs.iter().zip(names) {
        assert!(m.contains(name), "{m}");
        assert!(!m.contains("--"), "{m}");
    }
    // A front end's names replace the keys, and only them: typed parts, not text (`nx` in
    // "nx_min" or a word of the message is not a key).
    use tabor::error::Named;
    let upper = |k: &str| match k {
        "lambda_min" => Some("LMIN"),
        "lambda_max" => Some("LMAX"),
        "nx" => Some("NX"),
        "ny" => Some("NY"),
        "load_axis=linear" => Some("LINEAR"),
        "width_mm" => Some("WIDTH"),
        "precision=f32" => Some("F32"),
        _ => None,
    };
    let named = |f: &dyn Fn(&mut MapSpec)| with(f).validate().unwrap_err().named(&upper);
    assert_eq!(
        named(&|s| (s.lambda_min, s.lambda_max) = (10.0, 1.0)),
        "LMIN must be below LMAX, got 10 and 1"
    );
    assert_eq!(
        named(&|s| s.nx = 1),
        "NX and NY must be in 2..=16384, got 1 and 8"
    );
    assert_eq!(
        named(&|s| s.load_min = -1.0),
        "a log load axis needs load_min > 0 (got -1); use LINEAR for tensile loads"
    );
    assert!(tabor::render::Print::new(5.0, 300.0)
        .unwrap_err()
        .named(&upper)
        .starts_with("WIDTH 5 is outside 40..600"));
    assert!(tabor::gpu::GpuError::NoF64("x".into())
        .named(&upper)
        .contains("use F32, or the cpu backend for f64"));
    // The command line puts its flags back.
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args(["map", "--nx", "1", "--out", "/nonexistent/m.png"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--nx and --ny must be in 2..=16384"), "{err}");
}
