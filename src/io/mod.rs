//! Layer 2: mesh file formats.
//!
//! [`read`] picks the reader from the file's extension and returns a [`Loaded`] mesh: a
//! surface (welded with a tolerance relative to the model's size), a tet mesh or a point set,
//! validated, with notes on anything skipped. [`write()`] picks the writer the same way; every
//! writer writes a temporary file and renames it at the end, so a failed write leaves no file.
//!
//! | format | read | write | tags |
//! |---|---|---|---|
//! | STL (`.stl`) ASCII and binary | yes | binary (ASCII with [`WriteOptions::ascii`]) | ASCII: one `solid` per tag |
//! | Wavefront OBJ (`.obj`) | yes (tobj) | yes | objects and groups |
//! | glTF 2.0 (`.gltf`, `.glb`) | yes (gltf) | no | one per mesh instance and primitive |
//! | OFF (`.off`) | yes | yes | none |
//! | Medit (`.mesh`) | yes | yes | references |
//! | TetGen (`.node`, `.ele`, `.face`, `.poly`, `.smesh`) | yes | yes | markers and region attributes |
//! | Gmsh MSH 4.1 (`.msh`) ASCII and binary | yes | ASCII | physical groups |
//! | VTK XML unstructured grid (`.vtu`) | no | yes | cell data |
//! | points (`.xyz`) | yes | no | none |
//!
//! Triangle's 2D `.poly` (a planar graph with holes and regions, for `crate::mesh2d`) has its
//! own reader and writer, [`read_poly`] and [`write_poly`], and
//! [`PolyFile::to_domains`] turns it into checked 2D domains, one per region.
//!
//! Results: [`frd`] reads CalculiX's ASCII `.frd` result file into plain arrays (nodes, steps,
//! fields); [`vtu::write_grid_with_data`] writes FE results (linear or quadratic tets with
//! point and cell arrays) for ParaView.
//!
//! Tags follow `crate::core::ids` (0 untagged, made-up tags from 1). Writers that write tag
//! names (MSH physical names, OBJ groups, ASCII STL solids) make them unique first
//! ([`crate::core::TagNames::unique`]): the first keeps its name, later ones get `.2`, `.3`.

pub(crate) mod atomic;
pub(crate) mod common;
pub(crate) mod error;
pub(crate) mod ccx_dat;
mod data_uri;
pub mod frd;
pub(crate) mod gltf;
pub(crate) mod medit;
pub(crate) mod msh;
pub(crate) mod obj;
pub(crate) mod off;
pub(crate) mod poly;
pub(crate) mod polygon;
pub(crate) mod point_lines;
pub(crate) mod stl;
pub(crate) mod tetgen;
#[cfg(test)]
pub(crate) mod test_meshes;
pub(crate) mod text;
pub mod vtu;
pub(crate) mod xyz;

pub use error::{IoError, Location};
pub use poly::{PolyError, PolyFile, PolyRegion, RegionSeed, read as read_poly, write as write_poly};

use crate::core::{RegionId, Tolerance};
use crate::mesh::{MixedSurface, TetMesh, TriSurface};
use glam::DVec3;
use std::path::Path;

/// A file format, chosen from the file's extension.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// STL, ASCII or binary.
    Stl,
    /// Wavefront OBJ.
    Obj,
    /// glTF 2.0 JSON with its buffers.
    Gltf,
    /// glTF 2.0 binary.
    Glb,
    /// Object File Format.
    Off,
    /// Medit / INRIA `.mesh`.
    Medit,
    /// TetGen's `.node/.ele/.face/.poly/.smesh` family.
    TetGen,
    /// Gmsh MSH 4.1.
    Msh,
    /// VTK XML unstructured grid.
    Vtu,
    /// Plain `x y z` lines.
    Xyz,
}

