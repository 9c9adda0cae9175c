//! Placeholder until the obj format lands.
use crate::io::{IoError, Loaded};
use crate::mesh::TriSurface;
use std::path::Path;
/// Reads OBJ.
pub fn read(path: &Path, _bytes: &[u8]) -> Result<Loaded, IoError> { Err(IoError::in_file(path, "OBJ not yet supported")) }
/// Writes OBJ.
pub fn write(path: &Path, _s: &TriSurface) -> Result<(), IoError> { Err(IoError::in_file(path, "OBJ not yet supported")) }
