//! The one place spade's constrained Delaunay triangulation (CDT) is fed: the coordinate guard,
//! point insertion, constraints and the quality refinement, for the tessellator's face meshes
//! in `(u, v)` (`tessellate/face_mesh.rs`, `tessellate/refine.rs`) and the mesher's facets in
//! their planes (`mesh3d/mesher/surface_model.rs`).
//!
//! # The coordinate guard (one rule)
//! spade refuses a coordinate that is NaN, larger than [`spade::MAX_ALLOWED_VALUE`] (2²⁰¹) in
//! magnitude (infinities included) or non-zero and smaller than [`spade::MIN_ALLOWED_VALUE`]
//! (2⁻¹⁴²): beyond that range its exact predicates could overflow or underflow. Every
//! coordinate given to spade here goes through [`coordinate`]:
//! - magnitudes below [`FLUSH`] (10⁻³⁰) become exactly 0: they are rounding residue of a zero
//!   (a parameter or plane coordinate computed as 1e-33 instead of 0), far below any length
//!   fepre meshes and far above spade's floor, so collinear points stay collinear;
//! - non-finite values and magnitudes above [`spade::MAX_ALLOWED_VALUE`] are refused (`None`),
//!   and [`insert`] reports them as [`CdtError::Coordinate`] without touching the
//!   triangulation;
//! - everything else passes unchanged.
//!
//! Points spade's own refinement creates are spade's business (they lie inside the hull of
//! points that passed the guard).

use glam::DVec2;
use spade::handles::FixedVertexHandle;
use spade::{AngleLimit, ConstrainedDelaunayTriangulation, HasPosition, InsertionError, Point2, RefinementParameters, Triangulation};

/// Magnitudes below this are flushed to 0 by the guard (see the [module docs](self)).
pub(crate) const FLUSH: f64 = 1e-30;

/// Why a point could not go into the triangulation.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub(crate) enum CdtError {
    /// A coordinate is not finite or too large for spade's predicates.
    #[error("coordinates ({0}, {1}) are not finite or beyond spade's range")]
    Coordinate(f64, f64),
    /// spade refused the point.
    #[error("spade refused the point: {0:?}")]
    Spade(InsertionError),
}

/// The guard on one coordinate: flushed to 0 below [`FLUSH`], `None` if not finite or beyond
/// [`spade::MAX_ALLOWED_VALUE`].
#[inline]
pub(crate) fn coordinate(x: f64) -> Option<f64> {
    if !x.is_finite() || x.abs() > spade::MAX_ALLOWED_VALUE {
        None
    } else if x.abs() < FLUSH {
        Some(0.0)
    } else {
        Some(x)
    }
}

/// The guard's flush alone, for coordinates that are also used outside spade (so that those
/// uses see what spade sees); non-finite values pass (and [`insert`] refuses them).
#[inline]
pub(crate) fn flush(x: f64) -> f64 {
    if x.abs() < FLUSH { 0.0 } else { x }
}

/// `p` as spade's point, through the guard.
#[inline]
pub(crate) fn point(p: DVec2) -> Option<Point2<f64>> {
    Some(Point2::new(coordinate(p.x)?, coordinate(p.y)?))
}

/// Inserts the vertex `vertex(q)` at `q`, the guarded `p`; returns its handle (that of the
/// vertex already there if `p` coincides with one: spade then replaces its data).
///
/// # Errors
/// [`CdtError::Coordinate`] if a coordinate fails the guard (nothing inserted),
/// [`CdtError::Spade`] if spade refuses the point.
pub(crate) fn insert<V: HasPosition<Scalar = f64>>(
    cdt: &mut ConstrainedDelaunayTriangulation<V>,
    p: DVec2,
    vertex: impl FnOnce(Point2<f64>) -> V,
) -> Result<FixedVertexHandle, CdtError> {
    let q = point(p).ok_or(CdtError::Coordinate(p.x, p.y))?;
    cdt.insert(vertex(q)).map_err(CdtError::Spade)
}

