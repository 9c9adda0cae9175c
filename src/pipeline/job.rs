//! Job files: one TOML file names the input, the units, the selectors, the density, the
//! mesh method and options, and the outputs (every key is described in `docs/job-file.md`).
//!
//! ```toml
//! units = "mm"
//! [input]
//! file = "bracket.step"
//! [selectors]
//! holes = { name = "hole_*" }
//! [density]
//! size = 4.5
//! face = [{ faces = "holes", size = 2.25 }]
//! [mesh]
//! method = "delaunay"
//! [[output]]
//! file = "bracket.msh"
//! ```
//!
//! Unknown keys, wrong types and bad values are errors naming the key with its line and
//! column ([`PipelineError::Job`]); paths are relative to the job file's folder.

use super::PipelineError;
pub use super::job_fe::{
    Contacts, DisplacementSpec, Dof, ElementChoice, FilmSpec, FixedSpec, ForceSpec, GravitySpec, MaterialSpec, ModelSection, Poisson, PressureSpec, SectionSpec,
    SolidRef, SolveSection, StepKind, StepSpec, ValueOnFaces,
};
use crate::attributes::values::Positive;
use crate::attributes::{Density, SelectError, Selector};
use crate::mesh3d::mesher::{MeshOptions, dihedral_bound, radius_edge_bound};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// A job, as read from its file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Job {
    /// Unit of every length in the job (sizes, points, boxes, offsets, radii); default `mm`.
    #[serde(default)]
    pub units: LengthUnit,
    /// What to read (absent only for a `[mesh2d]` job of `[[mesh2d.region]]` polygons).
    #[serde(default)]
    pub input: Option<Input>,
    /// Named selectors.
    #[serde(default)]
    pub selectors: BTreeMap<String, Spanned<Selector>>,
    /// The mesh size.
    #[serde(default)]
    pub density: Density,
    /// The volume mesh.
    #[serde(default)]
    pub mesh: MeshSection,
    /// What the result must reach, or the run fails.
    #[serde(default)]
    pub require: Require,
    /// What to write.
    #[serde(default)]
    pub output: Vec<Output>,
    /// The FE model's elements.
    #[serde(default)]
    pub model: ModelSection,
    /// Materials by name.
    #[serde(default)]
    pub materials: BTreeMap<String, Spanned<MaterialSpec>>,
    /// Materials on solids.
    #[serde(default)]
    pub section: Vec<SectionSpec>,
    /// Analysis steps.
    #[serde(default)]
    pub step: Vec<Spanned<StepSpec>>,
    /// What `fepre solve` writes.
    #[serde(default)]
    pub solve: SolveSection,
    /// A 2D mesh of the part's planar faces (or a `.poly` file's regions) instead of a
    /// volume mesh.
    pub mesh2d: Option<Mesh2dSection>,
}

/// `[mesh2d]`: the lecture's 2D methods on the planar faces of a part or the regions of a
/// Triangle `.poly` file; the size comes from `[density]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mesh2dSection {
    /// `delaunay`, `ear`, `recursive`, `removal`, `front` or `quadtree`, as `fepre mesh2d
    /// --method`.
    pub method: Option<Spanned<String>>,
    /// All quadrilaterals.
    #[serde(default)]
    pub quads: bool,
    /// The smallest angle Delaunay refinement aims at, degrees.
    pub min_angle: Option<Positive>,
    /// The largest triangle area.
    pub max_area: Option<Positive>,
    /// The faces to mesh (ids; default every planar face).
    #[serde(default)]
    pub faces: Vec<u32>,
    /// Fail, writing nothing, when an angle is under this, degrees.
    pub require_min_angle: Option<Positive>,
    /// Polygons to mesh instead of an `[input]` file.
    #[serde(default)]
    pub region: Vec<Spanned<PolygonRegion>>,
}

