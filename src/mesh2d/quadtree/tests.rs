//! Unit tests of the quadtree mesher: shapes, balance, conformity, the boundary kept,
//! angles, area, determinism, errors.

use super::*;
use glam::DVec2;

fn d(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

/// Meshes and asserts the acceptance: balanced tree, conforming mesh keeping the boundary,
/// template angles 45°..90°, area equal to the domain's.
fn accept(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &QuadtreeOptions) -> (QuadtreeMesh, Angles) {
    let tree = build_tree(domain, size, options.tree).unwrap();
    check_balance(&tree).unwrap();
    let m = mesh(domain, size, options).unwrap();
    assert_eq!(m.mesh.validate(), Ok(()));
    check_conforming(&m, domain).unwrap();
    assert!(m.stats.balanced);
    let a = angles(&m, domain);
    if m.inside_triangles > 0 {
        assert!(a.inside[0] >= 45.0 - 1e-9 && a.inside[1] <= 90.0 + 1e-9, "{a:?}");
    }
    let rel = (m.mesh.area() - domain.area()).abs() / domain.area();
    assert!(rel < 1e-12, "area {} vs {} ({rel:e})", m.mesh.area(), domain.area());
    (m, a)
}

fn square() -> Domain {
    Domain::from_loops(&[vec![d(0.0, 0.0), d(1.0, 0.0), d(1.0, 1.0), d(0.0, 1.0)]], None).unwrap()
}

#[test]
fn a_square() {
    let (m, a) = accept(&square(), &|_| 0.1, &QuadtreeOptions::default());
    assert!(m.inside_triangles > 50, "{}", m.inside_triangles);
    assert!(a.band[0] > 20.0, "{a:?}");
    // every boundary segment cut into pieces
    assert!(m.boundary.iter().all(|c| c.len() > 3));
}

#[test]
fn an_l_shape_graded() {
    let l = Domain::from_loops(&[vec![d(0.0, 0.0), d(2.0, 0.0), d(2.0, 1.0), d(1.0, 1.0), d(1.0, 2.0), d(0.0, 2.0)]], None).unwrap();
    let corner = d(1.0, 1.0);
    let (m, a) = accept(&l, &|p| 0.01 + 0.3 * (p - corner).length(), &QuadtreeOptions::default());
    assert!(m.stats.levels[1] >= m.stats.levels[0] + 3, "graded: {:?}", m.stats);
    assert!(a.band[0] > 15.0, "{a:?}");
}

#[test]
fn a_polygon_with_a_hole() {
    let outer = vec![d(0.0, 0.0), d(4.0, 0.0), d(4.0, 3.0), d(0.0, 3.0)];
    // a rotated square hole, given counter-clockwise: from_loops makes it clockwise
    let c = d(2.0, 1.5);
    let hole: Vec<DVec2> = (0..4).map(|k| c + 0.6 * DVec2::from_angle(0.3 + k as f64 * std::f64::consts::FRAC_PI_2)).collect();
    let dom = Domain::from_loops(&[outer, hole], None).unwrap();
    assert!((dom.area() - (12.0 - 0.72)).abs() < 1e-12);
    assert!(!dom.contains(c));
    let (m, _) = accept(&dom, &|_| 0.25, &QuadtreeOptions::default());
    // nothing inside the hole
    for t in &m.mesh.triangles {
        let g = t.iter().map(|&i| m.mesh.vertices[i as usize]).sum::<DVec2>() / 3.0;
        assert!(dom.contains(g));
    }
}

#[test]
fn a_tiny_edge_and_a_ten_degree_corner() {
    let t = 10f64.to_radians();
    let pts = vec![d(0.0, 0.0), d(3.0, 0.0), d(3.0, 1e-3), d(3.0, 3.0 * t.tan())];
    let dom = Domain::from_loops(&[pts], None).unwrap();
    assert!((dom.smallest_angle_deg() - 10.0).abs() < 1e-9 || dom.smallest_angle_deg() < 10.0);
    let (m, a) = accept(&dom, &|_| 0.3, &QuadtreeOptions::default());
    // the tiny edge forces quadrants about its length
    let finest = m.stats.levels[1];
    let side = 1.25 * 3.0;
    assert!(side / (1u64 << finest) as f64 <= 2e-3, "finest level {finest}");
    // only the input's own small angle is below the band's floor
    assert!(a.band[0] >= a.input_smallest.min(20.0) - 1e-9 || a.band[0] > 5.0, "{a:?}");
}

#[test]
fn quads_inside_where_no_hanging_node() {
    let o = QuadtreeOptions { quads: true, ..QuadtreeOptions::default() };
    let (m, _) = accept(&square(), &|_| 0.1, &o);
    assert!(!m.mesh.quads.is_empty());
}

#[test]
fn deterministic() {
    let dom = square();
    let h = |p: DVec2| 0.05 + 0.2 * p.x;
    let a = mesh(&dom, &h, &QuadtreeOptions::default()).unwrap();
    let b = mesh(&dom, &h, &QuadtreeOptions::default()).unwrap();
    assert_eq!(a.mesh, b.mesh);
    assert_eq!(a.boundary, b.boundary);
}

#[test]
fn bad_input_is_an_error() {
    // a bow tie
    let bow = Domain::from_loops(&[vec![d(0.0, 0.0), d(1.0, 1.0), d(1.0, 0.0), d(0.0, 1.0)]], None);
    assert!(matches!(bow, Err(DomainError::Crossing(..)) | Err(DomainError::NotPositive(_))), "{bow:?}");
    let nan = Domain::from_loops(&[vec![d(0.0, 0.0), d(f64::NAN, 0.0), d(0.0, 1.0)]], None);
    assert!(matches!(nan, Err(DomainError::NonFinite { .. })));
    let dup = Domain::from_loops(&[vec![d(0.0, 0.0), d(1.0, 0.0), d(1.0, 0.0), d(0.0, 1.0)]], None);
    assert!(matches!(dup, Err(DomainError::DuplicatePoint(..))));
    let mut sq = square();
    sq.tags.pop();
    assert!(matches!(sq.validate(), Err(DomainError::TagCount { tags: 3, segments: 4 })));
    let r = mesh(&square(), &|_| -1.0, &QuadtreeOptions::default());
    assert!(matches!(r, Err(QuadtreeError::Size { .. })));
    let r = mesh(&square(), &|_| 1e-6, &QuadtreeOptions { tree: Params { max_quadrants: 1000, ..Params::default() }, ..QuadtreeOptions::default() });
    assert!(matches!(r, Err(QuadtreeError::TooManyQuadrants(1000))));
}

#[test]
fn the_balance_check_finds_an_unbalanced_tree() {
    let dom = square();
    let mut tree = Quadtree::new(&dom, Params::default());
    // split towards the centre three times without balancing: the level-3 leaves there
    // touch level-1 leaves
    let mut i = 0;
    for k in [3, 0, 0] {
        tree.split(i, &dom).unwrap();
        i = tree.nodes[i as usize].children + k;
    }
    assert!(check_balance(&tree).is_err());
    balance_tree(&mut tree, &dom).unwrap();
    check_balance(&tree).unwrap();
}
