//! Contact laws: one trait ([`Law`]) that every law tabor solves implements in its own file, and
//! [`ContactLaw`], the serialisable value the front ends build, whose `impl` is the one place
//! that matches on the law. A law's equilibrium path is a list of pieces after the free one,
//! each state an explicit function of its piece's parameter t with its slopes in t (and in
//! lambda where the law has one); its exact folds come from the law too. The one follower
//! is generic over it: [`follow::DrivenPath`], the path under any drive (a spring, rigid grips,
//! a dead load) with its folds, jumps and landings, evaluated at any control: the fits' force
//! and the cycles' steps.
//!
//! A new law is a file here implementing [`Law`], one [`ContactLaw`] variant with its arm in
//! [`ContactLaw::law`], and its run of the conformance suite (`tests/suite/law.rs`).

use crate::physics::model::ContactModel;
use serde::Serialize;

mod cache;
pub mod closed;
pub mod follow;
pub mod md;
pub mod path;
pub mod stretch;
pub mod tip;
pub mod tip_closed;
pub mod two_zone;

pub use closed::{Dmt, Hertz, Jkr};
pub use md::Md;
pub use path::{Branch, Drive, PathPoint};
pub use tip::Tip;
pub use tip_closed::TipClosed;
pub use two_zone::TwoZones;

/// What fixes a law's state: each front end's own names (a flag, a keyword, a column) map to it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Given {
    /// The load: the state stable under a dead load.
    Load,
    /// The approach: the state stable under rigid grips.
    Approach,
    /// The contact radius: the contact branch's point there, stable or not.
    Radius,
}

/// A piece of a law's equilibrium path, each with its own parameter t.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Piece {
    /// Apart, no force: t is the approach Dbar.
    Free,
    /// Apart with a cohesive zone (Maugis-Dugdale: its outer radius t = C > 0).
    NonContact,
    /// In contact: t = -ln mu for Maugis-Dugdale, t = A for the closed forms.
    Contact,
}

impl Piece {
    /// The branch of the path the piece is.
    pub fn branch(self) -> Branch {
        match self {
            Piece::Free => Branch::Free,
            Piece::NonContact => Branch::NonContact,
            Piece::Contact => Branch::Contact,
        }
    }
}

/// A state and its slopes with respect to the piece's parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pt {
    /// The load Pbar.
    pub load: f64,
    /// The approach Dbar.
    pub approach: f64,
    /// The contact radius A (0 apart).
    pub a: f64,
    /// dPbar/dt.
    pub dload: f64,
    /// dDbar/dt.
    pub dapproach: f64,
    /// dA/dt.
    pub da: f64,
}

impl Pt {
    /// No state: every number NaN.
    pub(crate) fn nan() -> Pt {
        Pt {
            load: f64::NAN,
            approach: f64::NAN,
            a: f64::NAN,
            dload: f64::NAN,
            dapproach: f64::NAN,
            da: f64::NAN,
        }
    }

    /// The free piece's state at approach `t`: every law's.
    pub(crate) fn free(t: f64) -> Pt {
        Pt {
            load: 0.0,
            approach: t,
            a: 0.0,
            dload: 0.0,
            dapproach: 1.0,
            da: 0.0,
        }
    }
}

/// A law's identity in the per-thread cache of its costly values: its model and its numbers'
/// bits (equal keys, equal states).
pub type LawKey = (ContactModel, [u64; 4]);

/// The contact piece starts at this radius (Maugis-Dugdale: where it meets the non-contact piece
/// to 1e-9; JKR: where its approach slope is still finite).
pub const A_START: f64 = 1e-9;
/// Nodes per piece: they only bracket folds and roots (folds closer than a node spacing, on a
/// stretch shorter than that, are not resolved; such a stretch moves the force by less than it).
pub const NODES: usize = 320;

