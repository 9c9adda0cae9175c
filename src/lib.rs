//! fepre: a finite-element preprocessor.
//!
//! CAD parts and surface meshes in; watertight tagged surfaces, quality tetrahedral meshes and
//! solver decks out. The modules follow the pipeline, each importing only from layers below
//! it (see `ARCHITECTURE.md`):
//!
//! - layer 0 [`core`]: ids, exact predicates, bounding boxes, tolerances, the size-field trait;
//! - layer 1 [`mesh`]: containers with `validate()` and the surface topology report;
//! - layer 2 [`quality`]: element quality measures (VTK/Verdict definitions);
//! - layer 3 [`io`]: mesh file formats and CalculiX results; [`cad`]: B-rep import (STEP);
//! - layer 4 [`tessellate`], [`mesh3d`]: surfaces of B-reps, tet meshes;
//! - layer 5 [`attributes`] (selectors, sizes), [`fe`] (the FE model);
//! - layer 6 [`pipeline`] (jobs, `fepre solve`), [`deck`] (solver decks);
//! - layer 7: the `fepre` binary's command line (its own crate, `src/main.rs` and `src/cli/`),
//!   which uses nothing but this API.

pub mod cad;
pub mod attributes;
pub mod core;
pub mod deck;
pub mod fe;
pub mod io;
pub mod mesh;
pub mod mesh2d;
pub mod mesh3d;
pub mod pipeline;
pub mod quality;
pub mod tessellate;
