//! A rough contact in SI units: the materials of a scene, the summits' radius, density and
//! height spread, and the nominal area (docs/PHYSICS.md section 9).

use super::{Leg, Mean, Rough, RoughError};
use crate::physics::domain::{short, DomainError};
use crate::physics::params::{reduced_modulus, Body, Contact, ForceRange};
use serde::{Deserialize, Serialize};

/// The rough scene file (JSON); SI units named in every key.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RoughScene {
    /// The scene's name.
    pub name: Option<String>,
    /// The two bodies' materials (their radii are not used: the summits' is), or `e_star_pa`.
    pub body1: Option<Body>,
    /// The second body.
    pub body2: Option<Body>,
    /// The effective modulus (Pa), instead of the bodies.
    pub e_star_pa: Option<f64>,
    /// The work of adhesion (J/m^2).
    pub work_of_adhesion_j_m2: f64,
    /// The Lennard-Jones range (m); one of z0, s0 and h0 sets the force's range.
    pub z0_m: Option<f64>,
    /// The Dugdale stress (Pa).
    pub s0_pa: Option<f64>,
    /// The Dugdale range (m).
    pub h0_m: Option<f64>,
    /// Radius of every summit (m).
    pub summit_radius_m: f64,
    /// Summits per unit nominal area (1/m^2).
    pub summit_density_m2: f64,
    /// Standard deviation of the summit heights (m).
    pub sigma_m: f64,
    /// The nominal (apparent) contact area (m^2).
    pub nominal_area_m2: f64,
    /// The smallest separation of the flat from the mean summit plane (m) [default: -3 sigma].
    pub min_separation_m: Option<f64>,
    /// Ambient humidity: a water meniscus on every summit (docs/PHYSICS.md section 10.1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub humidity: Option<crate::scene::humidity::HumidityInput>,
    /// Source of the values, for the record.
    pub source: Option<String>,
}

/// Built-in rough scenes: representative handbook values, printed with every result.
pub fn preset(name: &str) -> Option<RoughScene> {
    let poly = Body {
        youngs_modulus_pa: 160e9,
        poisson_ratio: 0.22,
        radius_m: None,
    };
    match name {
        "mems-polysilicon" => Some(RoughScene {
            name: Some("MEMS polysilicon beam (100 x 20 um) on its polysilicon substrate".into()),
            body1: Some(poly),
            body2: Some(poly),
            e_star_pa: None,
            work_of_adhesion_j_m2: 0.1,
            z0_m: Some(0.3e-9),
            s0_pa: None,
            h0_m: None,
            summit_radius_m: 0.5e-6,
            summit_density_m2: 2e12,
            sigma_m: 0.6e-9,
            nominal_area_m2: 100e-6 * 20e-6,
            min_separation_m: None,
            humidity: None,
            source: Some("polysilicon E = 160 GPa, nu = 0.22; w = 0.1 J/m^2 (hydrophilic, dry); summits of radius 0.5 um, 2 per um^2, rms height 0.6 nm: representative of CMP-polished polysilicon, not a measured sample".into()),
        }),
        "pdms-rough-glass" => Some(RoughScene {
            name: Some("PDMS block (1 cm^2) on frosted glass".into()),
            body1: None,
            body2: None,
            e_star_pa: Some(2.4e6),
            work_of_adhesion_j_m2: 0.044,
            z0_m: Some(0.3e-9),
            s0_pa: None,
            h0_m: None,
            summit_radius_m: 10e-6,
            summit_density_m2: 1e9,
            sigma_m: 0.2e-6,
            nominal_area_m2: 1e-4,
            min_separation_m: None,
            humidity: None,
            source: Some("PDMS on glass E* = 2.4 MPa, w = 44 mJ/m^2 (as the pdms-glass scene); summits of radius 10 um, 1000 per mm^2, rms height 0.2 um: representative, not a measured sample".into()),
        }),
        "colloidal-probe-wafer" => Some(RoughScene {
            name: Some("silica colloidal probe (radius 25 um) on a rough silicon wafer".into()),
            body1: Some(Body {
                youngs_modulus_pa: 73e9,
                poisson_ratio: 0.17,
                radius_m: None,
            }),
            body2: Some(Body {
                youngs_modulus_pa: 130e9,
                poisson_ratio: 0.28,
                radius_m: None,
            }),
            e_star_pa: None,
            work_of_adhesion_j_m2: 0.05,
            z0_m: Some(0.3e-9),
            s0_pa: None,
            h0_m: None,
            summit_radius_m: 200e-9,
            summit_density_m2: 5e13,
            sigma_m: 0.5e-9,
            nominal_area_m2: 2.0 * std::f64::consts::PI * 25e-6 * 6.0 * 0.5e-9,
            min_separation_m: Some(-1e-9),
            humidity: None,
            source: Some("silica E = 73 GPa, nu = 0.17 on silicon E = 130 GPa, nu = 0.28; w = 0.05 J/m^2 (oxide on oxide, dry); wafer summits of radius 200 nm, 50 per um^2, rms height 0.5 nm, pressed to 2 sigma below their mean plane: representative, not a measured sample. Nominal area: the patch of the 25 um probe within 6 sigma of the wafer, 2 pi R 6 sigma: only about 24 summits, so the statistics are stretched (the warning says so; an explicit ensemble of the measured summits under the probe, --asperities, is the tool), and the probe's own curvature across the patch (Greenwood and Tripp) and its attraction beyond the summits are not modelled".into()),
        }),
        _ => None,
    }
}

