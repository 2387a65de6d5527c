//! What a fit reports: the status, each model's fit, a curve's result, and the quantities of a
//! force map.

use super::*;

/// How a fit of a curve (or of one model to it) ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FitStatus {
    /// Fitted.
    Ok,
    /// The curve cannot be fitted as given (NaN, too few points, no segment to fit, ...).
    InvalidInput,
    /// No segment of the curve rises above the baseline's noise.
    NoContact,
    /// The optimiser failed or ended outside the models' domain.
    NotConverged,
}

/// One model's fit.
#[derive(Clone, Debug, Serialize)]
pub struct ModelFit {
    /// The model fitted.
    pub model: Model,
    /// How the fit ended.
    pub status: FitStatus,
    /// The reduced modulus E* (Pa).
    pub e_star_pa: f64,
    /// Its standard error (Pa; NaN without a covariance).
    pub e_star_pa_stderr: f64,
    /// The work of adhesion w (J/m^2). Zero for Hertz.
    pub work_of_adhesion_j_m2: f64,
    /// Its standard error (J/m^2).
    pub work_of_adhesion_j_m2_stderr: f64,
    /// The Maugis parameter. Maugis-Dugdale only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda: Option<f64>,
    /// Its standard error, where lambda is a fitted parameter or a function of them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda_stderr: Option<f64>,
    /// The contact point: the base height where the base displacement is zero (m).
    pub contact_point_m: f64,
    /// Its standard error (m).
    pub contact_point_m_stderr: f64,
    /// The fitted force offset, on top of the baseline removed before the fit (N).
    pub force_offset_n: f64,
    /// The rms of the force residuals (N; NaN where the model could not be evaluated).
    pub rms_residual_n: f64,
    /// The most tensile load of the fitted path under the cantilever (N, positive).
    pub pulloff_force_model_n: f64,
    /// The optimiser's Jacobian evaluations.
    pub iterations: usize,
    /// Why the optimiser stopped, in words.
    pub stop: String,
    #[serde(skip)]
    pub(super) cov: Option<DMatrix<f64>>,
    /// (J^T J)^-1 in the internal parameters (ln E*, ln w, [ln lambda,] z_c / z_scale,
    /// f0 / f_scale) with residuals in units of f_scale: the covariance at any noise level.
    #[serde(skip)]
    pub(super) jtj_inv: Option<DMatrix<f64>>,
    /// A Maugis-Dugdale fit's states at its parameters: the next fit started from it begins
    /// each point's search there (dropped from the curve's result).
    #[serde(skip)]
    pub(super) states: Option<std::sync::Arc<Vec<super::PathState>>>,
}

