//! Object File Format (Geomview OFF).
//!
//! ```text
//! OFF                 header: OFF, or a variant with per-vertex data: COFF, NOFF, STOFF, …
//! 8 6 12              vertex, face and edge counts (the edge count is ignored); may also
//!                     follow the header on its line
//! 0 0 0               one vertex per line: x y z, then any per-vertex data (ignored)
//! …
//! 4 0 3 2 1           one face per line: corner count, 0-based vertex indices, then an
//! …                   optional colour (ignored)
//! ```
//!
//! `#` starts a comment. A file without the header line (starting with the counts) is read
//! too. Faces with more than three corners are triangulated with
//! [`crate::io::polygon::triangulate`]; faces with fewer are skipped with a note. Binary OFF
//! and 4-dimensional or n-dimensional variants (`4OFF`, `nOFF`) are not supported. OFF has
//! no tags: every triangle gets tag 1.

use crate::core::FaceId;
use crate::io::atomic::{write_atomic, write_err};
use crate::io::common::Num;
use crate::io::polygon::{self, Outcome};
use crate::io::text::Tokens;
use crate::io::{Format, IoError, Loaded, Location, MeshData};
use crate::mesh::TriSurface;
use std::io::Write;
use std::path::Path;

/// Checks an OFF header keyword (`OFF`, `COFF`, `NOFF`, `STCNOFF`, …, ASCII case-insensitive).
///
/// `Ok(true)` for a header, `Ok(false)` for a token that is no header (the counts of a file
/// without one), `Err` for a variant fepre does not read.
fn header(token: &str) -> Result<bool, HeaderError> {
    let upper = token.to_ascii_uppercase();
    let Some(prefix) = upper.strip_suffix("OFF") else { return Ok(false) };
    let rest = prefix.strip_prefix("ST").unwrap_or(prefix);
    let rest = rest.strip_prefix('C').unwrap_or(rest);
    let rest = rest.strip_prefix('N').unwrap_or(rest);
    match rest {
        "" => Ok(true),
        "4" | "N" | "4N" => Err(HeaderError::NotThreeDimensional(token.to_owned())),
        _ => Err(HeaderError::Unknown(token.to_owned())),
    }
}

/// An OFF header fepre does not read; each names the header token.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
enum HeaderError {
    /// `4OFF`, `nOFF` and the like: vertices of another dimension.
    #[error("'{0}': only 3-dimensional vertices are supported")]
    NotThreeDimensional(String),
    /// A word ending in `OFF` that no OFF variant spells.
    #[error("'{0}' is not an OFF header (expected OFF, COFF, NOFF, STOFF, …)")]
    Unknown(String),
}

