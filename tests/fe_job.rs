//! The FE model through job files: bad jobs exit 1 naming the key and write nothing; every
//! selector's `*SURFACE` holds exactly the tet faces whose triangles carry its CAD faces; C3D10
//! mid nodes of the boundary lie on their CAD faces (elbow, flange) and CalculiX runs the
//! deck; meshio reads the deck.

mod common;

use common::tools;
use fepre::cad::brep::Model;
use fepre::cad::geom::Rigid;
use fepre::cad::parts::{Block, Elbow, Flange};
use fepre::core::FaceId;
use fepre::pipeline::job::JobFile;
use fepre::pipeline::carry_out;
use glam::DVec3;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::process::Command;

const STEEL: &str = "[materials.steel]\nyoung = 210000\npoisson = 0.3\n[[section]]\nmaterial = \"steel\"\n";

fn write_part(dir: &Path, name: &str, m: &Model) {
    fepre::cad::step::write(&dir.join(format!("{name}.step")), m, name).unwrap();
}

/// `fepre run` on `job` (after an `[input]` of `part.step`) in `dir`: exit code, stderr.
fn run_job(dir: &Path, job: &str) -> (i32, String) {
    let path = dir.join("job.toml");
    std::fs::write(&path, format!("[input]\nfile = \"part.step\"\n{job}")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_fepre")).arg("run").arg(&path).output().unwrap();
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// The block shifted by `d`.
fn shifted(m: &Model, d: DVec3) -> Model {
    let t = Rigid { translation: d, ..Rigid::IDENTITY };
    let mut m = m.clone();
    m.vertices.iter_mut().for_each(|v| v.point += d);
    m.surfaces = m.surfaces.iter().map(|s| s.transformed(&t)).collect();
    m.curves = m.curves.iter().map(|c| c.transformed(&t)).collect();
    m
}

#[test]
fn bad_jobs_exit_1_naming_the_key_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    write_part(dir.path(), "part", &Block::new(20.0, 10.0, 10.0).build().unwrap());
    let head = "[selectors]\nclamp = { name = \"xmin\" }\ntip = { name = \"xmax\" }\n[density]\nsize = 4\n";
    let out = "[[output]]\nfile = \"out.inp\"\n";
    // (job, the text of the line the error must name, a word the message must hold)
    let cases: Vec<(String, &str, &str)> = vec![
        // a selector that is not defined
        (format!("{head}{STEEL}[[step]]\nfixed = [{{ faces = \"clamp\" }}]\nforce = [{{ faces = \"tipp\", total = [0, 0, -1] }}]\n{out}"), "force =", "tipp"),
        // a selector that selects nothing
        (format!("{head}nothing = {{ name = \"no_such_face\" }}\n{STEEL}[[step]]\nfixed = [{{ faces = \"clamp\" }}]\n{out}"), "nothing =", "nothing"),
        // a solid without a material
        (format!("{head}[[step]]\nfixed = [{{ faces = \"clamp\" }}]\nforce = [{{ faces = \"tip\", total = [0, 0, -1] }}]\n{out}"), "[[step]]", "material"),
        // a material without what the step needs
        (format!("{head}[materials.steel]\nyoung = 210000\n[[section]]\nmaterial = \"steel\"\n[[step]]\nfixed = [{{ faces = \"clamp\" }}]\n{out}"), "[materials.steel]", "poisson"),
        // a static step held in one direction only: singular
        (format!("{head}{STEEL}[[step]]\nfixed = [{{ faces = \"clamp\", dofs = [1] }}]\nforce = [{{ faces = \"tip\", total = [1, 0, 0] }}]\n{out}"), "[[step]]", "singular"),
        // a heat key in a static step
        (format!("{head}{STEEL}[[step]]\nfixed = [{{ faces = \"clamp\" }}]\ntemperature = [{{ faces = \"tip\", value = 1 }}]\n{out}"), "temperature =", "temperature"),
        // an undefined material
        (format!("{head}[materials.steel]\nyoung = 1\npoisson = 0.3\n[[section]]\nmaterial = \"stel\"\n{out}"), "material = \"stel\"", "stel"),
        // a bad Poisson's ratio
        (format!("{head}[materials.steel]\nyoung = 1\npoisson = 0.7\n{out}"), "poisson =", "poisson"),
    ];
    for (job, marker, word) in cases {
        let (code, err) = run_job(dir.path(), &job);
        let full = format!("[input]\nfile = \"part.step\"\n{job}");
        let line = full.lines().position(|l| l.contains(marker)).unwrap() + 1;
        assert_eq!(code, 1, "{job}\n{err}");
        assert!(err.contains(&format!("job.toml:{line}:")) && err.contains(word), "line {line}, `{word}` expected in: {err}\n{job}");
        assert!(!dir.path().join("out.inp").exists(), "{err}");
    }
    // the same job, well formed, writes the deck
    let good = format!("{head}{STEEL}[[step]]\nfixed = [{{ faces = \"clamp\" }}]\nforce = [{{ faces = \"tip\", total = [0, 0, -1] }}]\n{out}");
    let (code, err) = run_job(dir.path(), &good);
    assert_eq!(code, 0, "{err}");
    assert!(dir.path().join("out.inp").is_file());
}

#[test]
fn a_boundary_condition_on_faces_between_two_solids_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let a = Block::new(20.0, 10.0, 10.0).build().unwrap();
    let mut two = a.clone();
    two.append(&shifted(&a, DVec3::new(20.0, 0.0, 0.0)));
    write_part(dir.path(), "part", &two);
    // the first block's xmax touches the second's xmin: an interface inside the model
    let job = format!(
        "[selectors]\nclamp = {{ inside = {{ min = [-1, -1, -1], max = [1, 11, 11] }} }}\ninner = {{ inside = {{ min = [19, -1, -1], max = [21, 11, 11] }} }}\n[density]\nsize = 4\n{STEEL}[[step]]\nfixed = [{{ faces = \"clamp\" }}]\npressure = [{{ faces = \"inner\", value = 1 }}]\n[[output]]\nfile = \"out.inp\"\n"
    );
    let (code, err) = run_job(dir.path(), &job);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("between two solids") && err.contains("job.toml:15:"), "{err}");
    assert!(!dir.path().join("out.inp").exists());
}

