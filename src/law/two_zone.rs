//! The two-zone law (docs/PHYSICS.md section 10): the solid's Dugdale zone plus a water
//! meniscus, a second zone of `stress_ratio` and `range_ratio` times the solid's stress and
//! range, in the total-w units. Its path: free until the approach reaches `-H_L` (the longer
//! range), the longer zone's disc alone until the axis gap is the shorter range, both discs
//! until the axis gap closes (the non-contact piece, t = `C_L` then `C_L + C_S`), then the
//! contact curve (t = -ln mu_L). A single zone, or two zones of one range, is Maugis-Dugdale at
//! the summed lambda and takes its path.

use super::path::{check_drive, contact_radii, point_of};
use super::path::{Branch, Drive, PathPoint};
use super::{cache, md, Given, Law, LawError, LawKey, Md, Piece, Pt, A_START};
use crate::error::Message;
use crate::physics::model::ContactModel;
use crate::physics::two_zone::{
    non_contact_both, non_contact_ends, non_contact_single, point, point_with_slopes,
    NonContactPoint, Shape, Zones,
};
use crate::solver::two_zone::{x_at_radius, TwoZoneContext, TwoZoneState, ZonesError};
use crate::solver::Status;
use serde::Serialize;

/// The two-zone law: the solid's Maugis parameter and the second zone's ratios.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TwoZones {
    /// The solid's Maugis parameter.
    pub lambda: f64,
    /// The meniscus's stress over the solid's.
    pub stress_ratio: f64,
    /// The meniscus's range over the solid's.
    pub range_ratio: f64,
}

/// How the path is computed: one zone (Maugis-Dugdale at the summed lambda), or two zones of
/// two ranges (the longer one's index, and the non-contact piece's two stretches' ends, `C_L`
/// and `C_S`).
enum Zoned {
    One(Md),
    Two(Zones, usize, (f64, f64)),
    Unsolvable,
}

impl TwoZones {
    /// The two-zone law of a solid's Dugdale zone (Maugis parameter `lambda`, stress `s1` in
    /// Pa, work `w` in J/m^2, so range `h1 = w / s1`) in a meniscus of stress `s2` (Pa, the
    /// Laplace pressure) and range `h2` (m), and the total w (J/m^2) whose units its path is in:
    /// the one conversion of a meniscus into the law's ratios (scenes, fits, DEM pairs).
    pub fn of_meniscus(lambda: f64, (s1, w): (f64, f64), (s2, h2): (f64, f64)) -> (TwoZones, f64) {
        (
            TwoZones {
                lambda,
                stress_ratio: s2 / s1,
                range_ratio: h2 * s1 / w,
            },
            w + s2 * h2,
        )
    }

    /// As [`TwoZones::of_meniscus`] for a sphere of radius `radius` (m) on a solid of E* (Pa),
    /// w and lambda: its Dugdale stress is `s1 = (lambda / 2) (pi w K^2 / R)^(1/3)`.
    pub fn of_sphere_in_meniscus(
        e_star: f64,
        w: f64,
        lambda: f64,
        radius: f64,
        meniscus: (f64, f64),
    ) -> (TwoZones, f64) {
        let k = 4.0 / 3.0 * e_star;
        let s1 = 0.5 * lambda * (std::f64::consts::PI * w * k * k / radius).cbrt();
        TwoZones::of_meniscus(lambda, (s1, w), meniscus)
    }

    /// The zones in the total-w units (refused ratios: an error naming them).
    pub fn zones(&self) -> Result<Zones, ZonesError> {
        Zones::from_ratios(self.lambda, self.stress_ratio, self.range_ratio)
    }

    /// The law's curve, folds and pull-offs, computed once for its states: the one way the
    /// front ends build it (refused ratios, or a curve that could not be computed: the error
    /// says which).
    pub fn context(&self) -> Result<TwoZoneContext, ContextError> {
        let z = self.zones().map_err(ContextError::Zones)?;
        TwoZoneContext::new(z).map_err(ContextError::Curve)
    }

