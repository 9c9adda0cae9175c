//! Parts of several solids (assemblies): one region per solid with its volume, face tags
//! kept, the contacts between solids reported with their areas, a conforming interface where
//! two solids' boundary triangles coincide, and solids that overlap refused with a message
//! naming both.

mod common;

use common::corpus_file;
use fepre::attributes::Density;
use fepre::cad::brep::Model;
use fepre::core::UniformSize;
use fepre::core::{FaceId, RegionId};
use fepre::io::{MeshData, ReadOptions, read};
use fepre::mesh::{TetMesh, TriSurface};
use fepre::mesh3d::mesher::{MeshOptions, MeshingError, SolidInfo, Solids, assembly_contacts, mesh_solids};
use fepre::pipeline::ContactReport;
use fepre::pipeline::{Plan, run_plan};
use fepre::pipeline::{Part, PipelineError};
use glam::DVec3;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::process::Command;

/// A box's corners: bit 0 of the index picks x, bit 1 y, bit 2 z. Its faces as quads turning
/// counter-clockwise seen from outside: -x, +x, -y, +y, -z, +z.
const QUADS: [[usize; 4]; 6] = [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]];

/// Appends the box `[lo, hi]` to `s` as 12 outward triangles with vertices of its own, its
/// faces tagged `first_tag`, `first_tag + 1`, ... in [`QUADS`] order; the quads of the faces in
/// `other_diagonal` are split along their other diagonal.
fn add_box(s: &mut TriSurface, lo: DVec3, hi: DVec3, first_tag: u32, other_diagonal: &[usize]) {
    let base = s.vertices.len() as u32;
    for i in 0..8 {
        s.vertices.push(DVec3::new(if i & 1 == 0 { lo.x } else { hi.x }, if i & 2 == 0 { lo.y } else { hi.y }, if i & 4 == 0 { lo.z } else { hi.z }));
    }
    for (k, q) in QUADS.iter().enumerate() {
        let [a, b, c, d] = q.map(|i| base + i as u32);
        let tris = if other_diagonal.contains(&k) { [[a, b, d], [b, c, d]] } else { [[a, b, c], [a, c, d]] };
        for t in tris {
            s.triangles.push(t);
            s.face_tags.push(FaceId(first_tag + k as u32));
        }
    }
}

fn two_boxes(b_lo: DVec3, b_hi: DVec3, other_diagonal: &[usize]) -> TriSurface {
    let mut s = TriSurface::default();
    add_box(&mut s, DVec3::ZERO, DVec3::ONE, 1, &[]);
    add_box(&mut s, b_lo, b_hi, 7, other_diagonal);
    s
}

/// The volume of each region's tets.
fn region_volumes(m: &TetMesh) -> BTreeMap<RegionId, f64> {
    let mut v = BTreeMap::new();
    for (t, r) in m.tets.iter().zip(&m.region_tags) {
        let [a, b, c, d] = t.map(|i| m.vertices[i as usize]);
        *v.entry(*r).or_insert(0.0) += (b - a).dot((c - a).cross(d - a)) / 6.0;
    }
    v
}

/// Tet faces shared by tets of two different regions.
fn interface_faces(m: &TetMesh) -> usize {
    let mut faces: Vec<([u32; 3], RegionId)> = Vec::new();
    for (t, r) in m.tets.iter().zip(&m.region_tags) {
        for skip in 0..4 {
            let mut f = [0u32; 3];
            let mut k = 0;
            for (i, v) in t.iter().enumerate() {
                if i != skip {
                    f[k] = *v;
                    k += 1;
                }
            }
            f.sort_unstable();
            faces.push((f, *r));
        }
    }
    faces.sort_unstable();
    faces.windows(2).filter(|w| w[0].0 == w[1].0 && w[0].1 != w[1].1).count()
}

/// Meshes `s` through the pipeline as a surface part.
fn mesh_part(s: TriSurface, opts: MeshOptions) -> Result<Part, PipelineError> {
    let mut part = Part::from_surface(Path::new("two_boxes.obj"), s);
    run_plan(&mut part, &Plan { unit: 1.0, mesh: opts, ..Plan::default() }, false)?;
    Ok(part)
}

