//! glTF 2.0: JSON (`.gltf`) with external or `data:` buffers, and binary (`.glb`).
//!
//! The [`gltf`] crate parses and validates the JSON; everything that touches bytes is
//! done here with checked arithmetic, so a broken file gives an error naming the GLB chunk, the
//! buffer, the buffer view or the accessor, never a panic: the GLB container (12-byte header,
//! a JSON chunk, an optional BIN chunk), buffers (the BIN chunk, `data:` URIs in base64, files
//! relative to the `.gltf`), and accessors (every component type, normalised or not, strided
//! buffer views, sparse substitution).
//!
//! The scene walked is the default scene, else scene 0, else every root node. Node transforms
//! (a matrix or translation/rotation/scale, parsed again from the JSON in `f64`) are composed
//! down the hierarchy in `f64`. Every instance of a mesh (a node with a mesh) and every
//! primitive of it that yields triangles gets its own tag 1, 2, … named
//! `<node name or "node N">/<mesh name or "mesh M">/primitive P`; instanced meshes are
//! repeated. Triangle strips and fans become triangles; point and line primitives are skipped
//! with a note. Under a transform with negative determinant (a mirror) the winding is reversed
//! so that outward normals stay outward. Images, materials, skins and morph targets are
//! ignored. The reader returns every vertex of every instance; [`crate::io::read`] welds.

use super::data_uri::{data_uri, percent_decode};
use crate::core::FaceId;
use crate::io::{Format, IoError, Loaded, Location, MeshData};
use crate::mesh::TriSurface;
use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::buffer::{Source, View};
use ::gltf::json::mesh::Semantic as JsonSemantic;
use ::gltf::json::validation::{Checked, Error as Invalid, Validate};
use ::gltf::mesh::{Mode, Semantic};
use ::gltf::scene::Transform;
use ::gltf::{Accessor, Document, Node};
use glam::{DMat3, DMat4, DQuat, DVec3};
use std::borrow::Cow;
use std::collections::{BTreeMap, HashMap, HashSet};
use std::path::Path;
use std::rc::Rc;

const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;
/// Deepest node hierarchy followed (deeper ones are almost certainly cycles or attacks).
const MAX_DEPTH: usize = 512;
/// Most node visits (instances) in one walk.
const MAX_VISITS: usize = 1_000_000;
/// Most elements of an accessor that has no buffer view (its values are zeros or sparse).
const MAX_ZERO_ELEMENTS: usize = 1 << 26;

/// Required extensions that do not change geometry: read as if absent.
const HARMLESS_EXTENSIONS: &[&str] =
    &["KHR_materials_", "KHR_texture_", "EXT_texture_", "KHR_lights_", "EXT_lights_", "MSFT_texture_", "KHR_xmp", "KHR_mesh_quantization"];

fn le_u32(b: &[u8], at: usize) -> Option<u32> {
    b.get(at..at.checked_add(4)?)?.try_into().ok().map(u32::from_le_bytes)
}

fn chunk_name(ty: u32) -> String {
    match ty {
        CHUNK_JSON => "JSON".into(),
        CHUNK_BIN => "BIN".into(),
        t => format!("type 0x{t:08X}"),
    }
}

/// Splits a GLB file into its JSON chunk and its BIN chunk (if any).
fn split_glb<'a>(path: &Path, bytes: &'a [u8], notes: &mut Vec<String>) -> Result<(&'a [u8], Option<&'a [u8]>), IoError> {
    let err = |entity: &str, message: String| IoError::at_entity(path, entity, message);
    let (Some(magic), Some(version), Some(length)) = (bytes.get(..4), le_u32(bytes, 4), le_u32(bytes, 8)) else {
        return Err(err("header", format!("the file is {} bytes long; a GLB header alone takes 12", bytes.len())));
    };
    if magic != b"glTF" {
        return Err(err("header", format!("bad magic {:?}: a binary glTF file starts with \"glTF\"", String::from_utf8_lossy(magic))));
    }
    if version != 2 {
        let message = format!("GLB version {version}: only glTF 2.0 is read");
        return Err(IoError::Unsupported { path: path.to_path_buf(), at: Location::Entity("header".into()), message });
    }
    let total = length as usize;
    if total > bytes.len() {
        return Err(err("header", format!("the header gives a length of {total} bytes but the file has {} (is it truncated?)", bytes.len())));
    }
    if total < bytes.len() {
        notes.push(format!("ignored {} bytes after the length given in the GLB header", bytes.len() - total));
    }
    let data = bytes.get(..total).unwrap_or_default();
    let (mut json, mut bin) = (None, None);
    let (mut at, mut i) = (12usize, 0usize);
    while at < total {
        let (Some(len), Some(ty)) = (le_u32(data, at), le_u32(data, at + 4)) else {
            return Err(err(&format!("chunk {i}"), format!("truncated chunk header: {} bytes left, a chunk header takes 8", total - at)));
        };
        let entity = format!("chunk {i} ({})", chunk_name(ty));
        let start = at + 8;
        let body = start
            .checked_add(len as usize)
            .and_then(|end| data.get(start..end))
            .ok_or_else(|| err(&entity, format!("the chunk length {len} runs past the end of the file: {} bytes follow its header", total - start)))?;
        match (i, ty) {
            (0, CHUNK_JSON) => json = Some(body),
            (0, _) => return Err(err(&entity, "the first chunk must be the JSON chunk".into())),
            (_, CHUNK_BIN) if bin.is_none() => bin = Some(body),
            _ => notes.push(format!("ignored GLB {entity}")),
        }
        at = start + body.len();
        i += 1;
    }
    let json = json.ok_or_else(|| err("chunk 0 (JSON)", "missing: the file ends after the GLB header".into()))?;
    Ok((json, bin))
}

