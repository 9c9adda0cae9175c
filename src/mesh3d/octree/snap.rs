//! Feature snapping: boundary vertices of the stuffed mesh moved onto the input's feature
//! edges and corners, where every tet they touch keeps its angles in [15°, 160°] (inside the
//! paper's bounds) or no worse than they were.
//!
//! Why: isosurface stuffing treats the surface as a smooth isosurface, so it cuts sharp edges
//! and corners off by up to about a cell (a bevel of boundary triangles across the edge):
//! the input's edge is then that far from the mesh, the Hausdorff distance's largest term on
//! CAD parts (wing_fuselage's trailing edge, Zylkopf's fins).
//!
//! Stage: inside `mesh_at`, after the boundary faces and before the deviation is measured.
//! Input: the input [`TriSurface`], the mesh with its boundary, the cell size `h`, the feature
//! angle. Output: boundary vertices moved in place, and [`Snapped`].
//!
//! # Invariants
//! - Feature edges are those of
//!   [`feature_edges_with_triangles`](super::deviation::feature_edges_with_triangles), found
//!   once by the caller; feature corners are their ends where the feature edges do not run
//!   on as one line: one or three or more meet, or two turn by more than the feature angle.
//! - Only boundary vertices move, each at most once, onto a point of a feature edge (its
//!   closest) or onto a corner, within [`REACH`] cells. Corners go first (each takes its
//!   nearest boundary vertex if it is that vertex's nearest corner), then the other boundary
//!   vertices by their distance to the features, nearest first, ties by index: serial, so the
//!   result is the same bytes on any thread count. A vertex whose boundary neighbour was
//!   snapped within half a cell of its own target is left (the edge has a vertex there).
//! - A move is kept only when every tet at the vertex stays positively oriented (exact
//!   [`orient3d`]), its dihedral angles stay within [`FLOOR`] (or no worse than before for a
//!   tet already outside), no boundary triangle at the vertex
//!   turns by 90° or more, the vertex's old place (a point of the input) and every feature
//!   corner within a cell of it stay within half a cell of those triangles (or, a corner, no
//!   farther than before), and they stay near the input (centroids and edge midpoints at
//!   the vertex within half a cell of it, or no farther than before); else half the move is
//!   tried, and then none.
//! - Connectivity, tags and regions are untouched; the boundary stays a face set of the mesh.

use super::deviation::Feature;
#[cfg(test)]
use super::{MAX_DIHEDRAL, MIN_DIHEDRAL};
use crate::core::Aabb;
use crate::core::bvh::Bvh;
use crate::core::closest::{closest_point_on_segment, point_triangle_distance};
use crate::core::predicates::orient3d;
use crate::mesh::{TetMesh, TriSurface};
use crate::quality::tetrahedron::tet_min_max_dihedral;
use glam::DVec3;
use rayon::prelude::*;
use serde::Serialize;

/// How far a boundary vertex may move onto a feature, in cells.
pub const REACH: f64 = 1.5;

/// The dihedral angles a move may take a tet to (degrees), or no worse than it was: well
/// inside the paper's [`super::MIN_DIHEDRAL`], [`super::MAX_DIHEDRAL`], so that snapping does
/// not spend the stencils' margin (at the paper's bounds themselves the corpus' smallest
/// angles fell from 15–20° to 10.7°).
pub const FLOOR: [f64; 2] = [15.0, 160.0];

/// What snapping did.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Snapped {
    /// Boundary vertices moved onto (or half way to) a feature corner.
    pub corners: usize,
    /// Boundary vertices moved onto (or half way to) a feature edge.
    pub edge_vertices: usize,
    /// Moves refused, whole and half, because a tet at the vertex would leave the bounds or
    /// the boundary the input.
    pub refused: usize,
}

/// The vertex stars of the listed vertices: `(offsets, tets)` in CSR form, over `wanted`.
fn stars(mesh: &TetMesh, wanted: &[bool]) -> (Vec<u32>, Vec<u32>) {
    let mut count = vec![0u32; mesh.vertices.len() + 1];
    for t in &mesh.tets {
        for &v in t {
            if wanted[v as usize] {
                count[v as usize + 1] += 1;
            }
        }
    }
    for i in 1..count.len() {
        count[i] += count[i - 1];
    }
    let mut fill = count.clone();
    let mut tets = vec![0u32; count[mesh.vertices.len()] as usize];
    for (t, tet) in mesh.tets.iter().enumerate() {
        for &v in tet {
            if wanted[v as usize] {
                tets[fill[v as usize] as usize] = t as u32;
                fill[v as usize] += 1;
            }
        }
    }
    (count, tets)
}

