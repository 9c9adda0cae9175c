//! Stage 3 of element removal: improvement of the cut triangles.
//!
//! - Inputs: vertices (the first `fixed` are the domain's points and never move), counter-
//!   clockwise triangles covering the domain, the domain's segments (never flipped).
//! - Output: the same vertices and triangle count, improved in place; counts of flips and
//!   moves.
//! - Lawson flips to the constrained Delaunay triangulation: an interior edge that is not a
//!   domain segment is flipped when the opposite vertex lies strictly inside the circle of
//!   the triangle (exact `incircle`) and both new triangles are positive (exact `orient2d`).
//!   Each flip increases the sorted angle vector, so the flips end; a count bound guards.
//! - Laplacian smoothing: each added vertex, in index order, moves to the mean of its
//!   neighbours when every triangle around it stays positive (exact) and the smallest corner
//!   sine around it (Verdict's Jacobian, unscaled) does not decrease; after each pass, flips
//!   again, until a pass moves nothing.

use crate::core::predicates::orient2d;
use crate::core::Sign;
use crate::mesh2d::flips::lawson_flips;
use crate::mesh2d::stars::Stars;
use crate::mesh2d::measure::min_corner_jacobian;
use glam::DVec2;
use rustc_hash::FxHashSet;

/// Counts of the improvement.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Improved {
    pub flips: usize,
    pub moves: usize,
}

/// Flips, then `passes` times smoothing and flips (see the module docs).
pub(crate) fn improve(points: &mut [DVec2], triangles: &mut [[u32; 3]], fixed: usize, segments: &[[u32; 2]], passes: usize) -> Improved {
    let constrained: FxHashSet<[u32; 2]> = segments.iter().map(|&[a, b]| [a.min(b), a.max(b)]).collect();
    let mut out = Improved { flips: lawson_flips(points, triangles, &constrained), moves: 0 };
    for _ in 0..passes {
        let moved = smooth(points, triangles, fixed);
        out.moves += moved;
        out.flips += lawson_flips(points, triangles, &constrained);
        if moved == 0 {
            break;
        }
    }
    out
}

/// One Gauss-Seidel pass of guarded Laplacian smoothing; returns the moves made.
fn smooth(points: &mut [DVec2], triangles: &[[u32; 3]], fixed: usize) -> usize {
    let n = points.len();
    let stars = Stars::new(n, triangles);
    let mut moves = 0;
    for v in fixed..n {
        let around = stars.of(v);
        if around.is_empty() {
            continue;
        }
        let mut sum = DVec2::ZERO;
        for &k in around {
            for &w in &triangles[k as usize] {
                if w as usize != v {
                    sum += points[w as usize];
                }
            }
        }
        let target = sum / (2 * around.len()) as f64;
        let old = points[v];
        let quality = |points: &[DVec2]| {
            around.iter().map(|&k| min_corner_jacobian(&triangles[k as usize].map(|i| points[i as usize]))).fold(f64::INFINITY, f64::min)
        };
        let before = quality(points);
        points[v] = target;
        let positive = around.iter().all(|&k| {
            let t = triangles[k as usize];
            orient2d(points[t[0] as usize], points[t[1] as usize], points[t[2] as usize]) == Sign::Positive
        });
        if positive && quality(points) >= before {
            moves += usize::from(target != old);
        } else {
            points[v] = old;
        }
    }
    moves
}
