//! The FE model: nodes, one block of elements, sets, element-face surfaces, ties between
//! surfaces, materials, sections and steps. Indices are 0-based; deck writers add one.

use super::element::ElementKind;
use super::step::{Bc, Load, Step};
use crate::core::RegionId;
use glam::DVec3;
use serde::Serialize;
use std::collections::BTreeMap;

/// One face of one element: the element's index and its Abaqus face (0 for `S1`).
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub struct ElementFace {
    /// The element (0-based).
    pub element: u32,
    /// The face, 0..4 for `S1`..`S4`.
    pub face: u8,
}

/// An isotropic material. Values are in the job's consistent units (for example mm, N, s,
/// tonne: MPa for stresses, tonne/mm³ for densities); fepre converts none of them.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Material {
    /// Young's modulus.
    pub young: Option<f64>,
    /// Poisson's ratio.
    pub poisson: Option<f64>,
    /// Mass density.
    pub density: Option<f64>,
    /// Coefficient of thermal expansion.
    pub expansion: Option<f64>,
    /// Thermal conductivity.
    pub conductivity: Option<f64>,
    /// Specific heat.
    pub specific_heat: Option<f64>,
}

/// A solid section: a material on an element set.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Section {
    /// The element set.
    pub element_set: String,
    /// The material's name.
    pub material: String,
}

/// Two element-face surfaces held together (`*TIE`): each node of the slave surface within
/// `tolerance` of the master surface follows the master surface's displacement there. Ties
/// join solids whose meshes do not share nodes where they touch.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Tie {
    /// The tie's name.
    pub name: String,
    /// The slave (dependent) surface: by convention the finer mesh of the two.
    pub slave: String,
    /// The master (independent) surface: the coarser mesh.
    pub master: String,
    /// Where the two surfaces share nodes (a contact conforming in part), the node set of the
    /// slave surface's nodes less those: the deck ties it, as a node-based slave surface, in
    /// place of `slave` (a node cannot be tied to a face it is a node of).
    pub slave_nodes: Option<String>,
    /// How far, in the deck's length unit, a slave node may lie from the master surface and
    /// still be tied (`POSITION TOLERANCE`).
    pub tolerance: f64,
}

/// What second order did to the mesh.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct CurvingReport {
    /// Mid-edge nodes placed on a CAD face.
    pub on_faces: usize,
    /// Mid-edge nodes placed on a CAD edge (between two faces).
    pub on_edges: usize,
    /// Boundary mid-edge nodes left at the chord's midpoint: no geometry, or the projection
    /// was farther than a quarter of the edge from the chord.
    pub left_straight: usize,
    /// Mid-edge nodes moved back to the chord because curving inverted an element.
    pub straightened: usize,
    /// Elements that needed straightening.
    pub straightened_elements: usize,
    /// The smallest ratio of the Jacobian determinant to the straight element's, over the
    /// check points of every element.
    pub min_jacobian_ratio: f64,
}

/// An FE model.
#[derive(Clone, Debug, Serialize)]
pub struct FeModel {
    /// Node positions, in the deck's length unit.
    pub nodes: Vec<DVec3>,
    /// The element kind of every element.
    pub kind: ElementKind,
    /// Element connectivity, [`ElementKind::nodes`] per element, flat.
    pub elements: Vec<u32>,
    /// The region (solid) of each element.
    pub element_regions: Vec<RegionId>,
    /// Node sets by name.
    pub node_sets: BTreeMap<String, Vec<u32>>,
    /// Element sets by name.
    pub element_sets: BTreeMap<String, Vec<u32>>,
    /// Element-face surfaces by name.
    pub surfaces: BTreeMap<String, Vec<ElementFace>>,
    /// Ties between surfaces.
    pub ties: Vec<Tie>,
    /// Materials by name.
    pub materials: BTreeMap<String, Material>,
    /// Solid sections.
    pub sections: Vec<Section>,
    /// Analysis steps.
    pub steps: Vec<Step>,
    /// What second order did (C3D10).
    pub curving: Option<CurvingReport>,
}

/// Why an [`FeModel`] is inconsistent (a bug of whoever built it, never of user input).
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum FeModelError {
    /// Array lengths disagree.
    #[error("{0}")]
    Length(String),
    /// A node index out of range.
    #[error("{what} refers to node {node}, the model has {nodes}")]
    Node {
        /// Where.
        what: String,
        /// The index.
        node: u32,
        /// The node count.
        nodes: usize,
    },
    /// An element index out of range.
    #[error("{what} refers to element {element}, the model has {elements}")]
    Element {
        /// Where.
        what: String,
        /// The index.
        element: u32,
        /// The element count.
        elements: usize,
    },
    /// An element with a non-positive Jacobian.
    #[error("element {0} is inverted or flat (Jacobian determinant {1:.3e} at a check point)")]
    Inverted(u32, f64),
    /// A name used but not defined, or defined twice, or not valid in a deck.
    #[error("{0}")]
    Name(String),
}