/// Reads an OFF file's bytes.
///
/// # Errors
/// A bad header or counts, a malformed or non-finite coordinate, a vertex index out of range
/// or a file shorter than its counts say: each names its line.
pub fn read(path: &Path, bytes: &[u8]) -> Result<Loaded, IoError> {
    let mut tok = Tokens::new(path, bytes, Some(b'#'));
    let first = tok.next_or_error("the 'OFF' header")?;
    let mut notes = Vec::new();
    let has_header = header(first)
        .map_err(|e| IoError::Unsupported { path: path.to_path_buf(), at: Location::Line(tok.line()), message: e.to_string() })?;
    // The counts: after the header on its line, on the next line, or first in the file.
    let count_tokens: Vec<&str> = if has_header {
        let rest = tok.rest_of_line();
        if rest.first().is_some_and(|t| t.eq_ignore_ascii_case("BINARY")) {
            return Err(IoError::Unsupported { path: path.to_path_buf(), at: Location::Line(tok.line()), message: "binary OFF".into() });
        }
        if rest.is_empty() {
            let nv = tok.next_or_error("the vertex count")?;
            let nf = tok.next_or_error("the face count")?;
            let mut c = vec![nv, nf];
            c.extend(tok.rest_of_line());
            c
        } else {
            rest
        }
    } else {
        if first.parse::<usize>().is_err() {
            return Err(tok.error(format!("expected the 'OFF' header, found '{first}'")));
        }
        notes.push("the file has no 'OFF' header line; it starts with the counts".to_string());
        let mut c = vec![first];
        c.extend(tok.rest_of_line());
        c
    };
    let count_line = tok.line();
    let count = |k: usize, what: &str| -> Result<usize, IoError> {
        let t = count_tokens.get(k).copied().ok_or_else(|| IoError::at_line(path, count_line, format!("expected the {what} after the vertex count")))?;
        t.parse::<usize>()
            .map_err(|_| IoError::at_line(path, count_line, format!("expected the {what} (a non-negative integer), found '{t}'")))
    };
    let nv = count(0, "vertex count")?;
    let nf = count(1, "face count")?;
    if u32::try_from(nv).is_err() {
        return Err(IoError::at_line(path, count_line, format!("{nv} vertices: at most 4,294,967,295 are supported")));
    }

    let mut vertices = Vec::with_capacity(nv.min(bytes.len() / 6));
    for k in 0..nv {
        if tok.at_end() {
            return Err(IoError::at_line(
                path,
                tok.line(),
                format!("unexpected end of file after {k} of {nv} vertices (is the file truncated?)"),
            ));
        }
        vertices.push(tok.point3("vertex coordinate")?);
        tok.rest_of_line();
    }

    let mut s = TriSurface { vertices, ..TriSurface::default() };
    let mut corners: Vec<u32> = Vec::new();
    let (mut small, mut degenerate, mut approximate) = (0usize, 0usize, 0usize);
    for k in 0..nf {
        if tok.at_end() {
            return Err(IoError::at_line(path, tok.line(), format!("unexpected end of file after {k} of {nf} faces (is the file truncated?)")));
        }
        let n: usize = tok.parse("the corner count of a face (a non-negative integer)")?;
        corners.clear();
        for _ in 0..n {
            let t = tok.next_or_error("a vertex index")?;
            let i = t.parse::<i64>().map_err(|_| tok.error(format!("expected a vertex index, found '{t}'")))?;
            match u32::try_from(i) {
                Ok(i) if (i as usize) < nv => corners.push(i),
                _ => {
                    return Err(tok.error(format!(
                        "face {k}: vertex index {i} is out of range: the file has {nv} vertices (OFF indices start at 0)"
                    )));
                }
            }
        }
        // the rest of the line is the face's colour
        tok.rest_of_line();
        if n < 3 {
            small += 1;
            continue;
        }
        match polygon::triangulate(&corners, &s.vertices, &mut s.triangles) {
            Outcome::Exact => {}
            Outcome::Approximate => approximate += 1,
            Outcome::Degenerate => degenerate += 1,
        }
    }
    s.face_tags = vec![FaceId(1); s.triangles.len()];
    let trailing = !tok.at_end();
    let mut loaded = Loaded::new(MeshData::Surface(s), Format::Off, nv);
    let more = [
        (small > 0, format!("skipped {small} faces with fewer than three corners")),
        (degenerate > 0, format!("dropped {degenerate} faces with fewer than three distinct vertices")),
        (approximate > 0, format!("{approximate} polygons are not simple in their plane; they were triangulated approximately")),
        (trailing, format!("ignored data after the last of the {nf} faces (line {})", tok.line())),
    ];
    notes.extend(more.into_iter().filter(|(on, _)| *on).map(|(_, n)| n));
    loaded.notes = notes;
    Ok(loaded)
}

