//! The inside/outside oracle of the octree mesher: the generalised winding number of a
//! triangle surface (Jacobson et al. 2013), evaluated fast after Barill et al. 2018 ("Fast
//! winding numbers for soups and clouds").
//!
//! Stage: first of the octree mesher. Input: a [`TriSurface`] (any: open, with holes,
//! self-intersecting, inconsistently tagged). Output: [`Winding`], answering `w(q)` for any
//! point `q`, and the crossings of a segment with the surface.
//!
//! # Invariants
//! - `w(q)` is the sum over the triangles of their signed solid angle seen from `q`, over
//!   4π: 1 inside a closed outward-oriented surface, 0 outside, an integer (the nesting
//!   count) off a self-intersecting closed one, and a smooth value in between across the
//!   holes of an open one. Inside means `w > 0.5` ([`INSIDE`]).
//! - Far from a BVH node (distance from its area-weighted centre above [`BETA`] times its
//!   radius) the node's triangles are replaced by one dipole (their summed area-weighted
//!   normal at their centre: Barill's first-order term); near, every triangle's solid angle
//!   is summed exactly (Van Oosterom and Strackee's formula). The result depends only on the
//!   surface and `q` (the BVH is deterministic; the sum order is the traversal order).
//! - The far-field error grows with the square of a node's angular size: with `BETA = 2` it
//!   is a few percent of `w` at worst (seen from a centre of curvature). Barill's higher
//!   orders were tried and, truncated after the gradient term, did worse on curved patches
//!   (the Hessian term is of the same order there). The sign `w > 0.5` is never close to the
//!   threshold far from the surface of a closed one, where the mesher evaluates with
//!   [`FAR_BETA`] (farther than a cell from every triangle's box) or once per block of cells;
//!   near the surface the triangles within reach are summed exactly, so a point whose sign
//!   the far error could flip lies much closer to the surface than the warping distance.
//!   Across the hole of an open surface the level set moves by that error.

use crate::core::bvh::{Bvh, NodeView};
use crate::core::ids::NONE;
use crate::core::intersection::{SegmentCrossing, segment_crosses_triangle};
use crate::core::predicates::orient3d;
use crate::core::Sign;
use crate::mesh::TriSurface;
use glam::DVec3;
use std::borrow::Cow;
use std::f64::consts::PI;

/// The winding number above which a point is inside.
pub const INSIDE: f64 = 0.5;

/// Far-field acceptance: a node is approximated when the query is farther than `BETA` times
/// its radius from its centre (Barill et al. use 2).
pub const BETA: f64 = 2.0;

/// The far-field acceptance for points farther than a cell from every triangle.
pub const FAR_BETA: f64 = 1.2;

/// Per BVH node: the dipole of its triangles.
#[derive(Copy, Clone, Debug, Default)]
struct Dipole {
    /// Area-weighted centre of its triangles.
    centre: DVec3,
    /// Sum of area × unit normal (half the sum of the cross products).
    normal: DVec3,
    /// Largest distance from `centre` to a corner of its triangles.
    radius: f64,
}

/// The generalised winding number of a surface; see the module docs.
#[derive(Debug)]
pub struct Winding<'a> {
    surface: Cow<'a, TriSurface>,
    bvh: Bvh,
    dipoles: Vec<Dipole>,
    /// Per triangle, the triangles that meet it; computed when first asked.
    meets: std::sync::OnceLock<Vec<Vec<u32>>>,
    /// Per triangle, its shell; and the pairs of shells that cross; when first asked.
    crossing: std::sync::OnceLock<ShellCrossings>,
    /// The cap that closes the surface into a cycle and the cycle's oracle (`None`: a cycle
    /// already); made when first asked.
    counter: std::sync::OnceLock<Option<Box<Counter>>>,
}

/// The oracles of the cycle `S ∪ C` and of the cap `C` (`cap.rs`).
#[derive(Debug)]
struct Counter {
    union: Winding<'static>,
    cap: Winding<'static>,
}

