//! The MSH writer: ASCII 4.1, one entity and physical group per tag, physical names unique per dimension.

use crate::core::tag_names::make_unique;
use crate::core::{Aabb, TagNames};
use crate::io::IoError;
use crate::io::atomic::{write_atomic, write_err};
use crate::io::common::Num;
use crate::mesh::{TetMesh, TriSurface};
use glam::DVec3;
use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

/// An entity to write: a surface (triangles) or a volume (tets) holding the elements of one
/// tag, in the physical group of the same number.
struct Entity {
    dim: u8,
    /// Entity and physical tag as written.
    tag: u32,
    /// In a physical group (every entity but the one made for stray nodes).
    physical: bool,
    name: Option<String>,
    /// Indices into the triangles (dim 2) or tets (dim 3).
    elements: Vec<usize>,
}

/// A mesh as entities, ready to write.
pub(super) struct Parts<'a> {
    vertices: &'a [DVec3],
    tris: &'a [[u32; 3]],
    tets: &'a [[u32; 4]],
    entities: Vec<Entity>,
}

/// Groups element indices by tag and gives each group a positive tag: 0 becomes one more than
/// the largest tag (Gmsh has no physical group 0), named after its name or `tag_0`. Names are
/// cleaned for the file (`"` becomes `'`, control characters spaces) but not yet unique.
fn group<T: Copy + Ord>(dim: u8, tags: &[T], number: impl Fn(T) -> u32, names: &TagNames<T>) -> Vec<Entity> {
    let mut by_tag: BTreeMap<T, Vec<usize>> = BTreeMap::new();
    for (i, t) in tags.iter().enumerate() {
        by_tag.entry(*t).or_default().push(i);
    }
    let max = by_tag.keys().next_back().map_or(0, |t| number(*t));
    let mut out: Vec<Entity> = by_tag
        .into_iter()
        .map(|(t, elements)| {
            let (n, name) = (number(t), names.get(t).map(quoted));
            let (tag, name) = if n == 0 { (max.saturating_add(1).max(1), Some(name.unwrap_or_else(|| "tag_0".into()))) } else { (n, name) };
            Entity { dim, tag, physical: true, name, elements }
        })
        .collect();
    out.sort_by_key(|e| e.tag);
    out
}

/// Makes the physical names of one dimension unique, in tag order (Gmsh keys physical names
/// by dimension and name; a surface and a volume group may share a name).
fn unique_names(entities: &mut [Entity]) {
    make_unique(entities.iter_mut().filter_map(|e| e.name.as_mut()));
}

impl<'a> Parts<'a> {
    pub(super) fn surface(s: &'a TriSurface) -> Self {
        let mut entities = group(2, &s.face_tags, |t| t.0, &s.face_names);
        unique_names(&mut entities);
        Parts { vertices: &s.vertices, tris: &s.triangles, tets: &[], entities }
    }

    pub(super) fn volume(m: &'a TetMesh) -> Self {
        let mut entities = group(2, &m.face_tags, |t| t.0, &m.face_names);
        unique_names(&mut entities);
        let mut regions = group(3, &m.region_tags, |t| t.0, &m.region_names);
        unique_names(&mut regions);
        entities.extend(regions);
        Parts { vertices: &m.vertices, tris: &m.boundary, tets: &m.tets, entities }
    }

    fn nodes_of(&self, e: &Entity, k: usize) -> &[u32] {
        if e.dim == 2 { &self.tris[e.elements[k]] } else { &self.tets[e.elements[k]] }
    }
}

fn quoted(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c == '"' {
                '\''
            } else if c.is_control() {
                ' '
            } else {
                c
            }
        })
        .collect()
}

