//! Delaunay refinement inside the material.
//!
//! A tet is bad when its circumradius-to-shortest-edge ratio exceeds the bound, or its
//! circumradius exceeds 0.75 times the size wanted at its circumcentre. The worst bad tet is
//! split at its circumcentre. Where the centre lies inside the diametral sphere of a subface
//! on its cavity's boundary and would make a bad tet on a wall (a point too near the
//! surface), the subface is split instead when the boundary may change (`split_boundary.rs`:
//! at its circumcentre, or the subsegment that centre encroaches, as Delaunay refinement of a
//! piecewise linear complex does), and the bad tet is tried again. Where that is not allowed
//! (keep-surface, a tessellation sized already, a split that would come too near the local
//! feature size or leave a flat tet), or the centre lies behind a wall, points inside the
//! tet's circumsphere on the material side are tried instead: above each of its walls at the
//! height of a well-shaped tet, and half-way from its centroid to the centre. A point that
//! would lie flat over a wall of its cavity (nearer the wall's plane than a fifth of its
//! longest edge, above its circumcircle, yet outside its diametral sphere) is refused the same
//! way: the tet it would make on the wall is flat, and on a CAD part's curved faces, which
//! refinement does not split, nothing later lifts it off. New tets inherit the region of the
//! tet they replace.
//!
//! No point comes nearer a vertex than a share of the local feature size: the shortest edge
//! at each boundary and recovery point before refinement, carried to new points 1-Lipschitz
//! (the least, over the tet's vertices, of their size plus the distance). Walls and the
//! cavity corrections beside them leave the tetrahedralization short of Delaunay, so a
//! centre can lie near a vertex there; without the floor each such point made the next
//! tets smaller still, a cascade that spent the whole point budget in one spot (4,000 points
//! in a ball of radius 0.03 on `featuretype.STL`) and left the rest of the part unrefined.

use crate::core::ids::NONE;
use crate::core::{RegionId, SizeField};
use crate::mesh3d::mesher::carve::Labels;
use crate::mesh3d::mesher::recover::circumcenter;
use crate::mesh3d::mesher::split_boundary::{FacetEdges, split_wall};
use crate::mesh3d::mesher::surface_model::SurfaceModel;
use crate::mesh3d::mesher::tetra::{Inserted, Tetra};
use crate::mesh3d::mesher::{MeshOptions, MeshingError};
use crate::mesh3d::delaunay::store::{DEAD, GHOST};
use glam::DVec3;
use crate::mesh3d::mesher::bad_queue::BadQueue;
use std::hash::BuildHasher;

/// What refinement did.
#[derive(Clone, Debug, Default)]
pub(crate) struct Refined {
    /// Points inserted in the volume.
    pub volume_points: usize,
    /// Points put on the boundary (subsegments and facets) by splits of encroached subfaces.
    pub boundary_points: usize,
    /// Bad tets left as they were (keep-surface, or degenerate cases).
    pub rejected: usize,
    /// Refinement stopped at its point budget (near input angles too small for it to end).
    pub stopped: bool,
}

/// A queued bad tet is its priority (the radius-edge ratio, ordered by bits), slot and a
/// fingerprint of its vertices ([`fingerprint`]), in a [`BadQueue`]. Most of what the queue
/// holds goes stale (a later insertion took the tet); an entry is stale when its slot's tet
/// has another fingerprint. Two entries of one priority and slot are the same tet pushed twice
/// (or, as rarely as two fingerprints agree, a stale one beside it), so ordering them by
/// fingerprint instead of by vertices refines the tets in the same sequence.
/// A 32-bit fingerprint of a tet's vertices: the high half of their Fx hash.
fn fingerprint(v: [u32; 4]) -> u32 {
    (rustc_hash::FxBuildHasher.hash_one(v) >> 32) as u32
}

