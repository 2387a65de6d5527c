//! Axisymmetric tips (docs/PHYSICS.md section 12): a tip's profile, its Abel transform and the
//! Maugis-Dugdale gap integral over the zone, in the shape's normalised units; and the SI
//! description of a tip (sphere, power law, cone, pyramid, capped cone) with its units.

use super::measured::Profile;
use super::params::{check, ParamError};
use crate::error::Message;
use crate::numeric::legendre::{gauss_legendre, Order};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::sync::OnceLock;

/// A tip's shape in its normalised units (lengths in l, approaches in d; section 12).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "shape", rename_all = "snake_case")]
pub enum Shape {
    /// `fbar = r^n / k_n`, `Fbar = T^n` (the sphere is n = 2, the cone n = 1).
    Power {
        /// The exponent n >= 1.
        exponent: f64,
    },
    /// The exact spherical cap of radius rho (in l) joined tangentially to a cone of half-angle
    /// `half_angle` (radians) at `rho cos(half_angle)`.
    CappedCone {
        /// The cap's radius R / l.
        rho: f64,
        /// The cone's half-angle (radians, axis to flank).
        half_angle: f64,
    },
    /// A measured profile (section 12.3), in the units: interpolated, its tangent beyond its
    /// last point.
    Measured(MeasuredTip),
}

/// A measured profile in a tip's units: the table as given (held for the life of the process,
/// since a shape is `Copy`: one table of a few kilobytes per profile read) and the units its
/// radii and heights are divided by. The monotone cubic commutes with that scaling, so the
/// units of every E* and w a fit tries share the one table.
#[derive(Clone, Copy, Debug)]
pub struct MeasuredTip {
    /// The table, in its own length unit.
    table: &'static Profile,
    /// The radial unit l, in the table's unit.
    length: f64,
    /// The height (approach) unit d = F(l), in the table's unit.
    height: f64,
}

impl PartialEq for MeasuredTip {
    fn eq(&self, other: &MeasuredTip) -> bool {
        std::ptr::eq(self.table, other.table)
            && self.length == other.length
            && self.height == other.height
    }
}

impl Serialize for MeasuredTip {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut st = s.serialize_struct("MeasuredTip", 2)?;
        st.serialize_field("points", &self.points())?;
        st.serialize_field("largest_radius", &self.largest_radius())?;
        st.end()
    }
}

impl MeasuredTip {
    /// The radial unit l (the table's unit, metres for a scene's).
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The height unit d = F(l) (the table's unit).
    pub fn height(&self) -> f64 {
        self.height
    }

    /// The table's address: with l, the tip's identity.
    pub fn table_address(&self) -> u64 {
        self.table as *const Profile as u64
    }

    /// The table's points.
    pub fn points(&self) -> usize {
        self.table.points
    }

    /// The table's largest radius, in l.
    pub fn largest_radius(&self) -> f64 {
        self.table.largest_radius / self.length
    }

    /// `fbar(r) = f(r l) / d` and its slope.
    fn eval(&self, r: f64) -> (f64, f64) {
        let (f, d, _) = self.table.eval(r * self.length);
        (f / self.height, d * self.length / self.height)
    }

    /// `Fbar(T) = F(T l) / d` and its slope.
    fn abel(&self, t: f64) -> (f64, f64) {
        let (f, d) = self.table.abel(t * self.length);
        (f / self.height, d * self.length / self.height)
    }

    /// Sneddon's load integral in the units: `I(A l) / (l d)`.
    fn load_integral(&self, a: f64) -> f64 {
        self.table.load_integral(a * self.length) / (self.length * self.height)
    }

    /// [`Profile::error_between`] over the radii `lo..hi` (in l).
    pub fn error_between(&self, lo: f64, hi: f64) -> f64 {
        self.table.error_between(lo * self.length, hi * self.length)
    }

    /// The units of `table` for the reduced modulus `e_star` and the work of adhesion `w`
    /// (SI, the table in metres): l where `F(l)^2 / l = 3 pi w / (4 E*)`, `d = F(l)` (the power
    /// law's units for any profile: `F(l)^2 / l` rises, F growing at least like l for a convex
    /// tip). None where no l is found within 1e12 of the table's radii, or where the table is
    /// so far from convex there that `d ln F / d ln l <= 1/2`.
    pub fn of(table: &'static Profile, e_star: f64, w: f64) -> Option<MeasuredTip> {
        let target = 3.0 * PI * w / (4.0 * e_star);
        let excess = |l: f64| {
            let f = table.abel(l).0;
            f * f / l - target
        };
        let (mut lo, mut hi) = (table.largest_radius * 1e-12, table.largest_radius);
        while excess(hi) < 0.0 && hi < 1e12 * table.largest_radius {
            hi *= 4.0;
        }
        while excess(lo) > 0.0 && lo > 1e-300 {
            lo *= 1e-4;
        }
        if !(excess(lo) <= 0.0 && excess(hi) >= 0.0) {
            return None;
        }
        let m = MeasuredTip::at(table, crate::numeric::root::bisect_sign(excess, lo, hi));
        // A convex tip's F grows at least like l (g >= 1): below g = 1/2 the unit is not
        // unique and the units' slopes change sign (a plateau or a concave table).
        (m.log_slope() > 0.5).then_some(m)
    }

    /// `table` in the radial unit `length` (its height unit `F(length)`).
    pub fn at(table: &'static Profile, length: f64) -> MeasuredTip {
        MeasuredTip {
            table,
            length,
            height: table.abel(length).0,
        }
    }

    /// `g = d ln F / d ln l` at the unit l: the units move with `s = ln(w / E*)` as
    /// `d ln l / ds = 1 / (2g - 1)` (a power law's g is n).
    pub fn log_slope(&self) -> f64 {
        let (f, d) = self.table.abel(self.length);
        self.length * d / f
    }
}

/// The Gauss-Legendre rule every integral here uses, on [0, 1].
fn rule() -> &'static [(f64, f64)] {
    static RULE: OnceLock<Vec<(f64, f64)>> = OnceLock::new();
    RULE.get_or_init(|| gauss_legendre(64, Order::FromZero))
}

