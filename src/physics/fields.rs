//! Inside the contact: the pressure distribution and the surface gap of a Maugis-Dugdale state
//! and of the closed-form models, in the Johnson-Greenwood units (docs/PHYSICS.md section 8).
//!
//! Units: radii in `(pi w R^2 / K)^(1/3)` (so the contact radius is A and the cohesive zone ends
//! at C = m A), pressure (compressive positive) in `(pi w K^2 / R)^(1/3)` (so that
//! `Pbar = 2 pi integral p r dr` and the Dugdale stress is lambda/2), gap in the approach unit
//! `(pi^2 w^2 R / K^2)^(1/3)` (so that the gap at r = C is the Dugdale range 2/(pi lambda)).
//!
//! Maugis (1992) superposes the Hertz pressure of radius A and an adhesive stress: -lambda/2 on
//! A < r < C, and inside the contact `-lambda/2 + (lambda/pi) atan(sqrt((A^2 - r^2)/(C^2 - A^2)))`,
//! which keeps the stress bounded at r = A. That inner correction is a sum of flat punches of
//! radius s < A with loads `8 (lambda/2) s^2 ds / sqrt(C^2 - s^2)` (an Abel transform), which
//! gives its displacement outside the contact; the uniform stress on the disc r < C is the same
//! sum over s < C (see [`MdGeometry::gap`]).

use super::real::Real;
use crate::numeric::legendre::{self, Order};
use std::f64::consts::PI;
use std::sync::OnceLock;

/// The 96-point Gauss-Legendre rule on [0, 1].
fn gauss_legendre() -> &'static [(f64, f64)] {
    static RULE: OnceLock<Vec<(f64, f64)>> = OnceLock::new();
    RULE.get_or_init(|| legendre::gauss_legendre(96, Order::FromOne))
}

/// The integral of `f` over [0, 1] to about machine precision for smooth `f`.
pub fn integrate01(f: impl Fn(f64) -> f64) -> f64 {
    gauss_legendre().iter().map(|&(x, w)| w * f(x)).sum()
}

/// A Maugis-Dugdale state's geometry: lambda, the contact radius A and mu = sqrt(m^2 - 1).
#[derive(Clone, Copy, Debug)]
pub struct MdGeometry {
    /// The Maugis parameter.
    pub lambda: f64,
    /// Contact radius A.
    pub a: f64,
    /// `mu = sqrt(m^2 - 1)`, m = C/A the Dugdale zone's outer radius over A.
    pub mu: f64,
}

impl MdGeometry {
    /// C = m A, the outer radius of the cohesive zone.
    pub fn c(&self) -> f64 {
        (1.0 + self.mu * self.mu).sqrt() * self.a
    }

    /// The pressure at r (compressive positive); the Dugdale stress -lambda/2 on A < r <= C,
    /// zero beyond.
    pub fn pressure(&self, r: f64) -> f64 {
        let (l, a) = (self.lambda, self.a);
        if r < a {
            // C^2 - A^2 = A^2 mu^2, exact for small mu.
            let t = ((a * a - r * r).max(0.0)).sqrt() / (a * self.mu);
            hertz_pressure(a, r) - 0.5 * l + (l / PI) * t.atan()
        } else if r <= self.c() {
            -0.5 * l
        } else {
            0.0
        }
    }

    /// The load the pressure carries, `2 pi integral p r dr`, from the pressure formula itself
    /// (a high-order rule with r = A sin(theta) inside the contact, the Dugdale annulus exactly):
    /// equation (2)'s load, which the tests check it reproduces.
    pub fn load(&self) -> f64 {
        let (a, c) = (self.a, self.c());
        let half_pi = std::f64::consts::FRAC_PI_2;
        let inner = integrate01(|u| {
            let th = u * half_pi;
            let r = a * th.sin();
            self.pressure(r) * r * a * th.cos() * half_pi
        });
        2.0 * PI * inner - 0.5 * self.lambda * PI * (c * c - a * a)
    }

    /// The energy release rate over w, the J-integral through the Dugdale zone (the gap at C
    /// over h0): `(lambda A^2/2) [(m^2 - 2) arcsec m + sqrt(m^2 - 1)] +
    /// (4 lambda^2 A/3) [sqrt(m^2 - 1) arcsec m - m + 1]`, from mu and m - 1, which keep
    /// their digits where C and A are equal in f64 (the JKR side).
    pub fn energy_release_over_w(&self) -> f64 {
        let (l, a, mu) = (self.lambda, self.a, self.mu);
        let (at, mu_minus_at) = mu.atan_parts();
        // m - 1 = mu^2 / (m + 1) without cancellation.
        let m_minus_1 = mu * mu / ((1.0 + mu * mu).sqrt() + 1.0);
        0.5 * l * a * a * (mu * mu * at + mu_minus_at)
            + (4.0 * l * l * a / 3.0) * (mu * at - m_minus_1)
    }

