//! Measured force curves: exact Maugis-Dugdale fitted to AFM approach-retract curves, with
//! Hertz, DMT and JKR beside it, and the simplest model the curve needs.
//!
//! A curve is the force on the tip against the piezo height of the cantilever's base (larger is
//! farther from the sample). With spring constant k, the base displacement past the contact point
//! z_c is `Delta = z_c - height` (the tip's indentation plus its deflection F/k), and the model
//! force at each height is the state of the model's equilibrium path followed under the spring
//! (`path`): on retract it follows the stable branch until the force gradient reaches -k and then
//! jumps, as the measured curve does. Parameters: E*, w, lambda (or a fixed range z0), z_c and a
//! force offset, fitted by Levenberg-Marquardt (MINPACK's, through the `levenberg-marquardt`
//! crate) with finite-difference Jacobians that keep each point on its branch.

pub mod data;
pub mod humidity;
pub mod interval;
pub mod path;
pub mod segments;
pub mod synthetic;

pub use data::{read_curves, Curve, CurveSet, DataError};
pub use path::{Direction, Model, SpringPath};

use crate::physics::params::LJ_STRESS;
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt, TerminationReason};
use nalgebra::{storage::Owned, DMatrix, DVector, Dyn};
use path::{PathState, Piece, Side};
use serde::Serialize;
use std::cell::RefCell;
use std::f64::consts::PI;

/// Which segments are fitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Segments {
    Retract,
    Approach,
    Both,
}

impl Segments {
    fn takes(self, d: Direction) -> bool {
        matches!(
            (self, d),
            (Segments::Both, _)
                | (Segments::Retract, Direction::Retract)
                | (Segments::Approach, Direction::Approach)
        )
    }
}

#[derive(Clone, Debug)]
pub struct FitOptions {
    /// Tip radius R (m).
    pub radius: f64,
    /// Cantilever spring constant k (N/m).
    pub spring: f64,
    /// The sample's Poisson ratio, to report its Young's modulus (a rigid tip).
    pub poisson: Option<f64>,
    pub segments: Segments,
    /// Fix lambda through the Lennard-Jones range z0 (m) instead of fitting it.
    pub z0: Option<f64>,
    /// Remove a tilted baseline (a line in height), not only an offset.
    pub tilt: bool,
    /// The adequate model: force residual within this fraction of Maugis-Dugdale's, or contact
    /// radius within it.
    pub tolerance: f64,
    /// The far part of the approach used for the baseline (fraction of its points).
    pub baseline_fraction: f64,
    /// The humid air the curves were measured in: each fit then reports the solid's w with the
    /// water meniscus taken out of its pull-off ([`humidity::solid_work`]).
    pub humidity: Option<crate::scene::humidity::HumidityInput>,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            radius: 1e-8,
            spring: 1.0,
            poisson: None,
            segments: Segments::Retract,
            z0: None,
            tilt: false,
            tolerance: 0.05,
            baseline_fraction: 0.3,
            humidity: None,
        }
    }
}

/// The Lennard-Jones range z0 a fit may fix lambda with (m): a few picometres to a micrometre
/// (van der Waals: about 0.3 nm).
pub const Z0_RANGE: (f64, f64) = (1e-12, 1e-6);

/// Fitted parameters outside these are taken for a failed fit (wrong units, a wrong spring
/// constant or radius, or data the models cannot describe): E* (Pa), from the softest gels and
/// cells (measured cell curves fit a few hundred Pa) to diamond, and w (J/m^2) above metallic
/// adhesion. A w below the weakest van der Waals contact (1e-6) is
/// no measurable adhesion (a Hertz curve), not a failure.
pub const E_STAR_RANGE: (f64, f64) = (10.0, 1e12);
pub const W_MAX: f64 = 10.0;

impl FitOptions {
    /// Checks the options that hold for every curve (the tip radius and the spring constant are
    /// checked per curve, since each curve may carry its own): one message naming the quantity,
    /// its value and its limits. The command line and the Python package both call it.
    pub fn validate(&self) -> Result<(), OptionError> {
        self.check()
            .map_err(|(option, message)| OptionError { option, message })
    }

    fn check(&self) -> Result<(), (&'static str, String)> {
        let short = crate::physics::domain::short;
        if let Some(nu) = self.poisson {
            if !(nu > -1.0 && nu <= 0.5) {
                return Err((
                    "poisson",
                    format!(
                        "Poisson ratio {} must be in (-1, 0.5] (0.5 is incompressible)",
                        short(nu)
                    ),
                ));
            }
        }
        if let Some(z0) = self.z0 {
            if !(z0 >= Z0_RANGE.0 && z0 <= Z0_RANGE.1) {
                return Err((
                    "z0",
                    format!(
                    "Lennard-Jones range z0 {} m must be between {} and {} m (about 0.3e-9 for van der Waals)",
                    short(z0),
                    short(Z0_RANGE.0),
                    short(Z0_RANGE.1)
                )));
            }
        }
        if !(self.tolerance > 0.0 && self.tolerance < 1.0) {
            return Err((
                "tolerance",
                format!(
                    "adequate-model tolerance {} must be a fraction between 0 and 1 (0.05 is 5%)",
                    short(self.tolerance)
                ),
            ));
        }
        if !(self.baseline_fraction > 0.0 && self.baseline_fraction <= 1.0) {
            return Err((
                "baseline_fraction",
                format!(
                "baseline fraction {} must be in (0, 1] (the far part of the approach, 0.3 is 30%)",
                short(self.baseline_fraction)
            ),
            ));
        }
        if let Some(h) = &self.humidity {
            // The library's checks of a humidity, named by its keys.
            h.validate().map_err(|e| (e.key(), e.to_string()))?;
            if h.relative_humidity == 0.0 {
                return Err((
                    "relative_humidity",
                    "relative humidity 0 is dry air, where no meniscus forms: leave the humidity out for a dry fit, or give the humidity the curves were measured in, in (0, 1)".to_string(),
                ));
            }
        }
        Ok(())
    }
}

/// An option of the fit out of its range: which (the field of [`FitOptions`]) and why.
#[derive(Debug, Clone)]
pub struct OptionError {
    pub option: &'static str,
    pub message: String,
}

impl std::fmt::Display for OptionError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for OptionError {}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FitStatus {
    Ok,
    /// The curve cannot be fitted as given (NaN, too few points, no segment to fit, ...).
    InvalidInput,
    /// The force never rises above the baseline's noise.
    NoContact,
    /// The optimiser failed or ended outside the models' domain.
    NotConverged,
}

/// One model's fit.
#[derive(Clone, Debug, Serialize)]
pub struct ModelFit {
    pub model: Model,
    pub status: FitStatus,
    pub e_star_pa: f64,
    pub e_star_pa_stderr: f64,
    /// Zero for Hertz.
    pub work_of_adhesion_j_m2: f64,
    pub work_of_adhesion_j_m2_stderr: f64,
    /// Maugis-Dugdale only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda_stderr: Option<f64>,
    pub contact_point_m: f64,
    pub contact_point_m_stderr: f64,
    /// The fitted force offset, on top of the baseline removed before the fit.
    pub force_offset_n: f64,
    pub rms_residual_n: f64,
    pub pulloff_force_model_n: f64,
    pub iterations: usize,
    pub stop: String,
    #[serde(skip)]
    cov: Option<DMatrix<f64>>,
    /// (J^T J)^-1 in the internal parameters (ln E*, ln w, [ln lambda,] z_c / z_scale,
    /// f0 / f_scale) with residuals in units of f_scale: the covariance at any noise level.
    #[serde(skip)]
    jtj_inv: Option<DMatrix<f64>>,
}