/// A shorter rule for the graded panels of [`accumulate_before`], each of which sees its
/// singular point half its width beyond its end (ellipse parameter 2.6: 24 nodes give ~1e-20).
fn panel_rule() -> &'static [(f64, f64)] {
    static RULE: OnceLock<Vec<(f64, f64)>> = OnceLock::new();
    RULE.get_or_init(|| gauss_legendre(24, Order::FromZero))
}

/// `k_n = n sqrt(pi) Gamma(n/2) / (2 Gamma((n+1)/2))`: the power law's `F = k_n B t^n`.
pub fn k_n(n: f64) -> f64 {
    n * PI.sqrt() * libm::tgamma(n / 2.0) / (2.0 * libm::tgamma((n + 1.0) / 2.0))
}

impl Shape {
    /// The shape's name (a figure's title).
    pub fn name(&self) -> &'static str {
        match *self {
            Shape::Power { exponent: 1.0 } => "a cone",
            Shape::Power { exponent: 2.0 } => "a sphere",
            Shape::Power { .. } => "a power-law tip",
            Shape::CappedCone { .. } => "a capped cone",
            Shape::Measured(_) => "a measured tip",
        }
    }

    /// The shape with its numbers, in the tip's units (a state's or a profile's heading).
    pub fn label(&self) -> String {
        match *self {
            Shape::Power { exponent: 1.0 } => "a cone".into(),
            Shape::Power { exponent } => format!("the power law f = B r^{exponent}"),
            Shape::CappedCone { rho, half_angle } => format!(
                "a capped cone (cap radius {rho} l, half-angle {} degrees)",
                half_angle.to_degrees()
            ),
            Shape::Measured(p) => format!(
                "a measured profile ({} points to r = {:.4} l)",
                p.points(),
                p.largest_radius()
            ),
        }
    }

    /// The shape in a sentence (a figure's caption).
    pub fn describe(&self) -> String {
        match *self {
            Shape::Power { exponent: 1.0 } => {
                "A cone f = r cot α; its map holds for every half-angle α (its units absorb cot α)".into()
            }
            Shape::Power { exponent } => format!(
                "A power-law tip f = B r^{exponent}; its map holds for every B (its units absorb it)"
            ),
            Shape::CappedCone { rho, half_angle } => format!(
                "A spherical cap of radius R = {rho:.3} l joined to a cone of half-angle {:.1}°",
                half_angle.to_degrees()
            ),
            Shape::Measured(p) => format!(
                "A measured profile of {} points to r = {:.3} l, continued by its tangent",
                p.points(),
                p.largest_radius()
            ),
        }
    }

    /// The joint of a capped cone (`rho cos theta`), where the integrals are split.
    fn joint(&self) -> Option<f64> {
        match *self {
            Shape::Power { .. } | Shape::Measured(_) => None,
            Shape::CappedCone { rho, half_angle } => Some(rho * half_angle.cos()),
        }
    }

    /// The undeformed gap `fbar(r)` and its slope.
    pub fn profile(&self, r: f64) -> (f64, f64) {
        match *self {
            Shape::Power { exponent: n } => {
                let k = k_n(n);
                (r.powf(n) / k, n * r.powf(n - 1.0) / k)
            }
            Shape::CappedCone { rho, half_angle } => {
                let b = rho * half_angle.cos();
                if r <= b {
                    let q = (1.0 - (r / rho).powi(2)).sqrt();
                    (r * r / (1.0 + q), r / q)
                } else {
                    let cot = 1.0 / half_angle.tan();
                    (
                        rho * rho + rho * r * cot - rho * rho / half_angle.sin(),
                        rho * cot,
                    )
                }
            }
            Shape::Measured(p) => p.eval(r),
        }
    }

    /// The Abel transform `Fbar(T)` (the adhesion-free approach at contact radius T) and its
    /// slope.
    pub fn abel(&self, t: f64) -> (f64, f64) {
        match *self {
            Shape::Power { exponent: n } => (t.powf(n), n * t.powf(n - 1.0)),
            Shape::CappedCone { rho, half_angle } => {
                let b = rho * half_angle.cos();
                let x = t / rho;
                if t <= b {
                    let at = x.atanh();
                    (rho * t * at, rho * at + t / ((1.0 - x) * (1.0 + x)))
                } else {
                    let (sin, cos) = half_angle.sin_cos();
                    let cot = cos / sin;
                    let s = ((t - b) * (t + b)).sqrt();
                    // acos(b/t) as atan(s/b): no loss of precision as t -> b.
                    let g = ((rho + t) / (s + rho * sin)).ln() + cot * (s / b).atan();
                    // The 1/s terms of the two logarithms' slopes cancel (section 12.2).
                    let slope =
                        g + t / (rho + t) + (rho * cos * cos - s * sin) / (sin * (s + rho * sin));
                    (rho * t * g, rho * slope)
                }
            }
            Shape::Measured(p) => p.abel(t),
        }
    }

    /// `Qbar(A) = (3/2) int_0^A T Fbar'(T) dT`, the adhesion-free load, and its slope.
    pub fn load(&self, a: f64) -> (f64, f64) {
        let slope = 1.5 * a * self.abel(a).1;
        match *self {
            Shape::Power { exponent: n } => (1.5 * n / (n + 1.0) * a.powf(n + 1.0), slope),
            Shape::CappedCone { .. } => {
                let b = self.joint().unwrap_or(f64::INFINITY);
                let g = |t: f64| t * self.abel(t).1;
                let mut q = integrate(&g, 0.0, a.min(b), Ends::Smooth);
                if a > b {
                    q += integrate(&g, b, a, Ends::SqrtAtLo);
                }
                (1.5 * q, slope)
            }
            // Sneddon's load: (3/2) int_0^A T Fbar'(T) dT = (3/2) int_0^A r^2 fbar'(r) dr /
            // sqrt(A^2 - r^2) (the identity holds term by term for every power r^n).
            Shape::Measured(p) => (1.5 * p.load_integral(a), slope),
        }
    }

    /// The gap integral `Jbar(A, mu) = int_0^(atan mu) (Fbar(m A cos phi) - Fbar(A)) dphi` of
    /// equation (1t) with its slopes in A and in mu.
    pub fn gap(&self, a: f64, mu: f64) -> (f64, f64, f64) {
        let m = mu.hypot(1.0);
        let phi1 = mu.atan();
        match *self {
            Shape::Power { exponent: n } => {
                let (j, i) = power_gap(n, mu, m, phi1);
                let an = a.powf(n);
                (
                    an * j,
                    n * an / a * j,
                    an * n * m.powf(n - 1.0) * i * mu / m,
                )
            }
            Shape::CappedCone { .. } | Shape::Measured(_) => {
                let c = m * a;
                let (fa, fa_d) = self.abel(a);
                // Integrand triples (Jbar, dJbar/dA, the integral behind dJbar/dmu) at phi.
                let at = |phi: f64| {
                    let (cos, t) = (phi.cos(), c * phi.cos());
                    let (f, d) = self.abel(t);
                    [f - fa, d * m * cos - fa_d, d * cos]
                };
                let mut sum = [0.0; 3];
                match self.joint() {
                    // The joint inside the zone: the cone side [0, phi_b] has T - b ~ (phi_b - phi).
                    Some(b) if a < b && b < c => {
                        let phi_b = (b / c).acos();
                        accumulate(&at, 0.0, phi_b, Ends::SqrtAtHi, &mut sum);
                        accumulate(&at, phi_b, phi1, Ends::Smooth, &mut sum);
                    }
                    // The joint inside the contact: the integrand (on the cone, T > A) has its
                    // branch point T = b just beyond phi1, at phi_b = acos(b/C).
                    Some(b) if b <= a => {
                        let beyond = (b / c).acos() - phi1;
                        accumulate_before(&at, 0.0, phi1, beyond, &mut sum)
                    }
                    // The zone on the cap: the sphere's F, analytic on [A, C].
                    _ => accumulate(&at, 0.0, phi1, Ends::Smooth, &mut sum),
                }
                (sum[0], sum[1], a * mu / m * sum[2])
            }
        }
    }
}

