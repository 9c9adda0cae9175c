//! MSC/NX Nastran bulk data decks (`.bdf`, `.dat`, `.nas`) of an [`FeModel`], in small
//! (8-character) or large (16-character) fixed fields, through [`crate::io::atomic`].
//!
//! - Executive control `SOL 101` when every step is static, `SOL 103` when every step is a
//!   frequency step (`EIGRL` per step, selected by `METHOD`); a heat step, or static and
//!   frequency steps together, cannot be written as one deck and are an error naming the step.
//! - Case control: `TITLE`, one `SUBCASE` per step (step `k` is subcase `k`) with its
//!   `LABEL`, `SPC`, `LOAD` or `METHOD`, and `DISPLACEMENT`, `STRESS`, `SPCFORCES = ALL`.
//! - Bulk data: `GRID` (node `i` is grid `i + 1`), `CTETRA` with 4 or 10 grids (element `e`
//!   is `e + 1`; the C3D10 node order is CTETRA's), `PSOLID` per section (its PID the
//!   section's index plus one), `MAT1` (E, ν, ρ, α; its MID the material's index in name order
//!   plus one), then per step `SPC1` (fixed dofs, grouped by component string), `SPC`
//!   (prescribed displacements), `FORCE` (one card per node: magnitude and unit direction),
//!   `PLOAD4` (one card per element face: G1 a corner of the face, G4 the corner off it; the
//!   pressure written as given, positive into the element for both Abaqus and Nastran), `GRAV`,
//!   `LOAD` (when `GRAV` and other loads meet in one step: a `GRAV` set may not share its id
//!   with other loads) and `EIGRL`.
//! - Ids per step `k` of `n`: `SPC` set `k`; `FORCE`/`PLOAD4` set `k`, `GRAV` set `n + k`, the
//!   combining `LOAD` `2n + k`; `EIGRL` set `k`.
//! - Nastran has no named sets in bulk data: node sets, element sets and surfaces are written
//!   as `$` comments (name, size, members as grid or element id ranges) before the cards.
//!
//! Within a step, forces on one node add up into one `FORCE`, pressures on one element face
//! into one `PLOAD4`, gravity loads into one `GRAV`. Forces under 1e-12 of the step's largest
//! are the round-off of a zero (the corners of a flat 6-node face, [`crate::fe::loads`]) and
//! are not written. Fixed dofs (and displacements of 0) merge; a dof both held at 0 and
//! displaced, or displaced by two values, is an error.

pub(crate) mod field;

mod plan;

use self::field::{Field, LARGE, SMALL, card, parse_real, real};
use self::plan::{Plan, StepPlan, plan};
use crate::fe::element::{ABAQUS_FACES, abaqus_face_opposite};
use crate::fe::{Analysis, Bc, FeModel, Load};
use crate::io::IoError;
use crate::io::atomic::{write_atomic, write_err};
use glam::DVec3;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};
use std::io::Write;
use std::path::Path;

/// How to write a Nastran deck.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct NastranOptions {
    /// Large fields (16 characters, `GRID*`) on every card; small (8 characters) otherwise.
    pub large: bool,
    /// The case control `TITLE` (printable ASCII kept, at most 64 characters).
    pub title: String,
}

impl Default for NastranOptions {
    fn default() -> Self {
        NastranOptions { large: false, title: "fepre".into() }
    }
}

impl NastranOptions {
    /// With large (16-character) fields or small (8-character) ones.
    pub fn with_large(mut self, large: bool) -> Self {
        self.large = large;
        self
    }

    /// With this `TITLE`.
    pub fn with_title(mut self, title: impl Into<String>) -> Self {
        self.title = title.into();
        self
    }
}

/// What a deck holds.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct NastranSummary {
    /// The solution sequence: 101 (static) or 103 (normal modes).
    pub sol: u32,
    /// Subcases (one per step).
    pub subcases: usize,
    /// `GRID` cards.
    pub grids: usize,
    /// `CTETRA` cards.
    pub elements: usize,
    /// Grid-dof pairs constrained on `SPC1` and `SPC` cards, summed over the subcases.
    pub spc_dofs: usize,
    /// `FORCE` cards.
    pub force_cards: usize,
    /// `PLOAD4` cards.
    pub pload4_cards: usize,
    /// `GRAV` cards.
    pub grav_cards: usize,
    /// The sum of the `FORCE` cards as written (magnitude times direction, read back from
    /// their fields), over every subcase.
    pub force_total: DVec3,
}

