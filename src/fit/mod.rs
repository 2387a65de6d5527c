//! Measured force curves: exact Maugis-Dugdale fitted to AFM approach-retract curves, with
//! Hertz, DMT and JKR beside it, and the simplest model the curve needs.
//!
//! A curve is the force on the tip against the piezo height of the cantilever's base (larger is
//! farther from the sample). With spring constant k, the base displacement past the contact point
//! z_c is `Delta = z_c - height` (the tip's indentation plus its deflection F/k), and the model
//! force at each height is the state of the model's equilibrium path followed under the spring
//! (`crate::law::follow`): on retract it follows the stable branch until the force gradient reaches -k and then
//! jumps, as the measured curve does. Parameters: E*, w, lambda (or a fixed range z0), z_c and a
//! force offset, fitted by Levenberg-Marquardt (MINPACK's, through the `levenberg-marquardt`
//! crate) with finite-difference Jacobians that keep each point on its branch.

mod bins;
pub mod data;
mod error;
pub mod humidity;
pub mod interval;
mod map_summary;
pub mod model;
mod options;
mod prepare;
mod problem;
mod result;
mod search;
pub mod segments;
mod summary;
pub mod synthetic;
mod tip;

pub use crate::law::follow::{Direction, DrivenPath};
pub use data::{read_curves, Curve, CurveSet, DataError};
pub use error::{CurveError, SyntheticError};
pub use map_summary::*;
pub use model::Model;
pub use options::*;
pub use prepare::*;
pub use problem::*;
pub use result::*;
use search::*;
use summary::*;
pub use tip::Geometry;

use crate::error::Message;
use crate::law::follow::{PathState, Side};
use crate::law::{Law, Piece};
use crate::physics::params::LJ_STRESS;
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt, TerminationReason};
use nalgebra::{storage::Owned, DMatrix, DVector, Dyn};
use serde::Serialize;
use std::cell::RefCell;
use std::f64::consts::PI;

pub(super) fn fail(curve: &Curve, status: FitStatus, message: impl Into<Message>) -> CurveFit {
    CurveFit {
        curve: curve.id.clone(),
        x: curve.x,
        y: curve.y,
        status,
        message: message.into(),
        e_star_pa: None,
        e_star_pa_stderr: None,
        youngs_modulus_pa: None,
        work_of_adhesion_j_m2: None,
        work_of_adhesion_j_m2_stderr: None,
        lambda: None,
        lambda_stderr: None,
        tabor_parameter: None,
        tabor_parameter_stderr: None,
        z0_m: None,
        z0_m_stderr: None,
        contact_point_m: None,
        contact_point_m_stderr: None,
        force_offset_n: None,
        baseline_tilt_n_m: None,
        rms_residual_n: None,
        pulloff_force_measured_n: None,
        pulloff_force_model_n: None,
        max_load_n: None,
        max_contact_radius_m: None,
        load_range_normalised: None,
        iterations: 0,
        stop: String::new(),
        points_fitted: 0,
        points_in_contact: 0,
        models: Vec::new(),
        e_star_pa_interval_68: None,
        e_star_pa_interval_95: None,
        work_of_adhesion_j_m2_interval_68: None,
        work_of_adhesion_j_m2_interval_95: None,
        lambda_interval_68: None,
        lambda_interval_95: None,
        contact_point_m_interval_68: None,
        contact_point_m_interval_95: None,
        z0_m_interval_68: None,
        z0_m_interval_95: None,
        lambda_determined: None,
        lambda_bound: None,
        lambda_set_95: Vec::new(),
        lambda_basins: Vec::new(),
        noise_from_residual_n: None,
        adequate_model: None,
        why: String::new(),
        verdict: None,
        warnings: Vec::new(),
        humidity: None,
        dwell: None,
        md: None,
    }
}

