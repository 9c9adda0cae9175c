//! Placeholder until the msh format lands.
use crate::io::{IoError, Loaded};
use crate::mesh::{TetMesh, TriSurface};
use std::path::Path;
/// Reads MSH.
pub fn read(path: &Path, _bytes: &[u8]) -> Result<Loaded, IoError> { Err(IoError::in_file(path, "not yet supported")) }
/// Writes a surface.
pub fn write_surface(path: &Path, _s: &TriSurface) -> Result<(), IoError> { Err(IoError::in_file(path, "not yet supported")) }
/// Writes a tet mesh.
pub fn write_volume(path: &Path, _m: &TetMesh) -> Result<(), IoError> { Err(IoError::in_file(path, "not yet supported")) }
