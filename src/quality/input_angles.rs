//! The small angles of a closed tagged surface, which bound the quality of any tet mesh of it
//! that keeps the surface.
//!
//! Two kinds, both measured on the input as given:
//! - **dihedral**: at an edge shared by exactly two triangles, the angle between them measured
//!   inside the solid (90° at a cube's edge, 270° at a re-entrant edge, 3° at a knife edge).
//!   A tet with a face on each side of a knife edge has a dihedral angle no larger than it.
//!   Edges inside one flat piece of one tag ([`crate::mesh::topology::flat_pieces`], the
//!   mesher's facets) are not features. Edges with one or
//!   more than two triangles, or whose two triangles run the edge the same way (inconsistent
//!   orientation), have no inside angle and are left out.
//! - **corner**: at a vertex, the angle of a flat piece of one face between two feature edges:
//!   with `merge_flat`, the corner of the flat piece of one tag around it (the facets the
//!   mesher merges, so the thin triangles of a flat STL face do not count); without
//!   (`--keep-surface`: every triangle is kept as it is), each triangle's own corner. A vertex
//!   inside a flat region (its corners closing round it) has no corner.
//!
//! Only angles below a bound are listed, smallest first. Plain floating point: these are
//! figures for reports, no decision of the mesher depends on them.

use crate::core::FaceId;
use crate::core::bucket_sort::collect_sorted_by_lead;
use crate::core::union_find::UnionFind;
use crate::mesh::topology::flat_pieces;
use crate::mesh::TriSurface;
use glam::DVec3;
use serde::Serialize;

/// What kind of input angle.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum InputAngleKind {
    /// Between two input triangles at an edge, inside the solid.
    Dihedral,
    /// A corner of a flat piece of one face (or of one input triangle).
    Corner,
}

/// One small angle of the input surface.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct InputAngle {
    /// Dihedral or corner.
    pub kind: InputAngleKind,
    /// The angle, degrees.
    pub angle_deg: f64,
    /// Where it is: a dihedral angle's edge (its two endpoints), a corner's vertex (twice).
    pub at: [[f64; 3]; 2],
    /// The faces: on either side of the edge (smaller tag first), or the corner's face twice.
    pub faces: [FaceId; 2],
    /// The faces across its two sides: a dihedral angle's two faces (as `faces`); beyond the
    /// two edges that make a corner, each the face of the triangle across that edge (the
    /// corner's own face where a side has no other triangle).
    pub across: [FaceId; 2],
}

impl InputAngle {
    /// The distance from `p` to where the angle is (its edge, or its vertex).
    pub fn distance(&self, p: DVec3) -> f64 {
        let [a, b] = self.at.map(DVec3::from_array);
        crate::core::closest::closest_point_on_segment(p, a, b).distance(p)
    }
}

/// The angles of `surface` below `bound_deg` degrees, smallest first (ties: dihedral before
/// corner, then by place); see the module documentation for what is measured.
pub fn small_input_angles(surface: &TriSurface, bound_deg: f64, merge_flat: bool) -> Vec<InputAngle> {
    let edges = edge_triangles(surface);
    let pieces = flat_pieces(&surface.vertices, &surface.triangles, &surface.face_tags);
    let mut out = dihedral_angles(surface, &edges, &pieces, bound_deg);
    out.extend(corner_angles(surface, &edges, &pieces, bound_deg, merge_flat));
    out.sort_by(|x, y| {
        x.angle_deg
            .total_cmp(&y.angle_deg)
            .then((x.kind as u8).cmp(&(y.kind as u8)))
            .then_with(|| x.at.iter().flatten().zip(y.at.iter().flatten()).map(|(a, b)| a.total_cmp(b)).find(|o| o.is_ne()).unwrap_or(std::cmp::Ordering::Equal))
    });
    out
}

