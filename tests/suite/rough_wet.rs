//! Wet rough surfaces (docs/PHYSICS.md section 10.1): Greenwood-Williamson summits whose
//! cohesive law is the two-zone law (solid Dugdale zone plus a water meniscus), each under rigid
//! grips with its own history. Checked against the dry model (rho = 0, eta = 1), the single wet
//! summit (sigma -> 0), an explicit ensemble stepped through the two-zone grips cycle, and the
//! physics of humidity (pull-off grows with the meniscus).

use tabor::cycle::{Branch, Drive, PathPoint};
use tabor::physics::two_zone::Zones;
use tabor::rough::wet::WetRough;
use tabor::rough::{Leg, Rough};
use tabor::solver::two_zone::TwoZoneContext;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

#[test]
fn no_meniscus_is_the_dry_model() {
    // rho = 0 (and eta = 0) is the solid alone: the MD rough cycle exactly.
    for (lambda, sigma, d_min) in [(0.1, 0.5, -1.0), (1.0, 0.3, -0.6), (3.0, 1.0, -2.0)] {
        let dry = Rough::new(lambda, sigma)
            .unwrap()
            .cycle(d_min, None, 25)
            .unwrap();
        for (rho, eta) in [(0.0, 3.0), (0.7, 0.0)] {
            let wet = WetRough::new(lambda, rho, eta, sigma)
                .unwrap()
                .cycle(lambda, d_min, None, 25)
                .unwrap();
            for (a, b) in wet.approach.iter().zip(&dry.approach) {
                assert!(
                    (a.load - b.load).abs() <= 1e-9,
                    "{lambda} {rho}: {a:?} {b:?}"
                );
                assert!((a.separation - b.separation).abs() <= 1e-12);
            }
            for (a, b) in wet.retract.iter().zip(&dry.retract) {
                assert!((a.load - b.load).abs() <= 1e-9);
            }
            assert!((wet.pulloff_load - dry.pulloff_load).abs() <= 1e-9);
            assert!((wet.hysteresis - dry.hysteresis).abs() <= 1e-9);
        }
    }
}

#[test]
fn equal_ranges_are_md_with_the_summed_stress() {
    // eta = 1: one zone of stress s1 + s2 and range h1; in the total-w units lambda = lambda_1 +
    // lambda_2 = lambda_s (1 + rho)^(2/3) (section 10).
    let (lambda_s, rho, sigma, d_min): (f64, f64, f64, f64) = (0.8, 0.6, 0.4, -0.8);
    let lambda = lambda_s * (1.0 + rho).powf(2.0 / 3.0);
    let dry = Rough::new(lambda, sigma)
        .unwrap()
        .cycle(d_min, None, 20)
        .unwrap();
    let wet = WetRough::new(lambda_s, rho, 1.0, sigma)
        .unwrap()
        .cycle(lambda_s, d_min, None, 20)
        .unwrap();
    for (a, b) in wet.retract.iter().zip(&dry.retract) {
        assert!((a.load - b.load).abs() <= 1e-9, "{a:?} {b:?}");
    }
    assert!((wet.pulloff_load - dry.pulloff_load).abs() <= 1e-9);
}

#[test]
fn a_faint_meniscus_approaches_the_dry_model_through_the_two_zone_branches() {
    // rho = 1e-6 with eta = 3: the two-range path of this module (stretches, folds, contact
    // table), not the dry one; its curve must tend to the MD rough curve of the solid.
    let (lambda, sigma, d_min) = (1.0, 0.3, -0.6);
    let w = WetRough::new(lambda, 1e-6, 3.0, sigma).unwrap();
    assert!(matches!(w, WetRough::Wet { .. }));
    let dry = Rough::new(lambda, sigma).unwrap();
    let mut worst: f64 = 0.0;
    for d in [-0.5, -0.2, 0.0, 0.2, 0.4, 0.7] {
        for leg in [Leg::Approach, Leg::Retract { d_min }] {
            let a = w.mean(leg, d).unwrap().load;
            let b = dry.mean(leg, d).unwrap().load;
            worst = worst.max((a - b).abs());
        }
    }
    println!("rho = 1e-6: largest |P_wet - P_dry| = {worst:e}");
    assert!(worst < 2e-5, "{worst}");
}

