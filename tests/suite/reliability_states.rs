//! Reliability of states, profiles, cycles and scenes: stability near A = 0, the energy release
//! rate where C and A are equal in f64.

use tabor::profile::{profile, Given};
use tabor::solver::context::solve_radius;
use tabor::solver::{solve_radius_points, LambdaContext, Status};

/// The sign of dPbar/dA and dDbar/dA by central differences of the curve: an independent check
/// of the stability flags where the slopes are well resolved.
fn slopes(lambda: f64, a: f64) -> (bool, bool) {
    let h = 1e-4 * a;
    let (lo, hi) = (solve_radius(lambda, a - h), solve_radius(lambda, a + h));
    (hi.load > lo.load, hi.approach > lo.approach)
}

#[test]
fn stability_near_zero_radius_follows_the_pull_off_radii() {
    // lambda 1: load pull-off at A = 0.904, displacement jump-out at A = 0.085; below both,
    // neither control is stable, however small A is.
    for &a in &[1e-3, 1e-8, 1e-10, 1e-15, 1e-20, 1e-40, 1e-100] {
        let s = solve_radius(1.0, a);
        assert_eq!(s.status, Status::Ok, "A {a}");
        assert!(s.load.is_finite() && s.m_minus_1.is_finite());
        assert_eq!(
            (s.load_stable, s.displacement_stable),
            (false, false),
            "lambda 1 A {a}"
        );
    }
    // lambda 0.5 < lambda_D: displacement control is stable down to A = 0, load control not.
    for &a in &[1e-3, 1e-10, 1e-20, 1e-100] {
        let s = solve_radius(0.5, a);
        assert_eq!(s.status, Status::Ok, "A {a}");
        assert_eq!(
            (s.load_stable, s.displacement_stable),
            (false, true),
            "lambda 0.5 A {a}"
        );
    }
    // Where the slopes are resolved, the flags agree with their signs.
    for &(l, a) in &[
        (1.0, 0.05),
        (1.0, 0.5),
        (1.0, 2.0),
        (0.5, 0.3),
        (10.0, 0.3),
        (10.0, 3.0),
    ] {
        let s = solve_radius(l, a);
        assert_eq!(
            (s.load_stable, s.displacement_stable),
            slopes(l, a),
            "lambda {l} A {a}"
        );
    }
    // The flags change exactly at the pull-off radii.
    let ctx = LambdaContext::new(1.0).unwrap();
    let (ac, ad) = (ctx.load_pulloff.a, ctx.disp_pulloff().a);
    assert!(
        (ac - 0.904).abs() < 1e-3 && (ad - 0.085).abs() < 1e-3,
        "{ac} {ad}"
    );
    assert!(!ctx.solve_radius(ac * (1.0 - 1e-9)).load_stable);
    assert!(ctx.solve_radius(ac * (1.0 + 1e-9)).load_stable);
    assert!(!ctx.solve_radius(ad * (1.0 - 1e-9)).displacement_stable);
    assert!(ctx.solve_radius(ad * (1.0 + 1e-9)).displacement_stable);
    // The batch form (one context per lambda) gives the same.
    let b = solve_radius_points(&[(1.0, 1e-20), (0.5, 1e-10), (1.0, 2.0)]);
    let flags: Vec<_> = b
        .iter()
        .map(|s| (s.load_stable, s.displacement_stable))
        .collect();
    assert_eq!(flags, vec![(false, false), (false, true), (true, true)]);
}

#[test]
fn a_state_that_was_not_found_carries_no_numbers() {
    // Below about A = 1e-150 the curve cannot be evaluated in f64.
    let s = solve_radius(1.0, 1e-200);
    assert_eq!(s.status, Status::NotConverged);
    assert!(s.load.is_nan() && s.approach.is_nan() && s.m_minus_1.is_nan());
    assert!(!s.load_stable && !s.displacement_stable);
}

#[test]
fn energy_release_rate_is_one_where_c_equals_a_in_f64() {
    // At equilibrium J/w = 1 (the third MD equation), also where m - 1 is below 1e-16.
    for &(l, p) in &[
        (1e8, 0.0),
        (5e7, 1.0),
        (1e8, 1e6),
        (1e7, 1e6),
        (1e7, 1e9),
        (1e6, 1e12),
        (10.0, 0.0),
        (1.0, 3.0),
        (0.01, 1.0),
    ] {
        let pr = profile(l, Given::Load(p), 64).unwrap();
        let md = &pr.models[0];
        assert_eq!(md.model, tabor::physics::model::ContactModel::Md);
        let j = md.energy_release_rate_over_w.unwrap();
        assert!((j - 1.0).abs() < 1e-9, "lambda {l} load {p}: J/w = {j}");
    }
}

/// Trapezoid of the printed pressure over 2 pi r dr, and the load.
fn trapezoid_load(l: f64, p: f64, points: usize) -> (f64, f64) {
    let pr = profile(l, Given::Load(p), points).unwrap();
    let md = &pr.models[0];
    let f: Vec<f64> =
        md.r.iter()
            .zip(&md.pressure)
            .map(|(r, q)| 2.0 * std::f64::consts::PI * r * q.unwrap())
            .collect();
    let s: f64 = (1..f.len())
        .map(|i| 0.5 * (f[i] + f[i - 1]) * (md.r[i] - md.r[i - 1]))
        .sum();
    (s, md.load)
}

