//! Boundary vertices that may slide without leaving the boundary: a vertex whose constrained
//! faces all lie in one plane and belong to one surface (same face tag, same regions on either
//! side) may move in that plane, and a vertex on a straight crease between two such flat
//! surfaces may move along the crease, as Klingner and Shewchuk let their smoothing move
//! vertices on flat boundaries and straight boundary edges ("Aggressive tetrahedral mesh
//! improvement", 2007).
//!
//! The boundary then keeps its shape, the area of every tagged face and the volume of every
//! region (up to rounding): the faces around the vertex stay in their plane, and while every
//! tet of the star stays positively oriented (the smoother checks that exactly) the vertex
//! stays inside the polygon its boundary neighbours span in each plane, so the fans cover the
//! same polygons as before.
//!
//! Flatness is decided with a tolerance far below any real curvature (normals parallel to
//! 1e-9, vertices within 1e-9 of the star's longest edge from the plane): points that were put
//! on a plane by floating-point arithmetic (Steiner points) count as on it, the chords of a
//! tessellated curved face, whose neighbours turn by 1e-4 and more, do not.
//!
//! Where the mesh is given the geometry its boundary approximates (a
//! [`BoundaryGeometry`]: the B-rep of a STEP part), a vertex of one curved face moves in its
//! tangent plane and is put back onto the face, and a vertex on a smooth crease between two
//! faces moves along the crease and is put back onto the CAD edge between them ("sliding
//! on their CAD face and along their CAD edge, never off it"). Its place stays on the CAD
//! geometry; the chords around it change, so the areas and the volume change by what the
//! chords' sag changes. A vertex whose faces turn sharply (a cone's apex, a corner where the
//! crease turns) stays. Flat faces and straight creases slide as above, exactly.

use crate::core::{BoundaryGeometry, FaceId, RegionId};
use crate::core::ids::NONE;
use crate::mesh::TetMesh;
use crate::mesh::tet_mesh::{TET_FACES, sorted3};
use crate::mesh3d::optimize::vertex_slide::{Fan, Slide};
use crate::mesh3d::optimize::work::Work;
use glam::DVec3;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

/// Normals this close to parallel (the sine of their angle), and vertices this close to the
/// plane (relative to the longest edge of the faces at the vertex), count as flat.
const FLAT: f64 = 1e-9;

/// A curved surface's faces at a sliding vertex turn at most this far from their mean normal,
/// and a curved crease turns at most this far at the vertex (the cosine of 30°): beyond that
/// the vertex is a feature of the tessellation (a cone's apex, a corner of the crease) and
/// stays.
const SMOOTH_COS: f64 = 0.866;

/// Where a vertex that smoothing or the search moves may go: along its slide, if it has one,
/// and, on a curved face or edge, only where its boundary triangles keep their shape
/// ([`Fan::keeps`]).
#[derive(Copy, Clone)]
pub(crate) struct Mover<'a> {
    slide: Option<Slide>,
    fan: Option<(&'a Fan, (f64, f64))>,
}

impl<'a> Mover<'a> {
    /// A vertex that moves freely.
    pub(crate) fn free() -> Mover<'static> {
        Mover { slide: None, fan: None }
    }

    /// Vertex `v` of `w`, now at `x0` (its slide prepared by [`prepare`]).
    pub(crate) fn of(w: &'a Work, v: u32, x0: DVec3) -> Self {
        Mover { slide: w.slide[v as usize], fan: w.fans.get(&v).map(|fan| (fan, fan.bounds(&w.pts, x0))) }
    }

    /// The part of direction `g` along which the vertex may move.
    #[inline]
    pub(crate) fn project(&self, g: DVec3) -> DVec3 {
        self.slide.map_or(g, |s| s.project(g))
    }

    /// Where the vertex, now at `from`, goes when moved to `x` ([`Slide::snap`]), if its
    /// boundary triangles allow it there.
    #[inline]
    pub(crate) fn place(&self, w: &Work, from: DVec3, x: DVec3) -> Option<DVec3> {
        let y = match self.slide {
            None => x,
            Some(s) => s.snap(from, x, w.geo)?,
        };
        self.fan.is_none_or(|(fan, bounds)| fan.keeps(&w.pts, y, bounds)).then_some(y)
    }
}

