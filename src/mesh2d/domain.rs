//! The input of the quadtree mesher: a planar domain with holes.
//!
//! - Stage: input, before the tree is built.
//! - Inputs: points in the plane and directed boundary segments between them, each with a
//!   tag (for a CAD face: the B-rep edge it comes from); built from loops by
//!   [`Domain::from_loops`] or given as segments directly ([`Domain::new`]).
//! - Output: a checked [`Domain`].
//! - Invariants (checked by [`Domain::validate`], exactly where a sign decides): finite
//!   points, no two points equal, no zero-length segment, every point has as many segments
//!   in as out, no two segments cross or touch except at a shared end point, no point lies on
//!   a segment it does not end, positive area; the domain lies on the left of every segment
//!   (outer loops counter-clockwise, holes clockwise).

use crate::core::predicates::orient2d;
use crate::core::Sign;
use glam::DVec2;

/// Why a domain was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum DomainError {
    /// Fewer than three segments.
    #[error("the domain has {0} boundary segments (at least 3 are needed)")]
    TooSmall(usize),
    /// Not one tag per segment.
    #[error("{tags} tags for {segments} segments")]
    TagCount {
        /// Tags given.
        tags: usize,
        /// Segments given.
        segments: usize,
    },
    /// A point is not finite.
    #[error("point {index} ({x}, {y}) is not finite")]
    NonFinite {
        /// The point.
        index: usize,
        /// Its coordinates.
        x: f64,
        /// Its coordinates.
        y: f64,
    },
    /// A segment refers to a point that does not exist, or joins a point to itself.
    #[error("segment {segment} ({a} -> {b}) is degenerate or refers to a missing point")]
    BadSegment {
        /// The segment.
        segment: usize,
        /// Its start.
        a: u32,
        /// Its end.
        b: u32,
    },
    /// Two points coincide.
    #[error("points {0} and {1} coincide")]
    DuplicatePoint(u32, u32),
    /// The boundary is not made of closed loops.
    #[error("point {point} has {ins} boundary segments in and {outs} out: the boundary is not closed")]
    NotClosed {
        /// The point.
        point: u32,
        /// Segments ending there.
        ins: usize,
        /// Segments starting there.
        outs: usize,
    },
    /// Two segments cross or overlap, or a point lies on a segment.
    #[error("boundary segments {0} and {1} intersect")]
    Crossing(usize, usize),
    /// The loops enclose no area or are oriented the wrong way.
    #[error("the domain's area is {0} (outer loops must turn counter-clockwise, holes clockwise)")]
    NotPositive(f64),
}

/// A planar polygonal domain with holes: the region on the left of its directed segments.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Domain {
    /// Boundary points.
    pub points: Vec<DVec2>,
    /// Directed segments `[from, to]`, the domain on the left.
    pub segments: Vec<[u32; 2]>,
    /// One tag per segment (for a CAD face: the B-rep edge index plus one; 0 untagged).
    pub tags: Vec<u32>,
}

impl Domain {
    /// A checked domain from points, directed segments and their tags.
    ///
    /// # Errors
    /// The first violated invariant (see the module docs).
    pub fn new(points: Vec<DVec2>, segments: Vec<[u32; 2]>, tags: Vec<u32>) -> Result<Domain, DomainError> {
        let d = Domain { points, segments, tags };
        d.validate()?;
        Ok(d)
    }

    /// A checked domain from closed loops of points (the last point joins the first), each
    /// with one tag per segment (`None`: the loop's index plus one). Loops are re-oriented:
    /// the one of largest absolute area becomes counter-clockwise, every other loop is made
    /// clockwise when it lies inside an odd number of loops and counter-clockwise otherwise
    /// (islands in holes), so that the domain is on the left of every segment.
    ///
    /// # Errors
    /// As [`Domain::new`].
    pub fn from_loops(loops: &[Vec<DVec2>], tags: Option<&[Vec<u32>]>) -> Result<Domain, DomainError> {
        let mut points = Vec::new();
        let mut segments = Vec::new();
        let mut seg_tags = Vec::new();
        for (l, pts) in loops.iter().enumerate() {
            let area = loop_area(pts);
            let probe = pts.first().copied().unwrap_or(DVec2::ZERO);
            let depth = loops.iter().enumerate().filter(|&(k, other)| k != l && loop_area(other).abs() > area.abs() && inside_loop(other, probe)).count();
            let ccw = depth % 2 == 0;
            let base = points.len() as u32;
            let n = pts.len() as u32;
            points.extend_from_slice(pts);
            let tag_of = |k: usize| tags.and_then(|t| t.get(l)).and_then(|t| t.get(k)).copied().unwrap_or(l as u32 + 1);
            for k in 0..n {
                let (a, b) = (base + k, base + (k + 1) % n);
                if (area > 0.0) == ccw {
                    segments.push([a, b]);
                    seg_tags.push(tag_of(k as usize));
                } else {
                    segments.push([b, a]);
                    seg_tags.push(tag_of(k as usize));
                }
            }
        }
        Domain::new(points, segments, seg_tags)
    }

