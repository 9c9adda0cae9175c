//! `PlanarMesh`: a 2D mesh of triangles and quadrilaterals.

use crate::core::predicates::orient2d;
use crate::core::{RegionId, RegionNames, Sign};
use crate::mesh::tri_surface::check_simplex;
use crate::mesh::{Element, MeshError};
use glam::DVec2;

/// A planar mesh of triangles and quadrilaterals (the lecture's 2D methods produce these).
///
/// - `vertices`: #V positions in the plane.
/// - `triangles`: #T × 3, counter-clockwise; `triangle_tags`: #T region tags.
/// - `quads`: #Q × 4, strictly convex and counter-clockwise; `quad_tags`: #Q region tags.
/// - `region_names`: names of region tags where known.
///
/// Tags follow `crate::core::ids`: 0 is untagged, made-up tags start at 1.
///
/// A valid mesh is conforming: every edge is shared by at most two elements, which traverse it
/// in opposite directions.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PlanarMesh {
    /// Vertex positions.
    pub vertices: Vec<DVec2>,
    /// Triangles.
    pub triangles: Vec<[u32; 3]>,
    /// One tag per triangle.
    pub triangle_tags: Vec<RegionId>,
    /// Quadrilaterals.
    pub quads: Vec<[u32; 4]>,
    /// One tag per quadrilateral.
    pub quad_tags: Vec<RegionId>,
    /// Names of region tags, where known.
    pub region_names: RegionNames,
}

impl PlanarMesh {
    /// Checks the invariants: array lengths, finite coordinates, indices, strictly positive
    /// orientation of triangles and strict convexity of quads (exact), conformity of edges.
    ///
    /// # Errors
    /// The first violation found, naming the element or edge.
    pub fn validate(&self) -> Result<(), MeshError> {
        if self.triangle_tags.len() != self.triangles.len() {
            return Err(MeshError::LengthMismatch {
                what: "triangle_tags",
                found: self.triangle_tags.len(),
                expected: self.triangles.len(),
            });
        }
        if self.quad_tags.len() != self.quads.len() {
            return Err(MeshError::LengthMismatch { what: "quad_tags", found: self.quad_tags.len(), expected: self.quads.len() });
        }
        if let Some(v) = self.vertices.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFiniteVertex { vertex: v, coords: self.vertices[v].to_array().to_vec() });
        }
        let n = self.vertices.len();
        let p = |i: u32| self.vertices[i as usize];
        let mut edges: Vec<([u32; 2], bool, Element)> = Vec::new();
        for (t, tri) in self.triangles.iter().enumerate() {
            let e = Element::Triangle(t);
            check_simplex(e, tri, n)?;
            let s = orient2d(p(tri[0]), p(tri[1]), p(tri[2]));
            if s != Sign::Positive {
                return Err(MeshError::BadOrientation { element: e, vertices: tri.to_vec(), orientation: s });
            }
            push_edges(&mut edges, tri, e);
        }
        for (q, quad) in self.quads.iter().enumerate() {
            let e = Element::Quad(q);
            check_simplex(e, quad, n)?;
            for corner in 0..4 {
                let s = orient2d(p(quad[(corner + 3) % 4]), p(quad[corner]), p(quad[(corner + 1) % 4]));
                if s != Sign::Positive {
                    return Err(MeshError::NonConvexQuad { quad: q, vertices: *quad, corner });
                }
            }
            push_edges(&mut edges, quad, e);
        }
        edges.sort_unstable_by_key(|e| e.0);
        let mut i = 0;
        while i < edges.len() {
            let mut j = i + 1;
            while j < edges.len() && edges[j].0 == edges[i].0 {
                j += 1;
            }
            if j - i > 2 {
                return Err(MeshError::NonManifold { entity: edges[i].0.to_vec(), elements: edges[i..j].iter().map(|e| e.2).collect() });
            }
            if j - i == 2 && edges[i].1 == edges[i + 1].1 {
                return Err(MeshError::Overlap { entity: edges[i].0.to_vec(), first: edges[i].2, second: edges[i + 1].2 });
            }
            i = j;
        }
        Ok(())
    }

    /// Total signed area.
    pub fn area(&self) -> f64 {
        let p = |i: u32| self.vertices[i as usize];
        let poly = |v: &[u32]| -> f64 {
            (0..v.len()).map(|k| p(v[k]).perp_dot(p(v[(k + 1) % v.len()]))).sum::<f64>() * 0.5
        };
        self.triangles.iter().map(|t| poly(t)).sum::<f64>() + self.quads.iter().map(|q| poly(q)).sum::<f64>()
    }
}

fn push_edges(edges: &mut Vec<([u32; 2], bool, Element)>, v: &[u32], e: Element) {
    for k in 0..v.len() {
        let (a, b) = (v[k], v[(k + 1) % v.len()]);
        edges.push(([a.min(b), a.max(b)], a < b, e));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> PlanarMesh {
        PlanarMesh {
            vertices: vec![DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0), DVec2::new(2.0, 0.5)],
            triangles: vec![[1, 4, 2]],
            triangle_tags: vec![RegionId(1)],
            quads: vec![[0, 1, 2, 3]],
            quad_tags: vec![RegionId(1)],
            region_names: [(RegionId(1), "plate")].into_iter().collect(),
        }
    }

    #[test]
    fn validates_and_names_elements() {
        let m = square();
        assert_eq!(m.validate(), Ok(()));
        assert!((m.area() - 1.5).abs() < 1e-15);
        let mut bad = square();
        bad.quads[0] = [0, 1, 3, 2];
        assert!(matches!(bad.validate(), Err(MeshError::NonConvexQuad { quad: 0, .. })));
        let mut bad = square();
        bad.triangles[0] = [1, 2, 4];
        assert!(matches!(bad.validate(), Err(MeshError::BadOrientation { element: Element::Triangle(0), .. })));
        let mut bad = square();
        bad.triangles.push([0, 1, 2]);
        bad.triangle_tags.push(RegionId(1));
        assert!(bad.validate().is_err());
    }
}
