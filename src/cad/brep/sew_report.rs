//! What sewing did ([`super::Model::sew`], module `sew`): the T-junction splits and the holes
//! left, for reports.

use super::entity_ref::EntityRef;
use crate::core::FaceId;
use serde::Serialize;

/// What [`Model::sew`](super::Model::sew) did.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SewReport {
    /// The tolerance used, mm.
    pub tolerance: f64,
    /// Vertices merged into another.
    pub merged_vertices: usize,
    /// Edges merged into another.
    pub merged_edges: usize,
    /// Edges used by one face only, before and after.
    pub free_edges_before: usize,
    /// After sewing.
    pub free_edges_after: usize,
    /// Free edges split at the other side's vertex (T-junctions), before sewing.
    pub splits: Vec<EdgeSplit>,
    /// The free edges left in the open shells, grouped into holes.
    pub holes: Vec<Hole>,
}

/// A free edge split at a vertex of the other side (a T-junction).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EdgeSplit {
    /// The edge split (`EDGE_CURVE`); its pieces keep this id.
    pub edge: EntityRef,
    /// The vertex it was split at (`VERTEX_POINT` of the other side's edge).
    pub vertex: EntityRef,
    /// Where, mm.
    pub at: [f64; 3],
    /// Distance from the vertex to the edge's curve, mm (within the tolerance).
    pub distance: f64,
}

/// A hole: free edges (used by one face) joined at shared vertices.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Hole {
    /// Number of free edges around it.
    pub edges: usize,
    /// Their total length, mm.
    pub length: f64,
    /// A point near it (the centre of its edges, by length), mm.
    pub near: [f64; 3],
    /// The faces around it.
    pub faces: Vec<FaceId>,
    /// Their STEP instances.
    pub step_faces: Vec<EntityRef>,
    /// The free edges' STEP instances (`EDGE_CURVE`).
    pub step_edges: Vec<EntityRef>,
    /// The shells the faces belong to (STEP `#id`s).
    pub shells: Vec<EntityRef>,
    /// The ring of free edges closes on itself (every vertex joins two of them).
    pub closed_ring: bool,
}

impl SewReport {
    /// Lines for a text report: the T-junction splits and the holes left (at most `max` of
    /// each, then a count of the rest).
    pub fn detail_lines(&self, max: usize) -> Vec<String> {
        let mut out = Vec::new();
        if !self.splits.is_empty() {
            out.push(format!("split {} free edge(s) at the other side's vertex (T-junctions)", self.splits.len()));
            for x in self.splits.iter().take(max) {
                out.push(format!("  edge {} at vertex {} ({:.6}, {:.6}, {:.6}), {:.1e} mm off its curve", x.edge, x.vertex, x.at[0], x.at[1], x.at[2], x.distance));
            }
            if self.splits.len() > max {
                out.push(format!("  ... {} more", self.splits.len() - max));
            }
        }
        if self.free_edges_after > 0 {
            out.push(format!("{} hole(s) left open", self.holes.len()));
            for h in self.holes.iter().take(max) {
                out.push(format!("  {}", h.describe()));
            }
            if self.holes.len() > max {
                out.push(format!("  ... {} more", self.holes.len() - max));
            }
        }
        out
    }
}

impl Hole {
    /// One line: "4 free edges, 40 mm around, near (x, y, z), faces #a #b".
    pub fn describe(&self) -> String {
        let faces: Vec<String> = self.step_faces.iter().take(8).map(|f| f.to_string()).collect();
        let more = if self.step_faces.len() > 8 { format!(" and {} more", self.step_faces.len() - 8) } else { String::new() };
        format!(
            "{} free edge{}, {:.6} mm around, near ({:.6}, {:.6}, {:.6}), faces {}{more}",
            self.edges,
            if self.edges == 1 { "" } else { "s" },
            self.length,
            self.near[0],
            self.near[1],
            self.near[2],
            faces.join(" ")
        )
    }
}
