//! Triangle's 2D `.poly` format: a planar straight-line graph with holes and regions.
//!
//! - Stage: input, before 2D meshing (`crate::mesh2d`).
//! - Inputs: a `.poly` file as Shewchuk's Triangle reads it
//!   (<https://www.cs.cmu.edu/~quake/triangle.poly.html>): a vertex list (with attributes and
//!   a boundary marker, both optional; a count of 0 takes the vertices from the `.node` file
//!   beside it), segments with an optional marker, hole seeds, and optional regional
//!   attributes with area constraints. `#` starts a comment, blank lines are skipped, and the
//!   numbering is 0- or 1-based as the first vertex says (and must then run on by one).
//! - Output: a [`PolyFile`] (vertex attributes and vertex markers are read and dropped);
//!   [`PolyFile::to_regions`] / [`PolyFile::to_domains`] turn it into checked
//!   [`Domain`](crate::mesh2d::Domain)s, one per connected region, with Triangle's semantics
//!   (see `poly/regions.rs`).
//! - Invariants: every read error names the file and the 1-based line; [`write`] writes a
//!   1-based file that [`read`] gives back bit for bit (shortest round-trip decimals), through
//!   a temporary file renamed at the end.

mod regions;
#[cfg(test)]
mod tests;
mod types;

pub use regions::PolyRegion;
pub use types::{PolyError, PolyFile, RegionSeed};

use crate::io::atomic::{write_atomic, write_err};
use glam::DVec2;
use std::io::Write;
use std::path::Path;

/// One data line: its 1-based number and its whitespace-separated fields (comments removed).
struct Line<'a> {
    number: usize,
    fields: Vec<&'a str>,
}

/// Reads the non-blank, uncommented lines of a file.
struct Lines<'a> {
    path: &'a Path,
    lines: std::iter::Enumerate<std::str::Lines<'a>>,
}

impl<'a> Lines<'a> {
    fn new(path: &'a Path, text: &'a str) -> Self {
        Lines { path, lines: text.lines().enumerate() }
    }

    fn syntax(&self, line: usize, message: impl Into<String>) -> PolyError {
        PolyError::Syntax { path: self.path.to_path_buf(), line, message: message.into() }
    }

    /// The next data line, or `None` at the end.
    fn next_opt(&mut self) -> Option<Line<'a>> {
        for (k, raw) in self.lines.by_ref() {
            let text = raw.split('#').next().unwrap_or("");
            let fields: Vec<&str> = text.split_whitespace().collect();
            if !fields.is_empty() {
                return Some(Line { number: k + 1, fields });
            }
        }
        None
    }

    /// The next data line; an error saying `what` was expected at the end.
    fn next(&mut self, what: &str) -> Result<Line<'a>, PolyError> {
        self.next_opt().ok_or_else(|| self.syntax(0, format!("the file ends where {what} was expected")))
    }

    /// Field `k` of `line` as a number of type `T`.
    fn field<T: std::str::FromStr>(&self, line: &Line<'_>, k: usize, what: &str) -> Result<T, PolyError> {
        let f = line.fields.get(k).ok_or_else(|| self.syntax(line.number, format!("{what} is missing")))?;
        f.parse::<T>().map_err(|_| self.syntax(line.number, format!("{what} '{f}' is not a valid number")))
    }
}

