//! The octree path of a part (isosurface stuffing, [`crate::mesh3d::octree`]): its solids one
//! by one, and, where the job gives no size, a cell fine enough to hold the part's volume.
//!
//! Stage: the pipeline's volume mesh with `method = "octree"`. Input: the part's certified
//! surface (or the surface read), the size field, the octree options, and whether to choose
//! the cell ([`Resolve`]). Output: the tet mesh and [`OctreeReport`] in the [`Part`].
//!
//! Why a chosen cell: isosurface stuffing keeps one cell everywhere, and a wall thinner than
//! the cell holds no lattice vertex, so it is lost. At the mesh path's default size (the
//! diagonal over 25) the corpus' crankshaft lost 30 % of its volume, a cylinder head 10 %,
//! and three parts held no lattice vertex at all. So, where no size is given, the cell starts
//! at the default size and shrinks by √2 until every solid holds lattice vertices and every
//! solid whose input volume is exact ([`OctreeReport::input_volume_exact`]) is within
//! [`Resolve::volume_error`] of it; or until the next try would build more than
//! [`Resolve::max_lattice_vertices`] lattice vertices: then the last mesh is kept, and the
//! report's tries show how far it got. Counts, never clocks: the same cells on any machine.
//! A size given (`--size`, `[density] size`) is kept as it is.

use super::assembly::{contact_reports, gap_of, solids_of};
use super::PipelineError;
use super::part::Part;
use crate::core::{RegionId, SizeField};
use crate::mesh::{TetMesh, TriSurface};
use crate::mesh3d::mesher::{MeshReport, assembly_contacts, merge_solids, solid_surfaces};
use crate::mesh3d::octree::{CellTry, EmptySolid, Lattice, OctreeError, OctreeOptions, OctreeReport, cell_size, mesh_octree};
use crate::tessellate::TessellateOptions;
use glam::DVec3;
use std::time::Instant;

/// How the default cell is chosen; see the module docs.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Resolve {
    /// The largest relative volume error of a solid accepted.
    pub volume_error: f64,
    /// The most lattice vertices (all solids together) a try may build.
    pub max_lattice_vertices: u64,
}

/// The default: within 1 % of every solid's volume, at most 2^23 lattice vertices (about
/// 25 million tets where the part fills its box; 1.6 GB).
pub const RESOLVE: Resolve = Resolve { volume_error: 0.01, max_lattice_vertices: 1 << 23 };

impl Resolve {
    /// Whether a try's mesh is accepted: no solid empty, every exact volume within bounds.
    pub fn holds(&self, t: &CellTry) -> bool {
        t.empty_solids == 0 && t.volume_error.is_none_or(|e| e <= self.volume_error)
    }
}

/// Each try's cell is the last one's over this.
const STEP: f64 = std::f64::consts::SQRT_2;

/// A size field no coarser than `cap`.
struct Capped<'a> {
    inner: &'a dyn SizeField,
    cap: f64,
}

impl SizeField for Capped<'_> {
    fn size_at(&self, p: DVec3) -> f64 {
        self.inner.size_at(p).min(self.cap)
    }

    fn size_in(&self, p: DVec3, region: RegionId) -> f64 {
        self.inner.size_in(p, region).min(self.cap)
    }
}

/// One try's result: the merged mesh and report, and whether it holds the volume.
struct Try {
    mesh: TetMesh,
    report: OctreeReport,
    contacts: Vec<super::assembly::ContactReport>,
    cell: CellTry,
}

