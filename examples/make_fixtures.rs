//! Regenerates the parts in `cad_fixtures/` that fepre makes itself.
//!
//! `cargo run --example make_fixtures` writes
//! - `cad_fixtures/plate_with_hole.{obj,stl}`: a 40 × 40 × 8 plate with a 64-sided
//!   through-hole of radius 8, each CAD face tagged (top, bottom, four sides, hole), closed,
//!   outward-oriented, genus 1;
//! - `cad_fixtures/{bracket,flange,elbow}.step`: the parts of `fepre::cad::parts` at their
//!   default parameters, built with truck-modeling and written by our STEP writer (AP214, mm,
//!   named faces).
//!
//! A test checks that the committed files equal what this program writes.

use fepre::io::{MeshData, WriteOptions, write};
use fepre::mesh::shapes::plate_with_hole;
use std::path::Path;

fn main() -> anyhow::Result<()> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures");
    std::fs::create_dir_all(&dir)?;
    let plate = MeshData::Surface(plate_with_hole(64, 40.0, 8.0, 8.0));
    for name in ["plate_with_hole.obj", "plate_with_hole.stl"] {
        let path = dir.join(name);
        write(&path, &plate, &WriteOptions::default().with_ascii(true))?;
        println!("wrote {}", path.display());
    }
    for (name, model) in fepre::cad::parts::default_parts()? {
        let path = dir.join(format!("{name}.step"));
        fepre::cad::step::write(&path, &model, name)?;
        println!("wrote {} ({} faces)", path.display(), model.faces.len());
    }
    Ok(())
}