impl Format {
    /// The format for a path's extension (ASCII case-insensitive).
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "stl" => Format::Stl,
            "obj" => Format::Obj,
            "gltf" => Format::Gltf,
            "glb" => Format::Glb,
            "off" => Format::Off,
            "mesh" => Format::Medit,
            "node" | "ele" | "face" | "poly" | "smesh" => Format::TetGen,
            "msh" => Format::Msh,
            "vtu" => Format::Vtu,
            "xyz" => Format::Xyz,
            _ => return None,
        })
    }

    /// A short human name.
    pub fn name(self) -> &'static str {
        match self {
            Format::Stl => "STL",
            Format::Obj => "OBJ",
            Format::Gltf => "glTF",
            Format::Glb => "GLB",
            Format::Off => "OFF",
            Format::Medit => "Medit",
            Format::TetGen => "TetGen",
            Format::Msh => "MSH 4.1",
            Format::Vtu => "VTU",
            Format::Xyz => "XYZ",
        }
    }

    /// True if fepre reads this format.
    pub fn can_read(self) -> bool {
        !matches!(self, Format::Vtu)
    }

    /// True if fepre writes this format.
    pub fn can_write(self) -> bool {
        !matches!(self, Format::Gltf | Format::Glb | Format::Xyz)
    }
}

const READ_EXTENSIONS: &str = ".stl .obj .gltf .glb .off .mesh .node .ele .face .poly .smesh .msh .xyz";
const WRITE_EXTENSIONS: &str = ".stl .obj .off .mesh .node .ele .face .poly .smesh .msh .vtu";

/// What a mesh file holds.
#[derive(Clone, Debug, PartialEq)]
pub enum MeshData {
    /// A triangle surface.
    Surface(TriSurface),
    /// A tetrahedral mesh.
    Volume(TetMesh),
    /// A point set (TetGen `.node` without elements, `.xyz`).
    Points(Vec<DVec3>),
}

impl MeshData {
    /// A word for messages: "surface", "tetrahedral mesh" or "point set".
    pub fn kind(&self) -> &'static str {
        self.as_ref().kind()
    }

    /// The mesh, borrowed (what [`write_ref`] takes).
    pub fn as_ref(&self) -> MeshRef<'_> {
        match self {
            MeshData::Surface(s) => MeshRef::Surface(s),
            MeshData::Volume(m) => MeshRef::Volume(m),
            MeshData::Points(p) => MeshRef::Points(p),
        }
    }
}

/// A mesh to write, borrowed: a writer needs no copy of what it writes.
#[derive(Clone, Copy, Debug)]
pub enum MeshRef<'a> {
    /// A triangle surface.
    Surface(&'a TriSurface),
    /// A tetrahedral mesh.
    Volume(&'a TetMesh),
    /// A point set.
    Points(&'a [DVec3]),
    /// A surface of triangles and quads.
    Mixed(&'a MixedSurface),
}

impl MeshRef<'_> {
    /// A word for messages: "surface", "tetrahedral mesh" or "point set".
    pub fn kind(&self) -> &'static str {
        match self {
            MeshRef::Surface(_) => "surface",
            MeshRef::Volume(_) => "tetrahedral mesh",
            MeshRef::Points(_) => "point set",
            MeshRef::Mixed(_) => "surface of triangles and quads",
        }
    }
}

/// Hole and region seed points of a piecewise linear complex (TetGen `.poly`/`.smesh`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PlcSeeds {
    /// Points inside holes (cavities) that must stay empty.
    pub holes: Vec<DVec3>,
    /// Region seeds: a point, its region tag and an optional maximum tet volume.
    pub regions: Vec<(DVec3, RegionId, Option<f64>)>,
}

/// A mesh as read from a file.
#[derive(Clone, Debug, PartialEq)]
pub struct Loaded {
    /// The mesh.
    pub mesh: MeshData,
    /// The format it was read as.
    pub format: Format,
    /// Vertices as stored in the file, before welding (for a triangle soup such as STL this is
    /// three per triangle).
    pub file_vertices: usize,
    /// Things skipped, repaired or worth knowing ("welded 2,399 vertices into 2,108",
    /// "skipped 3 line primitives of mesh 'x'").
    pub notes: Vec<String>,
    /// Holes and region seeds, for PLC formats.
    pub seeds: PlcSeeds,
}

