//! Cross-module tests of the quality measures: invariances (proptest) and the mesh reports.

use super::*;
use crate::core::{FaceId, RegionId};
use crate::mesh::{PlanarMesh, TetMesh, TriSurface};
use crate::quality::tetrahedron::{tet_dihedral_angles, tet_volume};
use glam::{DMat3, DVec2, DVec3};
use proptest::prelude::*;

fn rel(a: f64, b: f64) -> f64 {
    if a == b { 0.0 } else { (a - b).abs() / a.abs().max(b.abs()) }
}

/// A tet far enough from degenerate for the invariance tolerances.
fn decent_tet() -> impl Strategy<Value = [DVec3; 4]> {
    prop::array::uniform4(prop::array::uniform3(-1.0f64..1.0)).prop_map(|a| a.map(DVec3::from_array)).prop_filter(
        "not too flat",
        |p| {
            let m = tet_measures(p);
            m.volume_length > 0.05
        },
    )
}

fn rotation() -> impl Strategy<Value = DMat3> {
    (0.0f64..std::f64::consts::TAU, -1.0f64..1.0, 0.0f64..std::f64::consts::TAU).prop_map(|(a, z, b)| {
        let axis = DVec3::new((1.0 - z * z).sqrt() * a.cos(), (1.0 - z * z).sqrt() * a.sin(), z);
        DMat3::from_axis_angle(axis.normalize(), b)
    })
}