/// `[[mesh2d.region]]`: a polygon with holes, in the job's units.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PolygonRegion {
    /// The boundary's points `[x, y]`, in order (either way round; the last joins the first).
    pub outer: Vec<[f64; 2]>,
    /// The holes, each a list of points.
    #[serde(default)]
    pub holes: Vec<Vec<[f64; 2]>>,
    /// The region's tag (default: its place in the list, from 1).
    pub tag: Option<u32>,
}

/// A length unit.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LengthUnit {
    /// Millimetres (the unit of fepre's B-rep).
    #[default]
    Mm,
    /// Centimetres.
    Cm,
    /// Metres.
    M,
    /// Inches.
    #[serde(alias = "in")]
    Inch,
}

impl LengthUnit {
    /// Millimetres per unit.
    pub fn to_mm(self) -> f64 {
        match self {
            LengthUnit::Mm => 1.0,
            LengthUnit::Cm => 10.0,
            LengthUnit::M => 1000.0,
            LengthUnit::Inch => 25.4,
        }
    }
}

/// `[input]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Input {
    /// The part: a STEP file or a surface mesh.
    pub file: Spanned<PathBuf>,
    /// The length unit of a mesh file's coordinates (default: the job's `units`); STEP files
    /// carry their own.
    pub units: Option<LengthUnit>,
}

/// The volume meshing method.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Delaunay refinement with boundary recovery and optimisation.
    #[default]
    Delaunay,
    /// Octree: isosurface stuffing of the volume the surface's winding number encloses
    /// ([`crate::mesh3d::octree`]); takes open and self-intersecting surfaces.
    Octree,
}

/// `[mesh]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSection {
    /// The method (default `delaunay`).
    pub method: Option<Spanned<Method>>,
    /// The octree's grading (`method = "octree"` only): `"uniform"` (default) or `"graded"`
    /// (the same boundary triangles, coarser inside: octree cells, then vertex collapses).
    pub grading: Option<Spanned<crate::mesh3d::octree::Grading>>,
    /// Graded octree only: collapse interior vertices after the octree (default `true`;
    /// `false`: the octree's cells only).
    pub coarsen: Option<Spanned<bool>>,
    /// See [`MeshOptions::max_radius_edge`] (at least 1.1; default 1.5).
    pub max_radius_edge: Option<Spanned<f64>>,
    /// See [`MeshOptions::min_dihedral`] (0 to 35; default 18).
    pub min_dihedral: Option<Spanned<f64>>,
    /// See [`MeshOptions::keep_surface`].
    #[serde(default)]
    pub keep_surface: bool,
    /// See [`MeshOptions::narrow_tolerance`]: a length in the job's unit, 0 keeps every
    /// strip (default 1e-4 of the diagonal).
    pub narrow_tolerance: Option<Spanned<f64>>,
    /// See [`MeshOptions::optimize`] (default true).
    pub optimize: Option<bool>,
}

/// `[require]`: what the result must reach; a run that falls short fails and writes nothing.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Require {
    /// Smallest dihedral angle of every tet, degrees (0 to 35). Unset: no tet under 1° that
    /// touches no input angle under 1°.
    pub min_dihedral: Option<Spanned<f64>>,
    /// Largest radius-edge ratio of every tet.
    pub max_radius_edge: Option<Positive>,
    /// Largest relative difference between the mesh's volume and the CAD solids'.
    pub volume_error: Option<Positive>,
}

/// What an `[[output]]` writes.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum OutputKind {
    /// The tet mesh (`.msh`, `.vtu`, `.mesh`, `.ele`).
    Mesh,
    /// The surface meshed (`.stl`, `.obj`, `.off`, `.msh`, `.vtu`).
    Surface,
    /// The JSON report of the run.
    Report,
    /// A solver deck: CalculiX/Abaqus (`.inp`).
    Deck,
}

/// `[[output]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Output {
    /// The file (relative to the job file's folder); its extension picks the format.
    pub file: Spanned<PathBuf>,
    /// What to write (default: a report for `.json`, the surface for `.stl`/`.obj`/`.off`,
    /// a deck for `.inp`/`.bdf`/`.nas`, the tet mesh otherwise).
    pub kind: Option<OutputKind>,
    /// Nastran decks: large (16-character) fields instead of small (8).
    #[serde(default)]
    pub large_fields: bool,
}

