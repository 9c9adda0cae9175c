//! 2:1 balance: leaves that share a side differ by at most one level.
//!
//! - Stage: second, after refinement, before templates and the boundary band.
//! - Inputs: a refined [`Quadtree`] and its [`Domain`] (to classify new children).
//! - Output: the same tree with leaves split until balanced; [`check_balance`] tests the
//!   property on any tree independently of how it was reached.
//! - Invariants: balancing only splits (every quadrant of the refined tree is still there),
//!   in a fixed order (deterministic); neighbours are across sides (corner neighbours may
//!   differ by more, which the templates do not need).
//!
//! With sides balanced, a leaf has at most one hanging node per side, the midpoint, which is
//! what the interior templates (`templates.rs`) are made for.

use crate::mesh2d::domain::Domain;
use super::tree::{Quadtree, DIRECTIONS};
use super::QuadtreeError;

/// Two leaves sharing a side whose levels differ by more than one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("quadrants {fine} (level {fine_level}) and {coarse} (level {coarse_level}) share a side")]
pub struct Unbalanced {
    /// The finer leaf, or a finer node beside `coarse`.
    pub fine: u32,
    /// Its level.
    pub fine_level: u8,
    /// The coarser leaf.
    pub coarse: u32,
    /// Its level.
    pub coarse_level: u8,
}

/// Splits leaves until every two leaves sharing a side differ by at most one level.
///
/// # Errors
/// [`QuadtreeError::TooManyQuadrants`] from a split.
pub fn balance(tree: &mut Quadtree, domain: &Domain) -> Result<(), QuadtreeError> {
    // a leaf's coarse neighbours are split until they are at most one level above it; the
    // children of every split are checked in turn (a split can unbalance them).
    let mut work: Vec<u32> = tree.leaves().collect();
    work.reverse();
    while let Some(i) = work.pop() {
        if !tree.nodes[i as usize].is_leaf() {
            continue;
        }
        let level = tree.nodes[i as usize].level;
        for dir in 0..DIRECTIONS.len() {
            while let Some(n) = tree.neighbour(i, dir) {
                let nq = &tree.nodes[n as usize];
                if !(nq.is_leaf() && nq.level + 1 < level) {
                    break;
                }
                let first = tree.nodes.len() as u32;
                tree.split(n, domain)?;
                // the new children must be checked against their own neighbours
                for c in (first..first + 4).rev() {
                    work.push(c);
                }
            }
        }
    }
    Ok(())
}

/// Checks that leaves sharing a side differ by at most one level.
///
/// # Errors
/// The first pair found (in node order) that does not.
pub fn check_balance(tree: &Quadtree) -> Result<(), Unbalanced> {
    for i in tree.leaves() {
        let level = tree.nodes[i as usize].level;
        for dir in 0..DIRECTIONS.len() {
            let Some(n) = tree.neighbour(i, dir) else { continue };
            let nq = &tree.nodes[n as usize];
            if nq.is_leaf() {
                if nq.level + 1 < level {
                    return Err(Unbalanced { fine: i, fine_level: level, coarse: n, coarse_level: nq.level });
                }
            } else {
                // same level with children: those along the side must be leaves
                for c in tree.children_facing(n, dir) {
                    if !tree.nodes[c as usize].is_leaf() {
                        return Err(Unbalanced { fine: c, fine_level: level + 1, coarse: i, coarse_level: level });
                    }
                }
            }
        }
    }
    Ok(())
}
