//! STL, ASCII and binary.
//!
//! Binary files are recognised by their size (84 + 50 × the triangle count in the header), not
//! by the header text, which may begin with "solid" too. ASCII files may hold several `solid`
//! blocks: each becomes a tag (1, 2, …) named after the solid. Any non-finite number is an
//! error naming the line (ASCII) or the triangle (binary). The reader returns the triangle
//! soup; [`crate::io::read`] welds it.

use crate::core::FaceId;
use crate::io::atomic::{write_atomic, write_err};
use crate::io::text::Tokens;
use crate::io::{Format, IoError, Loaded, Location, MeshData, WriteOptions};
use crate::mesh::TriSurface;
use glam::DVec3;
use std::io::Write;
use std::path::Path;

/// Reads an STL file's bytes (either encoding).
///
/// # Errors
/// A truncated binary file, malformed ASCII, or a non-finite number.
pub fn read(path: &Path, bytes: &[u8]) -> Result<Loaded, IoError> {
    if bytes.len() >= 84 {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
        if 84 + 50 * n == bytes.len() as u64 {
            return read_binary(path, bytes, n as usize);
        }
    }
    if looks_like_text(bytes) && starts_with_solid(bytes) {
        return read_ascii(path, bytes);
    }
    if bytes.len() < 84 {
        return Err(IoError::in_file(
            path,
            format!("not an ASCII STL (no 'solid' keyword) and too short for a binary STL ({} bytes, the header alone is 84)", bytes.len()),
        ));
    }
    let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
    Err(IoError::Parse {
        path: path.to_path_buf(),
        at: Location::Byte(bytes.len() as u64),
        message: format!(
            "binary STL is truncated or has trailing bytes: its header counts {n} triangles, which take {} bytes, but the file has {}",
            84 + 50 * n,
            bytes.len()
        ),
    })
}

fn starts_with_solid(bytes: &[u8]) -> bool {
    let start = bytes.iter().position(|b| !b.is_ascii_whitespace()).unwrap_or(bytes.len());
    bytes.len() >= start + 5 && bytes[start..start + 5].eq_ignore_ascii_case(b"solid")
}

/// Text has no control characters other than whitespace in its first kilobytes.
fn looks_like_text(bytes: &[u8]) -> bool {
    bytes.iter().take(4096).all(|&b| b >= 0x20 || b == b'\n' || b == b'\r' || b == b'\t' || b == 0x0c)
}

fn read_binary(path: &Path, bytes: &[u8], n: usize) -> Result<Loaded, IoError> {
    let mut vertices = Vec::with_capacity(3 * n);
    let f = |o: usize| f32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]) as f64;
    for t in 0..n {
        let base = 84 + 50 * t;
        for k in 0..4 {
            let o = base + 12 * k;
            let p = DVec3::new(f(o), f(o + 4), f(o + 8));
            if !p.is_finite() {
                let what = if k == 0 { "normal".to_string() } else { format!("vertex {k}") };
                return Err(IoError::Parse {
                    path: path.to_path_buf(),
                    at: Location::Entity(format!("triangle {}", t + 1)),
                    message: format!("{what} has a non-finite coordinate {p:?} (byte {o})"),
                });
            }
            if k > 0 {
                vertices.push(p);
            }
        }
    }
    let triangles = (0..n as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    let s = TriSurface::with_single_tag(vertices, triangles, FaceId(1));
    Ok(Loaded::new(MeshData::Surface(s), Format::Stl, 3 * n))
}

fn read_ascii(path: &Path, bytes: &[u8]) -> Result<Loaded, IoError> {
    let mut tok = Tokens::new(path, bytes, None);
    let mut s = TriSurface::default();
    let mut solid = 0u32;
    while let Some(t) = tok.next() {
        if !t.eq_ignore_ascii_case("solid") {
            return Err(tok.error(format!("expected 'solid', found '{t}'")));
        }
        solid += 1;
        let name = tok.rest_of_line().join(" ");
        if !name.is_empty() {
            s.face_names.insert(FaceId(solid), name);
        }
        loop {
            let t = tok.next_or_error("'facet' or 'endsolid'")?;
            if t.eq_ignore_ascii_case("endsolid") {
                tok.rest_of_line();
                break;
            }
            if !t.eq_ignore_ascii_case("facet") {
                return Err(tok.error(format!("expected 'facet' or 'endsolid', found '{t}'")));
            }
            tok.keyword("normal")?;
            tok.point3("facet normal coordinate")?;
            tok.keyword("outer")?;
            tok.keyword("loop")?;
            let first = s.vertices.len() as u32;
            for _ in 0..3 {
                tok.keyword("vertex")?;
                s.vertices.push(tok.point3("vertex coordinate")?);
            }
            let t = tok.next_or_error("'endloop'")?;
            if t.eq_ignore_ascii_case("vertex") {
                return Err(tok.error("facet has more than three vertices; STL facets are triangles"));
            }
            if !t.eq_ignore_ascii_case("endloop") {
                return Err(tok.error(format!("expected 'endloop', found '{t}'")));
            }
            tok.keyword("endfacet")?;
            s.triangles.push([first, first + 1, first + 2]);
            s.face_tags.push(FaceId(solid));
        }
    }
    let n = s.vertices.len();
    Ok(Loaded::new(MeshData::Surface(s), Format::Stl, n))
}

