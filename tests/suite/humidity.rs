//! The two-zone cohesive law (solid + water meniscus, docs/PHYSICS.md section 10): reductions to
//! MD, the rigid and JKR limits, the J-integral and the load balance, each checked against an
//! independent reference (the MD solver and reference tables, closed-form limits, quadrature of
//! the Abel sums that does not use the closed forms of the gaps).

use crate::common;

use common::{num, rel, table};
use std::f64::consts::PI;
use tabor::physics::two_zone::{non_contact_both, non_contact_single, Zones};
use tabor::solver::two_zone::{
    dimensional_zones, state_at_radius_dimensional, TwoZoneContext, TwoZoneState,
};
use tabor::solver::{LambdaContext, Status};

fn ctx(z: Zones) -> TwoZoneContext {
    TwoZoneContext::new(z).expect("context")
}

/// Zones from the solid's lambda and the second zone's stress and range ratios.
fn ratios(lambda: f64, rho: f64, eta: f64) -> TwoZoneContext {
    ctx(Zones::from_ratios(lambda, rho, eta).expect("zones"))
}

fn md_zones(lambda: f64, which: usize) -> Zones {
    let mut l = [0.0; 2];
    let mut h = [0.0; 2];
    l[which] = lambda;
    h[which] = 2.0 / (PI * lambda);
    Zones::new(l, h).unwrap()
}

#[test]
fn either_zone_alone_is_md_against_the_reference_table() {
    let rows = table("pulloff.csv");
    for row in rows.iter().step_by(10) {
        let lambda = num(row, "lambda");
        if !(1e-4..=1e4).contains(&lambda) {
            continue;
        }
        for which in 0..2 {
            let c = ctx(md_zones(lambda, which));
            assert!(
                rel(c.load_pulloff.load, num(row, "Pbar_load")) < 1e-12,
                "lambda {lambda}"
            );
            assert!(
                rel(c.disp_pulloff.load, num(row, "Pbar_disp")) < 1e-12,
                "lambda {lambda}"
            );
            assert!(
                rel(c.load_pulloff.a, num(row, "A_load")) < 1e-8,
                "lambda {lambda}"
            );
        }
    }
}

/// The general two-range path (not the MD shortcut) tends to MD as the second zone's work
/// vanishes, and to MD with the summed stress as the ranges meet.
#[test]
fn two_range_path_tends_to_md_at_both_reductions() {
    for &lambda in &[0.05, 0.5, 2.0, 20.0] {
        let md = LambdaContext::new(lambda).unwrap();
        // A meniscus with a 1e-9 share of the work: the pull-off moves by O(1e-9).
        let c = ratios(lambda, 1e-5, 0.1);
        assert!(matches!(
            c.zones.shape(),
            tabor::physics::two_zone::Shape::Two { .. }
        ));
        assert!(
            rel(c.load_pulloff.load, md.load_pulloff.load) < 1e-5,
            "lambda {lambda}: {} vs {}",
            c.load_pulloff.load,
            md.load_pulloff.load
        );
        let s = c.state_at_radius(1.3);
        let m = md.solve_radius(1.3);
        assert!(
            (s.load - m.load).abs() < 1e-5 && (s.approach - m.approach).abs() < 1e-5,
            "lambda {lambda}: {s:?} vs {m:?}"
        );

        // Equal stress ratio 1 and ranges 1 +- 1e-7 apart: MD with lambda_1 + lambda_2.
        for eta in [1.0 - 1e-7, 1.0 + 1e-7] {
            let c = ratios(lambda, 1.0, eta);
            let sum = c.zones.lambda[0] + c.zones.lambda[1];
            let md = LambdaContext::new(sum).unwrap();
            assert!(
                rel(c.load_pulloff.load, md.load_pulloff.load) < 1e-6,
                "lambda {lambda} eta {eta}: {} vs {}",
                c.load_pulloff.load,
                md.load_pulloff.load
            );
            let s = c.state_at_radius(0.9);
            let m = md.solve_radius(0.9);
            assert!(rel(s.load, m.load) < 1e-6, "{} vs {}", s.load, m.load);
            assert!(rel(s.c[0], 0.9 * (1.0 + m.m_minus_1)) < 1e-5);
        }
    }
}

#[test]
fn equal_ranges_are_md_with_the_summed_stress_exactly() {
    let c = ratios(0.7, 2.5, 1.0);
    let sum = c.zones.lambda[0] + c.zones.lambda[1];
    let md = LambdaContext::new(sum).unwrap();
    assert_eq!(c.load_pulloff.load, md.load_pulloff.load);
    let s = c.state_at_load(0.3);
    let m = md.solve_load(0.3);
    assert_eq!((s.a, s.approach), (m.a, m.approach));
    assert_eq!(s.c[0], s.c[1]);
}

#[test]
fn solid_absent_is_md_with_the_meniscus_stress_and_work_in_si() {
    // A 20 nm silicon tip (K = 4/3 * 85 GPa), meniscus of water at 40% RH, theta = 0.
    let (k, r) = (4.0 / 3.0 * 85e9, 20e-9);
    let r_k = 0.525e-9 / (1.0f64 / 0.4).ln();
    let (s2, h2) = (0.072 / r_k, 2.0 * r_k);
    let w2 = s2 * h2;
    let lambda = 2.0 * s2 * (r / (PI * w2 * k * k)).cbrt();
    let md = LambdaContext::new(lambda).unwrap();
    let rs = (PI * w2 * r * r / k).cbrt();
    let ds = (PI * PI * w2 * w2 * r / (k * k)).cbrt();
    for &a_bar in &[0.2, 0.8, 1.5] {
        let st = state_at_radius_dimensional(k, r, 0.0, 0.0, s2, h2, a_bar * rs).unwrap();
        let m = md.solve_radius(a_bar);
        assert!(rel(st.load, m.load * PI * w2 * r) < 1e-12);
        assert!(rel(st.approach, m.approach * ds) < 1e-12);
        assert!(rel(st.c2, a_bar * (1.0 + m.m_minus_1) * rs) < 1e-12);
        // The solid zone of zero range ends at the contact edge.
        assert_eq!(st.c1, a_bar * rs);
    }
}

