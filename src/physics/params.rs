//! From physical inputs (SI units) to the normalised parameters (PHYSICS.md section 1).

use std::f64::consts::PI;

#[derive(Debug, thiserror::Error, PartialEq)]
/// A physical input that cannot be normalised: one line naming the field.
#[non_exhaustive]
pub enum ParamError {
    #[error("{field} = {} is out of range: it must be {allowed}", super::domain::short(*.value))]
    /// A value outside its range.
    OutOfRange {
        /// The input's name in a scene file.
        field: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range, in words.
        allowed: &'static str,
    },
    #[error("{0}")]
    /// A needed input is absent (the message says which).
    Missing(&'static str),
    #[error("{0}")]
    /// Inputs that do not go together, the message naming them, their values and what to do.
    Conflict(crate::error::Message),
    #[error(transparent)]
    /// A normalised value outside the solver's domain.
    Domain(#[from] super::domain::DomainError),
}

impl crate::error::Named for ParamError {
    fn named(&self, names: crate::error::Names) -> String {
        match self {
            ParamError::OutOfRange {
                field,
                value,
                allowed,
            } => format!(
                "{} = {} is out of range: it must be {allowed}",
                names(field).unwrap_or(field),
                super::domain::short(*value)
            ),
            ParamError::Conflict(m) => m.named(names),
            ParamError::Domain(e) => e.named(names),
            ParamError::Missing(_) => self.to_string(),
        }
    }
}

pub(crate) fn check(
    field: &'static str,
    value: f64,
    ok: bool,
    allowed: &'static str,
) -> Result<f64, ParamError> {
    if value.is_finite() && ok {
        Ok(value)
    } else {
        Err(ParamError::OutOfRange {
            field,
            value,
            allowed,
        })
    }
}

/// One elastic body: Young's modulus (Pa), Poisson ratio, radius (m; `None` for a flat).
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// Young's modulus E (Pa).
    pub youngs_modulus_pa: f64,
    /// Poisson's ratio, in -1..0.5.
    pub poisson_ratio: f64,
    /// The radius of curvature R (m); `None` for a flat.
    pub radius_m: Option<f64>,
}

/// The range of the surface force.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ForceRange {
    /// Dugdale cohesive stress s0 (Pa).
    DugdaleStress(f64),
    /// Dugdale range h0 = w / s0 (m).
    DugdaleRange(f64),
    /// Lennard-Jones equilibrium spacing z0 (m); s0 is matched to the LJ maximum stress
    /// 16 w / (9 sqrt(3) z0).
    LennardJones(f64),
}

/// A sphere-on-flat contact in SI units, reduced to the effective radius and modulus.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// Effective radius R (m).
    pub radius: f64,
    /// Reduced modulus E* (Pa).
    pub e_star: f64,
    /// Work of adhesion w (J/m^2).
    pub work: f64,
    /// Dugdale stress s0 (Pa).
    pub s0: f64,
    /// Lennard-Jones z0 (m) if the range was given that way (for the Tabor parameter).
    pub z0: Option<f64>,
}

/// The LJ-matched Dugdale stress is `LJ_STRESS / z0 * w`.
/// Above this contact radius over sphere radius the half-space (small-strain) theory that every
/// model here rests on breaks down.
pub const A_OVER_R_MAX: f64 = 0.1;

/// The warning for a contact too large for small-strain theory (a/R above [`A_OVER_R_MAX`]),
/// the one check that scenes and profiles share.
pub fn small_strain_warning(a_over_r: f64) -> Option<String> {
    (a_over_r > A_OVER_R_MAX).then(|| {
        format!(
            "a/R = {a_over_r:.2} > {A_OVER_R_MAX}: small-strain (half-space) theory breaks down"
        )
    })
}