fn only_contact(part: &Part) -> ContactReport {
    let contacts = part.contact_reports();
    assert_eq!(contacts.len(), 1, "{contacts:?}");
    contacts[0].clone()
}

#[test]
fn two_boxes_sharing_a_face_triangulated_alike_mesh_with_a_conforming_interface() {
    // B's -x face (tag 7) is A's +x face (tag 2), the same two triangles the other way round
    let part = mesh_part(two_boxes(DVec3::X, DVec3::new(2.0, 1.0, 1.0), &[]), MeshOptions::default().with_keep_surface(true)).unwrap();
    let m = part.mesh.as_ref().unwrap();
    assert_eq!(m.validate(), Ok(()));
    let vols = region_volumes(m);
    assert_eq!(vols.keys().copied().collect::<Vec<_>>(), [RegionId(1), RegionId(2)]);
    for v in vols.values() {
        assert!((v - 1.0).abs() < 1e-12, "{vols:?}");
    }
    let c = only_contact(&part);
    assert_eq!((c.a.solid, c.a.face, c.b.solid, c.b.face), (1, FaceId(2), 2, FaceId(7)));
    assert!((c.area - 1.0).abs() < 1e-12 && (c.shared_area - 1.0).abs() < 1e-12, "{c:?}");
    // the two triangles of the shared face are faces between a tet of each solid, and both
    // solids keep their boundary triangles there with their own tags
    assert_eq!(interface_faces(m), 2);
    let tags: BTreeSet<FaceId> = m.face_tags.iter().copied().collect();
    assert_eq!(tags, (1..=12).map(FaceId).collect());
    assert_eq!(part.mesh_report.as_ref().unwrap().regions, 2);
}

#[test]
fn two_boxes_sharing_a_face_triangulated_differently_touch_without_sharing_nodes() {
    let part = mesh_part(two_boxes(DVec3::X, DVec3::new(2.0, 1.0, 1.0), &[0]), MeshOptions::default().with_keep_surface(true)).unwrap();
    let m = part.mesh.as_ref().unwrap();
    assert_eq!(m.validate(), Ok(()));
    let c = only_contact(&part);
    assert_eq!((c.a.solid, c.a.face, c.b.solid, c.b.face), (1, FaceId(2), 2, FaceId(7)));
    assert!((c.area - 1.0).abs() < 1e-12 && c.shared_area == 0.0, "{c:?}");
    assert_eq!(interface_faces(m), 0);
    // the default options (the surface cut to the size first) mesh them too
    let part = mesh_part(two_boxes(DVec3::X, DVec3::new(2.0, 1.0, 1.0), &[0]), MeshOptions::default()).unwrap();
    let m = part.mesh.as_ref().unwrap();
    assert_eq!(m.validate(), Ok(()));
    assert!(region_volumes(m).values().all(|v| (v - 1.0).abs() < 1e-12));
    assert!((only_contact(&part).area - 1.0).abs() < 1e-12);
}

