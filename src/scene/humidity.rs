//! Humidity: the water meniscus as a second Dugdale zone beside the solid's (docs/PHYSICS.md
//! section 10). The Kelvin radius fixes the meniscus' Laplace pressure and its height; the
//! contact is then the two-zone law, solved exactly.

use crate::error::Message;
use crate::physics::params::{Contact, ParamError};
use crate::solver::two_zone::{dimensional_zones, TwoZoneContext, Units};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The gas constant (J/(mol K)).
pub const R_GAS: f64 = 8.314_462_618;

/// Avogadro's constant (1/mol).
pub const AVOGADRO: f64 = 6.022_140_76e23;

/// The meniscus height `2 r_K cos(theta)`, as a fraction of R, beyond which the thin-annulus
/// meniscus fails (it floods the sphere near saturation).
pub const FLOODING: f64 = 0.1;

/// Where the continuum meniscus does not hold (docs/PHYSICS.md section 10).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limit {
    /// The Kelvin radius is below one molecule of the liquid: no meniscus is counted.
    Molecular,
    /// The meniscus height exceeds [`FLOODING`] R: the meniscus is counted, but its model fails.
    Flooding,
}

/// The scene's `"humidity"` object (SI units).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct HumidityInput {
    /// Relative humidity, 0..1 (0: no meniscus).
    pub relative_humidity: f64,
    /// Contact angle of water on the surfaces (degrees); 90 or more: no meniscus.
    pub contact_angle_deg: f64,
    /// Surface tension of the liquid (N/m), default 0.072 (water at 25 C).
    pub surface_tension_n_m: Option<f64>,
    /// Molar volume of the liquid (m^3/mol), default 1.8e-5 (water).
    pub molar_volume_m3_mol: Option<f64>,
    /// Temperature (K), default 298.15.
    pub temperature_k: Option<f64>,
}

/// The meniscus as a Dugdale zone, as the scene's JSON reports it.
#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct Meniscus {
    /// The Kelvin radius r_K (m).
    pub kelvin_radius_m: f64,
    /// gamma / r_K: the meniscus' tensile stress (Pa).
    pub laplace_pressure_pa: f64,
    /// 2 r_K cos(theta): the largest gap the meniscus bridges (m).
    pub range_m: f64,
    /// 2 gamma cos(theta) (J/m^2).
    pub work_of_adhesion_j_m2: f64,
    /// The Maugis parameter of the meniscus alone, `2 s (R/(pi w K^2))^(1/3)` with its own w.
    pub lambda: f64,
}

fn bad(field: &'static str, value: f64, allowed: &'static str) -> ParamError {
    ParamError::OutOfRange {
        field,
        value,
        allowed,
    }
}

/// The values of a humidity: its key in a scene's `"humidity"` object, the quantity in words
/// and what it must be.
const VALUES: [(&str, &str, &str, &str); 5] = [
    (
        "relative_humidity",
        "humidity.relative_humidity",
        "relative humidity",
        "in 0..1 (a fraction, below 1: at 1 the Kelvin radius is infinite)",
    ),
    (
        "contact_angle_deg",
        "humidity.contact_angle_deg",
        "contact angle",
        "in 0..180 (degrees)",
    ),
    (
        "surface_tension_n_m",
        "humidity.surface_tension_n_m",
        "surface tension",
        "> 0 (N/m; water 0.072)",
    ),
    (
        "molar_volume_m3_mol",
        "humidity.molar_volume_m3_mol",
        "molar volume",
        "> 0 (m^3/mol; water 1.8e-5)",
    ),
    (
        "temperature_k",
        "humidity.temperature_k",
        "temperature",
        "> 0 (K; 298.15 is 25 C)",
    ),
];

/// A value of a humidity out of its range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HumidityRangeError {
    which: usize,
    /// The value given.
    pub value: f64,
}

