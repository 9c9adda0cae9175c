//! Placeholder: the surface topology report lands here.
