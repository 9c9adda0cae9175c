//! Interior quadrants to elements by the 2:1 templates.
//!
//! - Stage: third, after balancing.
//! - Inputs: the balanced [`Quadtree`], its interior leaves.
//! - Output: triangles (and, when asked, quadrilaterals) over every interior leaf, and the
//!   interface: the sides (split at hanging nodes) that interior leaves share with boundary
//!   leaves, as directed edges with the interior on their right (the band on their left).
//! - Invariants: the element boundary of a leaf is its corners plus the midpoint of every
//!   side whose neighbour is finer (one hanging node at most per side, by the balance), so
//!   neighbouring leaves conform. A leaf without hanging nodes gives two right isosceles
//!   triangles (or one square); a leaf with some gives a fan from its centre over its
//!   boundary pieces, each a right isosceles triangle or half of a square's quarter: every
//!   angle is 45° or 90°.

use super::tree::{lattice, Quadtree, Status};
use super::vertices::Vertices;

/// The elements of the interior leaves and the interface to the band.
#[derive(Clone, Debug, Default)]
pub struct Templates {
    /// Counter-clockwise triangles.
    pub triangles: Vec<[u32; 3]>,
    /// Counter-clockwise squares (only when quadrilaterals were asked for).
    pub quads: Vec<[u32; 4]>,
    /// Interface edges `[a, b]`, the interior leaf on their right and the band on their
    /// left: the constraints the band is triangulated against.
    pub interface: Vec<[u32; 2]>,
}

/// The side order of a leaf's boundary walk: bottom (`-y`), right (`+x`), top (`+y`),
/// left (`-x`), as indices into [`super::tree::DIRECTIONS`].
const WALK: [usize; 4] = [2, 1, 3, 0];

/// Builds the templates of every interior leaf, in node order.
pub fn build(tree: &Quadtree, vertices: &mut Vertices, quads: bool) -> Templates {
    let mut out = Templates::default();
    for i in tree.leaves() {
        let q = &tree.nodes[i as usize];
        if q.status != Status::Interior {
            continue;
        }
        let (level, x, y) = (q.level, q.x, q.y);
        // corners at level + 1 lattice: (2x, 2y) .. (2x + 2, 2y + 2); midpoints between
        let fine = level + 1;
        let corner = [(0u32, 0u32), (2, 0), (2, 2), (0, 2)];
        let mid = [(1u32, 0u32), (2, 1), (1, 2), (0, 1)];
        let key = |(dx, dy): (u32, u32)| lattice(fine, 2 * x + dx, 2 * y + dy);
        let mut cycle: Vec<u32> = Vec::with_capacity(8);
        let mut hanging = false;
        for (k, &dir) in WALK.iter().enumerate() {
            let a = vertices.lattice(tree, key(corner[k]));
            cycle.push(a);
            let across = tree.neighbour(i, dir);
            let finer = across.is_some_and(|n| !tree.nodes[n as usize].is_leaf());
            let m = if finer {
                hanging = true;
                Some(vertices.lattice(tree, key(mid[k])))
            } else {
                None
            };
            if let Some(m) = m {
                cycle.push(m);
            }
            // the interface: sides (or half sides) whose other side is not interior
            let b_key = key(corner[(k + 1) % 4]);
            let pieces: Vec<(u32, u32, bool)> = match (across, m) {
                (None, _) => vec![(a, vertices.lattice(tree, b_key), true)],
                (Some(n), Some(m)) => {
                    let [c0, c1] = tree.children_facing(n, dir);
                    // walk order: bottom and right go up in coordinate, top and left go down
                    let (first, second) = if k < 2 { (c0, c1) } else { (c1, c0) };
                    let b = vertices.lattice(tree, b_key);
                    vec![(a, m, tree.nodes[first as usize].status != Status::Interior), (m, b, tree.nodes[second as usize].status != Status::Interior)]
                }
                (Some(n), None) => vec![(a, vertices.lattice(tree, b_key), tree.nodes[n as usize].status != Status::Interior)],
            };
            for (u, v, is_interface) in pieces {
                if is_interface {
                    out.interface.push([v, u]);
                }
            }
        }
        if !hanging {
            if quads {
                out.quads.push([cycle[0], cycle[1], cycle[2], cycle[3]]);
            } else {
                out.triangles.push([cycle[0], cycle[1], cycle[2]]);
                out.triangles.push([cycle[0], cycle[2], cycle[3]]);
            }
        } else {
            let c = vertices.lattice(tree, key((1, 1)));
            for k in 0..cycle.len() {
                out.triangles.push([c, cycle[k], cycle[(k + 1) % cycle.len()]]);
            }
        }
    }
    out
}