impl Shape {
    /// The adhesion-free (Hertz-type) pressure at radius `r` of a contact of radius `a`,
    /// `(3/(4 pi)) int_r^A Fbar'(T) dT / sqrt(T^2 - r^2)` in section 8's pressure unit (the
    /// non-singular punch pressure of Sneddon's solution), taken in `u = sqrt(T^2 - r^2)`;
    /// None at a cone's apex, where it is logarithmically infinite.
    pub fn hertz_pressure(&self, a: f64, r: f64) -> Option<f64> {
        if r >= a {
            return Some(0.0);
        }
        let big_u = ((a - r) * (a + r)).sqrt();
        let g = |u: f64| {
            let t = r.hypot(u);
            self.abel(t).1 / t
        };
        let integral = match *self {
            Shape::Power { exponent: n } if r == 0.0 => {
                // `int_0^A n u^(n-2) du`, infinite for the cone.
                if n <= 1.0 {
                    return None;
                }
                n / (n - 1.0) * a.powf(n - 1.0)
            }
            // T^(n-2) changes on the scale r near u = 0: [0, r] directly, beyond in ln u.
            Shape::Power { .. } if r < big_u => {
                integrate(&g, 0.0, r, Ends::Smooth)
                    + integrate(
                        &|x: f64| g(x.exp()) * x.exp(),
                        r.ln(),
                        big_u.ln(),
                        Ends::Smooth,
                    )
            }
            Shape::Power { .. } => integrate(&g, 0.0, big_u, Ends::Smooth),
            // The cone side's slope has a square-root kink at the joint.
            Shape::CappedCone { .. } | Shape::Measured(_) => match self.joint() {
                Some(b) if r < b && b < a => {
                    let ub = ((b - r) * (b + r)).sqrt();
                    integrate(&g, 0.0, ub, Ends::Smooth) + integrate(&g, ub, big_u, Ends::SqrtAtLo)
                }
                _ => integrate(&g, 0.0, big_u, Ends::Smooth),
            },
        };
        Some(0.75 / PI * integral)
    }

