//! An [`FeModel`] from a tagged tet mesh: C3D4 or C3D10 elements, an element set per region,
//! and for each named group of CAD faces (a selector) a node set and an element-face surface
//! made of exactly the tet faces whose boundary triangles carry the group's tags; on demand,
//! a surface of one CAD face's element faces on the outer boundary (a side of a tie).

use super::element::{ElementKind, abaqus_face_opposite};
use super::geometry::BoundaryGeometry;
use super::loads::face_nodes;
use super::model::{ElementFace, FeModel, MAX_NAME, deck_name};
use super::quadratic::make_quadratic;
use crate::core::{FaceId, RegionId};
use crate::mesh::TetMesh;
use rustc_hash::FxHashMap;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};

/// The element set of every element.
pub const ALL_ELEMENTS: &str = "EALL";

/// The node set of every node.
pub const ALL_NODES: &str = "NALL";

/// The sets made for one named group of CAD faces.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GroupSets {
    /// The node set: every node of the group's faces on the outer boundary (mid nodes
    /// included).
    pub node_set: String,
    /// The element-face surface: the group's faces on the outer boundary.
    pub surface: String,
    /// Tet faces on the outer boundary.
    pub boundary_faces: usize,
    /// Faces between two elements (an interface between solids, a face partly covered by
    /// another solid it is imprinted on): in neither the node set nor the surface.
    pub interface_faces: usize,
}

/// A model built, and the sets of each group.
#[derive(Clone, Debug)]
pub struct Built {
    /// The model (no materials, sections or steps yet).
    pub model: FeModel,
    /// Group name → its sets.
    pub groups: BTreeMap<String, GroupSets>,
    /// Region → its element set.
    pub regions: BTreeMap<RegionId, String>,
    /// CAD face tag → its element faces on the outer boundary of the mesh (tet faces of one
    /// element only, not an interface between solids), sorted.
    pub outer_faces: BTreeMap<FaceId, Vec<ElementFace>>,
    /// The names taken so far.
    names: Names,
}

impl Built {
    /// Adds to the model an element-face surface of CAD face `face`: its element faces on
    /// the outer boundary ([`Built::outer_faces`]), named after `base` (upper case, valid in a
    /// deck, at most `MAX_NAME` characters, made unique without regard to case). Returns the
    /// name and the number of element faces, or `None` (and adds nothing) where the face has
    /// no element face on the outer boundary.
    pub fn add_face_surface(&mut self, face: FaceId, base: &str) -> Option<(String, usize)> {
        let faces = self.outer_faces.get(&face).filter(|f| !f.is_empty())?.clone();
        let name = self.names.take(base, "");
        let n = faces.len();
        self.model.surfaces.insert(name.clone(), faces);
        Some((name, n))
    }

    /// A name after `base` that no set, surface or other name of the model takes (upper
    /// case, valid in a deck, unique without regard to case), for a tie for example.
    pub fn take_name(&mut self, base: &str) -> String {
        self.names.take(base, "")
    }
}

/// Names unique without regard to case (CalculiX reads names in upper case).
#[derive(Clone, Debug, Default)]
struct Names(BTreeSet<String>);

impl Names {
    /// `base` made valid, upper case, with `suffix`, and unique (`_2`, `_3`, ... before the
    /// suffix where taken).
    fn take(&mut self, base: &str, suffix: &str) -> String {
        let room = MAX_NAME - suffix.len() - 4;
        let mut b = deck_name(base).to_ascii_uppercase();
        b.truncate(room);
        let mut name = format!("{b}{suffix}");
        let mut k = 2;
        while self.0.contains(&name) {
            name = format!("{b}_{k}{suffix}");
            k += 1;
        }
        self.0.insert(name.clone());
        name
    }
}

