//! A fitted curve's result: its values, intervals, warnings, and the adequate model (by a
//! likelihood-ratio test at the noise of the residual, or by the tolerance for a noise-free
//! curve).

use super::*;
use crate::physics::params::{plausibility, E_STAR_RANGE, W_MAX};

/// The longest Lennard-Jones range a fitted zone may have and still be read as surface forces
/// (m): a water meniscus's height reaches about this at high humidity.
const SURFACE_FORCE_RANGE: f64 = 1e-8;

/// A result that stops before the judgement: its message, a status where it is not the fit's
/// own, and the fits made.
fn unfinished(
    mut out: CurveFit,
    status: Option<FitStatus>,
    message: String,
    md: ModelFit,
    models: Vec<ModelFit>,
) -> CurveFit {
    out.message = message.into();
    if let Some(s) = status {
        out.status = s;
    }
    out.models = models;
    out.md = Some(md);
    out
}

/// The humid fit's warnings: a doubtful reading of the fitted zone, and the limits of the
/// meniscus model at the tip, as every front end reports them.
fn humid_warnings(
    out: &CurveFit,
    opt: &FitOptions,
    h: &crate::scene::humidity::HumidityInput,
) -> Vec<String> {
    let mut warn = Vec::new();
    if let Some(fh) = out.humidity.as_ref().filter(|fh| !fh.fair_reading) {
        warn.push(format!("humidity: {}", fh.note));
    }
    warn.extend(
        h.warnings(opt.radius)
            .into_iter()
            .map(|w| format!("humidity: {w}")),
    );
    warn
}

/// A curve's result from its Maugis-Dugdale fit, the closed forms' fits and the intervals: the
/// parameters, the adequate model, the verdict on the adhesion map and the warnings.
pub(super) fn summarize(
    curve: &Curve,
    opt: &FitOptions,
    d: &Prepared,
    md: ModelFit,
    models: Vec<ModelFit>,
    iv: &interval::Intervals,
) -> CurveFit {
    let mut out = fail(curve, md.status, String::new());
    out.points_fitted = d.force.len();
    let fmin = d.force.iter().cloned().fold(f64::INFINITY, f64::min);
    out.pulloff_force_measured_n = Some((-fmin).max(0.0));
    out.max_load_n = Some(d.force.iter().cloned().fold(f64::NEG_INFINITY, f64::max));
    out.iterations = md.iterations;
    out.stop = md.stop.clone();
    out.baseline_tilt_n_m = opt.tilt.then_some(d.baseline.1);
    out.warnings = d.notes.clone();
    if md.status != FitStatus::Ok {
        let message = format!("the Maugis-Dugdale fit did not converge: {}", md.stop);
        return unfinished(out, None, message, md, models);
    }
    let p = Params {
        e_star: md.e_star_pa,
        w: md.work_of_adhesion_j_m2,
        lambda: md.lambda.unwrap_or(1.0),
        zc: md.contact_point_m,
        f0: md.force_offset_n,
    };
    let short = crate::physics::domain::short;
    let Some((_, a_md, states, _)) = model_forces(
        Model::Md,
        &p,
        opt.geometry(),
        opt.spring,
        &d.height,
        &d.dir,
        None,
    ) else {
        let message = format!(
            "the fitted parameters (E* = {} Pa, w = {} J/m^2, lambda = {}) cannot be evaluated: the fit left the models' domain{}",
            short(p.e_star), short(p.w), short(p.lambda), unit_hints(d, opt)
        );
        return unfinished(out, Some(FitStatus::NotConverged), message, md, models);
    };
    let in_contact = states.iter().filter(|s| s.piece == Piece::Contact).count();
    if let Some((status, message)) = implausible(&p, in_contact, d, opt) {
        let mut r = fail(curve, status, message);
        r.points_fitted = out.points_fitted;
        r.pulloff_force_measured_n = out.pulloff_force_measured_n;
        r.max_load_n = out.max_load_n;
        return with_fits(r, d, md, models);
    }
    let amax = a_md.iter().cloned().fold(0.0, f64::max);
    let loads: Vec<f64> = states
        .iter()
        .filter(|s| s.piece == Piece::Contact)
        .map(|s| s.load)
        .collect();
    let z0 = put_parameters(&mut out, opt, d, &p, &md, amax, in_contact, &loads);
    put_intervals(&mut out, iv);
    if offset_at_bound(&md, d, opt) {
        offset_bound(&mut out, &md);
    }
    let l95 = iv.lambda[1];
    let m = d.force.len() as f64;
    let n_md = if opt.z0.is_some() { 4.0 } else { 5.0 };
    let fmax = d.force.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    let s2 = (md.rms_residual_n.powi(2) * m / (m - n_md).max(1.0)).max((1e-13 * fmax).powi(2));
    out.noise_from_residual_n = Some(s2.sqrt());
    // A noise-free curve (the residual at rounding): no statistics, the tolerance decides.
    let adequate = if s2.sqrt() <= 1e-9 * fmax {
        adequate_by_tolerance(opt, d, &p, &md, &models, &a_md, &states, in_contact)
    } else {
        adequate_by_test(opt, &md, &models, s2, m, n_md, l95)
    };
    out.adequate_model = Some(adequate.0);
    out.why = adequate.1;
    let pull = out.pulloff_force_measured_n.unwrap_or(0.0);
    // The verdict reads the sphere's adhesion map.
    if pull > 0.0 && opt.tip.is_none() {
        out.verdict = crate::scene::infer(pull, opt.radius, p.e_star, out.z0_m.unwrap_or(z0))
            .ok()
            .map(|i| i.verdict);
    }
    let mut warn = warnings(&out, d, opt, &p, &md, amax, in_contact);
    if let Some(h) = &opt.humidity {
        out.humidity = humidity::in_humid_air(&out, d, opt, &md, h);
        warn.extend(humid_warnings(&out, opt, h));
    }
    out.status = FitStatus::Ok;
    out.message = "ok".into();
    let mut out = with_fits(out, d, md, models);
    out.warnings = warn;
    out
}

