//! What a Nastran deck of an [`FeModel`] will hold, decided and checked before a byte is
//! written: the solution sequence, a property id per element, the materials written, and per
//! step its constrained dofs, loads and set ids. Every model a deck cannot represent is
//! refused here, with a message naming the step, material, element or set.

use super::field::MAX_ID;
use crate::fe::{Analysis, Bc, ElementFace, FeModel, Load, Material, Step};
use glam::DVec3;
use std::collections::{BTreeMap, BTreeSet};

/// Forces below this fraction of a step's largest are round-off of a zero and not written.
pub(super) const ROUND_OFF: f64 = 1e-12;

/// One `PSOLID`.
pub(super) struct Psolid<'a> {
    /// Its id: the section's index + 1.
    pub pid: u64,
    /// The material's id.
    pub mid: u64,
    /// The section's element set.
    pub element_set: &'a str,
    /// The section's material.
    pub material: &'a str,
}

/// One step's cards.
pub(super) struct StepPlan<'a> {
    /// The step.
    pub step: &'a Step,
    /// Its subcase (1-based).
    pub k: u64,
    /// Fixed dofs per node: bit `d - 1` for dof `d`.
    pub fixed: BTreeMap<u32, u8>,
    /// Prescribed non-zero displacements per node and dof.
    pub displaced: BTreeMap<(u32, u8), f64>,
    /// Forces per node, summed over the step's nodal loads, those under [`ROUND_OFF`] of the
    /// largest left out.
    pub forces: BTreeMap<u32, DVec3>,
    /// Non-zero pressures per element face, summed over the step's pressure loads.
    pub pressures: BTreeMap<ElementFace, f64>,
    /// The step's gravity, summed (zero when none).
    pub gravity: DVec3,
    /// The `SPC` set, when anything is constrained.
    pub spc_sid: Option<u64>,
    /// The set of `FORCE` and `PLOAD4`, when there are any.
    pub simple_sid: Option<u64>,
    /// The `GRAV` set, when there is gravity.
    pub grav_sid: Option<u64>,
    /// The `LOAD` combining the two, when both exist.
    pub combined_sid: Option<u64>,
}

impl StepPlan<'_> {
    /// The set the case control's `LOAD` selects.
    pub fn case_load(&self) -> Option<u64> {
        self.combined_sid.or(self.simple_sid).or(self.grav_sid)
    }
}