impl Part {
    /// Meshes the volume the part's surface encloses by isosurface stuffing
    /// ([`crate::mesh3d::octree`]): the winding number decides inside, so open and
    /// self-intersecting surfaces mesh too, as one region (named after the solid of a
    /// one-solid CAD part). A CAD part is tessellated to `size` first; one with several B-rep
    /// solids has each meshed on its own (its own winding number, its own region, tag and
    /// name), and the faces where solids touch are listed in [`Part::contacts`]. With
    /// `resolve`, the cell shrinks from `size`'s until the mesh holds the volume (module
    /// docs); the tries are in the report.
    ///
    /// # Errors
    /// A failed certificate; [`PipelineError::Octree`] (a size too fine for the box, nothing
    /// inside, a tet the warping turned over; in an assembly, naming the solid); solids of an
    /// assembly that overlap or cross themselves, as [`Part::mesh`] says.
    pub fn mesh_octree(&mut self, size: &dyn SizeField, tess: &TessellateOptions, opts: &OctreeOptions, resolve: Option<Resolve>) -> Result<&TetMesh, PipelineError> {
        if self.is_cad() && self.certified.is_none() {
            self.tessellate(size, tess)?;
        }
        let Some(surface) = &self.surface else {
            return Err(PipelineError::Usage { path: self.path.clone(), message: "no surface to mesh".into() });
        };
        let t0 = Instant::now();
        let (mesh, report, contacts) = match resolve {
            None => {
                let t = self.octree_try(surface, size, opts)?;
                (t.mesh, t.report, t.contacts)
            }
            Some(r) => self.octree_resolved(surface, size, opts, r)?,
        };
        if self.model.is_some() && report.solids > 1 {
            self.contacts = contacts;
        }
        self.seconds.mesh = t0.elapsed().as_secs_f64();
        self.mesh_report = Some(MeshReport {
            nodes: mesh.vertices.len(),
            tets: mesh.tets.len(),
            regions: report.solids,
            stage_seconds: report.stage_seconds.clone(),
            seconds: self.seconds.mesh,
            ..MeshReport::default()
        });
        self.octree_report = Some(report);
        Ok(self.mesh.insert(mesh))
    }

    /// Tries cells from `size`'s down by [`STEP`] until the volume holds or the budget ends;
    /// see the module docs.
    fn octree_resolved(&self, surface: &TriSurface, size: &dyn SizeField, opts: &OctreeOptions, r: Resolve) -> Result<(TetMesh, OctreeReport, Vec<super::assembly::ContactReport>), PipelineError> {
        let solids = solids_of(self, surface);
        let boxes: Vec<_> = if self.model.is_some() && solids.solids.len() > 1 { solid_surfaces(surface, &solids).iter().map(TriSurface::bbox).collect() } else { vec![surface.bbox()] };
        let lattice_vertices = |h: f64| -> Option<u64> { boxes.iter().map(|b| Lattice::covering(b, h).ok().map(|l| l.num_vertices() as u64)).sum() };
        let mut h = cell_size(surface, size);
        let mut tries: Vec<CellTry> = Vec::new();
        loop {
            let capped = Capped { inner: size, cap: h };
            let t = self.octree_try(surface, &capped, opts);
            let next = h / STEP;
            let room = lattice_vertices(next).is_some_and(|n| n <= r.max_lattice_vertices);
            match t {
                Ok(mut t) => {
                    tries.push(t.cell.clone());
                    if r.holds(&t.cell) || !room {
                        t.report.cell_tries = tries;
                        return Ok((t.mesh, t.report, t.contacts));
                    }
                }
                // nothing inside at this cell: a finer one, while there is room
                Err(PipelineError::Octree { source, .. }) if room && is_empty(&source) => {
                    tries.push(CellTry { cell: h, lattice_vertices: lattice_vertices(h).unwrap_or(0) as usize, volume_error: None, empty_solids: solids.solids.len().max(1) });
                }
                Err(e) => return Err(e),
            }
            h = next;
        }
    }

