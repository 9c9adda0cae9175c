//! How far the octree mesh's boundary is from the input surface: the two one-sided
//! Hausdorff distances, sampled, with an upper bound; and the input's feature edges that the
//! cell size does not resolve.
//!
//! Stage: the octree mesher's report. Input: the input [`TriSurface`] and its BVH, the
//! [`TetMesh`] with its boundary, the cell size `h` and the feature angle. Output:
//! [`Deviation`].
//!
//! # Invariants
//! - Each triangle (of either surface) is measured at its corners (once per vertex) and cut
//!   by longest-edge bisection, each new midpoint measured, until every piece is *settled*:
//!   with `r` its covering radius (below) and `m` its largest corner distance,
//!   `m + r ≤ h / 2`, or `r ≤ h / 8`, or the triangle's budget of 65,536 midpoints
//!   (`MAX_SPLITS`; in the second, buried-aware measure below, a share of 2 per triangle of
//!   the mesh's boundary, at least 1,024) is spent. A piece so settled with `m ≤ h < m + r` (its samples within the
//!   cell, its bound past it) is measured again *finely*, to `r ≤ h / 64` (and the thin rule
//!   below at `h / 64`), and if its fine bound still passes the cell, *closely*, to
//!   `r ≤ h / 256`: the bound is tight where it decides whether the boundary is within the
//!   cell, and the pieces far inside or far outside it cost no more. Every point of a piece lies within `r` of one of its corners, and the distance to
//!   a surface is 1-Lipschitz, so the true one-sided distance is at most the largest `m + r`
//!   over the pieces: `hausdorff_bound` is that upper bound, never an estimate below the
//!   truth; `hausdorff` is the largest distance actually found. Where no second measure
//!   follows (below), a piece bounded within the farthest corner of the whole surface is
//!   settled at once: it can hold no farther sample than that corner, and its bound does not
//!   pass it (a soup's boundary, floating off every input triangle, costs its corners).
//! - A piece thinner than `h / 16` (its altitude onto its longest side) is instead sampled
//!   along that side at spacing `h / 8`: its angles there are acute, so every point of it
//!   lies within the altitude of the side, and its bound is the side's sampled maximum plus
//!   half the spacing plus the altitude. Long thin triangles (long STL facets) cost their
//!   length over `h`, not its square.
//! - The covering radius (the largest distance from a point of the triangle to its nearest
//!   corner) is the circumradius of a triangle without an obtuse angle; with an obtuse angle
//!   at `C`, the farthest points lie on the longest side `AB`, where the perpendicular
//!   bisectors of `AC` and `BC` meet it, at `|AC| / (2 cos A)` and `|BC| / (2 cos B)`.
//! - Input that is not the boundary of the stuffed volume (`buried.rs`: a sheet inside it,
//!   where bodies overlap, or an inward shell outside it) is not measured: an input triangle
//!   whose measure passes the cell is measured again, its buried pieces left out and the
//!   samples taken from the pieces kept (a thin piece's side samples only where it is
//!   bounded there). Pieces the judge is unsure of (another triangle meets them) are kept, so
//!   the bound stays an upper bound over the boundary; one whose measure passes the cell is
//!   cut further, at the fine level even with its samples past the cell, and not bounded by
//!   the thin rule past the coarse level, so that its pieces clear of the triangles that
//!   meet it are judged (rabbit.obj: the sheets inside its overlapping bodies); at the
//!   coarse level a thin piece so unplaced is cut the same way, not bounded along its side.
//!   Pieces in gaps narrower than the seal between crossing shells are left out too
//!   (`buried.rs`), their area reported. A feature
//!   edge between two buried triangles is not counted.
//! - A feature edge is an input edge of exactly two triangles whose normals turn by more
//!   than the feature angle. It is *resolved* when every sample along it (spacing at most
//!   `h / 4`) lies within `h` of the mesh's boundary.
//! - Distances come from exact closest points on triangles and branch and bound on BVHs:
//!   the report depends only on the input; it is computed in parallel, reduced by `max`.

