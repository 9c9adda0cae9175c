//! `fepre inspect` as a library call: the topology report of a mesh file (a surface, or a tet
//! mesh's boundary) and, for tet meshes, element quality; for a surface that is open,
//! overlapping or faces inward, also the volume its winding number encloses.

use super::PipelineError;
use super::warning::Warning;
use crate::core::{FaceId, Tolerance};
use crate::io::{self, MeshData, ReadOptions};
use crate::mesh::TriSurface;
use crate::mesh::topology::{IntersectingPair, ReportOptions, ShellReport, SurfaceReport, surface_report};
use crate::quality::explained::{Explained, explained};
use crate::quality::input_angles::small_input_angles;
use crate::quality::mesh_quality::{TetQualityReport, tet_mesh_quality};
use crate::quality::worst_tet::{BoundaryIndex, TetPlace};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;

/// What [`inspect_file`] reads and measures.
#[derive(Clone, Copy, Debug)]
pub struct InspectOptions {
    /// Merge vertices closer than this (`None`: keep the file's vertices as they are).
    pub weld: Option<Tolerance>,
    /// Run the exact self-intersection test.
    pub self_intersections: bool,
    /// Measure the volume an open, overlapping or inward surface's winding number encloses.
    pub winding_volume: bool,
    /// List at most this many offending pairs, edges or triangles.
    pub max_listed: usize,
}

impl Default for InspectOptions {
    fn default() -> InspectOptions {
        InspectOptions { weld: Some(Tolerance::WELD), self_intersections: true, winding_volume: true, max_listed: 10 }
    }
}

/// A tag with its name and how many triangles carry it.
#[derive(Clone, Debug, Serialize)]
pub struct TagInfo {
    /// The tag.
    pub tag: u32,
    /// Its name.
    pub name: Option<String>,
    /// Triangles (of a tet mesh: its boundary's).
    pub triangles: usize,
}

/// Keys present for tet meshes only.
#[derive(Clone, Debug, Serialize)]
pub struct TetKeys {
    /// Smallest dihedral angle, degrees.
    pub min_dihedral_deg: f64,
    /// Largest dihedral angle, degrees.
    pub max_dihedral_deg: f64,
    /// Largest radius-edge ratio.
    pub max_radius_edge: f64,
    /// Tets with a dihedral angle under 5°.
    pub tets_under_5_deg: usize,
    /// Tets with a dihedral angle under 1°.
    pub tets_under_1_deg: usize,
    /// Tets under 10°; of those, the ones that touch no angle under 10° of the mesh's
    /// boundary (its dihedral angles at edges and the corners of its faces, as
    /// `fepre mesh` reports them), and of those the ones between the two sides of one.
    pub tets_under_10_deg: usize,
    /// Of those, the ones that touch no angle under 10° of the boundary.
    pub tets_under_10_deg_unexplained: usize,
    /// Of those, the ones between the two sides of one.
    pub tets_under_10_deg_between_sides: usize,
    /// The boundary's angles under 10° (counted where some tet is under 10°).
    pub input_angles_under_10_deg: usize,
    /// Volume-length ratio under `NEAR_DEGENERATE_VOLUME_LENGTH` (exactly flat ones included).
    pub near_degenerate: usize,
    /// The tet with the smallest dihedral angle: its centroid, nearest face and feature edge.
    pub worst_tet: Option<TetPlace>,
    /// Tets of negative volume.
    pub inverted: usize,
    /// Boundary triangles carrying a tag.
    pub boundary_triangles: usize,
    /// The regions and their tets.
    pub regions: Vec<TagInfo>,
    /// The quality statistics and histograms.
    pub quality: TetQualityReport,
}

