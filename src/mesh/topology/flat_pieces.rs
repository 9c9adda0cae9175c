//! Flat pieces of a tagged triangle surface: maximal sets of edge-connected triangles of one
//! tag that lie in one plane within a tolerance. The mesher merges each piece into one facet
//! that it may retriangulate freely; the input-angle report measures corners on the same
//! pieces.
//!
//! STL's single-precision corners and tessellated planes are rarely exactly coplanar, so the
//! tolerance is TetGen's (`-p`: facets meeting at more than 179.9 degrees are one). Pieces grow
//! from seeds in triangle order, so the result does not depend on hashing or threads.
//! A neighbour across an edge of exactly two triangles joins a piece when:
//! - its tag agrees;
//! - it lies flat with the triangle it is reached from ([`flat_across`]);
//! - every one of its corners lies near the seed's plane, as seen from the seed (so a gently
//!   curved surface never becomes one flat piece).
//!
//! A piece holds at most [`MAX_PIECE`] triangles.

use crate::core::ids::NONE;
use crate::core::FaceId;
use crate::core::bucket_sort::collect_sorted_by_lead;
use glam::DVec3;

/// The flatness tolerance: the sine of 0.1 degrees.
pub const FLAT_SINE: f64 = 1.745e-3;

/// The most triangles in one piece (every Steiner point on a facet costs the mesher a
/// retriangulation of the whole facet).
pub const MAX_PIECE: usize = 1024;

/// The piece of every triangle, numbered in order of the smallest triangle of each piece.
/// Triangles whose corners repeat or lie on a line stay alone.
pub fn flat_pieces(points: &[DVec3], triangles: &[[u32; 3]], tags: &[FaceId]) -> Vec<u32> {
    // the other triangle on each side's edge, when that edge has exactly two
    let neighbours = neighbours_across(points.len(), triangles);
    let neighbour = |x: u32, k: usize| -> Option<u32> {
        let y = neighbours[3 * x as usize + k];
        (y != NONE).then_some(y)
    };
    let tag = |t: u32| tags.get(t as usize).copied().unwrap_or_default();
    let mut piece = vec![NONE; triangles.len()];
    let mut queue: Vec<u32> = Vec::new();
    let mut count = 0u32;
    for seed in 0..triangles.len() as u32 {
        if piece[seed as usize] != NONE {
            continue;
        }
        piece[seed as usize] = count;
        let seed_tri = triangles[seed as usize];
        let mut members = 1usize;
        queue.clear();
        queue.push(seed);
        let mut head = 0;
        while head < queue.len() && members < MAX_PIECE {
            let x = queue[head];
            head += 1;
            let t = triangles[x as usize];
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let Some(y) = neighbour(x, k) else { continue };
                if piece[y as usize] != NONE || tag(y) != tag(x) || members >= MAX_PIECE {
                    continue;
                }
                let ty = triangles[y as usize];
                if flat_across(points, t, ty, (a, b)) && near_plane(points, seed_tri, ty) {
                    piece[y as usize] = count;
                    members += 1;
                    queue.push(y);
                }
            }
        }
        count += 1;
    }
    piece
}

/// Per triangle side `3 t + k` (from corner `k` to corner `k + 1`), the triangle across it
/// where exactly two triangle sides lie on that edge ([`NONE`] elsewhere): the other one, or
/// the triangle itself where both sides are its own. The side records are sorted by edge in
/// vertex buckets ([`collect_sorted_by_lead`]; a full sort where an index is out of range).
fn neighbours_across(n: usize, triangles: &[[u32; 3]]) -> Vec<u32> {
    let records = || {
        triangles.iter().enumerate().flat_map(|(i, t)| {
            (0..3).map(move |k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                ((u64::from(a.min(b)) << 32) | u64::from(a.max(b)), 3 * i as u32 + k as u32)
            })
        })
    };
    let on_edge: Vec<(u64, u32)> = if triangles.iter().flatten().all(|&v| (v as usize) < n) {
        collect_sorted_by_lead(n, records, |r| (r.0 >> 32) as u32)
    } else {
        let mut all: Vec<(u64, u32)> = records().collect();
        all.sort_unstable();
        all
    };
    let mut across = vec![NONE; 3 * triangles.len()];
    for run in on_edge.chunk_by(|x, y| x.0 == y.0) {
        if let [p, q] = run {
            let (tp, tq) = (p.1 / 3, q.1 / 3);
            across[p.1 as usize] = tq;
            across[q.1 as usize] = tp;
        }
    }
    across
}

/// True if triangles `x` and `y`, sharing edge `e`, lie flat together and do not fold: their
/// normals agree within the tolerance, or one's far corner lies off the other's plane by at
/// most the tolerance's sine times its distance from the shared edge (or the other's
/// thickness, its smallest altitude, when that is more). For well-shaped
/// triangles the two agree; a cap or a needle, whose own normal means little, is judged by
/// where its corners lie (TetGen loosens its rule at small angles for the same reason).
fn flat_across(points: &[DVec3], x: [u32; 3], y: [u32; 3], e: (u32, u32)) -> bool {
    let p = |i: u32| points.get(i as usize).copied().unwrap_or(DVec3::NAN);
    let apex = |t: [u32; 3]| t.into_iter().find(|&v| v != e.0 && v != e.1);
    let (Some(c), Some(d)) = (apex(x), apex(y)) else { return false };
    let (a, b) = (p(e.0), p(e.1));
    let normal = |t: [u32; 3]| (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0]));
    let (nx, ny) = (normal(x), normal(y));
    let (lx, ly) = (nx.length(), ny.length());
    if !(lx > 0.0 && ly > 0.0 && nx.dot(ny) > 0.0) {
        return false;
    }
    let by_normal = nx.cross(ny).length() <= FLAT_SINE * lx * ly;
    // a far corner off the other's plane, as an angle seen from the shared edge or, nearer
    // than the other's thickness, from inside the other
    let thickness = |t: [u32; 3], area2: f64| {
        let [u, v, w] = t.map(p);
        area2 / u.distance(v).max(v.distance(w)).max(w.distance(u))
    };
    let off = |n: DVec3, ln: f64, q: DVec3, reach: f64| (n.dot(q - a) / ln).abs() <= FLAT_SINE * distance_to_segment(q, a, b).max(reach);
    by_normal || off(nx, lx, p(d), thickness(x, lx)) || off(ny, ly, p(c), thickness(y, ly))
}