impl FeModel {
    /// The number of elements.
    pub fn element_count(&self) -> usize {
        self.elements.len() / self.kind.nodes()
    }

    /// The nodes of element `e`.
    pub fn element(&self, e: usize) -> &[u32] {
        let n = self.kind.nodes();
        &self.elements[n * e..n * e + n]
    }

    /// The positions of element `e`'s nodes.
    pub fn element_points(&self, e: usize) -> Vec<DVec3> {
        self.element(e).iter().map(|&v| self.nodes[v as usize]).collect()
    }

    /// Checks the model: lengths, indices, every element's Jacobian positive at its check
    /// points (`super::jacobian`), sets and surfaces in range, sections naming defined
    /// materials and sets, ties between two different, defined, non-empty surfaces with a
    /// positive tolerance and unique names, step items naming defined sets and surfaces, names
    /// valid in Abaqus and Nastran decks.
    ///
    /// # Errors
    /// The first violation found.
    pub fn validate(&self) -> Result<(), FeModelError> {
        let n = self.kind.nodes();
        if self.elements.len() % n != 0 {
            return Err(FeModelError::Length(format!("{} element node indices is not a multiple of {n}", self.elements.len())));
        }
        let ne = self.element_count();
        if self.element_regions.len() != ne {
            return Err(FeModelError::Length(format!("{} region tags for {ne} elements", self.element_regions.len())));
        }
        if let Some(p) = self.nodes.iter().position(|p| !p.is_finite()) {
            return Err(FeModelError::Length(format!("node {p} has a coordinate that is not finite")));
        }
        let nn = self.nodes.len();
        for (e, c) in self.elements.chunks(n).enumerate() {
            if let Some(&v) = c.iter().find(|&&v| v as usize >= nn) {
                return Err(FeModelError::Node { what: format!("element {e}"), node: v, nodes: nn });
            }
            let pts: Vec<DVec3> = c.iter().map(|&v| self.nodes[v as usize]).collect();
            let j = super::jacobian::min_jacobian(&pts);
            if !(j > 0.0) {
                return Err(FeModelError::Inverted(e as u32, j));
            }
        }
        for (name, set) in &self.node_sets {
            check_name(name)?;
            if let Some(&v) = set.iter().find(|&&v| v as usize >= nn) {
                return Err(FeModelError::Node { what: format!("node set {name}"), node: v, nodes: nn });
            }
        }
        for (name, set) in &self.element_sets {
            check_name(name)?;
            if let Some(&e) = set.iter().find(|&&e| e as usize >= ne) {
                return Err(FeModelError::Element { what: format!("element set {name}"), element: e, elements: ne });
            }
        }
        for (name, faces) in &self.surfaces {
            check_name(name)?;
            if let Some(f) = faces.iter().find(|f| f.element as usize >= ne || f.face > 3) {
                return Err(FeModelError::Element { what: format!("surface {name} (face S{})", f.face + 1), element: f.element, elements: ne });
            }
        }
        for name in self.materials.keys() {
            check_name(name)?;
        }
        for s in &self.sections {
            if !self.element_sets.contains_key(&s.element_set) {
                return Err(FeModelError::Name(format!("a section names element set {}, which is not defined", s.element_set)));
            }
            if !self.materials.contains_key(&s.material) {
                return Err(FeModelError::Name(format!("a section names material {}, which is not defined", s.material)));
            }
        }
        self.check_ties()?;
        for step in &self.steps {
            self.check_step(step)?;
        }
        Ok(())
    }

    /// Checks that every set and surface `step` names is defined in this model.
    fn check_step(&self, step: &Step) -> Result<(), FeModelError> {
        let node_set = |s: &String| if self.node_sets.contains_key(s) { Ok(()) } else { Err(FeModelError::Name(format!("step {}: node set {s} is not defined", step.name))) };
        let surface = |s: &String| if self.surfaces.contains_key(s) { Ok(()) } else { Err(FeModelError::Name(format!("step {}: surface {s} is not defined", step.name))) };
        for bc in &step.bcs {
            match bc {
                Bc::Fixed { nodes, dofs } => {
                    node_set(nodes)?;
                    if dofs.is_empty() || dofs.iter().any(|d| !(1..=3).contains(d)) {
                        return Err(FeModelError::Name(format!("step {}: fixed dofs {dofs:?} on {nodes} (1 to 3)", step.name)));
                    }
                }
                Bc::Displacement { nodes, .. } | Bc::Temperature { nodes, .. } => node_set(nodes)?,
            }
        }
        for load in &step.loads {
            match load {
                Load::Nodal { forces, .. } => {
                    if let Some(&(v, _)) = forces.iter().find(|(v, _)| *v as usize >= self.nodes.len()) {
                        return Err(FeModelError::Node { what: format!("step {}: a nodal force", step.name), node: v, nodes: self.nodes.len() });
                    }
                }
                Load::Pressure { surface: s, .. } | Load::HeatFlux { surface: s, .. } | Load::Film { surface: s, .. } => surface(s)?,
                Load::Gravity { elements, .. } => {
                    if !self.element_sets.contains_key(elements) {
                        return Err(FeModelError::Name(format!("step {}: element set {elements} is not defined", step.name)));
                    }
                }
            }
        }
        Ok(())
    }

