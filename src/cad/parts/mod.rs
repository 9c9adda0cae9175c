//! Parametric parts built in code with truck-modeling and converted into our [`Model`]: an
//! L-shaped bracket with a filleted inner corner and holes (`bracket`), a flange with a bore
//! and bolt holes (`flange`), a 90° pipe elbow (`elbow`), a block with an optional hole
//! (`block`) and a tube or a sector of one (`tube`); the last two are the analytic checks'
//! parts (cantilever, plate with a hole, slab, thick-walled cylinder).
//!
//! Each part has a parameter struct in millimetres with sensible defaults, a `build` that
//! sweeps its profile with truck (`tsweep`, `rsweep`; no booleans) and converts the solid
//! (`truck_topology`, `truck_geometry.rs`: truck's rational arcs and swept surfaces become
//! exact circles, planes, cylinders and tori), and a `volume` computed from the parameters.
//! Every face is named (`bottom`, `top`, `hole_1`, ...) so that boundary conditions can be
//! attached to named faces; a name may cover several faces (truck builds a full hole from two
//! half cylinders, and both are `hole_1`).

pub(crate) mod block;
pub(crate) mod bracket;
pub(crate) mod elbow;
pub(crate) mod flange;
mod sketch;
mod truck_geometry;
pub(crate) mod truck_topology;
pub(crate) mod tube;

pub use block::Block;
pub use bracket::Bracket;
pub use elbow::Elbow;
pub use flange::Flange;
pub use truck_topology::solid_to_model;
pub use tube::Tube;

use crate::cad::brep::Model;
use crate::cad::geom::Surface;
use crate::core::FaceId;
use glam::DVec3;

/// Why a part could not be built.
#[derive(Debug, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum PartError {
    /// The parameters do not describe a valid part.
    #[error("invalid {part} parameters: {why}")]
    Parameters {
        /// The part.
        part: &'static str,
        /// Which parameter, and what it must satisfy.
        why: String,
    },
    /// truck refused to build the shape (a wire that is not planar, loops that cross).
    #[error("truck could not build the {part}: {why}")]
    Modeling {
        /// The part.
        part: &'static str,
        /// truck's message.
        why: String,
    },
    /// A curve or surface of truck's solid could not be converted.
    #[error("face {face}: {why}")]
    Geometry {
        /// The face being converted.
        face: FaceId,
        /// Why.
        why: GeometryError,
    },
    /// A face the part's naming rules do not recognise (a bug in the part's builder).
    #[error("face {face} of the {part} matches none of its names (internal error)")]
    Unnamed {
        /// The part.
        part: &'static str,
        /// The face.
        face: FaceId,
    },
}

/// Why a curve or surface of truck's solid could not be converted to ours ([`PartError::Geometry`]
/// names the face).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum GeometryError {
    /// A line whose two points coincide.
    #[error("a line of zero length")]
    ZeroLengthLine,
    /// An intersection curve, which is not converted.
    #[error("an intersection curve (fepre converts lines, circles and B-splines)")]
    IntersectionCurve,
    /// A plane without a normal or an axis.
    #[error("a degenerate plane")]
    DegeneratePlane,
    /// A surface of revolution whose axis has no direction.
    #[error("a revolution about a zero axis")]
    ZeroAxis,
    /// A B-spline or NURBS surface without a parameter range.
    #[error("an unbounded {surface}")]
    Unbounded {
        /// "B-spline surface" or "NURBS surface".
        surface: &'static str,
    },
    /// Degrees, knots, control points or weights that make no B-spline.
    #[error("{why}")]
    Spline {
        /// What is wrong with them (as the B-spline's constructor says).
        why: String,
    },
    /// The face's surface has no normal at the point sampled to compare senses.
    #[error("no normal at the sample point")]
    NoNormal,
}

/// What the naming rules look at: the face's surface, its outward normal where it is a plane,
/// and the mean of its vertices.
pub(crate) struct FaceProbe<'m> {
    pub surface: &'m Surface,
    /// Outward unit normal of a planar face.
    pub plane_normal: Option<DVec3>,
    /// Mean of the vertices of its loops.
    pub centre: DVec3,
}

/// Names every face by `rule`; a face without a name is an error.
pub(crate) fn name_faces(model: &mut Model, part: &'static str, rule: impl Fn(&FaceProbe<'_>) -> Option<String>) -> Result<(), PartError> {
    let mut names = Vec::with_capacity(model.faces.len());
    for fid in model.face_ids() {
        let f = model.face(fid);
        let surface = model.surface(f.surface);
        let plane_normal = match surface {
            Surface::Plane(p) => Some(if f.same_sense { p.frame.z } else { -p.frame.z }),
            _ => None,
        };
        let (mut sum, mut n) = (DVec3::ZERO, 0.0);
        for &l in &f.loops {
            for c in &model.loops[l as usize].coedges {
                let e = &model.edges[c.edge as usize];
                sum += model.vertices[if c.forward { e.start } else { e.end } as usize].point;
                n += 1.0;
            }
        }
        let centre = if n > 0.0 { sum / n } else { DVec3::ZERO };
        let probe = FaceProbe { surface, plane_normal, centre };
        names.push(rule(&probe).ok_or(PartError::Unnamed { part, face: fid })?);
    }
    for (f, n) in model.faces.iter_mut().zip(names) {
        f.name = Some(n);
    }
    Ok(())
}

/// True when `a` and `b` point the same way (unit vectors, within 1e-6).
pub(crate) fn along(a: DVec3, b: DVec3) -> bool {
    (a - b).length() < 1e-6
}

/// Every part at its default parameters, by name (`bracket`, `flange`, `elbow`): what
/// `cargo run --example make_fixtures` writes to `cad_fixtures/NAME.step`.
///
/// # Errors
/// None in practice (the defaults are valid); a [`PartError`] would mean a bug.
pub fn default_parts() -> Result<Vec<(&'static str, Model)>, PartError> {
    Ok(vec![("bracket", Bracket::default().build()?), ("flange", Flange::default().build()?), ("elbow", Elbow::default().build()?)])
}
