//! Wavefront OBJ.
//!
//! Reading takes two passes over the text:
//!
//! 1. A scan of the statements, line by line, which is what makes errors name their line: it
//!    parses `v` coordinates in full `f64` precision (a non-finite coordinate is an error),
//!    resolves `f` corner references (1-based, or negative relative to the last vertex
//!    defined; an index outside the file's vertices is an error naming the line of the `f`
//!    statement), and tracks objects (`o`) and groups (`g`).
//! 2. [`tobj`] parses the geometric statements again, normalised (positions only, absolute
//!    indices, one `g` per run of faces with the same tag) so that none of its limitations
//!    apply (`l` polylines read as faces, mandatory two-component texture coordinates,
//!    vertex colours on only some vertices, `f32` coordinates). Its objects, face arities and
//!    indices are cross-checked against the scan, face by face.
//!
//! Each distinct (object, group) pair holding faces becomes a tag 1, 2, … in order of
//! appearance, named after the group (or the object where there is no group; `object/group`
//! where two pairs would otherwise share a name). Polygons are triangulated with
//! [`crate::io::polygon::triangulate`]. Points, lines, free-form geometry, materials, texture
//! coordinates and normals are ignored (with a note). The reader returns every vertex of the
//! file; [`crate::io::read`] welds and drops unused ones.

use crate::core::FaceId;
use crate::io::atomic::{write_atomic, write_err};
use crate::io::common::Num;
use crate::io::polygon::{self, Outcome};
use crate::io::{Format, IoError, Loaded, MeshData};
use crate::mesh::TriSurface;
use glam::DVec3;
use std::borrow::Cow;
use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;
use std::str::SplitAsciiWhitespace;

/// An (object, group) pair: faces with the same pair share a tag.
type GroupKey = (Option<String>, Option<String>);

/// One `f` statement with at least three corners.
struct Face {
    /// 1-based line of the statement.
    line: usize,
    /// First corner in [`Scan::corners`].
    start: usize,
    /// Number of corners.
    len: usize,
    /// Its tag.
    tag: u32,
}

/// What the scan of the statements found.
#[derive(Default)]
struct Scan {
    vertices: Vec<DVec3>,
    texcoords: usize,
    normals: usize,
    /// 0-based vertex index of every face corner; absolute indices are checked against the
    /// vertex count at the end (they may refer forward).
    corners: Vec<u32>,
    faces: Vec<Face>,
    /// Tag `k` is `keys[k - 1]`.
    keys: Vec<GroupKey>,
    key_tags: HashMap<GroupKey, u32>,
    object: Option<String>,
    group: Option<String>,
    tag: Option<u32>,
    points_lines: usize,
    free_form: usize,
    missing_attributes: usize,
    unknown: Option<(usize, String)>,
}

const IGNORED: &[&str] = &[
    "vp", "s", "mg", "usemtl", "mtllib", "usemap", "maplib", "lod", "bevel", "c_interp", "d_interp", "shadow_obj",
    "trace_obj", "ctech", "stech", "call", "csh",
];
const FREE_FORM: &[&str] = &["cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end", "con"];

fn shorten(t: &str) -> String {
    if t.chars().count() > 40 { format!("{}…", t.chars().take(40).collect::<String>()) } else { t.to_string() }
}

/// A finite number, or an error naming the line.
fn number(path: &Path, line: usize, what: &str, t: &str) -> Result<f64, IoError> {
    let x: f64 = t.parse().map_err(|_| IoError::at_line(path, line, format!("expected {what}, found '{}'", shorten(t))))?;
    if x.is_finite() { Ok(x) } else { Err(IoError::at_line(path, line, format!("{what} is not a finite number: '{}'", shorten(t)))) }
}

/// The name after `o` or `g`: its words joined by single spaces, `None` if there are none.
fn name(words: SplitAsciiWhitespace<'_>) -> Option<String> {
    let n = words.collect::<Vec<_>>().join(" ");
    if n.is_empty() { None } else { Some(n) }
}

