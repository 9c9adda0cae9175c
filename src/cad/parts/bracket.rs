//! A flat L-shaped bracket: two legs of one width meeting at a right angle, the inner corner
//! rounded by a fillet, through-holes in both legs; the profile (with the holes as inner
//! wires) is swept along +z by the thickness.
//!
//! Faces: `bottom` (z = 0), `top`, `outer_x` (y = 0), `outer_y` (x = 0), `end_x` (x = leg_x),
//! `end_y` (y = leg_y), `inner_x` (y = width, the inside of the x leg), `inner_y`, `fillet`,
//! and `hole_1` ... `hole_n` (the x leg's holes first, from the corner outwards).

use super::sketch::{Segment, circle, profile};
use super::{FaceProbe, PartError, along, name_faces, solid_to_model};
use crate::cad::brep::Model;
use crate::cad::geom::Surface;
use glam::{DVec2, DVec3};
use std::f64::consts::PI;
use truck_modeling::{Point3, Vector3, builder};

/// The bracket's parameters, in millimetres.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Bracket {
    /// Length of the leg along x, from the outer corner (default 80).
    pub leg_x: f64,
    /// Length of the leg along y (default 80).
    pub leg_y: f64,
    /// Width of both legs (default 30).
    pub width: f64,
    /// Thickness, along z (default 8).
    pub thickness: f64,
    /// Radius of the fillet in the inner corner (default 10).
    pub fillet: f64,
    /// Diameter of the holes (default 9).
    pub hole_diameter: f64,
    /// Holes in each leg, on its centre line, spread evenly beyond the fillet (default 2).
    pub holes_per_leg: usize,
}

impl Default for Bracket {
    fn default() -> Self {
        Bracket { leg_x: 80.0, leg_y: 80.0, width: 30.0, thickness: 8.0, fillet: 10.0, hole_diameter: 9.0, holes_per_leg: 2 }
    }
}

impl Bracket {
    /// Sets [`Bracket::holes_per_leg`].
    pub fn with_holes_per_leg(mut self, n: usize) -> Self {
        self.holes_per_leg = n;
        self
    }

    /// The hole centres in the `z = 0` plane: the x leg's, then the y leg's.
    pub fn hole_centres(&self) -> Vec<DVec2> {
        let n = self.holes_per_leg;
        let start = self.width + self.fillet;
        let along_leg = |len: f64, k: usize| start + (len - start) * (k as f64 + 0.5) / n as f64;
        let mut c: Vec<DVec2> = (0..n).map(|k| DVec2::new(along_leg(self.leg_x, k), self.width / 2.0)).collect();
        c.extend((0..n).map(|k| DVec2::new(self.width / 2.0, along_leg(self.leg_y, k))));
        c
    }

    /// The exact volume, mm³: the L's area plus the fillet's corner, less the holes, times the
    /// thickness.
    pub fn volume(&self) -> f64 {
        let (w, r, d) = (self.width, self.fillet, self.hole_diameter);
        let area = self.leg_x * w + (self.leg_y - w) * w + r * r * (1.0 - PI / 4.0) - 2.0 * self.holes_per_leg as f64 * PI * d * d / 4.0;
        area * self.thickness
    }

    fn check(&self) -> Result<(), PartError> {
        let bad = |why: String| Err(PartError::Parameters { part: "bracket", why });
        let all = [self.leg_x, self.leg_y, self.width, self.thickness, self.fillet, self.hole_diameter];
        if all.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
            return bad(format!("every length must be positive and finite: {self:?}"));
        }
        let start = self.width + self.fillet;
        if self.leg_x <= start || self.leg_y <= start {
            return bad(format!("each leg must be longer than width + fillet = {start}"));
        }
        let gap = 0.05 * self.width;
        if self.hole_diameter + 2.0 * gap > self.width {
            return bad(format!("hole_diameter {} leaves no wall in a leg of width {}", self.hole_diameter, self.width));
        }
        let n = self.holes_per_leg as f64;
        let pitch = (self.leg_x.min(self.leg_y) - start) / n.max(1.0);
        if self.holes_per_leg > 0 && self.hole_diameter + gap > pitch {
            return bad(format!("{} holes of diameter {} do not fit in a leg (pitch {pitch:.3})", self.holes_per_leg, self.hole_diameter));
        }
        Ok(())
    }

    /// Builds the bracket: outer corner at the origin, legs along +x and +y, thickness along +z.
    ///
    /// # Errors
    /// [`PartError::Parameters`] for lengths that are not positive or holes that do not fit.
    pub fn build(&self) -> Result<Model, PartError> {
        self.check()?;
        let (a, b, w, r) = (self.leg_x, self.leg_y, self.width, self.fillet);
        let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let corners = [p(0.0, 0.0), p(a, 0.0), p(a, w), p(w + r, w), p(w, w + r), p(w, b), p(0.0, b)];
        let mut segments = [Segment::Line; 7];
        segments[3] = Segment::Arc(p(w + r - r * s, w + r - r * s));
        let mut wires = vec![profile(&corners, &segments)];
        for c in self.hole_centres() {
            wires.push(circle(p(c.x, c.y), Vector3::unit_z(), Vector3::unit_x(), self.hole_diameter / 2.0).inverse());
        }
        let modeling = |e: truck_modeling::errors::Error| PartError::Modeling { part: "bracket", why: e.to_string() };
        let face = builder::try_attach_plane(&wires).map_err(modeling)?;
        let solid = builder::tsweep(&face, Vector3::new(0.0, 0.0, self.thickness));
        let mut model = solid_to_model(&solid, "bracket")?;
        let holes = self.hole_centres();
        let t = self.thickness;
        name_faces(&mut model, "bracket", |f: &FaceProbe<'_>| {
            let c = f.centre;
            let name = match (f.surface, f.plane_normal) {
                (_, Some(n)) if along(n, -DVec3::Z) && c.z.abs() < 1e-6 * t => "bottom",
                (_, Some(n)) if along(n, DVec3::Z) => "top",
                (_, Some(n)) if along(n, -DVec3::Y) => "outer_x",
                (_, Some(n)) if along(n, -DVec3::X) => "outer_y",
                (_, Some(n)) if along(n, DVec3::X) && c.x > w + r => "end_x",
                (_, Some(n)) if along(n, DVec3::X) => "inner_y",
                (_, Some(n)) if along(n, DVec3::Y) && c.y > w + r => "end_y",
                (_, Some(n)) if along(n, DVec3::Y) => "inner_x",
                (Surface::Cylinder(cyl), None) if (cyl.radius - r).abs() < 1e-6 * r => "fillet",
                (Surface::Cylinder(_), None) => {
                    let k = holes.iter().position(|h| (DVec2::new(c.x, c.y) - *h).length() < 0.25 * self.hole_diameter)?;
                    return Some(format!("hole_{}", k + 1));
                }
                _ => return None,
            };
            Some(name.to_string())
        })?;
        Ok(model)
    }
}
