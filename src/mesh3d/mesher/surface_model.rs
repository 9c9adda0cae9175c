//! The boundary as the mesher sees it: the input triangles (facets, each with its face tag) and
//! their edges (segments), with the Steiner points inserted on them.
//!
//! Every facet keeps the 2D Delaunay triangulation of its points in its own plane (spade); its
//! triangles are the subfaces, each carrying the facet's tag, that the tetrahedralization must
//! contain. Segments keep their points in order; consecutive ones are the subsegments.
//!
//! Invariant: the subfaces of a facet tile it (up to rounding of Steiner points), their edges
//! along the facet's sides are exactly the subsegments of its segments.

use crate::core::FaceId;
use crate::core::cdt;
use crate::mesh::topology::flat_pieces;
use super::subface_list::SubfaceList;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use rustc_hash::FxHashMap;
use spade::handles::{FixedFaceHandle, FixedVertexHandle, InnerTag};
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

/// Where a vertex of the mesh lies.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Location {
    /// An input vertex.
    Input,
    /// A Steiner point on a segment.
    Segment(u32),
    /// A Steiner point inside a facet.
    Facet(u32),
    /// A Steiner point in the volume.
    Volume,
    /// A Steiner point removed again (merged into a neighbour).
    Gone,
}

/// A facet: one input triangle, or (when merging) a maximal set of edge-connected, coplanar
/// input triangles with one tag, which may then be retriangulated freely inside.
#[derive(Clone, Debug)]
pub(crate) struct Facet {
    /// The input triangles it is made of, as given (they tile it).
    pub triangles: Vec<[u32; 3]>,
    /// Its tag.
    pub tag: FaceId,
    /// Its sides (the segments on its boundary).
    pub sides: Vec<u32>,
    /// Its boundary as (segment, forward): forward when the segment's points run in the
    /// facet's counter-clockwise direction (the facet on their left).
    pub loops: Vec<(u32, bool)>,
    /// Points strictly inside it: input vertices inside a merged facet, and Steiner points.
    pub inner: Vec<u32>,
    /// Current subfaces, oriented like the facet.
    pub subfaces: SubfaceList,
    /// Its plane: an origin and two orthonormal directions (counter-clockwise about the
    /// outward normal of its triangles).
    frame: [DVec3; 3],
}

/// An edge between two facets (every input edge, when facets are not merged).
#[derive(Clone, Debug)]
pub(crate) struct Segment {
    /// Its endpoints and Steiner points, in order from its smaller endpoint to its larger.
    pub points: Vec<u32>,
    /// The facets having it as a side.
    pub facets: Vec<u32>,
}

/// The input surface with its Steiner points.
pub(crate) struct SurfaceModel {
    /// The facets.
    pub facets: Vec<Facet>,
    /// The segments.
    pub segments: Vec<Segment>,
    /// Where every vertex lies (grows with the points).
    pub location: Vec<Location>,
    /// The facet of every current subface and its slot there, by its sorted vertices.
    index: FxHashMap<[u32; 3], (u32, u32)>,
    /// Boundary points from this index on were put there by refinement (boundary splits):
    /// merging recovery's points back leaves them. `None` before refinement.
    pub refined_from: Option<u32>,
    /// The most the enclosed volume can change by merging input triangles that are flat only
    /// within the tolerance: over every merged facet, twice its area times how far its input
    /// vertices lie from its plane (every subface stays in that slab over the same polygon).
    /// Zero when every merged facet is exactly planar.
    pub flattening_volume: f64,
    /// Per facet, whether deferred splits changed its points since it was last triangulated
    /// ([`SurfaceModel::split_segment_deferred`], [`SurfaceModel::flush`]).
    pending: Vec<bool>,
}

/// One facet's change by a boundary split: the facet, the subfaces removed, those added.
pub(crate) type FacetEdit = (u32, Vec<[u32; 3]>, Vec<[u32; 3]>);