/// The result for one curve (SI units; `_stderr` from the covariance of the fit).
#[derive(Clone, Debug, Serialize)]
pub struct CurveFit {
    /// The curve's id ([`Curve::id`]).
    pub curve: String,
    /// The force map's pixel column, if the curve has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub x: Option<i64>,
    /// The force map's pixel row, if the curve has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub y: Option<i64>,
    /// How the fit ended; the fitted values are null unless it is `ok`.
    pub status: FitStatus,
    /// `ok`, or why the curve was not fitted. Advice to fit the other segment names it by the
    /// key `segments=approach` or `segments=retract` (Python adds its argument there).
    pub message: Message,
    /// The reduced modulus E* of the Maugis-Dugdale fit (Pa).
    pub e_star_pa: Option<f64>,
    /// Its standard error (Pa).
    pub e_star_pa_stderr: Option<f64>,
    /// The sample's Young's modulus `E* (1 - nu^2)` with the given Poisson ratio (a rigid tip).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub youngs_modulus_pa: Option<f64>,
    /// The work of adhesion w (J/m^2).
    pub work_of_adhesion_j_m2: Option<f64>,
    /// Its standard error (J/m^2).
    pub work_of_adhesion_j_m2_stderr: Option<f64>,
    /// The Maugis parameter lambda.
    pub lambda: Option<f64>,
    /// Its standard error.
    pub lambda_stderr: Option<f64>,
    /// Tabor's parameter `mu_T = (R w^2 / (E*^2 z0^3))^(1/3)` with the z0 of the fit.
    pub tabor_parameter: Option<f64>,
    /// Its standard error.
    pub tabor_parameter_stderr: Option<f64>,
    /// The Lennard-Jones range z0 (m): the given one, or the one lambda implies.
    pub z0_m: Option<f64>,
    /// Its standard error (m; 0 where z0 was given).
    pub z0_m_stderr: Option<f64>,
    /// The contact point: the base height where the base displacement is zero (m).
    pub contact_point_m: Option<f64>,
    /// Its standard error (m).
    pub contact_point_m_stderr: Option<f64>,
    /// Baseline offset plus the fitted offset (N).
    pub force_offset_n: Option<f64>,
    /// With `tilt`: the baseline's slope (N/m of height).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub baseline_tilt_n_m: Option<f64>,
    /// The rms of the Maugis-Dugdale fit's force residuals (N).
    pub rms_residual_n: Option<f64>,
    /// The most tensile force measured in the fitted segments, as a positive number (N).
    pub pulloff_force_measured_n: Option<f64>,
    /// The same on the fitted Maugis-Dugdale path.
    pub pulloff_force_model_n: Option<f64>,
    /// The largest force in the fitted segments, baseline removed (N).
    pub max_load_n: Option<f64>,
    /// The largest contact radius of the fitted Maugis-Dugdale states (m).
    pub max_contact_radius_m: Option<f64>,
    /// Normalised loads the fitted segments span on the adhesion map (min, max).
    pub load_range_normalised: Option<[f64; 2]>,
    /// The Maugis-Dugdale fit's Jacobian evaluations.
    pub iterations: usize,
    /// Why its optimiser stopped, in words.
    pub stop: String,
    /// The points fitted (spikes dropped, the fitted segments only).
    pub points_fitted: usize,
    /// How many of them the fitted Maugis-Dugdale path puts in contact.
    pub points_in_contact: usize,
    /// Hertz, DMT and JKR fitted with the same spring and jumps.
    pub models: Vec<ModelFit>,
    /// E* at 68% (Pa). The intervals are profile-likelihood ones, `[low, high]` (68% and 95%;
    /// `null` for an end the data leave open), which carry lambda's ambiguity into E*, w, z0
    /// and the contact point.
    pub e_star_pa_interval_68: Option<interval::Interval>,
    /// E* at 95% (Pa).
    pub e_star_pa_interval_95: Option<interval::Interval>,
    /// w at 68% (J/m^2).
    pub work_of_adhesion_j_m2_interval_68: Option<interval::Interval>,
    /// w at 95% (J/m^2).
    pub work_of_adhesion_j_m2_interval_95: Option<interval::Interval>,
    /// lambda at 68%.
    pub lambda_interval_68: Option<interval::Interval>,
    /// lambda at 95%.
    pub lambda_interval_95: Option<interval::Interval>,
    /// The contact point at 68% (m).
    pub contact_point_m_interval_68: Option<interval::Interval>,
    /// The contact point at 95% (m).
    pub contact_point_m_interval_95: Option<interval::Interval>,
    /// z0 at 68% (m).
    pub z0_m_interval_68: Option<interval::Interval>,
    /// z0 at 95% (m).
    pub z0_m_interval_95: Option<interval::Interval>,
    /// Whether the 95% interval of lambda is bounded at both ends.
    pub lambda_determined: Option<bool>,
    /// What the data say of lambda at 95% ("lambda > 4.1 at 95%", or the interval), with any
    /// second basin.
    pub lambda_bound: Option<String>,
    /// lambda's 95% set: one interval, or several where the profile has separate basins below
    /// the 95% level (in order of lambda; `lambda_interval_95` spans them all).
    pub lambda_set_95: Vec<interval::Interval>,
    /// The basins of lambda's profile apart from the best fit's, up to the 99% level: each
    /// leaves lambda undetermined, and the 95% intervals of E*, w, the contact point and z0
    /// hold its values.
    pub lambda_basins: Vec<interval::Basin>,
    /// The noise the closed forms are tested at against Maugis-Dugdale (Delta chi^2): the
    /// residual's rms over the degrees of freedom (N).
    pub noise_from_residual_n: Option<f64>,
    /// The simplest model the curve does not reject (by that test, or by
    /// [`FitOptions::tolerance`] on a noise-free curve).
    pub adequate_model: Option<Model>,
    /// Why that model, in words.
    pub why: String,
    /// The Tabor self-consistency verdict of `tabor infer` on the measured pull-off, with the
    /// fitted E* and z0.
    pub verdict: Option<String>,
    /// What the reader should know about this fit (data, range, plausibility).
    pub warnings: Vec<String>,
    /// With a humidity: the meniscus and the solid's w with it taken out.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub humidity: Option<humidity::FitHumidity>,
    /// For a curve with a dwell between approach and retract: what happened during it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dwell: Option<DwellReport>,
    /// The Maugis-Dugdale fit itself (not written: its values are the ones above).
    #[serde(skip)]
    pub md: Option<ModelFit>,
}

