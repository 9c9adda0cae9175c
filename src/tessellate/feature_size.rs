//! The size a face's width asks for: along a B-rep edge, a multiple of the distance across
//! its faces to their nearest other edge (a narrow strip, a chamfer, a hole near a face's
//! side), carried into the faces 1-Lipschitz.
//!
//! Without it, a face narrower than the size gets triangles as long as the size and as wide
//! as the face (angles of 1° on the 0.06 mm strips of the corpus' `part.step` at size 8.5),
//! and every tet on them is a sliver. Edges that share a vertex are not measured against each
//! other: their distance goes to zero at the vertex (a small input angle, which no size
//! removes).

use super::edge_points::EdgePoints;
use crate::cad::brep::Model;
use crate::core::aabb::Aabb;
use crate::core::bvh::{Bvh, NodeView, SmallStack, box_distance_sq};
use crate::core::closest::closest_point_on_segment;
use crate::core::SizeField;
use glam::DVec3;

/// Edges are cut to this many times the width of the face across them: a strip of width `w`
/// then gets triangles of base `1.5 w` and height `w`, angles of 53° and more.
const WIDTH_FACTOR: f64 = 1.5;

/// The size never falls under this share of the size asked for: a face far narrower than
/// the size (a sliver face of the CAD model) keeps thin triangles rather than a hundred
/// thousand small ones. 1/256: at 1/64 a real part's 0.01 mm faces (a lever housing at size
/// 7.9) kept triangles of 3.6° and tets of 4.6°, now 11.9°; on 44 real parts the parts with
/// every dihedral angle of 10° or more went from 31 to 33 for 0.1 % more tets, on the corpus
/// box_sides 16.7° → 18.0°; the sweep's leverrod, a part of tapering slivers, 2.3° → 1.4°.
const FLOOR: f64 = 1.0 / 256.0;

/// A short edge's size never falls under this share of the size asked for (a CAD edge of
/// rounding length, 1e-6 of the part, keeps its needles rather than a cascade of points).
const SHORT_FLOOR: f64 = 1.0 / 1024.0;

/// Bisections of an edge piece at most when looking for its narrowest place.
const MAX_DEPTH: u32 = 14;

/// A size field: the smaller of the one asked for and the width-driven sizes at sample points
/// of the edges, each grown by the distance from its point.
pub(super) struct FeatureSize<'a> {
    inner: &'a dyn SizeField,
    /// Sample points and their sizes (only where the width asks for less than `inner`).
    samples: Vec<(DVec3, f64)>,
    /// The boxes of `samples`: each sample's reach (where its size plus the distance can be
    /// under the size asked for at its point).
    bvh: Bvh,
    /// Per node of `bvh`: the smallest size of a sample under it, and the box of their
    /// points. A query skips a node whose samples cannot lower the size found so far.
    node_min: Vec<f64>,
    node_points: Vec<Aabb>,
    /// The reach of each sample (its box's half side).
    reach: Vec<f64>,
}

impl SizeField for FeatureSize<'_> {
    fn size_at(&self, p: DVec3) -> f64 {
        let h = self.inner.size_at(p);
        if self.samples.is_empty() {
            return h;
        }
        self.min_over_samples(p, h)
    }

    fn size_in(&self, p: DVec3, region: crate::core::RegionId) -> f64 {
        self.size_at(p).min(self.inner.size_in(p, region))
    }
}

