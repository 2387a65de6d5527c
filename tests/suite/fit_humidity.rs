//! `tabor fit --relative-humidity`: a curve made with known E*, w and lambda, fitted in humid
//! air, reports the solid's w that `tabor infer --relative-humidity` gives for the fitted
//! model's load-controlled pull-off; without a meniscus (90 degrees or more) the fitted w; and
//! bad humidities are one line, through the command line and Python alike.

use std::f64::consts::PI;
use std::process::{Command, Output, Stdio};
use tabor::fit::synthetic::{synthetic, Synthetic};
use tabor::fit::{Model, Params};

const R: f64 = 20e-9;
const K: &str = "2";

fn curve_csv(w: f64, lambda: f64) -> String {
    let c = synthetic(&Synthetic {
        model: Model::Md,
        params: Params {
            e_star: 1.5e9,
            w,
            lambda,
            zc: 40e-9,
            f0: 0.0,
        },
        radius: R,
        spring: 2.0,
        points: 400,
        depth: 6.0,
        noise: 0.0,
        seed: 1,
    });
    let mut s = String::from("segment,height_m,force_n\n");
    for k in 0..c.len() {
        let seg = match c.segment[k] {
            tabor::fit::Direction::Approach => "approach",
            tabor::fit::Direction::Retract => "retract",
        };
        s += &format!("{seg},{:e},{:e}\n", c.height[k], c.force[k]);
    }
    s
}

fn tabor(args: &[&str], stdin: &str) -> Output {
    use std::io::Write;
    let mut child = Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // A refused option ends tabor before it reads its input: the write then meets a closed
    // pipe, which is not the test's failure.
    if let Err(e) = child.stdin.take().unwrap().write_all(stdin.as_bytes()) {
        assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe, "{e}");
    }
    child.wait_with_output().unwrap()
}

/// `tabor fit` of the curve with the humidity flags `extra`: the one curve's JSON.
fn fit(csv: &str, extra: &[&str]) -> serde_json::Value {
    let mut args = vec!["fit", "-i", "-", "--radius", "20e-9", "--spring-n-m", K];
    args.extend_from_slice(extra);
    let out = tabor(&args, csv);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    j["curves"][0].clone()
}