impl Output {
    /// What this output writes.
    pub fn kind(&self) -> OutputKind {
        self.kind.unwrap_or_else(|| {
            let ext = self.file.get_ref().extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
            match ext.as_str() {
                "json" => OutputKind::Report,
                "inp" | "bdf" | "nas" => OutputKind::Deck,
                "stl" | "obj" | "off" => OutputKind::Surface,
                _ => OutputKind::Mesh,
            }
        })
    }
}

/// The formats a deck output is written in.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum DeckFormat {
    /// CalculiX/Abaqus `.inp`.
    Inp,
    /// Nastran bulk data `.bdf`, `.nas`.
    Nastran,
    /// Gmsh MSH 4.1 with the sets as named physical groups.
    Msh,
    /// VTK XML with the sets as point and cell data.
    Vtu,
}

/// The deck format of a path, by its extension.
pub fn deck_format(path: &Path) -> Option<DeckFormat> {
    let ext = path.extension().and_then(|e| e.to_str())?.to_ascii_lowercase();
    match ext.as_str() {
        "inp" => Some(DeckFormat::Inp),
        "bdf" | "nas" => Some(DeckFormat::Nastran),
        "msh" => Some(DeckFormat::Msh),
        "vtu" => Some(DeckFormat::Vtu),
        _ => None,
    }
}

/// A job file read and checked: the job, its text (for messages) and its folder.
#[derive(Debug)]
pub struct JobFile {
    /// The job.
    pub job: Job,
    /// The file.
    pub path: PathBuf,
    /// Its text.
    pub text: String,
}

impl JobFile {
    /// Reads and checks a job file.
    ///
    /// # Errors
    /// [`PipelineError::Job`] naming the key, line and column: a syntax error, an unknown key,
    /// a wrong type, a bad value.
    pub fn read(path: &Path) -> Result<JobFile, PipelineError> {
        let text = std::fs::read_to_string(path).map_err(|e| PipelineError::Job { path: path.to_path_buf(), line: 0, column: 0, key: None, message: format!("cannot read: {e}") })?;
        JobFile::parse(path, text)
    }

    /// Checks the text of a job file (`path` is used for messages and relative paths).
    ///
    /// # Errors
    /// As [`JobFile::read`].
    pub fn parse(path: &Path, text: String) -> Result<JobFile, PipelineError> {
        let job: Job = match toml::from_str(&text) {
            Ok(j) => j,
            Err(e) => {
                let span = e.span().unwrap_or(0..0);
                let key = key_at(&text, span.start);
                let message = match key {
                    Some(k) if !e.message().contains(&format!("`{k}`")) => format!("key `{k}`: {}", e.message().trim()),
                    _ => e.message().trim().to_string(),
                };
                return Err(error_at(path, &text, span.start, message));
            }
        };
        let jf = JobFile { job, path: path.to_path_buf(), text };
        jf.check_values()?;
        Ok(jf)
    }

    /// The `[input]` section.
    ///
    /// # Errors
    /// A job without one.
    pub fn input(&self) -> Result<&Input, PipelineError> {
        self.job.input.as_ref().ok_or_else(|| self.error_at(0, "missing `[input]`: the part to read".into()))
    }

