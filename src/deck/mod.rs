//! Layer 6: solver decks written from an [`crate::fe::FeModel`]: CalculiX/Abaqus `.inp`
//! ([`inp`]), Nastran bulk data ([`nastran`]), and for pre- and post-processors MSH 4.1 with
//! the sets as named physical groups ([`msh`]) and VTU with the sets as data ([`vtu`]). Every writer goes through
//! [`crate::io::atomic`] and refuses, before writing a byte, what its format cannot hold.

pub mod inp;
pub mod msh;
pub mod nastran;
pub mod vtu;
