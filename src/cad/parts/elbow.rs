//! A pipe elbow: an annulus (the pipe's cross-section) turned about an axis by the bend
//! angle. The annulus lies in the plane y = 0 centred at `(bend_radius, 0, 0)`; the bend turns
//! about +z, so the pipe leaves through the plane at `angle` from it.
//!
//! Faces: `inlet` (the annulus at y = 0), `outlet`, `outer_wall` (tori of the outer radius),
//! `inner_wall` (tori of the inner radius).

use super::sketch::circle;
use super::{FaceProbe, PartError, along, name_faces, solid_to_model};
use crate::cad::brep::Model;
use crate::cad::geom::Surface;
use glam::DVec3;
use std::f64::consts::PI;
use truck_modeling::{Point3, Rad, Vector3, builder};

/// The elbow's parameters, in millimetres and degrees.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Elbow {
    /// Radius of the bend, axis to pipe centre line (default 40).
    pub bend_radius: f64,
    /// Outer diameter of the pipe (default 30).
    pub outer_diameter: f64,
    /// Wall thickness (default 4).
    pub wall: f64,
    /// Bend angle, degrees, in (0, 180] (default 90).
    pub angle_deg: f64,
}

impl Default for Elbow {
    fn default() -> Self {
        Elbow { bend_radius: 40.0, outer_diameter: 30.0, wall: 4.0, angle_deg: 90.0 }
    }
}

impl Elbow {
    /// The exact volume, mm³ (Pappus: the annulus's area times the path of its centroid).
    pub fn volume(&self) -> f64 {
        let ro = self.outer_diameter / 2.0;
        let ri = ro - self.wall;
        PI * (ro * ro - ri * ri) * self.bend_radius * self.angle_deg.to_radians()
    }

    fn check(&self) -> Result<(), PartError> {
        let bad = |why: String| Err(PartError::Parameters { part: "elbow", why });
        if [self.bend_radius, self.outer_diameter, self.wall].iter().any(|x| !(x.is_finite() && *x > 0.0)) {
            return bad(format!("every length must be positive and finite: {self:?}"));
        }
        if self.wall >= self.outer_diameter / 2.0 {
            return bad(format!("wall {} must be less than the outer radius {}", self.wall, self.outer_diameter / 2.0));
        }
        if self.bend_radius <= self.outer_diameter / 2.0 {
            return bad(format!("bend_radius {} must exceed the outer radius {}", self.bend_radius, self.outer_diameter / 2.0));
        }
        if !(self.angle_deg > 0.0 && self.angle_deg <= 180.0) {
            return bad(format!("angle_deg {} must be in (0, 180]", self.angle_deg));
        }
        Ok(())
    }

    /// Builds the elbow.
    ///
    /// # Errors
    /// [`PartError::Parameters`] for a wall thicker than the radius, a bend tighter than the
    /// pipe, or an angle outside (0, 180].
    pub fn build(&self) -> Result<Model, PartError> {
        self.check()?;
        let ro = self.outer_diameter / 2.0;
        let ri = ro - self.wall;
        let centre = Point3::new(self.bend_radius, 0.0, 0.0);
        let (n, x) = (Vector3::unit_y(), Vector3::unit_x());
        let wires = vec![circle(centre, n, x, ro), circle(centre, n, x, ri).inverse()];
        let modeling = |e: truck_modeling::errors::Error| PartError::Modeling { part: "elbow", why: e.to_string() };
        let face = builder::try_attach_plane(&wires).map_err(modeling)?;
        let solid = builder::rsweep(&face, Point3::new(0.0, 0.0, 0.0), Vector3::unit_z(), Rad(self.angle_deg.to_radians()));
        let mut model = solid_to_model(&solid, "elbow")?;
        name_faces(&mut model, "elbow", |f: &FaceProbe<'_>| {
            let name = match (f.surface, f.plane_normal) {
                (_, Some(n)) if along(n, -DVec3::Y) => "inlet",
                (_, Some(_)) => "outlet",
                (Surface::Torus(t), None) if (t.minor - ro).abs() < 1e-6 * ro => "outer_wall",
                (Surface::Torus(t), None) if (t.minor - ri).abs() < 1e-6 * ri => "inner_wall",
                _ => return None,
            };
            Some(name.to_string())
        })?;
        Ok(model)
    }
}
