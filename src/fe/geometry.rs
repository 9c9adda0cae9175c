//! The B-rep as the [`BoundaryGeometry`] oracle: the closest point on a CAD face's surface,
//! or on the curve of the CAD edge two faces share. Boundary mid nodes go there, and the
//! optimiser's sliding boundary vertices go back there.

use crate::cad::brep::Model;
use crate::core::FaceId;
use crate::cad::geom::surface::Surface;
use glam::{DVec2, DVec3};
use std::collections::{BTreeMap, BTreeSet};

pub use crate::core::BoundaryGeometry;

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

impl BrepGeometry<'_> {
    /// The surface of face `face`.
    fn surface(&self, face: FaceId) -> Option<&Surface> {
        let f = self.model.faces.get(face.index()?)?;
        self.model.surfaces.get(f.surface as usize)
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

    fn face_hint(&self, face: FaceId, p: DVec3) -> Option<DVec2> {
        let s = self.surface(face)?;
        // closed forms project at once; the others search globally, once here
        let searched = !matches!(s, Surface::Plane(_) | Surface::Cylinder(_) | Surface::Cone(_) | Surface::Sphere(_) | Surface::Torus(_));
        let uv = s.project(p);
        (searched && uv.is_finite()).then_some(uv)
    }

    fn on_face_from(&self, face: FaceId, from: DVec3, hint: Option<DVec2>, p: DVec3) -> Option<DVec3> {
        if let (Some(uv), Some(s)) = (hint, self.surface(face)) {
            // Newton from the hint; the global search only where that fails
            let uv = s.refine(p, uv);
            let q = s.point(uv.x, uv.y);
            if q.is_finite() {
                return Some(q);
            }
        }
        self.on_face(face, from, from, p)
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
