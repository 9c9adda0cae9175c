//! Layer 6: solver decks written from an [`crate::fe::FeModel`]: Nastran bulk data
//! ([`nastran`]). Every writer goes through [`crate::io::atomic`].

pub mod nastran;