#[test]
fn a_smaller_box_on_a_face_is_imprinted_on_it_over_its_footprint() {
    let part = mesh_part(two_boxes(DVec3::new(1.0, 0.25, 0.25), DVec3::new(2.0, 0.75, 0.75), &[]), MeshOptions::default()).unwrap();
    let m = part.mesh.as_ref().unwrap();
    assert_eq!(m.validate(), Ok(()));
    let vols = region_volumes(m);
    assert!((vols[&RegionId(1)] - 1.0).abs() < 1e-12 && (vols[&RegionId(2)] - 0.25).abs() < 1e-12, "{vols:?}");
    let c = only_contact(&part);
    assert_eq!((c.a.face, c.b.face), (FaceId(2), FaceId(7)));
    // imprinted: the footprint is one set of triangles of both solids, each between a tet
    // of each solid
    assert!((c.area - 0.25).abs() < 1e-12 && (c.shared_area - 0.25).abs() < 1e-12, "{c:?}");
    assert!(interface_faces(m) >= 2);
    // the big box's face keeps its area: its part outside the footprint is meshed to the
    // footprint's border
    let a2: f64 = m.boundary.iter().zip(&m.face_tags).filter(|(_, f)| **f == FaceId(2)).map(|(t, _)| {
        let [a, b, c] = t.map(|v| m.vertices[v as usize]);
        0.5 * (b - a).cross(c - a).length()
    }).sum();
    assert!((a2 - 1.0).abs() < 1e-12, "face 2 has area {a2}");
    // with keep-surface nothing is imprinted: the triangles differ, the contact is tied
    let part = mesh_part(two_boxes(DVec3::new(1.0, 0.25, 0.25), DVec3::new(2.0, 0.75, 0.75), &[]), MeshOptions::default().with_keep_surface(true)).unwrap();
    assert_eq!(only_contact(&part).shared_area, 0.0);
}

/// The overlap error of meshing `s`, checked to name solids 1 and 2.
fn overlap(s: TriSurface) -> (String, f64) {
    let e = mesh_part(s, MeshOptions::default()).map(|_| ()).unwrap_err();
    let text = e.to_string();
    let PipelineError::Meshing { source: MeshingError::Overlap { a, b, depth, gap, .. }, .. } = e else { panic!("not an overlap: {text}") };
    assert_eq!((a.solid, b.solid), (RegionId(1), RegionId(2)), "{text}");
    assert!(depth > gap, "{text}");
    assert!(text.contains("two_boxes.obj") && text.contains("solid 1") && text.contains("solid 2") && text.contains("overlap"), "{text}");
    (text, depth)
}

#[test]
fn overlapping_boxes_are_refused_naming_both_solids() {
    // B reaches half-way into A
    overlap(two_boxes(DVec3::new(0.5, 0.25, 0.25), DVec3::new(1.5, 0.75, 0.75), &[]));
    // B 0.001 into A over a face wider than A's: only a tessellation's chord could excuse that
    let (_, depth) = overlap(two_boxes(DVec3::new(0.999, -0.5, -0.5), DVec3::new(2.0, 1.5, 1.5), &[]));
    assert!(depth < 0.01, "{depth}");
    // B where A is: the same faces, both solids on the same side of them
    overlap(two_boxes(DVec3::ZERO, DVec3::ONE, &[]));
    // two bars crossing like a plus sign: no vertex of either inside the other
    let mut s = TriSurface::default();
    add_box(&mut s, DVec3::new(-2.0, -0.5, -0.5), DVec3::new(2.0, 0.5, 0.5), 1, &[]);
    add_box(&mut s, DVec3::new(-0.5, -2.0, -0.5), DVec3::new(0.5, 2.0, 0.5), 7, &[]);
    let (text, _) = overlap(s);
    assert!(text.contains("face"), "{text}");
}

#[test]
fn a_solid_inside_another_is_an_overlap_when_the_caller_says_they_are_two() {
    // a surface mesh reads a shell inside a shell as a void; a caller that knows them to be two
    // solids (a B-rep) is told they overlap
    let mut s = TriSurface::default();
    add_box(&mut s, DVec3::ZERO, DVec3::splat(3.0), 1, &[]);
    add_box(&mut s, DVec3::ONE, DVec3::splat(2.0), 7, &[]);
    let solids = Solids {
        of_triangle: (0..24).map(|t| u32::from(t >= 12)).collect(),
        solids: vec![SolidInfo { tag: RegionId(1), name: Some("outer".into()) }, SolidInfo { tag: RegionId(2), name: Some("inner".into()) }],
    };
    let e = assembly_contacts(&s, &solids, 1e-6).unwrap_err();
    assert!(matches!(&e, MeshingError::Overlap { a, b, .. } if a.solid == RegionId(1) && b.solid == RegionId(2)), "{e}");
    let text = e.to_string();
    assert!(text.contains("\"outer\"") && text.contains("\"inner\""), "{text}");
    // as a surface part it is a box with a cubic void
    let part = mesh_part(s, MeshOptions::default()).unwrap();
    let vols = region_volumes(part.mesh.as_ref().unwrap());
    assert_eq!(vols.len(), 1);
    assert!((vols[&RegionId(1)] - 26.0).abs() < 1e-9, "{vols:?}");
}

