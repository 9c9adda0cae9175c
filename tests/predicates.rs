//! Exact predicates: sign conventions under argument permutations, degenerate inputs (grids,
//! collinear, coplanar, cospherical points) at scales from 1e-8 to 1e8, the symbolic
//! perturbation's consistency (the perturbed Delaunay tets of grid points tile their hull),
//! and a case where plain floating point gives the wrong sign.

use fepre::core::predicates::*;
use glam::{DVec2, DVec3};
use proptest::prelude::*;

/// Powers of two keep exact degeneracies exact; 2^-27 ≈ 7e-9, 2^27 ≈ 1.3e8.
fn scale() -> impl Strategy<Value = f64> {
    (-27i32..=27).prop_map(|k| 2f64.powi(k))
}

/// Integer grid points (many exact degeneracies), scaled.
fn grid3(n: usize) -> impl Strategy<Value = (Vec<DVec3>, f64)> {
    (prop::collection::vec((-3i32..=3, -3i32..=3, -3i32..=3), n), scale())
        .prop_map(|(v, s)| (v.into_iter().map(|(x, y, z)| DVec3::new(x as f64, y as f64, z as f64) * s).collect(), s))
}

fn grid2(n: usize) -> impl Strategy<Value = Vec<DVec2>> {
    (prop::collection::vec((-3i32..=3, -3i32..=3), n), scale())
        .prop_map(|(v, s)| v.into_iter().map(|(x, y)| DVec2::new(x as f64, y as f64) * s).collect())
}

/// Points on the sphere of radius 3 with integer coordinates (all cospherical), scaled and
/// shifted by an integer grid offset (exact).
fn cospherical(n: usize) -> impl Strategy<Value = Vec<DVec3>> {
    let base: Vec<[i32; 3]> = {
        let mut b = Vec::new();
        for x in -3i32..=3 {
            for y in -3i32..=3 {
                for z in -3i32..=3 {
                    if x * x + y * y + z * z == 9 {
                        b.push([x, y, z]);
                    }
                }
            }
        }
        b
    };
    (prop::collection::vec(0..base.len(), n), scale(), (-5i32..5, -5i32..5, -5i32..5)).prop_map(move |(idx, s, o)| {
        idx.into_iter()
            .map(|i| (DVec3::new(base[i][0] as f64, base[i][1] as f64, base[i][2] as f64) + DVec3::new(o.0 as f64, o.1 as f64, o.2 as f64)) * s)
            .collect()
    })
}

/// Points on a line or in a plane through integer combinations (exactly collinear/coplanar).
fn coplanar(n: usize) -> impl Strategy<Value = Vec<DVec3>> {
    (prop::collection::vec((-4i32..=4, -4i32..=4), n), scale(), prop::bool::ANY).prop_map(|(uv, s, line)| {
        let (o, u, w) = (DVec3::new(1.0, -2.0, 3.0), DVec3::new(1.0, 2.0, -1.0), DVec3::new(-2.0, 1.0, 1.0));
        uv.into_iter().map(|(a, b)| (o + u * a as f64 + if line { DVec3::ZERO } else { w * b as f64 }) * s).collect()
    })
}

fn perm_sign(p: &[usize]) -> i32 {
    let mut s = 1;
    for i in 0..p.len() {
        for j in i + 1..p.len() {
            if p[i] > p[j] {
                s = -s;
            }
        }
    }
    s
}

fn all_perms(n: usize) -> Vec<Vec<usize>> {
    if n == 1 {
        return vec![vec![0]];
    }
    let mut out = Vec::new();
    for p in all_perms(n - 1) {
        for k in 0..n {
            let mut q = p.clone();
            q.insert(k, n - 1);
            out.push(q);
        }
    }
    out
}