/// Adds the constraint edge `a`–`b` unless it would cross an existing constraint (then nothing
/// changes); true if it was added. An edge through other vertices is split at them.
pub(crate) fn constrain<V: HasPosition<Scalar = f64>>(cdt: &mut ConstrainedDelaunayTriangulation<V>, a: FixedVertexHandle, b: FixedVertexHandle) -> bool {
    if !cdt.can_add_constraint(a, b) {
        return false;
    }
    cdt.add_constraint(a, b);
    true
}

/// The quality refinement both users want: triangles of angles at least 25°, constraint edges
/// kept (never split), outer faces left alone, at most `max_added` new vertices, and, when
/// `size` is positive and finite, areas at most `size² / 2` (right triangles of legs `size`).
pub(crate) fn quality_refinement(size: f64, max_added: usize) -> RefinementParameters<f64> {
    let params = RefinementParameters::<f64>::new()
        .with_angle_limit(AngleLimit::from_deg(25.0))
        .keep_constraint_edges()
        .exclude_outer_faces(true)
        .with_max_additional_vertices(max_added);
    if size.is_finite() && size > 0.0 { params.with_max_allowed_area(0.5 * size * size) } else { params }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_guard_flushes_residue_and_refuses_what_spade_cannot_take() {
        assert_eq!(coordinate(0.0), Some(0.0));
        assert_eq!(coordinate(-3.5), Some(-3.5));
        assert_eq!(coordinate(1e-33), Some(0.0));
        assert_eq!(coordinate(-1e-31), Some(0.0));
        assert_eq!(coordinate(1e-29), Some(1e-29));
        assert_eq!(coordinate(spade::MAX_ALLOWED_VALUE), Some(spade::MAX_ALLOWED_VALUE));
        assert_eq!(coordinate(2.0 * spade::MAX_ALLOWED_VALUE), None);
        assert_eq!(coordinate(f64::INFINITY), None);
        assert_eq!(coordinate(f64::NAN), None);
        assert_eq!(flush(1e-40), 0.0);
        assert!(flush(f64::NAN).is_nan());
        // what passes the guard, spade takes
        for x in [0.0, 1e-30, -1e-30, 1e-29, 1e10, spade::MAX_ALLOWED_VALUE, 1e-40, 5e-324] {
            let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> = ConstrainedDelaunayTriangulation::new();
            assert!(insert(&mut cdt, DVec2::new(x, 1.0), |q| q).is_ok(), "{x}");
        }
    }

    #[test]
    fn refused_points_leave_the_triangulation_alone() {
        let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> = ConstrainedDelaunayTriangulation::new();
        insert(&mut cdt, DVec2::new(0.0, 0.0), |q| q).unwrap();
        assert!(matches!(insert(&mut cdt, DVec2::new(f64::NAN, 0.0), |q| q), Err(CdtError::Coordinate(..))));
        assert!(insert(&mut cdt, DVec2::new(1.0, f64::INFINITY), |q| q).is_err());
        assert_eq!(cdt.num_vertices(), 1);
    }

    #[test]
    fn constraints_that_cross_are_refused() {
        let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> = ConstrainedDelaunayTriangulation::new();
        let h: Vec<_> = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)].iter().map(|&(x, y)| insert(&mut cdt, DVec2::new(x, y), |q| q).unwrap()).collect();
        assert!(constrain(&mut cdt, h[0], h[2]));
        assert!(!constrain(&mut cdt, h[1], h[3]));
        assert_eq!(cdt.num_constraints(), 1);
    }

    #[test]
    fn refinement_keeps_constraints_and_bounds_areas_only_for_a_size() {
        let square = |size: f64| {
            let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> = ConstrainedDelaunayTriangulation::new();
            let h: Vec<_> = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)].iter().map(|&(x, y)| insert(&mut cdt, DVec2::new(x, y), |q| q).unwrap()).collect();
            for i in 0..4 {
                assert!(constrain(&mut cdt, h[i], h[(i + 1) % 4]));
            }
            cdt.refine(quality_refinement(size, 1000));
            assert_eq!(cdt.num_constraints(), 4, "constraint edges kept");
            cdt.num_vertices()
        };
        // two 45° triangles pass the angle limit; the area bound (8 > 0.5) asks for more
        assert_eq!(square(f64::NAN), 4);
        assert_eq!(square(0.0), 4);
        assert!(square(1.0) > 4);
    }
}
