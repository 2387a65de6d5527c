//! The search for the global minimum of the Maugis-Dugdale fit: the profile over lambda,
//! short free fits from its basins and every fifth point (from all of its points where those
//! miss the noise floor), the best of them fitted fully, and the errors widened by the
//! profile's region.

use super::*;

/// The lambdas of the profile that starts a free Maugis-Dugdale fit: 0.01..1000, 16 points.
pub(super) fn profile_lambdas() -> impl Iterator<Item = f64> {
    (0..16).map(|i| 10f64.powf(-2.0 + 5.0 * i as f64 / 15.0))
}

/// The profile points a free fit starts from first: the best two, every local minimum of the
/// misfit along lambda with its two neighbours, and every fifth point. Near the truth the
/// misfit can dip sharply between profile points (lambda sets the attractive tail and the
/// jump), so a free fit has to start where it can roll into the dip; free fits from the other
/// points of a basin end in the same minimum.
/// `order`: the profile's points, best first.
pub(super) fn scout_starts(profile: &[ModelFit], order: &[usize]) -> Vec<usize> {
    let r: Vec<f64> = profile.iter().map(rank).collect();
    let n = r.len();
    let mut pick = vec![false; n];
    for &i in order.iter().take(2) {
        pick[i] = true;
    }
    for i in (0..n).filter(|&i| r[i].is_finite()) {
        if (i == 0 || r[i] <= r[i - 1]) && (i + 1 == n || r[i] <= r[i + 1]) {
            pick[i.saturating_sub(1)..(i + 2).min(n)].fill(true);
        }
    }
    // A dip can hide between two profile points on a stretch where the profile only falls
    // (the fixed-lambda fits beside it do not see it): free fits from every fifth point
    // (a factor 46 in lambda apart) roll down such stretches into it.
    for i in (0..n).step_by(5) {
        pick[i] = true;
    }
    order.iter().copied().filter(|&i| pick[i]).collect()
}

/// Where the best free fit's rms residual exceeds the baseline's noise by more than this
/// factor, it has not reached the noise floor: a fixed-lambda fit of the profile may itself
/// have stopped in a local minimum and hidden a basin, so free fits start from every other
/// profile point too. (Below it a missed dip can still cost a fraction of the noise: the first
/// starts are chosen to find those.)
pub(super) const NOISE_FLOOR: f64 = 1.25;

/// Misfit for ranking: the rms residual, even where the iteration limit stopped a fit.
pub(super) fn rank(m: &ModelFit) -> f64 {
    if m.rms_residual_n.is_finite() {
        m.rms_residual_n
    } else {
        f64::INFINITY
    }
}

/// The free Maugis-Dugdale fit from the best two distinct short free fits, with standard
/// errors that also cover the profile's confidence region: where the misfit is flat in lambda
/// (one retract curve often cannot tell lambda = 0.3 from 30 within its noise) the covariance's
/// local picture understates the spread, while the profile sees it.
pub(super) fn free_fit(
    d: &Prepared,
    opt: &FitOptions,
    w_ref: f64,
    profile: Vec<ModelFit>,
) -> ModelFit {
    let mut order: Vec<usize> = (0..profile.len()).collect();
    order.sort_by(|&a, &b| rank(&profile[a]).total_cmp(&rank(&profile[b])));
    // The profile has its 16 fixed lambdas.
    let best_profile = rank(&profile[order[0]]);
    // Scouts: short free fits from the profile's basins; the best two distinct ones are then
    // fitted fully.
    // Where that does not reach the noise floor, from every other profile point as well.
    let first = scout_starts(&profile, &order);
    let (mut scouts, mut fulls) = scout(d, opt, w_ref, &profile, &first, best_profile);
    let best = fulls.iter().map(key).fold(f64::INFINITY, f64::min);
    if !(best <= NOISE_FLOOR * d.noise) {
        let rest: Vec<usize> = order
            .iter()
            .copied()
            .filter(|i| !first.contains(i))
            .collect();
        let (more, more_fulls) = scout(d, opt, w_ref, &profile, &rest, best_profile);
        scouts.extend(more);
        fulls.extend(more_fulls);
    }
    let Some(mut md) = fulls.iter().cloned().reduce(better) else {
        return profile[order[0]].clone();
    };
    if key(&md) > best_profile {
        // The free fits failed or did worse: the best fixed-lambda fit stands.
        md = profile[order[0]].clone();
        md.stop = format!("{} (lambda from the profile)", md.stop);
        if md.rms_residual_n.is_finite() {
            md.status = FitStatus::Ok;
        }
    }
    if md.status != FitStatus::Ok {
        return md;
    }
    let others: Vec<&ModelFit> = scouts.iter().chain(&fulls).collect();
    widen_by_region(md, d, &profile, &others)
}

