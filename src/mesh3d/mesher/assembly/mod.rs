//! Meshing a part made of several solids (an assembly): each solid is its own region.
//!
//! Input: the part's closed tagged surface, the solid each triangle bounds ([`Solids`]: a
//! region tag and name per solid) and the gap within which surfaces of different solids
//! touch. Stages:
//! 1. the surface is cut into one closed surface per solid, and each passes the mesher's
//!    input check on its own (a solid crossing itself stays an error, naming the solid);
//! 2. triangles of different solids within the gap of each other are paired (one BVH over
//!    all of them); [`overlap`] refuses solids whose interiors overlap deeper than the gap,
//!    [`contact`] measures the area over which facing faces touch, per pair of faces;
//! 3. [`imprint`] (unless [`MeshOptions::imprint`] is off, or with `keep_surface`): faces in
//!    contact that lie in one plane are remade of one triangulation of that plane, so that
//!    where two solids overlap they have the same triangles;
//! 4. each solid is meshed on its own by [`mesh_surface`](crate::mesh3d::mesher::mesh_surface) (in parallel, results in solid
//!    order: the same mesh for any thread count), which always works for solids that only
//!    touch;
//! 5. [`merge`] makes one mesh: region tag and name per solid, face tags kept, and where two
//!    solids' boundary triangles coincide exactly their nodes merged into a conforming
//!    interface. Each [`Contact`] says how much of its area became such an interface
//!    (`shared_area`); the rest is where a solver must tie the solids.

mod contact;
mod imprint;
mod imprint_plane;
mod merge;
mod overlap;
mod solid;

use crate::core::bvh::Bvh;
use crate::core::intersection::is_degenerate;
use crate::core::{Aabb, BoundaryGeometry, FaceId, RegionId, SizeField};
use crate::mesh::{TetMesh, TriSurface};
use crate::mesh3d::mesher::{MeshOptions, MeshReport, MeshingError, Seeds, input, mesh_surface_pinned};
use glam::DVec3;
use rayon::prelude::*;
use serde::Serialize;
use std::fmt;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// One solid of an assembly.
#[derive(Clone, Debug, PartialEq)]
pub struct SolidInfo {
    /// Its region tag in the mesh.
    pub tag: RegionId,
    /// Its name (the B-rep solid's or product's), where known.
    pub name: Option<String>,
}

/// The solids of a surface.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Solids {
    /// Per triangle of the surface, the index of its solid in `solids`.
    pub of_triangle: Vec<u32>,
    /// The solids, each with its region tag and name.
    pub solids: Vec<SolidInfo>,
}

/// A solid and one of its faces, for messages and reports.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SolidFace {
    /// The solid's region tag.
    pub solid: RegionId,
    /// The solid's name.
    pub solid_name: Option<String>,
    /// The face's tag.
    pub face: FaceId,
    /// The face's name.
    pub face_name: Option<String>,
}

impl fmt::Display for SolidFace {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "solid {}", self.solid.0)?;
        if let Some(n) = &self.solid_name {
            write!(f, " ({n:?})")?;
        }
        write!(f, ", face {}", self.face.0)?;
        if let Some(n) = &self.face_name {
            write!(f, " ({n:?})")?;
        }
        Ok(())
    }
}

/// Two faces of different solids that touch.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Contact {
    /// The solid with the smaller index, its region tag.
    pub solid_a: RegionId,
    /// Its face.
    pub face_a: FaceId,
    /// The other solid.
    pub solid_b: RegionId,
    /// Its face.
    pub face_b: FaceId,
    /// The area over which the two faces are within the gap of each other, facing.
    pub area: f64,
    /// Of it, the area of mesh faces the two solids share (a conforming interface: nodes
    /// merged); the rest must be tied.
    pub shared_area: f64,
}

/// Two triangles of different solids within the gap of each other: (solid, local triangle),
/// the first of the smaller solid.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Pair {
    pub a: (usize, u32),
    pub b: (usize, u32),
}