/// Fits one curve: Maugis-Dugdale and the three closed forms, the adequate model, warnings.
/// Whatever the data, the result is the curve's status: a panic inside (a bug) is caught here
/// and becomes this curve's `not_converged`, so that the other curves of a batch go on.
pub fn fit_curve(curve: &Curve, opt: &FitOptions) -> CurveFit {
    if let Err(e) = opt.validate() {
        return fail(curve, FitStatus::InvalidInput, e.message);
    }
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let mut r = fit_curve_inner(curve, opt);
        // The path states only start the next fit: a force map keeps none.
        for m in r.md.iter_mut().chain(r.models.iter_mut()) {
            m.states = None;
        }
        r
    }))
    .unwrap_or_else(|p| {
        let what = p
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        fail(
            curve,
            FitStatus::NotConverged,
            format!(
                "internal error while fitting this curve ({what}); please report it with the curve"
            ),
        )
    })
}

fn fit_curve_inner(curve: &Curve, opt: &FitOptions) -> CurveFit {
    let d = match prepare(curve, opt) {
        Ok(d) => d,
        Err((status, message)) => return fail(curve, status, message),
    };
    let mut out = fit_prepared(curve, opt, &d);
    out.dwell = d.dwell.clone();
    // The approach fitted in place of the retract after a relaxing dwell: said in the status's
    // message too (the note is the first warning).
    let switched =
        opt.segments != Segments::Approach && d.dwell.as_ref().is_some_and(|w| w.relaxed);
    if out.status == FitStatus::Ok && switched {
        if let Some(note) = d.notes.first() {
            out.message = format!("ok: {note}").into();
        }
    }
    out
}

/// The models fitted to a prepared curve, the adequate one chosen.
/// Where the fits of one curve start: the estimates read from the curve, the w that the
/// measured pull-off gives a model of normalised pull-off `pc_bar`, and Maugis-Dugdale's start
/// from another model's answer.
struct Starts {
    tip: Geometry,
    est: Estimates,
    /// The pull-off the starts' w are read from (at least ten times the noise, and a floor).
    pull: f64,
    /// The w of a normalised pull-off 1.75: the fits' scale of w.
    w_ref: f64,
    /// The units the normalised pull-offs are read in (a capped cone's at the start's E* and
    /// the sphere-like w of its cap).
    u_start: Units,
    /// The largest force measured (N): the bound of a Maugis-Dugdale fit's force offset.
    f_max: f64,
}

impl Starts {
    fn new(raw: &Prepared, opt: &FitOptions) -> Starts {
        let tip = opt.geometry();
        let est = estimates(raw, tip, opt.spring);
        // A floor for a curve without adhesion: a force far below the contact's (1e-6 E* R^2 on
        // a sphere; a power law has no radius, and its largest force stands for it).
        let floor = match tip.radius() {
            Some(r) => 1e-6 * est.e_star * r * r,
            None => 1e-6 * raw.scales.0,
        };
        let pull = est.pulloff.max(10.0 * raw.noise).max(floor);
        let w_ref = tip.w_for_pulloff(pull, 1.75, est.e_star);
        let u_start = tip.units(est.e_star, w_ref, opt.spring);
        Starts {
            tip,
            est,
            pull,
            w_ref,
            u_start,
            f_max: raw.scales.0,
        }
    }

    /// The w whose normalised pull-off `pc_bar` is the measured pull-off.
    fn w_of(&self, pc_bar: f64) -> f64 {
        self.tip.w_for_pulloff(self.pull, pc_bar, self.est.e_star)
    }

    /// The estimates with this w and lambda.
    fn at(&self, w: f64, lambda: f64) -> Params {
        Params {
            e_star: self.est.e_star,
            w,
            lambda,
            zc: self.est.zc,
            f0: 0.0,
        }
    }

    /// A model's normalised pull-off at lambda, in the start's units.
    fn pulloff(&self, model: Model, lambda: f64) -> f64 {
        self.tip.law(model, lambda, &self.u_start).pulloff()
    }

