//! TetGen's file family: `.node`, `.ele`, `.face`, `.poly`, `.smesh`.
//!
//! Read, by the extension of the path given (`x` standing for the path without extension):
//! - `x.ele`, or `x.node` when `x.ele` exists: a tet mesh from `x.node` + `x.ele`, with the
//!   boundary triangles of `x.face` if that exists. The first `.ele` attribute is the region
//!   tag (region 1 without attributes); `.face` markers are the face tags (0 without).
//!   Quadratic (10-node) tets keep their 4 corners; negatively oriented tets are reoriented.
//! - `x.node` alone: a point set.
//! - `x.face`: a surface from `x.node` + `x.face`, tagged by the markers.
//! - `x.poly`, `x.smesh`: a piecewise linear complex read as a surface tagged by the facet
//!   markers; its nodes come from `x.node` when the file's node list is empty. Polygons with
//!   more than three vertices are triangulated (ear clipping in their plane); facets with holes
//!   are not supported. The volume hole and region lists become [`PlcSeeds`].
//!
//! Numbering starts at 0 or 1, as the first node of the `.node` list says; `#` starts a
//! comment. Node attributes and boundary markers are ignored.
//!
//! Written, always numbered from 1:
//! - a tet mesh, whichever of `.node`, `.ele` or `.face` is given: `x.node`, `x.ele` (region
//!   tag as the one attribute) and `x.face` (face tags as markers), all renamed into place
//!   together; `tetgen -r x` refines them.
//! - a surface: `x.poly` or `x.smesh` as given (one triangle per facet with its marker, no
//!   holes, no regions), otherwise `x.node` + `x.face`.
//! - a point set: `x.node`.
//!
//! TetGen has no names: tag names are not written.
//!
//! [`PlcSeeds`]: crate::io::PlcSeeds

mod poly;

use crate::core::{FaceId, RegionId};
use crate::io::atomic::{write_atomic, write_atomic_many, write_err};
use crate::io::common::{Num, integral_tag, orient_tets, unused_vertices_note};
use crate::io::point_lines::{self, Layout};
use crate::io::text::Tokens;
use crate::io::{Format, IoError, Loaded, Location, MeshData, read_bytes};
use crate::mesh::{TetMesh, TriSurface};
use glam::DVec3;
use std::fmt;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Reads a TetGen file and, as its extension requires, its siblings.
///
/// # Errors
/// A missing sibling file, malformed lines, node numbers out of range, non-finite
/// coordinates; each names the file and line.
pub fn read(path: &Path) -> Result<Loaded, IoError> {
    let ext = extension(path);
    let sibling = |e: &str| path.with_extension(e);
    match ext.as_str() {
        "poly" | "smesh" => poly::read(path, &read_bytes(path)?, ext == "smesh"),
        "face" => {
            let node_path = sibling("node");
            let nodes = read_node_file(&node_path)?;
            let bytes = read_bytes(path)?;
            let faces = read_faces(path, &bytes, &nodes)?;
            let n = nodes.points.len();
            let s = TriSurface { vertices: nodes.points, triangles: faces.0, face_tags: faces.1, ..Default::default() };
            Ok(Loaded::new(MeshData::Surface(s), Format::TetGen, n))
        }
        "node" if !sibling("ele").exists() => {
            let nodes = read_node_file(path)?;
            let n = nodes.points.len();
            Ok(Loaded::new(MeshData::Points(nodes.points), Format::TetGen, n))
        }
        _ => read_volume(path),
    }
}

fn extension(path: &Path) -> String {
    path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default()
}