impl<'a> FeatureSize<'a> {
    /// The field for `model` whose edges have the chord-only points `edges` (vertex indices
    /// into `vertices`), on top of `inner`.
    /// `walls` are more samples (the solid's thickness, `proximity`), their floors too taken
    /// from `inner`.
    pub fn new(model: &Model, edges: &[EdgePoints], vertices: &[DVec3], inner: &'a dyn SizeField, walls: &[(DVec3, f64)]) -> FeatureSize<'a> {
        // the faces on each edge
        let faces_of = model.edge_faces();
        // every chord segment of every edge
        let mut segs: Vec<(u32, DVec3, DVec3)> = Vec::new();
        for (e, ep) in edges.iter().enumerate() {
            if model.edges[e].degenerate {
                continue;
            }
            for w in ep.ids.windows(2) {
                let (a, b) = (vertices[w[0] as usize], vertices[w[1] as usize]);
                if a != b {
                    segs.push((e as u32, a, b));
                }
            }
        }
        let bvh = Bvh::build(segs.iter().enumerate().map(|(i, &(_, a, b))| (i as u32, Aabb::from_points([a, b].iter()))));
        let ends = |e: usize| [model.edges[e].start, model.edges[e].end];
        // the distance from `x` on edge `e` to the nearest other edge of its faces (sharing
        // no vertex with it) when under `r`, else infinity: a nearest search that opens no
        // box farther than the nearest found (a box query of radius `r` visited every
        // segment in it, thousands on a part of many small arcs at a coarse size)
        let width = |e: usize, x: DVec3, r: f64| -> f64 {
            let mine = ends(e);
            let dist = |i: u32| {
                let (o, a, b) = segs[i as usize];
                let o = o as usize;
                if o == e || ends(o).iter().any(|v| mine.contains(v)) || !faces_of[o].iter().any(|f| faces_of[e].contains(f)) {
                    return f64::INFINITY;
                }
                x.distance(closest_point_on_segment(x, a, b))
            };
            bvh.nearest_within(x, r, dist).map_or(f64::INFINITY, |(_, d)| d)
        };
        let mut samples = walls.to_vec();
        for (e, ep) in edges.iter().enumerate() {
            if model.edges[e].degenerate || faces_of[e].is_empty() {
                continue;
            }
            let pts: Vec<DVec3> = ep.ids.iter().map(|&v| vertices[v as usize]).collect();
            // the size the width asks for at x, if under the size asked for there
            let want = |x: DVec3| -> Option<f64> {
                let h = inner.size_at(x);
                if !(h.is_finite() && h > 0.0) {
                    return None;
                }
                let w = width(e, x, h / WIDTH_FACTOR);
                let s = (WIDTH_FACTOR * w).max(FLOOR * h);
                (s < h).then_some(s)
            };
            for w in pts.windows(2) {
                // pieces no longer than the size at their ends, then halved where the width
                // asks for less than the piece is long
                let (a, b) = (w[0], w[1]);
                let h = inner.size_at(a).min(inner.size_at(b));
                let n = if h > 0.0 && h.is_finite() { ((a.distance(b) / h).ceil() as usize).clamp(1, 4096) } else { 1 };
                for k in 0..n {
                    let (p, q) = (a.lerp(b, k as f64 / n as f64), a.lerp(b, (k + 1) as f64 / n as f64));
                    sample_piece(&want, p, q, 0, &mut samples);
                }
            }
            if let Some(&last) = pts.last() {
                if let Some(s) = want(last) {
                    samples.push((last, s));
                }
            }
            // a short edge asks for its own length at its points (Netgen restricts its local
            // size to every edge's length likewise), and so does a closed one (a circle of
            // 0.02 mm at a cone's truncated tip): the edges and faces beside it grade down to
            // it instead of fanning needles from its ends
            if pts.len() >= 2 {
                let len: f64 = pts.windows(2).map(|w| w[0].distance(w[1])).sum();
                for &x in &pts {
                    let h = inner.size_at(x);
                    if h.is_finite() && h > 0.0 && len < h {
                        samples.push((x, len.max(SHORT_FLOOR * h)));
                    }
                }
            }
        }
        FeatureSize::from_samples(inner, samples)
    }

    /// This field with more samples (`corner_strips`' sizes).
    pub fn with_samples(self, more: Vec<(DVec3, f64)>) -> FeatureSize<'a> {
        if more.is_empty() {
            return self;
        }
        let mut samples = self.samples;
        samples.extend(more);
        FeatureSize::from_samples(self.inner, samples)
    }

