//! The FE model of a job: the part's tet mesh as C3D4 or C3D10 elements (boundary mid nodes
//! on the CAD geometry), a node set and an element-face surface per selector, a tie for each
//! contact of an assembly's solids without shared nodes ([`crate::fe::ties`], unless
//! `[model] tie = false`), the materials and sections, and the steps with their boundary conditions and loads. Everything a solver
//! would refuse, or solve into nonsense, is an error naming the job's key and line: a
//! selector that is not defined, faces between two solids used as a boundary, a solid
//! without a material, a material without what a step needs, a step that leaves a piece
//! free to move.

use crate::fe::ties::{TIE_TOLERANCE_GAPS, TieSummary, tie_contacts};
use super::job::JobFile;
use super::job_fe::{ElementChoice, SolidRef, StepKind, StepSpec};
use super::part::Part;
use super::PipelineError;
use crate::attributes::Groups;
use crate::core::RegionId;
use crate::fe::loads::consistent_forces;
use crate::fe::model::deck_name;
use crate::fe::restraint::free_pieces;
use crate::fe::{Analysis, Bc, BrepGeometry, CurvingReport, ElementKind, FeModel, GroupSets, Load, Material, Section, Step, build_model};
use glam::DVec3;
use serde::Serialize;
use std::collections::BTreeMap;
use toml::Spanned;

/// What the FE model holds, for reports.
#[derive(Clone, Debug, Default, Serialize)]
pub struct FeSummary {
    /// `C3D4` or `C3D10`.
    pub element: String,
    /// Nodes.
    pub nodes: usize,
    /// Elements.
    pub elements: usize,
    /// What second order did.
    pub curving: Option<CurvingReport>,
    /// The sets of each selector.
    pub selectors: BTreeMap<String, GroupSets>,
    /// Each solid's element set and material.
    pub solids: Vec<SolidSummary>,
    /// Steps.
    pub steps: Vec<StepSummary>,
    /// Ties between solids that touch without sharing nodes.
    pub ties: Vec<TieSummary>,
}

/// A solid of the FE model.
#[derive(Clone, Debug, Serialize)]
pub struct SolidSummary {
    /// Its region tag.
    pub region: u32,
    /// Its element set.
    pub element_set: String,
    /// Its material (deck name).
    pub material: Option<String>,
    /// Elements.
    pub elements: usize,
}

/// A step of the FE model.
#[derive(Clone, Debug, Serialize)]
pub struct StepSummary {
    /// Its name.
    pub name: String,
    /// `static`, `frequency` or `heat`.
    pub analysis: String,
    /// The sum of the nodal forces written, per force (selector, vector).
    pub forces: Vec<(String, [f64; 3])>,
}

/// True where the job asks for an FE model: a deck output or a step.
pub fn wants_fe(jf: &JobFile) -> bool {
    !jf.job.step.is_empty() || jf.job.output.iter().any(|o| o.kind() == super::job::OutputKind::Deck)
}