/// Writes `m` as a Nastran bulk data deck.
///
/// # Errors
/// [`IoError::NotRepresentable`] naming the step, material, element or set where the model
/// fails [`FeModel::validate`], holds what SOL 101/103 cannot (a heat step, a temperature,
/// heat flux or film, static and frequency steps together, loads or displacements in a
/// frequency step, gravity on part of the model), lacks what a card needs (E and ν for
/// `MAT1`, a density for gravity or modes, a section for every element), or has ids or values
/// that do not fit the fields; [`IoError::Write`].
pub fn write_nastran(path: &Path, m: &FeModel, options: &NastranOptions) -> Result<NastranSummary, IoError> {
    let not = |what: String| IoError::NotRepresentable { path: path.to_path_buf(), format: "Nastran bulk data", what };
    m.validate().map_err(|e| not(e.to_string()))?;
    let plan = plan(m).map_err(|e| not(e.to_string()))?;
    let mut summary = NastranSummary { sol: plan.sol, subcases: plan.steps.len(), ..NastranSummary::default() };
    write_atomic(path, |w| {
        let mut out = Out { w, s: String::new(), large: options.large };
        let done = write_deck(&mut out, m, &plan, options, &mut summary);
        done.map_err(|f| match f {
            Fail::Io(source) => write_err(path)(source),
            Fail::Field(what) => not(what),
        })
    })?;
    Ok(summary)
}

/// Why writing stopped.
#[derive(Debug)]
enum Fail {
    /// The file system.
    Io(std::io::Error),
    /// A value that does not fit its field.
    Field(String),
}

/// Cards and lines on their way to the file.
struct Out<'w> {
    w: &'w mut dyn Write,
    /// One card's text.
    s: String,
    large: bool,
}

impl Out<'_> {
    /// Writes a card.
    fn card(&mut self, name: &str, fields: &[Field]) -> Result<(), Fail> {
        self.s.clear();
        card(&mut self.s, name, fields, self.large).ok_or_else(|| Fail::Field(format!("a {name} card does not fit its fields: {fields:?}")))?;
        self.w.write_all(self.s.as_bytes()).map_err(Fail::Io)
    }

    /// Writes a line of case control or a comment (the newline is added).
    fn line(&mut self, text: &str) -> Result<(), Fail> {
        self.w.write_all(text.as_bytes()).and_then(|()| self.w.write_all(b"\n")).map_err(Fail::Io)
    }

    /// The width of a real field.
    fn width(&self) -> usize {
        if self.large { LARGE } else { SMALL }
    }
}

/// `text` as printable ASCII (others become `?`), at most `max` characters.
fn ascii(text: &str, max: usize) -> String {
    text.chars().map(|c| if c == ' ' || c.is_ascii_graphic() { c } else { '?' }).take(max).collect()
}

/// `x` as the deck holds it: formatted into a field of `width` and read back.
fn written(x: f64, width: usize) -> f64 {
    real(x, width).and_then(|s| parse_real(&s)).unwrap_or(f64::NAN)
}

/// Ids (increasing, 1-based) as `a THRU b` ranges and single ids, as `$` comment lines.
fn id_lines(out: &mut Out<'_>, ids: impl IntoIterator<Item = u64>) -> Result<(), Fail> {
    let mut items: Vec<String> = Vec::new();
    let mut run: Option<(u64, u64)> = None;
    let flush = |items: &mut Vec<String>, (a, b): (u64, u64)| items.push(if a == b { a.to_string() } else { format!("{a} THRU {b}") });
    for id in ids {
        run = match run {
            Some((a, b)) if id == b + 1 => Some((a, id)),
            Some(r) => {
                flush(&mut items, r);
                Some((id, id))
            }
            None => Some((id, id)),
        };
    }
    if let Some(r) = run {
        flush(&mut items, r);
    }
    let mut line = String::from("$  ");
    for (i, item) in items.iter().enumerate() {
        if line.len() + item.len() + 2 > 72 {
            out.line(&line)?;
            line = String::from("$  ");
        }
        line.push(' ');
        line.push_str(item);
        if i + 1 < items.len() {
            line.push(',');
        }
    }
    if line.len() > 3 { out.line(&line) } else { Ok(()) }
}

