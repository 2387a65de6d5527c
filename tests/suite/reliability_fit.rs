//! The fitter on data that would give absurd fits: outlier spikes, units off by 1e9, options no
//! AFM has, repeated cycles, jittering heights, option values out of range, and data that once
//! made it panic. Each case against the clean curve's fit or a stated refusal.

use std::process::Command;
use tabor::fit::synthetic::{synthetic, Synthetic};
use tabor::fit::{fit_curve, Curve, CurveFit, Direction, FitOptions, FitStatus, Model, Params};

/// Maugis-Dugdale at lambda = 1 (E* = 1.5 GPa, w = 0.05 J/m^2, R = 20 nm) under a 2 N/m
/// cantilever, 400 points per segment, 10 pN of noise.
fn clean() -> (Curve, FitOptions) {
    let s = Synthetic {
        model: Model::Md,
        params: Params {
            e_star: 1.5e9,
            w: 0.05,
            lambda: 1.0,
            zc: 40e-9,
            f0: 0.0,
        },
        radius: 20e-9,
        spring: 2.0,
        points: 400,
        depth: 6.0,
        noise: 1e-11,
        seed: 5,
    };
    let opt = FitOptions {
        radius: s.radius,
        spring: s.spring,
        ..FitOptions::default()
    };
    (synthetic(&s), opt)
}

fn rel(x: f64, t: f64) -> f64 {
    (x / t - 1.0).abs()
}

fn ok(r: &CurveFit) -> (f64, f64) {
    assert_eq!(r.status, FitStatus::Ok, "{}", r.message);
    (r.e_star_pa.unwrap(), r.work_of_adhesion_j_m2.unwrap())
}

/// A refused fit carries its status and message, and no parameters.
fn refused(r: &CurveFit, status: FitStatus, says: &[&str]) {
    assert_eq!(r.status, status, "{}", r.message);
    for s in says {
        assert!(
            r.message.to_string().contains(s),
            "{s:?} not in {}",
            r.message
        );
    }
    assert!(r.e_star_pa.is_none() && r.work_of_adhesion_j_m2.is_none());
}

#[test]
fn a_spike_is_dropped_and_the_clean_parameters_come_back() {
    let (c, opt) = clean();
    let base = fit_curve(&c, &opt);
    let (e0, w0) = ok(&base);
    assert!(rel(e0, 1.5e9) < 0.05 && rel(w0, 0.05) < 0.05, "{e0} {w0}");
    // A point on the retract's contact part (point 451 of 800), and one in its free part.
    for (at, spikes) in [
        (450, vec![1e-6]),
        (450, vec![1.0]),
        (700, vec![1e200, -1e200]),
        (120, vec![-3e-7]),
    ] {
        let mut s = c.clone();
        for (k, f) in spikes.iter().enumerate() {
            s.force[at + k] = *f;
        }
        let r = fit_curve(&s, &opt);
        let (e, w) = ok(&r);
        assert!(
            rel(e, e0) < 1e-3 && rel(w, w0) < 1e-3,
            "spike {spikes:?} at {at}: E* {e} against {e0}, w {w} against {w0}"
        );
        assert_eq!(r.adequate_model, base.adequate_model, "{spikes:?}");
        assert!(
            r.warnings.iter().any(|w| w
                .contains(&format!("dropped {} outlier point", spikes.len()))
                && w.contains(&format!("point {}", at + 1))),
            "{spikes:?}: {:?}",
            r.warnings
        );
        assert_eq!(r.points_fitted + spikes.len() * (at >= 400) as usize, 400);
    }
    // The clean curve loses no point.
    assert!(
        !base.warnings.iter().any(|w| w.contains("outlier")),
        "{:?}",
        base.warnings
    );
    assert_eq!(base.points_fitted, 400);
}