impl HumidityRangeError {
    /// Its key in a scene's `"humidity"` object (`relative_humidity`, `contact_angle_deg`,
    /// `surface_tension_n_m`, `molar_volume_m3_mol`, `temperature_k`).
    pub fn key(&self) -> &'static str {
        VALUES[self.which].0
    }

    /// The quantity in words ("relative humidity").
    pub fn quantity(&self) -> &'static str {
        VALUES[self.which].2
    }

    /// What the value must be, in words.
    pub fn allowed(&self) -> &'static str {
        VALUES[self.which].3
    }
}

impl std::fmt::Display for HumidityRangeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} {} is out of range: it must be {}",
            self.quantity(),
            crate::physics::domain::short(self.value),
            self.allowed()
        )
    }
}

impl std::error::Error for HumidityRangeError {}

impl From<HumidityRangeError> for ParamError {
    fn from(e: HumidityRangeError) -> ParamError {
        bad(VALUES[e.which].1, e.value, e.allowed())
    }
}

impl HumidityInput {
    /// A humidity for `rh` with water's defaults and the contact angle `theta_deg`.
    pub fn water(rh: f64, theta_deg: f64) -> HumidityInput {
        HumidityInput {
            relative_humidity: rh,
            contact_angle_deg: theta_deg,
            surface_tension_n_m: None,
            molar_volume_m3_mol: None,
            temperature_k: None,
        }
    }

    /// The surface tension (N/m), its default water's 0.072.
    pub fn surface_tension(&self) -> f64 {
        self.surface_tension_n_m.unwrap_or(0.072)
    }

    /// The molar volume (m^3/mol), its default water's 1.8e-5.
    pub fn molar_volume(&self) -> f64 {
        self.molar_volume_m3_mol.unwrap_or(1.8e-5)
    }

    /// The temperature (K), its default 298.15.
    pub fn temperature(&self) -> f64 {
        self.temperature_k.unwrap_or(298.15)
    }

