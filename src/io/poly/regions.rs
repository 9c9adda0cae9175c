//! A `.poly` file's regions as checked domains, with Triangle's semantics.
//!
//! - Stage: input, between reading a `.poly` and 2D meshing.
//! - Inputs: a [`PolyFile`].
//! - Output: one [`PolyRegion`] per connected region: a [`Domain`] whose directed segments are
//!   the region's boundary (the region on their left), tagged with the segment markers, with
//!   the region's tag and maximum area from the regional attribute seed inside it.
//! - How: the input is checked first (finite, distinct vertices; segments that neither cross,
//!   overlap nor pass through a vertex, decided exactly by `crate::core::predicates`); then the
//!   vertices and segments are triangulated (spade's CDT), the triangles reachable from the
//!   convex hull without crossing a segment are removed, then those reachable from each hole
//!   seed; what remains splits into connected components (segments separate them), each one
//!   a region. A segment with the same region on both sides is refused (dangling or internal),
//!   one with no region on either side (inside a hole or outside) is ignored, as Triangle
//!   ignores it; vertices on no segment are ignored (Triangle would keep them as mesh
//!   vertices).
//! - Invariants: deterministic (the regions are ordered by their first segment in the file;
//!   each domain's points by first use along its segments, which keep the file's order).

use super::types::{PolyError, PolyFile};
use crate::core::cdt;
use crate::core::predicates::orient2d;
use crate::core::{RegionId, Sign};
use crate::mesh2d::domain::segments_intersect;
use crate::mesh2d::Domain;
use glam::DVec2;
use spade::handles::{FixedDirectedEdgeHandle, FixedFaceHandle, FixedVertexHandle, PossiblyOuterTag};
use spade::{ConstrainedDelaunayTriangulation, Point2, PositionInTriangulation, Triangulation};

/// One connected region of a `.poly` file.
#[derive(Clone, Debug, PartialEq)]
pub struct PolyRegion {
    /// The region's tag: the attribute of the last region seed inside it, else 1.
    pub tag: RegionId,
    /// Its boundary.
    pub domain: Domain,
    /// The maximum triangle area of the last region seed inside it that gives one.
    pub max_area: Option<f64>,
}

type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

/// Face labels while the regions are found.
const OUTSIDE: u32 = u32::MAX;
const UNSEEN: u32 = u32::MAX - 1;
const HOLE: u32 = u32::MAX - 2;

impl PolyFile {
    /// The regions as `(tag, domain)` pairs (see [`PolyFile::to_regions`]).
    ///
    /// # Errors
    /// As [`PolyFile::to_regions`].
    pub fn to_domains(&self) -> Result<Vec<(RegionId, Domain)>, PolyError> {
        Ok(self.to_regions()?.into_iter().map(|r| (r.tag, r.domain)).collect())
    }

    /// The connected regions with Triangle's semantics (see the module docs of
    /// `io/poly/regions.rs`).
    ///
    /// # Errors
    /// The first problem found, naming the vertex, segment or seed (0-based): a bad or
    /// duplicate vertex, crossing or overlapping segments, a vertex inside a segment, no
    /// enclosed area, a hole or region seed outside every region or on a segment, an internal
    /// or dangling segment, a regional attribute that is not a tag, a region whose boundary
    /// fails [`Domain::validate`].
    pub fn to_regions(&self) -> Result<Vec<PolyRegion>, PolyError> {
        self.check_vertices()?;
        self.check_segments()?;
        let (tri, handles) = self.triangulate()?;
        let edge_segment = self.edge_segments(&tri, &handles)?;
        let mut label = vec![UNSEEN; tri.num_all_faces()];
        label[tri.outer_face().fix().index()] = OUTSIDE;
        // the convex hull's side: faces reached from the outer face without crossing a segment
        let hull: Vec<FixedFaceHandle<PossiblyOuterTag>> = tri.convex_hull().filter(|e| !e.as_undirected().is_constraint_edge()).flat_map(|e| [e.face().fix(), e.rev().face().fix()]).collect();
        flood(&tri, &hull, &mut label, OUTSIDE);
        for (k, &h) in self.holes.iter().enumerate() {
            let face = locate(&tri, h, "hole", k)?;
            match face {
                Some(f) if label[f.index()] != OUTSIDE => flood(&tri, &[f], &mut label, HOLE),
                _ => return Err(PolyError::HoleOutside { hole: k, x: h.x, y: h.y }),
            }
        }
        // components, numbered in the order of their first segment in the file
        let mut count = 0u32;
        for s in 0..self.segments.len() {
            let [a, b] = self.segments[s];
            let e = tri.get_edge_from_neighbors(handles[a as usize], handles[b as usize]).map(|e| e.fix());
            for d in e.into_iter().flat_map(|e| [e, e.rev()]) {
                let f = tri.directed_edge(d).face().fix();
                if label[f.index()] == UNSEEN {
                    flood(&tri, &[f], &mut label, count);
                    count += 1;
                }
            }
        }
        if count == 0 {
            return Err(PolyError::NoArea);
        }
        let mut tags = vec![RegionId(1); count as usize];
        let mut areas = vec![None; count as usize];
        for (k, r) in self.regions.iter().enumerate() {
            let f = locate(&tri, r.at, "region seed", k)?;
            let c = f.map_or(OUTSIDE, |f| label[f.index()]);
            if c >= count {
                return Err(PolyError::RegionOutside { region: k, x: r.at.x, y: r.at.y });
            }
            let a = r.attribute;
            if !(a >= 1.0 && a <= f64::from(u32::MAX) && a.fract() == 0.0) {
                return Err(PolyError::BadAttribute { region: k, value: a });
            }
            tags[c as usize] = RegionId(a as u32);
            if r.max_area.is_some() {
                areas[c as usize] = r.max_area;
            }
        }
        let mut out: Vec<(Vec<DVec2>, Vec<u32>, Vec<[u32; 2]>, Vec<u32>)> = vec![Default::default(); count as usize];
        for s in 0..self.segments.len() {
            let [a, b] = self.segments[s];
            let e = edge_segment[s];
            let left = label[tri.directed_edge(e).face().fix().index()];
            let right = label[tri.directed_edge(e).rev().face().fix().index()];
            if left == right && left < count {
                return Err(PolyError::InternalSegment { segment: s });
            }
            for (c, from, to) in [(left, a, b), (right, b, a)] {
                if c < count {
                    let (points, map, segments, seg_tags) = &mut out[c as usize];
                    if map.is_empty() {
                        map.resize(self.points.len(), u32::MAX);
                    }
                    let mut id = |v: u32| {
                        if map[v as usize] == u32::MAX {
                            map[v as usize] = points.len() as u32;
                            points.push(self.points[v as usize]);
                        }
                        map[v as usize]
                    };
                    let seg = [id(from), id(to)];
                    segments.push(seg);
                    seg_tags.push(self.markers.get(s).copied().unwrap_or(0));
                }
            }
        }
        out.into_iter().enumerate().map(|(c, (points, _, segments, seg_tags))| {
            let domain = Domain::new(points, segments, seg_tags).map_err(|source| PolyError::Domain { region: c, source })?;
            Ok(PolyRegion { tag: tags[c], domain, max_area: areas[c] })
        }).collect()
    }

