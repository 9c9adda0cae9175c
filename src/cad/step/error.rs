//! The error of the STEP reader: it always names the file, and the line or the `#id`.

use std::path::PathBuf;

/// Why a STEP file could not be read. Problems confined to one face or one piece of geometry
/// are not errors: the reader drops that item and lists it in
/// [`Model::dropped`](crate::cad::brep::Model::dropped).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StepError {
    /// The file could not be opened or read.
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// The file does not start with `ISO-10303-21;` (after comments).
    #[error("{}:{line}: not a STEP file (ISO 10303-21): expected 'ISO-10303-21;', found {found}", path.display())]
    NotStep {
        /// The file.
        path: PathBuf,
        /// The line of the first token.
        line: u32,
        /// What was there instead.
        found: String,
    },
    /// A token that does not fit the grammar.
    #[error("{}:{line}: {message}", path.display())]
    Syntax {
        /// The file.
        path: PathBuf,
        /// The line.
        line: u32,
        /// What was wrong and, where it helps, how to fix it.
        message: String,
    },
    /// The file ends inside an entity, a string, a comment or a section.
    #[error("{}:{line}: the file is truncated: it ends {inside}", path.display())]
    Truncated {
        /// The file.
        path: PathBuf,
        /// The line where the unfinished item starts.
        line: u32,
        /// What was left unfinished ("inside entity #12", "before ENDSEC of the DATA section").
        inside: String,
    },
    /// Two instances with the same `#id`.
    #[error("{}:{line}: #{id} is defined twice (first at line {first_line})", path.display())]
    DuplicateId {
        /// The file.
        path: PathBuf,
        /// The repeated id.
        id: u64,
        /// Line of the second definition.
        line: u32,
        /// Line of the first definition.
        first_line: u32,
    },
    /// A reference to an instance the file does not define.
    #[error("{}:{line}: #{from} refers to #{id}, which the file does not define", path.display())]
    MissingEntity {
        /// The file.
        path: PathBuf,
        /// The missing id.
        id: u64,
        /// The instance holding the reference.
        from: u64,
        /// Line of `#from`.
        line: u32,
    },
    /// Instances that refer to each other in a circle where the schema needs a tree (a
    /// surface whose basis surface is itself, an assembly that contains itself).
    #[error("{}:{line}: reference cycle through #{id} ({chain})", path.display())]
    Cycle {
        /// The file.
        path: PathBuf,
        /// An instance on the cycle.
        id: u64,
        /// Its line.
        line: u32,
        /// The cycle, `#a -> #b -> #a`.
        chain: String,
    },
    /// Tessellated geometry that cannot be read: an index outside its list, a malformed
    /// coordinate list.
    #[error("{}:{line}: #{id}: {message}", path.display())]
    Tessellation {
        /// The file.
        path: PathBuf,
        /// The instance.
        id: u64,
        /// Its line.
        line: u32,
        /// What is wrong.
        message: String,
    },
    /// The file parsed, but holds no solid, shell or surface model fepre can use.
    #[error("{}: {}{dropped}", path.display(), if roots.is_empty() { "no B-rep shape found (no MANIFOLD_SOLID_BREP, BREP_WITH_VOIDS or SHELL_BASED_SURFACE_MODEL)".to_string() } else { format!("no usable B-rep shape: {roots}, but not one face of them could be read") })]
    NoShape {
        /// The file.
        path: PathBuf,
        /// A summary of what was dropped, if anything.
        dropped: String,
        /// The shape entities the file has (`2 MANIFOLD_SOLID_BREP (#210, #211)`), when it
        /// has some; empty when it has none.
        roots: String,
    },
}