    /// Checks every value: the first out of its range, with its key and limit in words.
    pub fn validate(&self) -> Result<(), HumidityRangeError> {
        let err = |i: usize, value: f64| Err(HumidityRangeError { which: i, value });
        let rh = self.relative_humidity;
        if !(rh.is_finite() && (0.0..1.0).contains(&rh)) {
            return err(0, rh);
        }
        let theta = self.contact_angle_deg;
        if !(theta.is_finite() && (0.0..=180.0).contains(&theta)) {
            return err(1, theta);
        }
        for (i, v) in [
            (2, self.surface_tension()),
            (3, self.molar_volume()),
            (4, self.temperature()),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return err(i, v);
            }
        }
        Ok(())
    }

    /// The meniscus' Dugdale zone at Kelvin radius `r_k`: the Laplace pressure `gamma / r_K`
    /// over the range `2 r_K cos(theta)`.
    fn zone(&self, r_k: f64) -> (f64, f64) {
        let cos = (self.contact_angle_deg * PI / 180.0).cos();
        (self.surface_tension() / r_k, 2.0 * r_k * cos)
    }

    /// The meniscus' stress (Pa) and range (m), or `None` where there is none (see
    /// [`HumidityInput::meniscus`]; the values are checked).
    pub fn stress_and_range(&self) -> Option<(f64, f64)> {
        self.validate().ok()?;
        self.forms().then(|| self.zone(self.kelvin_radius()))
    }

    /// Whether a meniscus forms: RH above 0, a contact angle below 90 degrees (water bridges
    /// the gap) and a Kelvin radius of at least one molecule of the liquid (docs/PHYSICS.md
    /// section 10: below it there is no continuum meniscus, and none is counted).
    fn forms(&self) -> bool {
        self.relative_humidity > 0.0
            && self.contact_angle_deg < 90.0
            && self.kelvin_radius() >= self.molecule_size()
    }

    /// The size of one molecule of the liquid, `(V_m / N_A)^(1/3)` (m): 0.31 nm for water.
    pub fn molecule_size(&self) -> f64 {
        (self.molar_volume() / AVOGADRO).cbrt()
    }

    /// The relative humidity at which the Kelvin radius is one molecule's size: below it no
    /// meniscus is counted.
    pub fn molecular_rh(&self) -> f64 {
        let (gamma, vm, t) = (
            self.surface_tension(),
            self.molar_volume(),
            self.temperature(),
        );
        (-gamma * vm / (R_GAS * t * self.molecule_size())).exp()
    }

    /// Why no meniscus forms, in words; `None` where one does (the values are checked).
    pub fn no_meniscus(&self) -> Option<String> {
        let short = crate::physics::domain::short;
        if self.forms() {
            None
        } else if self.relative_humidity <= 0.0 {
            Some("RH = 0: no water condenses".into())
        } else if self.contact_angle_deg >= 90.0 {
            Some(format!(
                "a contact angle of {} degrees (90 or more): water does not bridge the gap",
                short(self.contact_angle_deg)
            ))
        } else {
            Some(format!(
                "the Kelvin radius {:.3} nm at RH = {:?} is below one molecule of the liquid ({:.3} nm, reached at RH = {:.3}): no continuum meniscus",
                self.kelvin_radius() * 1e9,
                self.relative_humidity,
                self.molecule_size() * 1e9,
                self.molecular_rh()
            ))
        }
    }

    /// Where the continuum meniscus does not hold at this humidity on a sphere of radius
    /// `radius` (m): the one check every front end reports (see [`Limit`]).
    pub fn limits(&self, radius: f64) -> Vec<Limit> {
        let mut out = Vec::new();
        if self.validate().is_err()
            || self.relative_humidity <= 0.0
            || self.contact_angle_deg >= 90.0
        {
            return out;
        }
        if !self.forms() {
            out.push(Limit::Molecular);
        } else if self.zone(self.kelvin_radius()).1 > FLOODING * radius {
            out.push(Limit::Flooding);
        }
        out
    }

    /// [`HumidityInput::limits`] in words, one sentence each.
    pub fn warnings(&self, radius: f64) -> Vec<String> {
        self.limits(radius)
            .into_iter()
            .map(|l| match l {
                Limit::Molecular => format!(
                    "{}, so none is counted (the dry contact; docs/PHYSICS.md section 10)",
                    self.no_meniscus().unwrap_or_default()
                ),
                Limit::Flooding => {
                    let h = self.zone(self.kelvin_radius()).1;
                    format!(
                        "the meniscus height 2 r_K cos(theta) = {:.3e} m at RH = {:?} is {:.0}% of R: the thin-annulus model fails near saturation",
                        h,
                        self.relative_humidity,
                        100.0 * h / radius
                    )
                }
            })
            .collect()
    }

    /// The Kelvin radius `gamma V_m / (R T ln(1/RH))` (m).
    pub fn kelvin_radius(&self) -> f64 {
        let (gamma, vm, t) = (
            self.surface_tension(),
            self.molar_volume(),
            self.temperature(),
        );
        gamma * vm / (R_GAS * t * (1.0 / self.relative_humidity).ln())
    }

    /// Checks every value and returns the meniscus, or `None` where there is none (RH = 0, a
    /// contact angle of 90 degrees or more, or a Kelvin radius below one molecule: see
    /// [`HumidityInput::no_meniscus`]). A meniscus whose stress beside the solid's is beyond
    /// the two-zone solver's reach is refused, naming the humidity's values.
    pub fn meniscus(&self, c: &Contact) -> Result<Option<Meniscus>, ParamError> {
        self.validate()?;
        if !self.forms() {
            return Ok(None);
        }
        let r_k = self.kelvin_radius();
        let (stress, range) = self.zone(r_k);
        let w = stress * range;
        let k = c.k();
        self.within_reach(c, stress, w)?;
        Ok(Some(Meniscus {
            kelvin_radius_m: r_k,
            laplace_pressure_pa: stress,
            range_m: range,
            work_of_adhesion_j_m2: w,
            lambda: 2.0 * stress * (c.radius / (PI * w * k * k)).cbrt(),
        }))
    }
}

