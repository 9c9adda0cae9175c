//! Tolerances relative to the model's size: no absolute epsilon anywhere in fepre.

use crate::core::Aabb;

/// A tolerance given as a fraction of the model's bounding-box diagonal.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Tolerance {
    /// Fraction of the bounding-box diagonal.
    pub relative: f64,
}

impl Tolerance {
    /// Default for merging coincident vertices of meshes read from files: 1e-9 of the model
    /// size, far below any meaningful feature and above the rounding of float32 formats'
    /// repeated vertices (which are bit-identical anyway).
    pub const WELD: Tolerance = Tolerance { relative: 1e-9 };

    /// A tolerance of `relative` times the model size.
    pub fn relative(relative: f64) -> Tolerance {
        Tolerance { relative }
    }

    /// The absolute length for a model with this bounding box. For a degenerate box (one point)
    /// the scale falls back to the largest coordinate magnitude, then to 1.
    pub fn absolute(&self, bbox: &Aabb) -> f64 {
        self.relative * model_scale(bbox)
    }
}

/// The length that relative tolerances multiply: the bounding-box diagonal, or the largest
/// coordinate magnitude for a degenerate box, or 1 for an empty one.
pub fn model_scale(bbox: &Aabb) -> f64 {
    if bbox.is_empty() {
        return 1.0;
    }
    let d = bbox.diagonal();
    if d > 0.0 {
        return d;
    }
    let m = bbox.min.abs().max_element().max(bbox.max.abs().max_element());
    if m > 0.0 { m } else { 1.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn scales_with_the_model() {
        let b = Aabb::from_points(&[DVec3::ZERO, DVec3::new(3.0, 4.0, 0.0)]);
        assert_eq!(Tolerance::relative(0.1).absolute(&b), 0.5);
        let p = Aabb::from_points(&[DVec3::new(0.0, 8.0, 0.0)]);
        assert_eq!(model_scale(&p), 8.0);
        assert_eq!(model_scale(&Aabb::EMPTY), 1.0);
    }
}
