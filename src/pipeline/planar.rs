//! `mesh2d` on a CAD part: a 2D method on the planar faces of a STEP file.
//!
//! Reads and tessellates the file ([`super::tessellate_file`]: the tessellation's edges on a
//! face's boundary are the discretised CAD edges), takes the faces whose B-rep surface is a
//! plane, makes each a domain in its plane's frame (vertices within the tessellation's chord
//! tolerance of the plane: the file's edge curves on a plane are only that planar) (`crate::mesh2d::face`), meshes it with
//! the method asked ([`crate::mesh2d::mesh_domain`]) at a uniform size, the face's boundary
//! points kept, checks it, and lifts the meshes back to
//! one tagged 3D surface (boundary vertices are the tessellation's own, so the faces meet
//! where they meet in the part). A face that fails is listed with its STEP `#id`; a face
//! asked for by number that is missing, not planar or fails is an error.

use super::default_size::default_size;
use super::job::Method;
use super::part::tessellate_file;
use super::{PipelineError, PlanarProblem};
use crate::cad::brep::{EntityRef, Model};
use crate::cad::geom::Surface;
use crate::core::{FaceId, RegionId, SizeField};
use crate::mesh::{MixedSurface, TriSurface};
use crate::mesh2d::face::{planar_face, PlanarFace};
use crate::mesh2d::{mesh_domain, Boundary, Mesh2dOptions, Meshed2d, Method as Method2d};
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
    /// Its mesh (region tag: the face's id) and the method's figures.
    pub meshed: Meshed2d,
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
    /// The faces' boundary points in 3D: the tessellation's vertices, then the points that
    /// divide its boundary edges by the size (shared by the faces on both sides).
    pub points: Vec<DVec3>,
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
pub fn mesh_planar_faces(path: &Path, choice: &FaceChoice, size: Option<f64>, options: &Mesh2dOptions) -> Result<PlanarFaces, PipelineError> {
    mesh_planar_faces_sized(path, choice, size, None, options)
}

