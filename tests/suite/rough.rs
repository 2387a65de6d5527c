//! Rough surfaces (docs/PHYSICS.md section 9) against limits computed here independently: the
//! single summit (sigma -> 0), Fuller and Tabor's JKR summits (lambda -> infinity) by a
//! quadrature in the contact radius, and a brute-force quadrature in the summit height.

use tabor::rough::{Leg, Rough};
use tabor::solver::{LambdaContext, Status};

/// The single summit's load at approach `delta` on the retract from contact, from the solver's
/// contact branch and the non-contact branch of PHYSICS.md section 4, written here again.
fn single_retract(ctx: &LambdaContext, lambda: f64, delta: f64) -> f64 {
    let out = ctx.disp_pulloff().approach;
    if delta >= out {
        let s = ctx.solve_approach(delta);
        assert_eq!(s.status, Status::Ok);
        return s.load;
    }
    let pi = std::f64::consts::PI;
    let (cs, h0) = (8.0 * lambda / (3.0 * pi), 2.0 / (pi * lambda));
    if lambda < 0.937947457210712 && delta >= -h0 - cs * cs / 2.0 {
        let c = cs + (cs * cs + 2.0 * (delta + h0)).sqrt();
        return -(pi * lambda / 2.0) * c * c;
    }
    0.0
}

#[test]
fn vanishing_roughness_is_the_single_summit() {
    for lambda in [0.1, 0.5, 2.0, 10.0] {
        let ctx = LambdaContext::new(lambda).unwrap();
        let r = Rough::new(lambda, 1e-9).unwrap();
        let c = r.cycle(-1.0, Some(3.0), 200).unwrap();
        let pc = ctx.load_pulloff.load;
        assert!(
            (c.pulloff_load - pc).abs() < 1e-9,
            "lambda {lambda}: pull-off {} against Pbar_c {pc}",
            c.pulloff_load
        );
        assert_eq!(c.smooth_pulloff, pc);
        // Away from the jumps (within a few sigma of one the Gaussian mixes two branches).
        for m in c.retract.iter().step_by(7) {
            let delta = -m.separation;
            let near_jump = [
                ctx.disp_pulloff().approach,
                r.summit.delta_nc.unwrap_or(0.0),
            ]
            .iter()
            .any(|j| (delta - j).abs() < 1e-6);
            if near_jump {
                continue;
            }
            let want = single_retract(&ctx, lambda, delta);
            assert!(
                (m.load - want).abs() < 1e-9 * (1.0 + want.abs()),
                "lambda {lambda}, d {}: {} against {want}",
                m.separation,
                m.load
            );
        }
    }
}

/// sigma -> 0 is `tabor cycle --control grips` itself: the rough retract after pressing to the
/// approach 1, at the separation minus each retract state of the single summit's grips cycle,
/// is that state's load within 1e-9 (the states at a jump, whose landing is interpolated on the
/// path, and those within 1e-5 of a jump left out: there the Gaussian mixes two branches, and
/// the last sample before a jump off the zone alone, which the cycle puts at the exact fold,
/// may lie just past that fold, on the branch's unstable side).
#[test]
fn vanishing_roughness_is_the_grips_cycle() {
    use tabor::cycle::{cycle, Drive, Phase};
    for lambda in [0.1, 0.5, 2.0, 10.0] {
        let c = cycle(lambda, Drive::RigidGrips, 4.0).unwrap();
        let r = Rough::new(lambda, 1e-9).unwrap();
        let jumps: Vec<f64> = c
            .jumps
            .iter()
            .flat_map(|j| [Some(j.from.approach), j.to.map(|t| t.approach)])
            .flatten()
            .collect();
        let mut checked = 0;
        for s in c
            .steps
            .iter()
            .filter(|s| s.phase == Phase::Retract && !s.jump)
        {
            let delta = s.point.approach;
            if delta > 1.0 || jumps.iter().any(|j| (delta - j).abs() < 1e-5) {
                continue;
            }
            let m = r.mean(Leg::Retract { d_min: -1.0 }, -delta).unwrap();
            let want = s.point.load;
            assert!(
                (m.load - want).abs() < 1e-9 * (1.0 + want.abs()),
                "lambda {lambda}, approach {delta}: {} against the cycle's {want}",
                m.load
            );
            checked += 1;
        }
        assert!(checked > 50, "lambda {lambda}: {checked} states");
    }
}

/// JKR in the summit's units: P(A), delta(A) and d delta / dA.
fn jkr(a: f64) -> (f64, f64, f64) {
    let s6 = 6f64.sqrt();
    (
        a * a * a - (6.0 * a * a * a).sqrt(),
        a * a - (2.0 / 3.0) * (6.0 * a).sqrt(),
        2.0 * a - s6 / (3.0 * a.sqrt()),
    )
}