#[test]
fn one_summit_height_gives_the_wet_summits_grips_pulloff() {
    // sigma = 1e-9: every summit at one height; pressed to approach 1 and pulled, the rough
    // pull-off is the wet summit's most tensile load under rigid grips. There the stable contact
    // branch under grips passes the load-controlled minimum (its radius is above the grips fold)
    // and the non-contact landing is less tensile, so that load is the load-controlled pull-off.
    for (lambda, rho, eta) in [(1.0, 0.5, 3.0), (2.0, 1.0, 2.0), (1.0, 0.05, 10.0)] {
        let ctx = TwoZoneContext::new(Zones::from_ratios(lambda, rho, eta).unwrap()).unwrap();
        assert!(ctx.load_pulloff.a > ctx.disp_pulloff.a);
        let c = tabor::cycle::run(
            &tabor::ContactLaw::solid_and_meniscus(lambda, rho, eta),
            Drive::RigidGrips,
            5.0,
        )
        .unwrap();
        let sampled = c
            .steps
            .iter()
            .filter(|s| s.phase == tabor::cycle::Phase::Retract)
            .map(|s| s.point.load)
            .fold(f64::INFINITY, f64::min);
        // The sampled grips cycle brackets it from above.
        assert!(sampled >= ctx.load_pulloff.load && sampled - ctx.load_pulloff.load < 1e-3);
        let w = WetRough::new(lambda, rho, eta, 1e-9).unwrap();
        let (_, p) = w.pulloff_after(-1.0, 64).unwrap();
        println!(
            "{lambda} {rho} {eta}: rough {p} summit {}",
            ctx.load_pulloff.load
        );
        assert!(
            rel(p, ctx.load_pulloff.load) < 1e-6,
            "{p} {:?}",
            ctx.load_pulloff
        );
    }
}

/// The two-zone grips cycle's sampled path, cut into its rising runs (the stable states under
/// rigid grips), stepped through by a summit: an independent follower on the cycle module's path.
struct Follower {
    path: Vec<PathPoint>,
    runs: Vec<(usize, usize)>,
}

impl Follower {
    fn new(lambda: f64, rho: f64, eta: f64) -> Follower {
        let c = tabor::cycle::run(
            &tabor::ContactLaw::solid_and_meniscus(lambda, rho, eta),
            Drive::RigidGrips,
            40.0,
        )
        .unwrap();
        let path = c.path;
        let mut runs = Vec::new();
        let mut i = 0;
        while i + 1 < path.len() {
            if path[i + 1].approach > path[i].approach {
                let mut j = i;
                while j + 1 < path.len() && path[j + 1].approach > path[j].approach {
                    j += 1;
                }
                runs.push((i, j));
                i = j;
            } else {
                i += 1;
            }
        }
        assert_eq!(path[runs[0].0].branch, Branch::Free);
        Follower { path, runs }
    }
    fn lo(&self, k: usize) -> f64 {
        if k == 0 {
            f64::NEG_INFINITY
        } else {
            self.path[self.runs[k].0].approach
        }
    }
    fn hi(&self, k: usize) -> f64 {
        self.path[self.runs[k].1].approach
    }
    fn holds(&self, k: usize, d: f64) -> bool {
        self.lo(k) <= d && d <= self.hi(k)
    }
    fn approach_run(&self, d: f64) -> usize {
        let mut k = 0;
        while d > self.hi(k) {
            let level = self.hi(k);
            k = (k + 1..self.runs.len())
                .find(|&j| self.holds(j, level))
                .expect("the path ends below the deepest approach");
        }
        k
    }
    fn retract_run(&self, d: f64, d_max: f64) -> usize {
        let mut k = self.approach_run(d_max);
        while d < self.lo(k) {
            let level = self.lo(k);
            k = (0..k).rev().find(|&j| self.holds(j, level)).unwrap_or(0);
        }
        k
    }
    fn load(&self, k: usize, d: f64) -> f64 {
        if k == 0 {
            return 0.0;
        }
        let (i0, i1) = self.runs[k];
        let p = &self.path[i0..=i1];
        let j = p.partition_point(|q| q.approach <= d).clamp(1, p.len() - 1);
        let (a, b) = (&p[j - 1], &p[j]);
        let t = (d - a.approach) / (b.approach - a.approach);
        a.load + t * (b.load - a.load)
    }
    fn mean(&self, leg: Leg, z: &[f64], d: f64) -> f64 {
        let total: f64 = z
            .iter()
            .map(|&zi| {
                let k = match leg {
                    Leg::Approach => self.approach_run(zi - d),
                    Leg::Retract { d_min } => self.retract_run(zi - d, zi - d_min),
                };
                self.load(k, zi - d)
            })
            .sum();
        total / z.len() as f64
    }
}