/// `x.node` + `x.ele` (+ `x.face`).
fn read_volume(path: &Path) -> Result<Loaded, IoError> {
    let node_path = path.with_extension("node");
    let ele_path = path.with_extension("ele");
    let face_path = path.with_extension("face");
    let nodes = read_node_file(&node_path)?;
    let (tets, region_tags, ele_notes) = read_ele(&ele_path, &read_bytes(&ele_path)?, &nodes)?;
    let (boundary, face_tags) =
        if face_path.exists() { read_faces(&face_path, &read_bytes(&face_path)?, &nodes)? } else { (Vec::new(), Vec::new()) };
    let n = nodes.points.len();
    let mut m = TetMesh { vertices: nodes.points, tets, region_tags, boundary, face_tags, ..Default::default() };
    let mut notes = ele_notes;
    notes.extend(orient_tets(&mut m));
    notes.extend(unused_vertices_note(&m));
    m.orient_boundary_outward();
    let mut loaded = Loaded::new(MeshData::Volume(m), Format::TetGen, n);
    loaded.notes = notes;
    Ok(loaded)
}

/// The lines of a TetGen file: tokens up to the end of each line, comments and blank lines
/// skipped.
pub(crate) struct Lines<'a> {
    tok: Tokens<'a>,
}

impl<'a> Lines<'a> {
    pub(crate) fn new(path: &'a Path, bytes: &'a [u8]) -> Self {
        Lines { tok: Tokens::new(path, bytes, Some(b'#')) }
    }

    pub(crate) fn path(&self) -> &'a Path {
        self.tok.path()
    }

    /// The next non-empty line and its number, or `None` at the end of the file.
    pub(crate) fn try_next(&mut self) -> Option<(usize, Vec<&'a str>)> {
        let first = self.tok.next()?;
        let line = self.tok.line();
        let mut v = vec![first];
        v.extend(self.tok.rest_of_line());
        Some((line, v))
    }

    /// A capacity for `n` entries of at least `line_bytes` bytes each: at most what the rest
    /// of the file can hold, so that a corrupt count cannot reserve huge memory.
    pub(crate) fn cap(&self, n: usize, line_bytes: usize) -> usize {
        n.min(self.tok.remaining().len() / line_bytes.max(1) + 1)
    }

    /// The bytes after the last line read.
    pub(crate) fn remaining(&self) -> &'a [u8] {
        self.tok.remaining()
    }

    /// Moves on `n` bytes (past lines read by other means), keeping the line count.
    pub(crate) fn skip_bytes(&mut self, n: usize) {
        self.tok.skip_bytes(n);
    }

    /// The next non-empty line; at the end of the file an error saying what was expected
    /// (`what` is formatted only then).
    pub(crate) fn next(&mut self, what: impl fmt::Display) -> Result<Line<'a>, IoError> {
        match self.try_next() {
            Some((line, tokens)) => Ok(Line { path: self.tok.path(), line, tokens }),
            None => Err(self.tok.error(format!("unexpected end of file: expected {what} (is the file truncated?)"))),
        }
    }
}

/// "node 3 of 10": an item of a list, for messages, formatted only when needed.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Nth(pub(crate) &'static str, pub(crate) usize, pub(crate) usize);

impl fmt::Display for Nth {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {} of {}", self.0, self.1, self.2)
    }
}

/// One line's tokens, with what is needed to report errors on it.
pub(crate) struct Line<'a> {
    pub(crate) path: &'a Path,
    pub(crate) line: usize,
    pub(crate) tokens: Vec<&'a str>,
}