/// Meshes each solid of `surface` on its own and merges the meshes: region tag and name per
/// solid, boundary triangles with their face tags, nodes merged where two solids' boundary
/// triangles coincide. Returns the mesh, the report (summed over the solids) and the contacts
/// between faces of different solids, sorted by solids and faces.
///
/// `gap`: surfaces of different solids closer than this touch; a solid reaching deeper than
/// this into another overlaps it (for a certified tessellation, a few times its chord
/// deviation: see `overlap`).
///
/// # Errors
/// [`MeshingError::Overlap`] where two solids' interiors overlap; [`MeshingError::InSolid`]
/// wrapping what the input check or the mesher says of one solid (triangle and vertex
/// numbers are the surface's); [`MeshingError::Degenerate`] for an inconsistent `solids` or a
/// zero-area triangle.
pub fn mesh_solids(surface: &TriSurface, solids: &Solids, gap: f64, size: &dyn SizeField, options: &MeshOptions) -> Result<(TetMesh, MeshReport, Vec<Contact>), MeshingError> {
    mesh_solids_on(surface, solids, gap, size, options, None)
}

/// [`mesh_solids`] on the geometry the surface approximates (see [`super::mesh_surface_on`]).
///
/// # Errors
/// As [`mesh_solids`].
pub fn mesh_solids_on(
    surface: &TriSurface,
    solids: &Solids,
    gap: f64,
    size: &dyn SizeField,
    options: &MeshOptions,
    geometry: Option<&dyn BoundaryGeometry>,
) -> Result<(TetMesh, MeshReport, Vec<Contact>), MeshingError> {
    let start = Instant::now();
    let mut stages: Vec<(String, f64)> = Vec::new();
    let mut clock = Instant::now();
    let mut stage = |name: &str, t: &mut Instant| {
        stages.push((name.to_string(), t.elapsed().as_secs_f64()));
        *t = Instant::now();
    };
    let count = solids.solids.len();
    let (mut parts, mut contacts) = checked_solids(surface, solids, gap)?;
    stage("solids", &mut clock);
    // keep-surface keeps the input's triangles as they are
    let imprinted = (options.imprint && !options.keep_surface).then(|| {
        let outcome = imprint::imprint(&mut parts, &contacts, solids, gap);
        stage("imprint", &mut clock);
        outcome
    });
    let in_solid = |s: usize, part: &solid::SolidSurface, e: MeshingError| in_solid(solids, s, part, e);
    // the error reported is the first solid's in order, whatever the thread count: a solid
    // after one known to fail is not started, every solid before it still is
    let first_failed = AtomicUsize::new(usize::MAX);
    // one narrow-strip tolerance for all the solids: the whole assembly's
    let options = &options.clone().with_narrow_tolerance(Some(options.narrow_length(surface)));
    let meshed: Vec<Option<Result<(TetMesh, MeshReport), MeshingError>>> = parts
        .par_iter()
        .enumerate()
        .map(|(s, p)| {
            if s > first_failed.load(Ordering::Relaxed) {
                return None;
            }
            // faces in contact keep their vertices: their nodes are merged with the other
            // solid's where the triangles coincide, or tied
            let tag = solids.solids[s].tag;
            let pinned: Vec<FaceId> = contacts
                .iter()
                .flat_map(|c| [(c.solid_a, c.face_a), (c.solid_b, c.face_b)])
                .filter(|&(r, _)| r == tag)
                .map(|(_, f)| f)
                .collect();
            let r = mesh_surface_pinned(&p.surface, &Seeds::default(), size, options, &pinned, geometry).map_err(|e| in_solid(s, p, e));
            if r.is_err() {
                first_failed.fetch_min(s, Ordering::Relaxed);
            }
            Some(r)
        })
        .collect();
    let (mut meshes, mut reports) = (Vec::with_capacity(count), Vec::with_capacity(count));
    for r in meshed {
        match r {
            Some(Ok((m, rep))) => {
                meshes.push(m);
                reports.push(rep);
            }
            Some(Err(e)) => return Err(e),
            None => return Err(MeshingError::Internal("a solid was skipped although none before it failed".into())),
        }
    }
    stage("mesh solids", &mut clock);
    let mesh = merge_solids(meshes, solids, &mut contacts);
    stage("merge", &mut clock);
    let mut report = merge::merge_reports(&reports);
    // the assembly's own stages, then each solid's summed over the solids
    stages.append(&mut report.stage_seconds);
    report.stage_seconds = stages;
    report.nodes = mesh.vertices.len();
    report.tets = mesh.tets.len();
    report.regions = count;
    if let Some(o) = imprinted {
        report.imprint_volume = o.volume;
        report.imprinted = Some((o.components, o.imprinted));
    }
    report.seconds = start.elapsed().as_secs_f64();
    Ok((mesh, report, contacts))
}