/// A curve's result with its Maugis-Dugdale fit (its iterations and stop) and the closed
/// forms' fits, and the data's notes as warnings.
pub(super) fn with_fits(
    mut r: CurveFit,
    d: &Prepared,
    md: ModelFit,
    models: Vec<ModelFit>,
) -> CurveFit {
    r.iterations = md.iterations;
    r.stop = md.stop.clone();
    r.warnings = d.notes.clone();
    r.models = models;
    r.md = Some(md);
    r
}

/// A fit that ended outside physical sense, or with no point in contact: its status and
/// message (None for a fit to report).
pub(super) fn implausible(
    p: &Params,
    in_contact: usize,
    d: &Prepared,
    opt: &FitOptions,
) -> Option<(FitStatus, String)> {
    let short = crate::physics::domain::short;
    // A modulus or adhesion above physical sense first: that is the cause to name (forces in
    // nN, a wrong spring constant), whatever else the fit shows; a modulus below the range with
    // no point in contact is a curve that does not press (no contact).
    let (plausible, values) = plausibility(p.e_star, p.w);
    let above = !(p.e_star <= E_STAR_RANGE.1) || !(p.w <= W_MAX);
    if !plausible && (above || in_contact > 0) {
        return Some((
            FitStatus::NotConverged,
            format!(
                "the fit ended outside physical sense: {values}{}",
                unit_hints(d, opt)
            ),
        ));
    }
    if in_contact == 0 {
        return Some((
            FitStatus::NoContact,
            format!(
                "no contact: no fitted point is in contact on the fitted Maugis-Dugdale path (E* = {} Pa, w = {} J/m^2), so the curve does not determine E*{}",
                short(p.e_star),
                short(p.w),
                unit_hints(d, opt)
            ),
        ));
    }
    None
}

