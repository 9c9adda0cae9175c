//! Placeholder: exact triangle-triangle intersection lands here.
