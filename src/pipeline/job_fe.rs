//! The FE keys of a job file: `[model]` (element type, ties), `[materials.NAME]`, `[[section]]`
//! (a material on a solid), `[[step]]` (procedure, boundary conditions and loads on
//! selectors) and `[solve]` (what `fepre solve` writes). Values are checked while they are
//! read, so errors name the key, its line and column; cross-references (a selector or
//! material that is not defined) are checked by [`super::fe_model`].

use crate::attributes::values::{NonNegative, Positive};
use serde::Deserialize;
use std::path::PathBuf;
use toml::Spanned;

/// The element type.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
pub enum ElementChoice {
    /// Linear tets.
    #[serde(rename = "C3D4", alias = "c3d4", alias = "tet4")]
    C3D4,
    /// Quadratic tets, mid nodes on the CAD geometry (the default).
    #[default]
    #[serde(rename = "C3D10", alias = "c3d10", alias = "tet10")]
    C3D10,
}

/// `[model]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSection {
    /// `"C3D10"` (default) or `"C3D4"`.
    #[serde(default)]
    pub element: ElementChoice,
    /// Tie the solids of an assembly where they touch without sharing nodes (`*TIE`; default
    /// true). `tie = false` leaves them untied, as `contacts = "none"` does.
    #[serde(default = "yes")]
    pub tie: bool,
    /// How the solids of an assembly hold together where they touch (default
    /// `"conforming"`).
    #[serde(default)]
    pub contacts: Contacts,
}

impl Default for ModelSection {
    fn default() -> Self {
        ModelSection { element: ElementChoice::default(), tie: true, contacts: Contacts::default() }
    }
}

impl ModelSection {
    /// True where the solids are imprinted on each other before meshing.
    pub fn imprint(&self) -> bool {
        self.contacts == Contacts::Conforming
    }

    /// True where contacts without shared nodes are tied.
    pub fn ties(&self) -> bool {
        self.tie && self.contacts != Contacts::None
    }
}

/// `[model] contacts`: how touching solids of an assembly are joined.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Contacts {
    /// Imprinted on each other where their faces in contact lie in one plane, so that the
    /// mesh shares nodes there (gmsh's fragment and coherence); tied where it does not.
    #[default]
    Conforming,
    /// Meshed on their own and tied (`*TIE`) wherever they touch.
    Tie,
    /// Meshed on their own and not joined (each solid free, as separate parts).
    None,
}

fn yes() -> bool {
    true
}

/// A Poisson's ratio: finite, in (-1, 0.5).
#[derive(Copy, Clone, Debug, PartialEq, Deserialize)]
#[serde(try_from = "f64")]
pub struct Poisson(pub f64);

impl TryFrom<f64> for Poisson {
    type Error = String;
    fn try_from(x: f64) -> Result<Self, String> {
        if x.is_finite() && x > -1.0 && x < 0.5 { Ok(Poisson(x)) } else { Err(format!("{x} must be in (-1, 0.5)")) }
    }
}

/// `[materials.NAME]`: an isotropic material in the job's consistent units.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// Young's modulus.
    pub young: Option<Positive>,
    /// Poisson's ratio.
    pub poisson: Option<Poisson>,
    /// Mass density.
    pub density: Option<Positive>,
    /// Coefficient of thermal expansion.
    pub expansion: Option<NonNegative>,
    /// Thermal conductivity.
    pub conductivity: Option<Positive>,
    /// Specific heat.
    pub specific_heat: Option<Positive>,
}

/// Which solid: its name, or its number (1 for the first).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum SolidRef {
    /// The solid's number, from 1.
    Number(u32),
    /// The solid's name.
    Name(String),
}

/// `[[section]]`: a material on one solid, or on every solid no other section names.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionSpec {
    /// The material (a key of `[materials]`).
    pub material: Spanned<String>,
    /// The solid; without it, every solid no other section names.
    pub solid: Option<Spanned<SolidRef>>,
}

