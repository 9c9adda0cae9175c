//! `TriSurface`: a triangulated surface with a face tag per triangle.

use crate::core::{Aabb, FaceId, FaceNames};
use crate::mesh::{Element, MeshError};
use glam::DVec3;

/// A triangle surface: the hand-off between readers or the tessellator and the volume mesher.
///
/// - `vertices`: #V positions.
/// - `triangles`: #T × 3 vertex indices; for a closed, outward-oriented surface the vertices
///   of every triangle turn counter-clockwise seen from outside.
/// - `face_tags`: #T tags, the CAD face (or group, primitive, facet marker) of each triangle;
///   `FaceId(0)` is untagged, made-up tags start at 1 (see `crate::core::ids`).
/// - `face_names`: names of tags where the source had them (OBJ group names, glTF node/mesh
///   names, STEP face names); not necessarily unique, writers make them so.
///
/// Topological properties (closed, manifold, genus, …) are not invariants of the type; the
/// surface report (`mesh::topology`) derives them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriSurface {
    /// Vertex positions.
    pub vertices: Vec<DVec3>,
    /// Triangles as vertex index triples.
    pub triangles: Vec<[u32; 3]>,
    /// One tag per triangle.
    pub face_tags: Vec<FaceId>,
    /// Names of tags, where the source had them.
    pub face_names: FaceNames,
}

impl TriSurface {
    /// A validated surface.
    ///
    /// # Errors
    /// Whatever [`TriSurface::validate`] reports.
    pub fn try_new(vertices: Vec<DVec3>, triangles: Vec<[u32; 3]>, face_tags: Vec<FaceId>) -> Result<Self, MeshError> {
        let s = TriSurface { vertices, triangles, face_tags, face_names: FaceNames::new() };
        s.validate()?;
        Ok(s)
    }

    /// A surface whose triangles all carry `tag`, not validated.
    pub fn with_single_tag(vertices: Vec<DVec3>, triangles: Vec<[u32; 3]>, tag: FaceId) -> Self {
        let n = triangles.len();
        TriSurface { vertices, triangles, face_tags: vec![tag; n], face_names: FaceNames::new() }
    }

    /// Checks the invariants: one tag per triangle, finite coordinates, indices in range, no
    /// triangle using a vertex twice.
    ///
    /// # Errors
    /// The first violation found, naming the triangle or vertex.
    ///
    /// ```
    /// use fepre::mesh::{TriSurface, MeshError};
    /// use fepre::core::FaceId;
    /// use glam::DVec3;
    /// let s = TriSurface::with_single_tag(vec![DVec3::ZERO; 3], vec![[0, 1, 3]], FaceId(1));
    /// assert!(matches!(s.validate(), Err(MeshError::IndexOutOfRange { index: 3, .. })));
    /// ```
    pub fn validate(&self) -> Result<(), MeshError> {
        if self.face_tags.len() != self.triangles.len() {
            return Err(MeshError::LengthMismatch {
                what: "face_tags",
                found: self.face_tags.len(),
                expected: self.triangles.len(),
            });
        }
        check_finite(&self.vertices)?;
        let n = self.vertices.len();
        for (t, tri) in self.triangles.iter().enumerate() {
            check_simplex(Element::Triangle(t), tri, n)?;
        }
        Ok(())
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.vertices.len()
    }

    /// Number of triangles.
    pub fn num_triangles(&self) -> usize {
        self.triangles.len()
    }

    /// The three corner positions of triangle `t`.
    #[inline]
    pub fn corners(&self, t: usize) -> [DVec3; 3] {
        let [a, b, c] = self.triangles[t];
        [self.vertices[a as usize], self.vertices[b as usize], self.vertices[c as usize]]
    }

    /// A BVH over the triangles' boxes (item = triangle index).
    pub fn triangle_bvh(&self) -> crate::core::bvh::Bvh {
        use rayon::prelude::*;
        let boxes: Vec<Aabb> = (0..self.triangles.len()).into_par_iter().map(|t| Aabb::from_points(&self.corners(t))).collect();
        crate::core::bvh::Bvh::from_boxes(&boxes)
    }

