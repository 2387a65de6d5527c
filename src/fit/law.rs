//! The laws a force curve is fitted with, as the path follower sees them: a law's path after
//! the free piece is a list of pieces, each state an explicit function of its piece's parameter
//! t, with its slopes in t and in lambda. Everything law-specific in a fit's path is here:
//! `path` (the follower under the spring: folds, jumps, each point's state) and `problem` (the
//! misfit and its Jacobian) take a law's states from [`Law`] and nothing else of it. A new law
//! for fits is a [`Model`] variant with its arms here (its pieces, states and slopes) and its
//! tests; the follower does not change.

use super::path::{Piece, Pt};
use crate::physics::md::{curve_point, curve_point_dlambda, non_contact_point, zero_radius_end};
use crate::physics::model::ContactModel;
use crate::physics::two_zone::{
    non_contact_both, non_contact_ends, non_contact_single, point, point_with_slopes, Shape, Zones,
};
use crate::solver::context::x_at_radius_newton;
use crate::solver::two_zone::{x_at_radius, TwoZoneContext};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The contact models a force curve is fitted with, from the simplest: those of
/// [`ContactModel`] with an elastic path under a spring (not the rigid or two-zone ones). Names
/// and labels are [`ContactModel`]'s.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Model {
    /// Hertz: no adhesion.
    Hertz,
    /// DMT: Hertz plus the adhesive load `2 pi w R` outside the contact.
    Dmt,
    /// JKR: adhesion inside the contact, a crack at its edge.
    Jkr,
    /// Maugis-Dugdale, lambda fitted (or fixed by z0).
    Md,
    /// The solid's Dugdale zone (its w and lambda fitted, or lambda fixed by z0) plus the water
    /// meniscus of a given humidity (docs/PHYSICS.md section 10): fitted to a humid curve's
    /// shape beside the ladder of [`Model::ALL`].
    SolidAndMeniscus,
}

impl Model {
    /// The ladder of fitted models, from the simplest: every curve is fitted with these, and
    /// the adequate model is one of them.
    pub const ALL: [Model; 4] = [Model::Hertz, Model::Dmt, Model::Jkr, Model::Md];

    /// Whether the model has adhesion, so that a fit has a w (all but Hertz).
    pub fn adhesive(self) -> bool {
        self != Model::Hertz
    }

    /// Whether the model has a Maugis parameter, so that a fit has a lambda (Maugis-Dugdale).
    pub fn has_lambda(self) -> bool {
        matches!(self, Model::Md | Model::SolidAndMeniscus)
    }

    /// Whether the model's normalised path depends on lambda alone, so that E* and w only
    /// scale it (the analytic Jacobian's premise). The two-zone law's does not: its meniscus is
    /// fixed in SI units, so its ratios to the solid's zone move with E* and w.
    pub fn scales(self) -> bool {
        self != Model::SolidAndMeniscus
    }

    /// The model in the common vocabulary.
    pub fn contact_model(self) -> ContactModel {
        match self {
            Model::Hertz => ContactModel::Hertz,
            Model::Dmt => ContactModel::Dmt,
            Model::Jkr => ContactModel::Jkr,
            Model::Md => ContactModel::Md,
            Model::SolidAndMeniscus => ContactModel::SolidAndMeniscus,
        }
    }

    /// The name in JSON and on the command line ([`ContactModel::name`]).
    pub fn name(self) -> &'static str {
        self.contact_model().name()
    }

    /// The name for people ([`ContactModel::label`]).
    pub fn label(self) -> &'static str {
        self.contact_model().label()
    }
}

impl From<Model> for ContactModel {
    fn from(m: Model) -> ContactModel {
        m.contact_model()
    }
}

impl TryFrom<ContactModel> for Model {
    type Error = String;