fn signed(s: Sign, parity: i32) -> Sign {
    if parity > 0 { s } else { s.reversed() }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn orient3d_alternates_under_permutations((p, _s) in grid3(4), ids in Just([0u32, 1, 2, 3])) {
        let base = orient3d(p[0], p[1], p[2], p[3]);
        let base_sos = orient3d_sos([p[0], p[1], p[2], p[3]], ids);
        prop_assert!(!base_sos.is_zero(), "distinct indices never give zero");
        if !base.is_zero() { prop_assert_eq!(base, base_sos); }
        for q in all_perms(4) {
            let s = perm_sign(&q);
            prop_assert_eq!(orient3d(p[q[0]], p[q[1]], p[q[2]], p[q[3]]), signed(base, s));
            let qs = orient3d_sos([p[q[0]], p[q[1]], p[q[2]], p[q[3]]], [ids[q[0]], ids[q[1]], ids[q[2]], ids[q[3]]]);
            prop_assert_eq!(qs, signed(base_sos, s));
            prop_assert!(!qs.is_zero());
        }
    }

    #[test]
    fn orient2d_alternates_under_permutations(p in grid2(3)) {
        let base = orient2d(p[0], p[1], p[2]);
        let base_sos = orient2d_sos([p[0], p[1], p[2]], [7, 3, 5]);
        prop_assert!(!base_sos.is_zero());
        if !base.is_zero() { prop_assert_eq!(base, base_sos); }
        let ids = [7u32, 3, 5];
        for q in all_perms(3) {
            let s = perm_sign(&q);
            prop_assert_eq!(orient2d(p[q[0]], p[q[1]], p[q[2]]), signed(base, s));
            prop_assert_eq!(orient2d_sos([p[q[0]], p[q[1]], p[q[2]]], [ids[q[0]], ids[q[1]], ids[q[2]]]), signed(base_sos, s));
        }
    }

    #[test]
    fn incircle_alternates_and_sos_is_decisive(p in grid2(4)) {
        let ids = [4u32, 9, 1, 6];
        let base = incircle(p[0], p[1], p[2], p[3]);
        let base_sos = incircle_sos([p[0], p[1], p[2], p[3]], ids);
        if !base.is_zero() { prop_assert_eq!(base, base_sos); }
        if !orient2d(p[0], p[1], p[2]).is_zero() { prop_assert!(!base_sos.is_zero()); }
        for q in all_perms(4) {
            let s = perm_sign(&q);
            prop_assert_eq!(incircle(p[q[0]], p[q[1]], p[q[2]], p[q[3]]), signed(base, s));
            let qs = incircle_sos([p[q[0]], p[q[1]], p[q[2]], p[q[3]]], q.iter().map(|&k| ids[k]).collect::<Vec<_>>().try_into().unwrap());
            prop_assert_eq!(qs, signed(base_sos, s));
        }
    }

    #[test]
    fn insphere_alternates_on_cospherical_points(p in cospherical(5)) {
        let ids = [11u32, 2, 7, 5, 3];
        let base = insphere(p[0], p[1], p[2], p[3], p[4]);
        let distinct = (0..5).all(|i| (0..i).all(|j| p[i] != p[j]));
        if distinct { prop_assert_eq!(base, Sign::Zero, "integer points on a sphere are exactly cospherical"); }
        let base_sos = insphere_sos([p[0], p[1], p[2], p[3], p[4]], ids);
        if !orient3d(p[0], p[1], p[2], p[3]).is_zero() { prop_assert!(!base_sos.is_zero()); }
        for q in all_perms(5) {
            let s = perm_sign(&q);
            let pts = [p[q[0]], p[q[1]], p[q[2]], p[q[3]], p[q[4]]];
            prop_assert_eq!(insphere(pts[0], pts[1], pts[2], pts[3], pts[4]), signed(base, s));
            let qs = insphere_sos(pts, [ids[q[0]], ids[q[1]], ids[q[2]], ids[q[3]], ids[q[4]]]);
            prop_assert_eq!(qs, signed(base_sos, s));
        }
    }

    #[test]
    fn coplanar_and_collinear_are_exactly_zero(p in coplanar(5)) {
        prop_assert_eq!(orient3d(p[0], p[1], p[2], p[3]), Sign::Zero);
        prop_assert_eq!(insphere(p[0], p[1], p[2], p[3], p[4]), Sign::Zero);
        let distinct = (0..4).all(|i| (0..i).all(|j| p[i] != p[j]));
        if distinct {
            prop_assert!(!orient3d_sos([p[0], p[1], p[2], p[3]], [0, 1, 2, 3]).is_zero());
        }
    }

    #[test]
    fn sos_agrees_with_exact_in_general_position(v in prop::collection::vec(-1e3f64..1e3, 15)) {
        let p: Vec<DVec3> = v.chunks(3).map(|c| DVec3::new(c[0], c[1], c[2])).collect();
        let o = orient3d(p[0], p[1], p[2], p[3]);
        prop_assert!(!o.is_zero());
        prop_assert_eq!(orient3d_sos([p[0], p[1], p[2], p[3]], [0, 1, 2, 3]), o);
        let i = insphere(p[0], p[1], p[2], p[3], p[4]);
        prop_assert_eq!(insphere_sos([p[0], p[1], p[2], p[3], p[4]], [0, 1, 2, 3, 4]), i);
    }
}

/// Twice the volume-signed determinant `det[b-a, c-a, d-a]` of integer points, exactly.
fn det_i(a: [i64; 3], b: [i64; 3], c: [i64; 3], d: [i64; 3]) -> i64 {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
    u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])
}

