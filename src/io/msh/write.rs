//! The one MSH writer: ASCII 4.1 from a [`Layout`] (entities, their elements and node blocks).
//! Two layers build a layout: [`Layout::surface`] and [`Layout::volume`] here (one entity and
//! physical group per tag, physical names unique per dimension) and the FE deck
//! (`deck::msh`: an entity and physical group per element set and surface).

use crate::core::tag_names::make_unique;
use crate::core::{Aabb, TagNames};
use crate::io::IoError;
use crate::io::atomic::{write_atomic, write_err};
use crate::io::common::Num;
use crate::mesh::{MixedSurface, TetMesh, TriSurface};
use glam::DVec3;
use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

/// One entity of the file: elements of one Gmsh type, in the physical group of its own tag
/// where `physical`.
pub(crate) struct Entity<'a> {
    pub dim: u8,
    /// Entity and physical tag as written.
    pub tag: u32,
    /// In a physical group (every entity but the one made for stray nodes).
    pub physical: bool,
    pub name: Option<String>,
    /// Gmsh element type: 2 (triangle), 4 (tet), 9 (6-node triangle), 11 (10-node tet).
    pub kind: u8,
    /// Nodes per element.
    pub per: usize,
    /// Element connectivity in Gmsh's node order, `per` 0-based vertex indices each.
    pub conn: &'a [u32],
    /// Which elements of `conn` this entity holds, in order.
    pub elements: Vec<usize>,
    /// Element `k` of `conn` is written with tag `first_id + k`.
    pub first_id: usize,
    /// The bounding box written in `$Entities`.
    pub bbox: Aabb,
}

impl Entity<'_> {
    fn nodes(&self, i: usize) -> &[u32] {
        let k = self.elements[i];
        &self.conn[k * self.per..(k + 1) * self.per]
    }

    /// The box of the vertices its elements use.
    pub(crate) fn element_box(&self, vertices: &[DVec3]) -> Aabb {
        let mut b = Aabb::EMPTY;
        for i in 0..self.elements.len() {
            self.nodes(i).iter().for_each(|&v| b.grow(vertices[v as usize]));
        }
        b
    }
}

/// A mesh as entities and node blocks, ready to write.
pub(crate) struct Layout<'a> {
    pub vertices: &'a [DVec3],
    /// In the order of `$PhysicalNames` and the `$Elements` blocks (`$Entities` lists them by
    /// dimension, each dimension in this order).
    pub entities: Vec<Entity<'a>>,
    /// The `$Nodes` blocks: an entity (index into `entities`) and the vertices it lists.
    pub blocks: Vec<(usize, Vec<u32>)>,
    /// Write `$Nodes` and `$Elements` even when they are empty (the FE deck always has);
    /// otherwise they are left out, as Gmsh does.
    pub empty_sections: bool,
}

/// Groups element indices by tag into entities of `dim` over `conn` and gives each a positive
/// tag: 0 becomes one more than the largest tag (Gmsh has no physical group 0), named after its
/// name or `tag_0`. Names are cleaned for the file (`"` becomes `'`, control characters spaces)
/// and made unique in tag order (Gmsh keys physical names by dimension and name; a surface and a
/// volume group may share a name). Boxes are filled in by [`Layout::of_mesh`].
fn group<'a, T: Copy + Ord, const N: usize>(
    dim: u8,
    kind: u8,
    conn: &'a [[u32; N]],
    first_id: usize,
    tags: &[T],
    number: impl Fn(T) -> u32,
    names: &TagNames<T>,
) -> Vec<Entity<'a>> {
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
            Entity { dim, tag, physical: true, name, kind, per: N, conn: conn.as_flattened(), elements, first_id, bbox: Aabb::EMPTY }
        })
        .collect();
    out.sort_by_key(|e| e.tag);
    make_unique(out.iter_mut().filter_map(|e| e.name.as_mut()));
    out
}