/// Fitted parameters outside these are taken for a failed fit (wrong units, a wrong spring
/// constant or radius, or data the models cannot describe): E* (Pa), from the softest gels and
/// cells (measured cell curves fit a few hundred Pa) to diamond, and w (J/m^2) above metallic
/// adhesion. A w below the weakest van der Waals contact (1e-6) is
/// no measurable adhesion (a Hertz curve), not a failure.
pub const E_STAR_RANGE: (f64, f64) = (10.0, 1e12);
/// The largest plausible work of adhesion w (J/m^2); see [`E_STAR_RANGE`].
pub const W_MAX: f64 = 10.0;

/// Whether a modulus E* (Pa) and a work of adhesion w (J/m^2) lie in the plausible ranges
/// ([`E_STAR_RANGE`], [`W_MAX`]), and both values with their ranges in words: the one check of
/// `fit` and `infer`.
pub fn plausibility(e_star: f64, w: f64) -> (bool, String) {
    let short = super::domain::short;
    let ok = (E_STAR_RANGE.0..=E_STAR_RANGE.1).contains(&e_star) && w <= W_MAX;
    let text = format!(
        "E* = {} Pa (plausible {}..{} Pa), w = {} J/m^2 (plausible up to {} J/m^2)",
        short(e_star),
        short(E_STAR_RANGE.0),
        short(E_STAR_RANGE.1),
        short(w),
        short(W_MAX)
    );
    (ok, text)
}

/// The Lennard-Jones law's largest stress in units of `w / z0`: `16 / (9 sqrt 3)`.
pub const LJ_STRESS: f64 = 16.0 / (9.0 * 1.7320508075688772);

/// `1/E* = (1-v1^2)/E1 + (1-v2^2)/E2`, with range checks that name the field.
pub fn reduced_modulus(b1: &Body, b2: &Body) -> Result<f64, ParamError> {
    let mut inv = 0.0;
    for (i, b) in [b1, b2].iter().enumerate() {
        let (fe, fv) = if i == 0 {
            ("body1.youngs_modulus_pa", "body1.poisson_ratio")
        } else {
            ("body2.youngs_modulus_pa", "body2.poisson_ratio")
        };
        let e = check(
            fe,
            b.youngs_modulus_pa,
            b.youngs_modulus_pa > 0.0,
            "> 0 (Pa)",
        )?;
        let v = check(
            fv,
            b.poisson_ratio,
            b.poisson_ratio > -1.0 && b.poisson_ratio <= 0.5,
            "in (-1, 0.5]",
        )?;
        inv += (1.0 - v * v) / e;
    }
    Ok(1.0 / inv)
}

/// `1/R = 1/R1 + 1/R2` (a flat has no radius).
pub fn effective_radius(b1: &Body, b2: &Body) -> Result<f64, ParamError> {
    let mut inv = 0.0;
    for (i, b) in [b1, b2].iter().enumerate() {
        if let Some(r) = b.radius_m {
            let f = if i == 0 {
                "body1.radius_m"
            } else {
                "body2.radius_m"
            };
            inv += 1.0 / check(f, r, r > 0.0, "> 0 (m), or absent for a flat")?;
        }
    }
    if inv == 0.0 {
        return Err(ParamError::Missing(
            "two flats: at least one body needs a radius",
        ));
    }
    Ok(1.0 / inv)
}

impl Contact {
    /// A contact from the combined radius (m), E* (Pa), w (J/m^2) and the force range; each checked.
    pub fn new(radius: f64, e_star: f64, work: f64, range: ForceRange) -> Result<Self, ParamError> {
        let radius = check("radius_m", radius, radius > 0.0, "> 0 (m)")?;
        let e_star = check("e_star_pa", e_star, e_star > 0.0, "> 0 (Pa)")?;
        let work = check("work_of_adhesion_j_m2", work, work > 0.0, "> 0 (J/m^2)")?;
        let (s0, z0) = match range {
            ForceRange::DugdaleStress(s) => (check("s0_pa", s, s > 0.0, "> 0 (Pa)")?, None),
            ForceRange::DugdaleRange(h) => (work / check("h0_m", h, h > 0.0, "> 0 (m)")?, None),
            ForceRange::LennardJones(z) => {
                let z = check("z0_m", z, z > 0.0, "> 0 (m)")?;
                (LJ_STRESS * work / z, Some(z))
            }
        };
        Ok(Self {
            radius,
            e_star,
            work,
            s0,
            z0,
        })
    }

