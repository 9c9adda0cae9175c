//! What selectors and size fields know of each face of a part: its name, colour, STEP `#id`
//! and solid, the kind of its surface (a plane's normal and offset, a cylinder's axis and
//! radius), its area, box, smallest radius of curvature, and its triangles (for distances).
//!
//! Built from a B-rep [`Model`] with a tessellation of it (the geometry oracle), or from a
//! tagged [`TriSurface`] (STL solids, OBJ groups, glTF primitives, MSH physical groups), where
//! a tag is a face and planes are recognised from its triangles.

use crate::cad::brep::{EntityRef, Model};
use crate::cad::geom::Surface;
use crate::core::{Aabb, FaceId};
use crate::mesh::TriSurface;
use crate::tessellate::Tessellation;
use glam::DVec3;
use serde::Serialize;

/// The geometry of a face, as far as selectors use it.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum FaceShape {
    /// A plane `normal · x = offset`, `normal` the outward unit normal of the face.
    Plane {
        /// Outward unit normal.
        normal: [f64; 3],
        /// `normal · x` on the plane.
        offset: f64,
    },
    /// A cylinder.
    Cylinder {
        /// A point of the axis.
        origin: [f64; 3],
        /// Unit axis direction (its sign means nothing).
        axis: [f64; 3],
        /// Radius.
        radius: f64,
    },
    /// Any other surface (its kind's name: `cone`, `sphere`, `torus`, `bspline`, ...).
    Other {
        /// The surface kind.
        surface: String,
    },
}

/// One face of a part.
#[derive(Clone, Debug, Serialize)]
pub struct FaceInfo {
    /// The face's id (the tag its triangles carry).
    pub id: FaceId,
    /// Its name in the file, if any.
    pub name: Option<String>,
    /// Its colour, RGB in `[0, 1]`, if any.
    pub colour: Option<[f32; 3]>,
    /// The STEP instance (`ADVANCED_FACE`), for a B-rep face.
    pub step_id: Option<EntityRef>,
    /// The solid it bounds (1-based, in the order of the model's solids), if any.
    pub solid: Option<u32>,
    /// Its surface.
    pub shape: FaceShape,
    /// Area of its triangles.
    pub area: f64,
    /// Box of its triangles.
    #[serde(skip)]
    pub bbox: Aabb,
    /// Smallest principal radius of curvature of its surface (infinite for a plane).
    #[serde(skip)]
    pub min_radius: f64,
}

/// Every face of a part, and the triangles of each.
#[derive(Clone, Debug, Default)]
pub struct FaceCatalogue {
    /// The faces, in id order.
    pub faces: Vec<FaceInfo>,
    /// Solid names (index = solid number - 1).
    pub solid_names: Vec<Option<String>>,
    /// Vertices of [`FaceCatalogue::triangles`].
    pub vertices: Vec<DVec3>,
    /// Triangles and the face each lies in.
    pub triangles: Vec<([u32; 3], FaceId)>,
    /// The curved B-rep edges: their points and smallest radius of curvature.
    pub curved_edges: Vec<(Vec<DVec3>, f64)>,
    /// The diagonal of the part's box.
    pub size: f64,
}

impl FaceCatalogue {
    /// The catalogue of a B-rep model, with `tessellation` (of the same model) as its geometry.
    pub fn from_model(model: &Model, tessellation: &Tessellation) -> FaceCatalogue {
        let s = &tessellation.surface;
        let mut cat = FaceCatalogue::from_triangles(s);
        cat.size = model.size();
        cat.solid_names = model.solids.iter().map(|x| x.name.clone()).collect();
        for (e, pts) in model.edges.iter().zip(&tessellation.edges) {
            let r = edge_min_radius(model, e);
            if r.is_finite() && pts.ids.len() >= 2 {
                cat.curved_edges.push((pts.ids.iter().map(|&i| s.vertices[i as usize]).collect(), r));
            }
        }
        for info in &mut cat.faces {
            let Some(face) = model.try_face(info.id) else { continue };
            info.name = face.name.clone();
            info.colour = face.colour;
            info.step_id = Some(face.source);
            info.solid = model.shells.get(face.shell as usize).and_then(|sh| sh.solid).map(|k| k + 1);
            let surf = model.surface(face.surface);
            let flip = if face.same_sense { 1.0 } else { -1.0 };
            info.shape = match surf {
                Surface::Plane(p) => {
                    let n = p.frame.z * flip;
                    FaceShape::Plane { normal: n.to_array(), offset: n.dot(p.frame.origin) }
                }
                Surface::Cylinder(c) => FaceShape::Cylinder { origin: c.frame.origin.to_array(), axis: c.frame.z.to_array(), radius: c.radius },
                other => FaceShape::Other { surface: other.kind().name().to_string() },
            };
            info.min_radius = surface_min_radius(surf, tessellation, info.id);
        }
        cat
    }

