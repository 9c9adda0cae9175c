//! Octree meshing (isosurface stuffing, issue 15) of corpus files through the pipeline: the
//! dihedral angles within the paper's [10.7°, 164.8°] by our own measure and by the shared
//! judge `shared/tools/cgal_ref/tetquality` (skipped when missing, a failure under
//! `CI=true`), the volume against the input's, the boundary within the reported Hausdorff
//! distance of the input and that distance within the cell size. The corpus comes from
//! `FEPRE_CORPUS` or `../shared/cad_corpus` (skipped when absent, a failure under `CI=true`).

use fepre::io::{MeshData, WriteOptions};
use fepre::mesh3d::octree::{Grading, MAX_DIHEDRAL, MIN_DIHEDRAL, OctreeOptions};
use fepre::pipeline::job::Method;
use fepre::pipeline::{Plan, run_plan};
use fepre::pipeline::Part;
use fepre::quality::tet_mesh_quality;
use std::path::Path;
use std::process::Command;

mod common;

/// Meshes `name` by octree at cell size diagonal / `div`; returns (volume error, report).
fn mesh(name: &str, div: f64) -> Option<(f64, fepre::mesh3d::octree::OctreeReport)> {
    mesh_graded(name, div, Grading::Uniform)
}

/// [`mesh`] with the grading.
fn mesh_graded(name: &str, div: f64, grading: Grading) -> Option<(f64, fepre::mesh3d::octree::OctreeReport)> {
    mesh_at(name, Some(div), grading)
}

/// [`mesh_graded`]; without `div`, at the default cell (chosen to hold the volume).
fn mesh_at(name: &str, div: Option<f64>, grading: Grading) -> Option<(f64, fepre::mesh3d::octree::OctreeReport)> {
    let path = common::corpus_file(name)?;
    let mut part = Part::open(&path).unwrap();
    let mut density = fepre::attributes::Density::default();
    density.size = div.and_then(|div| fepre::attributes::Positive::new(part.diagonal() / div));
    let octree = OctreeOptions { grading, ..OctreeOptions::default() };
    let plan = Plan { unit: 1.0, density, method: Method::Octree, octree, ..Plan::default() };
    let report = run_plan(&mut part, &plan, false).unwrap();
    let mesh = part.mesh.as_ref().unwrap();
    mesh.validate().unwrap();
    let o = report.octree.clone().unwrap();
    // our measure
    let q = tet_mesh_quality(mesh);
    let (lo, hi) = (q.min_dihedral_deg, q.max_dihedral_deg);
    assert!(lo >= MIN_DIHEDRAL && hi <= MAX_DIHEDRAL, "{name}: [{lo}, {hi}]");
    // the boundary is within the reported bound, and the bound within the cell
    assert!(o.deviation.hausdorff <= o.deviation.hausdorff_bound && o.bound_over_cell <= 1.0, "{name}: {:?} cell {}", o.deviation, o.cell_size);
    // an exact input volume needs no other reference
    assert_eq!(o.winding_volume.is_some(), !o.input_volume_exact, "{name}");
    if o.cell_tries.is_empty() {
        assert_eq!(o.bound_over_cell, o.deviation.hausdorff_bound / o.cell_size, "{name}: one cell");
    }
    // the shared judge
    let judge = common::shared_dir().join("tools/cgal_ref/tetquality");
    if judge.is_file() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("o.mesh");
        fepre::io::write(&out, &MeshData::Volume(mesh.clone()), &WriteOptions::default()).unwrap();
        let text = String::from_utf8(Command::new(&judge).arg(&out).output().unwrap().stdout).unwrap();
        let get = |k: &str| text.lines().find_map(|l| l.strip_prefix(k).map(|v| v.trim().parse::<f64>().unwrap())).unwrap();
        let (jl, jh) = (get("min_dihedral_deg "), get("max_dihedral_deg "));
        assert!(jl >= MIN_DIHEDRAL && jh <= MAX_DIHEDRAL, "{name}: judge [{jl}, {jh}]");
        assert_eq!(get("inverted_or_flat "), 0.0);
    } else {
        assert!(!common::in_ci(), "the shared judge {} is missing (CI=true)", judge.display());
        eprintln!("skipping the judge: {} is missing", Path::new(&judge).display());
    }
    Some(((o.volume - o.input_volume) / o.input_volume, o))
}

