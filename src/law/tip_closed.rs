//! The closed forms of an axisymmetric tip (docs/PHYSICS.md section 12.4), in the shape's
//! units: Sneddon's adhesion-free punch (the tip's Hertz, `Pbar = Qbar(A)`, `Dbar = Fbar(A)`)
//! and the JKR-type law (`Pbar = Qbar(A) - sqrt(6 A^3)`, `Dbar = Fbar(A) - sqrt(8 A/3)`), the
//! limits of [`super::Tip`] without adhesion and at lambda -> infinity. Their path is the free
//! piece, then the contact piece t = ln A, as the tip's Maugis-Dugdale law (a cone's units
//! shrink like w, so a fit towards w -> 0 meets radii of 1e9 units, where nodes even in A would
//! not resolve the start of contact; for the paraboloid, `Fbar = T^2`, they are Hertz and JKR). A DMT-type law is not among them: beyond the
//! paraboloid the rigid tip's Dugdale force depends on the range (`pi w h0 tan^2 alpha` for a
//! cone), so it has Maugis-Dugdale's parameters and is no simpler model.

use super::{Law, LawKey, Piece, Pt, A_START};
use crate::physics::model::ContactModel;
use crate::physics::tip::Shape;
use serde::Serialize;

/// A closed form on a tip of shape `shape`: `adhesive` false is Sneddon's punch (Hertz-type),
/// true the JKR-type law.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TipClosed {
    /// The tip in its normalised units.
    #[serde(flatten)]
    pub shape: Shape,
    /// JKR-type (true) or adhesion-free (false).
    pub adhesive: bool,
}

impl Law for TipClosed {
    fn model(&self) -> ContactModel {
        if self.adhesive {
            ContactModel::Jkr
        } else {
            ContactModel::Hertz
        }
    }
    fn lambda(&self) -> Option<f64> {
        None
    }
    fn state(&self, piece: Piece, t: f64) -> Pt {
        match piece {
            Piece::Contact => {
                let a = t.exp();
                let (q, dq) = self.shape.load(a);
                let (f, df) = self.shape.abel(a);
                let (jl, ja, djl, dja) = if self.adhesive {
                    let s6 = (6.0 * a).sqrt();
                    (
                        a * s6,
                        (8.0 * a / 3.0).sqrt(),
                        1.5 * s6,
                        (2.0 / (3.0 * a)).sqrt(),
                    )
                } else {
                    (0.0, 0.0, 0.0, 0.0)
                };
                // Slopes in t = ln A: A times those in A.
                Pt {
                    load: q - jl,
                    approach: f - ja,
                    a,
                    dload: a * (dq - djl),
                    dapproach: a * (df - dja),
                    da: a,
                }
            }
            Piece::Free => Pt::free(t),
            Piece::NonContact => Pt::nan(),
        }
    }
    fn state_dlambda(&self, _: Piece, _: f64) -> (f64, f64) {
        (0.0, 0.0)
    }
    fn free_end(&self) -> f64 {
        0.0
    }
    /// The contact piece's parameter is ln A.
    fn t_of_radius(&self, a: f64) -> f64 {
        a.ln()
    }
    fn pieces(&self, a_max: f64) -> Vec<(Piece, f64, f64)> {
        vec![(Piece::Contact, A_START.ln(), a_max.ln())]
    }
    fn pulloff(&self) -> f64 {
        if !self.adhesive {
            return 0.0;
        }
        let a = self.shape.jkr_pulloff_radius();
        -self.state(Piece::Contact, a.ln()).load
    }
    fn key(&self) -> LawKey {
        let [kind, a, b] = super::tip::shape_bits(&self.shape);
        (self.model(), [10 + kind, a, b, 0])
    }
}