fn unsigned(m: &TetMeasures) -> [f64; 7] {
    [m.min_dihedral, m.max_dihedral, m.radius_edge, m.radius_ratio, m.volume_length, m.aspect_ratio, m.edge_ratio]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Two arc cosines give bitwise the extremes of the six angles, flat and inverted tets too.
    #[test]
    fn min_max_dihedral_is_the_extremes_of_the_six(p in prop::array::uniform4(prop::array::uniform3(-1.0f64..1.0)), flat in any::<bool>()) {
        let mut p = p.map(DVec3::from_array);
        if flat {
            p[3] = p[0] + (p[1] - p[0]) * 0.25 + (p[2] - p[0]) * 0.5;
        }
        let want = match tet_dihedral_angles(&p) {
            Some(a) => a.iter().fold((180.0f64, 0.0f64), |(lo, hi), &x| (lo.min(x), hi.max(x))),
            None => (0.0, 180.0),
        };
        let got = crate::quality::tetrahedron::tet_min_max_dihedral(&p);
        prop_assert_eq!((got.0.to_bits(), got.1.to_bits()), (want.0.to_bits(), want.1.to_bits()));
    }

    #[test]
    fn tet_measures_invariant_under_similarity(p in decent_tet(), r in rotation(), t in prop::array::uniform3(-100.0f64..100.0), s in 0.01f64..100.0) {
        let t = DVec3::from_array(t);
        let q = p.map(|x| r * x * s + t);
        let (a, b) = (tet_measures(&p), tet_measures(&q));
        for (x, y) in unsigned(&a).iter().zip(unsigned(&b)) {
            prop_assert!(rel(*x, y) < 1e-7, "{a:?} vs {b:?}");
        }
        prop_assert!(rel(a.scaled_jacobian, b.scaled_jacobian) < 1e-7);
        prop_assert!(rel(a.volume * s * s * s, b.volume) < 1e-7);
    }

    #[test]
    fn tet_unsigned_measures_invariant_under_permutation(p in decent_tet(), perm in Just([0usize, 1, 2, 3]).prop_shuffle()) {
        let q = [p[perm[0]], p[perm[1]], p[perm[2]], p[perm[3]]];
        let (a, b) = (tet_measures(&p), tet_measures(&q));
        for (x, y) in unsigned(&a).iter().zip(unsigned(&b)) {
            prop_assert!(rel(*x, y) < 1e-9, "{a:?} vs {b:?}");
        }
        prop_assert!(rel(a.volume.abs(), b.volume.abs()) < 1e-9);
        prop_assert!(rel(a.scaled_jacobian.abs(), b.scaled_jacobian.abs()) < 1e-9);
        let mut da = tet_dihedral_angles(&p).unwrap();
        let mut db = tet_dihedral_angles(&q).unwrap();
        da.sort_by(f64::total_cmp);
        db.sort_by(f64::total_cmp);
        for (x, y) in da.iter().zip(db) {
            prop_assert!((x - y).abs() < 1e-9);
        }
    }

    #[test]
    fn tet_measures_ranges(p in prop::array::uniform4(prop::array::uniform3(-1.0f64..1.0))) {
        let p = p.map(DVec3::from_array);
        let m = tet_measures(&p);
        prop_assert!(!unsigned(&m).iter().any(|x| x.is_nan()) && !m.scaled_jacobian.is_nan());
        prop_assert!((0.0..=180.0).contains(&m.min_dihedral) && m.min_dihedral <= m.max_dihedral && m.max_dihedral <= 180.0);
        prop_assert!((-1.0..=1.0).contains(&m.scaled_jacobian));
        prop_assert!(m.volume_length <= 1.0 + 1e-12);
        prop_assert!(m.radius_ratio >= 1.0 - 1e-9 && m.aspect_ratio >= 1.0 - 1e-9 && m.edge_ratio >= 1.0);
        prop_assert!(m.radius_edge >= 6f64.sqrt() / 4.0 - 1e-9);
        if let Some(a) = tet_dihedral_angles(&p) {
            // the six dihedral angles of a tet sum to between 2π and 3π
            let sum: f64 = a.iter().sum();
            prop_assert!((360.0 - 1e-6..=540.0 + 1e-6).contains(&sum), "{a:?}");
        }
    }

    #[test]
    fn tri_measures_invariant(p in prop::array::uniform3(prop::array::uniform3(-1.0f64..1.0)), r in rotation(), t in prop::array::uniform3(-10.0f64..10.0), s in 0.01f64..100.0, k in 0usize..3) {
        let p = p.map(DVec3::from_array);
        let a = tri_measures(&p);
        prop_assume!(a.min_angle > 1.0);
        let t = DVec3::from_array(t);
        let q = [p[k], p[(k + 1) % 3], p[(k + 2) % 3]].map(|x| r * x * s + t);
        let mirrored = [q[0], q[2], q[1]];
        for b in [tri_measures(&q), tri_measures(&mirrored)] {
            for (x, y) in [(a.min_angle, b.min_angle), (a.max_angle, b.max_angle), (a.aspect_ratio, b.aspect_ratio),
                (a.radius_ratio, b.radius_ratio), (a.scaled_jacobian, b.scaled_jacobian), (a.edge_ratio, b.edge_ratio), (a.area * s * s, b.area)] {
                prop_assert!(rel(x, y) < 1e-8, "{a:?} vs {b:?}");
            }
        }
        prop_assert!(a.aspect_ratio >= 1.0 - 1e-12 && a.radius_ratio >= 1.0 - 1e-12 && a.scaled_jacobian <= 1.0);
    }

    #[test]
    fn quad_measures_invariant(c in prop::array::uniform4(0.2f64..1.0), th in 0.0f64..std::f64::consts::TAU, s in 0.1f64..10.0, k in 0usize..4) {
        // a convex quad: points on rays at 0, 90, 180, 270 degrees
        let p = [DVec2::new(c[0], 0.0), DVec2::new(0.0, c[1]), DVec2::new(-c[2], 0.0), DVec2::new(0.0, -c[3])];
        let a = quad_measures(&p);
        let rot = DVec2::from_angle(th);
        let q: [DVec2; 4] = std::array::from_fn(|i| rot.rotate(p[(i + k) % 4]) * s);
        let b = quad_measures(&q);
        for (x, y) in [(a.min_angle, b.min_angle), (a.max_angle, b.max_angle), (a.aspect_ratio, b.aspect_ratio),
            (a.scaled_jacobian, b.scaled_jacobian), (a.edge_ratio, b.edge_ratio), (a.area * s * s, b.area)] {
            prop_assert!(rel(x, y) < 1e-9, "{a:?} vs {b:?}");
        }
        prop_assert!(a.area > 0.0 && a.scaled_jacobian > 0.0 && a.max_angle < 180.0 && a.aspect_ratio >= 1.0 - 1e-12);
    }
}

