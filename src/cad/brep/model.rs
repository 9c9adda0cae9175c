//! The arena types of the B-rep.

use super::entity_ref::EntityRef;
use crate::cad::geom::{Curve, Interval, Surface};
use crate::core::FaceId;
use glam::DVec3;
use serde::Serialize;

/// A point of the model.
#[derive(Clone, Debug)]
pub struct Vertex {
    /// Position, mm.
    pub point: DVec3,
    /// `VERTEX_POINT`.
    pub source: EntityRef,
}

/// An edge: a piece of a curve between two vertices.
#[derive(Clone, Debug)]
pub struct Edge {
    /// Index into [`Model::curves`]; `None` where the file gives no usable curve (the edge is
    /// then the straight segment between its vertices, or a point when degenerate).
    pub curve: Option<u32>,
    /// Start vertex (index into [`Model::vertices`]).
    pub start: u32,
    /// End vertex.
    pub end: u32,
    /// The curve parameters the edge covers, increasing.
    pub range: Interval,
    /// True when the edge runs with its curve (`start` at `range.min`).
    pub same_sense: bool,
    /// Start and end are the same vertex (a full circle, a closed B-spline).
    pub closed: bool,
    /// Used twice by one face, once in each direction (the seam of a cylinder, cone, sphere).
    pub seam: bool,
    /// Of zero length (a sphere's or cone's pole).
    pub degenerate: bool,
    /// `EDGE_CURVE`.
    pub source: EntityRef,
}

/// An edge as a loop uses it.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Coedge {
    /// Index into [`Model::edges`].
    pub edge: u32,
    /// True when the loop runs from the edge's `start` to its `end`.
    pub forward: bool,
}

/// A boundary loop of a face.
#[derive(Clone, Debug)]
pub struct Loop {
    /// The face.
    pub face: FaceId,
    /// `FACE_OUTER_BOUND` (or the one bound of a face with a single bound).
    pub outer: bool,
    /// `FACE_BOUND.orientation`: false when the loop is to be read reversed.
    pub orientation: bool,
    /// The edges in order; empty for a vertex loop.
    pub coedges: Vec<Coedge>,
    /// The vertex of a `VERTEX_LOOP` (a cone apex or sphere pole).
    pub vertex: Option<u32>,
    /// `EDGE_LOOP` or `VERTEX_LOOP`.
    pub source: EntityRef,
}

/// A face: a bounded piece of a surface.
#[derive(Clone, Debug)]
pub struct Face {
    /// Index into [`Model::surfaces`].
    pub surface: u32,
    /// False when the face's outward normal is the surface normal negated (`same_sense`,
    /// combined with `ORIENTED_FACE`).
    pub same_sense: bool,
    /// Indices into [`Model::loops`], the outer one first.
    pub loops: Vec<u32>,
    /// Index into [`Model::shells`].
    pub shell: u32,
    /// The face's name in the file, if not empty.
    pub name: Option<String>,
    /// Colour from `STYLED_ITEM` presentation, RGB in `[0, 1]`.
    pub colour: Option<[f32; 3]>,
    /// `ADVANCED_FACE` or `FACE_SURFACE`.
    pub source: EntityRef,
}

/// A connected set of faces.
#[derive(Clone, Debug)]
pub struct Shell {
    /// The faces.
    pub faces: Vec<FaceId>,
    /// `CLOSED_SHELL` (true) or `OPEN_SHELL`.
    pub closed: bool,
    /// The solid it bounds, if any (`None` for a surface model's shell).
    pub solid: Option<u32>,
    /// A void of a `BREP_WITH_VOIDS`.
    pub void: bool,
    /// The shell entity.
    pub source: EntityRef,
}

/// A solid: an outer shell and voids.
#[derive(Clone, Debug)]
pub struct Solid {
    /// Indices into [`Model::shells`], the outer one first.
    pub shells: Vec<u32>,
    /// The solid's name in the file, if not empty.
    pub name: Option<String>,
    /// Which placed copy of its part this is (0 for the first or only one).
    pub instance: u32,
    /// `MANIFOLD_SOLID_BREP` or `BREP_WITH_VOIDS`.
    pub source: EntityRef,
}

/// Something the reader left out, and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Dropped {
    /// The STEP type (`PLANE`, `(BOUNDED_SURFACE B_SPLINE_SURFACE ...)`).
    pub kind: String,
    /// The instance.
    pub id: EntityRef,
    /// Why.
    pub why: String,
}

/// The length and angle units of the file, as factors to millimetres and radians.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Units {
    /// The length unit's name (`millimetre`, `metre`, `inch`, ...).
    pub length: String,
    /// Millimetres per file length unit.
    pub to_mm: f64,
    /// The plane angle unit's name (`radian`, `degree`).
    pub angle: String,
    /// Radians per file angle unit.
    pub to_rad: f64,
}

impl Default for Units {
    fn default() -> Self {
        Units { length: "millimetre".into(), to_mm: 1.0, angle: "radian".into(), to_rad: 1.0 }
    }
}