    fn check_values(&self) -> Result<(), PipelineError> {
        let regions = self.job.mesh2d.as_ref().map_or(&[][..], |m| m.region.as_slice());
        match (&self.job.input, regions.first()) {
            (None, None) => return Err(self.error_at(0, "missing `[input]`: the part to read (or `[[mesh2d.region]]` polygons)".into())),
            (Some(_), Some(r)) => return Err(self.error_at(r.span().start, "`[[mesh2d.region]]` polygons are meshed instead of an `[input]` file: give one or the other".into())),
            _ => {}
        }
        if let Some(m) = self.job.mesh2d.as_ref().and_then(|m| m.method.as_ref()) {
            if let Err(e) = m.get_ref().parse::<crate::mesh2d::Method>() {
                return Err(self.error_at(m.span().start, format!("key `method`: {e}")));
            }
        }
        let m = &self.job.mesh;
        if let Some(g) = &m.grading {
            if self.method() != Method::Octree {
                return Err(self.error_at(g.span().start, "key `grading`: only for method = \"octree\"".into()));
            }
        }
        if let Some(c) = &m.coarsen {
            if self.method() != Method::Octree || self.octree_options().grading != crate::mesh3d::octree::Grading::Graded {
                return Err(self.error_at(c.span().start, "key `coarsen`: only for method = \"octree\" with grading = \"graded\"".into()));
            }
        }
        if let Some(r) = &m.max_radius_edge {
            if let Err(e) = radius_edge_bound(*r.get_ref()) {
                return Err(self.error_at(r.span().start, format!("key `max_radius_edge`: {e}")));
            }
        }
        if let Some(d) = &m.min_dihedral {
            if let Err(e) = dihedral_bound(*d.get_ref()) {
                return Err(self.error_at(d.span().start, format!("key `min_dihedral`: {e}")));
            }
        }
        if let Some(t) = &m.narrow_tolerance {
            if !(t.get_ref().is_finite() && *t.get_ref() >= 0.0) {
                return Err(self.error_at(t.span().start, format!("key `narrow_tolerance`: {} must be a length >= 0 (0 keeps every strip)", t.get_ref())));
            }
        }
        if let Some(d) = &self.job.require.min_dihedral {
            if let Err(e) = dihedral_bound(*d.get_ref()) {
                return Err(self.error_at(d.span().start, format!("key `min_dihedral`: {e}")));
            }
        }
        for o in &self.job.output {
            let kind = o.kind();
            let ext = crate::io::Format::from_path(o.file.get_ref());
            use crate::io::Format as F;
            let ok = match kind {
                OutputKind::Report => o.file.get_ref().extension().is_some_and(|e| e.eq_ignore_ascii_case("json")),
                OutputKind::Mesh => matches!(ext, Some(F::Medit | F::TetGen | F::Vtu | F::Msh)),
                OutputKind::Surface => matches!(ext, Some(F::Stl | F::Obj | F::Off | F::Vtu | F::Msh)),
                OutputKind::Deck => deck_format(o.file.get_ref()).is_some(),
            };
            if o.large_fields && !(kind == OutputKind::Deck && deck_format(o.file.get_ref()) == Some(DeckFormat::Nastran)) {
                return Err(self.error_at(o.file.span().start, format!("key `large_fields`: only a Nastran deck (.bdf, .nas) has large fields, not {}", o.file.get_ref().display())));
            }
            if !ok {
                return Err(self.error_at(o.file.span().start, format!("key `file`: {} cannot hold a {kind:?} (mesh: .msh .vtu .mesh .ele; surface: .stl .obj .off .msh .vtu; report: .json; deck: .inp .bdf .nas .msh .vtu)", o.file.get_ref().display()).to_lowercase()));
            }
        }
        Ok(())
    }

    /// The job file's folder (relative paths start there).
    pub fn folder(&self) -> PathBuf {
        self.path.parent().map(Path::to_path_buf).unwrap_or_default()
    }

    /// `p` relative to the job file's folder.
    pub fn resolve(&self, p: &Path) -> PathBuf {
        if p.is_absolute() { p.to_path_buf() } else { self.folder().join(p) }
    }

    /// The selectors without their spans.
    pub fn selectors(&self) -> BTreeMap<String, Selector> {
        self.job.selectors.iter().map(|(k, v)| (k.clone(), v.get_ref().clone())).collect()
    }

    /// The meshing method (default Delaunay).
    pub fn method(&self) -> Method {
        self.job.mesh.method.as_ref().map_or(Method::Delaunay, |m| *m.get_ref())
    }

