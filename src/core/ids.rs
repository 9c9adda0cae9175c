//! Newtype identifiers used at API seams. Inside algorithms indices are plain `u32` in flat
//! arrays; these types mark what a tag means where it crosses a stage boundary.
//!
//! # The tag convention
//! - A tag is a `u32`. **`0` means untagged**: a triangle or tet that carries no tag (a TetGen
//!   `.face` without markers, a Medit reference 0, a hull face of a tet mesh that its
//!   boundary triangles do not list). [`FaceId::UNTAGGED`] and [`RegionId::UNTAGGED`] name it.
//! - **Tags a reader or a stage makes up start at 1**: the `k`-th (0-based) STL solid, OBJ
//!   group, glTF primitive instance or B-rep face is tag `k + 1`, made by
//!   [`FaceId::from_index`] and turned back into the index by [`FaceId::index`], the one place
//!   of this arithmetic. Files that carry their own tags (MSH physical groups, Medit
//!   references, TetGen markers, `.poly` facet markers) keep them, 0 included.
//! - Names of tags live in a [`TagNames`](crate::core::TagNames) table beside the tag array
//!   (`face_names`, `region_names`); writers that write names make them unique first
//!   ([`TagNames::unique`](crate::core::TagNames::unique)).

use serde::{Deserialize, Serialize};
use std::fmt;

/// Tag of a surface patch: a CAD face, an OBJ group, a glTF primitive instance, a PLC facet
/// marker. Carried by every triangle from reading through meshing to the solver deck.
///
/// `FaceId(0)` is [`FaceId::UNTAGGED`]; made-up tags start at `FaceId(1)` (module docs).
///
/// ```
/// use fepre::core::FaceId;
/// assert_eq!(FaceId::from_index(0), FaceId(1));
/// assert_eq!(FaceId(1).index(), Some(0));
/// assert_eq!(FaceId::UNTAGGED.index(), None);
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(transparent)]
pub struct FaceId(pub u32);

/// Tag of a volume region (a material or a solid); carried by every tetrahedron.
///
/// `RegionId(0)` is [`RegionId::UNTAGGED`]; made-up tags start at `RegionId(1)`.
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

/// The largest value a `u32` index, count or tag can take: the bound that readers check
/// counts and tags against before narrowing them to `u32`. A limit, not a sentinel (it shares
/// its value with [`NONE`], which no valid index reaches).
pub(crate) const INDEX_MAX: u32 = u32::MAX;

macro_rules! one_based {
    ($t:ident, $what:literal) => {
        impl $t {
            #[doc = concat!("Tag 0: a ", $what, " that carries no tag.")]
            pub const UNTAGGED: $t = $t(0);

            #[doc = concat!("The tag of the `index`-th (0-based) ", $what, " of a list: `index + 1`.")]
            ///
            /// # Panics
            /// If `index + 1` does not fit in a `u32`.
            #[inline]
            pub fn from_index(index: usize) -> $t {
                match u32::try_from(index).ok().and_then(|i| i.checked_add(1)) {
                    Some(t) => $t(t),
                    None => panic!(concat!(stringify!($t), "::from_index({}): more than u32::MAX - 1 tags"), index),
                }
            }

            /// The 0-based index this tag stands for (`tag - 1`); `None` for tag 0.
            #[inline]
            pub fn index(self) -> Option<usize> {
                (self.0 as usize).checked_sub(1)
            }

            /// True for tag 0.
            #[inline]
            pub fn is_untagged(self) -> bool {
                self.0 == 0
            }
        }
    };
}

one_based!(FaceId, "face");
one_based!(RegionId, "region");

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn index_round_trips_and_zero_is_untagged() {
        for i in [0usize, 1, 41, u32::MAX as usize - 1] {
            assert_eq!(FaceId::from_index(i).index(), Some(i));
            assert_eq!(RegionId::from_index(i).index(), Some(i));
        }
        assert_eq!(FaceId::default(), FaceId::UNTAGGED);
        assert!(FaceId(0).is_untagged() && !FaceId(1).is_untagged());
        assert_eq!(RegionId(0).index(), None);
    }

    #[test]
    #[should_panic(expected = "more than u32::MAX - 1 tags")]
    fn from_index_panics_past_u32() {
        FaceId::from_index(u32::MAX as usize);
    }
}