    /// K = (4/3) E*.
    pub fn k(&self) -> f64 {
        4.0 / 3.0 * self.e_star
    }
    /// Maugis parameter `lambda = 2 s0 (R / (pi w K^2))^(1/3)`.
    pub fn lambda(&self) -> f64 {
        2.0 * self.s0 * (self.radius / (PI * self.work * self.k() * self.k())).cbrt()
    }
    /// Tabor parameter `(R w^2 / (E*^2 z0^3))^(1/3)`; with no LJ z0 given, z0 is taken as the
    /// one whose LJ stress equals s0, so that `lambda = 1.1570 muT` holds.
    pub fn tabor(&self) -> f64 {
        let z0 = self.z0.unwrap_or(LJ_STRESS * self.work / self.s0);
        (self.radius * self.work * self.work / (self.e_star * self.e_star * z0.powi(3))).cbrt()
    }
    /// Force unit: Pbar = P / (pi w R).
    pub fn force_scale(&self) -> f64 {
        PI * self.work * self.radius
    }
    /// Length unit of the contact radius: a = A (pi w R^2 / K)^(1/3).
    pub fn radius_scale(&self) -> f64 {
        (PI * self.work * self.radius * self.radius / self.k()).cbrt()
    }
    /// Length unit of the approach: delta = Dbar (pi^2 w^2 R / K^2)^(1/3).
    pub fn approach_scale(&self) -> f64 {
        (PI * PI * self.work * self.work * self.radius / (self.k() * self.k())).cbrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lambda_is_1_157_times_tabor_for_lj_range() {
        let c = Contact::new(20e-9, 100e9, 0.05, ForceRange::LennardJones(0.3e-9)).unwrap();
        let ratio = c.lambda() / c.tabor();
        // 2 * 16/(9 sqrt 3) / pi^(1/3) * (3/4)^(2/3) ... = 1.1570 (PHYSICS.md section 1).
        assert!((ratio - 1.1570).abs() < 1e-4, "{ratio}");
    }

    #[test]
    fn conversions_are_consistent() {
        let c = Contact::new(1e-3, 1e6, 0.05, ForceRange::DugdaleStress(1e6)).unwrap();
        // delta/h0 = (pi lambda / 2) Dbar.
        let h0 = c.work / c.s0;
        assert!((c.approach_scale() / h0 - std::f64::consts::PI * c.lambda() / 2.0).abs() < 1e-12);
        // a/R = 2 A (s0/K) / lambda.
        assert!((c.radius_scale() / c.radius - 2.0 * (c.s0 / c.k()) / c.lambda()).abs() < 1e-12);
    }

    #[test]
    fn bad_inputs_name_the_field() {
        let b = Body {
            youngs_modulus_pa: -1.0,
            poisson_ratio: 0.3,
            radius_m: Some(1.0),
        };
        let f = Body {
            youngs_modulus_pa: 1e9,
            poisson_ratio: 0.3,
            radius_m: None,
        };
        let e = reduced_modulus(&b, &f).unwrap_err().to_string();
        assert!(e.contains("body1.youngs_modulus_pa"), "{e}");
        let b = Body {
            youngs_modulus_pa: 1e9,
            poisson_ratio: 0.7,
            radius_m: Some(1.0),
        };
        assert!(reduced_modulus(&b, &f)
            .unwrap_err()
            .to_string()
            .contains("(-1, 0.5]"));
        assert!(effective_radius(&f, &f).is_err());
    }
}
