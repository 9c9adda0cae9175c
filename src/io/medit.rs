//! Medit / INRIA `.mesh`, ASCII.
//!
//! Read: `MeshVersionFormatted` 1 to 4, `Dimension 3`, `Vertices`, `Triangles`, `Tetrahedra`
//! (and their quadratic forms `TrianglesP2`, `TetrahedraP2`, of which the corners are kept),
//! `End`; keywords are case-insensitive, `#` starts a comment, sections may come in any order.
//! Other known sections (`Edges`, `Corners`, `Ridges`, `Required*`, `Normals`,
//! `Quadrilaterals`, `Hexahedra`, …) are skipped with a note; an unknown keyword is an error,
//! because its entries cannot be skipped without knowing their size.
//!
//! A file with tetrahedra is a [`MeshData::Volume`]: each tet's reference becomes its region
//! tag, the triangles become the tagged boundary (oriented outward), and negatively oriented
//! tets are reoriented with a note. Without tetrahedra the triangles make a
//! [`MeshData::Surface`] tagged by their references; vertices alone make a point set.
//!
//! Written: `MeshVersionFormatted 2`, vertices with reference 0, triangles with their tag as
//! reference, tets with their region tag. Medit has no names: tag names are not written.

use crate::core::{FaceId, RegionId};
use crate::io::atomic::{write_atomic, write_err};
use crate::io::common::{Num, orient_tets, unused_vertices_note, write_int_line, write_lines};
use crate::io::text::Tokens;
use crate::io::{Format, IoError, Loaded, Location, MeshData};
use crate::mesh::{MixedSurface, TetMesh, TriSurface};
use glam::DVec3;
use std::io::Write;
use std::path::Path;

/// Sections skipped with a note: keyword (lower case) and numbers per entry.
const SKIPPED: &[(&str, usize)] = &[
    ("edges", 3),
    ("edgesp2", 4),
    ("corners", 1),
    ("ridges", 1),
    ("requiredvertices", 1),
    ("requirededges", 1),
    ("requiredtriangles", 1),
    ("requiredquadrilaterals", 1),
    ("requiredtetrahedra", 1),
    ("normals", 3),
    ("tangents", 3),
    ("normalatvertices", 2),
    ("normalattrianglevertices", 3),
    ("normalatquadrilateralvertices", 3),
    ("tangentatedges", 3),
    ("tangentatvertices", 2),
    ("quadrilaterals", 5),
    ("quadrilateralsq2", 10),
    ("hexahedra", 9),
    ("hexahedraq2", 28),
    ("prisms", 7),
    ("pyramids", 6),
];

/// Elements of one kind as read: corner indices (0-based), references, and the largest
/// 1-based index seen with its line, checked once the vertex count is known.
struct Elements<const N: usize> {
    corners: Vec<[u32; N]>,
    refs: Vec<u32>,
    max_index: Option<(u64, usize)>,
}

impl<const N: usize> Elements<N> {
    fn new() -> Self {
        Elements { corners: Vec::new(), refs: Vec::new(), max_index: None }
    }

    /// Reads `count` entries of `nodes` indices (the first `N` kept) and a reference.
    fn read(&mut self, tok: &mut Tokens, count: usize, nodes: usize, what: &str) -> Result<(), IoError> {
        self.corners.reserve(count.min(tok.remaining().len() / 8));
        for _ in 0..count {
            let mut c = [0u32; N];
            for k in 0..nodes {
                let i: u64 = tok.parse(&format!("{what} vertex index"))?;
                if i == 0 {
                    return Err(tok.error(format!("{what} vertex index 0: Medit numbers vertices from 1")));
                }
                let i0 = u32::try_from(i - 1).map_err(|_| tok.error(format!("{what} vertex index {i} is too large")))?;
                if self.max_index.is_none_or(|(m, _)| i > m) {
                    self.max_index = Some((i, tok.line()));
                }
                if let Some(slot) = c.get_mut(k) {
                    *slot = i0;
                }
            }
            let r: i64 = tok.parse(&format!("{what} reference"))?;
            let r = u32::try_from(r)
                .map_err(|_| tok.error(format!("{what} reference {r} is negative or too large; fepre tags are 0 to 4294967295")))?;
            self.corners.push(c);
            self.refs.push(r);
        }
        Ok(())
    }

