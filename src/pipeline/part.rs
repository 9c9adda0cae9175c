//! A part going through the pipeline: what was read (a B-rep or a tagged surface), its face
//! catalogue, the certified tessellation, the tet mesh, and every stage's report.

use super::{PipelineError, UsageProblem};
use super::default_size::default_size;
use super::job::Method;
use crate::attributes::density::RegionSizes;
use crate::attributes::{Density, DensityField, FaceCatalogue, Groups, Selector};
use crate::cad::brep::{Dropped, FaceEntry, Model, face_table_of_names};
use crate::cad::step;
use crate::core::{BoundaryGeometry, RegionId, SizeField};
use crate::fe::BrepGeometry;
use crate::io::{self, Format, MeshData, MeshRef, ReadOptions, WriteOptions};
use crate::mesh::{TetMesh, TriSurface};
use crate::mesh3d::mesher::{Abandon, Contact, MeshOptions, MeshReport, MeshingError, RegionSeed, Seeds, SolidInfo, Solids, mesh_solids_on, mesh_surface_on};
use super::assembly::{ContactReport, GAP_CHORDS, contact_reports, gap_of, solids_of, step_id};
use crate::tessellate::certificate::{Certificate, CertifyOptions, certify};
use crate::tessellate::{TessellateOptions, Tessellation, tessellate, tessellate_sized};
use crate::tessellate::orient::{turn_inside_out_shells, turn_misoriented_faces};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::Instant;

/// The largest chord deviation (a fraction of the diagonal) of the tessellation a CAD part is
/// meshed from, where the job gives none: the size governs, this bounds how far the boundary
/// leaves the CAD surface where the size is coarse for a curved face. See
/// [`Part::mesh_deviation`].
pub const MESH_DEVIATION: f64 = 1e-3;

/// The smallest default chord deviation, a fraction of the diagonal (the tessellator's own
/// default).
pub const MESH_DEVIATION_MIN: f64 = 2e-4;

/// The volume error the default deviation allows, a fraction of the part's volume.
pub const MESH_VOLUME_ERROR: f64 = 2e-3;

/// The largest turn of an edge's tangent along one segment, degrees, in a tessellation to a
/// size: at least 8 segments on a full circle, as Gmsh puts at least 7 (`MinimumCirclePoints`).
pub const MESH_MAX_ANGLE_DEG: f64 = 45.0;

/// The chord deviation of the geometry tessellation selectors and distances use.
const CATALOGUE_DEVIATION: f64 = 1e-3;

/// Seconds spent per stage.
#[derive(Clone, Debug, Default, Serialize)]
pub struct StageSeconds {
    /// Reading the file.
    pub read: f64,
    /// Tessellating a CAD part.
    pub tessellate: f64,
    /// Certifying the tessellation.
    pub certify: f64,
    /// Volume meshing.
    pub mesh: f64,
    /// The certificate was made beside the volume mesh (its seconds are within the mesh's).
    pub certify_beside_mesh: bool,
}

impl StageSeconds {
    /// The seconds of all the stages, once each where they ran beside each other.
    pub fn total(&self) -> f64 {
        self.read + self.tessellate + self.mesh + if self.certify_beside_mesh { 0.0 } else { self.certify }
    }
}

/// A tessellation of a B-rep and its certificate.
#[derive(Clone, Debug)]
pub struct Certified {
    /// The surface and each face's domain.
    pub tessellation: Tessellation,
    /// Its checks.
    pub certificate: Certificate,
}

/// One part and what the pipeline made of it.
#[derive(Debug)]
pub struct Part {
    /// The file it was read from.
    pub path: PathBuf,
    /// The B-rep of a CAD part (names, colours, STEP `#id`s, surface kinds).
    pub model: Option<Model>,
    /// The surface to mesh: as read, or the certified tessellation of a CAD part.
    pub surface: Option<TriSurface>,
    /// Holes and region seeds (from a `.poly` file).
    pub seeds: Seeds,
    /// Region sizes (from the maximum tet volumes of a `.poly` file's regions).
    pub region_sizes: Vec<(RegionId, f64)>,
    /// The certified tessellation of a CAD part.
    pub certified: Option<Certified>,
    /// The tet mesh.
    pub mesh: Option<TetMesh>,
    /// What the mesher did.
    pub mesh_report: Option<MeshReport>,
    /// What the octree mesher did (method octree).
    pub octree_report: Option<crate::mesh3d::octree::OctreeReport>,
    /// Faces of different solids that touch (a part of several solids), with the area over
    /// which they touch and how much of it the mesh shares: the mesher's, which the FE model's
    /// ties take ([`Part::contact_reports`] names them for reports).
    pub contacts: Vec<Contact>,
    /// The solids `contacts` name: region tag and name.
    pub solids: Vec<SolidInfo>,
    /// Seconds per stage.
    pub seconds: StageSeconds,
    /// A STEP file of tessellated geometry only: its faces and solids (its triangles are
    /// [`Part::surface`], meshed as a surface mesh's are).
    pub tessellated: Option<step::Tessellated>,
    /// Faces of open surface-model shells beside the solids, left out of the surface to mesh
    /// (their holes are in `fepre tessellate`'s report).
    pub open_surface_faces: usize,
    catalogue: OnceLock<FaceCatalogue>,
}