#[test]
fn units_off_by_1e9_and_options_no_afm_has_are_refused_with_the_cause() {
    let (c, opt) = clean();
    let mut nn = c.clone();
    nn.force.iter_mut().for_each(|f| *f *= 1e9);
    refused(
        &fit_curve(&nn, &opt),
        FitStatus::NotConverged,
        &["outside physical sense", "10..1e12 Pa", "in nN"],
    );
    let mut nm = c.clone();
    nm.height.iter_mut().for_each(|h| *h *= 1e9);
    refused(
        &fit_curve(&nm, &opt),
        FitStatus::NotConverged,
        &["outside physical sense", "in nm"],
    );
    // A spring so soft that the tip never presses: no point in contact.
    let soft = FitOptions {
        spring: 1e-30,
        ..opt.clone()
    };
    // Refused as no contact, or as a modulus below physical sense; either way naming the spring.
    let r = fit_curve(&c, &soft);
    if r.status == FitStatus::NoContact {
        refused(
            &r,
            FitStatus::NoContact,
            &["no fitted point is in contact", "spring constant 1e-30 N/m"],
        );
    } else {
        refused(
            &r,
            FitStatus::NotConverged,
            &["outside physical sense", "spring constant 1e-30 N/m"],
        );
    }
    // A curve measured with a 40 N/m cantilever fitted with 2 N/m: E* came out 5e59 Pa, `ok`.
    let mut stiff = c.clone();
    for i in 0..stiff.len() {
        // The same forces at the heights of a 20 times stiffer cantilever (deflection F/k).
        stiff.height[i] += stiff.force[i] / 2.0 - stiff.force[i] / 40.0;
    }
    let r = fit_curve(&stiff, &opt);
    let fine = fit_curve(
        &stiff,
        &FitOptions {
            spring: 40.0,
            ..opt.clone()
        },
    );
    let (e, _) = ok(&fine);
    assert!(rel(e, 1.5e9) < 0.05, "{e}");
    refused(
        &r,
        FitStatus::NotConverged,
        &["outside physical sense", "check the spring constant"],
    );
    let big = FitOptions {
        radius: 1.0,
        ..opt.clone()
    };
    // A 1 m tip: refused, or a fit whose warnings say that its numbers rest on that radius.
    let r = fit_curve(&c, &big);
    let says = "the tip radius 1 m is not an AFM tip's";
    if r.status == FitStatus::Ok {
        assert!(
            r.warnings.iter().any(|w| w.contains(says)),
            "{:?}",
            r.warnings
        );
    } else {
        assert!(r.message.to_string().contains(says), "{}", r.message);
        assert!(r.e_star_pa.is_none());
    }
}

#[test]
fn a_fit_far_above_the_noise_warns() {
    // A drift the model cannot follow: 1 nN per 10 nm of height added to the retract's contact.
    let (mut c, opt) = clean();
    let top = c.height.iter().cloned().fold(f64::INFINITY, f64::min);
    for i in 0..c.len() {
        if c.segment[i] == Direction::Retract && c.force[i] > 0.0 {
            c.force[i] += 0.3e-9 * (((c.height[i] - top) / 1e-9).sin());
        }
    }
    let r = fit_curve(&c, &opt);
    assert!(
        r.warnings
            .iter()
            .any(|w| w.contains("the fit does not describe this curve")),
        "{} {:?}",
        r.message,
        r.warnings
    );
    // The clean curve's residual is its noise: no such warning.
    let (c, opt) = clean();
    let r = fit_curve(&c, &opt);
    assert!(!r.warnings.iter().any(|w| w.contains("does not describe")));
    let rms = r.rms_residual_n.unwrap();
    assert!(rel(rms, 1e-11) < 0.2, "{rms}");
}

#[test]
fn repeated_cycles_are_refused_by_curve() {
    let (c, opt) = clean();
    let mut two = c.clone();
    two.segment.extend(c.segment.clone());
    two.height.extend(c.height.clone());
    two.force.extend(c.force.clone());
    refused(
        &fit_curve(&two, &opt),
        FitStatus::InvalidInput,
        &[
            "2 approach-retract cycles",
            "from retract to approach at point 801",
        ],
    );
    // Two retracts in one segment: the heights go back at the second's first point.
    let mut again = c.clone();
    for i in 400..800 {
        again.segment.push(Direction::Retract);
        again.height.push(c.height[i]);
        again.force.push(c.force[i]);
    }
    refused(
        &fit_curve(&again, &opt),
        FitStatus::InvalidInput,
        &["retract heights go back", "at point 801", "restarts"],
    );
}