/// Builds the FE model of a meshed `part` as job `jf` describes it; `groups` holds each
/// selector's faces, `unit` the part units per job unit (coordinates are written in job units).
///
/// # Errors
/// [`PipelineError::Job`] naming the key and line of what is wrong (module docs).
pub fn build_fe(jf: &JobFile, part: &Part, groups: &Groups, unit: f64) -> Result<(FeModel, FeSummary), PipelineError> {
    let job = &jf.job;
    let Some(mesh) = part.mesh.as_ref() else {
        return Err(PipelineError::Usage { path: part.path.clone(), problem: crate::pipeline::UsageProblem::NoTetMeshForModel });
    };
    let kind = match job.model.element {
        ElementChoice::C3D4 => ElementKind::C3D4,
        ElementChoice::C3D10 => ElementKind::C3D10,
    };
    let geometry = part.model.as_ref().map(BrepGeometry::new);
    let mut built = build_model(mesh, groups.as_map(), kind, geometry.as_ref().map(|g| g as &dyn crate::fe::BoundaryGeometry), 1.0 / unit);
    let ties = if job.model.ties() { tie_contacts(&mut built, &part.contacts, TIE_TOLERANCE_GAPS * part.gap() / unit) } else { Vec::new() };
    let mut m = built.model;
    // materials, under deck names unique without regard to case
    let mut material_name: BTreeMap<&str, String> = BTreeMap::new();
    for (key, spec) in &job.materials {
        let name = deck_name(key).to_ascii_uppercase();
        if material_name.values().any(|n| *n == name) {
            return Err(jf.error_at(spec.span().start, format!("material `{key}`: its deck name {name} is taken by another material (names are read without regard to case)")));
        }
        let s = spec.get_ref();
        m.materials.insert(
            name.clone(),
            Material {
                young: s.young.map(|x| x.get()),
                poisson: s.poisson.map(|x| x.0),
                density: s.density.map(|x| x.get()),
                expansion: s.expansion.map(|x| x.get()),
                conductivity: s.conductivity.map(|x| x.get()),
                specific_heat: s.specific_heat.map(|x| x.get()),
            },
        );
        material_name.insert(key.as_str(), name);
    }
    // sections: each region its material
    let regions: Vec<(RegionId, String)> = built.regions.iter().map(|(r, s)| (*r, s.clone())).collect();
    let mut material_of: BTreeMap<RegionId, (String, usize)> = BTreeMap::new(); // material, section index
    let mut default: Option<(String, usize)> = None;
    for (k, sec) in job.section.iter().enumerate() {
        let Some(mat) = material_name.get(sec.material.get_ref().as_str()) else {
            let known: Vec<&str> = material_name.keys().copied().collect();
            return Err(jf.error_at(sec.material.span().start, format!("key `material`: `{}` is not defined under [materials] (defined: {})", sec.material.get_ref(), list_or_none(&known))));
        };
        match &sec.solid {
            None => {
                if default.is_some() {
                    return Err(jf.error_at(sec.material.span().start, "key `section`: a second section without `solid`; only one may apply to the solids no other section names".into()));
                }
                default = Some((mat.clone(), k));
            }
            Some(solid) => {
                let region = find_region(&regions, mesh, solid.get_ref()).ok_or_else(|| {
                    let names: Vec<String> = regions.iter().enumerate().map(|(i, (r, s))| format!("{} = {}", i + 1, mesh.region_names.get(*r).unwrap_or(s))).collect();
                    jf.error_at(solid.span().start, format!("key `solid`: no solid {} (solids: {})", show_solid(solid.get_ref()), names.join(", ")))
                })?;
                if material_of.insert(region, (mat.clone(), k)).is_some() {
                    return Err(jf.error_at(solid.span().start, format!("key `solid`: solid {} has a section already", show_solid(solid.get_ref()))));
                }
            }
        }
    }
    let mut solids = Vec::new();
    for (r, set) in &regions {
        let mat = material_of.get(r).or(default.as_ref()).map(|(m, _)| m.clone());
        if let Some(mat) = &mat {
            m.sections.push(Section { element_set: set.clone(), material: mat.clone() });
        } else if !job.step.is_empty() {
            let at = job.step[0].span().start;
            return Err(jf.error_at(at, format!("solid {} ({set}) has no material: add a [[section]] with `material` (and `solid` to pick it)", mesh.region_names.get(*r).map_or_else(|| format!("{}", r.0), str::to_string))));
        }
        solids.push(SolidSummary { region: r.0, element_set: set.clone(), material: mat, elements: m.element_sets[set].len() });
    }
    // steps
    let mut steps = Vec::new();
    for (k, spec) in job.step.iter().enumerate() {
        let (step, summary) = build_step(jf, &m, &built.groups, groups, spec, k)?;
        check_materials(jf, &m, spec, &step)?;
        let free = free_pieces(&m, &step);
        if let Some(f) = free.first() {
            let p = m.nodes[f.node as usize];
            let what = if step.analysis == Analysis::Heat { "its temperature level is free: add a `temperature` or a `film`".to_string() } else { format!("{} rigid-body motion(s) are free: hold more degrees of freedom with `fixed` or `displacement`", f.free_modes) };
            return Err(jf.error_at(spec.span().start, format!("step `{}` is singular: a piece of {} elements (node {} at {:.4} {:.4} {:.4}): {what}", step.name, f.elements, f.node + 1, p.x, p.y, p.z)));
        }
        steps.push(summary);
        m.steps.push(step);
    }
    m.validate().map_err(|e| PipelineError::Usage { path: part.path.clone(), problem: crate::pipeline::UsageProblem::InconsistentModel { why: e.to_string() } })?;
    let summary = FeSummary { element: kind.name().into(), nodes: m.nodes.len(), elements: m.element_count(), curving: m.curving.clone(), selectors: built.groups, solids, steps, ties };
    Ok((m, summary))
}

