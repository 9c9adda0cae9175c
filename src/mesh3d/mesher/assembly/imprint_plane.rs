//! One common triangulation of coplanar faces of touching solids (the planar chart of
//! [`super::imprint`]): the faces' regions overlaid in their plane, every face made of the
//! triangles of one constrained Delaunay triangulation, so that where two solids' faces
//! overlap they have the same triangles.
//!
//! Stages, all in the plane's `(u, v)`:
//! 1. **Snapping.** The faces' boundary vertices are taken in rank order (the first face, of
//!    the first solid, is the master); a vertex within the tolerance of another solid's
//!    vertex is that vertex (the nearest).
//! 2. **Boundaries follow each other.** A vertex within the tolerance of another solid's
//!    boundary edge (not of its ends) splits that edge: two tessellations of one circle,
//!    chords of different lengths, become one chain of the points of both.
//! 3. **Crossings.** Boundary edges of different solids that still cross properly (exact
//!    orientation signs) are split at their crossing, a new point both use.
//! 4. **Interior points.** A face keeps its interior vertices, except where a face of another
//!    solid ranked before it covers them (the master's points mesh the overlap) and where
//!    they come closer to another solid's boundary than a third of their own edges (they
//!    would make slivers against it).
//! 5. **The triangulation.** Every point, every boundary chain as constraints; the regions
//!    the constraints bound are each inside or outside each face: inside where the face's
//!    own boundary bounds it on the face's side, else by where its largest triangle's
//!    centroid lies in the face's triangles.
//!
//! Anything unexpected (faces not in one plane, constraints that cross, a face whose new
//! triangles do not add up to its area, two faces of one side covering one region) refuses
//! the imprint (`None`): the faces stay as they were, and the solids are tied there.

use crate::core::bvh::Bvh;
use crate::core::cdt;
use crate::core::predicates::{Sign, orient2d};
use crate::core::Aabb;
use glam::{DVec2, DVec3};
use rustc_hash::FxHashMap;
use spade::handles::FixedVertexHandle;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

/// The normals of a face's triangles are within this of the plane's (cosine): a planar
/// face's facets are its plane up to rounding.
const PLANE_COS: f64 = 0.9999;

/// A face of the component: its solid, and its triangles in the solid's vertex numbering.
pub(super) struct Face<'a> {
    /// The solid (index in the assembly).
    pub solid: usize,
    /// The face's triangles.
    pub triangles: Vec<[u32; 3]>,
    /// The solid's vertices.
    pub vertices: &'a [DVec3],
}

/// A point of the common triangulation.
#[derive(Clone, Debug)]
pub(super) struct Point {
    /// Where it is in the plane.
    pub at: DVec2,
    /// Where it is in space: the position of its first original vertex, or on the plane.
    pub p3: DVec3,
    /// The solid vertices it stands for: (solid, vertex).
    pub of: Vec<(usize, u32)>,
}

/// The faces remade of one triangulation.
pub(super) struct Imprinted {
    /// Its points.
    pub points: Vec<Point>,
    /// Per face, its triangles in point numbers, oriented as the face was.
    pub faces: Vec<Vec<[u32; 3]>>,
    /// Per face, its boundary edges (the solid's vertex numbers, the face on the left) and
    /// the chain of points each became (from its start to its end).
    pub chains: Vec<Vec<([u32; 2], Vec<u32>)>>,
}

/// The plane of `faces` (the first one's), `None` unless every face lies in it within `tol`
/// with its triangles' normals along it: origin, `u`, `v`, normal, and each face's side
/// (true where its normal is the plane's).
fn plane(faces: &[Face]) -> Option<(DVec3, DVec3, DVec3, DVec3, Vec<bool>)> {
    let first = faces.first()?;
    let mut n = DVec3::ZERO;
    for t in &first.triangles {
        let [a, b, c] = t.map(|v| first.vertices[v as usize]);
        n += (b - a).cross(c - a);
    }
    let n = n.try_normalize()?;
    let o = first.vertices[first.triangles[0][0] as usize];
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    let mut sides = Vec::with_capacity(faces.len());
    for f in faces {
        let mut side = None;
        for t in &f.triangles {
            let [a, b, c] = t.map(|v| f.vertices[v as usize]);
            let m = (b - a).cross(c - a).try_normalize()?;
            let d = m.dot(n);
            let up = d > 0.0;
            if d.abs() < PLANE_COS || side.is_some_and(|s| s != up) {
                return None;
            }
            side = Some(up);
        }
        sides.push(side?);
    }
    Some((o, u, v, n, sides))
}