    /// The adhesion-free gap outside a contact of radius `a` at `r > a`,
    /// `(2/pi) int_A^r (Fbar(T) - Fbar(A)) dT / sqrt(r^2 - T^2)` in the approach unit: the
    /// integral of equation (1t) with r for C.
    pub fn hertz_gap(&self, a: f64, r: f64) -> f64 {
        if r <= a {
            return 0.0;
        }
        let mu = ((r - a) * (r + a)).sqrt() / a;
        2.0 / PI * self.gap(a, mu).0
    }
}

/// `J_n(mu)` and `int_0^phi1 cos^n phi dphi` for the power law, without cancellation as
/// mu -> 0 (section 12.1).
fn power_gap(n: f64, mu: f64, m: f64, phi1: f64) -> (f64, f64) {
    if n == 1.0 {
        cone_gap(mu, m, phi1)
    } else {
        power_gap_by_rule(n, m, phi1)
    }
}

/// [`power_gap`] by the Gauss-Legendre rule.
fn power_gap_by_rule(n: f64, m: f64, phi1: f64) -> (f64, f64) {
    let (mut j, mut i) = (0.0, 0.0);
    for &(s, w) in rule() {
        let phi = phi1 * s;
        let e = 2.0 * m * (0.5 * (phi1 + phi)).sin() * (0.5 * (phi1 - phi)).sin();
        j += w * (n * e.ln_1p()).exp_m1();
        i += w * phi.cos().powf(n);
    }
    (j * phi1, i * phi1)
}

/// The cone's (n = 1) [`power_gap`] in closed form: `J_1 = mu - atan mu` (its series where
/// the difference cancels, mu <= 1/2: within about 4 ulp everywhere, against 50-digit
/// arithmetic) and `sin phi1 = mu / m`. The
/// fits evaluate a tip's states thousands of times; the quadrature's 64 sines and exponentials
/// per root-search step dominated a cone's.
fn cone_gap(mu: f64, m: f64, phi1: f64) -> (f64, f64) {
    let j = if mu <= 0.5 {
        // mu^3/3 - mu^5/5 + ...: 25 terms reach 0.25^24 / 51 < 1e-16 of the first.
        let mu2 = mu * mu;
        let mut term = mu * mu2;
        let mut sum = 0.0;
        for k in 1..=25 {
            let sign = if k % 2 == 1 { 1.0 } else { -1.0 };
            sum += sign * term / (2 * k + 1) as f64;
            term *= mu2;
        }
        sum
    } else {
        mu - phi1
    };
    (j, mu / m)
}

/// Where an integrand goes like the square root of the distance to an end of its range.
#[derive(Clone, Copy)]
enum Ends {
    /// Smooth at both ends: t = lo + (hi - lo) s.
    Smooth,
    /// Like sqrt(t - lo) near lo: t = lo + (hi - lo) s^2.
    SqrtAtLo,
    /// Like sqrt(hi - t) near hi: t = hi - (hi - lo) s^2.
    SqrtAtHi,
}

/// Adds `int_lo^hi g` (N integrands at once) to `sum`, by the rule after the substitution that
/// makes the integrand smooth at its ends.
fn accumulate<const N: usize>(
    g: &dyn Fn(f64) -> [f64; N],
    lo: f64,
    hi: f64,
    ends: Ends,
    sum: &mut [f64; N],
) {
    accumulate_by(rule(), g, lo, hi, ends, sum)
}