use super::buried::{Buried, Side};
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
    /// Where the sampled Hausdorff distance is reached (a sample of the mesh's boundary or of
    /// the input; the first such sample in triangle order).
    pub hausdorff_at: [f64; 3],
    /// An upper bound of the true Hausdorff distance (sampled plus sample spacing).
    pub hausdorff_bound: f64,
    /// Points sampled on both surfaces.
    pub samples: usize,
    /// Gaps narrower than this between input shells that cross each other are closed: their
    /// walls are left out of the input's distance to the mesh (`buried.rs`; 0: none).
    pub seal: f64,
    /// The input area so left out.
    pub sealed_area: f64,
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

/// Measures the deviation of `mesh`'s boundary from `surface`; see the module docs. Also
/// returns, per boundary triangle, the input triangle nearest to its centroid (the first
/// sample of that triangle; ties to the lower index): the tags come from it.
/// `features` are the input's `feature_edges_with_triangles` at `feature_angle_deg`
/// (made once by the caller, which snaps to them too).
pub fn deviation(surface: &TriSurface, surface_bvh: &Bvh, mesh: &TetMesh, h: f64, feature_angle_deg: f64, features: &[Feature], buried: Option<&Buried>) -> (Deviation, Vec<Option<u32>>) {
    let bnd = TriSurface::with_single_tag(mesh.vertices.clone(), mesh.boundary.clone(), crate::core::FaceId(1));
    // the boundary's BVH (for the input's side) is built while the boundary's side is measured
    let (bnd_bvh, (m2i, m2i_bound, n1, nearest, _)) = rayon::join(|| bnd.triangle_bvh(), || one_sided(&bnd, surface, surface_bvh, h, true, None));
    let (i2m, i2m_bound, n2, _, sealed_area) = one_sided(surface, &bnd, &bnd_bvh, h, false, buried);
    let ((m2i, m2i_at), (i2m, i2m_at)) = (m2i, i2m);
    let mut d = Deviation {
        mesh_to_input: m2i,
        input_to_mesh: i2m,
        hausdorff: m2i.max(i2m),
        hausdorff_at: if i2m > m2i { i2m_at } else { m2i_at }.to_array(),
        hausdorff_bound: m2i_bound.max(i2m_bound),
        samples: n1 + n2,
        seal: buried.map_or(0.0, Buried::seal),
        sealed_area,
        feature_angle_deg,
        ..Deviation::default()
    };
    d.feature_edges = features.len();
    let per_edge: Vec<f64> = features
        .par_iter()
        .map(|&([a, b], tris)| {
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
            // an edge between two buried triangles is no edge of the stuffed volume
            if worst > h && buried.is_some_and(|b| tris.iter().all(|&t| b.piece(t as usize, &surface.corners(t as usize)) == Side::Buried)) {
                return 0.0;
            }
            worst
        })
        .collect();
    for ((e, _), &dist) in features.iter().zip(&per_edge) {
        d.feature_max_distance = d.feature_max_distance.max(dist);
        if dist > h {
            d.unresolved_feature_edges += 1;
            if d.unresolved_examples.len() < EXAMPLES {
                d.unresolved_examples.push(e.map(|v| surface.vertices[v as usize].to_array()));
            }
        }
    }
    (d, nearest)
}

/// The nearest triangle of `s` to `p` and its distance, the search bounded from the start by
/// triangle `hint` (the answer is the same).
fn nearest_from(s: &TriSurface, bvh: &Bvh, p: DVec3, hint: Option<u32>) -> Option<(u32, f64)> {
    bvh.nearest_from(p, hint, |t| point_triangle_distance(p, s.corners(t as usize)))
}

/// Most midpoints measured per triangle (its bound stays honest, only looser, past them).
const MAX_SPLITS: usize = 1 << 16;