/// What a Nastran deck (SOL 101 or 103) cannot represent; each names the step, material,
/// element, grid or set. The writer reports it as [`crate::io::IoError::NotRepresentable`].
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub(super) enum Unrepresentable {
    /// More items than Nastran's 8-digit ids number.
    #[error("{count} {what}: Nastran ids stop at {MAX_ID}")]
    TooManyIds {
        /// How many.
        count: u64,
        /// Of what.
        what: &'static str,
    },
    /// A tie (glued contact), which the writer cannot express yet.
    #[error(
        "tie {tie} (and {more} more) joins solids whose meshes do not share nodes; the Nastran writer has no glued contact (BSURFS/BCTABLE) yet: write a CalculiX deck (.inp), or mesh the assembly conforming"
    )]
    Tie {
        /// The first tie's name.
        tie: String,
        /// How many others.
        more: usize,
    },
    /// An element in the sets of two sections.
    #[error("element {element} is in the element sets of two sections ({first} and {second}): give each element one section")]
    TwoSections {
        /// The element, 1-based.
        element: u32,
        /// The first section's element set.
        first: String,
        /// The second's.
        second: String,
    },
    /// An element no section covers.
    #[error("element {element} (and {more} more) has no section: add a section (a material on an element set) that covers every element")]
    NoSection {
        /// The first such element, 1-based.
        element: usize,
        /// How many others.
        more: usize,
    },
    /// A material used by a section lacks an elastic constant.
    #[error("material {material} lacks {property}: MAT1 needs Young's modulus and Poisson's ratio")]
    MaterialLacks {
        /// The material.
        material: String,
        /// The constant missing.
        property: &'static str,
    },
    /// A material without the density a frequency step or gravity needs.
    #[error("material {material} has no density: {needed_by} needs one")]
    NoDensity {
        /// The material.
        material: String,
        /// What needs it.
        needed_by: &'static str,
    },
    /// A frequency step asking for no mode.
    #[error("step {step}: a frequency step must ask for at least one mode")]
    NoModes {
        /// The step.
        step: String,
    },
    /// A heat transfer step.
    #[error("step {step} is a heat transfer step: SOL 101 and 103 are structural (write it to a CalculiX deck)")]
    HeatStep {
        /// The step.
        step: String,
    },
    /// Steps that need two solution sequences.
    #[error("steps {first} (SOL {first_sol}) and {second} (SOL {second_sol}) need two solution sequences: one Nastran deck holds one; write them to two decks")]
    TwoSolutions {
        /// The first step.
        first: String,
        /// Its solution sequence.
        first_sol: u32,
        /// The step that needs the other.
        second: String,
        /// Its solution sequence.
        second_sol: u32,
    },
    /// A displacement of a degree of freedom other than 1 to 3.
    #[error("step {step}: displacement of dof {dof} on {nodes} (1 to 3)")]
    Dof {
        /// The step.
        step: String,
        /// The degree of freedom.
        dof: u8,
        /// The node set.
        nodes: String,
    },
    /// A prescribed displacement in a frequency step.
    #[error("step {step}: a frequency step (SOL 103) cannot prescribe a displacement of {value:e} on {nodes}")]
    FrequencyDisplacement {
        /// The step.
        step: String,
        /// The displacement.
        value: f64,
        /// The node set.
        nodes: String,
    },
    /// A grid displaced by two different values.
    #[error("step {step}: grid {grid} dof {dof} is displaced by both {first:e} and {second:e}")]
    DisplacedTwice {
        /// The step.
        step: String,
        /// The grid, 1-based.
        grid: u32,
        /// The degree of freedom.
        dof: u8,
        /// One value.
        first: f64,
        /// The other.
        second: f64,
    },
    /// A temperature boundary condition.
    #[error("step {step}: a temperature on {nodes} is not a structural boundary condition of SOL 101/103")]
    Temperature {
        /// The step.
        step: String,
        /// The node set.
        nodes: String,
    },
    /// A grid both held and displaced.
    #[error("step {step}: grid {grid} dof {dof} is both held at 0 and displaced by {value:e}")]
    HeldAndDisplaced {
        /// The step.
        step: String,
        /// The grid, 1-based.
        grid: u32,
        /// The degree of freedom.
        dof: u8,
        /// The displacement.
        value: f64,
    },
    /// Loads in a frequency step.
    #[error("step {step}: a frequency step (SOL 103) applies no loads; remove its loads or make it a static step")]
    FrequencyLoads {
        /// The step.
        step: String,
    },
    /// Gravity on part of the model.
    #[error("step {step}: gravity on element set {elements} ({covered} of {total} elements): Nastran's GRAV acts on the whole model")]
    PartialGravity {
        /// The step.
        step: String,
        /// The element set.
        elements: String,
        /// Elements it covers.
        covered: usize,
        /// Elements of the model.
        total: usize,
    },
    /// A heat flux or film load.
    #[error("step {step}: a heat flux or film on {surface} is not a structural load of SOL 101/103")]
    HeatLoad {
        /// The step.
        step: String,
        /// The surface.
        surface: String,
    },
    /// A load or displacement that is not finite.
    #[error("step {step}: a load or displacement is not a finite number")]
    NotFinite {
        /// The step.
        step: String,
    },
}

/// The deck decided.
pub(super) struct Plan<'a> {
    /// 101 or 103.
    pub sol: u32,
    /// Each element's property id.
    pub pids: Vec<u32>,
    /// One per section.
    pub psolids: Vec<Psolid<'a>>,
    /// Every material, name order: its name, its id when a section uses it (else not written).
    pub materials: Vec<(&'a str, Option<u64>, &'a Material)>,
    /// One per step.
    pub steps: Vec<StepPlan<'a>>,
}

