//! What to do with a part: the selectors, the density, the meshing method and its options,
//! and the requirements a run checks ([`Plan`]). [`super::run`] carries a plan out;
//! [`super::summary`] checks its requirements.

use super::part::{MESH_MAX_ANGLE_DEG, Part};
use crate::attributes::{Density, Selector};
use crate::mesh3d::mesher::MeshOptions;
use crate::tessellate::TessellateOptions;
use std::collections::BTreeMap;

/// What to do with a part.
#[derive(Clone, Debug, Default)]
pub struct Plan {
    /// Named selectors.
    pub selectors: BTreeMap<String, Selector>,
    /// The density (lengths in `unit`s).
    pub density: Density,
    /// Part units per density unit.
    pub unit: f64,
    /// The volume meshing method.
    pub method: super::job::Method,
    /// Volume mesher options (Delaunay).
    pub mesh: MeshOptions,
    /// Octree mesher options (`method` octree).
    pub octree: crate::mesh3d::octree::OctreeOptions,
    /// Smallest dihedral angle every tet must have (degrees), or the run fails. `None`: the
    /// run fails on a tet under 1° that touches no input angle under 1°.
    pub require_min_dihedral: Option<f64>,
    /// Largest radius-edge ratio every tet must have, or the run fails.
    pub require_max_radius_edge: Option<f64>,
    /// Largest relative difference between the mesh's volume and the CAD solids' (a CAD part),
    /// or the run fails.
    pub require_volume_error: Option<f64>,
    /// Where the options were given: the warnings name the option that makes one an error.
    pub interface: Interface,
}

impl Plan {
    /// The tessellation options of a CAD part: the density's deviation (default
    /// [`Part::mesh_deviation`]) and at least 8 segments per circle.
    pub fn tessellate_options(&self, part: &Part) -> TessellateOptions {
        // the deviation and the sizes as asked: no finer chords on solids that lose volume
        // (on a slender part at a coarse size they made needles and millions of tets); the
        // mesh summary says what a solid loses, and `--require-volume-error` demands less
        let deviation = self.density.deviation.map_or_else(|| part.mesh_deviation(), |d| d.0);
        TessellateOptions::default().with_chord_relative(deviation).with_max_angle_deg(MESH_MAX_ANGLE_DEG).with_volume_relative(0.0)
    }
}

/// Where a run's options were given: a warning names the option that makes it an error as
/// the user writes it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Interface {
    /// Command-line options (`fepre mesh`, a library caller).
    #[default]
    CommandLine,
    /// A job file (`fepre run`, `fepre solve`).
    JobFile,
}

impl Interface {
    /// The option that sets the smallest dihedral angle required.
    pub fn require_min_dihedral(self) -> &'static str {
        match self {
            Interface::CommandLine => "--require-min-dihedral D",
            Interface::JobFile => "[require] min_dihedral",
        }
    }
}