/// The second measure, leaving out what is buried (`buried.rs`), gets at most this many
/// midpoints per triangle of the mesh's boundary, shared among the input's triangles (at
/// least [`AWARE_MIN`] each): on a soup every piece near a crossing is unsure and would
/// otherwise be cut to the close measure along every crossing, 65,536 midpoints a triangle
/// for a mesh of a few thousand.
const AWARE_PER_BOUNDARY: usize = 2;

/// The least midpoints per triangle of the second measure.
const AWARE_MIN: usize = 1024;

/// The fine measure's covering radius, thin test and side spacing, in cells: a piece whose
/// coarse bound passes the cell is measured again to this.
const FINE: f64 = 1.0 / 64.0;

/// The measures' levels: coarse, fine, close. A piece whose samples are within the cell and
/// whose bound at one level passes it is measured again at the next.
const LEVELS: usize = 3;

/// Per level, the covering radius (in cells) at which a piece is settled.
const SETTLE: [f64; LEVELS] = [1.0 / 8.0, FINE, FINE / 4.0];

/// Per level, the altitude (in cells) under which a piece is thin.
const THIN: [f64; LEVELS] = [1.0 / 16.0, FINE, FINE / 4.0];

/// Per level, the spacing (in cells) of the samples on a thin piece's longest side.
const SPACING: [f64; LEVELS] = [1.0 / 8.0, FINE, FINE / 4.0];