    /// Maugis-Dugdale (pull-off `pc_md`) at lambda from a closed form's answer, its w scaled by
    /// the ratio of the pull-offs, and from the estimates where that fit failed.
    fn from(&self, m: &ModelFit, lambda: f64, pc_md: f64) -> Params {
        let ok = m.status == FitStatus::Ok;
        let scaled = m.work_of_adhesion_j_m2 * self.pulloff(m.model, 1.0) / pc_md;
        Params {
            e_star: if ok { m.e_star_pa } else { self.est.e_star },
            // A closed form whose adhesion collapsed (w far below what the measured pull-off
            // says) would start Maugis-Dugdale where w has no grip on the misfit: the
            // pull-off's w.
            w: if ok && scaled > 1e-2 * self.w_of(pc_md) {
                scaled
            } else {
                self.w_of(pc_md)
            },
            lambda,
            zc: if ok { m.contact_point_m } else { self.est.zc },
            // Within the bound of Maugis-Dugdale's offset (`Problem::checked`), which a closed
            // form does not have: a start beyond it would be refused whole.
            f0: if ok {
                m.force_offset_n
                    .clamp(-0.99 * self.f_max, 0.99 * self.f_max)
            } else {
                0.0
            },
        }
    }
}

/// A closed form with adhesion fitted, its w started from the measured pull-off with its own.
/// It holds Hertz (w = 0), so it never fits worse: where it did, it stopped in the flat misfit
/// of a contact point beyond every point (no point in contact), and is fitted again from Hertz's
/// answer with a little adhesion.
///
/// The first fit has a short budget ([`FIRST_PATIENCE`]): from the pull-off's w the model's
/// jump can lie inside the curve where the data show none, and as the jump crosses points the
/// misfit changes in steps, which Levenberg-Marquardt crawls along for a long budget, often
/// without converging. Where it stops unconverged, the fit from Hertz's answer (whose jump is
/// small) is made, and the better of the two taken: the first as it stands where it fits better
/// than Hertz. Where neither does, the first goes on with the full budget.
fn closed_form(
    model: Model,
    raw: &Prepared,
    opt: &FitOptions,
    s: &Starts,
    hertz: &ModelFit,
) -> ModelFit {
    let w = s.w_of(s.pulloff(model, 1.0));
    let full = |from: Params| fit_model(model, raw, opt, from, s.w_ref, None);
    let first = fit_model_for(
        model,
        raw,
        opt,
        s.at(w, 1.0),
        s.w_ref,
        None,
        FIRST_PATIENCE,
        None,
    );
    // Hertz's misfit, which the law holds as w -> 0: worse by more than rounding (at w -> 0 the
    // two misfits agree to about 1e-13) is a local minimum.
    let limit = hertz.rms_residual_n * (1.0 + 1e-9);
    if first.status == FitStatus::Ok && (hertz.status != FitStatus::Ok || key(&first) <= limit) {
        return first;
    }
    let again = (hertz.status == FitStatus::Ok).then(|| {
        full(Params {
            w: 1e-2 * w,
            ..hertz.params()
        })
    });
    let mut f = match again {
        Some(a)
            if first.status == FitStatus::Ok
                || (a.status == FitStatus::Ok && rank(&a) <= rank(&first)) =>
        {
            better(first, a)
        }
        // Stopped by the short budget where it fits better than Hertz and than the fit from
        // Hertz's answer: taken as it stands (as a free Maugis-Dugdale fit is, see `scout`; its
        // stop says so, and the adequacy test does not reject the model on it).
        Some(a) if rank(&first) <= limit && rank(&first) <= rank(&a) => ModelFit {
            status: FitStatus::Ok,
            ..first
        },
        // Neither: the first fit goes on with the full budget.
        a => {
            let on = full(first.params());
            better(on, a.unwrap_or(first))
        }
    };
    if key(&f) > limit {
        // Still worse: a local minimum, said so. (A cone's JKR-type law reaches its punch only
        // as w -> 0, where its contact radius in its units grows like 1/w, beyond the path's
        // range: docs/PHYSICS.md section 12.4.)
        f.stop += &format!(
            "; a local minimum: worse than Hertz ({:.3e} N), which the law holds as w -> 0",
            hertz.rms_residual_n
        );
    }
    f
}