/// True for a `.step` or `.stp` path (any case).
pub fn is_step(path: &Path) -> bool {
    path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("step") || e.eq_ignore_ascii_case("stp"))
}

impl Part {
    /// Reads a STEP part or a surface mesh (STL, OBJ, glTF, OFF, Medit, TetGen `.poly`/`.smesh`,
    /// MSH).
    ///
    /// # Errors
    /// The file cannot be read (the error names the line or entity), or holds no surface.
    pub fn open(path: &Path) -> Result<Part, PipelineError> {
        let t0 = Instant::now();
        let mut part = if is_step(path) {
            match step::read_shape(path)? {
                step::Shape::Brep(model) => Part::from_model(path, model),
                step::Shape::Tessellated(mut t) => {
                    let surface = std::mem::take(&mut t.surface);
                    Part { tessellated: Some(t), ..Part::from_surface(path, surface) }
                }
            }
        } else {
            let loaded = io::read(path, &ReadOptions::default())?;
            let surface = match loaded.mesh {
                MeshData::Surface(s) => s,
                other => return Err(PipelineError::NotASurface { path: path.to_path_buf(), kind: other.kind() }),
            };
            let mut part = Part::from_surface(path, surface);
            part.seeds = Seeds {
                holes: loaded.seeds.holes.clone(),
                regions: loaded.seeds.regions.iter().map(|&(point, tag, _)| RegionSeed { point, tag }).collect(),
            };
            // a regular tet of volume V has edges (6 sqrt(2) V)^(1/3)
            part.region_sizes = loaded.seeds.regions.iter().filter_map(|&(_, tag, v)| v.filter(|v| *v > 0.0 && v.is_finite()).map(|v| (tag, (6.0 * 2f64.sqrt() * v).cbrt()))).collect();
            part
        };
        part.seconds.read = t0.elapsed().as_secs_f64();
        Ok(part)
    }

    /// A part from a B-rep model (built in code, or read elsewhere).
    pub fn from_model(path: &Path, model: Model) -> Part {
        Part { model: Some(model), surface: None, ..Part::empty(path) }
    }

    /// A part from a tagged surface.
    pub fn from_surface(path: &Path, surface: TriSurface) -> Part {
        Part { surface: Some(surface), ..Part::empty(path) }
    }

    fn empty(path: &Path) -> Part {
        Part {
            path: path.to_path_buf(),
            model: None,
            surface: None,
            seeds: Seeds::default(),
            region_sizes: Vec::new(),
            certified: None,
            mesh: None,
            mesh_report: None,
            octree_report: None,
            contacts: Vec::new(),
            solids: Vec::new(),
            seconds: StageSeconds::default(),
            tessellated: None,
            open_surface_faces: 0,
            catalogue: OnceLock::new(),
        }
    }

    /// The solids of `surface`, the part's surface to mesh ([`solids_of`]).
    pub fn surface_solids(&self, surface: &TriSurface) -> Solids {
        let seeded = !(self.seeds.holes.is_empty() && self.seeds.regions.is_empty() && self.region_sizes.is_empty());
        solids_of(self.model.as_ref(), seeded, surface)
    }

    /// The contacts between the part's solids, with the names and STEP `#id`s of the face
    /// table.
    pub fn contact_reports(&self) -> Vec<ContactReport> {
        if self.contacts.is_empty() {
            return Vec::new();
        }
        contact_reports(&self.contacts, &self.face_table(), &self.solids)
    }

