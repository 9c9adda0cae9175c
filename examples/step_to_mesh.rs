//! A STEP part to a tet mesh through the library alone: read, select faces, set sizes, mesh,
//! write MSH with a named physical group per CAD face.
//!
//! `cargo run --release --example step_to_mesh -- cad_fixtures/bracket.step target/bracket.msh`

use fepre::attributes::FaceSize;
use fepre::attributes::Positive;
use fepre::attributes::{Density, Selector};
use fepre::pipeline::{Plan, run_plan};
use fepre::pipeline::{Part, PipelineError};
use std::collections::BTreeMap;
use std::path::Path;

/// Meshes `input` with size 4 and size 2 on the faces named `hole_*`, writes `output`.
pub fn step_to_mesh(input: &Path, output: &Path) -> Result<Part, PipelineError> {
    let mut part = Part::open(input)?;
    let selectors = BTreeMap::from([("holes".to_string(), Selector::Name("hole_*".into()))]);
    let mut density = Density::default();
    density.size = Positive::new(4.0);
    density.face.push(FaceSize { faces: "holes".into(), size: Positive::new(2.0).expect("positive") });
    let plan = Plan { selectors, density, unit: 1.0, ..Plan::default() };
    let report = run_plan(&mut part, &plan, false)?;
    part.write(output)?;
    let q = report.mesh.unwrap_or_default();
    println!("{} tets, dihedral {:.1}° .. {:.1}°, wrote {}", q.tets, q.min_dihedral_deg, q.max_dihedral_deg, output.display());
    Ok(part)
}

/// `step_to_mesh INPUT OUTPUT`.
pub fn main() -> Result<(), PipelineError> {
    let args: Vec<String> = std::env::args().collect();
    let input = args.get(1).map_or("cad_fixtures/bracket.step", String::as_str);
    let output = args.get(2).map_or("target/bracket.msh", String::as_str);
    step_to_mesh(Path::new(input), Path::new(output)).map(|_| ())
}
