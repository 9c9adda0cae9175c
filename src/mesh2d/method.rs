//! The method switch shared by the CLI and the job file: which of the lecture's 2D methods
//! meshes a [`Domain`], with what options, and one call, [`mesh_domain`], that runs it.
//!
//! - Stage: between a domain (a planar CAD face, a `.poly` region, a job's polygon) and its
//!   [`PlanarMesh`].
//! - The boundary: [`Boundary::Free`] lets a method that can split segments do so (a lone
//!   region; the others get it divided by the size); [`Boundary::Split`] divides the domain's segments by the size first
//!   ([`split_boundary`]), for regions whose segments are long; [`Boundary::Keep`] keeps the
//!   given points as the boundary (a CAD face: the tessellation's edge points, so that
//!   neighbouring faces conform).
//! - Quadrilaterals ([`Mesh2dOptions::quads`]): all quads for every method. The method's
//!   triangles are made at twice the size (the boundary divided at twice the size too), then
//!   paired and split by [`super::quads::from_triangles`]: every edge halved, so the quads
//!   come out at the size and every boundary edge gets its midpoint (listed in
//!   [`Meshed2d::midpoints`]). The quadtree's triangles are [`super::quads::mesh`]'s (its
//!   interior lattice as seeds, which pairs into squares).

use super::boundary::{split_boundary, SizeError};
use super::domain::{Domain, DomainError};
use super::quadtree::{self, QuadtreeError, QuadtreeOptions};
use crate::core::RegionId;
use crate::mesh::PlanarMesh;
use glam::DVec2;
use std::fmt;
use std::str::FromStr;

/// One of the lecture's 2D methods (section 23.2).
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Method {
    /// Constrained Delaunay triangulation and Ruppert/Chew refinement to a minimum angle.
    Delaunay,
    /// Topology decomposition: ear cutting (holes bridged), then Delaunay insertion to the
    /// size.
    Ear,
    /// Geometry decomposition by recursive subdivision (Bykat).
    Recursive,
    /// Geometry decomposition by iterative removal of elements (Sadek).
    Removal,
    /// Iterative removal of a boundary layer: the advancing front (Lo, Löhner).
    Front,
    /// Yerry and Shephard's modified quadtree.
    Quadtree,
}

impl Method {
    /// Every method, in the order `--help` lists them.
    pub const ALL: &'static [Method] = &[Method::Delaunay, Method::Ear, Method::Recursive, Method::Removal, Method::Front, Method::Quadtree];