    /// The gap within which the part's solids touch ([`gap_of`]).
    pub fn gap(&self) -> f64 {
        let chord = self.certified.as_ref().filter(|_| self.model.is_some()).map(|c| c.tessellation.chord);
        gap_of(chord, self.diagonal())
    }

    /// True for a B-rep part.
    pub fn is_cad(&self) -> bool {
        self.model.is_some()
    }

    /// The diagonal of the part's box.
    pub fn diagonal(&self) -> f64 {
        match (&self.model, &self.surface) {
            (Some(m), _) => m.size(),
            (None, Some(s)) if s.bbox().diagonal() > 0.0 => s.bbox().diagonal(),
            _ => 1.0,
        }
    }

    /// The default chord deviation of a CAD part's tessellation for meshing, a fraction of
    /// its diagonal: the inscribed tessellation loses about `(2/3) δ A_c` of volume (`A_c` the
    /// curved area), so `δ` is what keeps that under `MESH_VOLUME_ERROR` of the volume,
    /// between `MESH_DEVIATION_MIN` and `MESH_DEVIATION`.
    pub fn mesh_deviation(&self) -> f64 {
        let cat = self.catalogue();
        let curved: f64 = cat.faces.iter().filter(|f| !matches!(f.shape, crate::attributes::FaceShape::Plane { .. })).map(|f| f.area).sum();
        let volume = cat.volume();
        let by_volume = if curved > 0.0 { 1.5 * MESH_VOLUME_ERROR * volume / curved / self.diagonal() } else { MESH_DEVIATION };
        by_volume.clamp(MESH_DEVIATION_MIN, MESH_DEVIATION)
    }

    /// What selectors and sizes know of each face (built on first use; for a CAD part from a
    /// tessellation of its B-rep).
    pub fn catalogue(&self) -> &FaceCatalogue {
        self.catalogue.get_or_init(|| match (&self.model, &self.surface) {
            (Some(m), _) => FaceCatalogue::from_model(m, &tessellate(m, &TessellateOptions::default().with_chord_relative(CATALOGUE_DEVIATION).with_volume_relative(0.0))),
            (None, Some(s)) => FaceCatalogue::from_surface(s),
            _ => FaceCatalogue::default(),
        })
    }

    /// The faces for reports: id, unique name (as the writers name their groups), colour,
    /// STEP `#id`, solid.
    pub fn face_table(&self) -> Vec<FaceEntry> {
        match (&self.model, &self.surface) {
            (Some(m), _) => m.face_table(),
            (None, Some(s)) => {
                let mut table = face_table_of_names(&s.face_names, s.face_tags.iter().copied());
                if let Some(t) = &self.tessellated {
                    for e in &mut table {
                        if let Some(f) = e.face.index().and_then(|k| t.faces.get(k)) {
                            e.step_id = Some(f.step_id);
                            e.solid = f.solid;
                        }
                    }
                }
                table
            }
            _ => Vec::new(),
        }
    }

    /// True for a part in millimetres: a STEP part, B-rep or tessellated.
    pub fn is_step(&self) -> bool {
        self.is_cad() || self.tessellated.is_some()
    }

    /// Evaluates every selector of `selectors` on this part, once ([`Groups::evaluate`]).
    ///
    /// # Errors
    /// [`PipelineError::Select`]: the first selector that fails or selects nothing.
    pub fn groups(&self, selectors: &BTreeMap<String, Selector>) -> Result<Groups, PipelineError> {
        Groups::evaluate(selectors, self.catalogue()).map_err(|source| PipelineError::Select { path: self.path.clone(), source })
    }

    /// The size field of `density` on this part, its lengths times `unit`, the faces of its
    /// entries those `groups` gives; `default_size` the global size where the density gives
    /// none ([`super::default_size`]).
    ///
    /// # Errors
    /// A selector the density names that `groups` lacks; an inconsistent density.
    pub fn size_field(&self, density: &Density, groups: &Groups, unit: f64, default_size: f64) -> Result<DensityField, PipelineError> {
        DensityField::build(density, groups, self.catalogue(), unit, default_size).map_err(|source| PipelineError::Density { path: self.path.clone(), source })
    }

    /// [`Part::size_field`] with `selectors` evaluated and the Delaunay mesher's default size.
    ///
    /// # Errors
    /// A selector that fails or selects nothing; an inconsistent density.
    pub fn density_field(&self, density: &Density, selectors: &BTreeMap<String, Selector>, unit: f64) -> Result<DensityField, PipelineError> {
        let groups = self.groups(selectors)?;
        self.size_field(density, &groups, unit, default_size(self.diagonal(), self.is_cad(), Method::Delaunay).global)
    }

