//! A straight tube, or a sector of one: an annulus (or a sector of it, from the +x axis
//! counter-clockwise) swept along +z. The thick-walled cylinder of the Lamé check.
//!
//! Faces: `bore` (inner cylinder), `outer`, `bottom` (z = 0), `top`, and for a sector `cut_x`
//! (the plane through the x axis, y = 0) and `cut_end` (the plane at the sector's end angle).

use super::sketch::{Segment, circle, profile};
use super::{FaceProbe, PartError, along, name_faces, solid_to_model};
use crate::cad::brep::Model;
use crate::cad::geom::Surface;
use glam::DVec3;
use std::f64::consts::PI;
use truck_modeling::{Point3, Vector3, builder};

/// The tube's parameters, in millimetres and degrees.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Tube {
    /// Inner radius (default 10).
    pub inner_radius: f64,
    /// Outer radius (default 20).
    pub outer_radius: f64,
    /// Length along z (default 10).
    pub length: f64,
    /// The sector's angle, degrees: 360 for a whole tube (default 90).
    pub angle_deg: f64,
}

impl Default for Tube {
    fn default() -> Self {
        Tube { inner_radius: 10.0, outer_radius: 20.0, length: 10.0, angle_deg: 90.0 }
    }
}

impl Tube {
    /// The exact volume, mm³.
    pub fn volume(&self) -> f64 {
        PI * (self.outer_radius.powi(2) - self.inner_radius.powi(2)) * self.length * self.angle_deg / 360.0
    }

    /// Builds the tube.
    ///
    /// # Errors
    /// [`PartError::Parameters`] for radii out of order, lengths that are not positive, or an
    /// angle outside (0, 180] that is not 360.
    pub fn build(&self) -> Result<Model, PartError> {
        let bad = |why: String| Err(PartError::Parameters { part: "tube", why });
        let (a, b) = (self.inner_radius, self.outer_radius);
        if !(a.is_finite() && b.is_finite() && a > 0.0 && b > a && self.length.is_finite() && self.length > 0.0) {
            return bad(format!("need 0 < inner_radius < outer_radius and a positive length: {self:?}"));
        }
        let whole = self.angle_deg == 360.0;
        if !whole && !(self.angle_deg > 0.0 && self.angle_deg <= 180.0) {
            return bad(format!("angle_deg {} must be in (0, 180] or 360", self.angle_deg));
        }
        let z = Vector3::unit_z();
        let wires = if whole {
            vec![circle(Point3::new(0.0, 0.0, 0.0), z, Vector3::unit_x(), b), circle(Point3::new(0.0, 0.0, 0.0), z, Vector3::unit_x(), a).inverse()]
        } else {
            let t = self.angle_deg.to_radians();
            let (c, s) = (t.cos(), t.sin());
            let (ch, sh) = ((t / 2.0).cos(), (t / 2.0).sin());
            let corners = [Point3::new(a, 0.0, 0.0), Point3::new(b, 0.0, 0.0), Point3::new(b * c, b * s, 0.0), Point3::new(a * c, a * s, 0.0)];
            let segments = [Segment::Line, Segment::Arc(Point3::new(b * ch, b * sh, 0.0)), Segment::Line, Segment::Arc(Point3::new(a * ch, a * sh, 0.0))];
            vec![profile(&corners, &segments)]
        };
        let modeling = |e: truck_modeling::errors::Error| PartError::Modeling { part: "tube", why: e.to_string() };
        let face = builder::try_attach_plane(&wires).map_err(modeling)?;
        let solid = builder::tsweep(&face, Vector3::new(0.0, 0.0, self.length));
        let mut model = solid_to_model(&solid, "tube")?;
        name_faces(&mut model, "tube", |f: &FaceProbe<'_>| {
            let name = match (f.surface, f.plane_normal) {
                (_, Some(n)) if along(n, -DVec3::Z) => "bottom",
                (_, Some(n)) if along(n, DVec3::Z) => "top",
                (_, Some(n)) if along(n, -DVec3::Y) => "cut_x",
                (_, Some(_)) => "cut_end",
                (Surface::Cylinder(c), None) if (c.radius - a).abs() < 1e-6 * a => "bore",
                (Surface::Cylinder(_), None) => "outer",
                _ => return None,
            };
            Some(name.to_string())
        })?;
        Ok(model)
    }
}