/// Largest sampled distance from `from` to `to` and where it is reached (the first such
/// sample in triangle order), its upper bound, the number of samples, with `centroids` the triangle of `to` nearest to each triangle's centroid (sampled first), and the area of `from`
/// that `buried` sealed.
/// The corners are sampled once per vertex (shared by the triangles around it).
fn one_sided(from: &TriSurface, to: &TriSurface, to_bvh: &Bvh, h: f64, centroids: bool, buried: Option<&Buried>) -> ((f64, DVec3), f64, usize, Vec<Option<u32>>, f64) {
    let mut used = vec![false; from.vertices.len()];
    for t in &from.triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    // per vertex: the distance and the nearest triangle (a hint for the pieces around it)
    let at_vertex: Vec<(f64, Option<u32>)> = from
        .vertices
        .par_iter()
        .zip(&used)
        .map(|(&p, &u)| if u { nearest_from(to, to_bvh, p, None).map_or((f64::INFINITY, None), |x| (x.1, Some(x.0))) } else { (0.0, None) })
        .collect();
    let corners = used.iter().filter(|&&u| u).count();
    // without a second measure, every corner is a sample: a piece bounded within the
    // farthest corner can hold no farther sample, nor raise the bound past that sample
    let floor = if buried.is_none() { at_vertex.iter().map(|x| x.0).filter(|d| d.is_finite()).fold(0.0, f64::max) } else { 0.0 };
    // a piece is measured coarsely first (level 0); one whose samples are within the cell but
    // whose bound would pass it is measured again finely (level 1), and again closely (level
    // 2) if its fine bound still passes it: the bound is tight where it decides the cell's line
    let settled = |m: f64, r: f64, level: usize| m + r <= 0.5 * h || r <= SETTLE[level] * h;
    let aware_splits = (AWARE_PER_BOUNDARY * to.triangles.len() / from.triangles.len().max(1)).clamp(AWARE_MIN, MAX_SPLITS);
    // `aware`: the pieces buried in the stuffed volume (or outside it) are left out, and the
    // samples are those of the pieces kept
    let measure_as = |t: usize, aware: Option<&Buried>| {
        let tri = from.triangles[t];
        let centroid = centroids.then(|| {
            let p = tri.iter().map(|&v| from.vertices[v as usize]).sum::<DVec3>() / 3.0;
            // a corner's nearest triangle bounds the search (the answer is the same)
            nearest_from(to, to_bvh, p, tri.iter().find_map(|&v| at_vertex[v as usize].1))
        });
        let mut n = usize::from(centroid.is_some());
        let d = tri.map(|v| at_vertex[v as usize].0);
        // the largest distance and its sample, the first of equal ones
        let mut worst = (0.0, from.vertices[tri[0] as usize]);
        let farther = |worst: &mut (f64, DVec3), d: f64, at: DVec3| {
            if d > worst.0 {
                *worst = (d, at);
            }
        };
        // (aware) a piece's corners count only once the piece is bounded (kept)
        let corners_kept = |worst: &mut (f64, DVec3), p: &[DVec3; 3], d: &[f64; 3]| {
            if aware.is_some() {
                (0..3).for_each(|q| farther(worst, d[q], p[q]));
            }
        };
        if aware.is_none() {
            for (k, &v) in tri.iter().enumerate() {
                farther(&mut worst, d[k], from.vertices[v as usize]);
            }
            // a corner past the cell: the buried-aware measure follows, and this one's
            // figures would be dropped (a soup's triangles, mostly far inside)
            if buried.is_some() && worst.0 > h {
                return ((worst.0, worst.1, t), f64::INFINITY, n, centroid.flatten().map(|x| x.0), 0.0);
            }
        }
        if let Some(Some((_, dc))) = centroid {
            farther(&mut worst, dc, tri.iter().map(|&v| from.vertices[v as usize]).sum::<DVec3>() / 3.0);
        }
        let mut bound: f64 = 0.0;
        let hint = centroid.flatten().map(|x| x.0).or_else(|| tri.iter().find_map(|&v| at_vertex[v as usize].1));
        // pieces: corners, their distances, a hint for their midpoints, the level, and (aware)
        // whether the piece is known to be on the boundary
        let mut stack: Vec<([DVec3; 3], [f64; 3], Option<u32>, usize, bool)> = vec![(from.corners(t), d, hint, 0, false)];
        let mut splits = 0;
        let max_splits = if aware.is_some() { aware_splits } else { MAX_SPLITS };
        // (aware) the area of the pieces left out as sealed gaps
        let mut sealed = 0.0;
        while let Some((p, d, hint, level, mut on_boundary)) = stack.pop() {
            if let Some(b) = aware.filter(|_| !on_boundary) {
                match b.piece(t, &p) {
                    Side::Buried => continue,
                    Side::Sealed => {
                        sealed += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
                        continue;
                    }
                    Side::Boundary => on_boundary = true,
                    Side::Unsure => {}
                }
            }
            let len = [p[1].distance(p[2]), p[2].distance(p[0]), p[0].distance(p[1])];
            // the longest edge is opposite corner `k` (the first of equal lengths)
            let k = (0..3).fold(0, |k, i| if len[i] > len[k] { i } else { k });
            let m = d[0].max(d[1]).max(d[2]);
            let r = covering_radius(&p, len);
            if m + r <= floor {
                corners_kept(&mut worst, &p, &d);
                bound = bound.max(m + r);
                continue;
            }
            // (aware) a piece the judge could not place whose measure passes the cell is cut
            // further at the fine level even with its samples past the cell, and never bounded
            // by the thin rule while it is larger than the close measure: its pieces away from
            // the triangles that meet it are judged
            let unplaced = aware.is_some() && !on_boundary && m + r > h;
            let deeper = level < LEVELS - 1 && splits < max_splits;
            if settled(m, r, level) || splits >= max_splits {
                if deeper && (m <= h || (unplaced && level == 0)) && m + r > h {
                    stack.push((p, d, hint, level + 1, on_boundary));
                    continue;
                }
                corners_kept(&mut worst, &p, &d);
                bound = bound.max(m + r);
                continue;
            }
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            let altitude = (p[1] - p[0]).cross(p[2] - p[0]).length() / len[k];
            if altitude <= THIN[level] * h && !(unplaced && level > 0) {
                // thin: every point is within the altitude of a point of the longest side
                // (its angles at both ends are acute); sample that side at the spacing
                let steps = ((len[k] / (SPACING[level] * h)).ceil() as usize).clamp(1, max_splits - splits);
                let mut side = d[i].max(d[j]);
                // the samples, kept for `worst` only where this piece is bounded here
                let mut far = (0.0, p[i]);
                let mut hint = hint;
                for q in 1..steps {
                    let at = p[i] + (p[j] - p[i]) * (q as f64 / steps as f64);
                    let (near, dq) = nearest_from(to, to_bvh, at, hint).map_or((hint, f64::INFINITY), |x| (Some(x.0), x.1));
                    hint = near;
                    side = side.max(dq);
                    farther(&mut far, dq, at);
                    n += 1;
                    splits += 1;
                }
                let piece = (side + 0.5 * len[k] / steps as f64 + altitude) * (1.0 + 1e-9);
                if deeper && (side <= h || (unplaced && level == 0)) && piece > h {
                    stack.push((p, d, hint, level + 1, on_boundary));
                    continue;
                }
                corners_kept(&mut worst, &p, &d);
                farther(&mut worst, far.0, far.1);
                bound = bound.max(piece);
                continue;
            }
            let mid = (p[i] + p[j]) * 0.5;
            let (near, dm) = nearest_from(to, to_bvh, mid, hint).map_or((hint, f64::INFINITY), |x| (Some(x.0), x.1));
            splits += 1;
            n += 1;
            if aware.is_none() {
                farther(&mut worst, dm, mid);
            }
            let mut left = (p, d, near, level, on_boundary);
            left.0[j] = mid;
            left.1[j] = dm;
            let mut right = (p, d, near, level, on_boundary);
            right.0[i] = mid;
            right.1[i] = dm;
            stack.push(right);
            stack.push(left);
        }
        ((worst.0, worst.1, t), bound, n, centroid.flatten().map(|x| x.0), sealed)
    };
    // a triangle whose measure passes the cell is measured again leaving out what is buried
    let measure = |t: usize| {
        let first = measure_as(t, None);
        match buried {
            Some(b) if first.1 > h || first.0.0 > h => {
                let again = measure_as(t, Some(b));
                (again.0, again.1, first.2 + again.2, first.3, again.4)
            }
            _ => first,
        }
    };
    // the larger distance, of equal ones the lower triangle's: associative and commutative,
    // so the parallel reduction gives the same answer for any split
    type Stats = ((f64, DVec3, usize), f64, usize);
    let join = |x: Stats, y: Stats| -> Stats {
        let far = if y.0.0 > x.0.0 || (y.0.0 == x.0.0 && y.0.2 < x.0.2) { y.0 } else { x.0 };
        (far, x.1.max(y.1), x.2 + y.2)
    };
    let none: Stats = ((0.0, from.vertices.first().copied().unwrap_or(DVec3::ZERO), usize::MAX), 0.0, 0);
    let triangles = 0..from.triangles.len();
    let (stats, nearest, sealed) = if centroids {
        // one nearest triangle per triangle is kept (the tags); the rest is reduced
        let (stats, nearest): (Vec<Stats>, Vec<Option<u32>>) = triangles
            .into_par_iter()
            .map(|t| {
                let (w, b, n, near, _) = measure(t);
                ((w, b, n), near)
            })
            .unzip();
        (stats.into_iter().fold(none, join), nearest, 0.0)
    } else {
        // the sealed areas summed in triangle order: the same bits for any threads
        let (stats, areas): (Vec<Stats>, Vec<f64>) = triangles
            .into_par_iter()
            .map(|t| {
                let (w, b, n, _, sealed) = measure(t);
                ((w, b, n), sealed)
            })
            .unzip();
        (stats.into_iter().fold(none, join), Vec::new(), areas.iter().sum())
    };
    let ((worst, at, _), bound, n) = stats;
    ((worst, at), bound, n + corners, nearest, sealed)
}

