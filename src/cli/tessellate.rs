//! `fepre tessellate CAD -o OUT`: a watertight, certified triangle surface of a STEP file,
//! every triangle tagged with its B-rep face.
//!
//! Reads the STEP file, tessellates every face at the chord deviation asked for, checks the
//! result with [`crate::tessellate::certificate`] and writes it only when the certificate
//! passes (or with `--force`). Exit codes: 0 written, 1 the file could not be read or the
//! certificate failed (the message names the face and its STEP `#id`, or the solid left open
//! and its free edges; no file is written), 2 bad usage. A surface model left open after
//! sewing exits 0 with `watertight: false` and its holes listed (`open_surface`); open
//! surface shells beside solids are listed the same way, and `watertight` speaks of the
//! solids.

use crate::cad::brep::{Dropped, EntityRef, FaceEntry, Model, Units};
use crate::cli::usage_error;
use crate::core::size_field::UniformSize;
use crate::core::{FaceId, SizeField};
use crate::io::{self, Format, MeshData, WriteOptions};
use crate::pipeline;
use crate::tessellate::certificate::Certificate;
use crate::tessellate::{TessellateOptions, Tessellation};
use anyhow::Result;
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

/// Examples shown by `fepre tessellate --help`.
pub const EXAMPLES: &str = "\
Examples:
  fepre tessellate part.step -o part.stl                 certified surface, default deviation (2e-4 of the model size, less on slender parts)
  fepre tessellate part.step -o part.msh --deviation 5e-5  finer; MSH 4.1 keeps each face as a physical group
  fepre tessellate part.stp -o part.vtu --json           one JSON report: Euler per shell, volume, area, checks
  fepre tessellate part.step -o part.obj --force         write even when a check fails (the report says which)
  fepre tessellate part.step -o part.stl --max-edge 2    well-shaped triangles of edge about 2 mm (a volume mesher's input)

The output format follows the extension: .stl, .obj (one group per face), .vtu (face ids as
cell data), .msh (MSH 4.1, one physical group per face). The file is written only when the
certificate passes: closed, manifold, oriented outward, no self-intersection, Euler
characteristic and boundary loops as the B-rep's, volume and area within tolerance of the
B-rep's own (quadrature over the exact surfaces).";

/// Arguments of `fepre tessellate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// STEP file (.step, .stp; AP203, AP214, AP242).
    pub cad: PathBuf,
    /// Output surface: .stl, .obj, .vtu or .msh.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Largest distance between the triangles and the exact surface, as a fraction of the
    /// model size (the diagonal of its bounding box). Without it, 2e-4, and smaller on the
    /// faces of a solid that would lose more than 0.4 % of its volume (slender and thin
    /// parts); with it, exactly this everywhere: a deviation so coarse that a solid's volume
    /// is off by more than 0.5 % fails the certificate.
    #[arg(long, value_name = "REL", value_parser = positive_fraction)]
    pub deviation: Option<f64>,
    /// Longest triangle edge (model units, mm for STEP): edges are cut to it and faces refined
    /// to well-shaped triangles of about this size, as a volume mesher wants its boundary;
    /// smaller on faces narrower than it and across walls of the solid thinner than a third
    /// of it (1.5 times their width or thickness, down to 1/256 of it across a face and 1/64
    /// across the solid).
    #[arg(long, value_name = "H", value_parser = crate::cli::positive)]
    pub max_edge: Option<f64>,
    /// Print one JSON object on standard output.
    #[arg(long)]
    pub json: bool,
    /// Write the surface even when the certificate fails (exit code 0, failures reported).
    #[arg(long)]
    pub force: bool,
}

fn positive_fraction(s: &str) -> Result<f64, String> {
    let x = crate::cli::parse_fraction(s)?;
    if x > 0.0 && x <= 0.1 { Ok(x) } else { Err(format!("'{s}' must be in (0, 0.1]")) }
}

/// Euler characteristic of one shell group, mesh and B-rep.
#[derive(Debug, Serialize)]
struct EulerEntry {
    brep_shells: Vec<EntityRef>,
    mesh: i64,
    brep: i64,
}