fn unit_normal(p: [DVec3; 3]) -> DVec3 {
    (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero()
}

/// Writes `s` as binary STL (coordinates rounded to `f32`), or as ASCII STL with one `solid`
/// block per tag when `options.ascii` is set (named after the tag's name with whitespace made
/// `_`, `tag_<n>` if unnamed, names made unique).
///
/// # Errors
/// [`IoError::Write`], or [`IoError::NotRepresentable`] for more than 2³² − 1 triangles in
/// binary.
pub fn write(path: &Path, s: &TriSurface, options: &WriteOptions) -> Result<(), IoError> {
    if options.ascii { write_ascii(path, s) } else { write_binary(path, s) }
}

fn write_binary(path: &Path, s: &TriSurface) -> Result<(), IoError> {
    let n = u32::try_from(s.triangles.len()).map_err(|_| IoError::NotRepresentable {
        path: path.to_path_buf(),
        format: "binary STL",
        what: format!("{} triangles (at most 4,294,967,295)", s.triangles.len()),
    })?;
    write_atomic(path, |w| {
        let e = write_err(path);
        let mut header = [b' '; 80];
        let text = b"binary STL written by fepre";
        header[..text.len()].copy_from_slice(text);
        w.write_all(&header).map_err(&e)?;
        w.write_all(&n.to_le_bytes()).map_err(&e)?;
        let mut rec = [0u8; 50];
        for t in 0..s.triangles.len() {
            let p = s.corners(t);
            let vals = [unit_normal(p), p[0], p[1], p[2]];
            for (k, v) in vals.iter().enumerate() {
                for (c, x) in v.to_array().iter().enumerate() {
                    let o = 12 * k + 4 * c;
                    rec[o..o + 4].copy_from_slice(&(*x as f32).to_le_bytes());
                }
            }
            w.write_all(&rec).map_err(&e)?;
        }
        Ok(())
    })
}

fn write_ascii(path: &Path, s: &TriSurface) -> Result<(), IoError> {
    write_atomic(path, |w| {
        let e = write_err(path);
        let tags = s.tags();
        let tags = if tags.is_empty() { vec![FaceId(1)] } else { tags };
        let names = s.face_names.unique(tags.iter().copied(), |tag, name| {
            let name = name.filter(|n| !n.trim().is_empty()).map_or_else(|| format!("tag_{}", tag.0), str::to_string);
            Some(name.chars().map(|c| if c.is_whitespace() { '_' } else { c }).collect())
        });
        for tag in tags {
            let name = names.get(&tag).map_or("", String::as_str);
            writeln!(w, "solid {name}").map_err(&e)?;
            for t in (0..s.triangles.len()).filter(|&t| s.face_tags[t] == tag) {
                let p = s.corners(t);
                let n = unit_normal(p);
                writeln!(w, "  facet normal {:e} {:e} {:e}\n    outer loop", n.x, n.y, n.z).map_err(&e)?;
                for v in p {
                    writeln!(w, "      vertex {:e} {:e} {:e}", v.x, v.y, v.z).map_err(&e)?;
                }
                writeln!(w, "    endloop\n  endfacet").map_err(&e)?;
            }
            writeln!(w, "endsolid {name}").map_err(&e)?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::ReadOptions;

    fn tetra() -> TriSurface {
        let v = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let mut s = TriSurface::with_single_tag(v, vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]], FaceId(1));
        s.face_tags[3] = FaceId(2);
        s
    }

    #[test]
    fn round_trips_both_encodings() {
        let dir = tempfile::tempdir().unwrap();
        for ascii in [false, true] {
            let p = dir.path().join(format!("t{ascii}.stl"));
            write(&p, &tetra(), &WriteOptions::default().with_ascii(ascii)).unwrap();
            let l = crate::io::read(&p, &ReadOptions::default()).unwrap();
            let MeshData::Surface(s) = l.mesh else { panic!() };
            assert_eq!(s.vertices.len(), 4);
            assert_eq!(s.triangles.len(), 4);
            assert_eq!(l.file_vertices, 12);
            if ascii {
                assert_eq!(s.tags(), vec![FaceId(1), FaceId(2)]);
            }
        }
    }

    #[test]
    fn ascii_solid_names_are_unique() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("n.stl");
        let mut s = tetra();
        s.face_tags[2] = FaceId(3);
        s.face_names = [(FaceId(1), "side wall"), (FaceId(2), "side_wall"), (FaceId(3), "tag_1")].into_iter().collect();
        write(&p, &s, &WriteOptions::default().with_ascii(true)).unwrap();
        let MeshData::Surface(r) = crate::io::read(&p, &ReadOptions::default()).unwrap().mesh else { panic!() };
        let names: Vec<&str> = r.face_names.names().collect();
        assert_eq!(names, ["side_wall", "side_wall.2", "tag_1"]);
    }

    #[test]
    fn binary_header_starting_with_solid_is_binary() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("b.stl");
        write(&p, &tetra(), &WriteOptions::default()).unwrap();
        let mut bytes = std::fs::read(&p).unwrap();
        bytes[..5].copy_from_slice(b"solid");
        assert!(matches!(read(Path::new("b.stl"), &bytes).unwrap().mesh, MeshData::Surface(_)));
        let e = read(Path::new("b.stl"), &bytes[..bytes.len() - 7]).unwrap_err().to_string();
        assert!(e.starts_with("b.stl") && e.contains("truncated"), "{e}");
    }

    #[test]
    fn nan_names_the_line() {
        let text = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n";
        let e = read(Path::new("n.stl"), text.as_bytes()).unwrap_err().to_string();
        assert_eq!(e, "n.stl:5: vertex coordinate is not a finite number: 'NaN'");
    }
}