    /// Tessellates a CAD part to `size` and certifies the result; the certified surface becomes
    /// the surface to mesh. Does nothing for a surface mesh.
    ///
    /// # Errors
    /// [`PipelineError::Certificate`] when a check fails (the message names faces and STEP
    /// `#id`s); the failed tessellation is kept in [`Part::certified`] for reports.
    pub fn tessellate(&mut self, size: &dyn SizeField, opts: &TessellateOptions) -> Result<&Certificate, PipelineError> {
        let Some(model) = &mut self.model else {
            return Err(PipelineError::Usage { path: self.path.clone(), problem: UsageProblem::NotCad });
        };
        // the boundary of a volume mesh: its volume against the CAD solids' is the mesh
        // summary's to report (and `--require-volume-error`'s to demand)
        let (c, seconds) = certified_tessellation(model, opts, Some(size), &mesh_checks());
        self.accept(c, seconds, None)
    }

    /// Takes a CAD part's tessellation and its certificate (and their seconds): a certified
    /// surface becomes the surface to mesh (its solids' part, [`solids_only`], where the caller
    /// has it already).
    ///
    /// # Errors
    /// [`PipelineError::Certificate`] when a check failed.
    fn accept(&mut self, c: Certified, [tessellate_s, certify_s]: [f64; 2], solids: Option<(TriSurface, usize)>) -> Result<&Certificate, PipelineError> {
        let Some(model) = &self.model else {
            return Err(PipelineError::Usage { path: self.path.clone(), problem: UsageProblem::NotCad });
        };
        if !c.certificate.reoriented.is_empty() || !c.certificate.turned_faces.is_empty() {
            // faces turned: what the catalogue says of their normals is built again on use
            self.catalogue = OnceLock::new();
        }
        self.seconds.tessellate = tessellate_s;
        self.seconds.certify = certify_s;
        self.seconds.certify_beside_mesh = false;
        let failed = (!c.certificate.passed).then(|| PipelineError::certificate(&self.path, &c.certificate, &model.dropped));
        if failed.is_none() {
            let (surface, left_out) = solids.unwrap_or_else(|| solids_only(model, &c.tessellation.surface));
            self.surface = Some(surface);
            self.open_surface_faces = left_out;
        }
        let c = self.certified.insert(c);
        match failed {
            Some(e) => Err(e),
            None => Ok(&c.certificate),
        }
    }

    /// [`Part::tessellate`], and beside the certificate the tessellation meshed as
    /// [`Part::mesh`] meshes a certified one: the mesher does not wait for the checks, and the
    /// certificate decides whether its mesh stands. `None` where the checks turned shells
    /// inside out (the surface to mesh is not the one meshed), or found them inside out and
    /// passed: the caller meshes again.
    ///
    /// # Errors
    /// As [`Part::tessellate`]: a failed certificate, whatever the mesher made of it.
    fn tessellate_meshing(&mut self, size: &dyn SizeField, tess: &TessellateOptions, field: &dyn SizeField, opts: &MeshOptions) -> Result<Option<(Meshed, f64)>, PipelineError> {
        let Some(model) = &mut self.model else {
            return Err(PipelineError::Usage { path: self.path.clone(), problem: UsageProblem::NotCad });
        };
        let t0 = Instant::now();
        let mut tessellation = tessellate_sized(model, tess, size);
        let tessellate_s = t0.elapsed().as_secs_f64();
        let (surface, left_out) = solids_only(model, &tessellation.surface);
        let gap = GAP_CHORDS * tessellation.chord;
        let this = &*self;
        // a failed certificate, or shells to turn, stop the mesher at its next stage
        let abandon = Abandon::default();
        let meshing = opts.clone().with_abandon(abandon.clone());
        let (certificate, meshed) = rayon::join(
            || {
                let t = Instant::now();
                let c = this.model.as_ref().map(|m| certify(m, &tessellation, &mesh_checks()));
                let abandoned = c.as_ref().is_none_or(|c| !c.passed || !c.outward);
                if abandoned {
                    abandon.set();
                }
                c.map(|c| (c, t.elapsed().as_secs_f64(), abandoned))
            },
            || {
                let t = Instant::now();
                (this.mesh_once(&surface, field, &meshing, gap), t.elapsed().as_secs_f64())
            },
        );
        let (Some(model), Some((certificate, mut certify_s, abandoned))) = (&mut self.model, certificate) else {
            return Ok(None);
        };
        let t = Instant::now();
        let certificate = turned_certified(model, &mut tessellation, certificate, &mesh_checks());
        certify_s += t.elapsed().as_secs_f64();
        // the surface meshed is the surface to mesh where the checks let the mesher run
        let solids = (!abandoned).then_some((surface, left_out));
        self.accept(Certified { tessellation, certificate }, [tessellate_s, certify_s], solids)?;
        // the mesh stands where the mesher was let run on the surface that passed as it is
        self.seconds.certify_beside_mesh = !abandoned;
        Ok((!abandoned).then_some(meshed))
    }