/// The fitted values and their standard errors into `out`; returns z0 from lambda.
#[allow(clippy::too_many_arguments)]
pub(super) fn put_parameters(
    out: &mut CurveFit,
    opt: &FitOptions,
    d: &Prepared,
    p: &Params,
    md: &ModelFit,
    amax: f64,
    in_contact: usize,
    loads: &[f64],
) -> f64 {
    out.e_star_pa = Some(p.e_star);
    out.e_star_pa_stderr = Some(md.e_star_pa_stderr);
    out.youngs_modulus_pa = opt.poisson.map(|nu| p.e_star * (1.0 - nu * nu));
    out.work_of_adhesion_j_m2 = Some(p.w);
    out.work_of_adhesion_j_m2_stderr = Some(md.work_of_adhesion_j_m2_stderr);
    out.lambda = Some(p.lambda);
    out.lambda_stderr = md.lambda_stderr;
    let tip = opt.geometry();
    let z0 = tip.z0_from_lambda(p.e_star, p.w, p.lambda);
    // muT = lambda / 1.1570 exactly for the LJ-matched Dugdale stress: Tabor's parameter is
    // the sphere's (a tip's lambda is its own, section 12).
    if tip.is_sphere() {
        let mu_t = (opt.radius * p.w * p.w / (p.e_star * p.e_star * z0.powi(3))).cbrt();
        out.tabor_parameter = Some(mu_t);
        out.tabor_parameter_stderr = md.lambda_stderr.map(|e| e * mu_t / p.lambda);
    }
    out.z0_m = Some(opt.z0.unwrap_or(z0));
    let lambda_spread = z0 * md.lambda_stderr.unwrap_or(f64::NAN) / p.lambda;
    out.z0_m_stderr = Some(match (&md.cov, opt.z0) {
        // The covariance of (ln E*, ln w, ln lambda, ...) of a free fit.
        (Some(c), None) if c.nrows() == 5 => {
            // ln z0 = c (ln w - ln E*) - ln lambda + const (the sphere's c = 2/3).
            let slope = tip.z0_slope(p.e_star, p.w);
            let g = [-slope, slope, -1.0];
            let mut v = 0.0;
            for i in 0..3 {
                for j in 0..3 {
                    v += g[i] * g[j] * c[(i, j)];
                }
            }
            // At least the lambda spread (z0 is inversely proportional to lambda).
            (z0 * v.max(0.0).sqrt()).max(lambda_spread)
        }
        (_, Some(_)) => 0.0,
        // lambda from the profile: its spread.
        _ => lambda_spread,
    });
    out.contact_point_m = Some(p.zc);
    out.contact_point_m_stderr = Some(md.contact_point_m_stderr);
    out.force_offset_n = Some(d.baseline.0 + p.f0);
    out.rms_residual_n = Some(md.rms_residual_n);
    out.pulloff_force_model_n = Some(md.pulloff_force_model_n);
    out.max_contact_radius_m = Some(amax);
    out.points_in_contact = in_contact;
    if !loads.is_empty() {
        let lo = loads.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = loads.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        out.load_range_normalised = Some([lo, hi]);
    }
    z0
}

/// The profile intervals into `out`, and what they say of lambda.
pub(super) fn put_intervals(out: &mut CurveFit, iv: &interval::Intervals) {
    let [e68, e95] = iv.e_star_pa;
    let [w68, w95] = iv.work_of_adhesion_j_m2;
    let [l68, l95] = iv.lambda;
    let [c68, c95] = iv.contact_point_m;
    let [z68, z95] = iv.z0_m;
    out.e_star_pa_interval_68 = e68;
    out.e_star_pa_interval_95 = e95;
    out.work_of_adhesion_j_m2_interval_68 = w68;
    out.work_of_adhesion_j_m2_interval_95 = w95;
    out.lambda_interval_68 = l68;
    out.lambda_interval_95 = l95;
    out.contact_point_m_interval_68 = c68;
    out.contact_point_m_interval_95 = c95;
    out.z0_m_interval_68 = z68;
    out.z0_m_interval_95 = z95;
    out.lambda_set_95 = iv.lambda_set_95.clone();
    out.lambda_basins = iv.basins.clone();
    if let Some([lo, hi]) = l95 {
        // Determined: one bounded interval at 95%, and no second basin below 99%.
        out.lambda_determined = Some(
            lo.is_some() && hi.is_some() && iv.basins.is_empty() && iv.lambda_set_95.len() <= 1,
        );
        let end = |e: Option<f64>| e.map_or("open".to_string(), sig);
        let mut bound = if iv.lambda_set_95.len() > 1 {
            let parts: Vec<String> = iv
                .lambda_set_95
                .iter()
                .map(|[a, b]| format!("[{}, {}]", end(*a), end(*b)))
                .collect();
            format!("lambda's 95% set is a union: {}", parts.join(" or "))
        } else {
            match (lo, hi) {
                (Some(lo), Some(hi)) => format!("{} <= lambda <= {} at 95%", sig(lo), sig(hi)),
                (Some(lo), None) => format!("lambda > {} at 95% (no upper bound: towards JKR the curve cannot tell lambda apart)", sig(lo)),
                (None, Some(hi)) => format!("lambda < {} at 95% (no lower bound: towards DMT the curve cannot tell lambda apart)", sig(hi)),
                (None, None) => "lambda is not bounded at 95% (0.01..1000 fit equally well)".to_string(),
            }
        };
        for b in &iv.basins {
            bound += &format!(
                "; a second basin at lambda = {} (Delta chi^2 = {:.2}{}, E* = {} Pa, w = {} J/m^2)",
                sig(b.lambda),
                b.delta_chi2,
                if b.delta_chi2 <= interval::LEVELS[1] {
                    ", inside the 95% set"
                } else {
                    ", within 99%"
                },
                sig(b.e_star_pa),
                sig(b.work_of_adhesion_j_m2)
            );
        }
        out.lambda_bound = Some(bound);
    }
}