/// [`mesh_planar_faces`] with the size of a size field (a job's density) where `field` is
/// given: each face's size at a point is the field's at the point lifted onto the plane;
/// `size` (or the default) is the size reported and the field's floor of nothing.
///
/// # Errors
/// As [`mesh_planar_faces`].
pub fn mesh_planar_faces_sized(path: &Path, choice: &FaceChoice, size: Option<f64>, field: Option<&dyn SizeField>, options: &Mesh2dOptions) -> Result<PlanarFaces, PipelineError> {
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
    let mut points = surface.vertices.clone();
    let mut pieces: BTreeMap<(u32, u32), Vec<u32>> = BTreeMap::new();
    for f in faces {
        let face = model.face(f);
        let frame = match model.surface(face.surface) {
            Surface::Plane(p) => Some((p.frame.origin, p.frame.x)),
            _ => None,
        };
        let t = Instant::now();
        let tris = by_face.get(&f).map(Vec::as_slice).unwrap_or(&[]);
        let result = planar_face(surface, f, tris, frame, tess.chord, &tag).map_err(|e| e.to_string()).and_then(|planar| {
            // the boundary: the tessellation's edges divided by the size in 3D, kept, so that
            // neighbouring faces share its points; the quadtree cuts its own boundary by its
            // leaves (its band needs that for its angles), which neighbours do not share
            // (all quads halve every boundary edge: the edges are divided at twice the size)
            let quadtree = options.method == Method2d::Quadtree && !options.quads;
            let h3 = |p: DVec3| field.map_or(size, |fd| fd.size_at(p));
            let edge_factor = if options.quads { 2.0 } else { 1.0 };
            let edge_size = |p: DVec3| edge_factor * h3(p);
            let planar = if quadtree { planar } else { divide_edges(&planar, &edge_size, &mut points, &mut pieces).map_err(|e| format!("{f}: {e}"))? };
            let boundary = if quadtree { Boundary::Split } else { Boundary::Keep };
            let o = Mesh2dOptions { region: RegionId(f.0), boundary, ..options.clone() };
            let frame = planar.frame;
            let meshed = mesh_domain(&planar.domain, &|p| h3(frame.lift(p)), &o).map_err(|e| format!("{f}: {e}"))?;
            Ok(MeshedFace { planar, meshed, seconds: t.elapsed().as_secs_f64() })
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
    Ok(PlanarFaces { model, tessellation: tess.surface, points, size, planar_faces, meshed, failed, seconds: [(t1 - t0).as_secs_f64(), t1.elapsed().as_secs_f64()] })
}

/// `planar` with each boundary segment divided into pieces of about `size` at its middle, the dividing
/// points made in 3D between the segment's two surface vertices (so the face on the other
/// side of the edge gets the same points: `pieces` keeps them by edge) and appended to
/// `points`.
fn divide_edges(planar: &PlanarFace, size: &dyn Fn(DVec3) -> f64, points: &mut Vec<DVec3>, pieces: &mut BTreeMap<(u32, u32), Vec<u32>>) -> Result<PlanarFace, crate::mesh2d::DomainError> {
    let d = &planar.domain;
    let mut out_points = d.points.clone();
    let mut surface_vertex = planar.surface_vertex.clone();
    let mut segments = Vec::with_capacity(d.segments.len());
    let mut tags = Vec::with_capacity(d.segments.len());
    for (s, &[a, b]) in d.segments.iter().enumerate() {
        let (sa, sb) = (planar.surface_vertex[a as usize], planar.surface_vertex[b as usize]);
        let key = (sa.min(sb), sa.max(sb));
        let inner = pieces.entry(key).or_insert_with(|| {
            let (p0, p1) = (points[key.0 as usize], points[key.1 as usize]);
            let h = size(0.5 * (p0 + p1));
            let n = if h.is_finite() && h > 0.0 { ((p0.distance(p1) / h).round() as usize).max(1) } else { 1 };
            (1..n)
                .map(|k| {
                    points.push(p0.lerp(p1, k as f64 / n as f64));
                    (points.len() - 1) as u32
                })
                .collect()
        });
        let mut chain = vec![a];
        let mut add = |id: u32, chain: &mut Vec<u32>| {
            out_points.push(planar.frame.project(points[id as usize]));
            surface_vertex.push(id);
            chain.push((out_points.len() - 1) as u32);
        };
        if sa < sb {
            inner.iter().for_each(|&id| add(id, &mut chain));
        } else {
            inner.iter().rev().for_each(|&id| add(id, &mut chain));
        }
        chain.push(b);
        for w in chain.windows(2) {
            segments.push([w[0], w[1]]);
            tags.push(d.tags[s]);
        }
    }
    let domain = crate::mesh2d::Domain::new(out_points, segments, tags)?;
    Ok(PlanarFace { face: planar.face, domain, frame: planar.frame, surface_vertex })
}

impl PlanarFaces {
    /// The meshes lifted onto their planes as one surface of triangles and quads, each
    /// element tagged with its face. The faces' boundary points are the tessellation's,
    /// shared between faces that share an edge; a point a method put at the middle of a
    /// boundary segment (quadrilaterals) is the middle of the two shared points, shared too.
    pub fn surface(&self) -> MixedSurface {
        self.lift().0
    }

    /// Boundary vertices of the faces' meshes that are neither a point of the face's domain
    /// nor listed as a midpoint: points a method added on a face's boundary that the face on
    /// the other side of the edge does not have (the quadtree's cuts), where the lifted
    /// surface does not conform.
    pub fn unshared_boundary_points(&self) -> usize {
        self.lift().1
    }

    fn lift(&self) -> (MixedSurface, usize) {
        let mut unshared = 0;
        let mut out = MixedSurface::default();
        let mut shared: BTreeMap<u32, u32> = BTreeMap::new();
        let mut shared_mid: BTreeMap<(u32, u32), u32> = BTreeMap::new();
        for m in &self.meshed {
            let pm = &m.meshed.mesh;
            let domain = &m.planar.domain;
            // domain points are mesh vertices at the same coordinates
            let at: BTreeMap<[u64; 2], u32> = domain.points.iter().enumerate().map(|(i, p)| ([p.x.to_bits(), p.y.to_bits()], i as u32)).collect();
            let mut mid = vec![None; pm.vertices.len()];
            for &(v, ends) in &m.meshed.midpoints {
                if let Some(slot) = mid.get_mut(v as usize) {
                    *slot = Some(ends);
                }
            }
            let sv = |mesh_vertex: u32| -> Option<u32> {
                let p = pm.vertices.get(mesh_vertex as usize)?;
                at.get(&[p.x.to_bits(), p.y.to_bits()]).map(|&d| m.planar.surface_vertex[d as usize])
            };
            let mut share = |key: u32, p: DVec3, out: &mut MixedSurface| -> u32 {
                *shared.entry(key).or_insert_with(|| {
                    out.vertices.push(p);
                    (out.vertices.len() - 1) as u32
                })
            };
            let mut on_boundary = vec![false; pm.vertices.len()];
            let mut edges: BTreeMap<(u32, u32), usize> = BTreeMap::new();
            for e in pm.triangles.iter().map(|t| t.as_slice()).chain(pm.quads.iter().map(|q| q.as_slice())) {
                for k in 0..e.len() {
                    let (a, b) = (e[k], e[(k + 1) % e.len()]);
                    *edges.entry((a.min(b), a.max(b))).or_default() += 1;
                }
            }
            for (&(a, b), &n) in &edges {
                if n == 1 {
                    on_boundary[a as usize] = true;
                    on_boundary[b as usize] = true;
                }
            }
            let mut ids = Vec::with_capacity(pm.vertices.len());
            for (i, p) in pm.vertices.iter().enumerate() {
                let id = if let Some(s) = sv(i as u32) {
                    let q = self.points.get(s as usize).copied().unwrap_or_else(|| m.planar.frame.lift(*p));
                    share(s, q, &mut out)
                } else if let Some((a, b)) = mid[i].and_then(|[a, b]| Some((sv(a)?, sv(b)?))) {
                    let key = (a.min(b), a.max(b));
                    let v = &self.points;
                    let q = match (v.get(a as usize), v.get(b as usize)) {
                        (Some(&pa), Some(&pb)) => 0.5 * (pa + pb),
                        _ => m.planar.frame.lift(*p),
                    };
                    *shared_mid.entry(key).or_insert_with(|| {
                        out.vertices.push(q);
                        (out.vertices.len() - 1) as u32
                    })
                } else {
                    unshared += usize::from(on_boundary[i]);
                    out.vertices.push(m.planar.frame.lift(*p));
                    (out.vertices.len() - 1) as u32
                };
                ids.push(id);
            }
            let tag = m.planar.face;
            for t in &pm.triangles {
                out.triangles.push(t.map(|i| ids[i as usize]));
                out.triangle_tags.push(tag);
            }
            for q in &pm.quads {
                out.quads.push(q.map(|i| ids[i as usize]));
                out.quad_tags.push(tag);
            }
            if let Some(name) = self.model.face(tag).name.clone() {
                out.face_names.insert(tag, name);
            }
        }
        (out, unshared)
    }
}
