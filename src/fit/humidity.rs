//! A curve fitted in humid air: the solid's work of adhesion with the water meniscus taken out.
//!
//! The curve's shape is fitted with one Dugdale zone (Maugis-Dugdale: E*, w, lambda). That
//! zone's load-controlled pull-off, `Pbar_c(lambda) pi w R`, is then read as the pull-off of the
//! solid's zone and the meniscus beside it (the two-zone law, docs/PHYSICS.md section 10): the
//! solid's w is the one that, with the meniscus of the humidity given and the fitted E* and
//! Lennard-Jones range z0, pulls off at that force, the same exact inversion as
//! [`crate::scene::infer_wet`] (`tabor infer --relative-humidity`).

use super::problem::{fit_model, Params};
use super::{CurveFit, FitStatus, Model, ModelFit, Prepared};
use crate::physics::params::{Contact, ForceRange, LJ_STRESS};
use crate::scene::humidity::{HumidityInput, Meniscus};
use crate::solver::LambdaContext;
use serde::Serialize;
use std::f64::consts::PI;

/// The humidity of a fitted curve and the solid's w it leaves (SI units).
#[derive(Clone, Debug, Serialize)]
pub struct FitHumidity {
    /// Relative humidity, 0..1.
    pub relative_humidity: f64,
    /// Contact angle of water on the surfaces (degrees).
    pub contact_angle_deg: f64,
    /// Surface tension of the liquid (N/m), the default filled in.
    pub surface_tension_n_m: f64,
    /// Molar volume of the liquid (m^3/mol), the default filled in.
    pub molar_volume_m3_mol: f64,
    /// Temperature (K), the default filled in.
    pub temperature_k: f64,
    /// The meniscus as a Dugdale zone; null where none forms (a contact angle of 90 degrees or
    /// more, or a Kelvin radius below one molecule of the liquid).
    pub meniscus: Option<Meniscus>,
    /// The fitted Maugis-Dugdale model's load-controlled pull-off, `Pbar_c(lambda) pi w R` with
    /// the fitted E*, w, lambda and the curve's tip radius (N, its magnitude): the force the
    /// meniscus is taken out of.
    pub pulloff_force_load_control_n: f64,
    /// The Lennard-Jones range of the solid's zone, held while its w is found (the fit's z0, m).
    pub z0_m: f64,
    /// The load-controlled pull-off of the meniscus alone (N, its magnitude).
    pub meniscus_only_pulloff_n: Option<f64>,
    /// The solid's w with the meniscus taken out (J/m^2): the fitted w where no meniscus
    /// forms; null where the meniscus alone pulls off harder than the fitted model (`note`
    /// says so).
    pub solid_work_of_adhesion_j_m2: Option<f64>,
    /// The solid's Maugis parameter with that w and z0.
    pub solid_lambda: Option<f64>,
    /// The fraction of the fitted pull-off that the meniscus adds: 1 - (the solid's own
    /// Maugis-Dugdale pull-off with its w) / (the fitted pull-off); 0 without a meniscus.
    pub meniscus_share: Option<f64>,
    /// The meniscus' range 2 r_K cos(theta) against the fitted zone's Dugdale range w / s0.
    pub meniscus_range_over_fitted_range: Option<f64>,
    /// Whether the reading is fair: the meniscus reaches no farther than the fitted Dugdale
    /// zone, or its work is at most a tenth of the fitted w (see `note`).
    pub fair_reading: bool,
    /// What was found, and how far to trust it, in words.
    pub note: String,
    /// The two-zone law fitted to the curve's shape where this reading is doubtful: E*, the
    /// solid's w and lambda (or lambda from the z0 held), with this meniscus in its own zone;
    /// null without a meniscus or where the reading is fair.
    pub shape_fit: Option<ShapeFit>,
}

/// Where the meniscus' work is at most this fraction of the fitted w, the meniscus is small
/// and the reading fair whatever its range.
pub const SMALL_MENISCUS: f64 = 0.1;