    fn check_ties(&self) -> Result<(), FeModelError> {
        let mut names = std::collections::BTreeSet::new();
        for t in &self.ties {
            check_name(&t.name)?;
            if !names.insert(t.name.to_ascii_uppercase()) {
                return Err(FeModelError::Name(format!("tie {} is defined twice", t.name)));
            }
            for (role, s) in [("slave", &t.slave), ("master", &t.master)] {
                match self.surfaces.get(s) {
                    None => return Err(FeModelError::Name(format!("tie {} names {role} surface {s}, which is not defined", t.name))),
                    Some(f) if f.is_empty() => return Err(FeModelError::Name(format!("tie {} names {role} surface {s}, which is empty", t.name))),
                    Some(_) => {}
                }
            }
            if let Some(n) = &t.slave_nodes {
                match self.node_sets.get(n) {
                    None => return Err(FeModelError::Name(format!("tie {} names slave node set {n}, which is not defined", t.name))),
                    Some(v) if v.is_empty() => return Err(FeModelError::Name(format!("tie {} names slave node set {n}, which is empty", t.name))),
                    Some(_) => {}
                }
            }
            if t.slave == t.master {
                return Err(FeModelError::Name(format!("tie {} ties surface {} to itself", t.name, t.slave)));
            }
            if !(t.tolerance.is_finite() && t.tolerance > 0.0) {
                return Err(FeModelError::Name(format!("tie {} has position tolerance {}, not a positive number", t.name, t.tolerance)));
            }
        }
        Ok(())
    }
}

/// The longest set, surface or material name fepre writes: Abaqus allows 80 characters.
pub const MAX_NAME: usize = 80;

/// A name valid in an Abaqus/CalculiX deck and as a Nastran comment: 1 to 80 characters, a
/// letter first, then letters, digits and underscores.
pub fn check_name(name: &str) -> Result<(), FeModelError> {
    let ok = !name.is_empty()
        && name.len() <= MAX_NAME
        && name.starts_with(|c: char| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if ok { Ok(()) } else { Err(FeModelError::Name(format!("\"{name}\" is not a valid set name (1 to {MAX_NAME} characters: a letter, then letters, digits, underscores)"))) }
}

/// `name` made valid for a deck: characters other than letters, digits and underscores become
/// underscores, a leading non-letter gets `S_` before it, and the result is cut to
/// [`MAX_NAME`] characters. Callers make the results unique.
pub fn deck_name(name: &str) -> String {
    let mut s: String = name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '_' { c } else { '_' }).collect();
    if !s.starts_with(|c: char| c.is_ascii_alphabetic()) {
        s.insert_str(0, "S_");
    }
    s.truncate(MAX_NAME);
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::FaceId;
    use crate::fe::build_model;

    /// Two touching tets with a surface on each touching face, `A` and `B`.
    fn tied() -> FeModel {
        let mesh = crate::io::test_meshes::touching_tets();
        let mut b = build_model(&mesh, &BTreeMap::new(), ElementKind::C3D4, None, 1.0);
        b.add_face_surface(FaceId(10), "A").unwrap();
        b.add_face_surface(FaceId(20), "B").unwrap();
        let mut m = b.model;
        m.ties.push(Tie { name: "TIE1".into(), slave: "B".into(), master: "A".into(), tolerance: 0.01, slave_nodes: None });
        m
    }

    #[test]
    fn validate_checks_ties() {
        tied().validate().unwrap();
        let bad = |f: &dyn Fn(&mut FeModel), word: &str| {
            let mut m = tied();
            f(&mut m);
            let e = m.validate().unwrap_err().to_string();
            assert!(e.contains(word), "{word} expected in: {e}");
        };
        bad(&|m| m.ties[0].master = "NOPE".into(), "master surface NOPE, which is not defined");
        bad(&|m| m.ties[0].slave = "NOPE".into(), "slave surface NOPE, which is not defined");
        bad(&|m| m.ties[0].slave = "A".into(), "to itself");
        bad(&|m| m.ties[0].tolerance = 0.0, "not a positive number");
        bad(&|m| m.ties[0].tolerance = f64::NAN, "not a positive number");
        bad(&|m| m.ties[0].name = "1st".into(), "not a valid set name");
        bad(
            &|m| {
                let t = m.ties[0].clone();
                m.ties.push(Tie { name: "tie1".into(), ..t });
            },
            "defined twice",
        );
        bad(&|m| m.surfaces.get_mut("A").unwrap().clear(), "which is empty");
        bad(&|m| m.ties[0].slave_nodes = Some("NOPE".into()), "slave node set NOPE, which is not defined");
    }
}