impl HumidityInput {
    /// Whether the solid's and the meniscus' stress numbers (in the units of the total w,
    /// docs/PHYSICS.md section 10) lie in the two-zone solver's domain; if not, one line naming
    /// the humidity's values and what to give instead.
    fn within_reach(&self, c: &Contact, stress: f64, w: f64) -> Result<(), ParamError> {
        use crate::solver::two_zone::{LAMBDA_MAX, LAMBDA_MIN};
        let short = crate::physics::domain::short;
        // lambda_i = 2 s_i (R / (pi w K^2))^(1/3), w the total work.
        let unit = 2.0 * (c.radius / (PI * (c.work + w) * c.k() * c.k())).cbrt();
        let (solid, liquid) = (c.s0 * unit, stress * unit);
        let inside = |l: f64| (LAMBDA_MIN..=LAMBDA_MAX).contains(&l);
        if inside(solid) && inside(liquid) {
            return Ok(());
        }
        let what = format!(
            "the meniscus (Kelvin radius {} m, Laplace pressure {} Pa) has the stress number {} beside the solid's {}, outside {LAMBDA_MIN:e}..{LAMBDA_MAX:e} where the two-zone law is solved",
            short(self.kelvin_radius()),
            short(stress),
            short(liquid),
            short(solid)
        );
        // Near saturation the Kelvin radius, and so the meniscus' stress, is what fails.
        let r_max = self.surface_tension() * unit / LAMBDA_MIN;
        let rh_max = (-self.surface_tension() * self.molar_volume()
            / (R_GAS * self.temperature() * r_max))
            .exp();
        // Shown rounded down in 1 - RH to two digits, so that the value shown is taken.
        let gap = 1.0 - rh_max;
        let step = 10f64.powf(gap.log10().floor() - 1.0);
        let digits = (-step.log10()).round().max(0.0) as usize;
        let shown = 1.0 - (gap / step).ceil() * step;
        // Name the humidity where a lower one gives a meniscus the solver takes, else the liquid.
        let lower_helps = shown > self.molecular_rh();
        Err(ParamError::Conflict(
            if liquid < LAMBDA_MIN && lower_helps && inside(solid) {
                Message::new().key("humidity.relative_humidity").text(format!(
                " = {:?}: {what}: give a relative humidity below {shown:.digits$} (the meniscus model fails already where its height nears a tenth of R)",
                self.relative_humidity,
            ))
            } else {
                format!(
                "humidity (relative humidity {:?}, contact angle {} deg, surface tension {} N/m, molar volume {} m^3/mol, temperature {} K): {what}: check the liquid's values and their units",
                self.relative_humidity,
                short(self.contact_angle_deg),
                short(self.surface_tension()),
                short(self.molar_volume()),
                short(self.temperature())
            ).into()
            },
        ))
    }
}

/// The contact of the solid plus the meniscus: the two-zone context and its units.
pub fn wet_context(c: &Contact, m: &Meniscus) -> Result<(TwoZoneContext, Units), ParamError> {
    let h0 = c.work / c.s0;
    let (zones, units) = dimensional_zones(
        c.k(),
        c.radius,
        [c.s0, m.laplace_pressure_pa],
        [h0, m.range_m],
    )
    .map_err(|e| {
        ParamError::Conflict(format!(
            "the meniscus (Laplace pressure {} Pa, height {} m) beside the solid (stress {} Pa, range {} m) is beyond the two-zone solver ({e}): check the humidity's values and the scene's units",
            crate::physics::domain::short(m.laplace_pressure_pa),
            crate::physics::domain::short(m.range_m),
            crate::physics::domain::short(c.s0),
            crate::physics::domain::short(h0)
        ).into())
    })?;
    let ctx = TwoZoneContext::new(zones).map_err(|_| {
        bad(
            "the stress numbers of solid and meniscus",
            zones.lambda[1],
            "in 1e-8..1e6 (check the units of E*, R, w and the force range)",
        )
    })?;
    Ok((ctx, units))
}

