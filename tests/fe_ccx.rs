//! CalculiX runs of fepre's decks checked against analytic solutions. Parts are built in code
//! (`cad::parts`), written as STEP, and go through a job file and `fepre solve` (the library's
//! [`solve_job`]): CalculiX 2.20 reads the deck unchanged.
//!
//! - cantilever 100 × 10 × 10, tip force: C3D10 tip deflection within 1 % of Timoshenko, the
//!   reaction total equal to the force to 1e-6; C3D4 reported beside it;
//! - thick-walled cylinder under internal pressure (a quarter, symmetry planes held): hoop stress
//!   at the bore and radial displacement of the outer surface within 1 % of Lamé;
//! - thin plate with a central hole (a tenth of the width) in tension: the peak σxx at the hole
//!   within 3 % of Kirsch with Peterson's finite-width factor;
//! - the cantilever's first bending frequency within 2 % of Timoshenko beam theory;
//! - a slab between two temperatures: mid-thickness within 0.1 % of linear, flux within 0.5 %;
//! - the cantilever under its own weight (gravity): tip deflection within 1 % of Timoshenko;
//! - a slab with a heat flux or a film on one face: one-dimensional conduction;
//! - the Abaqus face numbering against ccx: a pressure on one face gives the reaction p·A,
//!   pointing the right way, for C3D4 and C3D10.
//!
//! A missing `ccx` skips these tests with a message, except under `CI=true` where it fails.

mod common;

use common::tools;
use fepre::cad::brep::Model;
use fepre::cad::parts::{Block, Tube};
use fepre::io::frd::{self, FrdResults};
use fepre::pipeline::job::JobFile;
use fepre::pipeline::{SolveReport, solve_job};
use glam::DVec3;
use std::path::Path;

const E: f64 = 210_000.0;
const NU: f64 = 0.3;

const STEEL: &str = "[materials.steel]\nyoung = 210000\npoisson = 0.3\ndensity = 7.85e-9\n[[section]]\nmaterial = \"steel\"\n";

fn have_ccx(check: &str) -> bool {
    tools::require(tools::ccx(), "ccx (CalculiX)", check).is_some()
}

/// Writes `part` as `NAME.step` and `job` as `NAME.toml` in `dir`, solves, and reads the
/// `.frd`.
fn solve(dir: &Path, name: &str, part: &Model, job: &str) -> (SolveReport, FrdResults) {
    fepre::cad::step::write(&dir.join(format!("{name}.step")), part, name).unwrap();
    let job_path = dir.join(format!("{name}.toml"));
    std::fs::write(&job_path, format!("[input]\nfile = \"{name}.step\"\n{job}")).unwrap();
    let jf = JobFile::read(&job_path).unwrap();
    let report = solve_job(&jf).unwrap_or_else(|e| panic!("{name}: {e}"));
    let results = frd::read(Path::new(&report.frd)).unwrap();
    (report, results)
}

/// The last increment's field `name` at each node: (position, values).
fn field(r: &FrdResults, name: &str) -> Vec<(DVec3, Vec<f64>)> {
    let step = r.steps.iter().rev().find(|s| s.field(name).is_some()).unwrap_or_else(|| panic!("no {name} in the results"));
    let f = step.field(name).unwrap();
    let pos: std::collections::HashMap<u32, DVec3> = r.nodes.iter().copied().collect();
    f.per_node().map(|(n, v)| (pos[&n], v.to_vec())).collect()
}

fn cantilever(dir: &Path, element: &str) -> (f64, SolveReport) {
    let job = format!(
        "[selectors]\nclamp = {{ name = \"xmin\" }}\ntip = {{ name = \"xmax\" }}\n[density]\nsize = 2.5\n[model]\nelement = \"{element}\"\n{STEEL}[[step]]\nfixed = [{{ faces = \"clamp\" }}]\nforce = [{{ faces = \"tip\", total = [0, 0, -1000] }}]\n[[output]]\nfile = \"beam_{element}.inp\"\n"
    );
    let (report, r) = solve(dir, &format!("beam_{element}"), &Block::default().build().unwrap(), &job);
    let tip: Vec<f64> = field(&r, "DISP").into_iter().filter(|(p, _)| (p.x - 100.0).abs() < 1e-9).map(|(_, u)| -u[2]).collect();
    (tip.iter().sum::<f64>() / tip.len() as f64, report)
}

