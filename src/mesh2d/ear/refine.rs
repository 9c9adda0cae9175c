//! Refinement of the gross elements of ear cutting to the size field: points inserted at
//! circumcenters (or centroids) of triangles larger than the size, Lawson flips after each.
//!
//! - Inputs: a constrained Delaunay [`TriMesh`] of the domain, the size `h(p)`, the ratio
//!   above which a triangle is split, a cap on the points.
//! - Output: the refined mesh (still constrained Delaunay); the points inserted.
//! - Invariants: no point is inserted on a domain segment or outside the domain: a
//!   circumcenter is used only when the walk from its triangle reaches it without crossing
//!   a domain segment, it lies strictly inside a triangle or on an interior edge, and it is
//!   outside the diametral circle of the domain segments of the triangle it falls in;
//!   otherwise the centroid, when it is strictly inside (exact). The largest triangle (by
//!   mean edge over the size) is split first, ties by index: deterministic.

use super::trimesh::{Location, TriMesh};
use super::Error;
use crate::core::predicates::orient2d;
use crate::core::Sign;
use crate::mesh2d::boundary::check_size;
use glam::DVec2;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// The circumcenter of a triangle (not finite when it is degenerate).
pub(crate) fn circumcenter(a: DVec2, b: DVec2, c: DVec2) -> DVec2 {
    let (u, v) = (b - a, c - a);
    let d = 2.0 * u.perp_dot(v);
    let (lu, lv) = (u.length_squared(), v.length_squared());
    a + DVec2::new(v.y * lu - u.y * lv, u.x * lv - v.x * lu) / d
}

/// Mean edge length of a triangle over the size at its centroid.
fn ratio(m: &TriMesh, t: u32, size: &dyn Fn(DVec2) -> f64) -> Result<f64, Error> {
    let [a, b, c] = m.tris[t as usize].map(|v| m.pts[v as usize]);
    let g = (a + b + c) / 3.0;
    let h = check_size(g, size(g))?;
    Ok((a.distance(b) + b.distance(c) + c.distance(a)) / 3.0 / h)
}

/// Splits every triangle whose mean edge exceeds `split` times the size (see the module
/// docs); returns the points inserted.
///
/// # Errors
/// [`Error::Size`] where the size is not positive and finite, [`Error::Refinement`] when more
/// than `max_points` points would be needed.
pub(crate) fn refine(m: &mut TriMesh, size: &dyn Fn(DVec2) -> f64, split: f64, max_points: usize) -> Result<usize, Error> {
    let mut generation = vec![0u32; m.tris.len()];
    let mut heap: BinaryHeap<(u64, Reverse<u32>, u32)> = BinaryHeap::new();
    for t in 0..m.tris.len() as u32 {
        let r = ratio(m, t, size)?;
        if r > split {
            heap.push((r.to_bits(), Reverse(t), 0));
        }
    }
    m.touched.clear();
    let mut inserted = 0;
    while let Some((_, Reverse(t), g)) = heap.pop() {
        if generation[t as usize] != g {
            continue;
        }
        if inserted >= max_points {
            return Err(Error::Refinement(inserted));
        }
        let [a, b, c] = m.tris[t as usize].map(|v| m.pts[v as usize]);
        let cc = circumcenter(a, b, c);
        let mut at = if cc.is_finite() { m.locate(t, cc) } else { Location::Blocked };
        if encroaches(m, at, cc) {
            at = Location::Blocked;
        }
        let done = match at {
            Location::Blocked => None,
            _ => m.insert(cc, at),
        };
        let done = done.or_else(|| {
            let g = (a + b + c) / 3.0;
            let inside = orient2d(a, b, g) == Sign::Positive && orient2d(b, c, g) == Sign::Positive && orient2d(c, a, g) == Sign::Positive;
            if inside { m.insert(g, Location::Inside(t)) } else { None }
        });
        if done.is_none() {
            continue; // a sliver whose centroid rounds onto an edge: left as it is
        }
        inserted += 1;
        generation.resize(m.tris.len(), 0);
        let mut touched = std::mem::take(&mut m.touched);
        touched.sort_unstable();
        touched.dedup();
        for &u in &touched {
            generation[u as usize] += 1;
            let r = ratio(m, u, size)?;
            if r > split {
                heap.push((r.to_bits(), Reverse(u), generation[u as usize]));
            }
        }
        touched.clear();
        m.touched = touched;
    }
    Ok(inserted)
}

/// Whether `p`, located at `at`, lies inside the diametral circle of a domain segment of the
/// triangle (or, on an edge, the two triangles) it falls in.
fn encroaches(m: &TriMesh, at: Location, p: DVec2) -> bool {
    let tris: Vec<u32> = match at {
        Location::Inside(t) => vec![t],
        Location::OnEdge(t, k) => vec![t, m.adj[t as usize][k]],
        Location::Blocked => return false,
    };
    tris.into_iter().filter(|&t| t != super::trimesh::NONE).any(|t| {
        (0..3).any(|k| {
            if !m.fixed[t as usize][k] {
                return false;
            }
            let tri = m.tris[t as usize];
            let (a, b) = (m.pts[tri[(k + 1) % 3] as usize], m.pts[tri[(k + 2) % 3] as usize]);
            (p - a).dot(p - b) < 0.0
        })
    })
}