/// Without a size the cell is chosen: the crankshaft lost 30 % of its volume at the first
/// default (diagonal / 25), and every solid of `base_interface_AP214` (thin plates) held no
/// lattice vertex. Now the cell shrinks until every solid is within 1 %; the tries are
/// reported, coarsest first, and a given size is kept as it is.
#[test]
fn the_default_cell_holds_every_solids_volume() {
    for name in ["Kurbelwelle.stp", "base_interface_AP214.STEP"] {
        default_cell_holds(name, 1);
    }
    // a size given is kept
    let Some((_, o)) = mesh("Kurbelwelle.stp", 100.0) else { return };
    assert!(o.cell_tries.is_empty() && o.input_volume_exact);
    let diagonal = Part::open(&common::corpus_file("Kurbelwelle.stp").unwrap()).unwrap().diagonal();
    assert!((o.cell_size - diagonal / 100.0).abs() < 1e-9 * diagonal);
}

/// [`the_default_cell_holds_every_solids_volume`] on an assembly of ten thin plates, each
/// its own solid and its own cell, most of them empty at the first cell.
#[test]
#[ignore = "heavy: run in release with --include-ignored"]
fn the_default_cell_holds_an_assemblys_volume() {
    default_cell_holds("box_sides.STEP", 10);
}

/// Meshes `name` at the default cell and checks the tries; `solids` B-rep solids, each with
/// its own tries (in solid order) and cell.
fn default_cell_holds(name: &str, solids: usize) {
    use fepre::mesh3d::octree::RESOLVE;
    let Some((err, o)) = mesh_at(name, None, Grading::Uniform) else { return };
    assert!(err.abs() <= RESOLVE.volume_error, "{name}: volume {err}");
    assert!(o.input_volume_exact && o.empty_solids.is_empty(), "{name}: {:?}", o.empty_solids);
    assert_eq!(o.solids, solids, "{name}");
    let diagonal = Part::open(&common::corpus_file(name).unwrap()).unwrap().diagonal();
    let mut by_solid: Vec<Vec<&fepre::mesh3d::octree::CellTry>> = Vec::new();
    for t in &o.cell_tries {
        match by_solid.last_mut() {
            Some(g) if g[0].solid == t.solid => g.push(t),
            _ => by_solid.push(vec![t]),
        }
    }
    assert_eq!(by_solid.len(), solids, "{name}: {:?}", o.cell_tries);
    assert!(by_solid.iter().any(|g| g.len() >= 3), "{name}: {:?}", o.cell_tries);
    for tries in &by_solid {
        assert_eq!(tries[0].solid, if solids > 1 { tries[0].solid.filter(|s| *s >= 1) } else { None }, "{name}");
        assert!(tries.windows(2).all(|w| w[1].cell < w[0].cell), "{name}: {tries:?}");
        // none holds before the first that does; one is kept, and it holds; at most
        // `bound_tries` follow for the Hausdorff bound
        let first = tries.iter().position(|t| RESOLVE.holds(t)).unwrap();
        assert!(tries.len() - 1 - first <= RESOLVE.bound_tries, "{name}: {tries:?}");
        let kept: Vec<_> = tries.iter().filter(|t| t.kept).collect();
        assert!(kept.len() == 1 && RESOLVE.holds(kept[0]), "{name}: {tries:?}");
        if kept[0].bound_over_cell <= 1.0 {
            assert!(std::ptr::eq(*kept[0], *tries.last().unwrap()), "{name}: {tries:?}");
        }
        // the first try is the mesh path's default size
        assert!((tries[0].cell - diagonal / 25.0).abs() < 1e-9 * diagonal, "{name}: {} vs {}", tries[0].cell, diagonal / 25.0);
    }
    let finest = o.cell_tries.iter().filter(|t| t.kept).map(|t| t.cell).fold(f64::INFINITY, f64::min);
    assert_eq!(finest, o.cell_size, "{name}");
}