/// Parses and validates the JSON; required extensions that change geometry are refused.
fn parse_document(path: &Path, json: &[u8], glb: bool, notes: &mut Vec<String>) -> Result<Document, IoError> {
    let json = json.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(json);
    // GLB JSON chunks are padded with spaces, and by some writers with zeros
    let end = json.iter().rposition(|&b| b != 0 && !b.is_ascii_whitespace()).map_or(0, |p| p + 1);
    let json = json.get(..end).unwrap_or_default();
    let root: ::gltf::json::Root = ::gltf::json::deserialize::from_slice(json).map_err(|e| {
        let at = match (glb, e.line()) {
            (true, _) => Location::Entity("chunk 0 (JSON)".into()),
            (false, 0) => Location::File,
            (false, l) => Location::Line(l),
        };
        IoError::Parse { path: path.to_path_buf(), at, message: format!("invalid glTF JSON: {e}") }
    })?;
    for ext in &root.extensions_required {
        if HARMLESS_EXTENSIONS.iter().any(|h| ext.starts_with(h)) {
            notes.push(format!("required extension {ext} does not change the geometry; ignored"));
        } else {
            return Err(IoError::Unsupported {
                path: path.to_path_buf(),
                at: Location::Entity("extensionsRequired".into()),
                message: format!("the file requires the glTF extension {ext}, which fepre does not read"),
            });
        }
    }
    for ext in root.extensions_used.iter().filter(|e| !root.extensions_required.contains(e)) {
        notes.push(format!("ignored the optional glTF extension {ext}"));
    }
    // the validation of the gltf crate indexes the POSITION accessor without checking it
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let pos = prim.attributes.get(&Checked::Valid(JsonSemantic::Positions));
            if let Some(a) = pos.filter(|a| a.value() >= root.accessors.len()) {
                let message = format!("POSITION refers to accessor {}, but there are {}", a.value(), root.accessors.len());
                return Err(IoError::at_entity(path, format!("meshes[{m}].primitives[{p}]"), message));
            }
        }
    }
    let mut errors = Vec::new();
    root.validate(&root, ::gltf::json::Path::new, &mut |p, e| {
        let (p, pos) = (p(), ["[\"POSITION\"].min", "[\"POSITION\"].max"]);
        // required extensions were checked above; POSITION bounds are not needed
        if !(e == Invalid::Unsupported && p.as_str().starts_with("extensionsRequired") || pos.iter().any(|m| p.as_str().ends_with(m))) {
            errors.push((p, e));
        }
    });
    if let Some((first, _)) = errors.first() {
        let list: Vec<String> = errors.iter().take(5).map(|(p, e)| format!("{p}: {e}")).collect();
        let more = if errors.len() > 5 { format!(" and {} more", errors.len() - 5) } else { String::new() };
        return Err(IoError::at_entity(path, first.as_str(), format!("invalid glTF: {}{more}", list.join("; "))));
    }
    Ok(Document::from_json_without_validation(root))
}

/// Node transforms as written in the JSON, in `f64` (the gltf crate keeps `f32`).
#[derive(serde::Deserialize)]
struct F64Nodes {
    #[serde(default)]
    nodes: Vec<F64Node>,
}

#[derive(serde::Deserialize)]
struct F64Node {
    matrix: Option<[f64; 16]>,
    translation: Option<[f64; 3]>,
    rotation: Option<[f64; 4]>,
    scale: Option<[f64; 3]>,
}

fn trs(t: [f64; 3], r: [f64; 4], s: [f64; 3]) -> DMat4 {
    let len = DQuat::from_array(r).length();
    let q = if len == 0.0 { DQuat::IDENTITY } else { DQuat::from_array(r.map(|c| c / len)) };
    DMat4::from_scale_rotation_translation(DVec3::from(s), q, DVec3::from(t))
}

impl F64Node {
    fn matrix(&self) -> DMat4 {
        match self.matrix {
            Some(m) => DMat4::from_cols_array(&m),
            None => trs(self.translation.unwrap_or_default(), self.rotation.unwrap_or([0.0, 0.0, 0.0, 1.0]), self.scale.unwrap_or([1.0; 3])),
        }
    }
}

