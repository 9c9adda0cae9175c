//! Layer 4: 2D meshing. Algorithms that take a planar domain and a size and return a
//! [`PlanarMesh`](crate::mesh::PlanarMesh).
//!
//! - [`quadtree`]: the lecture's quadtree mesher (Yerry and Shephard's modified quadtree,
//!   2:1 balanced, templates inside, cut quadrants at the boundary);
//! - `face`: the planar faces of a tagged surface (a CAD part's tessellation) as domains
//!   in their planes' coordinates, and the way back to 3D.

pub(crate) mod face;
pub mod quadtree;
