//! The physics: normalisation, the closed-form models and the Maugis-Dugdale curve.

pub mod closed;
pub mod domain;
pub mod f32math;
pub mod fields;
pub mod md;
pub mod measured;
/// The names of the contact models, one vocabulary for every part of tabor.
pub mod model;
pub mod params;
pub mod real;
pub mod tip;
/// Every threshold of the contract and of the solvers' branching, named once.
pub mod tolerances;
pub mod two_zone;