/// A face that could not be meshed.
#[derive(Debug, Serialize)]
struct FailedFaceEntry {
    face: FaceId,
    step_id: EntityRef,
    reason: String,
}

/// The JSON object `fepre tessellate --json` prints.
#[derive(Debug, Serialize)]
struct Report {
    input: String,
    output: Option<String>,
    solids: usize,
    /// Shells not bounding a solid (surface models).
    surface_model_shells: usize,
    /// What sewing the open shells did.
    sewing: Option<crate::cad::brep::SewReport>,
    faces: usize,
    /// Per face: unique name, colour, STEP `#id`, solid.
    face_table: Vec<FaceEntry>,
    triangles: usize,
    vertices: usize,
    /// Closed, manifold, oriented where it should be ([`Certificate::watertight`]).
    watertight: bool,
    /// What `watertight` speaks of: `solids` (open surface shells beside them are reported
    /// in `open_surface`), or `surface model`.
    watertight_of: &'static str,
    /// The shells of a surface model (no solid) left open after sewing: their free edges
    /// grouped into holes.
    open_surface: Option<OpenSurface>,
    euler: Vec<EulerEntry>,
    volume: f64,
    area: f64,
    units: Units,
    deviation: f64,
    max_edge: Option<f64>,
    chord_mm: f64,
    dropped: Vec<Dropped>,
    /// What was odd about the file as written but read anyway ([`Model::notes`]).
    notes: Vec<String>,
    failed_faces: Vec<FailedFaceEntry>,
    seconds: f64,
    read_seconds: f64,
    tessellate_seconds: f64,
    certificate: Certificate,
}

/// Open shells of a surface model after sewing.
#[derive(Debug, Serialize)]
struct OpenSurface {
    /// Shells that bound no solid and do not close.
    shells: usize,
    /// Their free edges.
    free_edges: usize,
    /// The free edges grouped into holes, largest first.
    holes: Vec<crate::cad::brep::Hole>,
}

/// The open surface-model shells of `m`, or `None` when every one closes (or there is none).
fn open_surface(m: &Model) -> Option<OpenSurface> {
    let holes = m.holes(|s| s.solid.is_none() && !s.closed);
    if holes.is_empty() {
        return None;
    }
    let mut shells: Vec<EntityRef> = holes.iter().flat_map(|h| h.shells.iter().copied()).collect();
    shells.sort_unstable();
    shells.dedup();
    Some(OpenSurface { shells: shells.len(), free_edges: holes.iter().map(|h| h.edges).sum(), holes })
}

/// The lines that say where a surface is open.
fn print_open(r: &Report) {
    if let Some(o) = &r.open_surface {
        let beside = if r.watertight_of == "solids" { " beside the solids (not part of `watertight`)" } else { "" };
        outln!("open shells  {}{beside}: {} free edges in {} hole{}", o.shells, o.free_edges, o.holes.len(), if o.holes.len() == 1 { "" } else { "s" });
        for h in o.holes.iter().take(10) {
            outln!("  hole       {}", h.describe());
        }
        if o.holes.len() > 10 {
            outln!("  ... {} more holes (--json lists all)", o.holes.len() - 10);
        }
    }
    for h in r.certificate.open_solids.iter().take(10) {
        outln!("OPEN SOLID   {}: {}", h.shells.iter().map(|s| format!("shell {s}")).collect::<Vec<_>>().join(", "), h.describe());
    }
}

/// What `fepre tessellate` made: the B-rep, its certified tessellation, the seconds.
struct Certified {
    model: Model,
    tessellation: Tessellation,
    certificate: Certificate,
    seconds: [f64; 2],
}