    fn zoned(&self) -> Zoned {
        let Ok(z) = self.zones() else {
            return Zoned::Unsolvable;
        };
        match z.shape() {
            Shape::Single { lambda } => Zoned::One(Md { lambda }),
            Shape::Two { long } => {
                let e = cache::ends(self.key(), || {
                    non_contact_ends(&z).unwrap_or((f64::NAN, f64::NAN))
                });
                if e.0.is_finite() && e.1.is_finite() {
                    Zoned::Two(z, long, e)
                } else {
                    Zoned::Unsolvable
                }
            }
        }
    }
}

/// Why a two-zone law's curve was not computed ([`TwoZones::context`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ContextError {
    /// The ratios were refused.
    #[error(transparent)]
    Zones(ZonesError),
    /// The curve could not be computed: the solver's status.
    #[error("the two-zone curve could not be computed ({})", .0.name())]
    Curve(Status),
}

impl crate::error::Named for ContextError {
    fn named(&self, names: crate::error::Names) -> String {
        match self {
            ContextError::Zones(e) => e.named(names),
            e => e.to_string(),
        }
    }
}

/// The two-zone state of `ctx` at the load, approach or contact radius `value`.
pub fn state(ctx: &TwoZoneContext, given: Given, value: f64) -> TwoZoneState {
    match given {
        Given::Load => ctx.state_at_load(value),
        Given::Approach => ctx.state_at_approach(value),
        Given::Radius => ctx.state_at_radius(value),
    }
}

