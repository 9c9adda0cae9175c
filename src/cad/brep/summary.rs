//! Counts of a [`Model`] for reports (`fepre cad-info`).

use super::model::{Model, Units};
use serde::Serialize;
use std::collections::BTreeMap;

/// What `fepre cad-info` reports about a model.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// Solids (assembly instances expanded).
    pub solids: usize,
    /// Shells.
    pub shells: usize,
    /// Shells bounding no solid (a surface model's).
    pub surface_model_shells: usize,
    /// What sewing the open shells did, if the model has any.
    pub sewing: Option<super::sew_report::SewReport>,
    /// Faces.
    pub faces: usize,
    /// Edges.
    pub edges: usize,
    /// Vertices.
    pub vertices: usize,
    /// Closed, seam and degenerate edges.
    pub closed_edges: usize,
    /// Edges used twice by one face.
    pub seam_edges: usize,
    /// Edges of zero length.
    pub degenerate_edges: usize,
    /// Units of the file.
    pub units: Units,
    /// Faces per surface kind (`plane`, `cylinder`, ...).
    pub faces_by_surface: BTreeMap<String, usize>,
    /// Dropped items per STEP type.
    pub dropped_by_kind: BTreeMap<String, usize>,
    /// Bounding box of the geometry ([`Model::bounds`]), mm: `[min, max]`.
    pub bounds: Option<[[f64; 3]; 2]>,
}

impl Summary {
    /// The summary of a model.
    pub fn of(model: &Model) -> Summary {
        let mut faces_by_surface = BTreeMap::new();
        for f in &model.faces {
            *faces_by_surface.entry(model.surface(f.surface).kind().name().to_string()).or_insert(0) += 1;
        }
        let mut dropped_by_kind = BTreeMap::new();
        for d in &model.dropped {
            *dropped_by_kind.entry(d.kind.clone()).or_insert(0) += 1;
        }
        Summary {
            solids: model.solids.len(),
            shells: model.shells.len(),
            surface_model_shells: model.surface_model_shells(),
            sewing: model.sewing.clone(),
            faces: model.faces.len(),
            edges: model.edges.len(),
            vertices: model.vertices.len(),
            closed_edges: model.edges.iter().filter(|e| e.closed).count(),
            seam_edges: model.edges.iter().filter(|e| e.seam).count(),
            degenerate_edges: model.edges.iter().filter(|e| e.degenerate).count(),
            units: model.units.clone(),
            faces_by_surface,
            dropped_by_kind,
            bounds: model.bounds().map(|(lo, hi)| [lo.to_array(), hi.to_array()]),
        }
    }
}
