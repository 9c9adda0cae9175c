//! MSC/NX Nastran bulk data decks of an [`crate::fe::FeModel`].

pub mod field;