/// Circumcentre, circumradius and shortest edge of tet `t`.
pub(crate) fn tet_sphere(tr: &Tetra, t: u32) -> (DVec3, f64, f64) {
    let [a, b, c, d] = tr.tets[t as usize].v.map(|v| tr.point(v));
    let (u, v, w) = (b - a, c - a, d - a);
    let det = u.dot(v.cross(w));
    let lmin = [u, v, w, c - b, d - b, d - c].iter().map(|e| e.length_squared()).fold(f64::INFINITY, f64::min).sqrt();
    if det == 0.0 {
        return (a, f64::INFINITY, lmin);
    }
    let num = u.length_squared() * v.cross(w) + v.length_squared() * w.cross(u) + w.length_squared() * u.cross(v);
    let off = num / (2.0 * det);
    (a + off, off.length(), lmin)
}

/// Points inside bad tet `t`'s circumsphere and, unlike its centre, on the material side of
/// its walls: for each wall face, the point above the face's centroid at the height of a
/// well-shaped tet on it; then the midpoint of the centroid and the centre. Points too near
/// a vertex of `t` (under 0.4 of its shortest edge) are left out.
fn inside_candidates(tr: &Tetra, t: u32, wall: Option<(u32, usize)>) -> Vec<DVec3> {
    let (c, r, lmin) = tet_sphere(tr, t);
    let v = tr.tets[t as usize].v;
    let p = v.map(|i| tr.point(i));
    let centroid = (p[0] + p[1] + p[2] + p[3]) / 4.0;
    let mut out = Vec::new();
    // the wall whose diametral sphere the centre fell in: points above it, on t's side
    if let Some((wt, wk)) = wall {
        let w = tr.tets[wt as usize].v;
        let face = crate::mesh::tet_mesh::TET_FACES[wk].map(|i| w[i]);
        if !face.contains(&GHOST) && !face.contains(&DEAD) {
            let [a, b, d] = face.map(|i| tr.point(i));
            let g = (a + b + d) / 3.0;
            let mut n = (b - a).cross(d - a).normalize_or_zero();
            if n.dot(centroid - g) < 0.0 {
                n = -n;
            }
            let edge = (a.distance(b) + b.distance(d) + d.distance(a)) / 3.0;
            for h in [0.8, 0.6] {
                out.push(g + n * (h * edge));
            }
        }
    }
    for (f, fv) in crate::mesh::tet_mesh::TET_FACES.iter().enumerate() {
        if tr.walls[t as usize] >> f & 1 == 0 {
            continue;
        }
        let [a, b, d] = fv.map(|i| p[i]);
        let g = (a + b + d) / 3.0;
        let n = (d - a).cross(b - a); // into t (the faces of TET_FACES turn so that (b-a)x(d-a) leaves it)
        let len = n.length();
        if len == 0.0 {
            continue;
        }
        let edge = (a.distance(b) + b.distance(d) + d.distance(a)) / 3.0;
        for h in [0.8, 0.6] {
            out.push(g + n / len * (h * edge));
        }
    }
    out.push((centroid + c) * 0.5);
    out.retain(|q| q.is_finite() && q.distance(c) < r && p.iter().all(|x| x.distance(*q) > 0.4 * lmin));
    out
}

/// The priority of tet `t` if it is bad.
fn badness(tr: &Tetra, t: u32, size: &dyn SizeField, opts: &MeshOptions, r_min: f64, region: RegionId) -> Option<u64> {
    let (c, r, lmin) = tet_sphere(tr, t);
    if !r.is_finite() || lmin <= 0.0 || r <= r_min {
        return None;
    }
    let ratio = r / lmin;
    let h = size.size_in(c, region);
    let too_big = h.is_finite() && h > 0.0 && r > 0.75 * h;
    if ratio > opts.max_radius_edge || too_big {
        // worst ratio first; size-driven splits after quality ones of equal ratio
        Some((ratio.max(if too_big { r / h } else { 0.0 })).to_bits())
    } else {
        None
    }
}