/// A B-rep model in millimetres.
#[derive(Clone, Debug, Default)]
pub struct Model {
    /// Solids.
    pub solids: Vec<Solid>,
    /// Shells.
    pub shells: Vec<Shell>,
    /// Faces; [`FaceId`] `k` is `faces[k - 1]` ([`FaceId::index`]), `FaceId(0)` none.
    pub faces: Vec<Face>,
    /// Loops.
    pub loops: Vec<Loop>,
    /// Edges.
    pub edges: Vec<Edge>,
    /// Vertices.
    pub vertices: Vec<Vertex>,
    /// Surfaces (faces refer to them by index).
    pub surfaces: Vec<Surface>,
    /// Curves (edges refer to them by index).
    pub curves: Vec<Curve>,
    /// The units of the root representation (the file's units in every corpus file).
    pub units: Units,
    /// Items left out, with the reason.
    pub dropped: Vec<Dropped>,
    /// What was odd about the file as written but read anyway (a STEP HEADER section
    /// missing or incomplete ...).
    pub notes: Vec<String>,
    /// What sewing did to the open shells of a surface model ([`Model::sew`]); `None` when
    /// the model has no open shell.
    pub sewing: Option<super::sew_report::SewReport>,
}

impl Model {
    /// Shells that bound no solid: the shells of a surface model
    /// (`SHELL_BASED_SURFACE_MODEL`, `OPEN_SHELL`s).
    pub fn surface_model_shells(&self) -> usize {
        self.shells.iter().filter(|s| s.solid.is_none()).count()
    }

    /// The ids of all faces, `FaceId(1)` to `FaceId(n)` ([`FaceId::from_index`] of each
    /// index into [`Model::faces`]).
    pub fn face_ids(&self) -> impl Iterator<Item = FaceId> + '_ {
        (0..self.faces.len()).map(FaceId::from_index)
    }

    /// The face with this id.
    ///
    /// # Panics
    /// If `id` is not one of [`Model::face_ids`].
    pub fn face(&self, id: FaceId) -> &Face {
        match self.try_face(id) {
            Some(f) => f,
            None => panic!("{id} is not a face of this model ({} faces)", self.faces.len()),
        }
    }

    /// The face with this id, or `None`.
    pub fn try_face(&self, id: FaceId) -> Option<&Face> {
        id.index().and_then(|k| self.faces.get(k))
    }

    /// Per edge, the indices into [`Model::faces`] of the faces whose loops use it, each once,
    /// in face order.
    pub fn edge_faces(&self) -> Vec<Vec<u32>> {
        let mut out: Vec<Vec<u32>> = vec![Vec::new(); self.edges.len()];
        for (f, face) in self.faces.iter().enumerate() {
            for &l in &face.loops {
                for c in &self.loops[l as usize].coedges {
                    let fs = &mut out[c.edge as usize];
                    if !fs.contains(&(f as u32)) {
                        fs.push(f as u32);
                    }
                }
            }
        }
        out
    }

    /// A surface by index.
    pub fn surface(&self, index: u32) -> &Surface {
        &self.surfaces[index as usize]
    }

    /// A curve by index.
    pub fn curve(&self, index: u32) -> &Curve {
        &self.curves[index as usize]
    }

    /// The bounding box of the vertices, `(min, max)`; `None` for a model without vertices.
    pub fn vertex_bounds(&self) -> Option<(DVec3, DVec3)> {
        let mut it = self.vertices.iter().map(|v| v.point);
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }

    /// A bounding box of the geometry, `(min, max)`: the vertices, 9 points along every edge,
    /// and a 5 × 5 grid on the surface of every face without edges whose surface has a
    /// bounded domain (a sphere bounded by a vertex loop has a single vertex). `None` for a
    /// model without any.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let mut pts: Vec<DVec3> = self.vertices.iter().map(|v| v.point).collect();
        for e in &self.edges {
            if let Some(c) = e.curve {
                if e.range.min.is_finite() && e.range.max.is_finite() {
                    let c = &self.curves[c as usize];
                    pts.extend((0..=8).map(|k| c.point(e.range.min + e.range.length() * k as f64 / 8.0)));
                }
            }
        }
        for f in &self.faces {
            if f.loops.iter().any(|&l| !self.loops[l as usize].coedges.is_empty()) {
                continue;
            }
            let s = &self.surfaces[f.surface as usize];
            let d = s.domain();
            if d.u.is_bounded() && d.v.is_bounded() {
                for i in 0..5 {
                    for j in 0..5 {
                        pts.push(s.point(d.u.min + d.u.length() * i as f64 / 4.0, d.v.min + d.v.length() * j as f64 / 4.0));
                    }
                }
            }
        }
        let mut it = pts.into_iter().filter(|p| p.is_finite());
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }

    /// The model's size: the diagonal of [`Model::bounds`] (1 for an empty model).
    /// Tolerances are fractions of it.
    pub fn size(&self) -> f64 {
        match self.bounds() {
            Some((lo, hi)) if (hi - lo).length() > 0.0 => (hi - lo).length(),
            _ => 1.0,
        }
    }
}
