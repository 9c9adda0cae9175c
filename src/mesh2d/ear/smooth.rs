//! Laplacian smoothing of the interior points of a triangle mesh, shared by ear cutting and
//! recursive subdivision.
//!
//! - Inputs: points, counter-clockwise triangles, which points may move.
//! - Output: moved points (the triangles are unchanged); the number of moves.
//! - Invariants: a point moves to the mean of its neighbours only when every triangle
//!   around it stays strictly counter-clockwise (exact [`orient2d`]) and their smallest
//!   angle grows; points are visited in index order (deterministic).

use super::trimesh::min_angle;
use crate::mesh2d::stars::Stars;
use crate::core::predicates::orient2d;
use crate::core::Sign;
use glam::DVec2;

/// Runs `passes` passes over the movable points (see the module docs).
pub(crate) fn smooth(pts: &mut [DVec2], tris: &[[u32; 3]], movable: &dyn Fn(u32) -> bool, passes: usize) -> usize {
    let n = pts.len();
    let stars = Stars::new(n, tris);
    let mut moves = 0;
    let mut ring: Vec<u32> = Vec::new();
    for _ in 0..passes {
        for v in 0..n as u32 {
            let around = stars.of(v as usize);
            if around.is_empty() || !movable(v) {
                continue;
            }
            ring.clear();
            for &t in around {
                ring.extend(tris[t as usize].iter().copied().filter(|&w| w != v));
            }
            ring.sort_unstable();
            ring.dedup();
            let target = ring.iter().map(|&w| pts[w as usize]).sum::<DVec2>() / ring.len() as f64;
            let worst = |pts: &[DVec2], at: DVec2| -> Option<f64> {
                let mut m = f64::INFINITY;
                for &t in around {
                    let c: [DVec2; 3] = std::array::from_fn(|k| if tris[t as usize][k] == v { at } else { pts[tris[t as usize][k] as usize] });
                    if orient2d(c[0], c[1], c[2]) != Sign::Positive {
                        return None;
                    }
                    m = m.min(min_angle(c[0], c[1], c[2]));
                }
                Some(m)
            };
            let old = worst(pts, pts[v as usize]).unwrap_or(f64::NEG_INFINITY);
            if let Some(new) = worst(pts, target) {
                if new > old {
                    pts[v as usize] = target;
                    moves += 1;
                }
            }
        }
    }
    moves
}
