//! Why a force curve, as given, cannot be fitted: its points, its segments, its cycles, its
//! place on a force map, or the numbers of a synthetic one. Each names the curve, the point or
//! the column, the value and what to give, in the columns' names (`height_m`, `segment`, `x`,
//! `y`), which the command line's files and Python's arrays share.

use crate::physics::domain::short;
use crate::physics::model::ContactModel;

/// Why a curve's points, segments or pixel were refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CurveError {
    /// The segment column is not one value per point.
    #[error("{heights} heights but {segments} segment values: give one segment value per point")]
    SegmentCount {
        /// Points with a height.
        heights: usize,
        /// Segment values.
        segments: usize,
    },
    /// A height is NaN or infinite.
    #[error("height {value} at point {point} is not a finite number")]
    Height {
        /// The height (m).
        value: f64,
        /// Its point, from 0.
        point: usize,
    },
    /// One segment for the whole curve, and its heights have no clear turning point.
    #[error(
        "approach and retract are not separated: the curve is one segment and its heights have no clear turning point (the base goes down by {} m and back up by {} m of a {} m range); give the segment of each point (0 approach, 1 retract)",
        short(*down),
        short(*up),
        short(*range)
    )]
    NotSeparated {
        /// How far the base goes down from the first height (m).
        down: f64,
        /// How far it comes back up at the last (m).
        up: f64,
        /// The heights' range (m).
        range: f64,
    },
    /// The segment goes back to one it has left: several cycles in one curve.
    #[error(
        "the curve holds {cycles} approach-retract cycles: its segment goes back from {from} to {to} at point {point} (a repeated cycle, or two curves with the same id or pixel x, y merged); give each cycle its own curve id"
    )]
    Cycles {
        /// The cycles counted.
        cycles: usize,
        /// The segment left (`approach` or `retract`).
        from: &'static str,
        /// The segment it goes back to.
        to: &'static str,
        /// Where, from 1.
        point: usize,
    },
    /// A segment's heights run the wrong way overall.
    #[error(
        "the {segment} heights are not in order: they go from {} m at its first point to {} m at its last, and the {segment} must {} the height; check the segment column (approach and retract swapped?) and that height_m grows away from the sample",
        short(*first),
        short(*last),
        way(segment)
    )]
    Order {
        /// `approach` or `retract`.
        segment: &'static str,
        /// Its first height (m).
        first: f64,
        /// Its last height (m).
        last: f64,
    },
    /// A segment's heights go back by a large part of their span.
    #[error(
        "the {segment} heights go back by {} m (their span is {} m) at point {point}: the {segment} restarts there (two cycles in one curve?) or its points are out of time order; give each cycle its own curve id, in the order measured",
        short(*back),
        short(*span)
    )]
    GoesBack {
        /// `approach` or `retract`.
        segment: &'static str,
        /// How far back (m).
        back: f64,
        /// The segment's span (m).
        span: f64,
        /// Where, from 1.
        point: usize,
    },
    /// A curve of a force map without pixel indices.
    #[error(
        "curve {curve} has no pixel indices (x, y): force maps need x and y columns with indices 0..99999"
    )]
    NoPixel {
        /// The curve's name.
        curve: String,
    },
    /// A pixel index out of 0..99999.
    #[error(
        "curve {curve} has pixel index {column} = {value}, outside 0..99999: give the {column} column as pixel indices from 0 (a force map holds at most 4096 x 4096 pixels)"
    )]
    Pixel {
        /// The curve's name.
        curve: String,
        /// `x` or `y`.
        column: &'static str,
        /// The index.
        value: i64,
    },
    /// The pixel indices span more than a force map holds.
    #[error(
        "the pixel indices span a {nx} x {ny} grid ({} pixels for {curves} curves): a force map holds at most 4096 x 4096 pixels; check the x and y columns (indices from 0)",
        nx * ny
    )]
    Grid {
        /// Columns spanned.
        nx: usize,
        /// Rows spanned.
        ny: usize,
        /// Curves.
        curves: usize,
    },
    /// A model that force curves are not fitted with.
    #[error("the {} model is not fitted to force curves: use hertz, dmt, jkr or md", .0.label())]
    NotFitted(ContactModel),
}

/// What a segment does to the height.
fn way(segment: &str) -> &'static str {
    if segment == "approach" {
        "decrease"
    } else {
        "increase"
    }
}

/// Why a synthetic curve was not made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SyntheticError {
    /// A wet curve of a model other than the two-zone law.
    #[error("a wet synthetic curve is of the two-zone law, not {0}")]
    WetModel(&'static str),
    /// E*, w, the radius, the spring or the depth not positive and finite, or lambda, the
    /// contact point or the offset not finite.
    #[error(
        "E* ({e_star} Pa), w ({w} J/m^2), the radius ({radius} m), the spring constant ({spring} N/m) and the depth ({depth}) must be positive and finite, lambda, the contact point and the offset finite"
    )]
    Numbers {
        /// E* (Pa).
        e_star: f64,
        /// w (J/m^2).
        w: f64,
        /// The radius (m).
        radius: f64,
        /// The spring constant (N/m).
        spring: f64,
        /// The depth (normalised).
        depth: f64,
    },
    /// Negative or non-finite noise.
    #[error("force noise {0} N: must be finite and not negative")]
    Noise(f64),
    /// A tip without this law.
    #[error(
        "a tip has no {0} law: give hertz, jkr or md (a tip's DMT-type force needs the range)"
    )]
    TipLaw(&'static str),
    /// Lambda outside the models' domain, or units that overflow.
    #[error(
        "lambda {} is outside the models' domain 1e-26..1e26, or the units overflow",
        short(*.0)
    )]
    Lambda(f64),
    /// The path could not be solved at a point.
    #[error(
        "the {model} path could not be solved at lambda {} (point {point}): use a lambda in the solver's domain",
        short(*lambda)
    )]
    Unsolved {
        /// The model's label.
        model: &'static str,
        /// Lambda.
        lambda: f64,
        /// The point, from 0.
        point: usize,
    },
}
