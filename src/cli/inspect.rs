//! `fepre inspect FILE`: the topology report of a surface (or of a tet mesh's boundary) and,
//! for tet meshes, element quality.

use crate::cli::progress::Progress;
use crate::core::{FaceId, Tolerance};
use crate::io::{self, MeshData, ReadOptions};
use crate::mesh::TriSurface;
use crate::mesh::topology::{IntersectingPair, ReportOptions, ShellReport, SurfaceReport, surface_report};
use crate::quality::explained::{Explained, explained};
use crate::quality::input_angles::small_input_angles;
use crate::quality::mesh_quality::{NEAR_DEGENERATE_VOLUME_LENGTH, TetQualityReport, tet_mesh_quality};
use crate::quality::worst_tet::{BoundaryIndex, TetPlace};
use anyhow::Result;
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

/// Examples shown by `fepre inspect --help`.
pub const EXAMPLES: &str = "\
Examples:
  fepre inspect part.stl                          closed? manifold? genus? volume? self-intersections?
  fepre inspect part.stl --json | jq .genus       one JSON object for scripts
  fepre inspect big.obj --no-self-intersections   skip the exact pairwise test on huge inputs
  fepre inspect scan.stl                          open or overlapping: also the volume its winding number encloses
  fepre inspect big_scan.stl --no-winding-volume  skip that measure (seconds on a large scan)
  fepre inspect mesh.1.ele                        a tet mesh: quality statistics and a dihedral-angle histogram";

/// Arguments of `fepre inspect`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Mesh file (.stl .obj .gltf .glb .off .mesh .node .ele .face .poly .smesh .msh .xyz).
    pub file: PathBuf,
    /// Print one JSON object on standard output instead of the text report.
    #[arg(long)]
    pub json: bool,
    /// Skip the exact self-intersection test (the report then says null).
    #[arg(long)]
    pub no_self_intersections: bool,
    /// Skip the volume an open, overlapping or inward surface's winding number encloses (2.1
    /// million samples; seconds on a large scan).
    #[arg(long)]
    pub no_winding_volume: bool,
    /// List at most N offending pairs, edges or triangles.
    #[arg(long, value_name = "N", default_value_t = 10)]
    pub max_listed: usize,
    /// Keep the file's vertices as they are instead of merging coincident ones.
    #[arg(long)]
    pub no_weld: bool,
    /// Merge vertices closer than REL times the bounding-box diagonal.
    #[arg(long, value_name = "REL", default_value_t = Tolerance::WELD.relative, value_parser = crate::cli::parse_fraction)]
    pub weld: f64,
}

/// A tag with its name and how many triangles carry it.
#[derive(Debug, Serialize)]
struct TagInfo {
    tag: u32,
    name: Option<String>,
    triangles: usize,
}

/// Keys present for tet meshes only.
#[derive(Debug, Serialize)]
struct TetKeys {
    min_dihedral_deg: f64,
    max_dihedral_deg: f64,
    max_radius_edge: f64,
    tets_under_5_deg: usize,
    tets_under_1_deg: usize,
    /// Tets under 10°; of those, the ones that touch no angle under 10° of the mesh's
    /// boundary (its dihedral angles at edges and the corners of its faces, as
    /// `fepre mesh` reports them), and of those the ones between the two sides of one.
    tets_under_10_deg: usize,
    tets_under_10_deg_unexplained: usize,
    tets_under_10_deg_between_sides: usize,
    /// The boundary's angles under 10° (counted where some tet is under 10°).
    input_angles_under_10_deg: usize,
    /// Volume-length ratio under `NEAR_DEGENERATE_VOLUME_LENGTH` (exactly flat ones included).
    near_degenerate: usize,
    /// The tet with the smallest dihedral angle: its centroid, nearest face and feature edge.
    worst_tet: Option<TetPlace>,
    inverted: usize,
    boundary_triangles: usize,
    regions: Vec<TagInfo>,
    quality: TetQualityReport,
}

