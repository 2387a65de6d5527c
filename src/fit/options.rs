//! The options of a fit, their defaults and their one check (for the command line and Python
//! alike), and the plausible ranges of the fitted values.

use super::*;

/// Which segments are fitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Segments {
    /// The retract segment only (the default: it holds the pull-off).
    Retract,
    /// The approach segment only.
    Approach,
    /// Both segments, in one fit.
    Both,
}

impl Segments {
    pub(super) fn takes(self, d: Direction) -> bool {
        matches!(
            (self, d),
            (Segments::Both, _)
                | (Segments::Retract, Direction::Retract)
                | (Segments::Approach, Direction::Approach)
        )
    }
}

/// What a fit of force curves is given besides the curves (SI units);
/// [`FitOptions::validate`] checks them.
#[derive(Clone, Debug)]
pub struct FitOptions {
    /// Tip radius R (m).
    pub radius: f64,
    /// Cantilever spring constant k (N/m).
    pub spring: f64,
    /// The sample's Poisson ratio, to report its Young's modulus (a rigid tip).
    pub poisson: Option<f64>,
    /// Which segments are fitted.
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
            tolerance: crate::physics::model::DEFAULT_TOLERANCE,
            baseline_fraction: 0.3,
            humidity: None,
        }
    }
}

/// The Lennard-Jones range z0 a fit may fix lambda with (m): a few picometres to a micrometre
/// (van der Waals: about 0.3 nm).
pub const Z0_RANGE: (f64, f64) = (1e-12, 1e-6);

impl FitOptions {
    /// Checks the options (those of every curve, the tip radius and the spring constant among
    /// them): one message naming the quantity, its value and its limits. The command line and
    /// the Python package both call it before any fit.
    pub fn validate(&self) -> Result<(), OptionError> {
        self.check()
            .map_err(|(option, message)| OptionError { option, message })
    }

    fn check(&self) -> Result<(), (&'static str, String)> {
        let short = crate::physics::domain::short;
        if !(self.spring > 0.0 && self.spring.is_finite()) {
            return Err((
                "spring",
                format!(
                    "spring constant {} N/m: give the cantilever's calibrated spring constant (> 0)",
                    short(self.spring)
                ),
            ));
        }
        if !(self.radius > 0.0 && self.radius.is_finite()) {
            return Err((
                "radius",
                format!(
                    "tip radius {} m: give a positive radius in metres",
                    short(self.radius)
                ),
            ));
        }
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
    /// The option's field name in [`FitOptions`].
    pub option: &'static str,
    /// What is wrong, with the value and its limits.
    pub message: String,
}

impl std::fmt::Display for OptionError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for OptionError {}