impl Line<'_> {
    pub(crate) fn error(&self, message: impl Into<String>) -> IoError {
        IoError::at_line(self.path, self.line, message)
    }

    /// Token `k`, which must exist.
    pub(crate) fn get(&self, k: usize, what: &str) -> Result<&str, IoError> {
        self.tokens.get(k).copied().ok_or_else(|| self.error(format!("expected {what} (the line has only {} numbers)", self.tokens.len())))
    }

    /// Token `k` as a count or small integer.
    pub(crate) fn count(&self, k: usize, what: &str) -> Result<usize, IoError> {
        let t = self.get(k, what)?;
        t.parse().map_err(|_| self.error(format!("expected {what}, found '{t}'")))
    }

    /// Token `k`, if present, as a count; `default` if the line is shorter.
    pub(crate) fn count_or(&self, k: usize, what: &str, default: usize) -> Result<usize, IoError> {
        if k < self.tokens.len() { self.count(k, what) } else { Ok(default) }
    }

    /// Token `k` as a finite number.
    pub(crate) fn finite(&self, k: usize, what: &str) -> Result<f64, IoError> {
        let t = self.get(k, what)?;
        let x: f64 = t.parse().map_err(|_| self.error(format!("expected {what}, found '{t}'")))?;
        if x.is_finite() { Ok(x) } else { Err(self.error(format!("{what} is not a finite number: '{x}'"))) }
    }

    /// Tokens `k..k+3` as a point.
    pub(crate) fn point(&self, k: usize, what: &str) -> Result<DVec3, IoError> {
        Ok(DVec3::new(self.finite(k, what)?, self.finite(k + 1, what)?, self.finite(k + 2, what)?))
    }

    /// Token `k` as an integral tag (marker or attribute).
    pub(crate) fn tag(&self, k: usize, what: &str) -> Result<u32, IoError> {
        integral_tag(self.get(k, what)?).map_err(|m| self.error(format!("{what}: {m}")))
    }

    /// Token `k` as a node number, turned into a 0-based index into `nodes`.
    pub(crate) fn node(&self, k: usize, nodes: &Nodes) -> Result<u32, IoError> {
        let t = self.get(k, "a node number")?;
        let i: i64 = t.parse().map_err(|_| self.error(format!("expected a node number, found '{t}'")))?;
        let n = nodes.points.len() as i64;
        let first = nodes.first as i64;
        if i < first || i - first >= n {
            return Err(self.error(format!(
                "node {i} does not exist: {} numbers its {n} nodes from {first} to {}",
                nodes.source.display(),
                first + n - 1
            )));
        }
        Ok((i - first) as u32)
    }
}

/// A node list and how it is numbered.
pub(crate) struct Nodes {
    pub(crate) points: Vec<DVec3>,
    /// The number of the first node: 0 or 1.
    pub(crate) first: u32,
    /// The file the list came from, for messages.
    pub(crate) source: PathBuf,
}

/// The points of a `.node` file (attributes and markers skipped).
///
/// # Errors
/// As for any `.node` file: the file and line of the first problem.
pub fn read_node_points(path: &Path) -> Result<Vec<DVec3>, IoError> {
    read_node_file(path).map(|n| n.points)
}

fn read_node_file(path: &Path) -> Result<Nodes, IoError> {
    let bytes = point_lines::read_file(path)?;
    let mut lines = Lines::new(path, &bytes);
    let header = lines.next("the header line 'nodes dimension attributes markers'")?;
    read_nodes_then(&mut lines, &header, false)
}

/// Reads a node list whose header line (`count [dimension [attributes [markers]]]`) is
/// `header`: in parallel when the list is well formed, otherwise line by line to report the
/// first problem.
pub(crate) fn read_nodes(lines: &mut Lines, header: &Line) -> Result<Nodes, IoError> {
    read_nodes_then(lines, header, true)
}

/// [`read_nodes`]; with `go_on` false, `lines` is left anywhere (when nothing follows the
/// node list, counting the lines read would be wasted time).
fn read_nodes_then(lines: &mut Lines, header: &Line, go_on: bool) -> Result<Nodes, IoError> {
    let n = node_header(header)?;
    if let Some(fast) = point_lines::parse(lines.remaining(), Layout::Numbered, Some(n)) {
        if go_on {
            lines.skip_bytes(fast.consumed);
        }
        return Ok(Nodes { points: fast.points, first: fast.first, source: lines.path().to_path_buf() });
    }
    read_nodes_careful(lines, header)
}

/// The number of nodes of a node list header, checked to be 3-D.
fn node_header(header: &Line) -> Result<usize, IoError> {
    let n = header.count(0, "the number of nodes")?;
    let dim = header.count_or(1, "the dimension", 3)?;
    if dim != 3 {
        return Err(IoError::Unsupported {
            path: header.path.to_path_buf(),
            at: Location::Line(header.line),
            message: format!("dimension {dim}; fepre reads 3-D TetGen files only"),
        });
    }
    Ok(n)
}