impl Law for TwoZones {
    fn model(&self) -> ContactModel {
        ContactModel::SolidAndMeniscus
    }
    fn lambda(&self) -> Option<f64> {
        Some(self.lambda)
    }
    fn state(&self, piece: Piece, t: f64) -> Pt {
        match self.zoned() {
            Zoned::One(l) => l.state(piece, t),
            Zoned::Two(..) if piece == Piece::Free => Pt::free(t),
            Zoned::Two(z, _, ends) => two_zone_state(&z, ends, piece, t),
            Zoned::Unsolvable => Pt::nan(),
        }
    }
    /// Taken by differences: the meniscus is fixed in SI units, so its ratios to the solid's
    /// zone move with E* and w (`fit::Model::scales`).
    fn state_dlambda(&self, _: Piece, _: f64) -> (f64, f64) {
        (f64::NAN, f64::NAN)
    }
    /// The longer zone's reach.
    fn free_end(&self) -> f64 {
        match self.zoned() {
            Zoned::One(l) => l.free_end(),
            Zoned::Two(z, long, _) => -z.range[long],
            Zoned::Unsolvable => f64::NAN,
        }
    }
    /// A bisection for two zones, kept per thread; NaN where no radius matches (the bisection
    /// ends at its bracket's end then).
    fn t_of_radius(&self, a: f64) -> f64 {
        match self.zoned() {
            Zoned::One(l) => l.t_of_radius(a),
            Zoned::Two(z, ..) => -cache::radius(self.key(), a, || {
                Some(x_at_radius(&z, a))
                    .filter(|&x| point(&z, x).is_some_and(|p| (p.a / a - 1.0).abs() <= 1e-9))
                    .unwrap_or(f64::NAN)
            }),
            Zoned::Unsolvable => f64::NAN,
        }
    }
    /// The non-contact piece's second disc starts at `C_L`.
    fn breaks(&self, piece: Piece) -> Vec<f64> {
        match self.zoned() {
            Zoned::Two(_, _, (c_l, _)) if piece == Piece::NonContact => vec![c_l],
            _ => Vec::new(),
        }
    }
    /// The non-contact piece is both of its stretches: the longer zone's disc `C_L` up to its
    /// end, then `C_L` plus the shorter zone's `C_S`.
    fn pieces(&self, a_max: f64) -> Vec<(Piece, f64, f64)> {
        let contact = (
            Piece::Contact,
            self.t_of_radius(A_START),
            self.t_of_radius(a_max),
        );
        match self.zoned() {
            Zoned::One(l) => {
                let c_end = crate::physics::md::zero_radius_end(l.lambda).c;
                vec![(Piece::NonContact, 0.0, c_end), contact]
            }
            Zoned::Two(_, _, (c_l, c_s)) => vec![(Piece::NonContact, 0.0, c_l + c_s), contact],
            Zoned::Unsolvable => vec![contact],
        }
    }
    /// The exact one, in the total w's units.
    fn pulloff(&self) -> f64 {
        self.zones()
            .ok()
            .and_then(|z| TwoZoneContext::new(z).ok())
            .map_or(f64::NAN, |c| c.load_pulloff.load.abs())
    }
    fn key(&self) -> LawKey {
        (
            ContactModel::SolidAndMeniscus,
            [
                self.lambda.to_bits(),
                self.stress_ratio.to_bits(),
                self.range_ratio.to_bits(),
                0,
            ],
        )
    }
    /// `PathPoint::c` is the outer radius of the longer-range zone.
    fn point(&self, piece: Piece, t: f64) -> PathPoint {
        let (z, long, (c_l, c_s)) = match self.zoned() {
            Zoned::One(l) => return l.point(piece, t),
            Zoned::Two(z, long, ends) if piece != Piece::Free => (z, long, ends),
            _ => return point_of(piece, t, &self.state(piece, t)),
        };
        let nan = || point_of(piece, t, &Pt::nan());
        match piece {
            Piece::Contact => point(&z, -t).map_or_else(nan, |p| PathPoint {
                branch: Branch::Contact,
                approach: p.approach,
                load: p.load,
                a: p.a,
                c: p.c[long],
            }),
            _ if t <= c_l => nc_point(&non_contact_single(&z, t.max(0.0)), long),
            _ => non_contact_both(&z, (t - c_l).min(c_s)).map_or_else(nan, |p| nc_point(&p, long)),
        }
    }
    fn cycle_path(&self, drive: Drive, max_load: f64) -> Result<Vec<(Piece, f64)>, LawError> {
        let err = |e: crate::solver::SolveError| ZonesError(e.message());
        let zones = self.zones()?;
        crate::solver::domain::check_lambda(self.lambda).map_err(|e| err(e.into()))?;
        check_drive(drive, max_load).map_err(err)?;
        match zones.shape() {
            Shape::Single { lambda } => {
                crate::solver::domain::check_lambda(lambda).map_err(|e| err(e.into()))?;
                Ok(md::cycle_samples(lambda, max_load, md::CYCLE_POINTS))
            }
            Shape::Two { .. } => {
                let ctx = TwoZoneContext::new(zones).map_err(|s| failed("its pull-offs", s))?;
                Ok(two_zone_samples(&ctx, max_load)?)
            }
        }
    }
    /// The pull-offs of the two-zone context, or under a spring
    /// [`TwoZoneContext::spring_fold`].
    fn fold(&self, drive: Drive, near: &PathPoint) -> Option<PathPoint> {
        let zones = self.zones().ok()?;
        let long = match zones.shape() {
            Shape::Single { lambda } => return Md { lambda }.fold(drive, near),
            Shape::Two { long } => long,
        };
        let ctx = TwoZoneContext::new(zones).ok()?;
        let exact = match drive {
            Drive::RigidGrips => ctx.disp_pulloff,
            Drive::DeadLoad => ctx.load_pulloff,
            Drive::Spring(k) => ctx.spring_fold(k, near.a)?,
        };
        (!exact.at_zero_radius()).then(|| PathPoint {
            branch: Branch::Contact,
            approach: exact.approach,
            load: exact.load,
            a: exact.a,
            c: exact.c[long],
        })
    }
}

