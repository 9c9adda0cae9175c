//! Layer 6: solver decks written from an [`crate::fe::FeModel`]: CalculiX/Abaqus `.inp`
//! ([`inp`]) and Nastran bulk data ([`nastran`]). Every writer goes through
//! [`crate::io::atomic`] and refuses, before writing a byte, what its format cannot hold.

pub mod inp;
pub mod nastran;