/// The careful node list reader: line by line, naming the line of the first problem.
pub(crate) fn read_nodes_careful(lines: &mut Lines, header: &Line) -> Result<Nodes, IoError> {
    let n = node_header(header)?;
    let mut points = Vec::with_capacity(lines.cap(n, 8));
    let mut first = 0;
    for i in 0..n {
        let l = lines.next(Nth("node", i + 1, n))?;
        let number: i64 = {
            let t = l.get(0, "a node number")?;
            t.parse().map_err(|_| l.error(format!("expected a node number, found '{t}'")))?
        };
        if i == 0 {
            if number != 0 && number != 1 {
                return Err(l.error(format!("the first node is numbered {number}; TetGen numbers nodes from 0 or 1")));
            }
            first = number as u32;
        } else if number != first as i64 + i as i64 {
            return Err(l.error(format!(
                "node numbered {number} where {} was expected; nodes must be numbered consecutively",
                first as i64 + i as i64
            )));
        }
        points.push(l.point(1, "a node coordinate")?);
    }
    Ok(Nodes { points, first, source: lines.path().to_path_buf() })
}

type Tets = (Vec<[u32; 4]>, Vec<RegionId>, Vec<String>);

fn read_ele(path: &Path, bytes: &[u8], nodes: &Nodes) -> Result<Tets, IoError> {
    let mut lines = Lines::new(path, bytes);
    let h = lines.next("the header line 'tetrahedra nodes-per-tet attributes'")?;
    let n = h.count(0, "the number of tetrahedra")?;
    let per = h.count_or(1, "the number of nodes per tetrahedron", 4)?;
    if per != 4 && per != 10 {
        return Err(h.error(format!("{per} nodes per tetrahedron; TetGen writes 4 or 10")));
    }
    let nattr = h.count_or(2, "the number of attributes", 0)?;
    let mut tets = Vec::with_capacity(lines.cap(n, 10));
    let mut tags = Vec::with_capacity(lines.cap(n, 10));
    for i in 0..n {
        let l = lines.next(Nth("tetrahedron", i + 1, n))?;
        if l.tokens.len() < 1 + per + nattr {
            return Err(l.error(format!(
                "expected {} numbers (number, {per} nodes, {nattr} attributes), found {}",
                1 + per + nattr,
                l.tokens.len()
            )));
        }
        let mut t = [0u32; 4];
        for (k, v) in t.iter_mut().enumerate() {
            *v = l.node(1 + k, nodes)?;
        }
        for k in 4..per {
            l.node(1 + k, nodes)?;
        }
        tets.push(t);
        tags.push(RegionId(if nattr > 0 { l.tag(1 + per, "the region attribute")? } else { 1 }));
    }
    let mut notes = Vec::new();
    if per == 10 && n > 0 {
        notes.push(format!("kept the corners of {n} 10-node tetrahedra"));
    }
    if nattr == 0 {
        notes.push("the .ele file has no region attribute: every tetrahedron is in region 1".into());
    }
    Ok((tets, tags, notes))
}

fn read_faces(path: &Path, bytes: &[u8], nodes: &Nodes) -> Result<(Vec<[u32; 3]>, Vec<FaceId>), IoError> {
    let mut lines = Lines::new(path, bytes);
    let h = lines.next("the header line 'faces markers'")?;
    let n = h.count(0, "the number of faces")?;
    let markers = h.count_or(1, "the number of boundary markers", 0)?;
    let mut tris = Vec::with_capacity(lines.cap(n, 8));
    let mut tags = Vec::with_capacity(lines.cap(n, 8));
    for i in 0..n {
        let l = lines.next(Nth("face", i + 1, n))?;
        tris.push([l.node(1, nodes)?, l.node(2, nodes)?, l.node(3, nodes)?]);
        tags.push(FaceId(if markers > 0 { l.tag(4, "the boundary marker")? } else { 0 }));
    }
    Ok((tris, tags))
}

