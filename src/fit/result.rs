//! What a fit reports: the status, each model's fit, a curve's result, and the quantities of a
//! force map.

use super::*;

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
    pub(super) cov: Option<DMatrix<f64>>,
    /// (J^T J)^-1 in the internal parameters (ln E*, ln w, [ln lambda,] z_c / z_scale,
    /// f0 / f_scale) with residuals in units of f_scale: the covariance at any noise level.
    #[serde(skip)]
    pub(super) jtj_inv: Option<DMatrix<f64>>,
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