fn heights(n: usize, sigma: f64, seed: u64) -> Vec<f64> {
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let normal = Normal::new(0.0, sigma).unwrap();
    (0..n).map(|_| normal.sample(&mut rng)).collect()
}

#[test]
fn an_explicit_ensemble_converges_to_the_statistical_curve() {
    let (lambda, rho, eta, sigma, d_min) = (1.0, 0.5, 3.0, 0.3, -0.6);
    let f = Follower::new(lambda, rho, eta);
    let w = WetRough::new(lambda, rho, eta, sigma).unwrap();
    let legs = [Leg::Approach, Leg::Retract { d_min }];
    let seps = [-0.3, 0.0, 0.2, 0.35, 0.6];
    // Summit by summit, this module's stretches agree with the follower on the sampled path.
    let z = heights(2000, sigma, 1);
    for leg in legs {
        for d in seps {
            let a = w.ensemble_load(leg, &z, d).unwrap();
            let b = f.mean(leg, &z, d);
            assert!((a - b).abs() < 1e-4, "{leg:?} {d}: {a} {b}");
        }
    }
    // The ensemble's error against the statistical curve falls as 1/sqrt(N).
    let stat: Vec<f64> = legs
        .iter()
        .flat_map(|&leg| seps.iter().map(move |&d| (leg, d)))
        .map(|(leg, d)| w.mean(leg, d).unwrap().load)
        .collect();
    let rms = |n: usize| -> f64 {
        let mut s2 = 0.0;
        let mut m = 0;
        for seed in 0..10 {
            let z = heights(n, sigma, 100 + seed);
            let mut i = 0;
            for &leg in &legs {
                for &d in &seps {
                    s2 += (f.mean(leg, &z, d) - stat[i]).powi(2);
                    i += 1;
                    m += 1;
                }
            }
        }
        (s2 / m as f64).sqrt()
    };
    let (e3, e4) = (rms(1000), rms(10_000));
    let ratio = e3 / e4;
    println!("rms error N = 1e3: {e3:e}, N = 1e4: {e4:e}, ratio {ratio} (sqrt 10 = 3.16)");
    assert!(
        ratio > 10f64.sqrt() / 2.0 && ratio < 2.0 * 10f64.sqrt(),
        "{ratio}"
    );
}

#[test]
fn the_meniscus_raises_the_pulloff_at_fixed_roughness() {
    // A fixed solid (lambda_s) and a fixed roughness in the solid's approach unit sigma_s; the
    // meniscus's stress grows (rho: more water, eta fixed). In the total-w units of the module
    // sigma = sigma_s (1 + rho eta)^(-2/3) and the pull-off in pi w1 R is Pbar (1 + rho eta).
    let (lambda_s, eta, sigma_s, press): (f64, f64, f64, f64) = (1.0, 5.0, 1.0, 3.0);
    let mut last = 0.0;
    let mut out = Vec::new();
    for rho in [0.0, 0.05, 0.1, 0.2, 0.4] {
        let k = 1.0 + rho * eta;
        let sigma = sigma_s * k.powf(-2.0 / 3.0);
        let w = WetRough::new(lambda_s, rho, eta, sigma).unwrap();
        let (_, p) = w.pulloff_after(-press * sigma, 48).unwrap();
        let p1 = p * k;
        out.push((rho, p1));
        assert!(p1 < last, "rho {rho}: pull-off {p1} not beyond {last}");
        last = p1;
    }
    println!("pull-off per summit (pi w1 R) against rho: {out:?}");
    // The meniscus dominates the rough pull-off: more than twice the dry one at rho = 0.4.
    assert!(out[4].1 / out[0].1 > 2.0, "{out:?}");
}