/// [`accumulate`] by a given rule on [0, 1].
fn accumulate_by<const N: usize>(
    rule: &[(f64, f64)],
    g: &dyn Fn(f64) -> [f64; N],
    lo: f64,
    hi: f64,
    ends: Ends,
    sum: &mut [f64; N],
) {
    let h = hi - lo;
    for &(s, w) in rule {
        let (v, scale) = match ends {
            Ends::Smooth => (g(lo + h * s), h),
            Ends::SqrtAtLo => (g(lo + h * s * s), 2.0 * s * h),
            Ends::SqrtAtHi => (g(hi - h * s * s), 2.0 * s * h),
        };
        for k in 0..N {
            sum[k] += w * v[k] * scale;
        }
    }
}

/// Adds `int_lo^hi g` to `sum` where g is singular a distance `beyond` past `hi`: on panels
/// growing geometrically from `hi`, each four times as wide as its distance from the singular
/// point, so that the rule converges on each as on a smooth integrand.
fn accumulate_before<const N: usize>(
    g: &dyn Fn(f64) -> [f64; N],
    lo: f64,
    hi: f64,
    beyond: f64,
    sum: &mut [f64; N],
) {
    // (At least 1e-15 of the range: the panels must shrink no further than rounding.)
    let (mut right, mut dist) = (hi, beyond.max(1e-15 * (hi - lo)));
    if 4.0 * dist >= hi - lo {
        return accumulate(g, lo, hi, Ends::Smooth, sum);
    }
    while right > lo {
        let left = (right - 4.0 * dist).max(lo);
        accumulate_by(panel_rule(), g, left, right, Ends::Smooth, sum);
        dist += right - left;
        right = left;
    }
}

/// `int_lo^hi g` for one integrand.
fn integrate(g: &dyn Fn(f64) -> f64, lo: f64, hi: f64, ends: Ends) -> f64 {
    let mut sum = [0.0];
    accumulate(&|t| [g(t)], lo, hi, ends, &mut sum);
    sum[0]
}

/// The radius where `q(A)` rises through `target` above `from`, by bisection (q increasing).
fn rising_root(q: impl Fn(f64) -> f64, target: f64, from: f64) -> f64 {
    let mut hi = from.max(1e-300) * 2.0 + 1.0;
    while q(hi) < target {
        hi *= 2.0;
        if hi > 1e150 {
            return f64::NAN;
        }
    }
    crate::numeric::root::bisect_sign(|a| q(a) - target, from, hi)
}

impl Shape {
    /// The rigid tip's Dugdale force `(pi lambda/2) C0^2`, `fbar(C0) = 2/(pi lambda)`: the
    /// tension over the disc where the undeformed gap is below h0 (the sphere's 2).
    pub fn rigid_force(&self, lambda: f64) -> f64 {
        let c0 = rising_root(|c| self.profile(c).0, 2.0 / (PI * lambda), 0.0);
        PI * lambda / 2.0 * c0 * c0
    }

    /// The JKR-type law's contact radius at its load-controlled pull-off: where its slope
    /// `(3/2)(A Fbar'(A) - sqrt(6 A))` turns positive (bisection).
    pub fn jkr_pulloff_radius(&self) -> f64 {
        let slope = |a: f64| self.abel(a).1 * a - (6.0 * a).sqrt();
        let mut hi = 1.0;
        while slope(hi) < 0.0 && hi < 1e150 {
            hi *= 2.0;
        }
        crate::numeric::root::bisect_sign(slope, 0.0, hi)
    }

    /// The closed forms' radii at load `p` for the shape: Sneddon's punch, the DMT-type (the
    /// punch under `p` plus the rigid tip's force `f0`) and the JKR-type on its stable side
    /// (NaN where the form has no contact).
    pub fn closed_radii(&self, p: f64, f0: f64) -> [f64; 3] {
        let shape = self;
        let q = |a: f64| shape.load(a).0;
        let hertz = if p > 0.0 {
            rising_root(q, p, 0.0)
        } else {
            f64::NAN
        };
        let dmt = if p + f0 > 0.0 {
            rising_root(q, p + f0, 0.0)
        } else {
            f64::NAN
        };
        // JKR-type: Qbar(A) - sqrt(6 A^3), stable from its load-controlled pull-off up.
        let jkr_load = |a: f64| q(a) - (6.0 * a * a * a).sqrt();
        let a_c = shape.jkr_pulloff_radius();
        let jkr = if p >= jkr_load(a_c) {
            rising_root(jkr_load, p, a_c)
        } else {
            f64::NAN
        };
        [hertz, dmt, jkr]
    }
}

/// A shape as the command line and Python give it, in its normalised units: `cone`, `sphere`,
/// `power:N` or `capped-cone:R_OVER_L:HALF_ANGLE_DEG` (the cap's radius in the length unit l).
impl std::str::FromStr for Shape {
    type Err = Message;