/// The result for one curve (SI units; `_stderr` from the covariance of the fit).
#[derive(Clone, Debug, Serialize)]
pub struct CurveFit {
    pub curve: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub x: Option<i64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub y: Option<i64>,
    pub status: FitStatus,
    pub message: String,
    pub e_star_pa: Option<f64>,
    pub e_star_pa_stderr: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub youngs_modulus_pa: Option<f64>,
    pub work_of_adhesion_j_m2: Option<f64>,
    pub work_of_adhesion_j_m2_stderr: Option<f64>,
    pub lambda: Option<f64>,
    pub lambda_stderr: Option<f64>,
    pub tabor_parameter: Option<f64>,
    pub tabor_parameter_stderr: Option<f64>,
    pub z0_m: Option<f64>,
    pub z0_m_stderr: Option<f64>,
    pub contact_point_m: Option<f64>,
    pub contact_point_m_stderr: Option<f64>,
    /// Baseline offset plus the fitted offset (N).
    pub force_offset_n: Option<f64>,
    /// With `tilt`: the baseline's slope (N/m of height).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub baseline_tilt_n_m: Option<f64>,
    pub rms_residual_n: Option<f64>,
    /// The most tensile force measured in the fitted segments, as a positive number (N).
    pub pulloff_force_measured_n: Option<f64>,
    /// The same on the fitted Maugis-Dugdale path.
    pub pulloff_force_model_n: Option<f64>,
    pub max_load_n: Option<f64>,
    pub max_contact_radius_m: Option<f64>,
    /// Normalised loads the fitted segments span on the adhesion map (min, max).
    pub load_range_normalised: Option<[f64; 2]>,
    pub iterations: usize,
    pub stop: String,
    pub points_fitted: usize,
    pub points_in_contact: usize,
    /// Hertz, DMT and JKR fitted with the same spring and jumps.
    pub models: Vec<ModelFit>,
    /// Profile-likelihood intervals `[low, high]` (68% and 95%; `null` for an end the data
    /// leave open), which carry lambda's ambiguity into E*, w, z0 and the contact point.
    pub e_star_pa_interval_68: Option<interval::Interval>,
    pub e_star_pa_interval_95: Option<interval::Interval>,
    pub work_of_adhesion_j_m2_interval_68: Option<interval::Interval>,
    pub work_of_adhesion_j_m2_interval_95: Option<interval::Interval>,
    pub lambda_interval_68: Option<interval::Interval>,
    pub lambda_interval_95: Option<interval::Interval>,
    pub contact_point_m_interval_68: Option<interval::Interval>,
    pub contact_point_m_interval_95: Option<interval::Interval>,
    pub z0_m_interval_68: Option<interval::Interval>,
    pub z0_m_interval_95: Option<interval::Interval>,
    /// Whether the 95% interval of lambda is bounded at both ends.
    pub lambda_determined: Option<bool>,
    /// What the data say of lambda at 95% ("lambda > 4.1 at 95%", or the interval).
    pub lambda_bound: Option<String>,
    /// The statistical test of each closed form against Maugis-Dugdale: Delta chi^2 at the
    /// noise of the residual.
    pub noise_from_residual_n: Option<f64>,
    pub adequate_model: Option<Model>,
    pub why: String,
    /// The Tabor self-consistency verdict of `tabor infer` on the measured pull-off, with the
    /// fitted E* and z0.
    pub verdict: Option<String>,
    pub warnings: Vec<String>,
    /// With a humidity: the meniscus and the solid's w with it taken out.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub humidity: Option<humidity::FitHumidity>,
    #[serde(skip)]
    pub md: Option<ModelFit>,
}

/// One quantity of a force map (`tabor fit --maps`): its file name, how to read it from a
/// curve's result, whether it is drawn on a log scale, and its label and SI unit (drawn with
/// the prefix that suits the values where `prefixed`).
pub struct MapQuantity {
    pub name: &'static str,
    pub value: fn(&CurveFit) -> Option<f64>,
    pub log: bool,
    pub label: &'static str,
    pub unit: &'static str,
    pub prefixed: bool,
    /// Drawn only where lambda is determined (its standard error below it): elsewhere the
    /// value is one end of a flat misfit, and would take the colour scale.
    pub needs_lambda: bool,
}

/// The force-map quantities, each a PNG with a colorbar and an NPY array.
pub const MAP_QUANTITIES: [MapQuantity; 5] = [
    MapQuantity {
        name: "e_star",
        value: |r| r.e_star_pa,
        log: true,
        label: "reduced modulus E*",
        unit: "Pa",
        prefixed: true,
        needs_lambda: false,
    },
    MapQuantity {
        name: "work_of_adhesion",
        value: |r| r.work_of_adhesion_j_m2,
        log: true,
        label: "work of adhesion w",
        unit: "J/m²",
        prefixed: false,
        needs_lambda: false,
    },
    MapQuantity {
        name: "lambda",
        value: |r| r.lambda,
        log: true,
        label: "λ (grey: not determined)",
        unit: "",
        prefixed: false,
        needs_lambda: true,
    },
    MapQuantity {
        name: "pulloff",
        value: |r| r.pulloff_force_measured_n,
        log: false,
        label: "pull-off force",
        unit: "N",
        prefixed: true,
        needs_lambda: false,
    },
    MapQuantity {
        name: "rms_residual",
        value: |r| r.rms_residual_n,
        log: true,
        label: "rms residual",
        unit: "N",
        prefixed: true,
        needs_lambda: false,
    },
];

/// The pixel grid of a force map: its size and, per pixel (row-major, row 0 at y = 0), the
/// index of its curve. Every curve needs x and y.
/// Most pixels of a force map (4096 x 4096, as an adhesion map): a grid sized by the largest
/// pixel index would otherwise take memory without bound.
pub const MAP_PIXELS_MAX: usize = 1 << 24;

/// The force map's size from the curves' pixel indices (`x`, `y`, and the curve's name for the
/// message), checked before any work: every curve needs indices in 0..99999 and the grid at most
/// [`MAP_PIXELS_MAX`] pixels.
pub fn map_size<'a>(
    cells: impl Iterator<Item = (Option<i64>, Option<i64>, &'a str)>,
) -> Result<(usize, usize), String> {
    let (mut nx, mut ny, mut n) = (0usize, 0usize, 0usize);
    for (x, y, name) in cells {
        match (x, y) {
            (Some(x), Some(y)) if (0..100_000).contains(&x) && (0..100_000).contains(&y) => {
                nx = nx.max(x as usize + 1);
                ny = ny.max(y as usize + 1);
                n += 1;
            }
            _ => {
                return Err(format!(
                    "curve {name} has no pixel indices (x, y): force maps need x and y columns with indices 0..99999"
                ))
            }
        }
    }
    if nx * ny > MAP_PIXELS_MAX {
        return Err(format!(
            "the pixel indices span a {nx} x {ny} grid ({} pixels for {n} curves): a force map holds at most 4096 x 4096 pixels; check the x and y columns (indices from 0)",
            nx * ny
        ));
    }
    Ok((nx, ny))
}

pub fn map_grid(results: &[CurveFit]) -> Result<(usize, usize, Vec<Option<usize>>), String> {
    let (nx, ny) = map_size(results.iter().map(|r| (r.x, r.y, r.curve.as_str())))?;
    let mut grid = vec![None; nx * ny];
    for (i, r) in results.iter().enumerate() {
        if let (Some(x), Some(y)) = (r.x, r.y) {
            grid[y as usize * nx + x as usize] = Some(i);
        }
    }
    Ok((nx, ny, grid))
}

impl CurveFit {
    /// Whether the data determine lambda: its 95% interval is bounded (without one, its
    /// standard error is below it).
    pub fn lambda_determined(&self) -> bool {
        match self.lambda_determined {
            Some(d) => d,
            None => matches!((self.lambda, self.lambda_stderr), (Some(l), Some(e)) if e <= l),
        }
    }
}

/// A curve made ready for fitting: baseline removed, the points of the fitted segments.
#[derive(Clone, Debug)]
pub struct Prepared {
    pub height: Vec<f64>,
    pub force: Vec<f64>,
    pub dir: Vec<Direction>,
    /// Each point's side of its segment's measured jump (Any where none was measured).
    pub side: Vec<Side>,
    /// The last points before a measured jump: fitted by their distance to the model's curve
    /// (`path::fold_distance`), which stays smooth in the parameters where the model's fold
    /// passes them.
    pub at_jump: Vec<bool>,
    pub baseline: (f64, f64),
    pub noise: f64,
    /// What preparing the curve changed or found (outliers dropped, jittering heights): warnings.
    pub notes: Vec<String>,
}

fn fail(curve: &Curve, status: FitStatus, message: String) -> CurveFit {
    CurveFit {
        curve: curve.id.clone(),
        x: curve.x,
        y: curve.y,
        status,
        message,
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
        noise_from_residual_n: None,
        adequate_model: None,
        why: String::new(),
        verdict: None,
        warnings: Vec::new(),
        humidity: None,
        md: None,
    }
}

/// Fewer points than this in the fitted segments, or in contact, and a curve is refused or warned.
pub const MIN_POINTS: usize = 20;
pub const MIN_CONTACT_POINTS: usize = 10;

