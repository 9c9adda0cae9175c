//! The constrained Delaunay triangulation of a face's parameter domain, as spade holds it: its
//! vertex type [`V`] and the parity of constraint edges between each triangle and the outside
//! ([`constraint_parity`]), shared by the face mesher and the refinements that insert into it.

use glam::{DVec2, DVec3};
use spade::{ConstrainedDelaunayTriangulation, HasPosition, Point2, Triangulation};

/// A vertex of the parameter-domain triangulation.
#[derive(Clone, Copy, Debug)]
pub(super) struct V {
    /// Position in scaled `(u, v)`.
    pub(super) p: Point2<f64>,
    /// Global vertex index, or `None` for an interior point not yet lifted.
    pub(super) id: Option<u32>,
    /// Position in `(u, v)`.
    pub(super) uv: DVec2,
    /// The point in 3D.
    pub(super) p3: DVec3,
}

/// A point spade's refinement inserts: lifted by [`super::sizing::lift_new`] once refinement is done.
impl From<Point2<f64>> for V {
    fn from(p: Point2<f64>) -> V {
        V { p, id: None, uv: DVec2::NAN, p3: DVec3::NAN }
    }
}

impl HasPosition for V {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.p
    }
}

/// Per face index (outer face included): true when an odd number of constraint edges
/// separates it from the outer face. A 0-1 breadth-first search over face adjacency.
pub(super) fn constraint_parity(cdt: &ConstrainedDelaunayTriangulation<V>) -> Vec<bool> {
    let n = cdt.num_all_faces();
    let mut depth = vec![usize::MAX; n];
    let mut queue = std::collections::VecDeque::new();
    let outer = cdt.outer_face().fix().index();
    depth[outer] = 0;
    // the outer face has no adjacent_edges list of three: seed from the convex hull
    for e in cdt.convex_hull() {
        for f in [e.face(), e.rev().face()] {
            if let Some(inner) = f.as_inner() {
                let d = usize::from(e.is_constraint_edge());
                let k = inner.fix().index();
                if d < depth[k] {
                    depth[k] = d;
                    if d == 0 { queue.push_front(k) } else { queue.push_back(k) }
                }
            }
        }
    }
    let faces: Vec<_> = cdt.inner_faces().collect();
    let mut by_index = vec![None; n];
    for (k, f) in faces.iter().enumerate() {
        by_index[f.fix().index()] = Some(k);
    }
    while let Some(k) = queue.pop_front() {
        let Some(fi) = by_index[k] else { continue };
        let f = faces[fi];
        for e in f.adjacent_edges() {
            let Some(nb) = e.rev().face().as_inner() else { continue };
            let j = nb.fix().index();
            let step = usize::from(e.is_constraint_edge());
            let d = depth[k] + step;
            if d < depth[j] {
                depth[j] = d;
                if step == 0 { queue.push_front(j) } else { queue.push_back(j) }
            }
        }
    }
    depth.into_iter().map(|d| d != usize::MAX && d % 2 == 1).collect()
}
