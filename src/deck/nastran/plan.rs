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
/// What the deck cannot represent, as a sentence naming the item.
pub(super) fn plan(m: &FeModel) -> Result<Plan<'_>, String> {
    let ne = m.element_count();
    let n_steps = m.steps.len() as u64;
    for (what, count) in [("grids", m.nodes.len() as u64), ("elements", ne as u64), ("sections", m.sections.len() as u64), ("materials", m.materials.len() as u64), ("load set ids (3 per step)", 3 * n_steps)] {
        if count > MAX_ID {
            return Err(format!("{count} {what}: Nastran ids stop at {MAX_ID}"));
        }
    }
    if let Some(t) = m.ties.first() {
        return Err(format!("tie {} (and {} more) joins solids whose meshes do not share nodes; the Nastran writer has no glued contact (BSURFS/BCTABLE) yet: write a CalculiX deck (.inp), or mesh the assembly conforming", t.name, m.ties.len() - 1));
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
                return Err(format!("element {} is in the element sets of two sections ({other} and {}): give each element one section", e + 1, s.element_set));
            }
            *old = pid;
        }
    }
    if let Some(e) = pids.iter().position(|&p| p == 0) {
        let n = pids.iter().filter(|&&p| p == 0).count();
        return Err(format!("element {} (and {} more) has no section: add a section (a material on an element set) that covers every element", e + 1, n - 1));
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
                return Err(format!("material {name} lacks {}: MAT1 needs Young's modulus and Poisson's ratio", if mat.young.is_none() { "Young's modulus" } else { "Poisson's ratio" }));
            }
            if let Some(why) = density_for.filter(|_| !mat.density.is_some_and(|d| d > 0.0)) {
                return Err(format!("material {name} has no density: {why} needs one"));
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
fn solution(steps: &[Step]) -> Result<u32, String> {
    let mut sol: Option<(u32, &str)> = None;
    for s in steps {
        let this = match s.analysis {
            Analysis::Static => 101,
            Analysis::Frequency { modes } => {
                if modes == 0 {
                    return Err(format!("step {}: a frequency step must ask for at least one mode", s.name));
                }
                103
            }
            Analysis::Heat => return Err(format!("step {} is a heat transfer step: SOL 101 and 103 are structural (write it to a CalculiX deck)", s.name)),
        };
        match sol {
            Some((other, first)) if other != this => {
                return Err(format!("steps {first} (SOL {other}) and {} (SOL {this}) need two solution sequences: one Nastran deck holds one; write them to two decks", s.name));
            }
            None => sol = Some((this, &s.name)),
            _ => {}
        }
    }
    Ok(sol.map_or(101, |(s, _)| s))
}

/// Step `k` of `n`: its dofs, loads and set ids.
fn step_plan<'a>(m: &'a FeModel, step: &'a Step, k: u64, n: u64) -> Result<StepPlan<'a>, String> {
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
                    return Err(format!("step {name}: displacement of dof {dof} on {nodes} (1 to 3)"));
                }
                if *value == 0.0 {
                    for &v in &m.node_sets[nodes] {
                        *fixed.entry(v).or_default() |= 1 << (dof - 1);
                    }
                    continue;
                }
                if frequency {
                    return Err(format!("step {name}: a frequency step (SOL 103) cannot prescribe a displacement of {value:e} on {nodes}"));
                }
                for &v in &m.node_sets[nodes] {
                    if let Some(old) = displaced.insert((v, *dof), *value).filter(|old| old != value) {
                        return Err(format!("step {name}: grid {} dof {dof} is displaced by both {old:e} and {value:e}", v + 1));
                    }
                }
            }
            Bc::Temperature { nodes, .. } => return Err(format!("step {name}: a temperature on {nodes} is not a structural boundary condition of SOL 101/103")),
        }
    }
    if let Some(((v, d), value)) = displaced.iter().find(|((v, d), _)| fixed.get(v).is_some_and(|m| m & 1 << (d - 1) != 0)) {
        return Err(format!("step {name}: grid {} dof {d} is both held at 0 and displaced by {value:e}", v + 1));
    }
    let mut forces: BTreeMap<u32, DVec3> = BTreeMap::new();
    let mut pressures: BTreeMap<ElementFace, f64> = BTreeMap::new();
    let mut gravity = DVec3::ZERO;
    if frequency && !step.loads.is_empty() {
        return Err(format!("step {name}: a frequency step (SOL 103) applies no loads; remove its loads or make it a static step"));
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
                    return Err(format!("step {name}: gravity on element set {elements} ({} of {} elements): Nastran's GRAV acts on the whole model", covered.len(), m.element_count()));
                }
                gravity += *acceleration;
            }
            Load::HeatFlux { surface, .. } | Load::Film { surface, .. } => {
                return Err(format!("step {name}: a heat flux or film on {surface} is not a structural load of SOL 101/103"));
            }
        }
    }
    // a flat 6-node face's corners get zero up to round-off (1e-14 of the mid nodes' share):
    // such forces are noise, not loads
    let largest = forces.values().fold(0.0f64, |a, f| a.max(f.length()));
    forces.retain(|_, f| f.length() > ROUND_OFF * largest);
    pressures.retain(|_, p| *p != 0.0);
    if !forces.values().all(|f| f.is_finite()) || !pressures.values().all(|p| p.is_finite()) || !gravity.is_finite() || !displaced.values().all(|d| d.is_finite()) {
        return Err(format!("step {name}: a load or displacement is not a finite number"));
    }
    let spc_sid = (!fixed.is_empty() || !displaced.is_empty()).then_some(k);
    let simple_sid = (!forces.is_empty() || !pressures.is_empty()).then_some(k);
    let grav_sid = (gravity.length() > 0.0).then_some(n + k);
    let combined_sid = (simple_sid.is_some() && grav_sid.is_some()).then_some(2 * n + k);
    Ok(StepPlan { step, k, fixed, displaced, forces, pressures, gravity, spc_sid, simple_sid, grav_sid, combined_sid })
}
