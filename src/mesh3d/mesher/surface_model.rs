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
use glam::{DVec2, DVec3};
use rustc_hash::FxHashMap;
use spade::{DelaunayTriangulation, Point2, Triangulation};

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

/// An input triangle.
#[derive(Clone, Debug)]
pub(crate) struct Facet {
    /// Its three corners (input vertex ids), as given.
    pub corners: [u32; 3],
    /// Its tag.
    pub tag: FaceId,
    /// Its three sides as segment ids: side `i` joins corners `i` and `i + 1`.
    pub sides: [u32; 3],
    /// Steiner points strictly inside it.
    pub inner: Vec<u32>,
    /// Current subfaces, oriented like the facet.
    pub subfaces: Vec<[u32; 3]>,
}

/// An input edge.
#[derive(Clone, Debug)]
pub(crate) struct Segment {
    /// Its endpoints and Steiner points, in order from one end to the other.
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
    /// The facet of every current subface, by its sorted vertices.
    index: FxHashMap<[u32; 3], u32>,
}

impl SurfaceModel {
    /// The model of `triangles` (vertex indices below `n`) with their tags.
    pub fn new(n: usize, triangles: &[[u32; 3]], tags: &[FaceId]) -> Self {
        let mut seg_of: FxHashMap<(u32, u32), u32> = FxHashMap::default();
        let mut segments: Vec<Segment> = Vec::new();
        let mut facets = Vec::with_capacity(triangles.len());
        for (i, (t, &tag)) in triangles.iter().zip(tags).enumerate() {
            let mut sides = [0u32; 3];
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let key = (a.min(b), a.max(b));
                let s = *seg_of.entry(key).or_insert_with(|| {
                    segments.push(Segment { points: vec![key.0, key.1], facets: Vec::new() });
                    (segments.len() - 1) as u32
                });
                segments[s as usize].facets.push(i as u32);
                sides[k] = s;
            }
            facets.push(Facet { corners: *t, tag, sides, inner: Vec::new(), subfaces: vec![*t] });
        }
        let mut index = FxHashMap::default();
        for (i, t) in triangles.iter().enumerate() {
            index.insert(sorted(*t), i as u32);
        }
        SurfaceModel { facets, segments, location: vec![Location::Input; n], index }
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
    pub fn split_segment(&mut self, s: u32, a: u32, b: u32, p: u32, points: &[DVec3]) -> bool {
        let seg = &mut self.segments[s as usize];
        let Some(i) = seg.points.windows(2).position(|w| (w[0] == a && w[1] == b) || (w[0] == b && w[1] == a)) else {
            return false;
        };
        seg.points.insert(i + 1, p);
        self.locate_vertex(p, Location::Segment(s));
        for f in self.segments[s as usize].facets.clone() {
            self.retriangulate(f, points);
        }
        true
    }

    /// Inserts vertex `p` inside facet `f` and re-triangulates it.
    pub fn add_to_facet(&mut self, f: u32, p: u32, points: &[DVec3]) {
        self.facets[f as usize].inner.push(p);
        self.locate_vertex(p, Location::Facet(f));
        self.retriangulate(f, points);
    }

    /// All points of facet `f`: its sides' points and its inner points, each once, with
    /// for every side point the side it lies on (corners on two sides: reported with one).
    fn facet_points(&self, f: u32) -> Vec<(u32, Option<u8>)> {
        let fc = &self.facets[f as usize];
        let mut out: Vec<(u32, Option<u8>)> = Vec::new();
        for (k, &s) in fc.sides.iter().enumerate() {
            for &v in &self.segments[s as usize].points {
                if !out.iter().any(|e| e.0 == v) {
                    out.push((v, Some(k as u8)));
                }
            }
        }
        out.extend(fc.inner.iter().map(|&v| (v, None)));
        out
    }

    /// Recomputes the subfaces of facet `f`: the 2D Delaunay triangulation of its points in
    /// its plane, without the slivers whose three points lie on one side.
    pub fn retriangulate(&mut self, f: u32, points: &[DVec3]) {
        let fc = &self.facets[f as usize];
        let [a, b, c] = fc.corners.map(|v| points[v as usize]);
        let normal = (b - a).cross(c - a);
        let e1 = (b - a).normalize_or_zero();
        let e2 = normal.normalize_or_zero().cross(e1);
        let pts = self.facet_points(f);
        let side_sets: [Vec<u32>; 3] = fc.sides.map(|s| self.segments[s as usize].points.clone());
        let on_side = |v: u32| -> u8 { (0..3).filter(|&k| side_sets[k].contains(&v)).fold(0u8, |m, k| m | 1 << k) };
        let mut dt: DelaunayTriangulation<Point2<f64>> = DelaunayTriangulation::new();
        let mut ids: Vec<u32> = Vec::with_capacity(pts.len());
        for &(v, _) in &pts {
            let d = points[v as usize] - a;
            let q = DVec2::new(d.dot(e1), d.dot(e2));
            match dt.insert(Point2::new(q.x, q.y)) {
                Ok(h) => {
                    if h.index() == ids.len() {
                        ids.push(v);
                    }
                }
                Err(_) => return, // non-finite: keep the previous subfaces
            }
        }
        let mut subfaces = Vec::with_capacity(2 * pts.len());
        for face in dt.inner_faces() {
            let [p, q, r] = face.vertices().map(|h| ids[h.fix().index()]);
            // a sliver along one side (points of one segment only) is outside the facet
            if on_side(p) & on_side(q) & on_side(r) != 0 {
                continue;
            }
            // spade's faces turn counter-clockwise in (e1, e2), i.e. like the facet
            subfaces.push([p, q, r]);
        }
        if !subfaces.is_empty() {
            for old in std::mem::take(&mut self.facets[f as usize].subfaces) {
                self.index.remove(&sorted(old));
            }
            for &t in &subfaces {
                self.index.insert(sorted(t), f);
            }
            self.facets[f as usize].subfaces = subfaces;
        }
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
            let old = std::mem::take(&mut self.facets[f as usize].subfaces);
            let mut new = Vec::with_capacity(old.len());
            for t in old {
                if !t.contains(&v) {
                    new.push(t);
                    continue;
                }
                self.index.remove(&sorted(t));
                if t.contains(&w) {
                    continue;
                }
                let u = t.map(|x| if x == v { w } else { x });
                self.index.insert(sorted(u), f);
                new.push(u);
            }
            self.facets[f as usize].subfaces = new;
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
                for t in &self.facets[*f as usize].subfaces {
                    if t.contains(&v) {
                        for &x in t {
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

    /// Every subface with its facet.
    pub fn subfaces(&self) -> impl Iterator<Item = (u32, [u32; 3])> + '_ {
        self.facets.iter().enumerate().flat_map(|(f, fc)| fc.subfaces.iter().map(move |s| (f as u32, *s)))
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

/// `t` sorted.
fn sorted(mut t: [u32; 3]) -> [u32; 3] {
    t.sort_unstable();
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitting_keeps_facets_tiled() {
        let points = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.5, 0.5, 0.0), DVec3::new(0.3, 0.3, 0.0)];
        let mut m = SurfaceModel::new(4, &[[0, 1, 2], [1, 3, 2]], &[FaceId(1), FaceId(2)]);
        assert_eq!(m.segments.len(), 5);
        // split the shared diagonal (1, 2) at its midpoint (vertex 4)
        let s = m.facets[0].sides[1];
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
}
