//! The tip a curve is fitted with: a sphere (its paraboloid) of radius R, or an axisymmetric tip
//! of docs/PHYSICS.md section 12 (a power law: a cone, a pyramid as its equivalent cone, a
//! blunt tip; a capped cone; a measured profile). It gives each fitted model's law in the tip's normalised units,
//! those units from E* and w, and how they move with E* and w (section 12.4).

use super::{Model, Units};
use crate::error::Message;
use crate::law::{ContactLaw, Tip, TipClosed};
use crate::physics::measured::Profile;
use crate::physics::params::LJ_STRESS;
use crate::physics::tip::{k_n, MeasuredTip, Shape, TipInput};
use std::f64::consts::PI;

/// The tip of a fit, its numbers checked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Geometry {
    /// A sphere of radius R (m): Maugis's units.
    Sphere(f64),
    /// `f = B r^n`: Sneddon's `F = kb t^n` with `kb = k_n B` (m^(1-n)).
    Power {
        /// The exponent n >= 1.
        n: f64,
        /// `k_n B`.
        kb: f64,
    },
    /// A spherical cap of radius R (m) joined tangentially to a cone of half-angle theta.
    CappedCone {
        /// The cap's radius (m).
        radius: f64,
        /// The cone's half-angle (radians, axis to flank).
        half_angle: f64,
    },
    /// A measured profile (metres; docs/PHYSICS.md section 12.3): its units are a search per
    /// E* and w ([`MeasuredTip::of`]).
    Measured(&'static Profile),
}

impl Units {
    /// A tip's units from its radial length l and approach unit d (m): the force unit
    /// `pi w l^2 / d` and the spring constant `spring` (N/m) in them.
    fn of_tip(w: f64, l: f64, d: f64, spring: f64) -> Units {
        let force = PI * w * l * l / d;
        Units {
            force,
            approach: d,
            radius: l,
            kbar: spring * d / force,
        }
    }
}

/// A radius is a sphere's.
impl From<f64> for Geometry {
    fn from(radius: f64) -> Geometry {
        Geometry::Sphere(radius)
    }
}

impl Geometry {
    /// The tip a scene's `"tip"` describes, its numbers checked as a scene checks them (a
    /// measured profile's table as [`Profile::new`] checks it).
    pub fn of(tip: &TipInput) -> Result<Geometry, Message> {
        if let TipInput::Profile { r_m, z_m } = tip {
            return Profile::interned(r_m, z_m)
                .map(Geometry::Measured)
                .map_err(|e| Message::new().key("tip").text(": ").then(e));
        }
        // The scene's checks of every number (named by its key).
        tip.units(1.0, 1.0, 1.0)
            .map_err(|e| Message::from(e.to_string()))?;
        Ok(match *tip {
            TipInput::Sphere { radius_m } => Geometry::Sphere(radius_m),
            TipInput::CappedCone {
                radius_m,
                half_angle_deg,
            } => Geometry::CappedCone {
                radius: radius_m,
                half_angle: half_angle_deg.to_radians(),
            },
            _ => {
                let (n, b) = tip
                    .power()
                    .map_err(|e| Message::from(e.to_string()))?
                    .ok_or(Message::from("the tip is not a power law"))?;
                if n == 2.0 {
                    // The paraboloid f = B r^2 is the sphere of radius 1/(2B), exactly.
                    Geometry::Sphere(0.5 / b)
                } else {
                    Geometry::Power { n, kb: k_n(n) * b }
                }
            }
        })
    }

    /// Whether the tip is the sphere (the models DMT and the sphere's closed forms apply).
    pub fn is_sphere(&self) -> bool {
        matches!(self, Geometry::Sphere(_))
    }

    /// The sphere's or the cap's radius (m): the scale the small-strain warnings and Tabor's
    /// parameter read; None for a power law and a measured profile.
    pub fn radius(&self) -> Option<f64> {
        match *self {
            Geometry::Sphere(r) | Geometry::CappedCone { radius: r, .. } => Some(r),
            Geometry::Power { .. } | Geometry::Measured(_) => None,
        }
    }