#[test]
fn fandisk_and_plate_at_a_coarse_cell() {
    for name in ["fandisk.obj", "plate_holes.STL"] {
        let Some((err, o)) = mesh(name, 25.0) else { return };
        assert!(err.abs() < 0.05, "{name}: volume {err}");
        assert!(o.tets > 1000);
    }
}

#[test]
#[ignore = "heavy: run in release with --include-ignored"]
fn closed_meshes_within_one_percent_at_a_fine_cell() {
    for name in ["plate_holes.STL", "featuretype.STL", "Duck.glb"] {
        let Some((err, _)) = mesh(name, 100.0) else { return };
        assert!(err.abs() < 0.01, "{name}: volume {err}");
    }
}

/// Dirty input (issue 15): the self-intersecting `Duck.glb`, `rabbit.obj` (overlapping
/// shells, one inward) and `pins.glb` (dowels through a plate), and the open
/// `bunny_binary.stl`, mesh at the default cell into valid tets whose volume is within 2 % of
/// the winding number's (the measure of `w > 1/2` by stratified sampling, its own error
/// under 0.2 %). Measured: −0.45 %, −0.36 %, −0.05 % and −0.41 %; against the divergence
/// theorem's figure, which counts overlaps twice and is not a volume for an open surface,
/// rabbit is −2.0 % and bunny −2.2 %. The closed ones' boundaries are within their cells.
#[test]
#[ignore = "heavy: run in release with --include-ignored"]
fn dirty_meshes_hold_the_winding_numbers_volume() {
    for name in ["Duck.glb", "rabbit.obj", "pins.glb", "bunny_binary.stl"] {
        let Some(path) = common::corpus_file(name) else { return };
        let mut part = Part::open(&path).unwrap();
        let plan = Plan { unit: 1.0, method: Method::Octree, ..Plan::default() };
        let o = run_plan(&mut part, &plan, false).unwrap().octree.unwrap();
        part.mesh.as_ref().unwrap().validate().unwrap();
        let w = fepre::mesh3d::octree::winding_volume(part.surface.as_ref().unwrap(), 128).unwrap();
        assert!(w.error < 0.002 * w.volume, "{name}: {w:?}");
        let err = o.volume / w.volume - 1.0;
        eprintln!("{name}: mesh {:.6e}, winding number's {:.6e} ± {:.1e}: {:+.3} %", o.volume, w.volume, w.error, 100.0 * err);
        assert!(err.abs() < 0.02, "{name}: {} against {w:?}: {err}", o.volume);
        // the closed ones' boundaries within the cell (pins: once the hairline gaps between
        // its dowels and their holes are sealed; bunny is open: its holes' rims are not
        // the boundary of `w > 1/2`)
        if name != "bunny_binary.stl" {
            assert!(o.bound_over_cell <= 1.0, "{name}: {:?}", o.deviation);
        }
        if name == "pins.glb" {
            assert!(o.deviation.sealed_area > 0.0 && o.deviation.seal == o.cell_size / 16.0, "{:?}", o.deviation);
        }
    }
}

/// Graded against uniform on a STEP sphere at diagonal / 100: the same volume to rounding
/// (the same boundary), the angles within the bounds by both measures, at most a third of
/// the tets, cells of at least four sizes.
#[test]
#[ignore = "heavy: run in release with --include-ignored"]
fn graded_sphere_has_a_third_of_the_tets() {
    let Some((eu, u)) = mesh("occt-sphere.step", 100.0) else { return };
    let Some((eg, g)) = mesh_graded("occt-sphere.step", 100.0, Grading::Graded) else { return };
    assert_eq!(g.grading, "graded");
    assert!((g.volume - u.volume).abs() < 1e-9 * u.volume, "{} {}", g.volume, u.volume);
    assert!(eg.abs() < 0.01 && eu.abs() < 0.01, "{eg} {eu}");
    assert!(3 * g.tets <= u.tets, "{} graded, {} uniform", g.tets, u.tets);
    assert!(g.cells_per_level.len() >= 4, "{:?}", g.cells_per_level);
}