fn local_f32(node: &Node<'_>) -> DMat4 {
    match node.transform() {
        Transform::Matrix { matrix } => DMat4::from_cols_array_2d(&matrix.map(|c| c.map(f64::from))),
        Transform::Decomposed { translation: t, rotation: r, scale: s } => trs(t.map(f64::from), r.map(f64::from), s.map(f64::from)),
    }
}

/// Buffers, loaded when first used.
struct Buffers<'a> {
    path: &'a Path,
    bin: Option<&'a [u8]>,
    data: HashMap<usize, Cow<'a, [u8]>>,
}

impl<'a> Buffers<'a> {
    fn load(&self, buffer: &::gltf::Buffer<'_>) -> Result<Cow<'a, [u8]>, IoError> {
        let entity = format!("buffer {}", buffer.index());
        let err = |m: String| IoError::at_entity(self.path, entity.as_str(), m);
        let data: Cow<'a, [u8]> = match buffer.source() {
            Source::Bin => Cow::Borrowed(self.bin.ok_or_else(|| err("refers to the BIN chunk of a GLB file, and there is none".into()))?),
            Source::Uri(uri) if uri.starts_with("data:") => Cow::Owned(data_uri(uri).map_err(|e| err(e.to_string()))?),
            Source::Uri(uri) if uri.contains("://") => {
                return Err(IoError::Unsupported {
                    path: self.path.to_path_buf(),
                    at: Location::Entity(entity.clone()),
                    message: format!("remote buffer '{uri}': only files beside the glTF file and data: URIs are read"),
                });
            }
            Source::Uri(uri) => {
                let name = String::from_utf8(percent_decode(uri)).map_err(|_| err(format!("the URI '{uri}' is not UTF-8 once decoded")))?;
                let file = self.path.parent().unwrap_or(Path::new("")).join(name);
                Cow::Owned(std::fs::read(&file).map_err(|e| err(format!("cannot read '{}': {e}", file.display())))?)
            }
        };
        if data.len() < buffer.length() {
            return Err(err(format!("holds {} bytes, but its byteLength is {}", data.len(), buffer.length())));
        }
        Ok(data)
    }

    /// The bytes of a buffer view.
    fn view(&mut self, view: &View<'_>) -> Result<&[u8], IoError> {
        let buffer = view.buffer();
        let b = buffer.index();
        if !self.data.contains_key(&b) {
            let d = self.load(&buffer)?;
            self.data.insert(b, d);
        }
        let data = self.data.get(&b).map(|d| &d[..]).unwrap_or_default();
        let (start, len) = (view.offset(), view.length());
        start.checked_add(len).and_then(|end| data.get(start..end)).ok_or_else(|| {
            IoError::at_entity(
                self.path,
                format!("buffer view {}", view.index()),
                format!("bytes {start}..{} run past the end of buffer {b} ({} bytes)", start as u128 + len as u128, data.len()),
            )
        })
    }
}

fn component_size(t: DataType) -> usize {
    match t {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    }
}

fn multiplicity(d: Dimensions) -> usize {
    match d {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 | Dimensions::Mat2 => 4,
        Dimensions::Mat3 => 9,
        Dimensions::Mat4 => 16,
    }
}

/// One component at byte `at`, normalised to [0, 1] or [-1, 1] if `normalized`.
fn component(d: &[u8], at: usize, t: DataType, normalized: bool) -> Option<f64> {
    let b = |n: usize| d.get(at..at.checked_add(n)?);
    let (x, scale) = match t {
        DataType::I8 => (f64::from(i8::from_le_bytes(b(1)?.try_into().ok()?)), 127.0),
        DataType::U8 => (f64::from(u8::from_le_bytes(b(1)?.try_into().ok()?)), 255.0),
        DataType::I16 => (f64::from(i16::from_le_bytes(b(2)?.try_into().ok()?)), 32767.0),
        DataType::U16 => (f64::from(u16::from_le_bytes(b(2)?.try_into().ok()?)), 65535.0),
        DataType::U32 => (f64::from(u32::from_le_bytes(b(4)?.try_into().ok()?)), 4294967295.0),
        DataType::F32 => return Some(f64::from(f32::from_le_bytes(b(4)?.try_into().ok()?))),
    };
    Some(if normalized { (x / scale).max(-1.0) } else { x })
}

/// Triangles of a primitive from its vertex sequence, and how many repeated a vertex.
fn assemble(mode: Mode, v: &[u32]) -> (Vec<[u32; 3]>, usize) {
    let n = v.len();
    let tris: Vec<[u32; 3]> = match mode {
        Mode::TriangleStrip => (0..n.saturating_sub(2))
            .filter_map(|i| Some(if i % 2 == 0 { [*v.get(i)?, *v.get(i + 1)?, *v.get(i + 2)?] } else { [*v.get(i)?, *v.get(i + 2)?, *v.get(i + 1)?] }))
            .collect(),
        Mode::TriangleFan => (1..n.saturating_sub(1)).filter_map(|i| Some([*v.get(i)?, *v.get(i + 1)?, *v.first()?])).collect(),
        _ => v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
    };
    let total = tris.len();
    let kept: Vec<[u32; 3]> = tris.into_iter().filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]).collect();
    let dropped = total - kept.len();
    (kept, dropped)
}

