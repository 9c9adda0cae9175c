//! Nastran decks read back by an independent reader, pyNastran (`tools/ref/nastran_report.py`,
//! version pinned in `tools/ref/requirements.txt`): a unit cube of six tets and the bundled
//! bracket meshed through the library, each as C3D4 and C3D10, in small and large fields.
//! pyNastran must find the same solution, subcase sets, grids (positions within the fields'
//! precision), elements (connectivity and property), materials, SPC'd grid-dofs, FORCE cards and
//! their total, PLOAD4 cards and their resultant (by its own face normals: positive pressure
//! pushes into the element, as `Load::Pressure` asks), GRAV and the LOAD combining them.
//! Without Python and pyNastran the checks skip, except under `CI=true`.

mod common;

use common::tools::{python_with, require};
use fepre::attributes::Positive;
use fepre::attributes::{Density, Selector};
use fepre::core::{FaceId, RegionId};
use fepre::deck::{NastranOptions, NastranSummary, write_nastran};
use fepre::fe::face_corners_outward;
use fepre::fe::consistent_forces;
use fepre::fe::{Analysis, Bc, BoundaryGeometry, BrepGeometry, ElementKind, FeModel, Load, Material, Section, Step, build_model};
use fepre::mesh::TetMesh;
use fepre::pipeline::Part;
use fepre::pipeline::{Plan, run_plan};
use glam::DVec3;
use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;

const TOTAL: DVec3 = DVec3::new(0.0, -300.0, -1000.0);
const PRESSURE: f64 = 2.5;
const GRAVITY: DVec3 = DVec3::new(0.0, 0.0, -9810.0);

/// `built` with steel on every element and a static step: `fixed` held in 1, 2, 3, the force
/// [`TOTAL`] spread over surface `loaded`, [`PRESSURE`] on it, and [`GRAVITY`].
fn with_step(mut m: FeModel, fixed: &str, loaded: &str) -> FeModel {
    m.materials.insert("STEEL".into(), Material { young: Some(210000.0), poisson: Some(0.3), density: Some(7.85e-9), ..Material::default() });
    m.sections.push(Section { element_set: "EALL".into(), material: "STEEL".into() });
    let forces = consistent_forces(&m, &m.surfaces[loaded], TOTAL);
    m.steps.push(Step {
        name: "pull".into(),
        analysis: Analysis::Static,
        bcs: vec![Bc::Fixed { nodes: fixed.into(), dofs: vec![1, 2, 3] }],
        loads: vec![
            Load::Nodal { name: "pull".into(), surface: loaded.into(), total: TOTAL, forces },
            Load::Pressure { surface: loaded.into(), value: PRESSURE },
            Load::Gravity { elements: "EALL".into(), acceleration: GRAVITY },
        ],
    });
    m.validate().expect("a valid model");
    m
}

/// The unit cube as six positively oriented tets around its diagonal 0-6; boundary triangles
/// tagged 1 (x = 0) and 2 (x = 1), 3 elsewhere.
fn cube() -> TetMesh {
    let vertices: Vec<DVec3> = (0..8).map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64)).collect();
    let paths = [[1, 3], [1, 5], [2, 3], [2, 6], [4, 5], [4, 6]];
    let tets: Vec<[u32; 4]> = paths
        .iter()
        .map(|&[a, b]| {
            let t = [0, a, b, 7];
            let p = t.map(|v| vertices[v as usize]);
            if (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) > 0.0 { t } else { [0, b, a, 7] }
        })
        .collect();
    let mut m = TetMesh { vertices, region_tags: vec![RegionId(1); tets.len()], tets, ..TetMesh::default() };
    m.boundary = m.hull_faces();
    m.face_tags = m
        .boundary
        .iter()
        .map(|t| {
            let xs = t.map(|v| m.vertices[v as usize].x);
            FaceId(if xs.iter().all(|&x| x == 0.0) { 1 } else if xs.iter().all(|&x| x == 1.0) { 2 } else { 3 })
        })
        .collect();
    m.validate().expect("a valid cube");
    m
}

/// Python with pyNastran, or `None` after a skip message (a failure under CI).
fn pynastran() -> Option<PathBuf> {
    require(python_with(&["numpy", "pyNastran"]), "python with pyNastran", "reading Nastran decks back")
}

