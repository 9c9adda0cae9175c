//! Right-handed orthonormal frames (STEP's `AXIS2_PLACEMENT_3D`) and rigid transforms.

use glam::{DMat3, DVec3};

/// A right-handed orthonormal frame: an origin and three unit axes with `x × y = z`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Frame {
    /// Origin.
    pub origin: DVec3,
    /// First axis (STEP's `ref_direction`, made orthogonal to `z`).
    pub x: DVec3,
    /// Second axis, `z × x`.
    pub y: DVec3,
    /// Third axis (STEP's `axis`).
    pub z: DVec3,
}

impl Frame {
    /// The world frame.
    pub const WORLD: Frame = Frame { origin: DVec3::ZERO, x: DVec3::X, y: DVec3::Y, z: DVec3::Z };

    /// The frame STEP's `AXIS2_PLACEMENT_3D` defines: `z` is `axis` (default +Z), `x` is
    /// `ref_direction` made orthogonal to `z` (default +X, or +Y where `z` is ±X, after ISO
    /// 10303-42's `first_proj_axis`). `None` when a given direction is zero
    /// or `ref_direction` is parallel to `axis`.
    pub fn from_axes(origin: DVec3, axis: Option<DVec3>, ref_direction: Option<DVec3>) -> Option<Frame> {
        let z = match axis {
            Some(a) => a.try_normalize()?,
            None => DVec3::Z,
        };
        let r = match ref_direction {
            Some(r) => r.try_normalize()?,
            None => {
                if (z - DVec3::X).length() > 1e-12 && (z + DVec3::X).length() > 1e-12 { DVec3::X } else { DVec3::Y }
            }
        };
        let x = (r - r.dot(z) * z).try_normalize()?;
        if r.cross(z).length() < 1e-12 {
            return None;
        }
        let y = z.cross(x);
        Some(Frame { origin, x, y, z })
    }

    /// World coordinates of a point given in this frame.
    #[inline]
    pub fn to_world(&self, local: DVec3) -> DVec3 {
        self.origin + local.x * self.x + local.y * self.y + local.z * self.z
    }

    /// Coordinates in this frame of a world point.
    #[inline]
    pub fn to_local(&self, p: DVec3) -> DVec3 {
        let d = p - self.origin;
        DVec3::new(d.dot(self.x), d.dot(self.y), d.dot(self.z))
    }

    /// World direction of a vector given in this frame.
    #[inline]
    pub fn vector_to_world(&self, v: DVec3) -> DVec3 {
        v.x * self.x + v.y * self.y + v.z * self.z
    }

    /// The frame moved by a rigid transform.
    pub fn transformed(&self, t: &Rigid) -> Frame {
        Frame {
            origin: t.apply_point(self.origin),
            x: t.apply_vector(self.x),
            y: t.apply_vector(self.y),
            z: t.apply_vector(self.z),
        }
    }

    /// The rigid transform taking world coordinates relative to the world frame onto this
    /// frame: local coordinates `l` go to `to_world(l)`.
    pub fn as_rigid(&self) -> Rigid {
        Rigid { rotation: DMat3::from_cols(self.x, self.y, self.z), translation: self.origin }
    }
}

/// A rigid motion `p ↦ rotation · p + translation` (rotation orthonormal, determinant +1).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Rigid {
    /// The rotation matrix.
    pub rotation: DMat3,
    /// The translation, applied after the rotation.
    pub translation: DVec3,
}

impl Default for Rigid {
    fn default() -> Self {
        Rigid::IDENTITY
    }
}

impl Rigid {
    /// The identity.
    pub const IDENTITY: Rigid = Rigid { rotation: DMat3::IDENTITY, translation: DVec3::ZERO };

    /// The motion that puts frame `from` onto frame `to`: a point with coordinates `l` in `from`
    /// goes to the point with the same coordinates in `to`. This is how an assembly places a
    /// component: `from` is the placement in the component, `to` the one in the assembly.
    pub fn between(from: &Frame, to: &Frame) -> Rigid {
        to.as_rigid().compose(&from.as_rigid().inverse())
    }

    /// A point moved.
    #[inline]
    pub fn apply_point(&self, p: DVec3) -> DVec3 {
        self.rotation * p + self.translation
    }

    /// A vector turned (no translation).
    #[inline]
    pub fn apply_vector(&self, v: DVec3) -> DVec3 {
        self.rotation * v
    }

    /// `self ∘ inner`: first `inner`, then `self`.
    pub fn compose(&self, inner: &Rigid) -> Rigid {
        Rigid { rotation: self.rotation * inner.rotation, translation: self.rotation * inner.translation + self.translation }
    }

    /// The inverse motion.
    pub fn inverse(&self) -> Rigid {
        let rt = self.rotation.transpose();
        Rigid { rotation: rt, translation: -(rt * self.translation) }
    }

    /// True for the identity (exactly).
    pub fn is_identity(&self) -> bool {
        *self == Rigid::IDENTITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn axis2_defaults_and_projection() {
        let f = Frame::from_axes(DVec3::ZERO, None, None).unwrap();
        assert_eq!(f, Frame::WORLD);
        // ref_direction not orthogonal to the axis is made orthogonal
        let f = Frame::from_axes(DVec3::ONE, Some(DVec3::new(0.0, 0.0, 2.0)), Some(DVec3::new(1.0, 0.0, 1.0))).unwrap();
        assert!(close(f.x, DVec3::X) && close(f.y, DVec3::Y) && close(f.z, DVec3::Z));
        // axis along +X: default ref direction must not be parallel
        let f = Frame::from_axes(DVec3::ZERO, Some(DVec3::X), None).unwrap();
        assert!(f.x.dot(f.z).abs() < 1e-15 && close(f.x.cross(f.y), f.z));
        assert!(Frame::from_axes(DVec3::ZERO, Some(DVec3::Z), Some(DVec3::Z)).is_none());
        assert!(Frame::from_axes(DVec3::ZERO, Some(DVec3::ZERO), None).is_none());
    }

    #[test]
    fn placements_compose_and_invert() {
        let a = Frame::from_axes(DVec3::new(1.0, 2.0, 3.0), Some(DVec3::new(0.0, 1.0, 1.0)), Some(DVec3::X)).unwrap();
        let b = Frame::from_axes(DVec3::new(-4.0, 0.5, 2.0), Some(DVec3::new(1.0, 1.0, 0.0)), Some(DVec3::Z)).unwrap();
        let t = Rigid::between(&a, &b);
        let l = DVec3::new(0.3, -0.7, 2.0);
        assert!(close(t.apply_point(a.to_world(l)), b.to_world(l)));
        assert!(close(t.inverse().apply_point(b.to_world(l)), a.to_world(l)));
        let c = t.compose(&t.inverse());
        assert!(close(c.apply_point(l), l));
        let moved = a.transformed(&t);
        assert!(close(moved.origin, b.origin) && close(moved.x, b.x) && close(moved.z, b.z));
        assert!((t.rotation.determinant() - 1.0).abs() < 1e-12);
        assert!(Rigid::IDENTITY.is_identity() && !t.is_identity());
    }
}
