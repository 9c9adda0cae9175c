//! Unit tests of the all-quad mesher: every test region of the issue, the contract checked
//! by [`accept`], the matching, determinism, errors.

use super::*;
use crate::mesh2d::boundary::split_boundary;
use glam::DVec2;
use std::f64::consts::TAU;

fn d(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

fn ngon(c: DVec2, r: f64, n: usize, phase: f64) -> Vec<DVec2> {
    (0..n).map(|k| c + r * DVec2::from_angle(phase + TAU * k as f64 / n as f64)).collect()
}

/// The test regions of HELPERS66.md: name, loops, size.
pub(super) fn regions() -> Vec<(&'static str, Vec<Vec<DVec2>>, Box<dyn Fn(DVec2) -> f64>)> {
    let star: Vec<DVec2> = (0..10).map(|k| DVec2::from_angle(TAU * k as f64 / 10.0) * if k % 2 == 0 { 1.0 } else { 0.45 }).collect();
    let comb = vec![d(0.0, 0.0), d(3.0, 0.0), d(3.0, 1.5), d(2.6, 1.5), d(2.6, 0.5), d(2.2, 0.5), d(2.2, 1.5), d(1.8, 1.5), d(1.8, 0.5), d(1.4, 0.5), d(1.4, 1.5), d(0.0, 1.5)];
    let c = d(1.5, 1.0);
    let l = 3.0;
    vec![
        ("12-gon", vec![ngon(DVec2::ZERO, 1.0, 12, 0.0)], Box::new(|_| 0.08)),
        ("rectangle", vec![vec![d(0.0, 0.0), d(2.0, 0.0), d(2.0, 1.0), d(0.0, 1.0)]], Box::new(|_| 0.1)),
        ("L", vec![vec![d(0.0, 0.0), d(2.0, 0.0), d(2.0, 1.0), d(1.0, 1.0), d(1.0, 2.0), d(0.0, 2.0)]], Box::new(|_| 0.1)),
        ("star", vec![star], Box::new(|_| 0.06)),
        ("comb", vec![comb], Box::new(|_| 0.07)),
        ("two-holes", vec![vec![d(0.0, 0.0), d(4.0, 0.0), d(4.0, 2.0), d(0.0, 2.0)], ngon(d(1.0, 1.0), 0.5, 24, 0.0), vec![d(2.6, 0.6), d(3.4, 0.6), d(3.4, 1.4), d(2.6, 1.4)]], Box::new(|_| 0.12)),
        ("strip", vec![vec![d(0.0, 0.0), d(5.0, 0.0), d(5.0, 0.2), d(0.0, 0.2)]], Box::new(|_| 0.1)),
        ("graded", vec![vec![d(0.0, 0.0), d(3.0, 0.0), d(3.0, 2.0), d(0.0, 2.0)]], Box::new(move |p: DVec2| 0.03 * (1.0 + 2.0 * (p - c).length() / l))),
    ]
}

/// The domain of a region with its boundary divided at twice the size (what the lead
/// hands over: the boundary points final, each segment then halved).
pub(super) fn domain_of(loops: &[Vec<DVec2>], size: &dyn Fn(DVec2) -> f64) -> Domain {
    let raw = Domain::from_loops(loops, None).unwrap();
    split_boundary(&raw, &|p| 2.0 * size(p)).unwrap().domain
}

/// Meshes and checks the contract: quads only, valid (strictly convex, conforming), the
/// domain's area, domain points kept with their ids, every segment halved at its midpoint
/// (listed) and the halves the only boundary edges, every quad tagged.
fn accept(domain: &Domain, size: &dyn Fn(DVec2) -> f64, options: &Options) -> Output {
    let out = mesh(domain, size, options).unwrap();
    let m = &out.mesh;
    assert_eq!(m.validate(), Ok(()));
    assert!(m.triangles.is_empty() && !m.quads.is_empty());
    assert!(m.quad_tags.iter().all(|&t| t == options.region));
    let rel = (m.area() - domain.area()).abs() / domain.area();
    assert!(rel < 1e-9, "area {} vs {}", m.area(), domain.area());
    for (i, p) in domain.points.iter().enumerate() {
        assert_eq!(m.vertices[i], *p, "domain point {i} kept");
    }
    // boundary edges of the quads (one quad), directed
    let mut edges: Vec<[u32; 2]> = m.quads.iter().flat_map(|q| (0..4).map(move |k| [q[k], q[(k + 1) % 4]])).collect();
    edges.sort_unstable();
    let has = |a: u32, b: u32| edges.binary_search(&[a, b]).is_ok();
    let boundary: Vec<[u32; 2]> = edges.iter().copied().filter(|&[a, b]| !has(b, a)).collect();
    assert_eq!(boundary.len(), 2 * domain.segments.len());
    assert_eq!(out.midpoints.len(), domain.segments.len());
    let mid: std::collections::BTreeMap<[u32; 2], u32> = out.midpoints.iter().map(|&(v, [a, b])| ([a.min(b), a.max(b)], v)).collect();
    for &[a, b] in &domain.segments {
        let v = mid[&[a.min(b), a.max(b)]];
        assert!(has(a, v) && has(v, b), "segment {a} {b} halved at {v}");
        assert_eq!(m.vertices[v as usize], 0.5 * (domain.points[a as usize] + domain.points[b as usize]));
    }
    let s = out.stats;
    assert_eq!(m.quads.len(), 4 * s.pairs + 3 * s.leftover_triangles);
    assert_eq!(2 * s.pairs + s.leftover_triangles, s.triangles);
    assert!(s.scaled_jacobian_after[0] >= s.scaled_jacobian_before[0], "{s:?}");
    assert!(s.scaled_jacobian_after[0] > 0.0);
    out
}

#[test]
fn every_test_region() {
    for (name, loops, size) in regions() {
        let dom = domain_of(&loops, &*size);
        let out = accept(&dom, &*size, &Options::default());
        let s = out.stats;
        // few leftovers, and the median quad good
        assert!(s.leftover_triangles * 10 <= s.triangles, "{name}: {s:?}");
        assert!(s.scaled_jacobian_after[1] > 0.8, "{name}: {s:?}");
        assert!(s.smoothing_moves > 0, "{name}: {s:?}");
    }
}

#[test]
fn the_matching_improves_on_greedy_and_pairs_a_square_lattice_into_squares() {
    // a 4 x 4 square lattice split into triangles along alternating diagonals
    let n = 4u32;
    let vertices: Vec<DVec2> = (0..=n).flat_map(|j| (0..=n).map(move |i| d(i as f64, j as f64))).collect();
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, e) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                triangles.extend([[a, b, c], [a, c, e]]);
            } else {
                triangles.extend([[a, b, e], [b, c, e]]);
            }
        }
    }
    let tris = PlanarMesh { vertices, triangle_tags: vec![RegionId(1); triangles.len()], triangles, ..PlanarMesh::default() };
    let out = from_triangles(&tris, &Options::default()).unwrap();
    assert_eq!(out.mesh.validate(), Ok(()));
    assert_eq!((out.stats.pairs, out.stats.leftover_triangles), (16, 0), "{:?}", out.stats);
    assert!((out.stats.scaled_jacobian_before[0] - 1.0).abs() < 1e-12, "{:?}", out.stats);
    // input vertex ids kept, boundary midpoints listed
    assert_eq!(&out.mesh.vertices[..25], &tris.vertices[..]);
    assert_eq!(out.midpoints.len(), 16);
    // greedy alone (no augmenting) on a strip where it strands triangles: the paths fix it
    let strip: Vec<DVec2> = (0..=6).flat_map(|i| [d(i as f64, 0.0), d(i as f64 + 0.5, 0.9)]).collect();
    let tri: Vec<[u32; 3]> = (0..6u32).flat_map(|i| [[2 * i, 2 * i + 2, 2 * i + 1], [2 * i + 1, 2 * i + 2, 2 * i + 3]]).collect();
    let tris = PlanarMesh { vertices: strip, triangle_tags: vec![RegionId(1); tri.len()], triangles: tri, ..PlanarMesh::default() };
    let greedy = from_triangles(&tris, &Options { augment_rounds: 0, ..Options::default() }).unwrap();
    let full = from_triangles(&tris, &Options::default()).unwrap();
    assert_eq!(full.stats.leftover_triangles, 0, "{:?}", full.stats);
    assert!(greedy.stats.leftover_triangles >= full.stats.leftover_triangles);
}