/// pyNastran's report of each deck.
fn read_back(python: &Path, decks: &[PathBuf]) -> Vec<Value> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/ref/nastran_report.py");
    let out = Command::new(python).arg("-W").arg("ignore").arg(&script).args(decks).output().expect("runs python");
    assert!(out.status.success(), "nastran_report.py failed:\n{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap().lines().map(|l| serde_json::from_str(l).expect("one JSON object a line")).collect()
}

fn vec3(v: &Value) -> DVec3 {
    let a: Vec<f64> = v.as_array().expect("an array").iter().map(|x| x.as_f64().unwrap()).collect();
    DVec3::new(a[0], a[1], a[2])
}

/// The resultant of a uniform pressure on `faces`, positive into the elements: minus the
/// pressure times the sum of the outward area vectors of the flat corner triangles.
fn pressure_resultant(m: &FeModel, surface: &str, p: f64) -> DVec3 {
    m.surfaces[surface]
        .iter()
        .map(|f| {
            let el = m.element(f.element as usize);
            let [a, b, c] = face_corners_outward(f.face).map(|k| m.nodes[el[k] as usize]);
            -p * 0.5 * (b - a).cross(c - a)
        })
        .sum()
}

/// Checks pyNastran's report `r` of the deck of `m` (written with `large` fields, `s` its
/// summary) against the model.
fn check(m: &FeModel, s: &NastranSummary, r: &Value, large: bool, fixed: &str, loaded: &str, what: &str) {
    let n = |v: &Value| v.as_u64().unwrap_or_else(|| panic!("{what}: {v} is not a count")) as usize;
    // 8-character fields keep at least 4 significant digits, 16-character ones 10
    let rel = if large { 1e-9 } else { 5e-4 };
    assert_eq!(n(&r["sol"]), 101, "{what}");
    assert_eq!(r["subcases"]["1"]["SPC"], 1, "{what}");
    assert_eq!(r["subcases"]["1"]["LOAD"], 3, "{what}: the LOAD combining FORCE/PLOAD4 (set 1) and GRAV (set 2)");
    // grids
    let grids = r["grids"].as_object().unwrap();
    assert_eq!((grids.len(), s.grids), (m.nodes.len(), m.nodes.len()), "{what}");
    let size = m.nodes.iter().fold(0.0f64, |a, p| a.max(p.abs().max_element()));
    for (i, p) in m.nodes.iter().enumerate() {
        let q = vec3(&grids[&(i + 1).to_string()]);
        assert!((q - *p).abs().max_element() <= rel * size, "{what}: grid {} at {q}, node at {p}", i + 1);
    }
    // elements: the model's nodes, 1-based, in order; property 1 (the one section)
    let elements = r["elements"].as_object().unwrap();
    assert_eq!((elements.len(), s.elements), (m.element_count(), m.element_count()), "{what}");
    for e in 0..m.element_count() {
        let rec = &elements[&(e + 1).to_string()];
        let want: Vec<u64> = m.element(e).iter().map(|&v| u64::from(v) + 1).collect();
        let got: Vec<u64> = rec[1].as_array().unwrap().iter().map(|v| n(v) as u64).collect();
        assert_eq!((n(&rec[0]), got), (1, want), "{what}: element {}", e + 1);
    }
    assert_eq!(r["psolids"]["1"], 1, "{what}");
    let mat = &r["materials"]["1"];
    assert_eq!((mat[0].as_f64(), mat[1].as_f64(), mat[2].as_f64()), (Some(210000.0), Some(0.3), Some(7.85e-9)), "{what}");
    // constraints: every node of the fixed set, three dofs each
    let fixed_nodes: BTreeSet<u32> = m.node_sets[fixed].iter().copied().collect();
    assert_eq!((n(&r["spc_dofs"]), s.spc_dofs), (3 * fixed_nodes.len(), 3 * fixed_nodes.len()), "{what}");
    // forces: one card per loaded node (but for the round-off zeros at the corners of flat
    // 6-node faces), the total as written and as asked
    let Load::Nodal { forces, .. } = &m.steps[0].loads[0] else { unreachable!() };
    let largest = forces.iter().fold(0.0f64, |a, (_, f)| a.max(f.length()));
    let loaded_nodes = forces.iter().filter(|(_, f)| f.length() > 1e-12 * largest).count();
    assert_eq!((n(&r["force_cards"]), s.force_cards), (loaded_nodes, loaded_nodes), "{what}");
    let force_total = vec3(&r["force_total"]);
    assert!((force_total - s.force_total).length() <= 1e-9 * TOTAL.length(), "{what}: pyNastran {force_total}, fepre {}", s.force_total);
    assert!((force_total - TOTAL).length() <= 1e-3 * TOTAL.length(), "{what}: FORCE total {force_total}, asked {TOTAL}");
    // pressure: one PLOAD4 per face, the resultant into the elements
    let faces = m.surfaces[loaded].len();
    assert_eq!((n(&r["pload4_cards"]), s.pload4_cards), (faces, faces), "{what}");
    let want = pressure_resultant(m, loaded, PRESSURE);
    let got = vec3(&r["pload4_total"]);
    println!("{what}: pyNastran reads {} grids, {} CTETRA, {} SPC'd grid-dofs, {} FORCE totalling {force_total}, {faces} PLOAD4 with resultant {got} (into the elements: {want})", grids.len(), elements.len(), n(&r["spc_dofs"]), n(&r["force_cards"]));
    assert!((got - want).length() <= 1e-3 * want.length(), "{what}: PLOAD4 resultant {got}, into the elements {want}");
    // gravity in its own set, combined with the others by LOAD 3
    assert_eq!(s.grav_cards, 1);
    let g = vec3(&r["grav"]["2"]);
    assert!((g - GRAVITY).length() <= 1e-9 * GRAVITY.length(), "{what}: GRAV {g}");
    assert_eq!(r["load_combinations"]["3"], serde_json::json!([[1.0, 1], [1.0, 2]]), "{what}");
}

