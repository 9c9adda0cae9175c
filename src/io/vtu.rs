//! VTK XML unstructured grid (`.vtu`), for viewing in ParaView and reading with meshio.
//!
//! Binary by default: every array is inline base64 of an 8-byte little-endian byte count
//! (`header_type="UInt64"`) followed by the little-endian data, encoded as one stream, as
//! VTK writes it. ASCII with [`WriteOptions::ascii`].
//!
//! Points are `Float64`. A surface is written as triangles (VTK type 5); a tet mesh as its
//! tets (type 10) followed by its boundary triangles (type 5). Cell data:
//! - `tag` (`Int32`): the face tag of a triangle, the region tag of a tet;
//! - `cell_kind` (`UInt8`, tet meshes only): 3 for a tet, 2 for a boundary triangle, to
//!   threshold one or the other away in ParaView.
//!
//! Tag names have no standard place in VTU and are not written.
//!
//! FE results go through [`write_grid_with_data`]: a [`Grid`] of linear (VTK type 10) or
//! quadratic (type 24) tets and optional triangles, with any number of named `Float64` point
//! and cell arrays and `Int32` cell arrays, checked for length before anything is written.

use crate::core::{FaceId, RegionId};
use crate::io::atomic::{write_atomic, write_err};
use crate::io::common::Num;
use crate::io::{IoError, WriteOptions};
use crate::mesh::{MixedSurface, TetMesh, TriSurface};
use base64::Engine;
use glam::DVec3;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

const VTK_TRIANGLE: u8 = 5;
const VTK_QUAD: u8 = 9;
const VTK_TETRA: u8 = 10;
const VTK_QUADRATIC_TETRA: u8 = 24;

/// Writes a surface: triangles with a `tag` cell array.
///
/// # Errors
/// [`IoError::NotRepresentable`] for a tag above `i32::MAX`, [`IoError::Write`].
pub fn write_surface(path: &Path, s: &TriSurface, options: &WriteOptions) -> Result<(), IoError> {
    let cells = Cells { tets: &[], tet_tags: &[], tris: &s.triangles, tri_tags: &s.face_tags, quads: &[], quad_tags: &[], kind: false };
    write_grid(path, &s.vertices, &cells, options)
}

/// Writes a surface of triangles and quads (VTK types 5 and 9), with a `tag` cell array.
///
/// # Errors
/// [`IoError::NotRepresentable`] for a tag above `i32::MAX`, [`IoError::Write`].
pub fn write_mixed(path: &Path, s: &MixedSurface, options: &WriteOptions) -> Result<(), IoError> {
    let cells = Cells { tets: &[], tet_tags: &[], tris: &s.triangles, tri_tags: &s.triangle_tags, quads: &s.quads, quad_tags: &s.quad_tags, kind: false };
    write_grid(path, &s.vertices, &cells, options)
}

/// Writes a tet mesh: tets then boundary triangles, with `tag` and `cell_kind` cell arrays.
///
/// # Errors
/// [`IoError::NotRepresentable`] for a tag above `i32::MAX`, [`IoError::Write`].
pub fn write_volume(path: &Path, m: &TetMesh, options: &WriteOptions) -> Result<(), IoError> {
    let cells = Cells { tets: &m.tets, tet_tags: &m.region_tags, tris: &m.boundary, tri_tags: &m.face_tags, quads: &[], quad_tags: &[], kind: true };
    write_grid(path, &m.vertices, &cells, options)
}

/// A named array of `Float64` values on the points or the cells of a [`Grid`]: `components`
/// values per point (or cell), point by point; `values.len()` is the count of points (or
/// cells) times `components`. One component is a scalar, three a vector, six a symmetric
/// tensor as CalculiX orders it.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct FieldArray<'a> {
    /// The array's name as ParaView shows it.
    pub name: &'a str,
    /// Values per point or cell, at least 1.
    pub components: usize,
    /// The values, entity by entity.
    pub values: &'a [f64],
}

