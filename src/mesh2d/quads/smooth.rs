//! Smoothing of the interior points of an all-quad mesh.
//!
//! - Stage: fourth, after the split.
//! - Inputs: a valid mesh of strictly convex quads, the vertices that may not move (the
//!   boundary), the number of passes.
//! - Output: the same mesh with interior points moved; the number of moves.
//! - Invariants: a move is kept only if every quad around the point stays strictly convex
//!   (exact `orient2d` at each of its corners) and the worst scaled Jacobian of those quads
//!   does not decrease; so the mesh stays valid and its worst quad never gets worse.
//!
//! Each pass visits the free points in index order twice: first the Laplacian move (the
//! mean of the point's edge neighbours, the lecture's smoothing), then a pattern search
//! that raises the worst plus the mean scaled Jacobian of the quads around the point, the
//! worst never below where it started (eight directions, the step a fifth of the nearest
//! neighbour's distance, halved on a miss, four steps).

use super::matching::strictly_convex;
use crate::mesh::PlanarMesh;
use crate::mesh2d::measure::min_corner_jacobian;
use glam::DVec2;

/// A gain in the worst scaled Jacobian at most this is no gain (the pattern search).
const MIN_GAIN: f64 = 1e-12;

/// Per vertex: the quads around it and its edge neighbours (compressed rows).
struct Around {
    quad_start: Vec<usize>,
    quads: Vec<u32>,
    nb_start: Vec<usize>,
    nbs: Vec<u32>,
}

impl Around {
    fn new(mesh: &PlanarMesh) -> Around {
        let nv = mesh.vertices.len();
        let mut vq: Vec<(u32, u32)> = Vec::with_capacity(4 * mesh.quads.len());
        let mut vv: Vec<(u32, u32)> = Vec::with_capacity(8 * mesh.quads.len());
        for (q, quad) in mesh.quads.iter().enumerate() {
            for k in 0..4 {
                vq.push((quad[k], q as u32));
                let (a, b) = (quad[k], quad[(k + 1) % 4]);
                vv.push((a, b));
                vv.push((b, a));
            }
        }
        vq.sort_unstable();
        vv.sort_unstable();
        vv.dedup();
        let rows = |pairs: &[(u32, u32)]| -> (Vec<usize>, Vec<u32>) {
            let mut start = vec![0usize; nv + 1];
            for &(a, _) in pairs {
                start[a as usize + 1] += 1;
            }
            for i in 0..nv {
                start[i + 1] += start[i];
            }
            (start, pairs.iter().map(|&(_, b)| b).collect())
        };
        let (quad_start, quads) = rows(&vq);
        let (nb_start, nbs) = rows(&vv);
        Around { quad_start, quads, nb_start, nbs }
    }

    fn quads(&self, v: u32) -> &[u32] {
        &self.quads[self.quad_start[v as usize]..self.quad_start[v as usize + 1]]
    }

    fn neighbours(&self, v: u32) -> &[u32] {
        &self.nbs[self.nb_start[v as usize]..self.nb_start[v as usize + 1]]
    }
}

/// The worst and the mean scaled Jacobian of the quads around `v` with `v` at `p`; `None`
/// when one of them would not be strictly convex.
fn local_quality(mesh: &PlanarMesh, around: &Around, v: u32, p: DVec2) -> Option<(f64, f64)> {
    let mut worst = f64::INFINITY;
    let mut sum = 0.0;
    let quads = around.quads(v);
    for &q in quads {
        let pts = mesh.quads[q as usize].map(|i| if i == v { p } else { mesh.vertices[i as usize] });
        if !strictly_convex(&pts) {
            return None;
        }
        let sj = min_corner_jacobian(&pts);
        worst = worst.min(sj);
        sum += sj;
    }
    Some((worst, sum / quads.len().max(1) as f64))
}

/// Smooths the free points of `mesh` (see the module docs); returns the moves made.
pub fn smooth(mesh: &mut PlanarMesh, fixed: &[bool], passes: usize) -> usize {
    let around = Around::new(mesh);
    let free: Vec<u32> = (0..mesh.vertices.len() as u32).filter(|&v| !fixed[v as usize] && !around.quads(v).is_empty()).collect();
    let mut moves = 0;
    for _ in 0..passes {
        let mut moved = 0;
        for &v in &free {
            let nbs = around.neighbours(v);
            let target = nbs.iter().map(|&i| mesh.vertices[i as usize]).sum::<DVec2>() / nbs.len() as f64;
            let here = mesh.vertices[v as usize];
            if target == here {
                continue;
            }
            let (Some((old, _)), Some((new, _))) = (local_quality(mesh, &around, v, here), local_quality(mesh, &around, v, target)) else { continue };
            if new >= old {
                mesh.vertices[v as usize] = target;
                moved += 1;
            }
        }
        for &v in &free {
            let here = mesh.vertices[v as usize];
            let Some((floor, mean)) = local_quality(mesh, &around, v, here) else { continue };
            // the worst around the point may not drop; the score adds the mean
            let mut best = floor + mean;
            let mut step = 0.2 * around.neighbours(v).iter().map(|&i| mesh.vertices[i as usize].distance(here)).fold(f64::INFINITY, f64::min);
            let mut at = here;
            for _ in 0..4 {
                let mut improved = None;
                for k in 0..8 {
                    let dir = DVec2::from_angle(k as f64 * std::f64::consts::FRAC_PI_4);
                    let p = at + step * dir;
                    if let Some((worst, mean)) = local_quality(mesh, &around, v, p) {
                        if worst >= floor && worst + mean > best + MIN_GAIN {
                            best = worst + mean;
                            improved = Some(p);
                        }
                    }
                }
                match improved {
                    Some(p) => at = p,
                    None => step *= 0.5,
                }
            }
            if at != here {
                mesh.vertices[v as usize] = at;
                moved += 1;
            }
        }
        moves += moved;
        if moved == 0 {
            break;
        }
    }
    moves
}
