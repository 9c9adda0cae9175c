//! `MixedSurface`: a surface of triangles and quadrilaterals in 3D, tagged per element; what
//! the 2D methods make of a part's planar faces (lifted back to 3D) or of a planar region
//! (at z = 0), written with quads as quads.

use crate::core::{FaceId, FaceNames, RegionId};
use crate::mesh::tri_surface::check_simplex;
use crate::mesh::{Element, MeshError, PlanarMesh, TriSurface};
use glam::DVec3;

/// A surface of triangles and quadrilaterals.
///
/// - `vertices`: positions; `triangles` and `quads`: vertex indices, each element traversing
///   its boundary consistently with its neighbours; `triangle_tags`, `quad_tags`: one tag per
///   element (a CAD face's id, or a 2D region's tag); `face_names`: names of tags.
///
/// A valid surface has distinct, in-range indices per element, finite coordinates, and every
/// edge shared by at most two elements, traversed in opposite directions.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MixedSurface {
    /// Vertex positions.
    pub vertices: Vec<DVec3>,
    /// Triangles.
    pub triangles: Vec<[u32; 3]>,
    /// One tag per triangle.
    pub triangle_tags: Vec<FaceId>,
    /// Quadrilaterals.
    pub quads: Vec<[u32; 4]>,
    /// One tag per quadrilateral.
    pub quad_tags: Vec<FaceId>,
    /// Names of tags, where known.
    pub face_names: FaceNames,
}

impl MixedSurface {
    /// A planar mesh at z = 0, its region tags as face tags and its region names as names.
    pub fn from_planar(m: &PlanarMesh) -> MixedSurface {
        let tag = |r: &RegionId| FaceId(r.0);
        MixedSurface {
            vertices: m.vertices.iter().map(|p| p.extend(0.0)).collect(),
            triangles: m.triangles.clone(),
            triangle_tags: m.triangle_tags.iter().map(tag).collect(),
            quads: m.quads.clone(),
            quad_tags: m.quad_tags.iter().map(tag).collect(),
            face_names: m.region_names.iter().map(|(r, n)| (tag(&r), n)).collect(),
        }
    }

    /// Checks the invariants (see the type's docs).
    ///
    /// # Errors
    /// The first violation, naming the element or edge.
    pub fn validate(&self) -> Result<(), MeshError> {
        if self.triangle_tags.len() != self.triangles.len() {
            return Err(MeshError::LengthMismatch { what: "triangle_tags", found: self.triangle_tags.len(), expected: self.triangles.len() });
        }
        if self.quad_tags.len() != self.quads.len() {
            return Err(MeshError::LengthMismatch { what: "quad_tags", found: self.quad_tags.len(), expected: self.quads.len() });
        }
        if let Some(v) = self.vertices.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFiniteVertex { vertex: v, coords: self.vertices[v].to_array().to_vec() });
        }
        let n = self.vertices.len();
        let mut edges: Vec<([u32; 2], bool, Element)> = Vec::new();
        for (t, tri) in self.triangles.iter().enumerate() {
            check_simplex(Element::Triangle(t), tri, n)?;
            push_edges(&mut edges, tri, Element::Triangle(t));
        }
        for (q, quad) in self.quads.iter().enumerate() {
            check_simplex(Element::Quad(q), quad, n)?;
            push_edges(&mut edges, quad, Element::Quad(q));
        }
        edges.sort_unstable_by_key(|e| e.0);
        for run in edges.chunk_by(|a, b| a.0 == b.0) {
            if run.len() > 2 {
                return Err(MeshError::NonManifold { entity: run[0].0.to_vec(), elements: run.iter().map(|e| e.2).collect() });
            }
            if run.len() == 2 && run[0].1 == run[1].1 {
                return Err(MeshError::Overlap { entity: run[0].0.to_vec(), first: run[0].2, second: run[1].2 });
            }
        }
        Ok(())
    }

    /// The same surface with each quad split into two triangles along its shorter diagonal
    /// (for formats without quads: STL, OFF), quads' triangles after the triangles.
    pub fn to_triangles(&self) -> TriSurface {
        let mut triangles = self.triangles.clone();
        let mut face_tags = self.triangle_tags.clone();
        for (q, &t) in self.quads.iter().zip(&self.quad_tags) {
            let p = |i: usize| self.vertices[q[i] as usize];
            let halves = if p(0).distance_squared(p(2)) <= p(1).distance_squared(p(3)) { [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] } else { [[q[0], q[1], q[3]], [q[1], q[2], q[3]]] };
            triangles.extend(halves);
            face_tags.extend([t, t]);
        }
        TriSurface { vertices: self.vertices.clone(), triangles, face_tags, face_names: self.face_names.clone() }
    }

    /// The tags present, ascending.
    pub fn tags(&self) -> Vec<FaceId> {
        let mut t: Vec<FaceId> = self.triangle_tags.iter().chain(&self.quad_tags).copied().collect();
        t.sort_unstable();
        t.dedup();
        t
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
    use glam::DVec2;

    fn plate() -> PlanarMesh {
        PlanarMesh {
            vertices: vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y, DVec2::new(2.0, 0.5)],
            triangles: vec![[1, 4, 2]],
            triangle_tags: vec![RegionId(2)],
            quads: vec![[0, 1, 2, 3]],
            quad_tags: vec![RegionId(1)],
            region_names: [(RegionId(1), "plate")].into_iter().collect(),
        }
    }

    #[test]
    fn lifts_validates_and_splits() {
        let s = MixedSurface::from_planar(&plate());
        s.validate().unwrap();
        assert_eq!(s.tags(), vec![FaceId(1), FaceId(2)]);
        assert_eq!(s.face_names.get(FaceId(1)), Some("plate"));
        let t = s.to_triangles();
        t.validate().unwrap();
        assert_eq!(t.triangles.len(), 3);
        let mut bad = s.clone();
        bad.quads[0] = [0, 2, 1, 3];
        assert!(bad.validate().is_err(), "the quad's edge 1-2 now runs the triangle's way");
        let mut bad = s;
        bad.quads[0] = [0, 1, 1, 3];
        assert!(matches!(bad.validate(), Err(MeshError::RepeatedVertex { element: Element::Quad(0), .. })));
    }
}
