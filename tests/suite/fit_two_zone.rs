//! The two-zone law (the solid's Dugdale zone plus a water meniscus) fitted to a humid curve's
//! shape through the law layer (`tabor::law`): its path under the cantilever against
//! the two-zone solver's states and the cycle's exact spring fold (an independent follower),
//! and fits of curves made with a known solid: noise-free ones give it back, a noisy one whose
//! curve cannot fix lambda brackets it, through the library and the command line.

use std::process::Command;
use tabor::cycle::{Drive, Phase};
use tabor::fit::synthetic::{try_synthetic_wet, Synthetic};
use tabor::fit::Direction;
use tabor::fit::{fit_curve, Curve, DrivenPath, FitOptions, Model, Params};
use tabor::law::{ContactLaw, Piece};
use tabor::physics::two_zone::Zones;
use tabor::scene::humidity::HumidityInput;
use tabor::solver::two_zone::TwoZoneContext;
use tabor::solver::Status;

/// Meniscus longer-ranged than the solid's zone (as in most humid AFM contacts), much longer,
/// and shorter and stronger.
const LAWS: [(f64, f64, f64); 3] = [(0.5, 0.2, 5.0), (2.0, 0.05, 10.0), (1.0, 3.0, 0.3)];

/// On the stable part of the contact branch, the path's load at each base displacement is the
/// solver's state there (its own root search in the curve's parameter), and the retract leaves
/// the contact branch at the cycle's spring fold (`TwoZoneContext::spring_fold`, bisection on
/// the control's slope): 1e-9 above it the path is on contact near the fold's load, 1e-9
/// below it the path has jumped.
#[test]
fn the_path_under_a_spring_is_the_solvers_states_and_jumps_at_its_fold() {
    for (lambda, rho, eta) in LAWS {
        let ctx = TwoZoneContext::new(Zones::from_ratios(lambda, rho, eta).unwrap()).unwrap();
        for kbar in [0.5, 2.0] {
            let at = format!("lambda {lambda}, ratios {rho} {eta}, kbar {kbar}");
            let path = DrivenPath::of(ContactLaw::solid_and_meniscus(lambda, rho, eta), kbar, 8.0);
            let cycle = tabor::cycle::run(
                &ContactLaw::solid_and_meniscus(lambda, rho, eta),
                Drive::Spring(kbar),
                30.0,
            )
            .unwrap();
            let fold = cycle
                .jumps
                .iter()
                .find(|j| j.phase == Phase::Retract)
                .unwrap()
                .from;
            let fold_delta = fold.approach + fold.load / kbar;
            let mut compared = 0;
            for k in 1..=60 {
                let a = fold.a * (1.0 + 1e-3) + 3.0 * k as f64 / 60.0;
                let s = ctx.state_at_radius(a);
                assert_eq!(s.status, Status::Ok, "{at}: a {a}");
                let delta = s.approach + s.load / kbar;
                if delta > 7.5 {
                    break;
                }
                let p = path.at(delta, Direction::Retract);
                assert_eq!(p.piece, Piece::Contact, "{at}: a {a}");
                assert!(
                    (p.load - s.load).abs() <= 1e-9 * s.load.abs().max(1.0),
                    "{at}: a {a}: path {} solver {}",
                    p.load,
                    s.load
                );
                assert!((p.a / a - 1.0).abs() <= 1e-9, "{at}: a {a}: path a {}", p.a);
                compared += 1;
            }
            assert!(compared >= 10, "{at}: {compared} states compared");
            // Within 1e-9 of the fold, the load is within about sqrt(1e-9) of the fold's.
            let on = path.at(fold_delta + 1e-9, Direction::Retract);
            assert_eq!(on.piece, Piece::Contact, "{at}");
            assert!(
                (on.load - fold.load).abs() <= 3e-5 * fold.load.abs(),
                "{at}: path {} fold {}",
                on.load,
                fold.load
            );
            let below = path.at(fold_delta - 1e-9, Direction::Retract);
            assert_ne!(below.piece, Piece::Contact, "{at}: {below:?}");
        }
    }
}