#[test]
fn printed_pressure_integrates_to_the_load() {
    for &(l, p) in &[
        (10.0, 0.0),
        (10.0, 1.0),
        (1.0, 0.0),
        (1.0, -1.0),
        (0.1, 0.5),
        (100.0, 2.0),
    ] {
        let (s, load) = trapezoid_load(l, p, 400);
        // Relative to the cohesive zone's force scale: the Dugdale stress over the zone.
        let pr = profile(l, Given::Load(p), 400).unwrap();
        let (a, c) = (pr.models[0].a.unwrap(), pr.models[0].c.unwrap());
        let zone = 0.5 * l * std::f64::consts::PI * (c * c - a * a);
        let e = (s - load).abs() / zone.max(load.abs()).max(1e-300);
        eprintln!("lambda {l} load {p}: trapezoid {s} load {load} rel {e:e}");
        assert!(
            e < 1e-4,
            "lambda {l} load {p}: trapezoid {s} against {load} ({e:e})"
        );
    }
}

#[test]
fn a_radius_too_small_to_resolve_says_so_without_speaking_of_loads() {
    let e = profile(1.0, Given::Radius(1e-300), 64)
        .unwrap_err()
        .to_string();
    assert!(e.contains("contact radius") && e.contains("1e-300"), "{e}");
    assert!(!e.contains("load"), "{e}");
    // A radius that resolves gives a profile with J/w = 1.
    let p = profile(1.0, Given::Radius(1e-30), 64).unwrap();
    let j = p.models[0].energy_release_rate_over_w.unwrap();
    assert!((j - 1.0).abs() < 1e-9, "{j}");
}

#[test]
fn cycle_jump_out_is_the_fold_found_exactly() {
    // Under rigid grips the retract jump-out is the displacement-controlled pull-off, a fold of
    // the curve: the cycle must find the same point as the pull-off solver, not the best sample.
    use tabor::cycle::{cycle, Drive, Phase};
    for &lambda in &[2.0, 10.0, 100.0] {
        let c = cycle(lambda, Drive::RigidGrips, 2.0).unwrap();
        let po = LambdaContext::new(lambda).unwrap().disp_pulloff();
        let j = c.jumps.iter().find(|j| j.phase == Phase::Retract).unwrap();
        assert!(
            (j.from.load - po.load).abs() < 1e-9,
            "lambda {lambda}: {} vs {}",
            j.from.load,
            po.load
        );
        assert!(
            (j.from.a - po.a).abs() < 1e-6,
            "lambda {lambda}: A {} vs {}",
            j.from.a,
            po.a
        );
    }
    // Under dead load the jump-out is the load-controlled pull-off.
    let c = cycle(10.0, Drive::DeadLoad, 2.0).unwrap();
    let j = c.jumps.iter().find(|j| j.phase == Phase::Retract).unwrap();
    assert!(
        (j.from.load - (-1.501624860426358)).abs() < 1e-9,
        "{}",
        j.from.load
    );
}

fn scene_run(json: &str) -> std::process::Output {
    let dir =
        std::env::temp_dir().join(format!("tabor-scene-{}-{}", std::process::id(), json.len()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("s.json");
    std::fs::write(&f, json).unwrap();
    std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
        .env("TABOR_BACKEND", "cpu")
        .arg("scene")
        .arg(&f)
        .output()
        .unwrap()
}

#[test]
fn scene_refusals_name_what_is_wrong() {
    let base = r#""e_star_pa":1e9,"radius_m":1e-6,"work_of_adhesion_j_m2":0.05,"z0_m":3e-10"#;
    let cases: &[(&str, &str)] = &[
        (r#""loads_n":[]"#, "loads_n"),
        (r#""load_range_n":[0,1e-6,1]"#, "at least 2"),
        (r#""load_range_n":[0,1e-6,0]"#, "at least 2"),
        (
            r#""control":{"cantilever_n_m":1,"bogus":2}"#,
            "cantilever_n_m",
        ),
        (
            r#""body1":{"youngs_modulus_pa":1e9,"poisson_ratio":0.3,"radius_m":1e-6},"body2":{"youngs_modulus_pa":1e9,"poisson_ratio":0.3}"#,
            "both",
        ),
    ];
    for (extra, want) in cases {
        let o = scene_run(&format!("{{{base},{extra}}}"));
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{extra}: {err}");
        assert!(err.contains(want), "{extra}: {err}");
        assert!(!err.contains("no load is above"), "{extra}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{extra}: {err}");
    }
    // A cantilever's stiffness is printed to a few digits, not hundreds.
    let o = scene_run(&format!(r#"{{{base},"control":{{"cantilever_n_m":0.1}}}}"#));
    let out = String::from_utf8_lossy(&o.stderr).to_string() + &String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{out}");
    let line = out.lines().find(|l| l.contains("cantilever k")).unwrap();
    assert!(line.len() < 200, "{line}");
}

#[test]
fn cycle_energy_uses_a_prefix_that_shows_it() {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
        .env("TABOR_BACKEND", "cpu")
        .args([
            "cycle",
            "--preset",
            "afm-si",
            "--format",
            "csv",
            "-o",
            "/dev/null",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    let line = err.lines().find(|l| l.contains("energy lost")).unwrap();
    assert!(!line.contains(" 0.0000 "), "{line}");
    let value: f64 = line
        .split('=')
        .nth(1)
        .unwrap()
        .trim()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(value > 0.0, "{line}");
}
