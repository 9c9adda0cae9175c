//! The FE model in the other decks, read by other programs: Gmsh and meshio read the MSH with
//! the sets as named physical groups (and meshio's reading of its 10-node tets equals the
//! VTU's), VTK reads the VTU with the sets as named arrays and its `vtkMeshQuality` agrees
//! with fepre's tet measures to 1e-9 (scaled Jacobian, radius ratio, aspect ratio, edge ratio,
//! volume; the smallest dihedral angle is checked against an independent computation in the
//! same script instead: VTK 9.6's `MinAngle` of a tet is not its smallest dihedral angle where
//! the tet has an obtuse one, e.g. 67.55° for a tet whose dihedral angles are 37.96°, 40.94°,
//! 67.55°, 74.30°, 91.78° and 100.18°). The Nastran deck is checked by pyNastran in
//! `tests/deck_nastran.rs`.

mod common;

use common::tools;
use fepre::cad::parts::Block;
use fepre::pipeline::job::JobFile;
use fepre::pipeline::carry_out;
use fepre::quality::tet_measures;
use glam::DVec3;
use std::path::Path;
use std::process::Command;

const STEEL: &str = "[materials.steel]\nyoung = 210000\npoisson = 0.3\n[[section]]\nmaterial = \"steel\"\n";

/// Writes the decks of a clamped block with a tip force, elements `element`, in `dir`; returns
/// the FE model's node and element counts.
fn decks(dir: &Path, element: &str) -> fepre::fe::FeModel {
    fepre::cad::step::write(&dir.join("part.step"), &Block::new(40.0, 10.0, 10.0).build().unwrap(), "part").unwrap();
    let job = format!(
        "[input]\nfile = \"part.step\"\n[selectors]\nclamp = {{ name = \"xmin\" }}\ntip = {{ name = \"xmax\" }}\nsides = {{ name = \"y*\" }}\n[density]\nsize = 4\n[model]\nelement = \"{element}\"\n{STEEL}[[step]]\nfixed = [{{ faces = \"clamp\" }}]\nforce = [{{ faces = \"tip\", total = [0, 0, -100] }}]\n[[output]]\nfile = \"d.msh\"\nkind = \"deck\"\n[[output]]\nfile = \"d.vtu\"\nkind = \"deck\"\n[[output]]\nfile = \"d.bdf\"\n"
    );
    std::fs::write(dir.join("job.toml"), job).unwrap();
    let outcome = carry_out(&JobFile::read(&dir.join("job.toml")).unwrap(), false).unwrap();
    assert!(dir.join("d.bdf").is_file());
    outcome.fe.unwrap()
}

fn python(script: &str, args: &[&Path], modules: &[&str], check: &str) -> Option<String> {
    let python = tools::require(tools::python_with(modules), &format!("python with {}", modules.join(", ")), check)?;
    let out = Command::new(python).arg("-c").arg(script).args(args).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    Some(String::from_utf8_lossy(&out.stdout).into_owned())
}