/// Writes the deck of `m` in small and large fields under `dir`, reads both back, checks them.
fn write_and_check(python: &Path, dir: &Path, m: &FeModel, fixed: &str, loaded: &str, what: &str) {
    let mut decks = Vec::new();
    let mut summaries = Vec::new();
    for large in [false, true] {
        let path = dir.join(format!("{what}-{}.bdf", if large { "large" } else { "small" }));
        summaries.push(write_nastran(&path, m, &NastranOptions::default().with_large(large)).expect("writes"));
        decks.push(path);
    }
    let reports = read_back(python, &decks);
    assert_eq!(reports.len(), 2);
    for ((r, s), large) in reports.iter().zip(&summaries).zip([false, true]) {
        check(m, s, r, large, fixed, loaded, &format!("{what}, large fields {large}"));
    }
}

#[test]
fn cube_decks_read_back_with_pynastran() {
    let Some(python) = pynastran() else { return };
    let dir = tempfile::tempdir().unwrap();
    let groups = BTreeMap::from([("x0".to_string(), vec![FaceId(1)]), ("x1".to_string(), vec![FaceId(2)])]);
    for kind in [ElementKind::C3D4, ElementKind::C3D10] {
        let built = build_model(&cube(), &groups, kind, None, 1.0);
        let (fixed, loaded) = (built.groups["x0"].node_set.clone(), built.groups["x1"].surface.clone());
        let m = with_step(built.model, &fixed, &loaded);
        // the pressure on x = 1 pushes towards -x: the cube's face there has area 1
        assert!((pressure_resultant(&m, &loaded, PRESSURE) - DVec3::new(-PRESSURE, 0.0, 0.0)).length() < 1e-12);
        write_and_check(&python, dir.path(), &m, &fixed, &loaded, &format!("cube-{}", kind.name()));
    }
}

#[test]
fn a_frequency_deck_reads_back_with_pynastran() {
    let Some(python) = pynastran() else { return };
    let dir = tempfile::tempdir().unwrap();
    let groups = BTreeMap::from([("x0".to_string(), vec![FaceId(1)])]);
    let built = build_model(&cube(), &groups, ElementKind::C3D10, None, 1.0);
    let fixed = built.groups["x0"].node_set.clone();
    let mut m = with_step(built.model, &fixed, &built.groups["x0"].surface.clone());
    m.steps = vec![Step { name: "modes".into(), analysis: Analysis::Frequency { modes: 8 }, bcs: vec![Bc::Fixed { nodes: fixed.clone(), dofs: vec![1, 2, 3] }], loads: vec![] }];
    let path = dir.path().join("modes.bdf");
    let s = write_nastran(&path, &m, &NastranOptions::default()).unwrap();
    let r = &read_back(&python, &[path])[0];
    assert_eq!((r["sol"].as_u64(), s.sol), (Some(103), 103));
    assert_eq!(r["subcases"]["1"]["METHOD"], 1);
    assert_eq!(r["subcases"]["1"]["SPC"], 1);
    assert!(r["subcases"]["1"].get("LOAD").is_none());
    assert_eq!(r["eigrl"]["1"], 8);
    assert_eq!(r["spc_dofs"].as_u64(), Some(3 * m.node_sets[&fixed].len() as u64));
}

