//! Writes a small tagged tet mesh and a tagged surface through the Medit, TetGen, MSH and VTU
//! writers, reads them back with fepre, and has external tools check them: `gmsh` re-saves
//! our `.msh` (ASCII, binary, 2.2), `tetgen -r` refines our `.node/.ele/.face`, `tetgen -p`
//! meshes our `.poly/.smesh`, and meshio (Python) reads `.msh`, `.vtu`, `.mesh` and `.ele`.
//!
//! A missing tool skips its check with a message, except under `CI=true` where it fails. The
//! Python interpreter is `$FEPRE_PYTHON`, else `.venv/bin/python` in the crate's directory
//! (`python3 -m venv .venv && .venv/bin/pip install meshio numpy`).

mod common;

use common::tools;
use fepre::core::{FaceId, RegionId};
use fepre::io::{MeshData, ReadOptions, WriteOptions, read, write};
use fepre::mesh::{TetMesh, TriSurface};
use glam::DVec3;
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

/// The unit cube split into 6 tets around its diagonal: regions 1 (`y < x`-ish half) and 2
/// (named "upper part"), boundary triangles tagged 1 to 6 by side (tag 1 named "xmin"), and
/// the two triangles between the regions tagged 7 ("interface").
fn cube() -> TetMesh {
    let v: Vec<DVec3> = (0..8).map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64)).collect();
    let mut tets = vec![[0u32, 1, 3, 7], [0, 3, 2, 7], [0, 2, 6, 7], [0, 6, 4, 7], [0, 4, 5, 7], [0, 5, 1, 7]];
    for t in &mut tets {
        let [a, b, c, d] = t.map(|i| v[i as usize]);
        if (b - a).dot((c - a).cross(d - a)) < 0.0 {
            t.swap(2, 3);
        }
    }
    let mut m = TetMesh { vertices: v, tets, region_tags: [1, 1, 1, 2, 2, 2].map(RegionId).to_vec(), ..Default::default() };
    for f in m.faces() {
        let region = |t: u32| m.region_tags[t as usize];
        let tag = match f.neighbor {
            Some(n) if region(n) != region(f.tet) => 7,
            Some(_) => continue,
            None => {
                let c = f.vertices.iter().map(|&i| m.vertices[i as usize]).sum::<DVec3>() / 3.0;
                [c.x == 0.0, c.x == 1.0, c.y == 0.0, c.y == 1.0, c.z == 0.0, c.z == 1.0].iter().position(|&b| b).unwrap() as u32 + 1
            }
        };
        m.boundary.push(f.vertices);
        m.face_tags.push(FaceId(tag));
    }
    m.face_names.insert(FaceId(1), "xmin");
    m.face_names.insert(FaceId(7), "interface");
    m.region_names.insert(RegionId(2), "upper part");
    m.validate().unwrap();
    assert_eq!((m.boundary.len(), m.tets.len()), (14, 6));
    m
}

/// The cube's outer boundary as a surface, tagged by side.
fn cube_surface() -> TriSurface {
    let m = cube();
    let keep: Vec<usize> = (0..m.boundary.len()).filter(|&i| m.face_tags[i] != FaceId(7)).collect();
    let mut s = TriSurface {
        vertices: m.vertices.clone(),
        triangles: keep.iter().map(|&i| m.boundary[i]).collect(),
        face_tags: keep.iter().map(|&i| m.face_tags[i]).collect(),
        ..Default::default()
    };
    s.face_names.insert(FaceId(1), "xmin");
    s
}

fn sorted<T: Ord + Clone>(v: &[T]) -> Vec<T> {
    let mut v = v.to_vec();
    v.sort();
    v
}

fn read_volume(p: &Path) -> TetMesh {
    match read(p, &ReadOptions::default()).unwrap_or_else(|e| panic!("{e}")).mesh {
        MeshData::Volume(m) => m,
        other => panic!("{}: expected a tet mesh, got a {}", p.display(), other.kind()),
    }
}

fn read_surface(p: &Path) -> TriSurface {
    match read(p, &ReadOptions::default().with_weld(None)).unwrap_or_else(|e| panic!("{e}")).mesh {
        MeshData::Surface(s) => s,
        other => panic!("{}: expected a surface, got a {}", p.display(), other.kind()),
    }
}