    /// The units of the reduced modulus `e_star` (Pa) and the work of adhesion `w` (J/m^2),
    /// with the spring constant `spring` (N/m) in them: the force unit `pi w l^2 / d`, the
    /// approach unit d, the radius unit l, `E* d^2 / l = 3 pi w / 4` (section 12).
    pub fn units(&self, e_star: f64, w: f64, spring: f64) -> Units {
        match *self {
            // Maugis's units (a capped cone's are its cap's).
            Geometry::Sphere(radius) | Geometry::CappedCone { radius, .. } => {
                let k = 4.0 / 3.0 * e_star;
                let force = PI * w * radius;
                let approach = (PI * PI * w * w * radius / (k * k)).cbrt();
                Units {
                    force,
                    approach,
                    radius: (PI * w * radius * radius / k).cbrt(),
                    kbar: spring * approach / force,
                }
            }
            Geometry::Power { n, kb } => {
                let l = (3.0 * PI * w / (4.0 * e_star * kb * kb)).powf(1.0 / (2.0 * n - 1.0));
                Units::of_tip(w, l, kb * l.powf(n), spring)
            }
            Geometry::Measured(table) => match MeasuredTip::of(table, e_star, w) {
                Some(m) => Units::of_tip(w, m.length(), m.height(), spring),
                // No unit within 1e12 of the table's radii: no number for this E* and w.
                None => Units::of_tip(w, f64::NAN, f64::NAN, spring),
            },
        }
    }

    /// The shape in the units `u` (None for the sphere, whose laws are Maugis's).
    fn shape(&self, u: &Units) -> Option<Shape> {
        match *self {
            Geometry::Sphere(_) => None,
            Geometry::Power { n, .. } => Some(Shape::Power { exponent: n }),
            Geometry::CappedCone { radius, half_angle } => Some(Shape::CappedCone {
                rho: radius / u.radius,
                half_angle,
            }),
            Geometry::Measured(table) => Some(Shape::Measured(MeasuredTip::at(table, u.radius))),
        }
    }

    /// The law of `model` at `lambda` on this tip, in the units `u`: the sphere's models, or the
    /// tip's Maugis-Dugdale law and its closed forms (Sneddon's punch for Hertz, the JKR-type
    /// law). A tip has no DMT-type and no two-zone law ([`Geometry::fits`]: the options and
    /// the synthetic curves refuse them first); asked for one, this is its Maugis-Dugdale law.
    pub fn law(&self, model: Model, lambda: f64, u: &Units) -> ContactLaw {
        match self.shape(u) {
            None => model.law(lambda),
            Some(shape) => match model {
                Model::Hertz | Model::Jkr => ContactLaw::TipClosed(TipClosed {
                    shape,
                    adhesive: model == Model::Jkr,
                }),
                Model::Md | Model::Dmt | Model::SolidAndMeniscus => {
                    debug_assert!(self.fits(model), "{model:?} on a tip");
                    ContactLaw::Tip(Tip { shape, lambda })
                }
            },
        }
    }

    /// Whether the tip has `model`: the sphere every one, a tip its ladder and Maugis-Dugdale.
    pub fn fits(&self, model: Model) -> bool {
        self.is_sphere() || model == Model::Md || self.ladder().contains(&model)
    }