impl<'a> Layout<'a> {
    /// A surface: an entity and physical group per face tag.
    pub(crate) fn surface(s: &'a TriSurface) -> Self {
        Self::of_mesh(&s.vertices, group(2, 2, &s.triangles, 1, &s.face_tags, |t| t.0, &s.face_names))
    }

    /// A tet mesh: an entity and physical group per boundary face tag, then per region tag.
    /// Element tags follow the mesh's order (triangles, then tets), which the reader restores.
    pub(crate) fn volume(m: &'a TetMesh) -> Self {
        let mut entities = group(2, 2, &m.boundary, 1, &m.face_tags, |t| t.0, &m.face_names);
        entities.extend(group(3, 4, &m.tets, 1 + m.boundary.len(), &m.region_tags, |t| t.0, &m.region_names));
        Self::of_mesh(&m.vertices, entities)
    }

    /// A surface of triangles and quads: per tag an entity and physical group, holding a block
    /// of triangles (type 2) and one of quads (type 3). Element tags: triangles, then quads.
    pub(crate) fn mixed(s: &'a MixedSurface) -> Self {
        let mut entities = group(2, 2, &s.triangles, 1, &s.triangle_tags, |t| t.0, &s.face_names);
        entities.extend(group(2, 3, &s.quads, 1 + s.triangles.len(), &s.quad_tags, |t| t.0, &s.face_names));
        Self::of_mesh(&s.vertices, entities)
    }