/// Runs `fepre tessellate`.
///
/// # Errors
/// An unreadable STEP file or a failed certificate without `--force` (exit 1); an output
/// format that cannot hold a surface (exit 2).
pub fn run(args: &Args) -> Result<()> {
    let out = &args.output;
    if !matches!(Format::from_path(out), Some(Format::Stl | Format::Obj | Format::Vtu | Format::Msh)) {
        return Err(usage_error(format!("{}: the surface is written as .stl, .obj, .vtu or .msh", out.display())));
    }
    let t0 = Instant::now();
    let opts = match args.deviation {
        Some(d) => TessellateOptions::default().with_chord_relative(d).with_volume_relative(0.0),
        None => TessellateOptions::default(),
    };
    let size = args.max_edge.map(UniformSize);
    let model = match crate::cad::step::read_shape(&args.cad)? {
        crate::cad::step::Shape::Brep(m) => m,
        crate::cad::step::Shape::Tessellated(t) => return run_tessellated(args, &t, t0),
    };
    let read = t0.elapsed().as_secs_f64();
    let (model, c, seconds) = pipeline::tessellate_model(model, read, &opts, size.as_ref().map(|s| s as &dyn SizeField), &crate::tessellate::certificate::CertifyOptions::default());
    let c = Certified { model, tessellation: c.tessellation, certificate: c.certificate, seconds: [seconds.read, seconds.tessellate] };
    let passed = c.certificate.passed;
    if !passed && !args.force {
        if args.json {
            outln!("{}", serde_json::to_string_pretty(&report(args, &c, None, t0))?);
        }
        anyhow::bail!("{}", pipeline::failure_message(&args.cad, &c.certificate, &c.model.dropped));
    }
    io::write(out, &MeshData::Surface(c.tessellation.surface.clone()), &WriteOptions::default())?;
    let r = report(args, &c, Some(out.display().to_string()), t0);
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&r)?);
    } else {
        outln!("solids       {} ({} surface-model shells)", r.solids, r.surface_model_shells);
        if let Some(sw) = &r.sewing {
            outln!("sewn         {} edges and {} vertices merged (tolerance {:.3e} mm), free edges {} -> {}", sw.merged_edges, sw.merged_vertices, sw.tolerance, sw.free_edges_before, sw.free_edges_after);
            for x in sw.splits.iter().take(10) {
                outln!("  split      edge {} at vertex {} ({:.6}, {:.6}, {:.6})", x.edge, x.vertex, x.at[0], x.at[1], x.at[2]);
            }
        }
        for x in &r.certificate.reoriented {
            let shells: Vec<String> = x.brep_shells.iter().map(|s| s.to_string()).collect();
            let what = if x.void { "void, enclosed" } else { "enclosed" };
            outln!("reoriented   shell {} ({} faces, {what} {:.6e} mm3 as written): its face senses disagree with its geometry: turned (OpenCASCADE turns it too)", shells.join(" "), x.faces, x.volume_as_written);
        }
        outln!("faces        {} ({} failed)", r.faces, r.failed_faces.len());
        outln!("triangles    {} ({} vertices)", r.triangles, r.vertices);
        outln!("watertight   {} (of the {})", r.watertight, r.watertight_of);
        print_open(&r);
        let e: Vec<String> = r.euler.iter().map(|e| format!("{}/{}", e.mesh, e.brep)).collect();
        outln!("euler        {} (mesh/B-rep per shell)", e.join(" "));
        outln!("volume mm3   {:.9} (B-rep {:.9})", r.volume, r.certificate.volume[1]);
        outln!("area mm2     {:.9} (B-rep {:.9})", r.area, r.certificate.area[1]);
        outln!("certificate  {}", if passed { "passed" } else { "FAILED (written with --force)" });
        if !passed {
            outln!("{}", pipeline::failure_message(&args.cad, &r.certificate, &r.dropped));
        }
        outln!("dropped      {}", r.dropped.len());
        for n in &r.notes {
            outln!("note         {n}");
        }
        outln!("seconds      {:.3}", r.seconds);
        outln!("wrote        {}", out.display());
    }
    Ok(())
}

/// The JSON object `fepre tessellate --json` prints for a file of tessellated geometry only.
#[derive(Debug, Serialize)]
struct TessReport<'a> {
    input: String,
    output: Option<String>,
    /// Always true here: the surface is the file's own triangles, certified as a mesh.
    tessellated: bool,
    #[serde(flatten)]
    summary: pipeline::tessellated::TessellatedSummary,
    face_table: Vec<FaceEntry>,
    units: &'a Units,
    certificate: pipeline::tessellated::MeshCertificate,
    dropped: &'a [Dropped],
    seconds: f64,
}

