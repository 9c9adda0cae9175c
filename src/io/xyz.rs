//! Point sets as plain text: one `x y z` per line (`#` starts a comment).

use crate::io::point_lines::{self, Layout};
use crate::io::text::Tokens;
use crate::io::{Format, IoError, Loaded, MeshData};
use glam::DVec3;
use std::path::Path;

/// Reads `x y z` lines: in parallel when every line is well formed, otherwise line by line to
/// report the first problem.
///
/// # Errors
/// A line without three finite numbers.
pub fn read(path: &Path, bytes: &[u8]) -> Result<Loaded, IoError> {
    let points = read_points(path, bytes)?;
    let n = points.len();
    Ok(Loaded::new(MeshData::Points(points), Format::Xyz, n))
}

/// The points of `x y z` lines, as [`read`] reads them.
///
/// # Errors
/// A line without three finite numbers.
pub fn read_points(path: &Path, bytes: &[u8]) -> Result<Vec<DVec3>, IoError> {
    match point_lines::parse(bytes, Layout::Xyz, None) {
        Some(fast) => Ok(fast.points),
        None => read_careful(path, bytes),
    }
}

/// The careful reader: token by token, naming the line of the first problem.
pub(crate) fn read_careful(path: &Path, bytes: &[u8]) -> Result<Vec<DVec3>, IoError> {
    let mut tok = Tokens::new(path, bytes, Some(b'#'));
    let mut points = Vec::with_capacity(bytes.len() / 50);
    while !tok.at_end() {
        let p = tok.point3("coordinate")?;
        let extra = tok.rest_of_line();
        if !extra.is_empty() {
            return Err(tok.error(format!("expected three coordinates per line, found more ('{}')", extra[0])));
        }
        points.push(p);
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_points_and_names_bad_lines() {
        let l = read(Path::new("p.xyz"), b"0 0 0\n1 2 3 # c\n\n4 5 6\n").unwrap();
        assert_eq!(l.mesh, MeshData::Points(vec![glam::DVec3::ZERO, glam::DVec3::new(1.0, 2.0, 3.0), glam::DVec3::new(4.0, 5.0, 6.0)]));
        let e = read(Path::new("p.xyz"), b"0 0 0\n1 2\n3 4 5\n").unwrap_err().to_string();
        assert!(e.starts_with("p.xyz:"), "{e}");
        let e = read(Path::new("p.xyz"), b"0 0 0 7\n").unwrap_err().to_string();
        assert_eq!(e, "p.xyz:1: expected three coordinates per line, found more ('7')");
    }
}
