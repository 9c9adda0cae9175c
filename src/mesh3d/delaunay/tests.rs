use super::*;
use crate::core::spatial_order::XorShift;

fn random(n: usize, seed: u64) -> Vec<DVec3> {
    let mut r = XorShift::new(seed);
    let mut f = move || (r.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
    (0..n).map(|_| DVec3::new(f(), f(), f())).collect()
}

fn grid(n: usize, spacing: f64) -> Vec<DVec3> {
    let mut p = Vec::new();
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                p.push(DVec3::new(i as f64, j as f64, k as f64) * spacing);
            }
        }
    }
    p
}

fn volume(d: &Delaunay, p: &[DVec3]) -> f64 {
    d.to_tet_mesh(p).volume()
}

#[test]
fn random_points_validate() {
    for (n, seed) in [(5, 1), (50, 2), (2000, 3)] {
        let p = random(n, seed);
        let d = tetrahedralize(&p, &DelaunayOptions::default()).unwrap();
        assert_eq!(d.kernel, KernelKind::Float);
        d.validate(&p).unwrap_or_else(|e| panic!("n = {n}: {e}"));
        assert!(d.duplicates.is_empty());
    }
}

#[test]
fn grids_are_exact_and_tile_the_cube() {
    for (n, spacing, kernel) in [(4, 1.0, KernelKind::Integer), (5, 0.25, KernelKind::Integer), (4, 0.1, KernelKind::Float)] {
        let p = grid(n, spacing);
        let d = tetrahedralize(&p, &DelaunayOptions::default()).unwrap();
        assert_eq!(d.kernel, kernel, "spacing {spacing}");
        d.validate(&p).unwrap_or_else(|e| panic!("grid {n} spacing {spacing}: {e}"));
        let side = (n - 1) as f64 * spacing;
        if kernel == KernelKind::Integer {
            assert_eq!(volume(&d, &p), side * side * side);
            // every cube cell is split into 6 tets of volume 1/6 (Delaunay of a grid)
            assert_eq!(d.tets.len(), 6 * (n - 1).pow(3));
        } else {
            assert!((volume(&d, &p) - side.powi(3)).abs() < 1e-12);
        }
    }
}

#[test]
fn result_does_not_depend_on_the_insertion_order() {
    let p = grid(4, 1.0);
    let a = tetrahedralize(&p, &DelaunayOptions::default().with_seed(1)).unwrap();
    let b = tetrahedralize(&p, &DelaunayOptions::default().with_seed(99)).unwrap();
    assert_eq!((a.tets, a.duplicates), (b.tets, b.duplicates));
    let q = random(500, 7);
    let a = tetrahedralize(&q, &DelaunayOptions::default().with_seed(1)).unwrap();
    let b = tetrahedralize(&q, &DelaunayOptions::default().with_seed(2)).unwrap();
    assert_eq!((a.tets, a.duplicates), (b.tets, b.duplicates));
}

#[test]
fn duplicates_are_reported_with_the_smallest_index_kept() {
    let mut p = random(200, 11);
    p.push(p[17]);
    p.push(p[3]);
    p.insert(0, p[50]); // index 0 duplicates old 50 (now 51)
    let d = tetrahedralize(&p, &DelaunayOptions::default()).unwrap();
    d.validate(&p).unwrap();
    assert_eq!(d.duplicates, vec![[51, 0], [201, 18], [202, 4]]);
}

#[test]
fn degenerate_inputs_are_errors() {
    let e = |p: &[DVec3]| tetrahedralize(p, &DelaunayOptions::default()).unwrap_err();
    let plane: Vec<DVec3> = (0..20).map(|i| DVec3::new((i % 5) as f64, (i / 5) as f64, 0.0)).collect();
    assert!(matches!(e(&plane), DelaunayError::Degenerate { what: "coplanar", distinct: 20 }));
    let line: Vec<DVec3> = (0..6).map(|i| DVec3::splat(i as f64)).collect();
    assert!(matches!(e(&line), DelaunayError::Degenerate { what: "collinear", .. }));
    assert!(matches!(e(&[DVec3::ONE; 9]), DelaunayError::Degenerate { what: "coincident", distinct: 1 }));
    assert!(matches!(e(&[DVec3::ZERO, DVec3::X]), DelaunayError::Degenerate { what: "fewer than four", .. }));
    let mut p = random(10, 1);
    p[4].y = f64::NAN;
    assert!(matches!(e(&p), DelaunayError::NonFinite { point: 4, .. }));
}

#[test]
fn cospherical_points_have_no_flat_tets() {
    // points on a sphere of radius 5 with integer coordinates: massively cospherical
    let mut p = Vec::new();
    for x in -5i32..=5 {
        for y in -5i32..=5 {
            for z in -5i32..=5 {
                if x * x + y * y + z * z == 25 {
                    p.push(DVec3::new(x as f64, y as f64, z as f64));
                }
            }
        }
    }
    p.push(DVec3::ZERO);
    let d = tetrahedralize(&p, &DelaunayOptions::default()).unwrap();
    d.validate(&p).unwrap();
}
