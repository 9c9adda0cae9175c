//! FE results written by [`fepre::io::vtu::write_grid_with_data`] and read back by meshio
//! (Python): a quadratic tet must come back as `tetra10` with its nodes in order, and every
//! point and cell array with its name, shape and values, in binary and in ASCII.
//!
//! The Python interpreter is `$FEPRE_PYTHON`, else `.venv/bin/python` in the crate's
//! directory. Without meshio the test skips with a message, except under `CI=true` where it
//! fails.

mod common;

use common::tools;
use fepre::io::WriteOptions;
use fepre::io::vtu::{Grid, write_grid_with_data};
use glam::DVec3;
use std::collections::BTreeMap;
use std::process::Command;

const SCRIPT: &str = r#"
import json, sys
import meshio, numpy as np
out = {}
for f in sys.argv[1:]:
    m = meshio.read(f)
    out[f] = {
        "points": np.asarray(m.points).tolist(),
        "cells": [[c.type, np.asarray(c.data).tolist()] for c in m.cells],
        "point_data": {k: np.asarray(v).tolist() for k, v in m.point_data.items()},
        "cell_data": {k: [np.asarray(b).tolist() for b in v] for k, v in m.cell_data.items()},
        "cell_dtypes": {k: str(np.asarray(v[0]).dtype) for k, v in m.cell_data.items()},
    }
print(json.dumps(out))
"#;

#[derive(Debug, serde::Deserialize)]
struct View {
    points: Vec<[f64; 3]>,
    cells: Vec<(String, Vec<Vec<u32>>)>,
    point_data: BTreeMap<String, serde_json::Value>,
    cell_data: BTreeMap<String, Vec<serde_json::Value>>,
    cell_dtypes: BTreeMap<String, String>,
}

#[test]
fn meshio_reads_a_quadratic_tet_with_its_arrays() {
    let Some(python) = tools::require(tools::meshio_python(), "Python with meshio", "the VTU results check") else { return };
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();

    // two quadratic tets sharing the face (1, 2, 3), mid-edge nodes in C3D10 order
    let corners = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::ONE];
    let mut points = corners.to_vec();
    let mut mid = BTreeMap::new();
    let mut tets = Vec::new();
    for c in [[0u32, 1, 2, 3], [4, 2, 1, 3]] {
        tets.extend(c);
        for (a, b) in [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)] {
            let key = (c[a].min(c[b]), c[a].max(c[b]));
            let id = *mid.entry(key).or_insert_with(|| {
                points.push((corners[key.0 as usize] + corners[key.1 as usize]) / 2.0);
                points.len() as u32 - 1
            });
            tets.push(id);
        }
    }
    assert_eq!(points.len(), 14);
    let tris = [[0u32, 2, 1]];
    let disp: Vec<f64> = points.iter().flat_map(|p| [0.1 * p.x, -0.2 * p.y, 0.3 * p.z * p.x]).collect();
    let temp: Vec<f64> = points.iter().map(|p| 20.0 + 80.0 * p.x).collect();
    let stress: Vec<f64> = (0..points.len()).flat_map(|i| (0..6).map(move |c| (10 * i + c) as f64)).collect();
    let mises = [150.0, 75.5, 0.0];
    let region = [1, 2, 0];
    let grid = Grid::new(&points, &tets, 10)
        .with_triangles(&tris)
        .with_point_data("DISP", 3, &disp)
        .with_point_data("NDTEMP", 1, &temp)
        .with_point_data("STRESS", 6, &stress)
        .with_cell_data("von Mises", 1, &mises)
        .with_cell_ints("region", &region);
    write_grid_with_data(&d.join("b.vtu"), &grid, &WriteOptions::default()).unwrap();
    write_grid_with_data(&d.join("a.vtu"), &grid, &WriteOptions::default().with_ascii(true)).unwrap();

    let out = tools::run_ok(Command::new(&python).arg("-c").arg(SCRIPT).args(["b.vtu", "a.vtu"]), d);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let last = stdout.lines().last().unwrap_or_default();
    let views: BTreeMap<String, View> = serde_json::from_str(last).unwrap_or_else(|e| panic!("{e}: {stdout}"));
    let per_point = |v: &[f64], n: usize| serde_json::json!(v.chunks(n).collect::<Vec<_>>());
    for name in ["b.vtu", "a.vtu"] {
        let v = &views[name];
        let pts: Vec<[f64; 3]> = points.iter().map(|p| p.to_array()).collect();
        assert_eq!(v.points, pts, "{name}");
        let types: Vec<&str> = v.cells.iter().map(|(t, _)| t.as_str()).collect();
        assert_eq!(types, ["tetra10", "triangle"], "{name}");
        let conn: Vec<Vec<u32>> = tets.chunks(10).map(<[u32]>::to_vec).collect();
        assert_eq!(v.cells[0].1, conn, "{name}: node order of the tets");
        assert_eq!(v.cells[1].1, vec![tris[0].to_vec()], "{name}");
        assert_eq!(v.point_data.keys().collect::<Vec<_>>(), ["DISP", "NDTEMP", "STRESS"], "{name}");
        assert_eq!(v.point_data["DISP"], per_point(&disp, 3), "{name}");
        assert_eq!(v.point_data["NDTEMP"], serde_json::json!(temp), "{name}");
        assert_eq!(v.point_data["STRESS"], per_point(&stress, 6), "{name}");
        // meshio splits cell arrays by cell block: the tets, then the triangle
        assert_eq!(v.cell_data["von Mises"], [serde_json::json!(mises[..2]), serde_json::json!(mises[2..])], "{name}");
        assert_eq!(v.cell_data["region"], [serde_json::json!(region[..2]), serde_json::json!(region[2..])], "{name}");
        assert_eq!(v.cell_dtypes["region"], "int32", "{name}");
        assert_eq!(v.cell_dtypes["von Mises"], "float64", "{name}");
    }

    // VTK itself (what ParaView uses), where the interpreter has it: the cell types, and the
    // volumes of the quadratic tets by VTK's own shape functions (1/6 and 1/3 when the
    // mid-edge nodes sit on the edges VTK expects them on)
    if tools::python_with(&["vtk"]).is_some() {
        let script = "import sys, vtk\nfor f in sys.argv[1:]:\n    r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(f); r.Update(); g = r.GetOutput()\n    \
                      s = vtk.vtkCellSizeFilter(); s.SetInputData(g); s.Update(); v = s.GetOutput().GetCellData().GetArray('Volume')\n    \
                      print(f, r.GetErrorCode(), [g.GetCellType(i) for i in range(g.GetNumberOfCells())], ['%.12f' % v.GetValue(i) for i in range(2)], \
                      g.GetPointData().GetArray('STRESS').GetNumberOfComponents())\n";
        let out = tools::run_ok(Command::new(&python).arg("-c").arg(script).args(["b.vtu", "a.vtu"]), d);
        let want = "b.vtu 0 [24, 24, 5] ['0.166666666667', '0.333333333333'] 6\na.vtu 0 [24, 24, 5] ['0.166666666667', '0.333333333333'] 6\n";
        assert_eq!(String::from_utf8_lossy(&out.stdout), want);
    } else {
        eprintln!("note: the Python interpreter has no vtk module; checked the VTU with meshio only");
    }
}
