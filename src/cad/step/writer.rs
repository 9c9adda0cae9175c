//! Our STEP writer: a [`Model`] as an AP214 (`AUTOMOTIVE_DESIGN`) file in millimetres and
//! radians, one product whose `ADVANCED_BREP_SHAPE_REPRESENTATION` holds a
//! `MANIFOLD_SOLID_BREP` per solid (`BREP_WITH_VOIDS` where it has voids) and a
//! `SHELL_BASED_SURFACE_MODEL` for shells outside solids (then a plain `SHAPE_REPRESENTATION`).
//!
//! Topology is written as the model holds it: `ADVANCED_FACE` (named after the face,
//! `same_sense` as in the model) → `FACE_OUTER_BOUND` / `FACE_BOUND` → `EDGE_LOOP` →
//! `ORIENTED_EDGE` → `EDGE_CURVE` (shared by the faces that share the edge) → `VERTEX_POINT`;
//! geometry by `write_geometry.rs`. The output is deterministic: the header carries a
//! fixed time stamp, entities are numbered in the order they are written, and reals are
//! written in their shortest exact form, so the same model gives the same bytes and reads back
//! to the same numbers.
//!
//! A model read from a file and written again loses what the model does not hold (colours,
//! assembly structure: instances are written as separate solids in place).

use crate::cad::brep::Model;
use crate::io::IoError;
use crate::io::atomic::write_atomic;
use std::io::Write;
use std::path::Path;

/// Why a model could not be written as STEP.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StepWriteError {
    /// A coordinate or parameter is NaN or infinite (STEP has no way to say so).
    #[error("cannot write {what}: a coordinate is not finite")]
    NotFinite {
        /// The item.
        what: String,
    },
    /// An index of the model points nowhere (the model is inconsistent: see
    /// [`Model::issues`]).
    #[error("the model is inconsistent: {what}")]
    BadIndex {
        /// The item.
        what: String,
    },
    /// Writing the file failed.
    #[error(transparent)]
    Io(#[from] IoError),
}

/// Entities in the order written; `#k` is `entities[k - 1]`.
pub(super) struct Writer {
    entities: Vec<String>,
}

impl Writer {
    /// Adds an entity (its text after `#k=`, without the `;`) and returns its id.
    pub(super) fn add(&mut self, text: String) -> u64 {
        self.entities.push(text);
        self.entities.len() as u64
    }
}

/// A STEP string literal: quotes doubled, backslashes doubled, characters outside printable
/// ASCII as `\X2\hhhh\X0\`.
pub(super) fn string(s: &str) -> String {
    let mut out = String::from("'");
    for ch in s.chars() {
        match ch {
            '\'' => out.push_str("''"),
            '\\' => out.push_str("\\\\"),
            ' '..='~' => out.push(ch),
            _ => {
                let mut buf = [0u16; 2];
                out.push_str("\\X2\\");
                for u in ch.encode_utf16(&mut buf) {
                    out.push_str(&format!("{u:04X}"));
                }
                out.push_str("\\X0\\");
            }
        }
    }
    out.push('\'');
    out
}

/// The model as the text of a STEP file; `name` names the product and the file in the header.
///
/// # Errors
/// [`StepWriteError::NotFinite`] for a non-finite coordinate, [`StepWriteError::BadIndex`]
/// for an index out of range.
pub fn to_string(model: &Model, name: &str) -> Result<String, StepWriteError> {
    let mut w = Writer { entities: Vec::new() };
    let (items, surface_model) = w.topology(model)?;
    let kind = if surface_model { "SHAPE_REPRESENTATION" } else { "ADVANCED_BREP_SHAPE_REPRESENTATION" };
    w.context_and_product(name, &items, kind)?;
    Ok(w.file_text(name, "AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }"))
}

impl Writer {
    /// An empty writer.
    pub(super) fn new() -> Writer {
        Writer { entities: Vec::new() }
    }

    /// The whole file: header (fixed time stamp, `schema`) and the entities written.
    pub(super) fn file_text(&self, name: &str, schema: &str) -> String {
        let mut out = String::new();
        out.push_str("ISO-10303-21;\nHEADER;\n");
        out.push_str(&format!("FILE_DESCRIPTION(({}),'2;1');\n", string(&format!("{name}: written by fepre"))));
        out.push_str(&format!(
            "FILE_NAME({},'2000-01-01T00:00:00',(''),(''),'fepre {}','fepre','');\n",
            string(&format!("{name}.step")),
            env!("CARGO_PKG_VERSION")
        ));
        out.push_str(&format!("FILE_SCHEMA(('{schema}'));\nENDSEC;\nDATA;\n"));
        for (k, e) in self.entities.iter().enumerate() {
            out.push_str(&format!("#{}={e};\n", k + 1));
        }
        out.push_str("ENDSEC;\nEND-ISO-10303-21;\n");
        out
    }
}

