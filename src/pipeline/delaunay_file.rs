//! `fepre delaunay POINTS [-o OUT]` as a library call: the Delaunay tetrahedralization of a
//! point set read from a file, on a pool of the threads asked for; without an output file the
//! tets are only counted (as `tetgen -NEF` and CGAL's driver do), with one they are built in
//! their canonical order and written. The tets are the same for any number of threads.

use super::{PipelineError, UsageProblem};
use crate::io::{self, Format, MeshData, WriteOptions};
use crate::mesh3d::delaunay::{DelaunayOptions, DelaunayTimings, KernelKind, count_tetrahedra, tetrahedralize};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// How many coincident point pairs a report names (all are counted).
pub const LISTED_DUPLICATES: usize = 10;

/// What [`delaunay_file`] did.
#[derive(Clone, Debug, Serialize)]
#[non_exhaustive]
pub struct DelaunayFileReport {
    /// Points read.
    pub points: usize,
    /// Tets of the tetrahedralization.
    pub tets: usize,
    /// Points that coincide with an earlier one (left out).
    pub duplicates: usize,
    /// The first [`LISTED_DUPLICATES`] such pairs: `[point, the earlier point]`.
    #[serde(skip)]
    pub first_duplicates: Vec<[u32; 2]>,
    /// The predicate kernel the points called for.
    pub kernel: KernelKind,
    /// Worker threads.
    pub threads: usize,
    /// Time of the tetrahedralization (ordering, insertion and, when the tets are written,
    /// their canonical ordering), seconds.
    pub seconds: f64,
    /// Time reading the points, seconds.
    pub read_seconds: f64,
    /// The file written.
    pub output: Option<String>,
    /// Time by stage.
    pub timings: DelaunayTimings,
}

/// Tetrahedralizes the points of `input` (`.xyz` or a TetGen `.node`) on `threads` worker
/// threads (`None`: all cores) and writes the tets to `output` (its extension picks the
/// format: `.mesh`, `.ele`/`.node`, `.vtu`, `.msh`); `stage` hears what is being done.
///
/// # Errors
/// [`PipelineError::Usage`] for an output extension that cannot hold tets or worker threads
/// that cannot start; unreadable points; [`PipelineError::Delaunay`] for a point set that spans
/// no tetrahedron; a failed write.
pub fn delaunay_file(input: &Path, output: Option<&Path>, threads: Option<usize>, stage: &(dyn Fn(&str) + Sync)) -> Result<DelaunayFileReport, PipelineError> {
    if let Some(out) = output {
        if !matches!(Format::from_path(out), Some(Format::Medit | Format::TetGen | Format::Vtu | Format::Msh)) {
            return Err(PipelineError::Usage { path: out.to_path_buf(), problem: UsageProblem::TetFormat });
        }
    }
    let threads = threads.unwrap_or_else(rayon::current_num_threads);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| PipelineError::Usage { path: input.to_path_buf(), problem: UsageProblem::Threads { why: e.to_string() } })?;
    pool.install(|| in_pool(input, output, threads, stage))
}

fn in_pool(input: &Path, output: Option<&Path>, threads: usize, stage: &(dyn Fn(&str) + Sync)) -> Result<DelaunayFileReport, PipelineError> {
    let t0 = Instant::now();
    let points = io::read_points(input)?;
    let read_seconds = t0.elapsed().as_secs_f64();
    stage(&format!("tetrahedralizing {} points", points.len()));
    let t1 = Instant::now();
    let build = if output.is_some() { tetrahedralize } else { count_tetrahedra };
    let d = build(&points, &DelaunayOptions::default()).map_err(|source| PipelineError::Delaunay { path: input.to_path_buf(), source })?;
    let seconds = t1.elapsed().as_secs_f64();
    if let Some(out) = output {
        stage(&format!("writing {}", out.display()));
        io::write(out, &MeshData::Volume(d.to_tet_mesh(&points)), &WriteOptions::default())?;
    }
    Ok(DelaunayFileReport {
        points: points.len(),
        tets: d.count,
        duplicates: d.duplicates.len(),
        first_duplicates: d.duplicates.iter().take(LISTED_DUPLICATES).copied().collect(),
        kernel: d.kernel,
        threads,
        seconds,
        read_seconds,
        output: output.map(|p| p.display().to_string()),
        timings: d.timings.clone(),
    })
}
