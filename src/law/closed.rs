//! The closed forms: Hertz, DMT and JKR (docs/PHYSICS.md section 2), in Maugis's normalised
//! units. Their path is the free piece, then the contact piece parametrised by the radius
//! t = A; the adhesive ones touch at approach 0 (DMT with its adhesive load -2 already acting).

use super::{Law, LawKey, Piece, Pt};
use crate::physics::model::ContactModel;

/// Hertz: elastic, no adhesion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hertz;

/// DMT: Hertz plus the adhesive load `2 pi w R` outside the contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dmt;

/// JKR: adhesion inside the contact, a crack at its edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jkr;

/// Hertz's contact piece shifted by DMT's adhesive load (`adhesion`: 0 or 2).
fn hertz_state(piece: Piece, t: f64, adhesion: f64) -> Pt {
    match piece {
        Piece::Contact => Pt {
            load: t * t * t - adhesion,
            approach: t * t,
            a: t,
            dload: 3.0 * t * t,
            dapproach: 2.0 * t,
            da: 1.0,
        },
        Piece::Free => Pt::free(t),
        Piece::NonContact => Pt::nan(),
    }
}

/// The contact piece only, from `A_START` to `a_max` (t = A).
fn contact_piece(a_max: f64) -> Vec<(Piece, f64, f64)> {
    vec![(Piece::Contact, super::A_START, a_max)]
}

macro_rules! closed_form {
    ($model:expr, $pulloff:expr) => {
        fn model(&self) -> ContactModel {
            $model
        }
        fn lambda(&self) -> Option<f64> {
            None
        }
        fn state_dlambda(&self, _: Piece, _: f64) -> (f64, f64) {
            (0.0, 0.0)
        }
        fn free_end(&self) -> f64 {
            0.0
        }
        fn t_of_radius(&self, a: f64) -> f64 {
            a
        }
        fn pieces(&self, a_max: f64) -> Vec<(Piece, f64, f64)> {
            contact_piece(a_max)
        }
        fn pulloff(&self) -> f64 {
            $pulloff
        }
        fn key(&self) -> LawKey {
            ($model, [0; 4])
        }
    };
}

impl Law for Hertz {
    closed_form!(ContactModel::Hertz, 0.0);
    fn state(&self, piece: Piece, t: f64) -> Pt {
        hertz_state(piece, t, 0.0)
    }
}

impl Law for Dmt {
    closed_form!(ContactModel::Dmt, 2.0);
    fn state(&self, piece: Piece, t: f64) -> Pt {
        hertz_state(piece, t, 2.0)
    }
}

impl Law for Jkr {
    closed_form!(ContactModel::Jkr, 1.5);
    fn state(&self, piece: Piece, t: f64) -> Pt {
        match piece {
            Piece::Contact => {
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
            Piece::Free => Pt::free(t),
            Piece::NonContact => Pt::nan(),
        }
    }
    /// The contact piece needs A > 0.
    fn on_piece(&self, piece: Piece, t: f64) -> bool {
        t.is_finite() && !(piece == Piece::Contact && t <= 0.0)
    }
}