/// Checks a curve and removes its baseline.
pub fn prepare(curve: &Curve, opt: &FitOptions) -> Result<Prepared, (FitStatus, String)> {
    let bad = |m: String| Err((FitStatus::InvalidInput, m));
    if !(opt.spring > 0.0 && opt.spring.is_finite()) {
        return bad(format!(
            "spring constant {} N/m: give the cantilever's calibrated spring constant (> 0)",
            crate::physics::domain::short(opt.spring)
        ));
    }
    if !(opt.radius > 0.0 && opt.radius.is_finite()) {
        return bad(format!(
            "tip radius {} m: give a positive radius in metres",
            crate::physics::domain::short(opt.radius)
        ));
    }
    for (i, (&h, &f)) in curve.height.iter().zip(&curve.force).enumerate() {
        if !h.is_finite() || !f.is_finite() {
            return bad(format!(
                "point {} has height_m = {h} and force_n = {f}: remove or repair non-finite values",
                i + 1
            ));
        }
    }
    if let Some(m) = &curve.refused {
        return bad(m.clone());
    }
    let mut notes = curve.notes.clone();
    if let Err(m) = check_cycles(curve) {
        return bad(m);
    }
    for d in [Direction::Approach, Direction::Retract] {
        match check_order(curve, d) {
            Err(m) => return bad(m),
            Ok(Some(note)) => notes.push(note),
            Ok(None) => {}
        }
    }
    // Outliers (spikes far beyond the noise) would steer the fit and the baseline: dropped.
    let cleaned;
    let curve = match drop_spikes(curve) {
        Some((c, note)) => {
            notes.push(note);
            cleaned = c;
            &cleaned
        }
        None => curve,
    };
    let fitted: Vec<usize> = (0..curve.len())
        .filter(|&i| opt.segments.takes(curve.segment[i]))
        .collect();
    if fitted.is_empty() {
        let which = match opt.segments {
            Segments::Retract => "no retract segment: fit the approach segment instead, or check the segment column (approach/retract or 0/1)",
            Segments::Approach => "no approach segment: fit the retract segment instead, or check the segment column",
            Segments::Both => "no points",
        };
        return bad(which.to_string());
    }
    if fitted.len() < MIN_POINTS {
        return bad(format!(
            "only {} points in the fitted segments: at least {MIN_POINTS} are needed",
            fitted.len()
        ));
    }
    let ((b0, b1), noise) = baseline(curve, opt);
    let height: Vec<f64> = fitted.iter().map(|&i| curve.height[i]).collect();
    let force: Vec<f64> = fitted
        .iter()
        .map(|&i| curve.force[i] - b0 - b1 * curve.height[i])
        .collect();
    let fmax = force.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let fmin = force.iter().cloned().fold(f64::INFINITY, f64::min);
    if !(fmax > 5.0 * noise && fmax > 1e-3 * (fmax - fmin).abs() && fmax > 0.0) {
        return Err((
            FitStatus::NoContact,
            format!(
                "no contact: the force never rises above the baseline (largest {:.3e} N, noise {:.2e} N); check the segment and the sign of force_n (positive is repulsive)",
                fmax, noise
            ),
        ));
    }
    let dir: Vec<Direction> = fitted.iter().map(|&i| curve.segment[i]).collect();
    let side = measured_sides(&force, &dir, noise);
    let at_jump = last_before_jump(&side, &dir);
    Ok(Prepared {
        side,
        at_jump,
        dir,
        height,
        force,
        baseline: (b0, b1),
        noise,
        notes,
    })
}

/// The baseline: a line (flat without `opt.tilt`) through the far part of the approach (of the
/// retract where the approach has fewer than 5 points), and the rms of the points about it.
fn baseline(curve: &Curve, opt: &FitOptions) -> ((f64, f64), f64) {
    let far_of = |d: Direction| -> Vec<usize> {
        let mut idx: Vec<usize> = (0..curve.len())
            .filter(|&i| curve.segment[i] == d)
            .collect();
        idx.sort_by(|&a, &b| curve.height[b].total_cmp(&curve.height[a]));
        let n = ((idx.len() as f64 * opt.baseline_fraction).ceil() as usize).max(3);
        idx.truncate(n);
        idx
    };
    let mut far = far_of(Direction::Approach);
    if far.len() < 5 {
        far = far_of(Direction::Retract);
    }
    let (b0, b1) = line_fit(
        &far.iter().map(|&i| curve.height[i]).collect::<Vec<_>>(),
        &far.iter().map(|&i| curve.force[i]).collect::<Vec<_>>(),
        opt.tilt,
    );
    let resid: Vec<f64> = far
        .iter()
        .map(|&i| curve.force[i] - b0 - b1 * curve.height[i])
        .collect();
    // The rms, scaled so that huge forces (1e200) do not overflow to an infinite noise.
    let scale = resid.iter().fold(0.0f64, |m, r| m.max(r.abs()));
    let noise = if scale > 0.0 {
        scale
            * (resid.iter().map(|r| (r / scale).powi(2)).sum::<f64>() / resid.len().max(1) as f64)
                .sqrt()
    } else {
        0.0
    };
    ((b0, b1), noise)
}

/// The indices of a curve's points in one segment, in time order.
fn segment_points(curve: &Curve, d: Direction) -> Vec<usize> {
    (0..curve.len())
        .filter(|&i| curve.segment[i] == d)
        .collect()
}

fn seg_name(d: Direction) -> &'static str {
    if d == Direction::Approach {
        "approach"
    } else {
        "retract"
    }
}

/// One approach and one retract at most: a curve whose segment goes back to one it has left
/// holds several cycles (repeated cycles, or curves with the same id or pixel merged).
fn check_cycles(curve: &Curve) -> Result<(), String> {
    let changes: Vec<usize> = (1..curve.len())
        .filter(|&i| curve.segment[i] != curve.segment[i - 1])
        .collect();
    if changes.len() >= 2 {
        let at = changes[1];
        return Err(format!(
            "the curve holds {} approach-retract cycles: its segment goes back from {} to {} at point {} (a repeated cycle, or two curves with the same id or pixel x, y merged); give each cycle its own curve id",
            (changes.len() + 1).div_ceil(2),
            seg_name(curve.segment[at - 1]),
            seg_name(curve.segment[at]),
            at + 1
        ));
    }
    Ok(())
}

/// A segment's heights must run its way (the approach lowers the base, the retract raises it).
/// Measured heights jitter, by more than their step where the sampling is dense: what is
/// refused is a segment that runs the wrong way overall or goes back by a large part of its
/// span (a restart, or points out of time order); jitter is a note.
fn check_order(curve: &Curve, d: Direction) -> Result<Option<String>, String> {
    let idx = segment_points(curve, d);
    if idx.len() < 3 {
        return Ok(None);
    }
    let sign = if d == Direction::Approach { -1.0 } else { 1.0 };
    let name = seg_name(d);
    let way = if d == Direction::Approach {
        "decrease"
    } else {
        "increase"
    };
    let h = |k: usize| curve.height[idx[k]];
    let n = idx.len();
    let (first, last) = (h(0), h(n - 1));
    let lo = (0..n).map(h).fold(f64::INFINITY, f64::min);
    let hi = (0..n).map(h).fold(f64::NEG_INFINITY, f64::max);
    let span = hi - lo;
    if !(sign * (last - first) > 0.0) {
        return Err(format!(
            "the {name} heights are not in order: they go from {} m at its first point to {} m at its last, and the {name} must {way} the height; check the segment column (approach and retract swapped?) and that height_m grows away from the sample",
            crate::physics::domain::short(first),
            crate::physics::domain::short(last)
        ));
    }
    // The largest way back: progress sign*h should grow; its largest fall below its running
    // maximum, and where.
    let (mut top, mut back, mut at) = (f64::NEG_INFINITY, 0.0f64, 0usize);
    for k in 0..n {
        let p = sign * h(k);
        top = top.max(p);
        if top - p > back {
            back = top - p;
            at = k;
        }
    }
    if back > 0.25 * span {
        return Err(format!(
            "the {name} heights go back by {} m (their span is {} m) at point {}: the {name} restarts there (two cycles in one curve?) or its points are out of time order; give each cycle its own curve id, in the order measured",
            crate::physics::domain::short(back),
            crate::physics::domain::short(span),
            idx[at] + 1
        ));
    }
    let wrong = (1..n).filter(|&k| sign * (h(k) - h(k - 1)) < 0.0).count();
    Ok((wrong * 4 > n).then(|| {
        format!(
            "the {name} heights jitter by up to {} m, more than their mean step of {} m ({wrong} of {} steps go back): they are fitted as measured",
            crate::physics::domain::short(back),
            crate::physics::domain::short(span / (n - 1) as f64),
            n - 1
        )
    }))
}