impl Scan {
    fn run(path: &Path, text: &str) -> Result<Scan, IoError> {
        let mut s = Scan::default();
        let mut lines = text.split('\n').enumerate();
        let strip = |r: &'_ str| -> usize { r.strip_suffix('\r').map_or(r.len(), str::len) };
        while let Some((i, raw)) = lines.next() {
            let line = i + 1;
            let mut stmt: Cow<'_, str> = Cow::Borrowed(&raw[..strip(raw)]);
            // a backslash at the end of a line continues the statement on the next one
            while stmt.ends_with('\\') {
                let mut joined = stmt.into_owned();
                joined.pop();
                joined.push(' ');
                if let Some((_, r)) = lines.next() {
                    joined.push_str(&r[..strip(r)]);
                }
                stmt = Cow::Owned(joined);
            }
            let body = match stmt.find('#') {
                Some(k) => &stmt[..k],
                None => &stmt[..],
            };
            let mut words = body.split_ascii_whitespace();
            let Some(keyword) = words.next() else { continue };
            match keyword {
                "v" => s.vertex(path, line, words)?,
                "vt" => s.texcoords += 1,
                "vn" => s.normals += 1,
                "f" | "fo" => s.face(path, line, words)?,
                "l" | "p" => s.points_lines += 1,
                "o" => {
                    s.object = name(words);
                    s.group = None;
                    s.tag = None;
                }
                "g" => {
                    s.group = name(words);
                    s.tag = None;
                }
                k if IGNORED.contains(&k) => {}
                k if FREE_FORM.contains(&k) => s.free_form += 1,
                k => {
                    if s.unknown.is_none() {
                        s.unknown = Some((line, shorten(k)));
                    }
                }
            }
        }
        let n = s.vertices.len();
        for f in &s.faces {
            if let Some(&c) = s.corners.get(f.start..f.start + f.len).and_then(|c| c.iter().find(|&&c| c as usize >= n)) {
                return Err(IoError::at_line(
                    path,
                    f.line,
                    format!("vertex index {} is out of range: the file defines {n} vertices (OBJ indices start at 1)", c as u64 + 1),
                ));
            }
        }
        Ok(s)
    }

    fn vertex(&mut self, path: &Path, line: usize, mut words: SplitAsciiWhitespace<'_>) -> Result<(), IoError> {
        let mut p = [0.0; 3];
        for (k, c) in p.iter_mut().enumerate() {
            let Some(t) = words.next() else {
                return Err(IoError::at_line(path, line, format!("expected 3 vertex coordinates, found {k}")));
            };
            *c = number(path, line, "vertex coordinate", t)?;
        }
        let mut p = DVec3::from_array(p);
        let rest: Vec<&str> = words.collect();
        // one more number is a weight; three or more are a colour, ignored
        if let [w] = rest[..] {
            let w = number(path, line, "vertex weight", w)?;
            if w == 0.0 {
                return Err(IoError::at_line(path, line, "vertex weight is 0"));
            }
            p /= w;
            if !p.is_finite() {
                return Err(IoError::at_line(path, line, "vertex coordinate divided by its weight is not a finite number"));
            }
        }
        if u32::try_from(self.vertices.len()).is_err() {
            return Err(IoError::at_line(path, line, "more than 4,294,967,296 vertices"));
        }
        self.vertices.push(p);
        Ok(())
    }

    /// Parses one index of a corner reference: positive (1-based) or negative (relative to the
    /// `count` elements defined so far). `Ok(None)` for a relative index before the first
    /// element or for 0.
    fn index(path: &Path, line: usize, t: &str, count: usize, what: &str) -> Result<Option<u64>, IoError> {
        let k: i64 = t
            .parse()
            .map_err(|_| IoError::at_line(path, line, format!("expected a {what} index (an integer), found '{}'", shorten(t))))?;
        Ok(match k {
            0 => None,
            k if k > 0 => Some(k as u64 - 1),
            k => (count as i64).checked_add(k).filter(|&r| r >= 0).map(|r| r as u64),
        })
    }