/// Writes the model to `path` through a temporary file (nothing is left on failure).
///
/// # Errors
/// As [`to_string`], and [`StepWriteError::Io`] when the file cannot be written.
pub fn write(path: &Path, model: &Model, name: &str) -> Result<(), StepWriteError> {
    let text = to_string(model, name)?;
    write_atomic(path, |f| f.write_all(text.as_bytes()).map_err(|source| IoError::Write { path: path.to_path_buf(), source }))?;
    Ok(())
}

impl Writer {
    /// Vertices, edges, faces, shells and solids; returns the representation items (solids
    /// and surface models) and whether any shell lies outside a solid.
    fn topology(&mut self, m: &Model) -> Result<(Vec<u64>, bool), StepWriteError> {
        let bad = |what: String| StepWriteError::BadIndex { what };
        let mut vertex_ids = Vec::with_capacity(m.vertices.len());
        for v in &m.vertices {
            let p = self.point(v.point)?;
            vertex_ids.push(self.add(format!("VERTEX_POINT('',#{p})")));
        }
        let mut curve_ids: Vec<Option<u64>> = vec![None; m.curves.len()];
        let mut edge_ids = Vec::with_capacity(m.edges.len());
        for (k, e) in m.edges.iter().enumerate() {
            let (Some(&vs), Some(&ve)) = (vertex_ids.get(e.start as usize), vertex_ids.get(e.end as usize)) else {
                return Err(bad(format!("edge {k}: vertex out of range")));
            };
            let (c, same) = match e.curve {
                Some(ci) => {
                    let curve = m.curves.get(ci as usize).ok_or_else(|| bad(format!("edge {k}: curve out of range")))?;
                    let id = match curve_ids[ci as usize] {
                        Some(id) => id,
                        None => {
                            let id = self.curve(curve)?;
                            curve_ids[ci as usize] = Some(id);
                            id
                        }
                    };
                    (id, e.same_sense)
                }
                None => {
                    // no curve: the straight segment between the vertices
                    let (a, b) = (m.vertices[e.start as usize].point, m.vertices[e.end as usize].point);
                    (self.curve(&crate::cad::geom::Curve::Line(crate::cad::geom::Line { origin: a, direction: b - a }))?, true)
                }
            };
            edge_ids.push(self.add(format!("EDGE_CURVE('',#{vs},#{ve},#{c},{})", if same { ".T." } else { ".F." })));
        }
        let mut surface_ids: Vec<Option<u64>> = vec![None; m.surfaces.len()];
        let mut face_ids = Vec::with_capacity(m.faces.len());
        for fid in m.face_ids() {
            let f = m.face(fid);
            let mut bounds = Vec::with_capacity(f.loops.len());
            for &li in &f.loops {
                let l = m.loops.get(li as usize).ok_or_else(|| bad(format!("face {fid}: loop out of range")))?;
                let lp = if let Some(v) = l.vertex {
                    let vid = *vertex_ids.get(v as usize).ok_or_else(|| bad(format!("face {fid}: vertex out of range")))?;
                    self.add(format!("VERTEX_LOOP('',#{vid})"))
                } else {
                    let mut oriented = Vec::with_capacity(l.coedges.len());
                    for c in &l.coedges {
                        let eid = *edge_ids.get(c.edge as usize).ok_or_else(|| bad(format!("face {fid}: edge out of range")))?;
                        oriented.push(self.add(format!("ORIENTED_EDGE('',*,*,#{eid},{})", if c.forward { ".T." } else { ".F." })));
                    }
                    let list: Vec<String> = oriented.iter().map(|i| format!("#{i}")).collect();
                    self.add(format!("EDGE_LOOP('',({}))", list.join(",")))
                };
                let kind = if l.outer { "FACE_OUTER_BOUND" } else { "FACE_BOUND" };
                bounds.push(self.add(format!("{kind}('',#{lp},{})", if l.orientation { ".T." } else { ".F." })));
            }
            let si = f.surface as usize;
            let surface = m.surfaces.get(si).ok_or_else(|| bad(format!("face {fid}: surface out of range")))?;
            let sid = match surface_ids[si] {
                Some(id) => id,
                None => {
                    let id = self.surface(surface)?;
                    surface_ids[si] = Some(id);
                    id
                }
            };
            let list: Vec<String> = bounds.iter().map(|i| format!("#{i}")).collect();
            let name = string(f.name.as_deref().unwrap_or(""));
            face_ids.push(self.add(format!("ADVANCED_FACE({name},({}),#{sid},{})", list.join(","), if f.same_sense { ".T." } else { ".F." })));
        }
        let shell_text = |s: &crate::cad::brep::Shell| -> Result<String, StepWriteError> {
            let list = s.faces.iter().map(|&f| match f.index().and_then(|k| face_ids.get(k)) {
                Some(id) => Ok(format!("#{id}")),
                None => Err(bad(format!("shell {}: {f} out of range", s.source))),
            });
            let list: Vec<String> = list.collect::<Result<_, _>>()?;
            Ok(format!("{}('',({}))", if s.closed { "CLOSED_SHELL" } else { "OPEN_SHELL" }, list.join(",")))
        };
        let mut items = Vec::new();
        for (k, s) in m.solids.iter().enumerate() {
            let name = string(s.name.as_deref().unwrap_or(""));
            let mut shells = s.shells.iter().map(|&i| m.shells.get(i as usize).ok_or_else(|| bad(format!("solid {k}: shell out of range"))));
            let outer = shells.next().ok_or_else(|| bad(format!("solid {k} has no shell")))??;
            let outer_id = self.add(shell_text(outer)?);
            let voids: Vec<_> = shells.collect::<Result<_, _>>()?;
            if voids.is_empty() {
                items.push(self.add(format!("MANIFOLD_SOLID_BREP({name},#{outer_id})")));
            } else {
                let mut ids = Vec::new();
                for v in voids {
                    let inner = self.add(shell_text(v)?);
                    ids.push(format!("#{}", self.add(format!("ORIENTED_CLOSED_SHELL('',*,#{inner},.T.)"))));
                }
                items.push(self.add(format!("BREP_WITH_VOIDS({name},#{outer_id},({}))", ids.join(","))));
            }
        }
        let loose: Vec<_> = m.shells.iter().filter(|s| s.solid.is_none()).collect();
        let surface_model = !loose.is_empty();
        if surface_model {
            let mut ids = Vec::with_capacity(loose.len());
            for s in loose {
                ids.push(format!("#{}", self.add(shell_text(s)?)));
            }
            items.push(self.add(format!("SHELL_BASED_SURFACE_MODEL('',({}))", ids.join(","))));
        }
        Ok((items, surface_model))
    }

