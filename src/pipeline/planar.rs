//! `mesh2d` on a CAD part: the quadtree mesher on the planar faces of a STEP file.
//!
//! Reads and tessellates the file ([`super::tessellate_file`]: the tessellation's edges on a
//! face's boundary are the discretised CAD edges), takes the faces whose B-rep surface is a
//! plane, makes each a domain in its plane's frame (vertices within the tessellation's chord
//! tolerance of the plane: the file's edge curves on a plane are only that planar) (`crate::mesh2d::face`), meshes it with
//! [`crate::mesh2d::quadtree`] at a uniform size, checks it, and lifts the meshes back to
//! one tagged 3D surface (boundary vertices are the tessellation's own, so the faces meet
//! where they meet in the part). A face that fails is listed with its STEP `#id`; a face
//! asked for by number that is missing, not planar or fails is an error.

use super::default_size::default_size;
use super::job::Method;
use super::part::tessellate_file;
use super::{PipelineError, PlanarProblem};
use crate::cad::brep::{EntityRef, Model};
use crate::cad::geom::Surface;
use crate::core::{FaceId, RegionId};
use crate::mesh::TriSurface;
use crate::mesh2d::face::{planar_face, PlanarFace};
use crate::mesh2d::quadtree::{self, Angles, QuadtreeMesh, QuadtreeOptions};
use crate::tessellate::certificate::CertifyOptions;
use crate::tessellate::TessellateOptions;
use glam::DVec3;
use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;

/// Which faces to mesh.
#[derive(Clone, Debug, PartialEq)]
pub enum FaceChoice {
    /// Every planar face.
    AllPlanar,
    /// These faces (each must be planar).
    Faces(Vec<FaceId>),
}

/// One meshed face.
#[derive(Clone, Debug)]
pub struct MeshedFace {
    /// The face as a domain, with its frame.
    pub planar: PlanarFace,
    /// Its mesh (region tag: the face's id).
    pub mesh: QuadtreeMesh,
    /// Its angles.
    pub angles: Angles,
    /// Seconds spent meshing it.
    pub seconds: f64,
}

/// A planar face that could not be meshed.
#[derive(Clone, Debug, serde::Serialize)]
pub struct FailedPlanarFace {
    /// The face.
    pub face: FaceId,
    /// Its STEP `#id`.
    pub step_id: EntityRef,
    /// Why.
    pub reason: String,
}

/// The result of [`mesh_planar_faces`].
#[derive(Clone, Debug)]
pub struct PlanarFaces {
    /// The B-rep.
    pub model: Model,
    /// Its tessellation (the faces' boundaries come from it).
    pub tessellation: TriSurface,
    /// The size used.
    pub size: f64,
    /// How many faces of the part are planar.
    pub planar_faces: usize,
    /// The faces meshed, in face order.
    pub meshed: Vec<MeshedFace>,
    /// The planar faces that failed.
    pub failed: Vec<FailedPlanarFace>,
    /// Seconds: read and tessellate, then mesh.
    pub seconds: [f64; 2],
}