    /// Checks the invariants (see the module docs).
    ///
    /// # Errors
    /// The first violation found.
    pub fn validate(&self) -> Result<(), DomainError> {
        if self.segments.len() < 3 {
            return Err(DomainError::TooSmall(self.segments.len()));
        }
        if self.tags.len() != self.segments.len() {
            return Err(DomainError::TagCount { tags: self.tags.len(), segments: self.segments.len() });
        }
        if let Some(i) = self.points.iter().position(|p| !p.is_finite()) {
            return Err(DomainError::NonFinite { index: i, x: self.points[i].x, y: self.points[i].y });
        }
        let n = self.points.len() as u32;
        let mut ins = vec![0usize; n as usize];
        let mut outs = vec![0usize; n as usize];
        for (s, &[a, b]) in self.segments.iter().enumerate() {
            if a >= n || b >= n || a == b {
                return Err(DomainError::BadSegment { segment: s, a, b });
            }
            outs[a as usize] += 1;
            ins[b as usize] += 1;
        }
        let mut order: Vec<u32> = (0..n).collect();
        order.sort_by(|&i, &j| self.points[i as usize].to_array().partial_cmp(&self.points[j as usize].to_array()).unwrap_or(std::cmp::Ordering::Equal).then(i.cmp(&j)));
        for w in order.windows(2) {
            if self.points[w[0] as usize] == self.points[w[1] as usize] {
                return Err(DomainError::DuplicatePoint(w[0].min(w[1]), w[0].max(w[1])));
            }
        }
        for p in 0..n as usize {
            if ins[p] != outs[p] {
                return Err(DomainError::NotClosed { point: p as u32, ins: ins[p], outs: outs[p] });
            }
        }
        if let Some((s, t)) = self.first_crossing() {
            return Err(DomainError::Crossing(s, t));
        }
        let area = self.area();
        if !(area > 0.0) {
            return Err(DomainError::NotPositive(area));
        }
        Ok(())
    }

    /// The segment's end points.
    #[inline]
    pub fn ends(&self, s: usize) -> (DVec2, DVec2) {
        let [a, b] = self.segments[s];
        (self.points[a as usize], self.points[b as usize])
    }

    /// The enclosed area (sum over segments; positive for a valid domain).
    pub fn area(&self) -> f64 {
        (0..self.segments.len()).map(|s| {
            let (a, b) = self.ends(s);
            a.perp_dot(b)
        }).sum::<f64>() * 0.5
    }