#[test]
fn a_zone_without_stress_still_gets_its_radius_where_the_gap_reaches_its_range() {
    // Solid alone (lambda = 1), zone 2 with no stress but range 3 h0: c2 where the MD gap is 3 h0.
    let (k, r, s1, h1) = (1.0, 1.0, 1.0, 0.01);
    let st = state_at_radius_dimensional(k, r, s1, h1, 0.0, 3.0 * h1, 0.05).unwrap();
    // A stress of 1e-6 s1 there moves c2 by O(1e-6).
    let with = state_at_radius_dimensional(k, r, s1, h1, 1e-6 * s1, 3.0 * h1, 0.05).unwrap();
    assert!(st.c2 > 1.2 * st.c1);
    assert!(rel(st.c2, with.c2) < 1e-5, "{} vs {}", st.c2, with.c2);
}

/// Pull-off in units of pi (w1 + w2) R: -2 (rigid, Bradley) and -1.5 (JKR) at the ends.
#[test]
fn rigid_and_jkr_limits_of_the_total_work() {
    for &(rho, eta) in &[(0.3, 4.0), (5.0, 0.2), (0.05, 40.0)] {
        let rigid = ratios(1e-4, rho, eta);
        assert!(
            (rigid.load_pulloff.load + 2.0).abs() < 2e-3,
            "rigid rho {rho} eta {eta}: {}",
            rigid.load_pulloff.load
        );
        let jkr = ratios(1e4, rho, eta);
        assert!(
            (jkr.load_pulloff.load + 1.5).abs() < 1.5e-3,
            "JKR rho {rho} eta {eta}: {}",
            jkr.load_pulloff.load
        );
        // JKR's displacement-controlled jump-out, -5/6.
        assert!((jkr.disp_pulloff.load + 5.0 / 6.0).abs() < 1e-3 * 5.0 / 6.0);
    }
}

/// `int_A^min(r,C) acos(s/r) s/sqrt(C^2-s^2) ds` by Gauss-Legendre after `s = b - (b - A) v^2`
/// (which removes the end-point square roots); independent of the Carlson forms. The radii are
/// given as `A` and the widths `r - A`, `C - A`, so that narrow bands keep their digits.
fn band_quadrature_w(a: f64, dr: f64, dc: f64) -> f64 {
    let db = dr.min(dc);
    if db <= 0.0 {
        return 0.0;
    }
    let (r, c) = (a + dr, a + dc);
    let (x, w) = gauss5();
    let n = 3000;
    let mut sum = 0.0;
    for k in 0..n {
        let (v0, v1) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
        for q in 0..5 {
            let v = 0.5 * (v0 + v1) + 0.5 * (v1 - v0) * x[q];
            let s = a + db * (1.0 - v * v);
            let ds = 2.0 * db * v;
            // r - s and c - s from their parts; acos(s/r) = 2 asin(sqrt((r - s)/(2r))) keeps
            // its digits near s = r.
            let (r_s, c_s) = ((dr - db) + db * v * v, (dc - db) + db * v * v);
            let f = 2.0 * (r_s / (2.0 * r)).sqrt().asin() * s / (c_s * (c + s)).sqrt();
            if f.is_finite() {
                sum += 0.5 * (v1 - v0) * w[q] * f * ds;
            }
        }
    }
    sum
}