/// Short free fits (scouts) from the profile points `starts`, best first, and the full fits
/// from the best two distinct ones.
fn scout(
    d: &Prepared,
    opt: &FitOptions,
    w_ref: f64,
    profile: &[ModelFit],
    starts: &[usize],
    best_profile: f64,
) -> (Vec<ModelFit>, Vec<ModelFit>) {
    let mut scouts: Vec<ModelFit> = starts
        .iter()
        .map(|&i| {
            let m = &profile[i];
            fit_md_from(m, d, opt, m.params(), w_ref, None, SCOUT_PATIENCE)
        })
        .collect();
    scouts.sort_by(|a, b| rank(a).total_cmp(&rank(b)));
    // The best two distinct scouts: two that ended at one point (scouts from a basin's two
    // sides often converge there) would give two full fits of one minimum.
    let mut distinct: Vec<&ModelFit> = Vec::new();
    for s in &scouts {
        if distinct.len() < 2 && !distinct.iter().any(|d| same_point(d, s)) {
            distinct.push(s);
        }
    }
    let fulls = distinct
        .into_iter()
        .map(|m| {
            let mut f = fit_md_from(m, d, opt, m.params(), w_ref, None, PATIENCE);
            // Stopped by the iteration limit but no worse than any fixed-lambda fit: accepted.
            if f.status == FitStatus::NotConverged && rank(&f) <= best_profile * (1.0 + 1e-9) {
                f.status = FitStatus::Ok;
            }
            f
        })
        .collect();
    (scouts, fulls)
}

/// Whether two fits ended at one point: E*, w and lambda within 1e-6, the misfit within 1e-9
/// (relative).
fn same_point(a: &ModelFit, b: &ModelFit) -> bool {
    let near = |x: f64, y: f64, tol: f64| (x - y).abs() <= tol * x.abs().max(y.abs());
    near(a.e_star_pa, b.e_star_pa, 1e-6)
        && near(a.work_of_adhesion_j_m2, b.work_of_adhesion_j_m2, 1e-6)
        && near(a.lambda.unwrap_or(0.0), b.lambda.unwrap_or(0.0), 1e-6)
        && near(a.rms_residual_n, b.rms_residual_n, 1e-9)
}

/// The free fit's standard errors widened by the 3-sigma region of the profile and of the
/// other minima found (`others`): where the misfit is flat in lambda the covariance's local
/// picture understates the spread, while the profile sees it.
pub(super) fn widen_by_region(
    mut md: ModelFit,
    d: &Prepared,
    profile: &[ModelFit],
    others: &[&ModelFit],
) -> ModelFit {
    // The 3-sigma region of the profile and of the minima found: Delta chi^2 = (RSS - RSS_min) / s^2 <= 9, its edges
    // interpolated in ln lambda between profile points.
    let m = d.count as f64;
    let rss = |f: &ModelFit| f.rms_residual_n.powi(2) * m;
    let s2 = rss(&md) / (m - 5.0).max(1.0);
    let lam = md.lambda.unwrap_or(1.0);
    let chi: Vec<(f64, f64)> = profile
        .iter()
        .map(|f| {
            let c = (rss(f) - rss(&md)) / s2;
            (
                f.lambda.unwrap_or(1.0).ln(),
                if c.is_finite() { c } else { f64::INFINITY },
            )
        })
        .collect();
    let (mut lo, mut hi) = (lam, lam);
    let (mut de, mut dw) = (0.0f64, 0.0f64);
    for (i, &(x, c)) in chi.iter().enumerate() {
        if c <= 9.0 {
            lo = lo.min(x.exp());
            hi = hi.max(x.exp());
            de = de.max((profile[i].e_star_pa - md.e_star_pa).abs());
            dw = dw.max((profile[i].work_of_adhesion_j_m2 - md.work_of_adhesion_j_m2).abs());
        }
        if let Some(&(x2, c2)) = chi.get(i + 1) {
            if (c <= 9.0) != (c2 <= 9.0) && c.is_finite() && c2.is_finite() {
                let t = ((9.0 - c) / (c2 - c)).clamp(0.0, 1.0);
                let e = (x + t * (x2 - x)).exp();
                lo = lo.min(e);
                hi = hi.max(e);
            }
        }
    }
    // Other minima the free fits found within the same region are as plausible: their
    // lambda, E* and w count too.
    for &f in others {
        let c = (rss(f) - rss(&md)) / s2;
        if c <= 9.0 {
            let l = f.lambda.unwrap_or(lam);
            lo = lo.min(l);
            hi = hi.max(l);
            de = de.max((f.e_star_pa - md.e_star_pa).abs());
            dw = dw.max((f.work_of_adhesion_j_m2 - md.work_of_adhesion_j_m2).abs());
        }
    }
    let spread = (hi - lam).max(lam - lo) / 3.0;
    // The local (covariance) error and the spread over the region add in quadrature: the
    // region moves the answer across lambda, the noise moves it at each lambda.
    let quad = |local: f64, spread: f64| {
        if local.is_finite() {
            local.hypot(spread)
        } else {
            spread
        }
    };
    md.lambda_stderr = Some(quad(md.lambda_stderr.unwrap_or(0.0), spread));
    md.e_star_pa_stderr = quad(md.e_star_pa_stderr, de / 3.0);
    md.work_of_adhesion_j_m2_stderr = quad(md.work_of_adhesion_j_m2_stderr, dw / 3.0);
    md
}

pub(super) fn key(m: &ModelFit) -> f64 {
    if m.status == FitStatus::Ok && m.rms_residual_n.is_finite() {
        m.rms_residual_n
    } else {
        f64::INFINITY
    }
}

pub(super) fn better(a: ModelFit, b: ModelFit) -> ModelFit {
    if key(&b) < key(&a) {
        b
    } else {
        a
    }
}
