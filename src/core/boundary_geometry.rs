//! The [`BoundaryGeometry`] trait: where a point of a tagged boundary belongs on the geometry
//! the boundary approximates (the CAD face a boundary triangle's tag names, the CAD edge
//! between two tags), in the spirit of CGAL's `MeshDomain_3`. The B-rep implements it
//! (`fe::BrepGeometry`); a plain surface mesh has none, and its boundary keeps its facets.
//!
//! Two layers use it: the optimiser, which lets boundary vertices slide on their curved face
//! or along their curved edge and puts them back on it (`mesh3d/optimize/slide.rs`), and the
//! FE model, whose boundary mid nodes go onto the face or edge (`fe/quadratic.rs`).

use super::FaceId;
use glam::{DVec2, DVec3};

/// The geometry behind a boundary whose triangles are tagged by [`FaceId`].
pub trait BoundaryGeometry: Sync {
    /// The point of face `face` closest to `p`, searched near `a` and `b` (points on the face
    /// near `p`: the ends of a mesh edge whose chord midpoint is `p`, or a vertex's place
    /// before a move), or `None` where the face has no geometry.
    fn on_face(&self, face: FaceId, a: DVec3, b: DVec3, p: DVec3) -> Option<DVec3>;
    /// The point of the curved edge between faces `f` and `g` closest to `p` (searched near `a`
    /// and `b` as in [`BoundaryGeometry::on_face`]), or `None` where they share no curved edge.
    fn on_edge(&self, f: FaceId, g: FaceId, a: DVec3, b: DVec3, p: DVec3) -> Option<DVec3>;
    /// Where to start searching face `face` for points near `p` (a point on it), where a
    /// search from there is cheaper than [`BoundaryGeometry::on_face`]'s (a B-spline's global
    /// search). `None` by default.
    fn face_hint(&self, _face: FaceId, _p: DVec3) -> Option<Hint> {
        None
    }
    /// [`BoundaryGeometry::on_face`] for a point `p` moved from `from` (on the face), searched
    /// from `hint` ([`BoundaryGeometry::face_hint`] near `from`) where there is one.
    fn on_face_from(&self, face: FaceId, from: DVec3, _hint: Option<Hint>, p: DVec3) -> Option<DVec3> {
        self.on_face(face, from, from, p)
    }
    /// Where to start searching the curved edge between faces `f` and `g` for points near `p`
    /// (a point on it): which of their edges, and where on it. `None` by default.
    fn edge_hint(&self, _f: FaceId, _g: FaceId, _p: DVec3) -> Option<Hint> {
        None
    }
    /// [`BoundaryGeometry::on_edge`] for a point `p` moved from `from` (on the edge), searched
    /// from `hint` ([`BoundaryGeometry::edge_hint`] near `from`) where there is one.
    fn on_edge_from(&self, f: FaceId, g: FaceId, from: DVec3, _hint: Option<Hint>, p: DVec3) -> Option<DVec3> {
        self.on_edge(f, g, from, from, p)
    }
}

/// Where a search on a [`BoundaryGeometry`] starts: a piece of it (for an edge, which of the
/// faces' edges) and parameters on it. What the numbers mean is the geometry's own.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Hint {
    /// The piece (an edge's index; unused for a face).
    pub item: u32,
    /// Parameters on it (a face's `(u, v)`; an edge's `t` in `x`).
    pub param: DVec2,
}