    /// Finite vertices, no two equal (exact comparison after sorting).
    fn check_vertices(&self) -> Result<(), PolyError> {
        if let Some(v) = self.points.iter().position(|p| !p.is_finite()) {
            return Err(PolyError::NonFinite { vertex: v as u32, x: self.points[v].x, y: self.points[v].y });
        }
        let mut order: Vec<u32> = (0..self.points.len() as u32).collect();
        let key = |i: u32| self.points[i as usize].to_array();
        order.sort_by(|&i, &j| key(i)[0].total_cmp(&key(j)[0]).then(key(i)[1].total_cmp(&key(j)[1])).then(i.cmp(&j)));
        let mut found: Option<(u32, u32)> = None;
        for w in order.windows(2) {
            if self.points[w[0] as usize] == self.points[w[1] as usize] {
                let pair = (w[0].min(w[1]), w[0].max(w[1]));
                found = Some(found.map_or(pair, |f| f.min(pair)));
            }
        }
        found.map_or(Ok(()), |(a, b)| Err(PolyError::DuplicateVertex(a, b)))
    }

    /// Valid ends, and no two segments meeting except at a shared end (a sweep over x; the
    /// first offending pair by index is reported).
    fn check_segments(&self) -> Result<(), PolyError> {
        let n = self.points.len() as u32;
        for (s, &[a, b]) in self.segments.iter().enumerate() {
            if a >= n || b >= n || a == b {
                return Err(PolyError::BadSegment { segment: s, a, b });
            }
        }
        let ends = |s: usize| (self.points[self.segments[s][0] as usize], self.points[self.segments[s][1] as usize]);
        let lo_x = |s: usize| ends(s).0.x.min(ends(s).1.x);
        let mut order: Vec<usize> = (0..self.segments.len()).collect();
        order.sort_by(|&i, &j| lo_x(i).total_cmp(&lo_x(j)).then(i.cmp(&j)));
        let mut found: Option<PolyError> = None;
        let mut found_pair = (usize::MAX, usize::MAX);
        for (k, &i) in order.iter().enumerate() {
            let (p, q) = ends(i);
            let hi_x = p.x.max(q.x);
            for &j in &order[k + 1..] {
                if lo_x(j) > hi_x {
                    break;
                }
                let pair = (i.min(j), i.max(j));
                if pair < found_pair {
                    if let Some(e) = self.meet(pair.0, pair.1) {
                        found = Some(e);
                        found_pair = pair;
                    }
                }
            }
        }
        found.map_or(Ok(()), Err)
    }

