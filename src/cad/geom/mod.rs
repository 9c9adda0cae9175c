//! Geometry of B-rep faces and edges, in millimetres: the surface and curve kinds STEP files
//! use, each evaluable (`point`, derivatives, normal) with its natural parameter domain and an
//! inverse (`project`) that the tessellator maps edge points into face parameter space with.
//!
//! B-splines are evaluated by our own Cox–de Boor code ([`basis`]) rather than
//! `truck-geometry`: it works on `glam` types like the rest of fepre, gives the second
//! derivatives Newton projection needs, and keeps the rational case exact without a
//! homogeneous-vector layer; the whole of it is a few hundred lines with tests against hand
//! values.

pub mod basis;
pub mod bspline_curve;
pub mod bspline_surface;
pub mod circle;
pub mod conic;
pub mod cone;
pub mod curve;
pub mod curve_replica;
pub mod cylinder;
pub mod derivs;
pub mod domain;
pub mod ellipse;
pub mod extrusion;
pub mod frame;
pub mod line;
pub mod newton;
pub mod offset;
pub mod offset_curve;
pub mod plane;
pub mod polyline;
pub mod revolution;
pub mod similarity;
pub mod sphere;
pub mod spline_error;
pub mod surface;
pub mod surface_replica;
pub mod torus;

#[cfg(test)]
mod tests;

pub use bspline_curve::BSplineCurve;
pub use bspline_surface::BSplineSurface;
pub use circle::Circle;
pub use conic::{Hyperbola, Parabola};
pub use cone::Cone;
pub use curve::{Curve, CurveKind};
pub use curve_replica::CurveReplica;
pub use cylinder::Cylinder;
pub use derivs::{CurveDerivs, SurfaceDerivs};
pub use domain::{CurveDomain, Interval, SurfaceDomain, unwrap_near, wrap_into};
pub use ellipse::Ellipse;
pub use extrusion::Extrusion;
pub use frame::{Frame, Rigid};
pub use line::Line;
pub use offset::Offset;
pub use offset_curve::OffsetCurve;
pub use plane::Plane;
pub use polyline::Polyline;
pub use revolution::Revolution;
pub use similarity::Similarity;
pub use sphere::Sphere;
pub use spline_error::SplineError;
pub use surface::{Surface, SurfaceKind};
pub use surface_replica::SurfaceReplica;
pub use torus::{Torus, TorusPart};