/// A two-zone state at parameter t of the non-contact piece (`C_L` up to `c_l`, then `c_l +
/// C_S`) or of the contact piece (`t = -ln mu_L`): the shorter zone's radius is an inner root,
/// so the curve is not explicit. The contact piece's slopes come from the root's implicit
/// slope, the non-contact piece's by differences (one-sided at a stretch's ends). NaN where no
/// state is found.
fn two_zone_state(z: &Zones, (c_l, c_s): (f64, f64), piece: Piece, t: f64) -> Pt {
    if piece == Piece::Contact {
        // The slopes in x = -t from the inner root's implicit slope.
        return match point_with_slopes(z, -t) {
            Some((p, [dload, dapproach, da])) => Pt {
                load: p.load,
                approach: p.approach,
                a: p.a,
                dload: -dload,
                dapproach: -dapproach,
                da: -da,
            },
            None => Pt::nan(),
        };
    }
    // The non-contact piece: (load, approach) on its stretch, A = 0.
    let at = |t: f64| -> Option<[f64; 2]> {
        let p = if t <= c_l {
            non_contact_single(z, t.max(0.0))
        } else {
            non_contact_both(z, (t - c_l).min(c_s))?
        };
        Some([p.load, p.approach])
    };
    let (lo, hi) = if t <= c_l {
        (0.0, c_l)
    } else {
        (c_l, c_l + c_s)
    };
    let h = 1e-6 * (1.0 + t.abs());
    let (Some(v), Some(up), Some(down)) = (at(t), at((t + h).min(hi)), at((t - h).max(lo))) else {
        return Pt::nan();
    };
    let span = (t + h).min(hi) - (t - h).max(lo);
    let d = |k: usize| (up[k] - down[k]) / span;
    Pt {
        load: v[0],
        approach: v[1],
        a: 0.0,
        dload: d(0),
        dapproach: d(1),
        da: 0.0,
    }
}

fn failed(what: &str, s: Status) -> ZonesError {
    ZonesError(
        Message::new()
            .text(format!(
                "the two-zone contact curve could not be solved for {what} (status {}): try \
                 ratios closer to 1 or a ",
                s.name()
            ))
            .key("lambda")
            .text(" nearer 1"),
    )
}

fn nc_point(p: &NonContactPoint, long: usize) -> PathPoint {
    PathPoint {
        branch: Branch::NonContact,
        approach: p.approach,
        load: p.load,
        a: 0.0,
        c: p.c[long],
    }
}

/// The ends of the non-contact branch's two stretches ([`non_contact_ends`] of its zones).
pub(crate) fn non_contact_ends_of(ctx: &TwoZoneContext) -> Result<(f64, f64), ZonesError> {
    non_contact_ends(&ctx.zones).ok_or_else(|| failed("the discs", Status::NotConverged))
}

/// Where a cycle samples the two-zone path (two ranges) up to `max_load`: the non-contact
/// piece's two stretches evenly (the longer zone's disc alone, then both discs), the contact
/// piece at `contact_radii`.
fn two_zone_samples(ctx: &TwoZoneContext, max_load: f64) -> Result<Vec<(Piece, f64)>, ZonesError> {
    const N: usize = md::CYCLE_POINTS;
    let (c1, c2) = non_contact_ends_of(ctx)?;
    let mut path: Vec<(Piece, f64)> = (0..N)
        .map(|i| (Piece::NonContact, c1 * i as f64 / (N - 1) as f64))
        .collect();
    for i in 1..N {
        let c_short = c2 * i as f64 / (N - 1) as f64;
        if non_contact_both(&ctx.zones, c_short).is_none() {
            return Err(failed("the two discs", Status::NotConverged));
        }
        path.push((Piece::NonContact, c1 + c_short));
    }
    let radius_at = |p: f64| {
        let s = ctx.state_at_load(p);
        (s.status == Status::Ok)
            .then_some(s.a)
            .ok_or_else(|| failed(&format!("the load {p}"), s.status))
    };
    let a_max = radius_at(max_load)?;
    let a_mid = a_max.min(radius_at(10.0)?);
    for a in contact_radii(a_mid, a_max, N) {
        let x = x_at_radius(&ctx.zones, a);
        if !point(&ctx.zones, x).is_some_and(|p| (p.a / a - 1.0).abs() <= 1e-9) {
            return Err(failed(
                &format!("the contact radius {a}"),
                Status::NotConverged,
            ));
        }
        path.push((Piece::Contact, -x));
    }
    Ok(path)
}
