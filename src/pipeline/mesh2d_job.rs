//! A job file with a `[mesh2d]` section: the 2D method on the planar faces of its STEP part,
//! sized by its `[density]` (the size field lifted onto each face's plane: face sizes,
//! distances, points and boxes apply), or on the regions of its `.poly` file (`[density] size`
//! only), or on its `[[mesh2d.region]]` polygons (no `[input]` then); its `[[output]]` files are the mesh (any mesh, surface or deck extension that holds
//! a 2D mesh: .msh, .vtu, .mesh, .inp, .obj, .stl) and the report (.json).

use super::job::{JobFile, Mesh2dSection, OutputKind};
use super::mesh2d_file::{mesh2d_step, Mesh2dReport, Mesh2dRequest};
use super::mesh2d_regions::{mesh2d_poly_to, mesh2d_regions_to};
use super::part::Part;
use super::planar::FaceChoice;
use super::PipelineError;
use crate::core::{FaceId, RegionId};
use crate::io::PolyRegion;
use crate::mesh2d::domain::loop_area;
use crate::mesh2d::Domain;
use glam::DVec2;
use crate::io::atomic::write_atomic;
use crate::mesh2d::{Mesh2dOptions, Method};
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// The request a `[mesh2d]` section makes (sizes in the part's units).
fn request(jf: &JobFile, m: &Mesh2dSection, unit: f64) -> Result<Mesh2dRequest, PipelineError> {
    let method = match &m.method {
        Some(s) => s.get_ref().parse::<Method>().map_err(|e| jf.error_at(s.span().start, format!("key `method`: {e}")))?,
        None => Mesh2dOptions::default().method,
    };
    let options = Mesh2dOptions {
        method,
        quads: m.quads,
        min_angle: m.min_angle.map(|a| a.get()),
        max_area: m.max_area.map(|a| a.get() * unit * unit),
        ..Mesh2dOptions::default()
    };
    Ok(Mesh2dRequest {
        faces: if m.faces.is_empty() { FaceChoice::AllPlanar } else { FaceChoice::Faces(m.faces.iter().map(|&f| FaceId(f)).collect()) },
        size: jf.job.density.size.map(|s| s.get() * unit),
        options,
        require_min_angle: m.require_min_angle.map(|a| a.get()),
    })
}

/// The `[[mesh2d.region]]` polygons as checked domains (`unit`: 1, the job's units, as a
/// `.poly` job's), tagged by their
/// `tag` or their place in the list; an invalid polygon is named by its line.
fn regions(jf: &JobFile, m: &Mesh2dSection, unit: f64) -> Result<Vec<PolyRegion>, PipelineError> {
    let point = |p: &[f64; 2]| DVec2::new(p[0] * unit, p[1] * unit);
    let mut out = Vec::with_capacity(m.region.len());
    for (k, r) in m.region.iter().enumerate() {
        let region = r.get_ref();
        let loops: Vec<Vec<DVec2>> = std::iter::once(&region.outer).chain(&region.holes).map(|l| l.iter().map(point).collect()).collect();
        let domain = Domain::from_loops(&loops, None).map_err(|e| jf.error_at(r.span().start, format!("[[mesh2d.region]] {}: {e}", k + 1)))?;
        // a hole outside the boundary would be kept as an island of its own
        if loops.len() > 1 && domain.area() > loop_area(&loops[0]).abs() * (1.0 + 1e-9) {
            return Err(jf.error_at(r.span().start, format!("[[mesh2d.region]] {}: a hole is not inside the outer boundary", k + 1)));
        }
        out.push(PolyRegion { tag: RegionId(region.tag.unwrap_or(k as u32 + 1)), domain, max_area: None });
    }
    Ok(out)
}

/// Checks a `[mesh2d]` job of `[[mesh2d.region]]` polygons without meshing (`fepre run
/// --check`): the number of polygons, each a valid domain.
///
/// # Errors
/// A job without `[mesh2d]`, a polygon that is not a valid domain (naming its line).
pub fn check_mesh2d_regions(jf: &JobFile) -> Result<usize, PipelineError> {
    let Some(section) = &jf.job.mesh2d else {
        return Err(jf.error_at(0, "the job has no [mesh2d] section".into()));
    };
    // the polygons and the mesh are in the job's units, as a .poly's coordinates are
    Ok(regions(jf, section, 1.0)?.len())
}

/// Runs the `[mesh2d]` section of `jf` (see the module docs) and writes its outputs.
///
/// # Errors
/// A job without `[mesh2d]` or whose outputs cannot hold a 2D mesh (naming the key); a
/// `.poly` job with density entries besides `size`; what [`super::mesh2d_file`] and
/// [`super::mesh2d_poly`] return.
pub fn mesh2d_job(jf: &JobFile) -> Result<Mesh2dReport, PipelineError> {
    let job = &jf.job;
    let Some(section) = &job.mesh2d else {
        return Err(jf.error_at(0, "the job has no [mesh2d] section".into()));
    };
    let polygons = !section.region.is_empty();
    let (input, input_units) = match &job.input {
        Some(i) => (jf.resolve(i.file.get_ref()), i.units),
        None => (jf.path.clone(), None),
    };
    let poly = polygons || input.extension().is_some_and(|e| e.eq_ignore_ascii_case("poly"));
    let unit = if poly { job.units.to_mm() / input_units.unwrap_or(job.units).to_mm() } else { job.units.to_mm() };
    let request = request(jf, section, unit)?;
    let mut meshes: Vec<PathBuf> = Vec::new();
    let mut reports: Vec<PathBuf> = Vec::new();
    for o in &job.output {
        let path = jf.resolve(o.file.get_ref());
        match o.kind() {
            OutputKind::Report => reports.push(path),
            OutputKind::Mesh | OutputKind::Surface | OutputKind::Deck => {
                super::mesh2d_file::check_output(&path).map_err(|e| jf.error_at(o.file.span().start, format!("key `file`: {e}")))?;
                meshes.push(path);
            }
        }
    }
    let outs: Vec<&Path> = meshes.iter().map(PathBuf::as_path).collect();
    let report = if poly {
        let d = &job.density;
        if d.min.is_some() || d.max.is_some() || !d.face.is_empty() || !d.distance.is_empty() || !d.point.is_empty() || d.curvature.is_some() {
            return Err(jf.error_at(0, "a .poly job takes [density] size only (the other entries need a CAD part's faces)".into()));
        }
        if polygons {
            let t0 = std::time::Instant::now();
            mesh2d_regions_to(&jf.path, &regions(jf, section, unit)?, t0, &request, &outs)?
        } else {
            mesh2d_poly_to(&input, &request, &outs)?
        }
    } else {
        let part = Part::open(&input)?;
        let field = part.density_field(&job.density, &jf.selectors(), unit).map_err(|e| match e {
            PipelineError::Select { source, .. } | PipelineError::Density { source: crate::attributes::DensityError::Select(source), .. } => jf.select_error(&source),
            e => e,
        })?;
        mesh2d_step(&input, &request, Some(&field), &outs)?
    };
    for path in &reports {
        let text = serde_json::to_string_pretty(&report).map_err(|e| PipelineError::Io(crate::io::IoError::Write { path: path.clone(), source: std::io::Error::other(e) }))?;
        write_atomic(path, |w| w.write_all(text.as_bytes()).map_err(crate::io::atomic::write_err(path)))?;
    }
    Ok(report)
}
