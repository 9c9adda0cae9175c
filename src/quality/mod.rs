//! Layer 2: element quality measures with the VTK/Verdict definitions (Knupp et al., "The
//! Verdict geometric quality library", SAND2007-1751), summary statistics and whole-mesh
//! reports.
//!
//! - `tetrahedron`: dihedral angles, radius-edge, radius ratio, scaled Jacobian,
//!   volume-length, aspect and edge ratio of one tet. Dihedral angles and radius-edge use the
//!   reference judge's formulas (`shared/tools/cgal_ref/tet_quality.h`) operation for
//!   operation.
//! - `triangle`: angles, aspect ratio, radius ratio, scaled Jacobian, area, edge ratio of
//!   one triangle in space or in the plane.
//! - `quad`: angles, aspect ratio, scaled Jacobian of one planar quadrilateral.
//! - `summary`: [`Stats`] and [`Histogram`], merged deterministically.
//! - `mesh_quality`: [`tet_mesh_quality`], [`tri_surface_quality`], [`planar_mesh_quality`].
//! - `input_angles`: the small dihedral and corner angles of a closed tagged surface, which
//!   bound the quality of any tet mesh that keeps it.
//! - `between_sides`: tets between the two sides of a small input angle, off its vertex or
//!   edge (a thin wedge, a sliver face, a knife edge), counted apart in reports.
//! - `explained`: of the tets under an angle, those an input angle explains.
//! - `worst_tet`: where a tet sits (centroid, nearest boundary face and feature edge, the
//!   small input angle in its reach), for reports and requirement errors.
//!
//! Every measure is total: degenerate elements get documented values (`0°`/`180°` angles,
//! `+∞` ratios, `0` scaled Jacobian), never `NaN` for finite input, never a panic.

pub(crate) mod between_sides;
pub(crate) mod explained;
pub(crate) mod extremes;
pub(crate) mod input_angles;
pub(crate) mod mesh_quality;
pub(crate) mod quad;
pub(crate) mod summary;
pub(crate) mod tetrahedron;
pub(crate) mod triangle;
pub(crate) mod worst_tet;

#[cfg(test)]
mod tests;

pub use mesh_quality::{
    PlanarQualityReport, QuadQualityReport, TetQualityReport, TriQualityReport, planar_mesh_quality, tet_mesh_quality,
    tri_surface_quality,
};
pub use extremes::{TetExtremes, tet_mesh_extremes};
pub use mesh_quality::NEAR_DEGENERATE_VOLUME_LENGTH;
pub use quad::{QuadMeasures, quad_measures};
pub use worst_tet::{TetPlace, fmt_num, fmt_point};
pub use summary::{Histogram, Stats, StatsAccumulator};
pub use tetrahedron::{
    TetMeasures, tet_circumradius, tet_dihedral_angles, tet_inradius, tet_measures, tet_min_max_dihedral, tet_radius_edge, tet_scaled_jacobian,
    tet_volume,
};
pub use triangle::{TriMeasures, tri_angles, tri_area, tri_measures, tri_measures_2d};