/// The topology report of a mesh file: the JSON object `fepre inspect --json` prints. For a tet mesh the surface keys describe
/// the boundary of the meshed volume (its faces that belong to one tet), and `volume` is the
/// sum of the tet volumes.
#[derive(Clone, Debug, Serialize)]
pub struct InspectReport {
    /// The file.
    pub file: String,
    /// The file format.
    pub format: &'static str,
    /// What the file holds (surface, tet mesh, point set).
    pub kind: &'static str,
    /// Vertices in the file (before welding).
    pub file_vertices: usize,
    /// Vertices.
    pub vertices: usize,
    /// Triangles (of a tet mesh: its boundary's).
    pub triangles: usize,
    /// Tets.
    pub tets: usize,
    /// Edge-connected components.
    pub components: usize,
    /// Every edge has two triangles.
    pub closed: bool,
    /// Edge- and vertex-manifold.
    pub manifold: bool,
    /// Consistently oriented.
    pub oriented: bool,
    /// Closed and every shell outward.
    pub outward: bool,
    /// Edges with one triangle.
    pub open_edges: usize,
    /// Edges with more than two triangles.
    pub nonmanifold_edges: usize,
    /// Vertices whose triangles do not form one fan.
    pub nonmanifold_vertices: usize,
    /// Triangles of zero area.
    pub degenerate_triangles: usize,
    /// Euler characteristic.
    pub euler: i64,
    /// Genus, where the surface is closed and manifold.
    pub genus: Option<i64>,
    /// Volume (of a tet mesh: the sum of its tets').
    pub volume: f64,
    /// Area.
    pub area: f64,
    /// Loops of open edges.
    pub boundary_loops: usize,
    /// Intersecting triangle pairs (exact test; `None`: not tested).
    pub self_intersections: Option<usize>,
    /// Where the surface is open, overlaps itself or faces inward: the volume where its
    /// winding number exceeds one half (what `--method octree` meshes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub winding_volume: Option<crate::mesh3d::octree::WindingVolume>,
    /// The first intersecting triangle pairs.
    pub first_intersections: Vec<IntersectingPair>,
    /// The bounding box, where there are vertices.
    pub bbox: Option<[[f64; 3]; 2]>,
    /// The face tags and their triangles.
    pub tags: Vec<TagInfo>,
    /// The shells.
    pub shells: Vec<ShellReport>,
    #[serde(flatten)]
    /// The tet mesh keys (tet meshes only).
    pub tet: Option<TetKeys>,
    /// What was odd about the file but read anyway.
    pub notes: Vec<String>,
    /// What the report found but would rather not have (none so far: the report itself says
    /// what is open, crossing or inverted).
    pub warnings: Vec<Warning>,
    /// Seconds in all.
    pub seconds: f64,
}

fn tag_infos(tags: impl Iterator<Item = u32>, names: impl Fn(u32) -> Option<String>) -> Vec<TagInfo> {
    let mut count: BTreeMap<u32, usize> = BTreeMap::new();
    for t in tags {
        *count.entry(t).or_default() += 1;
    }
    count.into_iter().map(|(tag, triangles)| TagInfo { tag, name: names(tag), triangles }).collect()
}

/// Cells per axis of the winding-number volume (2.1 million samples: a fraction of a
/// per cent on a part that fills its box).
const WINDING_CELLS: usize = 128;

