//! Tests of the shape improvement.
use super::*;
use crate::cad::geom::{Frame, Plane};
use crate::core::size_field::UniformSize;

/// A unit square's boundary (8 fixed points) and a row of 9 interior points close
/// together across its middle, triangulated by Delaunay: needles between the row and the
/// boundary.
fn needles() -> (Vec<Point>, Vec<[u32; 3]>, Vec<[u32; 2]>) {
    let mut pts = Vec::new();
    let pt = |x: f64, y: f64, id: Option<u32>| Point { s: DVec2::new(x, y), uv: DVec2::new(x, y), p3: DVec3::new(x, y, 0.0), id };
    let ring = [(0.0, 0.0), (0.5, 0.0), (1.0, 0.0), (1.0, 0.5), (1.0, 1.0), (0.5, 1.0), (0.0, 1.0), (0.0, 0.5)];
    for (k, &(x, y)) in ring.iter().enumerate() {
        pts.push(pt(x, y, Some(k as u32)));
    }
    for k in 0..9 {
        pts.push(pt(0.46 + 0.01 * k as f64, 0.5 + 0.001 * (k % 2) as f64, None));
    }
    let mut tris = Vec::new();
    let inner: Vec<u32> = (8..17).collect();
    let boundary: Vec<[u32; 2]> = (0..8).map(|k| [k, (k + 1) % 8]).collect();
    // connect the boundary ring to the row by a constrained Delaunay triangulation
    let mut cdt: spade::ConstrainedDelaunayTriangulation<spade::Point2<f64>> = spade::ConstrainedDelaunayTriangulation::new();
    use spade::Triangulation;
    let hs: Vec<_> = pts.iter().map(|p| cdt.insert(spade::Point2::new(p.s.x, p.s.y)).unwrap()).collect();
    for &[a, b] in &boundary {
        cdt.add_constraint(hs[a as usize], hs[b as usize]);
    }
    for f in cdt.inner_faces() {
        tris.push(f.vertices().map(|v| v.fix().index() as u32));
    }
    assert!(inner.iter().all(|&i| hs[i as usize].index() == i as usize));
    (pts, tris, boundary)
}

#[test]
fn shape_of_an_equilateral_a_right_and_a_flat_triangle() {
    let eq = [DVec3::ZERO, DVec3::X, DVec3::new(0.5, 0.75f64.sqrt(), 0.0)];
    assert!((shape(eq) + 0.5).abs() < 1e-12);
    let right = [DVec3::ZERO, DVec3::X, DVec3::Y];
    assert!((shape(right) + std::f64::consts::FRAC_PI_4.cos()).abs() < 1e-12);
    assert!(shape(right) < shape(eq));
    assert_eq!(shape([DVec3::ZERO, DVec3::X, DVec3::X]), -1.0);
    assert!(shape([DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0)]) < -1.0 + 1e-12);
}

#[test]
fn needles_on_a_plane_become_well_shaped_and_the_boundary_stays() {
    let (mut pts, mut tris, boundary) = needles();
    let surf = Surface::Plane(Plane { frame: Frame { origin: DVec3::ZERO, x: DVec3::X, y: DVec3::Y, z: DVec3::Z } });
    let worst = |pts: &[Point], tris: &[[u32; 3]]| tris.iter().map(|t| shape(t.map(|i| pts[i as usize].p3))).fold(f64::INFINITY, f64::min);
    let before = worst(&pts, &tris);
    assert!(before < -(5f64.to_radians().cos()), "the fixture has needles: {before}");
    let area = |pts: &[Point], tris: &[[u32; 3]]| tris.iter().map(|t| {
        let p = t.map(|i| pts[i as usize].p3);
        0.5 * (p[1] - p[0]).cross(p[2] - p[0]).z
    }).sum::<f64>();
    let done = improve(&mut pts, &mut tris, &boundary, &surf, 1.0, 1.0, &UniformSize(0.5), 1e-9, 40f64.to_radians().cos());
    let after = worst(&pts, &tris);
    assert!(after >= -(30f64.to_radians().cos()), "smallest angle {}°", (-after).acos().to_degrees());
    assert!(done.removed.iter().filter(|r| **r).count() >= 6, "the row of close points merges");
    // the domain is still the unit square, every triangle counter-clockwise, every
    // boundary segment on exactly one triangle, the fixed points where they were
    assert!((area(&pts, &tris) - 1.0).abs() < 1e-12);
    for t in &tris {
        let s = t.map(|i| pts[i as usize].s);
        assert_eq!(orient2d(s[0], s[1], s[2]), Sign::Positive);
        assert!(t.iter().all(|&i| !done.removed[i as usize]));
    }
    for &[a, b] in &boundary {
        let n = tris.iter().filter(|t| t.contains(&a) && t.contains(&b)).count();
        assert_eq!(n, 1, "segment {a} {b}");
    }
    for k in 0..8 {
        assert_eq!(pts[k].id, Some(k as u32));
    }
}