#[test]
fn cantilever_tip_deflection_matches_timoshenko_and_the_reaction_balances_the_load() {
    if !have_ccx("the cantilever check") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (l, b, h, p): (f64, f64, f64, f64) = (100.0, 10.0, 10.0, 1000.0);
    let i = b * h * h * h / 12.0;
    let g = E / (2.0 * (1.0 + NU));
    let k = 10.0 * (1.0 + NU) / (12.0 + 11.0 * NU);
    let timoshenko = p * l.powi(3) / (3.0 * E * i) + p * l / (k * g * b * h);
    let (c3d10, report) = cantilever(dir.path(), "C3D10");
    let (c3d4, _) = cantilever(dir.path(), "C3D4");
    eprintln!("cantilever tip deflection: C3D10 {c3d10:.6} ({:.4} of Timoshenko {timoshenko:.6}), C3D4 {c3d4:.6} ({:.4})", c3d10 / timoshenko, c3d4 / timoshenko);
    assert!((c3d10 / timoshenko - 1.0).abs() < 0.01, "C3D10 tip deflection {c3d10} against Timoshenko {timoshenko}");
    // linear tets are too stiff in bending, but not absurdly so on this mesh
    assert!(c3d4 < c3d10 && c3d4 > 0.5 * timoshenko, "C3D4 tip deflection {c3d4}");
    let reaction = report.steps[0].reactions["CLAMP"];
    assert!((reaction[2] - p).abs() <= 1e-6 * p, "reaction {reaction:?} against the tip force {p}");
    assert!(reaction[0].abs() <= 1e-6 * p && reaction[1].abs() <= 1e-6 * p, "reaction {reaction:?}");
    // the force written is the force asked for
    let written = report.run.fe.as_ref().unwrap().steps[0].forces[0].1;
    assert!((written[2] + p).abs() < 1e-9 * p, "{written:?}");
    // the summary and the VTU are written
    assert!(Path::new(&report.results).is_file() && Path::new(&report.summary).is_file());
}

#[test]
fn thick_walled_cylinder_matches_lame() {
    if !have_ccx("the thick-walled cylinder check") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (a, b, p): (f64, f64, f64) = (10.0, 20.0, 100.0);
    let tube = Tube::default();
    let job = format!(
        "[selectors]\nbore = {{ name = \"bore\" }}\nbottom = {{ name = \"bottom\" }}\ncut_x = {{ name = \"cut_x\" }}\ncut_end = {{ name = \"cut_end\" }}\n[density]\nsize = 1.5\n{STEEL}[[step]]\nfixed = [{{ faces = \"cut_x\", dofs = [2] }}, {{ faces = \"cut_end\", dofs = [1] }}, {{ faces = \"bottom\", dofs = [3] }}]\npressure = [{{ faces = \"bore\", value = {p} }}]\n"
    );
    let (_, r) = solve(dir.path(), "tube", &tube.build().unwrap(), &job);
    // open ends (σz = 0): σθ(a) = p (b² + a²)/(b² − a²); u(b) = p a² b · 2 / (E (b² − a²))
    let hoop_lame = p * (b * b + a * a) / (b * b - a * a);
    let u_lame = p * a * a / (E * (b * b - a * a)) * ((1.0 - NU) * b + (1.0 + NU) * b);
    let radius = |q: DVec3| q.x.hypot(q.y);
    let hoop: Vec<f64> = field(&r, "STRESS")
        .into_iter()
        .filter(|(q, _)| (radius(*q) - a).abs() < 1e-6)
        .map(|(q, s)| {
            let t = q.y.atan2(q.x);
            s[0] * t.sin().powi(2) + s[1] * t.cos().powi(2) - 2.0 * s[3] * t.sin() * t.cos()
        })
        .collect();
    let ur: Vec<f64> = field(&r, "DISP").into_iter().filter(|(q, _)| (radius(*q) - b).abs() < 1e-6).map(|(q, u)| (u[0] * q.x + u[1] * q.y) / radius(q)).collect();
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let worst = |v: &[f64], want: f64| v.iter().map(|x| (x / want - 1.0).abs()).fold(0.0, f64::max);
    eprintln!("Lamé: hoop at the bore {:.4} ({} nodes, worst {:.4} off), u(b) {:.6e} against {u_lame:.6e}", mean(&hoop) / hoop_lame, hoop.len(), worst(&hoop, hoop_lame), mean(&ur));
    assert!(worst(&hoop, hoop_lame) < 0.01, "hoop stress at the bore against Lamé {hoop_lame}: {hoop:?}");
    assert!(worst(&ur, u_lame) < 0.01, "radial displacement of the outer surface against Lamé {u_lame}");
}