/// Each solid of `surface` cut out on its own (vertices renumbered, face tags and names
/// kept), in the order of `solids`: for a mesher other than [`mesh_solids`]'s to mesh one by
/// one. `solids` must match the surface (as [`assembly_contacts`] checks).
pub fn solid_surfaces(surface: &TriSurface, solids: &Solids) -> Vec<TriSurface> {
    solid::split(surface, &solids.of_triangle, solids.solids.len()).into_iter().map(|p| p.surface).collect()
}

/// One mesh of the solids' meshes (`meshes[s]` meshes solid `s`): region tag and name per
/// solid, face tags kept, nodes merged where two solids' boundary triangles coincide exactly;
/// the area so merged is added to the contacts' `shared_area` (a contact is added where
/// there was none), and the contacts are sorted by solids and faces.
pub fn merge_solids(meshes: Vec<TetMesh>, solids: &Solids, contacts: &mut Vec<Contact>) -> TetMesh {
    let tags: Vec<RegionId> = solids.solids.iter().map(|s| s.tag).collect();
    let names: Vec<Option<String>> = solids.solids.iter().map(|s| s.name.clone()).collect();
    let (mesh, shared) = merge::merge(meshes, &tags, &names);
    for ((sa, fa), (sb, fb), area) in shared {
        let ((sa, fa), (sb, fb)) = if sa < sb { ((sa, fa), (sb, fb)) } else { ((sb, fb), (sa, fa)) };
        let (ta, tb) = (solids.solids[sa].tag, solids.solids[sb].tag);
        match contacts.iter_mut().find(|c| (c.solid_a, c.face_a, c.solid_b, c.face_b) == (ta, fa, tb, fb)) {
            Some(c) => c.shared_area += area,
            None => contacts.push(Contact { solid_a: ta, face_a: fa, solid_b: tb, face_b: fb, area, shared_area: area }),
        }
    }
    contacts.sort_by(|x, y| (x.solid_a, x.face_a, x.solid_b, x.face_b).cmp(&(y.solid_a, y.face_a, y.solid_b, y.face_b)));
    mesh
}

/// What [`mesh_solids`] checks before meshing, without meshing: each solid's own surface,
/// that no two solids overlap, and the contacts between them (`shared_area` 0: nothing is
/// merged yet). For reports on an assembly, and for tests.
///
/// # Errors
/// As [`mesh_solids`], but for the mesher's own errors.
pub fn assembly_contacts(surface: &TriSurface, solids: &Solids, gap: f64) -> Result<Vec<Contact>, MeshingError> {
    checked_solids(surface, solids, gap).map(|(_, c)| c)
}

/// Cuts the surface into its solids, checks each, refuses overlaps, measures contacts.
fn checked_solids(surface: &TriSurface, solids: &Solids, gap: f64) -> Result<(Vec<solid::SolidSurface>, Vec<Contact>), MeshingError> {
    check_input(surface, solids)?;
    let mut parts = solid::split(surface, &solids.of_triangle, solids.solids.len());
    let checked: Vec<Result<(), MeshingError>> = parts.par_iter().enumerate().map(|(s, p)| input::check(&p.surface).map_err(|e| in_solid(solids, s, p, e))).collect();
    checked.into_iter().collect::<Result<Vec<()>, _>>()?;
    parts.par_iter_mut().for_each(solid::SolidSurface::prepare);
    let pairs = candidate_pairs(&parts, gap);
    overlap::check(&parts, solids, &pairs, gap)?;
    let contacts = contacts(&parts, solids, &pairs, gap);
    Ok((parts, contacts))
}

/// Solid `s`'s error, its numbers the whole surface's.
fn in_solid(solids: &Solids, s: usize, part: &solid::SolidSurface, e: MeshingError) -> MeshingError {
    MeshingError::InSolid { solid: solids.solids[s].tag, name: solids.solids[s].name.clone(), source: Box::new(renumber(e, part)) }
}

/// The solids' list matches the surface; no zero-area triangle (named by its index in the
/// surface, before the surface is cut).
fn check_input(surface: &TriSurface, solids: &Solids) -> Result<(), MeshingError> {
    surface.validate().map_err(|e| MeshingError::Degenerate(e.to_string()))?;
    if solids.of_triangle.len() != surface.triangles.len() {
        return Err(MeshingError::Degenerate(format!("{} solid indices for {} triangles", solids.of_triangle.len(), surface.triangles.len())));
    }
    if let Some((t, s)) = solids.of_triangle.iter().enumerate().find(|(_, s)| **s as usize >= solids.solids.len()) {
        return Err(MeshingError::Degenerate(format!("triangle {t} is given solid {s} of {}", solids.solids.len())));
    }
    for (i, t) in surface.triangles.iter().enumerate() {
        let [a, b, c] = t.map(|v| surface.vertices[v as usize]);
        if is_degenerate(a, b, c) {
            return Err(MeshingError::Degenerate(format!("triangle {i} ({}) has zero area", surface.face_tags[i])));
        }
    }
    Ok(())
}

