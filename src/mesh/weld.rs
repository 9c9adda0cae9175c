//! Merging of coincident vertices with a tolerance relative to the model's size.

use crate::core::ids::NONE;
use crate::core::Tolerance;
use crate::mesh::TriSurface;
use glam::DVec3;
use rustc_hash::FxHashMap;

/// The outcome of [`weld_vertices`].
#[derive(Clone, Debug, PartialEq)]
pub struct Welded {
    /// The kept vertices (each the first of its cluster in input order).
    pub vertices: Vec<DVec3>,
    /// For every input vertex, the index of its kept vertex.
    pub remap: Vec<u32>,
}

/// Merges vertices closer than `tolerance` (absolute length; `0` merges exact duplicates only).
///
/// Greedy and deterministic: vertices are visited in input order, and each joins the first
/// kept vertex within `tolerance`. Bit-identical vertices (the common case: triangle soups) are
/// merged first through a hash of their coordinates; the distinct ones then go through a hash
/// grid of cell size `tolerance`. Non-finite vertices are never merged.
pub fn weld_vertices(points: &[DVec3], tolerance: f64) -> Welded {
    // 1. exact duplicates: the first occurrence stands for all
    let mut distinct: Vec<DVec3> = Vec::new();
    let mut to_distinct: Vec<u32> = Vec::with_capacity(points.len());
    let mut seen: FxHashMap<[u64; 3], u32> = FxHashMap::default();
    seen.reserve(points.len() / 4);
    for p in points {
        let id = if p.is_finite() {
            // +0.0 and -0.0 are the same point
            let key = [p.x + 0.0, p.y + 0.0, p.z + 0.0].map(f64::to_bits);
            *seen.entry(key).or_insert_with(|| {
                distinct.push(*p);
                (distinct.len() - 1) as u32
            })
        } else {
            distinct.push(*p);
            (distinct.len() - 1) as u32
        };
        to_distinct.push(id);
    }
    drop(seen);
    if tolerance <= 0.0 || !tolerance.is_finite() {
        return Welded { vertices: distinct, remap: to_distinct };
    }
    // 2. distinct points within the tolerance, in first-occurrence order
    let inv = 1.0 / tolerance;
    let tol2 = tolerance * tolerance;
    let cell = |p: DVec3| -> [i64; 3] { [(p.x * inv).floor() as i64, (p.y * inv).floor() as i64, (p.z * inv).floor() as i64] };
    let mut grid: FxHashMap<[i64; 3], Vec<u32>> = FxHashMap::default();
    grid.reserve(distinct.len());
    let mut vertices = Vec::with_capacity(distinct.len());
    let mut kept: Vec<u32> = Vec::with_capacity(distinct.len());
    for p in &distinct {
        if !p.is_finite() {
            vertices.push(*p);
            kept.push((vertices.len() - 1) as u32);
            continue;
        }
        let c = cell(*p);
        let mut found: Option<u32> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(list) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) else { continue };
                    for &k in list {
                        if vertices[k as usize].distance_squared(*p) <= tol2 && found.is_none_or(|f| k < f) {
                            found = Some(k);
                        }
                    }
                }
            }
        }
        let id = match found {
            Some(k) => k,
            None => {
                vertices.push(*p);
                let k = (vertices.len() - 1) as u32;
                grid.entry(c).or_default().push(k);
                k
            }
        };
        kept.push(id);
    }
    let remap = to_distinct.iter().map(|&d| kept[d as usize]).collect();
    Welded { vertices, remap }
}

/// What [`TriSurface::weld`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct WeldReport {
    /// Vertices before welding.
    pub vertices_before: usize,
    /// Vertices merged into another.
    pub merged: usize,
    /// Triangles dropped because two of their corners merged.
    pub collapsed_triangles: usize,
    /// Vertices no triangle uses, dropped.
    pub unused_vertices: usize,
}

impl TriSurface {
    /// Merges vertices closer than `tol` times the model size, drops triangles that
    /// collapse (two corners merged) and vertices that no triangle uses.
    pub fn weld(&mut self, tol: Tolerance) -> WeldReport {
        let before = self.vertices.len();
        let w = weld_vertices(&self.vertices, tol.absolute(&self.bbox()));
        let merged = before - w.vertices.len();
        let mut tris = Vec::with_capacity(self.triangles.len());
        let mut tags = Vec::with_capacity(self.triangles.len());
        let mut collapsed = 0;
        for (t, tag) in self.triangles.iter().zip(&self.face_tags) {
            let m = t.map(|i| w.remap[i as usize]);
            if m[0] == m[1] || m[1] == m[2] || m[0] == m[2] {
                collapsed += 1;
            } else {
                tris.push(m);
                tags.push(*tag);
            }
        }
        // drop unused vertices, keeping the order of first appearance in the vertex list
        let mut used = vec![false; w.vertices.len()];
        for t in &tris {
            for &i in t {
                used[i as usize] = true;
            }
        }
        let mut new_index = vec![NONE; w.vertices.len()];
        let mut verts = Vec::with_capacity(w.vertices.len());
        for (i, p) in w.vertices.iter().enumerate() {
            if used[i] {
                new_index[i] = verts.len() as u32;
                verts.push(*p);
            }
        }
        let unused = w.vertices.len() - verts.len();
        for t in &mut tris {
            *t = t.map(|i| new_index[i as usize]);
        }
        self.vertices = verts;
        self.triangles = tris;
        self.face_tags = tags;
        WeldReport { vertices_before: before, merged, collapsed_triangles: collapsed, unused_vertices: unused }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::FaceId;

    #[test]
    fn merges_within_tolerance_only() {
        let p = vec![DVec3::ZERO, DVec3::new(1e-12, 0.0, 0.0), DVec3::X, DVec3::new(1.0, 1e-3, 0.0)];
        let w = weld_vertices(&p, 1e-9);
        assert_eq!(w.remap, vec![0, 0, 1, 2]);
        let w = weld_vertices(&p, 0.0);
        assert_eq!(w.vertices.len(), 4);
        let w = weld_vertices(&[DVec3::ZERO, DVec3::new(-0.0, 0.0, 0.0)], 0.0);
        assert_eq!(w.vertices.len(), 1);
    }

    #[test]
    fn welds_a_triangle_soup() {
        // two triangles of a square, given as a soup, plus a sliver that collapses
        let v = vec![
            DVec3::ZERO, DVec3::X, DVec3::Y,
            DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y,
            DVec3::X, DVec3::new(1.0 + 1e-14, 0.0, 0.0), DVec3::Y,
        ];
        let mut s = TriSurface::with_single_tag(v, vec![[0, 1, 2], [3, 4, 5], [6, 7, 8]], FaceId(1));
        let r = s.weld(Tolerance::WELD);
        assert_eq!(s.vertices.len(), 4);
        assert_eq!(s.triangles, vec![[0, 1, 2], [1, 3, 2]]);
        assert_eq!(r.collapsed_triangles, 1);
        assert_eq!(r.merged, 5);
    }
}
