//! Reading AP242 tessellated geometry: `TESSELLATED_SOLID`, `TESSELLATED_SHELL`, `TRIANGULATED_FACE`,
//! `COMPLEX_TRIANGULATED_FACE` and the surface sets, read into one tagged `TriSurface` in
//! millimetres and world placement (assembly instances and units as for a B-rep), one
//! `FaceId` per tessellated face, its name kept.
//!
//! The schema (ISO 10303-42, as OpenCASCADE's `RWStepVisual` reads it):
//! - `COORDINATES_LIST(name, npoints, ((x, y, z), ...))`;
//! - `TRIANGULATED_FACE(name, coordinates, pnmax, normals, geometric_link, pnindex, triangles)`;
//! - `COMPLEX_TRIANGULATED_FACE(name, coordinates, pnmax, normals, geometric_link, pnindex,
//!   triangle_strips, triangle_fans)`;
//! - `TRIANGULATED_SURFACE_SET` and `COMPLEX_TRIANGULATED_SURFACE_SET`: the same without
//!   `geometric_link`;
//! - `TESSELLATED_SHELL(name, items, topological_link)`, `TESSELLATED_SOLID(name, items,
//!   geometric_link)`, `TESSELLATED_GEOMETRIC_SET(name, children)`.
//!
//! Indices are 1-based: into `pnindex` when it is not empty (whose values index the
//! coordinates), else into the coordinates. Strips and fans are turned into triangles as
//! OpenCASCADE turns them (the reader of reference for these files): a strip `s1 s2 s3 s4 ...`
//! gives `(s1, s3, s2)`, `(s2, s3, s4)`, `(s3, s5, s4)`, ...; a fan `f1 f2 f3 f4 ...` gives
//! `(f1, f3, f2)`, `(f1, f4, f3)`, ...; a triangle with a repeated index (a strip's
//! stitching) is skipped. Normals are not read: the surface's orientation is its triangles'.
//! Tessellated edges and vertices (`TESSELLATED_EDGE`, ...) bound no area and are listed as
//! dropped. An index out of range is an error naming the instance and its line.
//!
//! Vertices are shared where two faces use the same point of the same coordinate list in the
//! same placed instance, and where their coordinates are bit-identical after placement (faces
//! written with a coordinate list each).

use super::convert::{Args, Converter, Fail, R};
use super::error::StepError;
use super::param::Param;
use super::table::Entity;
use super::tessellated::{TessellatedFace, TessellatedSolid};
use crate::cad::brep::{Dropped, EntityRef, Units};
use crate::core::FaceId;
use glam::DVec3;

/// True for a representation item this module reads.
pub(super) fn is_tessellated(kind: &str) -> bool {
    matches!(
        kind,
        "TESSELLATED_SOLID" | "TESSELLATED_SHELL" | "TRIANGULATED_FACE" | "COMPLEX_TRIANGULATED_FACE" | "TRIANGULATED_SURFACE_SET" | "COMPLEX_TRIANGULATED_SURFACE_SET" | "TESSELLATED_GEOMETRIC_SET"
    )
}

/// A fatal error about instance `e`.
fn bad(c: &Converter<'_>, e: &Entity, message: String) -> Fail {
    Fail::Fatal(StepError::Tessellation { path: c.file.path.clone(), id: e.id, line: e.line, message })
}