/// Where the retract leaves the contact branch, the path lands where the cycle does (its
/// landing at the jump's control on the stable branch below: the meniscus' stretch of the
/// non-contact branch, or free), for the two-zone laws and Maugis-Dugdale; and where the
/// contact branch runs out without a fold (a stiff spring), Maugis-Dugdale's path goes on along
/// the non-contact branch, `Delta = (1/2 - pi lambda / (2 kbar)) C^2 - 8 lambda C / (3 pi) - 2 /
/// (pi lambda)` with the load `-(pi lambda / 2) C^2` in closed form, down to its fold.
#[test]
fn retract_landings_are_the_cycles() {
    let mut laws: Vec<(ContactLaw, f64)> = LAWS
        .iter()
        .flat_map(|&(l, r, e)| [0.5, 2.0].map(|k| (ContactLaw::solid_and_meniscus(l, r, e), k)))
        .collect();
    laws.extend([(0.3, 5.0), (1.0, 20.0), (3.0, 2.0)].map(|(l, k)| (ContactLaw::md(l), k)));
    let mut landed_on_the_meniscus = 0;
    for (law, kbar) in laws {
        let at = format!("{law:?}, kbar {kbar}");
        let path = DrivenPath::of(law, kbar, 8.0);
        let cycle = tabor::cycle::run(&law, Drive::Spring(kbar), 30.0).unwrap();
        for j in cycle.jumps.iter().filter(|j| j.phase == Phase::Retract) {
            if j.from.branch != tabor::cycle::Branch::Contact {
                continue;
            }
            let to = j.to.unwrap();
            let control = j.from.approach + j.from.load / kbar;
            let p = path.at(control - 1e-9, Direction::Retract);
            assert!(
                (p.load - to.load).abs() <= 1e-6 * to.load.abs().max(1.0),
                "{at}: path {p:?}, cycle {to:?}"
            );
            if to.load < -1e-3 {
                assert_eq!(p.piece, Piece::NonContact, "{at}");
                landed_on_the_meniscus += 1;
            }
        }
    }
    assert!(landed_on_the_meniscus >= 2, "{landed_on_the_meniscus}");
    // Maugis-Dugdale at lambda 0.5 under kbar 50: no fold on the contact branch.
    let (lambda, kbar) = (0.5, 50.0);
    let path = DrivenPath::of(ContactLaw::md(lambda), kbar, 8.0);
    let pi = std::f64::consts::PI;
    let (a2, a1, a0) = (
        0.5 - pi * lambda / (2.0 * kbar),
        -8.0 * lambda / (3.0 * pi),
        -2.0 / (pi * lambda),
    );
    let c_fold = -a1 / (2.0 * a2);
    let c_end = tabor::physics::md::zero_radius_end(lambda).c;
    for k in 1..20 {
        let c = c_fold + (c_end - c_fold) * k as f64 / 20.0;
        let delta = a2 * c * c + a1 * c + a0;
        let p = path.at(delta, Direction::Retract);
        assert_eq!(p.piece, Piece::NonContact, "C {c}");
        let load = -(pi * lambda / 2.0) * c * c;
        assert!(
            (p.load - load).abs() <= 1e-9,
            "C {c}: {} against {load}",
            p.load
        );
    }
}

const R: f64 = 20e-9;
const SPRING: f64 = 2.0;

/// A curve of the two-zone law with the solid (E* 1.5 GPa, `w`, `lambda`) in water at `rh` and
/// `angle_deg`, with Gaussian force noise `noise` (N).
fn wet_curve(rh: f64, angle_deg: f64, w: f64, lambda: f64, noise: f64) -> Curve {
    let h = HumidityInput::water(rh, angle_deg);
    let s = Synthetic {
        model: Model::SolidAndMeniscus,
        params: Params {
            e_star: 1.5e9,
            w,
            lambda,
            zc: 40e-9,
            f0: 0.0,
        },
        radius: R,
        spring: SPRING,
        points: 400,
        depth: 6.0,
        noise,
        seed: 3,
    };
    try_synthetic_wet(&s, h.stress_and_range().unwrap()).unwrap()
}