/// The tets that the perturbed in-sphere test calls Delaunay (non-flat, no other point
/// inside) must tile the convex hull: every face is shared by two of them from opposite sides
/// or is a hull face with no point beyond it, and their volumes sum to the hull's.
fn check_sos_delaunay_tiles(p: &[DVec3], ids: &[u32], hull_volume6: i64) {
    let n = p.len();
    let ip: Vec<[i64; 3]> = p.iter().map(|q| [q.x as i64, q.y as i64, q.z as i64]).collect();
    let mut tets = Vec::new();
    for a in 0..n {
        for b in a + 1..n {
            for c in b + 1..n {
                for d in c + 1..n {
                    let mut t = [a, b, c, d];
                    match orient3d(p[a], p[b], p[c], p[d]) {
                        Sign::Zero => continue,
                        Sign::Negative => t.swap(0, 1),
                        Sign::Positive => {}
                    }
                    let empty = (0..n).filter(|e| !t.contains(e)).all(|e| {
                        insphere_sos([p[t[0]], p[t[1]], p[t[2]], p[t[3]], p[e]], [ids[t[0]], ids[t[1]], ids[t[2]], ids[t[3]], ids[e]])
                            == Sign::Negative
                    });
                    if empty {
                        tets.push(t);
                    }
                }
            }
        }
    }
    let vol6: i64 = tets.iter().map(|t| det_i(ip[t[0]], ip[t[1]], ip[t[2]], ip[t[3]])).sum();
    assert_eq!(vol6, hull_volume6, "perturbed Delaunay tets do not tile the hull ({} tets)", tets.len());
    // faces: oriented outward from their tet (interior points give Negative, exterior Positive)
    let faces = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];
    let mut map: std::collections::HashMap<[usize; 3], Vec<[usize; 3]>> = Default::default();
    for t in &tets {
        for f in faces {
            let o = [t[f[0]], t[f[1]], t[f[2]]];
            let mut k = o;
            k.sort();
            map.entry(k).or_default().push(o);
        }
    }
    for (k, v) in map {
        assert!(v.len() <= 2, "face {k:?} in {} tets", v.len());
        if v.len() == 1 {
            let o = v[0];
            for e in (0..n).filter(|e| !o.contains(e)) {
                assert_ne!(orient3d(p[o[0]], p[o[1]], p[o[2]], p[e]), Sign::Positive, "point {e} beyond hull face {o:?}");
            }
        } else {
            let (mut a, mut b) = (v[0], v[1]);
            a.sort();
            b.sort();
            assert_eq!(a, b);
            // opposite orientation: the outward cycles differ by an odd permutation
            let pos = |o: [usize; 3], x| o.iter().position(|&y| y == x).unwrap();
            let s0 = perm_sign(&[pos(v[0], k[0]), pos(v[0], k[1]), pos(v[0], k[2])]);
            let s1 = perm_sign(&[pos(v[1], k[0]), pos(v[1], k[1]), pos(v[1], k[2])]);
            assert_ne!(s0, s1, "face {k:?} shared from the same side");
        }
    }
}

#[test]
fn perturbed_delaunay_of_a_grid_tiles_the_cube() {
    // 3×3×2 grid: every 8-point cell is cospherical, every face coplanar
    let mut p = Vec::new();
    for x in 0..3 {
        for y in 0..3 {
            for z in 0..2 {
                p.push(DVec3::new(x as f64, y as f64, z as f64));
            }
        }
    }
    let ids: Vec<u32> = (0..p.len() as u32).collect();
    check_sos_delaunay_tiles(&p, &ids, 6 * 2 * 2);
    // another global order of the perturbation: still a valid tiling
    let rev: Vec<u32> = ids.iter().rev().copied().collect();
    check_sos_delaunay_tiles(&p, &rev, 6 * 2 * 2);
}

#[test]
fn perturbed_delaunay_of_cospherical_points_tiles_the_octahedron() {
    // the 6 axis points of radius 3: all cospherical, and each coordinate plane holds 4
    let p = vec![
        DVec3::new(3.0, 0.0, 0.0),
        DVec3::new(-3.0, 0.0, 0.0),
        DVec3::new(0.0, 3.0, 0.0),
        DVec3::new(0.0, -3.0, 0.0),
        DVec3::new(0.0, 0.0, 3.0),
        DVec3::new(0.0, 0.0, -3.0),
    ];
    let ids: Vec<u32> = (0..p.len() as u32).collect();
    // octahedron |x|+|y|+|z| <= 3: volume 4/3 · 27 = 36, times 6 = 216
    check_sos_delaunay_tiles(&p, &ids, 216);
}

/// Exact orient2d for coordinates that are integers times 2^-53 (fits i128).
fn orient2d_exact_scaled(a: [i128; 2], b: [i128; 2], c: [i128; 2]) -> i32 {
    let d = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    d.signum() as i32
}