/// Decides the deck of `m` (which passed [`FeModel::validate`]).
///
/// # Errors
/// [`Unrepresentable`]: what the deck cannot represent, naming the item.
pub(super) fn plan(m: &FeModel) -> Result<Plan<'_>, Unrepresentable> {
    let ne = m.element_count();
    let n_steps = m.steps.len() as u64;
    for (what, count) in [("grids", m.nodes.len() as u64), ("elements", ne as u64), ("sections", m.sections.len() as u64), ("materials", m.materials.len() as u64), ("load set ids (3 per step)", 3 * n_steps)] {
        if count > MAX_ID {
            return Err(Unrepresentable::TooManyIds { count, what });
        }
    }
    if let Some(t) = m.ties.first() {
        return Err(Unrepresentable::Tie { tie: t.name.clone(), more: m.ties.len() - 1 });
    }
    let sol = solution(&m.steps)?;
    // a property per element, from the sections
    let mut pids = vec![0u32; ne];
    for (i, s) in m.sections.iter().enumerate() {
        let pid = i as u32 + 1;
        for &e in &m.element_sets[&s.element_set] {
            let old = &mut pids[e as usize];
            if *old != 0 && *old != pid {
                let other = &m.sections[*old as usize - 1].element_set;
                return Err(Unrepresentable::TwoSections { element: e + 1, first: other.clone(), second: s.element_set.clone() });
            }
            *old = pid;
        }
    }
    if let Some(e) = pids.iter().position(|&p| p == 0) {
        let n = pids.iter().filter(|&&p| p == 0).count();
        return Err(Unrepresentable::NoSection { element: e + 1, more: n - 1 });
    }
    let used: BTreeSet<&str> = m.sections.iter().map(|s| s.material.as_str()).collect();
    let density_for = if sol == 103 {
        Some("a frequency step")
    } else {
        m.steps.iter().any(|s| s.loads.iter().any(|l| matches!(l, Load::Gravity { .. }))).then_some("gravity")
    };
    let mut materials = Vec::new();
    let mut mids = BTreeMap::new();
    for (i, (name, mat)) in m.materials.iter().enumerate() {
        let mid = i as u64 + 1;
        let is_used = used.contains(name.as_str());
        if is_used {
            if mat.young.is_none() || mat.poisson.is_none() {
                return Err(Unrepresentable::MaterialLacks { material: name.clone(), property: if mat.young.is_none() { "Young's modulus" } else { "Poisson's ratio" } });
            }
            if let Some(why) = density_for.filter(|_| !mat.density.is_some_and(|d| d > 0.0)) {
                return Err(Unrepresentable::NoDensity { material: name.clone(), needed_by: why });
            }
            mids.insert(name.as_str(), mid);
        }
        materials.push((name.as_str(), is_used.then_some(mid), mat));
    }
    let psolids = m.sections.iter().enumerate().map(|(i, s)| Psolid { pid: i as u64 + 1, mid: mids[s.material.as_str()], element_set: &s.element_set, material: &s.material }).collect();
    let steps = m.steps.iter().enumerate().map(|(i, step)| step_plan(m, step, i as u64 + 1, n_steps)).collect::<Result<_, _>>()?;
    Ok(Plan { sol, pids, psolids, materials, steps })
}

/// The solution sequence every step fits: 101 for static, 103 for frequency steps.
fn solution(steps: &[Step]) -> Result<u32, Unrepresentable> {
    let mut sol: Option<(u32, &str)> = None;
    for s in steps {
        let this = match s.analysis {
            Analysis::Static => 101,
            Analysis::Frequency { modes } => {
                if modes == 0 {
                    return Err(Unrepresentable::NoModes { step: s.name.clone() });
                }
                103
            }
            Analysis::Heat => return Err(Unrepresentable::HeatStep { step: s.name.clone() }),
        };
        match sol {
            Some((other, first)) if other != this => {
                return Err(Unrepresentable::TwoSolutions { first: first.to_owned(), first_sol: other, second: s.name.clone(), second_sol: this });
            }
            None => sol = Some((this, &s.name)),
            _ => {}
        }
    }
    Ok(sol.map_or(101, |(s, _)| s))
}

