//! Ties between solids that touch without sharing nodes: two blocks stacked end to end, their
//! touching faces tessellated differently, get one `*TIE` (slave the finer side); CalculiX
//! solves the pair as one bar: the reaction equals the load, the interface moves as one (the
//! slave nodes follow the master faces) and the tip deflects as a single block of the same
//! length does; the same with the blocks aligned, whose contact is conforming in part (a
//! node-based slave surface); these run with `[model] contacts = "tie"`. By default
//! (`contacts = "conforming"`) the pair is imprinted: one mesh sharing the interface's nodes,
//! no tie, the tip deflection of one block within 0.5 %. Without joining them
//! (`contacts = "none"`) holding one block is singular.
//!
//! A missing `ccx` skips the solve with a message, except under `CI=true` where it fails.

mod common;

use common::tools;
use fepre::cad::brep::Model;
use fepre::cad::geom::Rigid;
use fepre::cad::parts::Block;
use fepre::io::frd::{self, FrdResults};
use fepre::pipeline::job::JobFile;
use fepre::pipeline::carry_out;
use fepre::pipeline::{SolveReport, solve_job};
use glam::{DMat3, DVec3};
use std::collections::{BTreeSet, HashMap};
use std::path::Path;

const STEEL: &str = "[materials.steel]\nyoung = 210000\npoisson = 0.3\n[[section]]\nmaterial = \"steel\"\n";

/// Each block's length (x); the cross-section is `SIDE` × `SIDE`.
const HALF: f64 = 20.0;
const SIDE: f64 = 10.0;

/// `m` rotated by `rotation`, then moved by `d`.
fn moved(m: &Model, rotation: DMat3, d: DVec3) -> Model {
    let t = Rigid { rotation, translation: d };
    let mut m = m.clone();
    m.vertices.iter_mut().for_each(|v| v.point = rotation * v.point + d);
    m.surfaces = m.surfaces.iter().map(|s| s.transformed(&t)).collect();
    m.curves = m.curves.iter().map(|c| c.transformed(&t)).collect();
    m
}

/// Two blocks `HALF` × `SIDE` × `SIDE` end to end along x, touching at x = `HALF`; the second
/// turned a quarter turn about the bar's axis (onto the same footprint), so that its end face
/// is parametrized, hence tessellated, differently from the first's.
fn stacked_pair() -> Model {
    let a = Block::new(HALF, SIDE, SIDE).build().unwrap();
    let mut two = a.clone();
    two.append(&moved(&a, DMat3::from_rotation_x(std::f64::consts::FRAC_PI_2), DVec3::new(HALF, SIDE, 0.0)));
    two
}

/// The far ends, both blocks' contact faces, and a size.
/// Contacts tied, not imprinted.
const TIED: &str = "[model]\ncontacts = \"tie\"\n";

fn selectors(length: f64) -> String {
    let bx = |x: f64| format!("{{ inside = {{ min = [{}, -1, -1], max = [{}, {}, {}] }} }}", x - 0.1, x + 0.1, SIDE + 1.0, SIDE + 1.0);
    format!("[selectors]\ntip = {}\nclamp = {}\n[density]\nsize = 3\n", bx(0.0), bx(length))
}

/// A static step: the clamp held, the tip pulled down with `p`.
fn bending(p: f64) -> String {
    format!("{STEEL}[[step]]\nfixed = [{{ faces = \"clamp\" }}]\nforce = [{{ faces = \"tip\", total = [0, 0, {}] }}]\n", -p)
}

fn write_job(dir: &Path, name: &str, part: &Model, job: &str) -> JobFile {
    fepre::cad::step::write(&dir.join(format!("{name}.step")), part, name).unwrap();
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, format!("[input]\nfile = \"{name}.step\"\n{job}[[output]]\nfile = \"{name}.inp\"\n")).unwrap();
    JobFile::read(&path).unwrap()
}