    /// The ladder's model of a contact model; the rigid and two-zone ones are not on it (the
    /// two-zone law is fitted beside it, with a humidity).
    fn try_from(m: ContactModel) -> Result<Model, String> {
        Model::ALL
            .into_iter()
            .find(|f| f.contact_model() == m)
            .ok_or_else(|| {
                format!(
                    "the {} model is not fitted to force curves: use hertz, dmt, jkr or md",
                    m.label()
                )
            })
    }
}

/// The two-zone law of a fitted solid (E* in Pa, its w in J/m^2 and its Maugis parameter
/// lambda) on a tip of radius `radius` (m) in a meniscus of stress `s2` (Pa, the Laplace
/// pressure) and range `h2` (m), and the total w (J/m^2) whose units its path is in. The solid's
/// zone is lambda's Dugdale zone, `s1 = (lambda / 2) (pi w K^2 / R)^(1/3)` over `h1 = w / s1`.
pub fn solid_and_meniscus_of(
    e_star: f64,
    w: f64,
    lambda: f64,
    radius: f64,
    (s2, h2): (f64, f64),
) -> (Law, f64) {
    let k = 4.0 / 3.0 * e_star;
    let s1 = 0.5 * lambda * (PI * w * k * k / radius).cbrt();
    let h1 = w / s1;
    (
        Law::solid_and_meniscus(lambda, s2 / s1, h2 / h1),
        w + s2 * h2,
    )
}

/// The contact piece starts at this radius (Maugis-Dugdale: where it meets the non-contact piece
/// to 1e-9; JKR: where its approach slope is still finite).
const A_START: f64 = 1e-9;
/// Nodes per piece: they only bracket folds and roots (folds closer than a node spacing, on a
/// stretch shorter than that, are not resolved; such a stretch moves the force by less than it).
const NODES: usize = 320;

/// A model at its Maugis parameter (ignored by the closed forms): the law whose path a curve is
/// fitted on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Law {
    /// The model.
    pub model: Model,
    /// Its Maugis parameter (Maugis-Dugdale; the solid's for the two-zone law).
    pub lambda: f64,
    /// The two-zone law's second zone: its stress and range over the solid's (0 otherwise).
    pub second: [f64; 2],
}

/// How a law's path is computed: a one-zone law (a two-zone law whose zones share one range, or
/// whose meniscus is absent, is Maugis-Dugdale at its summed lambda), or two zones of two ranges
/// (the longer one's index, and the non-contact branch's two stretches' ends, `C_L` and `C_S`).
enum Zoned {
    One(Law),
    Two(Zones, usize, (f64, f64)),
    Unsolvable,
}

impl Law {
    /// `model` at `lambda` (in the solver's domain where the model is Maugis-Dugdale).
    pub fn new(model: Model, lambda: f64) -> Law {
        Law {
            model,
            lambda,
            second: [0.0; 2],
        }
    }

    /// The two-zone law: the solid's zone at its own Maugis parameter `lambda_s` and a second
    /// zone of `stress_ratio` and `range_ratio` times its stress and range, in the total-w units
    /// of docs/PHYSICS.md section 10 ([`Zones::from_ratios`]).
    pub fn solid_and_meniscus(lambda_s: f64, stress_ratio: f64, range_ratio: f64) -> Law {
        Law {
            model: Model::SolidAndMeniscus,
            lambda: lambda_s,
            second: [stress_ratio, range_ratio],
        }
    }

    /// The two-zone law's zones in its total-w units (None where the ratios are refused).
    fn zones(&self) -> Option<Zones> {
        Zones::from_ratios(self.lambda, self.second[0], self.second[1]).ok()
    }

    /// The law's zones: one (itself, or the two-zone law that is one zone) or two.
    fn zoned(&self) -> Zoned {
        if self.model != Model::SolidAndMeniscus {
            return Zoned::One(*self);
        }
        let Some(z) = self.zones() else {
            return Zoned::Unsolvable;
        };
        match z.shape() {
            Shape::Single { lambda } => Zoned::One(Law::new(Model::Md, lambda)),
            Shape::Two { long } => {
                let key = Key::Ends(self.bits());
                match cached(key, || {
                    Cached::Ends(non_contact_ends(&z).unwrap_or((f64::NAN, f64::NAN)))
                }) {
                    Cached::Ends(e) if e.0.is_finite() && e.1.is_finite() => Zoned::Two(z, long, e),
                    _ => Zoned::Unsolvable,
                }
            }
        }
    }