fn num(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn rel(x: f64, t: f64) -> f64 {
    (x / t - 1.0).abs()
}

#[test]
fn fitted_wet_curve_gives_the_solid_w_of_infer_on_its_pulloff() {
    let csv = curve_csv(0.3, 1.0);
    let c = fit(
        &csv,
        &["--relative-humidity", "0.4", "--contact-angle-deg", "20"],
    );
    let (e, w, lambda, z0) = (
        num(&c["e_star_pa"]),
        num(&c["work_of_adhesion_j_m2"]),
        num(&c["lambda"]),
        num(&c["z0_m"]),
    );
    // The fit itself: the curve's parameters back.
    assert!(
        rel(e, 1.5e9) < 1e-6 && rel(w, 0.3) < 1e-6 && rel(lambda, 1.0) < 1e-6,
        "{c}"
    );
    let h = &c["humidity"];
    // The force taken: the fitted model's load-controlled pull-off, Pbar_c(lambda) pi w R.
    let pbar = tabor::solver::LambdaContext::new(lambda)
        .unwrap()
        .load_pulloff
        .load;
    let f = num(&h["pulloff_force_load_control_n"]);
    assert!(rel(f, -pbar * PI * w * R) < 1e-12, "{f}");
    assert_eq!(num(&h["z0_m"]), z0);
    // The meniscus of water at 40% RH and 20 degrees.
    let m = &h["meniscus"];
    let r_k = 0.072 * 1.8e-5 / (8.314_462_618 * 298.15 * (1.0f64 / 0.4).ln());
    assert!(rel(num(&m["kelvin_radius_m"]), r_k) < 1e-12);
    assert!(rel(num(&m["laplace_pressure_pa"]), 0.072 / r_k) < 1e-12);
    let cos = 20f64.to_radians().cos();
    assert!(rel(num(&m["range_m"]), 2.0 * r_k * cos) < 1e-12);
    assert!(rel(num(&m["work_of_adhesion_j_m2"]), 2.0 * 0.072 * cos) < 1e-12);
    // The solid's w: `tabor infer --relative-humidity` on that force, E*, R and z0.
    let ws = num(&h["solid_work_of_adhesion_j_m2"]);
    let (fs, es, zs) = (format!("{f:e}"), format!("{e:e}"), format!("{z0:e}"));
    let out = tabor(
        &[
            "infer",
            "--pulloff",
            &fs,
            "--radius",
            "20e-9",
            "--e-star",
            &es,
            "--z0",
            &zs,
            "--relative-humidity",
            "0.4",
            "--contact-angle-deg",
            "20",
            "--format",
            "json",
        ],
        "",
    );
    assert!(out.status.success());
    let inf: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let wi = num(&inf["solid_work_of_adhesion_j_m2"]);
    assert!(rel(ws, wi) < 1e-9, "fit {ws}, infer {wi}");
    // Less than the fitted w, which holds the meniscus' work too; and the two-zone law with that
    // solid w and the meniscus pulls off at the fitted force (the solver, not the inversion).
    assert!(ws < w, "{ws}");
    use tabor::physics::params::{Contact, ForceRange};
    use tabor::scene::humidity::{wet_context, HumidityInput};
    let solid = Contact::new(R, e, ws, ForceRange::LennardJones(z0)).unwrap();
    let men = HumidityInput::water(0.4, 20.0)
        .meniscus(&solid)
        .unwrap()
        .unwrap();
    let (ctx, u) = wet_context(&solid, &men).unwrap();
    assert!(rel(-ctx.load_pulloff.load * u.load, f) < 1e-9);
    // The meniscus' share: 1 - the solid's own pull-off over the fitted one.
    let alone = tabor::solver::LambdaContext::new(solid.lambda())
        .unwrap()
        .load_pulloff
        .load;
    let share = 1.0 - (-alone * PI * ws * R) / f;
    assert!((num(&h["meniscus_share"]) - share).abs() < 1e-12);
    assert!(share > 0.0 && share < 1.0);
    // The range against the fitted zone's Dugdale range w / s0 = z0 / (16 / (9 sqrt 3)).
    let ratio = num(&m["range_m"]) / (z0 * 9.0 * 3f64.sqrt() / 16.0);
    assert!(rel(num(&h["meniscus_range_over_fitted_range"]), ratio) < 1e-12);
    assert_eq!(h["fair_reading"].as_bool(), Some(ratio <= 1.0));
}

#[test]
fn no_meniscus_above_90_degrees_leaves_the_fitted_w_and_a_strong_one_leaves_none() {
    let csv = curve_csv(0.05, 0.5);
    let c = fit(
        &csv,
        &["--relative-humidity", "0.6", "--contact-angle-deg", "95"],
    );
    let h = &c["humidity"];
    assert_eq!(h["solid_work_of_adhesion_j_m2"], c["work_of_adhesion_j_m2"]);
    assert!(h["meniscus"].is_null());
    assert_eq!(num(&h["meniscus_share"]), 0.0);
    // RH = 1e-10: a Kelvin radius of 23 pm, below one molecule: no meniscus is counted (the
    // fitted w is the solid's, as a dry fit's) and the fit warns as `scene` does.
    let c = fit(
        &csv,
        &["--relative-humidity", "1e-10", "--contact-angle-deg", "20"],
    );
    let h = &c["humidity"];
    assert_eq!(h["solid_work_of_adhesion_j_m2"], c["work_of_adhesion_j_m2"]);
    assert!(h["meniscus"].is_null());
    let note = h["note"].as_str().unwrap();
    assert!(
        note.starts_with("no meniscus (the Kelvin radius 0.023 nm"),
        "{note}"
    );
    let warned = c["warnings"].as_array().unwrap().iter().any(|w| {
        w.as_str()
            .unwrap()
            .starts_with("humidity: the Kelvin radius 0.023 nm")
    });
    assert!(warned, "{}", c["warnings"]);
    // Water wetting fully at 90% RH: its w = 0.144 J/m^2 is nearly three times the fit's.
    let c = fit(
        &csv,
        &["--relative-humidity", "0.9", "--contact-angle-deg", "0"],
    );
    let h = &c["humidity"];
    assert!(h["solid_work_of_adhesion_j_m2"].is_null(), "{h}");
    assert!(h["meniscus_share"].is_null());
    let note = h["note"].as_str().unwrap();
    assert!(note.contains("the meniscus alone pulls off"), "{note}");
    assert!(num(&h["meniscus_only_pulloff_n"]) > num(&h["pulloff_force_load_control_n"]));
    // The CSV table carries the same numbers.
    let mut args = vec!["fit", "-i", "-", "--radius", "20e-9", "--spring-n-m", K];
    args.extend_from_slice(&[
        "--relative-humidity",
        "0.4",
        "--contact-angle-deg",
        "80",
        "--format",
        "csv",
    ]);
    let out = tabor(&args, &csv);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let mut rows = csv::Reader::from_reader(text.as_bytes());
    let head = rows.headers().unwrap().clone();
    let row = rows.records().next().unwrap().unwrap();
    let col = |k: &str| row[head.iter().position(|h| h == k).unwrap()].to_string();
    let j = fit(
        &csv,
        &["--relative-humidity", "0.4", "--contact-angle-deg", "80"],
    );
    let ws: f64 = col("solid_work_of_adhesion_j_m2").parse().unwrap();
    assert!(rel(ws, num(&j["humidity"]["solid_work_of_adhesion_j_m2"])) < 1e-9);
    assert_eq!(col("relative_humidity").parse::<f64>().unwrap(), 0.4);
}

/// Each bad humidity: exit 1, one line naming the flag, the value and its limit, no output.
#[test]
fn bad_humidities_are_refused_in_one_line_and_write_nothing() {
    let csv = curve_csv(0.05, 0.5);
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fit.json");
    for (flags, want) in [
        (
            vec!["--relative-humidity", "1.5"],
            "--relative-humidity: relative humidity 1.5 is out of range: it must be in 0..1",
        ),
        (
            vec!["--relative-humidity", "-0.1"],
            "--relative-humidity: relative humidity -0.1 is out of range",
        ),
        (
            vec!["--relative-humidity", "NaN"],
            "--relative-humidity: relative humidity NaN is out of range",
        ),
        (
            vec!["--relative-humidity", "0"],
            "--relative-humidity: relative humidity 0 is dry air, where no meniscus forms",
        ),
        (
            vec!["--relative-humidity", "0.4", "--contact-angle-deg", "200"],
            "--contact-angle-deg: contact angle 200 is out of range: it must be in 0..180",
        ),
        (
            vec!["--relative-humidity", "0.4", "--contact-angle-deg", "-5"],
            "--contact-angle-deg: contact angle -5 is out of range",
        ),
        (
            vec![
                "--relative-humidity",
                "0.4",
                "--surface-tension-n-m",
                "-0.07",
            ],
            "--surface-tension-n-m: surface tension -0.07 is out of range: it must be > 0",
        ),
        (
            vec!["--relative-humidity", "0.4", "--temperature-k", "0"],
            "--temperature-k: temperature 0 is out of range",
        ),
        (
            vec!["--relative-humidity", "0.4", "--molar-volume-m3-mol", "0"],
            "--molar-volume-m3-mol: molar volume 0 is out of range",
        ),
    ] {
        let mut args = vec![
            "fit",
            "-i",
            "-",
            "--radius",
            "20e-9",
            "--spring-n-m",
            K,
            "-o",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(&flags);
        let o = tabor(&args, &csv);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{flags:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains(want), "{flags:?}: {err}");
        assert!(!out.exists(), "{flags:?}");
    }
    // A contact angle without a humidity is not taken alone.
    let o = tabor(
        &[
            "fit",
            "-i",
            "-",
            "--radius",
            "20e-9",
            "--spring-n-m",
            K,
            "--contact-angle-deg",
            "20",
        ],
        &csv,
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("--relative-humidity"),
        "{err}"
    );
}