/// Asks the geometry once where the slide of vertex `v` starts its searches
/// ([`Slide::prepare`]).
pub(crate) fn prepare(w: &mut Work, v: u32) {
    let geo = w.geo;
    if let Some(s) = w.slide[v as usize].as_mut() {
        s.prepare(geo);
    }
}

/// A constrained face: its vertices (outward from the tet it was read from), the surface it
/// belongs to (face tag and the regions on either side) and its unit normal.
struct Face {
    v: [u32; 3],
    key: (u32, RegionId, RegionId),
    /// Its boundary triangle's tag, if it is one.
    tag: Option<u32>,
    /// Its normal times twice its area.
    area_n: DVec3,
    n: DVec3,
}

/// The slide of every vertex of `w` (built from `mesh`): `None` for vertices that are free
/// (no constrained face) or must stay (a corner, a tag-crossing neighbourhood, a curved one
/// without `geo` or turning sharply, a vertex of a boundary triangle tagged `pinned`).
pub(crate) fn slides(mesh: &TetMesh, w: &Work, pinned: &[FaceId], geo: Option<&dyn BoundaryGeometry>) -> (Vec<Option<Slide>>, FxHashMap<u32, Fan>) {
    let nv = w.pts.len();
    let tag_of: FxHashMap<[u32; 3], u32> = mesh.boundary.iter().zip(&mesh.face_tags).map(|(t, g)| (sorted3(*t).0, g.0)).collect();
    // every constrained face once (an interface face is seen from both of its tets: from the
    // first of them)
    let seen_before = |t: usize, other: u32| {
        let (o, g) = ((other >> 2) as usize, other & 3);
        other != NONE && o < t && w.tets[o][0] != NONE && w.cons[o] >> g & 1 != 0
    };
    let mut faces: Vec<Face> = Vec::new();
    for (t, tet) in w.tets.iter().enumerate() {
        if w.cons[t] == 0 || tet[0] == NONE {
            continue;
        }
        for (k, f) in TET_FACES.iter().enumerate() {
            if w.cons[t] >> k & 1 == 0 || seen_before(t, w.nbr[t][k]) {
                continue;
            }
            let v = f.map(|i| tet[i]);
            let key = sorted3(v).0;
            let other = w.nbr[t][k];
            let r0 = w.region[t];
            let r1 = if other == NONE { RegionId(NONE) } else { w.region[(other >> 2) as usize] };
            let (ra, rb) = if r0.0 <= r1.0 { (r0, r1) } else { (r1, r0) };
            let [a, b, c] = v.map(|i| w.pts[i as usize]);
            let area_n = (b - a).cross(c - a);
            let tag = tag_of.get(&key).copied();
            faces.push(Face { v, key: (tag.unwrap_or(0), ra, rb), tag, area_n, n: area_n.normalize_or_zero() });
        }
    }
    // faces by vertex (counting sort)
    let mut start = vec![0usize; nv + 1];
    for f in &faces {
        for &x in &f.v {
            start[x as usize + 1] += 1;
        }
    }
    for i in 0..nv {
        start[i + 1] += start[i];
    }
    let mut at = vec![0u32; start[nv]];
    let mut fill = start.clone();
    for (i, f) in faces.iter().enumerate() {
        for &x in &f.v {
            at[fill[x as usize]] = i as u32;
            fill[x as usize] += 1;
        }
    }
    let mut stays = vec![false; nv];
    for (f, tag) in mesh.boundary.iter().zip(&mesh.face_tags) {
        if pinned.contains(tag) {
            for &x in f {
                if let Some(s) = stays.get_mut(x as usize) {
                    *s = true;
                }
            }
        }
    }
    // each vertex's slide from its own faces alone: in parallel
    let curved = geo.is_some();
    let found: Vec<(Option<Slide>, Option<Fan>)> = (0..nv)
        .into_par_iter()
        .with_min_len(1024)
        .map(|v| {
            if stays[v] || start[v] == start[v + 1] {
                return (None, None);
            }
            let mine: Vec<&Face> = at[start[v]..start[v + 1]].iter().map(|&i| &faces[i as usize]).collect();
            let flat = slide_of(v as u32, &mine, &w.pts);
            if flat.is_some() || !curved {
                return (flat, None);
            }
            let bent = curved_slide_of(v as u32, &mine, &w.pts);
            let fan = bent.is_some().then(|| {
                let pairs = mine.iter().map(|f| {
                    let k = f.v.iter().position(|&x| x == v as u32).unwrap_or(0);
                    [f.v[(k + 1) % 3], f.v[(k + 2) % 3]]
                });
                Fan { pairs: pairs.collect() }
            });
            (bent, fan)
        })
        .collect();
    let mut fans = FxHashMap::default();
    let out = found
        .into_iter()
        .enumerate()
        .map(|(v, (slide, fan))| {
            if let Some(fan) = fan {
                fans.insert(v as u32, fan);
            }
            slide
        })
        .collect();
    (out, fans)
}