#[test]
fn meshio_and_gmsh_read_the_msh_with_the_sets_as_named_groups() {
    let dir = tempfile::tempdir().unwrap();
    let m = decks(dir.path(), "C3D10");
    let script = "import meshio, sys, numpy as np\nm = meshio.read(sys.argv[1]); v = meshio.read(sys.argv[2])\nt = [c.data for c in m.cells if c.type == 'tetra10'][0]\nvt = [c.data for c in v.cells if c.type == 'tetra10'][0]\nprint(len(m.points), len(t), int(np.array_equal(t, vt)), ' '.join(sorted(m.field_data)))";
    if let Some(out) = python(script, &[&dir.path().join("d.msh"), &dir.path().join("d.vtu")], &["meshio", "numpy"], "meshio reading the MSH deck") {
        let v: Vec<&str> = out.split_whitespace().collect();
        assert_eq!(v[0].parse::<usize>().unwrap(), m.nodes.len(), "{out}");
        assert_eq!(v[1].parse::<usize>().unwrap(), m.element_count(), "{out}");
        assert_eq!(v[2], "1", "meshio reads different 10-node tets from the MSH and the VTU: {out}");
        assert_eq!(&v[3..], ["BLOCK", "CLAMP_S", "SIDES_S", "TIP_S"], "{out}");
    }
    let Some(gmsh) = tools::require(tools::gmsh(), "gmsh", "gmsh reading the MSH deck") else { return };
    let again = dir.path().join("again.msh");
    let out = Command::new(gmsh).arg(dir.path().join("d.msh")).arg("-0").arg("-o").arg(&again).output().unwrap();
    assert!(out.status.success() && again.is_file(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&again).unwrap();
    for name in ["\"BLOCK\"", "\"CLAMP_S\"", "\"SIDES_S\"", "\"TIP_S\""] {
        assert!(text.contains(name), "gmsh dropped the group {name}");
    }
}

#[test]
fn vtk_reads_the_vtu_with_the_sets_and_agrees_with_the_tet_measures() {
    let dir = tempfile::tempdir().unwrap();
    let m = decks(dir.path(), "C3D4");
    let script = "import sys, vtk
r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(sys.argv[1]); r.Update(); g = r.GetOutput()
pd, cd = g.GetPointData(), g.GetCellData()
print(' '.join(sorted(pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays()))))
print(' '.join(sorted(cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays()))))
q = vtk.vtkMeshQuality(); q.SetInputData(g)
out = []
for name, setter in [('scaled_jacobian', q.SetTetQualityMeasureToScaledJacobian), ('radius_ratio', q.SetTetQualityMeasureToRadiusRatio), ('aspect_ratio', q.SetTetQualityMeasureToAspectRatio), ('edge_ratio', q.SetTetQualityMeasureToEdgeRatio), ('volume', q.SetTetQualityMeasureToVolume)]:
    setter(); q.Update(); a = q.GetOutput().GetCellData().GetArray('Quality')
    out.append(name + ' ' + ' '.join(repr(a.GetValue(i)) for i in range(g.GetNumberOfCells()) if g.GetCellType(i) == 10))
import itertools, math
def dihedrals(p):
    for i, j in itertools.combinations(range(4), 2):
        k, l = [x for x in range(4) if x not in (i, j)]
        e = [p[j][a] - p[i][a] for a in range(3)]; n = math.sqrt(sum(x * x for x in e)); e = [x / n for x in e]
        def perp(q):
            d = [q[a] - p[i][a] for a in range(3)]; t = sum(d[a] * e[a] for a in range(3)); return [d[a] - t * e[a] for a in range(3)]
        u, v = perp(p[k]), perp(p[l])
        yield math.degrees(math.acos(sum(u[a] * v[a] for a in range(3)) / math.sqrt(sum(x * x for x in u) * sum(x * x for x in v))))
mins = []
for i in range(g.GetNumberOfCells()):
    if g.GetCellType(i) == 10:
        c = g.GetCell(i); mins.append(min(dihedrals([g.GetPoint(c.GetPointId(k)) for k in range(4)])))
out.append('min_dihedral ' + ' '.join(repr(x) for x in mins))
print('\\n'.join(out))";
    let Some(out) = python(script, &[&dir.path().join("d.vtu")], &["vtk"], "VTK reading the VTU deck") else { return };
    let mut lines = out.lines();
    assert_eq!(lines.next().unwrap(), "CLAMP SIDES TIP", "point arrays");
    assert_eq!(lines.next().unwrap(), "BLOCK CLAMP_S SIDES_S TIP_S cell_kind region", "cell arrays");
    let mut worst = 0.0f64;
    for line in lines {
        let mut it = line.split_whitespace();
        let name = it.next().unwrap();
        let vtk: Vec<f64> = it.map(|x| x.parse().unwrap()).collect();
        assert_eq!(vtk.len(), m.element_count(), "{name}");
        for (e, q) in vtk.iter().enumerate() {
            let p: [DVec3; 4] = std::array::from_fn(|k| m.nodes[m.element(e)[k] as usize]);
            let t = tet_measures(&p);
            let ours = match name {
                "min_dihedral" => t.min_dihedral,
                "scaled_jacobian" => t.scaled_jacobian,
                "radius_ratio" => t.radius_ratio,
                "aspect_ratio" => t.aspect_ratio,
                "edge_ratio" => t.edge_ratio,
                _ => t.volume,
            };
            let rel = (ours - q).abs() / q.abs().max(1e-300);
            worst = worst.max(rel);
            assert!(rel < 1e-9, "{name} of element {}: fepre {ours}, VTK {q}", e + 1);
        }
    }
    eprintln!("vtkMeshQuality against fepre's measures on {} tets: worst relative difference {worst:.2e}", m.element_count());
}
