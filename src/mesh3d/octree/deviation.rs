//! How far the octree mesh's boundary is from the input surface: the two one-sided
//! Hausdorff distances, sampled, with an upper bound; and the input's feature edges that the
//! cell size does not resolve.
//!
//! Stage: the octree mesher's report. Input: the input [`TriSurface`] and its BVH, the
//! [`TetMesh`] with its boundary, the cell size `h` and the feature angle. Output:
//! [`Deviation`].
//!
//! # Invariants
//! - Each triangle (of either surface) is sampled on a barycentric grid of `k` steps per
//!   side, `k` from its longest edge over `h / 2` (1 to 16). The distance to a surface is
//!   1-Lipschitz, so the true one-sided distance is at most the sampled maximum plus the
//!   grid's spacing (corners are measured once per vertex) (the longest edge over `k`): `hausdorff_bound` is that upper bound, never
//!   an estimate below the truth; `hausdorff` is the largest distance actually found.
//! - A feature edge is an input edge of exactly two triangles whose normals turn by more
//!   than the feature angle. It is *resolved* when every sample along it (spacing at most
//!   `h / 4`) lies within `h` of the mesh's boundary.
//! - Distances come from exact closest points on triangles and branch and bound on BVHs:
//!   the report depends only on the input; it is computed in parallel, reduced by `max`.

use crate::core::Aabb;
use crate::core::bvh::Bvh;
use crate::core::closest::point_triangle_distance;
use crate::mesh::{TetMesh, TriSurface};
use glam::DVec3;
use rayon::prelude::*;
use serde::Serialize;

/// How many unresolved feature edges a report lists.
pub const EXAMPLES: usize = 5;

/// The boundary's deviation from the input; see the module docs.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Deviation {
    /// Largest sampled distance from the mesh's boundary to the input.
    pub mesh_to_input: f64,
    /// Largest sampled distance from the input to the mesh's boundary.
    pub input_to_mesh: f64,
    /// The larger of the two: the sampled Hausdorff distance.
    pub hausdorff: f64,
    /// An upper bound of the true Hausdorff distance (sampled plus sample spacing).
    pub hausdorff_bound: f64,
    /// Points sampled on both surfaces.
    pub samples: usize,
    /// The feature angle, degrees.
    pub feature_angle_deg: f64,
    /// Input feature edges.
    pub feature_edges: usize,
    /// Feature edges with a point farther than the cell size from the mesh's boundary.
    pub unresolved_feature_edges: usize,
    /// Largest distance from a feature edge sample to the mesh's boundary.
    pub feature_max_distance: f64,
    /// The first unresolved feature edges (their end points).
    pub unresolved_examples: Vec<[[f64; 3]; 2]>,
}

/// Measures the deviation of `mesh`'s boundary from `surface`; see the module docs.
pub fn deviation(surface: &TriSurface, surface_bvh: &Bvh, mesh: &TetMesh, h: f64, feature_angle_deg: f64) -> Deviation {
    let bnd = TriSurface::with_single_tag(mesh.vertices.clone(), mesh.boundary.clone(), crate::core::FaceId(1));
    let bnd_boxes: Vec<Aabb> = (0..bnd.triangles.len()).map(|t| Aabb::from_points(&bnd.corners(t))).collect();
    let bnd_bvh = Bvh::from_boxes(&bnd_boxes);
    let (m2i, m2i_bound, n1) = one_sided(&bnd, surface, surface_bvh, h);
    let (i2m, i2m_bound, n2) = one_sided(surface, &bnd, &bnd_bvh, h);
    let mut d = Deviation {
        mesh_to_input: m2i,
        input_to_mesh: i2m,
        hausdorff: m2i.max(i2m),
        hausdorff_bound: m2i_bound.max(i2m_bound),
        samples: n1 + n2,
        feature_angle_deg,
        ..Deviation::default()
    };
    let features = feature_edges(surface, feature_angle_deg);
    d.feature_edges = features.len();
    let per_edge: Vec<f64> = features
        .par_iter()
        .map(|&[a, b]| {
            let (pa, pb) = (surface.vertices[a as usize], surface.vertices[b as usize]);
            let k = ((pa.distance(pb) / (0.25 * h)).ceil() as usize).clamp(1, 1024);
            let mut hint = None;
            let mut worst: f64 = 0.0;
            for i in 0..=k {
                if let Some((t, d)) = nearest_from(&bnd, &bnd_bvh, pa + (pb - pa) * (i as f64 / k as f64), hint) {
                    worst = worst.max(d);
                    hint = Some(t);
                }
            }
            worst
        })
        .collect();
    for (e, &dist) in features.iter().zip(&per_edge) {
        d.feature_max_distance = d.feature_max_distance.max(dist);
        if dist > h {
            d.unresolved_feature_edges += 1;
            if d.unresolved_examples.len() < EXAMPLES {
                d.unresolved_examples.push(e.map(|v| surface.vertices[v as usize].to_array()));
            }
        }
    }
    d
}