/// The boundary edges of a face's triangles (used once, the face on their left), in the
/// order of the triangles.
fn boundary(triangles: &[[u32; 3]]) -> Vec<[u32; 2]> {
    let mut count: FxHashMap<(u32, u32), i32> = FxHashMap::default();
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_insert(0) += if a < b { 1 } else { -1 };
        }
    }
    let mut out = Vec::new();
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let c = count[&(a.min(b), a.max(b))];
            if (a < b && c == 1) || (a > b && c == -1) {
                out.push([a, b]);
            }
        }
    }
    out
}

fn box2(a: DVec2, b: DVec2, pad: f64) -> Aabb {
    Aabb { min: DVec3::new(a.x.min(b.x) - pad, a.y.min(b.y) - pad, 0.0), max: DVec3::new(a.x.max(b.x) + pad, a.y.max(b.y) + pad, 0.0) }
}

/// Where `p` projects on `a`–`b` (parameter) and how far it is from the segment.
fn on_segment(p: DVec2, a: DVec2, b: DVec2) -> (f64, f64) {
    let d = b - a;
    let l2 = d.length_squared();
    if l2 == 0.0 {
        return (0.0, p.distance(a));
    }
    let t = ((p - a).dot(d) / l2).clamp(0.0, 1.0);
    (t, p.distance(a + d * t))
}

/// True if `a`–`b` and `c`–`d` cross at a point inside both (exact signs).
fn cross_properly(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let s1 = orient2d(a, b, c);
    let s2 = orient2d(a, b, d);
    let s3 = orient2d(c, d, a);
    let s4 = orient2d(c, d, b);
    s1 != Sign::Zero && s2 != Sign::Zero && s3 != Sign::Zero && s4 != Sign::Zero && s1 != s2 && s3 != s4
}

/// A point of a face's boundary slides along it onto a neighbour in a shared chain (see
/// [`slide_onto_neighbours`]) where the turn of the boundary at it is under this (degrees):
/// a point of a curve's discretisation, not a corner.
const SMOOTH_TURN_DEG: f64 = 25.0;

/// ... and where the neighbour is nearer than this share of its shorter boundary edge.
const SLIDE_SHARE: f64 = 0.4;