    fn check(&self, path: &Path, what: &str, vertices: usize) -> Result<(), IoError> {
        match self.max_index {
            Some((i, line)) if i > vertices as u64 => {
                Err(IoError::at_line(path, line, format!("{what} vertex index {i} is out of range: the file has {vertices} vertices")))
            }
            _ => Ok(()),
        }
    }
}

/// Reads a Medit `.mesh` file's bytes.
///
/// # Errors
/// Malformed or truncated sections, indices out of range, non-finite coordinates, a
/// `Dimension` other than 3, or a binary `.meshb` file; each names the line.
pub fn read(path: &Path, bytes: &[u8]) -> Result<Loaded, IoError> {
    if bytes.iter().take(4096).any(|&b| b == 0) {
        return Err(IoError::Unsupported {
            path: path.to_path_buf(),
            at: Location::File,
            message: "this looks like a binary Medit file (.meshb); only ASCII .mesh is read".into(),
        });
    }
    let mut tok = Tokens::new(path, bytes, Some(b'#'));
    let mut vertices: Vec<DVec3> = Vec::new();
    let mut tris = Elements::<3>::new();
    let mut tets = Elements::<4>::new();
    let mut notes = Vec::new();
    let mut ended = false;
    while let Some(kw) = tok.next() {
        let lower = kw.to_ascii_lowercase();
        match lower.as_str() {
            "meshversionformatted" => {
                let v: u32 = tok.parse("a version number")?;
                if !(1..=4).contains(&v) {
                    return Err(tok.error(format!("unknown MeshVersionFormatted {v} (expected 1 to 4)")));
                }
            }
            "dimension" => {
                let d: u32 = tok.parse("a dimension")?;
                if d != 3 {
                    return Err(IoError::Unsupported {
                        path: path.to_path_buf(),
                        at: Location::Line(tok.line()),
                        message: format!("Dimension {d}; fepre reads 3-D meshes only"),
                    });
                }
            }
            "vertices" => {
                let n: usize = tok.parse("the number of vertices")?;
                vertices.reserve(n.min(tok.remaining().len() / 8));
                for _ in 0..n {
                    vertices.push(tok.point3("vertex coordinate")?);
                    tok.parse::<i64>("vertex reference")?;
                }
            }
            "triangles" | "trianglesp2" => {
                let n: usize = tok.parse("the number of triangles")?;
                let nodes = if lower == "triangles" { 3 } else { 6 };
                tris.read(&mut tok, n, nodes, "triangle")?;
                if nodes == 6 && n > 0 {
                    notes.push(format!("kept the corners of {n} quadratic triangles (TrianglesP2)"));
                }
            }
            "tetrahedra" | "tetrahedrap2" => {
                let n: usize = tok.parse("the number of tetrahedra")?;
                let nodes = if lower == "tetrahedra" { 4 } else { 10 };
                tets.read(&mut tok, n, nodes, "tetrahedron")?;
                if nodes == 10 && n > 0 {
                    notes.push(format!("kept the corners of {n} quadratic tetrahedra (TetrahedraP2)"));
                }
            }
            "end" => {
                ended = true;
                break;
            }
            _ => {
                let Some(&(_, width)) = SKIPPED.iter().find(|(k, _)| *k == lower) else {
                    return Err(tok.error(format!(
                        "unknown keyword '{kw}' (fepre reads Vertices, Triangles and Tetrahedra and skips the usual other sections)"
                    )));
                };
                let n: usize = tok.parse(&format!("the number of {kw}"))?;
                for _ in 0..n.saturating_mul(width) {
                    tok.parse::<f64>(&format!("a number of section {kw}"))?;
                }
                notes.push(format!("skipped section {kw} ({n} entries)"));
            }
        }
    }
    if !ended {
        notes.push("the file has no End keyword; read to its end".into());
    }
    tris.check(path, "triangle", vertices.len())?;
    tets.check(path, "tetrahedron", vertices.len())?;
    let file_vertices = vertices.len();
    let mesh = if !tets.corners.is_empty() {
        let mut m = TetMesh {
            vertices,
            region_tags: tets.refs.into_iter().map(RegionId).collect(),
            tets: tets.corners,
            face_tags: tris.refs.into_iter().map(FaceId).collect(),
            boundary: tris.corners,
            ..Default::default()
        };
        notes.extend(orient_tets(&mut m));
        notes.extend(unused_vertices_note(&m));
        m.orient_boundary_outward();
        MeshData::Volume(m)
    } else if !tris.corners.is_empty() {
        let tags = tris.refs.into_iter().map(FaceId).collect();
        MeshData::Surface(TriSurface { vertices, triangles: tris.corners, face_tags: tags, ..Default::default() })
    } else if !vertices.is_empty() {
        MeshData::Points(vertices)
    } else {
        return Err(IoError::in_file(path, "no Vertices section: not a Medit mesh"));
    };
    let mut loaded = Loaded::new(mesh, Format::Medit, file_vertices);
    loaded.notes = notes;
    Ok(loaded)
}