/// The walk over the scene, gathering the surface.
struct Walk<'a> {
    path: &'a Path,
    doc: &'a Document,
    buffers: Buffers<'a>,
    /// Local transforms in `f64` (empty if they could not be parsed again).
    local: Vec<Option<DMat4>>,
    /// Decoded accessors.
    cache: HashMap<usize, Rc<Vec<f64>>>,
    s: TriSurface,
    /// Vertices of all instances, node visits, triangles dropped for repeating a vertex.
    counts: (usize, usize, usize),
    /// Point and line primitives skipped, by mesh and kind.
    skipped: BTreeMap<(usize, &'static str), usize>,
    /// Meshes met so far (notes are made at the first instance only).
    noted_meshes: HashSet<usize>,
    notes: Vec<String>,
}

impl Walk<'_> {
    /// Decodes an accessor into `count × components` numbers.
    fn decode(&mut self, acc: &Accessor<'_>, role: &str) -> Result<Rc<Vec<f64>>, IoError> {
        if let Some(v) = self.cache.get(&acc.index()) {
            return Ok(Rc::clone(v));
        }
        let (path, entity) = (self.path, format!("accessor {} ({role})", acc.index()));
        let err = |m: String| IoError::at_entity(path, entity.as_str(), m);
        let (ty, norm, comps, count) = (acc.data_type(), acc.normalized(), multiplicity(acc.dimensions()), acc.count());
        let (csize, elem) = (component_size(ty), component_size(ty) * comps);
        let mut out = Vec::new();
        if let Some(view) = acc.view() {
            let data = self.buffers.view(&view)?;
            let stride = view.stride().unwrap_or(elem);
            if stride < elem {
                return Err(err(format!("the byteStride {stride} of buffer view {} is smaller than an element ({elem} bytes)", view.index())));
            }
            let need = count.checked_sub(1).map_or(Some(0), |c| c.checked_mul(stride)?.checked_add(elem)?.checked_add(acc.offset()));
            if need.is_none_or(|n| n > data.len()) {
                return Err(err(format!(
                    "{count} elements from byte {} need more than the {} bytes of buffer view {}",
                    acc.offset(),
                    data.len(),
                    view.index()
                )));
            }
            out.reserve(count * comps);
            for k in 0..count {
                for c in 0..comps {
                    let x = component(data, acc.offset() + k * stride + c * csize, ty, norm).ok_or_else(|| err("out of range".into()))?;
                    out.push(x);
                }
            }
        } else if count <= MAX_ZERO_ELEMENTS {
            out = vec![0.0; count * comps];
        } else {
            return Err(err(format!("{count} elements without a buffer view: too many")));
        }
        if let Some(sparse) = acc.sparse() {
            let n = sparse.count();
            if n > count {
                return Err(err(format!("{n} sparse elements for an accessor of {count}")));
            }
            let (iv, ioff, isize) = (sparse.indices().view(), sparse.indices().offset(), sparse.indices().index_type().size());
            let t = [DataType::U8, DataType::U16, DataType::U32][isize.min(4) / 2];
            let idata = self.buffers.view(&iv)?;
            let indices: Option<Vec<usize>> =
                (0..n).map(|k| component(idata, ioff.checked_add(k * isize)?, t, false).map(|x| x as usize)).collect();
            let indices = indices.ok_or_else(|| err(format!("its {n} sparse indices run past the end of buffer view {}", iv.index())))?;
            let (vv, voff) = (sparse.values().view(), sparse.values().offset());
            let vdata = self.buffers.view(&vv)?;
            for (k, &i) in indices.iter().enumerate() {
                if i >= count {
                    return Err(err(format!("sparse index {i} is out of range: the accessor has {count} elements")));
                }
                for c in 0..comps {
                    let at = voff.checked_add(k * elem + c * csize);
                    let x = at.and_then(|at| component(vdata, at, ty, norm));
                    let x = x.ok_or_else(|| err(format!("its {n} sparse values run past the end of buffer view {}", vv.index())))?;
                    if let Some(slot) = out.get_mut(i * comps + c) {
                        *slot = x;
                    }
                }
            }
        }
        let out = Rc::new(out);
        self.cache.insert(acc.index(), Rc::clone(&out));
        Ok(out)
    }

    fn node(&mut self, node: &Node<'_>, parent: DMat4, ancestors: &mut Vec<usize>) -> Result<(), IoError> {
        let entity = format!("node {}", node.index());
        if ancestors.contains(&node.index()) {
            return Err(IoError::at_entity(self.path, entity, "the node is its own ancestor: the hierarchy has a cycle"));
        }
        self.counts.1 += 1;
        if ancestors.len() >= MAX_DEPTH || self.counts.1 > MAX_VISITS {
            return Err(IoError::at_entity(self.path, entity, "the node hierarchy is too deep or has too many instances"));
        }
        let local = self.local.get(node.index()).copied().flatten().unwrap_or_else(|| local_f32(node));
        let m = parent * local;
        if !m.is_finite() {
            return Err(IoError::at_entity(self.path, entity, "the node's transform is not finite"));
        }
        if let Some(mesh) = node.mesh() {
            let label = node.name().filter(|n| !n.is_empty()).map_or_else(|| format!("node {}", node.index()), str::to_string);
            if node.skin().is_some() {
                self.notes.push(format!("{label} is skinned; its mesh is read in the bind pose"));
            }
            self.mesh(&label, &mesh, m)?;
        }
        ancestors.push(node.index());
        for child in node.children() {
            self.node(&child, m, ancestors)?;
        }
        ancestors.pop();
        Ok(())
    }

    fn mesh(&mut self, node_label: &str, mesh: &::gltf::Mesh<'_>, m: DMat4) -> Result<(), IoError> {
        let mirror = DMat3::from_mat4(m).determinant() < 0.0;
        let mesh_label = mesh.name().filter(|n| !n.is_empty()).map_or_else(|| format!("mesh {}", mesh.index()), str::to_string);
        let first_instance = self.noted_meshes.insert(mesh.index());
        for prim in mesh.primitives() {
            let p = prim.index();
            let mode = prim.mode();
            let kind = match mode {
                Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan => None,
                Mode::Points => Some("point"),
                Mode::Lines | Mode::LineLoop | Mode::LineStrip => Some("line"),
            };
            if let Some(kind) = kind {
                if first_instance {
                    *self.skipped.entry((mesh.index(), kind)).or_default() += 1;
                }
                continue;
            }
            if first_instance && prim.morph_targets().next().is_some() {
                self.notes.push(format!("ignored the morph targets of {mesh_label} primitive {p}"));
            }
            let role = |what: &str| format!("{what} of mesh {} primitive {p}", mesh.index());
            let Some(pos) = prim.get(&Semantic::Positions) else {
                if first_instance {
                    self.notes.push(format!("skipped {mesh_label} primitive {p}: it has no POSITION attribute"));
                }
                continue;
            };
            let (path, pos_role) = (self.path, role("POSITION"));
            let perr = |m: String| IoError::at_entity(path, format!("accessor {} ({pos_role})", pos.index()), m);
            if pos.dimensions() != Dimensions::Vec3 {
                return Err(perr(format!("POSITION must be VEC3, not {:?}", pos.dimensions())));
            }
            let positions = self.decode(&pos, &pos_role)?;
            let n = positions.len() / 3;
            let indices: Vec<u32> = match prim.indices() {
                None => (0..n).map(|i| i as u32).collect(),
                Some(acc) => {
                    let irole = role("indices");
                    let ierr = |m: String| IoError::at_entity(path, format!("accessor {} ({irole})", acc.index()), m);
                    if acc.dimensions() != Dimensions::Scalar || !matches!(acc.data_type(), DataType::U8 | DataType::U16 | DataType::U32) {
                        return Err(ierr(format!("indices must be unsigned integer scalars, not {:?} {:?}", acc.dimensions(), acc.data_type())));
                    }
                    let raw = self.decode(&acc, &irole)?;
                    let mut out = Vec::with_capacity(raw.len());
                    for (k, &i) in raw.iter().enumerate() {
                        if i >= n as f64 {
                            return Err(ierr(format!("index {i} (element {k}) is out of range: POSITION has {n} vertices")));
                        }
                        out.push(i as u32);
                    }
                    out
                }
            };
            if mode == Mode::Triangles && indices.len() % 3 != 0 && first_instance {
                self.notes.push(format!("ignored {} trailing vertices of {mesh_label} primitive {p}", indices.len() % 3));
            }
            let (tris, dropped) = assemble(mode, &indices);
            self.counts.2 += dropped;
            if tris.is_empty() {
                continue;
            }
            let base = self.s.vertices.len();
            if u32::try_from(base + n).is_err() {
                return Err(perr("more than 4,294,967,295 vertices in all instances".into()));
            }
            for (k, c) in positions.chunks_exact(3).enumerate() {
                let q = DVec3::new(c[0], c[1], c[2]);
                let w = m.transform_point3(q);
                if !w.is_finite() {
                    return Err(perr(format!("vertex {k} {q:?} is not finite (or not once transformed by {node_label})")));
                }
                self.s.vertices.push(w);
            }
            let tag = FaceId::from_index(self.s.face_names.len());
            self.s.face_names.insert(tag, format!("{node_label}/{mesh_label}/primitive {p}"));
            let b = base as u32;
            self.s.triangles.extend(tris.iter().map(|t| if mirror { [t[0] + b, t[2] + b, t[1] + b] } else { t.map(|i| i + b) }));
            self.s.face_tags.resize(self.s.triangles.len(), tag);
            self.counts.0 += n;
        }
        Ok(())
    }

    /// Walks the default scene, else scene 0, else the root nodes, else the meshes.
    fn run(&mut self) -> Result<(), IoError> {
        let doc = self.doc;
        let scene = doc.default_scene().or_else(|| doc.scenes().next());
        let roots: Vec<Node<'_>> = match &scene {
            Some(s) => {
                if doc.scenes().len() > 1 {
                    self.notes.push(format!("read scene {} of {}", s.index(), doc.scenes().len()));
                }
                s.nodes().collect()
            }
            None => {
                let children: HashSet<usize> = doc.nodes().flat_map(|n| n.children().map(|c| c.index())).collect();
                doc.nodes().filter(|n| !children.contains(&n.index())).collect()
            }
        };
        if scene.is_none() && doc.nodes().len() == 0 {
            for mesh in doc.meshes() {
                self.mesh("no node", &mesh, DMat4::IDENTITY)?;
            }
        }
        for root in roots {
            self.node(&root, DMat4::IDENTITY, &mut Vec::new())?;
        }
        Ok(())
    }
}

