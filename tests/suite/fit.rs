//! The force-curve fitter on synthetic curves with known parameters (the exact path under a
//! spring, Gaussian noise in the force), and on bad input.

use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use std::process::Command;
use tabor::fit::synthetic::{synthetic, Synthetic};
use tabor::fit::{fit_curve, CurveFit, FitOptions, FitStatus, Model, Params};

fn case(model: Model, lambda: f64, spring: f64, noise: f64, seed: u64) -> (Synthetic, FitOptions) {
    let s = Synthetic {
        model,
        params: Params {
            e_star: 1.5e9,
            w: 0.05,
            lambda,
            zc: 40e-9,
            f0: 0.0,
        },
        radius: 20e-9,
        spring,
        points: 400,
        depth: 6.0,
        noise,
        seed,
    };
    let opt = FitOptions {
        radius: s.radius,
        spring,
        ..FitOptions::default()
    };
    (s, opt)
}

fn rel(x: f64, t: f64) -> f64 {
    (x / t - 1.0).abs()
}

/// A fit of a `case` curve recovered E*, w and lambda to `tol` (relative).
fn assert_recovers(r: &CurveFit, lambda: f64, tol: f64, what: &str) {
    assert_eq!(r.status, FitStatus::Ok, "{what}: {}", r.message);
    let (e, w, l) = (
        r.e_star_pa.unwrap(),
        r.work_of_adhesion_j_m2.unwrap(),
        r.lambda.unwrap(),
    );
    assert!(
        rel(e, 1.5e9) < tol && rel(w, 0.05) < tol && rel(l, lambda) < tol,
        "{what}: E* {e}, w {w}, lambda {l}"
    );
}

#[test]
fn noise_free_curves_give_the_parameters_to_1e_6() {
    let cases = [
        (0.05, 1.0),
        (0.05, 40.0),
        (1.0, 0.2),
        (1.0, 2.0),
        (50.0, 1.0),
        (5.0, 10.0),
    ];
    cases.par_iter().for_each(|&(lambda, spring)| {
        let (s, opt) = case(Model::Md, lambda, spring, 0.0, 1);
        let r = fit_curve(&synthetic(&s), &opt);
        assert_recovers(&r, lambda, 1e-6, &format!("lambda {lambda}, k {spring}"));
        assert!((r.contact_point_m.unwrap() - 40e-9).abs() < 1e-15);
    });
}

/// The approach segment, both segments, and a retract curve on a tilted baseline (removed by
/// `--tilt`) give the noise-free parameters too.
#[test]
fn approach_both_segments_and_a_tilted_baseline_are_fitted_too() {
    use tabor::fit::Segments;
    let cases = [
        (Segments::Approach, 1.0, 2.0, false),
        (Segments::Both, 0.3, 40.0, false),
        (Segments::Retract, 3.0, 10.0, true),
    ];
    cases
        .par_iter()
        .for_each(|&(segments, lambda, spring, tilt)| {
            let (s, mut opt) = case(Model::Md, lambda, spring, 0.0, 2);
            let mut c = synthetic(&s);
            if tilt {
                // A baseline offset and slope (virtual deflection), removed by --tilt.
                for (f, h) in c.force.iter_mut().zip(&c.height) {
                    *f += 3e-10 + 0.02 * (h - 40e-9);
                }
            }
            opt.segments = segments;
            opt.tilt = tilt;
            let r = fit_curve(&c, &opt);
            let what = format!("{segments:?} lambda {lambda} k {spring} tilt {tilt}");
            assert_recovers(&r, lambda, 1e-5, &what);
            if tilt {
                assert!((r.baseline_tilt_n_m.unwrap() - 0.02).abs() < 1e-9);
            }
        });
}

/// Noisy fits reach the noise floor (rms residual within 12% of the noise's standard deviation:
/// none is stuck in a worse minimum), and the reported standard errors hold the truth: E*, w and
/// lambda each within three of them in at least 95% of the cases. Where one curve cannot tell
/// lambda apart within its noise, the standard error says so (it covers the profile's 3-sigma
/// region), rather than a local curvature that would understate it.
/// Does a profile interval hold the truth (an open end holds everything beyond)?
fn holds(i: Option<[Option<f64>; 2]>, t: f64) -> bool {
    match i {
        Some([lo, hi]) => lo.is_none_or(|l| l <= t) && hi.is_none_or(|h| t <= h),
        None => false,
    }
}