/// A solid's error with its triangle and vertex numbers turned into the part surface's.
fn renumber(e: MeshingError, part: &solid::SolidSurface) -> MeshingError {
    let v = |x: u32| part.vertex_of.get(x as usize).copied().unwrap_or(x);
    let t = |x: u32| part.triangle_of.get(x as usize).copied().unwrap_or(x);
    match e {
        MeshingError::Open { count, edges, at, faces } => MeshingError::Open { count, edges: edges.into_iter().map(|e| e.map(v)).collect(), at, faces },
        MeshingError::NonManifold { edge, count } => MeshingError::NonManifold { edge: edge.map(v), count },
        MeshingError::SelfIntersecting { a, b, tag_a, tag_b, count } => MeshingError::SelfIntersecting { a: t(a), b: t(b), tag_a, tag_b, count },
        MeshingError::Recovery { triangle, tag, message } => MeshingError::Recovery { triangle: t(triangle as u32) as usize, tag, message },
        other => other,
    }
}

/// Every pair of triangles of different solids whose boxes come within `gap` of each other,
/// sorted by solid pair, then triangles.
fn candidate_pairs(parts: &[solid::SolidSurface], gap: f64) -> Vec<Pair> {
    let mut first = Vec::with_capacity(parts.len() + 1);
    let mut n = 0usize;
    for p in parts {
        first.push(n);
        n += p.corners.len();
    }
    first.push(n);
    let locate = |g: u32| -> (usize, u32) {
        let s = first.partition_point(|&f| f <= g as usize) - 1;
        (s, g - first[s] as u32)
    };
    let half = DVec3::splat(0.5 * gap);
    let items = parts.iter().enumerate().flat_map(|(s, p)| {
        let base = first[s] as u32;
        p.corners.iter().enumerate().map(move |(t, c)| {
            let b = Aabb::from_points(c);
            (base + t as u32, Aabb { min: b.min - half, max: b.max + half })
        })
    });
    let bvh = Bvh::build(items);
    let mut pairs = bvh.par_filter_map_overlapping_pairs(|i, j| {
        let (x, y) = (locate(i), locate(j));
        if x.0 == y.0 {
            return None;
        }
        Some(if x < y { Pair { a: x, b: y } } else { Pair { a: y, b: x } })
    });
    // the pairs of one pair of solids together
    pairs.sort_unstable_by_key(|p| (p.a.0, p.b.0, p.a.1, p.b.1));
    pairs
}

/// The contacts of facing triangle pairs, summed per pair of faces; a pair of faces touching
/// over less than `gap²` (along an edge, at a corner: rounding) is no contact.
fn contacts(parts: &[solid::SolidSurface], solids: &Solids, pairs: &[Pair], gap: f64) -> Vec<Contact> {
    let pieces: Vec<Option<(usize, FaceId, usize, FaceId, f64)>> = pairs
        .par_iter()
        .map(|p| {
            let (sa, sb) = (&parts[p.a.0], &parts[p.b.0]);
            let (ta, tb) = (p.a.1 as usize, p.b.1 as usize);
            let area = contact::facing_area(sa.corners[ta], sa.normals[ta], sb.corners[tb], sb.normals[tb], gap);
            (area > 0.0).then(|| (p.a.0, sa.tag(p.a.1), p.b.0, sb.tag(p.b.1), area))
        })
        .collect();
    let mut sums: std::collections::BTreeMap<(usize, FaceId, usize, FaceId), f64> = std::collections::BTreeMap::new();
    for (a, fa, b, fb, area) in pieces.into_iter().flatten() {
        *sums.entry((a, fa, b, fb)).or_insert(0.0) += area;
    }
    sums.into_iter()
        .filter(|&(_, area)| area >= gap * gap)
        .map(|((a, fa, b, fb), area)| Contact { solid_a: solids.solids[a].tag, face_a: fa, solid_b: solids.solids[b].tag, face_b: fb, area, shared_area: 0.0 })
        .collect()
}