    fn from_str(s: &str) -> Result<Shape, Message> {
        let usage = "give cone, sphere, power:N or capped-cone:R_OVER_L:HALF_ANGLE_DEG";
        let tip = |rest: String| Message::new().key("tip").text(format!(" {s}: {rest}"));
        let num = |p: &str, what: &str| -> Result<f64, Message> {
            p.parse::<f64>()
                .map_err(|_| tip(format!("{what} {p:?} is not a number; {usage}")))
        };
        let parts: Vec<&str> = s.split(':').collect();
        match parts.as_slice() {
            ["cone"] => Ok(Shape::Power { exponent: 1.0 }),
            ["sphere"] => Ok(Shape::Power { exponent: 2.0 }),
            ["power", n] => {
                let n = num(n, "the exponent")?;
                if !(1.0..=8.0).contains(&n) {
                    return Err(tip(format!(
                        "the exponent {n} is out of range: give one from 1 (a cone) to 8"
                    )));
                }
                Ok(Shape::Power { exponent: n })
            }
            ["capped-cone", rho, deg] => {
                let (rho, deg) = (num(rho, "the cap's radius")?, num(deg, "the half-angle")?);
                if !(rho > 0.0 && rho.is_finite() && deg > 0.0 && deg < 90.0) {
                    return Err(tip("give a positive cap radius (in l) and a half-angle between 0 and 90 degrees".into()));
                }
                Ok(Shape::CappedCone {
                    rho,
                    half_angle: deg.to_radians(),
                })
            }
            _ => Err(tip(usage.into())),
        }
    }
}

/// A tip in SI units as the command line gives it: `sphere:R_M`, `cone:HALF_ANGLE_DEG`,
/// `pyramid:FACES:FACE_ANGLE_DEG`, `power:N:B` (B in m^(1-n)), `capped-cone:R_M:HALF_ANGLE_DEG`,
/// or a scene's `"tip"` object as JSON. Its numbers are checked where it is used
/// ([`TipInput::units`]).
impl std::str::FromStr for TipInput {
    type Err = Message;

    fn from_str(s: &str) -> Result<TipInput, Message> {
        let tip = |rest: String| Message::new().key("tip").text(format!(" {s}: {rest}"));
        if s.trim_start().starts_with('{') {
            return serde_json::from_str(s).map_err(|e| tip(e.to_string()));
        }
        let usage = "give sphere:R_M, cone:HALF_ANGLE_DEG, pyramid:FACES:FACE_ANGLE_DEG, power:N:B, capped-cone:R_M:HALF_ANGLE_DEG or a scene's tip object as JSON";
        let num = |p: &str, what: &str| -> Result<f64, Message> {
            p.parse::<f64>()
                .map_err(|_| tip(format!("{what} {p:?} is not a number; {usage}")))
        };
        let parts: Vec<&str> = s.split(':').collect();
        Ok(match parts.as_slice() {
            ["sphere", r] => TipInput::Sphere {
                radius_m: num(r, "the radius")?,
            },
            ["cone", deg] => TipInput::Cone {
                half_angle_deg: num(deg, "the half-angle")?,
            },
            ["pyramid", faces, deg] => TipInput::Pyramid {
                faces: faces.parse().map_err(|_| {
                    tip(format!(
                        "the number of faces {faces:?} is not a whole number; {usage}"
                    ))
                })?,
                face_angle_deg: num(deg, "the face angle")?,
            },
            ["power", n, b] => TipInput::Power {
                exponent: num(n, "the exponent")?,
                coefficient: num(b, "the coefficient B")?,
            },
            ["capped-cone", r, deg] => TipInput::CappedCone {
                radius_m: num(r, "the cap's radius")?,
                half_angle_deg: num(deg, "the half-angle")?,
            },
            _ => return Err(tip(usage.into())),
        })
    }
}

/// A tip in SI units, as a scene gives it.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum TipInput {
    /// A sphere (its paraboloid), as `radius_m` gives it.
    Sphere {
        /// The radius (m).
        radius_m: f64,
    },
    /// `f = B r^n`.
    Power {
        /// The exponent n >= 1.
        exponent: f64,
        /// B (m^(1-n)).
        coefficient: f64,
    },
    /// A cone of half-angle alpha (axis to flank): `f = r cot(alpha)`.
    Cone {
        /// The half-angle (degrees).
        half_angle_deg: f64,
    },
    /// A regular pyramid of `faces` faces, each at `face_angle_deg` to the axis, as the cone of
    /// the same area function (section 12.1): an approximation.
    Pyramid {
        /// The number of faces (3: Berkovich; 4: a four-sided pyramid).
        faces: u32,
        /// The angle between the axis and each face's centre line (degrees).
        face_angle_deg: f64,
    },
    /// A spherical cap of radius R joined tangentially to a cone of half-angle theta.
    CappedCone {
        /// The cap's radius (m).
        radius_m: f64,
        /// The cone's half-angle (degrees).
        half_angle_deg: f64,
    },
    /// A measured profile (SEM, blind tip reconstruction): the height `z_m` above the apex at
    /// each radius `r_m` (m), from the axis outwards; interpolated by the monotone cubic and
    /// continued by its tangent beyond the last point (section 12.3).
    Profile {
        /// The radii (m), from 0 rising.
        r_m: Vec<f64>,
        /// The heights (m), never falling.
        z_m: Vec<f64>,
    },
}