/// Writes `s` as plain `OFF` (tags are not kept): coordinates read back exactly, faces are
/// `3 a b c` with 0-based indices.
///
/// # Errors
/// [`IoError::Invalid`] if `s` is not a valid surface, [`IoError::Write`] for file-system
/// failures (no file is left behind).
pub fn write(path: &Path, s: &TriSurface) -> Result<(), IoError> {
    s.validate().map_err(|source| IoError::Invalid { path: path.to_path_buf(), source })?;
    write_atomic(path, |w| {
        let e = write_err(path);
        writeln!(w, "OFF\n{} {} 0", s.vertices.len(), s.triangles.len()).map_err(&e)?;
        for v in &s.vertices {
            writeln!(w, "{} {} {}", Num(v.x), Num(v.y), Num(v.z)).map_err(&e)?;
        }
        for [a, b, c] in &s.triangles {
            writeln!(w, "3 {a} {b} {c}").map_err(&e)?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::ReadOptions;
    use glam::DVec3;

    fn err(text: &str) -> String {
        read(Path::new("bad.off"), text.as_bytes()).unwrap_err().to_string()
    }

    const CUBE: &str = "OFF # a cube
8 6 12
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
# faces
4 0 3 2 1
4 0 1 5 4
4 1 2 6 5 255 0 0
4 2 3 7 6
4 3 0 4 7
4 4 5 6 7
";

    fn surface(text: &str) -> (TriSurface, Loaded) {
        let l = read(Path::new("t.off"), text.as_bytes()).unwrap();
        let MeshData::Surface(s) = l.mesh.clone() else { panic!() };
        (s, l)
    }

    #[test]
    fn reads_quads_variants_and_headerless_files() {
        let (s, l) = surface(CUBE);
        assert_eq!((s.vertices.len(), s.triangles.len(), l.file_vertices), (8, 12, 8));
        assert!(l.notes.is_empty(), "{:?}", l.notes);
        s.validate().unwrap();
        let vol: f64 = (0..12).map(|t| {
            let [a, b, c] = s.corners(t);
            a.dot(b.cross(c)) / 6.0
        }).sum();
        assert!((vol - 1.0).abs() < 1e-12);
        // counts on the header line, colours per vertex, a pentagon, a 2-corner face
        let text = "COFF 5 3 0\n0 0 0 1 0 0 1\n2 0 0 1 0 0 1\n2 2 0 1 0 0 1\n1 3 0 1 0 0 1\n0 2 0 1 0 0 1\n5 0 1 2 3 4\n2 0 1\n3 0 1 2\n";
        let (s, l) = surface(text);
        assert_eq!(s.triangles.len(), 4);
        assert_eq!(l.notes, vec!["skipped 1 faces with fewer than three corners".to_string()]);
        let (s, l) = surface("3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        assert_eq!(s.triangles, vec![[0, 1, 2]]);
        assert!(l.notes[0].contains("no 'OFF' header"));
    }

    #[test]
    fn errors_name_the_line() {
        assert_eq!(err("OFF\n3 1 0\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n"), "bad.off:4: vertex coordinate is not a finite number: 'NaN'");
        assert_eq!(
            err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n\n3 0 1 3\n"),
            "bad.off:7: face 0: vertex index 3 is out of range: the file has 3 vertices (OFF indices start at 0)"
        );
        assert!(err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n").starts_with("bad.off:6: face 0: vertex index -1"));
        assert_eq!(err("OFF\n4 1 0\n0 0 0\n1 0 0\n"), "bad.off:4: unexpected end of file after 2 of 4 vertices (is the file truncated?)");
        assert_eq!(err("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), "bad.off:6: unexpected end of file after 1 of 2 faces (is the file truncated?)");
        assert!(err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n").contains("unexpected end of file"));
        assert_eq!(err("OFF\n-3 1 0\n"), "bad.off:2: expected the vertex count (a non-negative integer), found '-3'");
        assert_eq!(err("OFF 3\n"), "bad.off:1: expected the face count after the vertex count");
        assert!(err("4OFF\n").starts_with("bad.off:1: unsupported: '4OFF'"));
        assert!(err("OFF BINARY\n").contains("unsupported: binary OFF"));
        assert_eq!(err("ply\nformat ascii 1.0\n"), "bad.off:1: expected the 'OFF' header, found 'ply'");
        assert!(err("# only a comment\n").contains("unexpected end of file"));
    }

    #[test]
    fn writes_and_reads_back() {
        let dir = tempfile::tempdir().unwrap();
        let (mut s, _) = surface(CUBE);
        s.vertices[3] = DVec3::new(-1e-20, 0.1 + 0.2, 1.0 / 3.0);
        s.face_tags[0] = FaceId(7);
        let p = dir.path().join("c.off");
        crate::io::write(&p, &MeshData::Surface(s.clone()), &crate::io::WriteOptions::default()).unwrap();
        let l = crate::io::read(&p, &ReadOptions::default().with_weld(None)).unwrap();
        let MeshData::Surface(r) = l.mesh else { panic!() };
        assert_eq!(r.vertices, s.vertices);
        assert_eq!(r.triangles, s.triangles);
        assert_eq!(r.tags(), vec![FaceId(1)]);
    }

    #[test]
    fn mangled_input_never_panics() {
        let base = CUBE.as_bytes();
        for cut in 0..base.len() {
            let _ = read(Path::new("m.off"), &base[..cut]);
        }
        for i in 0..base.len() {
            for &b in b"-9 \n#x" {
                let mut m = base.to_vec();
                m[i] = b;
                if let Ok(l) = read(Path::new("m.off"), &m) {
                    let MeshData::Surface(s) = l.mesh else { panic!() };
                    s.validate().unwrap();
                }
            }
        }
        let _ = read(Path::new("m.off"), b"OFF 99999999999999999 99999999999999 0\n1 2 3\n");
    }
}
