//! Density through the library: a size growing with the distance from a CAD face reaches the
//! tets, and curvature sizing puts the asked number of segments per radian on circular edges
//! while the surface stays within the asked chord.

use fepre::attributes::{DistanceSize, Fraction};
use fepre::attributes::{NonNegative, Positive};
use fepre::attributes::{Density, Selector};
use fepre::cad::geom::Curve;
use fepre::cad::parts::Bracket;
use fepre::mesh3d::mesher::MeshOptions;
use fepre::pipeline::Part;
use fepre::pipeline::Plan;
use glam::DVec3;
use std::collections::BTreeMap;
use std::path::Path;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

#[test]
fn distance_grading_reaches_the_tets() {
    // the bracket without holes; size 0.8 on its end_x face (x = 80), growing by 0.2 per mm
    // up to 3: h(d) = min(0.8 + 0.2 d, 3)
    let model = Bracket::default().with_holes_per_leg(0).build().unwrap();
    let mut part = Part::from_model(Path::new("bracket-0.step"), model);
    let selectors = BTreeMap::from([("end".to_string(), Selector::Name("end_x".into()))]);
    let mut density = Density::default();
    density.size = Positive::new(6.0);
    density.distance.push(DistanceSize { faces: "end".into(), size: Positive::new(0.8).unwrap(), growth: NonNegative::new(0.2), max: Positive::new(3.0) });
    let plan = Plan { selectors, density, unit: 1.0, mesh: MeshOptions::default(), ..Plan::default() };
    let report = fepre::pipeline::run_plan(&mut part, &plan, false).expect("meshes");
    let m = part.mesh.as_ref().unwrap();
    assert_eq!(m.validate(), Ok(()));
    println!("{} tets, min dihedral {:.2}", m.tets.len(), report.mesh.as_ref().unwrap().min_dihedral_deg);
    let h = |d: f64| (0.8 + 0.2 * d).min(3.0);
    // shells of tets of the x leg (y < 30) whose centroid is at distance d from x = 80
    for d in [1.0, 3.0, 6.0, 9.0, 14.0] {
        let w = 0.5 * h(d);
        let mut e = Vec::new();
        for t in &m.tets {
            let p = t.map(|v| m.vertices[v as usize]);
            let c = p.iter().copied().sum::<DVec3>() / 4.0;
            if c.y < 30.0 && ((80.0 - c.x) - d).abs() <= w {
                for i in 0..4 {
                    for j in i + 1..4 {
                        e.push(p[i].distance(p[j]));
                    }
                }
            }
        }
        let med = median(e);
        println!("d = {d}: median tet edge {med:.3}, asked {:.3}", h(d));
        assert!((med - h(d)).abs() <= 0.2 * h(d), "at distance {d}: median edge {med} for size {}", h(d));
    }
}

