//! `TetMesh`: positively oriented tetrahedra with region tags and tagged boundary triangles.

use crate::core::ids::NONE;
use crate::core::predicates::orient3d;
use crate::core::{Aabb, FaceId, FaceNames, RegionId, RegionNames, Sign};
use crate::mesh::tri_surface::{check_finite, check_simplex};
use crate::mesh::{Element, MeshError, TriSurface};
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;

/// Local faces of a tetrahedron `(v0, v1, v2, v3)`: face `k` is opposite vertex `k` and, for a
/// positively oriented tet, turns counter-clockwise seen from outside (its normal points out).
pub const TET_FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// A tetrahedral mesh.
///
/// - `vertices`: #V positions.
/// - `tets`: #T × 4 vertex indices, each tet positively oriented
///   (`det[v1-v0, v2-v0, v3-v0] > 0`, decided exactly).
/// - `region_tags`: #T region tags.
/// - `boundary`: #B × 3 triangles, each a face of some tet, oriented outward where it bounds
///   one tet only; `face_tags`: #B face tags (the CAD face each came from).
/// - `face_names`, `region_names`: names of tags where known (not necessarily unique: writers
///   make them so).
///
/// Tag 0 is untagged; see `crate::core::ids` for the convention.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TetMesh {
    /// Vertex positions.
    pub vertices: Vec<DVec3>,
    /// Tetrahedra as vertex index quadruples.
    pub tets: Vec<[u32; 4]>,
    /// One region tag per tetrahedron.
    pub region_tags: Vec<RegionId>,
    /// Tagged boundary (and interface) triangles.
    pub boundary: Vec<[u32; 3]>,
    /// One face tag per boundary triangle.
    pub face_tags: Vec<FaceId>,
    /// Names of face tags, where known.
    pub face_names: FaceNames,
    /// Names of region tags, where known.
    pub region_names: RegionNames,
}

/// A face of a tet, as found by [`TetMesh::faces`].
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct TetFace {
    /// The face's vertices, oriented outward from `tet`.
    pub vertices: [u32; 3],
    /// The tet it belongs to.
    pub tet: u32,
    /// The tet on the other side, if any.
    pub neighbor: Option<u32>,
}

