//! Is a step singular? Each connected piece of the mesh (elements joined by shared nodes or by
//! a tie between two surfaces, [`FeModel::ties`]) must have its rigid-body motions held
//! (a static step: six, by fixed or prescribed degrees of freedom) or its temperature tied
//! down (a heat step: a prescribed temperature or a film somewhere on it). A frequency step
//! may be free.

use super::model::FeModel;
use super::step::{Analysis, Bc, Load, Step};
use crate::core::ids::NONE;
use crate::core::union_find::UnionFind;
use glam::DVec3;

/// A connected piece of the mesh that the step leaves free.
#[derive(Clone, Debug, PartialEq)]
pub struct FreePiece {
    /// Its elements.
    pub elements: usize,
    /// A node of it (0-based), for messages.
    pub node: u32,
    /// Rigid-body motions left free (static: 1 to 6; heat: 1, the temperature level).
    pub free_modes: usize,
}

/// The pieces of `m` that `step` leaves free (empty when the step is not singular).
pub fn free_pieces(m: &FeModel, step: &Step) -> Vec<FreePiece> {
    if matches!(step.analysis, Analysis::Frequency { .. }) {
        return Vec::new();
    }
    let nn = m.nodes.len();
    let mut uf = UnionFind::new(nn);
    for e in 0..m.element_count() {
        let el = m.element(e);
        for &v in &el[1..] {
            uf.union(el[0], v);
        }
    }
    // a tie joins the pieces of its two surfaces
    for t in &m.ties {
        let mut nodes = [&t.slave, &t.master].into_iter().filter_map(|s| m.surfaces.get(s.as_str())).flatten().map(|f| m.element(f.element as usize)[0]);
        if let Some(first) = nodes.next() {
            for v in nodes {
                uf.union(first, v);
            }
        }
    }
    let mut piece_of = vec![NONE; nn];
    let mut pieces: Vec<(usize, u32)> = Vec::new(); // (elements, first node)
    for e in 0..m.element_count() {
        let r = uf.find(m.element(e)[0]) as usize;
        if piece_of[r] == NONE {
            piece_of[r] = pieces.len() as u32;
            pieces.push((0, m.element(e)[0]));
        }
        pieces[piece_of[r] as usize].0 += 1;
    }
    let mut piece = |v: u32| piece_of[uf.find(v) as usize] as usize;
    let mut out = Vec::new();
    match step.analysis {
        Analysis::Heat => {
            let mut held = vec![false; pieces.len()];
            for bc in &step.bcs {
                if let Bc::Temperature { nodes, .. } = bc {
                    for &v in &m.node_sets[nodes] {
                        held[piece(v)] = true;
                    }
                }
            }
            for load in &step.loads {
                if let Load::Film { surface, .. } = load {
                    for f in &m.surfaces[surface] {
                        held[piece(m.element(f.element as usize)[0])] = true;
                    }
                }
            }
            for (k, &(elements, node)) in pieces.iter().enumerate() {
                if !held[k] {
                    out.push(FreePiece { elements, node, free_modes: 1 });
                }
            }
        }
        _ => {
            // per piece, the constrained (node, dof) pairs
            let mut held: Vec<Vec<(u32, u8)>> = vec![Vec::new(); pieces.len()];
            for bc in &step.bcs {
                match bc {
                    Bc::Fixed { nodes, dofs } => {
                        for &v in &m.node_sets[nodes] {
                            held[piece(v)].extend(dofs.iter().map(|&d| (v, d)));
                        }
                    }
                    Bc::Displacement { nodes, dof, .. } => {
                        for &v in &m.node_sets[nodes] {
                            held[piece(v)].push((v, *dof));
                        }
                    }
                    Bc::Temperature { .. } => {}
                }
            }
            for (k, &(elements, node)) in pieces.iter().enumerate() {
                let free = 6 - rigid_rank(&m.nodes, &held[k]);
                if free > 0 {
                    out.push(FreePiece { elements, node, free_modes: free });
                }
            }
        }
    }
    out
}