/// A grid of FE results for [`write_grid_with_data`]: points, linear or quadratic tets, optional
/// triangles, and named arrays on the points and the cells.
///
/// Cells are the tets, then the triangles; cell arrays run over them in that order. A
/// quadratic tet lists its corners 0–3 and then the nodes on its edges (0,1), (1,2), (0,2),
/// (0,3), (1,3), (2,3): the Abaqus/CalculiX C3D10 order, which is VTK's `VTK_QUADRATIC_TETRA`.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid<'a> {
    /// The points (nodes), written as `Float64`.
    pub points: &'a [DVec3],
    /// #T × `nodes_per_tet` point indices, tet by tet.
    pub tets: &'a [u32],
    /// 4 (linear tets, VTK type 10) or 10 (quadratic tets, VTK type 24).
    pub nodes_per_tet: usize,
    /// Triangles (VTK type 5) written after the tets, e.g. the boundary faces.
    pub triangles: &'a [[u32; 3]],
    /// `Float64` arrays with `components` values per point.
    pub point_data: Vec<FieldArray<'a>>,
    /// `Float64` arrays with `components` values per cell.
    pub cell_data: Vec<FieldArray<'a>>,
    /// `Int32` arrays with one value per cell (region tags, element numbers).
    pub cell_ints: Vec<(&'a str, &'a [i32])>,
}

impl<'a> Grid<'a> {
    /// A grid of `points` and tets of `nodes_per_tet` (4 or 10) nodes each, with no triangles
    /// and no data.
    pub fn new(points: &'a [DVec3], tets: &'a [u32], nodes_per_tet: usize) -> Self {
        Grid { points, tets, nodes_per_tet, triangles: &[], point_data: Vec::new(), cell_data: Vec::new(), cell_ints: Vec::new() }
    }

    /// Sets [`Grid::triangles`].
    pub fn with_triangles(mut self, triangles: &'a [[u32; 3]]) -> Self {
        self.triangles = triangles;
        self
    }

    /// Adds a point array of `components` values per point.
    pub fn with_point_data(mut self, name: &'a str, components: usize, values: &'a [f64]) -> Self {
        self.point_data.push(FieldArray { name, components, values });
        self
    }

    /// Adds a `Float64` cell array of `components` values per cell.
    pub fn with_cell_data(mut self, name: &'a str, components: usize, values: &'a [f64]) -> Self {
        self.cell_data.push(FieldArray { name, components, values });
        self
    }

    /// Adds an `Int32` cell array of one value per cell.
    pub fn with_cell_ints(mut self, name: &'a str, values: &'a [i32]) -> Self {
        self.cell_ints.push((name, values));
        self
    }

    /// The number of cells: tets and triangles.
    pub fn cell_count(&self) -> usize {
        self.tets.len() / self.nodes_per_tet.max(1) + self.triangles.len()
    }