/// Parses a deck's `*SURFACE` blocks and elements: surface name → set of sorted corner node
/// triples (1-based ids), with the Abaqus face corners written out here, not taken from fepre.
fn deck_surfaces(text: &str) -> BTreeMap<String, BTreeSet<[u32; 3]>> {
    const FACES: [[usize; 3]; 4] = [[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]];
    let mut elements: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
    let mut surfaces: BTreeMap<String, Vec<(u32, usize)>> = BTreeMap::new();
    let mut mode = None::<String>;
    for line in text.lines() {
        if line.starts_with("**") {
            continue;
        }
        if line.starts_with('*') {
            let up = line.to_ascii_uppercase();
            mode = if up.starts_with("*ELEMENT") {
                Some(String::new())
            } else if up.starts_with("*SURFACE") {
                let name = up.split(',').find_map(|k| k.trim().strip_prefix("NAME=").map(str::to_string)).unwrap();
                surfaces.insert(name.clone(), Vec::new());
                Some(name)
            } else {
                None
            };
            continue;
        }
        match mode.as_deref() {
            Some("") => {
                let v: Vec<u32> = line.split(',').map(|x| x.trim().parse().unwrap()).collect();
                elements.insert(v[0], v[1..].to_vec());
            }
            Some(name) => {
                let (e, s) = line.split_once(',').unwrap();
                let face: usize = s.trim().trim_start_matches('S').parse().unwrap();
                surfaces.get_mut(name).unwrap().push((e.trim().parse().unwrap(), face - 1));
            }
            None => {}
        }
    }
    surfaces
        .into_iter()
        .map(|(name, faces)| {
            let set = faces
                .into_iter()
                .map(|(e, f)| {
                    let el = &elements[&e];
                    let mut c = FACES[f].map(|k| el[k]);
                    c.sort_unstable();
                    c
                })
                .collect();
            (name, set)
        })
        .collect()
}