/// The nearest triangle of `s` to `p` and its distance, the search bounded from the start by
/// triangle `hint` (the answer is the same).
fn nearest_from(s: &TriSurface, bvh: &Bvh, p: DVec3, hint: Option<u32>) -> Option<(u32, f64)> {
    bvh.nearest_from(p, hint, |t| point_triangle_distance(p, s.corners(t as usize)))
}

/// Largest sampled distance from `from` to `to`, its upper bound, and the number of samples.
/// The corners are sampled once per vertex (shared by the triangles around it).
fn one_sided(from: &TriSurface, to: &TriSurface, to_bvh: &Bvh, h: f64) -> (f64, f64, usize) {
    let mut used = vec![false; from.vertices.len()];
    for t in &from.triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    let at_vertex: Vec<f64> =
        from.vertices.par_iter().zip(&used).map(|(&p, &u)| if u { nearest_from(to, to_bvh, p, None).map_or(f64::INFINITY, |x| x.1) } else { 0.0 }).collect();
    let corners = used.iter().filter(|&&u| u).count();
    let (worst, bound, n) = (0..from.triangles.len())
        .into_par_iter()
        .map(|t| {
            let [a, b, c] = from.corners(t);
            let longest = a.distance(b).max(b.distance(c)).max(c.distance(a));
            let k = ((longest / (0.5 * h)).ceil() as usize).clamp(1, 16);
            let mut worst = from.triangles[t].iter().map(|&v| at_vertex[v as usize]).fold(0.0, f64::max);
            let mut n = 0;
            // neighbouring samples start from the last one's nearest triangle
            let mut hint = None;
            for i in 0..=k {
                for j in 0..=k - i {
                    if (i == 0 && (j == 0 || j == k)) || i == k {
                        continue; // a corner
                    }
                    let (u, v) = (i as f64 / k as f64, j as f64 / k as f64);
                    if let Some((t, d)) = nearest_from(to, to_bvh, a + (b - a) * u + (c - a) * v, hint) {
                        worst = worst.max(d);
                        hint = Some(t);
                    }
                    n += 1;
                }
            }
            (worst, worst + longest / k as f64, n)
        })
        .reduce(|| (0.0, 0.0, 0), |x, y| (x.0.max(y.0), x.1.max(y.1), x.2 + y.2));
    (worst, bound, n + corners)
}

/// The input edges of exactly two triangles whose normals turn by more than `angle_deg`.
pub fn feature_edges(s: &TriSurface, angle_deg: f64) -> Vec<[u32; 2]> {
    let mut rec: Vec<([u32; 2], u32)> = Vec::with_capacity(3 * s.triangles.len());
    for (t, tri) in s.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            rec.push(([a.min(b), a.max(b)], t as u32));
        }
    }
    rec.sort_unstable();
    let normal = |t: u32| {
        let [a, b, c] = s.corners(t as usize);
        (b - a).cross(c - a).normalize_or_zero()
    };
    let cos = angle_deg.to_radians().cos();
    let mut out = Vec::new();
    let mut i = 0;
    while i < rec.len() {
        let mut j = i + 1;
        while j < rec.len() && rec[j].0 == rec[i].0 {
            j += 1;
        }
        if j - i == 2 {
            let (n1, n2) = (normal(rec[i].1), normal(rec[i + 1].1));
            if n1 != DVec3::ZERO && n2 != DVec3::ZERO && n1.dot(n2) < cos {
                out.push(rec[i].0);
            }
        }
        i = j;
    }
    out
}
