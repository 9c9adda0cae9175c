//! Placeholder until the tetgen format lands.
use crate::io::{IoError, Loaded};
use crate::mesh::{TetMesh, TriSurface};
use glam::DVec3;
use std::path::Path;
/// Reads TetGen.
pub fn read(path: &Path) -> Result<Loaded, IoError> { Err(IoError::in_file(path, "not yet supported")) }
/// Writes a surface.
pub fn write_surface(path: &Path, _s: &TriSurface) -> Result<(), IoError> { Err(IoError::in_file(path, "not yet supported")) }
/// Writes a tet mesh.
pub fn write_volume(path: &Path, _m: &TetMesh) -> Result<(), IoError> { Err(IoError::in_file(path, "not yet supported")) }
/// Writes points.
pub fn write_points(path: &Path, _p: &[DVec3]) -> Result<(), IoError> { Err(IoError::in_file(path, "not yet supported")) }