/// Meshes the chosen planar faces of the STEP file `path` at the uniform size `size`
/// (`None`: a CAD part's default, [`default_size`]).
///
/// # Errors
/// The file cannot be read; a face asked for is missing, not planar or cannot be meshed.
pub fn mesh_planar_faces(path: &Path, choice: &FaceChoice, size: Option<f64>, options: &QuadtreeOptions) -> Result<PlanarFaces, PipelineError> {
    let t0 = Instant::now();
    let (model, certified, _) = tessellate_file(path, &TessellateOptions::default(), None, &CertifyOptions::default())?;
    let t1 = Instant::now();
    let tess = certified.tessellation;
    let surface = &tess.surface;
    let size = size.unwrap_or_else(|| default_size(model.size(), true, Method::Delaunay).global);
    let is_plane = |f: FaceId| model.try_face(f).is_some_and(|face| matches!(model.surface(face.surface), Surface::Plane(_)));
    let planar_faces = model.face_ids().filter(|&f| is_plane(f)).count();
    let faces: Vec<FaceId> = match choice {
        FaceChoice::AllPlanar => model.face_ids().filter(|&f| is_plane(f)).collect(),
        FaceChoice::Faces(list) => {
            for &f in list {
                let Some(face) = model.try_face(f) else {
                    return Err(PipelineError::Planar { path: path.to_path_buf(), problem: PlanarProblem::NoSuchFace { face: f, faces: model.faces.len() } });
                };
                if !is_plane(f) {
                    return Err(PipelineError::Planar { path: path.to_path_buf(), problem: PlanarProblem::NotPlanar { face: f, step_id: face.source } });
                }
            }
            list.clone()
        }
    };
    // triangles per face, and the B-rep edge of each boundary piece
    let mut by_face: BTreeMap<FaceId, Vec<u32>> = BTreeMap::new();
    for (t, &tag) in surface.face_tags.iter().enumerate() {
        by_face.entry(tag).or_default().push(t as u32);
    }
    let mut edge_of: BTreeMap<(u32, u32), u32> = BTreeMap::new();
    for (e, ep) in tess.edges.iter().enumerate() {
        for w in ep.ids.windows(2) {
            edge_of.insert((w[0].min(w[1]), w[0].max(w[1])), e as u32 + 1);
        }
    }
    let tag = |a: u32, b: u32| edge_of.get(&(a.min(b), a.max(b))).copied().unwrap_or(0);
    let mut meshed = Vec::new();
    let mut failed = Vec::new();
    for f in faces {
        let face = model.face(f);
        let frame = match model.surface(face.surface) {
            Surface::Plane(p) => Some((p.frame.origin, p.frame.x)),
            _ => None,
        };
        let t = Instant::now();
        let tris = by_face.get(&f).map(Vec::as_slice).unwrap_or(&[]);
        let result = planar_face(surface, f, tris, frame, tess.chord, &tag).map_err(|e| e.to_string()).and_then(|planar| {
            let o = QuadtreeOptions { region: RegionId(f.0), ..*options };
            let mesh = quadtree::mesh_uniform(&planar.domain, size, &o).map_err(|e| format!("{f}: {e}"))?;
            let angles = quadtree::angles(&mesh, &planar.domain);
            Ok(MeshedFace { planar, mesh, angles, seconds: t.elapsed().as_secs_f64() })
        });
        match result {
            Ok(m) => meshed.push(m),
            Err(reason) => {
                if matches!(choice, FaceChoice::Faces(_)) {
                    return Err(PipelineError::Planar { path: path.to_path_buf(), problem: PlanarProblem::Failed { face: f, step_id: face.source, reason } });
                }
                failed.push(FailedPlanarFace { face: f, step_id: face.source, reason });
            }
        }
    }
    Ok(PlanarFaces { model, tessellation: tess.surface, size, planar_faces, meshed, failed, seconds: [(t1 - t0).as_secs_f64(), t1.elapsed().as_secs_f64()] })
}

impl PlanarFaces {
    /// The meshes lifted onto their planes as one surface, each triangle tagged with its
    /// face (quads split into two triangles); boundary vertices are the tessellation's
    /// points, shared between faces that share an edge.
    pub fn surface(&self) -> TriSurface {
        let tessellation_vertices: Option<&[DVec3]> = Some(&self.tessellation.vertices);
        let mut out = TriSurface::default();
        let mut shared: BTreeMap<u32, u32> = BTreeMap::new();
        for m in &self.meshed {
            let pm = &m.mesh.mesh;
            // mesh vertex -> domain point, for the boundary
            let mut domain_point = vec![crate::core::ids::NONE; pm.vertices.len()];
            for (s, chain) in m.mesh.boundary.iter().enumerate() {
                let [a, b] = m.planar.domain.segments[s];
                domain_point[chain[0] as usize] = a;
                domain_point[*chain.last().unwrap_or(&chain[0]) as usize] = b;
            }
            let ids: Vec<u32> = (0..pm.vertices.len())
                .map(|i| {
                    let dp = domain_point[i];
                    if dp != crate::core::ids::NONE {
                        let sv = m.planar.surface_vertex[dp as usize];
                        if let Some(&id) = shared.get(&sv) {
                            return id;
                        }
                        let p = tessellation_vertices.and_then(|v| v.get(sv as usize).copied()).unwrap_or_else(|| m.planar.frame.lift(pm.vertices[i]));
                        out.vertices.push(p);
                        let id = (out.vertices.len() - 1) as u32;
                        shared.insert(sv, id);
                        id
                    } else {
                        out.vertices.push(m.planar.frame.lift(pm.vertices[i]));
                        (out.vertices.len() - 1) as u32
                    }
                })
                .collect();
            let tag = m.planar.face;
            for t in &pm.triangles {
                out.triangles.push(t.map(|i| ids[i as usize]));
                out.face_tags.push(tag);
            }
            for q in &pm.quads {
                let q = q.map(|i| ids[i as usize]);
                out.triangles.push([q[0], q[1], q[2]]);
                out.triangles.push([q[0], q[2], q[3]]);
                out.face_tags.extend([tag, tag]);
            }
            if let Some(name) = self.model.face(tag).name.clone() {
                out.face_names.insert(tag, name);
            }
        }
        out
    }
}
