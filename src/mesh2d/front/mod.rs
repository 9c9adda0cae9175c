//! (being written: see `crate::mesh2d`)