/// The wall on a cavity's boundary on which `c` would make a bad tet (radius-edge over
/// [`WALL_RADIUS_EDGE`], or not positive): a point too near the surface. As (tet, face).
fn bad_on_wall(tr: &Tetra, boundary: &[([u32; 3], u32)], c: DVec3) -> Option<(u32, usize)> {
    for (f, at) in cavity_walls(tr, boundary) {
        let [a, b, d] = f.map(|v| tr.point(v));
        let (u, v, w) = (b - a, d - a, c - a);
        let det = u.dot(v.cross(w));
        let lmin2 = [u, v, w, d - b, c - b, c - d].iter().map(|e| e.length_squared()).fold(f64::INFINITY, f64::min);
        let bad = if det <= 0.0 {
            true
        } else {
            let num = u.length_squared() * v.cross(w) + v.length_squared() * w.cross(u) + w.length_squared() * u.cross(v);
            let r2 = (num / (2.0 * det)).length_squared();
            r2 > WALL_RADIUS_EDGE * WALL_RADIUS_EDGE * lmin2
        };
        if bad {
            return Some(at);
        }
    }
    None
}

/// The walls among a cavity's boundary faces (each with `4 t + k`, face `k` of the outside
/// tet `t`, as [`Tetra::insert_checked`] gives them): each face and (tet, face).
fn cavity_walls<'a>(tr: &'a Tetra, boundary: &'a [([u32; 3], u32)]) -> impl Iterator<Item = ([u32; 3], (u32, usize))> + 'a {
    boundary
        .iter()
        .filter(|&&(f, r)| !f.contains(&GHOST) && tr.walls[(r >> 2) as usize] >> (r & 3) & 1 != 0)
        .map(|&(f, r)| (f, (r >> 2, (r & 3) as usize)))
}

/// A wall on a cavity's boundary that `c` lies flat over: nearer its plane than
/// [`FLAT_OVER_WALL`] of its longest edge, the foot inside its circumcircle (then, outside
/// the wall's diametral sphere, only in a thin ring under its rim). The tet that `c` would
/// make on that wall is flat, and no later step can lift `c` off it where the wall belongs to
/// a CAD face that refinement does not split. As (tet, face).
fn flat_over_wall(tr: &Tetra, boundary: &[([u32; 3], u32)], c: DVec3) -> Option<(u32, usize)> {
    cavity_walls(tr, boundary).find(|(f, _)| flat_over(f.map(|v| tr.point(v)), c)).map(|(_, at)| at)
}

/// Whether `c` lies flat over triangle `t`: nearer its plane than [`FLAT_OVER_WALL`] of its
/// longest edge, the foot inside its circumcircle.
fn flat_over(t: [DVec3; 3], c: DVec3) -> bool {
    let [a, b, d] = t;
    let Some(n) = (b - a).cross(d - a).try_normalize() else { return false };
    let h = (c - a).dot(n);
    let long = a.distance(b).max(b.distance(d)).max(d.distance(a));
    if h.abs() >= FLAT_OVER_WALL * long {
        return false;
    }
    let cc = circumcenter(a, b, d);
    (c - n * h).distance_squared(cc) < a.distance_squared(cc)
}

/// How near a wall's plane, in its longest edge, a new point lies flat over it. Measured on
/// 44 real parts: 0.2 took Part2's tets under 10° that touch no input angle from 16 to 6 and
/// fan_shroud's from 4 to 3, every other part and the corpus within a few tets; 0.1 changed
/// nothing there, 0.3 left Part2 at 10 and heaterBlock's worst at 1.84°.
const FLAT_OVER_WALL: f64 = 0.2;

/// The worst radius-edge ratio allowed for a new tet on a wall.
const WALL_RADIUS_EDGE: f64 = 1.6;