/// The budget of a closed form's first fit (MINPACK's, as [`PATIENCE`]).
const FIRST_PATIENCE: usize = 30;

/// Maugis-Dugdale free in lambda on `d` (the curve, or its bins): the misfit has local minima
/// in lambda (the jump moves with it), so a profile over lambda (each point a fit at fixed
/// lambda, started from the closed form of that side: `low` below lambda 1, `jkr` above) picks
/// the starts of the free fit and gives the confidence region of lambda.
fn md_profiled(
    raw: &Prepared,
    d: &Prepared,
    binned: bool,
    opt: &FitOptions,
    s: &Starts,
    (low, jkr): (&ModelFit, &ModelFit),
) -> (ModelFit, interval::Intervals) {
    let profile: Vec<ModelFit> = profile_lambdas()
        .map(|l| {
            let pc = s.pulloff(Model::Md, l);
            let start = s.from(if l < 1.0 { low } else { jkr }, l, pc);
            fit_model(Model::Md, d, opt, start, s.w_ref, Some(l))
        })
        .collect();
    let mut md = free_fit(d, opt, s.w_ref, profile.clone());
    let mut profile = profile;
    if binned {
        // The bins' scatter set from the fit found (see `recalibrate`), for the noise that the
        // intervals read from its misfit.
        let n = raw.count as f64;
        let gap = n * rms_on(&md, raw, opt, s.w_ref).powi(2) - n * md.rms_residual_n.powi(2);
        for f in profile.iter_mut().chain(std::iter::once(&mut md)) {
            recalibrate(f, gap, n);
        }
    }
    let iv = if md.status == FitStatus::Ok {
        interval::profile_intervals(d, opt, s.w_ref, &md, &profile)
    } else {
        interval::Intervals::default()
    };
    (md, iv)
}

fn fit_prepared(curve: &Curve, opt: &FitOptions, raw: &Prepared) -> CurveFit {
    let s = Starts::new(raw, opt);
    let (tip, w_ref) = (s.tip, s.w_ref);
    // The closed forms on the points: their fits are few and short, and the search of
    // Maugis-Dugdale starts from them.
    let hertz = fit_model(Model::Hertz, raw, opt, s.at(w_ref, 1.0), w_ref, None);
    // A tip's ladder has no DMT ([`Geometry::ladder`]): its Maugis-Dugdale profile starts
    // from Hertz's (Sneddon's) answer on the DMT side.
    let dmt = tip
        .is_sphere()
        .then(|| closed_form(Model::Dmt, raw, opt, &s, &hertz));
    let jkr = closed_form(Model::Jkr, raw, opt, &s, &hertz);
    let low = dmt.as_ref().unwrap_or(&hertz);
    // The search of Maugis-Dugdale runs on the curve in bins where it has many points
    // ([`Prepared::binned`]); what was measured (the pull-off, the largest load, the points)
    // is read from its points.
    let binned = raw.binned();
    let d = binned.as_ref().unwrap_or(raw);
    let (md, iv) = match opt.z0 {
        // From the better adhesive closed form (a tip's only one is JKR-type: Hertz's w and
        // pull-off are 0 and would start nothing).
        Some(z0) => match fixed_z0_fit(
            curve,
            d,
            opt,
            z0,
            (dmt.as_ref().unwrap_or(&jkr), &jkr),
            &|m, l, pc| s.from(m, l, pc),
            w_ref,
        ) {
            Ok(r) => r,
            Err(out) => return *out,
        },
        None => md_profiled(raw, d, binned.is_some(), opt, &s, (low, &jkr)),
    };
    // A fit that ended where it started found nothing to follow (the misfit was flat there).
    let stuck = md.status == FitStatus::Ok
        && (md.e_star_pa / s.est.e_star - 1.0).abs() < 1e-9
        && (md.contact_point_m - s.est.zc).abs() <= 1e-9 * s.est.zc.abs();
    // Fitted on the bins: each fit finished on the points, the intervals holding the answer.
    let (md, iv) = match binned {
        Some(_) => {
            let mut iv = iv;
            let points = keep_spread(finish_on_points(md.clone(), raw, opt, w_ref), &md);
            interval::recentre(&mut iv, &md, &points, tip);
            let md = points;
            interval::hold(&mut iv, &md, tip);
            (md, iv)
        }
        None => (md, iv),
    };
    let models = ladder(hertz, dmt, jkr);
    let mut out = summarize(curve, opt, raw, md, models, &iv);
    if stuck && out.status == FitStatus::Ok {
        out = unmoved(out, curve, raw, opt);
    }
    out
}

