//! Why a B-spline curve or surface, or a STEP knot list, was refused ([`SplineError`]).

use serde::Serialize;

/// A B-spline's data that does not make a spline. The messages are those a STEP reader shows
/// when it drops the entity (after the entity's `#id`).
#[derive(Clone, Debug, PartialEq, Serialize, thiserror::Error)]
#[non_exhaustive]
pub enum SplineError {
    /// Not one weight per control point.
    #[error("{weights} weights for {points} control points")]
    WeightCount {
        /// Weights given.
        weights: usize,
        /// Control points.
        points: usize,
    },
    /// A weight that is zero, negative or not finite.
    #[error("weight {weight} is not positive")]
    Weight {
        /// Its index.
        index: usize,
        /// Its value.
        weight: f64,
    },
    /// A control point with a coordinate that is not finite.
    #[error("a control point is not finite")]
    PointNotFinite {
        /// Its index.
        index: usize,
    },
    /// A degree of 0 or above the largest accepted (`basis::MAX_DEGREE`).
    #[error("degree {degree} is outside 1..={max}")]
    Degree {
        /// The degree.
        degree: usize,
        /// The largest degree accepted.
        max: usize,
    },
    /// Fewer than `degree + 1` control points.
    #[error("{points} control points are too few for degree {degree} (at least {})", degree + 1)]
    TooFewPoints {
        /// Control points.
        points: usize,
        /// The degree.
        degree: usize,
    },
    /// A knot vector whose length is not `points + degree + 1`.
    #[error("{knots} knots (with multiplicities) for {points} control points of degree {degree}; expected {}", points + degree + 1)]
    KnotCount {
        /// Knots given (multiplicities written out).
        knots: usize,
        /// Control points.
        points: usize,
        /// The degree.
        degree: usize,
    },
    /// A knot that is not finite.
    #[error("knot {knot} is not finite")]
    KnotNotFinite {
        /// Its index (multiplicities written out).
        index: usize,
        /// Its value.
        knot: f64,
    },
    /// A knot smaller than the one before it.
    #[error("knots decrease at index {index} ({knot} after {previous})")]
    KnotsDecrease {
        /// The index of the smaller knot.
        index: usize,
        /// Its value.
        knot: f64,
        /// The knot before it.
        previous: f64,
    },
    /// A knot repeated more than `degree + 1` times.
    #[error("knot {knot} is repeated more than degree + 1 = {} times", degree + 1)]
    KnotRepeated {
        /// The index of its first repetition too many.
        index: usize,
        /// Its value.
        knot: f64,
        /// The degree.
        degree: usize,
    },
    /// `knots[degree] >= knots[points]`: no parameter range.
    #[error("the knot vector's domain is empty")]
    EmptyDomain,
    /// STEP knot values and multiplicities of different lengths.
    #[error("{values} knot values but {multiplicities} multiplicities")]
    MultiplicityCount {
        /// Knot values.
        values: usize,
        /// Multiplicities.
        multiplicities: usize,
    },
    /// A multiplicity below 1, or a total too large to write out.
    #[error("knot multiplicities must be positive (and not absurdly large)")]
    Multiplicities {
        /// The index of the first multiplicity below 1, if one is.
        index: Option<usize>,
    },
    /// A surface's control points that are not `nu × nv`.
    #[error("{points} control points do not form a {nu} × {nv} grid")]
    Grid {
        /// Control points given.
        points: usize,
        /// Rows asked for (along `u`).
        nu: usize,
        /// Columns asked for (along `v`).
        nv: usize,
    },
    /// A surface's knots or degree in one parameter direction.
    #[error("{direction}: {error}")]
    Direction {
        /// `"u"` or `"v"`.
        direction: &'static str,
        /// What is wrong in that direction.
        error: Box<SplineError>,
    },
}