#[test]
fn noisy_fits_reach_the_noise_floor_and_their_intervals_hold_the_truth() {
    // 200 random cases: lambda 0.05..50, four springs, two noise levels (relative to the
    // pull-off force), with and without a jump in the sampled range (stiff springs at small
    // lambda leave continuously).
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    let cases: Vec<(f64, f64, f64, u64)> = (0..200)
        .map(|i| {
            let lambda = 0.05 * 1000f64.powf(rng.random::<f64>());
            let spring = [0.5, 2.0, 10.0, 40.0][i % 4];
            let noise = [0.005, 0.02][(i / 4) % 2] * 1.75 * std::f64::consts::PI * 0.05 * 20e-9;
            (lambda, spring, noise, i as u64 + 100)
        })
        .collect();
    type Row = (bool, [bool; 3], [bool; 3], [bool; 2], String, f64);
    let out: Vec<Row> = cases
        .par_iter()
        .map(|&(lambda, spring, noise, seed)| {
            let (s, opt) = case(Model::Md, lambda, spring, noise, seed);
            let r = fit_curve(&synthetic(&s), &opt);
            if r.status != FitStatus::Ok {
                return (false, [false; 3], [false; 3], [false; 2], format!("{lambda} {spring}: {}", r.message), f64::NAN);
            }
            let within = |x: f64, err: f64, t: f64| (x - t).abs() <= 3.0 * err;
            let l95 = r.lambda_interval_95;
            (
                true,
                [
                    within(r.e_star_pa.unwrap(), r.e_star_pa_stderr.unwrap(), 1.5e9),
                    within(r.work_of_adhesion_j_m2.unwrap(), r.work_of_adhesion_j_m2_stderr.unwrap(), 0.05),
                    within(r.lambda.unwrap(), r.lambda_stderr.unwrap(), lambda),
                ],
                [
                    holds(r.e_star_pa_interval_95, 1.5e9),
                    holds(r.work_of_adhesion_j_m2_interval_95, 0.05),
                    holds(l95, lambda),
                ],
                // lambda undetermined: its interval is open and holds the truth.
                [r.lambda_determined == Some(false), r.lambda_determined == Some(false) && holds(l95, lambda)],
                format!(
                    "lambda {lambda:.3} k {spring} noise {noise:.1e}: E* {:.4e} {:?} w {:.4e} {:?} lambda {:.4} {:?}",
                    r.e_star_pa.unwrap(), r.e_star_pa_interval_95, r.work_of_adhesion_j_m2.unwrap(),
                    r.work_of_adhesion_j_m2_interval_95, r.lambda.unwrap(), l95
                ),
                r.rms_residual_n.unwrap() / noise,
            )
        })
        .collect();
    let n = out.len() as f64;
    let frac = |f: &dyn Fn(&Row) -> bool| out.iter().filter(|o| f(o)).count() as f64 / n;
    let fitted = out.iter().filter(|o| o.0).count();
    for o in out.iter().filter(|o| !o.2.iter().all(|&b| b)) {
        eprintln!("truth outside a 95% interval: {}", o.4);
    }
    eprintln!("coverage over {n} curves      E*     w      lambda");
    eprintln!(
        "  within 3 stderr          {:.3}  {:.3}  {:.3}",
        frac(&|o| o.1[0]),
        frac(&|o| o.1[1]),
        frac(&|o| o.1[2])
    );
    eprintln!(
        "  95% profile interval     {:.3}  {:.3}  {:.3}",
        frac(&|o| o.2[0]),
        frac(&|o| o.2[1]),
        frac(&|o| o.2[2])
    );
    let undetermined = out.iter().filter(|o| o.3[0]).count();
    let open_holds = out.iter().filter(|o| o.3[1]).count();
    eprintln!("  lambda undetermined in {undetermined}; its open interval holds the truth in {open_holds}");
    let worst = out
        .iter()
        .filter(|o| o.0)
        .map(|o| (o.5 - 1.0).abs())
        .fold(0.0, f64::max);
    eprintln!("rms residual / noise of the converged fits: worst {worst:.3} from 1");
    assert_eq!(fitted, out.len(), "every curve fitted");
    assert!(worst < 0.12, "a fit above the noise floor: {worst}");
    // The standard errors of E* and lambda (which carry the profile's spread).
    for (k, name) in [(0, "E*"), (2, "lambda")] {
        let f = frac(&|o| o.1[k]);
        assert!(f >= 0.95, "{name} within 3 standard errors in {f}");
    }
    // The 95% intervals: 95% coverage, within what 200 binomial draws allow (sd 1.5%).
    for (k, name) in ["E*", "w", "lambda"].iter().enumerate() {
        let f = frac(&|o| o.2[k]);
        assert!(
            (0.91..=0.99).contains(&f),
            "{name}'s 95% interval holds the truth in {f}"
        );
    }
    assert!(open_holds as f64 >= 0.9 * undetermined as f64);
}

#[test]
fn hertz_and_jkr_curves_get_their_model() {
    // Hertz: no adhesion (w only sets the units); JKR: the closed form's own path.
    for (model, want) in [(Model::Hertz, Model::Hertz), (Model::Jkr, Model::Jkr)] {
        for (spring, seed) in [(2.0, 3), (20.0, 4)] {
            let (s, opt) = case(model, 1.0, spring, 2e-12, seed);
            let r = fit_curve(&synthetic(&s), &opt);
            assert_eq!(r.status, FitStatus::Ok, "{model:?}: {}", r.message);
            assert_eq!(
                r.adequate_model,
                Some(want),
                "{model:?} k {spring}: {}",
                r.why
            );
        }
    }
}

fn tabor(args: &[&str], stdin: &str) -> std::process::Output {
    use std::io::Write;
    let mut child = Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args(args)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // A command refused on its options exits before it reads its input: a broken pipe here.
    let _ = child.stdin.take().unwrap().write_all(stdin.as_bytes());
    child.wait_with_output().unwrap()
}

fn csv_of(curves: &[(&str, tabor::fit::Curve)]) -> String {
    let mut s = String::from("curve,segment,height_m,force_n\n");
    for (id, c) in curves {
        for k in 0..c.len() {
            let seg = match c.segment[k] {
                tabor::fit::Direction::Approach => "approach",
                tabor::fit::Direction::Retract => "retract",
            };
            s += &format!("{id},{seg},{:e},{:e}\n", c.height[k], c.force[k]);
        }
    }
    s
}