fn put(dir: &Path, name: &str, mesh: MeshData) -> std::path::PathBuf {
    let p = dir.join(name);
    write(&p, &mesh, &WriteOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    p
}

#[test]
fn own_readers_give_back_what_every_writer_wrote() {
    let dir = tempfile::tempdir().unwrap();
    let m = cube();
    for name in ["v.msh", "v.mesh", "v.ele"] {
        let p = put(dir.path(), name, MeshData::Volume(m.clone()));
        let mut back = read_volume(&p);
        if !name.ends_with(".msh") {
            // Medit and TetGen have no names.
            back.face_names = m.face_names.clone();
            back.region_names = m.region_names.clone();
        }
        assert_eq!(back, m, "{name}");
    }
    let s = cube_surface();
    for name in ["s.msh", "s.mesh", "s.poly", "s.smesh", "s.face"] {
        let p = put(dir.path(), name, MeshData::Surface(s.clone()));
        let mut back = read_surface(&p);
        if !name.ends_with(".msh") {
            back.face_names = s.face_names.clone();
        }
        assert_eq!(back, s, "{name}");
    }
}

#[test]
fn gmsh_reads_and_resaves_our_msh() {
    let Some(gmsh) = tools::require(tools::gmsh(), "gmsh", "the gmsh checks of .msh files") else { return };
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let m = cube();
    let s = cube_surface();
    put(d, "v.msh", MeshData::Volume(m.clone()));
    put(d, "s.msh", MeshData::Surface(s.clone()));
    for input in ["v.msh", "s.msh"] {
        let out = tools::run_ok(Command::new(&gmsh).args(["-check", input]), d);
        let log = String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
        assert!(!log.contains("Error") && !log.contains("Warning"), "gmsh -check {input}:\n{log}");
        for (suffix, extra) in
            [("41", &["-format", "msh41"][..]), ("41b", &["-format", "msh41", "-bin"][..]), ("22", &["-format", "msh22"][..])]
        {
            let output = format!("{}_{suffix}.msh", &input[..1]);
            let mut cmd = Command::new(&gmsh);
            cmd.args([input, "-0"]).args(extra).args(["-o", &output]);
            tools::run_ok(&mut cmd, d);
            let p = d.join(&output);
            if input.starts_with('v') {
                let back = read_volume(&p);
                if suffix == "22" {
                    // Gmsh renumbers nodes in 2.2; compare counts, tags and names.
                    assert_eq!((back.vertices.len(), back.tets.len(), back.boundary.len()), (8, 6, 14), "{output}");
                    assert_eq!(sorted(&back.region_tags), sorted(&m.region_tags), "{output}");
                    assert_eq!(sorted(&back.face_tags), sorted(&m.face_tags), "{output}");
                    assert_eq!((back.face_names.clone(), back.region_names.clone()), (m.face_names.clone(), m.region_names.clone()));
                    assert!((back.volume() - 1.0).abs() < 1e-12, "{output}");
                } else {
                    assert_eq!(back, m, "{output}: gmsh keeps node and element numbers");
                }
            } else {
                let back = read_surface(&p);
                assert_eq!(sorted(&back.face_tags), sorted(&s.face_tags), "{output}");
                assert_eq!(back.face_names, s.face_names, "{output}");
                if suffix != "22" {
                    assert_eq!(back, s, "{output}");
                }
            }
        }
    }
}

#[test]
fn tetgen_refines_our_mesh_and_meshes_our_plc() {
    let Some(tetgen) = tools::require(tools::tetgen(), "tetgen", "the tetgen checks of .node/.ele/.face/.poly/.smesh") else { return };
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let m = cube();
    put(d, "v.ele", MeshData::Volume(m.clone()));
    // Reconstruct only: the same mesh, markers and attributes.
    tools::run_ok(Command::new(&tetgen).args(["-rQ", "v"]), d);
    let r = read_volume(&d.join("v.1.ele"));
    assert_eq!((r.vertices.len(), r.tets.len()), (8, 6));
    assert_eq!(sorted(&r.region_tags), sorted(&m.region_tags));
    let tags: Vec<FaceId> = sorted(&r.face_tags);
    assert_eq!(tags, sorted(&m.face_tags), "tetgen keeps our face markers, the interface included");
    assert!((r.volume() - 1.0).abs() < 1e-12);
    // Refine: the regions and the tagged faces survive.
    std::fs::remove_file(d.join("v.1.ele")).unwrap();
    tools::run_ok(Command::new(&tetgen).args(["-rqa0.01Q", "v"]), d);
    let r = read_volume(&d.join("v.1.ele"));
    assert!(r.tets.len() > 100, "{} tets", r.tets.len());
    assert!((r.volume() - 1.0).abs() < 1e-9, "volume {}", r.volume());
    let mut regions = sorted(&r.region_tags);
    regions.dedup();
    assert_eq!(regions, vec![RegionId(1), RegionId(2)]);
    let mut faces = sorted(&r.face_tags);
    faces.dedup();
    assert!((1..=7).all(|t| faces.contains(&FaceId(t))), "{faces:?}");
    // The surface as a PLC, both syntaxes, each in its own directory (tetgen names the output x.1.*).
    let s = cube_surface();
    for name in ["s.poly", "s.smesh"] {
        let sub = d.join(&name[2..]);
        std::fs::create_dir(&sub).unwrap();
        put(&sub, name, MeshData::Surface(s.clone()));
        tools::run_ok(Command::new(&tetgen).args(["-pQ", name]), &sub);
        let r = read_volume(&sub.join("s.1.ele"));
        assert!((r.volume() - 1.0).abs() < 1e-12, "{name}: volume {}", r.volume());
        assert_eq!(sorted(&r.face_tags), sorted(&s.face_tags), "{name}");
    }
}

const MESHIO_SCRIPT: &str = r#"
import json, sys
import meshio, numpy as np
out = {}
for f in sys.argv[1:]:
    m = meshio.read(f)
    key = next((k for k in ("gmsh:physical", "tag", "medit:ref", "tetgen:ref") if k in m.cell_data), None)
    cells, tags = {}, {}
    for i, c in enumerate(m.cells):
        cells[c.type] = cells.get(c.type, 0) + len(c.data)
        if key is not None:
            tags.setdefault(c.type, []).extend(int(x) for x in np.asarray(m.cell_data[key][i]).ravel())
    out[f] = {"points": len(m.points), "cells": cells, "tags": {k: sorted(v) for k, v in tags.items()},
              "names": sorted(m.field_data.keys())}
print(json.dumps(out))
"#;

#[derive(Debug, serde::Deserialize, PartialEq)]
struct MeshioView {
    points: usize,
    cells: BTreeMap<String, usize>,
    tags: BTreeMap<String, Vec<u32>>,
    names: Vec<String>,
}

#[test]
fn meshio_reads_our_files_with_the_same_counts_and_tags() {
    let Some(python) = tools::require(tools::meshio_python(), "Python with meshio", "the meshio checks") else { return };
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let m = cube();
    let s = cube_surface();
    let ascii = WriteOptions::default().with_ascii(true);
    for name in ["v.msh", "v.vtu", "v.mesh", "v.ele"] {
        put(d, name, MeshData::Volume(m.clone()));
    }
    write(&d.join("va.vtu"), &MeshData::Volume(m.clone()), &ascii).unwrap();
    for name in ["s.msh", "s.vtu", "s.mesh"] {
        put(d, name, MeshData::Surface(s.clone()));
    }
    write(&d.join("sa.vtu"), &MeshData::Surface(s.clone()), &ascii).unwrap();
    let files = ["v.msh", "v.vtu", "va.vtu", "v.mesh", "v.ele", "s.msh", "s.vtu", "sa.vtu", "s.mesh"];
    let out = tools::run_ok(Command::new(&python).arg("-c").arg(MESHIO_SCRIPT).args(files), d);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let last = stdout.lines().last().unwrap_or_default();
    let views: BTreeMap<String, MeshioView> = serde_json::from_str(last).unwrap_or_else(|e| panic!("{e}: {stdout}"));

    let tets = sorted(&m.region_tags.iter().map(|r| r.0).collect::<Vec<_>>());
    let bnd = sorted(&m.face_tags.iter().map(|f| f.0).collect::<Vec<_>>());
    let srf = sorted(&s.face_tags.iter().map(|f| f.0).collect::<Vec<_>>());
    let view = |cells: &[(&str, usize)], tags: &[(&str, &Vec<u32>)], names: &[&str]| MeshioView {
        points: 8,
        cells: cells.iter().map(|(k, n)| (k.to_string(), *n)).collect(),
        tags: tags.iter().map(|(k, v)| (k.to_string(), (*v).clone())).collect(),
        names: names.iter().map(|n| n.to_string()).collect(),
    };
    let volume = |names: &[&str]| view(&[("tetra", 6), ("triangle", 14)], &[("tetra", &tets), ("triangle", &bnd)], names);
    let surface = |names: &[&str]| view(&[("triangle", 12)], &[("triangle", &srf)], names);
    let expected = [
        ("v.msh", volume(&["interface", "upper part", "xmin"])),
        ("v.vtu", volume(&[])),
        ("va.vtu", volume(&[])),
        ("v.mesh", volume(&[])),
        ("v.ele", view(&[("tetra", 6)], &[("tetra", &tets)], &[])),
        ("s.msh", surface(&["xmin"])),
        ("s.vtu", surface(&[])),
        ("sa.vtu", surface(&[])),
        ("s.mesh", surface(&[])),
    ];
    for (name, want) in expected {
        assert_eq!(views.get(name), Some(&want), "meshio's view of {name}");
    }

    // VTK itself (what ParaView uses), where the interpreter has it.
    if tools::python_with(&["vtk"]).is_some() {
        let script = "import sys, vtk\nfor f in sys.argv[1:]:\n    r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(f); r.Update(); g = r.GetOutput()\n    \
                      t = g.GetCellData().GetArray('tag')\n    print(f, g.GetNumberOfPoints(), g.GetNumberOfCells(), sum(int(t.GetValue(i)) for i in range(g.GetNumberOfCells())), r.GetErrorCode())\n";
        let out = tools::run_ok(Command::new(&python).arg("-c").arg(script).args(["v.vtu", "va.vtu", "s.vtu"]), d);
        let text = String::from_utf8_lossy(&out.stdout);
        let sum = |v: &[u32]| v.iter().sum::<u32>();
        let vol = format!("{} {}", sum(&tets) + sum(&bnd), 0);
        let want = format!("v.vtu 8 20 {vol}\nva.vtu 8 20 {vol}\ns.vtu 8 12 {} 0\n", sum(&srf));
        assert_eq!(text, want);
    } else {
        eprintln!("note: the Python interpreter has no vtk module; checked VTU with meshio only");
    }
}

/// Our points `.node` and surface `.node + .face` are read by TetGen itself: it tetrahedralizes
/// the points, and reads a `.face` written beside an `.ele` when reconstructing.
#[test]
fn tetgen_reads_our_points_and_surface_faces() {
    let Some(tetgen) = tools::require(tools::tetgen(), "tetgen", "the tetgen checks of points .node and surface .face") else { return };
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let m = cube();
    // points: TetGen's Delaunay tetrahedralization of our .node has every point and the hull volume
    put(d, "p.node", MeshData::Points(m.vertices.clone()));
    tools::run_ok(Command::new(&tetgen).args(["-Q", "p"]), d);
    let r = read_volume(&d.join("p.1.ele"));
    assert_eq!(r.vertices.len(), m.vertices.len());
    assert!((r.volume() - 1.0).abs() < 1e-12, "volume {}", r.volume());
    // surface as .node + .face: put the volume's .ele beside it and let tetgen -r take the faces
    let s = cube_surface();
    put(d, "f.face", MeshData::Surface(s.clone()));
    let ele = d.join("v.ele");
    put(d, "v.ele", MeshData::Volume(m.clone()));
    std::fs::copy(&ele, d.join("f.ele")).unwrap();
    tools::run_ok(Command::new(&tetgen).args(["-rQ", "f"]), d);
    let r = read_volume(&d.join("f.1.ele"));
    assert_eq!(r.tets.len(), m.tets.len());
    // TetGen also outputs the two faces between the regions, which our surface does not list,
    // with marker 0; every face we wrote comes back with its marker
    let mut got: Vec<FaceId> = r.face_tags.iter().copied().filter(|t| t.0 != 0).collect();
    got.sort();
    let mut want = s.face_tags.clone();
    want.sort();
    assert_eq!(got, want, "TetGen keeps the markers of our .face");
    assert_eq!(r.face_tags.len(), s.face_tags.len() + 2, "plus the two interface faces");
}
