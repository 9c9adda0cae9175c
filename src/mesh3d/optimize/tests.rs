//! Tests of the whole optimiser on small meshes.