/// For a part, a job with one selector per CAD face: each `*SURFACE` of the deck equals the
/// boundary triangles of the mesh that carry that face's tag.
fn surfaces_are_the_tagged_faces(part: &Path, size: f64, element: &str) {
    let dir = tempfile::tempdir().unwrap();
    let model = fepre::cad::step::read(part).unwrap();
    let mut job = format!("[input]\nfile = \"{}\"\n[selectors]\n", std::fs::canonicalize(part).unwrap().display());
    for f in model.face_ids() {
        job.push_str(&format!("f{} = {{ faces = [{}] }}\n", f.0, f.0));
    }
    job.push_str(&format!("[density]\nsize = {size}\n[model]\nelement = \"{element}\"\n[[output]]\nfile = \"deck.inp\"\n"));
    let path = dir.path().join("job.toml");
    std::fs::write(&path, &job).unwrap();
    let jf = JobFile::read(&path).unwrap();
    let outcome = carry_out(&jf, false).unwrap();
    let mesh = outcome.part.mesh.as_ref().unwrap();
    let deck = deck_surfaces(&std::fs::read_to_string(dir.path().join("deck.inp")).unwrap());
    let mut by_tag: BTreeMap<FaceId, BTreeSet<[u32; 3]>> = BTreeMap::new();
    for (t, tag) in mesh.boundary.iter().zip(&mesh.face_tags) {
        let mut c = t.map(|v| v + 1);
        c.sort_unstable();
        by_tag.entry(*tag).or_default().insert(c);
    }
    let mut checked = 0;
    for f in model.face_ids() {
        let surface = &deck[&format!("F{}_S", f.0)];
        assert_eq!(surface, &by_tag[&f], "{}: face {} ({} element faces against {} triangles)", part.display(), f.0, surface.len(), by_tag[&f].len());
        checked += surface.len();
    }
    assert_eq!(checked, mesh.boundary.len());
}

#[test]
fn every_selector_surface_is_exactly_its_tagged_tet_faces() {
    surfaces_are_the_tagged_faces(Path::new("cad_fixtures/bracket.step"), 6.0, "C3D10");
    surfaces_are_the_tagged_faces(Path::new("cad_fixtures/bracket.step"), 6.0, "C3D4");
    if let Some(p) = common::corpus_file("mambo_s34.step") {
        surfaces_are_the_tagged_faces(&p, 4.0, "C3D10");
    }
}

/// C3D10 of a part: every boundary mid node on the CAD faces of its edge within 1e-9 of the
/// diagonal, Jacobians positive (validate), and CalculiX solves a load case on it.
fn curved_second_order(name: &str, part: &Model, job_steps: &str) {
    let dir = tempfile::tempdir().unwrap();
    write_part(dir.path(), name, part);
    let path = dir.path().join("job.toml");
    std::fs::write(&path, format!("[input]\nfile = \"{name}.step\"\n{job_steps}[[output]]\nfile = \"{name}.inp\"\n")).unwrap();
    let jf = JobFile::read(&path).unwrap();
    let outcome = carry_out(&jf, false).unwrap();
    let fe = outcome.fe.as_ref().unwrap();
    fe.validate().unwrap();
    let mesh = outcome.part.mesh.as_ref().unwrap();
    let model = outcome.part.model.as_ref().unwrap();
    let diag = mesh.bbox().diagonal();
    // the mid node of each edge, from the elements (corners, then edges 0-1 1-2 2-0 0-3 1-3 2-3)
    const EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];
    let mut mid: BTreeMap<(u32, u32), u32> = BTreeMap::new();
    for e in fe.elements.chunks(10) {
        for (k, [a, b]) in EDGES.iter().enumerate() {
            mid.insert((e[*a].min(e[*b]), e[*a].max(e[*b])), e[4 + k]);
        }
    }
    let mut faces_of: BTreeMap<(u32, u32), BTreeSet<FaceId>> = BTreeMap::new();
    for (t, tag) in mesh.boundary.iter().zip(&mesh.face_tags) {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            faces_of.entry((a.min(b), a.max(b))).or_default().insert(*tag);
        }
    }
    let (mut worst, mut curved) = (0.0f64, 0);
    for (edge, tags) in &faces_of {
        let p = fe.nodes[mid[edge] as usize];
        let chord = (mesh.vertices[edge.0 as usize] + mesh.vertices[edge.1 as usize]) * 0.5;
        if (p - chord).length() > 1e-12 * diag {
            curved += 1;
        }
        for tag in tags {
            let s = &model.surfaces[model.faces[tag.index().unwrap()].surface as usize];
            let uv = s.project(p);
            worst = worst.max((s.point(uv.x, uv.y) - p).length());
        }
    }
    let c = fe.curving.as_ref().unwrap();
    eprintln!("{name}: {} boundary mid nodes, {curved} off the chord, farthest from its CAD faces {worst:.3e} (diagonal {diag:.1}); {} straightened; Jacobian ratio ≥ {:.3}", faces_of.len(), c.straightened, c.min_jacobian_ratio);
    assert!(curved > 0 && c.min_jacobian_ratio > 0.0);
    assert!(worst <= 1e-9 * diag, "{name}: a boundary mid node {worst} from its CAD face");
    if tools::require(tools::ccx(), "ccx (CalculiX)", "the curved C3D10 solve").is_some() {
        let out = Command::new("ccx").arg("-i").arg(name).current_dir(dir.path()).output().unwrap();
        let log = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success() && !log.contains("*ERROR") && dir.path().join(format!("{name}.frd")).is_file(), "{log}");
    }
}