    fn face(&mut self, path: &Path, line: usize, words: SplitAsciiWhitespace<'_>) -> Result<(), IoError> {
        let start = self.corners.len();
        for w in words {
            let mut parts = w.split('/');
            let v = parts.next().unwrap_or_default();
            let count = self.vertices.len();
            match Scan::index(path, line, v, count, "vertex")? {
                Some(i) if i <= u64::from(crate::core::ids::INDEX_MAX) => self.corners.push(i as u32),
                Some(i) => {
                    return Err(IoError::at_line(path, line, format!("vertex index {} is out of range (at most 4,294,967,296 vertices)", i + 1)));
                }
                None if v.starts_with('-') => {
                    return Err(IoError::at_line(
                        path,
                        line,
                        format!("relative vertex index {v} reaches before the first vertex: {count} vertices are defined before this line"),
                    ));
                }
                None => {
                    return Err(IoError::at_line(
                        path,
                        line,
                        "vertex index 0 is invalid: OBJ indices start at 1 (negative ones count back from the last vertex)",
                    ));
                }
            }
            let mut missing = false;
            for (t, count, what) in [(parts.next(), self.texcoords, "texture coordinate"), (parts.next(), self.normals, "normal")] {
                if let Some(t) = t.filter(|t| !t.is_empty()) {
                    missing |= Scan::index(path, line, t, count, what)?.is_none_or(|i| i >= count as u64);
                }
            }
            self.missing_attributes += usize::from(missing);
            if parts.next().is_some() {
                return Err(IoError::at_line(
                    path,
                    line,
                    format!("expected a corner like '3', '3/1', '3//2' or '3/1/2', found '{}'", shorten(w)),
                ));
            }
        }
        let len = self.corners.len() - start;
        if len < 3 {
            self.corners.truncate(start);
            self.points_lines += 1;
            return Ok(());
        }
        let tag = match self.tag {
            Some(t) => t,
            None => {
                let key = (self.object.clone(), self.group.clone());
                let next = FaceId::from_index(self.keys.len()).0;
                let keys = &mut self.keys;
                let t = *self.key_tags.entry(key.clone()).or_insert_with(|| {
                    keys.push(key);
                    next
                });
                self.tag = Some(t);
                t
            }
        };
        self.faces.push(Face { line, start, len, tag });
        Ok(())
    }

    /// The faces as tobj reads them from a normalised copy of the geometric statements.
    fn tobj_models(&self) -> Result<Vec<tobj::Model>, tobj::LoadError> {
        let mut text = String::with_capacity(24 * self.vertices.len() + 12 * self.corners.len());
        for p in &self.vertices {
            let _ = writeln!(text, "v {} {} {}", Num(p.x), Num(p.y), Num(p.z));
        }
        let mut tag = 0;
        for f in &self.faces {
            if f.tag != tag {
                tag = f.tag;
                let _ = writeln!(text, "g t{tag}");
            }
            text.push('f');
            for c in self.corners.get(f.start..f.start + f.len).unwrap_or_default() {
                let _ = write!(text, " {}", u64::from(*c) + 1);
            }
            text.push('\n');
        }
        // the update keeps this compiling should tobj's optional fields be enabled
        #[allow(clippy::needless_update)]
        let options = tobj::LoadOptions { triangulate: false, single_index: false, ignore_points: true, ignore_lines: true, ..Default::default() };
        tobj::load_obj_buf(&mut text.as_bytes(), &options, |_| Err(tobj::LoadError::OpenFileFailed)).map(|(models, _)| models)
    }

    /// Checks that tobj's objects, arities and indices describe the scanned faces.
    fn cross_check(&self, models: &[tobj::Model]) -> Result<(), Disagreement> {
        let mut faces = self.faces.iter();
        for m in models.iter().filter(|m| !m.mesh.indices.is_empty()) {
            let tag: u32 = m.name.strip_prefix('t').and_then(|t| t.parse().ok()).ok_or_else(|| Disagreement::Object(m.name.clone()))?;
            let arities: Vec<usize> = if m.mesh.face_arities.is_empty() {
                vec![3; m.mesh.indices.len() / 3]
            } else {
                m.mesh.face_arities.iter().map(|&a| a as usize).collect()
            };
            let mut to_global: Vec<u32> = Vec::new();
            let mut at = 0;
            for arity in arities {
                let f = faces.next().ok_or(Disagreement::MoreFaces)?;
                if f.len != arity || f.tag != tag {
                    return Err(Disagreement::Face { line: f.line, corners: f.len, tag: f.tag, tobj_corners: arity, tobj_tag: tag });
                }
                let ours = self.corners.get(f.start..f.start + f.len).ok_or(Disagreement::CornerOutOfRange { line: f.line })?;
                for (k, &g) in ours.iter().enumerate() {
                    let l = *m.mesh.indices.get(at + k).ok_or(Disagreement::FewerIndices { line: f.line })? as usize;
                    match to_global.get(l) {
                        Some(&x) if x == g => {}
                        None if l == to_global.len() => to_global.push(g),
                        _ => return Err(Disagreement::Corner { line: f.line, corner: k, vertex: g }),
                    }
                }
                at += arity;
            }
        }
        match faces.next() {
            Some(f) => Err(Disagreement::LostFace { line: f.line }),
            None => Ok(()),
        }
    }