    /// Meshes the part's surface into tets of `size` (a CAD part is tessellated to the same
    /// size first, at the deviation `opts` gives). A part of several solids (an assembly)
    /// gets one region per solid, named after it, each solid meshed on its own and the
    /// meshes merged (see [`crate::mesh3d::mesher::mesh_solids`]); the faces where solids
    /// touch are listed in [`Part::contacts`].
    ///
    /// # Errors
    /// A failed certificate, or a surface the mesher refuses (open, self-intersecting, solids
    /// that overlap, ...).
    pub fn mesh(&mut self, size: &dyn SizeField, tess: &TessellateOptions, opts: &MeshOptions) -> Result<&TetMesh, PipelineError> {
        // a sized tessellation is meshed as it is; a surface mesh is cut to the size first
        let opts = opts.clone().with_presize(opts.presize && !self.is_cad());
        let sized;
        let field: &dyn SizeField = if self.region_sizes.is_empty() {
            size
        } else {
            sized = RegionSizes::new(size, self.region_sizes.clone());
            &sized
        };
        // a CAD part is tessellated, and meshed while its tessellation is certified
        let speculative = if self.is_cad() && self.certified.is_none() { self.tessellate_meshing(size, tess, field, &opts)? } else { None };
        let Some(surface) = &self.surface else {
            return Err(PipelineError::Usage { path: self.path.clone(), problem: UsageProblem::NoSurface });
        };
        let t0 = Instant::now();
        let (mut result, before) = match speculative {
            Some((meshed, seconds)) => (meshed, seconds),
            None => (self.mesh_once(surface, field, &opts, self.gap()), 0.0),
        };
        if self.is_cad() && matches!(&result, Err(e) if is_recovery(e)) {
            // a sized tessellation whose edges recovery cannot take (pieces of faces nearer
            // each other than their triangles are long): the chords-only tessellation, cut to
            // the size by the mesher, as a surface mesh is
            if let Some(model) = &self.model {
                // the model's shells are turned already (by the first tessellation)
                let (chords, _) = certified_tessellation(&mut model.clone(), tess, None, &mesh_checks());
                if chords.certificate.passed {
                    let retry = self.mesh_once(&solids_only(model, &chords.tessellation.surface).0, field, &opts.clone().with_presize(true), self.gap());
                    if retry.is_ok() {
                        self.surface = Some(solids_only(model, &chords.tessellation.surface).0);
                        self.certified = Some(chords);
                        result = retry;
                    }
                }
            }
        }
        let (mut mesh, report, solids, contacts) = result.map_err(|source| self.meshing_error(source))?;
        if let Some(contacts) = contacts {
            self.contacts = contacts;
            self.solids = solids.solids.clone();
        }
        if let [solid] = &solids.solids[..] {
            // one solid: its name names the region it is
            if let Some(name) = &solid.name {
                if mesh.region_tags.iter().all(|&r| r == solid.tag) {
                    mesh.region_names.insert(solid.tag, name.clone());
                }
            }
        }
        self.seconds.mesh = before + t0.elapsed().as_secs_f64();
        self.mesh_report = Some(report);
        Ok(self.mesh.insert(mesh))
    }

