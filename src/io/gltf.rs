//! Placeholder until the gltf format lands.
use crate::io::{IoError, Loaded};
use std::path::Path;
/// Reads glTF.
pub fn read(path: &Path, _bytes: &[u8]) -> Result<Loaded, IoError> { Err(IoError::in_file(path, "glTF not yet supported")) }