impl TetMesh {
    /// Drops the vertices no tet uses, keeping the order of the rest, and renumbers the tets
    /// and the boundary triangles; returns how many went (as
    /// [`TriSurface::remove_unused_vertices`](crate::mesh::TriSurface::remove_unused_vertices)).
    ///
    /// ```
    /// use fepre::mesh::TetMesh;
    /// use glam::DVec3;
    /// let vertices = vec![DVec3::X, DVec3::splat(9.0), DVec3::ZERO, DVec3::Y, DVec3::Z];
    /// let mut m = TetMesh { vertices, tets: vec![[2, 0, 3, 4]], boundary: vec![[2, 3, 0]], ..TetMesh::default() };
    /// assert_eq!(m.remove_unused_vertices(), 1);
    /// assert_eq!((m.tets[0], m.boundary[0], m.vertices.len()), ([1, 0, 2, 3], [1, 2, 0], 4));
    /// ```
    pub fn remove_unused_vertices(&mut self) -> usize {
        let mut used = vec![false; self.vertices.len()];
        for &v in self.tets.iter().flatten() {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
        let mut id = vec![NONE; self.vertices.len()];
        let mut next = 0;
        for (i, &u) in used.iter().enumerate() {
            if u {
                id[i] = next as u32;
                self.vertices[next] = self.vertices[i];
                next += 1;
            }
        }
        let removed = self.vertices.len() - next;
        self.vertices.truncate(next);
        let renumber = |v: u32| id.get(v as usize).copied().unwrap_or(NONE);
        for tet in &mut self.tets {
            *tet = tet.map(renumber);
        }
        for tri in &mut self.boundary {
            *tri = tri.map(renumber);
        }
        removed
    }

    /// Checks the invariants: array lengths, finite coordinates, indices, positive orientation
    /// of every tet (exact), at most two tets per face and from opposite sides, and every
    /// boundary triangle a face of some tet.
    ///
    /// # Errors
    /// The first violation found, naming the tet, face or boundary triangle.
    pub fn validate(&self) -> Result<(), MeshError> {
        if self.region_tags.len() != self.tets.len() {
            return Err(MeshError::LengthMismatch { what: "region_tags", found: self.region_tags.len(), expected: self.tets.len() });
        }
        self.validate_face_tags()?;
        self.validate_cells()
    }

    /// The face tags' part of [`TetMesh::validate`]: one tag per boundary triangle.
    ///
    /// # Errors
    /// [`MeshError::LengthMismatch`].
    pub fn validate_face_tags(&self) -> Result<(), MeshError> {
        if self.face_tags.len() != self.boundary.len() {
            return Err(MeshError::LengthMismatch {
                what: "face_tags",
                found: self.face_tags.len(),
                expected: self.boundary.len(),
            });
        }
        Ok(())
    }

    /// [`TetMesh::validate`] but for the face tags (a mesher that tags its boundary while
    /// this runs checks them after with [`TetMesh::validate_face_tags`]).
    ///
    /// # Errors
    /// As [`TetMesh::validate`].
    pub fn validate_cells(&self) -> Result<(), MeshError> {
        if self.region_tags.len() != self.tets.len() {
            return Err(MeshError::LengthMismatch { what: "region_tags", found: self.region_tags.len(), expected: self.tets.len() });
        }
        check_finite(&self.vertices)?;
        let n = self.vertices.len();
        // in parallel; the first bad tet in order is the one reported
        let bad_tet = self.tets.par_iter().enumerate().with_min_len(4096).find_map_first(|(t, tet)| {
            if let Err(e) = check_simplex(Element::Tet(t), tet, n) {
                return Some(e);
            }
            let [a, b, c, d] = tet.map(|i| self.vertices[i as usize]);
            let s = orient3d(a, b, c, d);
            (s != Sign::Positive).then(|| MeshError::BadOrientation { element: Element::Tet(t), vertices: tet.to_vec(), orientation: s })
        });
        if let Some(e) = bad_tet {
            return Err(e);
        }
        for (t, tri) in self.boundary.iter().enumerate() {
            check_simplex(Element::BoundaryTriangle(t), tri, n)?;
        }
        let (start, faces) = self.face_records_by_lead();
        // in the order of the sorted faces: the first bad face is the one reported
        for a in 0..n {
            let bucket = &faces[start[a]..start[a + 1]];
            let key = |r: &FaceRecord| [a as u32, (r.0 >> 32) as u32, r.0 as u32];
            for run in bucket.chunk_by(|x, y| x.0 == y.0) {
                if run.len() > 2 {
                    return Err(MeshError::NonManifold { entity: key(&run[0]).to_vec(), elements: run.iter().map(|f| Element::Tet(f.1 as usize)).collect() });
                }
                if let [x, y] = run {
                    if x.2 == y.2 {
                        return Err(MeshError::Overlap { entity: key(x).to_vec(), first: Element::Tet(x.1 as usize), second: Element::Tet(y.1 as usize) });
                    }
                }
            }
        }
        for (t, tri) in self.boundary.iter().enumerate() {
            let ([a, b, c], _) = sorted3(*tri);
            let bc = (u64::from(b) << 32) | u64::from(c);
            if faces[start[a as usize]..start[a as usize + 1]].binary_search_by(|f| f.0.cmp(&bc)).is_err() {
                return Err(MeshError::BoundaryNotAFace { triangle: t, vertices: *tri });
            }
        }
        Ok(())
    }

    /// Every tet face's record, bucketed by the face's smallest vertex `a` (bucket `a` is
    /// `records[start[a]..start[a + 1]]`) and sorted within its bucket, so that the whole is
    /// in the order of the sorted faces: the face's other two vertices in one key, the tet, the
    /// parity of its outward orientation relative to the sorted order. Every index must be in
    /// range (checked before).
    fn face_records_by_lead(&self) -> (Vec<usize>, Vec<FaceRecord>) {
        let start = self.face_bucket_starts();
        let mut at = start.clone();
        let mut records = vec![(0u64, 0u32, false); start[start.len() - 1]];
        for (t, tet) in self.tets.iter().enumerate() {
            for f in TET_FACES {
                let ([a, b, c], parity) = sorted3([tet[f[0]], tet[f[1]], tet[f[2]]]);
                records[at[a as usize]] = ((u64::from(b) << 32) | u64::from(c), t as u32, parity);
                at[a as usize] += 1;
            }
        }
        // the records are distinct (tet indices differ), so any sort gives the same order
        crate::core::bucket_sort::sort_buckets_by(&mut records, &start, FaceRecord::cmp);
        (start, records)
    }

    /// Where each bucket of the tets' faces by their smallest vertex starts (`n + 1` entries,
    /// the last the number of faces counted, four per tet): the counting pass of the face
    /// records that [`TetMesh::validate_cells`] and the optimiser's adjacency sort. Every
    /// index must be in range.
    pub(crate) fn face_bucket_starts(&self) -> Vec<usize> {
        let n = self.vertices.len();
        let mut start = vec![0usize; n + 1];
        for tet in &self.tets {
            for f in TET_FACES {
                start[tet[f[0]].min(tet[f[1]]).min(tet[f[2]]) as usize + 1] += 1;
            }
        }
        for a in 0..n {
            start[a + 1] += start[a];
        }
        start
    }

    /// Every distinct face once, oriented outward from `tet`, with the neighbouring tet.
    /// Boundary faces (`neighbor == None`) form the mesh's boundary surface.
    pub fn faces(&self) -> Vec<TetFace> {
        let records = || {
            self.tets.iter().enumerate().flat_map(|(t, tet)| {
                TET_FACES.iter().map(move |f| {
                    let v = [tet[f[0]], tet[f[1]], tet[f[2]]];
                    (sorted3(v).0, t as u32, v)
                })
            })
        };
        // (face, tet) is unique, so the whole tuple's order is the order by face then tet
        let n = self.vertices.len();
        let rec: Vec<([u32; 3], u32, [u32; 3])> = if self.tets.iter().flatten().all(|&v| (v as usize) < n) {
            crate::core::bucket_sort::collect_sorted_by_lead(n, records, |r| r.0[0])
        } else {
            let mut rec: Vec<_> = records().collect();
            rec.sort_unstable();
            rec
        };
        let mut out = Vec::with_capacity(rec.len() / 2 + 1);
        let mut i = 0;
        while i < rec.len() {
            if i + 1 < rec.len() && rec[i + 1].0 == rec[i].0 {
                out.push(TetFace { vertices: rec[i].2, tet: rec[i].1, neighbor: Some(rec[i + 1].1) });
                i += 2;
                while i < rec.len() && rec[i].0 == rec[i - 1].0 {
                    i += 1; // non-manifold extra: validate() reports it
                }
            } else {
                out.push(TetFace { vertices: rec[i].2, tet: rec[i].1, neighbor: None });
                i += 1;
            }
        }
        out
    }

    /// The faces used by one tet only, oriented outward: the boundary of the meshed volume.
    pub fn hull_faces(&self) -> Vec<[u32; 3]> {
        self.faces().into_iter().filter(|f| f.neighbor.is_none()).map(|f| f.vertices).collect()
    }

    /// Signed volume of tet `t`.
    pub fn tet_volume(&self, t: usize) -> f64 {
        let [a, b, c, d] = self.tets[t].map(|i| self.vertices[i as usize]);
        (b - a).dot((c - a).cross(d - a)) / 6.0
    }

    /// Sum of the signed tet volumes: the determinants are summed first and divided by 6 once,
    /// so a mesh with integer coordinates gets its volume exactly (while the sums stay below
    /// 2^53).
    pub fn volume(&self) -> f64 {
        let det = |t: &[u32; 4]| {
            let [a, b, c, d] = t.map(|i| self.vertices[i as usize]);
            (b - a).dot((c - a).cross(d - a))
        };
        self.tets.iter().map(det).sum::<f64>() / 6.0
    }

    /// Bounding box of the vertices.
    pub fn bbox(&self) -> Aabb {
        Aabb::from_points(&self.vertices)
    }

    /// The boundary of the meshed volume as a surface over the mesh's own vertices (indices as
    /// in `tets`): its hull faces (faces of one tet only), oriented outward, in the order of
    /// [`TetMesh::faces`], each tagged as the `boundary` triangle on it where there is one,
    /// else [`FaceId::UNTAGGED`]; interface triangles (between two tets) are not part of it.
    /// Face names are kept. [`TriSurface::remove_unused_vertices`] makes it a surface of its
    /// own.
    ///
    /// ```
    /// use fepre::core::FaceId;
    /// let mut m = fepre::mesh::shapes::kuhn_cube(1, 0.0, 0);
    /// m.boundary.clear();
    /// m.face_tags.clear();
    /// let s = m.boundary_surface();
    /// assert_eq!(s.triangles.len(), 12);
    /// assert!(s.face_tags.iter().all(|t| *t == FaceId::UNTAGGED));
    /// ```
    pub fn boundary_surface(&self) -> TriSurface {
        let tag_of: HashMap<[u32; 3], FaceId> = self.boundary.iter().zip(&self.face_tags).map(|(t, tag)| (sorted3(*t).0, *tag)).collect();
        let triangles = self.hull_faces();
        let face_tags = triangles.iter().map(|f| tag_of.get(&sorted3(*f).0).copied().unwrap_or(FaceId::UNTAGGED)).collect();
        TriSurface { vertices: self.vertices.clone(), triangles, face_tags, face_names: self.face_names.clone() }
    }

    /// Reorders each boundary triangle that bounds a single tet so that it faces outward from
    /// that tet; interface triangles (two tets) and triangles that are no face are left as
    /// they are.
    pub fn orient_boundary_outward(&mut self) {
        let mut outward: HashMap<[u32; 3], [u32; 3]> = HashMap::new();
        for f in self.faces() {
            if f.neighbor.is_none() {
                outward.insert(sorted3(f.vertices).0, f.vertices);
            }
        }
        for tri in &mut self.boundary {
            if let Some(o) = outward.get(&sorted3(*tri).0) {
                if sorted3(*tri).1 != sorted3(*o).1 {
                    tri.swap(1, 2);
                }
            }
        }
    }
}

/// A tet face's record in [`TetMesh::validate_cells`]: its two larger vertices (the larger in
/// the low half), the tet, and the parity of the tet's outward orientation relative to the
/// sorted order.
type FaceRecord = (u64, u32, bool);

/// The sorted triple and whether the permutation from `v` to it is even.
#[inline]
pub(crate) fn sorted3(v: [u32; 3]) -> ([u32; 3], bool) {
    let mut s = v;
    let mut even = true;
    if s[0] > s[1] {
        s.swap(0, 1);
        even = !even;
    }
    if s[1] > s[2] {
        s.swap(1, 2);
        even = !even;
    }
    if s[0] > s[1] {
        s.swap(0, 1);
        even = !even;
    }
    (s, even)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_tets() -> TetMesh {
        TetMesh {
            vertices: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::new(1.0, 1.0, 1.0)],
            tets: vec![[0, 1, 2, 3], [1, 4, 2, 3]],
            region_tags: vec![RegionId(1); 2],
            ..Default::default()
        }
    }