/// Reads a header `count dim attributes markers` and the vertex list after it; returns the
/// vertices and the numbering's base (0 or 1). `None` when the count is 0 (in a `.poly`: the
/// vertices are in the `.node` beside it).
fn read_vertices(lines: &mut Lines<'_>) -> Result<Option<(Vec<DVec2>, u64)>, PolyError> {
    let head = lines.next("the vertex count line")?;
    let n: u64 = lines.field(&head, 0, "the vertex count")?;
    if n == 0 {
        return Ok(None);
    }
    if n > u64::from(u32::MAX) {
        return Err(lines.syntax(head.number, format!("{n} vertices: more than fepre's indices hold")));
    }
    let dim: u64 = if head.fields.len() > 1 { lines.field(&head, 1, "the dimension")? } else { 2 };
    if dim != 2 {
        return Err(lines.syntax(head.number, format!("dimension {dim}: a 2D .poly needs 2 (a 3D .poly is TetGen's)")));
    }
    let attrs: usize = if head.fields.len() > 2 { lines.field(&head, 2, "the attribute count")? } else { 0 };
    let marks: usize = if head.fields.len() > 3 { lines.field(&head, 3, "the marker count")? } else { 0 };
    if marks > 1 {
        return Err(lines.syntax(head.number, format!("{marks} boundary markers per vertex: 0 or 1 allowed")));
    }
    let mut points = Vec::with_capacity(n.min(1 << 20) as usize);
    let mut base = 0;
    for k in 0..n {
        let l = lines.next(&format!("vertex {} of {n}", k + 1))?;
        let id: u64 = lines.field(&l, 0, "the vertex number")?;
        if k == 0 {
            if id > 1 {
                return Err(lines.syntax(l.number, format!("the first vertex is numbered {id}: numbering starts at 0 or 1")));
            }
            base = id;
        } else if id != base + k {
            return Err(lines.syntax(l.number, format!("vertex number {id} where {} was expected (vertices are numbered in order)", base + k)));
        }
        let x: f64 = lines.field(&l, 1, "the x coordinate")?;
        let y: f64 = lines.field(&l, 2, "the y coordinate")?;
        if !x.is_finite() || !y.is_finite() {
            return Err(lines.syntax(l.number, format!("vertex {id} ({x}, {y}) is not finite")));
        }
        if l.fields.len() < 3 + attrs + marks {
            return Err(lines.syntax(l.number, format!("vertex {id} has {} fields, {} expected", l.fields.len(), 3 + attrs + marks)));
        }
        points.push(DVec2::new(x, y));
    }
    Ok(Some((points, base)))
}

fn read_text(path: &Path) -> Result<String, PolyError> {
    std::fs::read_to_string(path).map_err(|e| PolyError::Read { path: path.to_path_buf(), reason: e.to_string() })
}

