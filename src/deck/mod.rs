//! Layer 6: solver decks written from an [`crate::fe::FeModel`]: CalculiX/Abaqus `.inp`
//! (`inp`), Nastran bulk data (`nastran`), and for pre- and post-processors MSH 4.1 with
//! the sets as named physical groups (`msh`) and VTU with the sets as data (`vtu`). Every writer goes through
//! `crate::io::atomic` and refuses, before writing a byte, what its format cannot hold.

pub(crate) mod inp;
pub(crate) mod inp_faces;
pub(crate) mod msh;
pub(crate) mod nastran;
pub(crate) mod vtu;

pub use inp::{deck_text, num as inp_number, write_inp};
pub use inp_faces::{inp_faces_text, write_inp_faces};
pub use msh::write_msh;
pub use nastran::{NastranOptions, NastranSummary, write_nastran};
pub use vtu::write_vtu;
