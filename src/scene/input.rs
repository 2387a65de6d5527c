//! The scene file: one contact in SI units (JSON, every key named with its unit), and its
//! reduction to the normalised contact.

use crate::physics::params::{
    effective_radius, reduced_modulus, Body, Contact, ForceRange, ParamError,
};
use serde::{Deserialize, Serialize};

/// The scene file (JSON). Units are SI and named in every key.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SceneInput {
    /// The scene's name.
    pub name: Option<String>,
    /// The first body (sphere).
    pub body1: Option<Body>,
    /// The second body (a sphere or a flat).
    pub body2: Option<Body>,
    /// The reduced modulus and effective radius, instead of two bodies.
    pub e_star_pa: Option<f64>,
    /// The effective radius (m).
    pub radius_m: Option<f64>,
    /// The work of adhesion (J/m^2), or the surface energies.
    pub work_of_adhesion_j_m2: Option<f64>,
    /// Dupre: w = g1 + g2 - g12 (J/m^2).
    pub surface_energies_j_m2: Option<[f64; 3]>,
    /// The Lennard-Jones range (m); one of z0, s0 and h0 sets the force's range.
    pub z0_m: Option<f64>,
    /// The Dugdale stress (Pa).
    pub s0_pa: Option<f64>,
    /// The Dugdale range (m).
    pub h0_m: Option<f64>,
    /// The loads (N) at which the state is reported.
    pub loads_n: Option<Vec<f64>>,
    /// [min, max, count], linear.
    pub load_range_n: Option<(f64, f64, usize)>,
    /// The tolerance a simpler model must meet.
    pub tolerance: Option<f64>,
    /// Lattice spacing for the continuum check (default 0.25 nm).
    pub atomic_spacing_m: Option<f64>,
    /// Interfacial shear strength tau0 for the friction estimate F = tau0 pi a^2.
    pub shear_strength_pa: Option<f64>,
    /// The control of the experiment: "load", "displacement", or {"cantilever_n_m": k}.
    pub control: Option<SceneControl>,
    /// Source of the values, for the record.
    pub source: Option<String>,
    /// Ambient humidity: a water meniscus as a second Dugdale zone (docs/PHYSICS.md section 10).
    pub humidity: Option<super::humidity::HumidityInput>,
    /// A tip other than a sphere (docs/PHYSICS.md section 12): a cone, pyramid, power law or
    /// capped cone, instead of `radius_m`; a sphere given here is `radius_m`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tip: Option<crate::physics::tip::TipInput>,
}

/// The control of a scene's experiment.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SceneControl {
    /// Load control (a dead load).
    Load,
    /// Displacement control (rigid grips).
    Displacement,
    /// An AFM cantilever (a spring in series) of stiffness k (N/m).
    CantileverNM(f64),
}

/// The contact of a scene: its materials, radius, w and force range, checked.
pub fn contact_of(s: &SceneInput) -> Result<Contact, ParamError> {
    // A spherical tip is the radius; any other tip is a scene of its own (scene::tip).
    let s = &match s.tip {
        None => s.clone(),
        Some(crate::physics::tip::TipInput::Sphere { radius_m }) => {
            if s.radius_m.is_some() || s.body1.is_some() || s.body2.is_some() {
                return Err(ParamError::Missing(
                    "give the sphere once: as radius_m (or the bodies) or as the tip, not both",
                ));
            }
            SceneInput {
                radius_m: Some(radius_m),
                tip: None,
                ..s.clone()
            }
        }
        Some(_) => {
            return Err(ParamError::Missing(
                "this takes a sphere: a scene with a cone, pyramid, power-law or capped-cone tip is solved by `tabor scene` (and Python's tabor.scene)",
            ))
        }
    };
    if (s.body1.is_some() || s.body2.is_some()) && (s.e_star_pa.is_some() || s.radius_m.is_some()) {
        return Err(ParamError::Missing(
            "give the bodies (body1 and body2) or e_star_pa and radius_m, not both",
        ));
    }
    let (e_star, radius) = match (&s.body1, &s.body2) {
        (Some(b1), Some(b2)) => (reduced_modulus(b1, b2)?, effective_radius(b1, b2)?),
        (Some(_), None) | (None, Some(_)) => {
            return Err(ParamError::Missing(
                "give both body1 and body2, or e_star_pa and radius_m",
            ))
        }
        (None, None) => (
            s.e_star_pa.ok_or(ParamError::Missing(
                "missing e_star_pa (or body1 and body2)",
            ))?,
            s.radius_m
                .ok_or(ParamError::Missing("missing radius_m (or body1 and body2)"))?,
        ),
    };
    let w = match (s.work_of_adhesion_j_m2, s.surface_energies_j_m2) {
        (Some(w), None) => w,
        (None, Some([g1, g2, g12])) => g1 + g2 - g12,
        (Some(_), Some(_)) => {
            return Err(ParamError::Missing(
                "give work_of_adhesion_j_m2 or surface_energies_j_m2, not both",
            ))
        }
        (None, None) => {
            return Err(ParamError::Missing(
                "missing work_of_adhesion_j_m2 (or surface_energies_j_m2 = [g1, g2, g12])",
            ))
        }
    };
    let range = match (s.z0_m, s.s0_pa, s.h0_m) {
        (Some(z), None, None) => ForceRange::LennardJones(z),
        (None, Some(s0), None) => ForceRange::DugdaleStress(s0),
        (None, None, Some(h)) => ForceRange::DugdaleRange(h),
        (None, None, None) => {
            return Err(ParamError::Missing(
                "missing the force range: z0_m (Lennard-Jones), s0_pa or h0_m (Dugdale)",
            ))
        }
        _ => return Err(ParamError::Missing("give one of z0_m, s0_pa, h0_m")),
    };
    Contact::new(radius, e_star, w, range)
}