/// Every edge `(a, b)`, `a < b`, with the triangles on it, sorted by edge then triangle.
fn edge_triangles(s: &TriSurface) -> Vec<((u32, u32), Vec<u32>)> {
    let records = || {
        s.triangles.iter().enumerate().flat_map(|(i, t)| {
            (0..3).filter_map(move |k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                (a != b).then_some(((a.min(b), a.max(b)), i as u32))
            })
        })
    };
    // sorted in vertex buckets where every index is in range (linear), else in full
    let n = s.vertices.len();
    let list: Vec<((u32, u32), u32)> = if s.triangles.iter().flatten().all(|&v| (v as usize) < n) {
        collect_sorted_by_lead(n, records, |r| r.0.0)
    } else {
        let mut all: Vec<_> = records().collect();
        all.sort_unstable();
        all
    };
    list.chunk_by(|x, y| x.0 == y.0).map(|run| (run[0].0, run.iter().map(|r| r.1).collect())).collect()
}

fn normal(s: &TriSurface, t: u32) -> DVec3 {
    let [a, b, c] = s.corners(t as usize);
    (b - a).cross(c - a)
}

/// True when triangle `t` runs from `a` to `b`.
fn runs(s: &TriSurface, t: u32, a: u32, b: u32) -> bool {
    let v = s.triangles[t as usize];
    (0..3).any(|k| v[k] == a && v[(k + 1) % 3] == b)
}

/// The vertex of `t` that is neither `a` nor `b`.
fn third(s: &TriSurface, t: u32, a: u32, b: u32) -> u32 {
    s.triangles[t as usize].into_iter().find(|&v| v != a && v != b).unwrap_or(a)
}

fn tag(s: &TriSurface, t: u32) -> FaceId {
    s.face_tags.get(t as usize).copied().unwrap_or_default()
}

fn dihedral_angles(s: &TriSurface, edges: &[((u32, u32), Vec<u32>)], pieces: &[u32], bound_deg: f64) -> Vec<InputAngle> {
    // an inward-oriented surface (negative volume) has its inside on the other side
    let volume: f64 = s.triangles.iter().map(|t| {
        let [a, b, c] = t.map(|i| s.vertices[i as usize]);
        a.dot(b.cross(c))
    }).sum();
    let outward = volume >= 0.0;
    let mut out = Vec::new();
    for &((a, b), ref ts) in edges {
        let &[x, y] = ts.as_slice() else { continue };
        // x must run a -> b and y b -> a (consistently oriented)
        let (x, y) = if runs(s, x, a, b) && runs(s, y, b, a) {
            (x, y)
        } else if runs(s, y, a, b) && runs(s, x, b, a) {
            (y, x)
        } else {
            continue;
        };
        if pieces[x as usize] == pieces[y as usize] {
            continue;
        }
        let (pa, pb) = (s.vertices[a as usize], s.vertices[b as usize]);
        let e = (pb - pa).normalize_or_zero();
        let ux = (s.vertices[third(s, x, a, b) as usize] - pa).reject_from_normalized(e);
        let uy = (s.vertices[third(s, y, a, b) as usize] - pa).reject_from_normalized(e);
        if e == DVec3::ZERO || ux.length_squared() == 0.0 || uy.length_squared() == 0.0 {
            continue;
        }
        // the wedge between the two half-planes, and whether the solid fills it: y's
        // half-plane runs below x (against x's outward normal) at a convex edge
        let wedge = ux.angle_between(uy).to_degrees();
        let below = normal(s, x).dot(uy) < 0.0;
        let inside = if below == outward { wedge } else { 360.0 - wedge };
        if inside < bound_deg {
            let (tx, ty) = (tag(s, x), tag(s, y));
            let faces = [tx.min(ty), tx.max(ty)];
            out.push(InputAngle { kind: InputAngleKind::Dihedral, angle_deg: inside, at: [pa.to_array(), pb.to_array()], faces, across: faces });
        }
    }
    out
}