/// The closed forms' fits from the simplest (a tip's without DMT).
fn ladder(hertz: ModelFit, dmt: Option<ModelFit>, jkr: ModelFit) -> Vec<ModelFit> {
    std::iter::once(hertz).chain(dmt).chain([jkr]).collect()
}

/// A fit made on a curve's bins, finished on its points from there: the points' own minimum, which the bins' curvature moves by about a Delta chi^2 of
/// 1, reached in a few iterations. Where the finish fails or does worse, the bins' fit with its
/// misfit read on the points.
fn finish_on_points(f: ModelFit, raw: &Prepared, opt: &FitOptions, w_ref: f64) -> ModelFit {
    if !f.rms_residual_n.is_finite() {
        return f;
    }
    let on_points = rms_on(&f, raw, opt, w_ref);
    // A noisy curve's (only those are binned): the tolerance of the profile's fits, far below
    // the noise.
    let g = fit_model_tol(
        f.model,
        raw,
        opt,
        f.params(),
        w_ref,
        None,
        FINISH_PATIENCE,
        None,
        Some(PROFILE_TOL),
    );
    // A finish stopped by its short budget has still moved downhill from a converged fit.
    let moved = g.status == FitStatus::Ok || g.stop == stop_text(&TerminationReason::LostPatience);
    if f.status == FitStatus::Ok && moved && g.rms_residual_n <= on_points {
        ModelFit {
            iterations: f.iterations + g.iterations,
            status: FitStatus::Ok,
            stop: format!("{}; finished on the points", f.stop),
            ..g
        }
    } else {
        ModelFit {
            rms_residual_n: on_points,
            ..f
        }
    }
}

/// The iteration budget of a finish on the points (MINPACK's, as [`PATIENCE`]): it starts
/// within about a Delta chi^2 of 1 of its minimum, and a misfit that crawls along a flat valley
/// from there would spend the whole of a full fit's budget for nothing the intervals see.
const FINISH_PATIENCE: usize = 5;

/// A fit on a curve's bins with `gap` (N^2) added to its residual sum over `n` points: the
/// bins' scatter is estimated from the points about each bin's line, which runs low (a bin ends
/// where its scatter grows), and is set instead so that the best fit's sum on the bins is its
/// sum on the points. Differences of the sums, which the profile reads, do not change.
fn recalibrate(f: &mut ModelFit, gap: f64, n: f64) {
    let rss = n * f.rms_residual_n.powi(2) + gap;
    if gap.is_finite() && rss >= 0.0 {
        f.rms_residual_n = (rss / n).sqrt();
    }
}

/// The free fit finished on the points with the standard errors of the bins' fit, which the
/// profile's region widened ([`search::widen_by_region`]).
fn keep_spread(finished: ModelFit, binned: &ModelFit) -> ModelFit {
    ModelFit {
        e_star_pa_stderr: binned.e_star_pa_stderr,
        work_of_adhesion_j_m2_stderr: binned.work_of_adhesion_j_m2_stderr,
        lambda_stderr: binned.lambda_stderr,
        contact_point_m_stderr: binned.contact_point_m_stderr,
        ..finished
    }
}

/// A fit that ended where it started: `not_converged`, with the likely causes, keeping what
/// was measured and the models' fits.
fn unmoved(out: CurveFit, curve: &Curve, d: &Prepared, opt: &FitOptions) -> CurveFit {
    let mut r = fail(
        curve,
        FitStatus::NotConverged,
        format!(
            "the fit did not move from its start (the misfit does not change with E* and the contact point there){}",
            unit_hints(d, opt)
        ),
    );
    r.points_fitted = out.points_fitted;
    r.pulloff_force_measured_n = out.pulloff_force_measured_n;
    r.max_load_n = out.max_load_n;
    r.iterations = out.iterations;
    r.stop = out.stop;
    r.warnings = d.notes.clone();
    r.models = out.models;
    r.md = out.md;
    r
}

