//! Boundary segments of a face that cross in its parameter domain, found with exact
//! predicates.
//!
//! Two trim edges that do not meet in 3D can still have chord polylines that cross in
//! `(u, v)`: the chords of an edge cut inside its curve by up to the chord tolerance, so two
//! edges closer than that (a thin sliver face, a fillet running out) cross, and the
//! constrained triangulation cannot take both. The tessellator then splits the edge
//! segments named here (through the shared edge points, so the neighbouring faces get the
//! same points) and meshes again ([`super::tessellate`]).

use crate::core::predicates::{Sign, orient2d};
use glam::DVec2;

/// One boundary segment: its ends in the triangulation's coordinates and global vertex ids.
struct Seg {
    a: DVec2,
    b: DVec2,
    ids: [u32; 2],
}

/// True when `p` lies on the closed segment `a b`, given that `a, b, p` are collinear.
fn on_segment(a: DVec2, b: DVec2, p: DVec2) -> bool {
    p.x >= a.x.min(b.x) && p.x <= a.x.max(b.x) && p.y >= a.y.min(b.y) && p.y <= a.y.max(b.y)
}

/// True when the segments cross or touch (an end of one on the other, collinear overlap).
/// Segments sharing a vertex id only count when they overlap beyond that vertex.
fn meet(s: &Seg, t: &Seg) -> bool {
    let shared = s.ids.iter().any(|i| t.ids.contains(i));
    let d1 = orient2d(t.a, t.b, s.a);
    let d2 = orient2d(t.a, t.b, s.b);
    let d3 = orient2d(s.a, s.b, t.a);
    let d4 = orient2d(s.a, s.b, t.b);
    if shared {
        // adjacent segments: only a fold back along the same line (collinear, overlapping)
        let collinear = d1.is_zero() && d2.is_zero();
        let other_on = |seg: &Seg, p: DVec2, id: u32| !seg.ids.contains(&id) && on_segment(seg.a, seg.b, p);
        return collinear && (other_on(t, s.a, s.ids[0]) || other_on(t, s.b, s.ids[1]) || other_on(s, t.a, t.ids[0]) || other_on(s, t.b, t.ids[1]));
    }
    let opposite = |x: Sign, y: Sign| x.times(y).is_negative();
    if opposite(d1, d2) && opposite(d3, d4) {
        return true;
    }
    (d1.is_zero() && on_segment(t.a, t.b, s.a)) || (d2.is_zero() && on_segment(t.a, t.b, s.b)) || (d3.is_zero() && on_segment(s.a, s.b, t.a)) || (d4.is_zero() && on_segment(s.a, s.b, t.b))
}

/// The segments of the closed polygons that cross or touch another one, each once, as their
/// global vertex ids (`points[k]` are loop `k`'s points in the coordinates the triangulation
/// sees, `ids[k]` their global vertex ids). Segments whose ends are one vertex (along a pole)
/// are left out. A sweep over the segments sorted by their least `x`: about `n log n` plus
/// the pairs whose `x` ranges overlap.
pub(super) fn crossing_segments(points: &[Vec<DVec2>], ids: &[Vec<u32>]) -> Vec<[u32; 2]> {
    let mut segs: Vec<Seg> = Vec::new();
    for (l, li) in points.iter().zip(ids) {
        let n = l.len().min(li.len());
        for i in 0..n {
            let j = (i + 1) % n;
            if li[i] != li[j] && l[i] != l[j] {
                segs.push(Seg { a: l[i], b: l[j], ids: [li[i], li[j]] });
            }
        }
    }
    segs.sort_by(|s, t| s.a.x.min(s.b.x).total_cmp(&t.a.x.min(t.b.x)));
    let mut hit = vec![false; segs.len()];
    for i in 0..segs.len() {
        let (s, hi) = (&segs[i], segs[i].a.x.max(segs[i].b.x));
        let (ylo, yhi) = (s.a.y.min(s.b.y), s.a.y.max(s.b.y));
        for j in i + 1..segs.len() {
            let t = &segs[j];
            if t.a.x.min(t.b.x) > hi {
                break;
            }
            if t.a.y.max(t.b.y) < ylo || t.a.y.min(t.b.y) > yhi {
                continue;
            }
            if meet(s, t) {
                hit[i] = true;
                hit[j] = true;
            }
        }
    }
    segs.iter().zip(hit).filter(|(_, h)| *h).map(|(s, _)| s.ids).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_crossing_and_touching_segments_only() {
        // a bow tie: segments 0-1 and 2-3 cross
        let p = vec![vec![DVec2::new(0.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(1.0, 0.0), DVec2::new(0.0, 1.0)]];
        let mut c = crossing_segments(&p, &[vec![10, 11, 12, 13]]);
        c.sort();
        assert_eq!(c, vec![[10, 11], [12, 13]]);
        // a square: nothing
        let q = vec![vec![DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)]];
        assert!(crossing_segments(&q, &[vec![0, 1, 2, 3]]).is_empty());
        // a hole touching the outer loop at a point of it (a vertex on a segment)
        let h = vec![q[0].clone(), vec![DVec2::new(0.5, 0.0), DVec2::new(0.6, 0.5), DVec2::new(0.4, 0.5)]];
        let c = crossing_segments(&h, &[vec![0, 1, 2, 3], vec![4, 5, 6]]);
        assert!(c.contains(&[0, 1]) && c.contains(&[6, 4]) && c.contains(&[4, 5]), "{c:?}");
    }
}