/// The whole deck.
fn write_deck(out: &mut Out<'_>, m: &FeModel, plan: &Plan<'_>, options: &NastranOptions, summary: &mut NastranSummary) -> Result<(), Fail> {
    let fields = if options.large { "large (16-character) fields" } else { "small (8-character) fields" };
    out.line(&format!("$ written by fepre {}: Nastran bulk data, {fields}", env!("CARGO_PKG_VERSION")))?;
    case_control(out, plan, options)?;
    model_cards(out, m, plan, summary)?;
    for sp in &plan.steps {
        step_cards(out, m, sp, summary)?;
    }
    out.line("ENDDATA")
}

/// Executive and case control, up to `BEGIN BULK`.
fn case_control(out: &mut Out<'_>, plan: &Plan<'_>, options: &NastranOptions) -> Result<(), Fail> {
    out.line(&format!("SOL {}", plan.sol))?;
    out.line("CEND")?;
    // `$` would start a comment in case control
    out.line(&format!("TITLE = {}", ascii(&options.title, 64).replace('$', "_")))?;
    out.line("ECHO = NONE")?;
    if plan.steps.is_empty() {
        out.line("$ the model has no steps: no subcases")?;
    }
    for sp in &plan.steps {
        out.line(&format!("SUBCASE {}", sp.k))?;
        out.line(&format!("  LABEL = {}", ascii(&sp.step.name, 64).replace('$', "_")))?;
        if let Some(id) = sp.spc_sid {
            out.line(&format!("  SPC = {id}"))?;
        }
        if let Some(id) = sp.case_load() {
            out.line(&format!("  LOAD = {id}"))?;
        }
        if let Analysis::Frequency { .. } = sp.step.analysis {
            out.line(&format!("  METHOD = {}", sp.k))?;
        }
        out.line("  DISPLACEMENT = ALL")?;
        out.line("  STRESS = ALL")?;
        out.line("  SPCFORCES = ALL")?;
    }
    out.line("BEGIN BULK")
}

/// Materials, properties, the sets as comments, grids and elements.
fn model_cards(out: &mut Out<'_>, m: &FeModel, plan: &Plan<'_>, summary: &mut NastranSummary) -> Result<(), Fail> {
    let ne = m.element_count();
    out.line(&format!("$ {} grids, {} CTETRA with {} grids ({})", m.nodes.len(), ne, m.kind.nodes(), m.kind.name()))?;
    if let Some(c) = &m.curving {
        out.line(&format!("$ second order: {} mid nodes on CAD faces, {} on CAD edges, {} left on the chord,", c.on_faces, c.on_edges, c.left_straight))?;
        out.line(&format!("$ {} moved back to the chord in {} elements; smallest Jacobian ratio {:.3}", c.straightened, c.straightened_elements, c.min_jacobian_ratio))?;
    }
    for (name, mid, mat) in &plan.materials {
        let Some(mid) = mid else {
            out.line(&format!("$ material {name}: used by no section, not written"))?;
            continue;
        };
        out.line(&format!("$ material {name}"))?;
        let opt = |x: Option<f64>| x.map_or(Field::Blank, Field::Real);
        // MID E G NU RHO A: G left blank, Nastran derives it from E and NU
        out.card("MAT1", &[Field::Int(*mid), opt(mat.young), Field::Blank, opt(mat.poisson), opt(mat.density), opt(mat.expansion)])?;
    }
    for p in &plan.psolids {
        out.line(&format!("$ section {}: element set {}, material {}", p.pid, p.element_set, p.material))?;
        out.card("PSOLID", &[Field::Int(p.pid), Field::Int(p.mid)])?;
    }
    for (name, set) in &m.node_sets {
        let ids: BTreeSet<u64> = set.iter().map(|&v| u64::from(v) + 1).collect();
        out.line(&format!("$ fepre node set {name} ({} grids):", ids.len()))?;
        id_lines(out, ids)?;
    }
    for (name, set) in &m.element_sets {
        let ids: BTreeSet<u64> = set.iter().map(|&e| u64::from(e) + 1).collect();
        out.line(&format!("$ fepre element set {name} ({} elements):", ids.len()))?;
        id_lines(out, ids)?;
    }
    for (name, faces) in &m.surfaces {
        out.line(&format!("$ fepre surface {name}: {} element faces (loaded by PLOAD4 where a step asks)", faces.len()))?;
    }
    out.line("$ grids")?;
    for (i, p) in m.nodes.iter().enumerate() {
        out.card("GRID", &[Field::Int(i as u64 + 1), Field::Blank, Field::Real(p.x), Field::Real(p.y), Field::Real(p.z)])?;
    }
    summary.grids = m.nodes.len();
    out.line("$ elements")?;
    let mut fields = Vec::with_capacity(2 + m.kind.nodes());
    for e in 0..ne {
        fields.clear();
        fields.push(Field::Int(e as u64 + 1));
        fields.push(Field::Int(u64::from(plan.pids[e])));
        fields.extend(m.element(e).iter().map(|&v| Field::Int(u64::from(v) + 1)));
        out.card("CTETRA", &fields)?;
    }
    summary.elements = ne;
    Ok(())
}

