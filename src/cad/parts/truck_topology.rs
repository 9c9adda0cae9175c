//! A truck `Solid` → our [`Model`]: one solid, its shells, faces, loops, edges and vertices,
//! each truck item once (shared edges and vertices stay shared), geometry through
//! `truck_geometry.rs`.
//!
//! Orientation: a face's loops are truck's oriented boundaries (the face on their left seen
//! from outside), and the face's `same_sense` says whether our surface's normal points out
//! of the solid where truck's oriented surface normal does (compared at one sample point).

use super::{GeometryError, PartError};
use super::truck_geometry::{self, p3};
use crate::cad::brep::{Coedge, Edge, EntityRef, Face, Loop, Model, Shell, Solid, Vertex};
use crate::cad::geom::Surface;
use crate::core::FaceId;
use glam::DVec3;
use std::collections::HashMap;
use truck_modeling::{ParametricSurface, ParametricSurface3D};

/// Relative tolerance (fraction of the part size) for recognising circles, planes, cylinders
/// and tori in truck's B-spline geometry.
pub const RECOGNISE_RELATIVE: f64 = 1e-9;

/// Converts a truck solid into a model of one solid; faces get no names (the part builders
/// name them).
///
/// # Errors
/// [`PartError::Geometry`] for a curve or surface that cannot be converted (truck's
/// intersection curves), or a degenerate one.
pub fn solid_to_model(solid: &truck_modeling::Solid, name: &str) -> Result<Model, PartError> {
    let pts: Vec<DVec3> = solid.vertex_iter().map(|v| p3(v.point())).collect();
    let (lo, hi) = pts.iter().fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    let size = if pts.is_empty() { 1.0 } else { (hi - lo).length().max(f64::MIN_POSITIVE) };
    let tol = RECOGNISE_RELATIVE * size;
    let mut m = Model::default();
    let mut vertices: HashMap<truck_modeling::VertexID, u32> = HashMap::new();
    let mut edges: HashMap<truck_modeling::EdgeID, u32> = HashMap::new();
    m.solids.push(Solid { shells: Vec::new(), name: Some(name.to_string()), instance: 0, source: EntityRef(0) });
    for (k, shell) in solid.boundaries().iter().enumerate() {
        let si = m.shells.len() as u32;
        m.solids[0].shells.push(si);
        m.shells.push(Shell { faces: Vec::new(), closed: true, solid: Some(0), void: k > 0, source: EntityRef(0) });
        for face in shell.iter() {
            let fid = FaceId::from_index(m.faces.len());
            let ts = face.surface();
            let ours = truck_geometry::surface(&ts, tol).map_err(|why| PartError::Geometry { face: fid, why })?;
            let same_sense = agrees(&face.oriented_surface(), &ours).ok_or_else(|| PartError::Geometry { face: fid, why: GeometryError::NoNormal })?;
            m.surfaces.push(ours);
            let mut loops = Vec::new();
            for (j, wire) in face.boundaries().iter().enumerate() {
                let mut coedges = Vec::new();
                for e in wire.iter() {
                    let index = match edges.get(&e.id()) {
                        Some(&i) => i,
                        None => {
                            let start = vertex(&mut m, &mut vertices, e.absolute_front());
                            let end = vertex(&mut m, &mut vertices, e.absolute_back());
                            let c = truck_geometry::curve(&e.curve(), tol).map_err(|why| PartError::Geometry { face: fid, why })?;
                            m.curves.push(c.curve);
                            let edge = Edge {
                                curve: Some(m.curves.len() as u32 - 1),
                                start,
                                end,
                                range: c.range,
                                same_sense: true,
                                closed: start == end,
                                seam: false,
                                degenerate: false,
                                source: EntityRef(0),
                            };
                            m.edges.push(edge);
                            let i = m.edges.len() as u32 - 1;
                            edges.insert(e.id(), i);
                            i
                        }
                    };
                    coedges.push(Coedge { edge: index, forward: e.orientation() });
                }
                m.loops.push(Loop { face: fid, outer: j == 0, orientation: true, coedges, vertex: None, source: EntityRef(0) });
                loops.push(m.loops.len() as u32 - 1);
            }
            m.faces.push(Face { surface: m.surfaces.len() as u32 - 1, same_sense, loops, shell: si, name: None, colour: None, source: EntityRef(0) });
            m.shells[si as usize].faces.push(fid);
        }
    }
    m.mark_edges();
    Ok(m)
}

fn vertex(m: &mut Model, map: &mut HashMap<truck_modeling::VertexID, u32>, v: &truck_modeling::Vertex) -> u32 {
    *map.entry(v.id()).or_insert_with(|| {
        m.vertices.push(Vertex { point: p3(v.point()), source: EntityRef(0) });
        m.vertices.len() as u32 - 1
    })
}

/// Whether our surface's normal agrees with truck's oriented normal, at the middle of truck's
/// parameter range (at `(0, 0)` for its unbounded planes); `None` where either has no normal.
fn agrees(oriented: &truck_modeling::Surface, ours: &Surface) -> Option<bool> {
    let (u, v) = oriented.try_range_tuple();
    let mid = |r: Option<(f64, f64)>| r.map_or(0.0, |(a, b)| 0.5 * (a + b));
    let (u, v) = (mid(u), mid(v));
    let p = p3(oriented.subs(u, v));
    let n = oriented.normal(u, v);
    let nt = DVec3::new(n.x, n.y, n.z);
    let q = ours.project(p);
    let no = ours.normal(q.x, q.y)?;
    let d = nt.dot(no);
    (d.abs() > 0.5).then_some(d > 0.0)
}