/// The feature corners of `s` among the ends of `features`.
fn corners(s: &TriSurface, features: &[Feature], angle_deg: f64) -> Vec<DVec3> {
    let mut at: Vec<Vec<u32>> = vec![Vec::new(); s.vertices.len()];
    for &([a, b], _) in features {
        at[a as usize].push(b);
        at[b as usize].push(a);
    }
    let cos = angle_deg.to_radians().cos();
    at.iter()
        .enumerate()
        .filter(|(v, n)| match n.as_slice() {
            [] => false,
            [a, b] => {
                let p = s.vertices[*v];
                let (u, w) = ((p - s.vertices[*a as usize]).normalize_or_zero(), (s.vertices[*b as usize] - p).normalize_or_zero());
                u.dot(w) < cos
            }
            _ => true,
        })
        .map(|(v, _)| s.vertices[v])
        .collect()
}

/// The surface a move must stay near: the input's triangles, their BVH, and how near.
struct Near<'a> {
    surface: &'a TriSurface,
    bvh: &'a Bvh,
    /// Half the cell: a boundary triangle's centroid or edge midpoint may end up this far from
    /// the input, or as far as it was.
    slack: f64,
    /// The feature corners and their BVH: no move takes the boundary farther from one.
    corners: &'a [DVec3],
    corner_bvh: &'a Bvh,
}

impl Near<'_> {
    /// The distance from `p` to the input, the search bounded from the start by triangle
    /// `hint` (the distance is the same).
    fn distance(&self, p: DVec3, hint: Option<u32>) -> f64 {
        self.bvh.nearest_from(p, hint, |t| point_triangle_distance(p, self.surface.corners(t as usize))).map_or(f64::INFINITY, |(_, d)| d)
    }

    /// The input triangle nearest to `p`.
    fn nearest(&self, p: DVec3) -> Option<u32> {
        self.bvh.nearest(p, |t| point_triangle_distance(p, self.surface.corners(t as usize))).map(|(t, _)| t)
    }

    /// The centroid and the edge midpoints at `v` of boundary triangle `f`.
    fn samples(f: &[u32; 3], v: u32, at: impl Fn(u32) -> DVec3) -> [DVec3; 3] {
        let p = f.map(&at);
        let k = f.iter().position(|&w| w == v).unwrap_or(0);
        let c = (p[0] + p[1] + p[2]) / 3.0;
        [c, 0.5 * (p[k] + p[(k + 1) % 3]), 0.5 * (p[k] + p[(k + 2) % 3])]
    }
}

/// Whether vertex `v` may stand at `q`: every tet of its star positive and within the bounds
/// (or no worse than before), no boundary triangle at it turned by 90° or more, and each of
/// those triangles' centroid and edge midpoints at `v` within the slack of the input (or no
/// farther than before).
/// `hint` is the input triangle nearest to the vertex's place, where the distances of the
/// samples around it are searched from.
fn allowed(mesh: &TetMesh, star: &[u32], v: u32, q: DVec3, at_v: &[[u32; 3]], near: &Near, hint: Option<u32>) -> bool {
    let old = mesh.vertices[v as usize];
    // the position of vertex `w` with `v` at `to`
    let at = |to: DVec3| move |w: u32| if w == v { to } else { mesh.vertices[w as usize] };
    for &t in star {
        let tet = &mesh.tets[t as usize];
        let p = tet.map(at(q));
        if !orient3d(p[0], p[1], p[2], p[3]).is_positive() {
            return false;
        }
        let (lo, hi) = tet_min_max_dihedral(&p);
        if lo < FLOOR[0] || hi > FLOOR[1] {
            let (lo0, hi0) = tet_min_max_dihedral(&tet.map(at(old)));
            if lo < lo0.min(FLOOR[0]) || hi > hi0.max(FLOOR[1]) {
                return false;
            }
        }
    }
    let normal = |f: &[u32; 3], to: DVec3| {
        let p = f.map(at(to));
        (p[1] - p[0]).cross(p[2] - p[0])
    };
    if !at_v.iter().all(|f| normal(f, q).dot(normal(f, old)) > 0.0) {
        return false;
    }
    // the input where the vertex was (it lies on the input) stays near the boundary
    let left = at_v
        .iter()
        .map(|f| {
            let p = f.map(at(q));
            point_triangle_distance(old, p)
        })
        .fold(f64::INFINITY, f64::min);
    if left > near.slack {
        return false;
    }
    // a corner near the vertex (a sharp tip the lattice does not reach) keeps its distance
    let reach = Aabb { min: old - DVec3::splat(2.0 * near.slack), max: old + DVec3::splat(2.0 * near.slack) };
    let mut kept = true;
    near.corner_bvh.for_each_overlapping(&reach, |c| {
        let c = near.corners[c as usize];
        let to = |x: DVec3| at_v.iter().map(|f| point_triangle_distance(c, f.map(at(x)))).fold(f64::INFINITY, f64::min);
        let d = to(q);
        kept &= d <= near.slack || d <= to(old);
    });
    if !kept {
        return false;
    }
    at_v.iter().all(|f| {
        let new = Near::samples(f, v, at(q));
        let was = Near::samples(f, v, at(old));
        new.iter().zip(&was).all(|(&a, &b)| {
            // within the slack of the hint triangle is within it of the input: no search
            if hint.is_some_and(|t| point_triangle_distance(a, near.surface.corners(t as usize)) <= near.slack) {
                return true;
            }
            let d = near.distance(a, hint);
            d <= near.slack || d <= near.distance(b, hint)
        })
    })
}