/// A dwell between approach and retract (stress relaxation: the base held, the force relaxes;
/// creep: the force held, the indentation grows), as measured, the baseline removed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DwellReport {
    /// Its first point, numbered as read (from 0).
    pub first_point: usize,
    /// Its last point.
    pub last_point: usize,
    /// The force at its start (N, baseline removed).
    pub force_start_n: f64,
    /// The force at its end (N, baseline removed).
    pub force_end_n: f64,
    /// The share of the force at its start that relaxed, `(start - end) / start` (null where
    /// the dwell starts out of contact).
    pub relaxation: Option<f64>,
    /// How far the base moved toward the sample during it (m).
    pub base_advance_m: f64,
    /// How much the indentation grew during it (m): the base's advance plus the fall of the
    /// cantilever's deflection, `advance - (end - start) / k` (creep at a held force; the
    /// tip's advance as the force relaxes at a held base).
    pub indentation_creep_m: f64,
    /// Whether the force relaxed during it (by more than [`DWELL_RELAXED_SHARE`] of its start
    /// and five times the noise): the retract then unloads a relaxed contact, not the one the
    /// approach loaded, and the approach is fitted instead.
    pub relaxed: bool,
}

/// A dwell whose force falls by more than this share of its start relaxed the contact: the
/// retract that follows is not a loading curve of the contact the approach made.
pub const DWELL_RELAXED_SHARE: f64 = 0.1;

/// One quantity of a force map (`tabor fit --maps`): its file name, how to read it from a
/// curve's result, whether it is drawn on a log scale, and its label and SI unit (drawn with
/// the prefix that suits the values where `prefixed`).
pub struct MapQuantity {
    /// The file name's stem.
    pub name: &'static str,
    /// The value of a curve's result (None: a blank pixel).
    pub value: fn(&CurveFit) -> Option<f64>,
    /// Drawn on a log scale.
    pub log: bool,
    /// The colorbar's label.
    pub label: &'static str,
    /// The SI unit (empty for a number).
    pub unit: &'static str,
    /// Whether the unit takes an SI prefix suited to the values.
    pub prefixed: bool,
    /// Drawn only where lambda is determined (its standard error below it): elsewhere the
    /// value is one end of a flat misfit, and would take the colour scale.
    pub needs_lambda: bool,
}

impl MapQuantity {
    /// The value a fitted curve shows on the map and in its summary: None where the fit is not
    /// `ok`, or the quantity needs lambda and lambda is not determined.
    pub fn shown(&self, r: &CurveFit) -> Option<f64> {
        let shown = r.status == FitStatus::Ok && (!self.needs_lambda || r.lambda_determined());
        shown.then(|| (self.value)(r)).flatten()
    }
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

/// Most pixels of a force map (4096 x 4096, as an adhesion map): a grid sized by the largest
/// pixel index would otherwise take memory without bound.
pub const MAP_PIXELS_MAX: usize = 1 << 24;

/// The force map's size from the curves' pixel indices (`x`, `y`, and the curve's name for the
/// message), checked before any work: every curve needs indices in 0..99999 and the grid at most
/// [`MAP_PIXELS_MAX`] pixels.
pub fn map_size<'a>(
    cells: impl Iterator<Item = (Option<i64>, Option<i64>, &'a str)>,
) -> Result<(usize, usize), CurveError> {
    let (mut nx, mut ny, mut n) = (0usize, 0usize, 0usize);
    for (x, y, name) in cells {
        let (Some(x), Some(y)) = (x, y) else {
            return Err(CurveError::NoPixel {
                curve: name.to_string(),
            });
        };
        for (column, v) in [("x", x), ("y", y)] {
            if !(0..100_000).contains(&v) {
                return Err(CurveError::Pixel {
                    curve: name.to_string(),
                    column,
                    value: v,
                });
            }
        }
        nx = nx.max(x as usize + 1);
        ny = ny.max(y as usize + 1);
        n += 1;
    }
    if nx * ny > MAP_PIXELS_MAX {
        return Err(CurveError::Grid { nx, ny, curves: n });
    }
    Ok((nx, ny))
}

/// The pixel grid of a force map: its size and, per pixel (row-major, row 0 at y = 0), the
/// index of its curve. Every curve needs x and y.
pub fn map_grid(results: &[CurveFit]) -> Result<(usize, usize, Vec<Option<usize>>), CurveError> {
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

impl ModelFit {
    /// The fitted parameters (Hertz: any w, it cancels; here w of 1 mJ/m^2).
    pub fn params(&self) -> Params {
        Params {
            e_star: self.e_star_pa,
            w: if self.model.adhesive() {
                self.work_of_adhesion_j_m2
            } else {
                1e-3
            },
            lambda: self.lambda.unwrap_or(1.0),
            zc: self.contact_point_m,
            f0: self.force_offset_n,
        }
    }
}