#[test]
fn touching_blocks_meshed_differently_get_one_tie_slave_the_finer_side() {
    let dir = tempfile::tempdir().unwrap();
    let jf = write_job(dir.path(), "pair", &stacked_pair(), &format!("{TIED}{}{}", selectors(2.0 * HALF), bending(1000.0)));
    let outcome = carry_out(&jf, false).unwrap();
    // the contact: the whole end face, not conforming
    let contacts = &outcome.part.contacts;
    assert_eq!(contacts.len(), 1, "{contacts:?}");
    let c = &contacts[0];
    assert!((c.area - SIDE * SIDE).abs() < 1e-6 * SIDE * SIDE, "{c:?}");
    assert!(c.area - c.shared_area > 0.5 * c.area, "the contact is mostly conforming: {c:?}");
    // one tie, slave the side with more element faces, within the gap
    let fe = outcome.fe.as_ref().unwrap();
    fe.validate().unwrap();
    assert_eq!(fe.ties.len(), 1, "{:?}", fe.ties);
    let t = &fe.ties[0];
    let (ns, nm) = (fe.surfaces[&t.slave].len(), fe.surfaces[&t.master].len());
    assert!(ns >= nm && nm > 0, "slave {ns} faces, master {nm}");
    assert!(t.tolerance > 0.0 && t.tolerance < 0.1 * SIDE, "{t:?}");
    let summary = &outcome.report.fe.as_ref().unwrap().ties;
    assert_eq!(summary.len(), 1);
    assert_eq!((summary[0].slave_faces, summary[0].master_faces), (ns, nm));
    // every element face of the two surfaces lies on the contact plane
    for s in [&t.slave, &t.master] {
        for f in &fe.surfaces[s] {
            let el = fe.element(f.element as usize);
            for k in fepre::fe::ABAQUS_FACES[f.face as usize] {
                assert!((fe.nodes[el[k] as usize].x - HALF).abs() < 1e-9, "{s}: a face off the contact plane");
            }
        }
    }
    // the deck holds one *TIE after the surfaces and before the step
    let deck = std::fs::read_to_string(dir.path().join("pair.inp")).unwrap();
    let ties: Vec<&str> = deck.lines().filter(|l| l.starts_with("*TIE")).collect();
    assert_eq!(ties.len(), 1, "{ties:?}");
    assert!(ties[0].starts_with(&format!("*TIE, NAME={}, POSITION TOLERANCE=", t.name)), "{}", ties[0]);
    let at = deck.find("*TIE").unwrap();
    assert!(deck.contains(&format!("*TIE, NAME={}, POSITION TOLERANCE={}\n{}, {}\n", t.name, fepre::deck::inp_number(t.tolerance), t.slave, t.master)));
    assert!(deck.rfind("*SURFACE").unwrap() < at && at < deck.find("*STEP").unwrap());
}

#[test]
fn without_the_tie_holding_one_block_is_singular() {
    let dir = tempfile::tempdir().unwrap();
    let jf = write_job(dir.path(), "pair", &stacked_pair(), &format!("[model]\ncontacts = \"none\"\n{}{}", selectors(2.0 * HALF), bending(1000.0)));
    let e = carry_out(&jf, false).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("singular") && e.contains("6 rigid-body motion(s) are free"), "{e}");
    assert!(!dir.path().join("pair.inp").exists());
}

/// The deck's elements (1-based node ids) and the faces of surface `name` (element, 0-based
/// Abaqus face), parsed from the text.
fn deck_elements_and_surface(deck: &str, name: &str) -> (HashMap<u32, Vec<u32>>, Vec<(u32, usize)>) {
    let (mut elements, mut faces) = (HashMap::new(), Vec::new());
    let mut mode = 0;
    for line in deck.lines().filter(|l| !l.starts_with("**")) {
        if line.starts_with('*') {
            mode = if line.starts_with("*ELEMENT") {
                1
            } else if line.eq_ignore_ascii_case(&format!("*SURFACE, NAME={name}, TYPE=ELEMENT")) {
                2
            } else {
                0
            };
            continue;
        }
        let v: Vec<&str> = line.split(',').map(str::trim).collect();
        match mode {
            1 => {
                elements.insert(v[0].parse().unwrap(), v[1..].iter().map(|x| x.parse().unwrap()).collect());
            }
            2 => faces.push((v[0].parse().unwrap(), v[1].trim_start_matches('S').parse::<usize>().unwrap() - 1)),
            _ => {}
        }
    }
    (elements, faces)
}