/// Maugis-Dugdale with lambda tied to E* and w by a given z0, started from the better closed
/// form; Err with the curve's result where z0 puts lambda outside the domain.
fn fixed_z0_fit(
    curve: &Curve,
    d: &Prepared,
    opt: &FitOptions,
    z0: f64,
    (dmt, jkr): (&ModelFit, &ModelFit),
    from: &dyn Fn(&ModelFit, f64, f64) -> Params,
    w_ref: f64,
) -> Result<(ModelFit, interval::Intervals), Box<CurveFit>> {
    let tip = opt.geometry();
    let best = better(dmt.clone(), jkr.clone());
    let u = tip.units(
        best.e_star_pa,
        best.work_of_adhesion_j_m2.max(w_ref),
        opt.spring,
    );
    let pc = tip.law(best.model, 1.0, &u).pulloff();
    let mut s = from(&best, 1.0, pc);
    s.lambda = tip.lambda_from_z0(s.e_star, s.w, z0);
    if !tip.admits_lambda(s.lambda) {
        let mut out = fail(
            curve,
            FitStatus::InvalidInput,
            format!(
                "the Lennard-Jones range z0 = {} m gives lambda = {} with this curve's E* and w (about {} Pa and {} J/m^2), outside the models' domain {}: check z0 (about 0.3e-9 m for van der Waals), or leave it out to fit lambda",
                crate::physics::domain::short(z0),
                crate::physics::domain::short(s.lambda),
                crate::physics::domain::short(s.e_star),
                crate::physics::domain::short(s.w),
                tip.lambda_domain(),
            ),
        );
        out.warnings = d.notes.clone();
        return Err(Box::new(out));
    }
    let md = fit_model(Model::Md, d, opt, s, w_ref, None);
    let iv = interval::fixed_z0_intervals(d, &md);
    Ok((md, iv))
}

/// The likely causes of an absurd fit, from the scales of the data and options: units off by
/// 1e9 (nN or nm given where N or m are read), a radius or a spring constant that no AFM has.
fn unit_hints(d: &Prepared, opt: &FitOptions) -> String {
    let h = hints(d, opt);
    if h.is_empty() {
        format!(
            "; check the spring constant (a wrong one moves E* by orders of magnitude), {}, and that height_m is in metres and force_n in newtons",
            if opt.tip.is_some() { "the tip's shape" } else { "the tip radius" }
        )
    } else {
        format!("; likely cause: {}", h.join("; "))
    }
}

