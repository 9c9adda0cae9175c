//! CalculiX/Abaqus input decks (`.inp`): `*NODE`, `*ELEMENT`, `*NSET`, `*ELSET`,
//! `*SURFACE, TYPE=ELEMENT`, `*TIE` (slave surface, master surface; a `*SURFACE, TYPE=NODE`
//! slave where the tie names slave nodes), `*MATERIAL` (`*ELASTIC`, `*DENSITY`, `*EXPANSION`,
//! `*CONDUCTIVITY`, `*SPECIFIC HEAT`), `*SOLID SECTION`, and per step `*STATIC`,
//! `*FREQUENCY` or `*HEAT TRANSFER, STEADY STATE` with `*BOUNDARY`, `*CLOAD`, `*DSLOAD`,
//! `*DLOAD` (gravity), `*DFLUX`, `*FILM` and output requests (`*NODE FILE`, `*EL FILE`,
//! `*NODE PRINT ... TOTALS=ONLY` of the reactions on each fixed set). Ids are 1-based; names
//! are upper case, at most 80 characters (checked by [`FeModel::validate`]).

use crate::fe::{Analysis, Bc, FeModel, Load, Step};
use crate::io::IoError;
use crate::io::atomic::{write_atomic, write_err};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

/// Entries per data line of a set (Abaqus allows 16).
const PER_LINE: usize = 16;

/// Writes `m` as a CalculiX/Abaqus deck.
///
/// # Errors
/// [`IoError::NotRepresentable`] where the model fails [`FeModel::validate`];
/// [`IoError::Write`].
pub fn write_inp(path: &Path, m: &FeModel, title: &str) -> Result<(), IoError> {
    m.validate().map_err(|e| IoError::NotRepresentable { path: path.to_path_buf(), format: "CalculiX/Abaqus", what: e.to_string() })?;
    let text = deck_text(m, title);
    write_atomic(path, |w| w.write_all(text.as_bytes()).map_err(write_err(path)))
}

/// The widest number CalculiX reads: it cuts every field at 20 characters.
const FIELD: usize = 20;

/// A number as the deck writes it: the shortest text that reads back to the same `f64`
/// where that fits CalculiX's 20-character fields, else 20 characters of scientific notation
/// (13 or more significant digits).
pub fn num(x: f64) -> String {
    let a = x.abs();
    let s = if x == 0.0 || (1e-4..1e15).contains(&a) { format!("{x:?}") } else { format!("{x:e}") };
    if s.len() <= FIELD {
        return s;
    }
    let mut p = FIELD;
    loop {
        let t = format!("{x:.p$e}");
        if t.len() <= FIELD || p == 0 {
            return t;
        }
        p -= 1;
    }
}

