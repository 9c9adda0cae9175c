//! Newtype identifiers used at API seams. Inside algorithms indices are plain `u32` in flat
//! arrays; these types mark what a tag means where it crosses a stage boundary.

use serde::{Deserialize, Serialize};
use std::fmt;

/// Tag of a surface patch: a CAD face, an OBJ group, a glTF primitive instance, a PLC facet
/// marker. Carried by every triangle from reading through meshing to the solver deck.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(transparent)]
pub struct FaceId(pub u32);

/// Tag of a volume region (a material or a solid); carried by every tetrahedron.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(transparent)]
pub struct RegionId(pub u32);

/// The internal "no index" sentinel of flat `u32` arrays: no tet, no neighbour (a hull face),
/// no vertex tet yet, no hint, an unlabelled entry. One value under one name for every
/// algorithm that packs indices into `u32` arrays for speed (`mesh3d::delaunay`,
/// `mesh3d::mesher`, `mesh3d::optimize`).
///
/// It never crosses a public API: public signatures and types say "none" with `Option`.
/// The tet stores' ghost vertex (`mesh3d::delaunay::store::GHOST`, the point at infinity)
/// has the same value but its own name, as it is a vertex, not an absent one.
pub(crate) const NONE: u32 = u32::MAX;

impl fmt::Display for FaceId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "face {}", self.0)
    }
}

impl fmt::Display for RegionId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "region {}", self.0)
    }
}