fn list_or_none(v: &[&str]) -> String {
    if v.is_empty() { "none".into() } else { v.join(", ") }
}

fn show_solid(s: &SolidRef) -> String {
    match s {
        SolidRef::Number(n) => n.to_string(),
        SolidRef::Name(n) => format!("`{n}`"),
    }
}

fn find_region(regions: &[(RegionId, String)], mesh: &crate::mesh::TetMesh, s: &SolidRef) -> Option<RegionId> {
    match s {
        SolidRef::Number(n) => regions.get((*n as usize).checked_sub(1)?).map(|(r, _)| *r),
        SolidRef::Name(n) => regions.iter().find(|(r, set)| mesh.region_names.get(*r) == Some(n.as_str()) || set.eq_ignore_ascii_case(n)).map(|(r, _)| *r),
    }
}

/// One `[[step]]` as a [`Step`].
fn build_step(jf: &JobFile, m: &FeModel, sets: &BTreeMap<String, GroupSets>, groups: &Groups, spec: &Spanned<StepSpec>, k: usize) -> Result<(Step, StepSummary), PipelineError> {
    let s = spec.get_ref();
    let name = s.name.clone().unwrap_or_else(|| format!("step-{}", k + 1));
    let analysis = match s.kind {
        StepKind::Static => Analysis::Static,
        StepKind::Frequency => Analysis::Frequency { modes: s.modes.as_ref().map_or(10, |m| *m.get_ref()) },
        StepKind::Heat => Analysis::Heat,
    };
    if let Some(modes) = &s.modes {
        if s.kind != StepKind::Frequency || *modes.get_ref() == 0 {
            return Err(jf.error_at(modes.span().start, "key `modes`: a number of modes > 0, in a step of type \"frequency\" only".into()));
        }
    }
    let structural = s.kind != StepKind::Heat;
    let wrong = |key: &str, faces: &Spanned<String>| -> PipelineError {
        let kind = if structural { "a structural step (static or frequency)" } else { "a heat step" };
        jf.error_at(faces.span().start, format!("key `{key}` does not belong in {kind}"))
    };
    // the sets of a selector used as a boundary
    let group = |key: &str, faces: &Spanned<String>| -> Result<&GroupSets, PipelineError> {
        let sel = faces.get_ref();
        let Some(g) = sets.get(sel) else {
            let known: Vec<&str> = groups.as_map().keys().map(String::as_str).collect();
            return Err(jf.error_at(faces.span().start, format!("key `{key}`: selector `{sel}` is not defined under [selectors] (defined: {})", list_or_none(&known))));
        };
        // a face partly covered by another solid (imprinted) loads its outer part only
        if g.interface_faces > 0 && g.boundary_faces == 0 {
            return Err(jf.error_at(faces.span().start, format!("key `{key}`: selector `{sel}` takes {} element faces between two solids (an interface inside the model), not on its boundary; select boundary faces only", g.interface_faces)));
        }
        if g.boundary_faces == 0 {
            return Err(jf.error_at(faces.span().start, format!("key `{key}`: selector `{sel}` has no element face on the mesh's boundary")));
        }
        Ok(g)
    };
    let mut bcs = Vec::new();
    let mut loads = Vec::new();
    let mut forces = Vec::new();
    for f in &s.fixed {
        if !structural {
            return Err(wrong("fixed", &f.faces));
        }
        let g = group("fixed", &f.faces)?;
        let mut dofs: Vec<u8> = f.dofs.as_ref().map_or_else(|| vec![1, 2, 3], |d| d.iter().map(|x| x.0).collect());
        dofs.sort_unstable();
        dofs.dedup();
        if dofs.is_empty() {
            return Err(jf.error_at(f.faces.span().start, "key `dofs`: hold at least one degree of freedom (1, 2, 3)".into()));
        }
        bcs.push(Bc::Fixed { nodes: g.node_set.clone(), dofs });
    }
    for d in &s.displacement {
        if !structural {
            return Err(wrong("displacement", &d.faces));
        }
        let g = group("displacement", &d.faces)?;
        bcs.push(Bc::Displacement { nodes: g.node_set.clone(), dof: d.dof.0, value: d.value });
    }
    for f in &s.force {
        if !structural {
            return Err(wrong("force", &f.faces));
        }
        let g = group("force", &f.faces)?;
        let total = DVec3::from_array(f.total);
        let nodal = consistent_forces(m, &m.surfaces[&g.surface], total);
        let sum: DVec3 = nodal.iter().map(|(_, f)| *f).sum();
        forces.push((f.faces.get_ref().clone(), sum.to_array()));
        loads.push(Load::Nodal { name: f.faces.get_ref().clone(), surface: g.surface.clone(), total, forces: nodal });
    }
    for p in &s.pressure {
        if !structural {
            return Err(wrong("pressure", &p.faces));
        }
        let g = group("pressure", &p.faces)?;
        loads.push(Load::Pressure { surface: g.surface.clone(), value: p.value });
    }
    for g in &s.gravity {
        if !structural {
            return Err(jf.error_at(spec.span().start, "key `gravity` does not belong in a heat step".into()));
        }
        loads.push(Load::Gravity { elements: crate::fe::build::ALL_ELEMENTS.into(), acceleration: DVec3::from_array(g.acceleration) });
    }
    for t in &s.temperature {
        if structural {
            return Err(wrong("temperature", &t.faces));
        }
        let g = group("temperature", &t.faces)?;
        bcs.push(Bc::Temperature { nodes: g.node_set.clone(), value: t.value });
    }
    for q in &s.heat_flux {
        if structural {
            return Err(wrong("heat_flux", &q.faces));
        }
        let g = group("heat_flux", &q.faces)?;
        loads.push(Load::HeatFlux { surface: g.surface.clone(), value: q.value });
    }
    for f in &s.film {
        if structural {
            return Err(wrong("film", &f.faces));
        }
        let g = group("film", &f.faces)?;
        loads.push(Load::Film { surface: g.surface.clone(), coefficient: f.coefficient.get(), sink: f.sink });
    }
    let analysis_name = match analysis {
        Analysis::Static => "static",
        Analysis::Frequency { .. } => "frequency",
        Analysis::Heat => "heat",
    };
    let summary = StepSummary { name: name.clone(), analysis: analysis_name.into(), forces };
    Ok((Step { name, analysis, bcs, loads }, summary))
}