    /// Tag names: the group, else the object; `object/group` where names would repeat.
    fn face_names(&self) -> Vec<Option<String>> {
        let plain: Vec<Option<&String>> = self.keys.iter().map(|(o, g)| g.as_ref().or(o.as_ref())).collect();
        let mut uses: HashMap<Option<&String>, usize> = HashMap::new();
        for n in &plain {
            *uses.entry(*n).or_default() += 1;
        }
        self.keys
            .iter()
            .zip(&plain)
            .map(|((o, g), n)| match (o, g) {
                (Some(o), Some(g)) if uses.get(n).copied().unwrap_or(0) > 1 => Some(format!("{o}/{g}")),
                _ => n.cloned(),
            })
            .collect()
    }
}

/// Where tobj's reading of the faces disagrees with fepre's scan (a bug of one of the two,
/// reported as an internal error naming the face's line).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
enum Disagreement {
    /// tobj made an object that the scan's re-emitted text does not name.
    #[error("unexpected object '{0}'")]
    Object(String),
    /// tobj found faces beyond the scan's.
    #[error("tobj found more faces")]
    MoreFaces,
    /// The corner count or the tag of a face differs.
    #[error("face of line {line}: {corners} corners with tag {tag}, tobj: {tobj_corners} with tag {tobj_tag}")]
    Face {
        /// The face's line.
        line: usize,
        /// Its corners by the scan.
        corners: usize,
        /// Its tag by the scan.
        tag: u32,
        /// Its corners by tobj.
        tobj_corners: usize,
        /// Its tag by tobj.
        tobj_tag: u32,
    },
    /// The scan's corner range of a face lies outside its corner list.
    #[error("corner out of range")]
    CornerOutOfRange {
        /// The face's line.
        line: usize,
    },
    /// tobj holds fewer indices than the faces' corners.
    #[error("tobj has too few indices")]
    FewerIndices {
        /// The face's line.
        line: usize,
    },
    /// A corner refers to another vertex.
    #[error("face of line {line}: corner {corner} is vertex {vertex}, tobj disagrees")]
    Corner {
        /// The face's line.
        line: usize,
        /// The corner, 0-based.
        corner: usize,
        /// The scan's vertex, 0-based.
        vertex: u32,
    },
    /// tobj lost a face of the scan.
    #[error("tobj lost the face of line {line}")]
    LostFace {
        /// The face's line.
        line: usize,
    },
}