/// The files written for `path`: `x.<ext>` for each extension.
fn siblings(path: &Path, exts: &[&str]) -> Vec<PathBuf> {
    exts.iter().map(|e| path.with_extension(e)).collect()
}

fn not_representable(path: &Path, what: &str) -> IoError {
    IoError::NotRepresentable { path: path.to_path_buf(), format: "TetGen", what: what.to_string() }
}

/// Writes a tet mesh as `x.node`, `x.ele` (region tags as attributes) and `x.face` (face tags
/// as markers), numbered from 1, all renamed into place together.
///
/// # Errors
/// [`IoError::NotRepresentable`] for a `.poly`/`.smesh` path, [`IoError::Write`].
pub fn write_volume(path: &Path, m: &TetMesh) -> Result<(), IoError> {
    if !matches!(extension(path).as_str(), "node" | "ele" | "face") {
        return Err(not_representable(path, "a tetrahedral mesh as a piecewise linear complex (use .node, .ele or .face)"));
    }
    let paths = siblings(path, &["node", "ele", "face"]);
    write_atomic_many(&paths, |w| {
        let [wn, we, wf] = w else { unreachable!("three writers for three paths") };
        write_node_list(&paths[0], wn, &m.vertices)?;
        let e = write_err(&paths[1]);
        writeln!(we, "{} 4 1", m.tets.len()).map_err(&e)?;
        for (i, (t, r)) in m.tets.iter().zip(&m.region_tags).enumerate() {
            writeln!(we, "{} {} {} {} {} {}", i + 1, t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1, r.0).map_err(&e)?;
        }
        write_face_list(&paths[2], wf, &m.boundary, &m.face_tags)
    })
}

/// Writes a surface: `x.poly` or `x.smesh` when that is the extension given (one triangle per
/// facet, with its tag as marker), otherwise `x.node` + `x.face`.
///
/// # Errors
/// [`IoError::Write`].
pub fn write_surface(path: &Path, s: &TriSurface) -> Result<(), IoError> {
    match extension(path).as_str() {
        "poly" => poly::write(path, s, false),
        "smesh" => poly::write(path, s, true),
        _ => {
            let paths = siblings(path, &["node", "face"]);
            write_atomic_many(&paths, |w| {
                let [wn, wf] = w else { unreachable!("two writers for two paths") };
                write_node_list(&paths[0], wn, &s.vertices)?;
                write_face_list(&paths[1], wf, &s.triangles, &s.face_tags)
            })
        }
    }
}

/// Writes a point set as `x.node`.
///
/// # Errors
/// [`IoError::NotRepresentable`] unless the extension is `.node`, [`IoError::Write`].
pub fn write_points(path: &Path, points: &[DVec3]) -> Result<(), IoError> {
    if extension(path) != "node" {
        return Err(not_representable(path, &format!("a point set as .{} (use .node)", extension(path))));
    }
    write_atomic(path, |w| write_node_list(path, w, points))
}

/// Writes a node list with its header line, numbered from 1.
pub(crate) fn write_node_list(path: &Path, w: &mut BufWriter<File>, points: &[DVec3]) -> Result<(), IoError> {
    let e = write_err(path);
    writeln!(w, "{} 3 0 0", points.len()).map_err(&e)?;
    for (i, p) in points.iter().enumerate() {
        writeln!(w, "{} {} {} {}", i + 1, Num(p.x), Num(p.y), Num(p.z)).map_err(&e)?;
    }
    Ok(())
}

fn write_face_list(path: &Path, w: &mut BufWriter<File>, tris: &[[u32; 3]], tags: &[FaceId]) -> Result<(), IoError> {
    let e = write_err(path);
    writeln!(w, "{} 1", tris.len()).map_err(&e)?;
    for (i, (t, tag)) in tris.iter().zip(tags).enumerate() {
        writeln!(w, "{} {} {} {} {}", i + 1, t[0] + 1, t[1] + 1, t[2] + 1, tag.0).map_err(&e)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests;
