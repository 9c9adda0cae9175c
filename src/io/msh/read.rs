//! The MSH reader: 4.1 ASCII and binary, 2.2 ASCII.

use crate::core::{FaceId, RegionId};
use crate::io::common::{orient_tets, unused_vertices_note};
use crate::io::text::Tokens;
use crate::io::{Format, IoError, Loaded, Location, MeshData};
use crate::mesh::{TetMesh, TriSurface};
use glam::DVec3;
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::Path;

/// What an element type is to us: its node count and whether it is a triangle or a tet.
#[derive(Copy, Clone, PartialEq)]
enum Kind {
    Triangle,
    Tet,
    Other,
}

/// Node count and kind of a Gmsh element type, `None` for a type we do not know.
fn element_type(t: i32) -> Option<(usize, Kind)> {
    use Kind::*;
    Some(match t {
        2 => (3, Triangle),
        9 => (6, Triangle),
        20 => (9, Triangle),
        21 => (10, Triangle),
        22 => (12, Triangle),
        23 | 24 => (15, Triangle),
        25 => (21, Triangle),
        4 => (4, Tet),
        11 => (10, Tet),
        29 => (20, Tet),
        30 => (35, Tet),
        31 => (56, Tet),
        1 => (2, Other),
        3 => (4, Other),
        5 => (8, Other),
        6 => (6, Other),
        7 => (5, Other),
        8 => (3, Other),
        10 => (9, Other),
        12 => (27, Other),
        13 => (18, Other),
        14 => (14, Other),
        15 => (1, Other),
        16 => (8, Other),
        17 => (20, Other),
        18 => (15, Other),
        19 => (13, Other),
        26 => (4, Other),
        27 => (5, Other),
        28 => (6, Other),
        92 => (64, Other),
        93 => (125, Other),
        _ => return None,
    })
}

fn type_name(t: i32) -> String {
    let name = match t {
        1 => "2-node line",
        3 => "4-node quadrangle",
        5 => "8-node hexahedron",
        6 => "6-node prism",
        7 => "5-node pyramid",
        8 => "3-node line",
        15 => "point",
        _ => "",
    };
    if name.is_empty() { format!("type {t}") } else { format!("{name} (type {t})") }
}

#[derive(Copy, Clone, PartialEq)]
enum Version {
    V41,
    V22,
}

/// A cursor over a binary block of the file, with the byte order of the file.
struct Bin<'a> {
    path: &'a Path,
    data: &'a [u8],
    pos: usize,
    big_endian: bool,
    section: &'static str,
}

impl Bin<'_> {
    fn take<const N: usize>(&mut self, what: &str) -> Result<[u8; N], IoError> {
        match self.data.get(self.pos..self.pos + N).and_then(|s| <[u8; N]>::try_from(s).ok()) {
            Some(mut b) => {
                self.pos += N;
                if self.big_endian {
                    b.reverse();
                }
                Ok(b)
            }
            None => Err(IoError::Parse {
                path: self.path.to_path_buf(),
                at: Location::Byte(self.pos as u64),
                message: format!("{} is truncated: expected {what}", self.section),
            }),
        }
    }

    fn int(&mut self, what: &str) -> Result<i32, IoError> {
        Ok(i32::from_le_bytes(self.take(what)?))
    }

    fn size(&mut self, what: &str) -> Result<u64, IoError> {
        Ok(u64::from_le_bytes(self.take(what)?))
    }

    fn count(&mut self, what: &str) -> Result<usize, IoError> {
        let at = self.pos;
        let n = self.size(what)?;
        usize::try_from(n).ok().filter(|&n| n <= self.data.len()).ok_or_else(|| IoError::Parse {
            path: self.path.to_path_buf(),
            at: Location::Byte(at as u64),
            message: format!("{} has an impossible count {n} for {what}", self.section),
        })
    }

    fn f64(&mut self, what: &str) -> Result<f64, IoError> {
        Ok(f64::from_le_bytes(self.take(what)?))
    }
}