/// Every material a step uses has what the step needs.
fn check_materials(jf: &JobFile, m: &FeModel, spec: &Spanned<StepSpec>, step: &Step) -> Result<(), PipelineError> {
    let gravity = step.loads.iter().any(|l| matches!(l, Load::Gravity { .. }));
    for sec in &m.sections {
        let mat = &m.materials[&sec.material];
        let mut missing = Vec::new();
        match step.analysis {
            Analysis::Heat => {
                if mat.conductivity.is_none() {
                    missing.push("conductivity");
                }
            }
            _ => {
                if mat.young.is_none() {
                    missing.push("young");
                }
                if mat.poisson.is_none() {
                    missing.push("poisson");
                }
                if (gravity || matches!(step.analysis, Analysis::Frequency { .. })) && mat.density.is_none() {
                    missing.push("density");
                }
            }
        }
        if !missing.is_empty() {
            let key = jf.job.materials.iter().find(|(k, _)| deck_name(k).eq_ignore_ascii_case(&sec.material));
            let at = key.map_or(spec.span().start, |(_, s)| s.span().start);
            return Err(jf.error_at(at, format!("material `{}` lacks {} for step `{}`", key.map_or(sec.material.as_str(), |(k, _)| k.as_str()), missing.join(", "), step.name)));
        }
    }
    Ok(())
}
