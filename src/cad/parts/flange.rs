//! A flat flange: a disc with a central bore and bolt holes on a bolt circle, swept along +z
//! by its thickness.
//!
//! Faces: `bottom` (z = 0), `top`, `rim` (the outer cylinder), `bore`, and `bolt_1` ...
//! `bolt_n` counter-clockwise from +x.

use super::sketch::circle;
use super::{FaceProbe, PartError, along, name_faces, solid_to_model};
use crate::cad::brep::Model;
use crate::cad::geom::Surface;
use glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};
use truck_modeling::{Point3, Vector3, builder};

/// The flange's parameters, in millimetres.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Flange {
    /// Outer diameter (default 120).
    pub outer_diameter: f64,
    /// Diameter of the central bore (default 40).
    pub bore_diameter: f64,
    /// Thickness along z (default 12).
    pub thickness: f64,
    /// Diameter of the circle through the bolt hole centres (default 85).
    pub bolt_circle_diameter: f64,
    /// Diameter of the bolt holes (default 11).
    pub bolt_hole_diameter: f64,
    /// Number of bolt holes (default 6).
    pub bolts: usize,
}

impl Default for Flange {
    fn default() -> Self {
        Flange { outer_diameter: 120.0, bore_diameter: 40.0, thickness: 12.0, bolt_circle_diameter: 85.0, bolt_hole_diameter: 11.0, bolts: 6 }
    }
}

impl Flange {
    /// The bolt hole centres, counter-clockwise from +x.
    pub fn bolt_centres(&self) -> Vec<DVec2> {
        let r = self.bolt_circle_diameter / 2.0;
        (0..self.bolts).map(|k| r * DVec2::from_angle(TAU * k as f64 / self.bolts as f64)).collect()
    }

    /// The exact volume, mm³.
    pub fn volume(&self) -> f64 {
        let area = |d: f64| PI * d * d / 4.0;
        (area(self.outer_diameter) - area(self.bore_diameter) - self.bolts as f64 * area(self.bolt_hole_diameter)) * self.thickness
    }

    fn check(&self) -> Result<(), PartError> {
        let bad = |why: String| Err(PartError::Parameters { part: "flange", why });
        let all = [self.outer_diameter, self.bore_diameter, self.thickness, self.bolt_circle_diameter, self.bolt_hole_diameter];
        if all.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
            return bad(format!("every length must be positive and finite: {self:?}"));
        }
        let gap = 0.02 * self.outer_diameter;
        if self.bolt_circle_diameter - self.bolt_hole_diameter < self.bore_diameter + 2.0 * gap
            || self.bolt_circle_diameter + self.bolt_hole_diameter > self.outer_diameter - 2.0 * gap
        {
            return bad("the bolt holes must lie between the bore and the rim, with a wall on both sides".into());
        }
        if self.bolts > 1 && self.bolt_circle_diameter * (PI / self.bolts as f64).sin() < self.bolt_hole_diameter + gap {
            return bad(format!("{} bolt holes of diameter {} overlap on the bolt circle", self.bolts, self.bolt_hole_diameter));
        }
        Ok(())
    }

    /// Builds the flange: axis along +z through the origin, bottom face at z = 0.
    ///
    /// # Errors
    /// [`PartError::Parameters`] for lengths that are not positive or holes that do not fit.
    pub fn build(&self) -> Result<Model, PartError> {
        self.check()?;
        let z = Vector3::unit_z();
        let x = Vector3::unit_x();
        let mut wires = vec![circle(Point3::new(0.0, 0.0, 0.0), z, x, self.outer_diameter / 2.0)];
        wires.push(circle(Point3::new(0.0, 0.0, 0.0), z, x, self.bore_diameter / 2.0).inverse());
        for c in self.bolt_centres() {
            wires.push(circle(Point3::new(c.x, c.y, 0.0), z, x, self.bolt_hole_diameter / 2.0).inverse());
        }
        let modeling = |e: truck_modeling::errors::Error| PartError::Modeling { part: "flange", why: e.to_string() };
        let face = builder::try_attach_plane(&wires).map_err(modeling)?;
        let solid = builder::tsweep(&face, Vector3::new(0.0, 0.0, self.thickness));
        let mut model = solid_to_model(&solid, "flange")?;
        let bolts = self.bolt_centres();
        let (ro, rb, rh) = (self.outer_diameter / 2.0, self.bore_diameter / 2.0, self.bolt_hole_diameter / 2.0);
        name_faces(&mut model, "flange", |f: &FaceProbe<'_>| {
            let name = match (f.surface, f.plane_normal) {
                (_, Some(n)) if along(n, -DVec3::Z) => "bottom",
                (_, Some(n)) if along(n, DVec3::Z) => "top",
                (Surface::Cylinder(c), None) if (c.radius - ro).abs() < 1e-6 * ro => "rim",
                (Surface::Cylinder(c), None) if (c.radius - rb).abs() < 1e-6 * rb => "bore",
                (Surface::Cylinder(_), None) => {
                    let k = bolts.iter().position(|b| (DVec2::new(f.centre.x, f.centre.y) - *b).length() < 0.5 * rh)?;
                    return Some(format!("bolt_{}", k + 1));
                }
                _ => return None,
            };
            Some(name.to_string())
        })?;
        Ok(model)
    }
}