/// `fepre tessellate` of a file of tessellated geometry only: its triangles, certified as a
/// mesh (closed, manifold, oriented outward, no self-intersection), written when they pass.
fn run_tessellated(args: &Args, t: &crate::cad::step::Tessellated, t0: Instant) -> Result<()> {
    use pipeline::tessellated::{TessellatedSummary, certify_surface, mesh_failure_message};
    let out = &args.output;
    let certificate = certify_surface(&t.surface);
    let mut face_table = crate::cad::brep::face_table_of_names(&t.surface.face_names, t.surface.face_tags.iter().copied());
    for e in &mut face_table {
        if let Some(f) = e.face.index().and_then(|k| t.faces.get(k)) {
            e.step_id = Some(f.step_id);
            e.solid = f.solid;
        }
    }
    let passed = certificate.passed;
    let mut r = TessReport {
        input: args.cad.display().to_string(),
        output: None,
        tessellated: true,
        summary: TessellatedSummary::of(t, &t.surface),
        face_table,
        units: &t.units,
        certificate,
        dropped: &t.dropped,
        seconds: 0.0,
    };
    if !passed && !args.force {
        if args.json {
            r.seconds = t0.elapsed().as_secs_f64();
            outln!("{}", serde_json::to_string_pretty(&r)?);
        }
        anyhow::bail!("{}", mesh_failure_message(&args.cad, &r.certificate));
    }
    io::write(out, &MeshData::Surface(t.surface.clone()), &WriteOptions::default())?;
    r.output = Some(out.display().to_string());
    r.seconds = t0.elapsed().as_secs_f64();
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    let (s, c) = (&r.summary, &r.certificate);
    outln!("geometry     tessellated only (AP242): the file's triangles, certified as a mesh (--deviation and --max-edge do not apply)");
    outln!("solids       {} TESSELLATED_SOLID, {} TESSELLATED_SHELL", s.solids, s.shells);
    outln!("faces        {}", s.faces);
    outln!("triangles    {} ({} vertices)", s.triangles, s.vertices);
    outln!("watertight   {}", c.closed && c.manifold && c.oriented && c.outward);
    outln!("volume mm3   {:.9}", c.volume);
    outln!("area mm2     {:.9}", c.area);
    outln!("certificate  {}", if passed { "passed (as a mesh)" } else { "FAILED (written with --force)" });
    if !passed {
        outln!("{}", mesh_failure_message(&args.cad, c));
    }
    outln!("dropped      {}", r.dropped.len());
    outln!("seconds      {:.3}", r.seconds);
    outln!("wrote        {}", out.display());
    Ok(())
}

fn report(args: &Args, c: &Certified, output: Option<String>, t0: Instant) -> Report {
    let s = &c.tessellation.surface;
    let cert = c.certificate.clone();
    let volume: f64 = cert.shells.iter().filter(|x| x.brep_closed).map(|x| x.volume_mesh).sum();
    Report {
        input: args.cad.display().to_string(),
        output,
        solids: c.model.solids.len(),
        surface_model_shells: c.model.surface_model_shells(),
        sewing: c.model.sewing.clone(),
        faces: c.model.faces.len(),
        face_table: c.model.face_table(),
        triangles: s.triangles.len(),
        vertices: s.vertices.len(),
        watertight: cert.watertight(),
        watertight_of: if cert.shells.iter().any(|x| x.solid) { "solids" } else { "surface model" },
        open_surface: open_surface(&c.model),
        euler: cert.shells.iter().map(|x| EulerEntry { brep_shells: x.brep_shells.clone(), mesh: x.euler_mesh, brep: x.euler_brep }).collect(),
        volume,
        area: cert.area[0],
        units: c.model.units.clone(),
        deviation: args.deviation.unwrap_or(TessellateOptions::default().chord_relative),
        max_edge: args.max_edge,
        chord_mm: c.tessellation.chord,
        dropped: c.model.dropped.clone(),
        notes: c.model.notes.clone(),
        failed_faces: c.tessellation.failed.iter().map(|f| FailedFaceEntry { face: f.face, step_id: f.source, reason: f.why.clone() }).collect(),
        seconds: t0.elapsed().as_secs_f64(),
        read_seconds: c.seconds[0],
        tessellate_seconds: c.seconds[1],
        certificate: cert,
    }
}