/// The slide of vertex `v` whose constrained faces are `faces`, if it has one.
fn slide_of(v: u32, faces: &[&Face], pts: &[DVec3]) -> Option<Slide> {
    let p = pts[v as usize];
    let longest = faces
        .iter()
        .flat_map(|f| [0, 1, 2].map(|k| pts[f.v[k] as usize].distance(pts[f.v[(k + 1) % 3] as usize])))
        .fold(0.0f64, f64::max);
    if !(longest > 0.0) || !p.is_finite() {
        return None;
    }
    // the flat surfaces at v: faces of one key with parallel normals (they share v, so they
    // lie in one plane); at most two
    let mut normals: Vec<((u32, RegionId, RegionId), DVec3)> = Vec::with_capacity(2);
    let mut group = vec![0usize; faces.len()];
    for (i, f) in faces.iter().enumerate() {
        if f.n == DVec3::ZERO {
            return None;
        }
        let g = match normals.iter().position(|(k, n)| *k == f.key && f.n.cross(*n).length() <= FLAT && f.n.dot(*n) > 0.0) {
            Some(g) => g,
            None => {
                if normals.len() == 2 {
                    return None;
                }
                normals.push((f.key, f.n));
                normals.len() - 1
            }
        };
        group[i] = g;
        if f.v.iter().any(|&x| (pts[x as usize] - p).dot(normals[g].1).abs() > FLAT * longest) {
            return None;
        }
    }
    let creases = creases(v, faces, &group, normals.len())?;
    match (normals.len(), creases.len()) {
        (1, 0) => Some(Slide::Plane { at: p, n: normals[0].1 }),
        (2, 2) => {
            let (a, b) = (pts[creases[0] as usize] - p, pts[creases[1] as usize] - p);
            if a.cross(b).length() > FLAT * a.length() * b.length() || a.dot(b) >= 0.0 {
                return None;
            }
            let dir = (b - a).normalize_or_zero();
            (dir != DVec3::ZERO).then_some(Slide::Line { at: p, dir })
        }
        _ => None,
    }
}

/// The slide of vertex `v` on a curved face or along a curved crease (its constrained faces
/// `faces`), if it has one: the faces of at most two tagged surfaces, each one fan, each
/// turning less than [`SMOOTH_COS`] from its mean normal; on two, the crease between them
/// through `v` turning less than that too.
fn curved_slide_of(v: u32, faces: &[&Face], pts: &[DVec3]) -> Option<Slide> {
    let p = pts[v as usize];
    // the surfaces at v, by key
    let mut keys: Vec<(u32, RegionId, RegionId)> = Vec::with_capacity(2);
    let mut group = vec![0usize; faces.len()];
    for (i, f) in faces.iter().enumerate() {
        f.tag?;
        group[i] = match keys.iter().position(|k| *k == f.key) {
            Some(g) => g,
            None => {
                if keys.len() == 2 {
                    return None;
                }
                keys.push(f.key);
                keys.len() - 1
            }
        };
    }
    // each surface's mean normal, and every face near it
    let mut mean = [DVec3::ZERO; 2];
    for (i, f) in faces.iter().enumerate() {
        mean[group[i]] += f.area_n;
    }
    let mean = mean.map(|m| m.normalize_or_zero());
    for (i, f) in faces.iter().enumerate() {
        if !(f.n.dot(mean[group[i]]) >= SMOOTH_COS) {
            return None;
        }
    }
    let creases = creases(v, faces, &group, keys.len())?;
    let face = |g: usize| FaceId(keys[g].0);
    match (keys.len(), creases.len()) {
        (1, 0) => (mean[0] != DVec3::ZERO).then_some(Slide::Surface { at: p, n: mean[0], face: face(0), hint: None, hinted: false }),
        (2, 2) => {
            let (a, b) = (pts[creases[0] as usize], pts[creases[1] as usize]);
            let (into, out) = ((p - a).normalize_or_zero(), (b - p).normalize_or_zero());
            if !(into.dot(out) >= SMOOTH_COS) {
                return None;
            }
            let dir = (b - a).normalize_or_zero();
            (dir != DVec3::ZERO && face(0) != face(1)).then_some(Slide::Curve { at: p, dir, faces: [face(0), face(1)], hint: None, hinted: false })
        }
        _ => None,
    }
}