/// The deck's text.
pub fn deck_text(m: &FeModel, title: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "** written by fepre {}", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(s, "*HEADING\n{}", title.replace(['\n', '\r'], " "));
    if let Some(c) = &m.curving {
        let _ = writeln!(
            s,
            "** second order: {} mid nodes on CAD faces, {} on CAD edges, {} boundary mid nodes left on the chord, {} moved back to the chord in {} elements; smallest Jacobian ratio {:.3}",
            c.on_faces, c.on_edges, c.left_straight, c.straightened, c.straightened_elements, c.min_jacobian_ratio
        );
    }
    let _ = writeln!(s, "*NODE, NSET=NALL");
    for (i, p) in m.nodes.iter().enumerate() {
        let _ = writeln!(s, "{}, {}, {}, {}", i + 1, num(p.x), num(p.y), num(p.z));
    }
    let _ = writeln!(s, "*ELEMENT, TYPE={}, ELSET=EALL", m.kind.name());
    for e in 0..m.element_count() {
        let _ = write!(s, "{}", e + 1);
        for v in m.element(e) {
            let _ = write!(s, ", {}", v + 1);
        }
        s.push('\n');
    }
    for (name, set) in m.element_sets.iter().filter(|(n, _)| n.as_str() != "EALL") {
        let _ = writeln!(s, "*ELSET, ELSET={name}");
        list(&mut s, set);
    }
    for (name, set) in m.node_sets.iter().filter(|(n, _)| n.as_str() != "NALL") {
        let _ = writeln!(s, "*NSET, NSET={name}");
        list(&mut s, set);
    }
    for (name, faces) in &m.surfaces {
        let _ = writeln!(s, "*SURFACE, NAME={name}, TYPE=ELEMENT");
        for f in faces {
            let _ = writeln!(s, "{}, S{}", f.element + 1, f.face + 1);
        }
    }
    // ties: after the surfaces they name, before every step (ccx refuses a *TIE in a step)
    for t in &m.ties {
        let slave = match &t.slave_nodes {
            Some(n) => {
                let _ = writeln!(s, "*SURFACE, NAME={n}, TYPE=NODE\n{n}");
                n
            }
            None => &t.slave,
        };
        let _ = writeln!(s, "*TIE, NAME={}, POSITION TOLERANCE={}\n{slave}, {}", t.name, num(t.tolerance), t.master);
    }
    for (name, mat) in &m.materials {
        let _ = writeln!(s, "*MATERIAL, NAME={name}");
        if let (Some(e), Some(nu)) = (mat.young, mat.poisson) {
            let _ = writeln!(s, "*ELASTIC\n{}, {}", num(e), num(nu));
        }
        let mut one = |key: &str, v: Option<f64>| {
            if let Some(v) = v {
                let _ = writeln!(s, "*{key}\n{}", num(v));
            }
        };
        one("DENSITY", mat.density);
        one("EXPANSION", mat.expansion);
        one("CONDUCTIVITY", mat.conductivity);
        one("SPECIFIC HEAT", mat.specific_heat);
    }
    for sec in &m.sections {
        let _ = writeln!(s, "*SOLID SECTION, ELSET={}, MATERIAL={}", sec.element_set, sec.material);
    }
    for step in &m.steps {
        write_step(&mut s, m, step);
    }
    s
}

fn list(s: &mut String, ids: &[u32]) {
    for chunk in ids.chunks(PER_LINE) {
        let line: Vec<String> = chunk.iter().map(|v| (v + 1).to_string()).collect();
        let _ = writeln!(s, "{}", line.join(", "));
    }
}

fn write_step(s: &mut String, m: &FeModel, step: &Step) {
    let _ = writeln!(s, "** step {}", step.name);
    let _ = writeln!(s, "*STEP");
    match step.analysis {
        Analysis::Static => s.push_str("*STATIC\n"),
        Analysis::Frequency { modes } => {
            let _ = writeln!(s, "*FREQUENCY\n{modes}");
        }
        Analysis::Heat => s.push_str("*HEAT TRANSFER, STEADY STATE\n"),
    }
    if !step.bcs.is_empty() {
        s.push_str("*BOUNDARY\n");
    }
    for bc in &step.bcs {
        match bc {
            Bc::Fixed { nodes, dofs } => {
                for (a, b) in runs(dofs) {
                    let _ = writeln!(s, "{nodes}, {a}, {b}, 0.");
                }
            }
            Bc::Displacement { nodes, dof, value } => {
                let _ = writeln!(s, "{nodes}, {dof}, {dof}, {}", num(*value));
            }
            Bc::Temperature { nodes, value } => {
                let _ = writeln!(s, "{nodes}, 11, 11, {}", num(*value));
            }
        }
    }
    for load in &step.loads {
        match load {
            Load::Nodal { name, surface, total, forces } => {
                let _ = writeln!(s, "** force on {name} ({surface}): total {} {} {} as consistent nodal loads", num(total.x), num(total.y), num(total.z));
                s.push_str("*CLOAD\n");
                for (v, f) in forces {
                    for (d, c) in f.to_array().into_iter().enumerate() {
                        if c != 0.0 {
                            let _ = writeln!(s, "{}, {}, {}", v + 1, d + 1, num(c));
                        }
                    }
                }
            }
            Load::Pressure { surface, value } => {
                let _ = writeln!(s, "*DSLOAD\n{surface}, P, {}", num(*value));
            }
            Load::Gravity { elements, acceleration } => {
                let g = acceleration.length();
                if g > 0.0 {
                    let d = *acceleration / g;
                    let _ = writeln!(s, "*DLOAD\n{elements}, GRAV, {}, {}, {}, {}", num(g), num(d.x), num(d.y), num(d.z));
                }
            }
            Load::HeatFlux { surface, value } => {
                s.push_str("*DFLUX\n");
                for f in &m.surfaces[surface] {
                    let _ = writeln!(s, "{}, S{}, {}", f.element + 1, f.face + 1, num(*value));
                }
            }
            Load::Film { surface, coefficient, sink } => {
                s.push_str("*FILM\n");
                for f in &m.surfaces[surface] {
                    let _ = writeln!(s, "{}, F{}, {}, {}", f.element + 1, f.face + 1, num(*sink), num(*coefficient));
                }
            }
        }
    }
    match step.analysis {
        Analysis::Heat => {
            s.push_str("*NODE FILE\nNT\n*EL FILE\nHFL\n");
        }
        Analysis::Static => {
            s.push_str("*NODE FILE\nU, RF\n*EL FILE\nS, E\n");
            for bc in &step.bcs {
                if let Bc::Fixed { nodes, .. } | Bc::Displacement { nodes, .. } = bc {
                    let _ = writeln!(s, "*NODE PRINT, NSET={nodes}, TOTALS=ONLY\nRF");
                }
            }
        }
        Analysis::Frequency { .. } => s.push_str("*NODE FILE\nU\n"),
    }
    s.push_str("*END STEP\n");
}

