//! The contact models a force curve is fitted with: the ladder the adequacy test climbs (Hertz,
//! DMT, JKR, Maugis-Dugdale) and the two-zone law fitted beside it to a humid curve. Each is a
//! [`ContactLaw`] at the fitted lambda; the laws themselves, their paths and the follower under
//! the cantilever are the law layer's (`crate::law`).

use crate::law::ContactLaw;
use crate::physics::model::ContactModel;
use serde::{Deserialize, Serialize};

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

    /// The model's law at `lambda` (ignored by the closed forms; the two-zone law's is built
    /// with its meniscus by [`crate::law::TwoZones::of_sphere_in_meniscus`]).
    pub fn law(self, lambda: f64) -> ContactLaw {
        match self {
            Model::Hertz => ContactLaw::Hertz,
            Model::Dmt => ContactLaw::Dmt,
            Model::Jkr => ContactLaw::Jkr,
            Model::Md => ContactLaw::md(lambda),
            Model::SolidAndMeniscus => ContactLaw::solid_and_meniscus(lambda, 0.0, 0.0),
        }
    }
}

impl From<Model> for ContactModel {
    fn from(m: Model) -> ContactModel {
        m.contact_model()
    }
}

impl TryFrom<ContactModel> for Model {
    type Error = super::CurveError;

    /// The ladder's model of a contact model; the rigid and two-zone ones are not on it (the
    /// two-zone law is fitted beside it, with a humidity).
    fn try_from(m: ContactModel) -> Result<Model, super::CurveError> {
        Model::ALL
            .into_iter()
            .find(|f| f.contact_model() == m)
            .ok_or(super::CurveError::NotFitted(m))
    }
}