/// The solid's w of a fitted curve (`r`, status ok) in the humidity `h`, with the curve's tip
/// radius. `h` has been checked ([`HumidityInput::validate`]). Never fails: where the meniscus
/// cannot be taken out, the solid's w is null and `note` says why.
pub fn solid_work(r: &CurveFit, radius: f64, h: &HumidityInput) -> Option<FitHumidity> {
    let (e_star, w, lambda, z0) = (r.e_star_pa?, r.work_of_adhesion_j_m2?, r.lambda?, r.z0_m?);
    let mut out = FitHumidity {
        relative_humidity: h.relative_humidity,
        contact_angle_deg: h.contact_angle_deg,
        surface_tension_n_m: h.surface_tension(),
        molar_volume_m3_mol: h.molar_volume(),
        temperature_k: h.temperature(),
        meniscus: None,
        pulloff_force_load_control_n: f64::NAN,
        z0_m: z0,
        meniscus_only_pulloff_n: None,
        solid_work_of_adhesion_j_m2: None,
        solid_lambda: None,
        meniscus_share: None,
        meniscus_range_over_fitted_range: None,
        fair_reading: false,
        note: String::new(),
        shape_fit: None,
    };
    let fail = |mut out: FitHumidity, why: String| {
        out.note = format!("the meniscus could not be taken out of this fit: {why}");
        Some(out)
    };
    let ctx = match LambdaContext::new(lambda) {
        Ok(c) => c,
        Err(e) => return fail(out, e.to_string()),
    };
    let f = -ctx.load_pulloff.load * PI * w * radius;
    if !(f.is_finite() && f > 0.0) {
        return fail(out, format!("the fitted pull-off {f:e} N is not a force"));
    }
    out.pulloff_force_load_control_n = f;
    let contact = match Contact::new(radius, e_star, w, ForceRange::LennardJones(z0)) {
        Ok(c) => c,
        Err(e) => return fail(out, e.to_string()),
    };
    let meniscus = match h.meniscus(&contact) {
        Ok(m) => m,
        Err(e) => return fail(out, e.to_string()),
    };
    let Some(m) = meniscus else {
        out.solid_work_of_adhesion_j_m2 = Some(w);
        out.solid_lambda = Some(lambda);
        out.meniscus_share = Some(0.0);
        out.fair_reading = true;
        out.note = format!(
            "no meniscus ({}): the solid's w is the fitted w",
            h.no_meniscus().as_deref().unwrap_or("none forms")
        );
        return Some(out);
    };
    out.meniscus = Some(m);
    // The fitted zone's Dugdale range w / s0, s0 = LJ_STRESS w / z0.
    let ratio = m.range_m / (z0 / LJ_STRESS);
    out.meniscus_range_over_fitted_range = Some(ratio);
    let small = m.work_of_adhesion_j_m2 <= SMALL_MENISCUS * w;
    out.fair_reading = ratio <= 1.0 || small;
    let fairness = fairness(ratio, small, m.work_of_adhesion_j_m2, w);
    let inf = match crate::scene::infer_wet(f, radius, e_star, z0, h) {
        Ok(i) => i,
        Err(e) => return fail(out, e.to_string()),
    };
    out.meniscus_only_pulloff_n = Some(inf.meniscus_only_pulloff_n);
    match (inf.solid_work_of_adhesion_j_m2, inf.solid_lambda) {
        (Some(ws), Some(ls)) => {
            out.solid_work_of_adhesion_j_m2 = Some(ws);
            out.solid_lambda = Some(ls);
            let alone = LambdaContext::new(ls)
                .map(|c| -c.load_pulloff.load * PI * ws * radius)
                .ok();
            out.meniscus_share = alone.map(|a| 1.0 - a / f);
            out.note = format!(
                "solid w = {ws:.4e} J/m^2 (lambda = {ls:.3}): with the meniscus (w = {:.4e} J/m^2) it pulls off at the fitted {f:.4e} N; the fitted w = {w:.4e} J/m^2 holds both; {fairness}",
                m.work_of_adhesion_j_m2
            );
        }
        _ if inf.meniscus_only_pulloff_n >= f => {
            out.note = format!(
                "no solid w: the meniscus alone pulls off at {:.4e} N, more than the fitted model's {f:.4e} N (a larger contact angle or a lower humidity than given, or a meniscus not in equilibrium)",
                inf.meniscus_only_pulloff_n
            );
        }
        _ => {
            out.note = format!(
                "no solid w: the two-zone pull-off was not matched to 1e-9 of the fitted {f:.4e} N"
            );
        }
    }
    Some(out)
}

/// A fitted curve (`r`, its Maugis-Dugdale fit `md` on the prepared data `d`) in the humidity
/// `h`: the pull-off's reading ([`solid_work`]) and, where it is doubtful, the two-zone law
/// fitted to the curve's shape ([`fit_shape`]).
pub(super) fn in_humid_air(
    r: &CurveFit,
    d: &Prepared,
    opt: &super::FitOptions,
    md: &ModelFit,
    h: &HumidityInput,
) -> Option<FitHumidity> {
    let mut fh = solid_work(r, opt.radius, h)?;
    fit_shape(&mut fh, d, opt, md, h);
    Some(fh)
}