    fn bits(&self) -> [u64; 3] {
        [
            self.lambda.to_bits(),
            self.second[0].to_bits(),
            self.second[1].to_bits(),
        ]
    }

    /// The state at parameter t of a piece.
    pub fn state(&self, piece: Piece, t: f64) -> Pt {
        if self.model != Model::SolidAndMeniscus {
            // The hot path of every fit: no zones to look at.
            return self.one_zone_state(piece, t);
        }
        match self.zoned() {
            Zoned::One(l) => l.one_zone_state(piece, t),
            Zoned::Two(z, _, ends) if piece != Piece::Free => two_zone_state(&z, ends, piece, t),
            // The free piece is every law's.
            Zoned::Two(..) => self.one_zone_state(piece, t),
            Zoned::Unsolvable => Pt::nan(),
        }
    }

    /// The state of a one-zone law (Maugis-Dugdale or a closed form).
    fn one_zone_state(&self, piece: Piece, t: f64) -> Pt {
        let (model, lambda) = (self.model, self.lambda);
        match piece {
            Piece::Free => Pt {
                load: 0.0,
                approach: t,
                a: 0.0,
                dload: 0.0,
                dapproach: 1.0,
                da: 0.0,
            },
            Piece::NonContact => {
                let (load, approach) = non_contact_point(lambda, t);
                Pt {
                    load,
                    approach,
                    a: 0.0,
                    dload: -PI * lambda * t,
                    dapproach: t - 8.0 * lambda / (3.0 * PI),
                    da: 0.0,
                }
            }
            Piece::Contact => match model {
                Model::Md | Model::SolidAndMeniscus => {
                    let mu = (-t).exp();
                    let c = curve_point(lambda, mu);
                    Pt {
                        load: c.load,
                        approach: c.approach,
                        a: c.a,
                        dload: -mu * c.dload_dmu,
                        dapproach: -mu * c.dapproach_dmu,
                        da: -mu * c.da_dmu,
                    }
                }
                Model::Hertz | Model::Dmt => Pt {
                    load: t * t * t - if model == Model::Dmt { 2.0 } else { 0.0 },
                    approach: t * t,
                    a: t,
                    dload: 3.0 * t * t,
                    dapproach: 2.0 * t,
                    da: 1.0,
                },
                Model::Jkr => {
                    let s6 = (6.0 * t).sqrt();
                    Pt {
                        load: t * t * t - t * s6,
                        approach: t * t - 2.0 / 3.0 * s6,
                        a: t,
                        dload: 3.0 * t * t - 1.5 * s6,
                        dapproach: 2.0 * t - s6 / (3.0 * t),
                        da: 1.0,
                    }
                }
            },
        }
    }

    /// The slopes of the load and the approach with respect to lambda at fixed t on `piece`
    /// (zero for the free piece and the closed forms, which have no lambda).
    pub fn state_dlambda(&self, piece: Piece, t: f64) -> (f64, f64) {
        let (model, lambda) = (self.model, self.lambda);
        match (piece, model) {
            // The two-zone law's Jacobian is taken by differences (`Model::scales`).
            (_, Model::SolidAndMeniscus) => (f64::NAN, f64::NAN),
            (Piece::NonContact, _) => (
                -PI / 2.0 * t * t,
                -8.0 / (3.0 * PI) * t + 2.0 / (PI * lambda * lambda),
            ),
            (Piece::Contact, Model::Md) => {
                let (_, dload, dapproach) = curve_point_dlambda(lambda, (-t).exp());
                (dload, dapproach)
            }
            _ => (0.0, 0.0),
        }
    }