    /// The octree mesher's options.
    pub fn octree_options(&self) -> crate::mesh3d::octree::OctreeOptions {
        let grading = self.job.mesh.grading.as_ref().map_or_else(Default::default, |g| *g.get_ref());
        let coarsen = self.job.mesh.coarsen.as_ref().is_none_or(|c| *c.get_ref());
        crate::mesh3d::octree::OctreeOptions { grading, coarsen, ..Default::default() }
    }

    /// [`MeshOptions`] of the `[mesh]` section.
    pub fn mesh_options(&self) -> MeshOptions {
        let m = &self.job.mesh;
        let mut o = MeshOptions::default().with_keep_surface(m.keep_surface).with_imprint(self.job.model.imprint());
        if let Some(r) = &m.max_radius_edge {
            o = o.with_max_radius_edge(*r.get_ref());
        }
        if let Some(d) = &m.min_dihedral {
            o = o.with_min_dihedral(*d.get_ref());
        }
        if let Some(on) = m.optimize {
            o = o.with_optimize(on);
        }
        if let Some(t) = &m.narrow_tolerance {
            // in the job's unit: the caller scales it to the part's (see `carry_out`)
            o = o.with_narrow_tolerance(Some(*t.get_ref()));
        }
        o
    }

    /// A job error at byte `offset` of the file.
    pub fn error_at(&self, offset: usize, message: String) -> PipelineError {
        error_at(&self.path, &self.text, offset, message)
    }

    /// A selector error, placed at the selector it names (or, for a name that is not
    /// defined, where the name is used).
    pub fn select_error(&self, e: &SelectError) -> PipelineError {
        let at = match e {
            SelectError::Unknown { missing, .. } => find_quoted(&self.text, missing),
            SelectError::Empty(n) | SelectError::Cycle(n, _) | SelectError::Invalid { name: n, .. } => self.job.selectors.get(n).map(|s| s.span().start).or_else(|| find_quoted(&self.text, n)),
        };
        match at {
            Some(o) => self.error_at(o, e.to_string()),
            None => PipelineError::Job { path: self.path.clone(), line: 0, column: 0, key: None, message: e.to_string() },
        }
    }
}

/// 1-based line and column of byte `offset` in `text`.
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..floor_boundary(text, offset)];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

fn error_at(path: &Path, text: &str, offset: usize, message: String) -> PipelineError {
    let (line, column) = line_column(text, offset);
    PipelineError::Job { path: path.to_path_buf(), line, column, key: key_at(text, offset), message }
}

/// The key whose value starts at or before `offset` on its line (`size` in `size = -1`, the
/// last `key =` before the offset in an inline table).
fn key_at(text: &str, offset: usize) -> Option<String> {
    let offset = floor_boundary(text, offset);
    let start = text[..offset].rfind('\n').map_or(0, |k| k + 1);
    let end = text[offset..].find('\n').map_or(text.len(), |k| offset + k);
    let line = &text[start..end];
    let upto = &line[..offset - start];
    // the last `=` before the offset, or on the line when the offset is at the key itself
    let eq = upto.rfind('=').or_else(|| line.find('='))?;
    let head = &line[..eq];
    let key = head.rsplit(['{', ',', '[']).next()?.trim();
    let key = key.trim_matches('"');
    (!key.is_empty() && key.chars().all(|c| c.is_alphanumeric() || "_-.\"".contains(c))).then(|| key.to_string())
}

/// The largest char boundary of `text` at or below `offset`.
fn floor_boundary(text: &str, offset: usize) -> usize {
    let mut o = offset.min(text.len());
    while !text.is_char_boundary(o) {
        o -= 1;
    }
    o
}