    /// The catalogue of a tagged surface: one face per tag, named by the surface's tag names;
    /// a tag whose triangles all lie in one plane is a plane.
    pub fn from_surface(surface: &TriSurface) -> FaceCatalogue {
        let mut cat = FaceCatalogue::from_triangles(surface);
        let diag = surface.bbox().diagonal();
        cat.size = if diag > 0.0 { diag } else { 1.0 };
        for info in &mut cat.faces {
            info.name = surface.face_names.get(info.id).map(str::to_string);
        }
        // planes: every triangle's normal along the area-weighted mean, every vertex on it
        let tol = 1e-9 * cat.size;
        for info in &mut cat.faces {
            let tris: Vec<[DVec3; 3]> = cat.triangles.iter().filter(|(_, f)| *f == info.id).map(|(t, _)| t.map(|i| cat.vertices[i as usize])).collect();
            let n: DVec3 = tris.iter().map(|t| (t[1] - t[0]).cross(t[2] - t[0])).sum();
            let Some(n) = n.try_normalize() else { continue };
            let offset = n.dot(tris[0][0]);
            if tris.iter().flatten().all(|p| (n.dot(*p) - offset).abs() <= tol) {
                info.shape = FaceShape::Plane { normal: n.to_array(), offset };
            }
        }
        cat
    }

    fn from_triangles(s: &TriSurface) -> FaceCatalogue {
        let mut faces: std::collections::BTreeMap<FaceId, FaceInfo> = std::collections::BTreeMap::new();
        for (t, tri) in s.triangles.iter().enumerate() {
            let id = s.face_tags[t];
            let p = tri.map(|i| s.vertices[i as usize]);
            let info = faces.entry(id).or_insert_with(|| FaceInfo {
                id,
                name: None,
                colour: None,
                step_id: None,
                solid: None,
                shape: FaceShape::Other { surface: "mesh".into() },
                area: 0.0,
                bbox: Aabb::default(),
                min_radius: f64::INFINITY,
            });
            info.area += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
            for q in p {
                info.bbox.grow(q);
            }
        }
        FaceCatalogue {
            faces: faces.into_values().collect(),
            solid_names: Vec::new(),
            vertices: s.vertices.clone(),
            triangles: s.triangles.iter().copied().zip(s.face_tags.iter().copied()).collect(),
            curved_edges: Vec::new(),
            size: 1.0,
        }
    }

    /// The volume its triangles enclose (absolute; meaningful for closed surfaces).
    pub fn volume(&self) -> f64 {
        let v: f64 = self.triangles.iter().map(|(t, _)| {
            let [a, b, c] = t.map(|i| self.vertices[i as usize]);
            a.dot(b.cross(c)) / 6.0
        }).sum();
        v.abs()
    }

    /// The face with this id.
    pub fn get(&self, id: FaceId) -> Option<&FaceInfo> {
        self.faces.binary_search_by_key(&id, |f| f.id).ok().map(|k| &self.faces[k])
    }

    /// The corners of the triangles of the faces in `ids` (ascending).
    pub fn triangles_of(&self, ids: &[FaceId]) -> Vec<[DVec3; 3]> {
        self.triangles.iter().filter(|(_, f)| ids.binary_search(f).is_ok()).map(|(t, _)| t.map(|i| self.vertices[i as usize])).collect()
    }
}

/// The smallest radius of curvature along an edge (infinite for a line), from the curve's
/// derivatives at 17 points.
fn edge_min_radius(model: &Model, e: &crate::cad::brep::Edge) -> f64 {
    let Some(c) = e.curve else { return f64::INFINITY };
    if e.degenerate || !e.range.min.is_finite() || !e.range.max.is_finite() {
        return f64::INFINITY;
    }
    let c = model.curve(c);
    let mut r = f64::INFINITY;
    for k in 0..=16 {
        let t = e.range.min + e.range.length() * k as f64 / 16.0;
        let d = c.derivs(t);
        let s = d.d1.length();
        let k = d.d1.cross(d.d2).length() / (s * s * s);
        if k.is_finite() && k > 0.0 {
            r = r.min(1.0 / k);
        }
    }
    r
}

/// The smallest principal radius of curvature of `surf` at the parameter points of the face's
/// domain triangulation (infinite for a plane or a face without one).
fn surface_min_radius(surf: &Surface, t: &Tessellation, id: FaceId) -> f64 {
    match surf {
        Surface::Plane(_) => return f64::INFINITY,
        Surface::Cylinder(c) => return c.radius,
        Surface::Sphere(s) => return s.radius,
        _ => {}
    }
    let Some(Some(dom)) = (id.0 as usize).checked_sub(1).and_then(|k| t.domains.get(k)) else { return f64::INFINITY };
    let mut r = f64::INFINITY;
    let step = (dom.uv.len() / 200).max(1);
    for tri in dom.uv.iter().step_by(step) {
        for uv in tri {
            let d = surf.derivs(uv.x, uv.y);
            let Some(n) = d.du.cross(d.dv).try_normalize() else { continue };
            let (e, f, g) = (d.du.dot(d.du), d.du.dot(d.dv), d.dv.dot(d.dv));
            let (l, m, nn) = (d.duu.dot(n), d.duv.dot(n), d.dvv.dot(n));
            let det = e * g - f * f;
            if det <= 0.0 {
                continue;
            }
            let k = (l * nn - m * m) / det;
            let h = (e * nn - 2.0 * f * m + g * l) / (2.0 * det);
            let kmax = h.abs() + (h * h - k).max(0.0).sqrt();
            if kmax.is_finite() && kmax > 0.0 {
                r = r.min(1.0 / kmax);
            }
        }
    }
    r
}
