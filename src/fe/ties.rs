//! Ties between the solids of an assembly: for each contact the mesher found ([`Contact`]) whose faces
//! touch over more than a tiny fraction of their area without sharing nodes, an element-face
//! surface on each of the two CAD faces (their element faces on the outer boundary of the
//! mesh; where the mesh is conforming the faces are inside it and need no tie) and a `*TIE`
//! holding them together: the finer side (more element faces) is the slave, the coarser the
//! master, as CalculiX and Abaqus recommend. Where the contact is conforming in part, the two
//! surfaces share the nodes along the border of the conforming part: the slave is then the
//! slave surface's nodes less those ([`Tie::slave_nodes`]), since CalculiX cannot tie a node to
//! a face it belongs to ("zero coefficient" in its MPC cascade). Likewise a node is the slave
//! of one tie only and of none where it lies on any tie's master surface (ties that chain can
//! cycle): a face that touches several faces (a plate under several bolts) gives each later tie
//! the nodes the earlier ties left; slave nodes farther than the tolerance from their master
//! (which CalculiX would leave free) are not counted as tied.
//!
//! The position tolerance is [`TIE_TOLERANCE_GAPS`] times the part's assembly gap (the
//! pipeline's `assembly::gap_of`): the mesher calls two faces in contact where their
//! triangles come within the gap, three chord deviations of the certified tessellation for a
//! STEP part (each tessellation lies within one chord of the B-rep, so two tessellations of one
//! curved contact are at most two chords apart; C3D10 mid nodes on the CAD face only bring
//! them closer). A slave node within the gap of the master surface is therefore one the mesher
//! found touching, and one farther away, beside a master face that is smaller than the slave
//! face, is not tied. A multiple of the element size would reach that far past the edge of a
//! contact and tie nodes that only face the other solid across a clearance.

use super::loads::face_nodes;
use super::{Built, FeModel, Tie};
use crate::core::bvh::Bvh;
use crate::core::{Aabb, FaceId};
use crate::mesh3d::mesher::Contact;
use glam::DVec3;
use serde::Serialize;
use std::collections::BTreeSet;

/// A contact is tied where its area without shared nodes (`area - shared_area`) is more than
/// this fraction of its area; below it the difference is the rounding of the two areas.
pub const TIE_MIN_FRACTION: f64 = 1e-3;

/// The tie's position tolerance, in assembly gaps (see the module docs).
pub const TIE_TOLERANCE_GAPS: f64 = 1.0;

/// A tie the FE model holds, for reports.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TieSummary {
    /// The tie's name.
    pub name: String,
    /// The slave surface (the finer side).
    pub slave: String,
    /// The master surface (the coarser side).
    pub master: String,
    /// The slave surface's element faces.
    pub slave_faces: usize,
    /// The master surface's element faces.
    pub master_faces: usize,
    /// The slave side: its solid and CAD face.
    pub slave_side: (u32, FaceId),
    /// The master side: its solid and CAD face.
    pub master_side: (u32, FaceId),
    /// The slave node set that replaces the slave surface where the two surfaces share nodes.
    pub slave_nodes: Option<String>,
    /// Nodes the two surfaces share (left out of the slave side).
    pub shared_nodes: usize,
    /// The contact's area without shared nodes (part units squared).
    pub tied_area: f64,
    /// The position tolerance (deck length unit).
    pub tolerance: f64,
}

/// Adds to `built`'s model a tie for each of `contacts` that needs one (module docs), with
/// position tolerance `tolerance` (deck length unit). Surfaces are named `TIEk_A` (the face of
/// the contact's solid `a`) and `TIEk_B`, the tie `TIEk`, k from 1 (made unique against the
/// model's other names). A contact either of whose faces has no element face on the outer
/// boundary gets no tie (its mesh is conforming there).
pub fn tie_contacts(built: &mut Built, contacts: &[Contact], tolerance: f64) -> Vec<TieSummary> {
    // the pairs of surfaces, slave first
    type Side = ((u32, FaceId), String, usize);
    let mut pairs: Vec<(String, f64, Side, Side)> = Vec::new();
    for c in contacts {
        let open = c.area - c.shared_area;
        if !(open > TIE_MIN_FRACTION * c.area) {
            continue;
        }
        let count = |f: FaceId| built.outer_faces.get(&f).map_or(0, Vec::len);
        if count(c.face_a) == 0 || count(c.face_b) == 0 {
            continue;
        }
        let name = built.take_name(&format!("TIE{}", pairs.len() + 1));
        let Some((sa, na)) = built.add_face_surface(c.face_a, &format!("{name}_A")) else { continue };
        let Some((sb, nb)) = built.add_face_surface(c.face_b, &format!("{name}_B")) else { continue };
        let a = ((c.solid_a.0, c.face_a), sa, na);
        let b = ((c.solid_b.0, c.face_b), sb, nb);
        // the finer mesh is the slave; on equal counts, side b
        let (slave, master) = if na > nb { (a, b) } else { (b, a) };
        pairs.push((name, open, slave, master));
    }
    // A node is the dependent side of one equation at most, and never the independent side of
    // another: CalculiX stops with "zero coefficient on the dependent side" where a node is
    // tied twice, or where ties chain into a cycle (a plate's node tied to a bolt whose node
    // is tied back to the plate). So no node of any master surface is a slave, and a face that
    // touches several others gives each later tie only the nodes the earlier ones left.
    let masters: BTreeSet<u32> = pairs.iter().flat_map(|p| surface_nodes(&built.model, &p.3.1)).collect();
    let mut tied: BTreeSet<u32> = BTreeSet::new();
    let mut out = Vec::new();
    for (name, open, slave, master) in pairs {
        let mut dependent = surface_nodes(&built.model, &slave.1);
        let independent = surface_nodes(&built.model, &master.1);
        let before = dependent.len();
        dependent.retain(|v| !independent.contains(v));
        let shared_nodes = before - dependent.len();
        // only nodes within the tolerance of the master are tied (CalculiX leaves the others
        // free)
        let near = Near::new(master_triangles(&built.model, &master.1), tolerance);
        dependent.retain(|v| !masters.contains(v) && !tied.contains(v) && near.holds(built.model.nodes[*v as usize]));
        if dependent.is_empty() {
            built.model.surfaces.remove(&slave.1);
            built.model.surfaces.remove(&master.1);
            continue;
        }
        let whole = dependent.len() == before;
        tied.extend(dependent.iter().copied());
        let slave_nodes = (!whole).then(|| {
            let n = built.take_name(&format!("{}_N", slave.1));
            built.model.node_sets.insert(n.clone(), dependent.into_iter().collect());
            n
        });
        built.model.ties.push(Tie { name: name.clone(), slave: slave.1.clone(), master: master.1.clone(), tolerance, slave_nodes: slave_nodes.clone() });
        out.push(TieSummary { name, slave: slave.1, master: master.1, slave_faces: slave.2, master_faces: master.2, slave_side: slave.0, master_side: master.0, slave_nodes, shared_nodes, tied_area: open, tolerance });
    }
    out
}