/// Why a law's path or states could not be had: the law's or the drive's numbers (one line
/// naming the quantity, the value and what to give), or a two-zone curve that did not solve.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LawError {
    /// A Maugis-Dugdale lambda or a drive out of its domain.
    #[error(transparent)]
    Solve(#[from] crate::solver::SolveError),
    /// The two-zone law.
    #[error(transparent)]
    Zones(#[from] crate::solver::two_zone::ZonesError),
    /// An operation the law does not have (a closed form's cycle).
    #[error("the {model} law has no {what}: use md (or solid_and_meniscus)", model = .model.label())]
    Unsupported {
        /// The law.
        model: ContactModel,
        /// The operation.
        what: &'static str,
    },
}

impl crate::error::Named for LawError {
    fn named(&self, names: crate::error::Names) -> String {
        match self {
            LawError::Solve(e) => e.named(names),
            LawError::Zones(e) => e.named(names),
            e => e.to_string(),
        }
    }
}

/// A contact law in the normalised units of docs/PHYSICS.md (the two-zone law in its total-w
/// units): its equilibrium path as pieces, its states and slopes on them, its folds.
pub trait Law {
    /// The model in the common vocabulary.
    fn model(&self) -> ContactModel;
    /// The Maugis parameter (the solid's, for two zones); None for the closed forms.
    fn lambda(&self) -> Option<f64>;
    /// The state at parameter `t` of `piece` (NaN where there is none).
    fn state(&self, piece: Piece, t: f64) -> Pt;
    /// The slopes of the load and the approach with respect to lambda at fixed t on `piece`
    /// (zero where the law has no lambda; NaN where they are taken by differences).
    fn state_dlambda(&self, piece: Piece, t: f64) -> (f64, f64);
    /// The approach at which the free piece ends and a force first acts.
    fn free_end(&self) -> f64;
    /// The contact piece's parameter at contact radius `a` (NaN where no state has it).
    fn t_of_radius(&self, a: f64) -> f64;
    /// The pieces after the free one, from the free end up, each with the parameter range it
    /// is followed over: the contact piece from [`A_START`] up to radius `a_max`.
    fn pieces(&self, a_max: f64) -> Vec<(Piece, f64, f64)>;
    /// The load-controlled pull-off's magnitude |Pbar_c| (a fit's start for w; Maugis-Dugdale:
    /// the Johnson-Greenwood fit, within 2% of the exact).
    fn pulloff(&self) -> f64;
    /// The parameters inside `piece` where its states change formula (the two-zone law's second
    /// disc starting), where the path's slope may jump: a path that turns back there does so
    /// within rounding of the break, closer than evenly spread probes see.
    fn breaks(&self, piece: Piece) -> Vec<f64> {
        let _ = piece;
        Vec::new()
    }
    /// Whether a state exists at parameter `t` of `piece`.
    fn on_piece(&self, piece: Piece, t: f64) -> bool {
        let _ = piece;
        t.is_finite()
    }
    /// How many nodes bracket a piece's folds and roots.
    fn node_count(&self, piece: Piece) -> usize {
        let _ = piece;
        NODES
    }
    /// The cache's key of the law (its model and bits): equal keys, equal states.
    fn key(&self) -> LawKey;
    /// The state at parameter `t` of `piece` as a path point, with its zone's outer radius
    /// (`PathPoint::c`: by default t on the non-contact piece and the contact radius in contact,
    /// where a closed form has no zone).
    fn point(&self, piece: Piece, t: f64) -> PathPoint {
        path::point_of(piece, t, &self.state(piece, t))
    }
    /// Where a cycle samples the equilibrium path after the free piece, up to `max_load`: each
    /// sample's piece and parameter (non-contact, then contact; the parameter rising along
    /// each), after the law's and the drive's checks. The cycle adds the free piece and
    /// follows the path exactly ([`follow::DrivenPath`]); the samples are what it draws.
    fn cycle_path(&self, drive: Drive, max_load: f64) -> Result<Vec<(Piece, f64)>, LawError> {
        let _ = (drive, max_load);
        Err(LawError::Unsupported {
            model: self.model(),
            what: "approach-retract cycle",
        })
    }
    /// The law's own checks (its numbers in their domain) for an operation that follows its
    /// path; a law without one (a closed form) says so. By default its cycle's.
    fn check(&self) -> Result<(), LawError> {
        self.cycle_path(Drive::RigidGrips, 1.0).map(|_| ())
    }
    /// The exact fold of the contact branch under `drive` near the state `near`, from the law's
    /// own solver (rigid grips: the displacement-controlled pull-off; dead load: the
    /// load-controlled one; a spring: where dPbar/dDbar = -kbar), where the law has it: the
    /// conformance suite's reference for the follower's folds.
    fn fold(&self, drive: Drive, near: &PathPoint) -> Option<PathPoint> {
        let _ = (drive, near);
        None
    }
}

/// The states at the nodes of a piece between t0 and t1 (kept per thread: a fit at fixed
/// lambda evaluates them once).
pub fn nodes<L: Law + ?Sized>(
    law: &L,
    piece: Piece,
    t0: f64,
    t1: f64,
) -> std::rc::Rc<Vec<(f64, Pt)>> {
    cache::nodes(law.key(), piece, t0, t1, || {
        let n = law.node_count(piece);
        (0..n)
            .map(|i| {
                let t = t0 + (t1 - t0) * i as f64 / (n - 1) as f64;
                (t, law.state(piece, t))
            })
            .collect()
    })
}

/// A contact law tabor solves exactly, with its parameters: the value the front ends build and
/// every operation takes (in the normalised units of docs/PHYSICS.md; the two-zone law in its
/// total-w units). Serialised with its model's name under `model`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "model", rename_all = "snake_case")]
pub enum ContactLaw {
    /// Hertz: no adhesion.
    Hertz,
    /// DMT: Hertz plus the adhesive load `2 pi w R` outside the contact.
    Dmt,
    /// JKR: adhesion inside the contact, a crack at its edge.
    Jkr,
    /// Maugis-Dugdale: one Dugdale zone.
    Md(Md),
    /// The solid's Dugdale zone plus a water meniscus, a second zone (docs/PHYSICS.md section
    /// 10).
    SolidAndMeniscus(TwoZones),
    /// Maugis-Dugdale on an axisymmetric tip (a power law or a capped cone; docs/PHYSICS.md
    /// section 12), in the shape's units.
    Tip(Tip),
    /// A tip's closed forms: Sneddon's adhesion-free punch or the JKR-type law (docs/PHYSICS.md
    /// section 12.4), in the shape's units.
    TipClosed(TipClosed),
}

impl ContactLaw {
    /// MD at `lambda`, or with both of the second zone's ratios the two-zone law: the one
    /// pairing check of every front end (a lone ratio is refused, naming both).
    pub fn new(
        lambda: f64,
        stress_ratio: Option<f64>,
        range_ratio: Option<f64>,
    ) -> Result<ContactLaw, crate::error::Message> {
        let ratios = crate::physics::two_zone::paired_ratios(stress_ratio, range_ratio)?;
        Ok(ContactLaw::with_ratios(lambda, ratios))
    }

    /// MD at `lambda`, or with the second zone's (stress, range) ratios, already paired, the
    /// two-zone law.
    pub fn with_ratios(lambda: f64, ratios: Option<(f64, f64)>) -> ContactLaw {
        match ratios {
            None => ContactLaw::md(lambda),
            Some((stress_ratio, range_ratio)) => {
                ContactLaw::solid_and_meniscus(lambda, stress_ratio, range_ratio)
            }
        }
    }

    /// Maugis-Dugdale at `lambda`.
    pub fn md(lambda: f64) -> ContactLaw {
        ContactLaw::Md(Md { lambda })
    }

    /// The two-zone law: the solid's zone at its own Maugis parameter `lambda` and a second
    /// zone of `stress_ratio` and `range_ratio` times its stress and range.
    pub fn solid_and_meniscus(lambda: f64, stress_ratio: f64, range_ratio: f64) -> ContactLaw {
        ContactLaw::SolidAndMeniscus(TwoZones {
            lambda,
            stress_ratio,
            range_ratio,
        })
    }

    /// The law itself: the one match on the variant.
    pub fn law(&self) -> &dyn Law {
        match self {
            ContactLaw::Hertz => &Hertz,
            ContactLaw::Dmt => &Dmt,
            ContactLaw::Jkr => &Jkr,
            ContactLaw::Md(l) => l,
            ContactLaw::SolidAndMeniscus(l) => l,
            ContactLaw::Tip(l) => l,
            ContactLaw::TipClosed(l) => l,
        }
    }

    /// The law's model name.
    pub fn model(&self) -> ContactModel {
        self.law().model()
    }

    /// The (solid's) Maugis parameter; None for the closed forms.
    pub fn lambda(&self) -> Option<f64> {
        self.law().lambda()
    }
}

impl Law for ContactLaw {
    fn model(&self) -> ContactModel {
        self.law().model()
    }
    fn lambda(&self) -> Option<f64> {
        self.law().lambda()
    }
    fn state(&self, piece: Piece, t: f64) -> Pt {
        self.law().state(piece, t)
    }
    fn state_dlambda(&self, piece: Piece, t: f64) -> (f64, f64) {
        self.law().state_dlambda(piece, t)
    }
    fn free_end(&self) -> f64 {
        self.law().free_end()
    }
    fn t_of_radius(&self, a: f64) -> f64 {
        self.law().t_of_radius(a)
    }
    fn pieces(&self, a_max: f64) -> Vec<(Piece, f64, f64)> {
        self.law().pieces(a_max)
    }
    fn pulloff(&self) -> f64 {
        self.law().pulloff()
    }
    fn breaks(&self, piece: Piece) -> Vec<f64> {
        self.law().breaks(piece)
    }
    fn on_piece(&self, piece: Piece, t: f64) -> bool {
        self.law().on_piece(piece, t)
    }
    fn node_count(&self, piece: Piece) -> usize {
        self.law().node_count(piece)
    }
    fn key(&self) -> LawKey {
        self.law().key()
    }
    fn point(&self, piece: Piece, t: f64) -> PathPoint {
        self.law().point(piece, t)
    }
    fn cycle_path(&self, drive: Drive, max_load: f64) -> Result<Vec<(Piece, f64)>, LawError> {
        self.law().cycle_path(drive, max_load)
    }
    fn check(&self) -> Result<(), LawError> {
        self.law().check()
    }
    fn fold(&self, drive: Drive, near: &PathPoint) -> Option<PathPoint> {
        self.law().fold(drive, near)
    }
}
