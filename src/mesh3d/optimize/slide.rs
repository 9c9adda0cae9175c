//! Boundary vertices that may slide without changing the boundary: a vertex whose constrained
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

use crate::core::{FaceId, RegionId};
use crate::core::ids::NONE;
use crate::mesh::TetMesh;
use crate::mesh::tet_mesh::{TET_FACES, sorted3};
use crate::mesh3d::optimize::work::Work;
use glam::DVec3;
use rustc_hash::{FxHashMap, FxHashSet};

/// Normals this close to parallel (the sine of their angle), and vertices this close to the
/// plane (relative to the longest edge of the faces at the vertex), count as flat.
const FLAT: f64 = 1e-9;

/// How a boundary vertex may move.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) enum Slide {
    /// In the plane through `at` with unit normal `n`.
    Plane { at: DVec3, n: DVec3 },
    /// Along the line through `at` with unit direction `dir`.
    Line { at: DVec3, dir: DVec3 },
}

impl Slide {
    /// The part of direction `g` along which the vertex may move.
    #[inline]
    pub(crate) fn project(&self, g: DVec3) -> DVec3 {
        match *self {
            Slide::Plane { n, .. } => g - n * n.dot(g),
            Slide::Line { dir, .. } => dir * dir.dot(g),
        }
    }

    /// The point of the plane or line nearest `x`.
    #[inline]
    pub(crate) fn snap(&self, x: DVec3) -> DVec3 {
        match *self {
            Slide::Plane { at, n } => x - n * n.dot(x - at),
            Slide::Line { at, dir } => at + dir * dir.dot(x - at),
        }
    }
}

/// A constrained face: its vertices (outward from the tet it was read from), the surface it
/// belongs to (face tag and the regions on either side) and its unit normal.
struct Face {
    v: [u32; 3],
    key: (u32, RegionId, RegionId),
    n: DVec3,
}

/// The slide of every vertex of `w` (built from `mesh`): `None` for vertices that are free
/// (no constrained face) or must stay (a corner, a curved or tag-crossing neighbourhood, a
/// vertex of a boundary triangle tagged `pinned`).
pub(crate) fn slides(mesh: &TetMesh, w: &Work, pinned: &[FaceId]) -> Vec<Option<Slide>> {
    let nv = w.pts.len();
    let mut out = vec![None; nv];
    let tag_of: FxHashMap<[u32; 3], u32> = mesh.boundary.iter().zip(&mesh.face_tags).map(|(t, g)| (sorted3(*t).0, g.0)).collect();
    // every constrained face once (an interface face is seen from both of its tets)
    let mut seen: FxHashSet<[u32; 3]> = FxHashSet::default();
    let mut faces: Vec<Face> = Vec::new();
    for (t, tet) in w.tets.iter().enumerate() {
        if w.cons[t] == 0 || tet[0] == NONE {
            continue;
        }
        for (k, f) in TET_FACES.iter().enumerate() {
            if w.cons[t] >> k & 1 == 0 {
                continue;
            }
            let v = f.map(|i| tet[i]);
            let key = sorted3(v).0;
            if !seen.insert(key) {
                continue;
            }
            let other = w.nbr[t][k];
            let r0 = w.region[t];
            let r1 = if other == NONE { RegionId(u32::MAX) } else { w.region[(other >> 2) as usize] };
            let (ra, rb) = if r0.0 <= r1.0 { (r0, r1) } else { (r1, r0) };
            let [a, b, c] = v.map(|i| w.pts[i as usize]);
            let n = (b - a).cross(c - a).normalize_or_zero();
            faces.push(Face { v, key: (tag_of.get(&key).copied().unwrap_or(0), ra, rb), n });
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
    for v in 0..nv {
        if stays[v] {
            continue;
        }
        let mine: Vec<&Face> = at[start[v]..start[v + 1]].iter().map(|&i| &faces[i as usize]).collect();
        if !mine.is_empty() {
            out[v] = slide_of(v as u32, &mine, &w.pts);
        }
    }
    out
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
    // the edges at v: each in exactly two faces (a manifold fan around v); creases between the
    // two surfaces
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
    // each surface's faces connected across the edges that are no crease (one fan)
    let mut uf = crate::core::union_find::UnionFind::new(faces.len());
    for e in edges.values() {
        if group[e.1[0]] == group[e.1[1]] {
            uf.union(e.1[0] as u32, e.1[1] as u32);
        }
    }
    for g in 0..normals.len() {
        let mut roots = (0..faces.len()).filter(|&i| group[i] == g).map(|i| uf.find(i as u32));
        let first = roots.next()?;
        if roots.any(|r| r != first) {
            return None;
        }
    }
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
        slides(m, &w, &[])
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
        w.slide = slides(&m, &w, &[]);
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