/// A structured cube mesh of `n³` cells, six tets each (Kuhn subdivision), jittered.
pub(crate) fn cube_mesh(n: usize, jitter: f64) -> TetMesh {
    let id = |i: usize, j: usize, k: usize| (i + (n + 1) * (j + (n + 1) * k)) as u32;
    let mut vertices = Vec::new();
    let mut seed = 0x9e3779b97f4a7c15u64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                let interior = |x: usize| x > 0 && x < n;
                let mut p = DVec3::new(i as f64, j as f64, k as f64);
                if interior(i) && interior(j) && interior(k) {
                    p += DVec3::new(rnd(), rnd(), rnd()) * jitter;
                }
                vertices.push(p / n as f64);
            }
        }
    }
    let mut tets = Vec::new();
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let c = |b: usize| id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
                // paths from corner 0 to corner 7 through the cube's edges
                for path in [[1, 3], [1, 5], [2, 3], [2, 6], [4, 5], [4, 6]] {
                    let mut t = [c(0), c(path[0]), c(path[1]), c(7)];
                    let [a, b, cc, d] = t.map(|v| vertices[v as usize]);
                    if tet_volume(&[a, b, cc, d]) < 0.0 {
                        t.swap(1, 2);
                    }
                    tets.push(t);
                }
            }
        }
    }
    let region_tags = vec![RegionId(1); tets.len()];
    TetMesh { vertices, tets, region_tags, ..Default::default() }
}

#[test]
fn tet_report_on_cube_mesh() {
    let m = cube_mesh(6, 0.0);
    assert_eq!(m.validate(), Ok(()));
    let r = tet_mesh_quality(&m);
    assert_eq!((r.tets, r.inverted, r.degenerate), (6 * 216, 0, 0));
    assert!(rel(r.volume, 1.0) < 1e-14);
    // Kuhn tets: dihedral angles 45°, 60° and 90°
    assert!(rel(r.min_dihedral_deg, 45.0) < 1e-12 && rel(r.max_dihedral_deg, 90.0) < 1e-12);
    assert!(rel(r.max_radius_edge, 3f64.sqrt() / 2.0) < 1e-12 && rel(r.mean_radius_edge, 3f64.sqrt() / 2.0) < 1e-12);
    assert_eq!(r.dihedral_histogram.total(), 6 * r.tets as u64);
    assert_eq!((r.tets_min_dihedral_below_20, r.tets_radius_edge_over_sqrt2), (0, 0));
    assert_eq!(r.min_dihedral.count, r.tets);
    let text = r.render();
    assert!(text.contains("min_dihedral_deg 45.0000") && text.contains("max_radius_edge_ratio 0.8660"), "{text}");
    let json = serde_json::to_value(&r).unwrap();
    assert_eq!(json["tets"], 1296);
    assert!(json["dihedral_histogram"]["counts"].is_array());
}

#[test]
fn tet_report_is_thread_count_independent() {
    let m = cube_mesh(20, 0.3);
    assert_eq!(m.validate(), Ok(()));
    let r1 = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap().install(|| tet_mesh_quality(&m));
    let r3 = rayon::ThreadPoolBuilder::new().num_threads(3).build().unwrap().install(|| tet_mesh_quality(&m));
    assert_eq!(r1, r3);
    assert_eq!(serde_json::to_string(&r1).unwrap(), serde_json::to_string(&r3).unwrap());
    // the headline values agree with a plain sequential pass
    let ms: Vec<TetMeasures> = m.tets.iter().map(|t| tet_measures(&t.map(|i| m.vertices[i as usize]))).collect();
    let min = ms.iter().map(|x| x.min_dihedral).fold(f64::INFINITY, f64::min);
    let arg = ms.iter().position(|x| x.min_dihedral == min);
    assert_eq!((r1.min_dihedral_deg, r1.min_dihedral.argmin), (min, arg));
    let sum: f64 = ms.iter().map(|x| x.radius_edge).sum();
    assert!(rel(r1.mean_radius_edge, sum / ms.len() as f64) < 1e-13);
    assert!(rel(r1.volume, 1.0) < 1e-12);
}

#[test]
fn tet_report_counts_inverted_and_degenerate() {
    let mut m = cube_mesh(2, 0.0);
    m.tets[3].swap(0, 1);
    m.tets[5] = [0, 1, 2, 3]; // four corners of a face: flat
    let r = tet_mesh_quality(&m);
    assert_eq!((r.inverted, r.degenerate), (2, 1));
    assert_eq!(r.min_dihedral_deg, 0.0);
    assert_eq!(r.max_radius_edge, f64::INFINITY);
    assert_eq!(r.min_dihedral.argmin, Some(5));
    assert_eq!(r.dihedral_histogram.total(), 6 * (r.tets as u64 - 1));
    let empty = tet_mesh_quality(&TetMesh::default());
    assert_eq!((empty.tets, empty.volume, empty.mean_radius_edge), (0, 0.0, 0.0));
    assert!(serde_json::to_string(&empty).is_ok());
}

