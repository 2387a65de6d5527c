//! Inside the contact: the state at a given radius against the reference curves, and the
//! pressure and gap fields against the MD equations, the closed forms and their limits.

use crate::common;
use common::*;
use std::f64::consts::PI;
use tabor::physics::fields::{
    energy_release_over_w, hertz_pressure, jkr_pressure, jkr_stress_intensity, MdGeometry,
};
use tabor::physics::md::curve_point;
use tabor::physics::model::ContactModel;
use tabor::profile::{profile, Given, ProfileStatus};
use tabor::solver::{LambdaContext, Status};

#[test]
fn states_at_a_given_radius_match_the_reference_curves() {
    let mut worst = 0f64;
    for row in table("curves.csv") {
        let (l, a) = (num(&row, "lambda"), num(&row, "A"));
        if a == 0.0 {
            continue;
        }
        let s = LambdaContext::new(l).unwrap().solve_radius(a);
        assert_eq!(s.status, Status::Ok);
        let e = [
            rel(s.m_minus_1, num(&row, "m_minus_1")),
            (s.load - num(&row, "Pbar")).abs() / num(&row, "Pbar").abs().max(1.0),
            (s.approach - num(&row, "Dbar")).abs() / num(&row, "Dbar").abs().max(1.0),
        ]
        .into_iter()
        .fold(0.0, f64::max);
        assert!(e <= F64_TOL, "lambda {l} A {a}: {e:e}");
        worst = worst.max(e);
        assert_eq!(
            s.load_stable,
            num(&row, "load_stable") == 1.0,
            "lambda {l} A {a}"
        );
        assert_eq!(
            s.displacement_stable,
            num(&row, "disp_stable") == 1.0,
            "lambda {l} A {a}"
        );
    }
    eprintln!("states at a given radius: worst error {worst:.2e} (contract {F64_TOL:e})");
}

#[test]
fn md_fields_satisfy_the_md_equations() {
    for &l in &[0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 100.0] {
        let ctx = LambdaContext::new(l).unwrap();
        for &gap in &[1e-3, 0.1, 1.0, 10.0, 100.0] {
            let load = ctx.load_pulloff.load + gap;
            let s = ctx.solve_load(load);
            let mu = (s.m_minus_1 * (s.m_minus_1 + 2.0)).sqrt();
            let g = MdGeometry {
                lambda: l,
                a: s.a,
                mu,
            };
            // The load is the integral of the pressure.
            let e = (g.load() - load).abs() / load.abs();
            assert!(e < 1e-10, "lambda {l} load {load}: integral off by {e:e}");
            // The gap reaches the Dugdale range at r = c (the J-integral is w), is zero at the
            // contact edge and opens beyond it.
            let h0 = 2.0 / (PI * l);
            let e = (g.gap(g.c()) / h0 - 1.0).abs();
            assert!(e < 1e-12, "lambda {l} load {load}: gap at c off by {e:e}");
            assert!(g.gap(s.a) == 0.0 && g.gap(0.5 * s.a) == 0.0);
            let near = g.gap(s.a * (1.0 + 1e-10));
            assert!(
                near.abs() < 1e-8 * h0.max(1.0),
                "lambda {l}: gap at a+ {near:e}"
            );
            let mut prev = 0.0;
            for k in 1..=200 {
                let r = s.a * (1.0 + 0.02 * k as f64);
                let h = g.gap(r);
                assert!(
                    h > 0.0 && h >= prev,
                    "lambda {l} load {load}: gap {h} at r {r}"
                );
                prev = h;
            }
            // The pressure is continuous at a (no singularity; steep where the zone is thin)
            // and equals the Dugdale stress on the cohesive zone.
            let jump = (g.pressure(s.a * (1.0 - 1e-14)) + 0.5 * l).abs();
            assert!(jump < 1e-2 * l.max(1.0), "lambda {l} load {load}: {jump:e}");
            assert_eq!(g.pressure(0.5 * (s.a + g.c())), -0.5 * l);
            assert_eq!(g.pressure(1.01 * g.c()), 0.0);
        }
    }
}

