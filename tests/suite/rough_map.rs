//! The rough adhesion map (`tabor rough-map`) against `tabor rough`'s statistical path, the
//! smooth limit, the closed-form summit models computed here, and its refusals and outputs.

use tabor::map::Region;
use tabor::rough::map::{compute, jkr_table, BranchTable, RoughMapSpec};
use tabor::rough::{Leg, Rough, Summit};

fn spec(l: (f64, f64, usize), s: (f64, f64, usize)) -> RoughMapSpec {
    RoughMapSpec {
        lambda_min: l.0,
        lambda_max: l.1,
        nx: l.2,
        sigma_min: s.0,
        sigma_max: s.1,
        ny: s.2,
        tolerance: 0.05,
        press_sigmas: 3.0,
    }
}

#[test]
fn map_pulloffs_are_the_statistical_pulloffs() {
    let m = compute(&spec((0.1, 100.0, 4), (0.05, 5.0, 4)), 16).unwrap();
    for (i, (&pc, &sep)) in m.pulloff.iter().zip(&m.pulloff_separation).enumerate() {
        let (ix, iy) = (i % 4, i / 4);
        let (lambda, sigma) = (m.lambdas[ix], m.sigmas[iy]);
        let r = Rough::new(lambda, sigma).unwrap();
        // tabor rough's pull-off: its own samples and golden section, adaptive quadrature.
        let (d, want) = r.pulloff_after(-3.0 * sigma, 48).unwrap();
        let scale = want.abs().max(1e-3 * m.smooth_pulloff[ix].abs());
        assert!(
            (pc - want).abs() <= 1e-6 * scale,
            "lambda {lambda}, sigma {sigma}: map {pc} at {sep}, rough {want} at {d}"
        );
        // The ratio is that pull-off over the smooth summit's.
        let smooth = Summit::new(lambda).unwrap();
        let pcs = tabor::solver::LambdaContext::new(lambda)
            .unwrap()
            .load_pulloff
            .load;
        assert!(smooth.lambda == lambda && (m.relative_pulloff[i] - pc / pcs).abs() < 1e-15);
    }
    assert_eq!(m.check.points, 16);
    assert!(
        m.check.max_relative_difference < 1e-6,
        "check {:?}",
        m.check
    );
}

#[test]
fn vanishing_roughness_keeps_the_smooth_pulloff() {
    let m = compute(&spec((0.05, 50.0, 5), (1e-5, 1e-4, 2)), 0).unwrap();
    for ix in 0..5 {
        let r = m.relative_pulloff[ix];
        assert!(
            (r - 1.0).abs() < 1e-6,
            "lambda {}: ratio {r} at sigma 1e-5",
            m.lambdas[ix]
        );
    }
}

/// The interpolation error of the per-lambda table, measured here at points off its nodes and
/// midpoints against exact solves, is within twice the error it reports.
#[test]
fn table_error_is_bounded_by_its_estimate() {
    for lambda in [0.05, 0.5, 3.0, 100.0] {
        let s = Summit::new(lambda).unwrap();
        let t = BranchTable::new(s.delta_out, 400.0, |d| s.contact(d).map(|c| c.0)).unwrap();
        assert!(t.error < 1e-6, "lambda {lambda}: table error {:e}", t.error);
        let mut worst: f64 = 0.0;
        for k in 0..300 {
            // Irrational steps: never a node.
            let u = (k as f64 * 0.0671_f64.sqrt()).fract() * 20.0 + 1e-3 * k as f64;
            let delta = s.delta_out + u * u;
            let exact = s.contact(delta).unwrap().0;
            worst = worst.max((t.load_or(delta, Some(&s)) - exact).abs() / exact.abs().max(1.0));
        }
        assert!(
            worst <= 2.0 * t.error,
            "lambda {lambda}: {worst:e} against the estimate {:e}",
            t.error
        );
    }
    // JKR's table against its closed forms.
    let t = jkr_table(400.0);
    for a in [0.56, 0.6, 1.0, 2.0, 7.0, 19.0] {
        let (p, d) = (
            tabor::physics::closed::jkr_load(a),
            tabor::physics::closed::jkr_approach(a),
        );
        assert!((t.load(d) - p).abs() <= 2.0 * t.error * p.abs().max(1.0) + 1e-12);
    }
}