/// What the fit's tip stretches, as its scene says it: a steep flank, a pyramid as its cone
/// ([`TipInput::warnings`]); a measured table's error up to the largest contact radius `amax`
/// (m), and its tangent beyond its last point.
///
/// [`TipInput::warnings`]: crate::physics::tip::TipInput::warnings
fn tip_warnings(opt: &FitOptions, amax: f64) -> Vec<String> {
    let mut warn: Vec<String> = opt.tip.iter().flat_map(|t| t.warnings()).collect();
    if let super::Geometry::Measured(table) = opt.geometry() {
        let short = crate::physics::domain::short;
        warn.push(format!(
            "the measured profile ({} points to r = {} m) gives these states within {:.1e} (relative; an upper estimate: up to the largest contact radius {} m, its interpolant's Abel transform differs by that from that of every other point)",
            table.points,
            short(table.largest_radius),
            table.error_between(0.0, amax),
            short(amax)
        ));
        if amax > table.largest_radius {
            warn.push(format!(
                "the contact reaches r = {} m, beyond the measured profile's last radius {} m: the tip is continued there by its tangent",
                short(amax),
                short(table.largest_radius)
            ));
        }
    }
    warn
}

/// The warnings of a converged fit: the data's notes, implausible options, a residual far above
/// the noise, a stretched theory, too few points in contact, lambda undetermined, an unresolved
/// jump-out.
pub(super) fn warnings(
    out: &CurveFit,
    d: &Prepared,
    opt: &FitOptions,
    p: &Params,
    md: &ModelFit,
    amax: f64,
    in_contact: usize,
) -> Vec<String> {
    let mut warn = d.notes.clone();
    warn.extend(tip_warnings(opt, amax));
    // A fit that looks sound with a radius or a spring constant no AFM has: its numbers rest
    // on that value.
    for h in hints(d, opt) {
        warn.push(format!("{h}; the fitted values assume it"));
    }
    // Far above the noise of the baseline (and above rounding for noise-free data, where the
    // true parameters fit to 1e-12 of the force: a residual above 1e-8 is a local minimum or a
    // wrong model, not a fit).
    let floor = 1e-8 * d.force.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    if md.rms_residual_n > 10.0 * d.noise + floor {
        let against = if d.noise > 0.0 {
            format!(
                "{:.0} times the baseline's noise {:.3e} N",
                md.rms_residual_n / d.noise,
                d.noise
            )
        } else {
            format!(
                "{:.1e} of the largest force, on a noise-free baseline",
                md.rms_residual_n / (1e8 * floor)
            )
        };
        warn.push(format!(
            "the fit does not describe this curve: its rms residual {:.3e} N is {against} (drift, ringing, a wrong model, wrong units or a wrong spring constant); its parameters are doubtful",
            md.rms_residual_n,
        ));
    }
    if opt.tip.is_none() && amax / opt.radius > 0.1 {
        warn.push(format!(
            "a/R reaches {:.2} (> 0.1): the small-strain (paraboloid) theory is stretched",
            amax / opt.radius
        ));
    }
    if amax > 0.0 && amax < 1e-9 {
        warn.push(format!(
            "the largest contact radius is {:.2e} m, a few atoms across: continuum theory is doubtful",
            amax
        ));
    }
    if in_contact < MIN_CONTACT_POINTS {
        warn.push(format!(
            "only {in_contact} fitted points are in contact: E* is poorly determined"
        ));
    }
    if offset_at_bound(md, d, opt) {
        warn.push(format!(
            "the best Maugis-Dugdale fit needs a force offset as large as the largest force the curve measured ({:.3e} N, the bound the fit allows): its Dugdale zone (z0 = {:.3e} m) pulls nearly alike along the whole curve, so its adhesion trades against the offset (the misfit falls further as both grow), and w, z0 and lambda are not determined; fit the curve with its baseline far from contact, or give the Lennard-Jones range z0",
            md.force_offset_n,
            out.z0_m.unwrap_or(f64::NAN)
        ));
    } else if let (Some(false), Some(b)) = (out.lambda_determined, &out.lambda_bound) {
        warn.push(format!(
            "lambda is not determined by this curve: {b}; quote that bound and the intervals of E* and w (they span the lambdas the data cannot tell apart), or fix lambda by giving the Lennard-Jones range z0, fit both segments, or use a stiffer cantilever"
        ));
    } else if let (None, Some(e)) = (out.lambda_determined, md.lambda_stderr) {
        if e > p.lambda {
            warn.push(format!(
                "lambda is not determined by this curve (standard error {e:.3} against {:.3}: the misfit barely changes over the lambda profile); fix it by giving the Lennard-Jones range z0, fit both segments, or use a stiffer cantilever",
                p.lambda
            ));
        }
    }
    // A fitted zone far beyond surface forces (their range is about a nanometre, a water
    // meniscus's up to about ten) stands for something else that pulls as the tip leaves.
    if out.lambda_determined == Some(true) && opt.z0.is_none() {
        if let Some(z0) = out.z0_m.filter(|&z| z > SURFACE_FORCE_RANGE) {
            warn.push(format!(
                "the fitted Dugdale zone reaches z0 = {z0:.3e} m, beyond the range of surface forces (about 1e-9 m; a water meniscus up to about 1e-8 m): the zone stands for what pulls as the tip leaves (tethers, viscoelastic peeling, drift), and w and lambda describe it, not the surfaces' adhesion"
            ));
        }
    }
    let (mp, md_pull) = (
        out.pulloff_force_measured_n.unwrap_or(0.0),
        md.pulloff_force_model_n,
    );
    if md_pull > 0.0 && (md_pull - mp) > 0.05 * md_pull + 3.0 * d.noise {
        warn.push(format!(
            "the sampling does not resolve the jump-out: the model's pull-off {:.3e} N exceeds the most tensile measured force {:.3e} N; sample more densely near the jump",
            md_pull, mp
        ));
    }
    warn
}