#[test]
fn a_solid_crossing_itself_is_named_and_its_triangles_numbered_as_in_the_surface() {
    let mut s = TriSurface::default();
    add_box(&mut s, DVec3::ZERO, DVec3::ONE, 1, &[]);
    add_box(&mut s, DVec3::new(3.0, 0.0, 0.0), DVec3::new(4.0, 1.0, 1.0), 7, &[]);
    add_box(&mut s, DVec3::new(3.5, 0.25, 0.25), DVec3::new(4.5, 0.75, 0.75), 13, &[]);
    let solids = Solids {
        of_triangle: (0..36).map(|t| u32::from(t >= 12)).collect(),
        solids: vec![SolidInfo { tag: RegionId(1), name: None }, SolidInfo { tag: RegionId(2), name: Some("two boxes".into()) }],
    };
    let e = mesh_solids(&s, &solids, 1e-6, &UniformSize(f64::INFINITY), &MeshOptions::default()).unwrap_err();
    let MeshingError::InSolid { solid, source, .. } = &e else { panic!("{e}") };
    assert_eq!(*solid, RegionId(2));
    let MeshingError::SelfIntersecting { a, b, .. } = **source else { panic!("{e}") };
    assert!((12..36).contains(&a) && (12..36).contains(&b), "{e}");
    assert!(e.to_string().starts_with("solid 2 (\"two boxes\"): triangles"), "{e}");
}

/// A box built with truck, its faces named `{name}_0`, `{name}_1`, ...
fn step_box(lo: [f64; 3], size: [f64; 3], name: &str) -> Model {
    use truck_modeling::{Point3, Vector3, builder};
    let v = builder::vertex(Point3::new(lo[0], lo[1], lo[2]));
    let e = builder::tsweep(&v, Vector3::new(size[0], 0.0, 0.0));
    let f = builder::tsweep(&e, Vector3::new(0.0, size[1], 0.0));
    let s = builder::tsweep(&f, Vector3::new(0.0, 0.0, size[2]));
    let mut m = fepre::cad::parts::solid_to_model(&s, name).unwrap();
    for (k, f) in m.faces.iter_mut().enumerate() {
        f.name = Some(format!("{name}_{k}"));
    }
    m
}

/// Two named boxes written as one STEP file: `b` at `b_lo`, both 10 mm cubes.
fn write_boxes(dir: &Path, b_lo: [f64; 3]) -> std::path::PathBuf {
    let mut m = step_box([0.0; 3], [10.0; 3], "box_a");
    m.append(&step_box(b_lo, [10.0; 3], "box_b"));
    let path = dir.join("two_boxes.step");
    fepre::cad::step::write(&path, &m, "two_boxes").unwrap();
    path
}

fn fepre() -> Command {
    Command::new(env!("CARGO_BIN_EXE_fepre"))
}

