//! STEP (ISO 10303-21) import: a reader of our own, tolerant of what real AP203, AP214 and
//! AP242 files contain, and the conversion of their B-rep entities into a [`Model`].
//!
//! Stages: `parser` turns bytes into a [`StepFile`] (`#id → records`, with line numbers;
//! every reference checked), then the converter walks the shape representations
//! (`assembly`), expanding assembly instances with their placements, converting solids,
//! shells and faces (`topology`) and their geometry (`geometry`) into millimetres
//! (`units`).
//!
//! Why not `truck-stepio`: its tokenizer rejects valid files of the corpus (empty lists in
//! AP242), it drops unsupported entities silently, ignores assembly placements and units,
//! and its types are not our `geom` types; a reader of our own is a few hundred lines and
//! reports every item it leaves out ([`Model::dropped`]).
//!
//! The other way, `writer` writes a [`Model`] as an AP214 file (millimetres, named faces,
//! deterministic bytes) that this reader and OpenCASCADE read back.
//!
//! AP242 files may carry tessellated geometry only (`TESSELLATED_SOLID` of
//! `TRIANGULATED_FACE`s, ...): [`read_shape`] reads it (`tessellated`) into a tagged
//! triangle surface, a face per tag, when the file has no B-rep; a file with both gives the
//! B-rep and lists the tessellated items as dropped. [`write_tessellated`] writes such a file.
//!
//! Errors ([`StepError`]) concern the file as a whole and name the line or `#id`: a
//! truncated file, a reference to an undefined instance, a reference cycle, bad syntax.
//! Problems confined to one face or curve drop that item and list it.

mod assembly;
mod colour;
mod convert;
pub(crate) mod error;
mod geometry;
pub(crate) mod param;
pub(crate) mod parser;
pub(crate) mod table;
pub(crate) mod tessellated;
mod read_tessellated;
mod topology;
pub(crate) mod units;
mod write_geometry;
pub(crate) mod write_tessellated;
pub(crate) mod writer;

#[cfg(test)]
mod tests;

pub use error::StepError;
pub use param::Param;
pub use table::{Entity, Record, StepFile};
pub use tessellated::{Tessellated, TessellatedFace, TessellatedSolid};
pub use write_tessellated::{tessellated_to_string, write_tessellated};
pub use writer::{StepWriteError, to_string, write};

use crate::cad::brep::{Dropped, Model};
use std::path::Path;

/// Reads a STEP file into a B-rep model in millimetres, assembly instances expanded.
///
/// # Errors
/// See [`StepError`]: unreadable, not STEP, syntax, truncated, duplicate or missing `#id`,
/// reference cycle, or no B-rep shape at all.
pub fn read(path: &Path) -> Result<Model, StepError> {
    let bytes = std::fs::read(path).map_err(|source| StepError::Read { path: path.to_path_buf(), source })?;
    read_bytes(path, &bytes)
}

/// Like [`read`], from bytes already in memory (`path` is used in messages only).
///
/// # Errors
/// As [`read`].
pub fn read_bytes(path: &Path, bytes: &[u8]) -> Result<Model, StepError> {
    let file = parser::parse(path, bytes)?;
    to_model(&file)
}

/// What a STEP file's geometry is: a B-rep, or (an AP242 file without one) tessellated faces.
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)]
pub enum Shape {
    /// Solids, shells and faces with their exact geometry.
    Brep(Model),
    /// Triangulated faces only (`TESSELLATED_SOLID`, `TRIANGULATED_FACE`, ...).
    Tessellated(Tessellated),
}

/// Reads a STEP file's B-rep or, where it has none, its tessellated geometry. A file with both
/// gives the B-rep, the tessellated items listed in [`Model::dropped`].
///
/// # Errors
/// As [`read`]; [`StepError::Tessellation`] for an index out of range in a tessellated face.
pub fn read_shape(path: &Path) -> Result<Shape, StepError> {
    let bytes = std::fs::read(path).map_err(|source| StepError::Read { path: path.to_path_buf(), source })?;
    to_shape(&parser::parse(path, &bytes)?)
}

/// The B-rep shape entities of `file`, as a message lists them: `8 MANIFOLD_SOLID_BREP (#210,
/// #211, #212, ...)`; empty when there are none.
fn shape_roots(file: &StepFile) -> String {
    let mut out = Vec::new();
    for kind in ["MANIFOLD_SOLID_BREP", "BREP_WITH_VOIDS", "SHELL_BASED_SURFACE_MODEL"] {
        let ids: Vec<u64> = file.entities().iter().filter(|e| e.has(kind)).map(|e| e.id).collect();
        if !ids.is_empty() {
            let mut list: Vec<String> = ids.iter().take(3).map(|i| format!("#{i}")).collect();
            if ids.len() > 3 {
                list.push("...".into());
            }
            out.push(format!("{} {kind} ({})", ids.len(), list.join(", ")));
        }
    }
    out.join(", ")
}

/// Converts a parsed file into a B-rep or, where it has none, its tessellated geometry.
///
/// # Errors
/// As [`to_model`]; [`StepError::Tessellation`].
pub fn to_shape(file: &StepFile) -> Result<Shape, StepError> {
    let mut c = convert::Converter::new(file);
    c.convert_all()?;
    let tess = std::mem::take(&mut c.tess).finish();
    let mut model = c.model;
    if model.faces.is_empty() {
        if !tess.surface.triangles.is_empty() {
            let mut tess = tess;
            tess.dropped = model.dropped;
            return Ok(Shape::Tessellated(tess));
        }
        let mut dropped = if model.dropped.is_empty() {
            String::new()
        } else {
            let first: Vec<String> = model.dropped.iter().take(3).map(|d| format!("{} {}: {}", d.kind, d.id, d.why)).collect();
            format!("; dropped {} item(s), e.g. {}", model.dropped.len(), first.join("; "))
        };
        if !tess.faces.is_empty() {
            dropped.push_str(&format!("; {} tessellated face(s) without a triangle", tess.faces.len()));
        }
        return Err(StepError::NoShape { path: file.path.clone(), dropped, roots: shape_roots(file) });
    }
    for (id, kind) in &tess.roots {
        model.dropped.push(Dropped { kind: kind.clone(), id: *id, why: "tessellated geometry beside the B-rep: fepre reads the B-rep".into() });
    }
    model.notes.extend(file.notes.iter().cloned());
    model.mark_edges();
    // surface models: free edges that are the same curve become one edge
    model.sewing = model.sew();
    colour::assign(file, &mut model);
    Ok(Shape::Brep(model))
}

/// Converts a parsed file into a model.
///
/// # Errors
/// [`StepError::Cycle`] for a reference cycle among geometry or placements,
/// [`StepError::NoShape`] when no solid, shell or surface model could be read (a file of
/// tessellated geometry only included: [`to_shape`] reads it).
pub fn to_model(file: &StepFile) -> Result<Model, StepError> {
    match to_shape(file)? {
        Shape::Brep(m) => Ok(m),
        Shape::Tessellated(t) => Err(StepError::NoShape {
            path: file.path.clone(),
            dropped: format!("; the file holds tessellated geometry only ({} faces, {} triangles), which `fepre mesh`, `fepre tessellate` and `fepre cad-info` read", t.faces.len(), t.surface.triangles.len()),
            roots: String::new(),
        }),
    }
}