/// A tip's normalised units for a material pair: the shape in them, the radial length l (m),
/// the approach unit d (m), the force unit `pi w l^2 / d` (N) and the Maugis parameter.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TipUnits {
    /// The shape in the normalised units.
    pub shape: Shape,
    /// The radial length l (m).
    pub length_m: f64,
    /// The approach unit d (m).
    pub approach_m: f64,
    /// The force unit `pi w l^2 / d` (N).
    pub force_n: f64,
    /// The Maugis parameter `(3/2) s0 l / (E* d)`.
    pub lambda: f64,
}

/// A half-angle in degrees, checked (axis to flank, between 0 and 90).
fn half_angle(field: &'static str, deg: f64) -> Result<f64, ParamError> {
    check(
        field,
        deg,
        deg > 0.0 && deg < 90.0,
        "between 0 and 90 degrees (axis to flank)",
    )
}

/// A radius in metres, checked.
fn radius(radius_m: f64) -> Result<f64, ParamError> {
    check("radius_m", radius_m, radius_m > 0.0, "positive (m)")
}

impl TipInput {
    /// The power law `(n, B)` the tip is (a sphere's paraboloid, a cone, a pyramid's
    /// equivalent cone), None for a capped cone or a measured profile; its numbers checked.
    pub fn power(&self) -> Result<Option<(f64, f64)>, ParamError> {
        Ok(match *self {
            TipInput::Sphere { radius_m } => Some((2.0, 0.5 / radius(radius_m)?)),
            TipInput::Power {
                exponent,
                coefficient,
            } => {
                let n = check(
                    "exponent",
                    exponent,
                    (1.0..=8.0).contains(&exponent),
                    "from 1 (a cone) to 8",
                )?;
                let b = check(
                    "coefficient",
                    coefficient,
                    coefficient > 0.0,
                    "positive (B in m^(1-n))",
                )?;
                Some((n, b))
            }
            TipInput::Cone { half_angle_deg } => Some((
                1.0,
                1.0 / half_angle("half_angle_deg", half_angle_deg)?
                    .to_radians()
                    .tan(),
            )),
            TipInput::Pyramid {
                faces,
                face_angle_deg,
            } => {
                let n = check(
                    "faces",
                    faces as f64,
                    (3..=64).contains(&faces),
                    "from 3 (Berkovich) to 64",
                )?;
                let tan = half_angle("face_angle_deg", face_angle_deg)?
                    .to_radians()
                    .tan()
                    * (n * (PI / n).tan() / PI).sqrt();
                Some((1.0, 1.0 / tan))
            }
            TipInput::CappedCone { .. } | TipInput::Profile { .. } => None,
        })
    }

    /// Where the tip's idealisation is stretched, in words: a flank too steep for Sneddon's
    /// half-space theory, a pyramid solved as its equivalent cone. A scene and a fit say them.
    pub fn warnings(&self) -> Vec<String> {
        let mut w = Vec::new();
        let half_angle = match *self {
            TipInput::Cone { half_angle_deg } | TipInput::CappedCone { half_angle_deg, .. } => {
                Some(half_angle_deg)
            }
            TipInput::Pyramid { .. } => self.equivalent_cone_deg(),
            _ => None,
        };
        if let Some(a) = half_angle.filter(|&a| a < 60.0) {
            w.push(format!(
                "the flank's slope cot({a:.1} deg) = {:.2} is not small: Sneddon's half-space theory, which this law rests on, is an approximation for so sharp a tip",
                1.0 / a.to_radians().tan()
            ));
        }
        if let TipInput::Pyramid { faces, .. } = self {
            w.push(format!(
                "a {faces}-sided pyramid is solved as the cone of the same area function (half-angle {:.2} deg): its contact is not a circle",
                self.equivalent_cone_deg().unwrap_or(f64::NAN)
            ));
        }
        w
    }

    /// The half-angle of the cone a pyramid is solved as (degrees), where the tip is one.
    pub fn equivalent_cone_deg(&self) -> Option<f64> {
        match self {
            TipInput::Pyramid { .. } => self
                .power()
                .ok()
                .flatten()
                .map(|(_, b)| (1.0 / b).atan().to_degrees()),
            _ => None,
        }
    }