/// The built-in rough scenes.
pub const PRESETS: [&str; 3] = [
    "mems-polysilicon",
    "pdms-rough-glass",
    "colloidal-probe-wafer",
];

/// One half of the cycle in SI units, one entry per separation.
#[derive(Clone, Debug, Serialize)]
pub struct SiLeg {
    /// Separation of the flat from the mean summit plane (m).
    pub separation_m: Vec<f64>,
    /// Total force (N, compressive positive).
    pub force_n: Vec<f64>,
    /// Force over the nominal area (Pa).
    pub nominal_pressure_pa: Vec<f64>,
    /// Real contact area (m^2).
    pub real_contact_area_m2: Vec<f64>,
    /// Fraction of the summits in contact.
    pub contact_fraction: Vec<f64>,
    /// Fraction of the summits with a cohesive zone only.
    pub noncontact_fraction: Vec<f64>,
}

/// A rough scene's cycle in SI units.
#[derive(Clone, Debug, Serialize)]
pub struct RoughSceneResult {
    /// The scene's name.
    pub name: Option<String>,
    /// Where the scene came from (file or preset).
    pub source: Option<String>,
    /// Effective modulus (Pa).
    pub e_star_pa: f64,
    /// Work of adhesion (J/m^2).
    pub work_of_adhesion_j_m2: f64,
    /// Each summit's Maugis parameter and Tabor parameter.
    pub lambda: f64,
    /// Each summit's Tabor parameter.
    pub tabor_parameter: f64,
    /// sigma in the summit's approach unit, and Fuller and Tabor's adhesion parameter.
    pub sigma_normalised: f64,
    /// Fuller and Tabor's adhesion parameter.
    pub fuller_tabor_parameter: f64,
    /// Summits in the nominal area.
    pub summits: f64,
    /// The approach.
    pub approach: SiLeg,
    /// The retract.
    pub retract: SiLeg,
    /// The pull-off force (N, the most tensile retract force).
    pub pulloff_force_n: f64,
    /// The pull-off over the nominal area (Pa).
    pub pulloff_stress_pa: f64,
    /// The separation of the pull-off (m).
    pub pulloff_separation_m: f64,
    /// Every summit pulling as a smooth one (sigma -> 0): N times the summit's Pbar_c pi w R.
    pub smooth_pulloff_force_n: f64,
    /// Energy lost per cycle (J).
    pub hysteresis_j: f64,
    /// Where the model is stretched.
    pub warnings: Vec<String>,
    /// The model and its assumptions, in words.
    pub model: &'static str,
    /// With humidity: the meniscus on every summit, and the dry surface's pull-off after the same
    /// press, for comparison. The loads above are then those of the solid and the meniscus.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub meniscus: Option<crate::scene::humidity::Meniscus>,
    #[serde(skip_serializing_if = "Option::is_none")]
    /// The dry surface's pull-off after the same press (N).
    pub dry_pulloff_force_n: Option<f64>,
    /// The same cycle in the summit's units (for the figure).
    #[serde(skip)]
    pub normalised: super::RoughCycle,
}

/// The model of a wet rough scene, in words.
pub const MODEL_WET: &str = "Greenwood-Williamson with a water meniscus on every summit: identical spherical summits, Gaussian heights, each an exact two-zone (solid Dugdale zone plus a Kelvin meniscus) sphere under rigid grips with its own history; the summits and their menisci do not interact, which fails where the wetted annuli reach the summit spacing or the meniscus height is comparable with sigma (the menisci merge into one film), as for the dry model where contact spots crowd; the meniscus is in equilibrium with the vapour (slow cycles) and its Kelvin radius small against the summit radius";