/// The JSON object `fepre inspect --json` prints. For a tet mesh the surface keys describe
/// the boundary of the meshed volume (its faces that belong to one tet), and `volume` is the
/// sum of the tet volumes.
#[derive(Debug, Serialize)]
struct Report {
    file: String,
    format: &'static str,
    kind: &'static str,
    file_vertices: usize,
    vertices: usize,
    triangles: usize,
    tets: usize,
    components: usize,
    closed: bool,
    manifold: bool,
    oriented: bool,
    outward: bool,
    open_edges: usize,
    nonmanifold_edges: usize,
    nonmanifold_vertices: usize,
    degenerate_triangles: usize,
    euler: i64,
    genus: Option<i64>,
    volume: f64,
    area: f64,
    boundary_loops: usize,
    self_intersections: Option<usize>,
    /// Where the surface is open, overlaps itself or faces inward: the volume where its
    /// winding number exceeds one half (what `--method octree` meshes).
    #[serde(skip_serializing_if = "Option::is_none")]
    winding_volume: Option<crate::mesh3d::octree::WindingVolume>,
    first_intersections: Vec<IntersectingPair>,
    bbox: Option<[[f64; 3]; 2]>,
    tags: Vec<TagInfo>,
    shells: Vec<ShellReport>,
    #[serde(flatten)]
    tet: Option<TetKeys>,
    notes: Vec<String>,
    seconds: f64,
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

/// Runs `fepre inspect`.
///
/// # Errors
/// An unreadable or invalid input file (exit 1).
pub fn run(args: &Args) -> Result<()> {
    let start = Instant::now();
    let progress = Progress::start(&format!("reading {}", args.file.display()));
    let weld = if args.no_weld { None } else { Some(Tolerance::relative(args.weld)) };
    let loaded = io::read(&args.file, &ReadOptions::default().with_weld(weld))?;
    let opts = ReportOptions::default().with_self_intersections(!args.no_self_intersections).with_max_listed(args.max_listed);
    progress.stage("computing the topology report");
    let (surface, tet) = match &loaded.mesh {
        MeshData::Surface(s) => (s.clone(), None),
        MeshData::Volume(m) => {
            progress.stage("measuring element quality");
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
    progress.stage("computing the topology report");
    let r: SurfaceReport = surface_report(&surface, &opts);
    // a surface that is not a clean closed outward one: its divergence-theorem volume is not
    // what it encloses, so the winding number's is measured too
    let dirty = !(r.closed && r.manifold && r.oriented && r.outward) || r.self_intersections.is_some_and(|n| n > 0);
    let winding_volume = if tet.is_none() && dirty && !args.no_winding_volume && !surface.triangles.is_empty() {
        progress.stage("measuring the volume the winding number encloses");
        crate::mesh3d::octree::winding_volume(&surface, WINDING_CELLS)
    } else {
        None
    };
    progress.finish();
    let tags = tag_infos(surface.face_tags.iter().map(|t| t.0), |t| surface.face_names.get(FaceId(t)).map(str::to_string));
    let report = Report {
        file: args.file.display().to_string(),
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
        seconds: start.elapsed().as_secs_f64(),
    };
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        out!("{}", render(&report));
    }
    Ok(())
}

fn yes(b: bool) -> &'static str {
    if b { "yes" } else { "NO" }
}

fn opt<T: std::fmt::Display>(v: Option<T>) -> String {
    v.map_or_else(|| "-".to_string(), |x| x.to_string())
}

/// The text report.
fn render(r: &Report) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "{} ({}, {})", r.file, r.format, r.kind);
    if r.kind == "point set" {
        let _ = writeln!(s, "  points              {}", r.vertices);
        if let Some([lo, hi]) = r.bbox {
            let _ = writeln!(s, "  bbox                [{}, {}, {}] to [{}, {}, {}]", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
        }
        for n in &r.notes {
            let _ = writeln!(s, "  note: {n}");
        }
        return s;
    }
    let welded = if r.file_vertices != r.vertices { format!(" ({} in the file)", r.file_vertices) } else { String::new() };
    let _ = writeln!(s, "  vertices            {}{welded}", r.vertices);
    if r.tets > 0 {
        let _ = writeln!(s, "  tetrahedra          {}", r.tets);
        let _ = writeln!(s, "  boundary triangles  {} (tagged: {})", r.triangles, r.tet.as_ref().map_or(0, |t| t.boundary_triangles));
    } else {
        let _ = writeln!(s, "  triangles           {}", r.triangles);
    }
    let _ = writeln!(s, "  components          {}", r.components);
    let _ = writeln!(
        s,
        "  closed {}   manifold {}   oriented {}   outward {}",
        yes(r.closed),
        yes(r.manifold),
        yes(r.oriented),
        yes(r.outward)
    );
    let _ = writeln!(s, "  euler               {}   genus {}", r.euler, opt(r.genus));
    let _ = writeln!(s, "  volume              {:.9e}", r.volume);
    if let Some(w) = r.winding_volume {
        let _ = writeln!(s, "  winding volume      {:.6e} ± {:.1e} (where the winding number exceeds 1/2, what --method octree meshes; {}³ cells)", w.volume, w.error, w.cells_per_axis);
    }
    let _ = writeln!(s, "  area                {:.9e}", r.area);
    if let Some([lo, hi]) = r.bbox {
        let _ = writeln!(s, "  bbox                [{}, {}, {}] to [{}, {}, {}]", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    }
    if r.open_edges + r.nonmanifold_edges + r.nonmanifold_vertices + r.degenerate_triangles > 0 || r.boundary_loops > 0 {
        let _ = writeln!(
            s,
            "  open edges {} in {} loops, non-manifold edges {}, non-manifold vertices {}, degenerate triangles {}",
            r.open_edges, r.boundary_loops, r.nonmanifold_edges, r.nonmanifold_vertices, r.degenerate_triangles
        );
    }
    match r.self_intersections {
        None => {
            let _ = writeln!(s, "  self-intersections  not tested");
        }
        Some(n) => {
            let _ = writeln!(s, "  self-intersections  {n}");
            for p in &r.first_intersections {
                let _ = writeln!(s, "    triangle {} ({}) crosses triangle {} ({})", p.a, p.tag_a, p.b, p.tag_b);
            }
        }
    }
    if r.shells.len() > 1 {
        let _ = writeln!(s, "  shells:");
        let _ = writeln!(s, "    {:>3} {:>10} {:>7} {:>6} {:>7} {:>16} {:>8}", "#", "triangles", "closed", "euler", "genus", "volume", "outward");
        for (i, sh) in r.shells.iter().enumerate().take(20) {
            let _ = writeln!(
                s,
                "    {:>3} {:>10} {:>7} {:>6} {:>7} {:>16.9e} {:>8}",
                i,
                sh.triangles,
                yes(sh.closed),
                sh.euler,
                opt(sh.genus),
                sh.volume,
                sh.outward.map_or("-", yes)
            );
        }
        if r.shells.len() > 20 {
            let _ = writeln!(s, "    … {} more", r.shells.len() - 20);
        }
    }
    if !r.tags.is_empty() {
        let _ = writeln!(s, "  face tags:");
        for t in r.tags.iter().take(30) {
            let _ = writeln!(s, "    {:>6}  {:>9} triangles  {}", t.tag, t.triangles, t.name.as_deref().unwrap_or(""));
        }
        if r.tags.len() > 30 {
            let _ = writeln!(s, "    … {} more", r.tags.len() - 30);
        }
    }
    if let Some(t) = &r.tet {
        let _ = writeln!(s, "  regions:");
        for g in &t.regions {
            let _ = writeln!(s, "    {:>6}  {:>9} tets  {}", g.tag, g.triangles, g.name.as_deref().unwrap_or(""));
        }
        let _ = writeln!(
            s,
            "  dihedral            {:.2}° .. {:.2}° ({} tets under 5°, {} under 1°)",
            t.min_dihedral_deg, t.max_dihedral_deg, t.tets_under_5_deg, t.tets_under_1_deg
        );
        if t.tets_under_10_deg > 0 {
            let _ = writeln!(
                s,
                "  under 10°           {} tets; {} touch no angle under 10° of the boundary ({} such angles), {} of those lie between the two sides of one",
                t.tets_under_10_deg, t.tets_under_10_deg_unexplained, t.input_angles_under_10_deg, t.tets_under_10_deg_between_sides
            );
        }
        let _ = writeln!(s, "  max radius-edge     {:.3}", t.max_radius_edge);
        let _ = writeln!(
            s,
            "  near-degenerate     {} tets (volume-length under {NEAR_DEGENERATE_VOLUME_LENGTH}; exactly flat {}), inverted {}",
            t.near_degenerate, t.quality.degenerate, t.inverted
        );
        for (label, text) in t.worst_tet.as_ref().map(TetPlace::lines).unwrap_or_default() {
            let _ = writeln!(s, "  {label:<19} {text}");
        }
        let _ = writeln!(s, "  quality:");
        for line in t.quality.render().lines() {
            let _ = writeln!(s, "    {line}");
        }
    }
    for n in &r.notes {
        let _ = writeln!(s, "  note: {n}");
    }
    let _ = writeln!(s, "  ({:.3} s)", r.seconds);
    s
}
