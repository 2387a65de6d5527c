//! Force curves whose last retract point before the jump lies exactly at the fold (as measured
//! curves do), made by a generator independent of the fitter's path evaluation (`law::follow`):
//! the Maugis-Dugdale curve of `physics::md` under the spring, its fold and each state found here
//! by bisection, the Dugdale zone's non-contact branch in closed form.

use rayon::prelude::*;
use std::f64::consts::PI;
use tabor::fit::{fit_curve, Curve, CurveFit, Direction, FitOptions, FitStatus};
use tabor::physics::md::{curve_point, zero_radius_end};

const E_STAR: f64 = 1.5e9;
const W: f64 = 0.05;
const RADIUS: f64 = 20e-9;
const ZC: f64 = 40e-9;

/// (force unit pi w R, approach unit, kbar) for spring constant k.
fn units(k: f64) -> (f64, f64, f64) {
    let kk = 4.0 / 3.0 * E_STAR;
    let force = PI * W * RADIUS;
    let approach = (PI * PI * W * W * RADIUS / (kk * kk)).cbrt();
    (force, approach, k * approach / force)
}

/// Delta = Dbar + Pbar/kbar on the contact branch at mu, its load and dDelta/dmu.
fn contact(lambda: f64, kbar: f64, mu: f64) -> (f64, f64, f64) {
    let c = curve_point(lambda, mu);
    (
        c.approach + c.load / kbar,
        c.load,
        c.dapproach_dmu + c.dload_dmu / kbar,
    )
}

