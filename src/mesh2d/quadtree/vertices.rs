//! The mesh's vertex list while it is built: lattice points of the tree are numbered once
//! (shared by every template and by the boundary band), other points are appended.
//!
//! - Stage: used by the templates and the band.
//! - Inputs: lattice coordinates ([`super::tree::lattice`]) or plain points.
//! - Output: vertex ids into one position array.
//! - Invariants: a lattice point has exactly one id; ids are handed out in call order
//!   (deterministic when the callers are).

use super::tree::Quadtree;
use glam::DVec2;
use std::collections::HashMap;

/// Vertex positions and the ids of lattice points.
#[derive(Clone, Debug, Default)]
pub struct Vertices {
    /// Positions, by id.
    pub positions: Vec<DVec2>,
    lattice: HashMap<(u32, u32), u32>,
}

impl Vertices {
    /// The id of lattice point `key`, numbered on first use.
    pub fn lattice(&mut self, tree: &Quadtree, key: (u32, u32)) -> u32 {
        if let Some(&id) = self.lattice.get(&key) {
            return id;
        }
        let id = self.push(tree.point(key));
        self.lattice.insert(key, id);
        id
    }

    /// The id of lattice point `key` if it has one.
    pub fn lattice_id(&self, key: (u32, u32)) -> Option<u32> {
        self.lattice.get(&key).copied()
    }

    /// Appends a point.
    pub fn push(&mut self, p: DVec2) -> u32 {
        self.positions.push(p);
        (self.positions.len() - 1) as u32
    }
}