#[test]
fn floating_point_gets_the_sign_wrong_where_the_predicate_does_not() {
    // Kettner et al., "Classroom examples of robustness problems": points near the line
    // y = x through q = (12, 12), r = (24, 24), perturbed by multiples of 2^-53.
    let u = 2f64.powi(-53);
    let q = DVec2::new(12.0, 12.0);
    let r = DVec2::new(24.0, 24.0);
    let scale = 2f64.powi(53);
    let to_i = |v: DVec2| [(v.x * scale) as i128, (v.y * scale) as i128];
    let mut wrong = 0;
    let mut checked = 0;
    for i in 0..64 {
        for j in 0..64 {
            let p = DVec2::new(0.5 + i as f64 * u, 0.5 + j as f64 * u);
            let exact = orient2d_exact_scaled(to_i(p), to_i(q), to_i(r));
            let naive = (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
            let naive_sign = if naive > 0.0 { 1 } else if naive < 0.0 { -1 } else { 0 };
            assert_eq!(orient2d(p, q, r).as_i32(), exact, "exact predicate wrong at p = {p:?}");
            checked += 1;
            if naive_sign != exact {
                wrong += 1;
            }
        }
    }
    assert_eq!(checked, 4096);
    assert!(wrong > 100, "expected plain floating point to fail often here, failed {wrong} times");
}

#[test]
fn orient3d_where_floating_point_fails() {
    // Nearly coplanar points: d lies within one ulp of the plane through a, b, c.
    let a = DVec3::new(0.1, 0.1, 0.1);
    let b = DVec3::new(12.3, 0.7, 4.1);
    let c = DVec3::new(3.3, 9.1, 1.7);
    let mut disagreements = 0;
    for k in 0..2000 {
        let t = 0.37 + k as f64 * 1e-4;
        let s = 0.21 + k as f64 * 3e-5;
        let d = a + (b - a) * t + (c - a) * s; // on the plane up to rounding
        let naive = (b - a).dot((c - a).cross(d - a));
        let exact = orient3d(a, b, c, d);
        // the naive sign is not reproducible: the same configuration, permuted, must give the
        // opposite sign; count the cases where naive arithmetic breaks that law
        let naive_perm = (a - b).dot((c - b).cross(d - b));
        if (naive > 0.0) == (naive_perm > 0.0) && naive != 0.0 {
            disagreements += 1;
        }
        assert_eq!(orient3d(b, a, c, d), exact.reversed());
    }
    assert!(disagreements > 0, "naive orient3d was never inconsistent on near-coplanar points");
}

fn int_points(n: usize, range: i32) -> impl Strategy<Value = Vec<[i32; 3]>> {
    prop::collection::vec((-range..=range, -range..=range, -range..=range).prop_map(|(x, y, z)| [x, y, z]), n)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// The integer predicates decide exactly as the float ones on the same (exactly
    /// representable) coordinates: small ranges give many exact degeneracies, the limit range
    /// exercises the i128 bounds.
    #[test]
    fn integer_predicates_equal_float_predicates(
        small in int_points(5, 3),
        large in int_points(5, INT_COORD_LIMIT),
        ids in Just([9u32, 4, 7, 1, 5]),
    ) {
        for p in [&small, &large] {
            let f: Vec<DVec3> = p.iter().map(|q| DVec3::new(q[0] as f64, q[1] as f64, q[2] as f64)).collect();
            prop_assert_eq!(orient3d_int(p[0], p[1], p[2], p[3]), orient3d(f[0], f[1], f[2], f[3]));
            prop_assert_eq!(insphere_int(p[0], p[1], p[2], p[3], p[4]), insphere(f[0], f[1], f[2], f[3], f[4]));
            prop_assert_eq!(
                insphere_sos_int([p[0], p[1], p[2], p[3], p[4]], ids),
                insphere_sos([f[0], f[1], f[2], f[3], f[4]], ids)
            );
        }
    }
}

#[test]
fn integer_insphere_at_the_limits() {
    // extreme coordinates: the i128 evaluation must not overflow, and must agree with robust
    let l = INT_COORD_LIMIT;
    let corners = [[l, l, l], [-l, -l, l], [-l, l, -l], [l, -l, -l], [-l, -l, -l], [l, l, -l], [0, 0, 0], [l, -l, l]];
    let f = |q: [i32; 3]| DVec3::new(q[0] as f64, q[1] as f64, q[2] as f64);
    for a in 0..corners.len() {
        for e in 0..corners.len() {
            let (p, q, r, s, t) = (corners[a], corners[(a + 1) % 8], corners[(a + 2) % 8], corners[(a + 3) % 8], corners[e]);
            assert_eq!(insphere_int(p, q, r, s, t), insphere(f(p), f(q), f(r), f(s), f(t)));
            assert_eq!(orient3d_int(p, q, r, s), orient3d(f(p), f(q), f(r), f(s)));
        }
    }
}
