//! Placeholder until the vtu format lands.
use crate::io::{IoError, WriteOptions};
use crate::mesh::{TetMesh, TriSurface};
use std::path::Path;
/// Writes a surface.
pub fn write_surface(path: &Path, _s: &TriSurface, _o: &WriteOptions) -> Result<(), IoError> { Err(IoError::in_file(path, "not yet supported")) }
/// Writes a tet mesh.
pub fn write_volume(path: &Path, _m: &TetMesh, _o: &WriteOptions) -> Result<(), IoError> { Err(IoError::in_file(path, "not yet supported")) }