#[test]
fn deterministic() {
    let (_, loops, size) = regions().swap_remove(5);
    let dom = domain_of(&loops, &*size);
    let a = mesh(&dom, &*size, &Options::default()).unwrap();
    let b = mesh(&dom, &*size, &Options::default()).unwrap();
    assert_eq!(a.mesh, b.mesh);
    assert_eq!(a.midpoints, b.midpoints);
}

#[test]
fn errors_name_the_problem() {
    let sq = Domain::from_loops(&[vec![d(0.0, 0.0), d(1.0, 0.0), d(1.0, 1.0), d(0.0, 1.0)]], None).unwrap();
    assert!(matches!(mesh(&sq, &|_| -1.0, &Options::default()), Err(Error::Size { .. })));
    let mut bad = sq.clone();
    bad.tags.pop();
    assert!(matches!(mesh(&bad, &|_| 0.1, &Options::default()), Err(Error::Domain(_))));
    let quad = PlanarMesh { vertices: vec![d(0.0, 0.0), d(1.0, 0.0), d(1.0, 1.0), d(0.0, 1.0)], quads: vec![[0, 1, 2, 3]], quad_tags: vec![RegionId(1)], ..PlanarMesh::default() };
    assert!(matches!(from_triangles(&quad, &Options::default()), Err(Error::Input(_))));
    let cw = PlanarMesh { vertices: vec![d(0.0, 0.0), d(1.0, 0.0), d(0.0, 1.0)], triangles: vec![[0, 2, 1]], triangle_tags: vec![RegionId(1)], ..PlanarMesh::default() };
    assert!(matches!(from_triangles(&cw, &Options::default()), Err(Error::Input(_))));
}