/// Bisection on a monotone function of ln mu: the root of f between mu0 and mu1 (f changes sign).
fn bisect(f: impl Fn(f64) -> f64, mu0: f64, mu1: f64) -> f64 {
    let (mut lo, mut hi) = (mu0.ln(), mu1.ln());
    let s_lo = f(lo.exp()) > 0.0;
    if s_lo == (f(hi.exp()) > 0.0) {
        // No sign change (a root at an end, to rounding): the nearer end.
        return if f(mu0).abs() <= f(mu1).abs() {
            mu0
        } else {
            mu1
        };
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if !(mid > lo && mid < hi) {
            break;
        }
        if (f(mid.exp()) > 0.0) == s_lo {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (a, b) = (lo.exp(), hi.exp());
    if f(a).abs() <= f(b).abs() {
        a
    } else {
        b
    }
}

/// Delta on the non-contact branch at cohesive-zone radius C: a quadratic a2 C^2 + a1 C + a0.
fn non_contact(lambda: f64, kbar: f64) -> (f64, f64, f64) {
    (
        0.5 - PI * lambda / (2.0 * kbar),
        -8.0 * lambda / (3.0 * PI),
        -2.0 / (PI * lambda),
    )
}

/// The retract under the spring from Delta = 6 (approach units) until the jump-out, the last
/// point exactly at the fold, then the same spacing down past the force's reach: `n` points
/// before the jump, 0.7 n after. Heights and forces in SI units.
fn retract(lambda: f64, k: f64, n: usize) -> Curve {
    let (fu, du, kbar) = units(k);
    let (a2, a1, a0) = non_contact(lambda, kbar);
    let c_end = zero_radius_end(lambda).c;
    let nc_delta = |c: f64| a2 * c * c + a1 * c + a0;
    // The contact branch from deep contact (mu small) out: the first fold, where dDelta/dmu
    // turns from negative.
    // From mu = 1e-4 (contact radii of thousands, far beyond Delta = 6; below it the slopes
    // lose their precision), in steps of 0.1% to 1e8.
    let mus: Vec<f64> = (0..=12000)
        .map(|i| 10f64.powf(-4.0 + i as f64 * 1e-3))
        .collect();
    assert!(contact(lambda, kbar, mus[0]).0 > 6.0);
    let fold_at = mus
        .windows(2)
        .find(|w| contact(lambda, kbar, w[1]).2 >= 0.0)
        .map(|w| bisect(|m| contact(lambda, kbar, m).2, w[0], w[1]));
    let mu_top = bisect(
        |m| contact(lambda, kbar, m).0 - 6.0,
        1e-4,
        fold_at.unwrap_or(1e8),
    );
    // Where the stretch before the jump ends, and its Delta at the fold.
    let c_star = -a1 / (2.0 * a2);
    let delta_fold = match fold_at {
        Some(mu) => contact(lambda, kbar, mu).0,
        None => {
            assert!(
                a2 > 0.0 && c_star < c_end,
                "lambda {lambda}, k {k}: no fold on either branch"
            );
            nc_delta(c_star)
        }
    };
    let delta_end = contact(lambda, kbar, 1e8).0;
    // The pre-jump state at Delta: load.
    let before = |d: f64| -> f64 {
        match fold_at {
            Some(mu_f) => {
                contact(
                    lambda,
                    kbar,
                    bisect(|m| contact(lambda, kbar, m).0 - d, mu_top, mu_f),
                )
                .1
            }
            None if d > delta_end => {
                contact(
                    lambda,
                    kbar,
                    bisect(|m| contact(lambda, kbar, m).0 - d, mu_top, 1e8),
                )
                .1
            }
            None => {
                let c = (-a1 + (a1 * a1 - 4.0 * a2 * (a0 - d)).max(0.0).sqrt()) / (2.0 * a2);
                -(PI * lambda / 2.0) * c * c
            }
        }
    };
    // After the jump: the stable non-contact branch (C above its fold c_star) where it holds a
    // state at the jump's Delta, else free. A landing on the contact branch is not generated.
    let landed_nc = fold_at.is_some()
        && a2 > 0.0
        && c_star < c_end
        && nc_delta(c_star) <= delta_fold
        && nc_delta(c_end) >= delta_fold;
    if let Some(mu_f) = fold_at {
        let lands = mus.windows(2).filter(|w| w[0] > mu_f).any(|w| {
            let (d0, _, s0) = contact(lambda, kbar, w[0]);
            let (d1, _, s1) = contact(lambda, kbar, w[1]);
            s0 < 0.0 && s1 < 0.0 && (d0 - delta_fold) * (d1 - delta_fold) <= 0.0
        });
        assert!(
            !lands,
            "lambda {lambda}, k {k}: lands on the contact branch"
        );
        assert!(
            landed_nc || delta_fold <= a0,
            "lambda {lambda}, k {k}: no state after the jump"
        );
    }
    let after = |d: f64| -> f64 {
        if landed_nc && d >= nc_delta(c_star) {
            let c = (-a1 + (a1 * a1 - 4.0 * a2 * (a0 - d)).max(0.0).sqrt()) / (2.0 * a2);
            -(PI * lambda / 2.0) * c * c
        } else {
            assert!(
                d <= a0,
                "lambda {lambda}, k {k}: free at Delta {d} above {a0}"
            );
            0.0
        }
    };
    let h = (6.0 - delta_fold) / (n - 1) as f64;
    let mut deltas: Vec<f64> = (0..n).map(|j| 6.0 - j as f64 * h).collect();
    deltas[n - 1] = delta_fold;
    let mut load: Vec<f64> = deltas.iter().map(|&d| before(d)).collect();
    for j in 1..=(7 * n / 10) {
        let d = delta_fold - j as f64 * h;
        deltas.push(d);
        load.push(after(d));
    }
    Curve {
        id: format!("fold-{lambda}-{k}"),
        x: None,
        y: None,
        segment: vec![Direction::Retract; deltas.len()],
        height: deltas.iter().map(|d| ZC - d * du).collect(),
        force: load.iter().map(|p| p * fu).collect(),
        ..Curve::default()
    }
}

fn rel(x: f64, t: f64) -> f64 {
    (x / t - 1.0).abs()
}

fn recovered(r: &CurveFit, lambda: f64) -> f64 {
    assert_eq!(r.status, FitStatus::Ok, "{}: {}", r.curve, r.message);
    rel(r.e_star_pa.unwrap(), E_STAR)
        .max(rel(r.work_of_adhesion_j_m2.unwrap(), W))
        .max(rel(r.lambda.unwrap(), lambda))
}

fn opt(k: f64) -> FitOptions {
    FitOptions {
        radius: RADIUS,
        spring: k,
        ..FitOptions::default()
    }
}

/// Noise-free curves ending exactly at the fold recover E*, w and lambda to 1e-8, with and without
/// the fold's point: a point at the fold is fitted like any other.
#[test]
fn a_point_at_the_fold_is_fitted_like_any_other() {
    let cases = [
        (0.05, 0.5),
        (0.3, 2.0),
        (0.7, 2.083),
        (1.0, 0.5),
        (3.0, 2.0),
        (3.0, 40.0),
        (10.0, 10.0),
        (30.0, 1.0),
    ];
    let errs: Vec<(f64, f64, f64, f64)> = cases
        .par_iter()
        .map(|&(lambda, k)| {
            let c = retract(lambda, k, 300);
            let with = recovered(&fit_curve(&c, &opt(k)), lambda);
            // The same curve without the fold's point.
            let i = c
                .force
                .iter()
                .enumerate()
                .fold(0, |b, (i, f)| if *f < c.force[b] { i } else { b });
            let mut d = c.clone();
            let last = (i..d.len() - 1)
                .find(|&j| d.force[j + 1] > d.force[j] + 0.1 * (-d.force[i]))
                .expect("a jump");
            d.height.remove(last);
            d.force.remove(last);
            d.segment.remove(last);
            let without = recovered(&fit_curve(&d, &opt(k)), lambda);
            (lambda, k, with, without)
        })
        .collect();
    for &(lambda, k, with, without) in &errs {
        println!("lambda {lambda:5}, k {k:5} N/m (kbar {:.3}): largest relative error {with:.2e} with the fold's point, {without:.2e} without", units(k).2);
    }
    for (lambda, k, with, without) in errs {
        assert!(
            with < 1e-8 && without < 1e-8,
            "lambda {lambda}, k {k}: {with:e} with the fold's point, {without:e} without"
        );
    }
}

/// A noise-free curve fitted with a spring constant 10% off: no parameters fit it to rounding,
/// and the result says so.
#[test]
fn a_noise_free_curve_not_fitted_to_rounding_says_so() {
    let c = retract(1.0, 2.0, 300);
    let r = fit_curve(&c, &opt(2.2));
    assert_eq!(r.status, FitStatus::Ok, "{}", r.message);
    let fmax = c.force.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    assert!(r.rms_residual_n.unwrap() > 1e-8 * fmax);
    assert!(
        r.warnings
            .iter()
            .any(|w| w.contains("the fit does not describe this curve")),
        "{:?}",
        r.warnings
    );
    // The right spring: to rounding, and no such warning.
    let r = fit_curve(&c, &opt(2.0));
    assert!(r.rms_residual_n.unwrap() < 1e-12 * fmax);
    assert!(!r.warnings.iter().any(|w| w.contains("does not describe")));
}