#[test]
fn a_step_file_of_two_touching_boxes_meshes_two_named_regions_and_reports_their_contact() {
    let dir = tempfile::tempdir().unwrap();
    let step = write_boxes(dir.path(), [10.0, 0.0, 0.0]);
    let out = dir.path().join("two_boxes.msh");
    let o = fepre().arg("mesh").arg(&step).arg("-o").arg(&out).arg("--json").output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["regions"], 2, "{v}");
    let contacts = v["contacts"].as_array().unwrap();
    assert_eq!(contacts.len(), 1, "{contacts:?}");
    let c = &contacts[0];
    assert_eq!((c["a"]["solid"].as_u64(), c["a"]["solid_name"].as_str(), c["b"]["solid"].as_u64(), c["b"]["solid_name"].as_str()), (Some(1), Some("box_a"), Some(2), Some("box_b")), "{c}");
    assert!(c["a"]["face_name"].as_str().unwrap().starts_with("box_a_") && c["b"]["face_name"].as_str().unwrap().starts_with("box_b_"), "{c}");
    assert!(c["a"]["step_id"].as_u64().is_some() && c["b"]["step_id"].as_u64().is_some(), "{c}");
    assert!((c["area"].as_f64().unwrap() - 100.0).abs() < 1e-9, "{c}");
    // the written mesh: valid, a region per box of the box's volume, named after it
    let MeshData::Volume(m) = read(&out, &ReadOptions::default()).unwrap().mesh else { panic!("no tets in {}", out.display()) };
    assert_eq!(m.validate(), Ok(()));
    let vols = region_volumes(&m);
    assert_eq!(vols.len(), 2);
    for v in vols.values() {
        assert!((v - 1000.0).abs() < 1e-9, "{vols:?}");
    }
    let names: BTreeSet<&str> = m.region_names.names().collect();
    assert_eq!(names, BTreeSet::from(["box_a", "box_b"]));
    // the text report lists the contact
    let o = fepre().arg("mesh").arg(&step).arg("-o").arg(&out).output().unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("contacts         1 pairs") && text.contains("solid 1 \"box_a\" face") && text.contains("solid 2 \"box_b\""), "{text}");
    // a job's report lists it too
    let job = dir.path().join("job.toml");
    std::fs::write(&job, "[input]\nfile = \"two_boxes.step\"\n[[output]]\nfile = \"two_boxes.vtu\"\n").unwrap();
    let o = fepre().arg("run").arg(&job).arg("--json").output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["contacts"].as_array().map(Vec::len), Some(1), "{v}");
    assert_eq!(v["mesh"]["regions"], 2);
}

#[test]
fn a_step_file_of_two_overlapping_boxes_is_refused_naming_both_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let step = write_boxes(dir.path(), [5.0, 2.0, 2.0]);
    let out = dir.path().join("two_boxes.mesh");
    let o = fepre().arg("mesh").arg(&step).arg("-o").arg(&out).output().unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    for want in ["two_boxes.step", "solid 1 (\"box_a\")", "solid 2 (\"box_b\")", "overlap", "STEP faces #"] {
        assert!(err.contains(want), "no {want:?} in {err}");
    }
    assert!(!out.exists());
}

/// The corpus part `name` tessellated as `fepre mesh` does, with its solids and gap.
fn corpus_part(name: &str) -> Option<(Part, Solids, f64)> {
    let path = corpus_file(name)?;
    let mut part = Part::open(&path).unwrap();
    let plan = Plan { unit: 1.0, ..Plan::default() };
    let field = part.density_field(&Density::default(), &BTreeMap::new(), 1.0).unwrap();
    let tess = plan.tessellate_options(&part);
    part.tessellate(&field, &tess).unwrap();
    let s = part.surface.clone().unwrap();
    let solids = part.surface_solids(&s);
    let gap = part.gap();
    Some((part, solids, gap))
}

/// The area of the triangles of `face` in the surface.
fn face_area(s: &TriSurface, face: FaceId) -> f64 {
    s.triangles
        .iter()
        .zip(&s.face_tags)
        .filter(|(_, f)| **f == face)
        .map(|(t, _)| {
            let [a, b, c] = t.map(|v| s.vertices[v as usize]);
            0.5 * (b - a).cross(c - a).length()
        })
        .sum()
}

/// The solid pairs in contact, and for the contacts of whole planar faces, each contact's
/// area over the smaller face's.
fn corpus_contacts(name: &str, solids: usize) -> Option<(BTreeSet<(u32, u32)>, Vec<fepre::mesh3d::mesher::Contact>, TriSurface)> {
    let (part, spec, gap) = corpus_part(name)?;
    assert_eq!(spec.solids.len(), solids, "{name}");
    let s = part.surface.clone().unwrap();
    let contacts = assembly_contacts(&s, &spec, gap).unwrap_or_else(|e| panic!("{name}: {e}"));
    let pairs = contacts.iter().map(|c| (c.solid_a.0, c.solid_b.0)).collect();
    Some((pairs, contacts, s))
}