#[test]
fn plate_with_a_hole_matches_kirsch_with_the_finite_width_factor() {
    if !have_ccx("the plate-with-a-hole check") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (l, w, t, d, s): (f64, f64, f64, f64, f64) = (200.0, 100.0, 2.0, 10.0, 100.0);
    let job = format!(
        "[selectors]\nhole = {{ name = \"hole\" }}\nxmin = {{ name = \"xmin\" }}\nxmax = {{ name = \"xmax\" }}\n[density]\nsize = 6\ndistance = [{{ faces = \"hole\", size = 0.5, growth = 0.25, max = 6 }}]\n{STEEL}[[step]]\nfixed = [{{ faces = \"xmin\" }}]\nforce = [{{ faces = \"xmax\", total = [{}, 0, 0] }}]\n",
        s * w * t
    );
    let (_, r) = solve(dir.path(), "plate", &Block::new(l, w, t).with_hole(d).build().unwrap(), &job);
    // Peterson (Heywood): K_tn = 2 + (1 − d/W)³ on the net section
    let peak = (2.0 + (1.0 - d / w).powi(3)) * s * w / (w - d);
    let (cx, cy) = (l / 2.0, w / 2.0);
    let sxx = field(&r, "STRESS").into_iter().filter(|(q, _)| ((q.x - cx).hypot(q.y - cy) - d / 2.0).abs() < 1e-6).map(|(_, v)| v[0]).fold(f64::NEG_INFINITY, f64::max);
    eprintln!("Kirsch-Peterson: peak σxx {sxx:.3} against {peak:.3} ({:.4})", sxx / peak);
    assert!((sxx / peak - 1.0).abs() < 0.03, "peak σxx {sxx} at the hole against {peak}");
}

#[test]
fn cantilever_first_bending_frequency_matches_timoshenko() {
    if !have_ccx("the frequency check") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let job = format!("[selectors]\nclamp = {{ name = \"xmin\" }}\n[density]\nsize = 2.5\n{STEEL}[[step]]\ntype = \"frequency\"\nmodes = 3\nfixed = [{{ faces = \"clamp\" }}]\n");
    let (report, _) = solve(dir.path(), "modes", &Block::default().build().unwrap(), &job);
    let f1 = report.steps[0].frequencies[0];
    let want = timoshenko_cantilever_frequency(100.0, 10.0, 7.85e-9);
    eprintln!("first bending frequency {f1:.3} Hz against Timoshenko {want:.3} Hz ({:.4})", f1 / want);
    assert!((f1 / want - 1.0).abs() < 0.02, "{f1} against {want}");
}