/// Two tessellations of one boundary curve (the two solids' discretisations of a circle
/// they share) interleave in a chain, leaving pieces far shorter than either's edges: a
/// point of one solid next to a point of the other, nearer than [`SLIDE_SHARE`] of its own
/// shorter boundary edge, where its own boundary turns by less than [`SMOOTH_TURN_DEG`],
/// becomes that point (it slides along the curve; corners never move). Pairs are taken
/// nearest first, each point once. Returns which points are still their own.
fn slide_onto_neighbours(
    faces: &[Face],
    edges: &[Vec<[u32; 2]>],
    points: &mut [Point],
    point_of: &mut FxHashMap<(usize, u32), u32>,
    chains: &mut [Vec<Vec<u32>>],
    flat: &dyn Fn(DVec3) -> DVec2,
) -> Vec<bool> {
    // the share of its shorter edge a point may slide, where it may
    let mut reach: Vec<Option<f64>> = vec![None; points.len()];
    for (k, f) in faces.iter().enumerate() {
        let mut around: FxHashMap<u32, (Vec<u32>, Vec<u32>)> = FxHashMap::default();
        for &[a, b] in &edges[k] {
            around.entry(b).or_default().0.push(a);
            around.entry(a).or_default().1.push(b);
        }
        for (&x, (prev, next)) in &around {
            let p = point_of[&(f.solid, x)] as usize;
            if prev.len() != 1 || next.len() != 1 || points[p].of.len() != 1 {
                continue;
            }
            let [a, v, b] = [prev[0], x, next[0]].map(|y| flat(f.vertices[y as usize]));
            let (d1, d2) = (v - a, b - v);
            let turn = d1.angle_to(d2).abs().to_degrees();
            if turn < SMOOTH_TURN_DEG {
                reach[p] = Some(SLIDE_SHARE * d1.length().min(d2.length()));
            }
        }
    }
    let mut pairs: Vec<(f64, u32, u32)> = Vec::new();
    for cs in chains.iter() {
        for c in cs {
            for w in c.windows(2) {
                let (p, q) = (w[0] as usize, w[1] as usize);
                let (Some(sp), Some(sq)) = (points[p].of.first(), points[q].of.first()) else { continue };
                if sp.0 == sq.0 {
                    continue;
                }
                let d = points[p].at.distance(points[q].at);
                // the later point slides where it may, else the earlier one
                let (mover, keeper) = if q > p { (q, p) } else { (p, q) };
                if reach[mover].is_some_and(|r| d < r) {
                    pairs.push((d, mover as u32, keeper as u32));
                } else if reach[keeper].is_some_and(|r| d < r) {
                    pairs.push((d, keeper as u32, mover as u32));
                }
            }
        }
    }
    pairs.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.cmp(&y.2)));
    let mut taken = vec![false; points.len()];
    let mut rep: Vec<u32> = (0..points.len() as u32).collect();
    for (_, m, k) in pairs {
        if taken[m as usize] || taken[k as usize] {
            continue;
        }
        taken[m as usize] = true;
        taken[k as usize] = true;
        rep[m as usize] = k;
        let moved = std::mem::take(&mut points[m as usize].of);
        for o in &moved {
            point_of.insert(*o, k);
        }
        points[k as usize].of.extend(moved);
    }
    for cs in chains.iter_mut() {
        for c in cs.iter_mut() {
            for x in c.iter_mut() {
                *x = rep[*x as usize];
            }
            c.dedup();
        }
    }
    (0..points.len()).map(|i| rep[i] == i as u32).collect()
}