#[test]
fn heights_that_jitter_more_than_their_step_are_fitted_with_a_note() {
    let (c, opt) = clean();
    let (e0, w0) = ok(&fit_curve(&c, &opt));
    let step = (c.height[1] - c.height[0]).abs();
    let mut j = c.clone();
    // A deterministic jitter of 1.5 steps, alternating: half the steps go back.
    for (i, h) in j.height.iter_mut().enumerate() {
        *h += 1.5 * step * if i % 2 == 0 { 1.0 } else { -1.0 } * ((i % 3) as f64 / 2.0);
    }
    let r = fit_curve(&j, &opt);
    let (e, w) = ok(&r);
    assert!(rel(e, e0) < 0.05 && rel(w, w0) < 0.05, "{e} {w}");
    assert!(
        r.warnings
            .iter()
            .any(|w| w.contains("heights jitter") && w.contains("more than their mean step")),
        "{:?}",
        r.warnings
    );
    assert!(!r.message.to_string().contains("sort"));
    // Reversed heights are still refused, saying what is wrong.
    let mut rev = c.clone();
    rev.height[400..].reverse();
    refused(
        &fit_curve(&rev, &opt),
        FitStatus::InvalidInput,
        &[
            "retract heights are not in order",
            "must increase the height",
        ],
    );
}

#[test]
fn huge_forces_give_a_status_not_a_panic_and_the_batch_goes_on() {
    let (c, opt) = clean();
    // A third of the retract at +-1e200, and a curve scaled by 1e190.
    let mut many = c.clone();
    for i in (400..800).step_by(3) {
        many.force[i] = if i % 2 == 0 { 1e200 } else { -1e200 };
    }
    let mut huge = c.clone();
    huge.force.iter_mut().for_each(|f| *f *= 1e190);
    for bad in [&many, &huge] {
        let r = fit_curve(bad, &opt);
        assert_ne!(r.status, FitStatus::Ok, "{}", r.message);
        assert!(r.e_star_pa.is_none(), "{}", r.message);
        assert!(
            r.message.to_string().contains("forces reach"),
            "{}",
            r.message
        );
    }
    // Through the command line: exit 0, the good curve fitted, each bad one its status.
    let input = csv_of(&[("good", &c), ("many", &many), ("huge", &huge)]);
    let out = tabor(
        &["fit", "-i", "-", "--radius", "20e-9", "--spring-n-m", "2"],
        &input,
    );
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let status: Vec<&str> = v["curves"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["status"].as_str().unwrap())
        .collect();
    assert_eq!(status[0], "ok");
    assert!(status[1..].iter().all(|s| *s != "ok"), "{status:?}");
}