/// The 6 nodes of a C3D10 element face: corners, then the mid nodes of edges 01, 12, 20 of
/// the face.
fn face_nodes(el: &[u32], face: usize) -> [u32; 6] {
    const FACES: [[usize; 3]; 4] = [[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]];
    let mid = |a: usize, b: usize| {
        let k = match (a.min(b), a.max(b)) {
            (0, 1) => 4,
            (1, 2) => 5,
            (0, 2) => 6,
            (0, 3) => 7,
            (1, 3) => 8,
            _ => 9,
        };
        el[k]
    };
    let [a, b, c] = FACES[face];
    [el[a], el[b], el[c], mid(a, b), mid(b, c), mid(c, a)]
}

/// Writes and solves the job; the report and the results.
fn solve(jf: &JobFile) -> (SolveReport, FrdResults) {
    let report = solve_job(jf).unwrap_or_else(|e| panic!("{e}"));
    let r = frd::read(Path::new(&report.frd)).unwrap();
    (report, r)
}

/// The last increment's displacement per node number.
fn displacements(r: &FrdResults) -> HashMap<u32, DVec3> {
    let step = r.steps.iter().rev().find(|s| s.field("DISP").is_some()).unwrap();
    step.field("DISP").unwrap().per_node().map(|(n, u)| (n, DVec3::new(u[0], u[1], u[2]))).collect()
}

/// The mean z displacement of the nodes at x = 0 (the tip).
fn tip_deflection(r: &FrdResults, u: &HashMap<u32, DVec3>) -> f64 {
    let tip: Vec<f64> = r.nodes.iter().filter(|(_, p)| p.x.abs() < 1e-9).map(|(n, _)| -u[n].z).collect();
    tip.iter().sum::<f64>() / tip.len() as f64
}

/// The node ids of node set `name` in the deck.
fn deck_node_set(deck: &str, name: &str) -> BTreeSet<u32> {
    let head = format!("*NSET, NSET={name}\n");
    let at = deck.find(&head).unwrap_or_else(|| panic!("no node set {name}")) + head.len();
    deck[at..].lines().take_while(|l| !l.starts_with('*')).flat_map(|l| l.split(',').map(|x| x.trim().parse::<u32>().unwrap())).collect()
}

/// For each slave node of the tie (the nodes of `slave`'s faces, or of the node set of a
/// node-based slave surface), its displacement against the master faces' at the same (y, z) on
/// the plane x = `HALF` (quadratic interpolation on the 6-node face that holds it): the
/// largest difference, and the number of slave nodes checked.
fn interface_mismatch(deck: &str, slave: &str, master: &str, positions: &HashMap<u32, DVec3>, u: &HashMap<u32, DVec3>) -> (f64, usize) {
    let (elements, s_faces) = deck_elements_and_surface(deck, slave);
    let (_, m_faces) = deck_elements_and_surface(deck, master);
    let slave_nodes: BTreeSet<u32> = if deck.contains(&format!("*SURFACE, NAME={slave}, TYPE=NODE\n")) { deck_node_set(deck, slave) } else { s_faces.iter().flat_map(|&(e, f)| face_nodes(&elements[&e], f)).collect() };
    let masters: Vec<[u32; 6]> = m_faces.iter().map(|&(e, f)| face_nodes(&elements[&e], f)).collect();
    let yz = |n: u32| {
        let p = positions[&n];
        glam::DVec2::new(p.y, p.z)
    };
    let mut worst = 0.0f64;
    for &n in &slave_nodes {
        let q = yz(n);
        // the master face whose corners' triangle holds q best (largest smallest barycentric)
        let mut best = (f64::NEG_INFINITY, [0.0; 3], 0);
        for (k, f) in masters.iter().enumerate() {
            let (a, b, c) = (yz(f[0]), yz(f[1]), yz(f[2]));
            let d = (b - a).perp_dot(c - a);
            let l1 = (b - q).perp_dot(c - q) / d;
            let l2 = (c - q).perp_dot(a - q) / d;
            let l = [l1, l2, 1.0 - l1 - l2];
            let m = l[0].min(l[1]).min(l[2]);
            if m > best.0 {
                best = (m, l, k);
            }
        }
        let (_, l, k) = best;
        let f = masters[k];
        let w = [l[0] * (2.0 * l[0] - 1.0), l[1] * (2.0 * l[1] - 1.0), l[2] * (2.0 * l[2] - 1.0), 4.0 * l[0] * l[1], 4.0 * l[1] * l[2], 4.0 * l[2] * l[0]];
        let um: DVec3 = f.iter().zip(w).map(|(v, w)| u[v] * w).sum();
        worst = worst.max((u[&n] - um).length());
    }
    (worst, slave_nodes.len())
}