/// The model of a dry rough scene, in words.
pub const MODEL: &str = "Greenwood-Williamson: identical spherical summits, Gaussian heights, each an exact Maugis-Dugdale sphere under rigid grips with its own history; the summits do not interact (no elastic coupling), which fails when contact spots crowd (a real contact area beyond about 10% of the nominal), when sigma is comparable to the summit radius, or for few summits";

fn positive(name: &'static str, v: f64) -> Result<f64, RoughError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(DomainError {
            name,
            value: v,
            range: "(0, inf)",
            hint: "give a positive, finite value in SI units",
        }
        .into())
    }
}

impl RoughScene {
    /// One summit as a contact: the materials with the summit's radius.
    pub fn summit(&self) -> Result<Contact, RoughError> {
        let e_star = match (&self.body1, &self.body2, self.e_star_pa) {
            (Some(b1), Some(b2), None) => reduced_modulus(b1, b2).map_err(scene_err)?,
            (None, None, Some(e)) => e,
            _ => return Err(scene_err("give e_star_pa, or body1 and body2 (not both)")),
        };
        let range = match (self.z0_m, self.s0_pa, self.h0_m) {
            (Some(z), None, None) => ForceRange::LennardJones(z),
            (None, Some(s0), None) => ForceRange::DugdaleStress(s0),
            (None, None, Some(h)) => ForceRange::DugdaleRange(h),
            _ => {
                return Err(scene_err(
                    "give one force range: z0_m (Lennard-Jones), s0_pa or h0_m (Dugdale)",
                ))
            }
        };
        let r = positive("summit_radius_m", self.summit_radius_m)?;
        Contact::new(r, e_star, self.work_of_adhesion_j_m2, range).map_err(scene_err)
    }

    /// The cycle in SI units, `points` separations each way; with humidity, the wet summits of
    /// section 10.1 and the dry pull-off beside them.
    pub fn solve(&self, points: usize) -> Result<RoughSceneResult, RoughError> {
        use super::wet::WetRough;
        let c = self.summit()?;
        let density = positive("summit_density_m2", self.summit_density_m2)?;
        let area = positive("nominal_area_m2", self.nominal_area_m2)?;
        let sigma_m = positive("sigma_m", self.sigma_m)?;
        let meniscus = match &self.humidity {
            Some(h) => h.meniscus(&c).map_err(scene_err)?,
            None => None,
        };
        let wet = match &meniscus {
            Some(m) => Some(crate::scene::humidity::wet_ratios(&c, m).map_err(scene_err)?),
            None => None,
        };
        // The units: the solid's, or those of the total w with a meniscus.
        let (unit, f, radius_unit) = match &wet {
            None => (c.approach_scale(), c.force_scale(), c.radius_scale()),
            Some((_, _, u)) => (u.approach, u.load, u.radius),
        };
        let sigma_n = approach_units("sigma_m", sigma_m, unit, super::SIGMA_MAX)?;
        let d_min = match self.min_separation_m {
            Some(d) => approach_units("min_separation_m", d, unit, super::SEPARATION_MAX)?,
            None => -3.0 * sigma_n,
        };
        let rough = match wet {
            None => WetRough::Dry(Rough::new(c.lambda(), sigma_n)?),
            Some((rho, eta, _)) => WetRough::new(c.lambda(), rho, eta, sigma_n)?,
        };
        let reach = rough.free_separation();
        if d_min >= reach {
            return Err(scene_err(format!(
                "min_separation_m = {} m is beyond the summits' reach ({} m above the mean summit plane: no summit feels the flat there), so nothing would touch: give a smaller min_separation_m",
                short(self.min_separation_m.unwrap_or(d_min * unit)),
                short(reach * unit)
            )));
        }
        let cyc = rough.cycle(c.lambda(), d_min, None, points)?;
        let n = density * area;
        let a2 = radius_unit.powi(2);
        let leg = |v: &[Mean], l: Leg| -> Result<SiLeg, RoughError> {
            let areas = v
                .iter()
                .map(|m| Ok(n * std::f64::consts::PI * a2 * rough.mean_area(l, m.separation)?))
                .collect::<Result<Vec<f64>, RoughError>>()?;
            Ok(SiLeg {
                separation_m: v.iter().map(|m| m.separation * unit).collect(),
                force_n: v.iter().map(|m| m.load * f * n).collect(),
                nominal_pressure_pa: v.iter().map(|m| m.load * f * n / area).collect(),
                real_contact_area_m2: areas,
                contact_fraction: v.iter().map(|m| m.contact_fraction).collect(),
                noncontact_fraction: v.iter().map(|m| m.noncontact_fraction).collect(),
            })
        };
        let approach = leg(&cyc.approach, Leg::Approach)?;
        let retract = leg(&cyc.retract, Leg::Retract { d_min })?;
        let densest = retract
            .real_contact_area_m2
            .iter()
            .chain(&approach.real_contact_area_m2)
            .fold(0.0f64, |m, a| m.max(*a))
            / area;
        let mut warnings = stretched(sigma_m, self.summit_radius_m, n, densest);
        // (In the library's words: a scene's front ends both call the sampling `points`.)
        warnings.extend(cyc.warnings.iter().map(|w| w.to_string()));
        let mut dry_pulloff_force_n = None;
        if let Some(h) = &self.humidity {
            warnings.extend(h.warnings(c.radius));
        }
        if let Some(m) = &meniscus {
            warnings.extend(merging(m.range_m, self.summit_radius_m, density, sigma_m));
            let dry_unit = c.approach_scale();
            let dry = Rough::new(c.lambda(), sigma_m / dry_unit)?;
            let (_, p) = dry.pulloff_after(d_min * unit / dry_unit, 48)?;
            dry_pulloff_force_n = Some(p * c.force_scale() * n);
        }
        Ok(RoughSceneResult {
            name: self.name.clone(),
            source: self.source.clone(),
            e_star_pa: c.e_star,
            work_of_adhesion_j_m2: c.work,
            lambda: c.lambda(),
            tabor_parameter: c.tabor(),
            sigma_normalised: sigma_n,
            fuller_tabor_parameter: cyc.fuller_tabor_parameter,
            summits: n,
            approach,
            retract,
            pulloff_force_n: cyc.pulloff_load * f * n,
            pulloff_stress_pa: cyc.pulloff_load * f * n / area,
            pulloff_separation_m: cyc.pulloff_separation * unit,
            smooth_pulloff_force_n: cyc.smooth_pulloff * f * n,
            hysteresis_j: cyc.hysteresis * f * unit * n,
            warnings,
            model: if meniscus.is_some() { MODEL_WET } else { MODEL },
            meniscus,
            dry_pulloff_force_n,
            normalised: cyc,
        })
    }
}

