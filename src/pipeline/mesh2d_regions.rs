//! `fepre mesh2d REGIONS.poly`: a 2D method on every region of a Triangle `.poly` file
//! (holes removed, regions split by their segments and tagged by their attributes), the
//! meshes written as one tagged mesh at z = 0, and the report of [`super::mesh2d_file`].
//!
//! Regions that share a segment get the same points on it: the segments are divided by the
//! size first ([`crate::mesh2d::boundary`]), the same points from either side. A lone region
//! lets Delaunay refinement split its segments itself (Ruppert's method, as Triangle does).

use super::PipelineError;
use super::mesh2d_file::{angle_warnings, check_min_angle, concatenate, face_report, write_faces, FaceReport, Mesh2dReport, Mesh2dRequest};
use crate::core::FaceId;
use crate::io::{read_poly, PolyRegion};
use crate::mesh::MixedSurface;
use crate::mesh2d::measure::measure;
use crate::mesh2d::{mesh_domain, Boundary, Mesh2dOptions};
use glam::DVec2;
use std::path::Path;
use std::time::Instant;

/// The size of an equilateral triangle of area `a`.
fn size_of_area(a: f64) -> f64 {
    (4.0 * a / 3f64.sqrt()).sqrt()
}

/// Meshes every region of the `.poly` file `poly` by the request's method at its size (`None`:
/// from `--max-area` where given, else the regions' diagonal over 25) and writes them to
/// `output` where given (.msh, .vtu, .mesh, .inp, .obj, .stl).
///
/// # Errors
/// [`PipelineError::Usage`] for an output format that cannot hold the mesh (before anything is
/// read); an unreadable or invalid `.poly` (naming the line, vertex, segment or seed); a
/// region the method cannot mesh (naming it); an angle under the one required (nothing
/// written); a failed write.
pub fn mesh2d_poly(poly: &Path, request: &Mesh2dRequest, output: Option<&Path>) -> Result<Mesh2dReport, PipelineError> {
    mesh2d_poly_to(poly, request, output.as_slice())
}

/// [`mesh2d_poly`] with any number of outputs.
pub(crate) fn mesh2d_poly_to(poly: &Path, request: &Mesh2dRequest, outputs: &[&Path]) -> Result<Mesh2dReport, PipelineError> {
    for out in outputs {
        super::mesh2d_file::check_output(out)?;
    }
    let t0 = Instant::now();
    let file = read_poly(poly)?;
    let regions = file.to_regions().map_err(|source| PipelineError::PolyRegions { path: poly.to_path_buf(), source })?;
    mesh2d_regions_to(poly, &regions, t0, request, outputs)
}

/// Meshes `regions` (read from `source` at `t0`, which names them in messages) as
/// [`mesh2d_poly`] does.
pub(crate) fn mesh2d_regions_to(poly: &Path, regions: &[PolyRegion], t0: Instant, request: &Mesh2dRequest, outputs: &[&Path]) -> Result<Mesh2dReport, PipelineError> {
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for p in regions.iter().flat_map(|r| &r.domain.points) {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let size = request.size.or(request.options.max_area.map(size_of_area)).unwrap_or_else(|| (hi - lo).length() / 25.0);
    let t1 = Instant::now();
    let lone = regions.len() == 1;
    let mut meshes = Vec::with_capacity(regions.len());
    let mut per_face: Vec<FaceReport> = Vec::with_capacity(regions.len());
    for r in regions {
        let t = Instant::now();
        let options = Mesh2dOptions {
            region: r.tag,
            boundary: if lone { Boundary::Free } else { Boundary::Split },
            // only a max area asked (Triangle's -a): the size is not a bound of Delaunay's
            use_size: request.size.is_some() || request.options.max_area.is_none(),
            max_area: match (request.options.max_area, r.max_area) {
                (Some(a), Some(b)) => Some(a.min(b)),
                (a, b) => a.or(b),
            },
            ..request.options.clone()
        };
        let m = mesh_domain(&r.domain, &|_| size, &options).map_err(|e| PipelineError::Region2d { path: poly.to_path_buf(), region: r.tag.0, source: e })?;
        per_face.push(face_report(FaceId(r.tag.0), None, r.domain.segments.len(), &m.mesh, &m.stats, &|_| size, t.elapsed().as_secs_f64()));
        meshes.push(m.mesh);
    }
    // one mesh: regions side by side, the points they share merged (the same coordinates)
    // (a lone region is its own whole: no copy, no merge, measured once)
    let all = if lone { meshes.pop().unwrap_or_default() } else { concatenate(meshes.iter()) };
    let merged_owned;
    let merged = if lone {
        &all
    } else {
        merged_owned = merge_equal_points(&all);
        &merged_owned
    };
    let quality = match per_face.first() {
        Some(f) if lone => f.quality.clone(),
        _ => measure(&all, &|_| size),
    };
    check_min_angle(poly, request.require_min_angle, &quality, &per_face)?;
    let t2 = Instant::now();
    let surface = MixedSurface::from_planar(merged);
    for out in outputs {
        write_faces(out, &surface, &format!("{}: regions meshed by fepre mesh2d --method {}", poly.display(), request.options.method))?;
    }
    let write = t2.elapsed().as_secs_f64();
    Ok(Mesh2dReport {
        input: poly.display().to_string(),
        output: outputs.first().map(|o| o.display().to_string()),
        method: request.options.method,
        all_quads: request.options.quads,
        size,
        faces: regions.len(),
        planar_faces: regions.len(),
        meshed: regions.len(),
        failed: Vec::new(),
        vertices: surface.vertices.len(),
        triangles: surface.triangles.len(),
        quads: surface.quads.len(),
        quality,
        seconds: [(t1 - t0).as_secs_f64(), (t2 - t1).as_secs_f64(), write],
        warnings: angle_warnings(&request.options, &per_face, "region"),
        per_face,
        total_seconds: t0.elapsed().as_secs_f64(),
    })
}

/// `m` with vertices of equal coordinates merged (the first kept), elements renumbered.
fn merge_equal_points(m: &crate::mesh::PlanarMesh) -> crate::mesh::PlanarMesh {
    let mut first: std::collections::BTreeMap<[u64; 2], u32> = std::collections::BTreeMap::new();
    let mut vertices = Vec::with_capacity(m.vertices.len());
    let map: Vec<u32> = m
        .vertices
        .iter()
        .map(|p| {
            *first.entry([p.x.to_bits(), p.y.to_bits()]).or_insert_with(|| {
                vertices.push(*p);
                (vertices.len() - 1) as u32
            })
        })
        .collect();
    crate::mesh::PlanarMesh {
        vertices,
        triangles: m.triangles.iter().map(|t| t.map(|i| map[i as usize])).collect(),
        triangle_tags: m.triangle_tags.clone(),
        quads: m.quads.iter().map(|q| q.map(|i| map[i as usize])).collect(),
        quad_tags: m.quad_tags.clone(),
        region_names: m.region_names.clone(),
    }
}