/// Reads an OBJ file's bytes (text; bytes that are not UTF-8 are replaced, which matters only
/// in names and comments).
///
/// # Errors
/// A malformed or non-finite coordinate, a malformed corner reference, or a vertex index
/// outside the file's vertices: each names its line.
pub fn read(path: &Path, bytes: &[u8]) -> Result<Loaded, IoError> {
    let text = String::from_utf8_lossy(bytes);
    let mut scan = Scan::run(path, &text)?;
    if scan.faces.is_empty() {
        if let Some((line, k)) = &scan.unknown {
            return Err(IoError::at_line(path, *line, format!("no faces found, and '{k}' is not an OBJ statement: is this an OBJ file?")));
        }
    }
    let models = scan.tobj_models().map_err(|e| IoError::in_file(path, format!("tobj cannot parse the faces: {e}")))?;
    scan.cross_check(&models)
        .map_err(|e| IoError::in_file(path, format!("internal error, please report this file: tobj and fepre's scan disagree ({e})")))?;

    let file_vertices = scan.vertices.len();
    let mut s = TriSurface { vertices: std::mem::take(&mut scan.vertices), ..TriSurface::default() };
    let (mut approximate, mut degenerate) = (0usize, 0usize);
    for f in &scan.faces {
        let corners = scan.corners.get(f.start..f.start + f.len).unwrap_or_default();
        match polygon::triangulate(corners, &s.vertices, &mut s.triangles) {
            Outcome::Exact => {}
            Outcome::Approximate => approximate += 1,
            Outcome::Degenerate => degenerate += 1,
        }
        s.face_tags.resize(s.triangles.len(), FaceId(f.tag));
    }
    for (k, n) in scan.face_names().into_iter().enumerate() {
        if let Some(n) = n {
            s.face_names.insert(FaceId::from_index(k), n);
        }
    }
    let mut loaded = Loaded::new(MeshData::Surface(s), Format::Obj, file_vertices);
    let notes = [
        (scan.faces.is_empty(), "the file has no faces".to_string()),
        (scan.points_lines > 0, format!("ignored {} point and line elements", scan.points_lines)),
        (scan.free_form > 0, format!("ignored {} free-form geometry statements (curves and surfaces)", scan.free_form)),
        (
            scan.missing_attributes > 0,
            format!("{} face corners refer to missing texture coordinates or normals (ignored: only positions are read)", scan.missing_attributes),
        ),
        (degenerate > 0, format!("dropped {degenerate} faces with fewer than three distinct vertices")),
        (approximate > 0, format!("{approximate} polygons are not simple in their plane; they were triangulated approximately")),
    ];
    loaded.notes.extend(notes.into_iter().filter(|(on, _)| *on).map(|(_, n)| n));
    Ok(loaded)
}

/// The OBJ group names of the tags of `s`: the tag's name with whitespace and `#` made `_`,
/// `tag_<n>` if unnamed, then made unique ([`crate::core::TagNames::unique`]).
fn group_names(s: &TriSurface) -> BTreeMap<FaceId, String> {
    s.face_names.unique(s.face_tags.iter().copied(), |tag, name| {
        Some(match name.map(str::trim).filter(|n| !n.is_empty()) {
            Some(n) => n.chars().map(|c| if c.is_whitespace() || c == '#' { '_' } else { c }).collect(),
            None => format!("tag_{}", tag.0),
        })
    })
}