/// The quantile q (0..1) of sorted values.
fn quantile(sorted: &[f64], q: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

/// The longest run of consecutive points taken for a spike.
const MAX_SPIKE_RUN: usize = 3;

/// The points of one segment's forces (in time order) that are isolated spikes: outside the
/// segment's robust range (its 2%..98% quantiles widened by half their span on each side),
/// more than ten robust noise levels (the MAD of the second differences) from their
/// neighbours' line, and standing out against how much those neighbours differ themselves (so
/// that a sharp but genuine pull-off or snap-in is kept).
fn spikes(f: &[f64]) -> Vec<usize> {
    let n = f.len();
    if n < 5 {
        return Vec::new();
    }
    let mut sorted = f.to_vec();
    sorted.sort_by(f64::total_cmp);
    let (q02, q98) = (quantile(&sorted, 0.02), quantile(&sorted, 0.98));
    let range = q98 - q02;
    let out = |v: f64| v < q02 - 0.5 * range || v > q98 + 0.5 * range;
    let mut second: Vec<f64> = (1..n - 1)
        .map(|i| (f[i + 1] - 2.0 * f[i] + f[i - 1]).abs())
        .collect();
    second.sort_by(f64::total_cmp);
    // Of white noise sigma the second differences have sigma sqrt 6; the median of their
    // absolute values is 0.6745 of that.
    let sigma = (quantile(&second, 0.5) / 0.6745 / 6f64.sqrt()).max(1e-4 * range);
    let mut candidates: Vec<bool> = f.iter().map(|&v| out(v)).collect();
    // A spike is isolated: a run of more than MAX_SPIKE_RUN points beyond the range, or one at
    // either end of the segment, is the curve itself (the contact at the end of an approach
    // that is mostly baseline lies far beyond its quantiles), not a glitch.
    let mut i = 0;
    while i < n {
        if !candidates[i] {
            i += 1;
            continue;
        }
        let end = (i..n).find(|&j| !candidates[j]).unwrap_or(n);
        if end - i > MAX_SPIKE_RUN || i == 0 || end == n {
            candidates[i..end].fill(false);
        }
        i = end;
    }
    // The nearest points on each side that are not candidates.
    let left = |i: usize| (0..i).rev().find(|&j| !candidates[j]);
    let right = |i: usize| (i + 1..n).find(|&j| !candidates[j]);
    (0..n)
        .filter(|&i| candidates[i])
        .filter(|&i| {
            let (dev, spread) = match (left(i), right(i)) {
                (Some(a), Some(b)) => (f[i] - 0.5 * (f[a] + f[b]), (f[b] - f[a]).abs()),
                (None, Some(b)) => match right(b) {
                    Some(c) => (f[i] - f[b], (f[c] - f[b]).abs()),
                    None => return false,
                },
                (Some(a), None) => match left(a) {
                    Some(c) => (f[i] - f[a], (f[a] - f[c]).abs()),
                    None => return false,
                },
                (None, None) => return false,
            };
            dev.abs() > 10.0 * sigma && dev.abs() > 3.0 * spread
        })
        .collect()
}

/// The curve without its spikes and a note naming them, or None where there are none.
fn drop_spikes(curve: &Curve) -> Option<(Curve, String)> {
    let mut drop = vec![false; curve.len()];
    let mut named = Vec::new();
    for d in [Direction::Approach, Direction::Retract] {
        let idx = segment_points(curve, d);
        let f: Vec<f64> = idx.iter().map(|&i| curve.force[i]).collect();
        for k in spikes(&f) {
            drop[idx[k]] = true;
            named.push(idx[k]);
        }
    }
    if named.is_empty() {
        return None;
    }
    named.sort_unstable();
    let keep = |v: &[f64]| -> Vec<f64> {
        v.iter()
            .zip(&drop)
            .filter(|(_, &x)| !x)
            .map(|(v, _)| *v)
            .collect()
    };
    let c = Curve {
        height: keep(&curve.height),
        force: keep(&curve.force),
        segment: curve
            .segment
            .iter()
            .zip(&drop)
            .filter(|(_, &x)| !x)
            .map(|(s, _)| *s)
            .collect(),
        ..curve.clone()
    };
    let list: Vec<String> = named
        .iter()
        .take(5)
        .map(|&i| {
            format!(
                "point {} (force {} N)",
                i + 1,
                crate::physics::domain::short(curve.force[i])
            )
        })
        .collect();
    let note = format!(
        "dropped {} outlier point{} far beyond the noise, isolated spikes that would steer the fit: {}{}",
        named.len(),
        if named.len() == 1 { "" } else { "s" },
        list.join(", "),
        if named.len() > 5 { ", ..." } else { "" }
    );
    Some((c, note))
}

/// The measured jump of each segment: on retract the largest rise of the force between
/// consecutive points (the jump-out), on approach the largest fall (the snap-in), where it is
/// larger than five times the noise and a third of the segment's most tensile force.
fn measured_sides(force: &[f64], dir: &[Direction], noise: f64) -> Vec<Side> {
    let mut side = vec![Side::Any; force.len()];
    for d in [Direction::Approach, Direction::Retract] {
        let idx: Vec<usize> = (0..force.len()).filter(|&i| dir[i] == d).collect();
        if idx.len() < 3 {
            continue;
        }
        let sign = if d == Direction::Retract { 1.0 } else { -1.0 };
        let Some((k, step)) = idx
            .windows(2)
            .enumerate()
            .map(|(k, w)| (k, sign * (force[w[1]] - force[w[0]])))
            .max_by(|a, b| a.1.total_cmp(&b.1))
        else {
            continue;
        };
        let tensile = idx.iter().map(|&i| -force[i]).fold(0.0, f64::max);
        if step > 5.0 * noise && step > tensile / 3.0 && tensile > 0.0 {
            for (n, &i) in idx.iter().enumerate() {
                side[i] = if n <= k {
                    Side::BeforeJump
                } else {
                    Side::AfterJump
                };
            }
        }
    }
    side
}

/// Points fitted by their distance to the curve: this many before each measured jump (the fold's
/// point and its neighbour, which the fitted fold may pass while the fit moves).
const AT_JUMP_POINTS: usize = 2;

fn last_before_jump(side: &[Side], dir: &[Direction]) -> Vec<bool> {
    let mut out = vec![false; side.len()];
    for d in [Direction::Approach, Direction::Retract] {
        let before: Vec<usize> = (0..side.len())
            .filter(|&i| dir[i] == d && side[i] == Side::BeforeJump)
            .collect();
        for &i in before.iter().rev().take(AT_JUMP_POINTS) {
            out[i] = true;
        }
    }
    out
}

fn line_fit(x: &[f64], y: &[f64], tilt: bool) -> (f64, f64) {
    let n = x.len() as f64;
    let my = y.iter().sum::<f64>() / n;
    if !tilt || x.len() < 3 {
        return (my, 0.0);
    }
    let mx = x.iter().sum::<f64>() / n;
    let sxx: f64 = x.iter().map(|v| (v - mx) * (v - mx)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let b1 = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    (my - b1 * mx, b1)
}

/// Physical parameters of a model.
#[derive(Clone, Copy, Debug)]
pub struct Params {
    pub e_star: f64,
    pub w: f64,
    pub lambda: f64,
    pub zc: f64,
    pub f0: f64,
}

/// The unit conversions of one parameter set: force and approach units and kbar.
#[derive(Clone, Copy, Debug)]
pub struct Units {
    pub force: f64,
    pub approach: f64,
    pub radius: f64,
    pub kbar: f64,
}

pub fn units(p: &Params, radius: f64, spring: f64) -> Units {
    let k = 4.0 / 3.0 * p.e_star;
    let force = PI * p.w * radius;
    let approach = (PI * PI * p.w * p.w * radius / (k * k)).cbrt();
    Units {
        force,
        approach,
        radius: (PI * p.w * radius * radius / k).cbrt(),
        kbar: spring * approach / force,
    }
}

/// lambda from the Lennard-Jones range z0 (Dugdale stress matched to it).
pub fn lambda_from_z0(e_star: f64, w: f64, radius: f64, z0: f64) -> f64 {
    let k = 4.0 / 3.0 * e_star;
    2.0 * (LJ_STRESS * w / z0) * (radius / (PI * w * k * k)).cbrt()
}

/// The Lennard-Jones range z0 whose matched Dugdale stress gives lambda.
pub fn z0_from_lambda(e_star: f64, w: f64, radius: f64, lambda: f64) -> f64 {
    let k = 4.0 / 3.0 * e_star;
    2.0 * LJ_STRESS * w * (radius / (PI * w * k * k)).cbrt() / lambda
}

/// Model forces (N), contact radii (m), the states and the path they lie on.
pub type Evaluated = (Vec<f64>, Vec<f64>, Vec<PathState>, SpringPath);

/// The model force (N, without offset) and contact radius (m) at each height, and the state.
pub fn model_forces(
    model: Model,
    p: &Params,
    radius: f64,
    spring: f64,
    height: &[f64],
    dir: &[Direction],
    side: Option<&[Side]>,
) -> Option<Evaluated> {
    model_forces_from(model, p, radius, spring, height, dir, side, None)
}

/// [`model_forces`], each point's search started from its state in `hints` (nearby parameters).
#[allow(clippy::too_many_arguments)]
pub fn model_forces_from(
    model: Model,
    p: &Params,
    radius: f64,
    spring: f64,
    height: &[f64],
    dir: &[Direction],
    side: Option<&[Side]>,
    hints: Option<&[PathState]>,
) -> Option<Evaluated> {
    let u = units(p, radius, spring);
    if !(u.kbar > 0.0 && u.kbar.is_finite() && u.approach > 0.0) {
        return None;
    }
    if model == Model::Md && crate::solver::domain::check_lambda(p.lambda).is_err() {
        return None;
    }
    let deltas: Vec<f64> = height.iter().map(|h| (p.zc - h) / u.approach).collect();
    let top = deltas.iter().cloned().fold(1.0, f64::max);
    let path = SpringPath::new(model, p.lambda, u.kbar, top);
    let states: Vec<PathState> = deltas
        .iter()
        .zip(dir)
        .enumerate()
        .map(|(i, (&d, &dir))| {
            path.at_side_from(
                d,
                dir,
                side.map_or(Side::Any, |s| s[i]),
                hints.map(|h| &h[i]),
            )
        })
        .collect();
    let f = states.iter().map(|s| s.load * u.force).collect();
    let a = states.iter().map(|s| s.a * u.radius).collect();
    Some((f, a, states, path))
}

/// The least-squares problem of one model on one prepared curve.
struct Problem<'a> {
    model: Model,
    data: &'a Prepared,
    radius: f64,
    spring: f64,
    z0: Option<f64>,
    /// Maugis-Dugdale at a fixed lambda (the profile that picks the start).
    fixed_lambda: Option<f64>,
    /// Hertz has no w: its units use this one (it cancels).
    w_ref: f64,
    z_scale: f64,
    f_scale: f64,
    x: DVector<f64>,
    /// The states at the current parameters (the Jacobian keeps each point on its piece).
    states: RefCell<Option<Vec<PathState>>>,
    /// The last states evaluated: each point's search starts there at the next parameters.
    hints: RefCell<Option<Vec<PathState>>>,
    jacobians: RefCell<usize>,
}

impl Problem<'_> {
    fn has_w(&self) -> bool {
        self.model != Model::Hertz
    }
    fn has_lambda(&self) -> bool {
        self.model == Model::Md && self.z0.is_none() && self.fixed_lambda.is_none()
    }
    fn n(&self) -> usize {
        2 + self.has_w() as usize + 1 + self.has_lambda() as usize
    }

    fn params(&self, x: &DVector<f64>) -> Params {
        let mut i = 0;
        let mut next = || {
            i += 1;
            x[i - 1]
        };
        let e_star = next().exp();
        let w = if self.has_w() {
            next().exp()
        } else {
            self.w_ref
        };
        let lambda = if self.has_lambda() {
            next().exp()
        } else if let Some(l) = self.fixed_lambda {
            l
        } else if let (Model::Md, Some(z0)) = (self.model, self.z0) {
            lambda_from_z0(e_star, w, self.radius, z0)
        } else {
            1.0
        };
        let zc = next() * self.z_scale;
        let f0 = next() * self.f_scale;
        Params {
            e_star,
            w,
            lambda,
            zc,
            f0,
        }
    }

    fn internal(&self, p: &Params) -> DVector<f64> {
        let mut v = vec![p.e_star.ln()];
        if self.has_w() {
            v.push(p.w.ln());
        }
        if self.has_lambda() {
            v.push(p.lambda.ln());
        }
        v.push(p.zc / self.z_scale);
        v.push(p.f0 / self.f_scale);
        DVector::from_vec(v)
    }

    /// Residuals at parameters x; with `near`, each point stays on the piece it had.
    fn eval(
        &self,
        x: &DVector<f64>,
        near: Option<&[PathState]>,
    ) -> Option<(DVector<f64>, Vec<PathState>)> {
        let p = self.params(x);
        let d = self.data;
        let u = units(&p, self.radius, self.spring);
        if !(u.kbar > 0.0 && u.kbar.is_finite() && u.approach > 0.0 && u.force > 0.0) {
            return None;
        }
        if self.model == Model::Md && crate::solver::domain::check_lambda(p.lambda).is_err() {
            return None;
        }
        let states: Vec<PathState> = match near {
            Some(base) => {
                // Where Newton from the base state fails (a point at a fold, or at the A = 0
                // end of DMT), the point is located on the path itself.
                let mut full: Option<SpringPath> = None;
                let top = d
                    .height
                    .iter()
                    .map(|h| (p.zc - h) / u.approach)
                    .fold(1.0, f64::max);
                let mut out = Vec::with_capacity(base.len());
                for (i, s) in base.iter().enumerate() {
                    let delta = (p.zc - d.height[i]) / u.approach;
                    let newton = (!s.clamped)
                        .then(|| path::near(self.model, p.lambda, u.kbar, delta, s.piece, s.t))
                        .flatten();
                    out.push(match newton {
                        Some(s) => s,
                        None => full
                            .get_or_insert_with(|| {
                                SpringPath::new(self.model, p.lambda, u.kbar, top)
                            })
                            .at_side(delta, d.dir[i], d.side[i]),
                    });
                }
                out
            }
            None => {
                let hints = self.hints.borrow();
                model_forces_from(
                    self.model,
                    &p,
                    self.radius,
                    self.spring,
                    &d.height,
                    &d.dir,
                    Some(&d.side),
                    hints.as_deref(),
                )?
                .2
            }
        };
        let r = DVector::from_iterator(
            states.len(),
            states.iter().enumerate().map(|(i, s)| {
                self.fold_residual(&p, &u, i, s)
                    .unwrap_or_else(|| (s.load * u.force + p.f0 - d.force[i]) / self.f_scale)
            }),
        );
        r.iter().all(|v| v.is_finite()).then_some((r, states))
    }

    /// A point before a measured jump: its distance to the model's curve near its state (in
    /// the plane of load and FOLD_SCALE kbar Delta, so that away from the fold, where the slope
    /// dP/dDelta is at most about kbar, it is the force residual within 0.5%).
    fn fold_residual(&self, p: &Params, u: &Units, i: usize, s: &PathState) -> Option<f64> {
        if !self.data.at_jump[i] || s.piece == Piece::Free {
            return None;
        }
        let delta = (p.zc - self.data.height[i]) / u.approach;
        let load = (self.data.force[i] - p.f0) / u.force;
        path::fold_distance(
            self.model,
            p.lambda,
            u.kbar,
            FOLD_SCALE * u.kbar,
            s.piece,
            s.t,
            delta,
            load,
        )
        .map(|(r, _)| r * u.force / self.f_scale)
    }

    /// The rows of the points before a jump by central differences (the analytic slopes are the
    /// force residual's).
    fn fold_rows(&self, j: &mut DMatrix<f64>, base: &[PathState]) {
        for (i, s) in base.iter().enumerate() {
            if !self.data.at_jump[i] || s.piece == Piece::Free {
                continue;
            }
            for k in 0..self.n() {
                let h = 1e-6 * self.x[k].abs().max(1.0);
                let at = |dx: f64| {
                    let mut x = self.x.clone();
                    x[k] += dx;
                    let p = self.params(&x);
                    let u = units(&p, self.radius, self.spring);
                    self.fold_residual(&p, &u, i, s)
                };
                if let (Some(a), Some(b)) = (at(h), at(-h)) {
                    j[(i, k)] = (a - b) / (2.0 * h);
                }
            }
        }
    }
}