/// The faces remade of one triangulation of their plane (see the module docs); `tol` the
/// distance within which two solids' points are one.
pub(super) fn imprint(faces: &[Face], tol: f64) -> Option<Imprinted> {
    let (o, u, v, n, sides) = plane(faces)?;
    let flat = |p: DVec3| DVec2::new((p - o).dot(u), (p - o).dot(v));
    let lift = |q: DVec2| o + u * q.x + v * q.y;
    for f in faces {
        if f.triangles.iter().flatten().any(|&x| (f.vertices[x as usize] - o).dot(n).abs() > tol) {
            return None;
        }
    }
    let mut points: Vec<Point> = Vec::new();
    // (solid, vertex) -> point
    let mut point_of: FxHashMap<(usize, u32), u32> = FxHashMap::default();
    let cell = |q: DVec2| ((q.x / tol).floor() as i64, (q.y / tol).floor() as i64);
    let mut grid: FxHashMap<(i64, i64), Vec<u32>> = FxHashMap::default();
    // 1. boundary vertices, snapped to other solids' within tol
    let edges: Vec<Vec<[u32; 2]>> = faces.iter().map(|f| boundary(&f.triangles)).collect();
    for (k, f) in faces.iter().enumerate() {
        for &x in edges[k].iter().flatten() {
            if point_of.contains_key(&(f.solid, x)) {
                continue;
            }
            let p3 = f.vertices[x as usize];
            let q = flat(p3);
            let (cx, cy) = cell(q);
            let mut best: Option<(f64, u32)> = None;
            for i in cx - 1..=cx + 1 {
                for j in cy - 1..=cy + 1 {
                    for &c in grid.get(&(i, j)).into_iter().flatten() {
                        let p = &points[c as usize];
                        let d = p.at.distance(q);
                        if d <= tol && !p.of.iter().any(|o| o.0 == f.solid) && best.is_none_or(|b| d < b.0) {
                            best = Some((d, c));
                        }
                    }
                }
            }
            let id = match best {
                Some((_, c)) => {
                    points[c as usize].of.push((f.solid, x));
                    c
                }
                None => {
                    points.push(Point { at: q, p3, of: vec![(f.solid, x)] });
                    grid.entry((cx, cy)).or_default().push(points.len() as u32 - 1);
                    points.len() as u32 - 1
                }
            };
            point_of.insert((f.solid, x), id);
        }
    }
    // the chains: every boundary edge of every face, as points
    let mut chains: Vec<Vec<Vec<u32>>> = edges.iter().enumerate().map(|(k, es)| es.iter().map(|e| e.map(|x| point_of[&(faces[k].solid, x)]).to_vec()).collect()).collect();
    // 2. points within tol of another solid's edge split it
    {
        let items = chains.iter().enumerate().flat_map(|(k, cs)| cs.iter().enumerate().map(move |(e, c)| (k, e, c))).enumerate().map(|(i, (_, _, c))| (i as u32, box2(points[c[0] as usize].at, points[c[1] as usize].at, tol)));
        let bvh = Bvh::build(items.collect::<Vec<_>>());
        let index: Vec<(usize, usize)> = chains.iter().enumerate().flat_map(|(k, cs)| (0..cs.len()).map(move |e| (k, e))).collect();
        let mut inserts: Vec<Vec<(f64, u32)>> = vec![Vec::new(); index.len()];
        for (pi, p) in points.iter().enumerate() {
            let q = Aabb { min: DVec3::new(p.at.x, p.at.y, 0.0), max: DVec3::new(p.at.x, p.at.y, 0.0) };
            bvh.for_each_overlapping(&q, |i| {
                let (k, e) = index[i as usize];
                let c = &chains[k][e];
                let (a, b) = (&points[c[0] as usize], &points[c[1] as usize]);
                if c.contains(&(pi as u32)) || p.of.iter().any(|o| o.0 == faces[k].solid) {
                    return;
                }
                let (t, d) = on_segment(p.at, a.at, b.at);
                if d <= tol && p.at.distance(a.at) > tol && p.at.distance(b.at) > tol {
                    inserts[i as usize].push((t, pi as u32));
                }
            });
        }
        for (i, mut ins) in inserts.into_iter().enumerate() {
            if ins.is_empty() {
                continue;
            }
            ins.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            let (k, e) = index[i];
            let c = &mut chains[k][e];
            let end = c.pop().expect("two points");
            c.extend(ins.into_iter().map(|(_, p)| p));
            c.push(end);
        }
    }
    // 2b. along a boundary two solids share, a point next to one of the other solid closer
    // than a share of its own edges slides onto it
    let alive = slide_onto_neighbours(faces, &edges, &mut points, &mut point_of, &mut chains, &flat);
    // 3. crossings of edges of different solids
    for round in 0..4 {
        let mut segs: Vec<(usize, usize, usize)> = Vec::new();
        for (k, cs) in chains.iter().enumerate() {
            for (e, c) in cs.iter().enumerate() {
                for j in 0..c.len() - 1 {
                    segs.push((k, e, j));
                }
            }
        }
        let ends = |s: &(usize, usize, usize)| (chains[s.0][s.1][s.2], chains[s.0][s.1][s.2 + 1]);
        let bvh = Bvh::build(segs.iter().enumerate().map(|(i, s)| {
            let (a, b) = ends(s);
            (i as u32, box2(points[a as usize].at, points[b as usize].at, 0.0))
        }).collect::<Vec<_>>());
        let mut crossing: Vec<(u32, u32)> = Vec::new();
        bvh.for_each_overlapping_pair(|i, j| {
            let (si, sj) = (&segs[i as usize], &segs[j as usize]);
            if faces[si.0].solid == faces[sj.0].solid {
                return;
            }
            let ((a, b), (c, d)) = (ends(si), ends(sj));
            if a == c || a == d || b == c || b == d {
                return;
            }
            let [pa, pb, pc, pd] = [a, b, c, d].map(|x| points[x as usize].at);
            if cross_properly(pa, pb, pc, pd) {
                crossing.push((i.min(j), i.max(j)));
            }
        });
        if crossing.is_empty() {
            break;
        }
        if round == 3 {
            return None;
        }
        crossing.sort_unstable();
        crossing.dedup();
        let mut inserts: FxHashMap<(usize, usize, usize), Vec<(f64, u32)>> = FxHashMap::default();
        for (i, j) in crossing {
            let (si, sj) = (segs[i as usize], segs[j as usize]);
            let ((a, b), (c, d)) = (ends(&si), ends(&sj));
            let [pa, pb, pc, pd] = [a, b, c, d].map(|x| points[x as usize].at);
            let den = (pb - pa).perp_dot(pd - pc);
            if den == 0.0 {
                return None;
            }
            let t = (pc - pa).perp_dot(pd - pc) / den;
            let s = (pc - pa).perp_dot(pb - pa) / den;
            let at = pa + (pb - pa) * t;
            points.push(Point { at, p3: lift(at), of: Vec::new() });
            let id = points.len() as u32 - 1;
            inserts.entry(si).or_default().push((t, id));
            inserts.entry(sj).or_default().push((s, id));
        }
        // insert from the last segment of each chain backwards, so indices stay valid
        let mut keys: Vec<_> = inserts.keys().copied().collect();
        keys.sort_unstable_by(|x, y| y.cmp(x));
        for key in keys {
            let mut ins = inserts.remove(&key).expect("key");
            ins.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            let c = &mut chains[key.0][key.1];
            let at = key.2 + 1;
            c.splice(at..at, ins.into_iter().map(|(_, p)| p));
        }
    }
    // 4. interior points
    let locators: Vec<Bvh> = faces
        .iter()
        .map(|f| Bvh::build(f.triangles.iter().enumerate().map(|(i, t)| {
            let [a, b, c] = t.map(|x| flat(f.vertices[x as usize]));
            (i as u32, box2(a.min(b).min(c), a.max(b).max(c), 0.0))
        }).collect::<Vec<_>>()))
        .collect();
    let inside = |k: usize, q: DVec2| {
        let f = &faces[k];
        let mut found = false;
        locators[k].for_each_overlapping(&Aabb { min: DVec3::new(q.x, q.y, 0.0), max: DVec3::new(q.x, q.y, 0.0) }, |i| {
            if found {
                return;
            }
            let [a, b, c] = f.triangles[i as usize].map(|x| flat(f.vertices[x as usize]));
            let s = [orient2d(a, b, q), orient2d(b, c, q), orient2d(c, a, q)];
            let pos = s.iter().all(|&x| x != Sign::Negative);
            let neg = s.iter().all(|&x| x != Sign::Positive);
            found = pos || neg;
        });
        found
    };
    let all_segs: Vec<(usize, u32, u32)> = chains.iter().enumerate().flat_map(|(k, cs)| cs.iter().flat_map(move |c| c.windows(2).map(move |w| (k, w[0], w[1])))).collect();
    let seg_bvh = Bvh::build(all_segs.iter().enumerate().map(|(i, &(_, a, b))| (i as u32, box2(points[a as usize].at, points[b as usize].at, 0.0))).collect::<Vec<_>>());
    for (k, f) in faces.iter().enumerate() {
        let mut shortest: FxHashMap<u32, f64> = FxHashMap::default();
        for t in &f.triangles {
            for j in 0..3 {
                let (a, b) = (t[j], t[(j + 1) % 3]);
                let l = f.vertices[a as usize].distance(f.vertices[b as usize]);
                for x in [a, b] {
                    let e = shortest.entry(x).or_insert(f64::INFINITY);
                    *e = e.min(l);
                }
            }
        }
        let mut interior: Vec<u32> = shortest.keys().copied().filter(|x| !point_of.contains_key(&(f.solid, *x))).collect();
        interior.sort_unstable();
        for x in interior {
            let q = flat(f.vertices[x as usize]);
            if (0..k).any(|j| faces[j].solid != f.solid && inside(j, q)) {
                continue;
            }
            let keep_off = (shortest[&x] / 3.0).max(tol);
            let mut near = false;
            seg_bvh.for_each_overlapping(&Aabb { min: DVec3::new(q.x - keep_off, q.y - keep_off, 0.0), max: DVec3::new(q.x + keep_off, q.y + keep_off, 0.0) }, |i| {
                let (j, a, b) = all_segs[i as usize];
                if !near && faces[j].solid != f.solid && on_segment(q, points[a as usize].at, points[b as usize].at).1 < keep_off {
                    near = true;
                }
            });
            if near {
                continue;
            }
            points.push(Point { at: q, p3: f.vertices[x as usize], of: vec![(f.solid, x)] });
            point_of.insert((f.solid, x), points.len() as u32 - 1);
        }
    }
    // 5. the triangulation
    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> = ConstrainedDelaunayTriangulation::new();
    let mut handle: Vec<Option<FixedVertexHandle>> = Vec::with_capacity(points.len());
    let mut point_at: FxHashMap<usize, u32> = FxHashMap::default();
    for (i, p) in points.iter().enumerate() {
        if !alive.get(i).copied().unwrap_or(true) {
            handle.push(None);
            continue;
        }
        let h = cdt::insert(&mut cdt, p.at, |q| q).ok()?;
        if point_at.insert(h.index(), i as u32).is_some() {
            // two points at one place that snapping did not make one
            return None;
        }
        handle.push(Some(h));
    }
    // every chain piece, once, as a constraint
    let mut keys: Vec<(u32, u32)> = chains.iter().flatten().flat_map(|c| c.windows(2).map(|w| (w[0].min(w[1]), w[0].max(w[1])))).collect();
    keys.sort_unstable();
    keys.dedup();
    for &(a, b) in &keys {
        let (ha, hb) = (handle[a as usize]?, handle[b as usize]?);
        if !cdt::constrain(&mut cdt, ha, hb) {
            return None;
        }
        cdt.get_edge_from_neighbors(ha, hb)?;
    }
    // Ruppert's refinement (25°): where another solid's border passes near a face's points it
    // leaves triangles with one short side, which the tet mesher would carry into slivers.
    // The new points lie in the plane, one triangulation for all faces; those on a border
    // (an encroached constraint split) join its chain
    let before = cdt.num_vertices();
    let params = spade::RefinementParameters::<f64>::new()
        .with_angle_limit(spade::AngleLimit::from_deg(25.0))
        .exclude_outer_faces(true)
        .with_max_additional_vertices(4 * before + 100);
    cdt.refine(params);
    for h in cdt.fixed_vertices().skip(before) {
        let q = cdt.vertex(h).position();
        let at = DVec2::new(q.x, q.y);
        point_at.insert(h.index(), points.len() as u32);
        points.push(Point { at, p3: lift(at), of: Vec::new() });
    }
    let handle_of = |i: u32| handle[i as usize];
    for cs in chains.iter_mut() {
        for c in cs.iter_mut() {
            let mut out = vec![c[0]];
            for w in c.windows(2) {
                let (hp, hq) = (handle_of(w[0])?, handle_of(w[1])?);
                let (p, q) = (points[w[0] as usize].at, points[w[1] as usize].at);
                let mut cur = hp;
                let mut steps = 0;
                while cur != hq {
                    steps += 1;
                    if steps > 1 << 16 {
                        return None;
                    }
                    // the next vertex along the constraint toward q
                    let next = cdt.vertex(cur).out_edges().filter(|e| e.is_constraint_edge()).map(|e| e.to()).filter(|v| {
                        let x = cdt.vertex(v.fix()).position();
                        let x = DVec2::new(x.x, x.y);
                        let (t, d) = on_segment(x, p, q);
                        d <= 1e-9 * p.distance(q) && t > 0.0
                    }).min_by(|a, b| {
                        let pa = a.position();
                        let pb = b.position();
                        DVec2::new(pa.x, pa.y).distance(q).total_cmp(&DVec2::new(pb.x, pb.y).distance(q))
                    })?;
                    if DVec2::new(next.position().x, next.position().y).distance(q) >= DVec2::new(cdt.vertex(cur).position().x, cdt.vertex(cur).position().y).distance(q) {
                        return None;
                    }
                    cur = next.fix();
                    out.push(*point_at.get(&cur.index())?);
                }
            }
            *c = out;
        }
    }
    // per constraint piece of the chains as they are now: the faces it bounds, each with its
    // direction (the face on the left of a -> b in its own orientation: in the plane's where
    // its normal is the plane's, else on the right)
    let mut bounds: FxHashMap<(u32, u32), Vec<(usize, bool)>> = FxHashMap::default();
    for (k, cs) in chains.iter().enumerate() {
        for c in cs {
            for w in c.windows(2) {
                let (a, b) = (w[0], w[1]);
                bounds.entry((a.min(b), a.max(b))).or_default().push((k, (a < b) == sides[k]));
            }
        }
    }
    // regions: inner faces joined across edges that are not constraints
    let inner: Vec<_> = cdt.fixed_inner_faces().collect();
    let mut slot = vec![usize::MAX; cdt.num_all_faces()];
    for (i, f) in inner.iter().enumerate() {
        slot[f.index()] = i;
    }
    let mut region = vec![usize::MAX; inner.len()];
    let mut regions = 0;
    for start in 0..inner.len() {
        if region[start] != usize::MAX {
            continue;
        }
        region[start] = regions;
        let mut stack = vec![start];
        while let Some(i) = stack.pop() {
            for e in cdt.face(inner[i]).adjacent_edges() {
                if e.is_constraint_edge() {
                    continue;
                }
                if let Some(nb) = e.rev().face().as_inner() {
                    let j = slot[nb.fix().index()];
                    if region[j] == usize::MAX {
                        region[j] = regions;
                        stack.push(j);
                    }
                }
            }
        }
        regions += 1;
    }
    let corners = |i: usize| cdt.face(inner[i]).vertices().map(|h| point_at[&h.fix().index()]);
    // membership: Some(true/false) per (region, face)
    let nf = faces.len();
    let mut member: Vec<Option<bool>> = vec![None; regions * nf];
    for (i, _) in inner.iter().enumerate() {
        let c = corners(i);
        for j in 0..3 {
            let (a, b) = (c[j], c[(j + 1) % 3]);
            // the face is on the left of a -> b
            if let Some(list) = bounds.get(&(a.min(b), a.max(b))) {
                for &(k, forward) in list {
                    let left = forward == (a < b);
                    let m = &mut member[region[i] * nf + k];
                    if m.is_some_and(|x| x != left) {
                        return None;
                    }
                    *m = Some(left);
                }
            }
        }
    }
    // the largest triangle of each region, for the faces its boundary does not decide
    let mut largest = vec![(0.0f64, usize::MAX); regions];
    for i in 0..inner.len() {
        let [a, b, c] = corners(i).map(|x| points[x as usize].at);
        let area = 0.5 * (b - a).perp_dot(c - a);
        if area > largest[region[i]].0 {
            largest[region[i]] = (area, i);
        }
    }
    for r in 0..regions {
        let (_, i) = largest[r];
        if i == usize::MAX {
            continue;
        }
        let [a, b, c] = corners(i).map(|x| points[x as usize].at);
        let centroid = (a + b + c) / 3.0;
        for k in 0..nf {
            if member[r * nf + k].is_none() {
                member[r * nf + k] = Some(inside(k, centroid));
            }
        }
    }
    let mut out: Vec<Vec<[u32; 3]>> = vec![Vec::new(); nf];
    let mut area = vec![0.0f64; nf];
    for i in 0..inner.len() {
        let r = region[i];
        let c = corners(i);
        let [a, b, cc] = c.map(|x| points[x as usize].at);
        let ar = 0.5 * (b - a).perp_dot(cc - a);
        let mut sides_seen = [false; 2];
        let mut solids_seen: Vec<usize> = Vec::new();
        for k in 0..nf {
            if member[r * nf + k] != Some(true) {
                continue;
            }
            let side = sides[k] as usize;
            if sides_seen[side] || solids_seen.contains(&faces[k].solid) {
                return None;
            }
            sides_seen[side] = true;
            solids_seen.push(faces[k].solid);
            out[k].push(if sides[k] { c } else { [c[0], c[2], c[1]] });
            area[k] += ar;
        }
    }
    for (k, f) in faces.iter().enumerate() {
        let mut before = 0.0;
        let mut perimeter = 0.0;
        for t in &f.triangles {
            let [a, b, c] = t.map(|x| flat(f.vertices[x as usize]));
            before += 0.5 * (b - a).perp_dot(c - a).abs();
        }
        for e in &edges[k] {
            perimeter += f.vertices[e[0] as usize].distance(f.vertices[e[1] as usize]);
        }
        if (area[k] - before).abs() > 1e-9 * before + 2.0 * tol * perimeter {
            return None;
        }
    }
    let chains = chains.into_iter().zip(edges).map(|(cs, es)| es.into_iter().zip(cs).collect()).collect();
    Some(Imprinted { points, faces: out, chains })
}