#[test]
fn md_pressure_tends_to_jkr_and_to_hertz_plus_dugdale() {
    // lambda -> infinity at zero load: JKR's pressure away from the edge.
    let s = LambdaContext::new(1e4).unwrap().solve_load(0.0);
    let mu = (s.m_minus_1 * (s.m_minus_1 + 2.0)).sqrt();
    let g = MdGeometry {
        lambda: 1e4,
        a: s.a,
        mu,
    };
    let aj = tabor::physics::closed::jkr_radius(0.0).unwrap();
    let mut worst = 0f64;
    for k in 0..=90 {
        let r = aj * k as f64 / 100.0;
        worst = worst.max((g.pressure(r) - jkr_pressure(aj, r)).abs());
    }
    eprintln!(
        "MD vs JKR pressure at lambda 1e4, zero load, r <= 0.9 a: max difference {worst:.2e}"
    );
    assert!(worst < 1e-8, "MD vs JKR at lambda 1e4: {worst:e}");
    // lambda -> 0: the Hertz pressure of the same radius with the Dugdale stress on top.
    let l = 1e-4;
    let s = LambdaContext::new(l).unwrap().solve_load(0.0);
    let mu = (s.m_minus_1 * (s.m_minus_1 + 2.0)).sqrt();
    let g = MdGeometry {
        lambda: l,
        a: s.a,
        mu,
    };
    let mut worst = 0f64;
    for k in 0..100 {
        let r = s.a * k as f64 / 100.0;
        worst = worst.max((g.pressure(r) - (hertz_pressure(s.a, r) - 0.5 * l)).abs());
    }
    eprintln!(
        "MD vs Hertz minus the Dugdale stress at lambda 1e-4: max difference {:.2e} of lambda/2",
        worst / (0.5 * l)
    );
    assert!(
        worst < 1e-2 * 0.5 * l,
        "MD vs Hertz + Dugdale at lambda 1e-4: {worst:e}"
    );
}

#[test]
fn closed_form_fields() {
    // JKR: G = w at equilibrium, for every contact radius.
    for a in [0.3, 1.0, 1.5f64.cbrt(), 4.0] {
        let g = energy_release_over_w(jkr_stress_intensity(a));
        assert!((g - 1.0).abs() < 1e-14, "{g}");
    }
    // Hertz: 3P/(2 pi a^2) sqrt(1 - r^2/a^2), in the profile of a compressive load.
    let p = profile(1.0, Given::Load(2.0), 200).unwrap();
    let h = p
        .models
        .iter()
        .find(|m| m.model == ContactModel::Hertz)
        .unwrap();
    let a = h.a.unwrap();
    assert!((a.powi(3) - 2.0).abs() < 1e-14);
    for (r, q) in h.r.iter().zip(&h.pressure) {
        let expected = if *r < a {
            3.0 * 2.0 / (2.0 * PI * a * a) * (1.0 - r * r / (a * a)).sqrt()
        } else {
            0.0
        };
        assert!((q.unwrap() - expected).abs() < 1e-12, "r {r}");
    }
    // JKR's pressure is singular at r = a: null there, never inf.
    let j = p
        .models
        .iter()
        .find(|m| m.model == ContactModel::Jkr)
        .unwrap();
    let k = j.r.iter().position(|&r| r == j.a.unwrap()).unwrap();
    assert!(j.pressure[k].is_none());
    assert!(j.pressure.iter().flatten().all(|q| q.is_finite()));
    // MD's J-integral through the Dugdale zone is w.
    let md = &p.models[0];
    assert!((md.energy_release_rate_over_w.unwrap() - 1.0).abs() < 1e-12);
    assert_eq!(md.max_tension, Some(0.5));
    // The profile samples densely on both sides of a and c.
    let (a, c) = (md.a.unwrap(), md.c.unwrap());
    for e in [a, c] {
        assert!(md.r.iter().any(|&r| r < e && r > e * (1.0 - 1e-7)));
        assert!(md.r.iter().any(|&r| r > e && r < e * (1.0 + 1e-7)));
    }
    // Below the models' pull-offs: no contact, empty arrays.
    let p = profile(10.0, Given::Load(-1.45), 200).unwrap();
    let dmt = p
        .models
        .iter()
        .find(|m| m.model == ContactModel::Dmt)
        .unwrap();
    assert_eq!(dmt.status, ProfileStatus::Ok);
    let hertz = p
        .models
        .iter()
        .find(|m| m.model == ContactModel::Hertz)
        .unwrap();
    assert!(hertz.status == ProfileStatus::NoContact && hertz.r.is_empty());
    assert!(profile(1.0, Given::Load(-1.7), 200).is_err());
    assert!(profile(1e-30, Given::Load(0.0), 200).is_err());
    // Given the approach or the radius: the same state as given the load.
    let by_load = profile(1.0, Given::Load(0.5), 100).unwrap().models[0].clone();
    let by_a = profile(1.0, Given::Radius(by_load.a.unwrap()), 100)
        .unwrap()
        .models[0]
        .clone();
    assert!((by_a.load - 0.5).abs() < 1e-13);
    let by_d = profile(1.0, Given::Approach(by_load.approach.unwrap()), 100)
        .unwrap()
        .models[0]
        .clone();
    assert!((by_d.a.unwrap() / by_load.a.unwrap() - 1.0).abs() < 1e-12);
    assert!(curve_point(1.0, 1.0).a > 0.0);
}