/// Where a rough scene stretches the model: sigma against the summit radius, few summits, and
/// crowded contact spots (the real contact area `densest` of the nominal).
fn stretched(sigma_m: f64, radius_m: f64, n: f64, densest: f64) -> Vec<String> {
    let mut warnings = Vec::new();
    if sigma_m > 0.1 * radius_m {
        warnings.push(format!(
            "sigma is {} of the summit radius: the paraboloid summit is stretched",
            short(sigma_m / radius_m)
        ));
    }
    if n < 100.0 {
        warnings.push(format!(
            "only {} summits in the nominal area: the Gaussian statistics are stretched (use an explicit ensemble)",
            short(n)
        ));
    }
    if densest > 0.1 {
        warnings.push(format!(
            "the real contact area reaches {} of the nominal: the summits crowd and their elastic interaction, which the model ignores, matters",
            short(densest)
        ));
    }
    warnings
}

/// Where neighbouring menisci merge into one film (the meniscus height `range_m` comparable
/// with sigma, or its wetted radius with the summit spacing), which the model does not describe.
fn merging(range_m: f64, radius_m: f64, density: f64, sigma_m: f64) -> Option<String> {
    let wetted = (2.0 * radius_m * range_m).sqrt();
    let spacing = 1.0 / density.sqrt();
    (wetted > 0.3 * spacing || range_m > 0.3 * sigma_m).then(|| {
        format!(
            "the meniscus (height {} m, wetted radius about {} m) is comparable with sigma ({} m) or the summit spacing ({} m): neighbouring menisci merge into one film, which the model does not describe",
            short(range_m),
            short(wetted),
            short(sigma_m),
            short(spacing)
        )
    })
}

/// A scene's length `key` = `v` m in approach units (`unit` m), at most `max` of them in
/// magnitude: the message is in the scene's key and metres, the value as given.
fn approach_units(key: &str, v: f64, unit: f64, max: f64) -> Result<f64, RoughError> {
    let n = v / unit;
    if !v.is_finite() {
        return Err(scene_err(format!(
            "{key} = {v} is not a length: give a finite value in m"
        )));
    }
    if n.abs() <= max {
        return Ok(n);
    }
    Err(scene_err(format!(
        "{key} = {} m is {} approach units ((pi^2 w^2 R/K^2)^(1/3) = {} m for this scene), beyond the {max:e} the rough model takes: give {key} of at most {} m in magnitude",
        short(v),
        short(n),
        short(unit),
        short(max * unit)
    )))
}

fn scene_err(e: impl std::fmt::Display) -> RoughError {
    RoughError::Scene(e.to_string().into())
}