fn corner_angles(s: &TriSurface, edges: &[((u32, u32), Vec<u32>)], pieces: &[u32], bound_deg: f64, merge_flat: bool) -> Vec<InputAngle> {
    let n = s.triangles.len();
    // corner 3 t + k is triangle t's corner at its vertex k
    let corner = |t: u32, v: u32| s.triangles[t as usize].iter().position(|&w| w == v).map(|k| 3 * t + k as u32);
    let mut uf = UnionFind::new(3 * n);
    let mut flat_edges_at = vec![0u32; 3 * n];
    if merge_flat {
        for &((a, b), ref ts) in edges {
            let &[x, y] = ts.as_slice() else { continue };
            if pieces[x as usize] != pieces[y as usize] {
                continue;
            }
            for v in [a, b] {
                if let (Some(cx), Some(cy)) = (corner(x, v), corner(y, v)) {
                    uf.union(cx, cy);
                    flat_edges_at[cx as usize] += 1;
                }
            }
        }
    }
    // per group of corners (one vertex, one flat piece): the angle summed, corners and flat edges
    let mut sum = vec![0.0f64; 3 * n];
    let mut corners = vec![0u32; 3 * n];
    let mut flat_edges = vec![0u32; 3 * n];
    for t in 0..n as u32 {
        let v = s.triangles[t as usize].map(|i| s.vertices[i as usize]);
        for k in 0..3u32 {
            let c = 3 * t + k;
            let p = v[k as usize];
            let (u, w) = (v[((k + 1) % 3) as usize] - p, v[((k + 2) % 3) as usize] - p);
            let r = uf.find(c) as usize;
            if u.length_squared() > 0.0 && w.length_squared() > 0.0 {
                sum[r] += u.angle_between(w).to_degrees();
            }
            corners[r] += 1;
            flat_edges[r] += flat_edges_at[c as usize];
        }
    }
    let mut out = Vec::new();
    for c in 0..3 * n {
        // a closed fan (as many flat edges as corners) is a vertex inside a flat piece
        if !uf.is_root(c as u32) || flat_edges[c] >= corners[c] || sum[c] >= bound_deg {
            continue;
        }
        let t = (c / 3) as u32;
        let p = s.vertices[s.triangles[t as usize][c % 3] as usize].to_array();
        let f = tag(s, t);
        let across = corner_sides(s, edges, &mut uf, c as u32).map(|x| x.unwrap_or(f));
        out.push(InputAngle { kind: InputAngleKind::Corner, angle_deg: sum[c], at: [p, p], faces: [f, f], across });
    }
    out
}