    /// Each node goes in the block of the first entity using it; unused nodes in the first
    /// entity of the highest dimension (or an entity of their own, outside any physical group,
    /// when there are no elements). An entity's box holds its elements and its block.
    fn of_mesh(vertices: &'a [DVec3], mut entities: Vec<Entity<'a>>) -> Self {
        let nv = vertices.len();
        if entities.is_empty() && nv > 0 {
            let stray = Entity { dim: 2, tag: 1, physical: false, name: None, kind: 2, per: 3, conn: &[], elements: Vec::new(), first_id: 1, bbox: Aabb::EMPTY };
            entities.push(stray);
        }
        let mut owner = vec![usize::MAX; nv];
        for (k, e) in entities.iter().enumerate() {
            // element blocks of one entity (several element types) share its node block
            let first = entities.iter().position(|x| (x.dim, x.tag) == (e.dim, e.tag)).unwrap_or(k);
            for i in 0..e.elements.len() {
                for &v in e.nodes(i) {
                    if let Some(o) = owner.get_mut(v as usize).filter(|o| **o == usize::MAX) {
                        *o = first;
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
        for (e, own) in entities.iter_mut().zip(&owned) {
            let mut b = Aabb::EMPTY;
            // vertices out of range are refused by `write`; the box skips them
            for &v in own.iter().chain((0..e.elements.len()).flat_map(|i| e.nodes(i))) {
                if let Some(&p) = vertices.get(v as usize) {
                    b.grow(p);
                }
            }
            e.bbox = b;
        }
        // an entity listed once: its box holds every block of its tag
        for k in 0..entities.len() {
            let key = (entities[k].dim, entities[k].tag);
            if let Some(first) = entities[..k].iter().position(|x| (x.dim, x.tag) == key) {
                let b = entities[k].bbox;
                entities[first].bbox = entities[first].bbox.union(&b);
            }
        }
        let blocks = owned.into_iter().enumerate().filter(|(_, o)| !o.is_empty()).collect();
        Layout { vertices, entities, blocks, empty_sections: false }
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

/// Writes `layout` as ASCII MSH 4.1.
///
/// # Errors
/// [`IoError::NotRepresentable`] for a tag above Gmsh's `i32` range or an element using a
/// vertex the mesh does not have; [`IoError::Write`].
pub(crate) fn write(path: &Path, layout: &Layout) -> Result<(), IoError> {
    let not = |what: String| IoError::NotRepresentable { path: path.to_path_buf(), format: "MSH 4.1", what };
    let entities = &layout.entities;
    if let Some(x) = entities.iter().find(|x| x.tag > i32::MAX as u32) {
        return Err(not(format!("tag {} (Gmsh tags are at most 2147483647)", x.tag)));
    }
    let nv = layout.vertices.len();
    let mut corners = entities.iter().flat_map(|e| (0..e.elements.len()).flat_map(move |i| e.nodes(i)));
    if let Some(v) = corners.find(|&&v| v as usize >= nv) {
        return Err(not(format!("an element using vertex {v} of a mesh with {nv} vertices")));
    }

    write_atomic(path, |w| {
        let e = write_err(path);
        writeln!(w, "$MeshFormat\n4.1 0 8\n$EndMeshFormat").map_err(&e)?;
        // several element blocks (types) of one entity: the entity is listed once
        let listed: Vec<&Entity> = entities.iter().enumerate().filter(|(k, x)| !entities[..*k].iter().any(|y| (y.dim, y.tag) == (x.dim, x.tag))).map(|(_, x)| x).collect();
        let named: Vec<&Entity> = listed.iter().copied().filter(|x| x.physical && x.name.is_some()).collect();
        if !named.is_empty() {
            writeln!(w, "$PhysicalNames\n{}", named.len()).map_err(&e)?;
            for x in named {
                writeln!(w, "{} {} \"{}\"", x.dim, x.tag, x.name.as_deref().unwrap_or_default()).map_err(&e)?;
            }
            writeln!(w, "$EndPhysicalNames").map_err(&e)?;
        }
        let count = |d: u8| listed.iter().filter(|x| x.dim == d).count();
        writeln!(w, "$Entities\n0 0 {} {}", count(2), count(3)).map_err(&e)?;
        for d in [2, 3] {
            for x in listed.iter().filter(|x| x.dim == d) {
                let (lo, hi) = if x.bbox.is_empty() { (DVec3::ZERO, DVec3::ZERO) } else { (x.bbox.min, x.bbox.max) };
                write!(w, "{} {} {} {} {} {} {}", x.tag, Num(lo.x), Num(lo.y), Num(lo.z), Num(hi.x), Num(hi.y), Num(hi.z)).map_err(&e)?;
                if x.physical { writeln!(w, " 1 {} 0", x.tag) } else { writeln!(w, " 0 0") }.map_err(&e)?;
            }
        }
        writeln!(w, "$EndEntities").map_err(&e)?;

        // Gmsh writes no $Nodes or $Elements section for an empty mesh, and warns about
        // the node tag range of an empty one.
        if nv > 0 || layout.empty_sections {
            writeln!(w, "$Nodes\n{} {nv} 1 {nv}", layout.blocks.len()).map_err(&e)?;
            for (k, own) in &layout.blocks {
                let x = &entities[*k];
                writeln!(w, "{} {} 0 {}", x.dim, x.tag, own.len()).map_err(&e)?;
                for v in own {
                    writeln!(w, "{}", v + 1).map_err(&e)?;
                }
                for &v in own {
                    let p = layout.vertices[v as usize];
                    writeln!(w, "{} {} {}", Num(p.x), Num(p.y), Num(p.z)).map_err(&e)?;
                }
            }
            writeln!(w, "$EndNodes").map_err(&e)?;
        }
        let ne: usize = entities.iter().map(|x| x.elements.len()).sum();
        if ne == 0 && !layout.empty_sections {
            return Ok(());
        }
        let blocks = entities.iter().filter(|x| !x.elements.is_empty()).count();
        writeln!(w, "$Elements\n{blocks} {ne} 1 {ne}").map_err(&e)?;
        for x in entities.iter().filter(|x| !x.elements.is_empty()) {
            writeln!(w, "{} {} {} {}", x.dim, x.tag, x.kind, x.elements.len()).map_err(&e)?;
            for (i, k) in x.elements.iter().enumerate() {
                write!(w, "{}", x.first_id + k).map_err(&e)?;
                for v in x.nodes(i) {
                    write!(w, " {}", v + 1).map_err(&e)?;
                }
                writeln!(w).map_err(&e)?;
            }
        }
        writeln!(w, "$EndElements").map_err(&e)
    })
}
