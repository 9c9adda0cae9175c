//! The B-rep as the [`BoundaryGeometry`] oracle: the closest point on a CAD face's surface,
//! or on the curve of the CAD edge two faces share. Boundary mid nodes go there, and the
//! optimiser's sliding boundary vertices go back there.

use crate::cad::brep::Model;
use crate::cad::geom::curve::Curve;
use crate::cad::geom::surface::Surface;
use crate::core::{FaceId, Hint};
use glam::{DVec2, DVec3};
use std::collections::{BTreeMap, BTreeSet};

pub use crate::core::BoundaryGeometry;

/// The searches from a hint stop once a Newton step would move the point by this share of
/// its distance from the origin (plus one) or less: far below any mesh size, where the last
/// steps before rounding stops the search, and the step halvings that find no better point,
/// cost as much again (measured with the hints: the optimiser's projections onto t20_data's
/// B-spline edges took 13 % of its samples searched to rounding, 6 % with this).
const SLIDE_TOLERANCE: f64 = 1e-12;

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

    /// The curve of edge `e`.
    fn curve(&self, e: u32) -> Option<&Curve> {
        self.model.curves.get(self.model.edges.get(e as usize)?.curve? as usize)
    }
}

impl BoundaryGeometry for BrepGeometry<'_> {
    fn on_face(&self, face: FaceId, a: DVec3, _b: DVec3, p: DVec3) -> Option<DVec3> {
        let s = self.surface(face)?;
        let near = s.project(a);
        let uv = s.project_near(p, near);
        let q = s.point(uv.x, uv.y);
        q.is_finite().then_some(q)
    }

    fn face_hint(&self, face: FaceId, p: DVec3) -> Option<Hint> {
        let s = self.surface(face)?;
        // closed forms project at once; the others search globally, once here
        let searched = !matches!(s, Surface::Plane(_) | Surface::Cylinder(_) | Surface::Cone(_) | Surface::Sphere(_) | Surface::Torus(_));
        let uv = s.project(p);
        (searched && uv.is_finite()).then_some(Hint { item: 0, param: uv })
    }

    fn on_face_from(&self, face: FaceId, from: DVec3, hint: Option<Hint>, p: DVec3) -> Option<DVec3> {
        if let (Some(h), Some(s)) = (hint, self.surface(face)) {
            // Newton from the hint; the global search only where that fails
            let uv = s.refine_within(p, h.param, SLIDE_TOLERANCE);
            let q = s.point(uv.x, uv.y);
            if q.is_finite() {
                return Some(q);
            }
        }
        self.on_face(face, from, from, p)
    }

    fn edge_hint(&self, f: FaceId, g: FaceId, p: DVec3) -> Option<Hint> {
        // the faces' shared edge nearest p, and where on it
        let (ef, eg) = (self.edges_of.get(&f)?, self.edges_of.get(&g)?);
        ef.intersection(eg)
            .filter_map(|&e| {
                let c = self.curve(e)?;
                let t = c.project(p);
                let d = c.point(t).distance(p);
                d.is_finite().then_some((d, Hint { item: e, param: DVec2::new(t, 0.0) }))
            })
            .min_by(|x, y| x.0.total_cmp(&y.0))
            .map(|(_, h)| h)
    }

    fn on_edge_from(&self, f: FaceId, g: FaceId, from: DVec3, hint: Option<Hint>, p: DVec3) -> Option<DVec3> {
        if let Some((h, c)) = hint.and_then(|h| Some((h, self.curve(h.item)?))) {
            // conics project at once; the others by Newton from the hint
            let t = if matches!(c, Curve::Line(_) | Curve::Circle(_) | Curve::Ellipse(_)) { c.project(p) } else { c.refine_within(p, h.param.x, SLIDE_TOLERANCE) };
            let q = c.point(t);
            if q.is_finite() {
                return Some(q);
            }
        }
        self.on_edge(f, g, from, from, p)
    }

    fn on_edge(&self, f: FaceId, g: FaceId, _a: DVec3, _b: DVec3, p: DVec3) -> Option<DVec3> {
        // the nearest point of the shared edge nearest p
        let h = self.edge_hint(f, g, p)?;
        Some(self.curve(h.item)?.point(h.param.x))
    }
}