/// The wall on a cavity's boundary whose equatorial sphere holds `c`: its face and (tet, face).
fn encroached_wall(tr: &Tetra, boundary: &[([u32; 3], u32)], c: DVec3) -> Option<([u32; 3], (u32, usize))> {
    cavity_walls(tr, boundary).find(|(f, _)| {
        let [a, b, d] = f.map(|v| tr.point(v));
        let cc = circumcenter(a, b, d);
        c.distance_squared(cc) < a.distance_squared(cc) * (1.0 - 1e-12)
    })
}

/// The share of the local feature size under which no point off a centre joins a vertex.
const LFS_FLOOR: f64 = 0.5;

/// The share of the local feature size under which no boundary split puts a point (a quarter
/// measured better than a half, which left many bad tets, and a tenth, which cascades: on
/// `plate_holes.STL` 69,507 tets and 6.05°, against 53,497 and 4.00°, and 83,094 and 6.33°).
const SPLIT_FLOOR: f64 = 0.25;

/// The share of the local feature size under which no circumcentre joins a vertex.
const CC_FLOOR: f64 = 0.25;

/// The local feature size at each point of `tr` before refinement: its shortest edge (the
/// points are then the boundary's and recovery's, so this is the distance to the nearest
/// other feature). Points on no live tet get infinity.
fn local_feature_sizes(tr: &Tetra) -> Vec<f64> {
    let mut lfs = vec![f64::INFINITY; tr.num_points()];
    for t in tr.live() {
        let v = tr.tets[t as usize].v;
        for i in 0..4 {
            for j in i + 1..4 {
                let (a, b) = (v[i], v[j]);
                if a == GHOST || b == GHOST || a == DEAD || b == DEAD {
                    continue;
                }
                let d = tr.point(a).distance(tr.point(b));
                lfs[a as usize] = lfs[a as usize].min(d);
                lfs[b as usize] = lfs[b as usize].min(d);
            }
        }
    }
    lfs
}

/// Gives the new tets of a volume insertion (`tr.created`) the region of the tet it split
/// (ghosts: the exterior).
fn inherit(tr: &Tetra, labels: &mut Labels, region: u32) {
    for &s in &tr.created {
        labels.set(s, if tr.tets[s as usize].v[3] == GHOST { 0 } else { region });
    }
}

/// The local feature size of a point `q` placed among the vertices `v` (a tet's, a subface's
/// or a subsegment's): the least of each vertex's size plus its distance to `q` (a 1-Lipschitz
/// extension of the boundary's sizes).
fn inherited_lfs(lfs: &[f64], tr: &Tetra, v: &[u32], q: DVec3) -> f64 {
    v.iter()
        .filter(|&&x| x != GHOST && x != DEAD)
        .map(|&x| lfs.get(x as usize).copied().unwrap_or(f64::INFINITY) + tr.point(x).distance(q))
        .fold(f64::INFINITY, f64::min)
}

