//! Where a boundary mid-edge node goes: the [`BoundaryGeometry`] oracle, and its B-rep
//! implementation (closest point on the CAD face's surface, or on the curve of the CAD edge
//! two faces share).

use crate::cad::brep::Model;
use crate::core::FaceId;
use glam::DVec3;
use std::collections::{BTreeMap, BTreeSet};

/// The geometry a boundary mesh edge's mid node is placed on.
pub trait BoundaryGeometry: Sync {
    /// The point of CAD face `face` closest to `p` (the chord midpoint of mesh edge `a`-`b`,
    /// both on the face), or `None` where the face has no geometry.
    fn on_face(&self, face: FaceId, a: DVec3, b: DVec3, p: DVec3) -> Option<DVec3>;
    /// The point of the CAD edge between faces `f` and `g` closest to `p` (the chord midpoint
    /// of mesh edge `a`-`b`), or `None` where they share no curved edge.
    fn on_edge(&self, f: FaceId, g: FaceId, a: DVec3, b: DVec3, p: DVec3) -> Option<DVec3>;
}

/// A B-rep as a [`BoundaryGeometry`]; face tags are B-rep [`FaceId`]s.
pub struct BrepGeometry<'a> {
    model: &'a Model,
    /// The curved edges of each face (indices into `model.edges`).
    edges_of: BTreeMap<FaceId, BTreeSet<u32>>,
}

impl<'a> BrepGeometry<'a> {
    /// Indexes the faces' edges.
    pub fn new(model: &'a Model) -> Self {
        let mut edges_of: BTreeMap<FaceId, BTreeSet<u32>> = BTreeMap::new();
        for l in &model.loops {
            for c in &l.coedges {
                let e = &model.edges[c.edge as usize];
                if e.curve.is_some() && !e.degenerate {
                    edges_of.entry(l.face).or_default().insert(c.edge);
                }
            }
        }
        BrepGeometry { model, edges_of }
    }
}

impl BoundaryGeometry for BrepGeometry<'_> {
    fn on_face(&self, face: FaceId, a: DVec3, _b: DVec3, p: DVec3) -> Option<DVec3> {
        let f = self.model.faces.get(face.index()?)?;
        let s = self.model.surfaces.get(f.surface as usize)?;
        let near = s.project(a);
        let uv = s.project_near(p, near);
        let q = s.point(uv.x, uv.y);
        q.is_finite().then_some(q)
    }

    fn on_edge(&self, f: FaceId, g: FaceId, _a: DVec3, _b: DVec3, p: DVec3) -> Option<DVec3> {
        let (ef, eg) = (self.edges_of.get(&f)?, self.edges_of.get(&g)?);
        ef.intersection(eg)
            .filter_map(|&e| {
                let c = &self.model.curves[self.model.edges[e as usize].curve? as usize];
                let q = c.point(c.project(p));
                q.is_finite().then_some(q)
            })
            .min_by(|x, y| (*x - p).length().total_cmp(&(*y - p).length()))
    }
}
