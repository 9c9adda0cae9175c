//! The data of a `.poly` file and its errors (see `io/poly.rs`).

use crate::io::IoError;
use crate::mesh2d::DomainError;
use glam::DVec2;
use std::path::PathBuf;

/// A regional attribute / area constraint seed of a `.poly` file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegionSeed {
    /// The seed point: the region is the one that contains it.
    pub at: DVec2,
    /// The regional attribute, as in the file; [`PolyFile::to_domains`] takes it as the
    /// region's tag (a whole number from 1).
    pub attribute: f64,
    /// The region's maximum triangle area (`None`: the file gives none, or a negative one).
    pub max_area: Option<f64>,
}

/// The contents of a 2D `.poly` file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PolyFile {
    /// Vertices, renumbered from 0.
    pub points: Vec<DVec2>,
    /// Segments between vertices (0-based indices into `points`).
    pub segments: Vec<[u32; 2]>,
    /// One boundary marker per segment (0 where the file has none).
    pub markers: Vec<u32>,
    /// Hole seeds: the region containing each one is removed.
    pub holes: Vec<DVec2>,
    /// Regional attribute and area constraint seeds.
    pub regions: Vec<RegionSeed>,
}

/// Why a `.poly` file could not be read, written or turned into domains. Vertices, segments,
/// holes and regions are numbered from 0 in the order of the file.
#[derive(Debug, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum PolyError {
    /// The file could not be read.
    #[error("{}: cannot read: {reason}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        reason: String,
    },
    /// A line does not say what the format needs there.
    #[error("{}:{line}: {message}", path.display())]
    Syntax {
        /// The file.
        path: PathBuf,
        /// The 1-based line (0: the end of the file).
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The file could not be written.
    #[error(transparent)]
    Write(#[from] IoError),
    /// A vertex coordinate is not finite.
    #[error("vertex {vertex} ({x}, {y}) is not finite")]
    NonFinite {
        /// The vertex (0-based).
        vertex: u32,
        /// Its coordinates.
        x: f64,
        /// Its coordinates.
        y: f64,
    },
    /// A segment refers to a missing vertex or joins a vertex to itself.
    #[error("segment {segment} ({a} -> {b}, 0-based) refers to a missing vertex or joins a vertex to itself")]
    BadSegment {
        /// The segment (0-based).
        segment: usize,
        /// Its first end.
        a: u32,
        /// Its second end.
        b: u32,
    },
    /// Two vertices coincide.
    #[error("vertices {0} and {1} (0-based) coincide")]
    DuplicateVertex(u32, u32),
    /// A vertex lies inside a segment it does not end.
    #[error("vertex {vertex} (0-based) lies inside segment {segment}, which it does not end")]
    VertexOnSegment {
        /// The vertex.
        vertex: u32,
        /// The segment.
        segment: usize,
    },
    /// Two segments cross or overlap.
    #[error("segments {0} and {1} (0-based) cross or overlap")]
    SegmentsIntersect(usize, usize),
    /// The segments enclose no area (no segments, or every loop has zero area).
    #[error("the segments enclose no area (zero-area loops, or no closed loop)")]
    NoArea,
    /// A hole seed lies outside every region (outside the outer boundary or in another hole).
    #[error("hole {hole} at ({x}, {y}) lies outside every region")]
    HoleOutside {
        /// The hole (0-based).
        hole: usize,
        /// Its seed.
        x: f64,
        /// Its seed.
        y: f64,
    },
    /// A region seed lies outside every region (outside the outer boundary or in a hole).
    #[error("region seed {region} at ({x}, {y}) lies outside every region")]
    RegionOutside {
        /// The region seed (0-based).
        region: usize,
        /// Its seed.
        x: f64,
        /// Its seed.
        y: f64,
    },
    /// A hole or region seed lies on a segment or a vertex, so the side it picks is unclear.
    #[error("{what} {index} at ({x}, {y}) lies on a segment or a vertex")]
    SeedOnBoundary {
        /// "hole" or "region seed".
        what: &'static str,
        /// Its index (0-based).
        index: usize,
        /// Its seed.
        x: f64,
        /// Its seed.
        y: f64,
    },
    /// A segment has the same region on both sides (dangling or internal): it bounds nothing.
    #[error("segment {segment} (0-based) lies inside a region instead of on its boundary (a dangling or internal segment)")]
    InternalSegment {
        /// The segment.
        segment: usize,
    },
    /// A regional attribute is not a usable region tag.
    #[error("region seed {region} has attribute {value}: a region tag must be a whole number from 1 to 4294967295")]
    BadAttribute {
        /// The region seed (0-based).
        region: usize,
        /// The attribute.
        value: f64,
    },
    /// The triangulation of the vertices failed (a coordinate out of range).
    #[error("cannot triangulate the vertices: {0}")]
    Triangulation(String),
    /// A region's boundary failed the domain checks.
    #[error("region {region} (0-based, by its first segment): {source}")]
    Domain {
        /// The region (0-based, in the order of the output).
        region: usize,
        /// The failed check.
        source: DomainError,
    },
}
