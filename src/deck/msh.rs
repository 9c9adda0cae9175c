//! The FE model as Gmsh MSH 4.1 (ASCII): nodes, the elements as tets (4 or 10 nodes) in a
//! volume entity per solid, and each element-face surface as triangles (3 or 6 nodes) in a
//! surface entity of its own; every entity is a physical group named after its set, so Gmsh
//! and meshio read the sets by name. MSH has no node sets: a surface's nodes are its
//! triangles' nodes. The 10-node tet is written in Gmsh's order (its last two mid nodes are
//! those of edges 2-3 and 1-3, swapped from Abaqus and VTK).
//!
//! This file only lays the model out as entities; the one MSH writer
//! ([`crate::io::msh::write`]) writes them.

use crate::core::Aabb;
use crate::fe::build::ALL_ELEMENTS;
use crate::fe::loads::face_nodes;
use crate::fe::{ElementKind, FeModel};
use crate::io::IoError;
use crate::io::msh::write::{Entity, Layout, write};
use std::collections::BTreeMap;
use std::path::Path;

/// One set to write: its dimension, name and elements' nodes in Gmsh order, flat.
struct Set {
    dim: u8,
    name: String,
    conn: Vec<u32>,
}

/// Writes `m` as MSH 4.1.
///
/// # Errors
/// [`IoError::NotRepresentable`] where the model fails [`FeModel::validate`]; [`IoError::Write`].
pub fn write_msh(path: &Path, m: &FeModel) -> Result<(), IoError> {
    m.validate().map_err(|e| IoError::NotRepresentable { path: path.to_path_buf(), format: "MSH 4.1", what: e.to_string() })?;
    let sets = sets(m);
    write(path, &layout(m, &sets))
}

/// Gmsh's node order of an element of `kind` in terms of fepre's (Abaqus) order.
fn gmsh_order(kind: ElementKind) -> &'static [usize] {
    match kind {
        ElementKind::C3D4 => &[0, 1, 2, 3],
        ElementKind::C3D10 => &[0, 1, 2, 3, 4, 5, 6, 7, 9, 8],
    }
}

/// A volume per solid (the element sets other than EALL, in name order, or EALL where there
/// are none), then a surface per element-face surface.
fn sets(m: &FeModel) -> Vec<Set> {
    let order = gmsh_order(m.kind);
    let tet = |e: usize| order.iter().map(move |&k| m.element(e)[k]);
    let mut out: Vec<Set> = Vec::new();
    for (name, set) in m.element_sets.iter().filter(|(n, _)| n.as_str() != ALL_ELEMENTS) {
        out.push(Set { dim: 3, name: name.clone(), conn: set.iter().flat_map(|&e| tet(e as usize)).collect() });
    }
    if out.is_empty() {
        out.push(Set { dim: 3, name: ALL_ELEMENTS.into(), conn: (0..m.element_count()).flat_map(tet).collect() });
    }
    for (name, faces) in &m.surfaces {
        let conn = faces
            .iter()
            .flat_map(|f| {
                let el = m.element(f.element as usize);
                face_nodes(m.kind, f.face).into_iter().map(|k| el[k])
            })
            .collect();
        out.push(Set { dim: 2, name: name.clone(), conn });
    }
    out
}

/// The sets as entities: tags 1, 2, ... per dimension, element tags 1, 2, ... in entity
/// order, and every node in the first volume's block.
fn layout<'a>(m: &'a FeModel, sets: &'a [Set]) -> Layout<'a> {
    let mut next: BTreeMap<u8, u32> = BTreeMap::new();
    let mut first_id = 1;
    let entities = sets
        .iter()
        .map(|s| {
            let tag = next.entry(s.dim).or_insert(0);
            *tag += 1;
            let (kind, per) = match (s.dim, m.kind) {
                (3, ElementKind::C3D4) => (4, 4),
                (3, ElementKind::C3D10) => (11, 10),
                (_, ElementKind::C3D4) => (2, 3),
                (_, ElementKind::C3D10) => (9, 6),
            };
            let n = s.conn.len() / per;
            let mut e = Entity { dim: s.dim, tag: *tag, physical: true, name: Some(s.name.clone()), kind, per, conn: &s.conn, elements: (0..n).collect(), first_id, bbox: Aabb::EMPTY };
            e.bbox = e.element_box(&m.nodes);
            first_id += n;
            e
        })
        .collect::<Vec<_>>();
    let first_volume = entities.iter().position(|e| e.dim == 3).unwrap_or(0);
    let all = (0..m.nodes.len() as u32).collect();
    Layout { vertices: &m.nodes, entities, blocks: vec![(first_volume, all)], empty_sections: true }
}
