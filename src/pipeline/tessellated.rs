//! A STEP file of tessellated geometry only (AP242 `TESSELLATED_SOLID`, `TRIANGULATED_FACE`,
//! ...): its surface is certified as a mesh, as a surface mesh file is, since there is no
//! exact geometry to compare with: closed, manifold, consistently oriented and outward, no
//! two triangles intersecting (the topology report of `mesh/topology`), its volume and area
//! those of the triangles. `fepre tessellate` and `fepre cad-info` report it; `fepre mesh`
//! meshes it as it meshes an STL file, one face tag per tessellated face.

use crate::cad::step::Tessellated;
use crate::mesh::TriSurface;
use crate::mesh::topology::{IntersectingPair, ReportOptions, surface_report};
use serde::Serialize;
use std::path::Path;

/// The checks of a tessellated surface.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MeshCertificate {
    /// Every check passed.
    pub passed: bool,
    /// Every edge has two triangles.
    pub closed: bool,
    /// Edge- and vertex-manifold.
    pub manifold: bool,
    /// Consistently oriented.
    pub oriented: bool,
    /// Closed and every shell outward.
    pub outward: bool,
    /// Edges with one triangle.
    pub open_edges: usize,
    /// Edges with more than two triangles.
    pub nonmanifold_edges: usize,
    /// Intersecting triangle pairs (exact test).
    pub self_intersections: usize,
    /// The first intersecting pairs.
    pub first_intersections: Vec<IntersectingPair>,
    /// Triangles of zero area.
    pub degenerate_triangles: usize,
    /// Closed shells (edge-connected components).
    pub shells: usize,
    /// Volume enclosed (mm³), signed per shell.
    pub volume: f64,
    /// Area (mm²).
    pub area: f64,
}

/// Certifies a tessellated surface as a mesh.
pub fn certify_surface(s: &TriSurface) -> MeshCertificate {
    let r = surface_report(s, &ReportOptions::default());
    let self_intersections = r.self_intersections.unwrap_or(0);
    MeshCertificate {
        passed: r.closed && r.manifold && r.oriented && r.outward && self_intersections == 0 && r.degenerate_triangles == 0,
        closed: r.closed,
        manifold: r.manifold,
        oriented: r.oriented,
        outward: r.outward,
        open_edges: r.open_edges,
        nonmanifold_edges: r.nonmanifold_edges,
        self_intersections,
        first_intersections: r.first_intersections,
        degenerate_triangles: r.degenerate_triangles,
        shells: r.shells.len(),
        volume: r.volume,
        area: r.area,
    }
}

/// A failed certificate as one message.
pub fn mesh_failure_message(path: &Path, c: &MeshCertificate) -> String {
    let mut why = Vec::new();
    if !c.closed {
        why.push(format!("not closed ({} open edges)", c.open_edges));
    }
    if !c.manifold {
        why.push(format!("not manifold ({} edges of more than two triangles)", c.nonmanifold_edges));
    }
    if !c.oriented {
        why.push("not consistently oriented".to_string());
    } else if c.closed && !c.outward {
        why.push("oriented inward".to_string());
    }
    if c.self_intersections > 0 {
        let pairs: Vec<String> = c.first_intersections.iter().take(3).map(|p| format!("triangles {} (face {}) and {} (face {})", p.a, p.tag_a.0, p.b, p.tag_b.0)).collect();
        why.push(format!("{} intersecting triangle pairs, e.g. {}", c.self_intersections, pairs.join(", ")));
    }
    if c.degenerate_triangles > 0 {
        why.push(format!("{} triangles of zero area", c.degenerate_triangles));
    }
    format!("{}: the tessellated geometry fails its mesh certificate: {}", path.display(), why.join("; "))
}

/// Counts for reports: faces, triangles, `TESSELLATED_SOLID`s, `TESSELLATED_SHELL`s.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TessellatedSummary {
    /// Tessellated faces (one tag each).
    pub faces: usize,
    /// Triangles.
    pub triangles: usize,
    /// Vertices (shared between faces).
    pub vertices: usize,
    /// `TESSELLATED_SOLID`s (per placed instance).
    pub solids: usize,
    /// `TESSELLATED_SHELL`s (per placed instance).
    pub shells: usize,
    /// Triangles with a repeated index skipped (strip stitching).
    pub skipped_degenerate: usize,
}

impl TessellatedSummary {
    /// The counts of `t`, whose triangles are `surface`.
    pub fn of(t: &Tessellated, surface: &TriSurface) -> TessellatedSummary {
        TessellatedSummary {
            faces: t.faces.len(),
            triangles: surface.triangles.len(),
            vertices: surface.vertices.len(),
            solids: t.solids.iter().filter(|s| s.solid).count(),
            shells: t.solids.iter().filter(|s| !s.solid).count(),
            skipped_degenerate: t.skipped_degenerate,
        }
    }
}
