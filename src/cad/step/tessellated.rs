//! AP242 tessellated geometry as read: one tagged [`TriSurface`] in millimetres and world
//! placement, one [`FaceId`] per tessellated face with its name, the solids and shells, and
//! the accumulator ([`TessBuilder`]) the reader (module `read_tessellated`) fills.

use crate::cad::brep::{Dropped, EntityRef, Units};
use crate::core::FaceId;
use crate::mesh::TriSurface;
use crate::mesh::weld::weld_vertices;
use rustc_hash::FxHashMap;
use serde::Serialize;

/// One tessellated face (a `TRIANGULATED_FACE`, `COMPLEX_TRIANGULATED_FACE` or surface set).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TessellatedFace {
    /// Its tag in [`Tessellated::surface`].
    pub face: FaceId,
    /// Its name, where the file gives one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The STEP instance.
    pub step_id: EntityRef,
    /// The solid or shell it belongs to: 1-based in [`Tessellated::solids`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solid: Option<u32>,
    /// Its triangles.
    pub triangles: usize,
}

/// A `TESSELLATED_SOLID` or `TESSELLATED_SHELL` (one per placed instance).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TessellatedSolid {
    /// Its name, where the file gives one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The STEP instance.
    pub step_id: EntityRef,
    /// `TESSELLATED_SOLID` (true) or `TESSELLATED_SHELL`.
    pub solid: bool,
    /// Its faces.
    pub faces: Vec<FaceId>,
}

/// What a file's tessellated geometry holds.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Tessellated {
    /// Every tessellated face's triangles, tagged with the face, in millimetres.
    #[serde(skip)]
    pub surface: TriSurface,
    /// The faces, in tag order.
    pub faces: Vec<TessellatedFace>,
    /// The solids and shells, in file order of expansion.
    pub solids: Vec<TessellatedSolid>,
    /// The file's units (of the first representation holding tessellated geometry).
    pub units: Units,
    /// Items left out, with the reason.
    pub dropped: Vec<Dropped>,
    /// The top-level tessellated items read (for the report of a file that also has a B-rep).
    #[serde(skip)]
    pub(super) roots: Vec<(EntityRef, String)>,
    /// Triangles with a repeated index skipped (strip stitching).
    pub skipped_degenerate: usize,
}

/// The accumulator of tessellated geometry during a conversion.
#[derive(Default)]
pub(super) struct TessBuilder {
    pub out: Tessellated,
    /// `(coordinates list, instance, 0-based point) -> vertex`.
    pub(super) vertex: FxHashMap<(u64, u32, u32), u32>,
    /// Whether units were set.
    pub(super) units_set: bool,
}

impl TessBuilder {
    /// Merges bit-identical vertices and returns the result.
    pub fn finish(mut self) -> Tessellated {
        let s = &mut self.out.surface;
        let w = weld_vertices(&s.vertices, 0.0);
        for t in &mut s.triangles {
            *t = t.map(|v| w.remap[v as usize]);
        }
        s.vertices = w.vertices;
        self.out
    }
}