/// The first bending frequency (Hz with mm, N, tonne) of a clamped-free Timoshenko beam of
/// square section `h`: the root of Huang's (1961) frequency equation with Cowper's shear
/// coefficient, found by bisection near the Euler-Bernoulli root.
fn timoshenko_cantilever_frequency(l: f64, h: f64, rho: f64) -> f64 {
    let (a, i) = (h * h, h.powi(4) / 12.0);
    let g = E / (2.0 * (1.0 + NU));
    let k = 10.0 * (1.0 + NU) / (12.0 + 11.0 * NU);
    let (r2, s2) = (i / (a * l * l), E * i / (k * a * g * l * l));
    let f = |b: f64| {
        let q = ((r2 - s2).powi(2) + 4.0 / (b * b)).sqrt();
        let (al, be) = (((q - (r2 + s2)) / 2.0).sqrt(), ((q + (r2 + s2)) / 2.0).sqrt());
        2.0 + (b * b * (r2 - s2).powi(2) + 2.0) * (b * al).cosh() * (b * be).cos() - b * (r2 + s2) / (1.0 - b * b * r2 * s2).sqrt() * (b * al).sinh() * (b * be).sin()
    };
    // Euler-Bernoulli: b = 1.8751² = 3.516; shear and rotary inertia lower it
    let (mut lo, mut hi) = (2.5, 3.5160);
    assert!(f(lo) * f(hi) < 0.0);
    for _ in 0..100 {
        let m = 0.5 * (lo + hi);
        if f(lo) * f(m) <= 0.0 { hi = m } else { lo = m }
    }
    let omega = (lo * lo * E * i / (rho * a * l.powi(4))).sqrt();
    omega / (2.0 * std::f64::consts::PI)
}

#[test]
fn slab_between_two_temperatures_is_linear() {
    if !have_ccx("the heat check") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (t, k, hot) = (5.0, 50.0, 100.0);
    let job = format!(
        "[selectors]\nhot = {{ name = \"zmin\" }}\ncold = {{ name = \"zmax\" }}\n[density]\nsize = 2\n[materials.copper]\nconductivity = {k}\n[[section]]\nmaterial = \"copper\"\n[[step]]\ntype = \"heat\"\ntemperature = [{{ faces = \"hot\", value = {hot} }}, {{ faces = \"cold\", value = 0 }}]\n"
    );
    let (_, r) = solve(dir.path(), "slab", &Block::new(20.0, 20.0, t).build().unwrap(), &job);
    let mid: Vec<f64> = field(&r, "NDTEMP").into_iter().filter(|(q, _)| (q.z - t / 2.0).abs() < 1e-9).map(|(_, v)| v[0]).collect();
    assert!(!mid.is_empty());
    for v in &mid {
        assert!((v / (hot / 2.0) - 1.0).abs() < 1e-3, "mid-thickness temperature {v}");
    }
    let q = k * hot / t;
    for (_, f) in field(&r, "FLUX") {
        assert!((f[2] / q - 1.0).abs() < 5e-3, "flux {f:?} against {q}");
    }
}

#[test]
fn a_cantilever_under_its_own_weight_matches_timoshenko() {
    if !have_ccx("the gravity check") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let job = format!("[selectors]\nclamp = {{ name = \"xmin\" }}\n[density]\nsize = 3\n{STEEL}[[step]]\nfixed = [{{ faces = \"clamp\" }}]\ngravity = [{{ acceleration = [0, 0, -9810] }}]\n");
    // twice as slender as the tip-load cantilever: the clamped root's restraint of warping,
    // which beam theory leaves out, weighs less
    let (l, h): (f64, f64) = (200.0, 10.0);
    let (report, r) = solve(dir.path(), "weight", &Block::new(l, h, h).build().unwrap(), &job);
    // a uniform load w = ρ g A: w L⁴ / (8 E I) + w L² / (2 k G A)
    let (a, i) = (h * h, h.powi(4) / 12.0);
    let w = 7.85e-9 * 9810.0 * a;
    let k = 10.0 * (1.0 + NU) / (12.0 + 11.0 * NU);
    let want = w * l.powi(4) / (8.0 * E * i) + w * l * l / (2.0 * k * E / (2.0 * (1.0 + NU)) * a);
    let tip: Vec<f64> = field(&r, "DISP").into_iter().filter(|(p, _)| (p.x - l).abs() < 1e-9).map(|(_, u)| -u[2]).collect();
    let got = tip.iter().sum::<f64>() / tip.len() as f64;
    eprintln!("tip deflection under its own weight {got:.6e} against Timoshenko {want:.6e} ({:.4})", got / want);
    assert!((got / want - 1.0).abs() < 0.01, "{got} against {want}");
    // the clamp holds the weight but for the loads of its own nodes, which ccx's reactions
    // leave out (they go straight into the support)
    let weight = w * l;
    let reaction = report.steps[0].reactions["CLAMP"][2];
    assert!(reaction <= weight && reaction > 0.99 * weight, "reaction {reaction} against the weight {weight}");
}