#[test]
fn bad_curves_get_a_status_and_the_others_are_fitted() {
    let (s, _) = case(Model::Md, 1.0, 2.0, 1e-11, 9);
    let good = synthetic(&s);
    let mut nan = good.clone();
    nan.force[10] = f64::NAN;
    let mut unsorted = good.clone();
    let n = unsorted.len() / 2;
    unsorted.height[..n].reverse();
    let mut approach_only = good.clone();
    approach_only
        .segment
        .iter_mut()
        .for_each(|d| *d = tabor::fit::Direction::Approach);
    approach_only.height.truncate(n);
    approach_only.force.truncate(n);
    approach_only.segment.truncate(n);
    let mut few = good.clone();
    let keep: Vec<usize> = (0..few.len()).step_by(50).collect();
    few.height = keep.iter().map(|&i| good.height[i]).collect();
    few.force = keep.iter().map(|&i| good.force[i]).collect();
    few.segment = keep.iter().map(|&i| good.segment[i]).collect();
    let mut flat = good.clone();
    flat.force
        .iter_mut()
        .enumerate()
        .for_each(|(i, f)| *f = 1e-12 * ((i % 7) as f64 - 3.0));
    let input = csv_of(&[
        ("good", good),
        ("nan", nan),
        ("unsorted", unsorted),
        ("no_retract", approach_only),
        ("few", few),
        ("flat", flat),
    ]);
    let out = tabor(
        &["fit", "-i", "-", "--radius", "20e-9", "--spring-n-m", "2"],
        &input,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let by = |id: &str| {
        v["curves"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["curve"] == id)
            .unwrap()
            .clone()
    };
    assert_eq!(by("good")["status"], "ok");
    assert!((by("good")["lambda"].as_f64().unwrap() - 1.0).abs() < 0.5);
    for (id, status, says) in [
        ("nan", "invalid_input", "non-finite"),
        ("unsorted", "invalid_input", "not in order"),
        ("no_retract", "invalid_input", "no retract segment"),
        ("few", "invalid_input", "at least 20"),
        ("flat", "no_contact", "no contact"),
    ] {
        let c = by(id);
        assert_eq!(c["status"], status, "{id}: {c}");
        assert!(
            c["message"].as_str().unwrap().contains(says),
            "{id}: {}",
            c["message"]
        );
        assert!(c["e_star_pa"].is_null());
    }
    // A spring of 0 is refused before any fit: one line naming it, nothing written.
    let out = tabor(
        &[
            "fit",
            "-i",
            "-",
            "--radius",
            "20e-9",
            "--spring-n-m",
            "0",
            "--format",
            "csv",
        ],
        &input,
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("--spring-n-m: spring constant 0 N/m"), "{err}");
    // A missing column or an unreadable file: one line.
    let out = tabor(
        &["fit", "-i", "-", "--radius", "20e-9", "--spring-n-m", "2"],
        "segment,height_m\nretract,1\n",
    );
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(
        err.contains("no column `force_n`") && err.lines().count() == 1,
        "{err}"
    );
    let out = tabor(
        &[
            "fit",
            "-i",
            "/nonexistent.csv",
            "--radius",
            "20e-9",
            "--spring-n-m",
            "2",
        ],
        "",
    );
    assert!(String::from_utf8(out.stderr)
        .unwrap()
        .contains("cannot read /nonexistent.csv"));
}

#[test]
fn a_force_map_gives_npy_maps_that_match_the_table_and_figures() {
    // A 3 x 2 map: five good curves and one without contact.
    let mut input = String::from("x,y,segment,height_m,force_n\n");
    for k in 0..6 {
        let (s, _) = case(Model::Md, 0.5 + k as f64, 2.0, 1e-11, 20 + k as u64);
        let mut c = synthetic(&s);
        if k == 4 {
            c.force.iter_mut().for_each(|f| *f = 0.0);
        }
        for i in 0..c.len() {
            let seg = match c.segment[i] {
                tabor::fit::Direction::Approach => 0,
                tabor::fit::Direction::Retract => 1,
            };
            input += &format!(
                "{},{},{seg},{:e},{:e}\n",
                k % 3,
                k / 3,
                c.height[i],
                c.force[i]
            );
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let prefix = dir.path().join("fm");
    let on_map = dir.path().join("on_map.svg");
    let out = tabor(
        &[
            "fit",
            "-i",
            "-",
            "--radius",
            "20e-9",
            "--spring-n-m",
            "2",
            "--maps",
            prefix.to_str().unwrap(),
            "--on-map",
            on_map.to_str().unwrap(),
        ],
        &input,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let curves = v["curves"].as_array().unwrap();
    let read = |name: &str| -> Vec<f64> {
        let bytes = std::fs::read(format!("{}_{name}.npy", prefix.display())).unwrap();
        let npy = npyz::NpyFile::new(&bytes[..]).unwrap();
        assert_eq!(npy.shape(), &[2, 3]);
        npy.into_vec::<f64>().unwrap()
    };
    let w = read("work_of_adhesion");
    for c in curves {
        let (x, y) = (
            c["x"].as_u64().unwrap() as usize,
            c["y"].as_u64().unwrap() as usize,
        );
        let got = w[y * 3 + x];
        match c["work_of_adhesion_j_m2"].as_f64() {
            Some(want) => assert_eq!(got, want),
            None => assert!(got.is_nan() && c["status"] == "no_contact"),
        }
    }
    let bytes = std::fs::read(format!("{}_adequate_model.npy", prefix.display())).unwrap();
    let models = npyz::NpyFile::new(&bytes[..])
        .unwrap()
        .into_vec::<i8>()
        .unwrap();
    assert_eq!(models[4], -1); // x 1, y 1: no contact
    assert!(models.iter().filter(|&&m| m >= 0).count() == 5);
    // Per pixel how its fit ended: the index of PIXEL_STATUSES (0 ok, 2 no contact).
    let bytes = std::fs::read(format!("{}_status.npy", prefix.display())).unwrap();
    let status = npyz::NpyFile::new(&bytes[..])
        .unwrap()
        .into_vec::<i8>()
        .unwrap();
    assert_eq!(status, vec![0, 0, 0, 0, 2, 0]);
    // The summary agrees with the curves' own results.
    let text = std::fs::read_to_string(format!("{}_summary.json", prefix.display())).unwrap();
    let s: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!((s["nx"].as_u64(), s["ny"].as_u64()), (Some(3), Some(2)));
    assert_eq!(s["status"]["ok"], 5);
    assert_eq!(s["status"]["no_contact"], 1);
    assert_eq!(s["status"]["no_curve"], 0);
    let ok: Vec<&serde_json::Value> = curves.iter().filter(|c| c["status"] == "ok").collect();
    for m in ["hertz", "dmt", "jkr", "md"] {
        let n = ok.iter().filter(|c| c["adequate_model"] == m).count();
        assert_eq!(s["adequate_model"][m].as_u64(), Some(n as u64), "{m}");
    }
    let quantity = |name: &str| {
        s["quantities"]
            .as_array()
            .unwrap()
            .iter()
            .find(|q| q["name"] == name)
            .unwrap()
            .clone()
    };
    let e = quantity("e_star");
    let mut es: Vec<f64> = ok
        .iter()
        .map(|c| c["e_star_pa"].as_f64().unwrap())
        .collect();
    es.sort_by(f64::total_cmp);
    assert_eq!(e["count"], 5);
    assert_eq!(e["quantiles"]["median"].as_f64(), Some(es[2]));
    assert_eq!(e["quantiles"]["min"].as_f64(), Some(es[0]));
    assert_eq!(e["quantiles"]["max"].as_f64(), Some(es[4]));
    let counts: u64 = e["counts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_u64().unwrap())
        .sum();
    assert_eq!(counts, 5);
    assert_eq!(
        e["edges"].as_array().unwrap().len(),
        e["counts"].as_array().unwrap().len() + 1
    );
    let l = quantity("lambda");
    let determined = ok.iter().filter(|c| c["lambda_determined"] == true).count() as u64;
    assert_eq!(l["count"].as_u64(), Some(determined));
    assert_eq!(l["missing"].as_u64(), Some(5 - determined));
    for q in [
        "e_star",
        "lambda",
        "pulloff",
        "rms_residual",
        "adequate_model",
        "status",
        "histograms",
    ] {
        let png = std::fs::read(format!("{}_{q}.png", prefix.display())).unwrap();
        assert_eq!(&png[1..4], b"PNG", "{q}");
    }
    let svg = std::fs::read_to_string(&on_map).unwrap();
    assert!(
        svg.contains("5 fitted curves on the map"),
        "{}",
        &svg[..200]
    );
}

#[test]
fn tsv_with_comment_lines_reads_as_csv_does() {
    let (s, _) = case(Model::Md, 1.0, 2.0, 1e-11, 31);
    let c = synthetic(&s);
    let csv = csv_of(&[("a", c)]);
    let tsv = format!(
        "# exported by a test\n# spring constant: 2 N/m\n{}",
        csv.replace(',', "\t")
    );
    let args = [
        "fit",
        "-i",
        "-",
        "--radius",
        "20e-9",
        "--spring-n-m",
        "2",
        "--format",
        "csv",
    ];
    let (a, b) = (tabor(&args, &csv), tabor(&args, &tsv));
    assert!(a.status.success() && b.status.success());
    assert_eq!(a.stdout, b.stdout);
}

/// Curves made near the JKR end with a soft spring, which show little but the pull-off: lambda
/// is not determined (the DMT-like models, whose retract runs on along the Dugdale zone's
/// non-contact branch, fit them as well), its 95% interval holds the truth and holds the 68%
/// one, and w's interval spans what the lambdas the data cannot tell apart give.
#[test]
fn lambda_near_the_jkr_end_with_a_soft_spring_is_not_determined() {
    let cases = [(20.0, 3), (50.0, 4), (30.0, 5)];
    cases.par_iter().for_each(|&(lambda, seed)| {
        let noise = 0.01 * 1.5 * std::f64::consts::PI * 0.05 * 20e-9;
        let (s, opt) = case(Model::Md, lambda, 0.5, noise, seed);
        let r = fit_curve(&synthetic(&s), &opt);
        assert_eq!(r.status, FitStatus::Ok, "{}", r.message);
        let l = r.lambda_interval_95.unwrap();
        assert_eq!(r.lambda_determined, Some(false), "lambda {lambda}: {l:?}");
        assert!(l[1].is_none(), "lambda {lambda}: {l:?} closed towards JKR");
        assert!(holds(Some(l), lambda), "lambda {lambda}: {l:?}");
        let w = r.work_of_adhesion_j_m2_interval_95.unwrap();
        assert!(holds(Some(w), 0.05), "lambda {lambda}: w {w:?}");
        // Bounded by what the DMT-like and JKR-like fits give (their pull-offs differ by 4/3),
        // not by a linearisation stretched over decades of lambda.
        let (lo, hi) = (w[0].unwrap(), w[1].unwrap());
        assert!(
            lo > 0.05 / 1.6 && hi < 0.05 * 1.6,
            "lambda {lambda}: w {w:?}"
        );
        let l68 = r.lambda_interval_68.unwrap();
        let (lo68, lo95) = (l68[0].unwrap_or(0.0), l[0].unwrap_or(0.0));
        assert!(lo68 >= lo95, "lambda {lambda}: 68% {l68:?} 95% {l:?}");
    });
}

/// A file that numbers its segments its own way (a pause 0, the approach 1, a dwell 2, the
/// retract 3, as JPK's stress-relaxation files do) is read with approach and retract from the
/// heights and the pause and dwell left out: the same fit as the two segments alone.
#[test]
fn instrument_segment_numbers_with_a_pause_and_a_dwell_give_the_same_fit() {
    let (s, opt) = case(Model::Md, 1.0, 2.0, 0.0, 1);
    let c = synthetic(&s);
    let fo = FitOptions {
        segments: tabor::fit::Segments::Both,
        ..opt
    };
    let mut rows = String::from("segment,height_m,force_n\n");
    let (h0, f0) = (c.height[0], c.force[0]);
    for _ in 0..5 {
        rows += &format!("0,{h0:e},{f0:e}\n");
    }
    let turn = c
        .segment
        .iter()
        .position(|&d| d == tabor::fit::Direction::Retract)
        .unwrap();
    for i in 0..c.len() {
        if i == turn {
            // The dwell: the base held at the turn while the force relaxes a little.
            for k in 0..20 {
                let f = c.force[turn - 1] * (1.0 - 0.01 * k as f64 / 20.0);
                rows += &format!("2,{:e},{f:e}\n", c.height[turn - 1]);
            }
        }
        let id = if i < turn { 1 } else { 3 };
        rows += &format!("{id},{:e},{:e}\n", c.height[i], c.force[i]);
    }
    let read = tabor::fit::data::parse_csv("dwell.csv", rows.as_bytes()).unwrap();
    assert_eq!(read.len(), 1);
    let r = fit_curve(&read[0], &fo);
    let want = fit_curve(&c, &fo);
    assert_eq!(r.status, FitStatus::Ok, "{}", r.message);
    let (a, b) = (r.md.as_ref().unwrap(), want.md.as_ref().unwrap());
    for (x, y, what) in [
        (a.e_star_pa, b.e_star_pa, "E*"),
        (a.work_of_adhesion_j_m2, b.work_of_adhesion_j_m2, "w"),
        (a.lambda.unwrap(), b.lambda.unwrap(), "lambda"),
    ] {
        assert!(rel(x, y) < 1e-10, "{what}: {x} against {y}");
    }
    let dropped = r
        .warnings
        .iter()
        .filter(|w| w.contains("a dwell, left out"))
        .count();
    assert_eq!(dropped, 2, "{:?}", r.warnings);
    // Ids other than 0/1 that cannot be told apart by the heights: that curve's own status.
    let flat = "segment,height_m,force_n\n2,1e-8,0\n2,2e-8,0\n2,3e-8,0\n2,4e-8,0\n2,5e-8,0\n";
    let read = tabor::fit::data::parse_csv("flat.csv", flat.as_bytes()).unwrap();
    let r = fit_curve(&read[0], &fo);
    assert_eq!(r.status, FitStatus::InvalidInput);
    assert!(
        r.message
            .to_string()
            .contains("approach and retract are not separated"),
        "{}",
        r.message
    );
}

/// A curve's rows with a dwell at its turn, numbered as a JPK creep or stress-relaxation file
/// does (0 the approach, 1 the dwell, 2 the retract): the dwell's (height, force) given.
fn with_dwell(c: &tabor::fit::Curve, dwell: &[(f64, f64)]) -> String {
    let turn = c
        .segment
        .iter()
        .position(|&d| d == tabor::fit::Direction::Retract)
        .unwrap();
    let mut rows = String::from("segment,height_m,force_n\n");
    for i in 0..c.len() {
        if i == turn {
            for (h, f) in dwell {
                rows += &format!("1,{h:e},{f:e}\n");
            }
        }
        let id = if i < turn { 0 } else { 2 };
        rows += &format!("{id},{:e},{:e}\n", c.height[i], c.force[i]);
    }
    rows
}

/// 0 over the first 5 of n points, 1 over the last 5, rising smoothly between: a dwell's
/// course, its ends (the medians of 5 points) exact.
fn course(k: usize, n: usize) -> f64 {
    let x = ((k as f64 - 4.0) / (n - 9) as f64).clamp(0.0, 1.0);
    1.0 - (1.0 - x).powi(3)
}

/// Stress relaxation: the base held at the turn while the force relaxes to 40% of its start.
/// The retract then unloads a relaxed contact, no loading curve of the one the approach made:
/// the approach is fitted (the same fit as the approach alone), the message says so, and the
/// dwell's forces, relaxation and creep (the tip's advance as the cantilever unbends, 0.6 F/k)
/// are reported, by the library and by `tabor fit` in JSON and CSV.
#[test]
fn after_a_dwell_that_relaxed_the_force_the_approach_is_fitted_and_the_dwell_reported() {
    let (s, opt) = case(Model::Md, 1.0, 2.0, 0.0, 1);
    let c = synthetic(&s);
    let turn = c
        .segment
        .iter()
        .position(|&d| d == tabor::fit::Direction::Retract)
        .unwrap();
    let (h, f0) = (c.height[turn - 1], c.force[turn - 1]);
    let dwell: Vec<(f64, f64)> = (0..100)
        .map(|k| (h, f0 * (1.0 - 0.6 * course(k, 100))))
        .collect();
    let rows = with_dwell(&c, &dwell);
    let read = tabor::fit::data::parse_csv("relaxation.csv", rows.as_bytes()).unwrap();
    let r = fit_curve(&read[0], &opt);
    let approach = fit_curve(
        &c,
        &FitOptions {
            segments: tabor::fit::Segments::Approach,
            ..opt.clone()
        },
    );
    assert_eq!(r.status, FitStatus::Ok, "{}", r.message);
    assert_eq!(approach.status, FitStatus::Ok, "{}", approach.message);
    let note = format!(
        "the approach was fitted, not the retract: the retract follows a dwell (points {turn}..{}) in which the force relaxed from {:.3e} N to {:.3e} N (60%), so it unloads a relaxed contact and is not a loading curve of the one the approach made",
        turn + 99,
        f0,
        0.4 * f0
    );
    assert_eq!(r.message.to_string(), format!("ok: {note}"));
    assert_eq!(r.warnings[0], note);
    for (x, y, what) in [
        (r.e_star_pa, approach.e_star_pa, "E*"),
        (r.work_of_adhesion_j_m2, approach.work_of_adhesion_j_m2, "w"),
        (r.lambda, approach.lambda, "lambda"),
    ] {
        assert!(
            rel(x.unwrap(), y.unwrap()) < 1e-10,
            "{what}: {x:?} against {y:?}"
        );
    }
    assert_eq!(r.points_fitted, approach.points_fitted);
    // Both segments asked: the retract is still no loading curve.
    let both = fit_curve(
        &read[0],
        &FitOptions {
            segments: tabor::fit::Segments::Both,
            ..opt.clone()
        },
    );
    assert_eq!(both.points_fitted, approach.points_fitted);
    // The synthetic baseline is exactly 0: the dwell's forces as given.
    let w = r.dwell.as_ref().unwrap();
    assert_eq!((w.first_point, w.last_point), (turn, turn + 99));
    assert!(
        rel(w.force_start_n, f0) < 1e-12 && rel(w.force_end_n, 0.4 * f0) < 1e-12,
        "{w:?}"
    );
    assert!(rel(w.relaxation.unwrap(), 0.6) < 1e-12, "{w:?}");
    assert_eq!(w.base_advance_m, 0.0);
    assert!(rel(w.indentation_creep_m, 0.6 * f0 / 2.0) < 1e-12, "{w:?}");
    assert!(w.relaxed);
    // The command line: the same reading, the dwell in JSON and in CSV columns.
    let args = ["fit", "-i", "-", "--radius", "20e-9", "--spring-n-m", "2"];
    let out = tabor(&args, &rows);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let cv = &v["curves"][0];
    assert_eq!(cv["status"], "ok");
    assert_eq!(cv["message"], r.message.to_string());
    assert_eq!(cv["e_star_pa"].as_f64(), r.e_star_pa);
    assert_eq!(cv["dwell"]["relaxed"], true);
    assert_eq!(cv["dwell"]["first_point"], turn);
    assert_eq!(cv["dwell"]["force_end_n"].as_f64(), Some(w.force_end_n));
    assert_eq!(
        cv["dwell"]["indentation_creep_m"].as_f64(),
        Some(w.indentation_creep_m)
    );
    let out = tabor(&[&args[..], &["--format", "csv"]].concat(), &rows);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let mut rd = csv::Reader::from_reader(text.as_bytes());
    let head = rd.headers().unwrap().clone();
    let row = rd.records().next().unwrap().unwrap();
    let cell = |k: &str| row[head.iter().position(|h| h == k).unwrap()].to_string();
    assert_eq!(cell("dwell_first_point"), turn.to_string());
    assert_eq!(cell("dwell_relaxed"), "true");
    assert!(rel(cell("dwell_relaxation").parse().unwrap(), 0.6) < 1e-9);
    assert!(rel(cell("dwell_force_start_n").parse().unwrap(), f0) < 1e-9);
    // Without a dwell, no dwell columns: the CSV of other curves as before.
    let plain = tabor(
        &[&args[..], &["--format", "csv"]].concat(),
        &csv_of(&[("c", c.clone())]),
    );
    assert!(!String::from_utf8_lossy(&plain.stdout).contains("dwell_"));
}

/// Creep: the force held at the turn while the base advances (the indentation creeps). The
/// retract unloads the contact from the load the approach reached: it is fitted (the same fit
/// as the two segments without the dwell), and the creep is the base's advance.
#[test]
fn after_a_creep_at_a_held_force_the_retract_is_fitted_and_the_creep_reported() {
    let (s, opt) = case(Model::Md, 1.0, 2.0, 0.0, 1);
    let c = synthetic(&s);
    let turn = c
        .segment
        .iter()
        .position(|&d| d == tabor::fit::Direction::Retract)
        .unwrap();
    let (h, f0) = (c.height[turn - 1], c.force[turn - 1]);
    // 2% of the approach's span: a dwell, not a segment of the curve.
    let a = 0.02 * (c.height[0] - h);
    let dwell: Vec<(f64, f64)> = (0..100).map(|k| (h - a * course(k, 100), f0)).collect();
    let rows = with_dwell(&c, &dwell);
    let read = tabor::fit::data::parse_csv("creep.csv", rows.as_bytes()).unwrap();
    let r = fit_curve(&read[0], &opt);
    let want = fit_curve(&c, &opt);
    assert_eq!(r.status, FitStatus::Ok, "{}", r.message);
    assert_eq!(r.message.to_string(), "ok");
    assert!(rel(r.e_star_pa.unwrap(), want.e_star_pa.unwrap()) < 1e-10);
    assert!(
        rel(
            r.work_of_adhesion_j_m2.unwrap(),
            want.work_of_adhesion_j_m2.unwrap()
        ) < 1e-10
    );
    let w = r.dwell.as_ref().unwrap();
    assert!(!w.relaxed && w.relaxation == Some(0.0), "{w:?}");
    assert!(
        rel(w.base_advance_m, a) < 1e-9 && rel(w.indentation_creep_m, a) < 1e-9,
        "{w:?}"
    );
    assert!(
        r.warnings.iter().any(|x| x.contains("a dwell, left out")),
        "{:?}",
        r.warnings
    );
}

/// Curve i of the force-map benchmark's map of n curves (`bench/fit_map.sh`: 500 points a
/// segment, a 40 N/m cantilever, 20 pN noise) and its options.
fn map_case(i: usize, n: usize) -> (Synthetic, tabor::fit::Curve, FitOptions) {
    let s = tabor::fit::synthetic::map_curve(i, n, 500, 40.0, 2e-11);
    let c = synthetic(&s);
    let opt = FitOptions {
        radius: 20e-9,
        spring: 40.0,
        ..FitOptions::default()
    };
    (s, c, opt)
}

/// The free fit finds the global minimum where the misfit dips between two points of the lambda
/// profile: the first 16 curves of the force-map benchmark's 256-curve map (`bash
/// bench/fit_map.sh 16`: lambda 0.30..0.37, a 40 N/m cantilever, 20 pN noise), 9 of whose dips
/// a search from the profile's local minima alone missed (ending 0.1-0.8% higher in rms). The
/// misfit of a fit at the true Lennard-Jones range z0 (lambda tied to the truth) bounds the global minimum from above, up
/// to how closely the two fits converge: 2e-4 in rms is a Delta chi^2 of 0.2 on these curves.
#[test]
fn a_dip_between_profile_points_is_found() {
    let worst = (0..16usize)
        .into_par_iter()
        .map(|i| {
            let (s, c, opt) = map_case(i, 256);
            let free = fit_curve(&c, &opt);
            let p = s.params;
            let at_truth = fit_curve(
                &c,
                &FitOptions {
                    z0: Some(tabor::fit::z0_from_lambda(p.e_star, p.w, 20e-9, p.lambda)),
                    ..opt
                },
            );
            assert_eq!(free.status, FitStatus::Ok, "curve {i}: {}", free.message);
            assert_eq!(at_truth.status, FitStatus::Ok, "curve {i}: {}", at_truth.message);
            let excess = free.rms_residual_n.unwrap() / at_truth.rms_residual_n.unwrap() - 1.0;
            println!(
                "curve {i}: lambda {:.3}, fitted {:.3}, rms {:+.2e} relative to the fit at the true z0",
                p.lambda,
                free.lambda.unwrap(),
                excess
            );
            excess
        })
        .reduce(|| f64::NEG_INFINITY, f64::max);
    assert!(
        worst < 2e-4,
        "a free fit above the fit at the true z0 by {worst:e}"
    );
}

/// Curve (19, 20) of the benchmark's 64 x 64 map (lambda 0.90, 40 N/m, 20 pN noise): its best
/// two short free fits can end at one point of a shallower minimum (lambda 0.650, 1e-3 higher in
/// rms than the one at lambda 0.689), and two full fits from there find only that one. The free
/// fit must reach the lowest misfit of fits with lambda tied to a fixed z0, scanned over lambda
/// 0.5..1.1 (z0 from the true E* and w): within 2e-4 in rms (a Delta chi^2 of 0.2).
#[test]
fn the_full_fits_start_from_two_distinct_basins() {
    let (s, c, opt) = map_case(19 + 64 * 20, 4096);
    let free = fit_curve(&c, &opt);
    assert_eq!(free.status, FitStatus::Ok, "{}", free.message);
    let p = s.params;
    let scanned = (0..25)
        .into_par_iter()
        .map(|k| {
            let lambda = 0.5 * (1.1f64 / 0.5).powf(k as f64 / 24.0);
            let z0 = tabor::fit::z0_from_lambda(p.e_star, p.w, 20e-9, lambda);
            let r = fit_curve(
                &c,
                &FitOptions {
                    z0: Some(z0),
                    ..opt.clone()
                },
            );
            r.rms_residual_n
                .filter(|_| r.status == FitStatus::Ok)
                .unwrap_or(f64::INFINITY)
        })
        .reduce(|| f64::INFINITY, f64::min);
    let excess = free.rms_residual_n.unwrap() / scanned - 1.0;
    println!(
        "lambda fitted {:.3}, rms {excess:+.2e} relative to the best of the scan",
        free.lambda.unwrap()
    );
    assert!(
        excess < 2e-4,
        "the free fit is {excess:e} above the scan's best"
    );
}

/// Near the JKR end with soft springs a retract curve often cannot place lambda, and its
/// profile can have a second basin: over 200 noisy curves (lambda 5..50, springs 0.5 and 1
/// N/m, noise 1% and 2% of the pull-off) lambda's 95% set (the interval spanning every basin
/// below the level) and E*'s and w's hold the truth in about 95% of them.
#[test]
fn coverage_near_the_jkr_end_with_soft_springs() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(11);
    let cases: Vec<(f64, f64, f64, u64)> = (0..200)
        .map(|i| {
            let lambda = 5.0 * 10f64.powf(rng.random::<f64>());
            let spring = [0.5, 1.0][i % 2];
            let noise = [0.01, 0.02][(i / 2) % 2] * 1.75 * std::f64::consts::PI * 0.05 * 20e-9;
            (lambda, spring, noise, i as u64 + 1000)
        })
        .collect();
    // (fitted, [E*, w, lambda] held at 95%, determined, determined and held, basins)
    type Row = (bool, [bool; 3], bool, bool, usize);
    let out: Vec<Row> = cases
        .par_iter()
        .map(|&(lambda, spring, noise, seed)| {
            let (s, opt) = case(Model::Md, lambda, spring, noise, seed);
            let r = fit_curve(&synthetic(&s), &opt);
            if r.status != FitStatus::Ok {
                eprintln!("lambda {lambda:.2} k {spring}: {:?} {}", r.status, r.message);
                return (false, [false; 3], false, false, 0);
            }
            let l95 = r.lambda_interval_95;
            let det = r.lambda_determined == Some(true);
            if det {
                eprintln!(
                    "lambda {lambda:.2} determined (k {spring}, noise {noise:.1e}): {:?}, fit {:.3}, w {:.4}",
                    r.lambda_bound,
                    r.lambda.unwrap(),
                    r.work_of_adhesion_j_m2.unwrap()
                );
            }
            if !holds(l95, lambda) {
                eprintln!(
                    "lambda {lambda:.2} outside its 95% interval (k {spring}, noise {noise:.1e}): fit {:.3}, interval {:?}, w {:.4} {:?}",
                    r.lambda.unwrap(),
                    l95,
                    r.work_of_adhesion_j_m2.unwrap(),
                    r.work_of_adhesion_j_m2_interval_95
                );
            }
            (
                true,
                [
                    holds(r.e_star_pa_interval_95, 1.5e9),
                    holds(r.work_of_adhesion_j_m2_interval_95, 0.05),
                    holds(l95, lambda),
                ],
                det,
                det && holds(l95, lambda),
                r.lambda_basins.len(),
            )
        })
        .collect();
    let n = out.len() as f64;
    let frac = |f: &dyn Fn(&Row) -> bool| out.iter().filter(|o| f(o)).count() as f64 / n;
    let determined = out.iter().filter(|o| o.2).count();
    let determined_held = out.iter().filter(|o| o.3).count();
    let with_basins = out.iter().filter(|o| o.4 > 0).count();
    eprintln!(
        "JKR end, {n} curves: 95% held E* {:.3} w {:.3} lambda {:.3}; lambda determined in {determined}, held in {determined_held}; a second basin in {with_basins}",
        frac(&|o| o.1[0]),
        frac(&|o| o.1[1]),
        frac(&|o| o.1[2])
    );
    assert_eq!(
        out.iter().filter(|o| o.0).count(),
        out.len(),
        "every curve fitted"
    );
    for (k, name) in ["E*", "w", "lambda"].iter().enumerate() {
        let f = frac(&|o| o.1[k]);
        assert!(
            (0.91..=1.0).contains(&f),
            "{name}'s 95% interval holds the truth in {f}"
        );
    }
    // Not yet asserted: where lambda is called determined here (2 of the 200 curves) its
    // interval misses the truth. Both fits settle on the DMT side (lambda 0.02, w 3/4 of the
    // truth: the same pull-off) at the noise floor, and no profile point on the JKR side comes
    // within the 99% level, so no second basin is reported there. Fits at fixed lambda started
    // from the truth end no lower than the profile's JKR-side points (lambda 22.85: rms 1.0675e-10
    // N from the truth, 1.0530e-10 N on the DMT side): the noise draw favours the DMT side, a
    // property of the likelihood (its steps where the jump moves), not of the search.
    eprintln!("determined and holding the truth: {determined_held} of {determined}");
}

/// Long noisy curves are searched on their bins and finished on their points: over 100 curves of
/// 2000 points (lambda 0.05..50, three springs, noise 1% and 2% of the pull-off) the 95%
/// intervals hold the truth as the points' own fits do, and every fit reaches the noise floor.
#[test]
fn binned_long_curves_keep_their_coverage() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(23);
    let cases: Vec<(f64, f64, f64, u64)> = (0..100)
        .map(|i| {
            let lambda = 0.05 * 1000f64.powf(rng.random::<f64>());
            let spring = [2.0, 10.0, 40.0][i % 3];
            let noise = [0.01, 0.02][(i / 3) % 2] * 1.75 * std::f64::consts::PI * 0.05 * 20e-9;
            (lambda, spring, noise, i as u64 + 2000)
        })
        .collect();
    let out: Vec<(bool, [bool; 3], f64, bool)> = cases
        .par_iter()
        .map(|&(lambda, spring, noise, seed)| {
            let (mut s, opt) = case(Model::Md, lambda, spring, noise, seed);
            s.points = 2000;
            let r = fit_curve(&synthetic(&s), &opt);
            if r.status != FitStatus::Ok {
                return (false, [false; 3], f64::NAN, false);
            }
            (
                true,
                [
                    holds(r.e_star_pa_interval_95, 1.5e9),
                    holds(r.work_of_adhesion_j_m2_interval_95, 0.05),
                    holds(r.lambda_interval_95, lambda),
                ],
                r.rms_residual_n.unwrap() / noise,
                r.stop.ends_with("finished on the points"),
            )
        })
        .collect();
    let n = out.len() as f64;
    let binned = out.iter().filter(|o| o.3).count();
    let held: Vec<f64> = (0..3)
        .map(|k| out.iter().filter(|o| o.1[k]).count() as f64 / n)
        .collect();
    let worst = out.iter().map(|o| (o.2 - 1.0).abs()).fold(0.0, f64::max);
    eprintln!("{binned} of {n} curves fitted on bins: 95% held E* {:.2} w {:.2} lambda {:.2}; rms/noise worst {worst:.3} from 1", held[0], held[1], held[2]);
    assert!(out.iter().all(|o| o.0), "every curve fitted");
    assert!(binned >= 50, "{binned} curves fitted on bins");
    assert!(worst < 0.1, "a fit above the noise floor: {worst}");
    for (k, name) in ["E*", "w", "lambda"].iter().enumerate() {
        // 95% within what 100 binomial draws allow (sd 2.2%).
        assert!(
            held[k] >= 0.9,
            "{name}'s 95% interval holds the truth in {}",
            held[k]
        );
    }
}

/// A curve cut off inside its Dugdale zone: its far part, where the baseline is read, still
/// feels the zone's pull (a force offset), and no point lies beyond the zone's end. The zone's
/// shape along the curve still gives lambda: a fit may have a zone longer than the curve, and a
/// force offset up to the largest force measured (beyond that, its adhesion could trade against
/// the offset without end: `tabor.fit_afmformats` on the soft samples of python/tests).
#[test]
fn a_curve_cut_off_inside_its_zone_still_gives_its_lambda() {
    let (s, opt) = case(Model::Md, 0.05, 40.0, 2e-12, 11);
    let whole = synthetic(&s);
    let z0 = tabor::fit::z0_from_lambda(1.5e9, 0.05, 20e-9, 0.05);
    // The points within a third of the zone's range above the contact point.
    let keep: Vec<usize> = (0..whole.len())
        .filter(|&i| whole.height[i] < 40e-9 + z0 / 3.0)
        .collect();
    let cut = tabor::fit::Curve {
        segment: keep.iter().map(|&i| whole.segment[i]).collect(),
        height: keep.iter().map(|&i| whole.height[i]).collect(),
        force: keep.iter().map(|&i| whole.force[i]).collect(),
        ..whole.clone()
    };
    let span = |c: &tabor::fit::Curve| {
        let lo = c.height.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = c.height.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        hi - lo
    };
    assert!(
        span(&cut) < z0 && span(&whole) > z0,
        "the cut is inside the zone"
    );
    // (Cut, w trades a little against the offset: 1.6% found.)
    for (c, what, tol) in [
        (&whole, "the whole curve", 1e-2),
        (&cut, "the cut curve", 3e-2),
    ] {
        let r = fit_curve(c, &opt);
        assert_recovers(&r, 0.05, tol, what);
        assert_eq!(
            r.lambda_determined,
            Some(true),
            "{what}: {:?}",
            r.lambda_bound
        );
        assert!(
            rel(r.z0_m.unwrap(), z0) < tol,
            "{what}: z0 {:?} against {z0}",
            r.z0_m
        );
    }
}
