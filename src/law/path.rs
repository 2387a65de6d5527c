//! A law's equilibrium path as a cycle samples it: the drive, the branch a state is on, a
//! sampled state, and the checks every law's cycle shares.

use serde::Serialize;

/// How the cycle is driven: the base held by rigid grips, a dead load, or a spring between them.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Drive {
    /// Displacement control.
    RigidGrips,
    /// Load control.
    DeadLoad,
    /// A spring of normalised stiffness kbar in series.
    Spring(f64),
}

impl Drive {
    /// The drive as the follower's stiffness: infinity for rigid grips, 0 for a dead load.
    pub fn kbar(self) -> f64 {
        match self {
            Drive::RigidGrips => f64::INFINITY,
            Drive::DeadLoad => 0.0,
            Drive::Spring(k) => k,
        }
    }
}

/// Which part of the equilibrium path a point is on (the codes 0, 1, 2 of the DEM law's C ABI).
#[repr(u8)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Branch {
    /// No force: the surfaces farther apart than the force range.
    #[default]
    Free = 0,
    /// A cohesive zone alone across a gap (A = 0).
    NonContact = 1,
    /// In contact.
    Contact = 2,
}

impl Branch {
    /// The branch's name in tables and JSON (`free`, `non_contact`, `contact`).
    pub fn name(self) -> &'static str {
        match self {
            Branch::Free => "free",
            Branch::NonContact => "non_contact",
            Branch::Contact => "contact",
        }
    }
}

/// One equilibrium state on the path (normalised units).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct PathPoint {
    /// The branch it is on.
    pub branch: Branch,
    /// The approach (normalised).
    pub approach: f64,
    /// The load (normalised, compressive positive).
    pub load: f64,
    /// The contact radius (0 off contact).
    pub a: f64,
    /// Normalised radius of the cohesive zone: C on the non-contact branch, m A in contact
    /// (two zones: the longer-range zone's).
    pub c: f64,
}

/// The variable the drive controls at a state: the approach (rigid grips), the load (dead
/// load), or the base `Dbar + Pbar / kbar` (a spring).
pub fn control_of(p: &PathPoint, drive: Drive) -> f64 {
    match drive {
        Drive::RigidGrips => p.approach,
        Drive::DeadLoad => p.load,
        Drive::Spring(k) => p.approach + p.load / k,
    }
}

/// The checks every law's cycle shares: the final load and the spring.
pub fn check_drive(drive: Drive, max_load: f64) -> Result<(), crate::solver::SolveError> {
    if !(max_load > 0.0 && max_load <= 1e12) {
        return Err(crate::solver::domain::DomainError {
            name: "the largest load of the approach",
            value: max_load,
            range: "(0, 1e12]",
            hint: "the approach must end in compression",
        }
        .into());
    }
    if let Drive::Spring(k) = drive {
        if !(k > 0.0 && k.is_finite()) {
            return Err(crate::solver::domain::DomainError {
                name: "the spring stiffness kbar",
                value: k,
                range: "(0, inf)",
                hint: "give a positive, finite stiffness",
            }
            .into());
        }
    }
    Ok(())
}

/// The state `p` at parameter `t` of `piece` as a path point, its zone's outer radius t on the
/// non-contact piece and the contact radius in contact ([`super::Law::point`]'s default).
pub fn point_of(piece: super::Piece, t: f64, p: &super::Pt) -> PathPoint {
    PathPoint {
        branch: piece.branch(),
        approach: p.approach,
        load: p.load,
        a: p.a,
        c: match piece {
            super::Piece::Free => 0.0,
            super::Piece::NonContact => t,
            super::Piece::Contact => p.a,
        },
    }
}

/// The non-contact piece sampled for a cycle: `n` parameters from C = 0 to `c_end`.
pub(crate) fn non_contact_ts(c_end: f64, n: usize) -> Vec<(super::Piece, f64)> {
    (0..n)
        .map(|i| (super::Piece::NonContact, c_end * i as f64 / (n - 1) as f64))
        .collect()
}

/// The free segment before the force zones first meet (no force), from far enough below the
/// lowest approach (and load, scaled) of `path` for any spring's jump to land on, up to the
/// approach `d0` where the force starts: `n` points.
pub(crate) fn free_before(path: &[PathPoint], d0: f64, n: usize) -> Vec<PathPoint> {
    let lowest = path
        .iter()
        .map(|p| p.approach + p.load.min(0.0) * 1e3)
        .fold(d0, f64::min);
    (0..n)
        .map(|i| PathPoint {
            branch: Branch::Free,
            approach: lowest - 1.0 + (d0 - lowest + 1.0) * i as f64 / n as f64,
            load: 0.0,
            a: 0.0,
            c: 0.0,
        })
        .collect()
}

/// The contact branch's radii as a cycle samples them: the jumps happen at loads of order one,
/// so the branch up to the radius at load 10 (`a_mid`) gets 2n points, dense near A = 0 where
/// it leaves the non-contact branch, however large the final load; beyond it n more, spaced
/// geometrically up to `a_max`.
pub(crate) fn contact_radii(a_mid: f64, a_max: f64, n: usize) -> Vec<f64> {
    let mut radii: Vec<f64> = (1..=2 * n)
        .map(|i| a_mid * (i as f64 / (2 * n) as f64).powf(1.5))
        .collect();
    if a_max > a_mid {
        radii.extend((1..=n).map(|i| a_mid * (a_max / a_mid).powf(i as f64 / n as f64)));
    }
    radii
}