fn gauss5() -> ([f64; 5], [f64; 5]) {
    let a = (5.0 - 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0;
    let b = (5.0 + 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0;
    let wa = (322.0 + 13.0 * 70f64.sqrt()) / 900.0;
    let wb = (322.0 - 13.0 * 70f64.sqrt()) / 900.0;
    ([-b, -a, 0.0, a, b], [wb, wa, 128.0 / 225.0, wa, wb])
}

/// The gap at zone j's outer radius of a contact state, Hertz's closed form plus the bands by
/// quadrature.
fn gap_at_zone(z: &Zones, s: &TwoZoneState, j: usize) -> f64 {
    let dr = s.a * s.m_minus_1[j];
    let t = (dr * (2.0 * s.a + dr)).sqrt() / s.a;
    // t - atan(t) by its series where t is small.
    let t_at = if t < 1e-2 {
        t * t * t * (1.0 / 3.0 - t * t / 5.0 + t.powi(4) / 7.0)
    } else {
        t - t.atan()
    };
    let mut h = s.a * s.a / PI * (t * t * t.atan() + t_at);
    for i in 0..2 {
        h += 8.0 * z.lambda[i] / (3.0 * PI) * band_quadrature_w(s.a, dr, s.a * s.m_minus_1[i]);
    }
    h
}

/// The J-integral `sum_i s_i h(c_i)` over w: 1 for every state, with the gaps by quadrature.
#[test]
fn j_integral_is_the_total_work_across_the_branches() {
    for &(lambda, rho, eta) in &[(0.3, 0.5, 6.0), (2.0, 3.0, 0.3), (8.0, 0.2, 12.0)] {
        let c = ratios(lambda, rho, eta);
        let z = c.zones;
        let xs = [
            c.state_at_load(5.0),
            c.state_at_load(0.0),
            c.state_at_load(c.load_pulloff.load + 1e-3),
            // Beyond the load pull-off (unstable under load control).
            c.state_at_radius(0.5 * c.load_pulloff.a),
            c.state_at_radius(0.02),
        ];
        for s in xs {
            assert_eq!(s.status, Status::Ok);
            let j = 0.5
                * PI
                * (z.lambda[0] * gap_at_zone(&z, &s, 0) + z.lambda[1] * gap_at_zone(&z, &s, 1));
            assert!(
                (j - 1.0).abs() < 1e-9,
                "lambda {lambda} A {}: J/w = {j}",
                s.a
            );
            // And each zone's gap condition on its own.
            for i in 0..2 {
                let h = gap_at_zone(&z, &s, i);
                assert!((h / z.range[i] - 1.0).abs() < 1e-9, "zone {i}: {h}");
            }
        }
        // The non-contact branch: discs of tension, the displacement by an Abel sum.
        let end = c.state_at_radius(1e-9);
        let long = if z.range[1] > z.range[0] { 1 } else { 0 };
        let short = 1 - long;
        let states = [
            non_contact_single(&z, 0.3 * end.c[long]),
            non_contact_both(&z, 0.3 * end.c[short]).unwrap(),
            non_contact_both(&z, 0.9 * end.c[short]).unwrap(),
        ];
        for p in states {
            let mut j = 0.0;
            for i in 0..2 {
                if p.c[i] > 0.0 {
                    let mut h = -p.approach + 0.5 * p.c[i] * p.c[i];
                    for k in 0..2 {
                        h -= 8.0 * z.lambda[k] / (3.0 * PI) * disc_abel(p.c[i], p.c[k]);
                    }
                    j += 0.5 * PI * z.lambda[i] * h;
                    assert!((h / z.range[i] - 1.0).abs() < 1e-7, "non-contact zone {i}");
                } else {
                    // A zone not yet engaged: the whole gap is above its range.
                    assert!(p.axis_gap >= z.range[i]);
                }
            }
            if p.c[0] > 0.0 && p.c[1] > 0.0 {
                assert!((j - 1.0).abs() < 1e-7, "non-contact J/w = {j}");
            }
            assert!(p.axis_gap > 0.0);
        }
    }
}

/// `U(r; c) = (pi/2) int_0^c s/sqrt(c^2 - s^2) [r < s ? 1 : (2/pi) asin(s/r)] ds`, with
/// `s = c sin(phi)`, split at s = r.
fn disc_abel(r: f64, c: f64) -> f64 {
    if c <= 0.0 {
        return 0.0;
    }
    let (x, w) = gauss5();
    let split = if r < c { (r / c).asin() } else { 0.5 * PI };
    let mut sum = 0.0;
    for (lo, hi) in [(0.0, split), (split, 0.5 * PI)] {
        let n = 2000;
        for k in 0..n {
            let (p0, p1) = (
                lo + (hi - lo) * k as f64 / n as f64,
                lo + (hi - lo) * (k + 1) as f64 / n as f64,
            );
            for q in 0..5 {
                let phi = 0.5 * (p0 + p1) + 0.5 * (p1 - p0) * x[q];
                let s = c * phi.sin();
                let f = if r < s {
                    1.0
                } else {
                    2.0 / PI * (s / r).min(1.0).asin()
                };
                sum += 0.5 * (p1 - p0) * w[q] * c * phi.sin() * f;
            }
        }
    }
    0.5 * PI * sum
}

/// The non-contact branch ends, where the axis gap closes, at the contact curve's A -> 0 end.
#[test]
fn non_contact_branch_meets_the_contact_curve_at_zero_radius() {
    for &(lambda, rho, eta) in &[(0.3, 0.5, 6.0), (2.0, 3.0, 0.3)] {
        let c = ratios(lambda, rho, eta);
        let z = c.zones;
        let long = if z.range[1] > z.range[0] { 1 } else { 0 };
        let end = c.state_at_radius(1e-10);
        let short = 1 - long;
        let p = non_contact_both(&z, end.c[short]).unwrap();
        assert!(p.axis_gap.abs() < 1e-8, "axis gap {}", p.axis_gap);
        assert!(rel(p.load, end.load) < 1e-8, "{} vs {}", p.load, end.load);
        assert!((p.approach - end.approach).abs() < 1e-8 * end.approach.abs().max(1.0));
        assert!(rel(p.c[long], end.c[long]) < 1e-7);
    }
}

/// `2 pi int p r dr` equals the load: the Hertz and band pressures by Gauss-Legendre in
/// `r = A sin(theta)` inside the contact, the uniform bands outside exactly.
#[test]
fn pressure_integrates_to_the_load() {
    for &(lambda, rho, eta) in &[(0.3, 0.5, 6.0), (2.0, 3.0, 0.3), (1.0, 0.0, 1.0)] {
        let c = ratios(lambda, rho, eta);
        for s in [
            c.state_at_load(2.0),
            c.state_at_load(-0.5),
            c.state_at_radius(0.3),
        ] {
            assert_eq!(s.status, Status::Ok);
            let (x, w) = gauss5();
            let n = 2000;
            let mut inner = 0.0;
            for k in 0..n {
                let (t0, t1) = (
                    0.5 * PI * k as f64 / n as f64,
                    0.5 * PI * (k + 1) as f64 / n as f64,
                );
                for q in 0..5 {
                    let t = 0.5 * (t0 + t1) + 0.5 * (t1 - t0) * x[q];
                    let r = s.a * t.sin();
                    inner += 0.5 * (t1 - t0) * w[q] * c.pressure(&s, r) * r * s.a * t.cos();
                }
            }
            let mut load = 2.0 * PI * inner;
            for i in 0..2 {
                // -lambda_i/2 on A < r < C_i.
                load -= 0.5 * c.zones.lambda[i] * PI * (s.c[i] * s.c[i] - s.a * s.a);
            }
            assert!(
                (load - s.load).abs() < 1e-9 * s.load.abs().max(1.0),
                "{load} vs {}",
                s.load
            );
        }
    }
}

#[test]
fn states_at_load_and_approach_invert_the_curve() {
    let c = ratios(1.5, 0.8, 5.0);
    for &a in &[0.4, 1.0, 2.0] {
        let s = c.state_at_radius(a);
        if s.load_stable {
            let l = c.state_at_load(s.load);
            assert!(rel(l.a, a) < 1e-9, "{} vs {a}", l.a);
        }
        if s.displacement_stable {
            let d = c.state_at_approach(s.approach);
            assert!(rel(d.a, a) < 1e-9);
        }
    }
    assert_eq!(
        c.state_at_load(c.load_pulloff.load - 1e-6).status,
        Status::NoContact
    );
    // The load pull-off is the least load along the stable branch.
    for k in 1..20 {
        let s = c.state_at_radius(c.load_pulloff.a * (1.0 + 0.05 * k as f64));
        assert!(s.load > c.load_pulloff.load);
    }
}

#[test]
fn bad_zones_are_refused_with_one_line() {
    for e in [
        Zones::from_ratios(-1.0, 0.5, 2.0).unwrap_err(),
        Zones::from_ratios(1.0, f64::NAN, 2.0).unwrap_err(),
        Zones::new([1.0, 1.0], [1.0, 1.0]).unwrap_err(),
        dimensional_zones(1.0, 1.0, [0.0, 0.0], [1.0, 1.0]).unwrap_err(),
    ] {
        let m = e.to_string();
        assert!(!m.contains('\n') && !m.is_empty(), "{m}");
    }
}

// Scenes and the command line.

use tabor::scene::humidity::HumidityInput;
use tabor::scene::{contact_of, preset, solve_scene};
use tabor::solver::two_zone::pulloffs_dimensional;

fn tabor_cli(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn wet_scene_is_the_two_zone_law_with_the_kelvin_meniscus() {
    let mut s = preset("afm-si").unwrap();
    s.humidity = Some(HumidityInput::water(0.4, 20.0));
    let r = solve_scene(&s).unwrap();
    let c = contact_of(&s).unwrap();
    // Kelvin: gamma V_m / (R T ln(1/RH)).
    let r_k = 0.072 * 1.8e-5 / (8.314_462_618 * 298.15 * (1.0f64 / 0.4).ln());
    let m = r.meniscus.unwrap();
    assert!(rel(m.kelvin_radius_m, r_k) < 1e-14);
    let cos = (20.0f64).to_radians().cos();
    assert!(rel(m.range_m, 2.0 * r_k * cos) < 1e-14);
    assert!(rel(m.work_of_adhesion_j_m2, 2.0 * 0.072 * cos) < 1e-14);
    let (pl, pd) = pulloffs_dimensional(
        c.k(),
        c.radius,
        [c.s0, 0.072 / r_k],
        [c.work / c.s0, 2.0 * r_k * cos],
    )
    .unwrap();
    assert!(rel(r.pulloff_force_load_control_N, pl) < 1e-12);
    assert!(rel(r.pulloff_force_displacement_control_N, pd) < 1e-12);
    // The dry pull-off is kept and the meniscus pulls harder: near the rigid limit the total
    // is within 10% of 2 pi R (w + 2 gamma cos theta).
    let dry = solve_scene(&preset("afm-si").unwrap()).unwrap();
    assert_eq!(
        r.dry_pulloff_force_load_control_N,
        Some(dry.pulloff_force_load_control_N)
    );
    let rigid = -2.0 * PI * c.radius * (c.work + 2.0 * 0.072 * cos);
    assert!(rel(r.pulloff_force_load_control_N, rigid) < 0.1);
}

#[test]
fn no_meniscus_at_90_degrees_or_zero_humidity_is_the_dry_scene() {
    let dry = solve_scene(&preset("pdms-glass").unwrap()).unwrap();
    for (rh, theta) in [(0.5, 90.0), (0.9, 150.0), (0.0, 10.0)] {
        let mut s = preset("pdms-glass").unwrap();
        s.humidity = Some(HumidityInput::water(rh, theta));
        let r = solve_scene(&s).unwrap();
        assert!(r.meniscus.is_none());
        assert_eq!(
            r.pulloff_force_load_control_N,
            dry.pulloff_force_load_control_N
        );
        assert_eq!(r.zero_load_contact_radius_m, dry.zero_load_contact_radius_m);
    }
}

#[test]
fn bad_humidity_values_are_one_line_and_write_nothing() {
    let dir = std::env::temp_dir().join(format!("tabor-humidity-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (key, value) in [
        ("relative_humidity", "1.2"),
        ("relative_humidity", "-0.1"),
        ("contact_angle_deg", "200"),
        ("surface_tension_n_m", "-0.07"),
        ("temperature_k", "0"),
    ] {
        let mut h = serde_json::json!({"relative_humidity": 0.4, "contact_angle_deg": 20});
        h[key] = serde_json::from_str(value).unwrap();
        let mut scene = serde_json::to_value(preset("afm-si").unwrap()).unwrap();
        scene["humidity"] = h;
        let f = dir.join("scene.json");
        std::fs::write(&f, scene.to_string()).unwrap();
        let out = dir.join("out.json");
        let _ = std::fs::remove_file(&out);
        let o = tabor_cli(&[
            "scene",
            f.to_str().unwrap(),
            "--format",
            "json",
            "-o",
            out.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{key} = {value}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(
            err.contains(key) && err.contains(value.trim_start_matches('-')),
            "{err}"
        );
        assert!(!out.exists());
    }
    let o = tabor_cli(&["humidity", "--preset", "afm-si", "--rh-max", "1"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--rh-max"));
}

#[test]
fn humidity_sweep_of_a_soft_sphere_is_jkr_with_the_summed_work() {
    // PDMS on glass is deep in JKR (lambda ~ 1e4): every RH gives -1.5 pi R (w + 2 gamma cos).
    let o = tabor_cli(&[
        "humidity",
        "--preset",
        "pdms-glass",
        "--contact-angle-deg",
        "30",
        "--rh-min",
        "0.2",
        "--points",
        "4",
        "--format",
        "csv",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8(o.stdout).unwrap();
    let c = contact_of(&preset("pdms-glass").unwrap()).unwrap();
    let w2 = 2.0 * 0.072 * (30.0f64).to_radians().cos();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 4);
    for r in rows {
        let (solid, meniscus, total, share) = (r[4], r[5], r[6], r[7]);
        assert!(
            rel(total, -1.5 * PI * c.radius * (c.work + w2)) < 1e-3,
            "{total}"
        );
        assert!(rel(meniscus, -1.5 * PI * c.radius * w2) < 1e-3);
        assert!(rel(solid, -1.5 * PI * c.radius * c.work) < 1e-3);
        assert!((share - (1.0 - solid / total)).abs() < 1e-12);
    }
}

/// Every pair of zones over six decades of lambda and four of each ratio has both pull-offs,
/// between the rigid (-2) and JKR (-3/2) values of the total work under load control, and its
/// pull-off state meets both gap conditions (checked by quadrature).
#[test]
fn pulloffs_exist_across_the_parameter_plane() {
    let mut worst: f64 = 0.0;
    for &lambda in &[1e-3, 1e-2, 0.1, 1.0, 10.0, 100.0, 1e3] {
        for &rho in &[0.01, 0.1, 1.0, 10.0, 100.0] {
            for &eta in &[0.01, 0.1, 0.5, 2.0, 10.0, 100.0] {
                let c = ratios(lambda, rho, eta);
                let p = c.load_pulloff.load;
                assert!(
                    (-2.0 - 1e-12..=-1.5 + 1e-12).contains(&p),
                    "lambda {lambda} rho {rho} eta {eta}: {p}"
                );
                assert!(c.disp_pulloff.load.is_finite() && c.disp_pulloff.load >= p - 1e-12);
                let s = c.state_at_radius(c.load_pulloff.a.max(1e-6));
                assert_eq!(s.status, Status::Ok, "lambda {lambda} rho {rho} eta {eta}");
                for i in 0..2 {
                    let h = gap_at_zone(&c.zones, &s, i);
                    worst = worst.max((h / c.zones.range[i] - 1.0).abs());
                }
            }
        }
    }
    eprintln!("worst relative error of a gap condition over the plane: {worst:.2e}");
    assert!(worst < 1e-9, "worst gap condition {worst}");
}

#[test]
fn pulloff_command_takes_the_second_zone_as_two_ratios() {
    let csv = |args: &[&str]| -> Vec<f64> {
        let o = tabor_cli(args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let t = String::from_utf8(o.stdout).unwrap();
        let line = t.lines().nth(1).unwrap().to_string();
        line.split(',').map(|v| v.parse().unwrap()).collect()
    };
    // Equal ranges and stresses: MD with twice the solid's stress in the total-w units,
    // lambda_sum = 2 * 0.3 / 2^(1/3).
    let two = csv(&[
        "pulloff",
        "--lambda",
        "0.3",
        "--stress-ratio",
        "1",
        "--range-ratio",
        "1",
        "--format",
        "csv",
    ]);
    let sum = format!("{}", 2.0 * 0.3 / 2f64.cbrt());
    let md = csv(&["pulloff", "--lambda", &sum, "--format", "csv"]);
    assert!(rel(two[3], md[1]) < 1e-14, "{} vs {}", two[3], md[1]);
    assert!(rel(two[6], md[4]) < 1e-14);
    // A meniscus: between the limits, and below the solid's own pull-off in pi (w1 + w2) R.
    let wet = csv(&[
        "pulloff",
        "--lambda",
        "2",
        "--stress-ratio",
        "0.2",
        "--range-ratio",
        "8",
        "--format",
        "csv",
    ]);
    assert!(wet[3] > -2.0 && wet[3] < -1.5);
    let o = tabor_cli(&["pulloff", "--lambda", "1", "--stress-ratio", "0.5"]);
    assert_eq!(o.status.code(), Some(1));
}

/// A pull-off measured in humid air, made with a known solid w by the two-zone law, gives that
/// w back with the meniscus taken out; where the meniscus alone pulls off harder than measured
/// there is no solid w to report, and without a meniscus the wet inference refuses.
#[test]
fn infer_takes_the_meniscus_out_of_a_wet_pull_off() {
    use tabor::physics::params::{Contact, ForceRange};
    use tabor::scene::humidity::{wet_context, HumidityInput};
    let (r, e_star, z0) = (20e-9, 91.1444e9, 0.3e-9);
    let h = HumidityInput::water(0.4, 20.0);
    for w1 in [0.02, 0.1, 0.5] {
        let c = Contact::new(r, e_star, w1, ForceRange::LennardJones(z0)).unwrap();
        let m = h.meniscus(&c).unwrap().unwrap();
        let (ctx, u) = wet_context(&c, &m).unwrap();
        let f = ctx.load_pulloff.load * u.load; // negative, as measured
        let got = tabor::scene::infer_wet(f, r, e_star, z0, &h).unwrap();
        let w = got.solid_work_of_adhesion_j_m2.unwrap();
        assert!(rel(w, w1) < 1e-8, "w1 {w1}: got {w}");
        // A dry analysis of the same force credits the solid with the meniscus' work.
        let wm = got.meniscus.unwrap().work_of_adhesion_j_m2;
        assert!(
            got.dry_md_work_of_adhesion_j_m2.unwrap() > w1 + 0.5 * wm,
            "{got:?}"
        );
        assert!(got.meniscus_only_pulloff_n < f.abs());
    }
    let c = Contact::new(r, e_star, 0.1, ForceRange::LennardJones(z0)).unwrap();
    let m = h.meniscus(&c).unwrap().unwrap();
    let weak = 0.5 * 4.0 * PI * r * 0.072 * 20f64.to_radians().cos(); // half the rigid meniscus
    let got = tabor::scene::infer_wet(weak, r, e_star, z0, &h).unwrap();
    assert!(got.solid_work_of_adhesion_j_m2.is_none());
    assert!(
        got.verdict.contains("the meniscus alone pulls off"),
        "{}",
        got.verdict
    );
    // A larger contact angle weakens the meniscus: that is the advice (as `fit` gives it).
    assert!(
        got.verdict
            .contains("a larger contact angle or a lower humidity than given"),
        "{}",
        got.verdict
    );
    assert_eq!(got.meniscus, Some(m));
    let e = tabor::scene::infer_wet(-20e-9, r, e_star, z0, &HumidityInput::water(0.0, 20.0))
        .unwrap_err()
        .to_string();
    assert!(e.contains("no meniscus forms"), "{e}");
}

/// `tabor infer --relative-humidity`: the silicon tip of the README at 40% RH, whose wet scene
/// pulls off at 28.8155 nN with w = 0.1 J/m^2, gives that w back; a bad RH is one line.
#[test]
fn infer_on_the_command_line_takes_the_meniscus_out() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "infer",
            "--pulloff",
            "-28.8155e-9",
            "--radius",
            "20e-9",
            "--e-star",
            "91.1444e9",
            "--contact-angle-deg",
            "20",
            "--format",
            "json",
        ];
        args.extend_from_slice(extra);
        std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
            .args(&args)
            .output()
            .unwrap()
    };
    let out = run(&["--relative-humidity", "0.4"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let w = j["solid_work_of_adhesion_j_m2"].as_f64().unwrap();
    assert!(rel(w, 0.1) < 1e-5, "{w}");
    let out = run(&["--relative-humidity", "1.5"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("--relative-humidity = 1.5"), "{err}");
}

/// `tabor scene --plot` of a wet scene: a PNG, drawn from the a(P) of solid and meniscus (each
/// point's load found again from its radius by the dimensional two-zone solver) beside the dry
/// MD curve from the dry pull-off.
#[test]
fn wet_scene_plot_draws_solid_and_meniscus_beside_the_dry_curve() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/si_tip_40rh.json");
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("wet.png");
    let svg = dir.path().join("wet.svg");
    let text = dir.path().join("wet.txt");
    let o = tabor_cli(&[
        "scene",
        file,
        "--plot",
        png.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
        "-o",
        text.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    assert!(bytes.len() > 20_000, "{} bytes", bytes.len());
    let svg = std::fs::read_to_string(&svg).unwrap();
    assert!(svg.contains("solid + meniscus") && svg.contains("dry: Maugis-Dugdale"));
    // The figure's numbers.
    let s: tabor::scene::SceneInput =
        serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
    let r = solve_scene(&s).unwrap();
    let fig = tabor::figure_data::scene_data(&r).unwrap();
    let wet = fig.wet.as_ref().unwrap();
    let c = contact_of(&s).unwrap();
    let m = r.meniscus.unwrap();
    assert!(wet.len() > 250);
    for &(p, a) in wet.iter().step_by(10) {
        let st = state_at_radius_dimensional(
            c.k(),
            c.radius,
            c.s0,
            c.work / c.s0,
            m.laplace_pressure_pa,
            m.range_m,
            a,
        )
        .unwrap();
        assert!((st.load - p).abs() < 1e-9 * p.abs().max(1e-9), "{p} {a}");
    }
    // From the wet pull-off (the first point, or within the first step) and the dry pull-off.
    let dry = r.dry_pulloff_force_load_control_N.unwrap();
    let pc = r.pulloff_force_load_control_N;
    assert!(wet[0].0 < 0.99 * pc && wet[0].0 >= pc, "{:?}", wet[0]);
    assert!(fig.md[0].0 >= dry && fig.md[0].0 < 0.99 * dry);
}

/// `tabor solve --input FILE --stress-ratio --range-ratio`: each row of the table is the
/// single-state form's row, byte for byte, under load, approach and radius; the JSON rows carry
/// the same numbers; a row below the pull-off keeps its load and says no_contact.
#[test]
fn solve_table_of_two_zone_points_equals_the_single_state_form() {
    let dir = tempfile::tempdir().unwrap();
    let rows: [(f64, f64); 7] = [
        (0.5, 0.2),
        (0.5, -5.0),
        (2.0, 1.0),
        (0.1, 0.0),
        (0.5, 3.0),
        (10.0, -1.0),
        (0.03, 0.5),
    ];
    for (control, column, flag) in [
        ("load", "load", "--load"),
        ("displacement", "approach", "--approach"),
        ("radius", "A", "--radius-a"),
    ] {
        let file = dir.path().join(format!("{control}.csv"));
        let mut t = format!("lambda,{column}\n");
        let pts: Vec<(f64, f64)> = rows
            .iter()
            .map(|&(l, v)| {
                (
                    l,
                    if control == "radius" {
                        v.abs() + 0.3
                    } else {
                        v
                    },
                )
            })
            .collect();
        for (l, v) in &pts {
            t += &format!("{l},{v}\n");
        }
        std::fs::write(&file, t).unwrap();
        let table = |format: &str| {
            let o = tabor_cli(&[
                "solve",
                "-i",
                file.to_str().unwrap(),
                "--control",
                control,
                "--stress-ratio",
                "0.3",
                "--range-ratio",
                "3",
                "--format",
                format,
            ]);
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
            String::from_utf8(o.stdout).unwrap()
        };
        let csv = table("csv");
        let json: serde_json::Value = serde_json::from_str(&table("json")).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), pts.len() + 1);
        for (k, (l, v)) in pts.iter().enumerate() {
            let (ls, vs) = (l.to_string(), v.to_string());
            let one = |format: &str| {
                let o = tabor_cli(&[
                    "solve",
                    "--lambda",
                    &ls,
                    &format!("{flag}={vs}"),
                    "--stress-ratio",
                    "0.3",
                    "--range-ratio",
                    "3",
                    "--format",
                    format,
                ]);
                assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
                String::from_utf8(o.stdout).unwrap()
            };
            let single = one("csv");
            assert_eq!(lines[0], single.lines().next().unwrap());
            assert_eq!(
                lines[k + 1],
                single.lines().nth(1).unwrap(),
                "{control} row {k}"
            );
            let want: serde_json::Value = serde_json::from_str(&one("json")).unwrap();
            assert_eq!(json["results"][k], want, "{control} row {k}");
        }
        if control == "load" {
            // Below the pull-off (Pbar_c in [-2, -3/2]): no contact, the load kept.
            assert!(lines[2].ends_with("no_contact"), "{}", lines[2]);
            assert_eq!(json["results"][1]["load"].as_f64(), Some(-5.0));
            assert_eq!(json["metadata"]["points"].as_u64(), Some(pts.len() as u64));
        }
    }
    // Bad ratios: one line before anything is written.
    let out = dir.path().join("out.csv");
    let o = tabor_cli(&[
        "solve",
        "-i",
        dir.path().join("load.csv").to_str().unwrap(),
        "--stress-ratio",
        "-1",
        "--range-ratio",
        "3",
        "-o",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1));
    assert!(err.contains("stress ratio = -1"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(!out.exists());
}

/// Below one molecule's Kelvin radius (RH_mol = exp(-gamma V_m / (R T d)), d = (V_m/N_A)^(1/3),
/// docs/PHYSICS.md section 10) no meniscus is counted: at RH = 1e-10 the scene, the sweep and
/// `infer` give the dry contact's numbers exactly, and each says why; just above RH_mol the
/// meniscus is there.
#[test]
fn below_one_molecule_no_meniscus_is_counted_and_every_front_end_says_so() {
    let d = (1.8e-5f64 / 6.022_140_76e23).cbrt();
    let rh_mol = (-0.072 * 1.8e-5 / (8.314_462_618 * 298.15 * d)).exp();
    let h = HumidityInput::water(0.4, 20.0);
    assert!(rel(h.molecule_size(), d) < 1e-15 && rel(h.molecular_rh(), rh_mol) < 1e-14);
    assert!((rh_mol - 0.1855).abs() < 1e-3, "{rh_mol}");
    let dry = solve_scene(&preset("afm-si").unwrap()).unwrap();
    let mut s = preset("afm-si").unwrap();
    for (rh, counted) in [
        (1e-10, false),
        (0.999 * rh_mol, false),
        (1.001 * rh_mol, true),
    ] {
        s.humidity = Some(HumidityInput::water(rh, 20.0));
        let r = solve_scene(&s).unwrap();
        assert_eq!(r.meniscus.is_some(), counted, "RH {rh}");
        let below = r
            .meniscus_warnings
            .iter()
            .any(|w| w.contains("below one molecule of the liquid (0.310 nm"));
        assert_eq!(below, !counted, "{:?}", r.meniscus_warnings);
        if !counted {
            assert_eq!(
                r.pulloff_force_load_control_N,
                dry.pulloff_force_load_control_N
            );
            assert!(r.no_meniscus.unwrap().contains("below one molecule"));
        }
    }
    // The command line: scene text, the sweep and infer give the same warning.
    let dir = std::env::temp_dir().join(format!("tabor-molecule-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("dry_air.json");
    let mut j = serde_json::to_value(preset("afm-si").unwrap()).unwrap();
    j["humidity"] = serde_json::json!({"relative_humidity": 1e-10, "contact_angle_deg": 20});
    std::fs::write(&f, j.to_string()).unwrap();
    let o = tabor_cli(&["scene", f.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success());
    assert!(
        text.contains("  RH = 1e-10: no meniscus: the dry contact\n")
            && text.contains("  warning: the Kelvin radius 0.023 nm at RH = 1e-10 is below one molecule of the liquid (0.310 nm, reached at RH = 0.186): no continuum meniscus, so none is counted"),
        "{text}"
    );
    let o = tabor_cli(&["humidity", "--preset", "afm-si", "--format", "json"]);
    let sweep: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let pts = sweep["points"].as_array().unwrap();
    for p in pts {
        let counted = p["relative_humidity"].as_f64().unwrap() >= rh_mol;
        assert_eq!(!p["meniscus_lambda"].is_null(), counted, "{p}");
        if !counted {
            assert_eq!(p["pulloff_total_N"], p["pulloff_solid_N"]);
            assert_eq!(p["pulloff_meniscus_N"].as_f64(), Some(0.0));
        }
    }
    let warnings = sweep["warnings"].as_array().unwrap();
    assert!(
        warnings[0].as_str().unwrap().starts_with(
            "below RH = 0.186 the Kelvin radius is below one molecule of the liquid (0.310 nm): no continuum meniscus, so none is counted at 3 of the 19 points (RH = 0.05 to 0.15)"
        ),
        "{warnings:?}"
    );
    // The bisection finds where the meniscus starts to dominate: at RH_mol itself.
    let above = sweep["meniscus_dominates_above_rh"].as_f64().unwrap();
    assert!((above - rh_mol).abs() < 1e-6, "{above}");
    let infer = |rh: &str| {
        let mut a = vec![
            "infer",
            "--pulloff",
            "-28.8155e-9",
            "--radius",
            "20e-9",
            "--e-star",
            "91.1444e9",
        ];
        if !rh.is_empty() {
            a.extend(["--relative-humidity", rh, "--contact-angle-deg", "20"]);
        }
        a.extend(["--format", "json"]);
        let o = tabor_cli(&a);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        serde_json::from_slice::<serde_json::Value>(&o.stdout).unwrap()
    };
    let (wet, dry) = (infer("1e-10"), infer(""));
    assert_eq!(wet["solid_work_of_adhesion_j_m2"], dry["w_md_j_m2"]);
    assert!(wet["meniscus"].is_null());
    assert!(wet["warnings"][0]
        .as_str()
        .unwrap()
        .contains("below one molecule of the liquid"));
}

/// Near saturation: `tabor humidity` warns where the meniscus height exceeds a tenth of R, as
/// `scene` does; a humidity beyond the solver's reach is refused naming the value given.
#[test]
fn flooding_warning_and_saturation_refusal_name_the_humidity() {
    let o = tabor_cli(&[
        "humidity",
        "--preset",
        "afm-si",
        "--contact-angle-deg",
        "20",
    ]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success());
    // 2 r_K cos(theta) = 0.1 R at RH = 0.612 for R = 20 nm: the points 0.65..0.95.
    assert!(
        text.contains("warning: the meniscus height 2 r_K cos(theta) exceeds 10% of R (up to 96%) at 7 of the 19 points (RH = 0.65 to 0.95)"),
        "{text}"
    );
    let mut s = preset("afm-si").unwrap();
    s.humidity = Some(HumidityInput::water(0.95, 20.0));
    let r = solve_scene(&s).unwrap();
    assert!(
        r.meniscus_warnings[0].starts_with(
            "the meniscus height 2 r_K cos(theta) = 1.916e-8 m at RH = 0.95 is 96% of R"
        ),
        "{:?}",
        r.meniscus_warnings
    );
    s.humidity = Some(HumidityInput::water(0.9999999, 20.0));
    let e = solve_scene(&s).unwrap_err().to_string();
    assert!(
        e.starts_with("humidity.relative_humidity = 0.9999999: the meniscus (Kelvin radius")
            && e.contains("give a relative humidity below 0.99"),
        "{e}"
    );
    let o = tabor_cli(&["humidity", "--preset", "afm-si", "--rh-max", "0.9999999"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("--rh-max = 0.9999999: the meniscus"), "{err}");
    // An extreme liquid names the liquid's values.
    let mut h = HumidityInput::water(0.5, 20.0);
    h.surface_tension_n_m = Some(1e30);
    s.humidity = Some(h);
    let e = solve_scene(&s).unwrap_err().to_string();
    assert!(
        e.starts_with(
            "humidity (relative humidity 0.5, contact angle 20 deg, surface tension 1e30 N/m"
        ) && e.contains("check the liquid's values"),
        "{e}"
    );
}

/// `tabor infer` of an implausible force: the plausible ranges of `tabor fit`, no "Trust".
#[test]
fn infer_bounds_w_as_fit_does() {
    let r = tabor::scene::infer(1.0, 20e-9, 91.1444e9, 0.3e-9).unwrap();
    assert!(!r.verdict.contains("Trust"), "{}", r.verdict);
    assert!(
        r.verdict
            .starts_with("no w to trust: E* = 9.11444e10 Pa (plausible 10..1e12 Pa), w = ")
            && r.verdict
                .contains("(plausible up to 10 J/m^2): outside physical sense"),
        "{}",
        r.verdict
    );
    assert_eq!(r.warnings.len(), 1);
    let o = tabor_cli(&[
        "infer",
        "--pulloff",
        "1",
        "--radius",
        "20e-9",
        "--e-star",
        "91.1444e9",
    ]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("warning: E* = 9.11444e10 Pa"));
    // A plausible force has no warning.
    let r = tabor::scene::infer(-12.2e-9, 20e-9, 91.1444e9, 0.3e-9).unwrap();
    assert!(
        r.warnings.is_empty() && r.verdict.contains("Trust"),
        "{}",
        r.verdict
    );
}

/// A wet scene under a cantilever and its cycle name the w their kbar is built on: the total w
/// of solid and meniscus, the same number in both; a dry scene says the solid's.
#[test]
fn scene_and_cycle_label_the_w_of_their_kbar() {
    let dir = std::env::temp_dir().join(format!("tabor-kbar-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("wet_k.json");
    let mut j: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string("examples/si_tip_40rh.json").unwrap())
            .unwrap();
    j["control"] = serde_json::json!({"cantilever_n_m": 2.0});
    std::fs::write(&f, j.to_string()).unwrap();
    let mut s: tabor::scene::SceneInput = serde_json::from_value(j.clone()).unwrap();
    let r = solve_scene(&s).unwrap();
    let c = contact_of(&s).unwrap();
    let m = r.meniscus.unwrap();
    let (_, _, u) = tabor::scene::humidity::wet_ratios(&c, &m).unwrap();
    let label = format!(
        "kbar = {:.4e} in the units of the total w (solid and meniscus)",
        2.0 * u.approach / u.load
    );
    assert!(r.control.ends_with(&label), "{} / {label}", r.control);
    let o = tabor_cli(&[
        "cycle",
        "--scene",
        f.to_str().unwrap(),
        "--control",
        "spring",
        "--spring-n-m",
        "2",
        "-o",
        dir.join("c.csv").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success() && err.contains(&label), "{err}");
    s.humidity = None;
    let r = solve_scene(&s).unwrap();
    let kbar = tabor::cycle::normalised_stiffness(2.0, &c);
    assert!(
        r.control
            .ends_with(&format!("kbar = {kbar:.4e} in the units of the solid's w")),
        "{}",
        r.control
    );
}

/// `tabor profile --scene` of a wet scene prints a summary line as the dry scene does.
#[test]
fn wet_profile_prints_its_summary() {
    let o = tabor_cli(&[
        "profile",
        "--scene",
        "examples/si_tip_40rh.json",
        "--load-n",
        "0",
        "-o",
        std::env::temp_dir()
            .join("tabor-wet-profile.csv")
            .to_str()
            .unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("(solid), meniscus lambda = 0.0371")
            && err.contains("zone edges c1 = ")
            && err.contains("J/(w1 + w2) = 1.0000000000"),
        "{err}"
    );
}