#[test]
fn bracket_decks_read_back_with_pynastran() {
    let Some(python) = pynastran() else { return };
    let step = Path::new(env!("CARGO_MANIFEST_DIR")).join("cad_fixtures/bracket.step");
    let mut part = Part::open(&step).expect("opens the bracket");
    let mut density = Density::default();
    density.size = Positive::new(12.0);
    let selectors = BTreeMap::from([("fixed".to_string(), Selector::Name("end_y".into())), ("loaded".to_string(), Selector::Name("end_x".into()))]);
    let plan = Plan { selectors, density, unit: 1.0, ..Plan::default() };
    let report = run_plan(&mut part, &plan, false).expect("meshes the bracket");
    let mesh = part.mesh.as_ref().unwrap();
    let brep = part.model.as_ref().unwrap();
    let geometry = BrepGeometry::new(brep);
    let dir = tempfile::tempdir().unwrap();
    for kind in [ElementKind::C3D4, ElementKind::C3D10] {
        let built = build_model(mesh, &report.selectors, kind, Some(&geometry as &dyn BoundaryGeometry), 1.0);
        let (fixed, loaded) = (built.groups["fixed"].node_set.clone(), built.groups["loaded"].surface.clone());
        let m = with_step(built.model, &fixed, &loaded);
        println!("bracket {}: {} nodes, {} elements, {} faces loaded", kind.name(), m.nodes.len(), m.element_count(), m.surfaces[&loaded].len());
        write_and_check(&python, dir.path(), &m, &fixed, &loaded, &format!("bracket-{}", kind.name()));
    }
}

#[test]
fn two_static_subcases_and_a_prescribed_displacement_read_back_with_pynastran() {
    let Some(python) = pynastran() else { return };
    let dir = tempfile::tempdir().unwrap();
    let groups = BTreeMap::from([("x0".to_string(), vec![FaceId(1)]), ("x1".to_string(), vec![FaceId(2)])]);
    let built = build_model(&cube(), &groups, ElementKind::C3D4, None, 1.0);
    let (fixed, pulled, loaded) = (built.groups["x0"].node_set.clone(), built.groups["x1"].node_set.clone(), built.groups["x1"].surface.clone());
    let mut m = with_step(built.model, &fixed, &loaded);
    m.steps.push(Step {
        name: "stretch".into(),
        analysis: Analysis::Static,
        bcs: vec![Bc::Fixed { nodes: fixed.clone(), dofs: vec![1, 2, 3] }, Bc::Displacement { nodes: pulled.clone(), dof: 1, value: 0.01 }],
        loads: vec![],
    });
    let path = dir.path().join("two.bdf");
    let s = write_nastran(&path, &m, &NastranOptions::default()).unwrap();
    let r = &read_back(&python, &[path])[0];
    // step 2 of 2: SPC set 2 and no loads; step 1's sets: FORCE/PLOAD4 1, GRAV 3, LOAD 5
    assert_eq!(s.subcases, 2);
    assert_eq!(r["subcases"]["1"], serde_json::json!({"SPC": 1, "LOAD": 5}));
    assert_eq!(r["subcases"]["2"], serde_json::json!({"SPC": 2}));
    assert_eq!(r["load_combinations"]["5"], serde_json::json!([[1.0, 1], [1.0, 3]]));
    let (nf, np) = (m.node_sets[&fixed].len(), m.node_sets[&pulled].len());
    assert_eq!(r["spc_dofs"].as_u64(), Some((3 * nf + 3 * nf + np) as u64));
    assert_eq!(s.spc_dofs, 3 * nf + 3 * nf + np);
    assert_eq!(r["spc_values"]["2"], serde_json::json!([[0.01, np]]));
}