/// The meniscus as the two-zone cycle takes it: the stress ratio `s2/s1`, the range ratio
/// `h2/h1` (the solid's range `w/s0`), and the units of the total w (for a spring in N/m and the
/// energy lost in joules).
pub fn wet_ratios(c: &Contact, m: &Meniscus) -> Result<(f64, f64, Units), ParamError> {
    let (_, units) = wet_context(c, m)?;
    let (law, _) = crate::law::TwoZones::of_meniscus(
        c.lambda(),
        (c.s0, c.work),
        (m.laplace_pressure_pa, m.range_m),
    );
    Ok((law.stress_ratio, law.range_ratio, units))
}

/// One relative humidity of a sweep: the pull-offs (load control, N; tensile negative).
#[derive(Clone, Debug, Serialize)]
#[allow(non_snake_case)]
pub struct HumidityPoint {
    /// The relative humidity, 0..1.
    pub relative_humidity: f64,
    /// The Kelvin radius there (m).
    pub kelvin_radius_m: f64,
    /// The meniscus height 2 r_K cos(theta) (m).
    pub meniscus_range_m: f64,
    /// The meniscus zone's own Maugis parameter; null where no meniscus is counted (a Kelvin
    /// radius below one molecule: the dry contact, and the meniscus' pull-off 0).
    pub meniscus_lambda: Option<f64>,
    /// The dry contact (solid adhesion alone).
    pub pulloff_solid_N: f64,
    /// The meniscus alone (no solid adhesion).
    pub pulloff_meniscus_N: f64,
    /// Solid and meniscus together (the two-zone law).
    pub pulloff_total_N: f64,
    /// The fraction of the total pull-off that the meniscus adds, 1 - solid / total.
    pub meniscus_share: f64,
}

/// Pull-off against relative humidity for one scene.
#[derive(Clone, Debug, Serialize)]
pub struct HumiditySweep {
    /// The scene's name.
    pub name: String,
    /// The contact angle (degrees).
    pub contact_angle_deg: f64,
    /// The solid's work of adhesion (J/m^2).
    pub work_of_adhesion_solid_j_m2: f64,
    /// The meniscus' work of adhesion, 2 gamma cos(theta) (J/m^2).
    pub work_of_adhesion_meniscus_j_m2: f64,
    /// The pull-offs at each humidity.
    pub points: Vec<HumidityPoint>,
    /// The relative humidity above which the meniscus adds more than half of the pull-off
    /// (None where it never does in the range; the range's start where it always does).
    pub meniscus_dominates_above_rh: Option<f64>,
    /// The same, in words.
    pub meniscus_dominates: String,
    /// Where the continuum meniscus does not hold in the sweep ([`HumidityInput::limits`] at
    /// each point), one sentence each.
    pub warnings: Vec<String>,
}

/// Most points of a sweep.
pub const MAX_SWEEP_POINTS: usize = 10_000;

fn point_at(
    c: &Contact,
    base: &HumidityInput,
    rh: f64,
    dry: f64,
) -> Result<Option<HumidityPoint>, ParamError> {
    let h = HumidityInput {
        relative_humidity: rh,
        ..base.clone()
    };
    let Some(m) = h.meniscus(c)? else {
        if h.limits(c.radius) != [Limit::Molecular] {
            return Ok(None);
        }
        // Below one molecule: the dry contact, the Kelvin radius kept to show why.
        return Ok(Some(HumidityPoint {
            relative_humidity: rh,
            kelvin_radius_m: h.kelvin_radius(),
            meniscus_range_m: 0.0,
            meniscus_lambda: None,
            pulloff_solid_N: dry,
            pulloff_meniscus_N: 0.0,
            pulloff_total_N: dry,
            meniscus_share: 0.0,
        }));
    };
    let (ctx, u) = wet_context(c, &m)?;
    let alone = crate::solver::LambdaContext::new(m.lambda).map_err(|_| {
        bad(
            "the meniscus' Maugis parameter",
            m.lambda,
            "in 1e-8..1e8 (check the scene's units)",
        )
    })?;
    let total = ctx.load_pulloff.load * u.load;
    Ok(Some(HumidityPoint {
        relative_humidity: rh,
        kelvin_radius_m: m.kelvin_radius_m,
        meniscus_range_m: m.range_m,
        meniscus_lambda: Some(m.lambda),
        pulloff_solid_N: dry,
        pulloff_meniscus_N: alone.load_pulloff.load * PI * m.work_of_adhesion_j_m2 * c.radius,
        pulloff_total_N: total,
        meniscus_share: 1.0 - dry / total,
    }))
}

