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

use crate::core::{FaceId, RegionId};
use crate::io::atomic::{write_atomic, write_err};
use crate::io::common::Num;
use crate::io::{IoError, WriteOptions};
use crate::mesh::{TetMesh, TriSurface};
use base64::Engine;
use glam::DVec3;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

const VTK_TRIANGLE: u8 = 5;
const VTK_TETRA: u8 = 10;

/// Writes a surface: triangles with a `tag` cell array.
///
/// # Errors
/// [`IoError::NotRepresentable`] for a tag above `i32::MAX`, [`IoError::Write`].
pub fn write_surface(path: &Path, s: &TriSurface, options: &WriteOptions) -> Result<(), IoError> {
    let cells = Cells { tets: &[], tet_tags: &[], tris: &s.triangles, tri_tags: &s.face_tags, kind: false };
    write_grid(path, &s.vertices, &cells, options)
}

/// Writes a tet mesh: tets then boundary triangles, with `tag` and `cell_kind` cell arrays.
///
/// # Errors
/// [`IoError::NotRepresentable`] for a tag above `i32::MAX`, [`IoError::Write`].
pub fn write_volume(path: &Path, m: &TetMesh, options: &WriteOptions) -> Result<(), IoError> {
    let cells = Cells { tets: &m.tets, tet_tags: &m.region_tags, tris: &m.boundary, tri_tags: &m.face_tags, kind: true };
    write_grid(path, &m.vertices, &cells, options)
}

struct Cells<'a> {
    tets: &'a [[u32; 4]],
    tet_tags: &'a [RegionId],
    tris: &'a [[u32; 3]],
    tri_tags: &'a [FaceId],
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

fn tag_i32(path: &Path, t: u32) -> Result<i32, IoError> {
    i32::try_from(t).map_err(|_| IoError::NotRepresentable {
        path: path.to_path_buf(),
        format: "VTU",
        what: format!("tag {t} (Int32 cell data holds at most 2147483647)"),
    })
}

fn write_grid(path: &Path, vertices: &[DVec3], c: &Cells, options: &WriteOptions) -> Result<(), IoError> {
    let ncells = c.tets.len() + c.tris.len();
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
    let kind: Vec<u8> = types.iter().map(|&t| if t == VTK_TETRA { 3 } else { 2 }).collect();
    let coords: Vec<f64> = vertices.iter().flat_map(|p| p.to_array()).collect();
    let ascii = options.ascii;
    write_atomic(path, |w| {
        let e = write_err(path);
        let body = |w: &mut BufWriter<File>| -> std::io::Result<()> {
            writeln!(w, "<?xml version=\"1.0\"?>")?;
            writeln!(w, "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">")?;
            writeln!(w, "  <UnstructuredGrid>")?;
            writeln!(w, "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{ncells}\">", vertices.len())?;
            writeln!(w, "      <Points>")?;
            data_array(w, "Points", 3, &Values::F64(&coords), ascii)?;
            writeln!(w, "      </Points>")?;
            writeln!(w, "      <Cells>")?;
            data_array(w, "connectivity", 1, &Values::I64(&conn), ascii)?;
            data_array(w, "offsets", 1, &Values::I64(&offsets), ascii)?;
            data_array(w, "types", 1, &Values::U8(&types), ascii)?;
            writeln!(w, "      </Cells>")?;
            writeln!(w, "      <CellData Scalars=\"tag\">")?;
            data_array(w, "tag", 1, &Values::I32(&tags), ascii)?;
            if c.kind {
                data_array(w, "cell_kind", 1, &Values::U8(&kind), ascii)?;
            }
            writeln!(w, "      </CellData>")?;
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
}