/// How close to its bound (the largest force measured) a fit's force offset lies on it.
const OFFSET_AT_BOUND: f64 = 0.99;

/// Whether the Maugis-Dugdale fit lies on the bound of its force offset (`Problem` refuses
/// offsets beyond the largest force measured): there the misfit still falls as the offset and the
/// pull of a zone longer than the curve grow together.
fn offset_at_bound(md: &ModelFit, d: &Prepared, opt: &FitOptions) -> bool {
    opt.z0.is_none() && md.force_offset_n.abs() >= OFFSET_AT_BOUND * d.scales.0
}

/// A fit on the bound of its force offset: lambda not determined (what lambda_bound said is
/// kept after it), and the upper ends of w's and z0's intervals open (they grow along the
/// valley).
fn offset_bound(out: &mut CurveFit, md: &ModelFit) {
    out.lambda_determined = Some(false);
    let why = format!(
        "the best fit needs a force offset as large as the largest force measured (f0 = {:.3e} N): its Dugdale zone (z0 = {:.3e} m) pulls alike along the curve, and its adhesion and the offset cannot be told apart",
        md.force_offset_n,
        out.z0_m.unwrap_or(f64::NAN)
    );
    out.lambda_bound = Some(match out.lambda_bound.take() {
        Some(b) => format!("{why}; {b}"),
        None => why,
    });
    for iv in [
        &mut out.work_of_adhesion_j_m2_interval_68,
        &mut out.work_of_adhesion_j_m2_interval_95,
        &mut out.z0_m_interval_68,
        &mut out.z0_m_interval_95,
    ] {
        if let Some(i) = iv.as_mut() {
            i[1] = None;
        }
    }
}

