//! The similarity of a STEP `CARTESIAN_TRANSFORMATION_OPERATOR_3D`, `x ↦ scale · A x + origin`
//! with `A` orthonormal (a reflection where the operator's axes are left-handed): what a
//! replica ([`super::CurveReplica`], [`super::SurfaceReplica`]) moves its parent by.

use super::frame::Rigid;
use glam::{DMat3, DVec3};

/// A similarity transform `p ↦ scale · axes · p + origin`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Similarity {
    /// Orthonormal columns: the images of the parent's x, y and z axes (determinant ±1).
    pub axes: DMat3,
    /// The image of the parent's origin, in mm.
    pub origin: DVec3,
    /// The uniform scale (positive).
    pub scale: f64,
}

impl Similarity {
    /// ISO 10303-42's `cartesian_transformation_operator_3d` from its attributes (each axis
    /// optional; the directions need not be unit): `axis3` normalised (default +Z), `axis1`
    /// projected off it (`first_proj_axis`), `axis2` off both (`second_proj_axis`, default
    /// +Y, keeping its sign: a left-handed result is a reflection). `None` where an axis is
    /// zero or the axes are dependent, or the scale is not positive.
    pub fn from_operator(axis1: Option<DVec3>, axis2: Option<DVec3>, axis3: Option<DVec3>, origin: DVec3, scale: Option<f64>) -> Option<Similarity> {
        let scale = scale.unwrap_or(1.0);
        if !(scale > 0.0 && scale.is_finite()) {
            return None;
        }
        let d3 = match axis3 {
            Some(a) => a.try_normalize()?,
            None => DVec3::Z,
        };
        let a1 = match axis1 {
            Some(a) => a.try_normalize()?,
            None if (d3 - DVec3::X).length() > 1e-12 => DVec3::X,
            None => DVec3::Y,
        };
        if a1.cross(d3).length() < 1e-12 {
            return None;
        }
        let d1 = (a1 - a1.dot(d3) * d3).try_normalize()?;
        let a2 = match axis2 {
            Some(a) => a.try_normalize()?,
            None => DVec3::Y,
        };
        let d2 = (a2 - a2.dot(d3) * d3 - a2.dot(d1) * d1).try_normalize()?;
        Some(Similarity { axes: DMat3::from_cols(d1, d2, d3), origin, scale })
    }

    /// A point moved.
    pub fn apply_point(&self, p: DVec3) -> DVec3 {
        self.scale * (self.axes * p) + self.origin
    }

    /// A vector (a derivative) moved.
    pub fn apply_vector(&self, v: DVec3) -> DVec3 {
        self.scale * (self.axes * v)
    }

    /// The parent's point that goes to `p`.
    pub fn invert_point(&self, p: DVec3) -> DVec3 {
        self.axes.transpose() * (p - self.origin) / self.scale
    }

    /// True where the axes are left-handed.
    pub fn reflects(&self) -> bool {
        self.axes.determinant() < 0.0
    }

    /// The same motion as a rigid one, where it is one (scale 1, no reflection).
    pub fn as_rigid(&self) -> Option<Rigid> {
        ((self.scale - 1.0).abs() <= 1e-15 && !self.reflects()).then_some(Rigid { rotation: self.axes, translation: self.origin })
    }

    /// `t ∘ self`: this similarity followed by a rigid motion.
    pub fn then(&self, t: &Rigid) -> Similarity {
        Similarity { axes: t.rotation * self.axes, origin: t.apply_point(self.origin), scale: self.scale }
    }
}