impl Converter<'_> {
    /// A tessellated representation item, in the current representation's units and placement.
    pub(super) fn tessellated_item(&mut self, id: u64, units: &Units) -> R<()> {
        if !self.tess.units_set {
            self.tess.out.units = units.clone();
            self.tess.units_set = true;
        }
        let e = self.entity(id)?;
        self.tess.out.roots.push((EntityRef(id), e.display_type()));
        self.tessellated_child(id, None)
    }

    fn tessellated_child(&mut self, id: u64, solid: Option<u32>) -> R<()> {
        let e = self.entity(id)?;
        match e.type_name() {
            "TESSELLATED_SOLID" | "TESSELLATED_SHELL" => {
                let a = Args::of(e, e.type_name())?;
                let items = a.ids(1)?;
                let name = a.name(0);
                self.tess.out.solids.push(TessellatedSolid { name, step_id: EntityRef(id), solid: e.type_name() == "TESSELLATED_SOLID", faces: Vec::new() });
                let k = self.tess.out.solids.len() as u32;
                for item in items {
                    self.within(id, |c| c.tessellated_child(item, Some(k)))?;
                }
                Ok(())
            }
            "TESSELLATED_GEOMETRIC_SET" => {
                let a = Args::of(e, "TESSELLATED_GEOMETRIC_SET")?;
                for item in a.ids(1)? {
                    self.within(id, |c| c.tessellated_child(item, solid))?;
                }
                Ok(())
            }
            "TRIANGULATED_FACE" | "COMPLEX_TRIANGULATED_FACE" | "TRIANGULATED_SURFACE_SET" | "COMPLEX_TRIANGULATED_SURFACE_SET" => self.tessellated_face(e, solid),
            _ => {
                let why = if e.type_name().contains("EDGE") || e.type_name().contains("VERTEX") {
                    "a tessellated edge or vertex bounds no area (the faces carry the surface)"
                } else {
                    "a tessellated item fepre does not read (it reads triangulated faces, surface sets, shells and solids)"
                };
                self.report(Dropped { kind: e.display_type(), id: EntityRef(id), why: why.into() });
                Ok(())
            }
        }
    }

    /// One triangulated face or surface set.
    fn tessellated_face(&mut self, e: &Entity, solid: Option<u32>) -> R<()> {
        let kind = e.type_name();
        let a = Args::of(e, kind)?;
        // surface sets have no geometric_link
        let k0 = if kind.ends_with("FACE") { 5 } else { 4 };
        let coords_id = a.id(1)?;
        let ce = self.entity(coords_id)?;
        let points = coordinates(self, ce)?;
        let pnindex = index_list(self, e, a.list(k0)?, "pnindex")?;
        for &p in &pnindex {
            if p < 1 || p as usize > points.len() {
                return Err(bad(self, e, format!("pnindex value {p} is outside the {} points of COORDINATES_LIST #{coords_id}", points.len())));
            }
        }
        let count = if pnindex.is_empty() { points.len() } else { pnindex.len() };
        let mut tris: Vec<[i64; 3]> = Vec::new();
        let mut skipped = 0usize;
        if kind.starts_with("COMPLEX") {
            for strip in nested(self, e, a.list(k0 + 1)?, "triangle_strips")? {
                for k in 2..strip.len() {
                    let t = if k % 2 == 0 { [strip[k - 2], strip[k], strip[k - 1]] } else { [strip[k - 2], strip[k - 1], strip[k]] };
                    tris.push(t);
                }
            }
            for fan in nested(self, e, a.list(k0 + 2)?, "triangle_fans")? {
                for k in 2..fan.len() {
                    tris.push([fan[0], fan[k], fan[k - 1]]);
                }
            }
        } else {
            for t in nested(self, e, a.list(k0 + 1)?, "triangles")? {
                if t.len() != 3 {
                    return Err(bad(self, e, format!("a triangle has {} indices, expected 3", t.len())));
                }
                tris.push([t[0], t[1], t[2]]);
            }
        }
        let face = FaceId::from_index(self.tess.out.faces.len());
        let (scale, place, instance) = (self.ctx.scale, self.ctx.place, self.ctx.instance);
        let mut n = 0usize;
        for t in tris {
            for &i in &t {
                if i < 1 || i as usize > count {
                    let into = if pnindex.is_empty() { format!("the {count} points of COORDINATES_LIST #{coords_id}") } else { format!("the {count} entries of pnindex") };
                    return Err(bad(self, e, format!("index {i} is outside {into}")));
                }
            }
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                skipped += 1;
                continue;
            }
            let v = t.map(|i| {
                let p = if pnindex.is_empty() { i } else { pnindex[i as usize - 1] } as u32 - 1;
                let s = &mut self.tess.out.surface;
                *self.tess.vertex.entry((coords_id, instance, p)).or_insert_with(|| {
                    s.vertices.push(place.apply_point(points[p as usize] * scale));
                    (s.vertices.len() - 1) as u32
                })
            });
            self.tess.out.surface.triangles.push(v);
            self.tess.out.surface.face_tags.push(face);
            n += 1;
        }
        let name = a.name(0);
        if let Some(name) = &name {
            self.tess.out.surface.face_names.insert(face, name.clone());
        }
        if let Some(k) = solid {
            self.tess.out.solids[k as usize - 1].faces.push(face);
        }
        self.tess.out.skipped_degenerate += skipped;
        self.tess.out.faces.push(TessellatedFace { face, name, step_id: EntityRef(e.id), solid, triangles: n });
        Ok(())
    }
}

/// The points of a `COORDINATES_LIST`, in the file's units.
fn coordinates(c: &Converter<'_>, e: &Entity) -> R<Vec<DVec3>> {
    let a = Args::of(e, "COORDINATES_LIST").map_err(|_| bad(c, e, "expected a COORDINATES_LIST".into()))?;
    let list = a.list(2)?;
    let mut out = Vec::with_capacity(list.len());
    for (k, p) in list.iter().enumerate() {
        let xyz: Option<Vec<f64>> = p.as_list().map(|l| l.iter().map(|x| x.as_f64().filter(|x| x.is_finite())).collect::<Option<Vec<f64>>>()).flatten();
        match xyz.as_deref() {
            Some(&[x, y, z]) => out.push(DVec3::new(x, y, z)),
            _ => return Err(bad(c, e, format!("point {} is not three finite numbers", k + 1))),
        }
    }
    Ok(out)
}

/// A list of integers (`pnindex`).
fn index_list(c: &Converter<'_>, e: &Entity, list: &[Param], what: &str) -> R<Vec<i64>> {
    list.iter().map(|p| p.as_i64().ok_or_else(|| bad(c, e, format!("{what}: expected integers, found {p:?}")))).collect()
}

/// A list of lists of integers (triangles, strips, fans).
fn nested(c: &Converter<'_>, e: &Entity, list: &[Param], what: &str) -> R<Vec<Vec<i64>>> {
    list.iter()
        .map(|l| match l.as_list() {
            Some(l) => index_list(c, e, l, what),
            None => Err(bad(c, e, format!("{what}: expected lists of integers, found {l:?}"))),
        })
        .collect()
}