impl Loaded {
    /// A loaded mesh with no notes or seeds.
    pub fn new(mesh: MeshData, format: Format, file_vertices: usize) -> Self {
        Loaded { mesh, format, file_vertices, notes: Vec::new(), seeds: PlcSeeds::default() }
    }
}

/// How to read.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct ReadOptions {
    /// Merge surface vertices closer than this fraction of the model size (`None`: keep the
    /// file's vertices as they are).
    pub weld: Option<Tolerance>,
}

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions { weld: Some(Tolerance::WELD) }
    }
}

impl ReadOptions {
    /// Sets the welding tolerance (`None` to keep the file's vertices).
    pub fn with_weld(mut self, weld: Option<Tolerance>) -> Self {
        self.weld = weld;
        self
    }
}

/// How to write.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct WriteOptions {
    /// Text instead of binary where a format has both (STL, VTU).
    pub ascii: bool,
}

impl WriteOptions {
    /// Sets [`WriteOptions::ascii`].
    pub fn with_ascii(mut self, ascii: bool) -> Self {
        self.ascii = ascii;
        self
    }
}

/// Reads the whole file, turning a missing file, a directory and an empty file into clear
/// errors.
///
/// # Errors
/// [`IoError::Read`], [`IoError::IsDirectory`] or [`IoError::Empty`].
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, IoError> {
    let meta = std::fs::metadata(path).map_err(|source| IoError::Read { path: path.to_path_buf(), source })?;
    if meta.is_dir() {
        return Err(IoError::IsDirectory { path: path.to_path_buf() });
    }
    let bytes = std::fs::read(path).map_err(|source| IoError::Read { path: path.to_path_buf(), source })?;
    if bytes.is_empty() || bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(IoError::Empty { path: path.to_path_buf() });
    }
    Ok(bytes)
}

/// Reads a mesh file, its format chosen from the extension; surfaces are welded as
/// `options` says; the result is validated.
///
/// # Errors
/// An [`IoError`] naming the file and, where there is one, the line or entity.
pub fn read(path: &Path, options: &ReadOptions) -> Result<Loaded, IoError> {
    let format = Format::from_path(path).filter(|f| f.can_read());
    // A missing file or a directory is reported as such whatever its name.
    let meta = std::fs::metadata(path).map_err(|source| IoError::Read { path: path.to_path_buf(), source })?;
    if meta.is_dir() {
        return Err(IoError::IsDirectory { path: path.to_path_buf() });
    }
    let Some(format) = format else {
        return Err(IoError::UnknownFormat {
            path: path.to_path_buf(),
            ext: path.extension().map(|e| e.to_string_lossy().into_owned()),
            known: READ_EXTENSIONS.to_string(),
        });
    };
    let mut loaded = match format {
        Format::Stl => stl::read(path, &read_bytes(path)?)?,
        Format::Obj => obj::read(path, &read_bytes(path)?)?,
        Format::Gltf | Format::Glb => gltf::read(path, &read_bytes(path)?)?,
        Format::Off => off::read(path, &read_bytes(path)?)?,
        Format::Medit => medit::read(path, &read_bytes(path)?)?,
        Format::TetGen => tetgen::read(path)?,
        Format::Msh => msh::read(path, &read_bytes(path)?)?,
        Format::Xyz => xyz::read(path, &read_bytes(path)?)?,
        Format::Vtu => unreachable!("filtered by can_read"),
    };
    if let (MeshData::Surface(s), Some(tol)) = (&mut loaded.mesh, options.weld) {
        let r = s.weld(tol);
        if r.merged > 0 {
            loaded.notes.push(format!("welded {} vertices into {}", r.vertices_before, r.vertices_before - r.merged));
        }
        if r.collapsed_triangles > 0 {
            loaded.notes.push(format!("dropped {} triangles that collapsed when welding", r.collapsed_triangles));
        }
        if r.unused_vertices > 0 {
            loaded.notes.push(format!("dropped {} vertices used by no triangle", r.unused_vertices));
        }
    }
    let checked = match &loaded.mesh {
        MeshData::Surface(s) => s.validate(),
        MeshData::Volume(m) => m.validate(),
        MeshData::Points(p) => crate::mesh::tri_surface::check_finite(p),
    };
    checked.map_err(|source| IoError::Invalid { path: path.to_path_buf(), source })?;
    Ok(loaded)
}