/// Reads a glTF 2.0 file's bytes: binary (GLB) if they start with `glTF` or the name ends in
/// `.glb`, else JSON, with its buffers from `data:` URIs or files beside it.
///
/// # Errors
/// A broken GLB container (naming the header or chunk), invalid JSON (naming the line, or the
/// JSON chunk), a glTF validation error, a missing or short buffer, an accessor or index out
/// of range, a non-finite position or transform, or a required extension that changes the
/// geometry (Draco, meshopt, GPU instancing).
pub fn read(path: &Path, bytes: &[u8]) -> Result<Loaded, IoError> {
    let glb = bytes.starts_with(b"glTF") || Format::from_path(path) == Some(Format::Glb);
    let mut notes = Vec::new();
    let (json, bin) = if glb { split_glb(path, bytes, &mut notes)? } else { (bytes, None) };
    let doc = parse_document(path, json, glb, &mut notes)?;
    let json_trimmed = json.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(json);
    let f64_nodes = ::gltf::json::deserialize::from_slice::<F64Nodes>(json_trimmed.trim_ascii_end()).ok();
    let local = match f64_nodes {
        Some(n) if n.nodes.len() == doc.nodes().len() => n.nodes.iter().map(|n| Some(n.matrix())).collect(),
        _ => Vec::new(),
    };
    let mut walk = Walk {
        path,
        doc: &doc,
        buffers: Buffers { path, bin, data: HashMap::new() },
        local,
        cache: HashMap::new(),
        s: TriSurface::default(),
        counts: (0, 0, 0),
        skipped: BTreeMap::new(),
        noted_meshes: HashSet::new(),
        notes,
    };
    walk.run()?;
    for ((mesh, kind), n) in &walk.skipped {
        let name = doc.meshes().nth(*mesh).and_then(|m| m.name().map(str::to_string)).unwrap_or_else(|| format!("mesh {mesh}"));
        walk.notes.push(format!("skipped {n} {kind} primitive{} of mesh '{name}'", if *n == 1 { "" } else { "s" }));
    }
    if walk.counts.2 > 0 {
        walk.notes.push(format!("dropped {} triangles that repeat a vertex", walk.counts.2));
    }
    if walk.s.triangles.is_empty() {
        walk.notes.push("the scene holds no triangles".into());
    }
    let format = if glb { Format::Glb } else { Format::Gltf };
    let mut loaded = Loaded::new(MeshData::Surface(walk.s), format, walk.counts.0);
    loaded.notes = walk.notes;
    Ok(loaded)
}