/// The creases at vertex `v` between the `groups` surfaces its constrained `faces` belong to
/// (`group` of each face), as their other vertices, sorted: `None` unless the faces make a
/// manifold fan around `v` (each edge at `v` in exactly two of them) and each surface's part
/// of it is connected across the edges that are no crease.
fn creases(v: u32, faces: &[&Face], group: &[usize], groups: usize) -> Option<Vec<u32>> {
    let mut edges: FxHashMap<u32, (usize, [usize; 2])> = FxHashMap::default();
    for (i, f) in faces.iter().enumerate() {
        for &x in &f.v {
            if x != v {
                let e = edges.entry(x).or_insert((0, [usize::MAX; 2]));
                if e.0 < 2 {
                    e.1[e.0] = i;
                }
                e.0 += 1;
            }
        }
    }
    if edges.values().any(|e| e.0 != 2) {
        return None;
    }
    let mut creases: Vec<u32> = edges.iter().filter(|(_, e)| group[e.1[0]] != group[e.1[1]]).map(|(&x, _)| x).collect();
    creases.sort_unstable();
    let mut uf = crate::core::union_find::UnionFind::new(faces.len());
    for e in edges.values() {
        if group[e.1[0]] == group[e.1[1]] {
            uf.union(e.1[0] as u32, e.1[1] as u32);
        }
    }
    for g in 0..groups {
        let mut roots = (0..faces.len()).filter(|&i| group[i] == g).map(|i| uf.find(i as u32));
        let first = roots.next()?;
        if roots.any(|r| r != first) {
            return None;
        }
    }
    Some(creases)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes::{kuhn_cube, side_tag, tag_hull};
    use crate::mesh3d::optimize::measure::Targets;
    use crate::mesh3d::optimize::smooth::Smoother;

    /// A `n × n × n` Kuhn cube with its hull faces as boundary, tagged by `tag(normal, centroid)`.
    fn cube(n: usize, tag: impl Fn(DVec3, DVec3) -> u32) -> TetMesh {
        let mut m = kuhn_cube(n, 0.0, 1);
        tag_hull(&mut m, tag);
        m
    }

    /// One tag per side of the cube.
    fn by_side(n: DVec3, _: DVec3) -> u32 {
        side_tag(n)
    }

    fn vertex(m: &TetMesh, p: DVec3) -> usize {
        m.vertices.iter().position(|q| q.distance(p) < 1e-12).unwrap()
    }

    fn slides_of(m: &TetMesh) -> Vec<Option<Slide>> {
        let w = Work::build(m, Targets::new(18.0, 160.0)).unwrap();
        slides(m, &w, &[], None).0
    }

    #[test]
    fn faces_slide_in_their_plane_edges_along_their_line_corners_stay() {
        let m = cube(2, by_side);
        let s = slides_of(&m);
        // a corner stays, the centre is free (no constrained face: no slide)
        assert_eq!(s[vertex(&m, DVec3::ZERO)], None);
        assert_eq!(s[vertex(&m, DVec3::splat(0.5))], None);
        // the middle of a side slides in it
        match s[vertex(&m, DVec3::new(0.5, 0.5, 0.0))] {
            Some(Slide::Plane { n, .. }) => assert!((n.abs() - DVec3::Z).length() < 1e-12, "{n}"),
            other => panic!("{other:?}"),
        }
        // the middle of an edge slides along it
        match s[vertex(&m, DVec3::new(0.5, 0.0, 0.0))] {
            Some(Slide::Line { dir, .. }) => assert!((dir.abs() - DVec3::X).length() < 1e-12, "{dir}"),
            other => panic!("{other:?}"),
        }
        // one tag for the whole surface: the creases are still the planes' meeting lines
        let one = cube(2, |_, _| 1);
        let s1 = slides_of(&one);
        assert!(matches!(s1[vertex(&one, DVec3::new(0.5, 0.0, 0.0))], Some(Slide::Line { .. })));
        assert!(matches!(s1[vertex(&one, DVec3::new(0.0, 0.5, 0.5))], Some(Slide::Plane { .. })));
    }

    #[test]
    fn tags_within_a_plane_are_kept() {
        // the bottom split into two tags along y = 0.5: the centre of the bottom slides along
        // that line only
        let m = cube(2, |n, c| if n.z < -0.5 { if c.y < 0.5 { 10 } else { 11 } } else { by_side(n, c) });
        let s = slides_of(&m);
        match s[vertex(&m, DVec3::new(0.5, 0.5, 0.0))] {
            Some(Slide::Line { dir, .. }) => assert!((dir.abs() - DVec3::X).length() < 1e-12, "{dir}"),
            other => panic!("{other:?}"),
        }
        // four tags meeting at the centre of the bottom: it stays
        let m = cube(2, |n, c| if n.z < -0.5 { 20 + u32::from(c.x < 0.5) + 2 * u32::from(c.y < 0.5) } else { by_side(n, c) });
        assert_eq!(slides_of(&m)[vertex(&m, DVec3::new(0.5, 0.5, 0.0))], None);
    }

    #[test]
    fn a_curved_neighbourhood_stays() {
        // the middle of the bottom raised by a thousandth: neither it nor its neighbours on the
        // bottom are flat any more
        let mut m = cube(2, by_side);
        let c = vertex(&m, DVec3::new(0.5, 0.5, 0.0));
        m.vertices[c].z = 1e-3;
        let s = slides_of(&m);
        assert_eq!(s[c], None);
        assert_eq!(s[vertex(&m, DVec3::new(0.5, 0.0, 0.0))], None);
        // the other sides' centres still slide
        assert!(matches!(s[vertex(&m, DVec3::new(0.5, 0.5, 1.0))], Some(Slide::Plane { .. })));
    }

    #[test]
    fn a_sliding_vertex_stays_in_its_plane_and_keeps_areas_and_volume() {
        // the middle of the bottom pulled towards a corner: its tets are poor; it slides back
        // within z = 0, the bottom's area and the volume unchanged
        let mut m = cube(2, by_side);
        let c = vertex(&m, DVec3::new(0.5, 0.5, 0.0));
        m.vertices[c] = DVec3::new(0.12, 0.1, 0.0);
        assert_eq!(m.validate(), Ok(()));
        let (v0, a0) = (m.volume(), tag_areas(&m));
        let mut w = Work::build(&m, Targets::new(30.0, 130.0)).unwrap();
        let mut sm = Smoother::default();
        // fixed without slides
        assert!(!sm.try_smooth(&mut w, c as u32, 2.0));
        w.slide = slides(&m, &w, &[], None).0;
        let mut star = Vec::new();
        w.star(c as u32, &mut star);
        let before = star.iter().map(|&t| w.q[t as usize]).fold(f64::INFINITY, f64::min);
        assert!(sm.try_smooth(&mut w, c as u32, 2.0));
        let after = star.iter().map(|&t| w.q[t as usize]).fold(f64::INFINITY, f64::min);
        assert!(after > before + 0.1, "{before} -> {after}");
        let mut out = m.clone();
        w.write_back(&mut out);
        assert_eq!(out.validate(), Ok(()));
        assert_eq!(out.vertices[c].z, 0.0);
        assert!(out.vertices[c].distance(DVec3::new(0.12, 0.1, 0.0)) > 0.05);
        assert!((out.volume() - v0).abs() < 1e-14);
        for (x, y) in tag_areas(&out).iter().zip(&a0) {
            assert!((x - y).abs() < 1e-14, "{x} {y}");
        }
    }

    /// The cube's bottom (tag 5) bent onto a sphere of radius `r` whose centre lies under the
    /// cube's middle, the bottom's middle touching z = 0 (each vertex lifted straight up or
    /// down): a curved face, and curved creases with the sides y = 0 and y = 1 (tags 3 and 4),
    /// which stay planes.
    struct Dome {
        r: f64,
    }

    impl Dome {
        fn centre(&self) -> DVec3 {
            DVec3::new(0.5, 0.5, -self.r)
        }

        /// The point of the sphere nearest `p`.
        fn onto(&self, p: DVec3) -> DVec3 {
            self.centre() + (p - self.centre()).normalize() * self.r
        }

        /// The point of the sphere over `(x, y)`.
        fn lift(&self, x: f64, y: f64) -> DVec3 {
            let (dx, dy) = (x - 0.5, y - 0.5);
            DVec3::new(x, y, -self.r + (self.r * self.r - dx * dx - dy * dy).sqrt())
        }

        fn off(&self, p: DVec3) -> f64 {
            ((p - self.centre()).length() - self.r).abs()
        }

        fn bent(&self, n: usize) -> TetMesh {
            let mut m = cube(n, by_side);
            for p in &mut m.vertices {
                if p.z == 0.0 {
                    *p = self.lift(p.x, p.y);
                }
            }
            m
        }
    }

    impl BoundaryGeometry for Dome {
        fn on_face(&self, face: FaceId, _: DVec3, _: DVec3, p: DVec3) -> Option<DVec3> {
            (face == FaceId(5)).then(|| self.onto(p))
        }

        fn on_edge(&self, f: FaceId, g: FaceId, _: DVec3, _: DVec3, p: DVec3) -> Option<DVec3> {
            let side = if f == FaceId(5) { g } else { f };
            let y = match side.0 {
                3 => 0.0,
                4 => 1.0,
                _ => return None,
            };
            // the circle where the sphere meets the side's plane
            let c = DVec3::new(0.5, y, -self.r);
            let rho = (self.r * self.r - 0.25).sqrt();
            (f == FaceId(5) || g == FaceId(5)).then(|| c + DVec3::new(p.x - c.x, 0.0, p.z - c.z).normalize() * rho)
        }
    }

    #[test]
    fn with_the_geometry_curved_faces_and_creases_slide_and_corners_stay() {
        let dome = Dome { r: 2.0 };
        let m = dome.bent(4);
        let w = Work::build(&m, Targets::new(18.0, 160.0)).unwrap();
        let with = slides(&m, &w, &[], Some(&dome)).0;
        let without = slides(&m, &w, &[], None).0;
        let at = |x: f64, y: f64| vertex(&m, dome.lift(x, y));
        // the bottom's vertices: on the face, on the crease with y = 0, at the corner
        assert!(matches!(with[at(0.5, 0.5)], Some(Slide::Surface { face: FaceId(5), .. })), "{:?}", with[at(0.5, 0.5)]);
        match with[at(0.5, 0.0)] {
            Some(Slide::Curve { dir, faces, .. }) => {
                assert!((dir.abs() - DVec3::X).length() < 1e-12, "{dir}");
                assert!(faces.contains(&FaceId(5)) && faces.contains(&FaceId(3)), "{faces:?}");
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(with[at(0.0, 0.0)], None);
        // the crease with the side x = 0 slides too, though this geometry has no edge there
        // to put it on (so it will not move)
        assert!(matches!(with[at(0.0, 0.5)], Some(Slide::Curve { .. })));
        // without the geometry none of them slides; the flat sides still do
        for (x, y) in [(0.5, 0.5), (0.5, 0.0), (0.0, 0.0)] {
            assert_eq!(without[at(x, y)], None);
        }
        assert_eq!(with[vertex(&m, DVec3::new(0.5, 0.5, 1.0))], without[vertex(&m, DVec3::new(0.5, 0.5, 1.0))]);
        assert!(matches!(with[vertex(&m, DVec3::new(0.5, 0.5, 1.0))], Some(Slide::Plane { .. })));
    }

    /// Smooths vertex `c` of `m` against the geometry: the star's least score before and after,
    /// and the mesh written back.
    fn smooth_on(m: &TetMesh, c: usize, geo: Option<&dyn BoundaryGeometry>) -> (f64, f64, TetMesh) {
        let mut w = Work::build(m, Targets::new(30.0, 130.0)).unwrap();
        (w.slide, w.fans) = slides(m, &w, &[], geo);
        w.geo = geo;
        let mut star = Vec::new();
        w.star(c as u32, &mut star);
        let least = |w: &Work| star.iter().map(|&t| w.q[t as usize]).fold(f64::INFINITY, f64::min);
        let before = least(&w);
        Smoother::default().try_smooth(&mut w, c as u32, 2.0);
        let after = least(&w);
        let mut out = m.clone();
        w.write_back(&mut out);
        assert_eq!(out.validate(), Ok(()));
        (before, after, out)
    }

    #[test]
    fn a_vertex_on_a_curved_face_or_crease_slides_on_it_and_stays_on_it() {
        let dome = Dome { r: 2.0 };
        for ((x, y), (px, py)) in [((0.5, 0.5), (0.62, 0.6)), ((0.5, 0.0), (0.6, 0.0))] {
            let mut m = dome.bent(4);
            let home = dome.lift(x, y);
            let c = vertex(&m, home);
            m.vertices[c] = dome.lift(px, py);
            assert_eq!(m.validate(), Ok(()));
            // without the geometry it stays where it is
            let (b0, a0, out0) = smooth_on(&m, c, None);
            assert_eq!(out0.vertices[c], m.vertices[c]);
            assert_eq!(a0, b0);
            // with it, it moves back towards home, on the sphere (and on y = 0 on the crease)
            let (b1, a1, out1) = smooth_on(&m, c, Some(&dome));
            let p = out1.vertices[c];
            assert!(a1 > b1 + 0.1, "{b1} -> {a1}");
            assert!(dome.off(p) < 1e-12, "{p}");
            assert!(p.distance(home) < 0.5 * m.vertices[c].distance(home), "{p}");
            if y == 0.0 {
                assert_eq!(p.y, 0.0);
            }
            // the volume changes by what the chords' sag changes: little
            assert!((out1.volume() - m.volume()).abs() < 1e-3, "{} {}", out1.volume(), m.volume());
        }
    }

    #[test]
    fn the_fan_guard_refuses_needles_and_caps_but_not_what_was_there() {
        // a vertex at the centre of a square fan of four triangles (right angles and 45°)
        let pts = vec![DVec3::ZERO, DVec3::X, DVec3::Y, -DVec3::X, -DVec3::Y];
        let fan = Fan { pairs: vec![[1, 2], [2, 3], [3, 4], [4, 1]] };
        let bounds = fan.bounds(&pts, pts[0]);
        assert!(fan.keeps(&pts, DVec3::new(0.1, 0.05, 0.0), bounds));
        // towards the side (1, 2): a cap, its angle at the vertex over 120°
        assert!(!fan.keeps(&pts, DVec3::new(0.45, 0.45, 0.0), bounds));
        // onto a corner's diagonal near it: needles under 20°
        assert!(!fan.keeps(&pts, DVec3::new(0.9, 0.0, 0.0), bounds));
        // a fan with a needle and a cap (11° and 174° at the vertex) keeps them, no worse
        let thin = vec![DVec3::ZERO, DVec3::new(1.0, 0.1, 0.0), DVec3::new(1.0, -0.1, 0.0), DVec3::new(-1.0, 0.0, 0.0)];
        let fan = Fan { pairs: vec![[1, 2], [2, 3], [3, 1]] };
        let bounds = fan.bounds(&thin, thin[0]);
        assert!(fan.keeps(&thin, thin[0], bounds));
        assert!(fan.keeps(&thin, DVec3::new(0.05, 0.0, 0.0), bounds));
        assert!(!fan.keeps(&thin, DVec3::new(-0.5, 0.0, 0.0), bounds));
    }

    /// Area per tag 1..=6.
    fn tag_areas(m: &TetMesh) -> Vec<f64> {
        let mut a = vec![0.0; 7];
        for (f, t) in m.boundary.iter().zip(&m.face_tags) {
            let [p, q, r] = f.map(|v| m.vertices[v as usize]);
            a[t.0 as usize] += 0.5 * (q - p).cross(r - p).length();
        }
        a
    }
}