/// The same two blocks, the second not turned: the end faces are tessellated alike in part,
/// so the contact is partly conforming (nodes shared there) and partly tied.
fn aligned_pair() -> Model {
    let a = Block::new(HALF, SIDE, SIDE).build().unwrap();
    let mut two = a.clone();
    two.append(&moved(&a, DMat3::IDENTITY, DVec3::new(HALF, 0.0, 0.0)));
    two
}

/// What a solve of a pair measured.
struct PairRun {
    reaction: [f64; 3],
    /// The largest difference between a slave node's displacement and the master faces'.
    mismatch: f64,
    /// Slave nodes checked.
    checked: usize,
    /// The largest displacement.
    u_max: f64,
    /// The mean tip deflection.
    tip: f64,
    /// The contact's conforming fraction.
    shared: f64,
}

/// Solves `part` (two blocks end to end) under the tip force `p`: the far block's end
/// (x = 2·HALF) clamped, the force on the other's (x = 0).
fn solve_pair(dir: &Path, name: &str, part: &Model, p: f64) -> PairRun {
    let jf = write_job(dir, name, part, &format!("{TIED}{}{}", selectors(2.0 * HALF), bending(p)));
    let (report, r) = solve(&jf);
    let c = &report.run.contacts[0];
    let u = displacements(&r);
    let positions: HashMap<u32, DVec3> = r.nodes.iter().copied().collect();
    let deck = std::fs::read_to_string(&report.deck).unwrap();
    let ties: Vec<&str> = deck.lines().filter(|l| l.starts_with("*TIE")).collect();
    assert_eq!(ties.len(), 1, "{name}: {ties:?}");
    let tie = deck.lines().skip_while(|l| !l.starts_with("*TIE")).nth(1).unwrap();
    let (slave, master) = tie.split_once(',').map(|(a, b)| (a.trim(), b.trim())).unwrap();
    let (mismatch, checked) = interface_mismatch(&deck, slave, master, &positions, &u);
    let u_max = u.values().map(|v| v.length()).fold(0.0, f64::max);
    PairRun { reaction: report.steps[0].reactions["CLAMP"], mismatch, checked, u_max, tip: tip_deflection(&r, &u), shared: c.shared_area / c.area }
}

/// The mean tip deflection of one block as long as the pair, solved the same way.
fn single_block_tip(dir: &Path, p: f64) -> f64 {
    let jf = write_job(dir, "single", &Block::new(2.0 * HALF, SIDE, SIDE).build().unwrap(), &format!("{}{}", selectors(2.0 * HALF), bending(p)));
    let (_, rs) = solve(&jf);
    tip_deflection(&rs, &displacements(&rs))
}

#[test]
fn a_tied_pair_under_a_tip_force_bends_as_one_block() {
    if tools::require(tools::ccx(), "ccx (CalculiX)", "the tied pair's solve").is_none() {
        return;
    }
    let p = 1000.0;
    let dir = tempfile::tempdir().unwrap();
    let single = single_block_tip(dir.path(), p);
    for (name, part) in [("turned", stacked_pair()), ("aligned", aligned_pair())] {
        let run = solve_pair(dir.path(), name, &part, p);
        let ratio = run.tip / single;
        eprintln!(
            "tied pair ({name}, {:.1} % of the contact conforming): reaction {:?} (force {p}); {} slave nodes move with the master faces within {:.3e} ({:.2e} of the largest displacement {:.4e}); tip deflection {:.6} against one block's {single:.6}: ratio {ratio:.4}",
            100.0 * run.shared,
            run.reaction,
            run.checked,
            run.mismatch,
            run.mismatch / run.u_max,
            run.u_max,
            run.tip
        );
        let r = run.reaction;
        assert!((r[2] - p).abs() <= 1e-6 * p && r[0].abs() <= 1e-6 * p && r[1].abs() <= 1e-6 * p, "{name}: reaction {r:?} against the tip force {p}");
        assert!(run.checked > 0);
        // the .frd holds 6 significant digits: the interpolated master displacement carries
        // rounding of a few 1e-6 of the largest displacement
        assert!(run.mismatch <= 2e-5 * run.u_max, "{name}: the slave nodes move apart from the master faces: {} (largest displacement {})", run.mismatch, run.u_max);
        assert!((ratio - 1.0).abs() < 0.03, "{name}: tied pair tip deflection {} against one block's {single}", run.tip);
    }
}