/// The triangles of surface `name`'s element faces: a 3-node face, or the four corner
/// triangles of a 6-node face (within a quarter of its curvature's sag of the curved face).
fn master_triangles(m: &FeModel, name: &str) -> Vec<[DVec3; 3]> {
    let mut out = Vec::new();
    for f in &m.surfaces[name] {
        let el = m.element(f.element as usize);
        let p: Vec<DVec3> = face_nodes(m.kind, f.face).into_iter().map(|k| m.nodes[el[k] as usize]).collect();
        if p.len() == 6 {
            out.extend([[p[0], p[3], p[5]], [p[3], p[1], p[4]], [p[5], p[4], p[2]], [p[3], p[4], p[5]]]);
        } else {
            out.push([p[0], p[1], p[2]]);
        }
    }
    out
}

/// Triangles and a distance: which points lie within it of one of them (a bounding-volume
/// hierarchy of the triangles' boxes grown by the distance).
struct Near {
    triangles: Vec<[DVec3; 3]>,
    bvh: Bvh,
    tolerance: f64,
}

impl Near {
    fn new(triangles: Vec<[DVec3; 3]>, tolerance: f64) -> Near {
        let grow = DVec3::splat(tolerance);
        let boxes: Vec<Aabb> = triangles
            .iter()
            .map(|t| {
                let b = Aabb::from_points(t);
                Aabb { min: b.min - grow, max: b.max + grow }
            })
            .collect();
        Near { bvh: Bvh::from_boxes(&boxes), triangles, tolerance }
    }

    /// True when `p` lies within the distance of one of the triangles.
    fn holds(&self, p: DVec3) -> bool {
        let mut hit = false;
        self.bvh.for_each_overlapping(&Aabb { min: p, max: p }, |k| {
            hit = hit || crate::core::closest::point_triangle_distance(p, self.triangles[k as usize]) <= self.tolerance;
        });
        hit
    }
}

/// The nodes of surface `name`'s element faces (mid nodes included).
fn surface_nodes(m: &FeModel, name: &str) -> BTreeSet<u32> {
    m.surfaces[name].iter().flat_map(|f| face_nodes(m.kind, f.face).into_iter().map(move |k| m.element(f.element as usize)[k])).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::RegionId;
    use crate::fe::{ElementKind, build_model};
    use std::collections::BTreeMap;

    fn contact(area: f64, shared_area: f64) -> Contact {
        Contact { solid_a: RegionId(1), face_a: FaceId(10), solid_b: RegionId(2), face_b: FaceId(20), area, shared_area }
    }

    #[test]
    fn a_non_conforming_contact_gets_a_tie_and_a_conforming_one_none() {
        let mesh = crate::io::test_meshes::touching_tets();
        let mut built = build_model(&mesh, &BTreeMap::new(), ElementKind::C3D10, None, 1.0);
        let contacts = vec![contact(0.5, 0.5), contact(0.5, 0.0)];
        let ties = tie_contacts(&mut built, &contacts, 0.25);
        assert_eq!(ties.len(), 1, "{ties:?}");
        let t = &ties[0];
        // one element face each: side b is the slave
        assert_eq!((t.name.as_str(), t.slave.as_str(), t.master.as_str()), ("TIE1", "TIE1_B", "TIE1_A"));
        assert_eq!((t.slave_side, t.master_side, t.slave_faces, t.master_faces), ((2, FaceId(20)), (1, FaceId(10)), 1, 1));
        assert_eq!(built.model.ties, vec![Tie { name: "TIE1".into(), slave: "TIE1_B".into(), master: "TIE1_A".into(), tolerance: 0.25, slave_nodes: None }]);
        assert_eq!((t.slave_nodes.as_ref(), t.shared_nodes), (None, 0));
        built.model.validate().unwrap();
    }
}