impl SurfaceModel {
    /// The model of `triangles` (vertex indices into `points`) with their tags; with `merge`,
    /// flat pieces of one tag (coplanar within a tolerance) form one facet each.
    pub fn new(points: &[DVec3], triangles: &[[u32; 3]], tags: &[FaceId], merge: bool) -> Self {
        let n = points.len();
        let normal = |t: &[u32; 3]| {
            let [a, b, c] = t.map(|i| points[i as usize]);
            (b - a).cross(c - a)
        };
        // the triangles on each edge
        let mut on_edge: FxHashMap<(u32, u32), Vec<u32>> = FxHashMap::default();
        for (i, t) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                on_edge.entry((a.min(b), a.max(b))).or_default().push(i as u32);
            }
        }
        // facets: the flat pieces of the input (see `mesh::topology::flat_pieces`) when
        // merging, else every triangle alone
        let facet_of_tri: Vec<u32> = if merge { flat_pieces(points, triangles, tags) } else { (0..triangles.len() as u32).collect() };
        let mut facets: Vec<Facet> = Vec::new();
        for (i, &f) in facet_of_tri.iter().enumerate() {
            if f as usize == facets.len() {
                facets.push(Facet {
                    triangles: Vec::new(),
                    tag: tags[i],
                    sides: Vec::new(),
                    loops: Vec::new(),
                    inner: Vec::new(),
                    subfaces: SubfaceList::default(),
                    frame: [DVec3::ZERO; 3],
                });
            }
            facets[f as usize].triangles.push(triangles[i]);
        }
        // segments: edges between different facets
        let mut segments: Vec<Segment> = Vec::new();
        let mut keys: Vec<(u32, u32)> = on_edge.keys().copied().collect();
        keys.sort_unstable();
        let mut seg_of: FxHashMap<(u32, u32), u32> = FxHashMap::default();
        for key in keys {
            let ts = &on_edge[&key];
            let mut fs: Vec<u32> = ts.iter().map(|&t| facet_of_tri[t as usize]).collect();
            fs.sort_unstable();
            let interior = fs.len() == 2 && fs[0] == fs[1];
            if interior {
                continue;
            }
            fs.dedup();
            segments.push(Segment { points: vec![key.0, key.1], facets: fs.clone() });
            let s = (segments.len() - 1) as u32;
            seg_of.insert(key, s);
            for f in fs {
                facets[f as usize].sides.push(s);
            }
        }
        let mut flattening_volume = 0.0;
        for fc in facets.iter_mut() {
            let mut on_side: Vec<u32> = Vec::new();
            for t in &fc.triangles {
                for k in 0..3 {
                    let (a, b) = (t[k], t[(k + 1) % 3]);
                    if let Some(&s) = seg_of.get(&(a.min(b), a.max(b))) {
                        fc.loops.push((s, a < b));
                        on_side.push(a);
                        on_side.push(b);
                    }
                }
            }
            on_side.sort_unstable();
            on_side.dedup();
            let mut inner: Vec<u32> = fc.triangles.iter().flatten().copied().filter(|v| on_side.binary_search(v).is_err()).collect();
            inner.sort_unstable();
            inner.dedup();
            fc.inner = inner;
            fc.subfaces = SubfaceList::new(fc.triangles.clone());
            // the frame: the area-weighted normal, the first edge of the largest triangle
            let sum: DVec3 = fc.triangles.iter().map(normal).sum();
            let big = fc.triangles.iter().max_by(|x, y| normal(x).length_squared().total_cmp(&normal(y).length_squared())).copied();
            if let Some(t) = big {
                let o = points[t[0] as usize];
                let nrm = sum.normalize_or_zero();
                let e1 = (points[t[1] as usize] - o).reject_from_normalized(nrm).normalize_or_zero();
                fc.frame = [o, e1, nrm.cross(e1)];
                if fc.triangles.len() > 1 {
                    let off = fc.triangles.iter().flatten().map(|&v| (points[v as usize] - o).dot(nrm).abs()).fold(0.0, f64::max);
                    let area: f64 = fc.triangles.iter().map(|t| 0.5 * normal(t).length()).sum();
                    flattening_volume += 2.0 * area * off;
                }
            }
        }
        let mut index = FxHashMap::default();
        for (f, fc) in facets.iter().enumerate() {
            for (slot, t) in fc.subfaces.slotted() {
                index.insert(sorted(t), (f as u32, slot));
            }
        }
        let pending = vec![false; facets.len()];
        SurfaceModel { facets, segments, location: vec![Location::Input; n], index, refined_from: None, flattening_volume, pending }
    }

    /// Point `p` in facet `f`'s plane coordinates.
    pub(crate) fn to_plane(&self, f: u32, p: DVec3) -> DVec2 {
        let [o, e1, e2] = self.facets[f as usize].frame;
        let d = p - o;
        DVec2::new(d.dot(e1), d.dot(e2))
    }

    /// True if `p` (near the facet's plane) lies in facet `f`: in or on one of its input
    /// triangles, seen in its plane.
    pub fn inside(&self, f: u32, p: DVec3, points: &[DVec3]) -> bool {
        let q = self.to_plane(f, p);
        self.facets[f as usize].triangles.iter().any(|t| {
            let [a, b, c] = t.map(|i| self.to_plane(f, points[i as usize]));
            let cross = |u: DVec2, v: DVec2, w: DVec2| (v - u).perp_dot(w - u);
            let area = cross(a, b, c);
            let tol = -1e-12 * area.abs();
            area != 0.0 && cross(a, b, q) * area.signum() >= tol && cross(b, c, q) * area.signum() >= tol && cross(c, a, q) * area.signum() >= tol
        })
    }

    /// Records a new vertex's location.
    pub fn locate_vertex(&mut self, v: u32, at: Location) {
        if self.location.len() <= v as usize {
            self.location.resize(v as usize + 1, Location::Volume);
        }
        self.location[v as usize] = at;
    }

    /// The subsegments of segment `s`.
    pub fn subsegments(&self, s: u32) -> impl Iterator<Item = [u32; 2]> + '_ {
        self.segments[s as usize].points.windows(2).map(|w| [w[0], w[1]])
    }

    /// Inserts vertex `p` into segment `s` between its consecutive points `a` and `b`, and
    /// re-triangulates the facets around it. Returns false if `a`, `b` are not consecutive.
    #[cfg(test)]
    pub fn split_segment(&mut self, s: u32, a: u32, b: u32, p: u32, points: &[DVec3]) -> bool {
        if !self.split_segment_deferred(s, a, b, p) {
            return false;
        }
        self.flush(points);
        true
    }

    /// Inserts vertex `p` into segment `s` between its consecutive points `a` and `b` without
    /// retriangulating (false if they are not consecutive): the facets around the segment
    /// are marked, and their subfaces are stale until [`SurfaceModel::flush_facet`] or
    /// [`SurfaceModel::flush`]. A facet's subfaces are a function of its points alone, so
    /// triangulating it once after several splits gives what triangulating it after each did.
    pub fn split_segment_deferred(&mut self, s: u32, a: u32, b: u32, p: u32) -> bool {
        let seg = &mut self.segments[s as usize];
        let Some(i) = seg.points.windows(2).position(|w| (w[0] == a && w[1] == b) || (w[0] == b && w[1] == a)) else {
            return false;
        };
        seg.points.insert(i + 1, p);
        self.locate_vertex(p, Location::Segment(s));
        for &f in &self.segments[s as usize].facets {
            self.pending[f as usize] = true;
        }
        true
    }

    /// Retriangulates facet `f` if deferred splits changed it.
    pub fn flush_facet(&mut self, f: u32, points: &[DVec3]) {
        if std::mem::take(&mut self.pending[f as usize]) {
            self.retriangulate(f, points);
        }
    }

    /// Retriangulates every facet that deferred splits changed, in increasing order.
    pub fn flush(&mut self, points: &[DVec3]) {
        for f in 0..self.facets.len() as u32 {
            self.flush_facet(f, points);
        }
    }

    /// Inserts vertex `p` inside facet `f` and re-triangulates it.
    pub fn add_to_facet(&mut self, f: u32, p: u32, points: &[DVec3]) {
        self.pending[f as usize] = false;
        self.facets[f as usize].inner.push(p);
        self.locate_vertex(p, Location::Facet(f));
        self.retriangulate(f, points);
    }

    /// All points of facet `f`: its sides' points and its inner points, each once.
    fn facet_points(&self, f: u32) -> Vec<u32> {
        let fc = &self.facets[f as usize];
        let mut out: Vec<u32> = Vec::new();
        for &s in &fc.sides {
            out.extend_from_slice(&self.segments[s as usize].points);
        }
        out.sort_unstable();
        out.dedup();
        out.extend(fc.inner.iter().copied());
        out
    }

    /// Recomputes the subfaces of facet `f`: the constrained Delaunay triangulation of its
    /// points in its plane, its sides' subsegments as constraints, the triangles inside it
    /// found by a flood from the inner side of its boundary. Keeps the old subfaces if the
    /// plane mapping degenerates.
    pub fn retriangulate(&mut self, f: u32, points: &[DVec3]) {
        if let Some(subfaces) = self.triangulation(f, points) {
            self.set_subfaces(f, subfaces);
        }
    }

    /// The subfaces [`SurfaceModel::retriangulate`] gives facet `f`, or `None` where it keeps
    /// the old ones.
    fn triangulation(&self, f: u32, points: &[DVec3]) -> Option<Vec<[u32; 3]>> {
        let pts = self.facet_points(f);
        let mut tri: ConstrainedDelaunayTriangulation<Point2<f64>> = ConstrainedDelaunayTriangulation::new();
        let mut handle: FxHashMap<u32, FixedVertexHandle> = FxHashMap::default();
        let mut ids: Vec<u32> = Vec::with_capacity(pts.len());
        for &v in &pts {
            let q = self.to_plane(f, points[v as usize]);
            match cdt::insert(&mut tri, q, |p| p) {
                Ok(h) if h.index() == ids.len() => {
                    ids.push(v);
                    handle.insert(v, h);
                }
                _ => return None, // two points on one spot in the plane, or not finite
            }
        }
        let fc = &self.facets[f as usize];
        let mut seeds: Vec<(FixedVertexHandle, FixedVertexHandle)> = Vec::new();
        for &(s, forward) in &fc.loops {
            let p = &self.segments[s as usize].points;
            for w in p.windows(2) {
                let (a, b) = if forward { (w[0], w[1]) } else { (w[1], w[0]) };
                let (ha, hb) = (handle[&a], handle[&b]);
                if !cdt::constrain(&mut tri, ha, hb) {
                    return None;
                }
                seeds.push((ha, hb));
            }
        }
        // flood from the left of every boundary subsegment, never across a constraint
        let mut inside = vec![false; tri.num_all_faces()];
        let mut stack: Vec<FixedFaceHandle<InnerTag>> = Vec::new();
        for (a, b) in seeds {
            if let Some(e) = tri.get_edge_from_neighbors(a, b) {
                if let Some(face) = e.face().as_inner() {
                    if !std::mem::replace(&mut inside[face.fix().index()], true) {
                        stack.push(face.fix());
                    }
                }
            }
        }
        while let Some(fh) = stack.pop() {
            for e in tri.face(fh).adjacent_edges() {
                if e.is_constraint_edge() {
                    continue;
                }
                if let Some(n) = e.rev().face().as_inner() {
                    if !std::mem::replace(&mut inside[n.fix().index()], true) {
                        stack.push(n.fix());
                    }
                }
            }
        }
        // the sides (positions in `fc.sides`) through each point, by the point's handle
        let mut sides_at: Vec<Vec<u32>> = vec![Vec::new(); ids.len()];
        for (k, &s) in fc.sides.iter().enumerate() {
            for v in &self.segments[s as usize].points {
                if let Some(h) = handle.get(v) {
                    let at = &mut sides_at[h.index()];
                    if at.last() != Some(&(k as u32)) {
                        at.push(k as u32);
                    }
                }
            }
        }
        // whether one side holds all three points of a triangle (by handles)
        let one_side = |t: [usize; 3]| sides_at[t[0]].iter().any(|k| sides_at[t[1]].contains(k) && sides_at[t[2]].contains(k));
        let mut subfaces = Vec::new();
        for fh in tri.fixed_inner_faces() {
            if !inside[fh.index()] {
                continue;
            }
            let h = tri.face(fh).vertices().map(|h| h.fix().index());
            // a sliver along one side (points of one segment only) is no part of the facet
            if one_side(h) {
                continue;
            }
            subfaces.push(h.map(|i| ids[i]));
        }
        (!subfaces.is_empty()).then_some(subfaces)
    }

    /// Puts `subfaces` in place of facet `f`'s.
    fn set_subfaces(&mut self, f: u32, subfaces: Vec<[u32; 3]>) {
        for old in self.facets[f as usize].subfaces.take() {
            self.index.remove(&sorted(old));
        }
        for (slot, &t) in subfaces.iter().enumerate() {
            self.index.insert(sorted(t), (f, slot as u32));
        }
        self.facets[f as usize].subfaces = SubfaceList::new(subfaces);
    }

    /// Squeezes facet `f`'s subface list if holes outnumber its subfaces, keeping the index.
    fn squeeze(&mut self, f: u32) {
        let list = &mut self.facets[f as usize].subfaces;
        if list.worth_squeezing() {
            for (slot, t) in list.squeeze() {
                self.index.insert(sorted(t), (f, slot));
            }
        }
    }

    /// Cuts the surface to the size wanted before meshing (when the boundary may change):
    /// every segment into equal pieces no longer than the size at its midpoint nor, next to a
    /// facet that is a single input triangle, 1.5 times that triangle's smallest altitude, nor
    /// near a thin feature the local feature size (these two cut an edge into 64 pieces at
    /// most: thin input triangles come out better shaped); then every facet refined in its plane by
    /// spade's constrained Delaunay refinement (angle limit 25°, area from the size), its
    /// sides kept. New points are appended to `points` as Steiner points.
    ///
    /// `scale` bounds the size near every input vertex (a local feature size: how near the
    /// surface comes to itself there).
    ///
    /// The facets are refined and then triangulated in parallel: each is a function of its
    /// own points, and the new points are numbered in facet order as one facet after the
    /// other would number them.
    pub fn presize(&mut self, points: &mut Vec<DVec3>, size: &(dyn Fn(DVec3) -> f64 + Sync), scale: &[f64]) {
        const MAX_PIECES: f64 = 4096.0;
        // for shape alone an edge is cut into at most this many pieces (a fillet's long
        // strips would otherwise explode into tiny triangles): 4 left plate_holes.STL at 0.23°
        // and 207 tets under 5°, 64 gives 3.7° and 5
        const MAX_SHAPE_PIECES: f64 = 64.0;
        for s in 0..self.segments.len() {
            let (a, b) = (self.segments[s].points[0], self.segments[s].points[1]);
            let (pa, pb) = (points[a as usize], points[b as usize]);
            // the size wanted, and the shape of thin neighbours (at most 64 pieces for that:
            // a fillet's long strips would otherwise explode into tiny triangles)
            let length = pa.distance(pb);
            let mut shape = f64::INFINITY;
            for &f in &self.segments[s].facets {
                let fc = &self.facets[f as usize];
                if let [t] = fc.triangles.as_slice() {
                    shape = shape.min(1.5 * min_altitude(t.map(|i| points[i as usize])));
                } else if fc.triangles.len() <= STRIP_TRIANGLES {
                    // a strip of a few triangles (a faceted cylinder's flat between two
                    // generators): as wide as its farthest corner from this side
                    let width = fc.triangles.iter().flatten().map(|&i| distance_to_line(points[i as usize], pa, pb)).fold(0.0, f64::max);
                    if width > 0.0 {
                        shape = shape.min(1.5 * width);
                    }
                }
            }
            let shape = shape.min(scale[a as usize]).min(scale[b as usize]).max(length / MAX_SHAPE_PIECES);
            let len = size((pa + pb) * 0.5).min(shape);
            let n = (pa.distance(pb) / len).ceil();
            let n = if n.is_finite() && n > 1.0 { n.min(MAX_PIECES) as usize } else { 1 };
            if n > 1 {
                let mut pts = vec![a];
                for k in 1..n {
                    points.push(pa + (pb - pa) * (k as f64 / n as f64));
                    let v = (points.len() - 1) as u32;
                    self.locate_vertex(v, Location::Segment(s as u32));
                    pts.push(v);
                }
                pts.push(b);
                self.segments[s].points = pts;
            }
        }
        let nf = self.facets.len() as u32;
        let inside: Vec<Vec<DVec3>> = (0..nf)
            .into_par_iter()
            .map(|f| {
                let local = self.facets[f as usize].triangles.iter().flatten().map(|&v| scale[v as usize]).fold(f64::INFINITY, f64::min);
                self.refined_points(f, points, &|p| size(p).min(local))
            })
            .collect();
        for (f, new) in (0..nf).zip(inside) {
            for p in new {
                points.push(p);
                let v = (points.len() - 1) as u32;
                self.facets[f as usize].inner.push(v);
                self.locate_vertex(v, Location::Facet(f));
            }
        }
        let points = &*points;
        let triangulated: Vec<Option<Vec<[u32; 3]>>> = (0..nf).into_par_iter().map(|f| self.triangulation(f, points)).collect();
        for (f, subfaces) in (0..nf).zip(triangulated) {
            if let Some(subfaces) = subfaces {
                self.set_subfaces(f, subfaces);
            }
        }
    }

    /// Spade's refinement of facet `f` in its plane (sides kept): the new points, all inside
    /// it, in the order spade made them.
    fn refined_points(&self, f: u32, points: &[DVec3], size: &dyn Fn(DVec3) -> f64) -> Vec<DVec3> {
        let pts = self.facet_points(f);
        let mut tri: ConstrainedDelaunayTriangulation<Point2<f64>> = ConstrainedDelaunayTriangulation::new();
        let mut handle: FxHashMap<u32, FixedVertexHandle> = FxHashMap::default();
        for &v in &pts {
            let q = self.to_plane(f, points[v as usize]);
            match cdt::insert(&mut tri, q, |p| p) {
                Ok(h) if h.index() == handle.len() => {
                    handle.insert(v, h);
                }
                _ => return Vec::new(),
            }
        }
        for &(s, _) in &self.facets[f as usize].loops {
            for w in self.segments[s as usize].points.windows(2) {
                let (ha, hb) = (handle[&w[0]], handle[&w[1]]);
                if !cdt::constrain(&mut tri, ha, hb) {
                    return Vec::new();
                }
            }
        }
        let centre = self.facets[f as usize].triangles.iter().flatten().map(|&i| points[i as usize]).sum::<DVec3>()
            / (3 * self.facets[f as usize].triangles.len()) as f64;
        let h = size(centre);
        tri.refine(cdt::quality_refinement(h, 2 * pts.len() + 50));
        let [o, e1, e2] = self.facets[f as usize].frame;
        tri.vertices().skip(handle.len()).map(|vh| {
            let p = vh.position();
            o + e1 * p.x + e2 * p.y
        }).collect()
    }

    /// Merges boundary Steiner point `v` into its neighbour `w` (on the same segment, or in the
    /// same facet): `v` leaves its segment or facet, subfaces with both disappear, the others
    /// take `w` for `v`. The caller has checked that the result is valid.
    pub fn collapse(&mut self, v: u32, w: u32) {
        let facets: Vec<u32> = match self.location[v as usize] {
            Location::Segment(s) => {
                self.segments[s as usize].points.retain(|&x| x != v);
                self.segments[s as usize].facets.clone()
            }
            Location::Facet(f) => {
                self.facets[f as usize].inner.retain(|&x| x != v);
                vec![f]
            }
            _ => return,
        };
        self.location[v as usize] = Location::Gone;
        for f in facets {
            let with_v: Vec<(u32, [u32; 3])> = self.facets[f as usize].subfaces.slotted().filter(|(_, t)| t.contains(&v)).collect();
            for (slot, t) in with_v {
                self.index.remove(&sorted(t));
                let list = &mut self.facets[f as usize].subfaces;
                if t.contains(&w) {
                    list.remove(slot);
                    continue;
                }
                let u = t.map(|x| if x == v { w } else { x });
                list.replace(slot, u);
                self.index.insert(sorted(u), (f, slot));
            }
            self.squeeze(f);
        }
    }

    /// The points a boundary Steiner point `v` may merge into: its neighbours along its
    /// segment, or the points of its facet it shares a subface with.
    pub fn merge_targets(&self, v: u32) -> Vec<u32> {
        match self.location.get(v as usize) {
            Some(Location::Segment(s)) => {
                let pts = &self.segments[*s as usize].points;
                let i = pts.iter().position(|&x| x == v).unwrap_or(0);
                [i.checked_sub(1), Some(i + 1)].into_iter().flatten().filter_map(|j| pts.get(j).copied()).filter(|&x| x != v).collect()
            }
            Some(Location::Facet(f)) => {
                let mut out: Vec<u32> = Vec::new();
                for t in self.facets[*f as usize].subfaces.iter() {
                    if t.contains(&v) {
                        for x in t {
                            if x != v && !out.contains(&x) {
                                out.push(x);
                            }
                        }
                    }
                }
                out
            }
            _ => Vec::new(),
        }
    }

    /// The facet holding subface `t` (its vertices in any order), and the subface as stored
    /// (oriented like the facet).
    pub fn subface(&self, t: [u32; 3]) -> Option<(u32, [u32; 3])> {
        let (f, slot) = *self.index.get(&sorted(t))?;
        let s = self.facets[f as usize].subfaces.get(slot)?;
        Some((f, s))
    }

    /// Whether `t`, as oriented, is a subface of facet `f`.
    pub fn has_subface(&self, f: u32, t: [u32; 3]) -> bool {
        self.subface(t) == Some((f, t))
    }

    /// Takes the subfaces of facet `f` that are `r` up to a rotation (so oriented like it) out.
    fn remove_turned(&mut self, f: u32, r: [u32; 3]) {
        let turned = |t: [u32; 3]| t == r || t == [r[1], r[2], r[0]] || t == [r[2], r[0], r[1]];
        if let Some((g, slot)) = self.index.remove(&sorted(r)) {
            let list = &mut self.facets[f as usize].subfaces;
            if g == f && list.get(slot).is_some_and(turned) {
                list.remove(slot);
            }
        }
    }

    /// Adds subface `t` to facet `f`.
    fn add_subface(&mut self, f: u32, t: [u32; 3]) {
        let slot = self.facets[f as usize].subfaces.push(t);
        self.index.insert(sorted(t), (f, slot));
    }

    /// Replaces the subfaces `old` of facet `f` by `new`, oriented like it (a flip inside the
    /// facet: the caller has checked that both pairs tile the same quad).
    pub fn replace_subfaces(&mut self, f: u32, old: [[u32; 3]; 2], new: [[u32; 3]; 2]) {
        for o in old {
            if let Some((g, slot)) = self.index.remove(&sorted(o)) {
                if g == f {
                    self.facets[f as usize].subfaces.remove(slot);
                }
            }
        }
        for t in new {
            self.add_subface(f, t);
        }
        self.squeeze(f);
    }

    /// Makes a boundary split: vertex `p` goes onto segment `s` between its consecutive points
    /// `a` and `b` (`segment`), or else inside facet `inside`; each `(facet, removed, added)`
    /// replaces subfaces of that facet. Returns false (and changes nothing) if `a`, `b` are not
    /// consecutive on `s`.
    pub fn apply_split(&mut self, p: u32, segment: Option<(u32, u32, u32)>, inside: Option<u32>, edits: &[FacetEdit]) -> bool {
        if let Some((s, a, b)) = segment {
            let seg = &mut self.segments[s as usize];
            let Some(i) = seg.points.windows(2).position(|w| (w[0] == a && w[1] == b) || (w[0] == b && w[1] == a)) else {
                return false;
            };
            seg.points.insert(i + 1, p);
            self.locate_vertex(p, Location::Segment(s));
        } else if let Some(f) = inside {
            self.facets[f as usize].inner.push(p);
            self.locate_vertex(p, Location::Facet(f));
        }
        for (f, removed, added) in edits {
            // the removed ones are the stored ones, turned
            for &r in removed {
                self.remove_turned(*f, r);
            }
            for &t in added {
                self.add_subface(*f, t);
            }
            self.squeeze(*f);
        }
        true
    }

    /// The facet of subface `t` (its vertices in any order), if it is one.
    pub fn facet_of(&self, t: [u32; 3]) -> Option<u32> {
        self.index.get(&sorted(t)).map(|&(f, _)| f)
    }

    /// Every subface with its facet.
    pub fn subfaces(&self) -> impl Iterator<Item = (u32, [u32; 3])> + '_ {
        self.facets.iter().enumerate().flat_map(|(f, fc)| fc.subfaces.iter().map(move |s| (f as u32, s)))
    }

    /// Every subsegment with its segment.
    pub fn all_subsegments(&self) -> impl Iterator<Item = (u32, [u32; 2])> + '_ {
        (0..self.segments.len() as u32).flat_map(move |s| self.subsegments(s).map(move |e| (s, e)))
    }

    /// Number of Steiner points on the boundary.
    pub fn boundary_steiner_points(&self) -> usize {
        self.location.iter().filter(|l| matches!(l, Location::Segment(_) | Location::Facet(_))).count()
    }
}

