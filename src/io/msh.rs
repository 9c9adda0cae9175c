//! Gmsh MSH: version 4.1 read (ASCII and binary, either byte order) and written (ASCII);
//! version 2.2 ASCII read.
//!
//! Read: `$MeshFormat`, `$PhysicalNames`, `$Entities`, `$Nodes` (entity blocks, parametric
//! coordinates skipped) and `$Elements`; other sections (`$NodeData`, `$Periodic`, …) are
//! skipped with a note, as are elements other than triangles and tetrahedra. Quadratic and
//! higher-order triangles and tets (types 9, 11, 20–25, 29–31) keep their corner nodes.
//! A triangle's tag is the first physical tag of its surface entity, or the entity's tag
//! when it has none; a tet's region tag likewise from its volume entity. Physical names
//! become tag names. A file with tets is a [`MeshData::Volume`](crate::io::MeshData) whose
//! boundary is the file's triangles; otherwise the triangles make a surface and nodes alone a
//! point set. Nodes numbered `1..=n` without gaps keep that order; others are taken in file
//! order. Version 4.0 and binary 2.2 files are refused with a hint to re-export as 4.1;
//! partitioned meshes are refused too.
//!
//! Written: ASCII 4.1 with one surface entity per face tag and one volume entity per region
//! tag, each in the physical group of the same number, named after the tag's name where it
//! has one. Gmsh has no physical group 0 (0 means "no group"): a tag 0 is written as the
//! group one above the largest tag of its dimension, named after the tag's name or `tag_0`,
//! so reading the file back gives that number instead of 0. Each node is written in the block
//! of the first entity whose elements use it, surfaces before volumes.

mod read;
pub(crate) mod write;

use crate::io::{IoError, Loaded};
use crate::mesh::{MixedSurface, TetMesh, TriSurface};
use std::path::Path;

/// Reads an MSH file's bytes (4.1 ASCII or binary, 2.2 ASCII).
///
/// # Errors
/// Malformed or truncated sections, nodes referenced but not defined, non-finite coordinates,
/// unsupported versions; each names the file and the line (ASCII) or byte (binary) or element.
pub fn read(path: &Path, bytes: &[u8]) -> Result<Loaded, IoError> {
    read::read(path, bytes)
}

/// Writes a surface as ASCII MSH 4.1, one surface entity and physical group per tag.
///
/// # Errors
/// [`IoError::Write`].
pub fn write_surface(path: &Path, s: &TriSurface) -> Result<(), IoError> {
    write::write(path, &write::Layout::surface(s))
}

/// Writes a surface of triangles and quads as ASCII MSH 4.1: an entity and physical group per
/// tag, with a block of triangles (type 2) and one of quads (type 3).
///
/// # Errors
/// [`IoError::Write`].
pub fn write_mixed(path: &Path, s: &MixedSurface) -> Result<(), IoError> {
    write::write(path, &write::Layout::mixed(s))
}

/// Writes a tet mesh as ASCII MSH 4.1: a surface entity per boundary face tag and a volume
/// entity per region tag, each its own physical group.
///
/// # Errors
/// [`IoError::Write`].
pub fn write_volume(path: &Path, m: &TetMesh) -> Result<(), IoError> {
    write::write(path, &write::Layout::volume(m))
}

#[cfg(test)]
mod tests;