/// The gmsh expression of each region's size (the same field as [`regions`]).
fn gmsh_size(name: &str) -> String {
    match name {
        "12-gon" => "0.08".into(),
        "rectangle" | "L" => "0.1".into(),
        "star" => "0.06".into(),
        "comb" => "0.07".into(),
        "two-holes" => "0.12".into(),
        "strip" => "0.1".into(),
        _ => "0.03*(1+2*Sqrt((x-1.5)^2+(y-1.0)^2)/3.0)".into(),
    }
}

/// Writes every test region (its loops as the mesher got them, the size as a gmsh
/// expression, fepre's figures) as JSON into `$QUADS_DUMP` for `tools/gmsh_quads_sj.py`.
/// Run: `QUADS_DUMP=/tmp/quads cargo test --release --lib mesh2d::quads::tests::dump -- --ignored`.
#[test]
#[ignore]
fn dump_regions_for_gmsh() {
    let dir = std::path::PathBuf::from(std::env::var("QUADS_DUMP").unwrap_or_else(|_| "/tmp/quads".into()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, loops, size) in regions() {
        let dom = domain_of(&loops, &*size);
        let t0 = std::time::Instant::now();
        let out = accept(&dom, &*size, &Options::default());
        let secs = t0.elapsed().as_secs_f64();
        // loops back from the segments (each point has one segment out)
        let mut next = vec![u32::MAX; dom.points.len()];
        for &[a, b] in &dom.segments {
            next[a as usize] = b;
        }
        let mut seen = vec![false; dom.points.len()];
        let mut json_loops = Vec::new();
        for s in 0..dom.points.len() {
            if seen[s] {
                continue;
            }
            let mut l = Vec::new();
            let mut v = s;
            while !seen[v] {
                seen[v] = true;
                l.push(format!("[{:?},{:?}]", dom.points[v].x, dom.points[v].y));
                v = next[v] as usize;
            }
            json_loops.push(format!("[{}]", l.join(",")));
        }
        let s = out.stats;
        let text = format!(
            "{{\"name\":\"{name}\",\"size\":\"{}\",\"loops\":[{}],\"fepre\":{{\"quads\":{},\"pairs\":{},\"leftovers\":{},\"moves\":{},\"sj_before\":[{},{}],\"sj_after\":[{},{}],\"seconds\":{secs}}}}}\n",
            gmsh_size(name), json_loops.join(","), out.mesh.quads.len(), s.pairs, s.leftover_triangles, s.smoothing_moves,
            s.scaled_jacobian_before[0], s.scaled_jacobian_before[1], s.scaled_jacobian_after[0], s.scaled_jacobian_after[1]
        );
        std::fs::write(dir.join(format!("{name}.json")), text).unwrap();
    }
}