/// The smallest altitude of a triangle (twice its area over its longest side).
/// Facets of at most this many triangles are strips whose width cuts their sides (a CAD
/// export's faceted cylinder or fillet: two triangles between generators).
const STRIP_TRIANGLES: usize = 4;

/// The distance from `p` to the line through `a` and `b`.
fn distance_to_line(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let d = b - a;
    let l = d.length();
    if l > 0.0 { (p - a).cross(d).length() / l } else { p.distance(a) }
}

fn min_altitude(p: [DVec3; 3]) -> f64 {
    let longest = p[0].distance(p[1]).max(p[1].distance(p[2])).max(p[2].distance(p[0]));
    let area2 = (p[1] - p[0]).cross(p[2] - p[0]).length();
    if longest > 0.0 { area2 / longest } else { f64::INFINITY }
}

/// `t` sorted.
fn sorted(mut t: [u32; 3]) -> [u32; 3] {
    t.sort_unstable();
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deferred_splits_give_the_subfaces_of_immediate_ones() {
        // a square of two triangles, its diagonal and one side split twice each
        let mut points = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)];
        points.extend([DVec3::new(0.5, 0.5, 0.0), DVec3::new(0.25, 0.75, 0.0), DVec3::new(0.5, 0.0, 0.0), DVec3::new(0.75, 0.0, 0.0)]);
        let model = || SurfaceModel::new(&points[..4], &[[0, 1, 2], [1, 3, 2]], &[FaceId(1), FaceId(2)], false);
        let (mut now, mut later) = (model(), model());
        let seg = |m: &SurfaceModel, e: [u32; 2]| m.segments.iter().position(|g| g.points.first() == Some(&e[0]) && g.points.last() == Some(&e[1])).unwrap() as u32;
        let (d, x) = (seg(&now, [1, 2]), seg(&now, [0, 1]));
        for (s, a, b, p) in [(d, 1, 2, 4), (d, 4, 2, 5), (x, 0, 1, 6), (x, 6, 1, 7)] {
            assert!(now.split_segment(s, a, b, p, &points));
            assert!(later.split_segment_deferred(s, a, b, p));
        }
        // stale until flushed: facet 0 still has its one input triangle
        assert_eq!(later.facets[0].subfaces.len(), 1);
        later.flush_facet(1, &points);
        assert_eq!(later.facets[1].subfaces.iter().collect::<Vec<_>>(), now.facets[1].subfaces.iter().collect::<Vec<_>>());
        assert_eq!(later.facets[0].subfaces.len(), 1);
        later.flush(&points);
        for f in 0..2 {
            assert_eq!(later.facets[f].subfaces.iter().collect::<Vec<_>>(), now.facets[f].subfaces.iter().collect::<Vec<_>>(), "facet {f}");
        }
        assert_eq!(later.subfaces().collect::<Vec<_>>(), now.subfaces().collect::<Vec<_>>());
        assert_eq!(now.facets[0].subfaces.len(), 5);
    }

    #[test]
    fn splitting_keeps_facets_tiled() {
        let points = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.5, 0.5, 0.0), DVec3::new(0.3, 0.3, 0.0)];
        let mut m = SurfaceModel::new(&points[..4], &[[0, 1, 2], [1, 3, 2]], &[FaceId(1), FaceId(2)], false);
        assert_eq!(m.segments.len(), 5);
        // split the shared diagonal (1, 2) at its midpoint (vertex 4)
        let s = m.segments.iter().position(|g| g.points == [1, 2]).unwrap() as u32;
        assert_eq!(m.segments[s as usize].facets, [0, 1]);
        assert!(m.split_segment(s, 1, 2, 4, &points));
        assert_eq!(m.facets[0].subfaces.len(), 2);
        assert_eq!(m.facets[1].subfaces.len(), 2);
        m.add_to_facet(0, 5, &points);
        assert_eq!(m.facets[0].subfaces.len(), 4);
        // the subfaces keep the facet's orientation (counter-clockwise about +z)
        for (_, t) in m.subfaces() {
            let [a, b, c] = t.map(|v| points[v as usize]);
            assert!((b - a).cross(c - a).z > 0.0, "{t:?}");
        }
        let area: f64 = m.subfaces().map(|(_, t)| {
            let [a, b, c] = t.map(|v| points[v as usize]);
            0.5 * (b - a).cross(c - a).length()
        }).sum();
        assert!((area - 1.0).abs() < 1e-12);
        assert_eq!(m.boundary_steiner_points(), 2);
    }

    #[test]
    fn coplanar_triangles_with_one_tag_merge() {
        let points = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.5, 0.5, 0.0)];
        let mut m = SurfaceModel::new(&points[..4], &[[0, 1, 2], [1, 3, 2]], &[FaceId(1), FaceId(1)], true);
        // one facet, four sides; the diagonal is no segment any more
        assert_eq!(m.facets.len(), 1);
        assert_eq!(m.segments.len(), 4);
        assert_eq!(m.facets[0].sides.len(), 4);
        assert!(m.inside(0, DVec3::new(0.9, 0.9, 0.0), &points));
        assert!(!m.inside(0, DVec3::new(1.1, 0.5, 0.0), &points));
        m.add_to_facet(0, 4, &points);
        assert_eq!(m.facets[0].subfaces.len(), 4);
        let area: f64 = m.subfaces().map(|(_, t)| {
            let [a, b, c] = t.map(|v| points[v as usize]);
            let n = (b - a).cross(c - a);
            assert!(n.z > 0.0);
            0.5 * n.length()
        }).sum();
        assert!((area - 1.0).abs() < 1e-12);
        // a different tag keeps them apart
        let m = SurfaceModel::new(&points[..4], &[[0, 1, 2], [1, 3, 2]], &[FaceId(1), FaceId(2)], true);
        assert_eq!(m.facets.len(), 2);
        assert_eq!(m.flattening_volume, 0.0);
    }

    #[test]
    fn a_nearly_flat_pair_merges_and_bounds_what_its_diagonal_moves() {
        // the corner (1, 1) lifted so that the two triangles meet at 179.95 degrees
        let lift = 0.05f64.to_radians().tan() * 0.5f64.sqrt();
        let points = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, lift)];
        let m = SurfaceModel::new(&points, &[[0, 1, 2], [1, 3, 2]], &[FaceId(1), FaceId(1)], true);
        assert_eq!(m.facets.len(), 1);
        // flipping the diagonal moves the volume by the tet on the four corners
        let [a, b, c, d] = [0, 1, 2, 3].map(|i: usize| points[i]);
        let moved = (b - a).dot((c - a).cross(d - a)).abs() / 6.0;
        assert!(moved > 0.0 && m.flattening_volume >= moved, "{} < {moved}", m.flattening_volume);
        assert!(m.flattening_volume < 4.0 * lift);
        // exactly flat: nothing moves
        let flat = SurfaceModel::new(&points[..3].iter().copied().chain([DVec3::new(1.0, 1.0, 0.0)]).collect::<Vec<_>>(), &[[0, 1, 2], [1, 3, 2]], &[FaceId(1), FaceId(1)], true);
        assert_eq!(flat.flattening_volume, 0.0);
        // bent by a degree they stay two facets
        let bent = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 20.0 * lift)];
        assert_eq!(SurfaceModel::new(&bent, &[[0, 1, 2], [1, 3, 2]], &[FaceId(1), FaceId(1)], true).facets.len(), 2);
    }
}