/// The largest distance from a point of triangle `p` to its nearest corner (module docs),
/// `len[k]` the length of the side opposite corner `k`; rounded up a little, so that it stays
/// an upper bound.
fn covering_radius(p: &[DVec3; 3], len: [f64; 3]) -> f64 {
    // c the longest side, opposite corner C; a and b the others
    let k = (0..3).fold(0, |k, i| if len[i] > len[k] { i } else { k });
    let (c, a, b) = (len[k], len[(k + 1) % 3], len[(k + 2) % 3]);
    let r = if a == 0.0 || b == 0.0 {
        0.5 * c // two corners coincide: a segment
    } else if a * a + b * b >= c * c {
        // no obtuse angle: the circumradius abc / (4 area)
        let twice_area = (p[1] - p[0]).cross(p[2] - p[0]).length();
        if twice_area > 0.0 { a * b * c / (2.0 * twice_area) } else { 0.5 * c }
    } else {
        // obtuse at C: b / (2 cos A) and a / (2 cos B), cos A = (b² + c² − a²) / (2bc)
        let at_a = b * b * c / (b * b + c * c - a * a);
        let at_b = a * a * c / (a * a + c * c - b * b);
        at_a.max(at_b)
    };
    r * (1.0 + 1e-9)
}

/// A feature edge (its ends, the lower first) and its two triangles.
pub type Feature = ([u32; 2], [u32; 2]);