#[test]
fn needles_over_a_short_boundary_segment_are_graded_toward_it() {
    // a square with two short segments in the middle of its bottom side (a short CAD edge
    // beside a wide face): Delaunay fans them to the far corners, needles of about 2°
    let ring = [(0.0, 0.0), (0.95, 0.0), (1.0, 0.0), (1.05, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)];
    let mut pts: Vec<Point> = ring.iter().enumerate().map(|(k, &(x, y))| Point { s: DVec2::new(x, y), uv: DVec2::new(x, y), p3: DVec3::new(x, y, 0.0), id: Some(k as u32) }).collect();
    let boundary: Vec<[u32; 2]> = (0..7).map(|k| [k, (k + 1) % 7]).collect();
    let mut cdt: spade::ConstrainedDelaunayTriangulation<spade::Point2<f64>> = spade::ConstrainedDelaunayTriangulation::new();
    use spade::Triangulation;
    let hs: Vec<_> = pts.iter().map(|p| cdt.insert(spade::Point2::new(p.s.x, p.s.y)).unwrap()).collect();
    for &[a, b] in &boundary {
        cdt.add_constraint(hs[a as usize], hs[b as usize]);
    }
    let mut tris: Vec<[u32; 3]> = cdt.inner_faces().map(|f| f.vertices().map(|v| v.fix().index() as u32)).collect();
    let worst = |pts: &[Point], tris: &[[u32; 3]]| tris.iter().map(|t| shape(t.map(|i| pts[i as usize].p3))).fold(f64::INFINITY, f64::min);
    let deg = |w: f64| (-w).acos().to_degrees();
    let before = worst(&pts, &tris);
    assert!(deg(before) < 3.0, "the fixture has needles: {}°", deg(before));
    let surf = Surface::Plane(Plane { frame: Frame { origin: DVec3::ZERO, x: DVec3::X, y: DVec3::Y, z: DVec3::Z } });
    let done = improve(&mut pts, &mut tris, &boundary, &surf, 1.0, 1.0, &UniformSize(1.0), 1e-9, 40f64.to_radians().cos());
    let after = worst(&pts, &tris);
    assert!(deg(after) >= 18.0, "smallest angle {}° (from {}°)", deg(after), deg(before));
    let area: f64 = tris.iter().map(|t| {
        let p = t.map(|i| pts[i as usize].p3);
        0.5 * (p[1] - p[0]).cross(p[2] - p[0]).z
    }).sum();
    assert!((area - 4.0).abs() < 1e-12, "area {area}");
    for t in &tris {
        let s = t.map(|i| pts[i as usize].s);
        assert_eq!(orient2d(s[0], s[1], s[2]), Sign::Positive);
        assert!(t.iter().all(|&i| !done.removed[i as usize]));
    }
    for &[a, b] in &boundary {
        assert_eq!(tris.iter().filter(|t| t.contains(&a) && t.contains(&b)).count(), 1, "segment {a} {b}");
    }
}