/// Near lambda_D the branch turns within a tiny range of approaches and the table misses its
/// target next to the fold; the finer table of that stretch (`refine_fold`) is then
/// interpolated instead of solving there exactly, and it too stays within twice the error
/// reported, at points off its nodes.
#[test]
fn fold_stretch_table_is_within_its_estimate() {
    for lambda in [0.75, 0.93] {
        let s = Summit::new(lambda).unwrap();
        let exact_load = |d: f64| s.contact(d).map(|c| c.0);
        let mut t = BranchTable::new(s.delta_out, 400.0, exact_load).unwrap();
        let before = t.exact_below;
        assert!(
            before > 0.0,
            "lambda {lambda}: the table meets its target at the fold"
        );
        t.refine_fold(exact_load);
        assert!(
            t.exact_below < 0.1 * before && t.error < 1e-6,
            "lambda {lambda}: exact below {} (before {before}), error {:e}",
            t.exact_below,
            t.error
        );
        let mut worst: f64 = 0.0;
        for k in 0..400 {
            let u = ((k as f64 + 0.5) * 0.0671_f64.sqrt()).fract() * 0.2;
            let delta = s.delta_out + u * u;
            let exact = exact_load(delta).unwrap();
            worst = worst.max((t.load_or(delta, Some(&s)) - exact).abs() / exact.abs().max(1.0));
        }
        assert!(
            worst <= 2.0 * t.error,
            "lambda {lambda}: {worst:e} against the estimate {:e}",
            t.error
        );
    }
}

/// Fuller and Tabor's JKR summits, computed here by bisection on JKR's closed forms and a
/// composite Simpson quadrature in the height, split at the jump-out.
fn jkr_rough(sigma: f64, d_min: f64, d: f64) -> f64 {
    jkr_rough_n(sigma, d_min, d, 4000)
}