/// Graded mode on real parts at diagonal / 100, CAD and scanned, thick and thin-walled: the
/// same boundary triangles and volume as the uniform mesh at the same cell, with at most a
/// third of its tets; every tet coarsening made within [15°, 160°] and the whole mesh within
/// the paper's bounds. Measured: fandisk 0.123, part 0.142, Angled 0.202, linkrods 0.243,
/// Zylkopf 0.198, Duck 0.081 (the octree alone: 0.392, 0.505, 0.613, 0.695, 0.617, 0.292).
#[test]
#[ignore = "heavy: run in release with --include-ignored"]
fn graded_has_a_third_of_the_uniform_tets_on_real_parts() {
    for name in ["fandisk.obj", "part.step", "Angled.step", "linkrods.step", "Zylkopf.stp", "Duck.glb"] {
        let Some((tu, u)) = boundary_at(name, 100.0, Grading::Uniform) else { return };
        let Some((tg, g)) = boundary_at(name, 100.0, Grading::Graded) else { return };
        assert!(tg == tu, "{name}: {} graded boundary triangles, {} uniform", tg.len(), tu.len());
        assert!((g.volume - u.volume).abs() < 1e-9 * u.volume, "{name}: {} {}", g.volume, u.volume);
        assert!(3 * g.tets <= u.tets, "{name}: {} graded, {} uniform", g.tets, u.tets);
        let c = g.coarsened.unwrap_or_else(|| panic!("{name}: not coarsened"));
        assert!(c.vertices > 0, "{name}: {c:?}");
        assert!(g.dihedral[0] >= u.dihedral[0].min(15.0) && g.dihedral[1] <= u.dihedral[1].max(160.0), "{name}: {:?} {:?}", g.dihedral, u.dihedral);
    }
}

/// The boundary triangles (by their corners' bits, sorted) and the report of `name` meshed
/// by octree at cell size diagonal / `div`.
fn boundary_at(name: &str, div: f64, grading: Grading) -> Option<(Vec<[[u64; 3]; 3]>, fepre::mesh3d::octree::OctreeReport)> {
    let path = common::corpus_file(name)?;
    let mut part = Part::open(&path).unwrap();
    let mut density = fepre::attributes::Density::default();
    density.size = fepre::attributes::Positive::new(part.diagonal() / div);
    let octree = OctreeOptions { grading, ..OctreeOptions::default() };
    let plan = Plan { unit: 1.0, density, method: Method::Octree, octree, ..Plan::default() };
    let report = run_plan(&mut part, &plan, false).unwrap();
    let mesh = part.mesh.as_ref().unwrap();
    mesh.validate().unwrap();
    let mut tris: Vec<[[u64; 3]; 3]> = mesh
        .boundary
        .iter()
        .map(|f| {
            let mut c = f.map(|v| mesh.vertices[v as usize].to_array().map(f64::to_bits));
            c.sort_unstable();
            c
        })
        .collect();
    tris.sort_unstable();
    Some((tris, report.octree.unwrap()))
}

/// Graded keeps the uniform mode's boundary, triangle for triangle, where that is hardest:
/// a dirty mesh whose stencils leave out tets of four vertices on the surface (rabbit), and
/// CAD parts whose edges feature snapping moves vertices onto (part, fandisk, at diagonal /
/// 100, where coarse cells reach the surface).
#[test]
#[ignore = "heavy: run in release with --include-ignored"]
fn graded_keeps_the_uniform_boundary_on_real_parts() {
    // (rabbit at diagonal / 50, its default cell, where four such tets are left out)
    for (name, div) in [("rabbit.obj", 50.0), ("part.step", 100.0), ("fandisk.obj", 100.0)] {
        let Some((tu, u)) = boundary_at(name, div, Grading::Uniform) else { return };
        let Some((tg, g)) = boundary_at(name, div, Grading::Graded) else { return };
        assert_eq!(g.cell_size, u.cell_size, "{name}");
        assert_eq!(g.snapped, u.snapped, "{name}");
        assert!(tg == tu, "{name}: {} graded boundary triangles, {} uniform", tg.len(), tu.len());
        assert!((g.volume - u.volume).abs() < 1e-9 * u.volume, "{name}: {} {}", g.volume, u.volume);
        assert!(g.tets < u.tets, "{name}: {} {}", g.tets, u.tets);
    }
}

