//! Lawson flips to the constrained Delaunay triangulation, shared by the methods that make
//! their triangles some other way (element removal's improvement, the quads' source
//! triangles): an interior edge that is not constrained is flipped when the opposite vertex
//! lies strictly inside the circle of the triangle (exact `incircle`) and both new triangles
//! are positive (exact `orient2d`). Each flip increases the sorted angle vector, so the flips
//! end; a count bound guards. Deterministic: edges in triangle order, a stack.

use crate::core::predicates::{incircle, orient2d};
use crate::core::Sign;
use glam::DVec2;
use rustc_hash::{FxHashMap, FxHashSet};

/// Lawson flips until every unconstrained interior edge is locally Delaunay.
pub(crate) fn lawson_flips(points: &[DVec2], triangles: &mut [[u32; 3]], constrained: &FxHashSet<[u32; 2]>) -> usize {
    let mut map: FxHashMap<[u32; 2], u32> = FxHashMap::default();
    map.reserve(3 * triangles.len());
    let mut stack = Vec::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for e in 0..3 {
            let (a, b) = (tri[e], tri[(e + 1) % 3]);
            map.insert([a, b], t as u32);
            if a < b {
                stack.push([a, b]);
            }
        }
    }
    stack.reverse();
    let p = |i: u32| points[i as usize];
    let third = |t: &[u32; 3], a: u32, b: u32| t.iter().copied().find(|&v| v != a && v != b);
    let limit = 50 * triangles.len() + 100;
    let mut flips = 0;
    while let Some([a, b]) = stack.pop() {
        if flips >= limit {
            break;
        }
        if constrained.contains(&[a.min(b), a.max(b)]) {
            continue;
        }
        let (Some(&t), Some(&u)) = (map.get(&[a, b]), map.get(&[b, a])) else { continue };
        let (Some(r), Some(s)) = (third(&triangles[t as usize], a, b), third(&triangles[u as usize], a, b)) else { continue };
        // t = (a, b, r), u = (b, a, s)
        if incircle(p(a), p(b), p(r), p(s)) != Sign::Positive {
            continue;
        }
        if orient2d(p(a), p(s), p(r)) != Sign::Positive || orient2d(p(s), p(b), p(r)) != Sign::Positive {
            continue;
        }
        triangles[t as usize] = [a, s, r];
        triangles[u as usize] = [s, b, r];
        map.remove(&[a, b]);
        map.remove(&[b, a]);
        for (e, tri) in [([a, s], t), ([s, r], t), ([r, a], t), ([s, b], u), ([b, r], u), ([r, s], u)] {
            map.insert(e, tri);
        }
        stack.extend([[a, s], [s, b], [b, r], [r, a]]);
        flips += 1;
    }
    flips
}