    #[test]
    fn faces_and_orientation() {
        let mut m = two_tets();
        assert_eq!(m.validate(), Ok(()));
        assert_eq!(m.faces().len(), 7);
        let hull = m.hull_faces();
        assert_eq!(hull.len(), 6);
        // outward faces: each has positive volume with an interior point
        let c = DVec3::new(0.4, 0.4, 0.4);
        for f in &hull {
            let [a, b, d] = f.map(|i| m.vertices[i as usize]);
            assert_eq!(orient3d(a, b, d, c), Sign::Negative, "face {f:?} faces inward");
        }
        m.boundary = vec![[0, 1, 2]];
        m.face_tags = vec![FaceId(7)];
        m.orient_boundary_outward();
        assert_eq!(m.boundary[0], [0, 2, 1]);
        assert_eq!(m.validate(), Ok(()));
        assert!((m.volume() - 0.5).abs() < 1e-15, "1/6 + 2/6");
    }

    #[test]
    fn boundary_surface_tags_listed_hull_faces_and_leaves_the_rest_untagged() {
        let mut m = two_tets();
        // one hull face listed (given inward: the tag follows the face, not its orientation),
        // and the interface between the two tets, which is no part of the boundary
        m.boundary = vec![[0, 1, 2], [1, 2, 3]];
        m.face_tags = vec![FaceId(7), FaceId(8)];
        m.face_names.insert(FaceId(7), "bottom");
        let s = m.boundary_surface();
        assert_eq!(s.triangles, m.hull_faces());
        assert_eq!(s.vertices, m.vertices);
        let tagged: Vec<([u32; 3], FaceId)> = s.triangles.iter().zip(&s.face_tags).filter(|(_, t)| !t.is_untagged()).map(|(f, t)| (*f, *t)).collect();
        assert_eq!(tagged, vec![([0, 2, 1], FaceId(7))]);
        assert_eq!(s.face_tags.iter().filter(|t| t.is_untagged()).count(), 5);
        assert_eq!(s.face_names.get(FaceId(7)), Some("bottom"));
    }