#[test]
fn option_values_out_of_range_are_one_check_in_the_library() {
    let (c, opt) = clean();
    for (o, says) in [
        (
            FitOptions {
                poisson: Some(5.0),
                ..opt.clone()
            },
            "Poisson ratio 5 must be in (-1, 0.5]",
        ),
        (
            FitOptions {
                tolerance: 5.0,
                ..opt.clone()
            },
            "adequate-model tolerance 5 must be",
        ),
        (
            FitOptions {
                tolerance: -1.0,
                ..opt.clone()
            },
            "adequate-model tolerance -1 must be",
        ),
        (
            FitOptions {
                z0: Some(1.0),
                ..opt.clone()
            },
            "Lennard-Jones range z0 1 m must be between 1e-12 and 1e-6 m",
        ),
        (
            FitOptions {
                z0: Some(1e-30),
                ..opt.clone()
            },
            "Lennard-Jones range z0 1e-30 m must be between",
        ),
        (
            FitOptions {
                baseline_fraction: 0.0,
                ..opt.clone()
            },
            "baseline fraction 0 must be in (0, 1]",
        ),
    ] {
        let e = o.validate().unwrap_err();
        assert!(e.message.contains(says), "{}", e.message);
        assert!(!e.message.contains("--"), "{}", e.message);
        refused(&fit_curve(&c, &o), FitStatus::InvalidInput, &[says]);
    }
    assert!(opt.validate().is_ok());
    // The command line makes the same check, naming its flag: one line, exit 1.
    let input = csv_of(&[("good", &c)]);
    for (args, says) in [
        (vec!["--poisson", "5"], "--poisson: Poisson ratio 5"),
        (
            vec!["--tolerance", "5"],
            "--tolerance: adequate-model tolerance 5",
        ),
        (
            vec!["--tolerance=-1"],
            "--tolerance: adequate-model tolerance -1",
        ),
        (vec!["--z0", "1"], "--z0: Lennard-Jones range z0 1 m"),
        (
            vec!["--z0", "1e-30"],
            "--z0: Lennard-Jones range z0 1e-30 m",
        ),
    ] {
        let mut a = vec!["fit", "-i", "-", "--radius", "20e-9", "--spring-n-m", "2"];
        a.extend(args);
        let out = tabor(&a, &input);
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(
            err.starts_with("error: ") && err.contains(says) && err.lines().count() == 1,
            "{err}"
        );
        assert!(out.stdout.is_empty());
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
    // The command may refuse before reading its input.
    let _ = child.stdin.take().unwrap().write_all(stdin.as_bytes());
    child.wait_with_output().unwrap()
}

fn csv_of(curves: &[(&str, &Curve)]) -> String {
    let mut s = String::from("curve,segment,height_m,force_n\n");
    for (id, c) in curves {
        for k in 0..c.len() {
            let seg = match c.segment[k] {
                Direction::Approach => "approach",
                Direction::Retract => "retract",
            };
            s += &format!("{id},{seg},{:e},{:e}\n", c.height[k], c.force[k]);
        }
    }
    s
}

#[test]
fn the_generator_says_why_parameters_give_no_curve() {
    use tabor::fit::synthetic::try_synthetic;
    use tabor::fit::SyntheticError;
    let s = Synthetic {
        model: Model::Md,
        params: Params {
            e_star: 1.5e9,
            w: 0.05,
            lambda: 1.0,
            zc: 40e-9,
            f0: 0.0,
        },
        radius: 20e-9,
        spring: 2.0,
        points: 50,
        depth: 6.0,
        noise: 1e-11,
        seed: 1,
    };
    assert_eq!(try_synthetic(&s).unwrap().len(), 100);
    let mut nan = s.clone();
    nan.noise = f64::NAN;
    let e = try_synthetic(&nan).unwrap_err();
    assert!(
        matches!(e, SyntheticError::Noise(n) if n.is_nan())
            && e.to_string().contains("force noise NaN")
    );
    let mut far = s.clone();
    far.params.lambda = 1e30;
    let e = try_synthetic(&far).unwrap_err();
    assert!(e == SyntheticError::Lambda(1e30) && e.to_string().contains("lambda 1e30"));
    let mut soft = s.clone();
    soft.params.e_star = -1.0;
    let e = try_synthetic(&soft).unwrap_err();
    assert!(
        matches!(e, SyntheticError::Numbers { e_star, .. } if e_star == -1.0)
            && e.to_string().contains("must be positive")
    );
}

/// "No contact" only where no segment of the curve shows contact: a retract that never rises
/// above the baseline while the approach does is refused naming the segment and what to fit.
#[test]
fn a_retract_without_contact_beside_an_approach_with_it_is_not_no_contact() {
    let (c, opt) = clean();
    let far = c.force[0];
    let mut lifted = c.clone();
    for (f, d) in lifted.force.iter_mut().zip(&c.segment) {
        if *d == Direction::Retract {
            *f = far;
        }
    }
    refused(
        &fit_curve(&lifted, &opt),
        FitStatus::InvalidInput,
        &[
            "the retract never rises above five times the baseline's noise (largest ",
            ") while the approach does (up to ",
            "fit the approach segment instead",
        ],
    );
    let mut flat = lifted.clone();
    flat.force.fill(far);
    refused(
        &fit_curve(&flat, &opt),
        FitStatus::NoContact,
        &["no contact: no segment of the curve rises above the baseline"],
    );
}
