//! Layer 6: solver decks written from an [`crate::fe::FeModel`]: CalculiX/Abaqus `.inp`
//! ([`inp`]). Every writer goes through [`crate::io::atomic`].

pub mod inp;
