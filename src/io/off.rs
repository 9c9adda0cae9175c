//! Placeholder until the off format lands.
use crate::io::{IoError, Loaded};
use crate::mesh::TriSurface;
use std::path::Path;
/// Reads OFF.
pub fn read(path: &Path, _bytes: &[u8]) -> Result<Loaded, IoError> { Err(IoError::in_file(path, "OFF not yet supported")) }
/// Writes OFF.
pub fn write(path: &Path, _s: &TriSurface) -> Result<(), IoError> { Err(IoError::in_file(path, "OFF not yet supported")) }
