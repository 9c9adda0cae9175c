//! The mesh-size contract between attributes and meshers.

use glam::DVec3;

/// A target element size at every point of the domain. Meshers see only this trait; concrete
/// fields (uniform, from CAD-face density, graded) live in `attributes/`.
pub trait SizeField: Sync {
    /// The desired edge length near `p` (positive, finite).
    fn size_at(&self, p: DVec3) -> f64;
}

/// The same size everywhere.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct UniformSize(pub f64);

impl SizeField for UniformSize {
    fn size_at(&self, _p: DVec3) -> f64 {
        self.0
    }
}
