//! The physics: normalisation, the closed-form models and the Maugis-Dugdale curve.

pub mod closed;
pub mod domain;
pub mod f32math;
pub mod fields;
pub mod md;
pub mod params;
pub mod real;
pub mod tolerances;