/// The pull-off of `c` against relative humidity, `n` points from `rh_min` to `rh_max`, with
/// the liquid of `base` (its relative humidity is ignored).
pub fn sweep(
    name: &str,
    c: &Contact,
    base: &HumidityInput,
    rh_min: f64,
    rh_max: f64,
    n: usize,
) -> Result<HumiditySweep, ParamError> {
    if !(rh_min.is_finite() && rh_min > 0.0 && rh_min < 1.0) {
        return Err(bad("rh_min", rh_min, "in (0, 1)"));
    }
    if !(rh_max.is_finite() && rh_max > rh_min && rh_max < 1.0) {
        return Err(ParamError::Conflict(
            Message::new()
                .key("rh_max")
                .text(format!(
                    " = {} is out of range: it must be above ",
                    crate::physics::domain::short(rh_max)
                ))
                .key("rh_min")
                .text(" and below 1"),
        ));
    }
    if !(2..=MAX_SWEEP_POINTS).contains(&n) {
        return Err(bad("points", n as f64, "in 2..10000"));
    }
    let dry_ctx = crate::solver::LambdaContext::new(c.lambda()).map_err(|_| {
        bad(
            "the Maugis parameter lambda of these inputs",
            c.lambda(),
            "in 1e-8..1e8, the solver's domain",
        )
    })?;
    let dry = dry_ctx.load_pulloff.load * c.force_scale();
    reach_at(c, base, rh_max)?;
    let mut points = Vec::with_capacity(n);
    for i in 0..n {
        let rh = rh_min + (rh_max - rh_min) * i as f64 / (n - 1) as f64;
        match point_at(c, base, rh, dry)? {
            Some(p) => points.push(p),
            None => {
                return Err(bad(
                    "humidity.contact_angle_deg",
                    base.contact_angle_deg,
                    "below 90 for a meniscus (at 90 or more water does not bridge the gap: the dry scene)",
                ))
            }
        }
    }
    let share = |rh: f64| -> Result<f64, ParamError> {
        Ok(point_at(c, base, rh, dry)?.map_or(0.0, |p| p.meniscus_share))
    };
    let (above, text) = dominance(&points, (rh_min, rh_max), &share)?;
    let w2 = points_w(base);
    let warnings = sweep_warnings(c, base, &points);
    Ok(HumiditySweep {
        name: name.to_string(),
        contact_angle_deg: base.contact_angle_deg,
        work_of_adhesion_solid_j_m2: c.work,
        work_of_adhesion_meniscus_j_m2: w2,
        points,
        meniscus_dominates_above_rh: above,
        meniscus_dominates: text,
        warnings,
    })
}