    /// Checks the shapes: `nodes_per_tet` is 4 or 10 and divides `tets.len()`, every index
    /// names a point, every array has entities × components values, names are non-empty and
    /// unique among the point arrays and among the cell arrays.
    ///
    /// # Errors
    /// [`IoError::InvalidData`] naming the array or the cell, with `path` as the file.
    pub fn check(&self, path: &Path) -> Result<(), IoError> {
        let bad = |message: String| IoError::InvalidData { path: path.to_path_buf(), message };
        let npt = self.nodes_per_tet;
        if npt != 4 && npt != 10 {
            return Err(bad(format!("tets of {npt} nodes (VTU results take 4 for linear tets, 10 for quadratic ones)")));
        }
        if self.tets.len() % npt != 0 {
            return Err(bad(format!("{} tet indices are not a whole number of {npt}-node tets", self.tets.len())));
        }
        let np = self.points.len();
        let out_of_range = |cell: &str, i: usize, node: usize, v: u32| bad(format!("{cell} {i} node {node} is point {v}, but there are {np} points"));
        for (i, t) in self.tets.chunks(npt).enumerate() {
            if let Some((k, &v)) = t.iter().enumerate().find(|(_, v)| **v as usize >= np) {
                return Err(out_of_range("tet", i, k, v));
            }
        }
        for (i, t) in self.triangles.iter().enumerate() {
            if let Some((k, &v)) = t.iter().enumerate().find(|(_, v)| **v as usize >= np) {
                return Err(out_of_range("triangle", i, k, v));
            }
        }
        let nc = self.cell_count();
        let shape = |kind: &str, a: &FieldArray, n: usize, what: &str| -> Result<(), IoError> {
            if a.components == 0 {
                return Err(bad(format!("{kind} array '{}' has 0 components", a.name)));
            }
            let want = n.checked_mul(a.components).unwrap_or(usize::MAX);
            if a.values.len() != want {
                return Err(bad(format!(
                    "{kind} array '{}' has {} values; {n} {what} × {} components need {want}",
                    a.name,
                    a.values.len(),
                    a.components
                )));
            }
            Ok(())
        };
        for a in &self.point_data {
            shape("point", a, np, "points")?;
        }
        for a in &self.cell_data {
            shape("cell", a, nc, "cells")?;
        }
        for (name, v) in &self.cell_ints {
            if v.len() != nc {
                return Err(bad(format!("cell array '{name}' has {} values for {nc} cells", v.len())));
            }
        }
        let unique = |kind: &str, names: Vec<&str>| -> Result<(), IoError> {
            for (i, n) in names.iter().enumerate() {
                if n.is_empty() {
                    return Err(bad(format!("{kind} array {i} has no name")));
                }
                if names[..i].contains(n) {
                    return Err(bad(format!("two {kind} arrays are named '{n}'")));
                }
            }
            Ok(())
        };
        unique("point", self.point_data.iter().map(|a| a.name).collect())?;
        unique("cell", self.cell_data.iter().map(|a| a.name).chain(self.cell_ints.iter().map(|(n, _)| *n)).collect())
    }
}

/// Writes FE results: the grid's points, its tets (VTK type 10, or 24 for 10-node tets) then
/// its triangles (type 5), its point arrays and its cell arrays. Binary unless
/// [`WriteOptions::ascii`].
///
/// # Errors
/// [`IoError::InvalidData`] from [`Grid::check`] (nothing is written), [`IoError::Write`].
pub fn write_grid_with_data(path: &Path, g: &Grid, options: &WriteOptions) -> Result<(), IoError> {
    g.check(path)?;
    let npt = g.nodes_per_tet;
    let ntets = g.tets.len() / npt;
    let mut conn: Vec<i64> = Vec::with_capacity(g.tets.len() + 3 * g.triangles.len());
    conn.extend(g.tets.iter().map(|&v| v as i64));
    conn.extend(g.triangles.iter().flatten().map(|&v| v as i64));
    let offsets: Vec<i64> = (1..=ntets).map(|i| (i * npt) as i64).chain((1..=g.triangles.len()).map(|i| (ntets * npt + 3 * i) as i64)).collect();
    let tet_type = if npt == 10 { VTK_QUADRATIC_TETRA } else { VTK_TETRA };
    let types: Vec<u8> = std::iter::repeat_n(tet_type, ntets).chain(std::iter::repeat_n(VTK_TRIANGLE, g.triangles.len())).collect();
    let coords: Vec<f64> = g.points.iter().flat_map(|p| p.to_array()).collect();
    fn float<'b>(a: &FieldArray<'b>) -> Array<'b> {
        Array { name: a.name, components: a.components, values: Values::F64(a.values) }
    }
    let piece = Piece {
        coords: &coords,
        conn: &conn,
        offsets: &offsets,
        types: &types,
        point_arrays: g.point_data.iter().map(float).collect(),
        cell_arrays: g.cell_data.iter().map(float).chain(g.cell_ints.iter().map(|(name, v)| Array { name, components: 1, values: Values::I32(v) })).collect(),
        cell_scalars: None,
    };
    write_piece(path, &piece, options.ascii)
}

struct Cells<'a> {
    tets: &'a [[u32; 4]],
    tet_tags: &'a [RegionId],
    tris: &'a [[u32; 3]],
    tri_tags: &'a [FaceId],
    quads: &'a [[u32; 4]],
    quad_tags: &'a [FaceId],
    /// Write `cell_kind`.
    kind: bool,
}