/// True if every corner of triangle `t` lies near the plane of `seed`: within the tolerance's
/// sine times its distance from the seed's centre plus the seed's longest side, and `t` faces
/// the same way.
fn near_plane(points: &[DVec3], seed: [u32; 3], t: [u32; 3]) -> bool {
    let p = |i: u32| points.get(i as usize).copied().unwrap_or(DVec3::NAN);
    let [s0, s1, s2] = seed.map(p);
    let n0 = (s1 - s0).cross(s2 - s0);
    let nt = (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0]));
    let l0 = n0.length();
    if !(l0 > 0.0 && n0.dot(nt) > 0.0) {
        return false;
    }
    let size = s0.distance(s1).max(s1.distance(s2)).max(s2.distance(s0));
    let centre = (s0 + s1 + s2) / 3.0;
    t.iter().all(|&v| (n0.dot(p(v) - s0) / l0).abs() <= FLAT_SINE * (p(v).distance(centre) + size))
}

/// The distance from `q` to the segment from `a` to `b`.
fn distance_to_segment(q: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 { ((q - a).dot(ab) / len2).clamp(0.0, 1.0) } else { 0.0 };
    q.distance(a + ab * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strip of `n` squares along x, each split into two triangles, bent by `step_deg`
    /// degrees about the y axis at every square's edge.
    fn strip(n: usize, step_deg: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut points = vec![DVec3::ZERO, DVec3::Y];
        let (mut at, mut dir) = (DVec3::ZERO, DVec3::X);
        let rot = glam::DQuat::from_rotation_y(-step_deg.to_radians());
        let mut triangles = Vec::new();
        for i in 0..n as u32 {
            at += dir;
            dir = rot * dir;
            points.push(at);
            points.push(at + DVec3::Y);
            let (a, b, c, d) = (2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1);
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
        (points, triangles)
    }

    #[test]
    fn a_plane_with_noise_is_one_piece_and_a_bend_is_two() {
        let (mut points, triangles) = strip(6, 0.0);
        for (i, p) in points.iter_mut().enumerate() {
            p.z += 1e-6 * ((i * 7919) % 13) as f64;
        }
        let tags = vec![FaceId(1); triangles.len()];
        assert_eq!(flat_pieces(&points, &triangles, &tags), vec![0; 12]);
        // a tag of its own splits a piece
        let mut tags2 = tags.clone();
        tags2[10] = FaceId(2);
        tags2[11] = FaceId(2);
        assert_eq!(flat_pieces(&points, &triangles, &tags2), vec![0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1]);
        // a bend of 1 degree at every square: each square is its own piece
        let (points, triangles) = strip(6, 1.0);
        let pieces = flat_pieces(&points, &triangles, &tags);
        assert_eq!(pieces, vec![0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5]);
    }

    #[test]
    fn a_gentle_curve_is_not_one_flat_piece() {
        // 0.05 degrees a square (under the pair tolerance) over 200 squares: 10 degrees in all
        let (points, triangles) = strip(200, 0.05);
        let tags = vec![FaceId(1); triangles.len()];
        let pieces = flat_pieces(&points, &triangles, &tags);
        let count = *pieces.iter().max().unwrap() + 1;
        assert!(count >= 5, "{count} pieces");
        // each piece's normals stay within a few times the tolerance of the seed's (a corner at
        // distance r from the seed lies within the tolerance times r plus the seed's size of
        // its plane, so the surface turns by at most about twice that there)
        for p in 0..count {
            let normals: Vec<DVec3> = (0..triangles.len())
                .filter(|&t| pieces[t] == p)
                .map(|t| {
                    let [a, b, c] = triangles[t].map(|i| points[i as usize]);
                    (b - a).cross(c - a).normalize()
                })
                .collect();
            for n in &normals {
                assert!(n.angle_between(normals[0]) < 4.0 * FLAT_SINE.asin(), "{}", n.angle_between(normals[0]).to_degrees());
            }
        }
    }

    #[test]
    fn a_cap_whose_normal_is_off_joins_by_where_its_corners_lie() {
        // a square in z = 0 and a cap on its edge x = 1: its corner (1, 0.5, 0) lifted by a
        // hair makes its normal tilt by degrees while it stays within the plane
        let points = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.0 + 1e-4, 0.5, 1e-6),
        ];
        let triangles = vec![[0, 1, 2], [0, 2, 3], [1, 4, 2]];
        let nc = (points[4] - points[1]).cross(points[2] - points[1]).normalize();
        assert!(nc.angle_between(DVec3::Z).to_degrees() > 0.5);
        let tags = vec![FaceId(1); 3];
        assert_eq!(flat_pieces(&points, &triangles, &tags), vec![0, 0, 0]);
        // lifted well off the plane, it stays apart
        let mut off = points.clone();
        off[4].z = 1e-2;
        assert_eq!(flat_pieces(&off, &triangles, &tags), vec![0, 0, 1]);
    }
}
