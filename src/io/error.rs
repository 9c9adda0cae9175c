//! The error of every reader and writer: it always names the file, and the line or entity
//! where there is one.

use crate::mesh::MeshError;
use std::fmt;
use std::path::{Path, PathBuf};

/// Where in a file a problem was found.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Location {
    /// Nowhere in particular (the file as a whole).
    File,
    /// A 1-based line of a text file.
    Line(usize),
    /// A byte offset in a binary file.
    Byte(u64),
    /// A named entity: "triangle 12", "chunk 1", "mesh 'Duck' primitive 0", "$Elements block 3".
    Entity(String),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::File => Ok(()),
            Location::Line(l) => write!(f, ":{l}"),
            Location::Byte(b) => write!(f, " (byte {b})"),
            Location::Entity(e) => write!(f, " ({e})"),
        }
    }
}

/// Why a mesh file could not be read or written.
#[derive(Debug, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum IoError {
    /// The file could not be opened or read.
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        #[serde(serialize_with = "crate::core::error_json::message")]
        source: std::io::Error,
    },
    /// The path is a directory.
    #[error("{}: is a directory, not a mesh file", path.display())]
    IsDirectory {
        /// The path.
        path: PathBuf,
    },
    /// The file is empty.
    #[error("{}: the file is empty", path.display())]
    Empty {
        /// The file.
        path: PathBuf,
    },
    /// The extension names no format fepre knows.
    #[error("{}: unknown mesh format{}; use one of: {known}", path.display(), ext.as_deref().map(|e| format!(" '.{e}'")).unwrap_or_default())]
    UnknownFormat {
        /// The file.
        path: PathBuf,
        /// Its extension, if any.
        ext: Option<String>,
        /// The extensions fepre knows for this direction.
        known: String,
    },
    /// The content is malformed.
    #[error("{}{at}: {message}", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// Where.
        at: Location,
        /// What is wrong, and how to fix it where we can tell.
        message: String,
    },
    /// The file holds something fepre does not support.
    #[error("{}{at}: unsupported: {message}", path.display())]
    Unsupported {
        /// The file.
        path: PathBuf,
        /// Where.
        at: Location,
        /// What is not supported.
        message: String,
    },
    /// The mesh read is structurally invalid.
    #[error("{}: invalid mesh: {source}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// The container's validation error.
        source: MeshError,
    },
    /// The data cannot be written in this format (e.g. tetrahedra to STL).
    #[error("{}: cannot write {what} as {format}", path.display())]
    NotRepresentable {
        /// The output file.
        path: PathBuf,
        /// The format.
        format: &'static str,
        /// What it cannot hold.
        what: String,
    },
    /// The data handed to a writer is inconsistent (an array whose length does not match its
    /// entities, a node index out of range); the message names the array or the element.
    #[error("{}: cannot write: {message}", path.display())]
    InvalidData {
        /// The output file.
        path: PathBuf,
        /// What is inconsistent, naming the array or element.
        message: String,
    },
    /// Writing failed.
    #[error("{}: cannot write: {source}", path.display())]
    Write {
        /// The output file.
        path: PathBuf,
        /// The operating system's reason.
        #[serde(serialize_with = "crate::core::error_json::message")]
        source: std::io::Error,
    },
}

impl IoError {
    /// A parse error at a line.
    pub fn at_line(path: &Path, line: usize, message: impl Into<String>) -> IoError {
        IoError::Parse { path: path.to_path_buf(), at: Location::Line(line), message: message.into() }
    }

    /// A parse error at an entity.
    pub fn at_entity(path: &Path, entity: impl Into<String>, message: impl Into<String>) -> IoError {
        IoError::Parse { path: path.to_path_buf(), at: Location::Entity(entity.into()), message: message.into() }
    }

    /// A parse error about the file as a whole.
    pub fn in_file(path: &Path, message: impl Into<String>) -> IoError {
        IoError::Parse { path: path.to_path_buf(), at: Location::File, message: message.into() }
    }

    /// The file the error is about.
    pub fn path(&self) -> &Path {
        match self {
            IoError::Read { path, .. }
            | IoError::IsDirectory { path }
            | IoError::Empty { path }
            | IoError::UnknownFormat { path, .. }
            | IoError::Parse { path, .. }
            | IoError::Unsupported { path, .. }
            | IoError::Invalid { path, .. }
            | IoError::NotRepresentable { path, .. }
            | IoError::InvalidData { path, .. }
            | IoError::Write { path, .. } => path,
        }
    }
}