/// Builds the model of `mesh` with elements of `kind`, coordinates multiplied by `scale`
/// (deck units per mesh unit); boundary mid nodes of C3D10 go through `geometry`.
pub fn build_model(mesh: &TetMesh, groups: &BTreeMap<String, Vec<FaceId>>, kind: ElementKind, geometry: Option<&dyn BoundaryGeometry>, scale: f64) -> Built {
    let (mut nodes, elements, curving) = match kind {
        ElementKind::C3D4 => (mesh.vertices.clone(), mesh.tets.iter().flatten().copied().collect::<Vec<u32>>(), None),
        ElementKind::C3D10 => {
            let q = make_quadratic(mesh, geometry);
            (q.nodes, q.elements, Some(q.report))
        }
    };
    if scale != 1.0 {
        nodes.iter_mut().for_each(|p| *p *= scale);
    }
    let mut names = Names::default();
    names.0.insert(ALL_ELEMENTS.into());
    names.0.insert(ALL_NODES.into());
    let ne = mesh.tets.len() as u32;
    let mut element_sets = BTreeMap::new();
    element_sets.insert(ALL_ELEMENTS.to_string(), (0..ne).collect::<Vec<u32>>());
    let mut regions: BTreeMap<RegionId, String> = BTreeMap::new();
    for (e, r) in mesh.region_tags.iter().enumerate() {
        let name = regions.entry(*r).or_insert_with(|| {
            let base = mesh.region_names.get(*r).map_or_else(|| format!("SOLID{}", r.0), str::to_string);
            names.take(&base, "")
        });
        element_sets.entry(name.clone()).or_insert_with(Vec::new).push(e as u32);
    }
    let mut model = FeModel {
        nodes,
        kind,
        elements,
        element_regions: mesh.region_tags.clone(),
        node_sets: BTreeMap::new(),
        element_sets,
        surfaces: BTreeMap::new(),
        materials: BTreeMap::new(),
        ties: Vec::new(),
        sections: Vec::new(),
        steps: Vec::new(),
        curving,
    };
    model.node_sets.insert(ALL_NODES.to_string(), (0..model.nodes.len() as u32).collect());
    // each boundary triangle's element faces (one outside, two on an interface)
    let mut faces_of: FxHashMap<[u32; 3], Vec<ElementFace>> = FxHashMap::default();
    for tri in &mesh.boundary {
        faces_of.insert(sorted(*tri), Vec::new());
    }
    for (e, t) in mesh.tets.iter().enumerate() {
        for k in 0..4 {
            let f = sorted([t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]]);
            if let Some(v) = faces_of.get_mut(&f) {
                v.push(ElementFace { element: e as u32, face: abaqus_face_opposite(k) });
            }
        }
    }
    let mut outer_faces: BTreeMap<FaceId, Vec<ElementFace>> = BTreeMap::new();
    for (tri, tag) in mesh.boundary.iter().zip(&mesh.face_tags) {
        if let Some([only]) = faces_of.get(&sorted(*tri)).map(Vec::as_slice) {
            outer_faces.entry(*tag).or_default().push(*only);
        }
    }
    outer_faces.values_mut().for_each(|f| f.sort_unstable());
    let mut out = BTreeMap::new();
    for (group, tags) in groups {
        let tags: BTreeSet<FaceId> = tags.iter().copied().collect();
        let mut surface = Vec::new();
        let mut node_set = BTreeSet::new();
        let mut interface = 0;
        for (tri, tag) in mesh.boundary.iter().zip(&mesh.face_tags) {
            if !tags.contains(tag) {
                continue;
            }
            let Some(fs) = faces_of.get(&sorted(*tri)) else { continue };
            let Some(&first) = fs.first() else { continue };
            // the node set and surface of the outer part: a face partly covered by another
            // solid (an imprinted contact) leaves out the nodes inside the model
            if fs.len() == 1 {
                let el = model.element(first.element as usize);
                node_set.extend(face_nodes(kind, first.face).into_iter().map(|k| el[k]));
                surface.push(first);
            } else {
                interface += 1;
            }
        }
        surface.sort_unstable();
        let sets = GroupSets { node_set: names.take(group, ""), surface: names.take(group, "_S"), boundary_faces: surface.len(), interface_faces: interface };
        model.node_sets.insert(sets.node_set.clone(), node_set.into_iter().collect());
        model.surfaces.insert(sets.surface.clone(), surface);
        out.insert(group.clone(), sets);
    }
    Built { model, groups: out, regions, outer_faces, names }
}