    /// Meshes `surface` (the part's solids in it, each on its own when there are several,
    /// touching within `gap`).
    fn mesh_once(&self, surface: &TriSurface, field: &dyn SizeField, opts: &MeshOptions, gap: f64) -> Meshed {
        let solids = self.surface_solids(surface);
        // a CAD part's boundary vertices slide on its curved faces and edges, back onto them
        let brep = self.model.as_ref().map(BrepGeometry::new);
        let geometry = brep.as_ref().map(|g| g as &dyn BoundaryGeometry);
        if solids.solids.len() > 1 {
            let (mesh, report, contacts) = mesh_solids_on(surface, &solids, gap, field, opts, geometry)?;
            Ok((mesh, report, solids, Some(contacts)))
        } else {
            let (mesh, report) = mesh_surface_on(surface, &self.seeds, field, opts, geometry)?;
            Ok((mesh, report, solids, None))
        }
    }

    /// The mesher's error for this part; an overlap of solids also names the STEP faces.
    pub(super) fn meshing_error(&self, source: MeshingError) -> PipelineError {
        match &source {
            MeshingError::Overlap { a, b, .. } if self.is_cad() => {
                let faces = self.face_table();
                let id = |f| step_id(&faces, f).map_or_else(|| "?".to_string(), |e| e.to_string());
                let (ia, ib) = (id(a.face), id(b.face));
                PipelineError::Overlap { path: self.path.clone(), source, step_faces: format!("{ia} and {ib}") }
            }
            MeshingError::Open { count, edges, at, faces } if self.is_cad() => {
                // the open edges' faces by their STEP #ids too
                let table = self.face_table();
                let faces = faces
                    .iter()
                    .map(|(f, name)| {
                        let id = step_id(&table, *f).map(|e| format!("STEP {e}"));
                        let label = match (name.as_deref().filter(|n| !n.is_empty() && *n != "NONE"), id) {
                            (Some(n), Some(id)) => Some(format!("{n}, {id}")),
                            (Some(n), None) => Some(n.to_string()),
                            (None, id) => id,
                        };
                        (*f, label)
                    })
                    .collect();
                let source = MeshingError::Open { count: *count, edges: edges.clone(), at: at.clone(), faces };
                PipelineError::Meshing { path: self.path.clone(), source }
            }
            _ => PipelineError::Meshing { path: self.path.clone(), source },
        }
    }

    /// Writes the tet mesh (its format from the extension: `.mesh`, `.ele`/`.node`, `.vtu`,
    /// `.msh`) or, for a surface format (`.stl`, `.obj`, `.off`), the surface.
    ///
    /// # Errors
    /// Nothing to write, or a format that cannot hold it ([`PipelineError::Usage`]); the
    /// writer's errors. A failed write leaves no file.
    pub fn write(&self, out: &Path) -> Result<(), PipelineError> {
        match (Format::from_path(out), &self.mesh, &self.surface) {
            (Some(Format::Medit | Format::TetGen | Format::Vtu | Format::Msh), Some(mesh), _) => {
                io::write_ref(out, MeshRef::Volume(mesh), &WriteOptions::default())?;
            }
            (Some(Format::Stl | Format::Obj | Format::Off | Format::Vtu | Format::Msh), _, Some(surface)) => {
                io::write_ref(out, MeshRef::Surface(surface), &WriteOptions::default())?;
            }
            _ => return Err(PipelineError::Usage { path: out.to_path_buf(), problem: UsageProblem::OutputFormat }),
        }
        Ok(())
    }
}

/// Reads a STEP file, tessellates it (to `size` where given) and certifies the result. A failed
/// certificate is returned, not an error: the caller decides (`fepre tessellate --force`).
///
/// # Errors
/// The file cannot be read as STEP (the error names the line or `#id`).
pub fn tessellate_file(path: &Path, opts: &TessellateOptions, size: Option<&dyn SizeField>, checks: &CertifyOptions) -> Result<(Model, Certified, StageSeconds), PipelineError> {
    let t0 = Instant::now();
    let model = step::read(path)?;
    let read = t0.elapsed().as_secs_f64();
    Ok(tessellate_model(model, read, opts, size, checks))
}

/// [`tessellate_file`] of a model already read (`read` its seconds).
pub fn tessellate_model(mut model: Model, read: f64, opts: &TessellateOptions, size: Option<&dyn SizeField>, checks: &CertifyOptions) -> (Model, Certified, StageSeconds) {
    let (c, [tessellate, certify]) = certified_tessellation(&mut model, opts, size, checks);
    (model, c, StageSeconds { read, tessellate, certify, mesh: 0.0, certify_beside_mesh: false })
}

/// The checks [`Part::mesh`] certifies a tessellation by: the boundary of a volume mesh,
/// whose volume against the CAD solids' is the mesh summary's to report (and
/// `--require-volume-error`'s to demand), not a check of its own.
fn mesh_checks() -> CertifyOptions {
    CertifyOptions::default().with_volume_cap(false)
}

