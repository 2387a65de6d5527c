//! The one entry for a pressure-and-gap profile of any contact law (the command line's and
//! Python's): the law's own module computes it, MD in `profile/mod.rs`, the solid with its
//! meniscus in `profile/two_zone.rs`.

use crate::law::{ContactLaw, Md, TwoZones};
use crate::profile::tip::{tip_profile, TipProfile, TipProfileError};
use crate::profile::two_zone::{two_zone_profile, TwoZoneProfile, TwoZoneProfileError};
use crate::profile::{profile, Given, Profile, ProfileError};
use serde::Serialize;

/// A profile to compute: the law, the state (load, approach or contact radius, in the law's
/// normalised units) and about how many sampling radii (16..=100000).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfileSpec {
    /// The contact law.
    pub law: ContactLaw,
    /// The state.
    pub given: Given,
    /// About how many radii are sampled.
    pub points: usize,
}

/// A law's profile: MD's (with Hertz, DMT and JKR at the same load), or the two-zone state's.
/// Serialised as the law's own profile.
#[derive(Clone, Debug, Serialize)]
#[serde(untagged)]
pub enum LawProfile {
    /// Maugis-Dugdale.
    Md(Profile),
    /// The solid's Dugdale zone plus a meniscus.
    SolidAndMeniscus(TwoZoneProfile),
    /// A tip that is not a sphere.
    Tip(TipProfile),
}

/// Why a profile was not computed: the law's own error, which names the value.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LawProfileError {
    /// Maugis-Dugdale.
    #[error(transparent)]
    Md(#[from] ProfileError),
    /// The two-zone law.
    #[error(transparent)]
    SolidAndMeniscus(#[from] TwoZoneProfileError),
    /// A tip's law.
    #[error(transparent)]
    Tip(#[from] TipProfileError),
    /// A law without a profile here (the closed forms are drawn beside Maugis-Dugdale's).
    #[error(transparent)]
    Law(#[from] crate::law::LawError),
}

impl crate::error::Named for LawProfileError {
    fn named(&self, names: crate::error::Names) -> String {
        match self {
            LawProfileError::Md(e) => e.named(names),
            LawProfileError::SolidAndMeniscus(e) => e.named(names),
            LawProfileError::Tip(e) => e.named(names),
            LawProfileError::Law(e) => e.named(names),
        }
    }
}

impl ProfileSpec {
    /// The profile, by the law's module.
    pub fn run(&self) -> Result<LawProfile, LawProfileError> {
        Ok(match self.law {
            ContactLaw::Md(Md { lambda }) => {
                LawProfile::Md(profile(lambda, self.given, self.points)?)
            }
            ContactLaw::SolidAndMeniscus(TwoZones {
                lambda,
                stress_ratio,
                range_ratio,
            }) => LawProfile::SolidAndMeniscus(two_zone_profile(
                lambda,
                stress_ratio,
                range_ratio,
                self.given,
                self.points,
            )?),
            ContactLaw::Tip(t) => LawProfile::Tip(tip_profile(t, self.given, self.points)?),
            closed => {
                return Err(crate::law::LawError::Unsupported {
                    model: closed.model(),
                    what: "profile of its own (profiles of md draw it beside)",
                }
                .into())
            }
        })
    }
}