    /// The bounding box `(min, max)` of the points.
    pub fn bounds(&self) -> (DVec2, DVec2) {
        let mut lo = DVec2::splat(f64::INFINITY);
        let mut hi = DVec2::splat(f64::NEG_INFINITY);
        for p in &self.points {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        (lo, hi)
    }

    /// Whether `p` is inside the domain: the parity of the boundary segments crossed by the
    /// ray from `p` towards `+x`, each crossing decided by [`orient2d`] (exact; a point on the
    /// boundary counts as inside or outside consistently with the half-open rule).
    pub fn contains(&self, p: DVec2) -> bool {
        let mut inside = false;
        for s in 0..self.segments.len() {
            let (a, b) = self.ends(s);
            if (a.y > p.y) != (b.y > p.y) {
                // upward segment: p left of a->b means the crossing is right of p
                let o = if b.y > a.y { orient2d(a, b, p) } else { orient2d(b, a, p) };
                if o == Sign::Positive {
                    inside = !inside;
                }
            }
        }
        inside
    }

    /// The smallest angle between the two boundary segments at each point, in degrees (the
    /// interior angle, measured inside the domain), over all points: what no mesh keeping the
    /// boundary can beat.
    pub fn smallest_angle_deg(&self) -> f64 {
        let mut out: Vec<Vec<usize>> = vec![Vec::new(); self.points.len()];
        let mut inn: Vec<Vec<usize>> = vec![Vec::new(); self.points.len()];
        for (s, &[a, b]) in self.segments.iter().enumerate() {
            out[a as usize].push(s);
            inn[b as usize].push(s);
        }
        let mut best = 360.0f64;
        for p in 0..self.points.len() {
            for &si in &inn[p] {
                for &so in &out[p] {
                    let (a, v) = self.ends(si);
                    let (_, c) = self.ends(so);
                    // interior angle from the outgoing direction counter-clockwise to the incoming reversed
                    let d1 = c - v;
                    let d2 = a - v;
                    let mut ang = d1.perp_dot(d2).atan2(d1.dot(d2)).to_degrees();
                    if ang < 0.0 {
                        ang += 360.0;
                    }
                    best = best.min(ang);
                }
            }
        }
        best
    }

    /// The first pair of segments (by index) that intersect other than at a shared end point,
    /// decided exactly; a sweep over x keeps it near linear for boundaries that are not
    /// pathological.
    fn first_crossing(&self) -> Option<(usize, usize)> {
        let m = self.segments.len();
        let mut order: Vec<usize> = (0..m).collect();
        let lo_x = |s: usize| {
            let (a, b) = self.ends(s);
            a.x.min(b.x)
        };
        order.sort_by(|&i, &j| lo_x(i).total_cmp(&lo_x(j)).then(i.cmp(&j)));
        let mut found: Option<(usize, usize)> = None;
        for (k, &i) in order.iter().enumerate() {
            let (a, b) = self.ends(i);
            let hi_x = a.x.max(b.x);
            for &j in &order[k + 1..] {
                if lo_x(j) > hi_x {
                    break;
                }
                if self.segments_meet(i, j) {
                    let pair = (i.min(j), i.max(j));
                    if found.is_none_or(|f| pair < f) {
                        found = Some(pair);
                    }
                }
            }
        }
        found
    }

    /// Whether segments `i` and `j` intersect anywhere but at an end point they share.
    fn segments_meet(&self, i: usize, j: usize) -> bool {
        let [a0, a1] = self.segments[i];
        let [b0, b1] = self.segments[j];
        let (p, q) = self.ends(i);
        let (r, s) = self.ends(j);
        let shared = [a0, a1].iter().filter(|x| **x == b0 || **x == b1).count();
        if shared == 2 {
            return true; // the same segment twice (either direction)
        }
        if shared == 1 {
            // adjacent: they meet elsewhere only if collinear and overlapping
            let (v, u, w) = if a0 == b0 || a0 == b1 { (p, q, if a0 == b0 { s } else { r }) } else { (q, p, if a1 == b0 { s } else { r }) };
            return orient2d(v, u, w) == Sign::Zero && (u - v).dot(w - v) > 0.0;
        }
        segments_intersect(p, q, r, s)
    }
}

/// Signed area of a closed loop.
pub(crate) fn loop_area(pts: &[DVec2]) -> f64 {
    let n = pts.len();
    (0..n).map(|k| pts[k].perp_dot(pts[(k + 1) % n])).sum::<f64>() * 0.5
}

/// Whether `p` is inside the closed loop `pts` (exact crossing parity).
fn inside_loop(pts: &[DVec2], p: DVec2) -> bool {
    let n = pts.len();
    let mut inside = false;
    for k in 0..n {
        let (a, b) = (pts[k], pts[(k + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) {
            let o = if b.y > a.y { orient2d(a, b, p) } else { orient2d(b, a, p) };
            if o == Sign::Positive {
                inside = !inside;
            }
        }
    }
    inside
}

/// Whether the closed segments `pq` and `rs` share a point (exact).
pub(crate) fn segments_intersect(p: DVec2, q: DVec2, r: DVec2, s: DVec2) -> bool {
    let o1 = orient2d(p, q, r);
    let o2 = orient2d(p, q, s);
    let o3 = orient2d(r, s, p);
    let o4 = orient2d(r, s, q);
    let on = |a: DVec2, b: DVec2, c: DVec2| c.x >= a.x.min(b.x) && c.x <= a.x.max(b.x) && c.y >= a.y.min(b.y) && c.y <= a.y.max(b.y);
    if o1 != o2 && o3 != o4 && o1 != Sign::Zero && o2 != Sign::Zero && o3 != Sign::Zero && o4 != Sign::Zero {
        return true;
    }
    (o1 == Sign::Zero && on(p, q, r)) || (o2 == Sign::Zero && on(p, q, s)) || (o3 == Sign::Zero && on(r, s, p)) || (o4 == Sign::Zero && on(r, s, q))
}

/// Distance from segment `ab` to the closed axis-aligned square `[lo, lo + side]²`.
pub(crate) fn segment_square_distance(a: DVec2, b: DVec2, lo: DVec2, side: f64) -> f64 {
    let hi = lo + DVec2::splat(side);
    let inside = |p: DVec2| p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y;
    if inside(a) || inside(b) {
        return 0.0;
    }
    let c = [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
    for k in 0..4 {
        if segments_intersect(a, b, c[k], c[(k + 1) % 4]) {
            return 0.0;
        }
    }
    // disjoint: the distance is attained at an end point of one of them
    let mut d = f64::INFINITY;
    for p in [a, b] {
        d = d.min((p - p.clamp(lo, hi)).length());
    }
    for q in c {
        d = d.min(point_segment_distance(q, a, b));
    }
    d
}

/// Distance from `p` to the segment `ab`.
pub(crate) fn point_segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let l2 = ab.length_squared();
    let t = if l2 > 0.0 { ((p - a).dot(ab) / l2).clamp(0.0, 1.0) } else { 0.0 };
    (p - (a + t * ab)).length()
}