/// What [`Part::mesh_once`] gives: the mesh, the mesher's report, the solids and the contacts
/// between them (several solids).
type Meshed = Result<(TetMesh, MeshReport, Solids, Option<Vec<Contact>>), MeshingError>;

/// Tessellates `model` (to `size` where given) and certifies the result; with the seconds of
/// each.
/// Faces written against their shell and shells the file wrote inside out are turned in
/// `model` first ([`turn_misoriented_faces`], [`turn_inside_out_shells`]), and listed in the
/// certificate.
fn certified_tessellation(model: &mut Model, opts: &TessellateOptions, size: Option<&dyn SizeField>, checks: &CertifyOptions) -> (Certified, [f64; 2]) {
    let t0 = Instant::now();
    let mut tessellation = match size {
        Some(s) => tessellate_sized(model, opts, s),
        None => tessellate(model, opts),
    };
    let t1 = Instant::now();
    let certificate = certify(model, &tessellation, checks);
    let certificate = turned_certified(model, &mut tessellation, certificate, checks);
    (Certified { tessellation, certificate }, [(t1 - t0).as_secs_f64(), t1.elapsed().as_secs_f64()])
}

/// The certificate of `tessellation` once the shells `certificate` finds inside out are
/// turned (in `model` and `tessellation`, listed in [`Certificate::reoriented`]); `certificate`
/// itself where none is.
fn turned_certified(model: &mut Model, tessellation: &mut Tessellation, certificate: Certificate, checks: &CertifyOptions) -> Certificate {
    let mut certificate = certificate;
    if !certificate.oriented {
        let faces = turn_misoriented_faces(model, tessellation);
        if !faces.is_empty() {
            certificate = certify(model, tessellation, checks);
            certificate.turned_faces = faces.iter().map(|&f| model.face(f).source).collect();
        }
    }
    if certificate.outward {
        return certificate;
    }
    let turned = turn_inside_out_shells(model, tessellation, &certificate);
    if turned.is_empty() {
        return certificate;
    }
    let faces = std::mem::take(&mut certificate.turned_faces);
    let mut certificate = certify(model, tessellation, checks);
    certificate.reoriented = turned;
    certificate.turned_faces = faces;
    certificate
}

/// The surface to mesh of a model with solids: without the triangles of surface-model shells
/// (no solid) whose faces are left open after sewing; with the number of faces left out.
/// A model without solids, or without open surface shells, keeps its whole surface.
fn solids_only(model: &Model, surface: &TriSurface) -> (TriSurface, usize) {
    if model.solids.is_empty() {
        return (surface.clone(), 0);
    }
    let holes = model.holes(|s| s.solid.is_none() && !s.closed);
    if holes.is_empty() {
        return (surface.clone(), 0);
    }
    let (group, ngroups) = crate::tessellate::certificate::face_groups(model);
    let mut open = vec![false; ngroups];
    for f in holes.iter().flat_map(|h| h.faces.iter()) {
        if let Some(k) = f.index() {
            open[group[k] as usize] = true;
        }
    }
    let drop = |f: crate::core::FaceId| {
        f.index().is_some_and(|k| k < model.faces.len() && open[group[k] as usize] && model.shells[model.faces[k].shell as usize].solid.is_none())
    };
    let left_out = (0..model.faces.len()).filter(|&k| drop(crate::core::FaceId::from_index(k))).count();
    let mut out = surface.clone();
    let keep: Vec<bool> = out.face_tags.iter().map(|&f| !drop(f)).collect();
    let mut k = 0;
    out.triangles.retain(|_| {
        k += 1;
        keep[k - 1]
    });
    out.face_tags.retain(|&f| !drop(f));
    out.remove_unused_vertices();
    (out, left_out)
}

/// A boundary-recovery failure, of the part or of one solid of it.
fn is_recovery(e: &MeshingError) -> bool {
    match e {
        MeshingError::Recovery { .. } => true,
        MeshingError::InSolid { source, .. } => is_recovery(source),
        _ => false,
    }
}

/// The certificate's failures as one message, naming faces and STEP ids.
pub fn failure_message(path: &Path, c: &Certificate, dropped: &[Dropped]) -> String {
    PipelineError::certificate(path, c, dropped).to_string()
}