#[test]
fn curvature_sizing_puts_the_asked_segments_per_radian_on_circles() {
    // the bracket (cylindrical holes and fillet) and the elbow (tori), 3 segments per radian,
    // a global size of the part's diagonal (the flange is left out: the grading carries its
    // bolt holes' size onto the rim, as it should)
    for (name, model) in fepre::cad::parts::default_parts().unwrap() {
        if name == "flange" {
            continue;
        }
        let n = 3.0;
        let diagonal = model.size();
        let mut part = Part::from_model(Path::new(name), model);
        let mut density = Density::default();
        density.size = Positive::new(diagonal);
        density.curvature = Positive::new(n);
        density.deviation = Some(Fraction(1e-2));
        let plan = Plan { density, unit: 1.0, ..Plan::default() };
        let field = part.density_field(&plan.density, &plan.selectors, 1.0).unwrap();
        part.tessellate(&field, &plan.tessellate_options(&part)).expect("certified");
        let model = part.model.as_ref().unwrap();
        let t = &part.certified.as_ref().unwrap().tessellation;
        // the smallest radius of curvature of the faces around each edge: a circle is sized by
        // its own radius where no face beside it curves more tightly (the circles of a tube's
        // ends, not the bend's circles along a torus)
        let mut face_radius = vec![f64::INFINITY; model.edges.len()];
        for f in &part.catalogue().faces {
            for &l in &model.face(f.id).loops {
                for c in &model.loops[l as usize].coedges {
                    face_radius[c.edge as usize] = face_radius[c.edge as usize].min(f.min_radius);
                }
            }
        }
        let mut circles = 0;
        for ((e, pts), &rf) in model.edges.iter().zip(&t.edges).zip(&face_radius) {
            let Some(Curve::Circle(c)) = e.curve.map(|c| model.curve(c)) else { continue };
            if c.radius > 1.01 * rf {
                continue;
            }
            let angle = e.range.length();
            let per_radian = (pts.ids.len() - 1) as f64 / angle;
            assert!((per_radian - n).abs() <= 1.0, "{name}: a circle of {angle:.3} rad has {} segments ({per_radian:.2} per radian)", pts.ids.len() - 1);
            circles += 1;
        }
        assert!(circles >= 4, "{name}: {circles} circles");
        // the surface within the asked chord: each triangle's plane against the exact surface
        // at its parameter centroid
        let chord = t.chord;
        let s = &t.surface;
        let mut worst: f64 = 0.0;
        for (fi, dom) in t.domains.iter().enumerate() {
            let Some(dom) = dom else { continue };
            let surf = model.surface(model.faces[fi].surface);
            for (k, tri) in dom.triangles.clone().enumerate() {
                let p = s.triangles[tri].map(|v| s.vertices[v as usize]);
                let Some(nrm) = (p[1] - p[0]).cross(p[2] - p[0]).try_normalize() else { continue };
                let uv = (dom.uv[k][0] + dom.uv[k][1] + dom.uv[k][2]) / 3.0;
                worst = worst.max((surf.point(uv.x, uv.y) - p[0]).dot(nrm).abs());
            }
        }
        println!("{name}: {circles} circles, deviation {worst:.4} of chord {chord:.4}");
        assert!(worst <= chord, "{name}: the surface is {worst} from its triangles, chord {chord}");
    }
}

#[test]
fn poly_region_volumes_become_region_sizes() {
    // a unit cube whose one region asks for tets of volume 1e-3 at most (TetGen's `-a` per
    // region): the edge of the regular tet of that volume is its size
    let dir = tempfile::tempdir().unwrap();
    let poly = dir.path().join("cube.poly");
    let nodes = "8 3 0 0\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0 0 1\n6 1 0 1\n7 1 1 1\n8 0 1 1\n";
    let faces = [[1, 4, 3, 2], [5, 6, 7, 8], [1, 2, 6, 5], [2, 3, 7, 6], [3, 4, 8, 7], [4, 1, 5, 8]];
    let mut text = String::from(nodes);
    text.push_str("6 1\n");
    for (k, f) in faces.iter().enumerate() {
        text.push_str(&format!("1 0 {}\n4 {} {} {} {}\n", k + 1, f[0], f[1], f[2], f[3]));
    }
    text.push_str("0\n1\n1 0.5 0.5 0.5 7 0.001\n");
    std::fs::write(&poly, text).unwrap();
    let mut part = Part::open(&poly).unwrap();
    assert_eq!(part.region_sizes.len(), 1, "{:?}", part.seeds);
    let h = part.region_sizes[0].1;
    assert!((h - (6.0 * 2f64.sqrt() * 0.001).cbrt()).abs() < 1e-12);
    let plan = Plan { unit: 1.0, ..Plan::default() };
    fepre::pipeline::run_plan(&mut part, &plan, false).expect("meshes");
    let m = part.mesh.as_ref().unwrap();
    assert_eq!(m.validate(), Ok(()));
    assert!(m.region_tags.iter().all(|r| r.0 == 7), "the region keeps its attribute");
    let vols: Vec<f64> = (0..m.tets.len()).map(|t| m.tet_volume(t)).collect();
    let med = median(vols);
    println!("{} tets, median volume {med:.2e}", m.tets.len());
    assert!(m.tets.len() >= 600, "the region size refines the cube: {} tets", m.tets.len());
    assert!(med <= 0.001, "median tet volume {med}");
}