/// The faces across the two sides of the corner group whose root is corner `root` (corner
/// `3 t + k` is triangle `t`'s at its vertex `k`): the tags of the triangles beyond the
/// group's two edges at its vertex, `None` where an edge has no other triangle. A corner's
/// group is one triangle or a flat piece's fan, so this looks only at the triangles of the
/// vertex.
fn corner_sides(s: &TriSurface, edges: &[((u32, u32), Vec<u32>)], uf: &mut UnionFind, root: u32) -> [Option<FaceId>; 2] {
    let t0 = root / 3;
    let v = s.triangles[t0 as usize][(root % 3) as usize];
    let on_edge = |a: u32, b: u32| edges.binary_search_by_key(&(a.min(b), a.max(b)), |e| e.0).ok().map(|k| &edges[k].1);
    let group = uf.find(root);
    // the group's triangles are among those on the edges at v; walk them from t0
    let mut sides: Vec<Option<FaceId>> = Vec::new();
    let mut seen: Vec<u32> = Vec::new();
    let mut todo = vec![t0];
    while let Some(t) = todo.pop() {
        if seen.contains(&t) || seen.len() > 64 {
            continue;
        }
        seen.push(t);
        let tri = s.triangles[t as usize];
        for w in tri.into_iter().filter(|&w| w != v) {
            let Some(ts) = on_edge(v, w) else { continue };
            let others: Vec<u32> = ts.iter().copied().filter(|&y| y != t).collect();
            let same = others.iter().copied().find(|&y| {
                s.triangles[y as usize].iter().position(|&x| x == v).is_some_and(|k| uf.find(3 * y + k as u32) == group)
            });
            match (same, others.as_slice()) {
                (Some(y), _) => todo.push(y),
                (None, [y]) => sides.push(Some(tag(s, *y))),
                (None, _) => sides.push(None),
            }
        }
    }
    [sides.first().copied().flatten(), sides.get(1).copied().flatten()]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A prism of height 1 on the triangle (0,0,0) (1,0,0) (cos a, sin a, 0): a knife edge of
    /// `angle_deg` degrees from (0,0,0) to (0,0,1), between faces 3 (y = 0) and 5.
    fn prism(angle_deg: f64) -> TriSurface {
        let a = angle_deg.to_radians();
        let base = [DVec3::ZERO, DVec3::X, DVec3::new(a.cos(), a.sin(), 0.0)];
        let mut vertices: Vec<DVec3> = base.to_vec();
        vertices.extend(base.iter().map(|p| *p + DVec3::Z));
        // outward: bottom down, top up, three sides
        let triangles = vec![[0, 2, 1], [3, 4, 5], [0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4], [2, 0, 3], [2, 3, 5]];
        let face_tags = [1, 2, 3, 3, 4, 4, 5, 5].map(FaceId).to_vec();
        TriSurface { vertices, triangles, face_tags, ..Default::default() }
    }

    #[test]
    fn a_knife_edge_is_a_small_dihedral_angle_and_small_corners() {
        let s = prism(3.0);
        let angles = small_input_angles(&s, 10.0, true);
        let d: Vec<&InputAngle> = angles.iter().filter(|x| x.kind == InputAngleKind::Dihedral).collect();
        assert_eq!(d.len(), 1, "{angles:?}");
        assert!((d[0].angle_deg - 3.0).abs() < 1e-9, "{}", d[0].angle_deg);
        assert_eq!(d[0].faces, [FaceId(3), FaceId(5)]);
        assert_eq!(d[0].at, [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]]);
        // the bottom and top triangles' corners at the knife edge
        let c: Vec<&InputAngle> = angles.iter().filter(|x| x.kind == InputAngleKind::Corner).collect();
        assert_eq!(c.len(), 2, "{angles:?}");
        assert!(c.iter().all(|x| (x.angle_deg - 3.0).abs() < 1e-9));
        assert!(angles.windows(2).all(|w| w[0].angle_deg <= w[1].angle_deg));
        // nothing below 2 degrees; the right angles of the sides are not small
        assert!(small_input_angles(&s, 2.0, true).is_empty());
        assert_eq!(small_input_angles(&prism(60.0), 50.0, true), Vec::new());
    }

    #[test]
    fn an_inward_surface_measures_the_same_inside() {
        let mut s = prism(3.0);
        for t in &mut s.triangles {
            t.swap(1, 2);
        }
        let d: Vec<InputAngle> = small_input_angles(&s, 10.0, true).into_iter().filter(|x| x.kind == InputAngleKind::Dihedral).collect();
        assert_eq!(d.len(), 1);
        assert!((d[0].angle_deg - 3.0).abs() < 1e-9);
    }

    #[test]
    fn thin_triangles_of_a_flat_face_have_no_corner_unless_kept() {
        // a unit cube whose top is split into thin triangles by a fan from one vertex
        let mut vertices = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ];
        let mut triangles = vec![[0, 2, 1], [0, 3, 2], [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]];
        let mut face_tags: Vec<FaceId> = [1, 1, 2, 2, 3, 3, 4, 4, 5, 5].map(FaceId).to_vec();
        // the top (z = 1): points along the edge from (1,0,1) to (1,1,1), joined to (0,0,1)
        let mut side = vec![5u32];
        for k in 1..20 {
            vertices.push(DVec3::new(1.0, k as f64 / 20.0, 1.0));
            side.push((vertices.len() - 1) as u32);
        }
        side.push(6);
        for w in side.windows(2) {
            triangles.push([4, w[0], w[1]]);
            face_tags.push(FaceId(6));
        }
        triangles.push([4, 6, 7]);
        face_tags.push(FaceId(6));
        // the side x = 1 now has the points on its top edge: split it into a fan from 1
        let k = triangles.iter().position(|t| *t == [1, 6, 5]).unwrap();
        triangles.remove(k);
        face_tags.remove(k);
        for w in side.windows(2) {
            triangles.push([1, w[1], w[0]]);
            face_tags.push(FaceId(3));
        }
        let s = TriSurface { vertices, triangles, face_tags, ..Default::default() };
        assert!(small_input_angles(&s, 10.0, true).is_empty(), "{:?}", small_input_angles(&s, 10.0, true));
        let kept = small_input_angles(&s, 10.0, false);
        assert!(!kept.is_empty() && kept.iter().all(|x| x.kind == InputAngleKind::Corner && x.angle_deg < 10.0));
    }
}
