//! `fepre convert IN OUT`: any format fepre reads to any it writes, tags kept.

use crate::cli::progress::Progress;
use crate::cli::usage_error;
use fepre::core::Tolerance;
use fepre::pipeline::PipelineError;
use fepre::pipeline::{ConvertOptions, convert_file};
use anyhow::Result;
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

/// Runs `fepre convert`.
///
/// # Errors
/// Unreadable input or failed output (exit 1); an output extension fepre does not write
/// (bad usage, exit 2).
pub fn run(args: &Args) -> Result<()> {
    let progress = Progress::start(&format!("converting {} to {}", args.input.display(), args.output.display()));
    let options = ConvertOptions { weld: if args.no_weld { None } else { Some(Tolerance::relative(args.weld)) }, ascii: args.ascii };
    let summary = convert_file(&args.input, &args.output, &options).map_err(|e| match e {
        PipelineError::Usage { .. } => usage_error(e.to_string()),
        e => anyhow::Error::new(e),
    })?;
    progress.finish();
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        for n in &summary.notes {
            eprintln!("note: {n}");
        }
        let (tets, triangles) = (summary.tets, summary.triangles);
        let elements = if tets > 0 { format!("{tets} tets, {triangles} boundary triangles") } else { format!("{triangles} triangles") };
        outln!("wrote {} ({}): {} vertices, {}, {} tags", summary.output, summary.format, summary.vertices, elements, summary.tags);
    }
    crate::cli::print_warnings(&summary.warnings);
    Ok(())
}
