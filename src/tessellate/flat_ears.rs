//! Ears of a face's boundary that are flat in `(u, v)`: three consecutive points of a loop
//! that lie on one line of the parameter domain up to rounding (an edge along an
//! isoparametric line, a circle at a cylinder's end, cut into two pieces), and the triangle
//! between them that the triangulation keeps inside the face when the middle point dips by
//! 1e-16 past the chord. Its area in `(u, v)` is nothing; in 3D it is the edge's whole bulge,
//! lying across the face on its neighbour's side (on a 0.3 mm fillet at a profile's end, in
//! the end face's plane, the end face's own triangle there twice). Each such ear's chord is
//! flipped with the triangle across it, so the middle point joins the face's inside.

use super::improve::Point;
use crate::core::predicates::{Sign, orient2d};
use rustc_hash::{FxHashMap, FxHashSet};

/// An ear is flat when its middle point lies within this share of its chord's length from
/// the chord, in the scaled `(u, v)`.
const FLAT: f64 = 1e-9;

/// Flips the chord of every flat ear of `tris` (counter-clockwise in `pts`' scaled
/// coordinates; `segments` the face's boundary) with the triangle across it, where both new
/// triangles are counter-clockwise. Returns how many were flipped.
pub(super) fn flip_flat_ears(pts: &[Point], tris: &mut [[u32; 3]], segments: &[[u32; 2]]) -> usize {
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let boundary: FxHashSet<(u32, u32)> = segments.iter().map(|&[a, b]| key(a, b)).collect();
    let s = |i: u32| pts[i as usize].s;
    // an ear at its middle corner: two boundary sides, the chord inside and flat
    let flat_ear = |t: [u32; 3], r: usize| {
        let (a, b, c) = (t[r], t[(r + 1) % 3], t[(r + 2) % 3]);
        let chord = s(c) - s(a);
        boundary.contains(&key(a, b)) && boundary.contains(&key(b, c)) && !boundary.contains(&key(c, a)) && (s(b) - s(a)).perp_dot(chord).abs() <= FLAT * chord.length_squared()
    };
    // nearly every face has none: the triangles by edge only where one is
    if !tris.iter().any(|&t| (0..3).any(|r| flat_ear(t, r))) {
        return 0;
    }
    let mut by_edge: FxHashMap<(u32, u32), usize> = FxHashMap::default();
    for (k, t) in tris.iter().enumerate() {
        for i in 0..3 {
            by_edge.insert((t[i], t[(i + 1) % 3]), k);
        }
    }
    let mut flipped = 0;
    for k in 0..tris.len() {
        let t = tris[k];
        for r in (0..3).filter(|&r| flat_ear(t, r)) {
            let (a, b, c) = (t[r], t[(r + 1) % 3], t[(r + 2) % 3]);
            // the triangle across the chord runs along it from a to c
            let Some(&u) = by_edge.get(&(a, c)) else { continue };
            let Some(x) = tris[u].iter().copied().find(|&v| v != a && v != c) else { continue };
            let (n1, n2) = ([a, b, x], [b, c, x]);
            if [n1, n2].iter().any(|n| orient2d(s(n[0]), s(n[1]), s(n[2])) != Sign::Positive) {
                continue;
            }
            tris[k] = n1;
            tris[u] = n2;
            by_edge.remove(&(c, a));
            by_edge.remove(&(a, c));
            for (e, owner) in [((b, x), k), ((x, a), k), ((a, b), k), ((b, c), u), ((c, x), u), ((x, b), u)] {
                by_edge.insert(e, owner);
            }
            flipped += 1;
            break;
        }
    }
    flipped
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    fn points(s: &[DVec2]) -> Vec<Point> {
        s.iter().map(|&s| Point { s, uv: s, p3: DVec3::new(s.x, s.y, 0.0), id: None }).collect()
    }

    #[test]
    fn an_ear_flat_in_the_parameters_is_flipped_and_a_real_one_is_kept() {
        // a, b, c along the boundary, b a rounding's width below the chord a-c; x inside
        let flat = points(&[DVec2::ZERO, DVec2::new(1.0, -1e-12), DVec2::new(2.0, 0.0), DVec2::new(1.0, 1.0)]);
        let segments = [[0, 1], [1, 2], [2, 3], [3, 0]];
        let mut tris = vec![[0, 1, 2], [0, 2, 3]];
        assert_eq!(flip_flat_ears(&flat, &mut tris, &segments), 1);
        assert_eq!(tris, vec![[0, 1, 3], [1, 2, 3]]);
        // the same with b well below the chord: the ear has an inside of its own
        let real = points(&[DVec2::ZERO, DVec2::new(1.0, -0.5), DVec2::new(2.0, 0.0), DVec2::new(1.0, 1.0)]);
        let mut tris = vec![[0, 1, 2], [0, 2, 3]];
        assert_eq!(flip_flat_ears(&real, &mut tris, &segments), 0);
        assert_eq!(tris, vec![[0, 1, 2], [0, 2, 3]]);
    }
}
