//! `fepre convert` as a library call: a mesh file read and written in another format, tags
//! kept where the output format can hold them; a tet mesh written to a surface format gives
//! its boundary, and what could not be written is said in the notes.

use super::PipelineError;
use super::warning::Warning;
use crate::core::Tolerance;
use crate::io::{self, Format, MeshData, ReadOptions, WriteOptions};
use serde::Serialize;
use std::path::Path;

/// How [`convert_file`] reads and writes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConvertOptions {
    /// Merge vertices closer than this (`None`: keep the file's vertices as they are).
    pub weld: Option<Tolerance>,
    /// Write text where the format also has a binary form (STL, VTU).
    pub ascii: bool,
}

impl Default for ConvertOptions {
    fn default() -> ConvertOptions {
        ConvertOptions { weld: Some(Tolerance::WELD), ascii: false }
    }
}

/// What [`convert_file`] wrote: the JSON object `fepre convert --json` prints.
#[derive(Clone, Debug, Serialize)]
pub struct ConvertReport {
    /// The input file.
    pub input: String,
    /// The file written.
    pub output: String,
    /// Its format.
    pub format: &'static str,
    /// What it holds (surface, tet mesh, point set).
    pub kind: &'static str,
    /// Vertices written.
    pub vertices: usize,
    /// Triangles (a tet mesh's boundary triangles).
    pub triangles: usize,
    /// Tets written.
    pub tets: usize,
    /// Tags written (face tags of a surface, region tags of a tet mesh).
    pub tags: usize,
    /// What was odd about the input, and what could not be written.
    pub notes: Vec<String>,
    /// What the run made but would rather not have (none so far: the notes say what was left
    /// out).
    pub warnings: Vec<Warning>,
}

/// Reads the mesh file at `input` and writes it to `output` (its extension picks the format).
///
/// # Errors
/// [`PipelineError::Usage`] for an output extension fepre does not write (before anything is
/// read); an unreadable input, a failed write.
pub fn convert_file(input: &Path, output: &Path, options: &ConvertOptions) -> Result<ConvertReport, PipelineError> {
    let out_format = Format::from_path(output).filter(|f| f.can_write()).ok_or_else(|| PipelineError::Usage {
        path: output.to_path_buf(),
        problem: super::UsageProblem::ConvertFormat,
    })?;
    let mut loaded = io::read(input, &ReadOptions::default().with_weld(options.weld))?;
    let surface_only = matches!(out_format, Format::Stl | Format::Obj | Format::Off);
    if let (MeshData::Volume(m), true) = (&loaded.mesh, surface_only) {
        loaded.notes.push(format!("wrote the boundary surface of the tetrahedral mesh ({} tets are not representable in {})", m.tets.len(), out_format.name()));
        let mut s = m.boundary_surface();
        s.remove_unused_vertices();
        loaded.mesh = MeshData::Surface(s);
    }
    io::write(output, &loaded.mesh, &WriteOptions::default().with_ascii(options.ascii))?;
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
    let tagless = matches!(out_format, Format::Off) || (out_format == Format::Stl && !options.ascii);
    if tagless && tags > 1 {
        loaded.notes.push(format!("{} holds no tags: {tags} tags were not written (use --ascii for STL solids, or .obj, .msh, .mesh, .vtu)", out_format.name()));
        tags = 0;
    }
    Ok(ConvertReport {
        input: input.display().to_string(),
        output: output.display().to_string(),
        format: out_format.name(),
        kind: loaded.mesh.kind(),
        vertices,
        triangles,
        tets,
        tags,
        notes: loaded.notes,
        warnings: Vec::new(),
    })
}