    /// Meshes the part's solids (one by one in an assembly) at the cell `size` gives.
    fn octree_try(&self, surface: &TriSurface, size: &dyn SizeField, opts: &OctreeOptions) -> Result<Try, PipelineError> {
        let solids = solids_of(self, surface);
        let octree_error = |source| PipelineError::Octree { path: self.path.clone(), source };
        if self.model.is_some() && solids.solids.len() > 1 {
            let mut contacts = assembly_contacts(surface, &solids, gap_of(self)).map_err(|source| self.meshing_error(source))?;
            let mut meshes = Vec::with_capacity(solids.solids.len());
            let mut reports = Vec::with_capacity(solids.solids.len());
            // one solid after the other: each is meshed in parallel, and one lattice at a time
            // keeps the memory of the largest solid's
            // a solid thinner than the cell holds no lattice vertex: left out and reported
            let mut empty = Vec::new();
            let mut first_empty = None;
            for (k, one) in solid_surfaces(surface, &solids).iter().enumerate() {
                let info = &solids.solids[k];
                match mesh_octree(one, size, opts) {
                    Ok((m, r)) => {
                        meshes.push(m);
                        reports.push(r);
                    }
                    Err(e @ OctreeError::Empty(_)) => {
                        meshes.push(TetMesh::default());
                        empty.push(EmptySolid { solid: info.tag.0, name: info.name.clone(), volume: one.signed_volume() });
                        first_empty.get_or_insert((k, e));
                    }
                    Err(source) => {
                        return Err(octree_error(OctreeError::InSolid { solid: info.tag.0, name: info.name.clone(), source: Box::new(source) }));
                    }
                }
            }
            let cell = CellTry {
                cell: reports.iter().map(|r| r.cell_size).fold(f64::INFINITY, f64::min),
                lattice_vertices: reports.iter().map(|r| r.lattice_vertices).sum(),
                volume_error: worst_volume_error(&reports),
                empty_solids: empty.len(),
            };
            let mesh = merge_solids(meshes, &solids, &mut contacts);
            let contacts = contact_reports(&contacts, &self.face_table(), &solids);
            let Some(mut report) = OctreeReport::merged(&reports) else {
                // every solid is empty: the first one's error
                let (k, e) = first_empty.ok_or_else(|| PipelineError::Usage { path: self.path.clone(), message: "no solid to mesh".into() })?;
                let info = &solids.solids[k];
                return Err(octree_error(OctreeError::InSolid { solid: info.tag.0, name: info.name.clone(), source: Box::new(e) }));
            };
            report.solids = solids.solids.len();
            report.input_volume += empty.iter().map(|e| e.volume).sum::<f64>();
            report.empty_solids = empty;
            Ok(Try { mesh, report, contacts, cell })
        } else {
            let (mut mesh, report) = mesh_octree(surface, size, opts).map_err(octree_error)?;
            if let [solid] = &solids.solids[..] {
                if let Some(name) = &solid.name {
                    mesh.region_names.insert(RegionId(1), name.clone());
                }
            }
            let cell = CellTry { cell: report.cell_size, lattice_vertices: report.lattice_vertices, volume_error: worst_volume_error(std::slice::from_ref(&report)), empty_solids: 0 };
            Ok(Try { mesh, report, contacts: Vec::new(), cell })
        }
    }
}

/// The largest relative volume error among the reports whose input volume is exact.
fn worst_volume_error(reports: &[OctreeReport]) -> Option<f64> {
    reports
        .iter()
        .filter(|r| r.input_volume_exact && r.input_volume > 0.0)
        .map(|r| (r.volume / r.input_volume - 1.0).abs())
        .fold(None, |a, e| Some(a.map_or(e, |a: f64| a.max(e))))
}

/// Whether the error is "no lattice vertex inside" (of the part or of its only solids).
fn is_empty(e: &OctreeError) -> bool {
    match e {
        OctreeError::Empty(_) => true,
        OctreeError::InSolid { source, .. } => is_empty(source),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3d::octree::OctreeReport;

    fn report(volume: f64, input: f64, exact: bool) -> OctreeReport {
        OctreeReport { volume, input_volume: input, input_volume_exact: exact, ..OctreeReport::default() }
    }

    #[test]
    fn the_worst_volume_error_counts_exact_inputs_only() {
        assert_eq!(worst_volume_error(&[]), None);
        assert_eq!(worst_volume_error(&[report(0.5, 1.0, false)]), None);
        let e = worst_volume_error(&[report(0.98, 1.0, true), report(2.1, 2.0, true), report(0.1, 1.0, false)]).unwrap();
        assert!((e - 0.05).abs() < 1e-12, "{e}");
    }

    #[test]
    fn a_capped_field_is_never_coarser_than_its_cap() {
        let inner = crate::core::size_field::UniformSize(2.0);
        let c = Capped { inner: &inner, cap: 0.5 };
        assert_eq!(c.size_at(DVec3::ZERO), 0.5);
        assert_eq!(c.size_in(DVec3::ONE, RegionId(3)), 0.5);
        let c = Capped { inner: &inner, cap: 5.0 };
        assert_eq!(c.size_at(DVec3::ZERO), 2.0);
    }

    #[test]
    fn emptiness_is_seen_through_a_solid() {
        assert!(is_empty(&OctreeError::Empty(1.0)));
        assert!(is_empty(&OctreeError::InSolid { solid: 2, name: None, source: Box::new(OctreeError::Empty(1.0)) }));
        assert!(!is_empty(&OctreeError::Internal("x".into())));
    }
}