fn tabor(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args(args)
        .env("TABOR_BACKEND", "cpu")
        .output()
        .unwrap()
}

#[test]
fn command_line_profile_and_radius_control() {
    let o = tabor(&["profile", "--lambda", "1", "--load", "0"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let md = &v["models"][0];
    for key in ["r", "pressure", "gap", "a", "c", "load"] {
        assert!(md.get(key).is_some(), "no key {key}");
    }
    assert_eq!(v["models"][3]["model"], "jkr");
    // A scene in SI units.
    let o = tabor(&[
        "profile", "--preset", "afm-si", "--load-n", "1e-9", "--format", "csv",
    ]);
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.starts_with("model,r,pressure,gap\nmd,"));
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("p.png");
    let o = tabor(&[
        "profile",
        "--lambda",
        "0.1",
        "--load",
        "0",
        "--plot",
        png.to_str().unwrap(),
        "-o",
        "/dev/null",
    ]);
    assert!(o.status.success() && std::fs::metadata(&png).unwrap().len() > 10_000);
    // solve --control radius against the reference curves.
    let rows: Vec<_> = table("curves.csv")
        .into_iter()
        .filter(|r| num(r, "A") > 0.0)
        .take(50)
        .collect();
    let input = dir.path().join("a.csv");
    let mut t = String::from("lambda,A\n");
    for r in &rows {
        t += &format!("{},{}\n", r["lambda"], r["A"]);
    }
    std::fs::write(&input, t).unwrap();
    let o = tabor(&[
        "solve",
        "-i",
        input.to_str().unwrap(),
        "--control",
        "radius",
    ]);
    let out = String::from_utf8(o.stdout).unwrap();
    let mut lines = out.lines();
    assert_eq!(
        lines.next().unwrap(),
        "lambda,A,load,approach,m_minus_1,load_stable,displacement_stable,status"
    );
    for (line, r) in lines.zip(&rows) {
        let f: Vec<&str> = line.split(',').collect();
        let p: f64 = f[2].parse().unwrap();
        assert!(
            (p - num(r, "Pbar")).abs() <= 1e-12 * num(r, "Pbar").abs().max(1.0),
            "{line}"
        );
        assert_eq!(f[7], "ok");
    }
    let o = tabor(&[
        "solve",
        "--lambda",
        "1",
        "--radius-a",
        "1",
        "--format",
        "csv",
    ]);
    assert!(String::from_utf8(o.stdout)
        .unwrap()
        .contains(",-1.5796270206018335e0,"));
}

/// A profile of a scene applies the scene's small-strain check (one function for both): afm-si
/// at 1 kN has a/R = 274 (Hertz, `a = (3 P R / (4 E*))^(1/3)`, adhesion negligible there), far
/// beyond 0.1, and says so on stderr and in the JSON; at 1 nN it does not.
#[test]
fn profile_warns_of_a_contact_too_large_for_small_strain() {
    let o = tabor(&["profile", "--preset", "afm-si", "--load-n", "1e3"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let a = v["models"][0]["a"].as_f64().unwrap();
    let (r, e) = (2e-8, 169e9);
    let e_star = e / (2.0 * (1.0 - 0.27f64 * 0.27));
    let hertz = (3.0 * 1e3 * r / (4.0 * e_star)).cbrt();
    assert!((a / hertz - 1.0).abs() < 1e-3, "{a} vs Hertz {hertz}");
    let want = tabor::physics::params::small_strain_warning(a / r).unwrap();
    assert!(want.starts_with("a/R = 274.0"), "{want}");
    assert_eq!(v["warnings"][0], want.as_str());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(&format!("warning: {want}")), "{err}");
    let o = tabor(&["profile", "--preset", "afm-si", "--load-n", "1e-9"]);
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["warnings"].as_array().unwrap().len(), 0);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("warning"));
}