#[test]
fn the_corpus_assemblies_touch_where_their_solids_touch() {
    // abc-0000: three blobs apart, a glass standing on a base and closed by a cap; each
    // contact is a whole face of the glass (its bottom, its rim) on the base and the cap
    if let Some((pairs, contacts, s)) = corpus_contacts("abc-0000.step", 6) {
        assert_eq!(pairs, BTreeSet::from([(4, 5), (4, 6)]), "{contacts:?}");
        for c in &contacts {
            let smaller = face_area(&s, c.face_a).min(face_area(&s, c.face_b));
            assert!((c.area / smaller - 1.0).abs() < 0.01, "{c:?}: face area {smaller}");
        }
    }
    // wing_fuselage: two halves cut by the plane y = 0, touching over the cut face
    if let Some((pairs, contacts, s)) = corpus_contacts("wing_fuselage.step", 2) {
        assert_eq!(pairs, BTreeSet::from([(1, 2)]));
        let largest = contacts.iter().max_by(|x, y| x.area.total_cmp(&y.area)).unwrap();
        let smaller = face_area(&s, largest.face_a).min(face_area(&s, largest.face_b));
        assert!((largest.area / smaller - 1.0).abs() < 0.01, "{largest:?}: face area {smaller}");
    }
    // as1: plate, brackets, bolts, nuts and rod: every part touches another, bolts their
    // holes (curved contacts through chords that cross) and nuts, brackets the plate
    if let Some((pairs, contacts, _)) = corpus_contacts("as1-tu-203.stp", 18) {
        let touching: BTreeSet<u32> = pairs.iter().flat_map(|&(a, b)| [a, b]).collect();
        assert_eq!(touching, (1..=18).collect(), "{contacts:?}");
        assert!(contacts.iter().all(|c| c.area > 0.0 && c.shared_area == 0.0));
    }
}

/// `fepre mesh` on a corpus assembly: one region per solid with the volume its tessellation
/// encloses (up to what merging nearly flat facets may move, which the report bounds), a
/// valid mesh, the contacts of its solids reported.
fn corpus_assembly_meshes(name: &str, solids: usize, min_shared: f64) {
    let Some((part, spec, _)) = corpus_part(name) else { return };
    let s = part.surface.clone().unwrap();
    let mut expected: BTreeMap<RegionId, f64> = BTreeMap::new();
    for (t, &k) in s.triangles.iter().zip(&spec.of_triangle) {
        let [a, b, c] = t.map(|v| s.vertices[v as usize]);
        *expected.entry(spec.solids[k as usize].tag).or_insert(0.0) += a.dot(b.cross(c)) / 6.0;
    }
    assert_eq!(expected.len(), solids);
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.mesh");
    let o = fepre().arg("mesh").arg(corpus_file(name).unwrap()).arg("-o").arg(&out).arg("--json").output().unwrap();
    assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["regions"].as_u64(), Some(solids as u64), "{name}");
    assert!(!v["contacts"].as_array().unwrap().is_empty(), "{name}");
    let MeshData::Volume(m) = read(&out, &ReadOptions::default()).unwrap().mesh else { panic!("{name}: no tets") };
    assert_eq!(m.validate(), Ok(()), "{name}");
    let got = region_volumes(&m);
    assert_eq!(got.keys().collect::<Vec<_>>(), expected.keys().collect::<Vec<_>>(), "{name}");
    // exact but for merged facets that are flat only within 0.1° and for points imprinting
    // slid within the gap (the report bounds both changes)
    let moved = v["flattening_volume"].as_f64().unwrap() + v["imprint_volume"].as_f64().unwrap();
    for (r, want) in &expected {
        assert!((got[r] - want).abs() <= 1e-9 * want.abs() + moved, "{name}: region {} has volume {}, its solid {want} (flat facets may move it by {moved})", r.0, got[r]);
    }
    // imprinted: at least `min_shared` of the contacts' area shares nodes, and every boundary
    // triangle two solids share is a face between a tet of each
    let contacts = v["contacts"].as_array().unwrap();
    let area: f64 = contacts.iter().map(|c| c["area"].as_f64().unwrap()).sum();
    let shared: f64 = contacts.iter().map(|c| c["shared_area"].as_f64().unwrap()).sum();
    assert!(shared >= min_shared * area, "{name}: {shared} of the contacts' {area} shared");
    let mut sorted: Vec<[u32; 3]> = m.boundary.iter().map(|t| {
        let mut t = *t;
        t.sort_unstable();
        t
    }).collect();
    sorted.sort_unstable();
    let twice = sorted.windows(2).filter(|w| w[0] == w[1]).count();
    assert_eq!(interface_faces(&m), twice, "{name}: every shared boundary triangle lies between two solids' tets");
    assert_eq!(twice > 0, min_shared > 0.0, "{name}");
    println!("{name}: {} tets, {} regions, {} contacts, {:.1} % of their area shared ({twice} interface triangles)", m.tets.len(), got.len(), contacts.len(), 100.0 * shared / area.max(f64::MIN_POSITIVE));
}

