//! The mesh-size contract between attributes and meshers.

use crate::core::RegionId;
use glam::DVec3;

/// A target element size at every point of the domain. Meshers and the tessellator see only
/// this trait; concrete fields (from CAD-face density, graded) live in `attributes/`.
///
/// There is no "no size": a field that asks for nothing returns a size at least the domain's
/// diagonal (see [`UniformSize`]).
pub trait SizeField: Sync {
    /// The desired edge length near `p` (positive, finite).
    fn size_at(&self, p: DVec3) -> f64;

    /// The desired edge length near `p` inside the volume region `region` (a solid, a
    /// material): [`SizeField::size_at`] unless the field knows sizes per region.
    fn size_in(&self, p: DVec3, region: RegionId) -> f64 {
        let _ = region;
        self.size_at(p)
    }
}

/// The same size everywhere.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct UniformSize(pub f64);

impl SizeField for UniformSize {
    fn size_at(&self, _p: DVec3) -> f64 {
        self.0
    }
}