struct Reader<'a> {
    path: &'a Path,
    bytes: &'a [u8],
    tok: Tokens<'a>,
    version: Version,
    binary: bool,
    big_endian: bool,
    /// (dimension, physical tag) → name.
    names: BTreeMap<(i32, u32), String>,
    /// (dimension, entity tag) → physical tags.
    physicals: HashMap<(i32, u32), Vec<u32>>,
    node_tags: Vec<u64>,
    points: Vec<DVec3>,
    /// Element tag and corner node tags.
    tris: Vec<(u64, [u64; 3])>,
    tri_tags: Vec<u32>,
    tets: Vec<(u64, [u64; 4])>,
    tet_tags: Vec<u32>,
    /// Tags that came from physical groups, per dimension (2, 3).
    from_physical: BTreeSet<(i32, u32)>,
    skipped: BTreeMap<i32, usize>,
    reduced: BTreeMap<i32, usize>,
    notes: Vec<String>,
}

/// Reads an MSH file.
pub(super) fn read(path: &Path, bytes: &[u8]) -> Result<Loaded, IoError> {
    let mut r = Reader {
        path,
        bytes,
        tok: Tokens::new(path, bytes, None),
        version: Version::V41,
        binary: false,
        big_endian: false,
        names: BTreeMap::new(),
        physicals: HashMap::new(),
        node_tags: Vec::new(),
        points: Vec::new(),
        tris: Vec::new(),
        tri_tags: Vec::new(),
        tets: Vec::new(),
        tet_tags: Vec::new(),
        from_physical: BTreeSet::new(),
        skipped: BTreeMap::new(),
        reduced: BTreeMap::new(),
        notes: Vec::new(),
    };
    match r.tok.next() {
        Some("$MeshFormat") => r.mesh_format()?,
        Some(t) => {
            return Err(r
                .tok
                .error(format!("not a Gmsh MSH file: expected $MeshFormat, found '{}'", t.chars().take(40).collect::<String>())));
        }
        None => return Err(IoError::Empty { path: path.to_path_buf() }),
    }
    while let Some(t) = r.tok.next() {
        match t {
            "$PhysicalNames" => r.physical_names()?,
            "$Entities" => r.entities()?,
            "$Nodes" => r.nodes()?,
            "$Elements" => r.elements()?,
            "$PartitionedEntities" => {
                return Err(r.unsupported("a partitioned mesh; re-export it from Gmsh without partitions"));
            }
            s if s.starts_with('$') && !s.starts_with("$End") => r.skip_section(s)?,
            s => {
                return Err(r
                    .tok
                    .error(format!("expected a section such as $Nodes or $Elements, found '{}'", s.chars().take(40).collect::<String>())));
            }
        }
    }
    r.finish()
}

impl<'a> Reader<'a> {
    fn unsupported(&self, message: impl Into<String>) -> IoError {
        IoError::Unsupported { path: self.path.to_path_buf(), at: Location::Line(self.tok.line()), message: message.into() }
    }

    fn end(&mut self, section: &str) -> Result<(), IoError> {
        let want = format!("$End{section}");
        match self.tok.next() {
            Some(t) if t == want => Ok(()),
            Some(t) => Err(self.tok.error(format!(
                "expected {want}, found '{}' (does the section hold more data than its counts say?)",
                t.chars().take(40).collect::<String>()
            ))),
            None => Err(self.tok.error(format!("unexpected end of file: expected {want} (is the file truncated?)"))),
        }
    }

