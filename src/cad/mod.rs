//! Layer 3 (above `io`): B-rep import and export. A STEP (ISO 10303-21) reader of our own
//! ([`step`]) turns AP203, AP214 and AP242 files into a [`Model`]: an index arena of solids,
//! shells, faces, loops, edges and vertices with evaluable geometry ([`geom`]) in millimetres,
//! assemblies expanded; [`step::write`] writes a model back as AP214. [`parts`] builds
//! parametric parts (bracket, flange, elbow) in code with truck-modeling.
//!
//! ```no_run
//! let model = fepre::cad::step::read("part.step".as_ref())?;
//! for face in model.face_ids() {
//!     let f = model.face(face);
//!     let surface = model.surface(f.surface);
//!     println!("{face}: {} from {}", surface.kind(), f.source);
//! }
//! # Ok::<(), fepre::cad::step::StepError>(())
//! ```

pub mod brep;
pub mod geom;
pub mod parts;
pub mod step;

pub use brep::Model;