    /// The approach at which the free piece ends and a force first acts (Maugis-Dugdale: the
    /// Dugdale zone's reach; two zones: the longer one's; the closed forms: touching).
    pub fn free_end(&self) -> f64 {
        match self.zoned() {
            Zoned::One(l) if l.model == Model::Md => -2.0 / (PI * l.lambda),
            Zoned::One(_) => 0.0,
            Zoned::Two(z, long, _) => -z.range[long],
            Zoned::Unsolvable => f64::NAN,
        }
    }

    /// The contact piece's parameter at contact radius `a` (a Newton search for
    /// Maugis-Dugdale, a bisection for two zones, kept per thread: a fit at fixed lambda asks
    /// for the same radii again).
    pub fn t_of_radius(&self, a: f64) -> f64 {
        let zoned = self.zoned();
        let law = match &zoned {
            Zoned::One(l) if l.model != Model::Md => return a,
            Zoned::One(l) => *l,
            Zoned::Two(..) => *self,
            Zoned::Unsolvable => return f64::NAN,
        };
        -cached(Key::Radius(law.model, law.bits(), a.to_bits()), || {
            Cached::X(match &zoned {
                // The bisection ends at its bracket's end where no radius matches: NaN then.
                Zoned::Two(z, ..) => Some(x_at_radius(z, a))
                    .filter(|&x| point(z, x).is_some_and(|p| (p.a / a - 1.0).abs() <= 1e-9))
                    .unwrap_or(f64::NAN),
                _ => x_at_radius_newton(law.lambda, a),
            })
        })
        .x()
    }

    /// The pieces after the free one, from the free end up, each with the parameter range it is
    /// followed over: the contact piece from its start up to radius `a_max`. Two zones'
    /// non-contact piece is both of its stretches, the parameter `C_L` of the longer zone's disc
    /// up to its end, then `C_L` plus the shorter zone's `C_S`.
    pub fn pieces(&self, a_max: f64) -> Vec<(Piece, f64, f64)> {
        let contact = (
            Piece::Contact,
            self.t_of_radius(A_START),
            self.t_of_radius(a_max),
        );
        match self.zoned() {
            Zoned::One(l) if l.model == Model::Md => {
                let c_end = zero_radius_end(l.lambda).c;
                vec![(Piece::NonContact, 0.0, c_end), contact]
            }
            Zoned::Two(_, _, (c_l, c_s)) => vec![(Piece::NonContact, 0.0, c_l + c_s), contact],
            _ => vec![contact],
        }
    }

    /// The load-controlled pull-off's magnitude, |Pbar_c| in units of `pi w R` (Hertz: 0;
    /// Maugis-Dugdale: the Johnson-Greenwood fit, within 2% of the exact; two zones: the
    /// exact, in their total w's units): a fit starts each model's w from the measured
    /// pull-off with it.
    pub fn pulloff(&self) -> f64 {
        match self.model {
            Model::Hertz => 0.0,
            Model::Dmt => 2.0,
            Model::Jkr => 1.5,
            Model::Md => crate::physics::closed::cos_pulloff(self.lambda).abs(),
            Model::SolidAndMeniscus => self
                .zones()
                .and_then(|z| TwoZoneContext::new(z).ok())
                .map_or(f64::NAN, |c| c.load_pulloff.load.abs()),
        }
    }

    /// Whether a state exists at parameter `t` of `piece` (JKR's contact piece needs A > 0).
    pub fn on_piece(&self, piece: Piece, t: f64) -> bool {
        t.is_finite() && !(self.model == Model::Jkr && piece == Piece::Contact && t <= 0.0)
    }

