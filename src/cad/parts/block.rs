//! A rectangular block, optionally with a round hole through its thickness at the centre: the
//! cantilever, the slab and the plate with a hole of the analytic checks.
//!
//! The block spans `[0, length] × [0, width] × [0, thickness]`. Faces: `xmin`, `xmax`,
//! `ymin`, `ymax`, `zmin`, `zmax` (each named after the side it bounds), and `hole` (both
//! half cylinders).

use super::sketch::{Segment, circle, profile};
use super::{FaceProbe, PartError, along, name_faces, solid_to_model};
use crate::cad::brep::Model;
use crate::cad::geom::Surface;
use glam::DVec3;
use std::f64::consts::PI;
use truck_modeling::{Point3, Vector3, builder};

/// The block's parameters, in millimetres.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Block {
    /// Along x (default 100).
    pub length: f64,
    /// Along y (default 10).
    pub width: f64,
    /// Along z (default 10).
    pub thickness: f64,
    /// The diameter of a hole along z through the centre (default none).
    pub hole_diameter: Option<f64>,
}

impl Default for Block {
    fn default() -> Self {
        Block { length: 100.0, width: 10.0, thickness: 10.0, hole_diameter: None }
    }
}

impl Block {
    /// A block of these sides, without a hole.
    pub fn new(length: f64, width: f64, thickness: f64) -> Block {
        Block { length, width, thickness, hole_diameter: None }
    }

    /// The same block with a central hole of diameter `d`.
    pub fn with_hole(mut self, d: f64) -> Block {
        self.hole_diameter = Some(d);
        self
    }

    /// The exact volume, mm³.
    pub fn volume(&self) -> f64 {
        let hole = self.hole_diameter.map_or(0.0, |d| PI * d * d / 4.0);
        (self.length * self.width - hole) * self.thickness
    }

    /// Builds the block.
    ///
    /// # Errors
    /// [`PartError::Parameters`] for lengths that are not positive or a hole that does not
    /// fit inside with a wall around it.
    pub fn build(&self) -> Result<Model, PartError> {
        let bad = |why: String| Err(PartError::Parameters { part: "block", why });
        if [self.length, self.width, self.thickness].iter().any(|x| !(x.is_finite() && *x > 0.0)) {
            return bad(format!("every side must be positive and finite: {self:?}"));
        }
        if let Some(d) = self.hole_diameter {
            if !(d.is_finite() && d > 0.0 && d < 0.96 * self.length.min(self.width)) {
                return bad(format!("the hole ({d}) must be positive and leave a wall in a {} × {} block", self.length, self.width));
            }
        }
        let (l, w) = (self.length, self.width);
        let corners = [Point3::new(0.0, 0.0, 0.0), Point3::new(l, 0.0, 0.0), Point3::new(l, w, 0.0), Point3::new(0.0, w, 0.0)];
        let mut wires = vec![profile(&corners, &[Segment::Line; 4])];
        if let Some(d) = self.hole_diameter {
            wires.push(circle(Point3::new(l / 2.0, w / 2.0, 0.0), Vector3::unit_z(), Vector3::unit_x(), d / 2.0).inverse());
        }
        let modeling = |e: truck_modeling::errors::Error| PartError::Modeling { part: "block", why: e.to_string() };
        let face = builder::try_attach_plane(&wires).map_err(modeling)?;
        let solid = builder::tsweep(&face, Vector3::new(0.0, 0.0, self.thickness));
        let mut model = solid_to_model(&solid, "block")?;
        name_faces(&mut model, "block", |f: &FaceProbe<'_>| {
            let name = match (f.surface, f.plane_normal) {
                (_, Some(n)) if along(n, -DVec3::X) => "xmin",
                (_, Some(n)) if along(n, DVec3::X) => "xmax",
                (_, Some(n)) if along(n, -DVec3::Y) => "ymin",
                (_, Some(n)) if along(n, DVec3::Y) => "ymax",
                (_, Some(n)) if along(n, -DVec3::Z) => "zmin",
                (_, Some(n)) if along(n, DVec3::Z) => "zmax",
                (Surface::Cylinder(_), None) => "hole",
                _ => return None,
            };
            Some(name.to_string())
        })?;
        Ok(model)
    }
}