/// The byte offset of `"name"` (or `'name'`) in `text`.
fn find_quoted(text: &str, name: &str) -> Option<usize> {
    text.find(&format!("\"{name}\"")).or_else(|| text.find(&format!("'{name}'")))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<JobFile, PipelineError> {
        JobFile::parse(Path::new("job.toml"), s.to_string())
    }

    fn err(s: &str) -> (usize, String) {
        match parse(s) {
            Err(PipelineError::Job { line, message, .. }) => (line, message),
            other => panic!("expected a job error, got {other:?}"),
        }
    }

    #[test]
    fn a_full_job_reads() {
        let j = parse(
            r#"
units = "mm"
[input]
file = "part.step"
[selectors]
holes = { name = "hole_*" }
top = { plane = { normal = [0, 0, 1], offset = 8 } }
both = { union = ["holes", "top"] }
[density]
size = 4
grading = 1.3
face = [{ faces = "holes", size = 2 }]
distance = [{ faces = "top", size = 1, growth = 0.2, max = 3 }]
box = [{ min = [0, 0, 0], max = [1, 1, 1], size = 0.5 }]
point = [{ at = [1, 2, 3], size = 0.5, radius = 1 }]
[mesh]
method = "delaunay"
min_dihedral = 15
[[output]]
file = "part.msh"
[[output]]
file = "part.json"
"#,
        )
        .unwrap();
        assert_eq!(j.job.selectors.len(), 3);
        assert_eq!(j.job.density.face.len(), 1);
        assert_eq!(j.job.output[1].kind(), OutputKind::Report);
        assert_eq!(j.mesh_options().min_dihedral, 15.0);
    }

    #[test]
    fn errors_name_the_key_and_its_line() {
        let (line, m) = err("[input]\nfile = \"a.step\"\n[density]\nsise = 3\n");
        assert_eq!(line, 4, "{m}");
        assert!(m.contains("sise"), "{m}");
        let (line, m) = err("[input]\nfile = \"a.step\"\n[density]\nsize = \"big\"\n");
        assert_eq!(line, 4, "{m}");
        assert!(m.contains("size"), "{m}");
        let (line, m) = err("[input]\nfile = \"a.step\"\n[density]\nsize = -1\n");
        assert_eq!(line, 4, "{m}");
        assert!(m.contains("size") && m.contains("> 0"), "{m}");
        let (line, m) = err("[input]\nfile = \"a.step\"\n[density]\nbox = [{ min = [0, 0, 2], max = [1, 1, 1], size = 1 }]\n");
        assert_eq!(line, 4, "{m}");
        assert!(m.contains("above max"), "{m}");
        let (line, m) = err("[input]\nfile = \"a.step\"\n[selectors]\nx = { nam = \"a\" }\n");
        assert_eq!(line, 4, "{m}");
        assert!(m.contains("nam"), "{m}");
        let (line, m) = err("[input]\nfile = \"a.step\"\n[mesh]\nmax_radius_edge = 0.5\n");
        assert_eq!(line, 4, "{m}");
        assert!(m.contains("max_radius_edge"), "{m}");
        let (line, m) = err("[input]\nfile = \"a.step\"\n[mesh]\nnarrow_tolerance = -1\n");
        assert_eq!(line, 4, "{m}");
        assert!(m.contains("narrow_tolerance"), "{m}");
        let (line, m) = err("[input]\nfile = \"a.step\"\n[require]\nmin_dihedral = 50\n");
        assert_eq!(line, 4, "{m}");
        assert!(m.contains("min_dihedral") && m.contains("[0, 35]"), "{m}");
        let (line, m) = err("[input]\nfile = \"a.step\"\n[require]\nmax_radius_edge = 0\n");
        assert_eq!(line, 4, "{m}");
        assert!(m.contains("max_radius_edge"), "{m}");
        let (line, m) = err("[input]\nfile = \"a.step\"\n[[output]]\nfile = \"a.stl\"\nkind = \"mesh\"\n");
        assert_eq!(line, 4, "{m}");
        let (_, m) = err("[density]\nsize = 1\n");
        assert!(m.contains("input"), "{m}");
    }

    #[test]
    fn line_and_column_count_from_one() {
        assert_eq!(line_column("ab\ncd", 0), (1, 1));
        assert_eq!(line_column("ab\ncd", 4), (2, 2));
    }
}
