//! The pressure and gap of a two-zone state (docs/PHYSICS.md section 10): the pressure written
//! here from the equations, its Gauss-Legendre integral against the load, the gap at each zone's
//! edge against its range, the J-integral against w1 + w2, the MD profile as the second zone
//! vanishes, and the command line's outputs and refusals.

use crate::common;

use common::rel;
use std::f64::consts::PI;
use tabor::physics::fields::MdGeometry;
use tabor::profile::two_zone::{two_zone_profile, TwoZoneProfile};
use tabor::profile::{profile, Given};

const CASES: [(f64, f64, f64); 4] = [
    (1.0, 0.5, 3.0),
    (0.5, 2.0, 0.3),
    (3.0, 0.2, 5.0),
    (0.2, 1.0, 2.0),
];
const GIVEN: [Given; 3] = [Given::Load(0.5), Given::Approach(0.8), Given::Radius(1.2)];

/// Section 10's pressure inside the contact: Hertz plus, for each zone, -s_i over the disc c_i
/// less the part the contact carries, (2 s_i / pi) atan sqrt((a^2 - r^2)/(c_i^2 - a^2)).
fn pressure_inside(p: &TwoZoneProfile, a: f64, r: f64) -> f64 {
    let mut q = 1.5 / PI * ((a - r) * (a + r)).max(0.0).sqrt();
    for i in 0..2 {
        let (s, c) = (p.zone_stress[i], p.zone_edges[i]);
        if s > 0.0 && c > a {
            q += -s
                + 2.0 * s / PI
                    * (((a - r) * (a + r)).max(0.0) / ((c - a) * (c + a)))
                        .sqrt()
                        .atan();
        }
    }
    q
}

fn pressure_at(p: &TwoZoneProfile, a: f64, r: f64) -> f64 {
    if r < a {
        return pressure_inside(p, a, r);
    }
    (0..2)
        .filter(|&i| r <= p.zone_edges[i])
        .map(|i| -p.zone_stress[i])
        .sum()
}