/// Consecutive runs of sorted, distinct degrees of freedom: `[1, 2, 3]` → `(1, 3)`.
fn runs(dofs: &[u8]) -> Vec<(u8, u8)> {
    let mut d = dofs.to_vec();
    d.sort_unstable();
    d.dedup();
    let mut out: Vec<(u8, u8)> = Vec::new();
    for x in d {
        match out.last_mut() {
            Some((_, b)) if *b + 1 == x => *b = x,
            _ => out.push((x, x)),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_exactly_or_fit_twenty_characters() {
        for x in [0.0, 1.0, -2.5, 210000.0, 1e-20, 7.85e-9, 0.1, 1e300, -123456.789] {
            assert_eq!(num(x).parse::<f64>().unwrap(), x, "{}", num(x));
        }
        for x in [-1.5681900222830333e-14, 1.0 / 3.0, -2.0 / 3.0 * 1e-300, 12345678.123456789] {
            let s = num(x);
            assert!(s.len() <= 20, "{s}");
            assert!((s.parse::<f64>().unwrap() - x).abs() <= 1e-12 * x.abs(), "{s}");
        }
    }

    #[test]
    fn ties_come_after_the_surfaces_and_before_the_steps() {
        let mesh = crate::io::test_meshes::touching_tets();
        let mut b = crate::fe::build_model(&mesh, &std::collections::BTreeMap::new(), crate::fe::ElementKind::C3D4, None, 1.0);
        b.add_face_surface(crate::core::FaceId(10), "A").unwrap();
        b.add_face_surface(crate::core::FaceId(20), "B").unwrap();
        let mut m = b.model;
        m.ties.push(crate::fe::Tie { name: "TIE1".into(), slave: "B".into(), master: "A".into(), tolerance: 0.015, slave_nodes: None });
        m.steps.push(Step { name: "s".into(), analysis: Analysis::Static, bcs: Vec::new(), loads: Vec::new() });
        let text = deck_text(&m, "t");
        let tie = text.find("*TIE, NAME=TIE1, POSITION TOLERANCE=0.015\nB, A\n").unwrap();
        assert!(text.rfind("*SURFACE").unwrap() < tie && tie < text.find("*STEP").unwrap(), "{text}");
        // slave nodes: a node-based slave surface
        m.node_sets.insert("BN".into(), vec![4, 5]);
        m.ties[0].slave_nodes = Some("BN".into());
        let text = deck_text(&m, "t");
        assert!(text.contains("*SURFACE, NAME=BN, TYPE=NODE\nBN\n*TIE, NAME=TIE1, POSITION TOLERANCE=0.015\nBN, A\n"), "{text}");
    }

    #[test]
    fn dof_runs() {
        assert_eq!(runs(&[1, 2, 3]), vec![(1, 3)]);
        assert_eq!(runs(&[3, 1]), vec![(1, 1), (3, 3)]);
    }
}