    /// The smaller of `inner` and the sizes `samples` ask for at their points, each grown by
    /// the distance from its point.
    fn from_samples(inner: &'a dyn SizeField, mut samples: Vec<(DVec3, f64)>) -> FeatureSize<'a> {
        samples.sort_by(|x, y| x.0.x.total_cmp(&y.0.x).then(x.0.y.total_cmp(&y.0.y)).then(x.0.z.total_cmp(&y.0.z)).then(x.1.total_cmp(&y.1)));
        samples.dedup();
        // a sample matters where its size plus the distance is under the size asked for
        let reach: Vec<f64> = samples.iter().map(|&(x, s)| (inner.size_at(x) - s).max(0.0)).collect();
        let bvh = Bvh::build(samples.iter().zip(&reach).enumerate().map(|(i, (&(x, _), &r))| (i as u32, reach_box(x, r))));
        // children have larger indices than their parent: a reverse sweep sees them first
        let n = bvh.num_nodes();
        let mut node_min = vec![f64::INFINITY; n];
        let mut node_points = vec![Aabb::EMPTY; n];
        for k in (0..n).rev() {
            match bvh.node(k as u32) {
                NodeView::Leaf { items, .. } => {
                    for &i in items {
                        let (x, s) = samples[i as usize];
                        node_min[k] = node_min[k].min(s);
                        node_points[k].grow(x);
                    }
                }
                NodeView::Internal { left, right, .. } => {
                    let (l, r) = (left as usize, right as usize);
                    node_min[k] = node_min[l].min(node_min[r]);
                    node_points[k] = node_points[l].union(&node_points[r]);
                }
            }
        }
        FeatureSize { inner, samples, bvh, node_min, node_points, reach }
    }

    /// The smallest of `h` and `s + |x - p|` over the samples `(x, s)` whose reach holds `p`
    /// (the sizes they ask for there): branch and bound over the tree, skipping the nodes
    /// whose smallest size plus the distance to their points' box is above the least found
    /// so far, which cannot lower it. The minimum does not depend on the order.
    fn min_over_samples(&self, p: DVec3, mut h: f64) -> f64 {
        let at = Aabb { min: p, max: p };
        // a node's bound: its smallest size plus the distance to its points' box
        let bound = |k: u32| self.node_min[k as usize] + box_distance_sq(&self.node_points[k as usize], p).sqrt();
        // a little slack so that rounding never skips a node that holds the minimum
        let above = |lower: f64, h: f64| lower > h + 1e-9 * h.abs();
        let mut stack = SmallStack::<(u32, f64)>::new();
        if let Some(root) = self.bvh.root() {
            stack.push((root, bound(root)));
        }
        while let Some((k, lower)) = stack.pop() {
            if above(lower, h) {
                continue;
            }
            match self.bvh.node(k) {
                NodeView::Leaf { bbox, items } => {
                    if !bbox.overlaps(&at) {
                        continue;
                    }
                    for &i in items {
                        let (x, s) = self.samples[i as usize];
                        if reach_box(x, self.reach[i as usize]).overlaps(&at) {
                            h = h.min(s + x.distance(p));
                        }
                    }
                }
                NodeView::Internal { bbox, left, right } => {
                    if !bbox.overlaps(&at) {
                        continue;
                    }
                    // the child nearer by its bound is taken first: the least falls fast
                    let (bl, br) = (bound(left), bound(right));
                    if bl <= br {
                        stack.push((right, br));
                        stack.push((left, bl));
                    } else {
                        stack.push((left, bl));
                        stack.push((right, br));
                    }
                }
            }
        }
        h
    }

    /// Sample points in all.
    #[cfg(test)]
    fn samples(&self) -> usize {
        self.samples.len()
    }
}

/// The box of a sample at `x` with reach `r`.
fn reach_box(x: DVec3, r: f64) -> Aabb {
    Aabb { min: x - DVec3::splat(r), max: x + DVec3::splat(r) }
}

/// Samples the piece `p`-`q` of an edge: its start, and its halves again where the width at
/// either end asks for a size under the piece's length.
fn sample_piece(want: &dyn Fn(DVec3) -> Option<f64>, p: DVec3, q: DVec3, depth: u32, out: &mut Vec<(DVec3, f64)>) {
    let (sp, sq) = (want(p), want(q));
    let len = p.distance(q);
    let small = sp.into_iter().chain(sq).fold(f64::INFINITY, f64::min);
    if depth < MAX_DEPTH && small < len {
        let m = p.lerp(q, 0.5);
        sample_piece(want, p, m, depth + 1, out);
        sample_piece(want, m, q, depth + 1, out);
    } else if let Some(s) = sp {
        out.push((p, s));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::size_field::UniformSize;

    #[test]
    fn a_narrow_strip_asks_for_its_width_and_a_wide_face_for_nothing() {
        // a bracket 0.4 thick: its side faces are strips 0.4 wide
        let thin = crate::cad::parts::Bracket { thickness: 0.4, ..Default::default() }.build().unwrap();
        let t = super::super::tessellate(&thin, &super::super::TessellateOptions::default());
        let inner = UniformSize(5.0);
        let f = FeatureSize::new(&thin, &t.edges, &t.surface.vertices, &inner, &[]);
        assert!(f.samples() > 0);
        // on a long edge of a side, 1.5 times the thickness
        let h = f.size_at(DVec3::new(40.0, 0.0, 0.0));
        assert!((h - 0.6).abs() < 0.05, "{h}");
        // on the top face, 5 from the sides: the size asked for (0.6 + 5 is more)
        assert_eq!(f.size_at(DVec3::new(5.0, 5.0, 0.4)), 5.0);
        // the default bracket (8 thick, holes 10.5 from the sides) asks for nothing more
        let plain = crate::cad::parts::Bracket::default().build().unwrap();
        let t = super::super::tessellate(&plain, &super::super::TessellateOptions::default());
        let f = FeatureSize::new(&plain, &t.edges, &t.surface.vertices, &inner, &[]);
        assert_eq!(f.samples(), 0);
    }

    #[test]
    fn a_short_edge_asks_for_its_length_and_the_size_grows_from_it() {
        // a slab 0.3 thick at size 5: its vertical edges are 0.3 long, its sides strips 0.3 wide
        let slab = crate::cad::parts::Block::new(40.0, 10.0, 0.3).build().unwrap();
        let t = super::super::tessellate(&slab, &super::super::TessellateOptions::default());
        let inner = UniformSize(5.0);
        let f = FeatureSize::new(&slab, &t.edges, &t.surface.vertices, &inner, &[]);
        // at a corner: the edge's length, under the strips' 1.5 times their width
        let h = f.size_at(DVec3::new(0.0, 0.0, 0.0));
        assert!((h - 0.3).abs() < 1e-9, "{h}");
        // 2 along the long edge from the corner: the strip's width (1.5 x 0.3, plus the way to
        // its nearest sample) asks for less than the corner's 0.3 grown by 2
        let h = f.size_at(DVec3::new(2.0, 0.0, 0.0));
        assert!((0.45..0.6).contains(&h), "{h}");
        // edges as long as the size ask for nothing
        let block = crate::cad::parts::Block::new(40.0, 10.0, 10.0).build().unwrap();
        let t = super::super::tessellate(&block, &super::super::TessellateOptions::default());
        let f = FeatureSize::new(&block, &t.edges, &t.surface.vertices, &inner, &[]);
        assert_eq!(f.size_at(DVec3::ZERO), 5.0);
    }

    /// A size field that grows along x: the samples' reaches differ from point to point.
    struct Graded;
    impl SizeField for Graded {
        fn size_at(&self, p: DVec3) -> f64 {
            1.0 + 0.2 * p.x.abs()
        }
    }

    #[test]
    fn the_pruned_query_finds_what_a_scan_of_every_sample_finds() {
        // samples in clusters of equal sizes and scattered ones, under a graded field: the
        // branch and bound must give, bit for bit, the least over every sample whose reach
        // holds the point
        let mut g = crate::core::spatial_order::XorShift::new(7);
        let mut rnd = move || (g.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        let mut samples = Vec::new();
        for c in 0..40 {
            let centre = DVec3::new(10.0 * rnd() - 5.0, 10.0 * rnd() - 5.0, 2.0 * rnd());
            let s = if c % 3 == 0 { 0.05 } else { 0.01 + 0.5 * rnd() };
            for _ in 0..50 {
                samples.push((centre + DVec3::new(rnd(), rnd(), rnd()) * 0.3, s));
            }
        }
        let f = FeatureSize::from_samples(&Graded, samples.clone());
        for _ in 0..2000 {
            let p = DVec3::new(14.0 * rnd() - 7.0, 14.0 * rnd() - 7.0, 4.0 * rnd() - 1.0);
            let mut want = Graded.size_at(p);
            for &(x, s) in &f.samples {
                let r = (Graded.size_at(x) - s).max(0.0);
                if reach_box(x, r).overlaps(&Aabb { min: p, max: p }) {
                    want = want.min(s + x.distance(p));
                }
            }
            assert_eq!(f.size_at(p).to_bits(), want.to_bits(), "at {p}");
        }
        // and near the samples, where the least comes from them
        for &(x, _) in samples.iter().step_by(7) {
            let p = x + DVec3::new(0.01, -0.02, 0.005);
            let mut want = Graded.size_at(p);
            for &(y, s) in &f.samples {
                if reach_box(y, (Graded.size_at(y) - s).max(0.0)).overlaps(&Aabb { min: p, max: p }) {
                    want = want.min(s + y.distance(p));
                }
            }
            assert!(want < Graded.size_at(p));
            assert_eq!(f.size_at(p).to_bits(), want.to_bits(), "at {p}");
        }
    }
}
