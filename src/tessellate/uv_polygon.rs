//! A face boundary loop in parameter space, and its signed area.

use glam::DVec2;

/// A loop in parameter space: `(u, v)` and global vertex index per point (not repeated at
/// the end).
pub(super) type UvLoop = Vec<(DVec2, u32)>;

/// Signed area of a polygon (positive counter-clockwise).
pub(super) fn signed_area(p: &[DVec2]) -> f64 {
    let n = p.len();
    (0..n).map(|i| p[i].perp_dot(p[(i + 1) % n])).sum::<f64>() / 2.0
}
