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
