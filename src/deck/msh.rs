//! The FE model as Gmsh MSH 4.1 (ASCII): nodes, the elements as tets (4 or 10 nodes) in a
//! volume entity per solid, and each element-face surface as triangles (3 or 6 nodes) in a
//! surface entity of its own; every entity is a physical group named after its set, so Gmsh
//! and meshio read the sets by name. MSH has no node sets: a surface's nodes are its
//! triangles' nodes. The 10-node tet is written in Gmsh's order (its last two mid nodes are
//! those of edges 2-3 and 1-3, swapped from Abaqus and VTK).

use crate::core::Aabb;
use crate::fe::build::ALL_ELEMENTS;
use crate::fe::loads::face_nodes;
use crate::fe::{ElementKind, FeModel};
use crate::io::IoError;
use crate::io::atomic::{write_atomic, write_err};
use crate::io::common::Num;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

/// One entity: its dimension, name and elements (each a list of node indices).
struct Entity {
    dim: u8,
    name: String,
    elements: Vec<Vec<u32>>,
}

/// Writes `m` as MSH 4.1.
///
/// # Errors
/// [`IoError::NotRepresentable`] where the model fails [`FeModel::validate`]; [`IoError::Write`].
pub fn write_msh(path: &Path, m: &FeModel) -> Result<(), IoError> {
    m.validate().map_err(|e| IoError::NotRepresentable { path: path.to_path_buf(), format: "MSH 4.1", what: e.to_string() })?;
    let text = msh_text(m);
    write_atomic(path, |w| w.write_all(text.as_bytes()).map_err(write_err(path)))
}

/// Gmsh's node order of an element of `kind` in terms of fepre's (Abaqus) order.
fn gmsh_order(kind: ElementKind) -> &'static [usize] {
    match kind {
        ElementKind::C3D4 => &[0, 1, 2, 3],
        ElementKind::C3D10 => &[0, 1, 2, 3, 4, 5, 6, 7, 9, 8],
    }
}

fn entities(m: &FeModel) -> Vec<Entity> {
    // a volume per solid: the element sets other than EALL, in name order
    let mut out: Vec<Entity> = Vec::new();
    for (name, set) in m.element_sets.iter().filter(|(n, _)| n.as_str() != ALL_ELEMENTS) {
        let order = gmsh_order(m.kind);
        let elements = set.iter().map(|&e| order.iter().map(|&k| m.element(e as usize)[k]).collect()).collect();
        out.push(Entity { dim: 3, name: name.clone(), elements });
    }
    if out.is_empty() {
        let elements = (0..m.element_count()).map(|e| gmsh_order(m.kind).iter().map(|&k| m.element(e)[k]).collect()).collect();
        out.push(Entity { dim: 3, name: ALL_ELEMENTS.into(), elements });
    }
    for (name, faces) in &m.surfaces {
        let elements = faces
            .iter()
            .map(|f| {
                let el = m.element(f.element as usize);
                face_nodes(m.kind, f.face).into_iter().map(|k| el[k]).collect()
            })
            .collect();
        out.push(Entity { dim: 2, name: name.clone(), elements });
    }
    out
}

/// The file's text.
fn msh_text(m: &FeModel) -> String {
    let ents = entities(m);
    // entity and physical tags: 1, 2, ... per dimension
    let mut next: BTreeMap<u8, u32> = BTreeMap::new();
    let tags: Vec<u32> = ents
        .iter()
        .map(|e| {
            let t = next.entry(e.dim).or_insert(0);
            *t += 1;
            *t
        })
        .collect();
    let mut s = String::from("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    let _ = writeln!(s, "$PhysicalNames\n{}", ents.len());
    for (e, t) in ents.iter().zip(&tags) {
        let _ = writeln!(s, "{} {t} \"{}\"", e.dim, e.name);
    }
    s.push_str("$EndPhysicalNames\n");
    let count = |d: u8| ents.iter().filter(|e| e.dim == d).count();
    let _ = writeln!(s, "$Entities\n0 0 {} {}", count(2), count(3));
    for d in [2, 3] {
        for (e, t) in ents.iter().zip(&tags).filter(|(e, _)| e.dim == d) {
            let mut b = Aabb::EMPTY;
            e.elements.iter().flatten().for_each(|&v| b.grow(m.nodes[v as usize]));
            let (lo, hi) = if b.is_empty() { (glam::DVec3::ZERO, glam::DVec3::ZERO) } else { (b.min, b.max) };
            let _ = writeln!(s, "{t} {} {} {} {} {} {} 1 {t} 0", Num(lo.x), Num(lo.y), Num(lo.z), Num(hi.x), Num(hi.y), Num(hi.z));
        }
    }
    s.push_str("$EndEntities\n");
    // every node in the first volume's block
    let nn = m.nodes.len();
    let first_volume = ents.iter().zip(&tags).find(|(e, _)| e.dim == 3).map_or(1, |(_, t)| *t);
    let _ = writeln!(s, "$Nodes\n1 {nn} 1 {nn}\n3 {first_volume} 0 {nn}");
    for v in 1..=nn {
        let _ = writeln!(s, "{v}");
    }
    for p in &m.nodes {
        let _ = writeln!(s, "{} {} {}", Num(p.x), Num(p.y), Num(p.z));
    }
    s.push_str("$EndNodes\n");
    let ne: usize = ents.iter().map(|e| e.elements.len()).sum();
    let blocks = ents.iter().filter(|e| !e.elements.is_empty()).count();
    let _ = writeln!(s, "$Elements\n{blocks} {ne} 1 {ne}");
    let mut id = 1;
    for (e, t) in ents.iter().zip(&tags).filter(|(e, _)| !e.elements.is_empty()) {
        let ty = match (e.dim, m.kind) {
            (3, ElementKind::C3D4) => 4,
            (3, ElementKind::C3D10) => 11,
            (_, ElementKind::C3D4) => 2,
            (_, ElementKind::C3D10) => 9,
        };
        let _ = writeln!(s, "{} {t} {ty} {}", e.dim, e.elements.len());
        for el in &e.elements {
            let _ = write!(s, "{id}");
            for v in el {
                let _ = write!(s, " {}", v + 1);
            }
            s.push('\n');
            id += 1;
        }
    }
    s.push_str("$EndElements\n");
    s
}