fn sorted(mut t: [u32; 3]) -> [u32; 3] {
    t.sort_unstable();
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::test_meshes::two_tets;

    #[test]
    fn groups_get_node_sets_and_surfaces_of_their_tagged_faces() {
        let m = two_tets();
        m.validate().unwrap();
        let tag = m.face_tags[0];
        let groups = BTreeMap::from([("my face".to_string(), vec![tag])]);
        for kind in [ElementKind::C3D4, ElementKind::C3D10] {
            let b = build_model(&m, &groups, kind, None, 1.0);
            b.model.validate().unwrap();
            let g = &b.groups["my face"];
            assert_eq!(g.node_set, "MY_FACE");
            assert_eq!(g.surface, "MY_FACE_S");
            let n_tagged = m.face_tags.iter().filter(|&&t| t == tag).count();
            assert_eq!(g.boundary_faces + g.interface_faces, n_tagged);
            // every face of the surface has the corners of a triangle tagged `tag`
            for f in &b.model.surfaces[&g.surface] {
                let el = b.model.element(f.element as usize);
                let mut c: Vec<u32> = super::super::element::ABAQUS_FACES[f.face as usize].iter().map(|&k| el[k]).collect();
                c.sort_unstable();
                assert!(m.boundary.iter().zip(&m.face_tags).any(|(t, &ft)| ft == tag && sorted(*t).to_vec() == c));
            }
        }
    }

    #[test]
    fn a_face_surface_holds_the_outer_element_faces_of_one_cad_face() {
        // the touching faces of two separate tets are outer faces of one element each
        let m = crate::io::test_meshes::touching_tets();
        m.validate().unwrap();
        for kind in [ElementKind::C3D4, ElementKind::C3D10] {
            let mut b = build_model(&m, &BTreeMap::new(), kind, None, 1.0);
            let (a, na) = b.add_face_surface(FaceId(10), "tie1_a").unwrap();
            let (bb, nb) = b.add_face_surface(FaceId(20), "TIE1_A").unwrap();
            assert_eq!((a.as_str(), bb.as_str(), na, nb), ("TIE1_A", "TIE1_A_2", 1, 1));
            // face 10 is tet 0's face opposite vertex 0: S3 (corners 1, 3, 2)
            assert_eq!(b.model.surfaces[&a], vec![ElementFace { element: 0, face: abaqus_face_opposite(0) }]);
            assert_eq!(b.model.surfaces[&bb][0].element, 1);
            assert!(b.add_face_surface(FaceId(99), "none").is_none());
            b.model.validate().unwrap();
        }
        // where two solids share the face (an interface) it has no outer element face
        let m = two_tets();
        let shared: Vec<[u32; 3]> = vec![[1, 2, 3]];
        let mut with_interface = m.clone();
        with_interface.boundary.extend(shared);
        with_interface.face_tags.push(FaceId(7));
        let mut b = build_model(&with_interface, &BTreeMap::new(), ElementKind::C3D4, None, 1.0);
        assert!(b.add_face_surface(FaceId(7), "x").is_none());
    }

    #[test]
    fn names_are_unique_without_regard_to_case() {
        let mut n = Names::default();
        assert_eq!(n.take("top", ""), "TOP");
        assert_eq!(n.take("TOP", ""), "TOP_2");
        assert_eq!(n.take("1st face", "_S"), "S_1ST_FACE_S");
        assert!(n.take(&"x".repeat(200), "_S").len() <= MAX_NAME);
    }
}