#[test]
fn surface_report() {
    let h = 0.75f64.sqrt();
    let s = TriSurface::with_single_tag(
        vec![DVec3::ZERO, DVec3::X, DVec3::new(0.5, h, 0.0), DVec3::new(2.0, 0.0, 0.0), DVec3::new(3.0, 0.0, 0.0)],
        vec![[0, 1, 2], [1, 3, 2], [0, 3, 4]],
        FaceId(1),
    );
    let r = tri_surface_quality(&s);
    assert_eq!((r.triangles, r.degenerate, r.inverted), (3, 1, 0));
    assert_eq!(r.min_angle_deg, 0.0);
    assert_eq!(r.min_angle.argmin, Some(2));
    assert!(rel(r.max_angle.max, 180.0) < 1e-15);
    assert_eq!(r.min_angle.argmax, Some(0));
    assert!(rel(r.min_angle.max, 60.0) < 1e-12);
    assert_eq!(r.angle_histogram.total(), 6);
    assert!(rel(r.area, h) < 1e-15, "two triangles of area √3/4 plus a flat one");
    assert!(r.render().contains("triangles 3"));
}

#[test]
fn planar_report() {
    let m = PlanarMesh {
        vertices: vec![DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0), DVec2::new(2.0, 0.5)],
        triangles: vec![[1, 4, 2]],
        triangle_tags: vec![RegionId(1)],
        quads: vec![[0, 1, 2, 3]],
        quad_tags: vec![RegionId(1)],
        ..Default::default()
    };
    let r = planar_mesh_quality(&m);
    assert!(rel(r.area, m.area()) < 1e-15);
    assert_eq!((r.quads.quads, r.quads.non_convex, r.quads.min_angle_deg, r.quads.max_angle_deg), (1, 0, 90.0, 90.0));
    assert_eq!(r.quads.aspect_ratio.max, 1.0);
    assert_eq!((r.triangles.triangles, r.triangles.inverted, r.triangles.degenerate), (1, 0, 0));
    assert!(r.triangles.scaled_jacobian.min > 0.0);
    let mut bad = m.clone();
    bad.triangles[0] = [1, 2, 4];
    bad.quads[0] = [0, 1, 3, 2];
    let r = planar_mesh_quality(&bad);
    assert_eq!((r.triangles.inverted, r.quads.non_convex), (1, 1));
    assert!(r.triangles.scaled_jacobian.min < 0.0 && r.quads.scaled_jacobian.min < 0.0);
    assert!(r.render().contains("quads 1"));
    assert!(serde_json::to_string(&r).is_ok());
}

#[test]
fn cosine_bins_match_angle_bins() {
    use crate::quality::mesh_quality::{CosineBins, DIHEDRAL_EDGES};
    use crate::quality::tetrahedron::dihedral_from_cosine;
    let bins = CosineBins::new(&DIHEDRAL_EDGES);
    let mut by_cos = Histogram::with_edges(DIHEDRAL_EDGES.to_vec());
    let mut by_angle = by_cos.empty_like();
    let mut cs: Vec<f64> = (0..=20000).map(|i| -1.0 + i as f64 / 10000.0).collect();
    // the exact thresholds and their neighbours
    let key = |x: f64| {
        let b = x.to_bits() as i64;
        if b < 0 { i64::MIN - b } else { b }
    };
    let unkey = |k: i64| f64::from_bits((if k < 0 { i64::MIN - k } else { k }) as u64);
    for &e in &DIHEDRAL_EDGES {
        let c = key(-(e.to_radians().cos()));
        cs.extend((c - 4..=c + 4).map(|k| unkey(k).clamp(-1.0, 1.0)));
    }
    for &c in &cs {
        bins.add(&mut by_cos, c);
        by_angle.add(dihedral_from_cosine(c));
        let (mut a, mut b) = (by_cos.empty_like(), by_cos.empty_like());
        bins.add(&mut a, c);
        b.add(dihedral_from_cosine(c));
        assert_eq!(a, b, "cosine {c:e}, angle {}", dihedral_from_cosine(c));
    }
    assert_eq!(by_cos, by_angle);
}