#[cfg(test)]
mod tests {
    use super::*;
    use base64::Engine;

    /// Little-endian bytes of `f32` triples, then `u16` indices.
    fn bin(points: &[[f32; 3]], indices: &[u16]) -> Vec<u8> {
        let mut b: Vec<u8> = points.iter().flatten().flat_map(|c| c.to_le_bytes()).collect();
        b.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
        b.resize(b.len().next_multiple_of(4), 0);
        b
    }

    fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
        let mut j = json.as_bytes().to_vec();
        j.resize(j.len().next_multiple_of(4), b' ');
        let len = |n: usize| (n as u32).to_le_bytes();
        [&b"glTF"[..], &len(2), &len(28 + j.len() + bin.len()), &len(j.len()), b"JSON", &j, &len(bin.len()), b"BIN\0", bin].concat()
    }

    const SQUARE: [[f32; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];

    /// A unit square (indexed triangles, a fan and points) instanced by three nodes under a
    /// translated root, one of them mirrored; and a strip mesh given as a sparse accessor.
    fn scene_json(buffer: &str) -> String {
        format!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],
"nodes":[{{"name":"root","translation":[10,0,0],"children":[1,2,3]}},{{"name":"a","mesh":0}},
 {{"mesh":0,"matrix":[-1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}},{{"mesh":1,"rotation":[0,0,0.7071067811865476,0.7071067811865476]}}],
"meshes":[{{"name":"sq","primitives":[{{"attributes":{{"POSITION":0}},"indices":1}},{{"attributes":{{"POSITION":0}},"mode":6}},
  {{"attributes":{{"POSITION":0}},"mode":0}}]}},
 {{"primitives":[{{"attributes":{{"POSITION":2}},"mode":5}}]}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"}},
 {{"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}},
 {{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3",
   "sparse":{{"count":2,"indices":{{"bufferView":1,"componentType":5123,"byteOffset":8}},"values":{{"bufferView":2}}}}}}],
"bufferViews":[{{"buffer":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":12}},{{"buffer":0,"byteOffset":60,"byteLength":24}}],
"buffers":[{{"byteLength":84{buffer}}}]}}"#
        )
    }

    /// The binary of [`scene_json`]: square, indices (0 1 2, 0 2 3), and sparse values that
    /// turn the square's vertices 2 and 3 into (0 1 0) and (1 1 0), a strip order.
    fn scene_bin() -> Vec<u8> {
        let mut b = bin(&SQUARE, &[0, 1, 2, 0, 2, 3]);
        b.extend(bin(&[[0.0, 1.0, 0.0], [1.0, 1.0, 0.0]], &[]));
        b
    }

    fn surface(l: &Loaded) -> &TriSurface {
        let MeshData::Surface(s) = &l.mesh else { panic!() };
        s
    }

    fn normal(s: &TriSurface, t: usize) -> DVec3 {
        let [a, b, c] = s.corners(t);
        (b - a).cross(c - a)
    }

    #[test]
    fn walks_hierarchy_instances_modes_and_mirrors() {
        let l = read(Path::new("s.glb"), &glb(&scene_json(""), &scene_bin())).unwrap();
        let s = surface(&l);
        assert_eq!(l.format, Format::Glb);
        // 2 instances × (2 indexed + 2 fan) + 2 strip triangles
        assert_eq!(s.triangles.len(), 10);
        assert_eq!(l.file_vertices, 4 * 4 + 4);
        let names: Vec<&str> = s.face_names.names().collect();
        assert_eq!(names, ["a/sq/primitive 0", "a/sq/primitive 1", "node 2/sq/primitive 0", "node 2/sq/primitive 1", "node 3/mesh 1/primitive 0"]);
        assert_eq!(s.tags().len(), 5);
        assert!(l.notes.iter().any(|n| n == "skipped 1 point primitive of mesh 'sq'"), "{:?}", l.notes);
        // translated by the root; mirrored copy has x in [9, 10]; all normals stay +z
        assert_eq!(s.vertices[2], DVec3::new(11.0, 1.0, 0.0));
        assert_eq!(s.vertices[9], DVec3::new(9.0, 0.0, 0.0));
        for t in 0..s.triangles.len() {
            assert!(normal(s, t).z > 0.0, "triangle {t} is flipped");
        }
        // the strip (sparse) square, rotated 90° about z: (0 0 0) (1 0 0) (0 1 0) (1 1 0) -> x = -y
        let strip: Vec<DVec3> = s.vertices[16..20].to_vec();
        assert!((strip[3] - DVec3::new(9.0, 1.0, 0.0)).length() < 1e-12, "{strip:?}");
        let area: f64 = (8..10).map(|t| normal(s, t).z / 2.0).sum();
        assert!((area - 1.0).abs() < 1e-12);
    }

    #[test]
    fn gltf_with_data_uri_and_external_buffer() {
        let b = scene_bin();
        let uri = format!(r#","uri":"data:application/octet-stream;base64,{}""#, base64::engine::general_purpose::STANDARD.encode(&b));
        let l = read(Path::new("s.gltf"), scene_json(&uri).as_bytes()).unwrap();
        assert_eq!((l.format, surface(&l).triangles.len()), (Format::Gltf, 10));
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("my buf.bin"), &b).unwrap();
        let p = dir.path().join("s.gltf");
        std::fs::write(&p, scene_json(r#","uri":"my%20buf.bin""#)).unwrap();
        let l = crate::io::read(&p, &crate::io::ReadOptions::default()).unwrap();
        assert_eq!(surface(&l).triangles.len(), 10);
        std::fs::remove_file(dir.path().join("my buf.bin")).unwrap();
        let e = crate::io::read(&p, &crate::io::ReadOptions::default()).unwrap_err().to_string();
        assert!(e.contains("s.gltf (buffer 0): cannot read") && e.contains("my buf.bin"), "{e}");
        let e = read(Path::new("j.gltf"), b"{\"asset\":{\"version\":\"2.0\"},\n\"nodes\":[{]}").unwrap_err().to_string();
        assert!(e.starts_with("j.gltf:2: invalid glTF JSON"), "{e}");
    }

    fn err(bytes: &[u8]) -> String {
        read(Path::new("bad.glb"), bytes).unwrap_err().to_string()
    }

    #[test]
    fn broken_containers_name_the_chunk() {
        let good = glb(&scene_json(""), &scene_bin());
        assert!(err(&good[..good.len() - 5]).starts_with("bad.glb (header): the header gives a length of"));
        let mut m = good.clone();
        m[..4].copy_from_slice(b"GLTF");
        assert!(err(&m).starts_with("bad.glb (header): bad magic \"GLTF\""));
        assert!(err(b"{}").starts_with("bad.glb (header): the file is 2 bytes long"));
        let mut m = good.clone();
        m[8..12].copy_from_slice(&((good.len() + 1000) as u32).to_le_bytes());
        m.extend(vec![0u8; 1000]);
        m[12..16].copy_from_slice(&1_000_000u32.to_le_bytes());
        assert!(err(&m).starts_with("bad.glb (chunk 0 (JSON)): the chunk length 1000000 runs past the end"), "{}", err(&m));
        let json_len = u32::from_le_bytes(good[12..16].try_into().unwrap()) as usize;
        let mut m = good.clone();
        m[20 + json_len..24 + json_len].copy_from_slice(&4000u32.to_le_bytes());
        assert!(err(&m).starts_with("bad.glb (chunk 1 (BIN)): the chunk length 4000 runs past"), "{}", err(&m));
        let mut m = good.clone();
        m[16..20].copy_from_slice(b"BIN\0");
        assert_eq!(err(&m), "bad.glb (chunk 0 (BIN)): the first chunk must be the JSON chunk");
        let mut m = good.clone();
        m[20] = b'[';
        assert!(err(&m).starts_with("bad.glb (chunk 0 (JSON)): invalid glTF JSON"), "{}", err(&m));
        m[4] = 1;
        assert!(err(&m).contains("unsupported: GLB version 1"));
    }

    #[test]
    fn out_of_range_data_is_an_error() {
        let b = scene_bin();
        let e = err(&glb(&scene_json("").replace(r#""count":6"#, r#""count":7"#), &b));
        assert!(e.starts_with("bad.glb (accessor 1 (indices of mesh 0 primitive 0)): 7 elements"), "{e}");
        let e = err(&glb(&scene_json("").replace(r#""count":4,"type":"VEC3"}"#, r#""count":3,"type":"VEC3"}"#), &b));
        assert!(e.contains("index 3 (element 5) is out of range: POSITION has 3 vertices"), "{e}");
        let e = err(&glb(&scene_json("").replace(r#""byteOffset":60,"byteLength":24"#, r#""byteOffset":70,"byteLength":24"#), &b));
        assert!(e.starts_with("bad.glb (buffer view 2): bytes 70..94 run past the end of buffer 0 (84 bytes)"), "{e}");
        let e = err(&glb(&scene_json("").replace(r#""byteLength":84"#, r#""byteLength":184"#), &b));
        assert!(e.starts_with("bad.glb (buffer 0): holds 84 bytes, but its byteLength is 184"), "{e}");
        let e = err(&glb(&scene_json("").replace(r#""mesh":1,"#, r#""mesh":7,"#), &b));
        assert!(e.starts_with("bad.glb (nodes[3].mesh): invalid glTF"), "{e}");
        let e = err(&glb(&scene_json("").replace(r#""children":[1,2,3]"#, r#""children":[1,2,3,0]"#), &b));
        assert!(e.contains("(node 0): the node is its own ancestor"), "{e}");
        let mut nan = b.clone();
        nan[4..8].copy_from_slice(&f32::NAN.to_le_bytes());
        assert!(err(&glb(&scene_json(""), &nan)).contains("(accessor 0 (POSITION of mesh 0 primitive 0)): vertex 0"));
        let draco = scene_json("").replace(r#""scene":0,"#, r#""scene":0,"extensionsRequired":["KHR_draco_mesh_compression"],"#);
        assert!(err(&glb(&draco, &b)).contains("unsupported: the file requires the glTF extension KHR_draco_mesh_compression"));
    }

    #[test]
    fn mangled_input_never_panics() {
        let good = glb(&scene_json(""), &scene_bin());
        for cut in 0..good.len() {
            let _ = read(Path::new("m.glb"), &good[..cut]);
        }
        let json_len = u32::from_le_bytes(good[12..16].try_into().unwrap()) as usize;
        for i in (0..good.len()).filter(|&i| i < 24 || i >= 20 + json_len) {
            for v in [0u8, 1, 0x7f, 0xff] {
                let mut m = good.clone();
                m[i] = v;
                if let Ok(l) = read(Path::new("m.glb"), &m) {
                    surface(&l).validate().unwrap();
                }
            }
        }
        // digits of the JSON changed one at a time
        let json = scene_json("");
        for (i, c) in json.char_indices().filter(|(_, c)| c.is_ascii_digit()) {
            for d in ["9", "0", "-1", "99999999999"] {
                let mut j = json.clone();
                j.replace_range(i..i + c.len_utf8(), d);
                let _ = read(Path::new("m.glb"), &glb(&j, &scene_bin()));
            }
        }
    }
}