    /// The signed volume its triangles enclose, by the divergence theorem (positive for a
    /// closed surface oriented outward; for any surface, the integral of its winding number).
    pub fn signed_volume(&self) -> f64 {
        (0..self.triangles.len()).map(|t| {
            let [a, b, c] = self.corners(t);
            a.dot(b.cross(c)) / 6.0
        }).sum()
    }

    /// Bounding box of the vertices.
    pub fn bbox(&self) -> Aabb {
        Aabb::from_points(&self.vertices)
    }

    /// The distinct tags in increasing order.
    pub fn tags(&self) -> Vec<FaceId> {
        let mut t = self.face_tags.clone();
        t.sort_unstable();
        t.dedup();
        t
    }

    /// Drops the vertices no triangle uses, renumbering the triangles (order kept); returns
    /// how many were dropped.
    ///
    /// ```
    /// use fepre::mesh::TriSurface;
    /// use fepre::core::FaceId;
    /// use glam::DVec3;
    /// let mut s = TriSurface::with_single_tag(vec![DVec3::X, DVec3::ZERO, DVec3::Y, DVec3::Z], vec![[1, 0, 2]], FaceId(1));
    /// assert_eq!(s.remove_unused_vertices(), 1);
    /// assert_eq!(s.triangles, vec![[1, 0, 2]]);
    /// assert_eq!(s.vertices.len(), 3);
    /// ```
    pub fn remove_unused_vertices(&mut self) -> usize {
        let mut used = vec![false; self.vertices.len()];
        for &v in self.triangles.iter().flatten() {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
        let mut index = vec![0u32; self.vertices.len()];
        let mut next = 0u32;
        for (i, &u) in used.iter().enumerate() {
            index[i] = next;
            if u {
                self.vertices[next as usize] = self.vertices[i];
                next += 1;
            }
        }
        let dropped = self.vertices.len() - next as usize;
        self.vertices.truncate(next as usize);
        for t in &mut self.triangles {
            *t = t.map(|v| index.get(v as usize).copied().unwrap_or(v));
        }
        dropped
    }

    /// Appends `other`, renumbering its vertices; tags and names are kept as they are.
    pub fn append(&mut self, other: &TriSurface) {
        let off = self.vertices.len() as u32;
        self.vertices.extend_from_slice(&other.vertices);
        self.triangles.extend(other.triangles.iter().map(|t| [t[0] + off, t[1] + off, t[2] + off]));
        self.face_tags.extend_from_slice(&other.face_tags);
        self.face_names.extend_missing(&other.face_names);
    }
}

/// Checks that every coordinate is finite.
pub(crate) fn check_finite(vertices: &[DVec3]) -> Result<(), MeshError> {
    match vertices.iter().position(|p| !p.is_finite()) {
        Some(v) => Err(MeshError::NonFiniteVertex { vertex: v, coords: vertices[v].to_array().to_vec() }),
        None => Ok(()),
    }
}

/// Checks that a simplex's indices are in range and distinct.
pub(crate) fn check_simplex(element: Element, v: &[u32], count: usize) -> Result<(), MeshError> {
    for (i, &a) in v.iter().enumerate() {
        if a as usize >= count {
            return Err(MeshError::IndexOutOfRange { element, index: a, count });
        }
        if v[..i].contains(&a) {
            return Err(MeshError::RepeatedVertex { element, vertex: a, vertices: v.to_vec() });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validate_names_the_triangle() {
        let v = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
        let s = TriSurface::with_single_tag(v.clone(), vec![[0, 1, 2], [0, 2, 2]], FaceId(1));
        let e = s.validate().unwrap_err();
        assert_eq!(e, MeshError::RepeatedVertex { element: Element::Triangle(1), vertex: 2, vertices: vec![0, 2, 2] });
        assert!(e.to_string().contains("triangle 1"));
        let mut s = TriSurface::with_single_tag(v, vec![[0, 1, 2]], FaceId(1));
        assert!(s.validate().is_ok());
        s.vertices[1].y = f64::NAN;
        assert!(matches!(s.validate(), Err(MeshError::NonFiniteVertex { vertex: 1, .. })));
        s.vertices[1].y = 0.0;
        s.face_tags.clear();
        assert!(matches!(s.validate(), Err(MeshError::LengthMismatch { .. })));
    }
}