/// The weight of Delta against the load in the distance of a point before a jump, in units of
/// kbar (the largest slope of a stable stretch away from its fold).
const FOLD_SCALE: f64 = 10.0;

impl LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, x: &DVector<f64>) {
        self.x.copy_from(x);
        *self.states.borrow_mut() = None;
    }

    fn params(&self) -> DVector<f64> {
        self.x.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        // Outside the domain: a large residual, so the step is refused and shortened (a None
        // would end the whole minimisation).
        match self.eval(&self.x, None) {
            Some((r, s)) => {
                *self.hints.borrow_mut() = Some(s.clone());
                *self.states.borrow_mut() = Some(s);
                Some(r)
            }
            None => Some(DVector::from_element(self.data.force.len(), 1e6)),
        }
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        *self.jacobians.borrow_mut() += 1;
        let base = match self.states.borrow().clone() {
            Some(s) => s,
            None => self.eval(&self.x, None)?.1,
        };
        if self.model == Model::Md && self.z0.is_some() {
            // lambda moves with E* and w: every column by differences.
            return self.numeric_jacobian(&base, &(0..self.n()).collect::<Vec<_>>());
        }
        let mut j = self.analytic_jacobian(&base);
        if self.has_lambda() {
            let k = 1 + self.has_w() as usize;
            let c = self.numeric_jacobian(&base, &[k])?;
            j.set_column(k, &c.column(k));
        }
        self.fold_rows(&mut j, &base);
        Some(j)
    }
}

impl Problem<'_> {
    /// The Jacobian from the state's slopes. With u = (ln E*, ln w), the force is
    /// `F = Fs(w) P(Delta, kbar)` with `Delta = (z_c - h) / Ds`, `Ds ~ w^(2/3) E*^(-2/3)` and
    /// `kbar = k Ds / Fs ~ w^(-1/3) E*^(-2/3)`; along the branch `dP/dDelta = P'/g` and
    /// `dP/dkbar = P' P / (kbar^2 g)`, with `g = dDelta/dt = D' + P'/kbar`. Points on the free
    /// piece, or held at the end of their stretch (where the data put them past the model's
    /// jump), move with the offset only: for held points an approximation, which the iteration
    /// tolerates and which a converged fit rarely needs. The lambda column is left to
    /// differences.
    fn analytic_jacobian(&self, base: &[PathState]) -> DMatrix<f64> {
        let p = self.params(&self.x);
        let u = units(&p, self.radius, self.spring);
        let (m, n) = (base.len(), self.n());
        let mut j = DMatrix::zeros(m, n);
        for (i, s) in base.iter().enumerate() {
            let (dp_dd, dp_dk) = if s.piece == Piece::Free || s.clamped {
                (0.0, 0.0)
            } else {
                // The state's slopes at s.t, as stored with it (the same numbers as
                // `path::state` gives there).
                let g = s.dapproach + s.dload / u.kbar;
                if g.abs() > 0.0 {
                    (s.dload / g, s.dload * s.load / (u.kbar * u.kbar * g))
                } else {
                    (0.0, 0.0)
                }
            };
            let delta = (p.zc - self.data.height[i]) / u.approach;
            let col = |dln_fs: f64, dln_ds: f64, dln_k: f64| {
                u.force * (s.load * dln_fs - dp_dd * delta * dln_ds + dp_dk * u.kbar * dln_k)
                    / self.f_scale
            };
            let mut k = 0;
            j[(i, k)] = col(0.0, -2.0 / 3.0, -2.0 / 3.0);
            k += 1;
            if self.has_w() {
                j[(i, k)] = col(1.0, 2.0 / 3.0, -1.0 / 3.0);
                k += 1;
            }
            if self.has_lambda() {
                k += 1;
            }
            j[(i, k)] = u.force * dp_dd * (self.z_scale / u.approach) / self.f_scale;
            j[(i, k + 1)] = 1.0;
        }
        j
    }

    /// Central differences in the given columns (others zero), each point kept on its piece.
    fn numeric_jacobian(&self, base: &[PathState], cols: &[usize]) -> Option<DMatrix<f64>> {
        let m = base.len();
        let mut j = DMatrix::zeros(m, self.n());
        for &k in cols {
            let h = 1e-6 * self.x[k].abs().max(1.0);
            let mut xp = self.x.clone();
            xp[k] += h;
            let mut xm = self.x.clone();
            xm[k] -= h;
            let (rp, rm) = (self.eval(&xp, Some(base)), self.eval(&xm, Some(base)));
            match (rp, rm) {
                (Some((rp, _)), Some((rm, _))) => {
                    j.set_column(k, &((rp - rm) / (2.0 * h)));
                }
                _ => {
                    // One side left the domain or a branch: a one-sided difference.
                    let r0 = self.eval(&self.x, Some(base))?.0;
                    let (rp, _) = self
                        .eval(&xp, Some(base))
                        .or_else(|| self.eval(&xm, Some(base)).map(|(r, s)| (2.0 * &r0 - r, s)))?;
                    j.set_column(k, &((rp - r0) / h));
                }
            }
        }
        Some(j)
    }
}