    /// Units, context, the product and its shape representation holding `items`.
    pub(super) fn context_and_product(&mut self, name: &str, items: &[u64], kind: &str) -> Result<u64, StepWriteError> {
        let n = string(name);
        let length = self.add("(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.))".into());
        let angle = self.add("(NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.))".into());
        let solid_angle = self.add("(NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT())".into());
        let unc = self.add(format!("UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#{length},'distance_accuracy_value','confusion accuracy')"));
        let ctx = self.add(format!(
            "(GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{unc})) \
             GLOBAL_UNIT_ASSIGNED_CONTEXT((#{length},#{angle},#{solid_angle})) REPRESENTATION_CONTEXT('Context #1','3D Context with UNIT and UNCERTAINTY'))"
        ));
        let origin = self.placement(&crate::cad::geom::Frame::WORLD)?;
        let list: Vec<String> = items.iter().chain(std::iter::once(&origin)).map(|i| format!("#{i}")).collect();
        let rep = self.add(format!("{kind}({n},({}),#{ctx})", list.join(",")));
        let app = self.add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')".into());
        self.add(format!("APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})"));
        let pctx = self.add(format!("PRODUCT_CONTEXT('',#{app},'mechanical')"));
        let product = self.add(format!("PRODUCT({n},{n},'',(#{pctx}))"));
        self.add(format!("PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{product}))"));
        let formation = self.add(format!("PRODUCT_DEFINITION_FORMATION('','',#{product})"));
        let pdctx = self.add(format!("PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"));
        let pd = self.add(format!("PRODUCT_DEFINITION('design','',#{formation},#{pdctx})"));
        let pds = self.add(format!("PRODUCT_DEFINITION_SHAPE('','',#{pd})"));
        Ok(self.add(format!("SHAPE_DEFINITION_REPRESENTATION(#{pds},#{rep})")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strings_are_escaped() {
        assert_eq!(string("hole_1"), "'hole_1'");
        assert_eq!(string("it's"), "'it''s'");
        assert_eq!(string("a\\b"), "'a\\\\b'");
        assert_eq!(string("Ø"), "'\\X2\\00D8\\X0\\'");
    }
}