    /// The name the CLI and job files use.
    pub fn name(self) -> &'static str {
        match self {
            Method::Delaunay => "delaunay",
            Method::Ear => "ear",
            Method::Recursive => "recursive",
            Method::Removal => "removal",
            Method::Front => "front",
            Method::Quadtree => "quadtree",
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A method name that is not one of [`Method::ALL`].
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[error("unknown 2D method '{given}' (one of: {})", Method::ALL.iter().map(|m| m.name()).collect::<Vec<_>>().join(", "))]
pub struct UnknownMethod {
    /// What was given.
    pub given: String,
}

impl FromStr for Method {
    type Err = UnknownMethod;
    fn from_str(s: &str) -> Result<Method, UnknownMethod> {
        Method::ALL.iter().copied().find(|m| m.name().eq_ignore_ascii_case(s.trim())).ok_or_else(|| UnknownMethod { given: s.to_string() })
    }
}

/// How the domain's boundary is treated (see the module docs).
#[derive(Copy, Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Boundary {
    /// A lone region: the method may put points on the segments where it needs them
    /// (Delaunay refinement splits encroached segments); methods that cannot get the
    /// segments divided by the size first.
    Free,
    /// Divide the segments by the size first, then keep them (regions sharing segments).
    Split,
    /// Keep the given boundary points.
    Keep,
}

/// Options of [`mesh_domain`].
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh2dOptions {
    /// The method.
    pub method: Method,
    /// All quadrilaterals (the method's triangles paired and split).
    pub quads: bool,
    /// The smallest angle asked of Delaunay refinement, degrees (`None`: its default).
    pub min_angle: Option<f64>,
    /// A bound on every triangle's area (Triangle's `-a`), besides the size.
    pub max_area: Option<f64>,
    /// The boundary rule.
    pub boundary: Boundary,
    /// Whether the size bounds Delaunay refinement's triangles (false: the angle and
    /// `max_area` only, as Triangle's `-q -a`); the other methods always follow the size.
    pub use_size: bool,
    /// The tag of every element.
    pub region: RegionId,
}

impl Default for Mesh2dOptions {
    fn default() -> Self {
        Mesh2dOptions { method: Method::Delaunay, quads: false, min_angle: None, max_area: None, boundary: Boundary::Split, use_size: true, region: RegionId(1) }
    }
}

/// Why a domain could not be meshed.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum Mesh2dError {
    /// The domain is invalid.
    #[error("invalid domain: {0}")]
    Domain(#[from] DomainError),
    /// The size field is not positive and finite somewhere it was asked.
    #[error(transparent)]
    Size(#[from] SizeError),
    /// An option the method cannot take.
    #[error("{method} cannot take {what}")]
    Option {
        /// The method.
        method: Method,
        /// The option and why.
        what: String,
    },
    /// The quadtree failed.
    #[error("quadtree: {0}")]
    Quadtree(#[from] QuadtreeError),
    /// Delaunay refinement failed.
    #[error("delaunay: {0}")]
    Delaunay(#[from] super::delaunay::Error),
    /// Ear cutting failed.
    #[error("ear: {0}")]
    Ear(#[from] super::ear::Error),
    /// Recursive subdivision failed.
    #[error("recursive: {0}")]
    Recursive(#[from] super::recursive::Error),
    /// Element removal failed.
    #[error("removal: {0}")]
    Removal(#[from] super::removal::Error),
    /// The advancing front failed.
    #[error("front: {0}")]
    Front(#[from] super::front::Error),
    /// The split into quadrilaterals failed.
    #[error("quads: {0}")]
    Quads(#[from] super::quads::Error),
}

/// A meshed domain.
#[derive(Clone, Debug)]
pub struct Meshed2d {
    /// The mesh (every element tagged with the options' region).
    pub mesh: PlanarMesh,
    /// Vertices added at the middle of a boundary edge (quadrilaterals): the vertex and the
    /// two mesh vertices of the edge it halves (domain points unless Delaunay refinement
    /// split the segments first, [`Boundary::Free`]).
    pub midpoints: Vec<(u32, [u32; 2])>,
    /// The method's own figures, as JSON.
    pub stats: serde_json::Value,
}

/// The method's figures as JSON (a serialisation that cannot fail: plain numbers and lists).
fn json<T: serde::Serialize>(stats: &T) -> serde_json::Value {
    serde_json::to_value(stats).unwrap_or(serde_json::Value::Null)
}

/// Refuses `--min-angle` and `--max-area` for a method that sizes by the size field only.
fn no_angle_or_area(options: &Mesh2dOptions) -> Result<(), Mesh2dError> {
    if options.min_angle.is_some() || options.max_area.is_some() {
        return Err(Mesh2dError::Option { method: options.method, what: "--min-angle or --max-area (it sizes by the size field only)".into() });
    }
    Ok(())
}

/// Meshes `domain` by `options.method` at the size `size` (see the module docs).
///
/// # Errors
/// [`Mesh2dError`]: an invalid domain, a bad size, an option the method cannot take, or the
/// method's own error.
pub fn mesh_domain(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &Mesh2dOptions) -> Result<Meshed2d, Mesh2dError> {
    domain.validate()?;
    if !options.quads {
        return triangles(domain, size, options);
    }
    // all quads: the method's triangles at twice the size, each split into quads (every
    // edge halved); the quadtree's lattice seeds the triangles of `quads::mesh`
    let twice = |p: DVec2| 2.0 * size(p);
    let domain_free = options.boundary == Boundary::Free && options.method == Method::Delaunay;
    let split;
    let domain = match options.boundary {
        _ if options.boundary == Boundary::Keep || domain_free => domain,
        _ => {
            split = split_boundary(domain, &twice)?;
            &split.domain
        }
    };
    let qo = super::quads::Options { region: options.region, ..Default::default() };
    let (m, source) = if options.method == Method::Quadtree {
        no_angle_or_area(options)?;
        (super::quads::mesh(domain, size, &qo)?, serde_json::Value::Null)
    } else {
        let tri = triangles(domain, &twice, &Mesh2dOptions { quads: false, boundary: if domain_free { Boundary::Free } else { Boundary::Keep }, ..options.clone() })?;
        (super::quads::from_triangles(&tri.mesh, &qo)?, tri.stats)
    };
    Ok(Meshed2d { mesh: m.mesh, midpoints: m.midpoints, stats: serde_json::json!({ "triangles": source, "quads": m.stats }) })
}

/// [`mesh_domain`] without quads.
fn triangles(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &Mesh2dOptions) -> Result<Meshed2d, Mesh2dError> {
    let split;
    let domain = match options.boundary {
        Boundary::Split if options.method != Method::Quadtree => {
            split = split_boundary(domain, size)?;
            &split.domain
        }
        Boundary::Free if !matches!(options.method, Method::Quadtree | Method::Delaunay) => {
            split = split_boundary(domain, size)?;
            &split.domain
        }
        _ => domain,
    };
    match options.method {
        Method::Quadtree => {
            no_angle_or_area(options)?;
            let mut o = QuadtreeOptions { quads: options.quads, region: options.region, ..QuadtreeOptions::default() };
            o.band.keep_boundary = options.boundary == Boundary::Keep;
            let m = quadtree::mesh(domain, size, &o)?;
            let angles = quadtree::angles(&m, domain);
            let stats = serde_json::json!({ "tree": m.stats, "inside_triangles": m.inside_triangles, "angles": angles });
            Ok(Meshed2d { mesh: m.mesh, midpoints: Vec::new(), stats })
        }
        Method::Removal => {
            no_angle_or_area(options)?;
            let o = super::removal::Options { region: options.region, ..Default::default() };
            let m = super::removal::mesh(domain, size, &o)?;
            Ok(Meshed2d { mesh: m.mesh, midpoints: Vec::new(), stats: json(&m.stats) })
        }
        Method::Delaunay => {
            let mut o = super::delaunay::Options { region: options.region, use_size: options.use_size, max_area: options.max_area, split_segments: options.boundary == Boundary::Free, ..Default::default() };
            if let Some(a) = options.min_angle {
                o.min_angle = a;
            }
            let m = super::delaunay::mesh(domain, size, &o)?;
            Ok(Meshed2d { mesh: m.mesh, midpoints: Vec::new(), stats: json(&m.stats) })
        }
        Method::Ear => {
            no_angle_or_area(options)?;
            let m = super::ear::mesh(domain, size, &super::ear::Options::default().with_region(options.region))?;
            Ok(Meshed2d { mesh: m.mesh, midpoints: Vec::new(), stats: json(&m.stats) })
        }
        Method::Recursive => {
            no_angle_or_area(options)?;
            let m = super::recursive::mesh(domain, size, &super::recursive::Options::default().with_region(options.region))?;
            Ok(Meshed2d { mesh: m.mesh, midpoints: Vec::new(), stats: json(&m.stats) })
        }
        Method::Front => {
            no_angle_or_area(options)?;
            let m = super::front::mesh(domain, size, &super::front::Options::default().with_region(options.region))?;
            Ok(Meshed2d { mesh: m.mesh, midpoints: Vec::new(), stats: serde_json::json!({ "front": m.front, "improve": m.improve }) })
        }
    }
}