/// Three significant figures, as a bound is written.
pub(super) fn sig(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let e = v.abs().log10().floor() as i32;
    if (-3..5).contains(&e) {
        format!("{:.*}", (2 - e).max(0) as usize, v)
    } else {
        format!("{v:.2e}")
    }
}

/// The adequate model by statistics: the simplest closed form whose misfit is not significantly
/// worse than Maugis-Dugdale's (the likelihood-ratio test at the noise of the residual: Delta
/// chi^2 = (RSS - RSS_MD) / s^2 against chi^2's 95% point for the parameters it lacks), and
/// consistent with lambda's 95% interval (JKR needs it open towards large lambda, DMT towards
/// small).
pub(super) fn adequate_by_test(
    opt: &FitOptions,
    md: &ModelFit,
    models: &[ModelFit],
    s2: f64,
    m: f64,
    n_md: f64,
    l95: Option<interval::Interval>,
) -> (Model, String) {
    let rss = |f: &ModelFit| f.rms_residual_n.powi(2) * m;
    let fixed = opt.z0.is_some();
    let mut notes = Vec::new();
    let stopped = super::problem::stop_text(&TerminationReason::LostPatience);
    for f in models {
        // E*, the contact point, the offset, and w where the model has one.
        let n = if f.model.adhesive() { 4.0 } else { 3.0 };
        let q = (n_md - n).max(1.0);
        // chi^2's 95% points for 1 and 2 degrees of freedom.
        let crit = if q >= 2.0 {
            5.991464547107979
        } else {
            3.841458820694124
        };
        let dchi = (rss(f) - rss(md)) / s2;
        // A fit that stopped short of its minimum says nothing of the model: its misfit is
        // only an upper bound, and a test on it would reject the model for the search's sake.
        // (A closed form's first fit taken as it stands at its short budget is one too; within
        // the criterion it shows the model adequate all the same.)
        let short = f.stop == stopped;
        if (f.status != FitStatus::Ok || (short && dchi > crit)) && dchi.is_finite() {
            notes.push(format!(
                "{}'s fit did not converge (Delta chi^2 = {:.3} is an upper bound), so it is not tested",
                f.model.label(),
                dchi
            ));
            continue;
        }
        if !dchi.is_finite() {
            notes.push(format!("{} did not fit", f.model.label()));
            continue;
        }
        let open = |end: usize| l95.is_none_or(|l| l[end].is_none());
        let consistent = fixed
            || match f.model {
                Model::Jkr => open(1),
                Model::Dmt => open(0),
                _ => true,
            };
        if dchi <= crit && consistent {
            let why = adequate_why(f, md, (dchi, crit, q, s2), l95, &notes);
            return (f.model, why);
        }
        notes.push(if dchi > crit {
            format!("{} Delta chi^2 = {:.3} > {:.2}", f.model.label(), dchi, crit)
        } else {
            format!(
                "{} fits within the noise (Delta chi^2 = {:.2}) but lambda's 95% interval excludes its limit",
                f.model.label(),
                dchi
            )
        });
    }
    (
        Model::Md,
        format!(
            "no closed form is shown adequate: each is significantly worse than Maugis-Dugdale at the noise {:.3e} N of the residual (95%), or could not be tested: {}",
            s2.sqrt(),
            notes.join("; ")
        ),
    )
}