/// Reads a point set: `.xyz`, or the points of a TetGen `.node` (its elements, if any, are not
/// read).
///
/// # Errors
/// An [`IoError`] naming the file and line, or [`IoError::UnknownFormat`] for other extensions.
pub fn read_points(path: &Path) -> Result<Vec<DVec3>, IoError> {
    let ext = path.extension().and_then(|e| e.to_str()).map(|e| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some("xyz") => xyz::read_points(path, &point_lines::read_file(path)?),
        Some("node") => tetgen::read_node_points(path),
        _ => Err(IoError::UnknownFormat { path: path.to_path_buf(), ext, known: ".xyz .node".to_string() }),
    }
}

/// Writes `mesh` to `path` in the format of its extension, through a temporary file.
///
/// # Errors
/// [`IoError::UnknownFormat`] for an extension fepre does not write,
/// [`IoError::NotRepresentable`] where the format cannot hold the data (tetrahedra to STL),
/// [`IoError::Write`] for file-system failures. On error no file is left at `path`.
pub fn write(path: &Path, mesh: &MeshData, options: &WriteOptions) -> Result<(), IoError> {
    write_ref(path, mesh.as_ref(), options)
}

/// [`write()`] of a borrowed mesh.
///
/// # Errors
/// As [`write()`].
pub fn write_ref(path: &Path, mesh: MeshRef<'_>, options: &WriteOptions) -> Result<(), IoError> {
    let Some(format) = Format::from_path(path).filter(|f| f.can_write()) else {
        return Err(IoError::UnknownFormat {
            path: path.to_path_buf(),
            ext: path.extension().map(|e| e.to_string_lossy().into_owned()),
            known: WRITE_EXTENSIONS.to_string(),
        });
    };
    let not = |what: &str| IoError::NotRepresentable { path: path.to_path_buf(), format: format.name(), what: what.to_string() };
    match (format, mesh) {
        (Format::Stl, MeshRef::Surface(s)) => stl::write(path, s, options),
        (Format::Obj, MeshRef::Surface(s)) => obj::write(path, s),
        (Format::Off, MeshRef::Surface(s)) => off::write(path, s),
        (Format::Medit, MeshRef::Surface(s)) => medit::write_surface(path, s),
        (Format::Medit, MeshRef::Volume(m)) => medit::write_volume(path, m),
        (Format::TetGen, MeshRef::Surface(s)) => tetgen::write_surface(path, s),
        (Format::TetGen, MeshRef::Volume(m)) => tetgen::write_volume(path, m),
        (Format::TetGen, MeshRef::Points(p)) => tetgen::write_points(path, p),
        (Format::Msh, MeshRef::Surface(s)) => msh::write_surface(path, s),
        (Format::Msh, MeshRef::Volume(m)) => msh::write_volume(path, m),
        (Format::Msh, MeshRef::Mixed(s)) => msh::write_mixed(path, s),
        (Format::Vtu, MeshRef::Mixed(s)) => vtu::write_mixed(path, s, options),
        (Format::Medit, MeshRef::Mixed(s)) => medit::write_mixed(path, s),
        (Format::Stl | Format::Obj | Format::Off, MeshRef::Mixed(s)) => write_ref(path, MeshRef::Surface(&s.to_triangles()), options),
        (Format::Vtu, MeshRef::Surface(s)) => vtu::write_surface(path, s, options),
        (Format::Vtu, MeshRef::Volume(m)) => vtu::write_volume(path, m, options),
        (Format::Stl | Format::Obj | Format::Off, MeshRef::Volume(_)) => {
            Err(not("a tetrahedral mesh (write its boundary with a surface format, or use .mesh, .msh, .vtu, .node)"))
        }
        (_, m) => Err(not(&format!("a {}", m.kind()))),
    }
}