    /// How segments `i` and `j` meet other than at a shared end, if they do.
    fn meet(&self, i: usize, j: usize) -> Option<PolyError> {
        let [a0, a1] = self.segments[i];
        let [b0, b1] = self.segments[j];
        let pt = |v: u32| self.points[v as usize];
        let shared = [a0, a1].iter().filter(|x| **x == b0 || **x == b1).count();
        if shared == 2 {
            return Some(PolyError::SegmentsIntersect(i, j));
        }
        // a vertex of one strictly inside the other
        let inside = |v: u32, s: [u32; 2]| {
            let (p, q) = (pt(s[0]), pt(s[1]));
            let c = pt(v);
            v != s[0] && v != s[1] && orient2d(p, q, c) == Sign::Zero && c.x >= p.x.min(q.x) && c.x <= p.x.max(q.x) && c.y >= p.y.min(q.y) && c.y <= p.y.max(q.y)
        };
        for (v, s, seg) in [(b0, [a0, a1], i), (b1, [a0, a1], i), (a0, [b0, b1], j), (a1, [b0, b1], j)] {
            if inside(v, s) {
                return Some(PolyError::VertexOnSegment { vertex: v, segment: seg });
            }
        }
        (shared == 0 && segments_intersect(pt(a0), pt(a1), pt(b0), pt(b1))).then_some(PolyError::SegmentsIntersect(i, j))
    }

    /// The CDT of the vertices that end segments, with every segment a constraint; the
    /// handle of each vertex (those on no segment get the first one's, unused).
    fn triangulate(&self) -> Result<(Cdt, Vec<FixedVertexHandle>), PolyError> {
        let mut used = vec![false; self.points.len()];
        for s in &self.segments {
            used[s[0] as usize] = true;
            used[s[1] as usize] = true;
        }
        let mut tri = Cdt::new();
        let mut handles = vec![FixedVertexHandle::from_index(0); self.points.len()];
        let mut owner: Vec<u32> = Vec::new();
        for (v, &p) in self.points.iter().enumerate() {
            if !used[v] {
                continue;
            }
            let h = cdt::insert(&mut tri, p, |q| q).map_err(|e| PolyError::Triangulation(format!("vertex {v}: {e}")))?;
            if h.index() < owner.len() {
                // the guard flushed two vertices onto one
                return Err(PolyError::DuplicateVertex(owner[h.index()], v as u32));
            }
            owner.push(v as u32);
            handles[v] = h;
        }
        for &[a, b] in &self.segments {
            cdt::constrain(&mut tri, handles[a as usize], handles[b as usize]);
        }
        Ok((tri, handles))
    }

    /// The CDT edge of each segment, directed as the segment.
    fn edge_segments(&self, tri: &Cdt, handles: &[FixedVertexHandle]) -> Result<Vec<FixedDirectedEdgeHandle>, PolyError> {
        self.segments.iter().enumerate().map(|(s, &[a, b])| {
            tri.get_edge_from_neighbors(handles[a as usize], handles[b as usize])
                .filter(|e| e.as_undirected().is_constraint_edge())
                .map(|e| e.fix())
                .ok_or_else(|| PolyError::Triangulation(format!("segment {s} is not an edge of the triangulation")))
        }).collect()
    }
}

/// Labels every face reachable from `start` without crossing a constraint edge (or entering
/// the outer face) with `value`, skipping faces that already carry it.
fn flood(tri: &Cdt, start: &[FixedFaceHandle<PossiblyOuterTag>], label: &mut [u32], value: u32) {
    let mut stack: Vec<FixedFaceHandle<PossiblyOuterTag>> = Vec::new();
    for &f in start {
        if !tri.face(f).is_outer() && label[f.index()] != value {
            label[f.index()] = value;
            stack.push(f);
        }
    }
    while let Some(f) = stack.pop() {
        let Some(inner) = tri.face(f).as_inner() else { continue };
        for e in inner.adjacent_edges() {
            if e.as_undirected().is_constraint_edge() {
                continue;
            }
            let g = e.rev().face();
            if !g.is_outer() && label[g.fix().index()] != value {
                label[g.fix().index()] = value;
                stack.push(g.fix());
            }
        }
    }
}

/// The face containing a seed: `None` outside the convex hull; an error on a constraint edge
/// or a vertex (an edge that is not a constraint gives either side: both are one region).
fn locate(tri: &Cdt, p: DVec2, what: &'static str, index: usize) -> Result<Option<FixedFaceHandle<PossiblyOuterTag>>, PolyError> {
    let on = || PolyError::SeedOnBoundary { what, index, x: p.x, y: p.y };
    let q = cdt::point(p).ok_or_else(on)?;
    match tri.locate(q) {
        PositionInTriangulation::OnFace(f) => Ok(Some(tri.face(f).adjacent_edges()[0].face().fix())),
        PositionInTriangulation::OnEdge(e) => {
            let e = tri.directed_edge(e);
            if e.as_undirected().is_constraint_edge() {
                return Err(on());
            }
            let f = if e.face().is_outer() { e.rev().face() } else { e.face() };
            Ok((!f.is_outer()).then(|| f.fix()))
        }
        PositionInTriangulation::OnVertex(_) => Err(on()),
        PositionInTriangulation::OutsideOfConvexHull(_) | PositionInTriangulation::NoTriangulation => Ok(None),
    }
}