/// The scales of the data and options that no AFM curve has, each a sentence.
fn hints(d: &Prepared, opt: &FitOptions) -> Vec<String> {
    let short = crate::physics::domain::short;
    let fmax = d.force.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    let hmax = d.height.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let hmin = d.height.iter().cloned().fold(f64::INFINITY, f64::min);
    let mut h = Vec::new();
    if fmax > 1e-4 {
        h.push(format!(
            "the forces reach {} N, far beyond an AFM's: if force_n is in nN, multiply it by 1e-9 (forces are read in newtons)",
            short(fmax)
        ));
    }
    if hmax - hmin > 1e-3 {
        h.push(format!(
            "the heights span {} m, far beyond an AFM's: if height_m is in nm, multiply it by 1e-9 (heights are read in metres)",
            short(hmax - hmin)
        ));
    }
    if opt.tip.is_none() && !(1e-10..=1e-3).contains(&opt.radius) {
        h.push(format!(
            "the tip radius {} m is not an AFM tip's (1e-10..1e-3 m): give it in metres",
            short(opt.radius)
        ));
    }
    if !(1e-4..=1e4).contains(&opt.spring) {
        h.push(format!(
            "the spring constant {} N/m is not a cantilever's (1e-4..1e4 N/m): give it in N/m",
            short(opt.spring)
        ));
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_contact_at_the_end_of_a_mostly_flat_approach_is_not_a_spike() {
        // 1000 baseline points with a little deterministic noise, then the contact: a ramp of
        // 40 points far beyond the segment's quantiles, ending the segment.
        let mut f: Vec<f64> = (0..1000)
            .map(|i| 1e-3 * ((i * 7919) % 13) as f64 / 13.0)
            .collect();
        f.extend((1..=40).map(|k| k as f64 / 40.0));
        assert_eq!(spikes(&f), Vec::<usize>::new());
        // Isolated glitches inside it are spikes, one point or a run of up to three.
        let mut g = f.clone();
        g[300] = 5.0;
        g[600] = -4.0;
        g[601] = -4.0;
        assert_eq!(spikes(&g), vec![300, 600, 601]);
        // A run of four is a feature, kept.
        let mut h = f.clone();
        h[300..304].fill(5.0);
        assert_eq!(spikes(&h), Vec::<usize>::new());
    }

    /// A 200-point synthetic curve of `model` (E* 1.5 GPa, w 0.05 J/m^2, R 20 nm, 10 pN noise)
    /// under a cantilever of `spring` N/m, its options and the prepared curve.
    fn test_curve(
        model: Model,
        lambda: f64,
        spring: f64,
        seed: u64,
    ) -> (synthetic::Synthetic, FitOptions, Prepared) {
        let s = synthetic::Synthetic {
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
            points: 200,
            depth: 6.0,
            noise: 1e-11,
            seed,
        };
        let opt = FitOptions {
            radius: 20e-9,
            spring,
            ..FitOptions::default()
        };
        let d = prepare(&synthetic::synthetic(&s), &opt).unwrap();
        (s, opt, d)
    }

    #[test]
    fn the_analytic_jacobian_matches_differences() {
        for (model, lambda, spring) in [
            (Model::Md, 0.3, 2.0),
            (Model::Md, 5.0, 0.5),
            (Model::Jkr, 1.0, 2.0),
            (Model::Dmt, 1.0, 10.0),
            (Model::Hertz, 1.0, 2.0),
        ] {
            let (s, opt, d) = test_curve(model, lambda, spring, 3);
            let mut start = s.params;
            // Off the truth, so that the residuals and slopes are generic.
            start.e_star *= 1.1;
            start.w *= 0.95;
            start.zc += 0.2e-9;
            let mut prob = Problem::new(model, &d, &opt, 0.05, None);
            prob.z_scale = 1e-8;
            prob.f_scale = 1e-9;
            prob.x = prob.internal(&start);
            let base = prob.eval(&prob.x, None).unwrap().1;
            let mut a = prob.analytic_jacobian(&base).0;
            // The points before the jump are fitted by their distance to the curve: their rows
            // from its slopes at the nearest state, against differences of that distance.
            prob.fold_rows(&mut a, &base);
            let folds = (0..base.len())
                .filter(|&i| d.at_jump[i] && base[i].piece != Piece::Free)
                .count();
            assert!(
                folds > 0 || model == Model::Hertz,
                "{model:?}: no point before a jump"
            );
            let all: Vec<usize> = (0..prob.n()).collect();
            let n = prob.numeric_jacobian(&base, &all).unwrap();
            for k in 0..prob.n() {
                let scale = n.column(k).amax().max(1e-12);
                // Held points: the slopes leave out how the fold moves (a local approximation
                // the iteration tolerates); compared elsewhere.
                let mut diff = a.column(k) - n.column(k);
                for (i, st) in base.iter().enumerate() {
                    if st.clamped {
                        diff[i] = 0.0;
                    }
                }
                let err = diff.amax() / scale;
                let i = diff.iamax();
                assert!(
                    err < 1e-5,
                    "{model:?} column {k}: {err} at row {i}: {:?} {} {}",
                    base[i],
                    a[(i, k)],
                    n[(i, k)]
                );
            }
        }
    }

    #[test]
    fn lambdas_analytic_column_matches_central_differences() {
        // Every row not before a jump; these curves put their points on the contact and free
        // pieces (the non-contact piece's slopes are checked in the test above).
        let mut compared = 0;
        for (lambda, spring) in [(0.8, 2.0), (0.05, 50.0)] {
            let (s, opt, d) = test_curve(Model::Md, lambda, spring, 5);
            let mut start = s.params;
            start.e_star *= 1.1;
            start.lambda *= 1.3;
            let mut prob = Problem::new(Model::Md, &d, &opt, 0.05, None);
            prob.x = prob.internal(&start);
            LeastSquaresProblem::residuals(&prob).unwrap();
            // Some points may be held at the end of their stretch (lambda is 30% off): their
            // rows come from differences in both.
            let base = prob.states.borrow().clone().unwrap();
            let j = LeastSquaresProblem::jacobian(&prob).unwrap();
            let c = prob.numeric_jacobian(&base, &[2]).unwrap();
            // Central differences with a step of 1e-6 max(|ln lambda|, 1) (3e-6 at lambda 0.05):
            // truncation about 1e-11, rounding of the residuals (1e-16 of the largest force)
            // over the step about 1e-10.
            // The points before a jump have their own rows (the distance to the fold), by
            // differences in both.
            let scale = c.column(2).amax();
            for (i, s) in base.iter().enumerate().filter(|(i, _)| !d.at_jump[*i]) {
                let (a, n) = (j[(i, 2)], c[(i, 2)]);
                assert!(
                    (a - n).abs() <= 1e-7 * scale,
                    "lambda {lambda}, point {i} on {:?}: analytic {a:e} against central {n:e}",
                    s.piece
                );
                if s.piece != Piece::Free && !s.clamped {
                    assert!(a != 0.0, "lambda {lambda}, point {i}: no slope");
                    compared += 1;
                }
            }
        }
        assert!(compared > 100, "{compared} rows compared");
    }

    #[test]
    fn the_states_slides_match_differences() {
        // dt/dx of each state (the next trial's hints move along it) against central
        // differences of the states found by Newton steps from the base, every parameter.
        let mut compared = 0;
        for (model, lambda, spring) in [
            (Model::Md, 0.8, 2.0),
            (Model::Md, 5.0, 0.5),
            (Model::Jkr, 1.0, 2.0),
        ] {
            let (s, opt, d) = test_curve(model, lambda, spring, 7);
            let mut start = s.params;
            start.e_star *= 1.1;
            start.w *= 0.95;
            start.lambda *= 1.2;
            let mut prob = Problem::new(model, &d, &opt, 0.05, None);
            prob.x = prob.internal(&start);
            let base = prob.eval(&prob.x, None).unwrap().1;
            let (_, dt) = prob.analytic_jacobian(&base);
            for k in 0..prob.n() {
                let h = 1e-6 * prob.x[k].abs().max(1.0);
                let (mut xp, mut xm) = (prob.x.clone(), prob.x.clone());
                xp[k] += h;
                xm[k] -= h;
                let sp = prob.eval(&xp, Some(&base)).unwrap().1;
                let sm = prob.eval(&xm, Some(&base)).unwrap().1;
                for (i, b) in base.iter().enumerate() {
                    if b.piece == Piece::Free || b.clamped {
                        assert_eq!(dt[(i, k)], 0.0);
                        continue;
                    }
                    if sp[i].piece != b.piece || sm[i].piece != b.piece {
                        continue;
                    }
                    let n = (sp[i].t - sm[i].t) / (2.0 * h);
                    // The base states' slopes may be those one Newton step (below 1e-8) away,
                    // and the differences' truncation grows near a fold: hints need no more.
                    assert!(
                        (dt[(i, k)] - n).abs() <= 1e-4 * n.abs().max(1.0),
                        "{model:?} parameter {k}, point {i} on {:?}: {} against {n}",
                        b.piece,
                        dt[(i, k)]
                    );
                    compared += 1;
                }
            }
        }
        assert!(compared > 500, "{compared} slides compared");
    }
}