#[test]
#[ignore = "about 30 s; CI runs it (--include-ignored)"]
fn corpus_as1_meshes_one_region_per_solid() {
    corpus_assembly_meshes("as1-tu-203.stp", 18, 0.55);
}

#[test]
#[ignore = "about 2 minutes; CI runs it (--include-ignored)"]
fn corpus_abc_0000_meshes_one_region_per_solid() {
    corpus_assembly_meshes("abc-0000.step", 6, 0.999);
}


#[test]
#[ignore = "about 2 minutes; CI runs it (--include-ignored)"]
fn corpus_wing_fuselage_meshes_one_region_per_solid() {
    corpus_assembly_meshes("wing_fuselage.step", 2, 0.999);
}

/// Two unit cubes in one closed shell, the second at `(1, 1, 0)`: they touch along the line
/// `x = y = 1` only, and the shell has two edges there with the same two vertices (a solid
/// that touches itself along an edge, as some CAD parts are written).
fn cubes_touching_along_an_edge() -> Model {
    let mut m = step_box([0.0; 3], [1.0; 3], "a");
    let (nv, ne) = (m.vertices.len() as u32, m.edges.len());
    m.append(&step_box([1.0, 1.0, 0.0], [1.0; 3], "b"));
    // the second cube's vertices on the line are the first cube's
    let same = |m: &Model, v: u32| (0..nv).find(|&w| m.vertices[w as usize].point.distance(m.vertices[v as usize].point) < 1e-12);
    for e in ne..m.edges.len() {
        for end in [m.edges[e].start, m.edges[e].end] {
            if let Some(w) = same(&m, end) {
                if m.edges[e].start == end {
                    m.edges[e].start = w;
                }
                if m.edges[e].end == end {
                    m.edges[e].end = w;
                }
            }
        }
    }
    // one shell, one solid
    let second = m.shells[1].faces.clone();
    m.shells[0].faces.extend(second);
    for f in &mut m.faces {
        f.shell = 0;
    }
    m.shells.truncate(1);
    m.solids.truncate(1);
    m
}

#[test]
fn a_solid_that_touches_itself_along_an_edge_is_refused_naming_both_edges() {
    use fepre::tessellate::certificate::{CertifyOptions, certify};
    use fepre::tessellate::{TessellateOptions, tessellate};
    let m = cubes_touching_along_an_edge();
    let t = tessellate(&m, &TessellateOptions::default());
    let cert = certify(&m, &t, &CertifyOptions::default());
    assert!(!cert.passed);
    let named = cert.failures.iter().find(|f| f.check == "manifold" && f.message.contains("run along the same line")).unwrap_or_else(|| panic!("{:?}", cert.failures));
    assert!(named.message.contains("touches itself") && !cert.manifold, "{}", named.message);
}