/// Writes `s` as OBJ: `v` lines with coordinates that read back exactly, then one `g` block
/// per tag (in increasing tag order, named from `face_names`, else `tag_<n>`, names made
/// unique) of 1-based `f` lines.
///
/// # Errors
/// [`IoError::Invalid`] if `s` is not a valid surface, [`IoError::Write`] for file-system
/// failures (no file is left behind).
pub fn write(path: &Path, s: &TriSurface) -> Result<(), IoError> {
    s.validate().map_err(|source| IoError::Invalid { path: path.to_path_buf(), source })?;
    let mut order: Vec<usize> = (0..s.triangles.len()).collect();
    order.sort_by_key(|&t| s.face_tags.get(t).copied().unwrap_or_default());
    let names = group_names(s);
    write_atomic(path, |w| {
        let e = write_err(path);
        writeln!(w, "# written by fepre: {} vertices, {} triangles", s.vertices.len(), s.triangles.len()).map_err(&e)?;
        for v in &s.vertices {
            writeln!(w, "v {} {} {}", Num(v.x), Num(v.y), Num(v.z)).map_err(&e)?;
        }
        let mut current = None;
        for t in order {
            let (Some(tri), Some(&tag)) = (s.triangles.get(t), s.face_tags.get(t)) else { continue };
            if current != Some(tag) {
                current = Some(tag);
                writeln!(w, "g {}", names.get(&tag).map_or("", String::as_str)).map_err(&e)?;
            }
            writeln!(w, "f {} {} {}", u64::from(tri[0]) + 1, u64::from(tri[1]) + 1, u64::from(tri[2]) + 1).map_err(&e)?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::ReadOptions;

    fn surface(bytes: &str) -> (TriSurface, Loaded) {
        let l = read(Path::new("t.obj"), bytes.as_bytes()).unwrap();
        let MeshData::Surface(s) = l.mesh.clone() else { panic!() };
        (s, l)
    }

    fn err(text: &str) -> String {
        read(Path::new("bad.obj"), text.as_bytes()).unwrap_err().to_string()
    }

    const CUBE: &str = "# a unit cube of quads, split into two objects
o lower
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vn 0 0 1
usemtl red
f 1//1 4//1 3//1 2//1
g sides
f 1 2 6 5
f -7 -6 -2 -3
usemtl blue
f 3 4 8 7
f 4 1 5 8
o upper
f 5 6 7 8
";

    #[test]
    fn objects_and_groups_become_tags_in_order() {
        let (s, l) = surface(CUBE);
        assert_eq!(l.file_vertices, 8);
        assert_eq!(s.triangles.len(), 12);
        assert_eq!(s.tags(), vec![FaceId(1), FaceId(2), FaceId(3)]);
        assert_eq!(s.face_tags.iter().filter(|&&t| t == FaceId(2)).count(), 8);
        assert_eq!(s.face_names.get(FaceId(1)), Some("lower"));
        assert_eq!(s.face_names.get(FaceId(2)), Some("sides"));
        assert_eq!(s.face_names.get(FaceId(3)), Some("upper"));
        // relative indices: -7 -6 -2 -3 are 2 3 7 6 with 8 vertices defined
        assert!(s.triangles[4..6].iter().all(|t| t.iter().all(|&i| [1, 2, 6, 5].contains(&i))));
        s.validate().unwrap();
        // the cube is closed and outward: the signed volume is 1
        let vol: f64 = (0..s.triangles.len()).map(|t| {
            let [a, b, c] = s.corners(t);
            a.dot(b.cross(c)) / 6.0
        }).sum();
        assert!((vol - 1.0).abs() < 1e-12, "{vol}");
    }

    #[test]
    fn ngons_forward_references_continuations_and_ignored_elements() {
        let text = "f 1 2 3 4 5 6\nv 0 0 0\nv 2 0 0\nv 2 1 0 1\nv 1 \\\n 1 0\nv 0.5 1 0 0.5\nv 0 2 0 # six\nl 1 2 3\np 4\nf 1 2\nf 1 1 2\ncurv 0 1 1 2\nf 1/1/1 2/2/2 3/3/3\n";
        let (s, l) = surface(text);
        assert_eq!(l.file_vertices, 6);
        assert_eq!(s.vertices[4], DVec3::new(1.0, 2.0, 0.0), "the weight divides");
        assert_eq!(s.triangles.len(), 5, "an L-shaped hexagon gives 4, plus one triangle");
        let area: f64 = (0..4).map(|t| {
            let [a, b, c] = s.corners(t);
            (b - a).cross(c - a).z / 2.0
        }).sum();
        assert_eq!(area, 3.0);
        assert_eq!(s.tags(), vec![FaceId(1)]);
        assert!(s.face_names.is_empty());
        let notes = l.notes.join("\n");
        assert!(notes.contains("ignored 3 point and line elements"), "{notes}");
        assert!(notes.contains("free-form"), "{notes}");
        assert!(notes.contains("dropped 1 faces"), "{notes}");
        assert!(notes.contains("3 face corners refer to missing texture coordinates"), "{notes}");
    }

    #[test]
    fn errors_name_the_line() {
        let tet = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\n";
        assert_eq!(err(&format!("{tet}f 2 3 9\n")), "bad.obj:7: vertex index 9 is out of range: the file defines 4 vertices (OBJ indices start at 1)");
        assert!(err(&format!("{tet}\n\nf -1 -2 -5\n")).starts_with("bad.obj:9: relative vertex index -5 reaches before"));
        assert!(err(&format!("{tet}f 0 1 2\n")).starts_with("bad.obj:7: vertex index 0 is invalid"));
        assert!(err(&format!("{tet}f 1 2 x\n")).starts_with("bad.obj:7: expected a vertex index"));
        assert!(err(&format!("{tet}f 1/1/1/1 2 3\n")).starts_with("bad.obj:7: expected a corner"));
        assert_eq!(err("v 0 0 0\nv 1 nan 0\n"), "bad.obj:2: vertex coordinate is not a finite number: 'nan'");
        assert_eq!(err("v 0 0 0\nv 1 1e999 0\n"), "bad.obj:2: vertex coordinate is not a finite number: '1e999'");
        assert_eq!(err("v 0 0\n"), "bad.obj:1: expected 3 vertex coordinates, found 2");
        assert_eq!(err("v 0 0 1 0\n"), "bad.obj:1: vertex weight is 0");
        assert!(err("\u{0}\u{1}binary junk\n").starts_with("bad.obj:1: no faces found"));
        // a file of vertices only is a surface without triangles, with a note
        let (s, l) = surface("v 0 0 0\n");
        assert!(s.triangles.is_empty() && l.notes[0].contains("no faces"));
    }

    #[test]
    fn writes_and_reads_back() {
        let dir = tempfile::tempdir().unwrap();
        let (mut s, _) = surface(CUBE);
        s.face_names.insert(FaceId(3), "top lid#1");
        s.face_names.remove(FaceId(1));
        s.vertices[6] = DVec3::new(1.0 + 1e-15, 0.1 + 0.2, 1e-300);
        let p = dir.path().join("cube.obj");
        crate::io::write(&p, &MeshData::Surface(s.clone()), &crate::io::WriteOptions::default()).unwrap();
        let raw = crate::io::read(&p, &ReadOptions::default().with_weld(None)).unwrap();
        let MeshData::Surface(r) = raw.mesh else { panic!() };
        assert_eq!(r.vertices, s.vertices, "coordinates read back exactly");
        assert_eq!(r.triangles.len(), 12);
        assert_eq!(r.tags(), s.tags());
        for tag in s.tags() {
            assert_eq!(r.face_tags.iter().filter(|&&t| t == tag).count(), s.face_tags.iter().filter(|&&t| t == tag).count());
        }
        assert_eq!(r.face_names.get(FaceId(1)), Some("tag_1"));
        assert_eq!(r.face_names.get(FaceId(3)), Some("top_lid_1"));
        let welded = crate::io::read(&p, &ReadOptions::default()).unwrap();
        let MeshData::Surface(w) = welded.mesh else { panic!() };
        assert_eq!((w.vertices.len(), w.triangles.len()), (8, 12));
        // names that clean to the same group name, or to another tag's fallback, stay apart
        s.face_names.insert(FaceId(1), "tag 2");
        s.face_names.insert(FaceId(2), "tag#2");
        crate::io::write(&p, &MeshData::Surface(s.clone()), &crate::io::WriteOptions::default()).unwrap();
        let MeshData::Surface(u) = crate::io::read(&p, &ReadOptions::default()).unwrap().mesh else { panic!() };
        let names: Vec<&str> = u.face_names.names().collect();
        assert_eq!(names, ["tag_2", "tag_2.2", "top_lid_1"]);
        // an invalid surface is not written, and leaves no file
        s.face_tags.pop();
        let q = dir.path().join("bad.obj");
        assert!(matches!(write(&q, &s), Err(IoError::Invalid { .. })));
        assert!(!q.exists());
    }

    #[test]
    fn mangled_input_never_panics() {
        let base = CUBE.as_bytes();
        for cut in 0..base.len() {
            let _ = read(Path::new("m.obj"), &base[..cut]);
        }
        let subst: &[u8] = b"-0/ \n\\#9e";
        for i in 0..base.len() {
            for &b in subst {
                let mut m = base.to_vec();
                m[i] = b;
                if let Ok(l) = read(Path::new("m.obj"), &m) {
                    let MeshData::Surface(s) = l.mesh else { panic!() };
                    s.validate().unwrap();
                }
            }
        }
        for text in ["f -9223372036854775808 1 2", "f 99999999999999999999 1 2", "v 1 2 3\nf 1/-999999999999/2 1 1 1", "o\ng\nf\n"] {
            let _ = read(Path::new("m.obj"), text.as_bytes());
        }
    }
}