    /// The states at the nodes of a piece between t0 and t1 (kept per thread: a fit at fixed
    /// lambda evaluates them once).
    pub(crate) fn nodes(&self, piece: Piece, t0: f64, t1: f64) -> std::rc::Rc<Vec<(f64, Pt)>> {
        let key = Key::Nodes(self.model, self.bits(), piece, t0.to_bits(), t1.to_bits());
        let v = cached(key, || {
            // One zone's non-contact piece is a quadratic in C: one fold at most.
            let n = if piece == Piece::NonContact && self.model != Model::SolidAndMeniscus {
                64
            } else {
                NODES
            };
            Cached::Nodes(std::rc::Rc::new(
                (0..n)
                    .map(|i| {
                        let t = t0 + (t1 - t0) * i as f64 / (n - 1) as f64;
                        (t, self.state(piece, t))
                    })
                    .collect(),
            ))
        });
        match v {
            Cached::Nodes(n) => n,
            _ => unreachable!("a node key holds nodes"),
        }
    }
}

/// What the per-thread cache holds: a radius's parameter on the contact piece, the states at
/// a piece's nodes, or two zones' non-contact ends (keyed by the law's bits).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Key {
    Radius(Model, [u64; 3], u64),
    Nodes(Model, [u64; 3], Piece, u64, u64),
    Ends([u64; 3]),
}

#[derive(Clone)]
enum Cached {
    X(f64),
    Nodes(std::rc::Rc<Vec<(f64, Pt)>>),
    Ends((f64, f64)),
}