/// Why a closed form is adequate: its Delta chi^2 against the critical value, what lambda's
/// interval says, how far its w is from Maugis-Dugdale's, and the notes on the models before.
pub(super) fn adequate_why(
    f: &ModelFit,
    md: &ModelFit,
    (dchi, crit, q, s2): (f64, f64, f64, f64),
    l95: Option<interval::Interval>,
    notes: &[String],
) -> String {
    let w_note = if f.model == Model::Hertz {
        String::new()
    } else {
        format!(
            "; its w is {:+.1}% from Maugis-Dugdale's",
            100.0 * (f.work_of_adhesion_j_m2 / md.work_of_adhesion_j_m2 - 1.0)
        )
    };
    let lam = match (f.model, l95) {
        (Model::Jkr, Some([Some(lo), None])) => format!(
            ", and lambda's 95% interval is open towards JKR (lambda > {})",
            sig(lo)
        ),
        (Model::Dmt, Some([None, Some(hi)])) => format!(
            ", and lambda's 95% interval is open towards DMT (lambda < {})",
            sig(hi)
        ),
        _ => String::new(),
    };
    let before = if notes.is_empty() {
        String::new()
    } else {
        format!(" ({})", notes.join("; "))
    };
    format!(
        "{} is not significantly worse than Maugis-Dugdale: Delta chi^2 = {:.2} against {:.2} (95%, {} fewer parameter{}) at the noise {:.3e} N of the residual{lam}{w_note}{before}",
        f.model.label(),
        dchi,
        crit,
        q,
        if q >= 2.0 { "s" } else { "" },
        s2.sqrt()
    )
}

/// The adequate model of a noise-free curve (residual at rounding): the simplest whose rms
/// residual is within the tolerance of MD's, or whose contact radius is within it at every
/// fitted point in contact.
#[allow(clippy::too_many_arguments)]
pub(super) fn adequate_by_tolerance(
    opt: &FitOptions,
    d: &Prepared,
    p: &Params,
    md: &ModelFit,
    models: &[ModelFit],
    a_md: &[f64],
    states: &[PathState],
    in_contact: usize,
) -> (Model, String) {
    let floor = 1e-9 * d.force.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    let mut adequate = (
        Model::Md,
        format!(
            "no closed form fits within {:.0}%: {} leave rms residuals of {}",
            100.0 * opt.tolerance,
            {
                let names: Vec<&str> = models.iter().map(|m| m.model.label()).collect();
                match names.split_last() {
                    Some((last, rest)) if !rest.is_empty() => {
                        format!("{} and {last}", rest.join(", "))
                    }
                    _ => names.concat(),
                }
            },
            models
                .iter()
                .map(|m| format!("{:.3e} N", m.rms_residual_n))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    );
    for m in models {
        // A fit stopped by the iteration limit only over-states its misfit (each step lowers
        // it): if even that is within the tolerance, the model is adequate.
        if m.rms_residual_n.is_finite()
            && m.rms_residual_n <= (1.0 + opt.tolerance) * md.rms_residual_n + floor
        {
            // Its parameters are its own: say how far its w is from Maugis-Dugdale's.
            let w_note = if !m.model.adhesive() {
                String::new()
            } else {
                format!(
                    "; its w is {:+.1}% from Maugis-Dugdale's",
                    100.0 * (m.work_of_adhesion_j_m2 / md.work_of_adhesion_j_m2 - 1.0)
                )
            };
            adequate = (m.model, format!(
                "{} fits as well as Maugis-Dugdale: rms residual {:.3e} N against {:.3e} N (within {:.0}%){w_note}",
                m.model.label(), m.rms_residual_n, md.rms_residual_n, 100.0 * opt.tolerance
            ));
            break;
        }
        if m.status != FitStatus::Ok {
            continue;
        }
        let mp = Params {
            e_star: m.e_star_pa,
            w: if !m.model.adhesive() {
                p.w
            } else {
                m.work_of_adhesion_j_m2
            },
            lambda: 1.0,
            zc: m.contact_point_m,
            f0: m.force_offset_n,
        };
        if let Some((_, a_m, _, _)) = model_forces(
            m.model,
            &mp,
            opt.geometry(),
            opt.spring,
            &d.height,
            &d.dir,
            None,
        ) {
            let worst = a_md
                .iter()
                .zip(&a_m)
                .zip(states)
                .filter(|(_, s)| s.piece == Piece::Contact)
                .map(|((am, a), _)| (a / am - 1.0).abs())
                .fold(0.0, f64::max);
            if in_contact > 0 && worst <= opt.tolerance {
                adequate = (m.model, format!(
                    "{}'s contact radius is within {:.1}% of Maugis-Dugdale's at every fitted point in contact (tolerance {:.0}%)",
                    m.model.label(), 100.0 * worst, 100.0 * opt.tolerance
                ));
                break;
            }
        }
    }
    adequate
}