/// [`jkr_rough`] with `n` Simpson intervals.
fn jkr_rough_n(sigma: f64, d_min: f64, d: f64, n: usize) -> f64 {
    let a_out = 6f64.powf(-1.0 / 3.0);
    let d_out = tabor::physics::closed::jkr_approach(a_out);
    let load = |delta: f64| {
        let (mut lo, mut hi) = (a_out, 1e3);
        for _ in 0..100 {
            let m = 0.5 * (lo + hi);
            if tabor::physics::closed::jkr_approach(m) < delta {
                lo = m
            } else {
                hi = m
            }
        }
        tabor::physics::closed::jkr_load(0.5 * (lo + hi))
    };
    // Touched summits (z >= d_min) in contact down to the jump-out: z >= d + d_out.
    let lo = d_min.max(d + d_out);
    let hi = 12.0 * sigma;
    if hi <= lo {
        return 0.0;
    }
    // t = sqrt(z - lo) takes out the fold's square root.
    let h = (hi - lo).sqrt() / n as f64;
    let f = |t: f64| {
        let z = lo + t * t;
        let phi =
            (-0.5 * (z / sigma).powi(2)).exp() / ((2.0 * std::f64::consts::PI).sqrt() * sigma);
        2.0 * t * phi * load(z - d)
    };
    let mut s = f(0.0) + f(n as f64 * h);
    for k in 1..n {
        s += f(k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}

#[test]
fn jkr_side_is_fuller_and_tabor() {
    // lambda 1e4: the MD summits are JKR's to about 1e-3 in the pull-off.
    let m = compute(&spec((1e4, 2e4, 2), (0.1, 1.0, 3)), 0).unwrap();
    for iy in 0..3 {
        let sigma = m.sigmas[iy];
        let i = iy * 2;
        let d_min = -3.0 * sigma;
        // Fuller and Tabor's minimum by golden section around the map's separation.
        let (mut a, mut b) = (m.pulloff_separation[i] - 0.2, m.pulloff_separation[i] + 0.2);
        for _ in 0..60 {
            let (x, y) = (b - 0.618 * (b - a), a + 0.618 * (b - a));
            if jkr_rough(sigma, d_min, x) < jkr_rough(sigma, d_min, y) {
                b = y
            } else {
                a = x
            }
        }
        let ft = jkr_rough(sigma, d_min, 0.5 * (a + b));
        let smooth = m.smooth_pulloff[0];
        // MD at lambda 1e4 against JKR: the smooth pull-offs differ by |Pbar_c + 1.5|, and a
        // summit enters and leaves contact within the Dugdale range h0 of JKR's approaches,
        // which moves a fraction of about h0 / sigma of the summits (loads of order one).
        let h0 = 2.0 / (std::f64::consts::PI * m.lambdas[0]);
        let md_jkr = 3.0 * (smooth + 1.5).abs() + h0 / sigma;
        println!("sigma {sigma}: map {} Fuller-Tabor {ft}", m.pulloff[i]);
        assert!(
            (m.pulloff[i] - ft).abs() <= md_jkr,
            "sigma {sigma}: map {} against Fuller-Tabor {ft} (MD-JKR {md_jkr:e})",
            m.pulloff[i]
        );
        // JKR is adequate there (or Hertz, where the surface no longer sticks).
        assert!(
            matches!(m.regions[i], Region::Jkr | Region::Hertz),
            "sigma {sigma}: {:?}",
            m.regions[i]
        );
        assert!(m.model_error[i][3] <= 0.05 || m.regions[i] == Region::Hertz);
    }
}

/// At small sigma the rough retract rises steeply within a few sigma of each model's jump-out,
/// a stretch uniform samples alone hit or missed as lambda moved their grid: JKR was accepted at
/// isolated points inside the MD region (a border drawn as one-pixel spikes, up to five region
/// changes along one lambda column). Every point the map gives to JKR must pass a dense check of
/// the whole retract curve (the MD summits by `tabor rough`'s adaptive quadrature, Fuller and
/// Tabor's JKR summits computed here), and each column changes region at most once.
#[test]
fn small_sigma_mdjkr_border_is_a_curve() {
    let (nx, ny) = (8, 12);
    let m = compute(&spec((3.0, 6.0, nx), (0.01, 0.3, ny)), 0).unwrap();
    let d_out_jkr = tabor::physics::closed::jkr_approach(6f64.powf(-1.0 / 3.0));
    let mut jkr_points = 0;
    for ix in 0..nx {
        let column: Vec<Region> = (0..ny).map(|iy| m.regions[iy * nx + ix]).collect();
        let changes = column.windows(2).filter(|w| w[0] != w[1]).count();
        assert!(changes <= 1, "lambda {}: {column:?}", m.lambdas[ix]);
        for iy in 0..ny {
            if column[iy] != Region::Jkr {
                continue;
            }
            jkr_points += 1;
            let (lambda, sigma) = (m.lambdas[ix], m.sigmas[iy]);
            let r = Rough::new(lambda, sigma).unwrap();
            let d_min = -3.0 * sigma;
            let md_out = Summit::new(lambda).unwrap().delta_out;
            let d_hi = (-d_out_jkr).max(-md_out) + 6.0 * sigma;
            let (mut worst, mut scale) = (0.0f64, 0.0f64);
            for k in 0..=120 {
                let d = d_min + (d_hi - d_min) * k as f64 / 120.0;
                let md = r.mean(Leg::Retract { d_min }, d).unwrap().load;
                let jkr = jkr_rough_n(sigma, d_min, d, 400);
                worst = worst.max((md - jkr).abs());
                scale = scale.max(md.abs());
            }
            assert!(
                worst <= 1.02 * 0.05 * scale,
                "lambda {lambda}, sigma {sigma}: JKR on the map, but its retract differs by {} of the MD curve's largest load",
                worst / scale
            );
        }
    }
    assert!(jkr_points > 0 && jkr_points < nx * ny, "{:?}", m.regions);
}

/// DMT summits (Maugis 1996): delta^(3/2) - 2 in contact, the rigid sphere's Dugdale attraction
/// -2 (1 + delta/h0) at a gap, no hysteresis; their rough retract computed here.
fn dmt_rough(lambda: f64, sigma: f64, d: f64) -> f64 {
    let h0 = 2.0 / (std::f64::consts::PI * lambda);
    let f = |z: f64| {
        let delta = z - d;
        let p = if delta >= 0.0 {
            delta.powf(1.5) - 2.0
        } else if delta >= -h0 {
            -2.0 * (1.0 + delta / h0)
        } else {
            0.0
        };
        (-0.5 * (z / sigma).powi(2)).exp() / ((2.0 * std::f64::consts::PI).sqrt() * sigma) * p
    };
    // Composite Simpson split at the kinks delta = -h0 and delta = 0.
    let cuts = [-12.0 * sigma, d - h0, d, 12.0 * sigma];
    let mut total = 0.0;
    for w in cuts.windows(2) {
        let (a, b) = (w[0].max(cuts[0]), w[1].min(cuts[3]));
        if b <= a {
            continue;
        }
        let n = 4000;
        let h = (b - a) / n as f64;
        let mut s = f(a) + f(b);
        for k in 1..n {
            s += f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        total += s * h / 3.0;
    }
    total
}

#[test]
fn dmt_side_is_dmt_summits() {
    let lambda = 1e-3;
    let m = compute(&spec((lambda, 2e-3, 2), (30.0, 300.0, 3)), 0).unwrap();
    let smooth = m.smooth_pulloff[0];
    let md_dmt = (smooth + 2.0).abs();
    for iy in 0..3 {
        let sigma = m.sigmas[iy];
        let i = iy * 2;
        // DMT summits have no history: their retract is their approach; its minimum here.
        let (mut a, mut b) = (-3.0 * sigma, 8.0 * sigma + 700.0);
        for _ in 0..80 {
            let (x, y) = (b - 0.618 * (b - a), a + 0.618 * (b - a));
            if dmt_rough(lambda, sigma, x) < dmt_rough(lambda, sigma, y) {
                b = y
            } else {
                a = x
            }
        }
        let dmt = dmt_rough(lambda, sigma, 0.5 * (a + b));
        assert!(
            (m.pulloff[i] - dmt).abs() <= 3.0 * md_dmt + 1e-6,
            "sigma {sigma}: map {} against DMT summits {dmt} (MD-DMT {md_dmt:e})",
            m.pulloff[i]
        );
        assert!(
            matches!(m.regions[i], Region::Rigid | Region::Dmt | Region::Hertz),
            "sigma {sigma}: {:?}",
            m.regions[i]
        );
        assert!(m.model_error[i][2] <= 0.05 || m.regions[i] != Region::Dmt);
    }
}

#[test]
fn bad_specs_are_refused_with_one_line() {
    let good = spec((0.1, 10.0, 4), (0.1, 1.0, 4));
    let cases: Vec<(RoughMapSpec, &str)> = vec![
        (
            RoughMapSpec {
                sigma_min: 0.0,
                ..good.clone()
            },
            "sigma_min",
        ),
        (
            RoughMapSpec {
                sigma_max: f64::NAN,
                ..good.clone()
            },
            "sigma_max",
        ),
        (
            RoughMapSpec {
                lambda_min: -1.0,
                ..good.clone()
            },
            "lambda_min",
        ),
        (
            RoughMapSpec {
                lambda_max: 0.05,
                ..good.clone()
            },
            "lambda_max",
        ),
        (
            RoughMapSpec {
                nx: 1,
                ..good.clone()
            },
            "nx",
        ),
        (
            RoughMapSpec {
                tolerance: 1.5,
                ..good.clone()
            },
            "tolerance",
        ),
        (
            RoughMapSpec {
                press_sigmas: f64::INFINITY,
                ..good.clone()
            },
            "press_sigmas",
        ),
    ];
    for (s, flag) in cases {
        let e = compute(&s, 0).err().unwrap().to_string();
        assert!(
            e.contains(flag) && !e.contains("--") && !e.contains('\n'),
            "{flag}: {e}"
        );
    }
}

fn tabor(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn the_command_writes_its_outputs_and_refuses_bad_input() {
    let dir = std::env::temp_dir().join(format!("tabor-rough-map-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = |n: &str| dir.join(n).display().to_string();
    let (png, svg, json, npy) = (p("m.png"), p("m.svg"), p("m.json"), p("m"));
    let o = tabor(&[
        "rough-map",
        "--nx",
        "6",
        "--ny",
        "5",
        "--lambda-min",
        "0.1",
        "--lambda-max",
        "100",
        "--sigma-min",
        "0.05",
        "--sigma-max",
        "5",
        "--check",
        "4",
        "--out",
        &png,
        "--svg",
        &svg,
        "--json",
        &json,
        "--json-full",
        "--npy",
        &npy,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    let j: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(j["table_error"].as_f64().unwrap() < 1e-6);
    assert_eq!(j["quadrature_check"]["points"], 4);
    assert!(
        j["quadrature_check"]["max_relative_difference"]
            .as_f64()
            .unwrap()
            < 1e-6
    );
    let rel = j["relative_pulloff"].as_array().unwrap();
    assert_eq!(rel.len(), 30);
    // Each exported ratio is its pull-off over the column's smooth pull-off.
    let pc = j["pulloff"].as_array().unwrap();
    let smooth = j["smooth_pulloff"].as_array().unwrap();
    for i in 0..30 {
        let want = pc[i].as_f64().unwrap() / smooth[i % 6].as_f64().unwrap();
        assert!((rel[i].as_f64().unwrap() - want).abs() < 1e-15);
        assert!(want > 0.0 && want <= 1.0 + 1e-9, "ratio {want}");
    }
    // NPY: the ratio as (ny, nx) float64 equal to the JSON's.
    let bytes = std::fs::read(format!("{npy}_relative_pulloff.npy")).unwrap();
    let f = npyz::NpyFile::new(&bytes[..]).unwrap();
    assert_eq!(f.shape(), &[5, 6]);
    let v: Vec<f64> = f.into_vec().unwrap();
    for i in 0..30 {
        assert!((v[i] - rel[i].as_f64().unwrap()).abs() <= 1e-15 * v[i].abs());
    }
    let bytes = std::fs::read(format!("{npy}_model_error.npy")).unwrap();
    assert_eq!(npyz::NpyFile::new(&bytes[..]).unwrap().shape(), &[5, 6, 4]);
    // Refusals: one line, exit 1, nothing written.
    let fresh = p("never.png");
    for (args, what) in [
        (vec!["--sigma-min", "0"], "--sigma-min"),
        (vec!["--sigma-min", "nan"], "--sigma-min"),
        (vec!["--nx", "1"], "--nx"),
        (vec!["--tolerance", "2"], "--tolerance"),
        (vec!["--press-sigmas", "50"], "--press-sigmas"),
        (vec!["--json", &fresh], "--json"),
    ] {
        let mut all = vec!["rough-map", "--out", &fresh];
        all.extend(args.iter().copied());
        let o = tabor(&all);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains(what) && err.trim().lines().count() == 1,
            "{args:?}: {err}"
        );
        assert!(!std::path::Path::new(&fresh).exists());
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `tabor rough`'s reported quadrature error against an independent quadrature: composite
/// 20-point Gauss-Legendre on 64 panels per piece between the branch heights, the folds'
/// square roots taken out by t = lo + s^2.
#[test]
fn rough_quadrature_error_is_reported_and_honest() {
    for (lambda, sigma) in [(0.3, 0.7), (2.0, 0.4)] {
        let r = Rough::new(lambda, sigma).unwrap();
        let d_min = -0.8;
        let c = r.cycle(d_min, Some(2.5), 9).unwrap();
        assert!(
            c.quadrature_error > 0.0 && c.quadrature_error < 1e-9,
            "{:e}",
            c.quadrature_error
        );
        let s = &r.summit;
        let gl = gauss_legendre_20();
        for m in &c.retract {
            let d = m.separation;
            let leg = Leg::Retract { d_min };
            let mut cuts: Vec<f64> = [
                -s.h0,
                s.delta_in,
                s.delta_out,
                s.delta_nc.unwrap_or(-s.h0),
                d_min + s.delta_in - d,
                d_min - s.h0 - d,
            ]
            .iter()
            .map(|x| x + d)
            .collect();
            cuts.extend([-12.0 * sigma, 12.0 * sigma]);
            cuts.retain(|z| z.abs() <= 12.0 * sigma);
            cuts.sort_by(f64::total_cmp);
            let mut total = 0.0;
            for w in cuts.windows(2) {
                let (a, b) = (w[0], w[1]);
                if b <= a {
                    continue;
                }
                let mid = 0.5 * (a + b);
                let branch = s.retract_branch(mid - d, mid - d_min);
                let f = |z: f64| {
                    let phi = (-0.5 * (z / sigma).powi(2)).exp()
                        / ((2.0 * std::f64::consts::PI).sqrt() * sigma);
                    phi * s.load(branch, z - d).unwrap()
                };
                // z = a + (b - a) u^2, 64 panels in u.
                let panels = 64;
                for k in 0..panels {
                    let (u0, u1) = (k as f64 / panels as f64, (k + 1) as f64 / panels as f64);
                    for &(x, wt) in &gl {
                        let u = u0 + (u1 - u0) * x;
                        total += wt * (u1 - u0) * 2.0 * u * (b - a) * f(a + (b - a) * u * u);
                    }
                }
            }
            let _ = leg;
            let diff = (m.load - total).abs();
            assert!(
                diff <= 10.0 * c.quadrature_error + 1e-13 * (1.0 + total.abs()),
                "lambda {lambda}, d {d}: {} against {total} (reported {:e})",
                m.load,
                c.quadrature_error
            );
        }
    }
}

/// Gauss-Legendre 20 on [0, 1], nodes by Newton on P_20.
fn gauss_legendre_20() -> Vec<(f64, f64)> {
    let n = 20;
    (1..=n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 - 0.25) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..50 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    (p0, p1) = (p1, p2);
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                x -= p1 / dp;
            }
            (0.5 * (1.0 - x), 1.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// The bound on the points re-solved is the library's, so every front end refuses the same
/// number the same way, before any work.
#[test]
fn too_many_check_points_are_refused_by_the_library() {
    let s = spec((0.1, 10.0, 4), (0.1, 1.0, 4));
    let max = tabor::rough::map::MAX_CHECK;
    let e = compute(&s, max + 1).unwrap_err().to_string();
    assert_eq!(
        e,
        format!("check {}: give at most {max} points to re-solve", max + 1)
    );
    assert!(compute(&s, 0).is_ok());
}
