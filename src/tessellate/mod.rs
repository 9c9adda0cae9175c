//! Layer 4: B-rep → watertight tagged triangle surface.
//!
//! Stages: every edge is discretised once ([`edge_points`]: chord and angle criteria relative
//! to the model size), so two faces sharing an edge share its points and the surface is
//! watertight by construction; every face is then meshed in its parameter domain
//! ([`face_mesh`]): its loops are mapped to `(u, v)` (periodic parameters unwrapped along the
//! loop, so seams and closed edges become the two sides of a rectangle), a grid of interior
//! points is added where the surface curves (spacing from the chord tolerance and the
//! surface's second derivatives; points near a boundary segment are skipped, since spade
//! would split the constraint through them and break the edge sharing), spade's constrained Delaunay triangulation is built with the
//! loop segments as constraints, triangles outside the loops are removed (by the parity of constraint edges crossed from
//! the outside, exact where a point-in-polygon test fails on thin triangles), and the rest are
//! lifted to 3D, oriented by the face's sense and tagged with its [`FaceId`].
//!
//! Faces that cannot be meshed this way (a periodic face bounded by closed edges without a
//! seam, loops that cross in parameter space) are listed in [`Tessellation::failed`], never
//! left out silently. The result is meant to be checked with [`crate::mesh::topology`].

pub mod edge_points;
pub mod face_mesh;

#[cfg(test)]
mod tests;

use crate::cad::brep::{EntityRef, Model};
use crate::core::FaceId;
use crate::mesh::TriSurface;
use edge_points::EdgePoints;
use glam::DVec3;
use std::collections::BTreeMap;

/// Tessellation criteria.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct TessellateOptions {
    /// Largest distance between a segment or triangle and the exact geometry, as a fraction
    /// of the model size (default 1e-3).
    pub chord_relative: f64,
    /// Largest turn of the tangent along one edge segment, degrees (default 20).
    pub max_angle_deg: f64,
    /// Most interior grid points per face direction (default 200).
    pub max_grid: usize,
}

impl Default for TessellateOptions {
    fn default() -> Self {
        TessellateOptions { chord_relative: 1e-3, max_angle_deg: 20.0, max_grid: 200 }
    }
}

impl TessellateOptions {
    /// Sets [`TessellateOptions::chord_relative`].
    pub fn with_chord_relative(mut self, r: f64) -> Self {
        self.chord_relative = r;
        self
    }
}

/// A face the tessellator could not mesh.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FailedFace {
    /// The face.
    pub face: FaceId,
    /// Its STEP entity.
    pub source: EntityRef,
    /// Why.
    pub why: String,
}

/// The result: the surface and the faces left out.
#[derive(Clone, Debug)]
pub struct Tessellation {
    /// Triangles tagged with their face; vertices shared along B-rep edges.
    pub surface: TriSurface,
    /// Faces that could not be meshed.
    pub failed: Vec<FailedFace>,
}

/// Tessellates every face of `model`.
pub fn tessellate(model: &Model, opts: &TessellateOptions) -> Tessellation {
    let size = model.size();
    let tol = opts.chord_relative * size;
    let mut vertices: Vec<DVec3> = model.vertices.iter().map(|v| v.point).collect();
    let edges: Vec<EdgePoints> = model.edges.iter().map(|e| edge_points::discretise(model, e, tol, opts.max_angle_deg, &mut vertices)).collect();
    let mut triangles = Vec::new();
    let mut face_tags = Vec::new();
    let mut failed = Vec::new();
    let mut tag_names = BTreeMap::new();
    for fid in model.face_ids() {
        let face = model.face(fid);
        match face_mesh::mesh_face(model, fid, &edges, tol, opts, &mut vertices) {
            Ok(tris) => {
                face_tags.extend(std::iter::repeat_n(fid, tris.len()));
                triangles.extend(tris);
                if let Some(n) = &face.name {
                    tag_names.insert(fid, n.clone());
                }
            }
            Err(why) => failed.push(FailedFace { face: fid, source: face.source, why }),
        }
    }
    Tessellation { surface: TriSurface { vertices, triangles, face_tags, tag_names }, failed }
}