/// The starting point of a fit: closed-form estimates from the measured curve.
#[derive(Clone, Copy, Debug)]
pub struct Estimates {
    pub e_star: f64,
    /// The measured pull-off force (positive, N).
    pub pulloff: f64,
    pub zc: f64,
}

pub fn estimates(d: &Prepared, radius: f64, spring: f64) -> Estimates {
    let n = d.force.len();
    let (imin, fmin) = d
        .force
        .iter()
        .cloned()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0, 0.0));
    let fmax = d.force.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let tip = |i: usize| d.height[i] + d.force[i] / spring;
    let pulloff = (-fmin).max(0.0);
    // DMT: the pull-off at zero indentation; without adhesion, where the force leaves zero.
    let zc = if pulloff > 3.0 * d.noise {
        tip(imin)
    } else {
        let thr = 3.0 * d.noise + 0.02 * fmax;
        (0..n)
            .filter(|&i| d.force[i] > thr)
            .map(tip)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let base = fmin.min(0.0);
    let mut k: Vec<f64> = (0..n)
        .filter(|&i| d.force[i] - base > 0.5 * (fmax - base))
        .filter_map(|i| {
            let delta = zc - tip(i);
            (delta > 0.0).then(|| (d.force[i] - base) / (radius.sqrt() * delta.powf(1.5)))
        })
        .collect();
    k.sort_by(f64::total_cmp);
    let kk = k.get(k.len() / 2).cloned().unwrap_or(1e9);
    Estimates {
        e_star: 0.75 * kk,
        pulloff,
        zc,
    }
}

fn stop_text(t: &TerminationReason) -> String {
    match t {
        TerminationReason::ResidualsZero => "residuals zero".into(),
        TerminationReason::Orthogonal => "gradient orthogonal to the residuals (converged)".into(),
        TerminationReason::Converged { ftol, xtol } => match (ftol, xtol) {
            (true, true) => "converged (relative change of the residual and the parameters)".into(),
            (true, false) => "converged (relative change of the residual)".into(),
            _ => "converged (relative change of the parameters)".into(),
        },
        TerminationReason::LostPatience => "iteration limit reached".into(),
        TerminationReason::NoImprovementPossible(w) => {
            format!("no further improvement possible ({w})")
        }
        TerminationReason::Numerical(w) => format!("numerical failure ({w})"),
        TerminationReason::User(w) => format!("model evaluation failed ({w})"),
        other => format!("{other:?}"),
    }
}

/// Fits one model from a start.
fn fit_model(
    model: Model,
    d: &Prepared,
    opt: &FitOptions,
    start: Params,
    w_ref: f64,
    fixed_lambda: Option<f64>,
) -> ModelFit {
    fit_model_for(model, d, opt, start, w_ref, fixed_lambda, PATIENCE)
}

/// The iteration budget of a fit (MINPACK's: this many evaluations per parameter and one), and
/// the shorter one of a scouting free fit.
const PATIENCE: usize = 150;
const SCOUT_PATIENCE: usize = 4;

#[allow(clippy::too_many_arguments)]
fn fit_model_for(
    model: Model,
    d: &Prepared,
    opt: &FitOptions,
    start: Params,
    w_ref: f64,
    fixed_lambda: Option<f64>,
    patience: usize,
) -> ModelFit {
    let fscale = d
        .force
        .iter()
        .fold(0.0f64, |m, f| m.max(f.abs()))
        .max(1e-30);
    let hspan = d.height.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
        - d.height.iter().cloned().fold(f64::INFINITY, f64::min);
    let mut prob = Problem {
        model,
        data: d,
        radius: opt.radius,
        spring: opt.spring,
        z0: opt.z0,
        fixed_lambda,
        w_ref,
        z_scale: hspan.max(1e-30),
        f_scale: fscale,
        x: DVector::zeros(0),
        states: RefCell::new(None),
        hints: RefCell::new(None),
        jacobians: RefCell::new(0),
    };
    prob.x = prob.internal(&start);
    let scout = patience == SCOUT_PATIENCE;
    let lm = LevenbergMarquardt::new().with_patience(patience);
    let (prob, report) = lm.minimize(prob);
    let x = prob.x.clone();
    let p = prob.params(&x);
    let iterations = *prob.jacobians.borrow();
    let evaluated = prob.eval(&x, None);
    let ok = report.termination.was_successful()
        || matches!(
            report.termination,
            TerminationReason::NoImprovementPossible(_)
        );
    let (status, rms, cov, jtj_inv) = match &evaluated {
        Some((r, _)) if ok || matches!(report.termination, TerminationReason::LostPatience) => {
            let m = r.len();
            let n = prob.n();
            let rss = r.norm_squared();
            let rms = (rss / m as f64).sqrt() * prob.f_scale;
            // A scout's covariance is never read (only its misfit and parameters): its final
            // Jacobian, two path evaluations per column of lambda, is skipped.
            let inv = (!scout)
                .then(|| prob.jacobian())
                .flatten()
                .and_then(|j| (j.transpose() * &j).try_inverse());
            let cov = inv
                .as_ref()
                .map(|inv| inv * (rss / (m.saturating_sub(n).max(1)) as f64));
            let status = if ok {
                FitStatus::Ok
            } else {
                FitStatus::NotConverged
            };
            (status, rms, cov, inv)
        }
        _ => (FitStatus::NotConverged, f64::NAN, None, None),
    };
    let (e_err, w_err, lambda_err, zc_err) = standard_errors(&prob, &cov, &p, fixed_lambda);
    let pulloff = evaluated
        .as_ref()
        .filter(|_| !scout)
        .map_or(f64::NAN, |_| model_pulloff(model, &p, d, opt));
    ModelFit {
        model,
        status,
        e_star_pa: p.e_star,
        e_star_pa_stderr: e_err,
        work_of_adhesion_j_m2: if model == Model::Hertz { 0.0 } else { p.w },
        work_of_adhesion_j_m2_stderr: w_err,
        lambda: (model == Model::Md).then_some(p.lambda),
        lambda_stderr: lambda_err,
        contact_point_m: p.zc,
        contact_point_m_stderr: zc_err,
        force_offset_n: p.f0,
        rms_residual_n: rms,
        pulloff_force_model_n: pulloff,
        iterations,
        stop: stop_text(&report.termination),
        cov,
        jtj_inv,
    }
}

/// The standard errors of E*, w, lambda (None where it is not a parameter or a function of
/// them) and the contact point from a fit's covariance in its internal variables.
fn standard_errors(
    prob: &Problem,
    cov: &Option<DMatrix<f64>>,
    p: &Params,
    fixed_lambda: Option<f64>,
) -> (f64, f64, Option<f64>, f64) {
    let model = prob.model;
    let var = |i: usize| cov.as_ref().map_or(f64::NAN, |c| c[(i, i)].max(0.0).sqrt());
    let mut i = 1;
    let e_err = p.e_star * var(0);
    let w_err = if prob.has_w() {
        i += 1;
        p.w * var(1)
    } else {
        0.0
    };
    let lambda_err = if prob.has_lambda() {
        i += 1;
        Some(p.lambda * var(i - 1))
    } else if model == Model::Md && fixed_lambda.is_some() {
        Some(0.0)
    } else if model == Model::Md {
        // Fixed z0: lambda follows E* and w, ln lambda = (2/3)(ln w - ln E*) + const.
        cov.as_ref().map(|c| {
            let v = (4.0 / 9.0) * (c[(0, 0)] + c[(1, 1)] - 2.0 * c[(0, 1)]);
            p.lambda * v.max(0.0).sqrt()
        })
    } else {
        None
    };
    let zc_err = var(i) * prob.z_scale;
    (e_err, w_err, lambda_err, zc_err)
}

