//! Layer 4: 2D meshing, the lecture's generators (section 23.2). Every method takes a planar
//! [`Domain`] (a polygon with holes, tagged segments) and a size `h(p)`, and returns a
//! [`PlanarMesh`](crate::mesh::PlanarMesh) that passes `validate()`.
//!
//! - [`Domain`]: the input, checked exactly; [`boundary`]: its segments divided by the size
//!   (the first stage of the methods that keep their boundary points); [`measure`]: the
//!   quality figures every method reports; `method`: the method switch and [`mesh_domain`],
//!   the one call that runs any of them;
//! - [`quadtree`]: Yerry and Shephard's modified quadtree (2:1 balanced, templates inside,
//!   cut quadrants at the boundary);
//! - [`delaunay`]: constrained Delaunay triangulation and Ruppert/Chew refinement;
//! - [`ear`]: topology decomposition (ear cutting, holes bridged), then refinement;
//! - [`recursive`]: geometry decomposition by recursive subdivision (Bykat);
//! - [`removal`]: geometry decomposition by iterative removal of elements (Sadek);
//! - [`front`]: iterative removal of a boundary layer (the advancing front);
//! - [`quads`]: all-quadrilateral meshes;
//! - `face`: the planar faces of a tagged surface (a CAD part's tessellation) as domains
//!   in their planes' coordinates, and the way back to 3D.

pub mod boundary;
pub mod delaunay;
pub(crate) mod domain;
pub mod ear;
pub(crate) mod face;
pub(crate) mod flips;
pub mod front;
pub mod measure;
pub(crate) mod method;
pub mod quads;
pub mod quadtree;
pub mod recursive;
pub mod removal;
pub(crate) mod stars;

pub use domain::{Domain, DomainError};

/// A method's triangles and its counts (ear cutting, recursive subdivision, point removal:
/// each module's `Output`).
#[derive(Clone, Debug, PartialEq)]
pub struct Counted<S> {
    /// The triangles, each tagged with the method's `options.region`; the domain's points
    /// first (same indices), then the added ones.
    pub mesh: crate::mesh::PlanarMesh,
    /// The method's counts.
    pub stats: S,
}
pub use method::{mesh_domain, Boundary, Mesh2dError, Mesh2dOptions, Meshed2d, Method, UnknownMethod};