/// The ends of feature edge `e`.
fn segment(surface: &TriSurface, features: &[Feature], e: u32) -> [DVec3; 2] {
    features[e as usize].0.map(|v| surface.vertices[v as usize])
}

/// A BVH over the feature edges' boxes.
fn feature_bvh(surface: &TriSurface, features: &[Feature]) -> Bvh {
    Bvh::build((0..features.len() as u32).map(|e| (e, Aabb::from_points(&segment(surface, features, e)))))
}

/// Per point: whether it lies within [`REACH`] cells of a feature edge (a hair more, so
/// that every boundary vertex [`snap_features`] may move at `points` is among them: a
/// corner move's vertex is within reach of its corner, an end of a feature edge).
pub fn within_reach(surface: &TriSurface, features: &[Feature], h: f64, points: &[DVec3]) -> Vec<bool> {
    if features.is_empty() {
        return vec![false; points.len()];
    }
    let reach = REACH * h * (1.0 + 1e-6);
    let bvh = feature_bvh(surface, features);
    points
        .par_iter()
        .map(|&p| {
            bvh.nearest_within(p, reach, |e| {
                let [a, b] = segment(surface, features, e);
                closest_point_on_segment(p, a, b).distance(p)
            })
            .is_some()
        })
        .collect()
}