#[test]
fn an_imprinted_pair_shares_its_interface_and_bends_as_one_block() {
    if tools::require(tools::ccx(), "ccx (CalculiX)", "the imprinted pair's solve").is_none() {
        return;
    }
    let p = 1000.0;
    let dir = tempfile::tempdir().unwrap();
    let single = single_block_tip(dir.path(), p);
    // the turned pair: its end faces tessellated differently, imprinted into one
    let jf = write_job(dir.path(), "pair", &stacked_pair(), &format!("{}{}", selectors(2.0 * HALF), bending(p)));
    let (report, r) = solve(&jf);
    let c = &report.run.contacts[0];
    assert!((c.shared_area - c.area).abs() <= 1e-9 * c.area, "the contact is conforming: {c:?}");
    let deck = std::fs::read_to_string(&report.deck).unwrap();
    assert!(!deck.lines().any(|l| l.starts_with("*TIE")), "a conforming contact needs no tie");
    let u = displacements(&r);
    let tip = tip_deflection(&r, &u);
    let reaction = report.steps[0].reactions["CLAMP"];
    eprintln!("imprinted pair: tip deflection {tip:.6} against one block's {single:.6}: ratio {:.5}; reaction {reaction:?}", tip / single);
    assert!((reaction[2] - p).abs() <= 1e-6 * p, "reaction {reaction:?} against the tip force {p}");
    assert!((tip / single - 1.0).abs() < 0.005, "imprinted pair tip deflection {tip} against one block's {single}");
}

/// A real assembly (the corpus' `as1-tu-203`: 18 solids, 88 pairs of touching faces, none
/// conforming) tied and solved under gravity, fixed on its largest face: CalculiX accepts the
/// ties (a plate face under several bolts, ties that would chain), the solids carry their
/// weight to the support.
#[test]
fn a_corpus_assembly_tied_together_carries_its_weight() {
    let Some(part) = common::corpus_file("as1-tu-203.stp") else { return };
    if common::tools::require(common::tools::ccx(), "ccx (CalculiX)", "the tied corpus assembly").is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let job = format!(
        "[input]\nfile = \"{}\"\n[selectors]\nbase = {{ largest = {{ count = 1 }} }}\n[model]\nelement = \"C3D4\"\n[materials.steel]\nyoung = 210000\npoisson = 0.3\ndensity = 7.85e-9\n[[section]]\nmaterial = \"steel\"\n[[step]]\nfixed = [{{ faces = \"base\" }}]\ngravity = [{{ acceleration = [0, 0, -9810] }}]\n[[output]]\nfile = \"as1.inp\"\n",
        part.display()
    );
    std::fs::write(dir.path().join("as1.toml"), job).unwrap();
    let jf = fepre::pipeline::job::JobFile::read(&dir.path().join("as1.toml")).unwrap();
    let report = fepre::pipeline::solve_job(&jf).unwrap_or_else(|e| panic!("{e}"));
    let fe = report.run.fe.as_ref().unwrap();
    let open = report.run.contacts.iter().filter(|c| c.area - c.shared_area > 1e-3 * c.area).count();
    assert!(fe.ties.len() > 0 && fe.ties.len() <= open, "{} ties for {open} non-conforming contacts", fe.ties.len());
    let weight = report.run.mesh.as_ref().unwrap().volume * 7.85e-9 * 9810.0;
    let reaction = report.steps[0].reactions["BASE"][2];
    eprintln!("as1-tu-203: {} ties, reaction {reaction:.4} N of a weight {weight:.4} N (the rest loads the support's own nodes)", fe.ties.len());
    assert!(reaction > 0.8 * weight && reaction <= weight, "reaction {reaction} against the weight {weight}");
}
