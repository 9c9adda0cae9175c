//! Refinement of a face's parameter-domain triangulation until its lifted triangles follow
//! the surface: the interior grid of [`super::face_mesh`] follows the largest curvature of the
//! face's box; this follows the surface where the grid is too coarse (speeds varying over the
//! face, grids capped at `max_grid`) and removes long triangles across curved directions.
//! Only `(u, v)` centroids of inside triangles are inserted, never points on a boundary
//! segment, so the edges shared with other faces keep their points.

use super::TessellateOptions;
use super::face_error::FaceError;
use super::uv_cdt::{V, constraint_parity};
use crate::cad::geom::Surface;
use glam::{DVec2, DVec3};
use crate::core::cdt;
use spade::{ConstrainedDelaunayTriangulation, Triangulation};

/// Rounds of [`refine`] at most.
const REFINE_ROUNDS: usize = 10;
/// Points [`refine`] adds to one face at most.
const REFINE_POINTS: usize = 200_000;

/// How far triangle `t` (corners in 3D and `(u, v)`) is from the surface: the largest
/// distance of the surface points at its `(u, v)` centroid and at the midpoints of its
/// unconstrained edges from its plane; infinite when its normal turns more than
/// `cos_max` away from the surface normal (or against it: a fold).
pub(super) fn deviation(surf: &Surface, p: [DVec3; 3], uv: [DVec2; 3], free_edge: [bool; 3], cos_max: f64) -> f64 {
    let Some(n) = (p[1] - p[0]).cross(p[2] - p[0]).try_normalize() else { return 0.0 };
    let c = (uv[0] + uv[1] + uv[2]) / 3.0;
    let (sp, su, sv) = surf.point_and_tangents(c.x, c.y);
    if let Some(sn) = su.cross(sv).try_normalize() {
        if n.dot(sn) < cos_max {
            return f64::INFINITY;
        }
    }
    // the surface normal at every corner too: a triangle across half a thin cylinder (from
    // its seam to the far side, long along it) can have its centroid's normal and be within a
    // coarse chord, yet its corners' normals are opposite (and the other half's triangles
    // share its 3D side: a fold). Not at a singular corner (a cone's apex, a pole), where
    // the parametrization's normal is not the surface's
    let corner = uv.map(|q| {
        let (_, su, sv) = surf.point_and_tangents(q.x, q.y);
        su.cross(sv)
    });
    let big = corner.iter().map(|c| c.length()).fold(0.0, f64::max);
    for c in corner {
        if c.length() > 1e-3 * big && n.dot(c.normalize()) < cos_max {
            return f64::INFINITY;
        }
    }
    let mut d = (sp - p[0]).dot(n).abs();
    for i in 0..3 {
        if free_edge[i] {
            let m = 0.5 * (uv[i] + uv[(i + 1) % 3]);
            d = d.max((surf.point(m.x, m.y) - p[0]).dot(n).abs());
        }
    }
    d
}

/// Inserts the `(u, v)` centroid of every inside triangle farther than `tol` from the surface
/// ([`deviation`]), round after round, until none is (or the bounds are reached): the
/// interior grid follows the largest curvature of the face's box, this follows the surface
/// where the grid is too coarse (speeds varying over the face, grids capped at
/// `max_grid`) and removes long triangles across curved directions.
pub(super) fn refine(tri: &mut ConstrainedDelaunayTriangulation<V>, surf: &Surface, tol: f64, opts: &TessellateOptions) -> Result<(), FaceError> {
    let cos_max = (2.0 * opts.max_angle_deg).to_radians().cos();
    let mut added = 0;
    for _ in 0..REFINE_ROUNDS {
        let inside = constraint_parity(tri);
        let mut new_points = Vec::new();
        for f in tri.inner_faces() {
            if !inside[f.fix().index()] {
                continue;
            }
            let vs = f.vertices();
            let (p, uv) = (vs.map(|v| v.data().p3), vs.map(|v| v.data().uv));
            let longest = (0..3).map(|i| (p[i] - p[(i + 1) % 3]).length()).fold(0.0, f64::max);
            if longest <= tol {
                continue;
            }
            let edges = f.adjacent_edges();
            let free = [0, 1, 2].map(|i| !edges[i].is_constraint_edge());
            if deviation(surf, p, uv, free, cos_max) > tol {
                let sp = vs.map(|v| v.data().p);
                let c = DVec2::new((sp[0].x + sp[1].x + sp[2].x) / 3.0, (sp[0].y + sp[1].y + sp[2].y) / 3.0);
                let cuv = (uv[0] + uv[1] + uv[2]) / 3.0;
                new_points.push((c, cuv));
            }
        }
        if new_points.is_empty() {
            break;
        }
        added += new_points.len();
        for (c, uv) in new_points {
            cdt::insert(tri, c, |p| V { p, id: None, uv, p3: surf.point(uv.x, uv.y) }).map_err(|e| FaceError::Insert { point: "refinement point", reason: e.to_string() })?;
        }
        if added > REFINE_POINTS {
            break;
        }
    }
    Ok(())
}