#[test]
fn c3d10_boundary_mid_nodes_lie_on_the_cad_faces_of_the_elbow_and_the_flange() {
    curved_second_order(
        "elbow",
        &Elbow::default().build().unwrap(),
        &format!("[selectors]\ninlet = {{ name = \"inlet\" }}\nwall = {{ name = \"inner_wall\" }}\n[density]\nsize = 12\n{STEEL}[[step]]\nfixed = [{{ faces = \"inlet\" }}]\npressure = [{{ faces = \"wall\", value = 1 }}]\n"),
    );
    curved_second_order(
        "flange",
        &Flange::default().build().unwrap(),
        &format!("[selectors]\nbolts = {{ name = \"bolt_*\" }}\nbore = {{ name = \"bore\" }}\n[density]\nsize = 5\n{STEEL}[[step]]\nfixed = [{{ faces = \"bolts\" }}]\npressure = [{{ faces = \"bore\", value = 1 }}]\n"),
    );
}

#[test]
fn meshio_reads_the_deck() {
    let Some(python) = tools::require(tools::meshio_python(), "python with meshio", "reading the .inp deck") else { return };
    let dir = tempfile::tempdir().unwrap();
    write_part(dir.path(), "part", &Block::new(20.0, 10.0, 10.0).build().unwrap());
    let (code, err) = run_job(dir.path(), &format!("[selectors]\nclamp = {{ name = \"xmin\" }}\n[density]\nsize = 3\n{STEEL}[[step]]\nfixed = [{{ faces = \"clamp\" }}]\n[[output]]\nfile = \"out.inp\"\n[[output]]\nfile = \"out.json\"\n"));
    assert_eq!(code, 0, "{err}");
    let report: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.path().join("out.json")).unwrap()).unwrap();
    let (nodes, elements) = (report["fe"]["nodes"].as_u64().unwrap(), report["fe"]["elements"].as_u64().unwrap());
    let script = "import meshio, sys\nm = meshio.read(sys.argv[1])\nprint(len(m.points), sum(len(c.data) for c in m.cells if c.type == 'tetra10'), len(m.point_sets.get('CLAMP', m.point_sets.get('clamp', []))))";
    let out = Command::new(python).args(["-c", script]).arg(dir.path().join("out.inp")).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let got: Vec<u64> = String::from_utf8_lossy(&out.stdout).split_whitespace().map(|x| x.parse().unwrap()).collect();
    assert_eq!((got[0], got[1]), (nodes, elements), "meshio read {got:?}");
    assert!(got[2] > 0, "meshio found no CLAMP node set: {got:?}");
}