/// Nodes and weights of n-point Gauss-Legendre on [-1, 1] (Newton on P_n).
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (1..=n)
        .map(|k| {
            let mut x = (PI * (k as f64 - 0.25) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for j in 2..=n {
                    let pj = ((2 * j - 1) as f64 * x * p1 - (j - 1) as f64 * p0) / j as f64;
                    (p0, p1) = (p1, pj);
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// The load: 2 pi r p over the contact with r = a sin(theta) (smooth in theta), plus each
/// zone's uniform tension over the annulus a < r < c_i in closed form.
fn load_by_quadrature(p: &TwoZoneProfile, a: f64) -> f64 {
    let gl = gauss_legendre(24);
    let panels = 200;
    let h = 0.5 * PI / panels as f64;
    let mut inside = 0.0;
    for k in 0..panels {
        let mid = (k as f64 + 0.5) * h;
        for &(x, w) in &gl {
            let t = mid + 0.5 * h * x;
            let r = a * t.sin();
            inside += 0.5 * h * w * 2.0 * PI * r * pressure_inside(p, a, r) * a * t.cos();
        }
    }
    let band: f64 = (0..2)
        .filter(|&i| p.zone_edges[i] > a)
        .map(|i| -p.zone_stress[i] * PI * (p.zone_edges[i].powi(2) - a * a))
        .sum();
    inside + band
}

#[test]
fn the_pressure_is_the_equations_and_integrates_to_the_load() {
    for (l, rho, eta) in CASES {
        for g in GIVEN {
            let p = two_zone_profile(l, rho, eta, g, 400).unwrap();
            let m = &p.models[0];
            let a = m.a.unwrap();
            for (&r, q) in m.r.iter().zip(&m.pressure) {
                let want = pressure_at(&p, a, r);
                assert!(
                    (q.unwrap() - want).abs() < 1e-12 * (1.0 + want.abs()),
                    "{l} {rho} {eta} {g:?} r = {r}: {q:?} vs {want}"
                );
            }
            let load = load_by_quadrature(&p, a);
            assert!(
                (load - m.load).abs() < 1e-8 * m.load.abs().max(1.0),
                "{l} {rho} {eta} {g:?}: quadrature {load} vs load {}",
                m.load
            );
        }
    }
}

#[test]
fn the_gap_at_each_edge_is_its_range_and_j_is_the_total_work() {
    for (l, rho, eta) in CASES {
        for g in GIVEN {
            let p = two_zone_profile(l, rho, eta, g, 400).unwrap();
            // The zones carry w1 + w2 = 1 (pi s_i h_i in these units), w2/w1 = rho eta.
            let total =
                PI * (p.zone_stress[0] * p.zone_range[0] + p.zone_stress[1] * p.zone_range[1]);
            assert!(rel(total, 1.0) < 1e-13, "{total}");
            assert!(rel(p.work_share[1], rho * eta / (1.0 + rho * eta)) < 1e-13);
            assert!(rel(p.zone_stress[1] / p.zone_stress[0], rho) < 1e-13);
            assert!(rel(p.zone_range[1] / p.zone_range[0], eta) < 1e-13);
            let m = &p.models[0];
            let mut j = 0.0;
            for i in 0..2 {
                let c = p.zone_edges[i];
                let k = m.r.iter().position(|&r| r == c).expect("c_i sampled");
                assert!(
                    rel(m.gap[k], p.zone_range[i]) < 1e-9,
                    "{l} {rho} {eta} {g:?} zone {i}: gap {} vs range {}",
                    m.gap[k],
                    p.zone_range[i]
                );
                j += PI * p.zone_stress[i] * m.gap[k];
            }
            assert!(rel(j, 1.0) < 1e-9, "J/w = {j}");
            assert!(rel(p.energy_release_rate_over_w, 1.0) < 1e-9);
            // Hertz, DMT and JKR of the total w at the same load.
            let names: Vec<_> = p.models.iter().map(|m| m.model_name()).collect();
            assert_eq!(names, ["two_zone", "hertz", "dmt", "jkr"]);
            assert!(p.models.iter().all(|x| x.load == m.load));
        }
    }
}

#[test]
fn a_vanishing_second_zone_is_the_md_profile() {
    for l in [0.1, 1.0, 5.0] {
        for g in GIVEN {
            let md = profile(l, g, 400).unwrap();
            // rho = 0: the same state and grid.
            let p = two_zone_profile(l, 0.0, 2.0, g, 400).unwrap();
            for (x, y) in p.models.iter().zip(&md.models) {
                assert_eq!(x.r.len(), y.r.len(), "{l} {g:?} {}", y.model);
                for k in 0..x.r.len() {
                    assert!(rel(x.r[k], y.r[k]) < 1e-10);
                    assert!((x.gap[k] - y.gap[k]).abs() < 1e-10 * (1.0 + y.gap[k].abs()));
                    if let (Some(u), Some(v)) = (x.pressure[k], y.pressure[k]) {
                        assert!((u - v).abs() < 1e-10 * (1.0 + v.abs()), "{l} {g:?} {u} {v}");
                    } else {
                        assert_eq!(x.pressure[k].is_some(), y.pressure[k].is_some());
                    }
                }
            }
            // A small rho takes the two-range path: the MD fields on its own grid, the
            // difference linear in rho.
            let (e5, e6) = (md_distance(l, 1e-5, g, &md), md_distance(l, 1e-6, g, &md));
            assert!(e6 < 1e-5 && e6 > 0.0, "{l} {g:?}: {e6}");
            assert!((5.0..20.0).contains(&(e5 / e6)), "{l} {g:?}: {e5} {e6}");
        }
    }
}

/// The largest difference between the two-zone profile at (lambda, rho, eta = 2) and the MD
/// state of the MD profile `md`: contact radius, c1, load, and the fields on the first's grid.
fn md_distance(l: f64, rho: f64, g: Given, md: &tabor::profile::Profile) -> f64 {
    let p = two_zone_profile(l, rho, 2.0, g, 400).unwrap();
    let (m, d) = (&p.models[0], &md.models[0]);
    let (a, c) = (d.a.unwrap(), d.c.unwrap());
    let mm = c / a - 1.0;
    let geo = MdGeometry {
        lambda: l,
        a,
        mu: (mm * (mm + 2.0)).sqrt(),
    };
    let mut e = rel(m.a.unwrap(), a)
        .max(rel(p.zone_edges[0], c))
        .max((m.load - d.load).abs() / (1.0 + d.load.abs()));
    for (k, &r) in m.r.iter().enumerate() {
        // Away from the contact edge (a square root) and the zones' edges (steps), where a
        // small shift of a or c_i is a large change of the fields.
        if p.zone_edges
            .iter()
            .chain([&c, &a])
            .any(|&ci| (r / ci - 1.0).abs() < 1e-3)
        {
            continue;
        }
        e = e.max((m.pressure[k].unwrap() - geo.pressure(r)).abs() / (1.0 + l));
        e = e.max((m.gap[k] - geo.gap(r)).abs() / (1.0 + geo.gap(r)));
    }
    e
}

fn tabor(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args(args)
        .env("TABOR_BACKEND", "cpu")
        .output()
        .unwrap()
}

#[test]
fn the_command_line_prints_the_library_profile() {
    let o = tabor(&[
        "profile",
        "--lambda",
        "1",
        "--stress-ratio",
        "0.5",
        "--range-ratio",
        "3",
        "--load",
        "0.5",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let p = two_zone_profile(1.0, 0.5, 3.0, Given::Load(0.5), 400).unwrap();
    let want = serde_json::to_string_pretty(&p).unwrap() + "\n";
    assert!(String::from_utf8(o.stdout).unwrap() == want);
    let o = tabor(&[
        "profile",
        "--lambda",
        "1",
        "--stress-ratio",
        "0.5",
        "--range-ratio",
        "3",
        "--radius-a",
        "1",
        "--format",
        "csv",
    ]);
    assert!(o.status.success());
    let text = String::from_utf8(o.stdout).unwrap();
    let p = two_zone_profile(1.0, 0.5, 3.0, Given::Radius(1.0), 400).unwrap();
    let rows: Vec<_> = text
        .lines()
        .skip(1)
        .filter(|r| r.starts_with("two_zone,"))
        .collect();
    assert_eq!(rows.len(), p.models[0].r.len());
    let last: Vec<f64> = rows[rows.len() - 1]
        .split(',')
        .skip(1)
        .map(|x| x.parse().unwrap())
        .collect();
    let m = &p.models[0];
    let n = m.r.len() - 1;
    assert_eq!(last, [m.r[n], m.pressure[n].unwrap(), m.gap[n]]);
}

#[test]
fn bad_input_is_one_line() {
    for (args, word) in [
        (
            vec!["--stress-ratio", "-1", "--range-ratio", "3", "--load", "0"],
            "stress ratio",
        ),
        (
            vec!["--stress-ratio", "1", "--range-ratio", "nan", "--load", "0"],
            "range ratio",
        ),
        (
            vec!["--stress-ratio", "1", "--range-ratio", "3", "--load", "-50"],
            "no_contact",
        ),
        (
            vec![
                "--stress-ratio",
                "1",
                "--range-ratio",
                "3",
                "--radius-a",
                "-1",
            ],
            "--radius-a",
        ),
    ] {
        let mut a = vec!["profile", "--lambda", "1"];
        a.extend(args);
        let o = tabor(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && o.stdout.is_empty(), "{a:?}");
        assert_eq!(err.trim().lines().count(), 1, "{a:?}: {err}");
        assert!(err.contains(word) && !err.contains("panic"), "{a:?}: {err}");
    }
    assert!(two_zone_profile(1.0, 1.0, 3.0, Given::Load(0.0), 8).is_err());
}

#[test]
fn solve_gives_the_state_of_the_two_zone_context() {
    use tabor::physics::two_zone::Zones;
    use tabor::solver::two_zone::TwoZoneContext;
    let ctx = TwoZoneContext::new(Zones::from_ratios(0.5, 2.0, 0.3).unwrap()).unwrap();
    for (flag, v) in [
        ("--load", "-0.4"),
        ("--approach", "0.2"),
        ("--radius-a", "0.9"),
    ] {
        let o = tabor(&[
            "solve",
            "--lambda",
            "0.5",
            "--stress-ratio",
            "2",
            "--range-ratio",
            "0.3",
            flag,
            v,
            "--format",
            "csv",
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = String::from_utf8(o.stdout).unwrap();
        let row: Vec<&str> = text.lines().nth(1).unwrap().split(',').collect();
        let x: f64 = v.parse().unwrap();
        let s = match flag {
            "--load" => ctx.state_at_load(x),
            "--approach" => ctx.state_at_approach(x),
            _ => ctx.state_at_radius(x),
        };
        let want = [s.load, s.a, s.approach, s.c[0], s.c[1]];
        for (k, w) in want.iter().enumerate() {
            assert_eq!(row[3 + k].parse::<f64>().unwrap(), *w, "{flag} column {k}");
        }
        assert_eq!(row[8], "ok");
    }
    // Below the pull-off: the status, not numbers.
    let o = tabor(&[
        "solve",
        "--lambda",
        "0.5",
        "--stress-ratio",
        "2",
        "--range-ratio",
        "0.3",
        "--load",
        "-5",
        "--format",
        "json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["status"], "no_contact");
    assert!(v["A"].is_null());
    let o = tabor(&[
        "solve",
        "--lambda",
        "0.5",
        "--stress-ratio",
        "-2",
        "--range-ratio",
        "0.3",
        "--load",
        "0",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.trim().lines().count() == 1 && err.contains("stress ratio"));
}

#[test]
fn a_wet_scene_profile_is_the_scene_state_in_si() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("wet.json");
    let mut scene: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string("examples/si_tip_40rh.json").unwrap())
            .unwrap();
    scene["loads_n"] = serde_json::json!([2e-9]);
    std::fs::write(&path, scene.to_string()).unwrap();
    let f = path.to_str().unwrap();
    let o = tabor(&["scene", f, "--format", "json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let want_a = v["loads"][0]["contact_radius_m"].as_f64().unwrap();
    let o = tabor(&["profile", "--scene", f, "--load-n", "2e-9"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let p: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let m = &p["models"][0];
    assert_eq!(m["model"], "two_zone");
    assert_eq!(p["units"], "SI");
    assert!(rel(m["load"].as_f64().unwrap(), 2e-9) < 1e-12);
    assert!(
        rel(m["a"].as_f64().unwrap(), want_a) < 1e-9,
        "{m:?} {want_a}"
    );
    // In SI, J = sum of stress times the gap at each edge is w1 + w2 = 0.1 + 2 gamma cos(theta).
    let w2 = 2.0 * 0.072 * (20f64).to_radians().cos();
    let (s, h) = (&p["zone_stress"], &p["zone_range"]);
    let w = s[0].as_f64().unwrap() * h[0].as_f64().unwrap()
        + s[1].as_f64().unwrap() * h[1].as_f64().unwrap();
    assert!(rel(w, 0.1 + w2) < 1e-9, "{w} {}", 0.1 + w2);
    assert!(rel(s[0].as_f64().unwrap() * h[0].as_f64().unwrap(), 0.1) < 1e-9);
}

/// The one entry of Python's profile(): the law's own profile, serialised as before, and the
/// law's own refusals.
#[test]
fn the_profile_spec_dispatches_on_the_law() {
    use tabor::profile::spec::ProfileSpec;
    use tabor::ContactLaw;
    fn json<T: serde::Serialize>(v: &T) -> String {
        serde_json::to_string(v).unwrap()
    }
    let given = Given::Load(0.5);
    let md = ProfileSpec {
        law: ContactLaw::new(0.7, None, None).unwrap(),
        given,
        points: 64,
    };
    assert_eq!(
        json(&md.run().unwrap()),
        json(&profile(0.7, given, 64).unwrap())
    );
    let wet = ProfileSpec {
        law: ContactLaw::new(0.7, Some(0.2), Some(5.0)).unwrap(),
        ..md
    };
    assert_eq!(
        json(&wet.run().unwrap()),
        json(&two_zone_profile(0.7, 0.2, 5.0, given, 64).unwrap())
    );
    let few = ProfileSpec { points: 3, ..wet };
    assert!(few.run().unwrap_err().to_string().contains("points 3"));
}
