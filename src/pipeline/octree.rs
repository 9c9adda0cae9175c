//! The octree path of a part (isosurface stuffing, [`crate::mesh3d::octree`]): its solids one
//! by one, each at the cell the size gives or, where the job gives no size, at its own cell
//! chosen to hold its volume (`crate::mesh3d::octree::resolve`).
//!
//! Stage: the pipeline's volume mesh with `method = "octree"`. Input: the part's certified
//! surface (or the surface read), the size field, the octree options, and whether to choose
//! the cell. Output: the tet mesh, the contacts between solids and the [`OctreeReport`] in
//! the [`Part`].

use super::PipelineError;
use super::part::Part;
use crate::core::{RegionId, SizeField};
use crate::mesh::{TetMesh, TriSurface};
use crate::mesh3d::mesher::{Contact, MeshReport, MeshingError, SolidInfo, assembly_contacts, merge_solids, solid_surfaces};
use crate::mesh3d::octree::{EmptySolid, OctreeError, OctreeOptions, OctreeReport, Resolve, mesh_octree, mesh_octree_resolved};
use crate::tessellate::TessellateOptions;
use std::time::Instant;

impl Part {
    /// Meshes the volume the part's surface encloses by isosurface stuffing
    /// ([`crate::mesh3d::octree`]): the winding number decides inside, so open and
    /// self-intersecting surfaces mesh too, as one region (named after the solid of a
    /// one-solid CAD part). A CAD part is tessellated to `size` first; one with several B-rep
    /// solids has each meshed on its own (its own winding number, its own region, tag and
    /// name), and the faces where solids touch are listed in [`Part::contacts`]. With
    /// `resolve`, each solid's cell shrinks from `size`'s until its mesh holds its volume
    /// (`crate::mesh3d::octree::resolve`); the tries are in the report.
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
            return Err(PipelineError::Usage { path: self.path.clone(), problem: crate::pipeline::UsageProblem::NoSurface });
        };
        let t0 = Instant::now();
        let (mesh, report, contacts, solids) = self.octree_solids(surface, size, opts, resolve)?;
        if self.model.is_some() && report.solids > 1 {
            self.contacts = contacts;
            self.solids = solids;
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

    /// Meshes the part's solids (one by one in an assembly), each at the cell `size` gives
    /// or, with `resolve`, at its own cell chosen to hold its volume.
    /// With the mesh and report: the contacts between the solids and the solids they name.
    #[allow(clippy::type_complexity)]
    fn octree_solids(&self, surface: &TriSurface, size: &dyn SizeField, opts: &OctreeOptions, resolve: Option<Resolve>) -> Result<(TetMesh, OctreeReport, Vec<Contact>, Vec<SolidInfo>), PipelineError> {
        let solids = self.surface_solids(surface);
        let octree_error = |source| PipelineError::Octree { path: self.path.clone(), source };
        let mesh_one = |one: &TriSurface| match resolve {
            Some(r) => mesh_octree_resolved(one, size, opts, r),
            None => mesh_octree(one, size, opts),
        };
        if self.model.is_some() && solids.solids.len() > 1 {
            // solids that overlap cannot share a conforming mesh, but each has its own
            // winding number: meshed one by one, the overlap said (it is in both)
            let (mut contacts, overlap) = match assembly_contacts(surface, &solids, self.gap()) {
                Ok(c) => (c, None),
                Err(e @ MeshingError::Overlap { .. }) => (Vec::new(), Some(self.meshing_error(e).to_string())),
                Err(source) => return Err(self.meshing_error(source)),
            };
            let mut meshes = Vec::with_capacity(solids.solids.len());
            let mut reports = Vec::with_capacity(solids.solids.len());
            // one solid after the other: each is meshed in parallel, and one lattice at a time
            // keeps the memory of the largest solid's
            // a solid thinner than the cell holds no lattice vertex: left out and reported
            let mut empty = Vec::new();
            let mut first_empty = None;
            for (k, one) in solid_surfaces(surface, &solids).iter().enumerate() {
                let info = &solids.solids[k];
                match mesh_one(one) {
                    Ok((m, mut r)) => {
                        for t in &mut r.cell_tries {
                            t.solid = Some(info.tag.0);
                        }
                        meshes.push(m);
                        reports.push(r);
                    }
                    Err(e @ (OctreeError::Empty(_) | OctreeError::EmptyWithin { .. })) => {
                        meshes.push(TetMesh::default());
                        empty.push(EmptySolid { solid: info.tag.0, name: info.name.clone(), volume: one.signed_volume() });
                        first_empty.get_or_insert((k, e));
                    }
                    Err(source) => {
                        return Err(octree_error(OctreeError::InSolid { solid: info.tag.0, name: info.name.clone(), source: Box::new(source) }));
                    }
                }
            }
            let mesh = merge_solids(meshes, &solids, &mut contacts);
            let Some(mut report) = OctreeReport::merged(&reports) else {
                // every solid is empty: the first one's error
                let (k, e) = first_empty.ok_or_else(|| PipelineError::Usage { path: self.path.clone(), problem: crate::pipeline::UsageProblem::NoSolid })?;
                let info = &solids.solids[k];
                return Err(octree_error(OctreeError::InSolid { solid: info.tag.0, name: info.name.clone(), source: Box::new(e) }));
            };
            report.solids = solids.solids.len();
            report.input_volume += empty.iter().map(|e| e.volume).sum::<f64>();
            report.empty_solids = empty;
            report.overlap = overlap;
            Ok((mesh, report, contacts, solids.solids))
        } else {
            // a closed surface whose triangles face inward (a negative volume) has winding
            // number −1 inside: meshed turned outward, and said (an open one's volume has no
            // sign to go by)
            let outward;
            let turned = surface.signed_volume() < 0.0 && crate::mesh3d::octree::is_cycle(surface);
            let surface = if turned {
                outward = turned_outward(surface);
                &outward
            } else {
                surface
            };
            let (mut mesh, mut report) = mesh_one(surface).map_err(octree_error)?;
            report.turned_outward = turned;
            if let [solid] = &solids.solids[..] {
                if let Some(name) = &solid.name {
                    mesh.region_names.insert(RegionId(1), name.clone());
                }
            }
            Ok((mesh, report, Vec::new(), Vec::new()))
        }
    }
}

/// `s` with every triangle turned the other way.
fn turned_outward(s: &TriSurface) -> TriSurface {
    let mut t = s.clone();
    for tri in &mut t.triangles {
        tri.swap(1, 2);
    }
    t
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_surface_turned_outward_has_the_opposite_volume() {
        let s = crate::mesh::shapes::plate_with_hole(8, 2.0, 0.5, 0.4);
        let t = super::turned_outward(&s);
        assert!(s.signed_volume() > 0.0 && (t.signed_volume() + s.signed_volume()).abs() < 1e-12);
        assert_eq!(super::turned_outward(&t).triangles, s.triangles);
    }
}
