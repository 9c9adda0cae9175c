//! The typed error of every container's `validate()`: each variant names the offending element.

use crate::core::Sign;
use std::fmt;

/// An element of a mesh, by kind and 0-based position in its array.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Element {
    /// A triangle of a [`TriSurface`](crate::mesh::TriSurface) or a
    /// [`PlanarMesh`](crate::mesh::PlanarMesh).
    Triangle(usize),
    /// A quadrilateral of a [`PlanarMesh`](crate::mesh::PlanarMesh).
    Quad(usize),
    /// A tetrahedron of a [`TetMesh`](crate::mesh::TetMesh).
    Tet(usize),
    /// A boundary triangle of a [`TetMesh`](crate::mesh::TetMesh).
    BoundaryTriangle(usize),
}

impl fmt::Display for Element {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Element::Triangle(i) => write!(f, "triangle {i}"),
            Element::Quad(i) => write!(f, "quad {i}"),
            Element::Tet(i) => write!(f, "tetrahedron {i}"),
            Element::BoundaryTriangle(i) => write!(f, "boundary triangle {i}"),
        }
    }
}

/// Why a mesh container is invalid. Indices are 0-based positions in the container's arrays.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum MeshError {
    /// A per-element array (tags) does not have one entry per element.
    #[error("{what} has {found} entries but there are {expected} elements; give one per element")]
    LengthMismatch {
        /// The array, e.g. "face_tags".
        what: &'static str,
        /// Entries in the array.
        found: usize,
        /// Elements it should describe.
        expected: usize,
    },
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate {coords:?}")]
    NonFiniteVertex {
        /// The vertex.
        vertex: usize,
        /// Its coordinates.
        coords: Vec<f64>,
    },
    /// An element refers to a vertex that does not exist.
    #[error("{element} refers to vertex {index}, but there are only {count} vertices")]
    IndexOutOfRange {
        /// The element.
        element: Element,
        /// The bad vertex index.
        index: u32,
        /// Number of vertices.
        count: usize,
    },
    /// An element uses the same vertex twice.
    #[error("{element} uses vertex {vertex} twice (vertices {vertices:?}); remove degenerate elements")]
    RepeatedVertex {
        /// The element.
        element: Element,
        /// The repeated vertex.
        vertex: u32,
        /// All its vertices.
        vertices: Vec<u32>,
    },
    /// An element that must be positively oriented is flat or inverted (decided exactly).
    #[error("{element} (vertices {vertices:?}) is {}", orientation_word(*orientation))]
    BadOrientation {
        /// The element.
        element: Element,
        /// Its vertices.
        vertices: Vec<u32>,
        /// Its exact orientation (`Zero` for flat, `Negative` for inverted).
        orientation: Sign,
    },
    /// A quadrilateral is not strictly convex and counter-clockwise.
    #[error("quad {quad} (vertices {vertices:?}) is not strictly convex and counter-clockwise at its corner {corner}")]
    NonConvexQuad {
        /// The quad.
        quad: usize,
        /// Its vertices.
        vertices: [u32; 4],
        /// The corner (0..4) where the turn is not strictly counter-clockwise.
        corner: usize,
    },
    /// A face (3D) or an edge (2D) is shared by more than two elements.
    #[error("{} {entity:?} is shared by {} elements ({}): the mesh is not conforming", entity_word(entity.len()), elements.len(), list(elements))]
    NonManifold {
        /// The vertices of the face or edge.
        entity: Vec<u32>,
        /// The elements sharing it.
        elements: Vec<Element>,
    },
    /// Two elements share a face (3D) or an edge (2D) with the same orientation: they overlap.
    #[error("{first} and {second} share {} {entity:?} from the same side: they overlap", entity_word(entity.len()))]
    Overlap {
        /// The shared face or edge.
        entity: Vec<u32>,
        /// One element.
        first: Element,
        /// The other.
        second: Element,
    },
    /// A boundary triangle of a tet mesh is not a face of any of its tetrahedra.
    #[error("boundary triangle {triangle} (vertices {vertices:?}) is not a face of any tetrahedron")]
    BoundaryNotAFace {
        /// The boundary triangle.
        triangle: usize,
        /// Its vertices.
        vertices: [u32; 3],
    },
}

fn orientation_word(s: Sign) -> &'static str {
    match s {
        Sign::Zero => "flat (zero volume or area)",
        Sign::Negative => "inverted (negative orientation)",
        Sign::Positive => "positively oriented",
    }
}

fn entity_word(n: usize) -> &'static str {
    if n == 2 { "edge" } else { "face" }
}

fn list(e: &[Element]) -> String {
    e.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(", ")
}