/// Values of one data array, as written in either encoding.
enum Values<'a> {
    F64(&'a [f64]),
    I64(&'a [i64]),
    I32(&'a [i32]),
    U8(&'a [u8]),
}

impl Values<'_> {
    fn vtk_type(&self) -> &'static str {
        match self {
            Values::F64(_) => "Float64",
            Values::I64(_) => "Int64",
            Values::I32(_) => "Int32",
            Values::U8(_) => "UInt8",
        }
    }

    /// The binary block: the byte count as a little-endian `u64`, then the data.
    fn block(&self) -> Vec<u8> {
        let size = match self {
            Values::F64(v) => 8 * v.len(),
            Values::I64(v) => 8 * v.len(),
            Values::I32(v) => 4 * v.len(),
            Values::U8(v) => v.len(),
        };
        let mut b = Vec::with_capacity(8 + size);
        b.extend((size as u64).to_le_bytes());
        match self {
            Values::F64(v) => v.iter().for_each(|x| b.extend(x.to_le_bytes())),
            Values::I64(v) => v.iter().for_each(|x| b.extend(x.to_le_bytes())),
            Values::I32(v) => v.iter().for_each(|x| b.extend(x.to_le_bytes())),
            Values::U8(v) => b.extend_from_slice(v),
        }
        b
    }

    fn write_ascii(&self, w: &mut BufWriter<File>, per_line: usize) -> std::io::Result<()> {
        fn lines<T>(w: &mut BufWriter<File>, v: &[T], per_line: usize, f: impl Fn(&T) -> String) -> std::io::Result<()> {
            for chunk in v.chunks(per_line.max(1)) {
                let line: Vec<String> = chunk.iter().map(&f).collect();
                writeln!(w, "          {}", line.join(" "))?;
            }
            Ok(())
        }
        match self {
            Values::F64(v) => lines(w, v, per_line, |x| Num(*x).to_string()),
            Values::I64(v) => lines(w, v, per_line, |x| x.to_string()),
            Values::I32(v) => lines(w, v, per_line, |x| x.to_string()),
            Values::U8(v) => lines(w, v, per_line, |x| x.to_string()),
        }
    }
}

fn data_array(w: &mut BufWriter<File>, name: &str, components: usize, values: &Values, ascii: bool) -> std::io::Result<()> {
    let name = xml_escape(name);
    let comps = if components > 1 { format!(" NumberOfComponents=\"{components}\"") } else { String::new() };
    let format = if ascii { "ascii" } else { "binary" };
    writeln!(w, "        <DataArray type=\"{}\" Name=\"{name}\"{comps} format=\"{format}\">", values.vtk_type())?;
    if ascii {
        values.write_ascii(w, if components > 1 { components } else { 12 })?;
    } else {
        writeln!(w, "          {}", base64::engine::general_purpose::STANDARD.encode(values.block()))?;
    }
    writeln!(w, "        </DataArray>")
}

/// `text` with the characters that XML attributes may not hold as entities.
fn xml_escape(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.contains(['&', '<', '>', '"']) {
        return text.into();
    }
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;").into()
}

fn tag_i32(path: &Path, t: u32) -> Result<i32, IoError> {
    i32::try_from(t).map_err(|_| IoError::NotRepresentable {
        path: path.to_path_buf(),
        format: "VTU",
        what: format!("tag {t} (Int32 cell data holds at most 2147483647)"),
    })
}

fn write_grid(path: &Path, vertices: &[DVec3], c: &Cells, options: &WriteOptions) -> Result<(), IoError> {
    let ncells = c.tets.len() + c.tris.len() + c.quads.len();
    let mut conn = Vec::with_capacity(4 * c.tets.len() + 3 * c.tris.len());
    let mut offsets = Vec::with_capacity(ncells);
    let mut types = Vec::with_capacity(ncells);
    let mut tags = Vec::with_capacity(ncells);
    for (t, r) in c.tets.iter().zip(c.tet_tags) {
        conn.extend(t.iter().map(|&v| v as i64));
        offsets.push(conn.len() as i64);
        types.push(VTK_TETRA);
        tags.push(tag_i32(path, r.0)?);
    }
    for (t, f) in c.tris.iter().zip(c.tri_tags) {
        conn.extend(t.iter().map(|&v| v as i64));
        offsets.push(conn.len() as i64);
        types.push(VTK_TRIANGLE);
        tags.push(tag_i32(path, f.0)?);
    }
    for (q, f) in c.quads.iter().zip(c.quad_tags) {
        conn.extend(q.iter().map(|&v| v as i64));
        offsets.push(conn.len() as i64);
        types.push(VTK_QUAD);
        tags.push(tag_i32(path, f.0)?);
    }
    let kind: Vec<u8> = types.iter().map(|&t| if t == VTK_TETRA { 3 } else { 2 }).collect();
    let coords: Vec<f64> = vertices.iter().flat_map(|p| p.to_array()).collect();
    let mut cell_arrays = vec![Array { name: "tag", components: 1, values: Values::I32(&tags) }];
    if c.kind {
        cell_arrays.push(Array { name: "cell_kind", components: 1, values: Values::U8(&kind) });
    }
    let piece = Piece { coords: &coords, conn: &conn, offsets: &offsets, types: &types, point_arrays: Vec::new(), cell_arrays, cell_scalars: Some("tag") };
    write_piece(path, &piece, options.ascii)
}

/// A named data array as written.
struct Array<'a> {
    name: &'a str,
    components: usize,
    values: Values<'a>,
}