/// Whether one Dugdale zone fairly describes a curve with this meniscus, in words: its range
/// against the fitted zone's (`ratio`), or its work small against the fitted w.
fn fairness(ratio: f64, small: bool, meniscus_w: f64, w: f64) -> String {
    if ratio <= 1.0 {
        format!(
            "a fair reading: the meniscus reaches {ratio:.2} of the fitted zone's range, so one Dugdale zone describes the curve's shape with the meniscus in it"
        )
    } else if small {
        format!(
            "a fair reading: the meniscus reaches {ratio:.2} times the fitted zone's range, but its work is at most a tenth of the fitted w"
        )
    } else {
        format!(
            "a doubtful reading: the meniscus reaches {ratio:.2} times the fitted zone's range with a work {:.2} times the fitted w, so the curve's shape is not one Dugdale zone's and the fitted lambda (and the z0 held here) mixes solid and meniscus",
            meniscus_w / w
        )
    }
}

/// The two-zone law fitted to a humid curve's shape, where the pull-off's reading is doubtful
/// (the meniscus reaching beyond the one zone's range): see docs/PHYSICS.md section 10.
#[derive(Clone, Debug, Serialize)]
pub struct ShapeFit {
    /// The fit: E*, the solid's w (`work_of_adhesion_j_m2`) and Maugis parameter (`lambda`,
    /// its standard error linearised), the contact point, the offset and the misfit.
    pub fit: ModelFit,
    /// The solid's Lennard-Jones range with the fitted E*, w and lambda (m).
    pub z0_m: f64,
    /// The misfit's profile over the solid's lambda: `[lambda, rms residual (N)]` of the fits
    /// at fixed lambda from each start (empty where z0 is held).
    pub lambda_profile: Vec<[f64; 2]>,
    /// The smallest and largest lambda of the profile and the fit within Delta chi^2 = 3.84
    /// of the fit's misfit (95%, the noise from its residual): null where z0 is held.
    pub lambda_95: Option<[f64; 2]>,
    /// Whether the curve fixes the solid's lambda: the profile's smallest and largest lambdas lie
    /// outside that set, on either side of the fitted lambda (false: the set reaches the
    /// profile's end, and the curve allows lambdas beyond it). Null where z0 is held (z0 fixes
    /// lambda, not the curve) or the fit did not converge.
    pub lambda_bounded: Option<bool>,
    /// The smallest and largest solid w (J/m^2) of the fits in that set: where lambda is not
    /// fixed, w moves with it along the misfit's valley, farther than its linearised standard
    /// error says. Null where z0 is held.
    pub solid_w_95: Option<[f64; 2]>,
}

/// The solid's Lennard-Jones ranges (m) the two-zone shape fit is started from, besides the
/// one zone's: its misfit has local minima in lambda, as one zone's has (the jump moves with
/// it).
const SHAPE_Z0S: [f64; 6] = [0.1e-9, 0.2e-9, 0.4e-9, 0.8e-9, 1.6e-9, 3.2e-9];

/// How many of the profile's best points start a free fit.
const SHAPE_FITS: usize = 2;

/// Fits the two-zone law to the curve's shape where the pull-off's reading is doubtful (where
/// it is fair, one Dugdale zone describes the shape): the solid's zone (E*, its w and lambda,
/// or lambda from the z0 held) with the meniscus of the humidity in its own zone, as
/// docs/PHYSICS.md section 10 has them. Each start is the pull-off's reading at one z0 (the
/// one zone's, and a grid): E*, the contact point and the offset of the Maugis-Dugdale fit
/// `md`, and the solid's w and lambda that pull off with the meniscus at the one zone's force.
/// Each start is fitted at its lambda (the profile), and the free fit starts from the
/// profile's best points; the profile also gives lambda's 95% set.
pub(super) fn fit_shape(
    fh: &mut FitHumidity,
    d: &Prepared,
    opt: &super::FitOptions,
    md: &ModelFit,
    h: &HumidityInput,
) {
    if fh.meniscus.is_none() || md.status != FitStatus::Ok || fh.fair_reading {
        return;
    }
    let w_md = md.work_of_adhesion_j_m2;
    let z0s: Vec<f64> = match opt.z0 {
        Some(z0) => vec![z0],
        None => std::iter::once(fh.z0_m).chain(SHAPE_Z0S).collect(),
    };
    let readings: Vec<Params> = z0s
        .iter()
        .filter_map(|&z0| {
            let f = fh.pulloff_force_load_control_n;
            let inf = crate::scene::infer_wet(f, opt.radius, md.e_star_pa, z0, h).ok()?;
            Some(Params {
                e_star: md.e_star_pa,
                w: inf.solid_work_of_adhesion_j_m2?,
                lambda: inf.solid_lambda?,
                zc: md.contact_point_m,
                f0: md.force_offset_n,
            })
        })
        .collect();
    let fit = |p: &Params, fixed: Option<f64>| {
        fit_model(Model::SolidAndMeniscus, d, opt, *p, w_md, fixed)
    };
    let misfit = |f: &ModelFit| {
        if f.status == FitStatus::Ok {
            f.rms_residual_n
        } else {
            f64::INFINITY
        }
    };
    // The profile at the starts' lambdas (none where z0 ties lambda to E* and w).
    let mut profile: Vec<ModelFit> = match opt.z0 {
        Some(_) => Vec::new(),
        None => readings.iter().map(|p| fit(p, Some(p.lambda))).collect(),
    };
    profile.sort_by(|a, b| misfit(a).total_cmp(&misfit(b)));
    let starts: Vec<Params> = match opt.z0 {
        Some(_) => readings,
        None => profile
            .iter()
            .take(SHAPE_FITS)
            .filter(|f| f.status == FitStatus::Ok)
            .map(params_of)
            .collect(),
    };
    let best = starts
        .iter()
        .map(|p| fit(p, None))
        .min_by(|a, b| misfit(a).total_cmp(&misfit(b)));
    let sentence = match best {
        Some(f) => {
            let s = shape_sentence(&f, md);
            fh.shape_fit = Some(shape_of(f, &profile, d, opt));
            s
        }
        None => {
            "the two-zone law could not be fitted to the curve's shape: no start was found".into()
        }
    };
    fh.note = format!("{}; {sentence}", fh.note);
}