/// Refines the material tets of `tr`, up to `max_points` points in all. Tets with a circumradius at most `r_min` are left as
/// they are: every point inserted is then at least about `r_min` from the others, which bounds
/// the work near small input angles, where refinement alone would not end.
///
/// # Errors
/// [`MeshingError::Internal`] when the walls cannot be restored after a boundary split.
#[allow(clippy::too_many_arguments)]
pub(crate) fn refine(
    tr: &mut Tetra,
    labels: &mut Labels,
    size: &dyn SizeField,
    opts: &MeshOptions,
    r_min: f64,
    max_points: usize,
    mut boundary: Option<&mut SurfaceModel>,
) -> Result<Refined, MeshingError> {
    let mut out = Refined::default();
    // the region's tag for a label (labels are 1-based)
    let tags = labels.tags.clone();
    let badness = |tr: &Tetra, t: u32, size: &dyn SizeField, opts: &MeshOptions, label: u32| {
        let region = label.checked_sub(1).and_then(|k| tags.get(k as usize)).copied().unwrap_or_default();
        badness(tr, t, size, opts, r_min, region)
    };
    let mut heap = BadQueue::default();
    let mut lfs = local_feature_sizes(tr);
    let mut edges = boundary.as_deref().map(FacetEdges::new);
    if let Some(sm) = boundary.as_deref_mut() {
        sm.refined_from = Some(tr.num_points() as u32);
    }
    // the new tets of an insertion: those in the material that are bad go on the heap
    let queue_created = |tr: &mut Tetra, labels: &Labels, heap: &mut BadQueue| {
        for s in std::mem::take(&mut tr.created) {
            let l = labels.get(s);
            if l != 0 && tr.finite(s) {
                if let Some(q) = badness(tr, s, size, opts, l) {
                    heap.push(q, s, fingerprint(tr.tets[s as usize].v));
                }
            }
        }
    };
    for t in tr.live().collect::<Vec<_>>() {
        if labels.get(t) != 0 {
            if let Some(q) = badness(tr, t, size, opts, labels.get(t)) {
                heap.push(q, t, fingerprint(tr.tets[t as usize].v));
            }
        }
    }
    // a generous bound on the work, against cascades near tiny input angles
    let budget = 50 * tr.num_points() + 1_000_000;
    let mut steps = 0usize;
    while let Some((_, t, f)) = heap.pop() {
        let v = tr.tets[t as usize].v;
        if fingerprint(v) != f || labels.get(t) == 0 {
            continue;
        }
        steps += 1;
        if steps > budget || tr.num_points() >= max_points {
            out.stopped = true;
            break;
        }
        let Some(_) = badness(tr, t, size, opts, labels.get(t)) else { continue };
        let (c, _, _) = tet_sphere(tr, t);
        let p = tr.add_point(c);
        tr.created.clear();
        // a point inside a subface's diametral sphere is not inserted: the subface is split
        // instead, or with keep-surface, the tet is worked on from inside below
        // nor one that would come nearer a vertex than a share of the local feature size
        // (where walls and cavity corrections leave the mesh short of Delaunay, a centre can
        // lie near a vertex, and then the next centres nearer still)
        let c_lfs = inherited_lfs(&lfs, tr, &v, c);
        let c_floor = CC_FLOOR * c_lfs;
        let mut encroached = None;
        // (a centre strictly inside the tet the walk finds, too near one of its vertices, is
        // turned down without its cavity dug: 4,152 of 23,560 on part.step at TetGen's count);
        // a rejection whose wall tet is NONE names no wall: the point came too near a vertex
        let res = tr.insert_checked_near(p, t, Some((c_floor, (NONE, 0))), |tr, walls| {
            if walls.iter().flat_map(|x| x.0).filter(|&x| x != GHOST).any(|x| tr.point(x).distance(c) < c_floor) {
                Some((NONE, 0))
            } else if let Some((_, w)) = encroached_wall(tr, walls, c) {
                // the subface to split: the first on the outline whose outside tet is the
                // encroached one's. With the exterior gone every face that looks outside has
                // slot 0 there, so this is the first outside wall of the outline, near the tet
                // that holds the centre, and not always the encroached one: splitting exactly
                // the encroached subface measured worse (plate_holes.STL 4.28° and 1 tet under
                // 5° against 6.05° and 0, fandisk.obj 49 tets under 5° against 42)
                encroached = walls.iter().find(|x| (x.1 >> 2, (x.1 & 3) as usize) == w).map(|x| x.0);
                bad_on_wall(tr, walls, c)
            } else {
                // nor a centre that would lie flat over a wall: the points above it are tried
                flat_over_wall(tr, walls, c)
            }
        });
        match res {
            Inserted::Yes(_) => {
                debug_assert_eq!(lfs.len(), p as usize);
                lfs.push(c_lfs);
                let region = labels.get(t);
                inherit(tr, labels, region);
                queue_created(tr, labels, &mut heap);
                out.volume_points += 1;
            }
            _ => {
                tr.remove_last_point();
                // the centre encroaches a subface: split it (or the subsegment its own centre
                // encroaches), as Delaunay refinement of a piecewise linear complex does, and
                // try the bad tet again if it still stands
                if let (Inserted::Rejected(..), Some(w), Some(sm), Some(edges)) = (res, encroached, boundary.as_deref_mut(), edges.as_mut()) {
                    let size_at = |tr: &Tetra, near: &[u32], q: DVec3| inherited_lfs(&lfs, tr, near, q);
                    if let Some((b, b_lfs)) = split_wall(tr, sm, edges, labels, &size_at, w, SPLIT_FLOOR, r_min) {
                        debug_assert_eq!(lfs.len(), b as usize);
                        lfs.push(b_lfs);
                        out.boundary_points += 1;
                        queue_created(tr, labels, &mut heap);
                        if tr.tets[t as usize].v == v {
                            if let Some(q) = badness(tr, t, size, opts, labels.get(t)) {
                                heap.push(q, t, fingerprint(v));
                            }
                        }
                        continue;
                    }
                }
                // the centre lies beyond the boundary: a point inside, in the same sphere,
                // still breaks the tet up (off-centres towards the tet, then points above its
                // walls at a good height)
                let region = labels.get(t);
                let lmin = tet_sphere(tr, t).2.max(2.0 * r_min);
                let mut done = false;
                for q in inside_candidates(tr, t, if let Inserted::Rejected(wt, wk) = res { Some((wt, wk)).filter(|w| w.0 != NONE) } else { None }) {
                    // not too near any vertex it would join: half the tet's shortest edge, and
                    // never under half the local feature size there (the sizes of the
                    // boundary's vertices, carried on 1-Lipschitz), so that points off the
                    // centre do not cascade into ever shorter edges beside a wall
                    let q_lfs = inherited_lfs(&lfs, tr, &v, q);
                    let floor = (0.5 * lmin).max(LFS_FLOOR * q_lfs);
                    let p = tr.add_point(q);
                    tr.created.clear();
                    let res = tr.insert_checked_near(p, t, Some((floor, (0, 0))), |tr, faces| {
                        let near = faces.iter().flat_map(|x| x.0).filter(|&x| x != GHOST).any(|x| tr.point(x).distance(q) < floor);
                        if near { Some((0, 0)) } else { encroached_wall(tr, faces, q).map(|w| w.1).or_else(|| flat_over_wall(tr, faces, q)) }
                    });
                    if let Inserted::Yes(_) = res {
                        debug_assert_eq!(lfs.len(), p as usize);
                        lfs.push(q_lfs);
                        inherit(tr, labels, region);
                        queue_created(tr, labels, &mut heap);
                        out.volume_points += 1;
                        done = true;
                        break;
                    }
                    tr.remove_last_point();
                }
                if !done {
                    out.rejected += 1;
                }
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_lies_flat_over_a_wall_only_low_and_above_its_circumcircle() {
        // a right triangle with legs 1: circumcircle about (0.5, 0.5), radius 0.707; longest
        // edge 1.414, so "low" is under 0.283
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        // under the rim, outside the diametral sphere (distance to the centre 0.718 > 0.707)
        let rim = DVec3::new(1.0, 1.0, 0.0) * (0.5 + 0.69 / 2f64.sqrt());
        assert!(flat_over(t, rim + DVec3::Z * 0.2));
        assert!(flat_over(t, rim - DVec3::Z * 0.2), "either side of the plane");
        // too high, or beyond the circumcircle
        assert!(!flat_over(t, rim + DVec3::Z * 0.3));
        assert!(!flat_over(t, DVec3::new(1.3, 1.3, 0.05)));
        // a degenerate wall has no plane to lie flat over
        assert!(!flat_over([DVec3::ZERO, DVec3::X, DVec3::X * 2.0], DVec3::new(0.5, 0.0, 0.01)));
    }
}