/// Reads the mesh file at `path` and reports its topology and, for a tet mesh, its element
/// quality. `stage` is told the name of each stage as it starts (a spinner's message).
///
/// # Errors
/// An unreadable or invalid input file.
pub fn inspect_file(path: &Path, options: &InspectOptions, stage: &dyn Fn(&str)) -> Result<InspectReport, PipelineError> {
    let start = Instant::now();
    let loaded = io::read(path, &ReadOptions::default().with_weld(options.weld))?;
    let opts = ReportOptions::default().with_self_intersections(options.self_intersections).with_max_listed(options.max_listed);
    stage("computing the topology report");
    let (surface, tet) = match &loaded.mesh {
        MeshData::Surface(s) => (s.clone(), None),
        MeshData::Volume(m) => {
            stage("measuring element quality");
            let q = tet_mesh_quality(m);
            let regions = tag_infos(m.region_tags.iter().map(|r| r.0), |r| m.region_names.get(crate::core::RegionId(r)).map(str::to_string));
            // io::read validates what it returns: every index is in range. The input angles
            // are the boundary's own (a mesh keeps its input surface's angles)
            let index = BoundaryIndex::new(m);
            let (angles, e) = if q.min_dihedral_deg < 10.0 {
                let angles = small_input_angles(&m.boundary_surface(), 10.0, true);
                let e = explained(m, index.sides(), &angles, 10.0);
                (angles, e)
            } else {
                (Vec::new(), Explained::default())
            };
            let worst_tet = q.min_dihedral.argmin.map(|t| index.locate(m, t, &angles, 10.0, &|f| m.face_names.get(f).map(str::to_string)));
            let keys = TetKeys {
                min_dihedral_deg: q.min_dihedral_deg,
                max_dihedral_deg: q.max_dihedral_deg,
                max_radius_edge: q.max_radius_edge,
                tets_under_5_deg: q.tets_min_dihedral_below_5,
                tets_under_1_deg: q.tets_min_dihedral_below_1,
                tets_under_10_deg: e.under[2].0,
                tets_under_10_deg_unexplained: e.under[2].1,
                tets_under_10_deg_between_sides: e.between[0],
                input_angles_under_10_deg: angles.len(),
                near_degenerate: q.near_degenerate,
                worst_tet,
                inverted: q.inverted,
                boundary_triangles: m.boundary.len(),
                regions,
                quality: q,
            };
            (m.boundary_surface(), Some(keys))
        }
        MeshData::Points(p) => (TriSurface { vertices: p.clone(), ..Default::default() }, None),
    };
    stage("computing the topology report");
    let r: SurfaceReport = surface_report(&surface, &opts);
    // a surface that is not a clean closed outward one: its divergence-theorem volume is not
    // what it encloses, so the winding number's is measured too
    let dirty = !(r.closed && r.manifold && r.oriented && r.outward) || r.self_intersections.is_some_and(|n| n > 0);
    let winding_volume = if tet.is_none() && dirty && options.winding_volume && !surface.triangles.is_empty() {
        stage("measuring the volume the winding number encloses");
        crate::mesh3d::octree::winding_volume(&surface, WINDING_CELLS)
    } else {
        None
    };
    let tags = tag_infos(surface.face_tags.iter().map(|t| t.0), |t| surface.face_names.get(FaceId(t)).map(str::to_string));
    let report = InspectReport {
        file: path.display().to_string(),
        format: loaded.format.name(),
        kind: loaded.mesh.kind(),
        file_vertices: loaded.file_vertices,
        vertices: surface.vertices.len(),
        triangles: r.triangles,
        tets: if let MeshData::Volume(m) = &loaded.mesh { m.tets.len() } else { 0 },
        components: r.components,
        closed: r.closed,
        manifold: r.manifold,
        oriented: r.oriented,
        outward: r.outward,
        open_edges: r.open_edges,
        nonmanifold_edges: r.nonmanifold_edges,
        nonmanifold_vertices: r.nonmanifold_vertices,
        degenerate_triangles: r.degenerate_triangles,
        euler: r.euler,
        genus: r.genus,
        volume: tet.as_ref().map_or(r.volume, |t| t.quality.volume),
        area: r.area,
        boundary_loops: r.boundary_loops,
        self_intersections: r.self_intersections,
        winding_volume,
        first_intersections: r.first_intersections.clone(),
        bbox: r.bbox.or_else(|| crate::core::Aabb::from_points(&surface.vertices).to_array()),
        tags,
        shells: r.shells,
        tet,
        notes: loaded.notes,
        warnings: Vec::new(),
        seconds: start.elapsed().as_secs_f64(),
    };
    Ok(report)
}