    /// The closed forms fitted before Maugis-Dugdale, from the simplest. Beyond the paraboloid
    /// the DMT-type force depends on the range (a cone's `pi w h0 tan^2 alpha`): it has
    /// Maugis-Dugdale's parameters, so it is no simpler model and is not fitted.
    pub fn ladder(&self) -> &'static [Model] {
        if self.is_sphere() {
            &[Model::Hertz, Model::Dmt, Model::Jkr]
        } else {
            &[Model::Hertz, Model::Jkr]
        }
    }

    /// Whether the tip's Maugis-Dugdale law is solved at `lambda`.
    pub fn admits_lambda(&self, lambda: f64) -> bool {
        if self.is_sphere() {
            crate::solver::domain::check_lambda(lambda).is_ok()
        } else {
            let (lo, hi) = crate::law::tip::LAMBDA_RANGE;
            lambda >= lo && lambda <= hi
        }
    }

    /// The lambda range of [`Geometry::admits_lambda`], in words.
    pub fn lambda_domain(&self) -> &'static str {
        if self.is_sphere() {
            "1e-26..1e26"
        } else {
            "1e-3..1e3"
        }
    }

    /// Whether the normalised laws depend on lambda alone, so that E* and w only scale them
    /// (the analytic Jacobian's premise): not a capped cone's, whose cap is `R / l` in units
    /// that move with E* and w, nor a measured profile's.
    pub fn scales(&self) -> bool {
        !matches!(self, Geometry::CappedCone { .. } | Geometry::Measured(_))
    }

    /// How ln E* and ln w move the force unit, the approach unit and kbar (each a
    /// `(dln force, dln d, dln kbar)`): with `s = ln w - ln E*`, `ln l = s/(2n - 1)`,
    /// `ln d = n ln l`, `ln force = ln w + (2 - n) ln l`, `ln kbar = (2n - 2) ln l - ln w` (the
    /// sphere's n = 2). A capped cone's are its cap's units' only: its law moves with E* and w
    /// too (`rho = R / l`), so its Jacobian is taken by differences ([`Geometry::scales`]); a
    /// measured profile's shape moves with them too, and it has none (NaN).
    pub fn log_slopes(&self) -> [(f64, f64, f64); 2] {
        match *self {
            Geometry::Power { n, .. } => {
                let a = 1.0 / (2.0 * n - 1.0);
                [
                    (-(2.0 - n) * a, -n * a, -(2.0 * n - 2.0) * a),
                    (1.0 + (2.0 - n) * a, n * a, -1.0 + (2.0 * n - 2.0) * a),
                ]
            }
            Geometry::Sphere(_) | Geometry::CappedCone { .. } => {
                [(0.0, -2.0 / 3.0, -2.0 / 3.0), (1.0, 2.0 / 3.0, -1.0 / 3.0)]
            }
            // Its shape moves with E* and w: no slopes scale it (never read, `scales` false).
            Geometry::Measured(_) => [(f64::NAN, f64::NAN, f64::NAN); 2],
        }
    }

    /// lambda from the Lennard-Jones range z0 (the Dugdale stress `LJ_STRESS w / z0`):
    /// `(3/2) s0 l / (E* d)`.
    pub fn lambda_from_z0(&self, e_star: f64, w: f64, z0: f64) -> f64 {
        match *self {
            Geometry::Sphere(r) => super::lambda_from_z0(e_star, w, r, z0),
            _ => {
                let u = self.units(e_star, w, 1.0);
                1.5 * (LJ_STRESS * w / z0) * u.radius / (e_star * u.approach)
            }
        }
    }

    /// The Lennard-Jones range z0 whose matched Dugdale stress gives lambda.
    pub fn z0_from_lambda(&self, e_star: f64, w: f64, lambda: f64) -> f64 {
        match *self {
            Geometry::Sphere(r) => super::z0_from_lambda(e_star, w, r, lambda),
            _ => {
                let u = self.units(e_star, w, 1.0);
                1.5 * LJ_STRESS * w * u.radius / (e_star * u.approach * lambda)
            }
        }
    }

    /// c in `ln z0 = c (ln w - ln E*) - ln lambda + const` at `e_star`, `w`: `g / (2g - 1)`
    /// with `g = d ln F / d ln l` (a power law's g = n; the sphere's and the capped cone's
    /// g = 2, c = 2/3; a measured profile's g at its unit l).
    pub fn z0_slope(&self, e_star: f64, w: f64) -> f64 {
        let g = match *self {
            Geometry::Power { n, .. } => n,
            Geometry::Measured(table) => {
                MeasuredTip::of(table, e_star, w).map_or(f64::NAN, |m| m.log_slope())
            }
            _ => 2.0,
        };
        g / (2.0 * g - 1.0)
    }

    /// The w whose force unit at `e_star` times the normalised pull-off `pc_bar` is `pull` (N):
    /// a fit's start from the measured pull-off.
    pub fn w_for_pulloff(&self, pull: f64, pc_bar: f64, e_star: f64) -> f64 {
        match *self {
            Geometry::Sphere(r) | Geometry::CappedCone { radius: r, .. } => {
                pull / (pc_bar * PI * r)
            }
            // force = pi w^(1+g) c^g / kb, c = 3 pi / (4 E* kb^2), g = (2 - n)/(2n - 1).
            Geometry::Power { n, kb } => {
                let g = (2.0 - n) / (2.0 * n - 1.0);
                let c = 3.0 * PI / (4.0 * e_star * kb * kb);
                (pull * kb / (pc_bar * PI * c.powf(g))).powf(1.0 / (1.0 + g))
            }
            // Newton in ln w: ln force rises with ln w at the slope (g + 1)/(2g - 1).
            Geometry::Measured(table) => {
                let mut w = 0.01;
                for _ in 0..60 {
                    let Some(m) = MeasuredTip::of(table, e_star, w) else {
                        return f64::NAN;
                    };
                    let force = PI * w * m.length() * m.length() / m.height();
                    let g = m.log_slope();
                    let step = (pull / (pc_bar * force)).ln() * (2.0 * g - 1.0) / (g + 1.0);
                    w *= step.exp();
                    if step.abs() < 1e-13 {
                        return w;
                    }
                }
                f64::NAN
            }
        }
    }

    /// E* of the adhesion-free punch pressed by `force` (N) to the approach `delta` (m), as
    /// 4/3 of it (the sphere's `F / (sqrt(R) delta^(3/2))`; a power law's
    /// `P = 2 E* (n/(n+1)) kb^(-1/n) delta^((n+1)/n)`; a capped cone's cap): a fit's start.
    pub fn punch_stiffness(&self, force: f64, delta: f64) -> f64 {
        match *self {
            Geometry::Sphere(r) | Geometry::CappedCone { radius: r, .. } => {
                force / (r.sqrt() * delta.powf(1.5))
            }
            Geometry::Power { n, kb } => {
                4.0 / 3.0 * force * (n + 1.0) * kb.powf(1.0 / n)
                    / (2.0 * n * delta.powf((n + 1.0) / n))
            }
            // The punch's radius a where F(a) = delta, its load `2 E* I(a)` (Sneddon's load
            // integral; section 12).
            Geometry::Measured(table) => {
                let mut hi = table.largest_radius;
                while table.abel(hi).0 < delta && hi < 1e12 * table.largest_radius {
                    hi *= 4.0;
                }
                let a = crate::numeric::root::bisect_sign(|a| table.abel(a).0 - delta, 0.0, hi);
                2.0 / 3.0 * force / table.load_integral(a)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two tips' units (force, approach, radius, kbar) agree within `tol` (relative).
    fn same_units(a: Units, b: Units, tol: f64) {
        for (x, y) in [
            (a.force, b.force),
            (a.approach, b.approach),
            (a.radius, b.radius),
            (a.kbar, b.kbar),
        ] {
            assert!((x / y - 1.0).abs() < tol, "{x} {y}");
        }
    }

    /// A finely tabulated `f = B r^3` has the cubic power law's units, starts and z0 slope
    /// within its table's error; its z0 slope is its units' (by differences), and its start's
    /// w gives back the pull-off.
    #[test]
    fn a_measured_tables_units_and_starts_are_its_power_laws() {
        let b = 1e15;
        let r: Vec<f64> = (0..=600).map(|i| 3e-8 * i as f64 / 600.0).collect();
        let z: Vec<f64> = r.iter().map(|x| b * x.powi(3)).collect();
        let table = Geometry::Measured(Profile::interned(&r, &z).unwrap());
        let cubic = Geometry::Power {
            n: 3.0,
            kb: k_n(3.0) * b,
        };
        let (e, w) = (1e9, 0.05);
        same_units(table.units(e, w, 1.0), cubic.units(e, w, 1.0), 1e-5);
        assert!((table.z0_slope(e, w) - 0.6).abs() < 1e-5);
        let h = 1e-5;
        let z0 = |w: f64| table.z0_from_lambda(e, w, 0.7).ln();
        let d = (z0(w * f64::exp(h)) - z0(w * f64::exp(-h))) / (2.0 * h);
        assert!((d - table.z0_slope(e, w)).abs() < 1e-6, "{d}");
        let wp = table.w_for_pulloff(3e-9, 1.2, e);
        assert!((1.2 * table.units(e, wp, 1.0).force / 3e-9 - 1.0).abs() < 1e-12);
        let (sm, sp) = (
            table.punch_stiffness(2e-8, 5e-9),
            cubic.punch_stiffness(2e-8, 5e-9),
        );
        assert!((sm / sp - 1.0).abs() < 1e-5, "{sm} {sp}");
        assert!(!table.scales() && table.radius().is_none());
    }

    /// The power law's units at n = 2 are the sphere's, its lambda from z0 too; the log slopes
    /// are the units' derivatives (by differences).
    #[test]
    fn power_units_and_their_slopes() {
        let r = 2e-8;
        let sphere = Geometry::Sphere(r);
        let square = Geometry::Power {
            n: 2.0,
            kb: k_n(2.0) * 0.5 / r,
        };
        let (e, w) = (2e9, 0.05);
        same_units(sphere.units(e, w, 1.0), square.units(e, w, 1.0), 1e-13);
        let (ls, lp) = (
            sphere.lambda_from_z0(e, w, 3e-10),
            square.lambda_from_z0(e, w, 3e-10),
        );
        assert!((ls / lp - 1.0).abs() < 1e-13);
        assert!((square.z0_from_lambda(e, w, lp) / 3e-10 - 1.0).abs() < 1e-13);
        for g in [
            Geometry::Power { n: 1.0, kb: 3.0 },
            Geometry::Power { n: 3.5, kb: 1e12 },
            sphere,
        ] {
            let h = 1e-6;
            let ln = |e: f64, w: f64| {
                let u = g.units(e, w, 1.0);
                [u.force.ln(), u.approach.ln(), u.kbar.ln()]
            };
            let slopes = g.log_slopes();
            for (k, (de, dw)) in [(h, 0.0), (0.0, h)].into_iter().enumerate() {
                let (p, m) = (
                    ln(e * f64::exp(de), w * f64::exp(dw)),
                    ln(e * f64::exp(-de), w * f64::exp(-dw)),
                );
                let want = [slopes[k].0, slopes[k].1, slopes[k].2];
                for i in 0..3 {
                    let d = (p[i] - m[i]) / (2.0 * h);
                    assert!((d - want[i]).abs() < 1e-7, "{g:?} {k} {i}: {d} {}", want[i]);
                }
            }
            // z0's slope: ln z0 against ln w - ln E* at fixed lambda.
            let z = |e: f64, w: f64| g.z0_from_lambda(e, w, 0.7).ln();
            let d = (z(e, w * f64::exp(h)) - z(e, w * f64::exp(-h))) / (2.0 * h);
            assert!((d - g.z0_slope(e, w)).abs() < 1e-7, "{g:?}: {d}");
            // The start's w gives back the pull-off.
            let wp = g.w_for_pulloff(3e-9, 1.2, e);
            assert!((1.2 * g.units(e, wp, 1.0).force / 3e-9 - 1.0).abs() < 1e-12);
        }
    }
}