    #[test]
    fn validate_names_the_tet() {
        let mut m = two_tets();
        m.tets[1] = [1, 2, 4, 3];
        let e = m.validate().unwrap_err();
        assert!(matches!(e, MeshError::BadOrientation { element: Element::Tet(1), orientation: Sign::Negative, .. }));
        let mut m = two_tets();
        m.tets.push([0, 1, 2, 3]);
        m.region_tags.push(RegionId(1));
        assert!(matches!(m.validate(), Err(MeshError::Overlap { .. })));
        let mut m = two_tets();
        m.boundary = vec![[0, 1, 4]];
        m.face_tags = vec![FaceId(1)];
        assert!(matches!(m.validate(), Err(MeshError::BoundaryNotAFace { triangle: 0, .. })));
        let mut m = two_tets();
        m.vertices[4] = DVec3::new(0.5, 0.5, 0.0);
        assert!(matches!(m.validate(), Err(MeshError::BadOrientation { orientation: Sign::Zero, .. })));
        // a third tet on the shared face: the face and its three tets, in order
        let mut m = two_tets();
        m.vertices.push(DVec3::splat(0.9));
        m.tets.push([1, 5, 2, 3]);
        m.region_tags.push(RegionId(1));
        assert_eq!(m.validate(), Err(MeshError::NonManifold { entity: vec![1, 2, 3], elements: vec![Element::Tet(0), Element::Tet(1), Element::Tet(2)] }));
    }
}
