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
    /// Tip radius R (m): a sphere's (ignored where `tip` is given).
    pub radius: f64,
    /// A tip that is not a sphere (docs/PHYSICS.md section 12: a cone, a pyramid as its
    /// equivalent cone, a power law, a capped cone), as a scene gives it.
    pub tip: Option<crate::physics::tip::TipInput>,
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
            tip: None,
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

impl FitOptions {
    /// The options from a JSON object (the Python binding's keywords: `radius`, `spring`,
    /// `poisson`, `segment`, `z0`, `tilt`, `tolerance`, and the humidity's
    /// `relative_humidity`, `contact_angle_deg`, `surface_tension_n_m`, `molar_volume_m3_mol`,
    /// `temperature_k`); non-finite numbers come as text ("nan", "inf"), JSON having none, and
    /// a missing radius or spring as NaN, which [`FitOptions::validate`] then refuses. Every
    /// other default is [`FitOptions::default`]'s. Not yet validated.
    pub fn from_json(json: &str) -> Result<FitOptions, crate::error::Message> {
        let o: serde_json::Value =
            serde_json::from_str(json).map_err(|e| format!("not valid fit options: {e}"))?;
        let num = |k: &str| {
            o.get(k).and_then(|v| {
                v.as_f64()
                    .or_else(|| v.as_str().and_then(|s| s.parse().ok()))
            })
        };
        let segments = match o
            .get("segment")
            .and_then(|v| v.as_str())
            .unwrap_or("retract")
        {
            "retract" => Segments::Retract,
            "approach" => Segments::Approach,
            "both" => Segments::Both,
            other => {
                return Err(crate::error::Message::new().key("segment").text(format!(
                    "={other:?}: use \"retract\", \"approach\" or \"both\""
                )))
            }
        };
        // A tip as a scene's object or as the command line's text (`cone:20`).
        let tip = match o.get("tip") {
            None | Some(serde_json::Value::Null) => None,
            Some(serde_json::Value::String(t)) => Some(t.parse::<crate::physics::tip::TipInput>()?),
            Some(v) => Some(serde_json::from_value(v.clone()).map_err(|e| format!("tip: {e}"))?),
        };
        Ok(FitOptions {
            radius: num("radius").unwrap_or(f64::NAN),
            tip,
            spring: num("spring").unwrap_or(f64::NAN),
            poisson: num("poisson"),
            segments,
            z0: num("z0"),
            tilt: o.get("tilt").and_then(|v| v.as_bool()).unwrap_or(false),
            tolerance: num("tolerance").unwrap_or(crate::physics::model::DEFAULT_TOLERANCE),
            humidity: o
                .get("relative_humidity")
                .map(|_| crate::scene::humidity::HumidityInput {
                    relative_humidity: num("relative_humidity").unwrap_or(f64::NAN),
                    contact_angle_deg: num("contact_angle_deg").unwrap_or(0.0),
                    surface_tension_n_m: num("surface_tension_n_m"),
                    molar_volume_m3_mol: num("molar_volume_m3_mol"),
                    temperature_k: num("temperature_k"),
                }),
            ..FitOptions::default()
        }
        .sphere_as_radius())
    }

    /// The options with a spherical `tip` (a sphere, or a power law of exponent 2) given as
    /// its `radius`: a sphere is fitted as a sphere (its DMT, Tabor parameter, verdict,
    /// humidity and warnings), however it was given.
    pub fn sphere_as_radius(self) -> FitOptions {
        match self.tip.as_ref().map(super::Geometry::of) {
            Some(Ok(super::Geometry::Sphere(radius))) => FitOptions {
                radius,
                tip: None,
                ..self
            },
            _ => self,
        }
    }
}

/// The Lennard-Jones range z0 a fit may fix lambda with (m): a few picometres to a micrometre
/// (van der Waals: about 0.3 nm).
pub const Z0_RANGE: (f64, f64) = (1e-12, 1e-6);

impl FitOptions {
    /// The tip the curves are fitted with: `tip`, or the sphere of `radius` (after
    /// [`FitOptions::validate`]; an unchecked tip that is wrong stands as that sphere).
    pub fn geometry(&self) -> super::Geometry {
        self.tip
            .as_ref()
            .and_then(|t| super::Geometry::of(t).ok())
            .unwrap_or(super::Geometry::Sphere(self.radius))
    }

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
        if let Some(tip) = &self.tip {
            super::Geometry::of(tip).map_err(|e| ("tip", e.to_string()))?;
            if self.humidity.is_some() {
                return Err((
                    "relative_humidity",
                    "the water meniscus is fitted on a sphere: leave out the humidity, or fit the tip's apex as a sphere".into(),
                ));
            }
        } else if !(self.radius > 0.0 && self.radius.is_finite()) {
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

/// The option by a front end's name (its field's where it has none), then what is wrong.
impl crate::error::Named for OptionError {
    fn named(&self, names: crate::error::Names) -> String {
        format!(
            "{}: {}",
            names(self.option).unwrap_or(self.option),
            self.message
        )
    }
}

impl std::error::Error for OptionError {}

#[cfg(test)]
mod json_tests {
    use super::*;

    #[test]
    fn options_from_json_take_the_defaults_and_refuse_a_bad_segment() {
        let o = FitOptions::from_json(r#"{"radius": 2e-8, "spring": "inf", "segment": "both"}"#)
            .unwrap();
        let d = FitOptions::default();
        assert_eq!((o.radius, o.spring), (2e-8, f64::INFINITY));
        assert_eq!(o.segments, Segments::Both);
        assert_eq!(
            (o.tolerance, o.baseline_fraction),
            (d.tolerance, d.baseline_fraction)
        );
        assert!(o.humidity.is_none() && o.z0.is_none() && !o.tilt);
        assert!(FitOptions::from_json("{}").unwrap().radius.is_nan());
        let h = FitOptions::from_json(r#"{"relative_humidity": 0.4}"#).unwrap();
        assert_eq!(h.humidity.unwrap().relative_humidity, 0.4);
        let e = FitOptions::from_json(r#"{"segment": "sideways"}"#).unwrap_err();
        assert_eq!(e.keys().collect::<Vec<_>>(), ["segment"]);
        let e = e.to_string();
        assert!(e.contains("\"sideways\"") && e.contains("retract"), "{e}");
    }
}
