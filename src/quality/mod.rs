//! Placeholder: element quality measures land here.