    /// The tip's units for the reduced modulus `e_star`, the work of adhesion `w` and the
    /// Dugdale stress `s0` (SI; checked by the caller).
    pub fn units(&self, e_star: f64, w: f64, s0: f64) -> Result<TipUnits, ParamError> {
        let (shape, l, d) = match (self.power()?, self) {
            (Some((n, b)), _) => {
                let kb = k_n(n) * b;
                let l = (3.0 * PI * w / (4.0 * e_star * kb * kb)).powf(1.0 / (2.0 * n - 1.0));
                (Shape::Power { exponent: n }, l, kb * l.powf(n))
            }
            (
                None,
                &TipInput::CappedCone {
                    radius_m,
                    half_angle_deg,
                },
            ) => {
                let r = radius(radius_m)?;
                let theta = half_angle("half_angle_deg", half_angle_deg)?.to_radians();
                let l = (3.0 * PI * w * r * r / (4.0 * e_star)).cbrt();
                (
                    Shape::CappedCone {
                        rho: r / l,
                        half_angle: theta,
                    },
                    l,
                    l * l / r,
                )
            }
            (None, TipInput::Profile { r_m, z_m }) => {
                let p = Profile::interned(r_m, z_m)
                    .map_err(|e| ParamError::Conflict(format!("tip: {e}").into()))?;
                let m = MeasuredTip::of(p, e_star, w).ok_or_else(|| {
                    ParamError::Conflict(format!(
                        "tip: the measured profile's length unit was not found (E* = {e_star} Pa, w = {w} J/m^2): check the units of r_m and z_m (metres), and that the tip is convex (its table neither flat nor concave over the contact)"
                    ).into())
                })?;
                (Shape::Measured(m), m.length, m.height)
            }
            (None, _) => unreachable!("every other tip is a power law"),
        };
        Ok(TipUnits {
            shape,
            length_m: l,
            approach_m: d,
            force_n: PI * w * l * l / d,
            lambda: 1.5 * s0 * l / (e_star * d),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// For the sphere's shape the closed radii are section 3's: Hertz A^3 = P, DMT A^3 = P + 2,
    /// JKR A^3 = P + 3 + sqrt(9 + 6 P), and the rigid force is 2.
    #[test]
    fn closed_radii_of_the_square_power_law_are_the_spheres() {
        let shape = Shape::Power { exponent: 2.0 };
        assert!((shape.rigid_force(0.3) - 2.0).abs() < 1e-14);
        for p in [0.5, 2.0, 10.0] {
            let [h, d, j] = shape.closed_radii(p, 2.0);
            assert!((h - p.cbrt()).abs() < 1e-12);
            assert!((d - (p + 2.0).cbrt()).abs() < 1e-12);
            assert!((j - (p + 3.0 + (9.0 + 6.0 * p).sqrt()).cbrt()).abs() < 1e-12);
        }
    }

    /// The cone's closed form is the rule's value, to a few ulp, from the JKR end (mu -> 0,
    /// where mu - atan mu cancels) to the DMT end.
    #[test]
    fn the_cones_gap_in_closed_form_is_the_rules() {
        for k in -60..=40 {
            let mu = 10f64.powf(k as f64 / 10.0);
            let (m, phi1) = (mu.hypot(1.0), mu.atan());
            let (j, i) = cone_gap(mu, m, phi1);
            let (jr, ir) = power_gap_by_rule(1.0, m, phi1);
            assert!((j / jr - 1.0).abs() < 4e-15, "mu {mu}: {j} {jr}");
            assert!((i / ir - 1.0).abs() < 4e-15, "mu {mu}: {i} {ir}");
        }
    }

    #[test]
    fn k_n_is_the_gamma_ratio() {
        // k_3 = 3 pi/4, k_4 = 8/3, k_1.5 from Gamma(0.75)/Gamma(1.25).
        assert!((k_n(3.0) - 0.75 * PI).abs() < 1e-14);
        assert!((k_n(4.0) - 8.0 / 3.0).abs() < 1e-14);
        let g075 = 1.225_416_702_465_177_6_f64;
        let g125 = 0.906_402_477_055_477_f64;
        assert!((k_n(1.5) - 1.5 * PI.sqrt() * g075 / (2.0 * g125)).abs() < 1e-13);
    }

    #[test]
    fn capped_cone_abel_is_continuous_and_its_slope_the_difference() {
        let s = Shape::CappedCone {
            rho: 3.0,
            half_angle: 20f64.to_radians(),
        };
        let b = 3.0 * 20f64.to_radians().cos();
        // The cap's formula at b against the cone's just beyond: F to rounding, F' to its
        // sqrt(t - b) change over 1e-14 b.
        let (below, above) = (s.abel(b), s.abel(b * (1.0 + 1e-14)));
        assert!(
            (below.0 - above.0).abs() < 1e-11 * below.0 && (below.1 - above.1).abs() < 1e-4,
            "{below:?} {above:?}"
        );
        for t in [0.5, 2.0, 2.9, 4.0, 9.0] {
            let h = 1e-6;
            let diff = (s.abel(t + h).0 - s.abel(t - h).0) / (2.0 * h);
            assert!((diff - s.abel(t).1).abs() < 1e-7 * diff.abs(), "at {t}");
        }
    }
}
