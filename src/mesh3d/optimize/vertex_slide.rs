//! How one boundary vertex may move ([`Slide`]: in a plane, along a line, on a curved CAD face
//! or along a curved CAD edge) and, on a curved face or edge, the guard on its boundary
//! triangles ([`Fan`]). Module `slide` finds them for a mesh; the smoother and the search move
//! vertices by them.

use crate::core::{BoundaryGeometry, FaceId, Hint};
use glam::DVec3;

/// A vertex sliding on a curved face or edge leaves no angle of the boundary triangles at it
/// under this one (the cosine of 20°), or under the smallest of them before where that was
/// smaller: the tets measure the triangles only through their dihedral angles,
/// and measured on real parts, slides along a strip's edge left needles and caps there (on
/// T-Lind_Part1 boundary triangles with an angle over 170° went from 4 to 10, and tets at
/// the strip's corners from 11.7° to 4.0°).
const FAN_MIN_COS: f64 = 0.9397;

/// As [`FAN_MIN_COS`] for the largest angle (the cosine of 120°): none over it, or over the
/// largest before.
const FAN_MAX_COS: f64 = -0.5;

/// How a boundary vertex may move.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) enum Slide {
    /// In the plane through `at` with unit normal `n`.
    Plane { at: DVec3, n: DVec3 },
    /// Along the line through `at` with unit direction `dir`.
    Line { at: DVec3, dir: DVec3 },
    /// On curved face `face` (through `at`, unit normal about `n` there): moves in the tangent
    /// plane, then onto the face by the geometry, searched from `hint`
    /// ([`BoundaryGeometry::face_hint`] at `at`, once `hinted`).
    Surface { at: DVec3, n: DVec3, face: FaceId, hint: Option<Hint>, hinted: bool },
    /// On the curved edge between `faces` (through `at`, direction about `dir` there): moves
    /// along it, then onto the edge by the geometry, searched from `hint`
    /// ([`BoundaryGeometry::edge_hint`] at `at`, once `hinted`).
    Curve { at: DVec3, dir: DVec3, faces: [FaceId; 2], hint: Option<Hint>, hinted: bool },
}

impl Slide {
    /// The part of direction `g` along which the vertex may move.
    #[inline]
    pub(crate) fn project(&self, g: DVec3) -> DVec3 {
        match *self {
            Slide::Plane { n, .. } | Slide::Surface { n, .. } => g - n * n.dot(g),
            Slide::Line { dir, .. } | Slide::Curve { dir, .. } => dir * dir.dot(g),
        }
    }

    /// Where the vertex, now at `from`, goes when moved to `x`: the point of the plane or line
    /// nearest `x`, or the point of the CAD face or edge nearest `x` by `geo`. `None` where
    /// the geometry gives none, or one farther from `x` than `from` is (a projection onto
    /// another sheet of the surface: the vertex's own place is nearer).
    #[inline]
    pub(crate) fn snap(&self, from: DVec3, x: DVec3, geo: Option<&dyn BoundaryGeometry>) -> Option<DVec3> {
        let y = match *self {
            Slide::Plane { at, n } => return Some(x - n * n.dot(x - at)),
            Slide::Line { at, dir } => return Some(at + dir * dir.dot(x - at)),
            Slide::Surface { face, hint, .. } => geo?.on_face_from(face, from, hint, x)?,
            Slide::Curve { faces: [f, g], hint, .. } => geo?.on_edge_from(f, g, from, hint, x)?,
        };
        (y.is_finite() && y.distance_squared(x) <= x.distance_squared(from)).then_some(y)
    }

    /// Asks `geo` where to start searching the face or edge from, the first time (the search
    /// for it may be slow: it is made only for vertices that the optimiser moves).
    pub(crate) fn prepare(&mut self, geo: Option<&dyn BoundaryGeometry>) {
        let Some(geo) = geo else { return };
        match self {
            Slide::Surface { at, face, hint, hinted, .. } if !*hinted => {
                *hint = geo.face_hint(*face, *at);
                *hinted = true;
            }
            Slide::Curve { at, faces: [f, g], hint, hinted, .. } if !*hinted => {
                *hint = geo.edge_hint(*f, *g, *at);
                *hinted = true;
            }
            _ => {}
        }
    }

    /// Whether the vertex moves off its flat surface's plane or straight crease (onto the
    /// CAD geometry).
    pub(crate) fn curved(&self) -> bool {
        matches!(self, Slide::Surface { .. } | Slide::Curve { .. })
    }
}

/// The boundary triangles at a vertex sliding on a curved face or edge, as the pairs of their
/// other vertices: the slide's guard ([`Fan::keeps`]).
#[derive(Clone, Debug)]
pub(crate) struct Fan {
    /// Per boundary triangle at the vertex, its other two vertices.
    pub(crate) pairs: Vec<[u32; 2]>,
}

impl Fan {
    /// The largest and the smallest cosine of the angles of the fan's triangles with the
    /// vertex at `x`.
    fn cosines(&self, pts: &[DVec3], x: DVec3) -> (f64, f64) {
        let (mut hi, mut lo) = (-1.0f64, 1.0f64);
        for &[a, b] in &self.pairs {
            let (pa, pb) = (pts[a as usize], pts[b as usize]);
            for (o, p, q) in [(x, pa, pb), (pa, pb, x), (pb, x, pa)] {
                let (u, v) = (p - o, q - o);
                let c = u.dot(v) / (u.length() * v.length());
                if !c.is_finite() {
                    return (1.0, -1.0);
                }
                hi = hi.max(c);
                lo = lo.min(c);
            }
        }
        (hi, lo)
    }

    /// The bounds on the cosines that a move of the vertex from `x0` must keep
    /// ([`FAN_MIN_COS`], [`FAN_MAX_COS`]; see [`Fan::keeps`]).
    pub(crate) fn bounds(&self, pts: &[DVec3], x0: DVec3) -> (f64, f64) {
        let (hi, lo) = self.cosines(pts, x0);
        (hi.max(FAN_MIN_COS), lo.min(FAN_MAX_COS))
    }

    /// Whether the fan's triangles with the vertex at `y` keep `bounds` (from
    /// [`Fan::bounds`]): no angle smaller, none larger.
    pub(crate) fn keeps(&self, pts: &[DVec3], y: DVec3, bounds: (f64, f64)) -> bool {
        let (hi, lo) = self.cosines(pts, y);
        hi <= bounds.0 && lo >= bounds.1
    }
}