impl Cached {
    fn x(&self) -> f64 {
        match self {
            Cached::X(x) => *x,
            _ => unreachable!("a radius key holds a parameter"),
        }
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

/// Entries kept per thread: a fit at fixed lambda needs a handful (the radii of the doubling
/// and the two pieces' nodes); a free fit, whose lambda moves at every step, only cycles them,
/// as does every fit of the two-zone law (its zones' ratios move with E* and w).
const CACHE: usize = 16;

thread_local! {
    static PATH_CACHE: std::cell::RefCell<(usize, Vec<(Key, Cached)>)> =
        const { std::cell::RefCell::new((0, Vec::new())) };
}

/// The cached value of `key`, computed by `f` on a miss (the same value, bit for bit).
fn cached(key: Key, f: impl FnOnce() -> Cached) -> Cached {
    if let Some(v) = PATH_CACHE.with(|c| {
        c.borrow()
            .1
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| v.clone())
    }) {
        return v;
    }
    let v = f();
    PATH_CACHE.with(|c| {
        let mut c = c.borrow_mut();
        let (next, entries) = &mut *c;
        if entries.len() < CACHE {
            entries.push((key, v.clone()));
        } else {
            entries[*next] = (key, v.clone());
            *next = (*next + 1) % CACHE;
        }
    });
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lambda_slopes_of_the_pieces_match_differences() {
        for &lambda in &[0.05, 0.7, 6.0] {
            let c_end = crate::physics::md::zero_radius_end(lambda).c;
            for (piece, t) in [
                (Piece::NonContact, 0.3 * c_end),
                (Piece::NonContact, 0.9 * c_end),
                (Piece::Contact, -3.0),
                (Piece::Contact, 0.5),
                (Piece::Contact, 4.0),
            ] {
                let (dl, dd) = Law::new(Model::Md, lambda).state_dlambda(piece, t);
                let h = 1e-5 * lambda;
                let (p, m) = (
                    Law::new(Model::Md, lambda + h).state(piece, t),
                    Law::new(Model::Md, lambda - h).state(piece, t),
                );
                let fl = (p.load - m.load) / (2.0 * h);
                let fd = (p.approach - m.approach) / (2.0 * h);
                let at = format!("{piece:?} at lambda {lambda}, t {t}");
                assert!(
                    (dl - fl).abs() <= 1e-7 * fl.abs().max(1.0),
                    "{at}: {dl} {fl}"
                );
                assert!(
                    (dd - fd).abs() <= 1e-7 * fd.abs().max(1.0),
                    "{at}: {dd} {fd}"
                );
            }
        }
        assert_eq!(
            Law::new(Model::Jkr, 1.0).state_dlambda(Piece::Contact, 2.0),
            (0.0, 0.0)
        );
        assert_eq!(
            Law::new(Model::Md, 1.0).state_dlambda(Piece::Free, 2.0),
            (0.0, 0.0)
        );
    }

    /// The pull-offs the starts take w from: DMT's and JKR's are Maugis-Dugdale's limits and
    /// their paths' most tensile loads; Maugis-Dugdale's is within 2% of its path's.
    #[test]
    fn pulloffs_are_the_models_and_the_limits() {
        let md = |lambda: f64| Law::new(Model::Md, lambda).pulloff();
        assert!((md(1e-4) - Law::new(Model::Dmt, 1.0).pulloff()).abs() < 1e-3);
        assert!((md(1e4) - Law::new(Model::Jkr, 1.0).pulloff()).abs() < 1e-3);
        assert_eq!(Law::new(Model::Hertz, 1.0).pulloff(), 0.0);
        for law in [
            Law::new(Model::Jkr, 1.0),
            Law::new(Model::Md, 0.3),
            Law::new(Model::Md, 3.0),
        ] {
            let contact = law.pieces(4.0).pop().unwrap();
            let lowest = (0..20001)
                .map(|i| contact.1 + (contact.2 - contact.1) * i as f64 / 20000.0)
                .map(|t| law.state(Piece::Contact, t).load)
                .fold(f64::INFINITY, f64::min);
            let tol = if law.model == Model::Md { 0.02 } else { 1e-6 };
            assert!(
                (-lowest / law.pulloff() - 1.0).abs() < tol,
                "{law:?}: {lowest} {}",
                law.pulloff()
            );
        }
    }

    /// Each law's pieces join: the free piece ends where the first starts (DMT's load apart:
    /// its adhesion, -2, acts from the touch), and each piece's end is the next one's start
    /// (the contact piece starts at A = 1e-9, where JKR's approach is -(2/3) sqrt(6 A), 5e-5:
    /// joints within 1e-4).
    #[test]
    fn each_laws_pieces_join() {
        for model in Model::ALL {
            for lambda in [0.05, 0.7, 6.0, 40.0] {
                let law = Law::new(model, lambda);
                let pieces = law.pieces(4.0);
                let at = format!("{model:?} at lambda {lambda}");
                let first = law.state(pieces[0].0, pieces[0].1);
                assert!((first.approach - law.free_end()).abs() <= 1e-4, "{at}");
                let touch = if model == Model::Dmt { -2.0 } else { 0.0 };
                assert!((first.load - touch).abs() <= 1e-6, "{at}: {}", first.load);
                for w in pieces.windows(2) {
                    let (end, start) = (law.state(w[0].0, w[0].2), law.state(w[1].0, w[1].1));
                    assert!(
                        (end.load - start.load).abs() <= 1e-4,
                        "{at}: {end:?} {start:?}"
                    );
                    assert!((end.approach - start.approach).abs() <= 1e-4, "{at}");
                }
                let top = law.state(Piece::Contact, pieces.last().unwrap().2);
                assert!((top.a - 4.0).abs() <= 1e-12 * 4.0, "{at}: {}", top.a);
            }
        }
    }

    /// Two zones (meniscus longer, much longer, and shorter than the solid's): the pieces join
    /// at the contact curve's A -> 0 end, the free end is the longer range, the contact piece
    /// reaches the asked radius, and every state's slopes in t are the central differences of
    /// the states. A meniscus without stress is Maugis-Dugdale itself.
    #[test]
    fn two_zone_pieces_join_and_their_slopes_are_the_differences() {
        for (lambda, rho, eta) in [(0.5, 0.2, 5.0), (2.0, 0.05, 10.0), (1.0, 3.0, 0.3)] {
            let law = Law::solid_and_meniscus(lambda, rho, eta);
            let at = format!("lambda {lambda}, ratios {rho} {eta}");
            let pieces = law.pieces(3.0);
            assert_eq!(pieces.len(), 2, "{at}");
            let z = Zones::from_ratios(lambda, rho, eta).unwrap();
            let h_long = z.range[0].max(z.range[1]);
            assert_eq!(law.free_end(), -h_long, "{at}");
            let first = law.state(Piece::NonContact, 0.0);
            assert!(
                (first.approach + h_long).abs() <= 1e-12 && first.load == 0.0,
                "{at}"
            );
            let (end, start) = (
                law.state(Piece::NonContact, pieces[0].2),
                law.state(Piece::Contact, pieces[1].1),
            );
            assert!(
                (end.load - start.load).abs() <= 1e-8,
                "{at}: {end:?} {start:?}"
            );
            assert!((end.approach - start.approach).abs() <= 1e-8, "{at}");
            let top = law.state(Piece::Contact, pieces[1].2);
            assert!((top.a / 3.0 - 1.0).abs() <= 1e-12, "{at}: {}", top.a);
            for (piece, t0, t1) in pieces {
                for k in 1..20 {
                    let t = t0 + (t1 - t0) * k as f64 / 20.0;
                    let h = 1e-5 * (1.0 + t.abs());
                    let (p, up, down) = (
                        law.state(piece, t),
                        law.state(piece, t + h),
                        law.state(piece, t - h),
                    );
                    for (name, slope, diff) in [
                        ("load", p.dload, (up.load - down.load) / (2.0 * h)),
                        (
                            "approach",
                            p.dapproach,
                            (up.approach - down.approach) / (2.0 * h),
                        ),
                        ("a", p.da, (up.a - down.a) / (2.0 * h)),
                    ] {
                        let scale = diff.abs().max(1e-3);
                        assert!(
                            (slope - diff).abs() <= 1e-5 * scale,
                            "{at}, {piece:?} t {t}: d{name}/dt {slope} against {diff}"
                        );
                    }
                }
            }
        }
        // The single stretch of the non-contact piece: the longer zone's disc alone, its load
        // -(pi/2) lambda_L C^2 in closed form, its slope -pi lambda_L C.
        let z = Zones::from_ratios(0.5, 0.2, 5.0).unwrap();
        let (law, long) = (Law::solid_and_meniscus(0.5, 0.2, 5.0), 1);
        let c_l = law.pieces(3.0)[0].2 - non_contact_ends(&z).unwrap().1;
        for c in [0.0, 0.3 * c_l, c_l] {
            let p = law.state(Piece::NonContact, c);
            let l = z.lambda[long];
            assert!((p.load + PI / 2.0 * l * c * c).abs() <= 1e-15, "C {c}");
            assert!(
                (p.dload + PI * l * c).abs() <= 1e-6 * (1.0 + c),
                "C {c}: {}",
                p.dload
            );
        }
        // The load-controlled pull-off: within the two-zone bounds [3/2, 2] for two ranges, and
        // Maugis-Dugdale's exact one where the zones share a range (the summed lambda).
        for (lambda, rho, eta) in [(0.5, 0.2, 5.0), (2.0, 0.05, 10.0), (1.0, 3.0, 0.3)] {
            let p = Law::solid_and_meniscus(lambda, rho, eta).pulloff();
            assert!((1.5..=2.0).contains(&p), "{lambda} {rho} {eta}: {p}");
        }
        let z = Zones::from_ratios(0.8, 0.5, 1.0).unwrap();
        let exact = crate::solver::LambdaContext::new(z.lambda[0] + z.lambda[1])
            .unwrap()
            .load_pulloff
            .load;
        let p = Law::solid_and_meniscus(0.8, 0.5, 1.0).pulloff();
        assert!((p + exact).abs() <= 1e-12, "{p} against {exact}");
        // No meniscus stress: one zone, Maugis-Dugdale at the solid's lambda.
        let (dry, md) = (
            Law::solid_and_meniscus(0.8, 0.0, 3.0),
            Law::new(Model::Md, 0.8),
        );
        assert_eq!(dry.pieces(2.0), md.pieces(2.0));
        let t = md.t_of_radius(1.3);
        assert_eq!(dry.state(Piece::Contact, t), md.state(Piece::Contact, t));
    }
}