fn tabor(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn bad_wet_input_is_refused_in_one_line() {
    let dir = std::env::temp_dir().join(format!("tabor-rough-wet-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("out.json");
    let o = out.to_str().unwrap();
    let base = [
        "rough",
        "--lambda",
        "1",
        "--sigma",
        "0.3",
        "--min-separation",
        "-0.6",
    ];
    let cases: &[(&[&str], &str)] = &[
        (
            &["--stress-ratio", "-1", "--range-ratio", "3"],
            "stress ratio",
        ),
        (
            &["--stress-ratio", "0.5", "--range-ratio", "NaN"],
            "range ratio",
        ),
        (
            &["--stress-ratio", "1e9", "--range-ratio", "3"],
            "stress ratio",
        ),
        (&["--stress-ratio", "0.5"], "--range-ratio"),
        (&["--range-ratio", "3"], "--stress-ratio"),
    ];
    for (extra, needle) in cases {
        let mut args: Vec<&str> = base.to_vec();
        args.extend_from_slice(extra);
        args.extend_from_slice(&["-o", o]);
        let r = tabor(&args);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} wrote its output");
    }
    // The roughness and lambda keep their refusals with a meniscus.
    for (flag, value, needle) in [("--sigma", "0", "sigma"), ("--lambda", "-1", "lambda")] {
        let mut args: Vec<&str> = base.to_vec();
        let i = args.iter().position(|a| *a == flag).unwrap();
        args[i + 1] = value;
        args.extend_from_slice(&["--stress-ratio", "0.5", "--range-ratio", "3", "-o", o]);
        let r = tabor(&args);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains(needle) && err.trim().lines().count() == 1,
            "{err}"
        );
        assert!(!out.exists());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

fn humid_scene(dir: &std::path::Path, name: &str, humidity: &str) -> std::path::PathBuf {
    let p = dir.join(name);
    std::fs::write(
        &p,
        format!(
            r#"{{"e_star_pa": 8.4e10, "work_of_adhesion_j_m2": 0.05, "z0_m": 0.3e-9,
 "summit_radius_m": 0.5e-6, "summit_density_m2": 2e12, "sigma_m": 1e-9, "nominal_area_m2": 2e-9
 {humidity}}}"#
        ),
    )
    .unwrap();
    p
}

#[test]
fn a_humid_si_scene_reports_the_wet_and_the_dry_pulloff() {
    use tabor::rough::scene::RoughScene;
    let dir = std::env::temp_dir().join(format!("tabor-rough-wet-si-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let dry_path = humid_scene(&dir, "dry.json", "");
    let dry: RoughScene =
        serde_json::from_str(&std::fs::read_to_string(&dry_path).unwrap()).unwrap();
    let d = dry.solve(40).unwrap();
    let mut last = d.pulloff_force_n;
    for rh in [0.3, 0.9] {
        let p = humid_scene(
            &dir,
            "wet.json",
            &format!(r#", "humidity": {{"relative_humidity": {rh}, "contact_angle_deg": 20}}"#),
        );
        let s: RoughScene = serde_json::from_str(&std::fs::read_to_string(&p).unwrap()).unwrap();
        // 16 reported separations: the pull-off is searched for at 64 whatever the number.
        let r = s.solve(16).unwrap();
        // The dry comparison is the dry scene's own pull-off (same press: -3 sigma).
        let dry_f = r.dry_pulloff_force_n.unwrap();
        assert!(
            rel(dry_f, d.pulloff_force_n) < 1e-6,
            "{dry_f} {}",
            d.pulloff_force_n
        );
        // The wet pull-off, from the library's units: N * Pbar * pi w R with the total w.
        let m = r.meniscus.unwrap();
        let w = 0.05 + m.work_of_adhesion_j_m2;
        let f = r.normalised.pulloff_load * std::f64::consts::PI * w * 0.5e-6 * r.summits;
        assert!(rel(r.pulloff_force_n, f) < 1e-12);
        println!("RH {rh}: pull-off {} N (dry {dry_f} N)", r.pulloff_force_n);
        assert!(
            r.pulloff_force_n < last,
            "RH {rh}: {} vs {last}",
            r.pulloff_force_n
        );
        last = r.pulloff_force_n;
    }
    // A bad humidity is refused in one line naming it, nothing written.
    let bad = humid_scene(
        &dir,
        "bad.json",
        r#", "humidity": {"relative_humidity": 1.5, "contact_angle_deg": 20}"#,
    );
    let out = dir.join("out.json");
    let r = tabor(&[
        "rough",
        "--scene",
        bad.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(
        err.contains("relative_humidity") && err.trim().lines().count() == 1,
        "{err}"
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_contact_table_matches_the_solver() {
    // The stable contact curve is interpolated from 3000 radii: against the solver's state at
    // the approach, from the grips fold to 9 beyond it.
    let mut worst: f64 = 0.0;
    for (lambda, rho, eta) in [
        (1.0, 0.5, 3.0),
        (0.3, 0.2, 5.0),
        (2.0, 1.0, 2.0),
        (1.0, 0.05, 10.0),
    ] {
        let w = WetRough::new(lambda, rho, eta, 0.3).unwrap();
        let WetRough::Wet(Rough { summit, .. }) = &w else {
            panic!("two ranges")
        };
        let k = summit.stretches.len() - 1;
        let lo = summit.stretches[k].lo;
        for i in 0..400 {
            let d = lo + 9.0 * ((i as f64 + 0.37) / 400.0).powi(3);
            let e = (summit.load(k, d).unwrap() - summit.contact_exact(d).unwrap()).abs();
            worst = worst.max(e);
        }
    }
    println!("contact table: largest load error {worst:e}");
    assert!(worst < 1e-11, "{worst}");
}

#[test]
fn the_wet_loss_and_pulloff_do_not_depend_on_the_reported_separations() {
    // The case reported at 2 points as a loss of -1e-15 and a 17% jump at 5 points: both are
    // now found from the summits' own loops and a search of the retract, whatever the sampling.
    let (lambda, rho, eta, sigma, d_min) = (1.0, 0.2, 5.0, 0.63, -1.89);
    let w = WetRough::new(lambda, rho, eta, sigma).unwrap();
    let fine = w.cycle(lambda, d_min, None, 400).unwrap();
    assert!(fine.hysteresis > 0.1, "loss {}", fine.hysteresis);
    for points in [2, 5, 40] {
        let c = w.cycle(lambda, d_min, None, points).unwrap();
        assert!(
            rel(c.hysteresis, fine.hysteresis) < 1e-9,
            "{points} points: loss {} against {}",
            c.hysteresis,
            fine.hysteresis
        );
        assert!(
            rel(c.pulloff_load, fine.pulloff_load) < 1e-9,
            "{points} points: pull-off {} against {}",
            c.pulloff_load,
            fine.pulloff_load
        );
    }
    // Independently: the trapezoid sum of the reported legs at 4000 separations (its error is
    // the legs' jumps' and kinks' share of one step).
    let dense = w.cycle(lambda, d_min, None, 4000).unwrap();
    let n = dense.approach.len();
    let trapezoid: f64 = (0..n - 1)
        .map(|i| {
            let (a, r) = (&dense.approach, &dense.retract);
            let da = a[i].separation - a[i + 1].separation;
            0.5 * (a[i].load + a[i + 1].load - r[n - 1 - i].load - r[n - 2 - i].load) * da
        })
        .sum();
    assert!(
        rel(trapezoid, fine.hysteresis) < 2e-3,
        "trapezoid {trapezoid} against {}",
        fine.hysteresis
    );
    // The sampled retract never goes below the pull-off found.
    assert!(dense
        .retract
        .iter()
        .all(|m| m.load >= fine.pulloff_load - 1e-12));
}

#[test]
fn vanishing_roughness_loses_the_wet_summits_grips_loop() {
    // sigma -> 0: every summit at one height; pressed to approach 3, each loses the two-zone
    // rigid-grips cycle's loop (sampled there, so within 2e-3).
    for (lambda, rho, eta) in [(1.0, 0.5, 3.0), (0.3, 0.2, 5.0), (3.0, 1.0, 2.0)] {
        let single = tabor::cycle::run(
            &tabor::ContactLaw::solid_and_meniscus(lambda, rho, eta),
            Drive::RigidGrips,
            8.0,
        )
        .unwrap()
        .hysteresis
        .unwrap();
        let c = WetRough::new(lambda, rho, eta, 1e-6)
            .unwrap()
            .cycle(lambda, -3.0, None, 50)
            .unwrap();
        assert!(
            (c.hysteresis - single).abs() < 2e-3 * (1.0 + single),
            "{lambda} {rho} {eta}: {} against {single}",
            c.hysteresis
        );
    }
}

#[test]
fn the_wet_loss_is_never_negative() {
    // lambda 0.001: a nearly rigid solid whose loops are tiny; reported as -8.6e-13 before (the
    // loss comes from the summits' own loops, whatever the sampling: 40 separations).
    for (lambda, sigma, d_min) in [(0.001, 0.63, -1.89), (0.001, 3.0, -9.0), (0.01, 0.1, -0.3)] {
        let c = WetRough::new(lambda, 0.2, 5.0, sigma)
            .unwrap()
            .cycle(lambda, d_min, None, 40)
            .unwrap();
        assert!(c.hysteresis >= 0.0, "lambda {lambda}: {}", c.hysteresis);
    }
}

#[test]
fn a_retract_that_ends_inside_the_force_range_is_warned() {
    let (lambda, sigma, d_min) = (1.0, 0.63, -1.89);
    for w in [
        WetRough::new(lambda, 0.2, 5.0, sigma).unwrap(),
        WetRough::new(lambda, 0.0, 0.0, sigma).unwrap(),
    ] {
        let full = w.cycle(lambda, d_min, None, 100).unwrap();
        assert!(full.warnings.is_empty(), "{:?}", full.warnings);
        let cut = w.cycle(lambda, d_min, Some(0.0), 100).unwrap();
        // The advice names its key, for each front end to call it its own way.
        assert!(
            cut.warnings.iter().any(
                |s| s.to_string().contains("inside the summits' force range")
                    && s.keys().eq(["max_separation"])
            ),
            "{:?}",
            cut.warnings
        );
    }
}

#[test]
fn explicit_ensembles_refuse_a_humid_scene_and_take_one_radius() {
    // A humid scene's meniscus was silently dropped by --asperities and --topography (their
    // summits are dry): refused in one line naming the key. The same summits in a dry scene
    // run, every one of one radius (which once panicked).
    let dir = tempfile::tempdir().unwrap();
    let wet = humid_scene(
        dir.path(),
        "wet.json",
        r#", "humidity": {"relative_humidity": 0.9, "contact_angle_deg": 20}"#,
    );
    let dry = humid_scene(dir.path(), "dry.json", "");
    let summits = dir.path().join("two.csv");
    std::fs::write(&summits, "height_m,radius_m\n0,5e-7\n1e-9,5e-7\n").unwrap();
    let topo = dir.path().join("one_peak.npy");
    {
        // A 3 x 3 height map with one peak in the middle (NPY by hand: '<f8', C order).
        let mut header = b"{'descr': '<f8', 'fortran_order': False, 'shape': (3, 3), }".to_vec();
        while (10 + header.len() + 1) % 64 != 0 {
            header.push(b' ');
        }
        header.push(b'\n');
        let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
        bytes.extend((header.len() as u16).to_le_bytes());
        bytes.extend(header);
        for v in [0.0f64, 0.0, 0.0, 0.0, 1e-9, 0.0, 0.0, 0.0, 0.0] {
            bytes.extend(v.to_le_bytes());
        }
        std::fs::write(&topo, bytes).unwrap();
    }
    let s = |p: &std::path::Path| p.to_str().unwrap().to_string();
    for input in [
        vec!["--asperities".to_string(), s(&summits)],
        vec![
            "--topography".to_string(),
            s(&topo),
            "--pixel-m".into(),
            "1e-8".into(),
        ],
    ] {
        let mut args = vec!["rough".to_string(), "--scene".into(), s(&wet)];
        args.extend(input.iter().cloned());
        let args: Vec<&str> = args.iter().map(|a| a.as_str()).collect();
        let o = tabor(&args);
        let e = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert!(
            e.contains("\"humidity\"") && e.trim().lines().count() == 1,
            "{e}"
        );
        let mut args = vec!["rough".to_string(), "--scene".into(), s(&dry)];
        args.extend(input.iter().cloned());
        let args: Vec<&str> = args.iter().map(|a| a.as_str()).collect();
        let o = tabor(&args);
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{args:?}: {e}");
        let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert!(j["pulloff_force_n"].as_f64().unwrap() < 0.0, "{j}");
    }
    let o = tabor(&[
        "rough",
        "--preset",
        "mems-polysilicon",
        "--asperities",
        &s(&summits),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