/// Where the meniscus adds more than half of the pull-off over a sweep's `points` (from
/// `rh_min` to `rh_max`): the humidity above which it does (its crossing refined by bisection on
/// `share`, the meniscus's share at a humidity) and the sentence that says so.
fn dominance(
    points: &[HumidityPoint],
    (rh_min, rh_max): (f64, f64),
    share: &dyn Fn(f64) -> Result<f64, ParamError>,
) -> Result<(Option<f64>, String), ParamError> {
    let first = &points[0];
    Ok(if first.meniscus_share > 0.5 {
        (
            Some(rh_min),
            format!(
                "the meniscus adds more than half of the pull-off at every RH from {:.0}%",
                100.0 * rh_min
            ),
        )
    } else if let Some(k) = points.iter().position(|p| p.meniscus_share > 0.5) {
        let (mut lo, mut hi) = (points[k - 1].relative_humidity, points[k].relative_humidity);
        for _ in 0..30 {
            let mid = 0.5 * (lo + hi);
            if share(mid)? > 0.5 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let rh = 0.5 * (lo + hi);
        (
            Some(rh),
            format!(
                "the meniscus adds more than half of the pull-off above RH = {:.1}%",
                100.0 * rh
            ),
        )
    } else {
        (
            None,
            format!(
                "the meniscus adds less than half of the pull-off at every RH up to {:.0}%",
                100.0 * rh_max
            ),
        )
    })
}

/// The meniscus at a sweep's largest humidity, where one beyond the solver's reach fails
/// first: refused naming `rh_max`.
fn reach_at(c: &Contact, base: &HumidityInput, rh_max: f64) -> Result<(), ParamError> {
    let top = HumidityInput {
        relative_humidity: rh_max,
        ..base.clone()
    };
    top.meniscus(c).map(|_| ()).map_err(|e| match e {
        ParamError::Conflict(m) => {
            ParamError::Conflict(m.rekey("humidity.relative_humidity", "rh_max"))
        }
        e => e,
    })
}

/// `tabor humidity` of a scene: the pull-off against relative humidity with the scene's liquid
/// and contact angle (`contact_angle_deg` replacing the scene's; water at 0 degrees where the
/// scene has no humidity), the liquid's values checked first. Every front end calls this.
pub fn sweep_scene(
    s: &super::SceneInput,
    contact_angle_deg: Option<f64>,
    rh_min: f64,
    rh_max: f64,
    n: usize,
) -> Result<HumiditySweep, ParamError> {
    let c = super::contact_of(s)?;
    let mut base = s
        .humidity
        .clone()
        .unwrap_or_else(|| HumidityInput::water(0.5, 0.0));
    if let Some(t) = contact_angle_deg {
        base.contact_angle_deg = t;
    }
    // The sweep replaces the scene's humidity; the liquid is checked at one inside (0, 1).
    base.relative_humidity = 0.5;
    base.validate()?;
    let name = s.name.clone().unwrap_or_else(|| "scene".into());
    sweep(&name, &c, &base, rh_min, rh_max, n)
}

/// The limits of the continuum meniscus over a sweep's points, one sentence per limit with
/// the points it applies to.
fn sweep_warnings(c: &Contact, base: &HumidityInput, points: &[HumidityPoint]) -> Vec<String> {
    let short = crate::physics::domain::short;
    let at = |p: &HumidityPoint| HumidityInput {
        relative_humidity: p.relative_humidity,
        ..base.clone()
    };
    let mut out = Vec::new();
    for limit in [Limit::Molecular, Limit::Flooding] {
        let hit: Vec<&HumidityPoint> = points
            .iter()
            .filter(|p| at(p).limits(c.radius).contains(&limit))
            .collect();
        let (Some(first), Some(last)) = (hit.first(), hit.last()) else {
            continue;
        };
        let span = format!(
            "{} of the {} points (RH = {} to {})",
            hit.len(),
            points.len(),
            short(first.relative_humidity),
            short(last.relative_humidity)
        );
        out.push(match limit {
            Limit::Molecular => format!(
                "below RH = {:.3} the Kelvin radius is below one molecule of the liquid ({:.3} nm): no continuum meniscus, so none is counted at {span} (the dry contact; docs/PHYSICS.md section 10)",
                base.molecular_rh(),
                base.molecule_size() * 1e9
            ),
            Limit::Flooding => format!(
                "the meniscus height 2 r_K cos(theta) exceeds {:.0}% of R (up to {:.0}%) at {span}: the thin-annulus model fails near saturation",
                100.0 * FLOODING,
                100.0 * last.meniscus_range_m / c.radius
            ),
        });
    }
    out
}

fn points_w(base: &HumidityInput) -> f64 {
    2.0 * base.surface_tension() * (base.contact_angle_deg * PI / 180.0).cos()
}