/// The most tensile load of a model's path under the cantilever (N, positive), along the
/// fitted segment's direction: the path alone, not the states at the points.
fn model_pulloff(model: Model, p: &Params, d: &Prepared, opt: &FitOptions) -> f64 {
    let u = units(p, opt.radius, opt.spring);
    let top = d
        .height
        .iter()
        .map(|h| (p.zc - h) / u.approach)
        .fold(1.0, f64::max);
    let dir = if opt.segments == Segments::Approach {
        Direction::Approach
    } else {
        Direction::Retract
    };
    -SpringPath::new(model, p.lambda, u.kbar, top)
        .min_load(dir)
        .0
        * u.force
}

impl ModelFit {
    /// The fitted parameters (Hertz: any w, it cancels; here w of 1 mJ/m^2).
    pub fn params(&self) -> Params {
        Params {
            e_star: self.e_star_pa,
            w: if self.model == Model::Hertz {
                1e-3
            } else {
                self.work_of_adhesion_j_m2
            },
            lambda: self.lambda.unwrap_or(1.0),
            zc: self.contact_point_m,
            f0: self.force_offset_n,
        }
    }
}

/// The lambdas of the profile that starts a free Maugis-Dugdale fit: 0.01..1000, 16 points.
fn profile_lambdas() -> impl Iterator<Item = f64> {
    (0..16).map(|i| 10f64.powf(-2.0 + 5.0 * i as f64 / 15.0))
}

/// Free fits start from this many of the best profile points: near the truth the misfit can
/// dip sharply between profile points (lambda sets the attractive tail and the jump), so the
/// free fit has to start near the dip to find it.
const FREE_STARTS: usize = 16;

/// Misfit for ranking: the rms residual, even where the iteration limit stopped a fit.
fn rank(m: &ModelFit) -> f64 {
    if m.rms_residual_n.is_finite() {
        m.rms_residual_n
    } else {
        f64::INFINITY
    }
}

/// The free Maugis-Dugdale fit from the best two points of the lambda profile, with standard
/// errors that also cover the profile's confidence region: where the misfit is flat in lambda
/// (one retract curve often cannot tell lambda = 0.3 from 30 within its noise) the covariance's
/// local picture understates the spread, while the profile sees it.
fn free_fit(d: &Prepared, opt: &FitOptions, w_ref: f64, profile: Vec<ModelFit>) -> ModelFit {
    let mut order: Vec<usize> = (0..profile.len()).collect();
    order.sort_by(|&a, &b| rank(&profile[a]).total_cmp(&rank(&profile[b])));
    // The profile has its 16 fixed lambdas.
    let best_profile = rank(&profile[order[0]]);
    // Scouts: short free fits from every profile point; the best two are then fitted fully.
    let mut scouts: Vec<ModelFit> = order
        .iter()
        .take(FREE_STARTS)
        .map(|&i| {
            let m = &profile[i];
            fit_model_for(Model::Md, d, opt, m.params(), w_ref, None, SCOUT_PATIENCE)
        })
        .collect();
    scouts.sort_by(|a, b| rank(a).total_cmp(&rank(b)));
    let fulls: Vec<ModelFit> = scouts
        .iter()
        .take(2)
        .map(|m| {
            let mut f = fit_model(Model::Md, d, opt, m.params(), w_ref, None);
            // Stopped by the iteration limit but no worse than any fixed-lambda fit: accepted.
            if f.status == FitStatus::NotConverged && rank(&f) <= best_profile * (1.0 + 1e-9) {
                f.status = FitStatus::Ok;
            }
            f
        })
        .collect();
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

/// The free fit's standard errors widened by the 3-sigma region of the profile and of the
/// other minima found (`others`): where the misfit is flat in lambda the covariance's local
/// picture understates the spread, while the profile sees it.
fn widen_by_region(
    mut md: ModelFit,
    d: &Prepared,
    profile: &[ModelFit],
    others: &[&ModelFit],
) -> ModelFit {
    // The 3-sigma region of the profile and of the minima found: Delta chi^2 = (RSS - RSS_min) / s^2 <= 9, its edges
    // interpolated in ln lambda between profile points.
    let m = d.force.len() as f64;
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

fn key(m: &ModelFit) -> f64 {
    if m.status == FitStatus::Ok && m.rms_residual_n.is_finite() {
        m.rms_residual_n
    } else {
        f64::INFINITY
    }
}

fn better(a: ModelFit, b: ModelFit) -> ModelFit {
    if key(&b) < key(&a) {
        b
    } else {
        a
    }
}

/// Fits one curve: Maugis-Dugdale and the three closed forms, the adequate model, warnings.
/// Whatever the data, the result is the curve's status: a panic inside (a bug) is caught here
/// and becomes this curve's `not_converged`, so that the other curves of a batch go on.
pub fn fit_curve(curve: &Curve, opt: &FitOptions) -> CurveFit {
    if let Err(e) = opt.validate() {
        return fail(curve, FitStatus::InvalidInput, e.message);
    }
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| fit_curve_inner(curve, opt)))
        .unwrap_or_else(|p| {
            let what = p
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            fail(
                curve,
                FitStatus::NotConverged,
                format!("internal error while fitting this curve ({what}); please report it with the curve"),
            )
        })
}

