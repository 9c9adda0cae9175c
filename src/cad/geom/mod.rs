//! Geometry of B-rep faces and edges, in millimetres: the surface and curve kinds STEP files
//! use, each evaluable (`point`, derivatives, normal) with its natural parameter domain and an
//! inverse (`project`) that the tessellator maps edge points into face parameter space with.
//!
//! B-splines are evaluated by our own Cox–de Boor code (`basis`) rather than
//! `truck-geometry`: it works on `glam` types like the rest of fepre, gives the second
//! derivatives Newton projection needs, and keeps the rational case exact without a
//! homogeneous-vector layer; the whole of it is a few hundred lines with tests against hand
//! values.

pub(crate) mod basis;
pub(crate) mod bspline_curve;
pub(crate) mod bspline_surface;
pub(crate) mod circle;
pub(crate) mod conic;
pub(crate) mod cone;
pub(crate) mod curve;
pub(crate) mod cylinder;
pub(crate) mod derivs;
pub(crate) mod domain;
pub(crate) mod ellipse;
pub(crate) mod extrusion;
pub(crate) mod frame;
pub(crate) mod line;
pub(crate) mod newton;
pub(crate) mod plane;
pub(crate) mod polyline;
pub(crate) mod revolution;
pub(crate) mod similarity;
pub(crate) mod sphere;
pub(crate) mod spline_error;
pub(crate) mod surface;
pub(crate) mod torus;

#[cfg(test)]
mod tests;

pub use bspline_curve::BSplineCurve;
pub use bspline_surface::BSplineSurface;
pub use circle::Circle;
pub use conic::{Hyperbola, Parabola};
pub use cone::Cone;
pub use curve::{Curve, CurveKind, CurveReplica, OffsetCurve};
pub use cylinder::Cylinder;
pub use derivs::{CurveDerivs, SurfaceDerivs};
pub use domain::{CurveDomain, Interval, SurfaceDomain, unwrap_near, wrap_into};
pub use ellipse::Ellipse;
pub use extrusion::Extrusion;
pub use frame::{Frame, Rigid};
pub use line::Line;
pub use plane::Plane;
pub use polyline::Polyline;
pub use revolution::Revolution;
pub use similarity::Similarity;
pub use sphere::Sphere;
pub use spline_error::SplineError;
pub use surface::{Offset, Surface, SurfaceKind, SurfaceReplica};
pub use torus::{Torus, TorusPart};