/// Writes `parts` as ASCII MSH 4.1.
pub(super) fn write(path: &Path, parts: &Parts) -> Result<(), IoError> {
    let not = |what: String| IoError::NotRepresentable { path: path.to_path_buf(), format: "MSH 4.1", what };
    if let Some(x) = parts.entities.iter().find(|x| x.tag > i32::MAX as u32) {
        return Err(not(format!("tag {} (Gmsh tags are at most 2147483647)", x.tag)));
    }
    let nv = parts.vertices.len();
    let corners = parts.tris.iter().flatten().chain(parts.tets.iter().flatten());
    if let Some(v) = corners.copied().find(|&v| v as usize >= nv) {
        return Err(not(format!("an element using vertex {v} of a mesh with {nv} vertices")));
    }
    let mut entities: Vec<&Entity> = parts.entities.iter().collect();
    let stray;
    if entities.is_empty() && !parts.vertices.is_empty() {
        stray = Entity { dim: 2, tag: 1, physical: false, name: None, elements: Vec::new() };
        entities.push(&stray);
    }
    // Each node goes in the block of the first entity using it; unused nodes in the first
    // entity of the highest dimension.
    let mut owner = vec![usize::MAX; nv];
    for (k, e) in entities.iter().enumerate() {
        for i in 0..e.elements.len() {
            for &v in parts.nodes_of(e, i) {
                if let Some(o) = owner.get_mut(v as usize).filter(|o| **o == usize::MAX) {
                    *o = k;
                }
            }
        }
    }
    let top = entities.iter().map(|e| e.dim).max().unwrap_or(2);
    let fallback = entities.iter().position(|e| e.dim == top).unwrap_or(0);
    let mut owned: Vec<Vec<u32>> = vec![Vec::new(); entities.len()];
    for (v, o) in owner.iter().enumerate() {
        if let Some(list) = owned.get_mut(if *o == usize::MAX { fallback } else { *o }) {
            list.push(v as u32);
        }
    }
    let bboxes: Vec<Aabb> = entities
        .iter()
        .zip(&owned)
        .map(|(e, own)| {
            let mut b = Aabb::EMPTY;
            for &v in own.iter().chain((0..e.elements.len()).flat_map(|i| parts.nodes_of(e, i))) {
                b.grow(parts.vertices[v as usize]);
            }
            b
        })
        .collect();

    write_atomic(path, |w| {
        let e = write_err(path);
        writeln!(w, "$MeshFormat\n4.1 0 8\n$EndMeshFormat").map_err(&e)?;
        let named: Vec<&&Entity> = entities.iter().filter(|x| x.physical && x.name.is_some()).collect();
        if !named.is_empty() {
            writeln!(w, "$PhysicalNames\n{}", named.len()).map_err(&e)?;
            for x in named {
                writeln!(w, "{} {} \"{}\"", x.dim, x.tag, x.name.as_deref().unwrap_or_default()).map_err(&e)?;
            }
            writeln!(w, "$EndPhysicalNames").map_err(&e)?;
        }
        let count = |d: u8| entities.iter().filter(|x| x.dim == d).count();
        writeln!(w, "$Entities\n0 0 {} {}", count(2), count(3)).map_err(&e)?;
        for d in [2, 3] {
            for (x, b) in entities.iter().zip(&bboxes).filter(|(x, _)| x.dim == d) {
                let (lo, hi) = if b.is_empty() { (DVec3::ZERO, DVec3::ZERO) } else { (b.min, b.max) };
                write!(w, "{} {} {} {} {} {} {}", x.tag, Num(lo.x), Num(lo.y), Num(lo.z), Num(hi.x), Num(hi.y), Num(hi.z)).map_err(&e)?;
                if x.physical { writeln!(w, " 1 {} 0", x.tag) } else { writeln!(w, " 0 0") }.map_err(&e)?;
            }
        }
        writeln!(w, "$EndEntities").map_err(&e)?;

        // Gmsh writes no $Nodes or $Elements section for an empty mesh, and warns about
        // the node tag range of an empty one.
        if nv > 0 {
            let blocks = owned.iter().filter(|o| !o.is_empty()).count();
            writeln!(w, "$Nodes\n{blocks} {nv} 1 {nv}").map_err(&e)?;
            for (x, own) in entities.iter().zip(&owned).filter(|(_, o)| !o.is_empty()) {
                writeln!(w, "{} {} 0 {}", x.dim, x.tag, own.len()).map_err(&e)?;
                for v in own {
                    writeln!(w, "{}", v + 1).map_err(&e)?;
                }
                for &v in own {
                    let p = parts.vertices[v as usize];
                    writeln!(w, "{} {} {}", Num(p.x), Num(p.y), Num(p.z)).map_err(&e)?;
                }
            }
            writeln!(w, "$EndNodes").map_err(&e)?;
        }
        let ne = parts.tris.len() + parts.tets.len();
        if ne == 0 {
            return Ok(());
        }
        let blocks = entities.iter().filter(|x| !x.elements.is_empty()).count();
        writeln!(w, "$Elements\n{blocks} {ne} 1 {ne}").map_err(&e)?;
        // Element tags follow the mesh's order (triangles, then tets), which the reader
        // restores.
        for x in entities.iter().filter(|x| !x.elements.is_empty()) {
            writeln!(w, "{} {} {} {}", x.dim, x.tag, if x.dim == 2 { 2 } else { 4 }, x.elements.len()).map_err(&e)?;
            let first = if x.dim == 2 { 1 } else { 1 + parts.tris.len() };
            for (i, k) in x.elements.iter().enumerate() {
                write!(w, "{}", first + k).map_err(&e)?;
                for v in parts.nodes_of(x, i) {
                    write!(w, " {}", v + 1).map_err(&e)?;
                }
                writeln!(w).map_err(&e)?;
            }
        }
        writeln!(w, "$EndElements").map_err(&e)
    })
}