/// The number of the six rigid-body motions (`u = a + ω × x`) that holding `held` at zero
/// removes: the rank of the constraint rows `[e_d, x × e_d]`, positions centred and scaled.
fn rigid_rank(points: &[DVec3], held: &[(u32, u8)]) -> usize {
    if held.is_empty() {
        return 0;
    }
    let c = held.iter().map(|&(v, _)| points[v as usize]).sum::<DVec3>() / held.len() as f64;
    let scale = held.iter().map(|&(v, _)| (points[v as usize] - c).length()).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
    let mut a = [[0.0f64; 6]; 6];
    for &(v, d) in held {
        let x = (points[v as usize] - c) / scale;
        let e = match d {
            1 => DVec3::X,
            2 => DVec3::Y,
            _ => DVec3::Z,
        };
        let r = x.cross(e);
        let row = [e.x, e.y, e.z, r.x, r.y, r.z];
        for i in 0..6 {
            for j in 0..6 {
                a[i][j] += row[i] * row[j];
            }
        }
    }
    // rank by Gaussian elimination with full pivoting, relative to the largest pivot
    let mut rank = 0;
    let mut used_r = [false; 6];
    let mut used_c = [false; 6];
    let mut first = 0.0;
    for _ in 0..6 {
        let mut best = (0.0, 0, 0);
        for i in (0..6).filter(|&i| !used_r[i]) {
            for j in (0..6).filter(|&j| !used_c[j]) {
                if a[i][j].abs() > best.0 {
                    best = (a[i][j].abs(), i, j);
                }
            }
        }
        if rank == 0 {
            first = best.0;
        }
        if best.0 <= 1e-9 * first || best.0 == 0.0 {
            break;
        }
        let (_, pi, pj) = best;
        used_r[pi] = true;
        used_c[pj] = true;
        rank += 1;
        for i in (0..6).filter(|&i| !used_r[i]) {
            let f = a[i][pj] / a[pi][pj];
            for j in 0..6 {
                a[i][j] -= f * a[pi][j];
            }
        }
    }
    rank
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::FaceId;
    use crate::fe::model::Tie;
    use crate::fe::{ElementKind, build_model};
    use std::collections::BTreeMap;

    #[test]
    fn a_tie_joins_two_pieces() {
        // two tets touching without shared nodes; the first held at its three base nodes
        let mesh = crate::io::test_meshes::touching_tets();
        let mut b = build_model(&mesh, &BTreeMap::new(), ElementKind::C3D4, None, 1.0);
        let (a, _) = b.add_face_surface(FaceId(10), "a").unwrap();
        let (c, _) = b.add_face_surface(FaceId(20), "b").unwrap();
        let mut m = b.model;
        m.node_sets.insert("HELD".into(), vec![0, 1, 2]);
        let step = Step { name: "s".into(), analysis: Analysis::Static, bcs: vec![Bc::Fixed { nodes: "HELD".into(), dofs: vec![1, 2, 3] }], loads: Vec::new() };
        let free = free_pieces(&m, &step);
        assert_eq!(free.len(), 1, "{free:?}");
        assert_eq!((free[0].elements, free[0].free_modes), (1, 6));
        m.ties.push(Tie { name: "T".into(), slave: c, master: a, tolerance: 1e-6, slave_nodes: None });
        m.validate().unwrap();
        assert_eq!(free_pieces(&m, &step), Vec::new());
    }

    #[test]
    fn rigid_rank_counts_the_motions_held() {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)];
        // one point fixed in all three: translations only
        assert_eq!(rigid_rank(&p, &[(0, 1), (0, 2), (0, 3)]), 3);
        // two points fixed: the rotation about the line through them stays free
        assert_eq!(rigid_rank(&p, &[(0, 1), (0, 2), (0, 3), (1, 1), (1, 2), (1, 3)]), 5);
        // three points not on a line: all six
        let three: Vec<(u32, u8)> = (0..3).flat_map(|v| (1..=3).map(move |d| (v, d))).collect();
        assert_eq!(rigid_rank(&p, &three), 6);
        // a plane held in z only: x, y and the rotation about z stay free
        let z: Vec<(u32, u8)> = (0..4).map(|v| (v, 3)).collect();
        assert_eq!(rigid_rank(&p, &z), 3);
    }
}