/// Snaps `mesh`'s boundary vertices onto the feature edges and corners of `surface`; see the
/// module docs.
/// `features` are the input's
/// [`feature_edges_with_triangles`](super::deviation::feature_edges_with_triangles) at
/// `angle_deg`.
pub fn snap_features(surface: &TriSurface, surface_bvh: &Bvh, mesh: &mut TetMesh, h: f64, angle_deg: f64, features: &[Feature]) -> Snapped {
    let mut out = Snapped::default();
    if features.is_empty() || mesh.boundary.is_empty() {
        return out;
    }
    let reach = REACH * h;
    let seg = |e: u32| segment(surface, features, e);
    let fbvh = feature_bvh(surface, features);
    let nv = mesh.vertices.len();
    let mut on_boundary = vec![false; nv];
    for f in &mesh.boundary {
        f.iter().for_each(|&v| on_boundary[v as usize] = true);
    }
    // each boundary vertex's nearest feature point within reach
    let target: Vec<Option<(f64, DVec3)>> = (0..nv)
        .into_par_iter()
        .map(|v| {
            if !on_boundary[v] {
                return None;
            }
            let p = mesh.vertices[v];
            let (e, d) = fbvh.nearest_within(p, reach, |e| {
                let [a, b] = seg(e);
                closest_point_on_segment(p, a, b).distance(p)
            })?;
            let [a, b] = seg(e);
            (d > 0.0 && d <= reach).then(|| (d, closest_point_on_segment(p, a, b)))
        })
        .collect();
    // corners: each takes its nearest boundary vertex within reach
    let boundary_vertices: Vec<u32> = (0..nv as u32).filter(|&v| on_boundary[v as usize]).collect();
    let vbvh = Bvh::build(boundary_vertices.iter().enumerate().map(|(i, &v)| {
        let p = mesh.vertices[v as usize];
        (i as u32, Aabb { min: p, max: p })
    }));
    let mut moves: Vec<(u8, f64, u32, DVec3)> = Vec::new();
    let corners = corners(surface, features, angle_deg);
    let cbvh = Bvh::build(corners.iter().enumerate().map(|(i, &c)| (i as u32, Aabb { min: c, max: c })));
    let near = Near { surface, bvh: surface_bvh, slack: 0.5 * h, corners: &corners, corner_bvh: &cbvh };
    for (k, &c) in corners.iter().enumerate() {
        let Some((i, d)) = vbvh.nearest_within(c, reach, |i| mesh.vertices[boundary_vertices[i as usize] as usize].distance(c)) else {
            continue;
        };
        let v = boundary_vertices[i as usize];
        // only a vertex whose nearest corner this is: a vertex near a sharp tip is not pulled
        // back to a corner behind it
        let p = mesh.vertices[v as usize];
        let mine = cbvh.nearest_within(p, d * (1.0 + 1e-9) + f64::MIN_POSITIVE, |j| corners[j as usize].distance(p)).is_some_and(|(j, _)| j as usize == k);
        if d > 0.0 && d <= reach && mine {
            moves.push((0, d, v, c));
        }
    }
    moves.extend(target.iter().enumerate().filter_map(|(v, t)| t.map(|(d, q)| (1, d, v as u32, q))));
    moves.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)).then(a.2.cmp(&b.2)));
    let mut wanted = vec![false; nv];
    moves.iter().for_each(|m| wanted[m.2 as usize] = true);
    let (off, star) = stars(mesh, &wanted);
    // boundary triangles and neighbours at each wanted vertex
    let mut tri_at: Vec<Vec<[u32; 3]>> = vec![Vec::new(); nv];
    for f in &mesh.boundary {
        for &v in f {
            if wanted[v as usize] {
                tri_at[v as usize].push(*f);
            }
        }
    }
    // each moving vertex's nearest input triangle, from its place (a vertex moves once, so
    // it is still there when its move is weighed)
    let hints: Vec<Option<u32>> = moves.par_iter().map(|m| near.nearest(mesh.vertices[m.2 as usize])).collect();
    let mut snapped_to: Vec<Option<DVec3>> = vec![None; nv];
    for ((kind, _, v, q), hint) in moves.into_iter().zip(hints) {
        if snapped_to[v as usize].is_some() {
            continue;
        }
        let tris = &tri_at[v as usize];
        if kind == 1 && tris.iter().flatten().any(|&w| w != v && snapped_to[w as usize].is_some_and(|s| s.distance(q) < 0.5 * h)) {
            continue;
        }
        let s = &star[off[v as usize] as usize..off[v as usize + 1] as usize];
        let p = mesh.vertices[v as usize];
        let half = 0.5 * (p + q);
        let to = if allowed(mesh, s, v, q, tris, &near, hint) {
            Some(q)
        } else if allowed(mesh, s, v, half, tris, &near, hint) {
            out.refused += 1;
            Some(half)
        } else {
            out.refused += 2;
            None
        };
        if let Some(to) = to {
            mesh.vertices[v as usize] = to;
            snapped_to[v as usize] = Some(to);
            if kind == 0 {
                out.corners += 1;
            } else {
                out.edge_vertices += 1;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3d::octree::{OctreeOptions, mesh_octree};

    /// A box `[0, a] × [0, b] × [0, c]`, twelve triangles, outward.
    fn cuboid(a: f64, b: f64, c: f64) -> TriSurface {
        let mut s = crate::mesh3d::octree::tests::cube_surface(1);
        s.vertices.iter_mut().for_each(|p| *p *= DVec3::new(a, b, c));
        s
    }

    /// On a box whose sides are no multiple of the cell, stuffing bevels the edges; snapping
    /// brings the corners and edges back within the angle bounds, and the mesh stays valid.
    #[test]
    fn a_box_gets_its_corners_and_edges_back() {
        let s = cuboid(1.03, 0.77, 0.59);
        let size = crate::core::size_field::UniformSize(0.13);
        let (mesh, report) = mesh_octree(&s, &size, &OctreeOptions::default()).unwrap();
        assert_eq!(mesh.validate(), Ok(()));
        let sn = report.snapped.clone();
        assert!(sn.corners >= 6 && sn.edge_vertices > 20, "{sn:?}");
        let [lo, hi] = report.dihedral;
        assert!(lo >= MIN_DIHEDRAL && hi <= MAX_DIHEDRAL, "{lo} {hi}");
        let unsnapped = mesh_octree(&s, &size, &OctreeOptions { snap: false, ..OctreeOptions::default() }).unwrap().1;
        assert!(
            report.deviation.hausdorff < unsnapped.deviation.hausdorff,
            "{} vs {}",
            report.deviation.hausdorff,
            unsnapped.deviation.hausdorff
        );
        // nearer the box's volume
        let v = 1.03 * 0.77 * 0.59;
        assert!((report.volume - v).abs() < (unsnapped.volume - v).abs(), "{} {} {v}", report.volume, unsnapped.volume);
    }
}