/// Step `k` of `n`: its dofs, loads and set ids.
fn step_plan<'a>(m: &'a FeModel, step: &'a Step, k: u64, n: u64) -> Result<StepPlan<'a>, Unrepresentable> {
    let name = &step.name;
    let frequency = matches!(step.analysis, Analysis::Frequency { .. });
    let mut fixed: BTreeMap<u32, u8> = BTreeMap::new();
    let mut displaced: BTreeMap<(u32, u8), f64> = BTreeMap::new();
    for bc in &step.bcs {
        match bc {
            Bc::Fixed { nodes, dofs } => {
                let mask = dofs.iter().fold(0u8, |a, d| a | 1 << (d - 1));
                for &v in &m.node_sets[nodes] {
                    *fixed.entry(v).or_default() |= mask;
                }
            }
            Bc::Displacement { nodes, dof, value } => {
                if !(1..=3).contains(dof) {
                    return Err(Unrepresentable::Dof { step: name.clone(), dof: *dof, nodes: nodes.clone() });
                }
                if *value == 0.0 {
                    for &v in &m.node_sets[nodes] {
                        *fixed.entry(v).or_default() |= 1 << (dof - 1);
                    }
                    continue;
                }
                if frequency {
                    return Err(Unrepresentable::FrequencyDisplacement { step: name.clone(), value: *value, nodes: nodes.clone() });
                }
                for &v in &m.node_sets[nodes] {
                    if let Some(old) = displaced.insert((v, *dof), *value).filter(|old| old != value) {
                        return Err(Unrepresentable::DisplacedTwice { step: name.clone(), grid: v + 1, dof: *dof, first: old, second: *value });
                    }
                }
            }
            Bc::Temperature { nodes, .. } => return Err(Unrepresentable::Temperature { step: name.clone(), nodes: nodes.clone() }),
        }
    }
    if let Some(((v, d), value)) = displaced.iter().find(|((v, d), _)| fixed.get(v).is_some_and(|m| m & 1 << (d - 1) != 0)) {
        return Err(Unrepresentable::HeldAndDisplaced { step: name.clone(), grid: v + 1, dof: *d, value: *value });
    }
    let mut forces: BTreeMap<u32, DVec3> = BTreeMap::new();
    let mut pressures: BTreeMap<ElementFace, f64> = BTreeMap::new();
    let mut gravity = DVec3::ZERO;
    if frequency && !step.loads.is_empty() {
        return Err(Unrepresentable::FrequencyLoads { step: name.clone() });
    }
    for load in &step.loads {
        match load {
            Load::Nodal { forces: f, .. } => {
                for &(v, f) in f {
                    *forces.entry(v).or_default() += f;
                }
            }
            Load::Pressure { surface, value } => {
                for f in &m.surfaces[surface] {
                    *pressures.entry(*f).or_default() += value;
                }
            }
            Load::Gravity { elements, acceleration } => {
                let covered: BTreeSet<u32> = m.element_sets[elements].iter().copied().collect();
                if covered.len() != m.element_count() {
                    return Err(Unrepresentable::PartialGravity { step: name.clone(), elements: elements.clone(), covered: covered.len(), total: m.element_count() });
                }
                gravity += *acceleration;
            }
            Load::HeatFlux { surface, .. } | Load::Film { surface, .. } => {
                return Err(Unrepresentable::HeatLoad { step: name.clone(), surface: surface.clone() });
            }
        }
    }
    // a flat 6-node face's corners get zero up to round-off (1e-14 of the mid nodes' share):
    // such forces are noise, not loads
    let largest = forces.values().fold(0.0f64, |a, f| a.max(f.length()));
    forces.retain(|_, f| f.length() > ROUND_OFF * largest);
    pressures.retain(|_, p| *p != 0.0);
    if !forces.values().all(|f| f.is_finite()) || !pressures.values().all(|p| p.is_finite()) || !gravity.is_finite() || !displaced.values().all(|d| d.is_finite()) {
        return Err(Unrepresentable::NotFinite { step: name.clone() });
    }
    let spc_sid = (!fixed.is_empty() || !displaced.is_empty()).then_some(k);
    let simple_sid = (!forces.is_empty() || !pressures.is_empty()).then_some(k);
    let grav_sid = (gravity.length() > 0.0).then_some(n + k);
    let combined_sid = (simple_sid.is_some() && grav_sid.is_some()).then_some(2 * n + k);
    Ok(StepPlan { step, k, fixed, displaced, forces, pressures, gravity, spc_sid, simple_sid, grav_sid, combined_sid })
}
