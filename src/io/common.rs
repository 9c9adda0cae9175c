//! Small helpers shared by the volume formats (Medit, TetGen, MSH, VTU): number formatting
//! that reads back exactly, integer lines written fast, repair of tet orientation after reading, and integer tags parsed
//! from the text of a file.

use crate::core::Sign;
use crate::core::predicates::orient3d;
use crate::mesh::TetMesh;
use std::fmt;
use std::io::{self, Write};

/// Writes one text line per item, formatted by `line(buffer, index, item)` in parallel (in batches of at most
/// `LINES_PER_TASK × 64` lines, so the text held at once stays bounded) and written in order:
/// the bytes are those of formatting the items one after the other.
pub(crate) fn write_lines<T: Sync>(w: &mut impl Write, items: &[T], line: impl Fn(&mut Vec<u8>, usize, &T) -> io::Result<()> + Sync) -> io::Result<()> {
    use rayon::prelude::*;
    const LINES_PER_TASK: usize = 4096;
    const BATCH: usize = LINES_PER_TASK * 64;
    for (b, batch) in items.chunks(BATCH).enumerate() {
        let texts: Vec<io::Result<Vec<u8>>> = batch
            .par_chunks(LINES_PER_TASK)
            .enumerate()
            .map(|(c, chunk)| {
                let mut buf = Vec::with_capacity(chunk.len() * 32);
                for (k, x) in chunk.iter().enumerate() {
                    line(&mut buf, b * BATCH + c * LINES_PER_TASK + k, x)?;
                }
                Ok(buf)
            })
            .collect();
        for t in texts {
            w.write_all(&t?)?;
        }
    }
    Ok(())
}

/// Writes `values` as one line of decimal integers separated by single spaces (what
/// `writeln!` with `{}` gives, without the formatting machinery: a mesh has millions).
pub(crate) fn write_int_line(w: &mut impl Write, values: &[u64]) -> io::Result<()> {
    let mut line = [0u8; 8 * 21];
    let mut n = 0;
    let mut buf = itoa::Buffer::new();
    for (i, &v) in values.iter().enumerate() {
        if n + 22 > line.len() {
            w.write_all(&line[..n])?;
            n = 0;
        }
        if i > 0 {
            line[n] = b' ';
            n += 1;
        }
        let digits = buf.format(v).as_bytes();
        line[n..n + digits.len()].copy_from_slice(digits);
        n += digits.len();
    }
    line[n] = b'\n';
    w.write_all(&line[..n + 1])
}

/// Displays an `f64` so that parsing the text gives back the same value: plain decimals for
/// ordinary magnitudes (`0.25`, `-3`, `1234.5`), scientific notation (`1.5e-9`, `2e20`) for
/// very small or very large ones. Every reader we target (gmsh, TetGen, meshio, C's `strtod`)
/// parses both.
#[derive(Copy, Clone, Debug)]
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if x == 0.0 || (1e-5..1e16).contains(&x.abs()) { write!(f, "{x}") } else { write!(f, "{x:e}") }
    }
}

/// Makes every negatively oriented tet positive by swapping its last two vertices (decided
/// exactly). Flat tets are left as they are, for [`TetMesh::validate`] to report. Returns a
/// note for [`crate::io::Loaded::notes`] when any tet was swapped.
///
/// Every tet index must be in range.
pub(crate) fn orient_tets(m: &mut TetMesh) -> Option<String> {
    let mut flipped = 0usize;
    for tet in &mut m.tets {
        let [a, b, c, d] = tet.map(|i| m.vertices[i as usize]);
        if orient3d(a, b, c, d) == Sign::Negative {
            tet.swap(2, 3);
            flipped += 1;
        }
    }
    match flipped {
        0 => None,
        n if n == m.tets.len() => Some(format!(
            "all {n} tetrahedra were negatively oriented; swapped two vertices of each (the file uses the opposite orientation convention)"
        )),
        n => Some(format!("reoriented {n} negatively oriented tetrahedra (swapped two vertices)")),
    }
}

/// A note when some vertices of a tet mesh are used by no tet (mid-edge nodes of quadratic
/// elements, geometry points); they are kept so that vertex numbers match the file.
pub(crate) fn unused_vertices_note(m: &TetMesh) -> Option<String> {
    let mut used = vec![false; m.vertices.len()];
    for t in &m.tets {
        for &v in t {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
    }
    let n = used.iter().filter(|u| !**u).count();
    (n > 0).then(|| format!("{n} vertices are used by no tetrahedron (kept, so that vertex numbers match the file)"))
}

/// Why a token is not a tag ([`integral_tag`]); each names the token.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub(crate) enum TagError {
    /// An integer outside `0..=INDEX_MAX`.
    #[error("'{0}' is not a tag fepre can hold (0 to 4294967295)")]
    OutOfRange(String),
    /// A number with a fractional part (or not finite).
    #[error("'{0}' is not an integer")]
    NotInteger(String),
    /// Not a number at all.
    #[error("'{0}' is not a number")]
    NotANumber(String),
}

/// Parses a non-negative integer tag, written as an integer or as an integral real (`3`,
/// `3.0`, `3e0`), as TetGen writes attributes. The error says what is wrong with `text`.
pub(crate) fn integral_tag(text: &str) -> Result<u32, TagError> {
    if let Ok(v) = text.parse::<i64>() {
        return u32::try_from(v).map_err(|_| TagError::OutOfRange(text.to_owned()));
    }
    match text.parse::<f64>() {
        Ok(x) if x.is_finite() && x.fract() == 0.0 && (0.0..=f64::from(crate::core::ids::INDEX_MAX)).contains(&x) => Ok(x as u32),
        Ok(x) if x.is_finite() && x.fract() == 0.0 => Err(TagError::OutOfRange(text.to_owned())),
        Ok(_) => Err(TagError::NotInteger(text.to_owned())),
        Err(_) => Err(TagError::NotANumber(text.to_owned())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::RegionId;
    use glam::DVec3;

    #[test]
    fn numbers_read_back_exactly() {
        for x in [0.0, -0.0, 1.0, 0.1, 1.0 / 3.0, -2.5e-12, 6.02e23, 1e-5, 9.99e15, f64::MAX, f64::MIN_POSITIVE] {
            let s = Num(x).to_string();
            assert_eq!(s.parse::<f64>().unwrap().to_bits(), x.to_bits(), "{s}");
            assert!(s.len() < 26, "{s}");
        }
        assert_eq!(Num(0.25).to_string(), "0.25");
        assert_eq!(Num(3.0).to_string(), "3");
        assert_eq!(Num(1.5e-9).to_string(), "1.5e-9");
    }

    #[test]
    fn tags_and_orientation() {
        assert_eq!(integral_tag("7"), Ok(7));
        assert_eq!(integral_tag("7.0"), Ok(7));
        assert!(integral_tag("-1").unwrap_err().to_string().contains("0 to"));
        assert!(integral_tag("1.5").unwrap_err().to_string().contains("not an integer"));
        assert!(integral_tag("x").unwrap_err().to_string().contains("not a number"));
        let mut m = TetMesh {
            vertices: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::ONE],
            tets: vec![[0, 2, 1, 3], [0, 1, 2, 3]],
            region_tags: vec![RegionId(1); 2],
            ..Default::default()
        };
        assert_eq!(orient_tets(&mut m).unwrap(), "reoriented 1 negatively oriented tetrahedra (swapped two vertices)");
        assert_eq!(m.tets[0], [0, 2, 3, 1]);
        assert_eq!(orient_tets(&mut m), None);
        assert!(unused_vertices_note(&m).unwrap().starts_with("1 vertices"));
    }
}