#[test]
fn solving_the_bracket_job_writes_results_that_meshio_reads_and_reactions_that_balance_the_load() {
    if tools::require(tools::ccx(), "ccx (CalculiX)", "fepre solve on the bracket job").is_none() {
        return;
    }
    let Some(python) = tools::require(tools::meshio_python(), "python with meshio", "reading the results VTU") else { return };
    // the README's job, with its outputs in a temporary folder
    let dir = tempfile::tempdir().unwrap();
    let job = std::fs::read_to_string("cad_fixtures/bracket.toml").unwrap().replace("../target/", "");
    std::fs::copy("cad_fixtures/bracket.step", dir.path().join("bracket.step")).unwrap();
    std::fs::write(dir.path().join("bracket.toml"), &job).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_fepre")).args(["solve", "--json"]).arg(dir.path().join("bracket.toml")).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let summary: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.path().join("bracket_results.json")).unwrap()).unwrap();
    let step = &summary["steps"][0];
    let reaction: Vec<f64> = step["reactions"]["FIXED"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    // the job pulls end_x down with 500 N; the fixed end holds it
    assert!((reaction[2] - 500.0).abs() < 1e-6 * 500.0 && reaction[0].abs() < 1e-6 * 500.0 && reaction[1].abs() < 1e-6 * 500.0, "{reaction:?}");
    assert!(step["max_displacement"]["value"].as_f64().unwrap() > 0.0 && step["max_von_mises"]["value"].as_f64().unwrap() > 0.0);
    let script = "import meshio, sys\nm = meshio.read(sys.argv[1])\nd = m.point_data\nprint(d['displacement'].shape[1], d['von_mises'].ndim, len(m.points), m.cells[0].type)";
    let out = Command::new(python).args(["-c", script]).arg(dir.path().join("bracket_results.vtu")).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let got = String::from_utf8_lossy(&out.stdout);
    let v: Vec<&str> = got.split_whitespace().collect();
    assert_eq!((v[0], v[1], v[3]), ("3", "1", "tetra10"), "{got}");
    assert_eq!(v[2].parse::<u64>().unwrap(), summary["run"]["fe"]["nodes"].as_u64().unwrap());
    // VTK itself reads the results with their names
    let Some(vtk_python) = tools::require(tools::python_with(&["vtk"]), "python with vtk", "VTK reading the results VTU") else { return };
    let script = "import sys, vtk\nr = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(sys.argv[1]); r.Update(); g = r.GetOutput(); p = g.GetPointData()\nprint(g.GetCellType(0), ' '.join(sorted(p.GetArrayName(i) for i in range(p.GetNumberOfArrays()))))";
    let out = Command::new(vtk_python).args(["-c", script]).arg(dir.path().join("bracket_results.vtu")).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(String::from_utf8_lossy(&out.stdout).trim(), "24 displacement reaction stress von_mises");
}

#[test]
fn solve_without_calculix_says_how_to_install_it() {
    let dir = tempfile::tempdir().unwrap();
    write_part(dir.path(), "part", &Block::new(20.0, 10.0, 10.0).build().unwrap());
    std::fs::write(dir.path().join("job.toml"), format!("[input]\nfile = \"part.step\"\n[selectors]\nclamp = {{ name = \"xmin\" }}\n[density]\nsize = 4\n{STEEL}[[step]]\nfixed = [{{ faces = \"clamp\" }}]\n")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_fepre")).arg("solve").arg(dir.path().join("job.toml")).env("FEPRE_CCX", dir.path().join("no-ccx-here")).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("apt install calculix-ccx") && err.contains("FEPRE_CCX"), "{err}");
    assert!(!dir.path().join("job.inp").exists());
}

#[test]
fn decks_are_the_same_bytes_for_any_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy("cad_fixtures/bracket.step", dir.path().join("part.step")).unwrap();
    let job = format!("[selectors]\nholes = {{ name = \"hole_*\" }}\nfixed = {{ name = \"end_y\" }}\nloaded = {{ name = \"end_x\" }}\n[density]\nsize = 6\n{STEEL}[[step]]\nfixed = [{{ faces = \"fixed\" }}]\nforce = [{{ faces = \"loaded\", total = [0, 0, -500] }}]\npressure = [{{ faces = \"holes\", value = 1 }}]\n[[output]]\nfile = \"out.inp\"\n[[output]]\nfile = \"out.bdf\"\n");
    let mut decks = Vec::new();
    for threads in ["1", "2", "1"] {
        let path = dir.path().join("job.toml");
        std::fs::write(&path, format!("[input]\nfile = \"part.step\"\n{job}")).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_fepre")).arg("run").arg(&path).env("RAYON_NUM_THREADS", threads).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        decks.push((std::fs::read(dir.path().join("out.inp")).unwrap(), std::fs::read(dir.path().join("out.bdf")).unwrap()));
    }
    assert!(decks.windows(2).all(|w| w[0] == w[1]), "the decks differ between thread counts");
}