fn fit_curve_inner(curve: &Curve, opt: &FitOptions) -> CurveFit {
    let d = match prepare(curve, opt) {
        Ok(d) => d,
        Err((status, message)) => return fail(curve, status, message),
    };
    let est = estimates(&d, opt.radius, opt.spring);
    let pull = est
        .pulloff
        .max(10.0 * d.noise)
        .max(1e-6 * est.e_star * opt.radius * opt.radius);
    let w_of = |pc_bar: f64| pull / (pc_bar * PI * opt.radius);
    let start = |w: f64, lambda: f64| Params {
        e_star: est.e_star,
        w,
        lambda,
        zc: est.zc,
        f0: 0.0,
    };
    let w_ref = w_of(1.75);
    let hertz = fit_model(Model::Hertz, &d, opt, start(w_ref, 1.0), w_ref, None);
    let dmt = fit_model(Model::Dmt, &d, opt, start(w_of(2.0), 1.0), w_ref, None);
    let jkr = fit_model(Model::Jkr, &d, opt, start(w_of(1.5), 1.0), w_ref, None);
    // Maugis-Dugdale from the closed forms' answers and from the middle.
    let from = |m: &ModelFit, lambda: f64, pc_bar: f64, pc_md: f64| Params {
        e_star: if m.status == FitStatus::Ok {
            m.e_star_pa
        } else {
            est.e_star
        },
        w: if m.status == FitStatus::Ok {
            m.work_of_adhesion_j_m2 * pc_bar / pc_md
        } else {
            w_of(pc_md)
        },
        lambda,
        zc: if m.status == FitStatus::Ok {
            m.contact_point_m
        } else {
            est.zc
        },
        f0: if m.status == FitStatus::Ok {
            m.force_offset_n
        } else {
            0.0
        },
    };
    // Maugis-Dugdale: the misfit has local minima in lambda (the jump moves with it), so a
    // profile over lambda (each point a fit at fixed lambda, started from the closed form of
    // that side) picks the starts of the free fit, and gives the confidence region of lambda.
    let (md, iv) = match opt.z0 {
        Some(z0) => match fixed_z0_fit(curve, &d, opt, z0, (&dmt, &jkr), &from, w_ref) {
            Ok(r) => r,
            Err(out) => return out,
        },
        None => {
            let profile: Vec<ModelFit> = profile_lambdas()
                .map(|l| {
                    let pc = crate::physics::closed::cos_pulloff(l).abs();
                    let s = if l < 1.0 {
                        from(&dmt, l, 2.0, pc)
                    } else {
                        from(&jkr, l, 1.5, pc)
                    };
                    fit_model(Model::Md, &d, opt, s, w_ref, Some(l))
                })
                .collect();
            let md = free_fit(&d, opt, w_ref, profile.clone());
            let iv = if md.status == FitStatus::Ok {
                interval::profile_intervals(&d, opt, w_ref, &md, &profile)
            } else {
                interval::Intervals::default()
            };
            (md, iv)
        }
    };
    // A fit that ended where it started found nothing to follow (the misfit was flat there).
    let stuck = md.status == FitStatus::Ok
        && (md.e_star_pa / est.e_star - 1.0).abs() < 1e-9
        && (md.contact_point_m - est.zc).abs() <= 1e-9 * est.zc.abs();
    let mut out = summarize(curve, opt, &d, md, vec![hertz, dmt, jkr], &iv);
    if stuck && out.status == FitStatus::Ok {
        out = unmoved(out, curve, &d, opt);
    }
    out
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
    from: &dyn Fn(&ModelFit, f64, f64, f64) -> Params,
    w_ref: f64,
) -> Result<(ModelFit, interval::Intervals), CurveFit> {
    let best = better(dmt.clone(), jkr.clone());
    let pc = if best.model == Model::Dmt { 2.0 } else { 1.5 };
    let mut s = from(&best, 1.0, pc, pc);
    s.lambda = lambda_from_z0(s.e_star, s.w, opt.radius, z0);
    if crate::solver::domain::check_lambda(s.lambda).is_err() {
        let mut out = fail(
            curve,
            FitStatus::InvalidInput,
            format!(
                "the Lennard-Jones range z0 = {} m gives lambda = {} with this curve's E* and w (about {} Pa and {} J/m^2), outside the models' domain 1e-26..1e26: check z0 (about 0.3e-9 m for van der Waals), or leave it out to fit lambda",
                crate::physics::domain::short(z0),
                crate::physics::domain::short(s.lambda),
                crate::physics::domain::short(s.e_star),
                crate::physics::domain::short(s.w)
            ),
        );
        out.warnings = d.notes.clone();
        return Err(out);
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
        "; check the spring constant (a wrong one moves E* by orders of magnitude), the tip radius, and that height_m is in metres and force_n in newtons".into()
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
    if !(1e-10..=1e-3).contains(&opt.radius) {
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

fn summarize(
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
        out.message = format!("the Maugis-Dugdale fit did not converge: {}", md.stop);
        out.models = models;
        out.md = Some(md);
        return out;
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
        opt.radius,
        opt.spring,
        &d.height,
        &d.dir,
        None,
    ) else {
        out.message = format!(
            "the fitted parameters (E* = {} Pa, w = {} J/m^2, lambda = {}) cannot be evaluated: the fit left the models' domain{}",
            short(p.e_star), short(p.w), short(p.lambda), unit_hints(d, opt)
        );
        out.status = FitStatus::NotConverged;
        out.models = models;
        out.md = Some(md);
        return out;
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
    if pull > 0.0 {
        out.verdict = crate::scene::infer(pull, opt.radius, p.e_star, out.z0_m.unwrap_or(z0))
            .ok()
            .map(|i| i.verdict);
    }
    let mut warn = warnings(&out, d, opt, &p, &md, amax, in_contact);
    if let Some(h) = &opt.humidity {
        out.humidity = humidity::solid_work(&out, opt.radius, h);
        if let Some(fh) = out.humidity.as_ref().filter(|fh| !fh.fair_reading) {
            warn.push(format!("humidity: {}", fh.note));
        }
    }
    out.status = FitStatus::Ok;
    out.message = "ok".into();
    let mut out = with_fits(out, d, md, models);
    out.warnings = warn;
    out
}

/// A curve's result with its Maugis-Dugdale fit (its iterations and stop) and the closed
/// forms' fits, and the data's notes as warnings.
fn with_fits(mut r: CurveFit, d: &Prepared, md: ModelFit, models: Vec<ModelFit>) -> CurveFit {
    r.iterations = md.iterations;
    r.stop = md.stop.clone();
    r.warnings = d.notes.clone();
    r.models = models;
    r.md = Some(md);
    r
}

/// A fit that ended outside physical sense, or with no point in contact: its status and
/// message (None for a fit to report).
fn implausible(
    p: &Params,
    in_contact: usize,
    d: &Prepared,
    opt: &FitOptions,
) -> Option<(FitStatus, String)> {
    let short = crate::physics::domain::short;
    // A modulus or adhesion above physical sense first: that is the cause to name (forces in
    // nN, a wrong spring constant), whatever else the fit shows; a modulus below the range with
    // no point in contact is a curve that does not press (no contact).
    let inside = |v: f64, r: (f64, f64)| v >= r.0 && v <= r.1;
    let beyond = !inside(p.e_star, E_STAR_RANGE) || !(p.w <= W_MAX);
    let above = !(p.e_star <= E_STAR_RANGE.1) || !(p.w <= W_MAX);
    if beyond && (above || in_contact > 0) {
        return Some((
            FitStatus::NotConverged,
            format!(
                "the fit ended outside physical sense: E* = {} Pa (plausible {}..{} Pa), w = {} J/m^2 (plausible up to {} J/m^2){}",
                short(p.e_star),
                short(E_STAR_RANGE.0),
                short(E_STAR_RANGE.1),
                short(p.w),
                short(W_MAX),
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
fn put_parameters(
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
    // muT = lambda / 1.1570 exactly for the LJ-matched Dugdale stress.
    let z0 = z0_from_lambda(p.e_star, p.w, opt.radius, p.lambda);
    let mu_t = (opt.radius * p.w * p.w / (p.e_star * p.e_star * z0.powi(3))).cbrt();
    out.tabor_parameter = Some(mu_t);
    out.tabor_parameter_stderr = md.lambda_stderr.map(|e| e * mu_t / p.lambda);
    out.z0_m = Some(opt.z0.unwrap_or(z0));
    let lambda_spread = z0 * md.lambda_stderr.unwrap_or(f64::NAN) / p.lambda;
    out.z0_m_stderr = Some(match (&md.cov, opt.z0) {
        // The covariance of (ln E*, ln w, ln lambda, ...) of a free fit.
        (Some(c), None) if c.nrows() == 5 => {
            // ln z0 = (2/3)(ln w - ln E*) - ln lambda + const.
            let g = [-2.0 / 3.0, 2.0 / 3.0, -1.0];
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
fn put_intervals(out: &mut CurveFit, iv: &interval::Intervals) {
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
    if let Some([lo, hi]) = l95 {
        out.lambda_determined = Some(lo.is_some() && hi.is_some());
        out.lambda_bound = Some(match (lo, hi) {
            (Some(lo), Some(hi)) => format!("{} <= lambda <= {} at 95%", sig(lo), sig(hi)),
            (Some(lo), None) => format!("lambda > {} at 95% (no upper bound: towards JKR the curve cannot tell lambda apart)", sig(lo)),
            (None, Some(hi)) => format!("lambda < {} at 95% (no lower bound: towards DMT the curve cannot tell lambda apart)", sig(hi)),
            (None, None) => "lambda is not bounded at 95% (0.01..1000 fit equally well)".to_string(),
        });
    }
}

/// The warnings of a converged fit: the data's notes, implausible options, a residual far above
/// the noise, a stretched theory, too few points in contact, lambda undetermined, an unresolved
/// jump-out.
fn warnings(
    out: &CurveFit,
    d: &Prepared,
    opt: &FitOptions,
    p: &Params,
    md: &ModelFit,
    amax: f64,
    in_contact: usize,
) -> Vec<String> {
    let mut warn = d.notes.clone();
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
        warn.push(format!(
            "the fit does not describe this curve: its rms residual {:.3e} N is {:.0} times the baseline's noise {:.3e} N (drift, ringing, a wrong model, wrong units or a wrong spring constant); its parameters are doubtful",
            md.rms_residual_n,
            md.rms_residual_n / d.noise,
            d.noise
        ));
    }
    if amax / opt.radius > 0.1 {
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
    if let (Some(false), Some(b)) = (out.lambda_determined, &out.lambda_bound) {
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

/// Three significant figures, as a bound is written.
fn sig(v: f64) -> String {
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
fn adequate_by_test(
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
    for f in models {
        let n = match f.model {
            Model::Hertz => 3.0,
            _ => 4.0,
        };
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
        if f.status != FitStatus::Ok && dchi.is_finite() {
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
fn adequate_why(
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
fn adequate_by_tolerance(
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
            "no closed form fits within {:.0}%: Hertz, DMT and JKR leave rms residuals of {}",
            100.0 * opt.tolerance,
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
            let w_note = if m.model == Model::Hertz {
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
            w: if m.model == Model::Hertz {
                p.w
            } else {
                m.work_of_adhesion_j_m2
            },
            lambda: 1.0,
            zc: m.contact_point_m,
            f0: m.force_offset_n,
        };
        if let Some((_, a_m, _, _)) = model_forces(
            m.model, &mp, opt.radius, opt.spring, &d.height, &d.dir, None,
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

    #[test]
    fn the_analytic_jacobian_matches_differences() {
        for (model, lambda, spring) in [
            (Model::Md, 0.3, 2.0),
            (Model::Md, 5.0, 0.5),
            (Model::Jkr, 1.0, 2.0),
            (Model::Dmt, 1.0, 10.0),
            (Model::Hertz, 1.0, 2.0),
        ] {
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
                seed: 3,
            };
            let opt = FitOptions {
                radius: 20e-9,
                spring,
                ..FitOptions::default()
            };
            let d = prepare(&synthetic::synthetic(&s), &opt).unwrap();
            let mut start = s.params;
            // Off the truth, so that the residuals and slopes are generic.
            start.e_star *= 1.1;
            start.w *= 0.95;
            start.zc += 0.2e-9;
            let prob = Problem {
                model,
                data: &d,
                radius: opt.radius,
                spring,
                z0: None,
                fixed_lambda: None,
                w_ref: 0.05,
                z_scale: 1e-8,
                f_scale: 1e-9,
                x: DVector::zeros(0),
                states: RefCell::new(None),
                hints: RefCell::new(None),
                jacobians: RefCell::new(0),
            };
            let prob = Problem {
                x: prob.internal(&start),
                ..prob
            };
            let base = prob.eval(&prob.x, None).unwrap().1;
            let mut a = prob.analytic_jacobian(&base);
            // The points before the jump are fitted by their distance to the curve, by
            // differences in both.
            prob.fold_rows(&mut a, &base);
            let all: Vec<usize> = (0..prob.n()).collect();
            let n = prob.numeric_jacobian(&base, &all).unwrap();
            let lam = if model == Model::Md { Some(2) } else { None };
            for k in (0..prob.n()).filter(|&k| Some(k) != lam) {
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
}