#[test]
fn heat_flux_and_film_on_a_slab_match_one_dimensional_conduction() {
    if !have_ccx("the heat flux and film check") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (t, k) = (5.0, 50.0);
    let head = format!("[selectors]\nbase = {{ name = \"zmin\" }}\ntop = {{ name = \"zmax\" }}\n[density]\nsize = 2.5\n[materials.copper]\nconductivity = {k}\n[[section]]\nmaterial = \"copper\"\n[[step]]\ntype = \"heat\"\n");
    let part = Block::new(20.0, 20.0, t).build().unwrap();
    // a flux q into the top, the base at 0: the top at q t / k
    let q = 200.0;
    let (_, r) = solve(dir.path(), "flux", &part, &format!("{head}temperature = [{{ faces = \"base\", value = 0 }}]\nheat_flux = [{{ faces = \"top\", value = {q} }}]\n"));
    for (p, v) in field(&r, "NDTEMP").into_iter().filter(|(p, _)| (p.z - t).abs() < 1e-9) {
        assert!((v[0] / (q * t / k) - 1.0).abs() < 1e-3, "top temperature {} at {p} against {}", v[0], q * t / k);
    }
    // a film (h, sink) on the top, the base at 100: the flux (100 − sink) / (t/k + 1/h)
    let (h, sink) = (20.0, 20.0);
    let (_, r) = solve(dir.path(), "film", &part, &format!("{head}temperature = [{{ faces = \"base\", value = 100 }}]\nfilm = [{{ faces = \"top\", coefficient = {h}, sink = {sink} }}]\n"));
    let flux = (100.0 - sink) / (t / k + 1.0 / h);
    for (p, f) in field(&r, "FLUX") {
        assert!((f[2] / flux - 1.0).abs() < 5e-3, "flux {f:?} at {p} against {flux}");
    }
}

#[test]
fn a_pressure_on_one_face_gives_its_reaction_through_the_abaqus_face_numbers() {
    if !have_ccx("the face numbering check") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let p = 10.0;
    for element in ["C3D4", "C3D10"] {
        let job = format!(
            "[selectors]\nbase = {{ name = \"zmin\" }}\ntop = {{ name = \"zmax\" }}\n[density]\nsize = 5\n[model]\nelement = \"{element}\"\n{STEEL}[[step]]\nfixed = [{{ faces = \"base\" }}]\npressure = [{{ faces = \"top\", value = {p} }}]\n"
        );
        let (report, r) = solve(dir.path(), &format!("press_{element}"), &Block::new(20.0, 20.0, 10.0).build().unwrap(), &job);
        // the pressure pushes into the top face (down); the base holds it up
        let reaction = report.steps[0].reactions["BASE"];
        assert!((reaction[2] - p * 400.0).abs() < 1e-6 * p * 400.0, "{element}: reaction {reaction:?} against p A = {}", p * 400.0);
        let top_uz = field(&r, "DISP").into_iter().filter(|(q, _)| (q.z - 10.0).abs() < 1e-9).map(|(_, u)| u[2]).fold(f64::INFINITY, f64::min);
        assert!(top_uz < 0.0, "{element}: the top moves {top_uz}");
    }
}