#[cfg(test)]
mod tests {
    use super::*;

    /// A square `[x0, x0 + side]²` in z = 0 cut into `n × n` cells of two triangles each,
    /// facing +z (`up`) or -z.
    fn square(x0: f64, y0: f64, side: f64, n: usize, up: bool) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut v = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                v.push(DVec3::new(x0 + side * i as f64 / n as f64, y0 + side * j as f64 / n as f64, 0.0));
            }
        }
        let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        let mut t = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                for tri in [[a, b, c], [a, c, d]] {
                    t.push(if up { tri } else { [tri[0], tri[2], tri[1]] });
                }
            }
        }
        (v, t)
    }

    fn area(points: &[Point], t: &[[u32; 3]]) -> f64 {
        t.iter().map(|t| {
            let [a, b, c] = t.map(|x| points[x as usize].p3);
            0.5 * (b - a).cross(c - a).length()
        }).sum()
    }

    #[test]
    fn two_overlapping_squares_share_the_triangles_of_their_overlap() {
        // the top of a unit block (4×4 cells) and the bottom of a block shifted by (0.3, 0.45)
        // (3×3 cells of another size): they overlap over 0.7 × 0.55
        let (va, ta) = square(0.0, 0.0, 1.0, 4, true);
        let (vb, tb) = square(0.3, 0.45, 1.0, 3, false);
        let faces = [Face { solid: 0, triangles: ta, vertices: &va }, Face { solid: 1, triangles: tb, vertices: &vb }];
        let im = imprint(&faces, 1e-9).expect("coplanar squares imprint");
        assert!((area(&im.points, &im.faces[0]) - 1.0).abs() < 1e-12);
        assert!((area(&im.points, &im.faces[1]) - 1.0).abs() < 1e-12);
        // the triangles both faces hold are the overlap, each once the other way round
        let key = |t: &[u32; 3]| {
            let mut s = *t;
            s.sort_unstable();
            s
        };
        let a: std::collections::BTreeSet<[u32; 3]> = im.faces[0].iter().map(key).collect();
        let shared: Vec<&[u32; 3]> = im.faces[1].iter().filter(|t| a.contains(&key(t))).collect();
        assert!((area(&im.points, &shared.iter().map(|t| **t).collect::<Vec<_>>()) - 0.7 * 0.55).abs() < 1e-12);
        for t in &shared {
            let other = im.faces[0].iter().find(|u| key(u) == key(t)).unwrap();
            let rot = |t: &[u32; 3], k: usize| [t[k], t[(k + 1) % 3], t[(k + 2) % 3]];
            assert!((0..3).any(|k| rot(other, k) == [t[0], t[2], t[1]]), "{t:?} and {other:?} face the same way");
        }
        // A's edges along y = 1 and x = 1 are split where B's border crosses them, at (0.3, 1)
        // and (1, 0.45)
        for at in [DVec3::new(0.3, 1.0, 0.0), DVec3::new(1.0, 0.45, 0.0)] {
            let on_chain = im.chains[0].iter().any(|(_, c)| c[1..c.len() - 1].iter().any(|&x| im.points[x as usize].p3.distance(at) < 1e-12));
            assert!(on_chain, "{at} is on none of A's chains");
        }
        // every chain runs along its edge, in order
        for ([a, b], c) in &im.chains[0] {
            let (pa, pb) = (va[*a as usize], va[*b as usize]);
            let t: Vec<f64> = c.iter().map(|&x| (im.points[x as usize].p3 - pa).dot(pb - pa) / pa.distance_squared(pb)).collect();
            assert!(t.windows(2).all(|w| w[0] < w[1]) && t[0].abs() < 1e-12 && (t[t.len() - 1] - 1.0).abs() < 1e-12, "{t:?}");
        }
    }

    #[test]
    fn faces_that_are_not_coplanar_are_not_imprinted() {
        let (va, ta) = square(0.0, 0.0, 1.0, 2, true);
        let (mut vb, tb) = square(0.0, 0.0, 1.0, 2, false);
        for p in &mut vb {
            p.z = 0.01;
        }
        let faces = [Face { solid: 0, triangles: ta, vertices: &va }, Face { solid: 1, triangles: tb, vertices: &vb }];
        assert!(imprint(&faces, 1e-3).is_none());
        assert!(imprint(&faces, 0.1).is_some());
    }
}