/// The corner of a tet not on Abaqus face `face`.
fn corner_off(face: u8) -> usize {
    (0..4).find(|&k| abaqus_face_opposite(k) == face).unwrap_or(0)
}

/// One step's constraints and loads.
fn step_cards(out: &mut Out<'_>, m: &FeModel, sp: &StepPlan<'_>, summary: &mut NastranSummary) -> Result<(), Fail> {
    let step = sp.step;
    let what = match step.analysis {
        Analysis::Frequency { modes } => format!("frequency, {modes} modes"),
        _ => "static".to_string(),
    };
    out.line(&format!("$ step {} {} ({what})", sp.k, ascii(&step.name, 60)))?;
    for bc in &step.bcs {
        let text = match bc {
            Bc::Fixed { nodes, dofs } => format!("fixed: node set {nodes}, dofs {dofs:?}"),
            Bc::Displacement { nodes, dof, value } => format!("displacement: node set {nodes}, dof {dof} = {value:e}"),
            Bc::Temperature { nodes, value } => format!("temperature: node set {nodes} = {value:e}"),
        };
        out.line(&format!("$   {text}"))?;
    }
    for load in &step.loads {
        let text = match load {
            Load::Nodal { name, surface, total, forces } => format!("nodal forces {}: surface {surface}, {} nodes, total ({:e}, {:e}, {:e})", ascii(name, 40), forces.len(), total.x, total.y, total.z),
            Load::Pressure { surface, value } => format!("pressure {value:e} on surface {surface} (positive into the elements)"),
            Load::Gravity { elements, acceleration: a } => format!("gravity ({:e}, {:e}, {:e}) on element set {elements}", a.x, a.y, a.z),
            Load::HeatFlux { surface, .. } | Load::Film { surface, .. } => format!("a thermal load on surface {surface}"),
        };
        out.line(&format!("$   {text}"))?;
    }
    if let Some(sid) = sp.spc_sid {
        // fixed dofs grouped by component string, grids increasing
        let mut groups: BTreeMap<u8, Vec<u32>> = BTreeMap::new();
        for (&v, &mask) in &sp.fixed {
            groups.entry(mask).or_default().push(v);
        }
        for (mask, nodes) in groups {
            let comp: String = (1..=3u8).filter(|d| mask & (1 << (d - 1)) != 0).map(|d| char::from(b'0' + d)).collect();
            // several cards of at most 1000 grids each keep lines reasonable for any reader
            for chunk in nodes.chunks(1000) {
                let mut fields = vec![Field::Int(sid), Field::Text(comp.clone())];
                fields.extend(chunk.iter().map(|&v| Field::Int(u64::from(v) + 1)));
                out.card("SPC1", &fields)?;
            }
            summary.spc_dofs += nodes.len() * comp.len();
        }
        for (&(v, dof), &value) in &sp.displaced {
            out.card("SPC", &[Field::Int(sid), Field::Int(u64::from(v) + 1), Field::Text(dof.to_string()), Field::Real(value)])?;
            summary.spc_dofs += 1;
        }
    }
    if let Some(sid) = sp.simple_sid {
        let w = out.width();
        // (the plan keeps forces of positive length, pressures not zero)
        for (&v, &f) in &sp.forces {
            let mag = f.length();
            let n = f / mag;
            // FORCE SID G CID F N1 N2 N3: the force is F times N
            out.card("FORCE", &[Field::Int(sid), Field::Int(u64::from(v) + 1), Field::Blank, Field::Real(mag), Field::Real(n.x), Field::Real(n.y), Field::Real(n.z)])?;
            summary.force_cards += 1;
            summary.force_total += written(mag, w) * DVec3::new(written(n.x, w), written(n.y, w), written(n.z, w));
        }
        for (face, &p) in &sp.pressures {
            let el = m.element(face.element as usize);
            let g1 = u64::from(el[ABAQUS_FACES[face.face as usize][0]]) + 1;
            let g4 = u64::from(el[corner_off(face.face)]) + 1;
            // Sign: PLOAD4 on a solid face without a direction acts normal to the face, a
            // positive pressure pointing into the element, as Abaqus's `*DSLOAD ... P` does
            // (`Load::Pressure`), so the value is written unchanged. Checked against NX
            // Nastran 6.0's OLOAD resultant for PLOAD4 on a CTETRA (Alneos/vega,
            // testdata/nastran/irt/pload4-ctetra-multi: pressure 100 with G1 = 1, G4 = 4 on
            // the tet 1 (0,0,0), 2 (3,0,0), 3 (1,1,0), 4 (0,0,1) loads face 1-2-3 with +150
            // in z, into the element), and against pyNastran 1.4.1 (`sum_forces_moments`,
            // `ctetra_face_area_centroid_normal`: the face normal points into a positively
            // oriented tet and the force is pressure × area × that normal).
            // PLOAD4 SID EID P1 P2 P3 P4 G1 G4: P2..P4 blank, a uniform pressure
            out.card("PLOAD4", &[Field::Int(sid), Field::Int(u64::from(face.element) + 1), Field::Real(p), Field::Blank, Field::Blank, Field::Blank, Field::Int(g1), Field::Int(g4)])?;
            summary.pload4_cards += 1;
        }
    }
    if let Some(sid) = sp.grav_sid {
        let a = sp.gravity;
        let mag = a.length();
        // GRAV SID CID A N1 N2 N3: the acceleration is A times N
        out.card("GRAV", &[Field::Int(sid), Field::Blank, Field::Real(mag), Field::Real(a.x / mag), Field::Real(a.y / mag), Field::Real(a.z / mag)])?;
        summary.grav_cards += 1;
    }
    if let (Some(load), Some(simple), Some(grav)) = (sp.combined_sid, sp.simple_sid, sp.grav_sid) {
        // LOAD SID S S1 L1 S2 L2: GRAV may not share its set id with other loads
        out.card("LOAD", &[Field::Int(load), Field::Real(1.0), Field::Real(1.0), Field::Int(simple), Field::Real(1.0), Field::Int(grav)])?;
    }
    if let Analysis::Frequency { modes } = step.analysis {
        // EIGRL SID V1 V2 ND: the lowest ND modes by Lanczos
        out.card("EIGRL", &[Field::Int(sp.k), Field::Blank, Field::Blank, Field::Int(u64::from(modes))])?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::FaceId;
    use crate::fe::{ElementKind, Material, Section, Step, build_model, loads::consistent_forces};
    use crate::io::test_meshes::two_tets;

    /// The two tets with a fixed face group, a loaded face group, steel on every element and
    /// a static step: fixed, a nodal load of (0, 0, -100), a pressure of 2 and gravity.
    fn model(kind: ElementKind) -> FeModel {
        let groups = BTreeMap::from([("fixed".to_string(), vec![FaceId(1)]), ("loaded".to_string(), vec![FaceId(2)])]);
        let mut m = build_model(&two_tets(), &groups, kind, None, 1.0).model;
        m.materials.insert("STEEL".into(), Material { young: Some(210000.0), poisson: Some(0.3), density: Some(7.85e-9), ..Material::default() });
        m.sections.push(Section { element_set: "EALL".into(), material: "STEEL".into() });
        let forces = consistent_forces(&m, &m.surfaces["LOADED_S"], DVec3::new(0.0, 0.0, -100.0));
        m.steps.push(Step {
            name: "load step".into(),
            analysis: Analysis::Static,
            bcs: vec![Bc::Fixed { nodes: "FIXED".into(), dofs: vec![1, 2, 3] }],
            loads: vec![
                Load::Nodal { name: "push".into(), surface: "LOADED_S".into(), total: DVec3::new(0.0, 0.0, -100.0), forces },
                Load::Pressure { surface: "LOADED_S".into(), value: 2.0 },
                Load::Gravity { elements: "EALL".into(), acceleration: DVec3::new(0.0, 0.0, -9810.0) },
            ],
        });
        m.validate().unwrap();
        m
    }

    fn write(m: &FeModel, options: &NastranOptions) -> (Result<NastranSummary, IoError>, String, tempfile::TempDir) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("deck.bdf");
        let r = write_nastran(&path, m, options);
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        (r, text, dir)
    }

    /// The small fields of a card line (the name first).
    fn fields(line: &str) -> Vec<String> {
        line.as_bytes().chunks(8).map(|c| String::from_utf8_lossy(c).trim().to_string()).collect()
    }

    /// The small-field cards of a deck, continuation lines joined (their first field dropped).
    fn cards(text: &str) -> Vec<Vec<String>> {
        let mut out: Vec<Vec<String>> = Vec::new();
        let mut bulk = false;
        for line in text.lines() {
            if line == "BEGIN BULK" {
                bulk = true;
            } else if !bulk || line.starts_with('$') {
                continue;
            } else if line.starts_with(' ') {
                out.last_mut().unwrap().extend(fields(line).into_iter().skip(1));
            } else {
                out.push(fields(line));
            }
        }
        out
    }

    #[test]
    fn a_static_deck_has_every_card_and_its_summary() {
        for kind in [ElementKind::C3D4, ElementKind::C3D10] {
            let m = model(kind);
            let (r, text, _dir) = write(&m, &NastranOptions::default());
            let s = r.unwrap();
            let count = |name: &str| text.lines().filter(|l| fields(l).first().is_some_and(|f| f == name)).count();
            for line in ["SOL 101", "CEND", "SUBCASE 1", "  LABEL = load step", "  SPC = 1", "  LOAD = 3", "  DISPLACEMENT = ALL", "  STRESS = ALL", "  SPCFORCES = ALL", "BEGIN BULK", "ENDDATA"] {
                assert!(text.lines().any(|l| l == line), "{kind:?}: no line {line:?}");
            }
            assert_eq!(count("GRID"), m.nodes.len());
            assert_eq!(count("CTETRA"), 2);
            assert_eq!((s.grids, s.elements, s.sol, s.subcases), (m.nodes.len(), 2, 101, 1));
            assert_eq!((count("MAT1"), count("PSOLID"), count("GRAV"), count("LOAD")), (1, 1, 1, 1));
            let fixed = m.node_sets["FIXED"].len();
            assert_eq!(s.spc_dofs, 3 * fixed);
            let spc1: Vec<Vec<String>> = cards(&text).into_iter().filter(|f| f[0] == "SPC1").collect();
            assert_eq!(spc1.iter().map(|f| f.len() - 3).sum::<usize>(), fixed);
            assert!(spc1.iter().all(|f| f[1] == "1" && f[2] == "123"));
            let surface = &m.surfaces["LOADED_S"];
            assert_eq!(s.pload4_cards, surface.len());
            assert_eq!(count("PLOAD4"), surface.len());
            assert_eq!(s.force_cards, count("FORCE"));
            // no round-off zeros (the corners of the flat 6-node faces) among the forces
            let magnitudes: Vec<f64> = cards(&text).iter().filter(|f| f[0] == "FORCE").map(|f| parse_real(&f[4]).unwrap()).collect();
            assert!(magnitudes.iter().all(|&f| f > 1.0), "{magnitudes:?}");
            assert!((s.force_total - DVec3::new(0.0, 0.0, -100.0)).length() < 1e-3, "{}", s.force_total);
            // the 10 grids of a C3D10 continue on a second line
            let ct = cards(&text).into_iter().find(|f| f[0] == "CTETRA").unwrap();
            let grids: Vec<u64> = ct[3..].iter().map(|g| g.parse().unwrap()).collect();
            let want: Vec<u64> = m.element(0).iter().map(|&v| u64::from(v) + 1).collect();
            assert_eq!(grids, want);
        }
    }

    #[test]
    fn pload4_names_a_corner_of_the_face_and_the_corner_off_it() {
        let m = model(ElementKind::C3D4);
        let (r, text, _dir) = write(&m, &NastranOptions::default());
        r.unwrap();
        let mut seen = 0;
        for f in text.lines().filter(|l| l.starts_with("PLOAD4")).map(fields) {
            let (eid, p, g1, g4): (usize, f64, u32, u32) = (f[2].parse().unwrap(), parse_real(&f[3]).unwrap(), f[7].parse().unwrap(), f[8].parse().unwrap());
            assert_eq!(p, 2.0);
            let el = m.element(eid - 1);
            let face = m.surfaces["LOADED_S"].iter().find(|x| x.element as usize == eid - 1).unwrap();
            let corners: Vec<u32> = ABAQUS_FACES[face.face as usize].iter().map(|&k| el[k] + 1).collect();
            assert!(corners.contains(&g1) && !corners.contains(&g4) && el[..4].contains(&(g4 - 1)));
            seen += 1;
        }
        assert!(seen > 0);
    }

    #[test]
    fn large_fields_continue_with_a_star() {
        let m = model(ElementKind::C3D10);
        let (r, text, _dir) = write(&m, &NastranOptions::default().with_large(true).with_title("big $ fields"));
        let s = r.unwrap();
        assert!(text.lines().any(|l| l == "TITLE = big _ fields"));
        let grids: Vec<&str> = text.lines().filter(|l| l.starts_with("GRID*")).collect();
        assert_eq!(grids.len(), s.grids);
        let lines: Vec<&str> = text.lines().collect();
        for (i, l) in lines.iter().enumerate() {
            assert!(l.len() <= 80, "{l:?}");
            if l.starts_with("GRID*") {
                assert!(lines[i + 1].starts_with("*       "), "{}", lines[i + 1]);
                assert_eq!(l.len(), 8 + 4 * 16);
            }
        }
        assert!((s.force_total.z + 100.0).abs() < 1e-9, "{}", s.force_total);
    }

    #[test]
    fn a_frequency_deck_asks_for_its_modes() {
        let mut m = model(ElementKind::C3D4);
        m.steps = vec![Step { name: "modes".into(), analysis: Analysis::Frequency { modes: 12 }, bcs: vec![Bc::Fixed { nodes: "FIXED".into(), dofs: vec![1, 2, 3] }], loads: vec![] }];
        let (r, text, _dir) = write(&m, &NastranOptions::default());
        assert_eq!(r.unwrap().sol, 103);
        assert!(text.starts_with("$ written by fepre") && text.contains("\nSOL 103\n") && text.contains("\n  METHOD = 1\n"));
        let eigrl = text.lines().find(|l| l.starts_with("EIGRL")).map(fields).unwrap();
        assert_eq!(eigrl, ["EIGRL", "1", "", "", "12"]);
        assert!(!text.contains("\n  LOAD ="));
    }

    #[test]
    fn displacements_go_on_spc_cards_and_zero_ones_merge_with_fixed() {
        let mut m = model(ElementKind::C3D4);
        m.steps[0].loads.clear();
        m.steps[0].bcs.push(Bc::Displacement { nodes: "LOADED".into(), dof: 3, value: 0.0 });
        let (r, text, _dir) = write(&m, &NastranOptions::default());
        let plain = r.unwrap().spc_dofs;
        assert!(!text.lines().any(|l| l.starts_with("SPC ")), "{text}");
        m.steps[0].bcs = vec![Bc::Displacement { nodes: "LOADED".into(), dof: 2, value: 0.5 }];
        let (r, text, _dir) = write(&m, &NastranOptions::default());
        let n = m.node_sets["LOADED"].len();
        assert_eq!(r.unwrap().spc_dofs, n);
        let spc: Vec<Vec<String>> = text.lines().filter(|l| l.starts_with("SPC ")).map(fields).collect();
        assert_eq!(spc.len(), n);
        assert!(spc.iter().all(|f| f[1] == "1" && f[3] == "2" && f[4] == ".5"));
        assert!(plain > 0);
        // held at 0 and displaced: an error
        m.steps[0].bcs.push(Bc::Fixed { nodes: "LOADED".into(), dofs: vec![2] });
        let (r, _, _dir) = write(&m, &NastranOptions::default());
        assert!(r.unwrap_err().to_string().contains("both held at 0 and displaced"));
    }

    #[test]
    fn what_a_deck_cannot_hold_is_an_error_naming_it_and_leaves_no_file() {
        let check = |m: &FeModel, want: &str| {
            let dir = tempfile::tempdir().unwrap();
            let path = dir.path().join("deck.bdf");
            let e = write_nastran(&path, m, &NastranOptions::default()).unwrap_err();
            assert!(matches!(e, IoError::NotRepresentable { .. }), "{e}");
            assert!(e.to_string().contains(want), "{e} lacks {want:?}");
            assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "a file was left");
        };
        let mut m = model(ElementKind::C3D4);
        m.steps.push(Step { name: "warm".into(), analysis: Analysis::Heat, bcs: vec![], loads: vec![] });
        check(&m, "step warm is a heat transfer step");
        let mut m = model(ElementKind::C3D4);
        m.steps.push(Step { name: "modes".into(), analysis: Analysis::Frequency { modes: 5 }, bcs: vec![], loads: vec![] });
        check(&m, "two solution sequences");
        let mut m = model(ElementKind::C3D4);
        m.materials.get_mut("STEEL").unwrap().poisson = None;
        check(&m, "material STEEL lacks Poisson's ratio");
        let mut m = model(ElementKind::C3D4);
        m.materials.get_mut("STEEL").unwrap().density = None;
        check(&m, "material STEEL has no density: gravity");
        let mut m = model(ElementKind::C3D4);
        m.sections.clear();
        check(&m, "element 1 (and 1 more) has no section");
        let mut m = model(ElementKind::C3D4);
        let part = m.element_sets.keys().find(|k| k.as_str() != "EALL").unwrap().clone();
        m.steps[0].loads.push(Load::Gravity { elements: part.clone(), acceleration: DVec3::X });
        check(&m, &format!("gravity on element set {part}"));
        let mut m = model(ElementKind::C3D4);
        m.steps[0].bcs.push(Bc::Temperature { nodes: "FIXED".into(), value: 20.0 });
        check(&m, "step load step: a temperature");
    }

    #[test]
    fn set_members_are_comments_in_ranges() {
        let mut s = Vec::new();
        let mut out = Out { w: &mut s, s: String::new(), large: false };
        id_lines(&mut out, [1, 2, 3, 5, 7, 8]).unwrap();
        id_lines(&mut out, 1..=40).unwrap();
        id_lines(&mut out, (1..=60).map(|i| 2 * i)).unwrap();
        let text = String::from_utf8(s).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "$   1 THRU 3, 5, 7 THRU 8");
        assert_eq!(lines[1], "$   1 THRU 40");
        assert!(lines[2..].iter().all(|l| l.starts_with("$   ") && l.len() <= 72), "{text}");
        assert_eq!(lines[2..].join(" ").matches(',').count(), 59, "{text}");
    }
}