/// One unstructured-grid piece, ready to write.
struct Piece<'a> {
    /// Point coordinates, three per point.
    coords: &'a [f64],
    conn: &'a [i64],
    offsets: &'a [i64],
    types: &'a [u8],
    point_arrays: Vec<Array<'a>>,
    cell_arrays: Vec<Array<'a>>,
    /// The cell array named as the active scalars, if any.
    cell_scalars: Option<&'a str>,
}

fn write_piece(path: &Path, p: &Piece, ascii: bool) -> Result<(), IoError> {
    write_atomic(path, |w| {
        let e = write_err(path);
        let body = |w: &mut BufWriter<File>| -> std::io::Result<()> {
            writeln!(w, "<?xml version=\"1.0\"?>")?;
            writeln!(w, "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">")?;
            writeln!(w, "  <UnstructuredGrid>")?;
            writeln!(w, "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">", p.coords.len() / 3, p.types.len())?;
            if !p.point_arrays.is_empty() {
                writeln!(w, "      <PointData>")?;
                for a in &p.point_arrays {
                    data_array(w, a.name, a.components, &a.values, ascii)?;
                }
                writeln!(w, "      </PointData>")?;
            }
            writeln!(w, "      <Points>")?;
            data_array(w, "Points", 3, &Values::F64(p.coords), ascii)?;
            writeln!(w, "      </Points>")?;
            writeln!(w, "      <Cells>")?;
            data_array(w, "connectivity", 1, &Values::I64(p.conn), ascii)?;
            data_array(w, "offsets", 1, &Values::I64(p.offsets), ascii)?;
            data_array(w, "types", 1, &Values::U8(p.types), ascii)?;
            writeln!(w, "      </Cells>")?;
            if !p.cell_arrays.is_empty() {
                match p.cell_scalars {
                    Some(s) => writeln!(w, "      <CellData Scalars=\"{}\">", xml_escape(s))?,
                    None => writeln!(w, "      <CellData>")?,
                }
                for a in &p.cell_arrays {
                    data_array(w, a.name, a.components, &a.values, ascii)?;
                }
                writeln!(w, "      </CellData>")?;
            }
            writeln!(w, "    </Piece>")?;
            writeln!(w, "  </UnstructuredGrid>")?;
            writeln!(w, "</VTKFile>")
        };
        body(w).map_err(&e)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::io::test_meshes::two_tets;

    /// The text between `<DataArray … Name="name" …>` and `</DataArray>`.
    fn array<'a>(xml: &'a str, name: &str) -> &'a str {
        let start = xml.find(&format!("Name=\"{name}\"")).unwrap();
        let open = start + xml[start..].find('>').unwrap() + 1;
        let close = open + xml[open..].find("</DataArray>").unwrap();
        xml[open..close].trim()
    }

    #[test]
    fn binary_arrays_carry_their_byte_count() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("v.vtu");
        let m = two_tets();
        write_volume(&p, &m, &WriteOptions::default()).unwrap();
        let xml = std::fs::read_to_string(&p).unwrap();
        assert!(xml.contains("NumberOfPoints=\"5\" NumberOfCells=\"8\""), "{xml}");
        let decode = |name| base64::engine::general_purpose::STANDARD.decode(array(&xml, name)).unwrap();
        let types = decode("types");
        assert_eq!(u64::from_le_bytes(types[..8].try_into().unwrap()), 8);
        assert_eq!(&types[8..], &[10, 10, 5, 5, 5, 5, 5, 5]);
        let tags = decode("tag");
        let tags: Vec<i32> = tags[8..].chunks(4).map(|c| i32::from_le_bytes(c.try_into().unwrap())).collect();
        assert_eq!(tags, vec![1, 2, 0, 1, 2, 0, 1, 2]);
        let pts = decode("Points");
        assert_eq!(pts.len(), 8 + 5 * 24);
        assert_eq!(f64::from_le_bytes(pts[8 + 13 * 8..8 + 14 * 8].try_into().unwrap()), 1.0, "z of vertex 4");
    }

    #[test]
    fn ascii_surface() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("s.vtu");
        let m = two_tets();
        let s = TriSurface { vertices: m.vertices, triangles: m.boundary, face_tags: m.face_tags, ..Default::default() };
        write_surface(&p, &s, &WriteOptions::default().with_ascii(true)).unwrap();
        let xml = std::fs::read_to_string(&p).unwrap();
        assert_eq!(array(&xml, "offsets").split_whitespace().last(), Some("18"));
        assert_eq!(array(&xml, "types").split_whitespace().count(), 6);
        assert_eq!(array(&xml, "Points").lines().nth(4).map(str::trim), Some("1 1 1"));
        assert!(!xml.contains("cell_kind"));
        let mut s2 = s.clone();
        s2.face_tags[0] = FaceId(u32::MAX);
        let e = write_surface(&p, &s2, &WriteOptions::default()).unwrap_err();
        assert!(matches!(e, IoError::NotRepresentable { .. }), "{e}");
        assert_eq!(std::fs::read_to_string(&p).unwrap(), xml, "a failed write leaves the old file");
    }

    /// The unit tet with its six mid-edge nodes in C3D10 order.
    fn quadratic_tet() -> (Vec<DVec3>, Vec<u32>) {
        let c = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let mut p = c.to_vec();
        for (a, b) in [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)] {
            p.push((c[a] + c[b]) / 2.0);
        }
        (p, (0..10).collect())
    }

    fn decode(xml: &str, name: &str) -> Vec<u8> {
        let b = base64::engine::general_purpose::STANDARD.decode(array(xml, name)).unwrap();
        assert_eq!(u64::from_le_bytes(b[..8].try_into().unwrap()) as usize, b.len() - 8, "{name}: byte count");
        b[8..].to_vec()
    }

    fn f64s(b: &[u8]) -> Vec<f64> {
        b.chunks(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect()
    }

    #[test]
    fn quadratic_tet_with_point_and_cell_arrays() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("r.vtu");
        let (pts, tet) = quadratic_tet();
        let disp: Vec<f64> = pts.iter().flat_map(|q| [q.x, 2.0 * q.y, -q.z]).collect();
        let temp: Vec<f64> = pts.iter().map(|q| q.x + 10.0).collect();
        let tris = [[0u32, 2, 1]];
        let vm = [150.0, 0.0];
        let region = [7, -1];
        let g = Grid::new(&pts, &tet, 10)
            .with_triangles(&tris)
            .with_point_data("DISP", 3, &disp)
            .with_point_data("NT \"C\"", 1, &temp)
            .with_cell_data("von Mises", 1, &vm)
            .with_cell_ints("region", &region);
        write_grid_with_data(&p, &g, &WriteOptions::default()).unwrap();
        let xml = std::fs::read_to_string(&p).unwrap();
        assert!(xml.contains("NumberOfPoints=\"10\" NumberOfCells=\"2\""), "{xml}");
        assert!(xml.contains("<DataArray type=\"Float64\" Name=\"DISP\" NumberOfComponents=\"3\" format=\"binary\">"), "{xml}");
        assert!(xml.contains("Name=\"NT &quot;C&quot;\""), "names are escaped: {xml}");
        assert_eq!(decode(&xml, "types"), [24, 5]);
        let offsets: Vec<i64> = decode(&xml, "offsets").chunks(8).map(|c| i64::from_le_bytes(c.try_into().unwrap())).collect();
        assert_eq!(offsets, [10, 13]);
        assert_eq!(f64s(&decode(&xml, "DISP")), disp);
        assert_eq!(f64s(&decode(&xml, "von Mises")), vm);
        let r: Vec<i32> = decode(&xml, "region").chunks(4).map(|c| i32::from_le_bytes(c.try_into().unwrap())).collect();
        assert_eq!(r, region);
        assert!(xml.find("<PointData>").unwrap() < xml.find("<Points>").unwrap());

        // ASCII: one point per line for a vector, 12 scalars per line
        let a = dir.path().join("a.vtu");
        write_grid_with_data(&a, &g, &WriteOptions::default().with_ascii(true)).unwrap();
        let xml = std::fs::read_to_string(&a).unwrap();
        assert_eq!(array(&xml, "DISP").lines().nth(1).map(str::trim), Some("1 0 -0"));
        assert_eq!(array(&xml, "connectivity").split_whitespace().count(), 13);
        assert_eq!(array(&xml, "types"), "24 5");
        assert_eq!(array(&xml, "region"), "7 -1");
    }

    #[test]
    fn inconsistent_grids_are_refused_naming_the_array() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("bad.vtu");
        let (pts, tet) = quadratic_tet();
        let short = vec![0.0; 29];
        let ok = vec![0.0; 30];
        let err = |g: &Grid| {
            let e = write_grid_with_data(&p, g, &WriteOptions::default()).unwrap_err();
            assert!(matches!(e, IoError::InvalidData { .. }), "{e}");
            assert!(!p.exists(), "nothing written");
            e.to_string()
        };
        let e = err(&Grid::new(&pts, &tet, 10).with_point_data("DISP", 3, &ok).with_point_data("S", 3, &short));
        assert!(e.ends_with("cannot write: point array 'S' has 29 values; 10 points × 3 components need 30"), "{e}");
        let e = err(&Grid::new(&pts, &tet, 10).with_cell_data("E", 2, &ok));
        assert!(e.contains("cell array 'E' has 30 values; 1 cells × 2 components need 2"), "{e}");
        let e = err(&Grid::new(&pts, &tet, 10).with_cell_ints("tag", &[1, 2]));
        assert!(e.contains("cell array 'tag' has 2 values for 1 cells"), "{e}");
        let e = err(&Grid::new(&pts, &tet, 8));
        assert!(e.contains("tets of 8 nodes"), "{e}");
        let e = err(&Grid::new(&pts, &[0, 1, 2, 12], 4));
        assert!(e.contains("tet 0 node 3 is point 12, but there are 10 points"), "{e}");
        let e = err(&Grid::new(&pts[..4], &tet[..4], 4).with_triangles(&[[0, 1, 9]]));
        assert!(e.contains("triangle 0 node 2 is point 9, but there are 4 points"), "{e}");
        let e = err(&Grid::new(&pts, &tet[..9], 4));
        assert!(e.contains("9 tet indices are not a whole number of 4-node tets"), "{e}");
        let e = err(&Grid::new(&pts, &tet, 10).with_point_data("T", 1, &ok[..10]).with_point_data("T", 1, &ok[..10]));
        assert!(e.contains("two point arrays are named 'T'"), "{e}");
        let e = err(&Grid::new(&pts, &tet, 10).with_cell_data("id", 1, &[1.0]).with_cell_ints("id", &[1]));
        assert!(e.contains("two cell arrays are named 'id'"), "{e}");
        let e = err(&Grid::new(&pts, &tet, 10).with_point_data("X", 0, &[]));
        assert!(e.contains("point array 'X' has 0 components"), "{e}");
    }
}
