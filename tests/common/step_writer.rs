//! Hand-written STEP files for the entity tests (`tests/step_entities*.rs`): numbered
//! instances, a box shell, the product structure around a solid, and the comparison with
//! OpenCASCADE (`shared/tools/occ/ocpref.py` through `$FEPRE_PYTHON`).

use super::tools;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The header every file here has.
pub const HEAD: &str = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('a box with a B-spline top'),'2;1');\nFILE_NAME('box','',(''),(''),'','fepre tests','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n";

/// How the top face and its edges are written.
pub struct Form {
    pub name: &'static str,
    pub degree: usize,
    /// Control points per direction of the top surface (the bump is at the middle one).
    pub n: usize,
    /// The surface entity, given `(degree, control point rows)`.
    pub surface: fn(usize, &str) -> String,
    /// The curve entity, given `(degree, control points)`.
    pub curve: fn(usize, &str) -> String,
}

/// Entity text with numbered instances.
pub struct Writer {
    pub text: String,
    pub next: usize,
}

impl Writer {
    pub fn add(&mut self, entity: String) -> usize {
        self.next += 1;
        writeln!(self.text, "#{}={entity};", self.next).unwrap();
        self.next
    }
    pub fn point(&mut self, p: [f64; 3]) -> usize {
        self.add(format!("CARTESIAN_POINT('',({:?},{:?},{:?}))", p[0], p[1], p[2]))
    }
    pub fn direction(&mut self, d: [f64; 3]) -> usize {
        self.add(format!("DIRECTION('',({:?},{:?},{:?}))", d[0], d[1], d[2]))
    }
}

pub fn refs(ids: &[usize]) -> String {
    format!("({})", ids.iter().map(|i| format!("#{i}")).collect::<Vec<_>>().join(","))
}

/// A closed shell of the box `lo + [0, s]^3` (its top face B-spline in `top`'s form where
/// given), every face's normal out of the box when `sense` (faces written `.F.` on their
/// outward planes otherwise: the shell inside out); returns the shell's id.
pub fn box_shell(w: &mut Writer, lo: [f64; 3], s: f64, top: Option<&Form>, sense: bool) -> usize {
    box_shell_written(w, lo, s, top, sense, false)
}

/// Like [`box_shell`]; where `against`, every flag that can be is written `.F.` and the shell
/// is still the same: the planes' axes point into the box under `ADVANCED_FACE(.F.)`, each
/// loop runs backwards under `FACE_BOUND(.F.)`, each line runs from the higher corner to
/// the lower under `EDGE_CURVE(.F.)` (with `ORIENTED_EDGE(.F.)` where the loop runs up).
pub fn box_shell_written(w: &mut Writer, lo: [f64; 3], s: f64, top: Option<&Form>, sense: bool, against: bool) -> usize {
    let bump = s * 0.4;
    let corner = |i: usize| [lo[0] + (i & 1) as f64 * s, lo[1] + ((i >> 1) & 1) as f64 * s, lo[2] + ((i >> 2) & 1) as f64 * s];
    let points: Vec<usize> = (0..8).map(|i| w.point(corner(i))).collect();
    let vertices: Vec<usize> = points.iter().map(|&p| w.add(format!("VERTEX_POINT('',#{p})"))).collect();
    // the top's control net, rows along x (u), columns along y (v): so the normal is +z
    let n = top.map_or(2, |f| f.n);
    let at = |k: usize| k as f64 * s / (n - 1) as f64;
    let mut net = vec![vec![0usize; n]; n];
    if top.is_some() {
        for (i, row) in net.iter_mut().enumerate() {
            for (j, id) in row.iter_mut().enumerate() {
                let z = if i == n / 2 && j == n / 2 { s + bump } else { s };
                *id = w.point([lo[0] + at(i), lo[1] + at(j), lo[2] + z]);
            }
        }
    }
    // edges between corners a < b; the top ones (both on top) are B-spline rows of the net
    let mut edges = std::collections::BTreeMap::new();
    let mut edge = |w: &mut Writer, a: usize, b: usize| -> (usize, bool) {
        let (lo_c, hi_c) = (a.min(b), a.max(b));
        let id = *edges.entry((lo_c, hi_c)).or_insert_with(|| {
            let (p, q) = (corner(lo_c), corner(hi_c));
            let curve = match top {
                Some(form) if lo_c >= 4 && hi_c >= 4 => {
                    let row: Vec<usize> = (0..n)
                        .map(|k| {
                            let t = k as f64 / (n - 1) as f64;
                            let (x, y) = (p[0] - lo[0] + (q[0] - p[0]) * t, p[1] - lo[1] + (q[1] - p[1]) * t);
                            net[(x / s * (n - 1) as f64).round() as usize][(y / s * (n - 1) as f64).round() as usize]
                        })
                        .collect();
                    w.add((form.curve)(form.degree, &refs(&row)))
                }
                _ if against => {
                    let d = w.direction([(p[0] - q[0]) / s, (p[1] - q[1]) / s, (p[2] - q[2]) / s]);
                    let v = w.add(format!("VECTOR('',#{d},{s:?})"));
                    w.add(format!("LINE('',#{},#{v})", points[hi_c]))
                }
                _ => {
                    let d = w.direction([(q[0] - p[0]) / s, (q[1] - p[1]) / s, (q[2] - p[2]) / s]);
                    let v = w.add(format!("VECTOR('',#{d},{s:?})"));
                    w.add(format!("LINE('',#{},#{v})", points[lo_c]))
                }
            };
            let along = if against && !(top.is_some() && lo_c >= 4) { ".F." } else { ".T." };
            w.add(format!("EDGE_CURVE('',#{},#{},#{curve},{along})", vertices[lo_c], vertices[hi_c]))
        });
        (id, a < b)
    };
    // corners (bit 0 x, bit 1 y, bit 2 z) of each face, counter-clockwise seen from outside
    let faces: [([usize; 4], [f64; 3]); 6] = [
        ([0, 2, 3, 1], [0.0, 0.0, -1.0]),
        ([4, 5, 7, 6], [0.0, 0.0, 1.0]),
        ([0, 1, 5, 4], [0.0, -1.0, 0.0]),
        ([2, 6, 7, 3], [0.0, 1.0, 0.0]),
        ([0, 4, 6, 2], [-1.0, 0.0, 0.0]),
        ([1, 3, 7, 5], [1.0, 0.0, 0.0]),
    ];
    let mut face_ids = Vec::new();
    for (corners, normal) in faces {
        // an inside-out face runs its loop the other way round
        let order: Vec<usize> = if sense != against { corners.to_vec() } else { corners.iter().rev().copied().collect() };
        let oriented: Vec<usize> = (0..4)
            .map(|k| {
                let (e, along) = edge(w, order[k], order[(k + 1) % 4]);
                w.add(format!("ORIENTED_EDGE('',*,*,#{e},{})", if along { ".T." } else { ".F." }))
            })
            .collect();
        let lp = w.add(format!("EDGE_LOOP('',{})", refs(&oriented)));
        let bound = if against { w.add(format!("FACE_BOUND('',#{lp},.F.)")) } else { w.add(format!("FACE_OUTER_BOUND('',#{lp},.T.)")) };
        let surface = match top {
            Some(form) if normal[2] > 0.0 => {
                let rows: Vec<String> = net.iter().map(|r| refs(r)).collect();
                w.add((form.surface)(form.degree, &format!("({})", rows.join(","))))
            }
            _ => {
                let axis = w.direction(if against { normal.map(|x| -x) } else { normal });
                let reference = w.direction(if normal[0] != 0.0 { [0.0, 1.0, 0.0] } else { [1.0, 0.0, 0.0] });
                let place = w.add(format!("AXIS2_PLACEMENT_3D('',#{},#{axis},#{reference})", points[corners[0]]));
                w.add(format!("PLANE('',#{place})"))
            }
        };
        let planar_against = against && !(top.is_some() && normal[2] > 0.0);
        face_ids.push(w.add(format!("ADVANCED_FACE('',(#{bound}),#{surface},{})", if sense != planar_against { ".T." } else { ".F." })));
    }
    w.add(format!("CLOSED_SHELL('',{})", refs(&face_ids)))
}

/// A STEP file of one solid (`solid` writes it, returning its id), named `name`.
pub fn step_file(name: &str, solid: impl FnOnce(&mut Writer) -> usize) -> String {
    let mut w = Writer { text: String::new(), next: 0 };
    let solid = solid(&mut w);
    let unit = w.add("( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )".into());
    let angle = w.add("( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) )".into());
    let solid_angle = w.add("( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() )".into());
    let uncertainty = w.add(format!("UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#{unit},'distance_accuracy_value','')"));
    let context = w.add(format!(
        "( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{uncertainty})) GLOBAL_UNIT_ASSIGNED_CONTEXT((#{unit},#{angle},#{solid_angle})) REPRESENTATION_CONTEXT('','') )"
    ));
    let origin = w.point([0.0; 3]);
    let (z, x) = (w.direction([0.0, 0.0, 1.0]), w.direction([1.0, 0.0, 0.0]));
    let frame = w.add(format!("AXIS2_PLACEMENT_3D('',#{origin},#{z},#{x})"));
    let rep = w.add(format!("ADVANCED_BREP_SHAPE_REPRESENTATION('{name}',(#{solid},#{frame}),#{context})"));
    // the product structure OpenCASCADE transfers from
    let app = w.add("APPLICATION_CONTEXT('automotive design')".into());
    let pcontext = w.add(format!("PRODUCT_CONTEXT('',#{app},'mechanical')"));
    let product = w.add(format!("PRODUCT('{name}','{name}','',(#{pcontext}))"));
    let dcontext = w.add(format!("PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"));
    let formation = w.add(format!("PRODUCT_DEFINITION_FORMATION('','',#{product})"));
    let definition = w.add(format!("PRODUCT_DEFINITION('design','',#{formation},#{dcontext})"));
    let shape = w.add(format!("PRODUCT_DEFINITION_SHAPE('','',#{definition})"));
    w.add(format!("SHAPE_DEFINITION_REPRESENTATION(#{shape},#{rep})"));
    format!("{HEAD}{}ENDSEC;\nEND-ISO-10303-21;\n", w.text)
}

/// Writes `files` (name, text) into `dir`, reads them with OpenCASCADE and with `fepre
/// tessellate --json`, and compares: one solid, certified, watertight, nothing dropped, volume
/// within 0.5 % of OpenCASCADE's and area within 0.25 %, `reoriented` shells as given; and
/// OpenCASCADE's volume within `occ_volume` (so the file means what the test says).
pub fn agrees_with_opencascade(test: &str, files: &[(String, String, usize, [f64; 2])]) {
    let Some(python) = tools::require(tools::python_with(&["OCP"]), "Python with OCP (pip install cadquery-ocp)", "the OpenCASCADE oracle") else { return };
    let script = super::shared_dir().join("tools/occ/ocpref.py");
    assert!(script.is_file() || !super::in_ci(), "{} is missing (CI=true)", script.display());
    if !script.is_file() {
        eprintln!("SKIP: {} is missing", script.display());
        return;
    }
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(test);
    std::fs::create_dir_all(&dir).unwrap();
    let paths: Vec<PathBuf> = files
        .iter()
        .map(|(name, text, _, _)| {
            let path = dir.join(format!("{name}.stp"));
            std::fs::write(&path, text).unwrap();
            path
        })
        .collect();
    let out = Command::new(&python).arg(&script).args(&paths).output().expect("run ocpref.py");
    assert!(out.status.success(), "ocpref.py failed: {}", String::from_utf8_lossy(&out.stderr));
    // OpenCASCADE prints its own messages on stdout too (`*** ERR StepReaderData ...`)
    let occ: Vec<serde_json::Value> = String::from_utf8_lossy(&out.stdout).lines().filter(|l| l.starts_with('{')).map(|l| serde_json::from_str(l).expect("one JSON object per line")).collect();
    assert_eq!(occ.len(), paths.len());
    let mut failures = Vec::new();
    for ((path, r), (name, _, reoriented, [vmin, vmax])) in paths.iter().zip(&occ).zip(files) {
        let (occ_volume, occ_area) = (r["volume_mm3"].as_f64().unwrap_or(f64::NAN), r["area_mm2"].as_f64().unwrap_or(f64::NAN));
        assert_eq!(r["solids"].as_u64(), Some(1), "{name}: OpenCASCADE reads {r}");
        assert!(occ_volume > *vmin && occ_volume < *vmax, "{name}: OpenCASCADE's volume {occ_volume}, not in {vmin}..{vmax}");
        let j = match tessellate(path) {
            Ok(j) => j,
            Err(e) => {
                failures.push(format!("{name}: {e}"));
                continue;
            }
        };
        let (volume, area) = (j["volume"].as_f64().unwrap_or(f64::NAN), j["area"].as_f64().unwrap_or(f64::NAN));
        let (dv, da) = ((volume - occ_volume) / occ_volume, (area - occ_area) / occ_area);
        eprintln!("{name}: volume {volume:.6} / OCC {occ_volume:.6} ({:+.4} %), area {area:.6} / OCC {occ_area:.6} ({:+.4} %)", 100.0 * dv, 100.0 * da);
        if j["solids"].as_u64() != Some(1) || j["watertight"] != serde_json::Value::Bool(true) {
            failures.push(format!("{name}: solids {}, watertight {}", j["solids"], j["watertight"]));
        }
        if j["dropped"].as_array().is_some_and(|d| !d.is_empty()) {
            failures.push(format!("{name}: dropped {}", j["dropped"]));
        }
        let turned = j["certificate"]["reoriented"].as_array().map_or(usize::MAX, Vec::len);
        if turned != *reoriented {
            failures.push(format!("{name}: {turned} shells reoriented, expected {reoriented}: {}", j["certificate"]["reoriented"]));
        }
        if !(dv.abs() <= 0.005) || !(da.abs() <= 0.0025) {
            failures.push(format!("{name}: volume {volume} area {area}, OpenCASCADE {occ_volume} and {occ_area}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `fepre tessellate --json` of `path` (the mesh written beside it): its report, or why not.
pub fn tessellate(path: &Path) -> Result<serde_json::Value, String> {
    let out = Command::new(env!("CARGO_BIN_EXE_fepre")).arg("tessellate").arg(path).arg("-o").arg(path.with_extension("stl")).arg("--json").output().map_err(|e| e.to_string())?;
    if !out.status.success() {
        return Err(format!("exit {:?}: {}", out.status.code(), String::from_utf8_lossy(&out.stderr)));
    }
    serde_json::from_slice(&out.stdout).map_err(|e| e.to_string())
}

/// Writes `text` as `name.stp` under the test's folder; returns its path.
pub fn write_file(test: &str, name: &str, text: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(test);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{name}.stp"));
    std::fs::write(&path, text).unwrap();
    path
}

/// A box of side 10 whose top is a B-spline in each form, one file each, with the volume
/// range OpenCASCADE should give (the bump is 3 % to 10 % of the box), as
/// [`agrees_with_opencascade`] takes them.
pub fn bspline_box_files(forms: &[Form]) -> Vec<(String, String, usize, [f64; 2])> {
    forms
        .iter()
        .map(|f| {
            let text = step_file(f.name, |w| {
                let shell = box_shell(w, [0.0; 3], 10.0, Some(f), true);
                w.add(format!("MANIFOLD_SOLID_BREP('box',#{shell})"))
            });
            (format!("box_{}", f.name), text, 0, [1015.0, 1200.0])
        })
        .collect()
}