/// The procedure of a step.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StepKind {
    /// Linear static.
    #[default]
    Static,
    /// Natural frequencies.
    Frequency,
    /// Steady-state heat transfer.
    Heat,
}

/// A degree of freedom, 1 to 3.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Deserialize)]
#[serde(try_from = "i64")]
pub struct Dof(pub u8);

impl TryFrom<i64> for Dof {
    type Error = String;
    fn try_from(x: i64) -> Result<Self, String> {
        if (1..=3).contains(&x) { Ok(Dof(x as u8)) } else { Err(format!("degree of freedom {x} must be 1, 2 or 3 (x, y, z)")) }
    }
}

/// `fixed = [{ faces = "SEL", dofs = [1, 2, 3] }]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FixedSpec {
    /// The selector.
    pub faces: Spanned<String>,
    /// The degrees of freedom held (default all three).
    pub dofs: Option<Vec<Dof>>,
}

/// `displacement = [{ faces = "SEL", dof = 1, value = 0.1 }]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DisplacementSpec {
    /// The selector.
    pub faces: Spanned<String>,
    /// The degree of freedom.
    pub dof: Dof,
    /// The displacement.
    pub value: f64,
}

/// `force = [{ faces = "SEL", total = [0, 0, -1000] }]`: a total force spread as a uniform
/// traction.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceSpec {
    /// The selector.
    pub faces: Spanned<String>,
    /// The total force vector.
    pub total: [f64; 3],
}

/// `pressure = [{ faces = "SEL", value = 10 }]`: positive pushes into the solid.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PressureSpec {
    /// The selector.
    pub faces: Spanned<String>,
    /// The pressure.
    pub value: f64,
}

/// `gravity = [{ acceleration = [0, 0, -9810] }]`, on every solid.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GravitySpec {
    /// The acceleration vector.
    pub acceleration: [f64; 3],
}

/// `temperature = [{ faces = "SEL", value = 100 }]`, or `heat_flux = [...]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ValueOnFaces {
    /// The selector.
    pub faces: Spanned<String>,
    /// The value.
    pub value: f64,
}

/// `film = [{ faces = "SEL", coefficient = 1e-2, sink = 20 }]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FilmSpec {
    /// The selector.
    pub faces: Spanned<String>,
    /// The film coefficient.
    pub coefficient: Positive,
    /// The sink temperature.
    pub sink: f64,
}

/// `[[step]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepSpec {
    /// Its name (default `step-1`, `step-2`, ...).
    pub name: Option<String>,
    /// `static` (default), `frequency` or `heat`.
    #[serde(rename = "type", default)]
    pub kind: StepKind,
    /// Modes of a frequency step (default 10).
    pub modes: Option<Spanned<u32>>,
    /// Held degrees of freedom.
    #[serde(default)]
    pub fixed: Vec<FixedSpec>,
    /// Prescribed displacements.
    #[serde(default)]
    pub displacement: Vec<DisplacementSpec>,
    /// Total forces.
    #[serde(default)]
    pub force: Vec<ForceSpec>,
    /// Pressures.
    #[serde(default)]
    pub pressure: Vec<PressureSpec>,
    /// Gravity.
    #[serde(default)]
    pub gravity: Vec<GravitySpec>,
    /// Prescribed temperatures (heat).
    #[serde(default)]
    pub temperature: Vec<ValueOnFaces>,
    /// Heat fluxes into faces (heat).
    #[serde(default)]
    pub heat_flux: Vec<ValueOnFaces>,
    /// Convection (heat).
    #[serde(default)]
    pub film: Vec<FilmSpec>,
}

/// `[solve]`: what `fepre solve` writes besides the deck.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolveSection {
    /// The results for ParaView (default: the deck's name with `_results.vtu`).
    pub results: Option<Spanned<PathBuf>>,
    /// The JSON summary (default: the deck's name with `_results.json`).
    pub summary: Option<Spanned<PathBuf>>,
}