fn options(rh: f64, angle_deg: f64) -> FitOptions {
    FitOptions {
        radius: R,
        spring: SPRING,
        humidity: Some(HumidityInput::water(rh, angle_deg)),
        ..FitOptions::default()
    }
}

fn rel(x: f64, t: f64) -> f64 {
    (x / t - 1.0).abs()
}

/// The curve the fit's forward model makes in SI units is the dimensional two-zone solver's,
/// with the solid's zone from the textbook Maugis parameter, `lambda = 2 s1 (R / (pi w
/// K^2))^(1/3)` over `h1 = w / s1`, and the meniscus's zone: at each compressive retract
/// point, the contact radius whose load is the measured force gives the tip's approach, the
/// base's displacement less the cantilever's deflection. This checks the fit's units and its
/// ratios of the zones (`law::solid_and_meniscus_of`), which the curves made and fitted with
/// them cannot.
#[test]
fn the_wet_curve_is_the_dimensional_solvers() {
    use tabor::solver::two_zone::state_at_radius_dimensional;
    let (rh, angle, w, lambda) = (0.7, 10.0, 0.03, 0.5);
    let c = wet_curve(rh, angle, w, lambda, 0.0);
    let (s2, h2) = HumidityInput::water(rh, angle).stress_and_range().unwrap();
    let k = 4.0 / 3.0 * 1.5e9;
    let s1 = 0.5 * lambda * (std::f64::consts::PI * w * k * k / R).cbrt();
    let h1 = w / s1;
    let load_at = |a: f64| {
        let s = state_at_radius_dimensional(k, R, s1, h1, s2, h2, a).unwrap();
        assert_eq!(s.status, Status::Ok);
        s
    };
    let mut compared = 0;
    for i in 0..c.len() {
        let f = c.force[i];
        if c.segment[i] != Direction::Retract || f <= 1e-9 || i % 3 != 0 {
            continue;
        }
        // The load rises with the radius on the compressive part: bisection in a.
        let (mut lo, mut hi) = (1e-12, R);
        for _ in 0..64 {
            let mid = 0.5 * (lo + hi);
            if load_at(mid).load < f {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let s = load_at(0.5 * (lo + hi));
        let tip = (40e-9 - c.height[i]) - f / SPRING;
        assert!(
            (s.approach - tip).abs() <= 1e-9 * tip.abs().max(1e-9),
            "point {i}: force {f}: solver's approach {} against the curve's {tip}",
            s.approach
        );
        compared += 1;
    }
    assert!(compared > 15, "{compared} points compared");
}

/// Noise-free wet curves where the meniscus reaches beyond the one zone's range (the pull-off's
/// reading is doubtful, and off): the shape fit gives back E*, the solid's w and lambda, and its
/// profile fixes lambda.
#[test]
fn noise_free_wet_curves_give_back_their_solid() {
    for (rh, angle, w, lambda) in [(0.7, 10.0, 0.03, 0.5), (0.4, 20.0, 0.05, 1.0)] {
        let at = format!("RH {rh}, {angle} degrees, w {w}, lambda {lambda}");
        let r = fit_curve(&wet_curve(rh, angle, w, lambda, 0.0), &options(rh, angle));
        let h = r.humidity.as_ref().unwrap();
        assert!(!h.fair_reading, "{at}: {}", h.note);
        let reading = h.solid_work_of_adhesion_j_m2.unwrap();
        assert!(
            rel(reading, w) > 0.01,
            "{at}: the reading {reading} is already right"
        );
        let s = h
            .shape_fit
            .as_ref()
            .unwrap_or_else(|| panic!("{at}: {}", h.note));
        let f = &s.fit;
        assert!(rel(f.e_star_pa, 1.5e9) < 1e-6, "{at}: E* {}", f.e_star_pa);
        assert!(
            rel(f.work_of_adhesion_j_m2, w) < 1e-6,
            "{at}: w {}",
            f.work_of_adhesion_j_m2
        );
        assert!(
            rel(f.lambda.unwrap(), lambda) < 1e-5,
            "{at}: lambda {:?}",
            f.lambda
        );
        assert_eq!(s.lambda_bounded, Some(true), "{at}: {:?}", s.lambda_profile);
        let [lo, hi] = s.lambda_95.unwrap();
        let near = |l: f64| rel(l, lambda) < 1e-5;
        assert!(
            (lo <= lambda || near(lo)) && (lambda <= hi || near(hi)),
            "{at}: {lo} {hi}"
        );
        assert!(hi / lo < 1.01, "{at}: {lo} {hi}");
        assert!(
            h.note
                .contains("the two-zone law fitted to the curve's shape"),
            "{at}"
        );
    }
}

/// A noisy curve in near-saturated air, where the meniscus' work exceeds the solid's: the
/// misfit's profile over the solid's lambda is flat within the noise, so lambda is reported as
/// not fixed, and the 95% sets of lambda and of the solid's w hold the truth.
#[test]
fn a_noisy_curve_that_cannot_fix_lambda_brackets_its_solid() {
    let (rh, angle, w, lambda) = (0.9, 0.0, 0.1, 2.0);
    let r = fit_curve(&wet_curve(rh, angle, w, lambda, 1e-11), &options(rh, angle));
    let h = r.humidity.as_ref().unwrap();
    let s = h.shape_fit.as_ref().unwrap_or_else(|| panic!("{}", h.note));
    assert_eq!(s.lambda_bounded, Some(false), "{:?}", s.lambda_profile);
    let [lo, hi] = s.lambda_95.unwrap();
    assert!(lo <= lambda && lambda <= hi, "lambda 95%: {lo} {hi}");
    let [wlo, whi] = s.solid_w_95.unwrap();
    assert!(wlo <= w && w <= whi, "w 95%: {wlo} {whi}");
    // Its misfit is the noise's, as is the one zone's.
    let rms = s.fit.rms_residual_n;
    assert!(
        rms < 1.1e-11 && rms <= r.rms_residual_n.unwrap() * 1.001,
        "{rms}"
    );
}

/// `tabor fit --relative-humidity` writes the shape fit into the JSON and its columns into the
/// CSV table (`tests/data/wet_curve.csv`: `examples/wet_curve.rs`'s curve, the first case of
/// `noise_free_wet_curves_give_back_their_solid`).
#[test]
fn the_command_line_reports_the_shape_fit() {
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/wet_curve.csv");
    let run = |format: &str| {
        let out = Command::new(env!("CARGO_BIN_EXE_tabor"))
            .args(["fit", "-i", data, "--radius", "20e-9", "--spring-n-m", "2"])
            .args(["--relative-humidity", "0.7", "--contact-angle-deg", "10"])
            .args(["--format", format])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let j: serde_json::Value = serde_json::from_str(&run("json")).unwrap();
    let s = &j["curves"][0]["humidity"]["shape_fit"];
    assert_eq!(s["fit"]["model"], "solid_and_meniscus", "{s}");
    let w = s["fit"]["work_of_adhesion_j_m2"].as_f64().unwrap();
    assert!(rel(w, 0.03) < 1e-6, "{s}");
    assert_eq!(s["lambda_bounded"], true, "{s}");
    let table = run("csv");
    let mut reader = csv::Reader::from_reader(table.as_bytes());
    let header = reader.headers().unwrap().clone();
    let row = reader.records().next().unwrap().unwrap();
    let col = |name: &str| {
        let i = header.iter().position(|h| h == name).unwrap();
        row[i].to_string()
    };
    assert!(
        rel(
            col("shape_solid_work_of_adhesion_j_m2").parse().unwrap(),
            0.03
        ) < 1e-6
    );
    assert!(rel(col("shape_solid_lambda").parse().unwrap(), 0.5) < 1e-5);
    assert_eq!(col("shape_fit_status"), "ok");
    assert_eq!(col("shape_lambda_bounded"), "true");
}
