//! Numerical methods that know no physics: bracketed root finding, golden-section search and
//! Gauss-Legendre quadrature. The bottom layer: every other module may use it, it uses none.

pub mod golden;
pub mod grid;
pub mod legendre;
pub mod root;
