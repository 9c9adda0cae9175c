//! `fepre convert IN OUT`: any format fepre reads to any it writes, tags kept.

use crate::cli::progress::Progress;
use crate::cli::usage_error;
use crate::core::Tolerance;
use crate::io::{self, Format, MeshData, ReadOptions, WriteOptions};
use anyhow::Result;
use serde::Serialize;
use std::path::PathBuf;

/// Examples shown by `fepre convert --help`.
pub const EXAMPLES: &str = "\
Examples:
  fepre convert part.stl part.obj              STL soup to welded OBJ
  fepre convert model.glb model.msh            glTF scene (instances expanded) to Gmsh MSH 4.1, one physical group per primitive
  fepre convert mesh.1.ele mesh.vtu            TetGen tet mesh to ParaView, region and face tags as cell data
  fepre convert mesh.msh boundary.stl --ascii  a tet mesh's boundary as ASCII STL, one solid per face tag";

/// Arguments of `fepre convert`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Input mesh file (.stl .obj .gltf .glb .off .mesh .node .ele .face .poly .smesh .msh .xyz).
    pub input: PathBuf,
    /// Output file; its extension picks the format (.stl .obj .off .mesh .node .ele .face .poly .smesh .msh .vtu).
    pub output: PathBuf,
    /// Write text where the format also has a binary form (STL, VTU).
    #[arg(long)]
    pub ascii: bool,
    /// Keep the file's vertices as they are instead of merging coincident ones.
    #[arg(long)]
    pub no_weld: bool,
    /// Merge vertices closer than REL times the bounding-box diagonal.
    #[arg(long, value_name = "REL", default_value_t = Tolerance::WELD.relative, value_parser = crate::cli::parse_fraction)]
    pub weld: f64,
    /// Print a JSON summary of what was written on standard output.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Summary<'a> {
    input: String,
    output: String,
    format: &'a str,
    kind: &'a str,
    vertices: usize,
    triangles: usize,
    tets: usize,
    tags: usize,
    notes: Vec<String>,
}

/// Runs `fepre convert`.
///
/// # Errors
/// Unreadable input or failed output (exit 1); an output extension fepre does not write
/// (bad usage, exit 2).
pub fn run(args: &Args) -> Result<()> {
    let out_format = Format::from_path(&args.output).filter(|f| f.can_write()).ok_or_else(|| {
        usage_error(format!(
            "{}: fepre cannot write this extension; use one of .stl .obj .off .mesh .node .ele .face .poly .smesh .msh .vtu",
            args.output.display()
        ))
    })?;
    let progress = Progress::start(&format!("reading {}", args.input.display()));
    let weld = if args.no_weld { None } else { Some(Tolerance::relative(args.weld)) };
    let mut loaded = io::read(&args.input, &ReadOptions::default().with_weld(weld))?;
    let surface_only = matches!(out_format, Format::Stl | Format::Obj | Format::Off);
    if let (MeshData::Volume(m), true) = (&loaded.mesh, surface_only) {
        loaded.notes.push(format!("wrote the boundary surface of the tetrahedral mesh ({} tets are not representable in {})", m.tets.len(), out_format.name()));
        let mut s = m.boundary_surface();
        s.remove_unused_vertices();
        loaded.mesh = MeshData::Surface(s);
    }
    progress.stage(&format!("writing {}", args.output.display()));
    io::write(&args.output, &loaded.mesh, &WriteOptions::default().with_ascii(args.ascii))?;
    progress.finish();
    let (vertices, triangles, tets, mut tags) = match &loaded.mesh {
        MeshData::Surface(s) => (s.vertices.len(), s.triangles.len(), 0, s.tags().len()),
        MeshData::Volume(m) => {
            let mut t: Vec<_> = m.region_tags.clone();
            t.sort_unstable();
            t.dedup();
            (m.vertices.len(), m.boundary.len(), m.tets.len(), t.len())
        }
        MeshData::Points(p) => (p.len(), 0, 0, 0),
    };
    let tagless = matches!(out_format, Format::Off) || (out_format == Format::Stl && !args.ascii);
    if tagless && tags > 1 {
        loaded.notes.push(format!("{} holds no tags: {tags} tags were not written (use --ascii for STL solids, or .obj, .msh, .mesh, .vtu)", out_format.name()));
        tags = 0;
    }
    let summary = Summary {
        input: args.input.display().to_string(),
        output: args.output.display().to_string(),
        format: out_format.name(),
        kind: loaded.mesh.kind(),
        vertices,
        triangles,
        tets,
        tags,
        notes: loaded.notes,
    };
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        for n in &summary.notes {
            eprintln!("note: {n}");
        }
        let elements = if tets > 0 { format!("{tets} tets, {triangles} boundary triangles") } else { format!("{triangles} triangles") };
        outln!("wrote {} ({}): {} vertices, {}, {} tags", summary.output, summary.format, vertices, elements, tags);
    }
    Ok(())
}
