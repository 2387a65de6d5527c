//! The contact models tabor names, one vocabulary for every part of it: the map's regions, the
//! fit's models, the profiles, the scenes' recommendations, the renderer and Python all take
//! their names (JSON, command line) and labels (figures, text) from here.

use serde::{Deserialize, Serialize};

/// How far a simpler model may be from the exact Maugis-Dugdale answer and still be the one a
/// contact needs (the map's regions, a scene's recommended model, a fit's adequate model, the
/// rough map's summit models), unless told otherwise: 5%.
pub const DEFAULT_TOLERANCE: f64 = 0.05;

/// A contact model, from the simplest.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactModel {
    /// Elastic, no adhesion.
    Hertz,
    /// Bradley's rigid spheres: adhesion without elasticity (pull-off `2 pi w R`).
    Rigid,
    /// Derjaguin-Muller-Toporov: Hertz plus the adhesive load outside the contact.
    Dmt,
    /// Johnson-Kendall-Roberts: adhesion inside the contact, a crack at its edge.
    Jkr,
    /// Maugis-Dugdale: one Dugdale zone of stress `s0` over the range `h0`, exact.
    Md,
    /// The solid's Dugdale zone plus a water meniscus: two zones (docs/PHYSICS.md section 10).
    SolidAndMeniscus,
}

impl ContactModel {
    /// Every model, simplest first.
    pub const ALL: [ContactModel; 6] = [
        ContactModel::Hertz,
        ContactModel::Rigid,
        ContactModel::Dmt,
        ContactModel::Jkr,
        ContactModel::Md,
        ContactModel::SolidAndMeniscus,
    ];

    /// The closed forms an adhesion map (smooth or rough) tries before Maugis-Dugdale, in the
    /// order of its per-model columns.
    pub const CLOSED_FORMS: [ContactModel; 4] = [
        ContactModel::Hertz,
        ContactModel::Rigid,
        ContactModel::Dmt,
        ContactModel::Jkr,
    ];

    /// The name in JSON, CSV and on the command line (serde's).
    pub fn name(self) -> &'static str {
        match self {
            ContactModel::Hertz => "hertz",
            ContactModel::Rigid => "rigid",
            ContactModel::Dmt => "dmt",
            ContactModel::Jkr => "jkr",
            ContactModel::Md => "md",
            ContactModel::SolidAndMeniscus => "solid_and_meniscus",
        }
    }

    /// The name for people: figures and text.
    pub fn label(self) -> &'static str {
        match self {
            ContactModel::Hertz => "Hertz",
            ContactModel::Rigid => "Bradley (rigid)",
            ContactModel::Dmt => "DMT",
            ContactModel::Jkr => "JKR",
            ContactModel::Md => "Maugis-Dugdale",
            ContactModel::SolidAndMeniscus => "solid and meniscus",
        }
    }
}

impl std::fmt::Display for ContactModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not a contact model.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownModel(pub String);

impl std::fmt::Display for UnknownModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let names: Vec<&str> = ContactModel::ALL.iter().map(|m| m.name()).collect();
        write!(
            f,
            "unknown contact model {:?}: use one of {}",
            self.0,
            names.join(", ")
        )
    }
}

impl std::error::Error for UnknownModel {}

impl std::str::FromStr for ContactModel {
    type Err = UnknownModel;

    /// The name, case-insensitive, or a common spelling ("bradley", "maugis-dugdale").
    fn from_str(s: &str) -> Result<ContactModel, UnknownModel> {
        let key = s.trim().to_ascii_lowercase().replace(['-', ' '], "_");
        let alias = match key.as_str() {
            "bradley" => Some(ContactModel::Rigid),
            "maugis_dugdale" | "maugis" => Some(ContactModel::Md),
            "two_zone" | "humid" => Some(ContactModel::SolidAndMeniscus),
            _ => None,
        };
        alias
            .or_else(|| ContactModel::ALL.into_iter().find(|m| m.name() == key))
            .ok_or_else(|| UnknownModel(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_through_text_and_serde() {
        for m in ContactModel::ALL {
            assert_eq!(m.name().parse::<ContactModel>(), Ok(m));
            assert_eq!(m.to_string(), m.name());
            let json = serde_json::to_string(&m).unwrap();
            assert_eq!(json, format!("\"{}\"", m.name()));
            assert_eq!(serde_json::from_str::<ContactModel>(&json).unwrap(), m);
        }
        assert_eq!("Bradley".parse::<ContactModel>(), Ok(ContactModel::Rigid));
        assert_eq!(
            "Maugis-Dugdale".parse::<ContactModel>(),
            Ok(ContactModel::Md)
        );
        let e = "greenwood".parse::<ContactModel>().unwrap_err().to_string();
        assert!(
            e.contains("\"greenwood\"") && e.contains("hertz, rigid, dmt"),
            "{e}"
        );
    }
}