/// Per triangle its shell ([`NONE`]: none), and the pairs of shells that cross, sorted.
type ShellCrossings = (Vec<u32>, Vec<(u32, u32)>);

/// How a segment meets the surface: the parameter along it and the winding number's jump.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Crossing {
    /// Where, in `[0, 1]` from the segment's start.
    pub t: f64,
    /// The triangle crossed.
    pub triangle: u32,
    /// +1 when the winding number goes up across it (entering from its front), -1 down.
    pub jump: i32,
    /// Through an edge or vertex of the triangle or along its plane (counts are unreliable).
    pub degenerate: bool,
}

impl<'a> Winding<'a> {
    /// Builds the BVH and the node dipoles of `surface`.
    pub fn new(surface: &'a TriSurface) -> Winding<'a> {
        Self::of(Cow::Borrowed(surface))
    }

    /// [`Winding::new`] owning its surface.
    pub fn owned(surface: TriSurface) -> Winding<'static> {
        Winding::of(Cow::Owned(surface))
    }

    fn of(surface: Cow<'a, TriSurface>) -> Winding<'a> {
        let bvh = surface.triangle_bvh();
        let mut dipoles = vec![Dipole::default(); bvh.num_nodes()];
        // per node: area, Σ a c (centroids relative to `o`), Σ a n, summed from the
        // children: a reverse sweep sees them first
        let o = bvh.bbox().center();
        let mut sums = vec![(0.0f64, DVec3::ZERO, DVec3::ZERO); bvh.num_nodes()];
        for n in (0..bvh.num_nodes() as u32).rev() {
            let (bbox, sum) = match bvh.node(n) {
                NodeView::Leaf { bbox, items } => {
                    let mut acc = (0.0, DVec3::ZERO, DVec3::ZERO);
                    for &t in items {
                        let [p, q, r] = surface.corners(t as usize);
                        let an = 0.5 * (q - p).cross(r - p);
                        let at = an.length();
                        let c = (p + q + r) / 3.0 - o;
                        acc.0 += at;
                        acc.1 += at * c;
                        acc.2 += an;
                    }
                    (bbox, acc)
                }
                NodeView::Internal { bbox, left, right } => {
                    let (l, r) = (sums[left as usize], sums[right as usize]);
                    (bbox, (l.0 + r.0, l.1 + r.1, l.2 + r.2))
                }
            };
            sums[n as usize] = sum;
            let (a, ac, normal) = sum;
            let centre = if a > 0.0 { ac / a + o } else { bbox.center() };
            // the box's farthest corner bounds the farthest triangle corner
            let far = (centre - bbox.min).abs().max((bbox.max - centre).abs());
            let radius = if bbox.is_empty() { 0.0 } else { far.length() };
            dipoles[n as usize] = Dipole { centre, normal, radius };
        }
        Winding { surface, bvh, dipoles, meets: Default::default(), crossing: Default::default(), counter: Default::default() }
    }

    /// Per triangle, the other triangles that meet it (the exact pairwise test of
    /// [`crate::mesh::topology::intersecting_pairs`]: shared vertices and edges allowed),
    /// each list increasing; computed once, when first asked.
    pub fn meets(&self) -> &[Vec<u32>] {
        self.meets.get_or_init(|| {
            let mut m = vec![Vec::new(); self.surface.triangles.len()];
            for [a, b] in crate::mesh::topology::intersecting_pairs(&self.surface) {
                m[a as usize].push(b);
                m[b as usize].push(a);
            }
            m.iter_mut().for_each(|l| l.sort_unstable());
            m
        })
    }

    /// Whether the shells (edge-connected components) of triangles `a` and `b` cross each
    /// other (the same shell: crosses itself) somewhere, by [`Winding::meets`].
    pub fn shells_cross(&self, a: usize, b: usize) -> bool {
        let (shell, pairs) = self.crossing();
        let (x, y) = (shell[a], shell[b]);
        x != NONE && y != NONE && pairs.binary_search(&(x.min(y), x.max(y))).is_ok()
    }

    /// Per triangle its shell, and the pairs of shells that cross (sorted); made once.
    fn crossing(&self) -> &ShellCrossings {
        self.crossing.get_or_init(|| {
            let shell: Vec<u32> = crate::mesh::topology::triangle_shells(&self.surface).into_iter().map(|s| s.unwrap_or(NONE)).collect();
            let mut pairs: Vec<(u32, u32)> = Vec::new();
            for (t, l) in self.meets().iter().enumerate() {
                for &o in l {
                    let (x, y) = (shell[t], shell[o as usize]);
                    if x != NONE && y != NONE {
                        pairs.push((x.min(y), x.max(y)));
                    }
                }
            }
            pairs.sort_unstable();
            pairs.dedup();
            (shell, pairs)
        })
    }

    /// Whether triangle `t`'s shell crosses any shell (itself included).
    pub fn crosses_any(&self, t: usize) -> bool {
        let (shell, pairs) = self.crossing();
        shell[t] != NONE && pairs.iter().any(|&(x, y)| x == shell[t] || y == shell[t])
    }

    /// The surface.
    pub fn surface(&self) -> &TriSurface {
        &self.surface
    }

    /// The oracle of the surface closed into a cycle by its cap (itself where it is one),
    /// and the cap's (`cap.rs`); made once, when first asked.
    pub fn closed(&self) -> (&Winding<'_>, Option<&Winding<'static>>) {
        let counter = self.counter.get_or_init(|| {
            super::cap::capped(&self.surface).map(|c| Box::new(Counter { union: Winding::owned(c.union), cap: Winding::owned(c.cap) }))
        });
        match counter {
            Some(c) => (&c.union, Some(&c.cap)),
            None => (self, None),
        }
    }

    /// The winding number at `q` counted: the crossings of the closed surface
    /// ([`Winding::closed`]) along a ray from `q` in `+x` out of the box, exact integers by
    /// exact predicates, less the cap's solid angle; the sum of [`Winding::at`] where the
    /// ray is degenerate (through an edge or vertex, in a plane, or from a point on the
    /// surface). Same value as `at` up to its far-field error, at the cost of a ray query
    /// (and the cap's few triangles) instead of summing the triangles near `q`; `at` itself
    /// where the cap has more than a quarter of the surface's triangles.
    pub fn counted(&self, q: DVec3) -> f64 {
        let (cycle, cap) = self.closed();
        // a cap of more than a quarter of the triangles (a soup: each triangle its own loop,
        // capped by itself reversed) costs as much as the sum, with a ray query on top
        if cap.is_some_and(|c| 4 * c.surface.triangles.len() > self.surface.triangles.len()) {
            return self.at(q);
        }
        let bbox = cycle.bvh().bbox();
        let out = DVec3::new(bbox.max.x + 1e-3 * bbox.diagonal() + (bbox.max.x - q.x).abs(), q.y, q.z);
        match cycle.along_row(&[out, q]) {
            Some(u) => u[1] as f64 - cap.map_or(0.0, |c| c.at(q)),
            None => self.at(q),
        }
    }

    /// The BVH over the surface's triangles (item `t` is triangle `t`).
    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// The winding number at `q`.
    pub fn at(&self, q: DVec3) -> f64 {
        self.at_with(q, BETA)
    }

    /// The winding number at `q`, nodes farther than `beta` times their radius taken as
    /// dipoles (smaller is faster and coarser: `FAR_BETA` for points far from every
    /// triangle, where only the sign is wanted and it is far from one half).
    pub fn at_with(&self, q: DVec3, beta: f64) -> f64 {
        let Some(root) = self.bvh.root() else { return 0.0 };
        let mut sum = 0.0;
        let mut stack: Vec<u32> = Vec::with_capacity(64);
        stack.push(root);
        while let Some(n) = stack.pop() {
            let d = &self.dipoles[n as usize];
            let r = d.centre - q;
            let dist = r.length();
            if dist > beta * d.radius {
                sum += d.normal.dot(r) / (dist * dist * dist);
                continue;
            }
            match self.bvh.node(n) {
                NodeView::Leaf { items, .. } => {
                    for &t in items {
                        sum += 2.0 * solid_angle_half(self.surface.corners(t as usize), q);
                    }
                }
                NodeView::Internal { left, right, .. } => {
                    stack.push(right);
                    stack.push(left);
                }
            }
        }
        sum / (4.0 * PI)
    }

    /// True when `q` is inside (`w(q) > 0.5`, by [`Winding::counted`]).
    pub fn inside(&self, q: DVec3) -> bool {
        self.counted(q) > INSIDE
    }

    /// The winding numbers of a cycle at `points`, which lie in this order along one segment
    /// whose first point is outside the cycle's box (winding number 0); `None` when the row is
    /// degenerate (see the module docs).
    pub fn along_row(&self, points: &[DVec3]) -> Option<Vec<i32>> {
        let last = points.len().checked_sub(1)?;
        let mut jump = vec![0i32; points.len()];
        for c in self.crossings(points[0], points[last]) {
            if c.degenerate {
                return None;
            }
            let tri = self.surface().corners(c.triangle as usize);
            let side = |k: usize| orient3d(tri[0], tri[1], tri[2], points[k]);
            let start = side(0);
            // the last point on the start's side: the sign along the row changes once
            let (mut lo, mut hi) = (0usize, last);
            while hi - lo > 1 {
                let mid = (lo + hi) / 2;
                let s = side(mid);
                if s == Sign::Zero {
                    return None;
                }
                if s == start {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            jump[hi] += c.jump;
        }
        let mut w = 0;
        Some(jump.into_iter().map(|j| {
            w += j;
            w
        }).collect())
    }

    /// Every triangle the closed segment `p`–`q` meets, in the order of the parameter (ties
    /// by triangle index), decided by exact predicates; the parameter itself is computed in
    /// floating point from the two end points' signed distances to the triangle's plane.
    pub fn crossings(&self, p: DVec3, q: DVec3) -> Vec<Crossing> {
        let mut out = Vec::new();
        self.bvh.for_each_on_segment(p, q, |t| {
            let tri = self.surface.corners(t as usize);
            let kind = segment_crosses_triangle(p, q, tri);
            if kind == SegmentCrossing::Miss {
                return;
            }
            let (sp, sq) = (orient3d(tri[0], tri[1], tri[2], p), orient3d(tri[0], tri[1], tri[2], q));
            let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
            let (dp, dq) = (n.dot(p - tri[0]), n.dot(q - tri[0]));
            let t_at = if dp != dq { (dp / (dp - dq)).clamp(0.0, 1.0) } else { 0.5 };
            // from the front (positive side) to the back the winding number goes up
            let jump = match (sp, sq) {
                (Sign::Positive, Sign::Negative) => 1,
                (Sign::Negative, Sign::Positive) => -1,
                _ => 0,
            };
            out.push(Crossing { t: t_at, triangle: t, jump, degenerate: kind == SegmentCrossing::Degenerate || jump == 0 });
        });
        out.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.triangle.cmp(&b.triangle)));
        out
    }
}

/// Half the signed solid angle of triangle `[a, b, c]` seen from `q` (Van Oosterom and
/// Strackee): positive when `q` is behind the triangle (on the side its normal points away
/// from).
fn solid_angle_half([a, b, c]: [DVec3; 3], q: DVec3) -> f64 {
    let (a, b, c) = (a - q, b - q, c - q);
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let det = a.dot(b.cross(c));
    let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    det.atan2(den)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::FaceId;

    fn cube() -> TriSurface {
        super::super::tests::cube_surface(1)
    }

    #[test]
    fn cube_inside_outside() {
        let s = cube();
        let w = Winding::new(&s);
        assert!((w.at(DVec3::splat(0.5)) - 1.0).abs() < 1e-9);
        assert!((w.at(DVec3::new(0.1, 0.2, 0.9)) - 1.0).abs() < 1e-9);
        assert!(w.at(DVec3::splat(1.5)).abs() < 1e-3);
        assert!(w.at(DVec3::new(-3.0, 0.5, 0.5)).abs() < 1e-3);
        assert!(w.inside(DVec3::splat(0.25)));
        assert!(!w.inside(DVec3::new(0.5, 0.5, 1.01)));
    }

    #[test]
    fn open_cube_is_half_at_the_hole() {
        // the top face removed: inside stays inside, the hole's centre reads one half
        let mut s = cube();
        let keep: Vec<usize> = (0..s.triangles.len())
            .filter(|&t| !s.corners(t).iter().all(|p| (p.z - 1.0).abs() < 1e-12))
            .collect();
        assert_eq!(keep.len(), s.triangles.len() - 2);
        s.triangles = keep.iter().map(|&t| s.triangles[t]).collect();
        s.face_tags = vec![FaceId(1); s.triangles.len()];
        let w = Winding::new(&s);
        assert!(w.inside(DVec3::splat(0.5)));
        assert!(w.inside(DVec3::new(0.5, 0.5, 0.2)));
        assert!((w.at(DVec3::new(0.5, 0.5, 1.0)) - 0.5).abs() < 1e-9);
        assert!(!w.inside(DVec3::new(0.5, 0.5, 1.3)));
        assert!(!w.inside(DVec3::new(2.0, 0.5, 0.5)));
    }

    #[test]
    fn far_field_matches_the_exact_sum() {
        // a finely split cube: the dipoles are used; compare with the exact sum
        let s = super::super::tests::cube_surface(6);
        let w = Winding::new(&s);
        for q in [DVec3::new(0.5, 0.5, 0.5), DVec3::new(0.05, 0.5, 0.5), DVec3::new(1.2, 0.3, 0.7), DVec3::new(3.0, -2.0, 1.0)] {
            let exact: f64 = (0..s.triangles.len()).map(|t| 2.0 * solid_angle_half(s.corners(t), q)).sum::<f64>() / (4.0 * PI);
            assert!((w.at(q) - exact).abs() < 4e-2, "{q}: {} vs {exact}", w.at(q));
        }
    }

    /// Counted through the cap, the winding number of an open, partly flipped surface and of
    /// a soup (where the sum is used) is the exact sum's.
    #[test]
    fn counted_is_the_sum() {
        let mut open = super::super::tests::cube_surface(3);
        open.triangles.truncate(open.triangles.len() - 5);
        open.triangles[4].swap(0, 1);
        open.face_tags.truncate(open.triangles.len());
        let soup = TriSurface {
            vertices: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.2, 0.1, -0.5), DVec3::new(0.3, 0.2, 0.6), DVec3::new(0.9, 0.8, 0.1)],
            triangles: vec![[0, 1, 2], [3, 4, 5]],
            face_tags: vec![FaceId(1); 2],
            ..TriSurface::default()
        };
        for s in [&open, &soup] {
            let w = Winding::new(s);
            for q in [DVec3::splat(0.5), DVec3::new(0.11, 0.23, 0.37), DVec3::new(0.5, 0.5, 1.2), DVec3::new(1.3, -0.2, 0.4)] {
                let (a, b) = (w.counted(q), w.at_with(q, f64::INFINITY));
                assert!((a - b).abs() < 1e-3, "{q}: {a} {b}");
            }
        }
    }

    #[test]
    fn crossings_of_a_segment() {
        let s = cube();
        let w = Winding::new(&s);
        let c = w.crossings(DVec3::new(0.5, 0.37, 0.41), DVec3::new(1.5, 0.37, 0.41));
        assert_eq!(c.len(), 1);
        assert!((c[0].t - 0.5).abs() < 1e-12);
        assert_eq!(c[0].jump, -1);
        assert!(!c[0].degenerate);
    }
}