/// `fepre mesh --method octree --octree-grading graded` on a bundled part, and
/// `grading = "graded"` in a job file: accepted, graded, cells of several sizes printed.
#[test]
fn graded_from_the_command_line_and_a_job_file() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("f.msh");
    let run = |args: &[&std::ffi::OsStr]| Command::new(env!("CARGO_BIN_EXE_fepre")).args(args).output().unwrap();
    let flange = root.join("cad_fixtures/flange.step");
    let o = run(&["mesh".as_ref(), flange.as_os_str(), "-o".as_ref(), out.as_os_str(), "--method".as_ref(), "octree".as_ref(), "--octree-grading".as_ref(), "graded".as_ref(), "--size".as_ref(), "2".as_ref()]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{text}{}", String::from_utf8_lossy(&o.stderr));
    assert!(text.contains("octree           graded cell"), "{text}");
    let cells = text.lines().find(|l| l.starts_with("  cells ")).unwrap_or_else(|| panic!("{text}"));
    assert!(cells.matches(" of ").count() >= 2, "{cells}");
    // and how many of the octree's tets lie in one-cube cells, the octree's floor at this
    // cell, and how many coarsening took off: the tets written
    let tets: usize = text.lines().find_map(|l| l.strip_prefix("tets ")).and_then(|t| t.trim().parse().ok()).unwrap_or_else(|| panic!("{text}"));
    let coarsened = text.lines().find(|l| l.starts_with("  coarsened ")).unwrap_or_else(|| panic!("{text}"));
    let fewer: usize = coarsened.split(", ").nth(1).and_then(|x| x.split(' ').next()).and_then(|x| x.parse().ok()).unwrap_or_else(|| panic!("{coarsened}"));
    assert!(fewer > 0 && coarsened.ends_with(&format!(": {tets} tets")), "{coarsened}");
    assert!(text.contains(&format!(" of the octree's {} tets (", tets + fewer)) && text.contains("%) in one-cube cells"), "{text}");
    assert!(out.is_file());
    let job = dir.path().join("job.toml");
    std::fs::write(
        &job,
        format!("[input]\nfile = {:?}\n[density]\nsize = 2\n[mesh]\nmethod = \"octree\"\ngrading = \"graded\"\n[[output]]\nfile = {:?}\n", flange, dir.path().join("j.msh")),
    )
    .unwrap();
    let o = run(&["run".as_ref(), job.as_os_str()]);
    assert!(o.status.success(), "{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    assert!(dir.path().join("j.msh").is_file());
    // without coarsening: the octree's cells only, more tets
    let o = run(&["mesh".as_ref(), flange.as_os_str(), "-o".as_ref(), out.as_os_str(), "--method".as_ref(), "octree".as_ref(), "--octree-grading".as_ref(), "graded".as_ref(), "--octree-coarsen".as_ref(), "off".as_ref(), "--size".as_ref(), "2".as_ref()]);
    let off = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success() && !off.contains("  coarsened "), "{off}");
    let off_tets: usize = off.lines().find_map(|l| l.strip_prefix("tets ")).and_then(|t| t.trim().parse().ok()).unwrap_or_else(|| panic!("{off}"));
    assert_eq!(off_tets, tets + fewer);
    // and only there
    let o = run(&["mesh".as_ref(), flange.as_os_str(), "-o".as_ref(), out.as_os_str(), "--method".as_ref(), "octree".as_ref(), "--octree-coarsen".as_ref(), "off".as_ref()]);
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    // `coarsen` in a job file: accepted with a graded octree, refused otherwise at its line
    for (grading, ok) in [("graded", true), ("uniform", false)] {
        std::fs::write(
            &job,
            format!("[input]\nfile = {:?}\n[density]\nsize = 2\n[mesh]\nmethod = \"octree\"\ngrading = \"{grading}\"\ncoarsen = false\n[[output]]\nfile = {:?}\n", flange, dir.path().join("j.msh")),
        )
        .unwrap();
        let o = run(&["run".as_ref(), job.as_os_str()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.success(), ok, "{grading}: {err}");
        if !ok {
            assert!(o.status.code() == Some(1) || o.status.code() == Some(2), "{err}");
            assert!(err.contains("key `coarsen`") && err.contains(":8:"), "{err}");
        }
    }
}

/// A CAD assembly (18 solids): each solid meshed on its own, its own region, the contacts
/// listed, the volume of every solid kept within 1 % and the boundary within the cell size
/// of the solids' surfaces (the faces where solids touch included).
#[test]
#[ignore = "heavy: run in release with --include-ignored"]
fn assembly_meshes_solid_by_solid() {
    let Some(path) = common::corpus_file("as1-tu-203.stp") else { return };
    let Some((err, o)) = mesh("as1-tu-203.stp", 100.0) else { return };
    assert_eq!(o.solids, 18);
    assert!(o.empty_solids.is_empty(), "{:?}", o.empty_solids);
    assert!(err.abs() < 0.01, "volume {err}");
    // at a quarter of that resolution the thinner solids are left out, named
    let mut part = Part::open(&path).unwrap();
    let mut density = fepre::attributes::Density::default();
    density.size = fepre::attributes::Positive::new(part.diagonal() / 25.0);
    let plan = Plan { unit: 1.0, density, method: Method::Octree, ..Plan::default() };
    let report = run_plan(&mut part, &plan, false).unwrap();
    let o = report.octree.unwrap();
    let mesh = part.mesh.as_ref().unwrap();
    let mut regions: Vec<u32> = mesh.region_tags.iter().map(|r| r.0).collect();
    regions.sort_unstable();
    regions.dedup();
    assert_eq!(regions.len() + o.empty_solids.len(), 18, "{regions:?} {:?}", o.empty_solids);
    assert!(o.empty_solids.iter().all(|e| !regions.contains(&e.solid) && e.volume > 0.0));
    assert!(!part.contacts.is_empty());
}

/// A solid thinner than the cell is left out with a warning naming it, not silently.
#[test]
fn a_solid_thinner_than_the_cell_is_named() {
    let Some(path) = common::corpus_file("abc-0000.step") else { return };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("a.mesh");
    let o = Command::new(env!("CARGO_BIN_EXE_fepre"))
        .args(["mesh".as_ref(), path.as_os_str(), "-o".as_ref(), out.as_os_str(), "--method".as_ref(), "octree".as_ref(), "--size".as_ref(), "12".as_ref()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("solids left out") && err.contains("\"Glass\""), "{err}");
    assert!(err.contains("volume is"), "{err}");
    // the left-out pane is input surface far from the mesh: the report gives how far, with a
    // place and the bound. Its farthest point is 1.1923e1 from the mesh against the cell of
    // 12, and the bound, with the pieces whose bound straddles the cell measured finely and
    // then closely, 1.1995e1, within the cell: no warning (the bound was 1.013 cells with the
    // fine measure alone, 1.069 before it, and 2.0043e1 was sampled before the frame's
    // boundary was snapped onto its edges beside the pane)
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("input→mesh 1.1923e1; farthest at (-50.559015, -14.758019, 410.877267)), at most 1.1995e1"), "{text}");
    assert!(!err.contains("the boundary strays"), "{err}");
}

/// A surface whose triangles face inward (as some tessellated STEP files and STL exports
/// come) encloses a negative volume and winding number −1: meshed turned outward, and said.
#[test]
fn an_inward_surface_is_meshed_turned_outward() {
    let mut s = fepre::mesh::shapes::plate_with_hole(16, 10.0, 2.0, 2.0);
    let volume = s.signed_volume();
    for t in &mut s.triangles {
        t.swap(1, 2);
    }
    let mut part = Part::from_surface(Path::new("inward.stl"), s);
    let plan = Plan { unit: 1.0, method: Method::Octree, ..Plan::default() };
    let report = run_plan(&mut part, &plan, false).unwrap();
    let o = report.octree.unwrap();
    assert!(o.turned_outward && o.input_volume_exact);
    assert!((o.volume / volume - 1.0).abs() <= 0.01 && (o.input_volume - volume).abs() < 1e-9 * volume, "{} {} {volume}", o.volume, o.input_volume);
    part.mesh.as_ref().unwrap().validate().unwrap();
}

/// Solids of an assembly that overlap (a real export of the sweep, `pr1ct.stp`: two of its
/// solids 0.38 deep in each other) are refused by the Delaunay path, which needs one
/// conforming boundary; the octree meshes each solid on its own winding number and says
/// where the overlap is.
#[test]
fn overlapping_solids_mesh_one_by_one_and_the_overlap_is_said() {
    let Some(dir) = common::sweep_dir() else { return };
    let mut part = Part::open(&dir.join("pr1ct.stp")).unwrap();
    let plan = Plan { unit: 1.0, method: Method::Octree, ..Plan::default() };
    let report = run_plan(&mut part, &plan, false).unwrap();
    let o = report.octree.unwrap();
    let m = o.overlap.as_deref().unwrap_or_default();
    assert!(m.contains("overlap: the point (") && m.contains("solid 2") && m.contains("solid 3"), "{m}");
    assert!(o.solids == 4 && o.empty_solids.is_empty(), "{} {:?}", o.solids, o.empty_solids);
    assert!(part.contacts.is_empty());
    let mesh = part.mesh.as_ref().unwrap();
    mesh.validate().unwrap();
    let mut regions: Vec<u32> = mesh.region_tags.iter().map(|r| r.0).collect();
    regions.sort_unstable();
    regions.dedup();
    assert_eq!(regions, [1, 2, 3, 4]);
    // the Delaunay path refuses it, naming the overlap
    let mut part = Part::open(&dir.join("pr1ct.stp")).unwrap();
    let e = run_plan(&mut part, &Plan { unit: 1.0, ..Plan::default() }, false).unwrap_err().to_string();
    assert!(e.contains("overlap"), "{e}");
}

/// An open surface (the corpus' `rabbit.obj`, with holes) has no exact volume: at the default
/// the cell gets finer until the mesh's volume changes by at most 1 % from one cell to the
/// next (it converges to the winding number's); without that, the first cell was 3.5 % under
/// the volume it converges to.
#[test]
fn an_open_surface_gets_a_cell_whose_volume_has_settled() {
    use fepre::mesh3d::octree::RESOLVE;
    let Some(path) = common::corpus_file("rabbit.obj") else { return };
    let mut part = Part::open(&path).unwrap();
    let plan = Plan { unit: 1.0, method: Method::Octree, ..Plan::default() };
    let o = run_plan(&mut part, &plan, false).unwrap().octree.unwrap();
    assert!(!o.input_volume_exact);
    // the report's reference: the winding number's volume (6.539 on 128³ cells; the mesh
    // −0.36 % from it, the divergence theorem's 6.6485 −2.0 %)
    let w = o.winding_volume.expect("an inexact input gets the winding number's volume");
    assert!((w.volume - 6.539).abs() < w.error.max(0.01) && (o.volume / w.volume - 1.0).abs() < 0.01, "{} against {w:?}", o.volume);
    let t = &o.cell_tries;
    assert!(t.len() >= 3 && t.iter().all(|t| t.volume_error.is_none() && !t.empty), "{t:?}");
    assert!(t[0].volume_change.is_none() && t[1..].iter().all(|t| t.volume_change.is_some()), "{t:?}");
    let kept: Vec<_> = t.iter().filter(|t| t.kept).collect();
    assert!(kept.len() == 1 && RESOLVE.holds(kept[0]) && kept[0].cell == o.cell_size, "{t:?}");
    // none before the kept one holds
    assert!(t.iter().take_while(|x| !x.kept).all(|x| !RESOLVE.holds(x)), "{t:?}");
    part.mesh.as_ref().unwrap().validate().unwrap();
}