/// Reads a 2D `.poly` file (and the `.node` beside it when its vertex count is 0).
///
/// # Errors
/// [`PolyError::Read`] if a file cannot be read, [`PolyError::Syntax`] naming the file and
/// line where the format is broken (counts, numbering, fields, an endpoint that names no
/// vertex, a negative marker, a non-finite coordinate).
pub fn read(path: &Path) -> Result<PolyFile, PolyError> {
    let text = read_text(path)?;
    let mut lines = Lines::new(path, &text);
    let (points, base) = match read_vertices(&mut lines)? {
        Some(v) => v,
        None => {
            let node = path.with_extension("node");
            let node_text = read_text(&node)?;
            let mut node_lines = Lines::new(&node, &node_text);
            read_vertices(&mut node_lines)?.ok_or_else(|| node_lines.syntax(1, "the .node file lists no vertices"))?
        }
    };
    let n = points.len() as u64;
    let head = lines.next("the segment count line")?;
    let m: u64 = lines.field(&head, 0, "the segment count")?;
    if m > u64::from(u32::MAX) {
        return Err(lines.syntax(head.number, format!("{m} segments: more than fepre's indices hold")));
    }
    let has_marker = head.fields.len() > 1 && lines.field::<u64>(&head, 1, "the marker count")? > 0;
    let mut segments = Vec::with_capacity(m.min(1 << 20) as usize);
    let mut markers = Vec::with_capacity(segments.capacity());
    for k in 0..m {
        let l = lines.next(&format!("segment {} of {m}", k + 1))?;
        let mut end = [0u32; 2];
        for (e, slot) in end.iter_mut().enumerate() {
            let v: u64 = lines.field(&l, 1 + e, "a segment endpoint")?;
            if v < base || v - base >= n {
                return Err(lines.syntax(l.number, format!("segment endpoint {v} names no vertex (vertices {base} to {})", base + n - 1)));
            }
            *slot = (v - base) as u32;
        }
        let marker: i64 = if has_marker && l.fields.len() > 3 { lines.field(&l, 3, "the segment marker")? } else { 0 };
        let marker = u32::try_from(marker).map_err(|_| lines.syntax(l.number, format!("segment marker {marker}: fepre's tags are whole numbers from 0")))?;
        segments.push(end);
        markers.push(marker);
    }
    let head = lines.next("the hole count line")?;
    let h: u64 = lines.field(&head, 0, "the hole count")?;
    let mut holes = Vec::new();
    for k in 0..h {
        let l = lines.next(&format!("hole {} of {h}", k + 1))?;
        let x: f64 = lines.field(&l, 1, "the hole's x")?;
        let y: f64 = lines.field(&l, 2, "the hole's y")?;
        if !x.is_finite() || !y.is_finite() {
            return Err(lines.syntax(l.number, format!("hole seed ({x}, {y}) is not finite")));
        }
        holes.push(DVec2::new(x, y));
    }
    let mut regions = Vec::new();
    if let Some(head) = lines.next_opt() {
        let r: u64 = lines.field(&head, 0, "the region count")?;
        for k in 0..r {
            let l = lines.next(&format!("region {} of {r}", k + 1))?;
            let x: f64 = lines.field(&l, 1, "the region's x")?;
            let y: f64 = lines.field(&l, 2, "the region's y")?;
            let attribute: f64 = lines.field(&l, 3, "the regional attribute")?;
            let area: f64 = if l.fields.len() > 4 { lines.field(&l, 4, "the maximum area")? } else { -1.0 };
            if !x.is_finite() || !y.is_finite() || !attribute.is_finite() || area.is_nan() {
                return Err(lines.syntax(l.number, "a region seed's coordinates, attribute and area must be finite"));
            }
            regions.push(RegionSeed { at: DVec2::new(x, y), attribute, max_area: (area > 0.0).then_some(area) });
        }
    }
    if let Some(extra) = lines.next_opt() {
        return Err(lines.syntax(extra.number, "unexpected data after the region list"));
    }
    Ok(PolyFile { points, segments, markers, holes, regions })
}

/// Writes `poly` as a 1-based 2D `.poly` file (one boundary marker per segment, no vertex
/// attributes or markers; a region without a maximum area gets `-1`).
///
/// # Errors
/// [`PolyError::Write`] if the file cannot be written (nothing is left at `path`).
pub fn write(path: &Path, poly: &PolyFile) -> Result<(), PolyError> {
    let e = write_err(path);
    write_atomic(path, |w| {
        writeln!(w, "# written by fepre").map_err(&e)?;
        writeln!(w, "{} 2 0 0", poly.points.len()).map_err(&e)?;
        for (k, p) in poly.points.iter().enumerate() {
            writeln!(w, "{} {:?} {:?}", k + 1, p.x, p.y).map_err(&e)?;
        }
        writeln!(w, "{} 1", poly.segments.len()).map_err(&e)?;
        for (k, s) in poly.segments.iter().enumerate() {
            writeln!(w, "{} {} {} {}", k + 1, s[0] + 1, s[1] + 1, poly.markers.get(k).copied().unwrap_or(0)).map_err(&e)?;
        }
        writeln!(w, "{}", poly.holes.len()).map_err(&e)?;
        for (k, p) in poly.holes.iter().enumerate() {
            writeln!(w, "{} {:?} {:?}", k + 1, p.x, p.y).map_err(&e)?;
        }
        writeln!(w, "{}", poly.regions.len()).map_err(&e)?;
        for (k, r) in poly.regions.iter().enumerate() {
            writeln!(w, "{} {:?} {:?} {:?} {:?}", k + 1, r.at.x, r.at.y, r.attribute, r.max_area.unwrap_or(-1.0)).map_err(&e)?;
        }
        Ok(())
    })?;
    Ok(())
}