/// Writes a surface: its vertices, and its triangles with their tags as references.
///
/// # Errors
/// [`IoError::Write`].
pub fn write_surface(path: &Path, s: &TriSurface) -> Result<(), IoError> {
    write_mesh(path, &s.vertices, (&s.triangles, &s.face_tags), (&[], &[]), &[], &[])
}

/// Writes a surface of triangles and quads: vertices, `Triangles` and `Quadrilaterals` with
/// their tags as references.
///
/// # Errors
/// [`IoError::Write`].
pub fn write_mixed(path: &Path, s: &MixedSurface) -> Result<(), IoError> {
    write_mesh(path, &s.vertices, (&s.triangles, &s.triangle_tags), (&s.quads, &s.quad_tags), &[], &[])
}

/// Writes a tet mesh: vertices, the boundary triangles with their face tags as references and
/// the tets with their region tags as references.
///
/// # Errors
/// [`IoError::Write`].
pub fn write_volume(path: &Path, m: &TetMesh) -> Result<(), IoError> {
    write_mesh(path, &m.vertices, (&m.boundary, &m.face_tags), (&[], &[]), &m.tets, &m.region_tags)
}

fn write_mesh(
    path: &Path,
    vertices: &[DVec3],
    (tris, tri_tags): (&[[u32; 3]], &[FaceId]),
    (quads, quad_tags): (&[[u32; 4]], &[FaceId]),
    tets: &[[u32; 4]],
    tet_tags: &[RegionId],
) -> Result<(), IoError> {
    write_atomic(path, |w| {
        let e = write_err(path);
        writeln!(w, "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n{}", vertices.len()).map_err(&e)?;
        write_lines(w, vertices, |b, _, p| writeln!(b, "{} {} {} 0", Num(p.x), Num(p.y), Num(p.z))).map_err(&e)?;
        if !tris.is_empty() {
            writeln!(w, "\nTriangles\n{}", tris.len()).map_err(&e)?;
            let tri_tags = |i: usize| tri_tags.get(i).map_or(0, |t| t.0 as u64);
            write_lines(w, tris, |b, i, t| write_int_line(b, &[t[0] as u64 + 1, t[1] as u64 + 1, t[2] as u64 + 1, tri_tags(i)])).map_err(&e)?;
        }
        if !quads.is_empty() {
            writeln!(w, "\nQuadrilaterals\n{}", quads.len()).map_err(&e)?;
            let quad_tags = |i: usize| quad_tags.get(i).map_or(0, |t| t.0 as u64);
            write_lines(w, quads, |b, i, q| write_int_line(b, &[q[0] as u64 + 1, q[1] as u64 + 1, q[2] as u64 + 1, q[3] as u64 + 1, quad_tags(i)])).map_err(&e)?;
        }
        if !tets.is_empty() {
            writeln!(w, "\nTetrahedra\n{}", tets.len()).map_err(&e)?;
            let tet_tags = |i: usize| tet_tags.get(i).map_or(0, |t| t.0 as u64);
            write_lines(w, tets, |b, i, t| write_int_line(b, &[t[0] as u64 + 1, t[1] as u64 + 1, t[2] as u64 + 1, t[3] as u64 + 1, tet_tags(i)])).map_err(&e)?;
        }
        writeln!(w, "\nEnd").map_err(&e)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::ReadOptions;

    use crate::io::test_meshes::two_tets;

    #[test]
    fn volume_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("v.mesh");
        let m = two_tets();
        write_volume(&p, &m).unwrap();
        let l = crate::io::read(&p, &ReadOptions::default()).unwrap();
        assert_eq!(l.mesh, MeshData::Volume(m));
        assert!(l.notes.is_empty(), "{:?}", l.notes);
    }

    #[test]
    fn surface_round_trip_keeps_tags() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("s.mesh");
        let m = two_tets();
        let s = TriSurface {
            vertices: m.vertices.clone(),
            triangles: m.boundary.clone(),
            face_tags: m.face_tags.clone(),
            ..Default::default()
        };
        write_surface(&p, &s).unwrap();
        let l = crate::io::read(&p, &ReadOptions::default().with_weld(None)).unwrap();
        assert_eq!(l.mesh, MeshData::Surface(s));
    }

    #[test]
    fn reorients_skips_and_accepts_any_case() {
        let text = "# a comment\nMeshVersionFormatted 1\nDimension\n3\nvertices 4\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\n\
                    Edges 1\n1 2 0\nCorners 2 1 2\nTETRAHEDRA 1\n1 3 2 4 7\ntriangles 1\n1 2 3 5\nEND\n";
        let l = read(Path::new("r.mesh"), text.as_bytes()).unwrap();
        let MeshData::Volume(m) = &l.mesh else { panic!("{:?}", l.mesh) };
        assert_eq!(m.tets, vec![[0, 2, 3, 1]]);
        assert_eq!(m.region_tags, vec![RegionId(7)]);
        assert_eq!(m.face_tags, vec![FaceId(5)]);
        assert_eq!(m.boundary, vec![[0, 2, 1]], "oriented outward");
        assert!(m.validate().is_ok());
        assert_eq!(l.notes.len(), 3, "{:?}", l.notes);
        assert!(l.notes.iter().any(|n| n.contains("Edges (1 entries)")));
    }

    #[test]
    fn malformed_inputs_name_the_line() {
        let head = "MeshVersionFormatted 2\nDimension 3\nVertices\n3\n0 0 0 0\n1 0 0 0\n0 1 0 0\n";
        let cases = [
            (format!("{head}Triangles\n1\n1 2 4 0\nEnd\n"), "m.mesh:10: triangle vertex index 4 is out of range: the file has 3 vertices"),
            (format!("{head}Triangles\n1\n1 0 2 0\n"), "m.mesh:10: triangle vertex index 0: Medit numbers vertices from 1"),
            (
                format!("{head}Triangles\n2\n1 2 3 0\n"),
                "m.mesh:11: unexpected end of file: expected triangle vertex index (is the file truncated?)",
            ),
            (
                format!("{head}Triangles\n1\n1 2 3 -4\n"),
                "m.mesh:10: triangle reference -4 is negative or too large; fepre tags are 0 to 4294967295",
            ),
            ("Vertices 1\n0 nan 0 0\n".to_string(), "m.mesh:2: vertex coordinate is not a finite number: 'NaN'"),
            (format!("{head}Foo 1\n"), "m.mesh:8: unknown keyword 'Foo'"),
            ("MeshVersionFormatted 2\nDimension 2\n".to_string(), "m.mesh:2: unsupported: Dimension 2"),
            ("Vertices x\n".to_string(), "m.mesh:1: expected the number of vertices, found 'x'"),
            ("MeshVersionFormatted 2\nEnd\n".to_string(), "m.mesh: no Vertices section"),
        ];
        for (text, want) in cases {
            let e = read(Path::new("m.mesh"), text.as_bytes()).unwrap_err().to_string();
            assert!(e.starts_with(want), "{e}\nwanted: {want}");
        }
        let e = read(Path::new("b.mesh"), b"\x01\x00\x00\x00\x02\x00").unwrap_err().to_string();
        assert!(e.contains("binary Medit"), "{e}");
    }

    #[test]
    fn triangles_only_is_a_surface_vertices_only_points() {
        let l = read(Path::new("s.mesh"), b"Vertices 3 0 0 0 0 1 0 0 0 0 1 0 0 Triangles 1 1 2 3 9 End").unwrap();
        let MeshData::Surface(s) = l.mesh else { panic!() };
        assert_eq!(s.face_tags, vec![FaceId(9)]);
        let l = read(Path::new("p.mesh"), b"Vertices 1 0 0 0 0 End").unwrap();
        assert_eq!(l.mesh, MeshData::Points(vec![DVec3::ZERO]));
    }

    #[test]
    fn mangled_input_never_panics() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("w.mesh");
        write_volume(&p, &two_tets()).unwrap();
        let file = std::fs::read(&p).unwrap();
        for cut in 0..file.len() {
            let _ = read(Path::new("m.mesh"), &file[..cut]);
        }
        for i in 0..file.len() {
            for b in [0u8, 0xff, b'9', b'-', b'\n', b'#', b'0'] {
                let mut f = file.clone();
                f[i] = b;
                let _ = read(Path::new("m.mesh"), &f);
            }
        }
    }
}