    fn mesh_format(&mut self) -> Result<(), IoError> {
        let version = self.tok.next_or_error("the version number")?;
        let file_type: u32 = self.tok.parse("the file type (0 for ASCII, 1 for binary)")?;
        let data_size: u32 = self.tok.parse("the data size")?;
        self.binary = match file_type {
            0 => false,
            1 => true,
            t => return Err(self.tok.error(format!("file type {t}: expected 0 (ASCII) or 1 (binary)"))),
        };
        self.version = match version {
            "4.1" => Version::V41,
            "2.2" | "2.1" | "2.0" | "2" if !self.binary => Version::V22,
            "2.2" | "2.1" | "2.0" | "2" => {
                return Err(self.unsupported("binary MSH 2.2; re-export as MSH 4.1 (gmsh in.msh -save -format msh41 -o out.msh)"));
            }
            "4" | "4.0" => return Err(self.unsupported("MSH 4.0; re-export as MSH 4.1 (gmsh in.msh -save -format msh41 -o out.msh)")),
            v => return Err(self.unsupported(format!("MSH version {v}; fepre reads 4.1 and 2.2"))),
        };
        if self.binary {
            if data_size != 8 {
                return Err(self.unsupported(format!("binary data size {data_size}; fepre reads files with 8-byte sizes")));
            }
            let mut b = self.binary_block("$MeshFormat")?;
            let one = i32::from_le_bytes(b.take("the integer 1 that tells the byte order")?);
            self.big_endian = match one {
                1 => false,
                0x0100_0000 => true,
                x => {
                    return Err(IoError::Parse {
                        path: self.path.to_path_buf(),
                        at: Location::Byte(b.pos as u64 - 4),
                        message: format!("expected the integer 1 after the binary header, found {x}"),
                    });
                }
            };
            let pos = b.pos;
            self.skip_to(pos);
        }
        self.end("MeshFormat")
    }