/// The input edges of exactly two triangles whose normals turn by more than `angle_deg`,
/// each with its two triangles, in the order of their ends.
pub fn feature_edges_with_triangles(s: &TriSurface, angle_deg: f64) -> Vec<Feature> {
    let mut rec: Vec<([u32; 2], u32)> = s
        .triangles
        .par_iter()
        .enumerate()
        .flat_map_iter(|(t, tri)| (0..3).map(move |k| ([tri[k].min(tri[(k + 1) % 3]), tri[k].max(tri[(k + 1) % 3])], t as u32)))
        .collect();
    // (edge, triangle) pairs: equal records are the same record, so any sort gives one order
    rec.par_sort_unstable();
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
                out.push((rec[i].0, [rec[i].1, rec[i + 1].1]));
            }
        }
        i = j;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::FaceId;

    fn surface(v: Vec<DVec3>, t: Vec<[u32; 3]>) -> (TriSurface, Bvh) {
        let s = TriSurface::with_single_tag(v, t, FaceId(1));
        let bvh = s.triangle_bvh();
        (s, bvh)
    }

    /// A long thin triangle whose farthest point from the target (two small triangles at its
    /// ends) is in its middle, far from every corner: the samples come near it, the bound
    /// holds it within the slack, and the thin triangle costs its length over h / 8.
    #[test]
    fn the_bound_holds_a_maximum_inside_a_long_thin_triangle() {
        let (from, _) = surface(vec![DVec3::ZERO, DVec3::new(100.0, 0.0, 0.0), DVec3::new(0.0, 0.01, 0.0)], vec![[0, 1, 2]]);
        let tv = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.5, 0.0, 0.0),
            DVec3::new(0.0, 0.5, 0.0),
            DVec3::new(100.0, 0.0, 0.0),
            DVec3::new(99.5, 0.0, 0.0),
            DVec3::new(100.0, 0.5, 0.0),
        ];
        let (to, to_bvh) = surface(tv, vec![[0, 1, 2], [3, 4, 5]]);
        let h = 1.0;
        let ((worst, at), bound, n, _, _) = one_sided(&from, &to, &to_bvh, h, false, None);
        assert!((at.x - 50.0).abs() <= h / 8.0, "the farthest sample at {at}");
        // the truth: the middle of the long edge, (50, 0.005), is this far from the corners
        // (0.5, 0) and (99.5, 0) of the ends' triangles; every corner is within 0.01 of them
        let truth = 49.5f64.hypot(0.005);
        assert!(worst <= truth + 1e-9 && worst >= truth - h / 8.0, "{worst} against {truth}");
        assert!(bound >= truth && bound <= truth + 0.5 * h, "{truth} {bound}");
        assert!(n < 2000, "{n} samples for a thin triangle");
    }

    /// Every point of a triangle is within its covering radius of a corner, and the radius is
    /// reached (up to the sampling) on acute, right, obtuse and flat triangles.
    #[test]
    fn covering_radius_covers() {
        let mut rng = crate::core::spatial_order::XorShift::new(99);
        let mut rnd = || rng.below(1_000_000) as f64 / 1_000_000.0;
        let mut shapes: Vec<[DVec3; 3]> = vec![
            [DVec3::ZERO, DVec3::X, DVec3::new(0.5, 0.866, 0.0)],
            [DVec3::ZERO, DVec3::X, DVec3::Y],
            [DVec3::ZERO, DVec3::new(10.0, 0.0, 0.0), DVec3::new(3.0, 0.1, 0.0)],
            [DVec3::ZERO, DVec3::new(10.0, 0.0, 0.0), DVec3::new(4.0, 0.0, 0.0)],
        ];
        for _ in 0..200 {
            shapes.push([0, 1, 2].map(|_| DVec3::new(rnd(), rnd(), rnd())));
        }
        for p in shapes {
            let len = [p[1].distance(p[2]), p[2].distance(p[0]), p[0].distance(p[1])];
            let r = covering_radius(&p, len);
            let mut reached: f64 = 0.0;
            for i in 0..=60 {
                for j in 0..=60 - i {
                    let q = p[0] + (p[1] - p[0]) * (i as f64 / 60.0) + (p[2] - p[0]) * (j as f64 / 60.0);
                    let near = p.iter().map(|c| c.distance(q)).fold(f64::INFINITY, f64::min);
                    assert!(near <= r, "{p:?}: {near} > {r}");
                    reached = reached.max(near);
                }
            }
            let longest = len.iter().copied().fold(0.0, f64::max);
            assert!(reached >= r - longest / 30.0, "{p:?}: {reached} far below {r}");
        }
    }

    /// Planes 0.95 cells apart: the coarse bound (up to 0.95 + h / 8) would pass the cell, so
    /// the pieces are measured finely and the bound is within 1.5 h / 64 of the truth (the
    /// thin rule's half spacing and altitude); planes 1.5
    /// cells apart are measured coarsely (no finer bound could bring them within the cell).
    #[test]
    fn a_bound_that_straddles_the_cell_is_measured_finely() {
        let sq = |z: f64| vec![DVec3::new(0.0, 0.0, z), DVec3::new(2.0, 0.0, z), DVec3::new(2.0, 2.0, z), DVec3::new(0.0, 2.0, z)];
        let (a, _) = surface(sq(0.0), vec![[0, 1, 2], [0, 2, 3]]);
        for (gap, slack) in [(0.95, 1.5 / 64.0), (1.5, 1.0 / 8.0)] {
            let (b, b_bvh) = surface(sq(gap), vec![[0, 1, 2], [0, 2, 3]]);
            let ((worst, _), bound, n, _, _) = one_sided(&a, &b, &b_bvh, 1.0, false, None);
            assert!((worst - gap).abs() < 1e-12, "{worst}");
            assert!(bound >= gap && bound <= gap + slack + 1e-9, "{gap}: {bound}");
            if gap < 1.0 {
                assert!(bound <= 1.0 && n > 1000, "{bound} with {n} samples");
            }
        }
    }

    /// A cube inside a cube: the inner one's faces are buried in the stuffed volume, 1.5 from
    /// the boundary. Measured plainly they are the farthest input; left out as buried, the
    /// input is on the boundary.
    #[test]
    fn buried_sheets_are_left_out() {
        use super::super::tests::{cube_at, together};
        use super::super::winding::Winding;
        let input = together(&[cube_at(DVec3::ZERO, 4.0), cube_at(DVec3::splat(1.5), 1.0)]);
        let (outer, outer_bvh) = { let c = cube_at(DVec3::ZERO, 4.0); surface(c.vertices, c.triangles) };
        let w = Winding::new(&input);
        let b = Buried::new(&w, 0.0);
        let ((plain, _), plain_bound, _, _, _) = one_sided(&input, &outer, &outer_bvh, 1.0, false, None);
        assert!((plain - 1.5).abs() < 1e-12 && plain_bound >= 1.5, "{plain} {plain_bound}");
        let ((kept, _), bound, _, _, _) = one_sided(&input, &outer, &outer_bvh, 1.0, false, Some(&b));
        assert!(kept == 0.0 && bound <= 0.5, "{kept} {bound}");
    }

    /// Two boxes crossing inside a cube (all their walls buried, the cube's faces the
    /// boundary): the wall of the second box that goes down into the first from their crossing
    /// line (0.9 under the cube's top) is 1 or more from the boundary just below the line, so
    /// the pieces that the judge cannot place there (the first box's top meets them) pass the
    /// cell when measured as a whole. Cut further, their pieces clear of the crossing are
    /// judged buried and those along it are within the cell.
    #[test]
    fn pieces_along_a_crossing_inside_are_cut_until_judged() {
        use super::super::tests::{cube_at, together};
        use super::super::winding::Winding;
        let boxed = |lo: DVec3, size: DVec3| {
            let mut c = cube_at(DVec3::ZERO, 1.0);
            c.vertices.iter_mut().for_each(|p| *p = lo + *p * size);
            c
        };
        let first = boxed(DVec3::splat(0.5), DVec3::new(3.0, 3.0, 2.6));
        let second = boxed(DVec3::new(2.0, 1.0, 2.0), DVec3::new(1.7, 2.0, 1.7));
        let input = together(&[cube_at(DVec3::ZERO, 4.0), first, second]);
        let (outer, outer_bvh) = {
            let c = cube_at(DVec3::ZERO, 4.0);
            surface(c.vertices, c.triangles)
        };
        let w = Winding::new(&input);
        let b = Buried::new(&w, 0.0);
        let ((plain, _), _, _, _, _) = one_sided(&input, &outer, &outer_bvh, 1.0, false, None);
        assert!(plain >= 1.5, "{plain}");
        let ((kept, _), bound, _, _, _) = one_sided(&input, &outer, &outer_bvh, 1.0, false, Some(&b));
        assert!(kept <= 0.95 && bound <= 1.0, "{kept} {bound}");
    }

    /// Parallel planes one apart: every sample is 1 away, and the bound is within the slack.
    #[test]
    fn parallel_planes_one_apart() {
        let sq = |z: f64| vec![DVec3::new(0.0, 0.0, z), DVec3::new(10.0, 0.0, z), DVec3::new(10.0, 10.0, z), DVec3::new(0.0, 10.0, z)];
        let (a, a_bvh) = surface(sq(0.0), vec![[0, 1, 2], [0, 2, 3]]);
        let (b, b_bvh) = surface(sq(1.0), vec![[0, 1, 2], [0, 2, 3]]);
        for (from, to, bvh) in [(&a, &b, &b_bvh), (&b, &a, &a_bvh)] {
            let ((worst, _), bound, _, near, _) = one_sided(from, to, bvh, 0.5, true, None);
            assert!((worst - 1.0).abs() < 1e-12, "{worst}");
            assert!((1.0..=1.0 + 0.5 / 8.0 + 1e-12).contains(&bound), "{bound}");
            assert_eq!(near.len(), 2);
        }
    }
}