/// A fit's parameters.
fn params_of(f: &ModelFit) -> Params {
    Params {
        e_star: f.e_star_pa,
        w: f.work_of_adhesion_j_m2,
        lambda: f.lambda.unwrap_or(1.0),
        zc: f.contact_point_m,
        f0: f.force_offset_n,
    }
}

/// The shape fit with its profile over lambda and lambda's 95% set from it.
fn shape_of(
    fit: ModelFit,
    profile: &[ModelFit],
    d: &Prepared,
    opt: &super::FitOptions,
) -> ShapeFit {
    let lambda = fit.lambda.unwrap_or(f64::NAN);
    let z0_m = super::z0_from_lambda(fit.e_star_pa, fit.work_of_adhesion_j_m2, opt.radius, lambda);
    let mut points: Vec<[f64; 3]> = profile
        .iter()
        .filter(|f| f.status == FitStatus::Ok)
        .filter_map(|f| Some([f.lambda?, f.rms_residual_n, f.work_of_adhesion_j_m2]))
        .collect();
    points.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let (mut lambda_95, mut solid_w_95, mut lambda_bounded) = (None, None, None);
    if !points.is_empty() && fit.status == FitStatus::Ok {
        // Delta chi^2 = m (rms^2 - rms_fit^2) / s^2, s^2 from the fit's residual (5 parameters)
        // with the floor of a noise-free curve, as the Maugis-Dugdale fit's profile.
        let m = d.count as f64;
        let fmax = d.force.iter().fold(0.0f64, |a, f| a.max(f.abs()));
        let rms = fit.rms_residual_n;
        let s2 = (rms * rms * m / (m - 5.0).max(1.0)).max((1e-13 * fmax).powi(2));
        let inside = |r: f64| m * (r * r - rms * rms) / s2 <= 3.84;
        let ins: Vec<[f64; 3]> = points
            .iter()
            .filter(|p| inside(p[1]))
            .copied()
            .chain(std::iter::once([lambda, rms, fit.work_of_adhesion_j_m2]))
            .collect();
        let range = |k: usize| {
            let lo = ins.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
            let hi = ins.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
            [lo, hi]
        };
        lambda_95 = Some(range(0));
        solid_w_95 = Some(range(2));
        // The profile's ends outside the set, on either side of the fit's lambda (a set with
        // several basins may have gaps: its ends are what bound it).
        let (first, last) = (points[0], points[points.len() - 1]);
        lambda_bounded =
            Some(!inside(first[1]) && !inside(last[1]) && first[0] < lambda && lambda < last[0]);
    }
    ShapeFit {
        fit,
        z0_m,
        lambda_profile: points.iter().map(|p| [p[0], p[1]]).collect(),
        lambda_95,
        lambda_bounded,
        solid_w_95,
    }
}

/// The shape fit in words, its misfit against the one zone's.
fn shape_sentence(f: &ModelFit, md: &ModelFit) -> String {
    if f.status == FitStatus::Ok {
        format!(
            "the two-zone law fitted to the curve's shape: solid w = {:.4e} J/m^2, lambda = {:.3}, E* = {:.4e} Pa, rms residual {:.3e} N (one zone: {:.3e} N)",
            f.work_of_adhesion_j_m2,
            f.lambda.unwrap_or(f64::NAN),
            f.e_star_pa,
            f.rms_residual_n,
            md.rms_residual_n
        )
    } else {
        format!(
            "the two-zone law's fit to the curve's shape did not converge ({})",
            f.stop
        )
    }
}