    /// A binary cursor starting after the end of the current line.
    fn binary_block(&self, section: &'static str) -> Result<Bin<'a>, IoError> {
        let start = self.tok.offset();
        let rest = self.tok.remaining();
        let nl = rest.iter().position(|&b| b == b'\n').filter(|&i| rest[..i].iter().all(|b| b.is_ascii_whitespace()));
        let Some(nl) = nl else {
            return Err(self.tok.error(format!("expected the end of the line before the binary data of {section}")));
        };
        Ok(Bin { path: self.path, data: self.bytes, pos: start + nl + 1, big_endian: self.big_endian, section })
    }

    fn skip_to(&mut self, pos: usize) {
        let n = pos.saturating_sub(self.tok.offset());
        self.tok.skip_bytes(n);
    }

    fn skip_section(&mut self, header: &str) -> Result<(), IoError> {
        let name = &header[1..];
        let end = format!("$End{name}");
        let rest = self.tok.remaining();
        let Some(at) = rest.windows(end.len()).position(|w| w == end.as_bytes()) else {
            return Err(self.tok.error(format!("section {header} has no {end}")));
        };
        self.tok.skip_bytes(at + end.len());
        self.notes.push(format!("skipped section {header}"));
        Ok(())
    }

    fn physical_names(&mut self) -> Result<(), IoError> {
        let n: usize = self.tok.parse("the number of physical names")?;
        for _ in 0..n {
            let dim: i32 = self.tok.parse("a physical group's dimension")?;
            let tag: i64 = self.tok.parse("a physical group's tag")?;
            let words = self.tok.rest_of_line().join(" ");
            let name = words.trim().trim_matches('"').to_string();
            self.names.insert((dim, tag.unsigned_abs() as u32), name);
        }
        self.end("PhysicalNames")
    }

    fn entities(&mut self) -> Result<(), IoError> {
        if self.version == Version::V22 {
            return self.skip_section("$Entities");
        }
        if self.binary {
            let mut b = self.binary_block("$Entities")?;
            let mut counts = [0usize; 4];
            for c in &mut counts {
                *c = b.count("the number of entities")?;
            }
            for (dim, &n) in counts.iter().enumerate() {
                for _ in 0..n {
                    let tag = b.int("an entity tag")?;
                    for _ in 0..if dim == 0 { 3 } else { 6 } {
                        b.f64("an entity's bounding box")?;
                    }
                    let np = b.count("the number of physical tags")?;
                    let phys = (0..np).map(|_| b.int("a physical tag").map(|p| p.unsigned_abs())).collect::<Result<Vec<_>, _>>()?;
                    if dim > 0 {
                        let nb = b.count("the number of bounding entities")?;
                        for _ in 0..nb {
                            b.int("a bounding entity")?;
                        }
                    }
                    self.physicals.insert((dim as i32, tag.unsigned_abs()), phys);
                }
            }
            let pos = b.pos;
            self.skip_to(pos);
        } else {
            let mut counts = [0usize; 4];
            for c in &mut counts {
                *c = self.tok.parse("the number of entities")?;
            }
            for (dim, &n) in counts.iter().enumerate() {
                for _ in 0..n {
                    let tag: i32 = self.tok.parse("an entity tag")?;
                    for _ in 0..if dim == 0 { 3 } else { 6 } {
                        self.tok.parse::<f64>("an entity's bounding box")?;
                    }
                    let np: usize = self.tok.parse("the number of physical tags")?;
                    let phys = (0..np)
                        .map(|_| self.tok.parse::<i32>("a physical tag").map(|p| p.unsigned_abs()))
                        .collect::<Result<Vec<_>, _>>()?;
                    if dim > 0 {
                        let nb: usize = self.tok.parse("the number of bounding entities")?;
                        for _ in 0..nb {
                            self.tok.parse::<i32>("a bounding entity")?;
                        }
                    }
                    self.physicals.insert((dim as i32, tag.unsigned_abs()), phys);
                }
            }
        }
        self.end("Entities")
    }

    fn nodes(&mut self) -> Result<(), IoError> {
        let cap = |n: usize, rest: usize| n.min(rest / 8 + 1);
        if self.version == Version::V22 {
            let n: usize = self.tok.parse("the number of nodes")?;
            self.node_tags.reserve(cap(n, self.tok.remaining().len()));
            for _ in 0..n {
                self.node_tags.push(self.tok.parse("a node tag")?);
                self.points.push(self.tok.point3("a node coordinate")?);
            }
        } else if self.binary {
            let mut b = self.binary_block("$Nodes")?;
            let blocks = b.count("the number of entity blocks")?;
            let total = b.count("the number of nodes")?;
            b.size("the smallest node tag")?;
            b.size("the largest node tag")?;
            let before = self.points.len();
            self.node_tags.reserve(cap(total, self.bytes.len()));
            self.points.reserve(cap(total, self.bytes.len()));
            for _ in 0..blocks {
                let dim = b.int("an entity dimension")?;
                b.int("an entity tag")?;
                let parametric = b.int("the parametric flag")? != 0;
                let n = b.count("the number of nodes in the block")?;
                let first = self.node_tags.len();
                for _ in 0..n {
                    self.node_tags.push(b.size("a node tag")?);
                }
                let extra = if parametric { dim.clamp(0, 3) as usize } else { 0 };
                for k in 0..n {
                    let at = b.pos;
                    let p = DVec3::new(b.f64("a node coordinate")?, b.f64("a node coordinate")?, b.f64("a node coordinate")?);
                    if !p.is_finite() {
                        return Err(IoError::Parse {
                            path: self.path.to_path_buf(),
                            at: Location::Byte(at as u64),
                            message: format!("node {} has a non-finite coordinate {p:?}", self.node_tags[first + k]),
                        });
                    }
                    for _ in 0..extra {
                        b.f64("a parametric coordinate")?;
                    }
                    self.points.push(p);
                }
            }
            if self.points.len() - before != total {
                return Err(IoError::at_entity(
                    self.path,
                    "$Nodes",
                    format!("the header counts {total} nodes but the blocks hold {}", self.points.len() - before),
                ));
            }
            let pos = b.pos;
            self.skip_to(pos);
        } else {
            let blocks: usize = self.tok.parse("the number of entity blocks")?;
            let total: usize = self.tok.parse("the number of nodes")?;
            self.tok.parse::<u64>("the smallest node tag")?;
            self.tok.parse::<u64>("the largest node tag")?;
            let header_line = self.tok.line();
            let before = self.points.len();
            self.node_tags.reserve(cap(total, self.tok.remaining().len()));
            self.points.reserve(cap(total, self.tok.remaining().len()));
            for _ in 0..blocks {
                let dim: i32 = self.tok.parse("an entity dimension")?;
                self.tok.parse::<i32>("an entity tag")?;
                let parametric: i32 = self.tok.parse("the parametric flag")?;
                let n: usize = self.tok.parse("the number of nodes in the block")?;
                for _ in 0..n {
                    self.node_tags.push(self.tok.parse("a node tag")?);
                }
                let extra = if parametric != 0 { dim.clamp(0, 3) as usize } else { 0 };
                for _ in 0..n {
                    self.points.push(self.tok.point3("a node coordinate")?);
                    for _ in 0..extra {
                        self.tok.parse::<f64>("a parametric coordinate")?;
                    }
                }
            }
            if self.points.len() - before != total {
                return Err(IoError::at_line(
                    self.path,
                    header_line,
                    format!("$Nodes counts {total} nodes but its blocks hold {}", self.points.len() - before),
                ));
            }
        }
        self.end("Nodes")
    }

    /// The tag of an element of entity (`dim`, `entity`): the entity's first physical tag, or
    /// the entity's own tag.
    fn tag_of(&mut self, dim: i32, entity: u32) -> u32 {
        match self.physicals.get(&(dim, entity)).and_then(|p| p.first()) {
            Some(&p) => {
                self.from_physical.insert((dim, p));
                p
            }
            None => entity,
        }
    }

    /// Keeps a triangle or a tet given its node tags; counts the others.
    fn push(&mut self, etype: i32, kind: Kind, elem: u64, nodes: &[u64], tag: u32) {
        if kind == Kind::Other {
            *self.skipped.entry(etype).or_default() += 1;
            return;
        }
        if (kind == Kind::Triangle && nodes.len() > 3) || (kind == Kind::Tet && nodes.len() > 4) {
            *self.reduced.entry(etype).or_default() += 1;
        }
        match (kind, nodes) {
            (Kind::Triangle, [a, b, c, ..]) => {
                self.tris.push((elem, [*a, *b, *c]));
                self.tri_tags.push(tag);
            }
            (Kind::Tet, [a, b, c, d, ..]) => {
                self.tets.push((elem, [*a, *b, *c, *d]));
                self.tet_tags.push(tag);
            }
            _ => {}
        }
    }

    fn elements(&mut self) -> Result<(), IoError> {
        if self.version == Version::V22 {
            return self.elements_v22();
        }
        let mut nodes = Vec::with_capacity(64);
        if self.binary {
            let mut b = self.binary_block("$Elements")?;
            let blocks = b.count("the number of entity blocks")?;
            b.count("the number of elements")?;
            b.size("the smallest element tag")?;
            b.size("the largest element tag")?;
            for k in 0..blocks {
                let dim = b.int("an entity dimension")?;
                let entity = b.int("an entity tag")?.unsigned_abs();
                let at = b.pos;
                let etype = b.int("an element type")?;
                let n = b.count("the number of elements in the block")?;
                let Some((per, kind)) = element_type(etype) else {
                    return Err(IoError::Unsupported {
                        path: self.path.to_path_buf(),
                        at: Location::Byte(at as u64),
                        message: format!("element type {etype} in $Elements block {} (its size is unknown)", k + 1),
                    });
                };
                let tag = self.tag_of(dim, entity);
                for _ in 0..n {
                    let elem = b.size("an element tag")?;
                    nodes.clear();
                    for _ in 0..per {
                        nodes.push(b.size("a node tag")?);
                    }
                    self.push(etype, kind, elem, &nodes, tag);
                }
            }
            let pos = b.pos;
            self.skip_to(pos);
        } else {
            let blocks: usize = self.tok.parse("the number of entity blocks")?;
            self.tok.parse::<u64>("the number of elements")?;
            self.tok.parse::<u64>("the smallest element tag")?;
            self.tok.parse::<u64>("the largest element tag")?;
            for _ in 0..blocks {
                let dim: i32 = self.tok.parse("an entity dimension")?;
                let entity = self.tok.parse::<i32>("an entity tag")?.unsigned_abs();
                let etype: i32 = self.tok.parse("an element type")?;
                let n: usize = self.tok.parse("the number of elements in the block")?;
                let tag = self.tag_of(dim, entity);
                let known = element_type(etype);
                for _ in 0..n {
                    let elem: u64 = self.tok.parse("an element tag")?;
                    let rest = self.tok.rest_of_line();
                    let Some((per, kind)) = known else {
                        *self.skipped.entry(etype).or_default() += 1;
                        continue;
                    };
                    nodes.clear();
                    for t in &rest {
                        nodes.push(
                            t.parse::<u64>().map_err(|_| self.tok.error(format!("expected a node tag of element {elem}, found '{t}'")))?,
                        );
                    }
                    if nodes.len() != per {
                        return Err(self
                            .tok
                            .error(format!("element {elem} of type {etype} should have {per} nodes, found {}", nodes.len())));
                    }
                    self.push(etype, kind, elem, &nodes, tag);
                }
            }
        }
        self.end("Elements")
    }

    fn elements_v22(&mut self) -> Result<(), IoError> {
        let n: usize = self.tok.parse("the number of elements")?;
        let mut nodes = Vec::with_capacity(64);
        for _ in 0..n {
            let elem: u64 = self.tok.parse("an element tag")?;
            let etype: i32 = self.tok.parse("an element type")?;
            let ntags: usize = self.tok.parse("the number of element tags")?;
            let rest = self.tok.rest_of_line();
            let Some((per, kind)) = element_type(etype) else {
                *self.skipped.entry(etype).or_default() += 1;
                continue;
            };
            if rest.len() != ntags + per {
                return Err(self
                    .tok
                    .error(format!("element {elem} should have {ntags} tags and {per} nodes, found {} numbers", rest.len())));
            }
            let mut ints = Vec::with_capacity(rest.len());
            for t in &rest {
                ints.push(t.parse::<i64>().map_err(|_| self.tok.error(format!("expected an integer in element {elem}, found '{t}'")))?);
            }
            let physical = ints.first().filter(|_| ntags >= 1).map_or(0, |p| p.unsigned_abs() as u32);
            let elementary = ints.get(1).filter(|_| ntags >= 2).map_or(0, |p| p.unsigned_abs() as u32);
            let dim = if kind == Kind::Tet { 3 } else { 2 };
            let tag = if physical != 0 { physical } else { elementary };
            if physical != 0 && kind != Kind::Other {
                self.from_physical.insert((dim, physical));
            }
            nodes.clear();
            nodes.extend(ints[ntags..].iter().map(|&v| v as u64));
            self.push(etype, kind, elem, &nodes, tag);
        }
        self.end("Elements")
    }

    fn finish(mut self) -> Result<Loaded, IoError> {
        let path = self.path;
        // Node tag → vertex index.
        let n = self.points.len();
        let (min, max) = self.node_tags.iter().fold((u64::MAX, 0), |(a, b), &t| (a.min(t), b.max(t)));
        let dup = |t: u64| IoError::at_entity(path, format!("node {t}"), "the node tag appears twice in $Nodes");
        let (vertices, lookup) = if n > 0 && max - min == n as u64 - 1 {
            let mut v = vec![DVec3::NAN; n];
            let mut seen = vec![false; n];
            for (&t, &p) in self.node_tags.iter().zip(&self.points) {
                let i = (t - min) as usize;
                if std::mem::replace(&mut seen[i], true) {
                    return Err(dup(t));
                }
                v[i] = p;
            }
            (v, NodeMap::Dense { min, n: n as u64 })
        } else {
            let mut map = HashMap::with_capacity(n);
            for (i, &t) in self.node_tags.iter().enumerate() {
                if map.insert(t, i as u32).is_some() {
                    return Err(dup(t));
                }
            }
            (std::mem::take(&mut self.points), NodeMap::Sparse(map))
        };
        let resolve = |elem: u64, t: u64| {
            lookup.get(t).ok_or_else(|| IoError::at_entity(path, format!("element {elem}"), format!("node {t} is not defined in $Nodes")))
        };
        // Elements in the order of their tags (fepre writes them so; Gmsh numbers them in
        // block order anyway).
        sort_by_element_tag(&mut self.tris, &mut self.tri_tags);
        sort_by_element_tag(&mut self.tets, &mut self.tet_tags);
        let mut tris = Vec::with_capacity(self.tris.len());
        for &(e, [a, b, c]) in &self.tris {
            tris.push([resolve(e, a)?, resolve(e, b)?, resolve(e, c)?]);
        }
        let mut tets = Vec::with_capacity(self.tets.len());
        for &(e, [a, b, c, d]) in &self.tets {
            tets.push([resolve(e, a)?, resolve(e, b)?, resolve(e, c)?, resolve(e, d)?]);
        }
        let mut notes = std::mem::take(&mut self.notes);
        for (t, c) in &self.reduced {
            notes.push(format!("kept the corner nodes of {c} higher-order elements of type {t}"));
        }
        if !self.skipped.is_empty() {
            let list: Vec<String> = self.skipped.iter().map(|(t, c)| format!("{c} {}", type_name(*t))).collect();
            notes.push(format!("skipped elements other than triangles and tetrahedra: {}", list.join(", ")));
        }
        let names = |dim: i32, tags: &[u32]| -> BTreeMap<u32, String> {
            let present: BTreeSet<u32> = tags.iter().copied().collect();
            present
                .into_iter()
                .filter(|t| self.from_physical.contains(&(dim, *t)))
                .filter_map(|t| self.names.get(&(dim, t)).map(|n| (t, n.clone())))
                .collect()
        };
        let file_vertices = vertices.len();
        let mesh = if !tets.is_empty() {
            let mut m = TetMesh {
                vertices,
                tets,
                region_tags: self.tet_tags.iter().map(|&t| RegionId(t)).collect(),
                boundary: tris,
                face_tags: self.tri_tags.iter().map(|&t| FaceId(t)).collect(),
                face_names: names(2, &self.tri_tags).into_iter().map(|(t, n)| (FaceId(t), n)).collect(),
                region_names: names(3, &self.tet_tags).into_iter().map(|(t, n)| (RegionId(t), n)).collect(),
            };
            notes.extend(orient_tets(&mut m));
            notes.extend(unused_vertices_note(&m));
            m.orient_boundary_outward();
            MeshData::Volume(m)
        } else if !tris.is_empty() {
            MeshData::Surface(TriSurface {
                vertices,
                triangles: tris,
                face_tags: self.tri_tags.iter().map(|&t| FaceId(t)).collect(),
                face_names: names(2, &self.tri_tags).into_iter().map(|(t, n)| (FaceId(t), n)).collect(),
            })
        } else if !vertices.is_empty() {
            MeshData::Points(vertices)
        } else {
            return Err(IoError::in_file(path, "the file has no nodes"));
        };
        let mut loaded = Loaded::new(mesh, Format::Msh, file_vertices);
        loaded.notes = notes;
        Ok(loaded)
    }
}

/// Sorts elements (element tag, nodes) and their tags together by element tag, stably, unless
/// they already are in order.
fn sort_by_element_tag<const N: usize>(elems: &mut Vec<(u64, [u64; N])>, tags: &mut Vec<u32>) {
    if elems.windows(2).all(|w| w[0].0 <= w[1].0) {
        return;
    }
    let mut order: Vec<usize> = (0..elems.len()).collect();
    order.sort_by_key(|&i| elems[i].0);
    *elems = order.iter().map(|&i| elems[i]).collect();
    *tags = order.iter().map(|&i| tags[i]).collect();
}

/// Node tag → vertex index: tags `min..min + n` in tag order, or any tags in file order.
enum NodeMap {
    Dense { min: u64, n: u64 },
    Sparse(HashMap<u64, u32>),
}

impl NodeMap {
    fn get(&self, tag: u64) -> Option<u32> {
        match self {
            NodeMap::Dense { min, n } => tag.checked_sub(*min).filter(|i| i < n).map(|i| i as u32),
            NodeMap::Sparse(map) => map.get(&tag).copied(),
        }
    }
}