    /// The surface gap at r (zero inside the contact).
    ///
    /// The uniform tension on the disc r < C is itself a sum of flat punches (density
    /// `s / sqrt(C^2 - s^2)`, as the inner correction with A = C), so the punches of radius
    /// s < A cancel; with s = C cos(psi) what is left is a sum of positive terms,
    /// `h = hertz_gap + (8 lambda / 3 pi) integral acos(C cos(psi) / r) C cos(psi) dpsi`
    /// over psi from acos(min(r, C)/C) to atan(mu) (s from min(r, C) down to A), so no digit
    /// is lost where the Dugdale zone is thin (the JKR side) or wide (the DMT side).
    pub fn gap(&self, r: f64) -> f64 {
        let (l, a, mu) = (self.lambda, self.a, self.mu);
        if r <= a {
            return 0.0;
        }
        let c = self.c();
        let psi_a = mu.atan();
        let psi_b = if r < c {
            (((c - r) * (c + r)).sqrt() / r).atan()
        } else {
            0.0
        };
        // psi = psi_b + (psi_a - psi_b) v^2 takes out the square root at s = r.
        let integral = integrate01(|v| {
            let d = (psi_a - psi_b) * v * v;
            let psi = psi_b + d;
            // 1 - C cos(psi)/r without cancellation: for r < C, C cos(psi_b) = r and
            // cos(psi_b) - cos(psi) = 2 sin((psi + psi_b)/2) sin(d/2); beyond C the extra
            // (r - C) / r.
            let h = (0.5 * d).sin();
            let one_minus = if r < c {
                c * (2.0 * (psi_b + 0.5 * d).sin() * h) / r
            } else {
                ((r - c) + 2.0 * c * (0.5 * psi).sin().powi(2)) / r
            };
            let acos = 2.0 * (0.5 * one_minus).clamp(0.0, 1.0).sqrt().asin();
            acos * c * psi.cos() * 2.0 * (psi_a - psi_b) * v
        });
        hertz_gap(a, r) + (8.0 * l / (3.0 * PI)) * integral
    }
}

/// The Hertz pressure of contact radius A at r (zero outside).
pub fn hertz_pressure(a: f64, r: f64) -> f64 {
    if r < a {
        1.5 / PI * (a * a - r * r).sqrt()
    } else {
        0.0
    }
}

/// The gap outside a Hertz contact of radius A (its approach A^2): with m' = r/A,
/// `(A^2/pi) [(m'^2 - 2) arcsec m' + sqrt(m'^2 - 1)]`.
pub fn hertz_gap(a: f64, r: f64) -> f64 {
    if r <= a {
        return 0.0;
    }
    // With t = sqrt(m'^2 - 1): (t^2 - 1) atan t + t = t^2 atan t + (t - atan t), both terms
    // positive (f1 of docs/PHYSICS.md), so no cancellation just outside the edge.
    let t = ((r - a) * (r + a)).sqrt() / a;
    let (at, t_minus_at) = t.atan_parts();
    (a * a / PI) * (t * t * at + t_minus_at)
}

/// JKR at contact radius A: the Hertz pressure plus a flat punch of load -sqrt(6 A^3), singular
/// (infinite tension) at r = A: NaN there.
pub fn jkr_pressure(a: f64, r: f64) -> f64 {
    if r >= a {
        return if r == a { f64::NAN } else { 0.0 };
    }
    hertz_pressure(a, r) - (6.0 * a * a * a).sqrt() / (2.0 * PI * a * (a * a - r * r).sqrt())
}

/// JKR gap: the Hertz gap plus the flat punch's, `(2/3) sqrt(6 A) (2/pi) arcsec(r/A)`.
pub fn jkr_gap(a: f64, r: f64) -> f64 {
    if r <= a {
        return 0.0;
    }
    let sec = ((r / a).powi(2) - 1.0).sqrt().atan();
    hertz_gap(a, r) + (2.0 / 3.0) * (6.0 * a).sqrt() * (2.0 / PI) * sec
}

/// The JKR stress intensity factor at the contact edge, in units of the pressure unit times the
/// square root of the radius unit: `sqrt(6 A^3) / (2 A sqrt(pi A))` (a constant, sqrt(3/(2 pi))).
pub fn jkr_stress_intensity(a: f64) -> f64 {
    (6.0 * a * a * a).sqrt() / (2.0 * a * (PI * a).sqrt())
}

/// The energy release rate over w for a stress intensity factor in these units:
/// `G/w = (2 pi / 3) K^2` (from G = K_I^2 / (2 E*) and K = 4/3 E*).
pub fn energy_release_over_w(k_i: f64) -> f64 {
    2.0 * PI / 3.0 * k_i * k_i
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn md_fields_satisfy_the_md_equations() {
        use crate::physics::md::curve_point;
        for &l in &[0.1, 1.0, 10.0] {
            for &mu in &[0.05, 0.3, 1.0, 3.0, 30.0] {
                let p = curve_point(l, mu);
                let g = MdGeometry {
                    lambda: l,
                    a: p.a,
                    mu,
                };
                let h0 = 2.0 / (PI * l);
                let e = (g.gap(g.c()) / h0 - 1.0).abs();
                assert!(e < 1e-12, "lambda {l} mu {mu}: gap at C off by {e:e}");
                let e = (g.load() - p.load).abs() / p.load.abs().max(1.0);
                assert!(e < 1e-10, "lambda {l} mu {mu}: load off by {e:e}");
                assert!(
                    g.gap(p.a * (1.0 + 1e-12)).abs() < 1e-9,
                    "gap at A+: {}",
                    g.gap(p.a * (1.0 + 1e-12))
                );
            }
        }
    }

    #[test]
    fn quadrature_is_exact_for_polynomials_and_smooth_functions() {
        assert!((integrate01(|x| x.powi(20)) - 1.0 / 21.0).abs() < 1e-16);
        assert!((integrate01(|x| (x * PI).sin()) - 2.0 / PI).abs() < 1e-15);
    }
}