/// Fuller and Tabor's mean retract load per summit at separation `d` after `d_min`: summits that
/// touched (z >= d_min) stay in contact down to JKR's rigid-grip jump-out, A = 6^(-1/3). The
/// integral over z is taken in A (z = d + delta(A)), where the integrand is smooth, by composite
/// 5-point Gauss-Legendre.
fn fuller_tabor(sigma: f64, d_min: f64, d: f64) -> f64 {
    let a_out = 6f64.powf(-1.0 / 3.0);
    let a_at = |delta: f64| {
        // delta(A) rises on A >= a_out: bisection.
        let (mut lo, mut hi) = (a_out, 1e3);
        for _ in 0..200 {
            let m = 0.5 * (lo + hi);
            if jkr(m).1 < delta {
                lo = m
            } else {
                hi = m
            }
        }
        0.5 * (lo + hi)
    };
    let a_lo = if d_min <= d + jkr(a_out).1 {
        a_out
    } else {
        a_at(d_min - d)
    };
    let a_hi = a_at(12.0 * sigma - d);
    if a_hi <= a_lo {
        return 0.0;
    }
    let gl = [
        (0.0, 128.0 / 225.0),
        (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
        (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
        (0.906_179_845_938_664, 0.236_926_885_056_189_1),
        (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    ];
    let n = 4000;
    let h = (a_hi - a_lo) / n as f64;
    let mut sum = 0.0;
    for k in 0..n {
        let mid = a_lo + (k as f64 + 0.5) * h;
        for (x, w) in gl {
            let a = mid + 0.5 * h * x;
            let (p, delta, slope) = jkr(a);
            let z = (d + delta) / sigma;
            let phi = (-0.5 * z * z).exp() / ((2.0 * std::f64::consts::PI).sqrt() * sigma);
            sum += 0.5 * h * w * phi * p * slope;
        }
    }
    sum
}

#[test]
fn large_lambda_is_fuller_and_tabor() {
    for (lambda, sigma) in [(1e6, 0.5), (1e7, 1.0)] {
        let r = Rough::new(lambda, sigma).unwrap();
        let d_min = -0.5;
        let c = r.cycle(d_min, Some(4.0 * sigma + 1.0), 120).unwrap();
        let mut worst: f64 = 0.0;
        for m in &c.retract {
            let want = fuller_tabor(sigma, d_min, m.separation);
            worst = worst.max((m.load - want).abs());
        }
        assert!(worst < 1e-6, "lambda {lambda}: retract off by {worst:e}");
        // The pull-off: Fuller and Tabor's minimum by golden section here.
        let (mut a, mut b) = (c.pulloff_separation - 0.1, c.pulloff_separation + 0.1);
        for _ in 0..100 {
            let (x, y) = (b - 0.618 * (b - a), a + 0.618 * (b - a));
            if fuller_tabor(sigma, d_min, x) < fuller_tabor(sigma, d_min, y) {
                b = y
            } else {
                a = x
            }
        }
        let ft = fuller_tabor(sigma, d_min, 0.5 * (a + b));
        assert!(
            (c.pulloff_load - ft).abs() < 1e-6,
            "lambda {lambda}: pull-off {} against Fuller-Tabor {ft}",
            c.pulloff_load
        );
        println!(
            "lambda {lambda:e}, sigma {sigma}: pull-off {:.9} (Fuller-Tabor {ft:.9}), retract within {worst:.1e}",
            c.pulloff_load
        );
    }
}

/// The mean load by brute force: composite Simpson over the summit height with 400,000 panels,
/// against the piecewise double-exponential quadrature.
#[test]
fn quadrature_agrees_with_brute_force() {
    for (lambda, sigma, d) in [(0.3, 0.7, 0.2), (1.0, 1.0, -0.4), (5.0, 0.4, 0.3)] {
        let r = Rough::new(lambda, sigma).unwrap();
        let d_min = -0.8;
        for leg in [Leg::Approach, Leg::Retract { d_min }] {
            let got = r.mean(leg, d).unwrap().load;
            let n = 400_000;
            let (lo, hi) = (-12.0 * sigma, 12.0 * sigma);
            let h = (hi - lo) / n as f64;
            let ctx = LambdaContext::new(lambda).unwrap();
            let f = |z: f64| {
                let phi = (-0.5 * (z / sigma).powi(2)).exp()
                    / ((2.0 * std::f64::consts::PI).sqrt() * sigma);
                let delta = z - d;
                let b = match leg {
                    Leg::Approach => r.summit.approach_branch(delta),
                    Leg::Retract { d_min } => r.summit.retract_branch(delta, z - d_min),
                };
                let p = match b {
                    tabor::rough::SummitBranch::Free => 0.0,
                    tabor::rough::SummitBranch::Contact => ctx.solve_approach(delta).load,
                    tabor::rough::SummitBranch::NonContact => r.summit.non_contact(delta),
                };
                phi * p
            };
            let (mut s, mut fmax) = (f(lo) + f(hi), 0f64);
            for k in 1..n {
                let v = f(lo + k as f64 * h);
                fmax = fmax.max(v.abs());
                s += v * if k % 2 == 1 { 4.0 } else { 2.0 };
            }
            let brute = s * h / 3.0;
            // Simpson across a jump of the integrand is off by at most (4/3) h times the jump;
            // a summit's load jumps at most six times.
            let bound = 6.0 * (4.0 / 3.0) * h * 2.0 * fmax;
            assert!(
                (got - brute).abs() < bound,
                "lambda {lambda}, {leg:?}: {got} against {brute} (bound {bound:e})"
            );
            println!(
                "lambda {lambda}, {leg:?}: {got} against brute force {brute}, bound {bound:.1e}"
            );
        }
    }
}

#[test]
fn bad_roughness_is_refused() {
    for s in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = Rough::new(1.0, s).err().unwrap().to_string();
        assert!(e.contains("sigma"), "{e}");
    }
    let r = Rough::new(1.0, 1.0).unwrap();
    assert!(r.cycle(1.0, Some(0.5), 10).is_err());
    assert!(r.cycle(f64::NAN, None, 10).is_err());
    assert!(r.cycle(0.0, None, 1).is_err());
}

#[test]
fn vanishing_roughness_loses_the_single_summit_loop() {
    // The single summit's loop area from `tabor cycle`'s path (sampled, so within 2e-3).
    for lambda in [0.5, 1.0, 3.0] {
        let single = tabor::cycle::cycle(lambda, tabor::cycle::Drive::RigidGrips, 4.0)
            .unwrap()
            .hysteresis
            .unwrap();
        let c = Rough::new(lambda, 1e-6)
            .unwrap()
            .cycle(-1.5, None, 50)
            .unwrap();
        assert!(
            (c.hysteresis - single).abs() < 2e-3 * (1.0 + single),
            "lambda {lambda}: {} against {single}",
            c.hysteresis
        );
    }
}

fn tabor(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args(args)
        .output()
        .unwrap()
}

/// Data and figure are written together or not at all: a figure that cannot be written leaves
/// no data file (and a data file that cannot be written no figure), for every command that
/// writes both.
#[test]
fn a_failed_figure_leaves_no_data_file() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("out.json");
    let fig = dir.path().join("fig.png");
    let (d, f) = (data.to_str().unwrap(), fig.to_str().unwrap());
    let nowhere = "/nonexistent-dir/x";
    let cases: [&[&str]; 4] = [
        &[
            "rough",
            "--lambda",
            "1",
            "--sigma",
            "0.5",
            "--min-separation",
            "-1",
        ],
        &["rough-pulloff", "--points", "4"],
        &["cycle", "--lambda", "1"],
        &["profile", "--lambda", "1", "--load", "1"],
    ];
    for args in cases {
        let bad_plot = [nowhere, ".png"].concat();
        let o = tabor(&[args, &["-o", d, "--plot", &bad_plot]].concat());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success() && err.contains("/nonexistent-dir"),
            "{args:?}: {err}"
        );
        assert!(
            !data.exists(),
            "{args:?}: the data file was written without its figure"
        );
        let bad_data = [nowhere, ".json"].concat();
        let o = tabor(&[args, &["-o", &bad_data, "--plot", f]].concat());
        assert!(
            !o.status.success() && !fig.exists(),
            "{args:?}: a figure without its data"
        );
        let o = tabor(&[args, &["-o", d, "--plot", f]].concat());
        assert!(
            o.status.success() && data.exists() && fig.exists(),
            "{args:?}"
        );
        std::fs::remove_file(&data).unwrap();
        std::fs::remove_file(&fig).unwrap();
    }
    // An explicit ensemble has no figure: refused, not ignored.
    let csv = dir.path().join("summits.csv");
    std::fs::write(&csv, "height_m,radius_m\n1e-9,1e-6\n-2e-9,2e-6\n").unwrap();
    let o = tabor(&[
        "rough",
        "--preset",
        "mems-polysilicon",
        "--asperities",
        csv.to_str().unwrap(),
        "-o",
        d,
        "--plot",
        f,
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("--plot") && !data.exists() && !fig.exists(),
        "{err}"
    );
}

#[test]
fn the_command_writes_the_keys_and_refuses_bad_input() {
    let o = tabor(&[
        "rough",
        "--lambda",
        "1",
        "--sigma",
        "0.5",
        "--min-separation",
        "-0.5",
        "--points",
        "40",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // The JSON says what the model leaves out and where that fails.
    let model = j["model"].as_str().unwrap();
    assert!(
        model.contains("do not interact") && model.contains("fails when contact spots crowd"),
        "{model}"
    );
    for k in [
        "pulloff_load",
        "pulloff_separation",
        "hysteresis",
        "smooth_pulloff",
        "fuller_tabor_parameter",
    ] {
        assert!(j[k].as_f64().unwrap().is_finite(), "{k}");
    }
    for leg in ["approach", "retract"] {
        for k in [
            "separation",
            "load",
            "contact_fraction",
            "noncontact_fraction",
            "contact_load",
            "noncontact_load",
        ] {
            assert_eq!(j[leg][k].as_array().unwrap().len(), 40, "{leg}.{k}");
        }
    }
    // The retract runs from the smallest separation up; the approach down to it.
    assert_eq!(j["retract"]["separation"][0].as_f64(), Some(-0.5));
    assert_eq!(j["approach"]["separation"][39].as_f64(), Some(-0.5));
    let smooth = j["smooth_pulloff"].as_f64().unwrap();
    assert!((smooth + 1.600734911254092).abs() < 1e-12);
    assert!(
        j["pulloff_load"].as_f64().unwrap() > smooth,
        "roughness lowers the pull-off"
    );
    for (args, needle) in [
        (vec!["--sigma", "0"], "sigma"),
        (vec!["--sigma", "nan"], "sigma"),
        (
            vec!["--sigma", "1", "--max-separation", "-2"],
            "largest separation",
        ),
        (
            vec!["--sigma", "1", "--points", "1"],
            "number of separations",
        ),
    ] {
        let mut a = vec!["rough", "--lambda", "1", "--min-separation", "-1"];
        a.extend(args);
        let o = tabor(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{a:?}: {err}");
        assert!(
            err.contains(needle) && !err.contains("panicked"),
            "{a:?}: {err}"
        );
        assert!(o.stdout.is_empty());
    }
}

#[test]
fn explicit_ensembles_converge_as_one_over_root_n() {
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};
    let (lambda, sigma, d_min) = (0.7, 0.8, -0.6);
    let r = Rough::new(lambda, sigma).unwrap();
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    let normal = Normal::new(0.0, sigma).unwrap();
    for leg in [Leg::Approach, Leg::Retract { d_min }] {
        for d in [-0.3, 0.4, 1.2] {
            let exact = r.mean(leg, d).unwrap();
            let mut errors = Vec::new();
            for n in [1_000, 10_000, 100_000] {
                let z: Vec<f64> = (0..n).map(|_| normal.sample(&mut rng)).collect();
                let e = r.ensemble_mean(leg, &z, d).unwrap();
                // The spread of one summit's load, from the sample.
                let loads: Vec<f64> = z
                    .iter()
                    .map(|&zi| r.ensemble_mean(leg, &[zi], d).unwrap().load)
                    .collect();
                let m = loads.iter().sum::<f64>() / n as f64;
                let sd = (loads.iter().map(|l| (l - m).powi(2)).sum::<f64>() / n as f64).sqrt();
                let err = (e.load - exact.load).abs();
                assert!(
                    err < 4.5 * sd / (n as f64).sqrt(),
                    "{leg:?}, d {d}, N {n}: {} against {} (sd {sd})",
                    e.load,
                    exact.load
                );
                let fc = (e.contact_fraction - exact.contact_fraction).abs();
                assert!(fc < 4.5 * 0.5 / (n as f64).sqrt(), "contact fraction {fc}");
                errors.push(err);
            }
            println!("{leg:?}, d {d}: |ensemble - statistical| for N = 1e3, 1e4, 1e5: {:.2e} {:.2e} {:.2e}", errors[0], errors[1], errors[2]);
        }
    }
}

/// lambda -> 0: each summit a DMT sphere with the rigid Dugdale law outside contact (Maugis
/// 1996): load delta^(3/2) - 2 in contact (delta >= 0), -2 - pi lambda delta for -h0 <= delta < 0,
/// reversible. The MD summit differs from it by terms of order lambda^(1/2) (PHYSICS.md section 3).
#[test]
fn small_lambda_is_dmt_summits() {
    let (lambda, sigma) = (1e-3, 0.5);
    let r = Rough::new(lambda, sigma).unwrap();
    let h0 = 2.0 / (std::f64::consts::PI * lambda);
    let dmt = |delta: f64| {
        if delta >= 0.0 {
            delta.powf(1.5) - 2.0
        } else if delta >= -h0 {
            -2.0 - std::f64::consts::PI * lambda * delta
        } else {
            0.0
        }
    };
    for d in [-0.5, 0.0, 0.5, 1.0, 2.0] {
        // Composite Simpson over heights with a node at the kink delta = 0 (z = d).
        let n = 20_000;
        let (lo, hi) = (-12.0 * sigma, 12.0 * sigma);
        let f = |z: f64| {
            (-0.5 * (z / sigma).powi(2)).exp() / ((2.0 * std::f64::consts::PI).sqrt() * sigma)
                * dmt(z - d)
        };
        let simpson = |a: f64, b: f64| {
            let h = (b - a) / n as f64;
            let mut s = f(a) + f(b);
            for k in 1..n {
                s += f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
            }
            s * h / 3.0
        };
        let want = simpson(lo, d.clamp(lo, hi)) + simpson(d.clamp(lo, hi), hi);
        for leg in [Leg::Approach, Leg::Retract { d_min: -0.5 }] {
            let got = r.mean(leg, d).unwrap().load;
            assert!(
                (got - want).abs() < 3.0 * lambda.sqrt(),
                "d {d}, {leg:?}: {got} against DMT {want}"
            );
        }
    }
}

#[test]
fn pulloff_falls_with_roughness() {
    let sigmas = [1e-3, 0.1, 0.5, 2.0, 8.0];
    let curves =
        tabor::rough::pulloff_against_roughness(&[0.1, 1.0, 100.0], &sigmas, -3.0).unwrap();
    for c in &curves {
        let ctx = LambdaContext::new(c.lambda).unwrap();
        assert_eq!(c.smooth_pulloff, ctx.load_pulloff.load);
        // Nearly smooth: all but the 0.13% of summits below -3 sigma pull as one summit.
        assert!((c.relative_pulloff[0] - 0.99865).abs() < 2e-3, "{c:?}");
        for w in c.relative_pulloff.windows(2) {
            assert!(w[1] < w[0] && w[1] >= 0.0, "{c:?}");
        }
    }
    // Longer-range adhesion (smaller lambda) survives more roughness.
    assert!(curves[0].relative_pulloff[3] > curves[1].relative_pulloff[3]);
    let o = tabor(&[
        "rough-pulloff",
        "--lambda",
        "1",
        "--points",
        "4",
        "--format",
        "csv",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(String::from_utf8_lossy(&o.stdout).lines().count(), 5);
}

#[test]
fn si_scenes_scale_the_summit_units_and_warn() {
    use tabor::rough::scene::{preset, RoughScene};
    let sc = preset("pdms-rough-glass").unwrap();
    let r = sc.solve(60).unwrap();
    // The same cycle in the summit's units, scaled by pi w R per summit and the summit count.
    let c = sc.summit().unwrap();
    let cyc = Rough::new(c.lambda(), sc.sigma_m / c.approach_scale())
        .unwrap()
        .cycle(-3.0 * r.sigma_normalised, None, 60)
        .unwrap();
    let n = sc.summit_density_m2 * sc.nominal_area_m2;
    let want =
        cyc.pulloff_load * std::f64::consts::PI * sc.work_of_adhesion_j_m2 * sc.summit_radius_m * n;
    assert!(
        (r.pulloff_force_n / want - 1.0).abs() < 1e-12,
        "{} against {want}",
        r.pulloff_force_n
    );
    assert!((r.pulloff_stress_pa * sc.nominal_area_m2 / r.pulloff_force_n - 1.0).abs() < 1e-12);
    // Real contact area: every summit in contact at the deepest point has a >= its Hertz value.
    let deepest = r.retract.real_contact_area_m2[0];
    assert!(deepest > 0.0 && deepest < sc.nominal_area_m2);
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    // Few summits, and sigma comparable to R, are named.
    let few = RoughScene {
        nominal_area_m2: 1e-8,
        sigma_m: 2e-6,
        ..sc.clone()
    };
    let w = few.solve(20).unwrap().warnings.join("; ");
    assert!(
        w.contains("summits in the nominal area") && w.contains("summit radius"),
        "{w}"
    );
    let bad = RoughScene {
        summit_density_m2: -1.0,
        ..sc
    };
    assert!(bad
        .solve(20)
        .err()
        .unwrap()
        .to_string()
        .contains("summit_density_m2"));
    let o = tabor(&["rough", "--preset", "nonsense"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("mems-polysilicon"));
    // Every preset sticks: a tensile pull-off force equal to the summits' count times the
    // normalised one; the colloidal probe covers only a few dozen summits and says so.
    for name in tabor::rough::scene::PRESETS {
        let sc = preset(name).unwrap();
        let r = sc.solve(60).unwrap();
        let few = name == "colloidal-probe-wafer";
        assert_eq!(
            r.warnings.len(),
            usize::from(few),
            "{name}: {:?}",
            r.warnings
        );
        assert!(!few || r.warnings[0].contains("summits in the nominal area"));
        let c = sc.summit().unwrap();
        let d_min = sc
            .min_separation_m
            .map_or(-3.0 * r.sigma_normalised, |d| d / c.approach_scale());
        let cyc = Rough::new(c.lambda(), sc.sigma_m / c.approach_scale())
            .unwrap()
            .cycle(d_min, None, 60)
            .unwrap();
        let per = std::f64::consts::PI * sc.work_of_adhesion_j_m2 * sc.summit_radius_m;
        let want = cyc.pulloff_load * per * sc.summit_density_m2 * sc.nominal_area_m2;
        assert!(
            r.pulloff_force_n < 0.0 && (r.pulloff_force_n / want - 1.0).abs() < 1e-12,
            "{name}: {} against {want}",
            r.pulloff_force_n
        );
    }
}

/// A .npy file of float64 values written here byte by byte (the format is four lines of spec).
fn write_npy(path: &std::path::Path, shape: (usize, usize), fortran: bool, values: &[f64]) {
    let dict = format!(
        "{{'descr': '<f8', 'fortran_order': {}, 'shape': ({}, {}), }}",
        if fortran { "True" } else { "False" },
        shape.0,
        shape.1
    );
    let mut header = dict.into_bytes();
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(b' ');
    }
    header.push(b'\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend((header.len() as u16).to_le_bytes());
    bytes.extend(header);
    for v in values {
        bytes.extend(v.to_le_bytes());
    }
    std::fs::write(path, bytes).unwrap();
}

#[test]
fn explicit_summits_each_follow_their_own_branch() {
    use tabor::physics::params::{Contact, ForceRange};
    use tabor::rough::ensemble::{cycle, summits_of_topography, Asperity, Materials};
    let m = Materials {
        e_star_pa: 2.4e6,
        work_of_adhesion_j_m2: 0.044,
        range: ForceRange::LennardJones(0.3e-9),
    };
    // Two summits of different radius (and so different lambda) and height.
    let asp = [
        Asperity {
            height_m: 0.1e-6,
            radius_m: 5e-6,
        },
        Asperity {
            height_m: -0.05e-6,
            radius_m: 20e-6,
        },
    ];
    let d_min = -0.2e-6;
    let c = cycle(&asp, &m, d_min, Some(0.4e-6), 40).unwrap();
    for (k, &d) in c.retract.separation_m.iter().enumerate() {
        // Each summit by itself: the solver's contact branch while it holds on (down to its
        // jump-out; these are far above lambda_D), else free.
        let want: f64 = asp
            .iter()
            .map(|a| {
                let s = Contact::new(a.radius_m, m.e_star_pa, m.work_of_adhesion_j_m2, m.range)
                    .unwrap();
                let ctx = LambdaContext::new(s.lambda()).unwrap();
                assert!(s.lambda() > 1.0);
                let delta = (a.height_m - d) / s.approach_scale();
                if delta >= ctx.disp_pulloff().approach {
                    ctx.solve_approach(delta).load * s.force_scale()
                } else {
                    0.0
                }
            })
            .sum();
        assert!(
            (c.retract.force_n[k] - want).abs() <= 1e-12 * want.abs().max(1e-9),
            "d {d}: {} against {want}",
            c.retract.force_n[k]
        );
    }
    // A height map of three paraboloid bumps of known radius on a flat: found with their
    // heights, and radii exact (a parabola's central difference is exact).
    let (nx, ny, px) = (60, 40, 1e-8);
    let bumps = [
        (10, 10, 30e-9, 1e-7),
        (30, 20, 50e-9, 1.5e-7),
        (50, 30, 20e-9, 8e-8),
    ];
    let z: Vec<f64> = (0..nx * ny)
        .map(|i| {
            let (x, y) = ((i % nx) as f64 * px, (i / nx) as f64 * px);
            bumps
                .iter()
                .map(|&(bx, by, h, r)| {
                    let r2 = (x - bx as f64 * px).powi(2) + (y - by as f64 * px).powi(2);
                    h - r2 / (2.0 * r)
                })
                .fold(0.0, f64::max)
        })
        .collect();
    let s = summits_of_topography(&z, nx, px).unwrap();
    assert_eq!(s.len(), 3, "{s:?}");
    for (a, b) in s.iter().zip([bumps[0], bumps[1], bumps[2]]) {
        assert!(
            (a.height_m - b.2).abs() < 1e-20 && (a.radius_m / b.3 - 1.0).abs() < 1e-9,
            "{a:?}"
        );
    }
    // The command: the same map in Fortran order gives the same bytes.
    let dir = tempfile::tempdir().unwrap();
    let (pc, pf) = (dir.path().join("c.npy"), dir.path().join("f.npy"));
    write_npy(&pc, (ny, nx), false, &z);
    let zf: Vec<f64> = (0..nx * ny).map(|k| z[(k % ny) * nx + k / ny]).collect();
    write_npy(&pf, (ny, nx), true, &zf);
    let run = |p: &std::path::Path| {
        tabor(&[
            "rough",
            "--preset",
            "pdms-rough-glass",
            "--topography",
            p.to_str().unwrap(),
            "--pixel-m",
            "1e-8",
            "--points",
            "20",
        ])
    };
    let (oc, of) = (run(&pc), run(&pf));
    assert!(
        oc.status.success(),
        "{}",
        String::from_utf8_lossy(&oc.stderr)
    );
    assert_eq!(oc.stdout, of.stdout);
    let j: serde_json::Value = serde_json::from_slice(&oc.stdout).unwrap();
    assert_eq!(j["summits"], 3);
    // Bad ensembles: one line each.
    let bad = dir.path().join("bad.csv");
    for (text, needle) in [
        ("height_m,radius_m\n0,-1e-6\n", "radius"),
        ("height_m,radius_m\nnan,1e-6\n", "height"),
        ("height_m,radius_m\n", "number of summits"),
        ("h,r\n0,1\n", "no column height_m"),
    ] {
        std::fs::write(&bad, text).unwrap();
        let o = tabor(&[
            "rough",
            "--preset",
            "pdms-rough-glass",
            "--asperities",
            bad.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{text}: {err}");
        assert!(err.contains(needle), "{text}: {err}");
    }
    let o = tabor(&["rough", "--asperities", bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    // The summits as .npy (rows height_m, radius_m) give the CSV's bytes.
    let (csv, npy) = (dir.path().join("s.csv"), dir.path().join("s.npy"));
    let rows = [(1e-8, 2e-5), (-5e-9, 8e-6), (2.5e-8, 1.2e-5)];
    let text: String = rows.iter().map(|(h, r)| format!("{h:e},{r:e}\n")).collect();
    std::fs::write(&csv, format!("height_m,radius_m\n{text}")).unwrap();
    let flat: Vec<f64> = rows.iter().flat_map(|&(h, r)| [h, r]).collect();
    write_npy(&npy, (3, 2), false, &flat);
    let ens = |p: &std::path::Path| {
        tabor(&[
            "rough",
            "--preset",
            "pdms-rough-glass",
            "--asperities",
            p.to_str().unwrap(),
            "--points",
            "20",
        ])
    };
    let (a, b) = (ens(&csv), ens(&npy));
    assert!(a.status.success(), "{}", String::from_utf8_lossy(&a.stderr));
    assert_eq!(a.stdout, b.stdout);
    // Bad height maps: empty, or with a missing pixel; one line each, nothing written.
    let out = dir.path().join("out.json");
    for (shape, values, needle) in [
        ((0, 5), vec![], "size"),
        (
            (3, 3),
            vec![0.0, 1.0, 0.0, 1.0, f64::NAN, 1.0, 0.0, 1.0, 0.0],
            "finite",
        ),
    ] {
        let p = dir.path().join("bad.npy");
        write_npy(&p, shape, false, &values);
        let o = tabor(&[
            "rough",
            "--preset",
            "pdms-rough-glass",
            "--topography",
            p.to_str().unwrap(),
            "--pixel-m",
            "1e-8",
            "-o",
            out.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{shape:?}: {err}");
        assert!(
            err.contains(needle) && err.lines().count() == 1,
            "{shape:?}: {err}"
        );
        assert!(!out.exists(), "{shape:?}: an output was written");
    }
}

/// An ensemble whose summits span lambda 0.31..3.1 (across lambda_D): each summit's states from
/// the tables over lambda are its exact states within the tables' stated error. The bound per
/// separation is the sum over the summits of 2 x TARGET x max(pi w R, |force|): the error is
/// measured at the grid's worst points, and the interpolations in v and in lambda add.
#[test]
fn tabulated_summits_are_the_exact_ones_within_the_stated_error() {
    use std::f64::consts::PI;
    use tabor::engine::Engine;
    use tabor::physics::params::{Contact, ForceRange};
    use tabor::rough::ensemble::{cycle, cycle_with, Asperity, Materials, SummitSolver};
    use tabor::rough::lambda_table::TARGET;
    let (e, w) = (1e9, 0.05);
    let k = 4.0 / 3.0 * e;
    // lambda = 1 at R = 1 um; lambda grows as R^(1/3).
    let s0 = 0.5 / (1e-6 / (PI * w * k * k)).cbrt();
    let m = Materials {
        e_star_pa: e,
        work_of_adhesion_j_m2: w,
        range: ForceRange::DugdaleStress(s0),
    };
    let asp: Vec<Asperity> = (0..300)
        .map(|i| {
            let (f, g) = ((i as f64 * 0.618034) % 1.0, (i as f64 * 0.754878) % 1.0);
            Asperity {
                height_m: (g - 0.5) * 40e-9,
                radius_m: 3e-8 * 1000f64.powf(f),
            }
        })
        .collect();
    let (d_min, d_max, n) = (-20e-9, 40e-9, 60);
    let t = cycle_with(
        &asp,
        &m,
        d_min,
        Some(d_max),
        n,
        SummitSolver::Tables,
        &Engine::Cpu,
    )
    .unwrap();
    let x = cycle(&asp, &m, d_min, Some(d_max), n).unwrap();
    let err = t.table_error.unwrap();
    assert!(err <= TARGET, "measured table error {err}");
    assert!(t.summit_solver.starts_with("tables") && x.summit_solver == "exact");
    // Each summit alone, exactly: its force at every separation, for the bound.
    let mut bound = vec![[0.0f64; 2]; n];
    for a in &asp {
        let one = cycle(std::slice::from_ref(a), &m, d_min, Some(d_max), n).unwrap();
        let scale = Contact::new(a.radius_m, e, w, m.range)
            .unwrap()
            .force_scale();
        for (k, b) in bound.iter_mut().enumerate() {
            b[0] += 2.0 * TARGET * one.approach.force_n[k].abs().max(scale);
            b[1] += 2.0 * TARGET * one.retract.force_n[k].abs().max(scale);
        }
    }
    let mut in_contact = 0;
    for (k, bound) in bound.iter().enumerate() {
        for (leg, (a, b)) in [(&t.approach, &x.approach), (&t.retract, &x.retract)]
            .into_iter()
            .enumerate()
        {
            assert_eq!(a.contact_fraction[k], b.contact_fraction[k]);
            assert_eq!(a.noncontact_fraction[k], b.noncontact_fraction[k]);
            let d = (a.force_n[k] - b.force_n[k]).abs();
            assert!(
                d <= bound[leg],
                "separation {k}, leg {leg}: {d} over {}",
                bound[leg]
            );
            let da = (a.real_contact_area_m2[k] - b.real_contact_area_m2[k]).abs();
            assert!(da <= 1e-5 * b.real_contact_area_m2[k], "area at {k}: {da}");
            in_contact += usize::from(b.contact_fraction[k] > 0.0);
        }
    }
    assert!(
        in_contact > n,
        "the cycle reaches contact on most of its separations"
    );
}

/// The load carried by each branch: the two parts add up to the load, the cohesive zones'
/// part is tensile and vanishes with its fraction, and both agree with an explicit ensemble
/// drawn from the same Gaussian (each summit on its own branch) within its sampling error.
#[test]
fn each_branch_carries_its_part_of_the_load() {
    use tabor::rough::{Leg, Rough};
    let r = Rough::new(0.2, 0.3).unwrap();
    let c = r.cycle(-1.0, None, 60).unwrap();
    let mut split = 0;
    for m in c.approach.iter().chain(&c.retract) {
        let sum = m.contact_load + m.noncontact_load;
        assert!(
            (sum - m.load).abs() <= 1e-14 * m.load.abs().max(1.0),
            "{m:?}"
        );
        assert!(m.noncontact_load <= 0.0, "{m:?}");
        if m.noncontact_fraction == 0.0 {
            assert_eq!(m.noncontact_load, 0.0);
        }
        if m.contact_fraction == 0.0 {
            assert_eq!(m.contact_load, 0.0);
        }
        split += usize::from(m.contact_fraction > 0.01 && m.noncontact_fraction > 0.01);
    }
    assert!(split > 5, "the cycle crosses from one branch to the other");
    // Heights by the inverse Gaussian at evenly spaced probabilities (a quasi-random draw).
    let n = 100_000;
    let z: Vec<f64> = (0..n)
        .map(|i| {
            let p = (i as f64 + 0.5) / n as f64;
            // The inverse of the normal distribution by bisection.
            let (mut lo, mut hi) = (-9.0f64, 9.0f64);
            for _ in 0..80 {
                let m = 0.5 * (lo + hi);
                if 0.5 * erfc_own(-m / std::f64::consts::SQRT_2) < p {
                    lo = m;
                } else {
                    hi = m;
                }
            }
            0.3 * 0.5 * (lo + hi)
        })
        .collect();
    for (leg, d) in [(Leg::Approach, 0.9), (Leg::Retract { d_min: -1.0 }, 0.9)] {
        let (exact, drawn) = (
            r.mean(leg, d).unwrap(),
            r.ensemble_mean(leg, &z, d).unwrap(),
        );
        for (a, b) in [
            (exact.contact_load, drawn.contact_load),
            (exact.noncontact_load, drawn.noncontact_load),
        ] {
            assert!((a - b).abs() < 2e-3, "{leg:?} d = {d}: {a} against {b}");
        }
    }
}

/// erfc by its continued fraction and series (the test's own, not the library's).
fn erfc_own(x: f64) -> f64 {
    if x < 0.0 {
        return 2.0 - erfc_own(-x);
    }
    if x < 2.0 {
        // erf by its Taylor series.
        let (mut term, mut sum, mut k) = (x, x, 0.0);
        while term.abs() > 1e-17 * sum.abs() {
            k += 1.0;
            term *= -x * x / k;
            sum += term / (2.0 * k + 1.0);
        }
        return 1.0 - 2.0 / std::f64::consts::PI.sqrt() * sum;
    }
    // Lentz's continued fraction for erfc.
    let mut f = x;
    for k in (1..60).rev() {
        f = x + (k as f64 / 2.0) / f;
    }
    (-x * x).exp() / (f * std::f64::consts::PI.sqrt())
}

#[test]
fn one_radius_ensembles_run_and_their_pulloff_is_searched() {
    // Every summit of one radius (the plain Greenwood-Williamson ensemble) once indexed past the
    // end of a one-lambda table. Its tables must give the exact summits' cycle, and the pull-off
    // must be the retract's minimum, not its least sample: the same at 2, 40 and 400 points.
    use tabor::engine::Engine;
    use tabor::physics::params::{Contact, ForceRange};
    use tabor::rough::ensemble::{cycle_with, Asperity, Materials, SummitSolver};
    let m = Materials {
        e_star_pa: 87.2e9,
        work_of_adhesion_j_m2: 0.1,
        range: ForceRange::LennardJones(0.3e-9),
    };
    for asp in [
        vec![Asperity {
            height_m: 0.0,
            radius_m: 5e-7,
        }],
        (0..200)
            .map(|i| Asperity {
                height_m: ((i as f64 * 0.618034) % 1.0 - 0.5) * 2e-9,
                radius_m: 5e-7,
            })
            .collect(),
    ] {
        let d_min = -1e-9;
        let run = |points, solver| {
            cycle_with(&asp, &m, d_min, None, points, solver, &Engine::Cpu).unwrap()
        };
        let exact = run(400, SummitSolver::Exact);
        let tables = run(400, SummitSolver::Tables);
        let scale = exact.pulloff_force_n.abs();
        for (a, b) in tables.retract.force_n.iter().zip(&exact.retract.force_n) {
            assert!((a - b).abs() <= 2e-6 * scale, "{a} against {b}");
        }
        let least = exact
            .retract
            .force_n
            .iter()
            .fold(f64::INFINITY, |a, &b| a.min(b));
        assert!(exact.pulloff_force_n <= least);
        for points in [2, 40] {
            let c = run(points, SummitSolver::Exact);
            assert!(
                (c.pulloff_force_n - exact.pulloff_force_n).abs() <= 1e-9 * scale,
                "{} summits, {points} points: {} against {}",
                asp.len(),
                c.pulloff_force_n,
                exact.pulloff_force_n
            );
        }
        if asp.len() == 1 {
            // One summit: its grips retract passes the load-controlled pull-off (the most
            // tensile state of its path) before it jumps out or reaches zero radius.
            let s = Contact::new(5e-7, m.e_star_pa, 0.1, m.range).unwrap();
            let ctx = LambdaContext::new(s.lambda()).unwrap();
            let want = ctx.load_pulloff.load * s.force_scale();
            assert!(
                (exact.pulloff_force_n - want).abs() <= 1e-9 * want.abs(),
                "{} against {want}",
                exact.pulloff_force_n
            );
        }
    }
}
