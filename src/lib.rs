//! fepre: a finite-element preprocessor.
//!
//! CAD parts and surface meshes in; watertight tagged surfaces, quality tetrahedral meshes and
//! solver decks out. Everything the `fepre` binary does is a call here, and the binary uses
//! nothing but this API. The modules follow the pipeline, each importing only from layers
//! below it (see `ARCHITECTURE.md`); each shows its API at its top, its files are internal:
//!
//! - layer 0 [`core`]: ids, exact predicates and intersections, boxes, tolerances, the
//!   size-field trait;
//! - layer 1 [`mesh`]: containers with `validate()` and the surface topology report;
//! - layer 2 [`quality`]: element quality measures (VTK/Verdict definitions);
//! - layer 3 [`io`]: mesh file formats and CalculiX results; [`cad`]: B-reps, STEP in and
//!   out, parts built in code;
//! - layer 4 [`tessellate`] (certified surfaces of B-reps), [`mesh2d`], [`mesh3d`] (Delaunay
//!   and octree tet meshes);
//! - layer 5 [`attributes`] (selectors, groups, sizes), [`fe`] (the FE model);
//! - layer 6 [`pipeline`] (one call per command, jobs, reports with their warnings, errors),
//!   [`deck`] (solver decks);
//! - layer 7: the `fepre` binary's command line (`src/main.rs` and `src/cli/`, a crate of its
//!   own).
//!
//! # Example
//!
//! A part built in code, tessellated and certified, meshed into quality tets, written as
//! Gmsh MSH 4.1 with a physical group per CAD face:
//!
//! ```
//! use fepre::cad::parts::Block;
//! use fepre::core::UniformSize;
//! use fepre::io::{MeshData, WriteOptions, write};
//! use fepre::mesh3d::mesher::{MeshOptions, Seeds, mesh_surface};
//! use fepre::tessellate::certificate::{CertifyOptions, certify};
//! use fepre::tessellate::{TessellateOptions, tessellate};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let model = Block::new(40.0, 10.0, 10.0).build()?; // a 40 x 10 x 10 mm bar, six named faces
//! let t = tessellate(&model, &TessellateOptions::default());
//! let certificate = certify(&model, &t, &CertifyOptions::default());
//! assert!(certificate.passed, "closed, manifold, outward, Euler and volume as the B-rep's");
//!
//! let (tets, report) = mesh_surface(&t.surface, &Seeds::default(), &UniformSize(4.0), &MeshOptions::default())?;
//! tets.validate()?;
//! assert!((tets.volume() - 4000.0).abs() < 1e-6 * 4000.0);
//! println!("{} tets on {} nodes", report.tets, report.nodes);
//!
//! let out = std::env::temp_dir().join("fepre_doc_bar.msh");
//! write(&out, &MeshData::Volume(tets), &WriteOptions::default())?;
//! # std::fs::remove_file(out)?;
//! # Ok(())
//! # }
//! ```
//!
//! A job file (selectors on CAD faces, sizes, materials, loads, decks) goes through
//! [`pipeline::carry_out`]; each subcommand of the binary has its call in [`pipeline`]
//! ([`pipeline::mesh_file`], [`pipeline::inspect_file`], [`pipeline::tessellate_step`], ...),
//! whose report carries its [`pipeline::Warning`]s as data.

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
