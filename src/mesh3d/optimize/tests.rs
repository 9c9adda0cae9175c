//! Tests of the whole optimiser on small meshes: what it must keep (boundary, fixed vertices,
//! regions, volume), what it must do (remove slivers, insert where nothing else helps), and
//! that it is deterministic.

use super::*;
use crate::core::{FaceId, RegionId};
use crate::mesh::shapes::kuhn_cube;
use crate::mesh::tet_mesh::{TET_FACES, sorted3};
use crate::mesh3d::delaunay::{DelaunayOptions, tetrahedralize};
use crate::quality::tetrahedron::tet_min_max_dihedral;
use glam::DVec3;
use std::collections::BTreeMap;

/// `mesh` with its hull faces as boundary triangles, tagged 1, 2, 3, 1, ...
fn with_hull_boundary(mut mesh: TetMesh) -> TetMesh {
    mesh.boundary = mesh.hull_faces();
    mesh.face_tags = (0..mesh.boundary.len()).map(|i| FaceId(1 + (i % 3) as u32)).collect();
    mesh
}

/// Regions 1 and 2 by the tets' centroids left and right of `x = 0.5`.
fn split_regions(mut mesh: TetMesh) -> TetMesh {
    mesh.region_tags = mesh
        .tets
        .iter()
        .map(|t| if t.iter().map(|&i| mesh.vertices[i as usize].x).sum::<f64>() < 2.0 { RegionId(1) } else { RegionId(2) })
        .collect();
    mesh
}

/// Delaunay mesh of the unit cube's corners and `n` pseudo-random points inside: plenty of
/// slivers.
fn random_box(n: usize, seed: u64) -> TetMesh {
    let mut state = seed | 1;
    let mut rnd = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut p: Vec<DVec3> = (0..8).map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64)).collect();
    for _ in 0..n {
        p.push(DVec3::new(0.1 + 0.8 * rnd(), 0.1 + 0.8 * rnd(), 0.1 + 0.8 * rnd()));
    }
    let d = tetrahedralize(&p, &DelaunayOptions::default()).unwrap();
    d.to_tet_mesh(&p)
}

/// Sorted keys of the faces between tets of different regions.
fn interfaces(m: &TetMesh) -> Vec<[u32; 3]> {
    let mut faces: BTreeMap<[u32; 3], Vec<RegionId>> = BTreeMap::new();
    for (t, r) in m.tets.iter().zip(&m.region_tags) {
        for f in TET_FACES {
            faces.entry(sorted3([t[f[0]], t[f[1]], t[f[2]]]).0).or_default().push(*r);
        }
    }
    faces.into_iter().filter(|(_, r)| r.len() == 2 && r[0] != r[1]).map(|(k, _)| k).collect()
}

fn region_volumes(m: &TetMesh) -> BTreeMap<RegionId, f64> {
    let mut v = BTreeMap::new();
    for t in 0..m.tets.len() {
        *v.entry(m.region_tags[t]).or_insert(0.0) += m.tet_volume(t);
    }
    v
}

fn min_max_dihedral(m: &TetMesh) -> (f64, f64) {
    m.tets
        .iter()
        .map(|t| tet_min_max_dihedral(&t.map(|i| m.vertices[i as usize])))
        .fold((180.0, 0.0), |a, b| (a.0.min(b.0), a.1.max(b.1)))
}

/// Checks what the optimiser keeps: validity, boundary triangles and tags, the vertices of hull,
/// boundary and interface faces (bitwise), the interface faces, each region's volume.
fn check_kept(before: &TetMesh, after: &TetMesh, report: &OptimizeReport) {
    assert_eq!(after.validate(), Ok(()));
    assert_eq!(after.boundary, before.boundary);
    assert_eq!(after.face_tags, before.face_tags);
    assert_eq!(after.vertices.len(), before.vertices.len() + report.insertions);
    let mut fixed = vec![false; before.vertices.len()];
    for f in before.hull_faces().iter().chain(&before.boundary).chain(&interfaces(before)) {
        f.iter().for_each(|&v| fixed[v as usize] = true);
    }
    for (v, _) in fixed.iter().enumerate().filter(|f| *f.1) {
        assert_eq!(after.vertices[v], before.vertices[v], "fixed vertex {v} moved");
    }
    assert_eq!(interfaces(after), interfaces(before), "the region interfaces changed");
    let (v0, v1) = (region_volumes(before), region_volumes(after));
    assert_eq!(v0.keys().collect::<Vec<_>>(), v1.keys().collect::<Vec<_>>(), "region tags changed");
    for (r, a) in &v0 {
        assert!((a - v1[r]).abs() <= 1e-12 * a, "region {r:?}: volume {a} became {}", v1[r]);
    }
    assert_eq!(report.tets_after, after.tets.len());
}

/// An octahedron (apexes `T`, `B`, a twisted equator) cut into a sliver and the four tets
/// joining it to the apexes: every vertex is on the hull, so only flips can help.
fn sliver_octahedron(h: f64) -> TetMesh {
    let vertices = vec![
        DVec3::new(0.0, 0.0, 1.0),  // 0: T
        DVec3::new(0.0, 0.0, -1.0), // 1: B
        DVec3::new(1.0, 0.0, h),    // 2
        DVec3::new(-1.0, 0.0, h),   // 3
        DVec3::new(0.0, 1.0, -h),   // 4
        DVec3::new(0.0, -1.0, -h),  // 5
    ];
    let mut tets = vec![[2, 3, 4, 5], [0, 2, 3, 4], [0, 2, 3, 5], [1, 4, 5, 2], [1, 4, 5, 3]];
    for t in &mut tets {
        let [a, b, c, d] = t.map(|i| vertices[i as usize]);
        if (b - a).dot((c - a).cross(d - a)) < 0.0 {
            t.swap(0, 1);
        }
    }
    let n = tets.len();
    with_hull_boundary(TetMesh { vertices, tets, region_tags: vec![RegionId(1); n], ..Default::default() })
}

#[test]
fn a_sliver_between_constrained_faces_is_flipped_away() {
    let m = sliver_octahedron(0.05);
    assert_eq!(m.validate(), Ok(()));
    assert_eq!(m.boundary.len(), 8);
    let (lo, _) = min_max_dihedral(&m);
    assert!(lo < 10.0, "the input has a sliver: {lo}");
    let mut out = m.clone();
    let r = optimize(&mut out, &OptimizeOptions::default()).unwrap();
    check_kept(&m, &out, &r);
    assert_eq!(out.vertices, m.vertices, "every vertex is fixed");
    assert_eq!((r.smoothing_moves, r.insertions), (0, 0));
    assert!(r.flips32 + r.flips44 + r.edge_removals + r.flips23 > 0);
    let (lo, hi) = min_max_dihedral(&out);
    assert!(lo >= 15.0 && hi <= 160.0, "{lo} {hi}");
    assert_eq!((r.min_dihedral_after, r.max_dihedral_after), (lo, hi));
    assert_eq!(r.bad_after, 0);
}

#[test]
fn boundary_and_interface_vertices_never_move() {
    let m = with_hull_boundary(split_regions(kuhn_cube(4, 0.45, 7)));
    let opts = OptimizeOptions::default().with_min_dihedral(30.0).with_max_dihedral(130.0);
    let mut out = m.clone();
    let r = optimize(&mut out, &opts).unwrap();
    assert!(r.bad_before > 0);
    check_kept(&m, &out, &r);
    assert!(r.smoothing_moves > 0, "{r:?}");
    let moved = (0..m.vertices.len()).filter(|&v| out.vertices[v] != m.vertices[v]).count();
    assert!(moved > 0);
    assert!(r.min_dihedral_after > r.min_dihedral_before, "{r:?}");
    assert!(r.bad_after < r.bad_before, "{r:?}");
}

#[test]
fn region_tags_are_kept_across_regions() {
    let m = with_hull_boundary(split_regions(random_box(300, 11)));
    assert!(!interfaces(&m).is_empty());
    let mut out = m.clone();
    let r = optimize(&mut out, &OptimizeOptions::default()).unwrap();
    check_kept(&m, &out, &r);
    assert!(r.flips32 + r.flips44 + r.flips23 > 0, "{r:?}");
    assert!(r.bad_after < r.bad_before, "{r:?}");
    // an interface face between two regions is in the boundary list of neither: constrained
    // all the same, as checked by `check_kept`; each region's tets stay on their side
    let left: f64 = (0..out.tets.len()).filter(|&t| out.region_tags[t] == RegionId(1)).map(|t| out.tet_volume(t)).sum();
    assert!((left - region_volumes(&m)[&RegionId(1)]).abs() < 1e-12);
}

#[test]
fn listed_interior_triangles_are_kept() {
    // an internal surface inside one region: the faces between tets with centroids below and
    // above y = 0.5, listed as boundary triangles (tag 9) although both sides are region 1
    let mut m = with_hull_boundary(random_box(300, 5));
    let below = |t: &[u32; 4]| t.iter().map(|&i| m.vertices[i as usize].y).sum::<f64>() < 2.0;
    let side: Vec<bool> = m.tets.iter().map(below).collect();
    let mut faces: BTreeMap<[u32; 3], Vec<(usize, [u32; 3])>> = BTreeMap::new();
    for (t, tet) in m.tets.iter().enumerate() {
        for f in TET_FACES {
            let tri = [tet[f[0]], tet[f[1]], tet[f[2]]];
            faces.entry(sorted3(tri).0).or_default().push((t, tri));
        }
    }
    let internal: Vec<[u32; 3]> =
        faces.values().filter(|v| v.len() == 2 && side[v[0].0] != side[v[1].0]).map(|v| v[0].1).collect();
    assert!(internal.len() > 20);
    m.boundary.extend(&internal);
    m.face_tags.extend(std::iter::repeat_n(FaceId(9), internal.len()));
    assert_eq!(m.validate(), Ok(()));
    let mut out = m.clone();
    let r = optimize(&mut out, &OptimizeOptions::default()).unwrap();
    // `validate` checks that every boundary triangle is still a face
    check_kept(&m, &out, &r);
    assert!(r.flips32 + r.flips44 + r.flips23 + r.smoothing_moves > 0, "{r:?}");
    // the same optimisation without the listed faces changes some of them
    let mut free = with_hull_boundary(random_box(300, 5));
    optimize(&mut free, &OptimizeOptions::default()).unwrap();
    let kept: std::collections::BTreeSet<[u32; 3]> = free.faces().iter().map(|f| sorted3(f.vertices).0).collect();
    assert!(internal.iter().any(|f| !kept.contains(&sorted3(*f).0)), "the test would not notice a removed face");
}

#[test]
fn a_good_mesh_is_left_unchanged() {
    // Kuhn tets: dihedral angles 45°–90°, radius-edge 0.87
    let m = with_hull_boundary(kuhn_cube(3, 0.0, 1));
    let mut out = m.clone();
    let r = optimize(&mut out, &OptimizeOptions::default()).unwrap();
    assert_eq!(out, m);
    assert_eq!((r.bad_before, r.bad_after, r.passes), (0, 0, 0));
    assert_eq!(r.flips23 + r.flips32 + r.flips44 + r.edge_removals + r.smoothing_moves + r.insertions, 0);
}

#[test]
fn results_are_deterministic() {
    let m = with_hull_boundary(random_box(400, 3));
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let mut out = m.clone();
        let mut r = pool.install(|| optimize(&mut out, &OptimizeOptions::default())).unwrap();
        (r.seconds, r.setup_seconds) = (0.0, 0.0);
        (out, r)
    };
    let (a, ra) = run(1);
    let (b, rb) = run(3);
    assert_eq!(ra, rb);
    assert_eq!(a, b);
    assert!(ra.flips32 + ra.smoothing_moves > 0);
    check_kept(&m, &a, &ra);
}

/// The 12 vertices of an icosahedron, all cospherical: every Delaunay tet has its four vertices
/// on the hull, and some are flat.
fn icosahedron() -> TetMesh {
    let g = (1.0 + 5f64.sqrt()) / 2.0;
    let mut p = Vec::new();
    for (a, b) in [(1.0, g), (-1.0, g), (1.0, -g), (-1.0, -g)] {
        p.push(DVec3::new(0.0, a, b));
        p.push(DVec3::new(a, b, 0.0));
        p.push(DVec3::new(b, 0.0, a));
    }
    let d = tetrahedralize(&p, &DelaunayOptions::default()).unwrap();
    with_hull_boundary(d.to_tet_mesh(&p))
}

#[test]
fn only_insertion_helps_inside_an_icosahedron() {
    let m = icosahedron();
    assert_eq!(m.validate(), Ok(()));
    assert_eq!(m.boundary.len(), 20);
    let opts = OptimizeOptions::default().with_min_dihedral(40.0).with_max_dihedral(130.0);
    let mut flips_only = m.clone();
    let r0 = optimize(&mut flips_only, &opts.clone().with_insertion(false)).unwrap();
    check_kept(&m, &flips_only, &r0);
    assert!(r0.bad_after > 0, "{r0:?}");
    let mut out = m.clone();
    let r = optimize(&mut out, &opts).unwrap();
    check_kept(&m, &out, &r);
    assert!(r.insertions > 0, "{r:?}");
    assert_eq!(r.bad_after, 0, "{r:?}");
    let (lo, hi) = min_max_dihedral(&out);
    assert!(lo >= 40.0 && hi <= 130.0, "{lo} {hi}");
    assert!(lo > r0.min_dihedral_after, "{lo} vs {}", r0.min_dihedral_after);
}

#[test]
fn invalid_meshes_are_refused_and_left_alone() {
    let mut m = kuhn_cube(2, 0.0, 1);
    m.tets[0].swap(0, 1);
    let copy = m.clone();
    assert!(matches!(optimize(&mut m, &OptimizeOptions::default()), Err(OptimizeError::InvalidMesh(_))));
    assert_eq!(m, copy);
    let mut m = kuhn_cube(2, 0.0, 1);
    m.tets[0][0] = 1000;
    assert!(matches!(optimize(&mut m, &OptimizeOptions::default()), Err(OptimizeError::InvalidMesh(_))));
}

#[test]
fn the_polish_raises_a_mesh_that_met_its_targets_and_lowers_nothing() {
    // jittered Kuhn tets: some under 30°, every one reachable by smoothing
    let m = with_hull_boundary(kuhn_cube(5, 0.3, 7));
    let opts = OptimizeOptions::default().with_min_dihedral(30.0).with_max_dihedral(135.0).with_max_passes(16);
    let mut plain = m.clone();
    let r0 = optimize(&mut plain, &opts.clone().with_polish(0.0)).unwrap();
    let (lo0, hi0) = min_max_dihedral(&plain);
    // the work without the polish met both targets, so the polish runs
    assert!(lo0 >= 30.0 && hi0 <= 135.0 && r0.polish_attempts == 0, "{lo0} {hi0} {r0:?}");
    let mut out = m.clone();
    let r = optimize(&mut out, &opts.clone().with_polish(0.1)).unwrap();
    check_kept(&m, &out, &r);
    let (lo, hi) = min_max_dihedral(&out);
    assert!(r.polish_attempts > 0, "{r:?}");
    assert!(lo > lo0, "the polish left the smallest angle at {lo}° (without it {lo0}°)");
    // a largest angle passes its target by at most (180° − 135°)(1 − least score)
    assert!(hi <= 135.0 + 45.0 * (1.0 - lo0 / 33.0), "{hi}");
    // the report is of the plain targets: nothing missed them
    assert_eq!(r.bad_after, 0);
    assert!(!r.out_of_attempts);
}

#[test]
fn the_focus_works_around_the_worst_tets_within_its_share_and_caps_the_largest_angle() {
    // two passes (insertion comes from the third) leave slivers in a random box
    let m = with_hull_boundary(random_box(400, 5));
    let opts = OptimizeOptions::default().with_max_passes(2).with_polish(0.0);
    let mut plain = m.clone();
    let r0 = optimize(&mut plain, &opts).unwrap();
    let (lo0, hi0) = min_max_dihedral(&plain);
    assert!(lo0 < 16.0, "the fixture must leave tets under target: {lo0}");
    let under = |m: &TetMesh, deg: f64| m.tets.iter().filter(|t| tet_min_max_dihedral(&t.map(|v| m.vertices[v as usize])).0 < deg).count();
    let focus = Focus { below_deg: 14.0, target_deg: 30.0 };
    let mut out = m.clone();
    let r = optimize(&mut out, &opts.clone().with_focus(Some(focus))).unwrap();
    check_kept(&m, &out, &r);
    // the same work first, then the phase within its share of the attempts made before it
    assert_eq!(r.attempts - r.focus_attempts - r.focus_dihedral_attempts - r.focus_repeat_attempts, r0.attempts, "{r:?}");
    assert!(r.focus_attempts > 0 && r.focus_attempts as f64 <= FOCUS_SHARE * r0.attempts as f64 + 1.0, "{r:?}");
    // the second round (the hull's slivers stay under the bound) within its own share
    assert!(r.focus_dihedral_attempts > 0 && r.focus_dihedral_attempts as f64 <= FOCUS_SHARE * r0.attempts as f64 + 1.0, "{r:?}");
    // then the search, on the free vertices of the tets still under the bound, and the
    // round's repeats, each within its own share
    assert!(r.searched_vertices > 0 && r.search_moves <= r.searched_vertices, "{r:?}");
    assert!(r.focus_repeat_attempts as f64 <= (FOCUS_SEARCH_ROUNDS - 1) as f64 * (FOCUS_SHARE * r0.attempts as f64 + 1.0), "{r:?}");
    let (lo, hi) = min_max_dihedral(&out);
    // the hull's slivers cannot change (their faces are the boundary); the others around them
    // get better, and the worst does not get worse
    assert!(under(&out, 14.0) < under(&plain, 14.0), "{} tets under 14°, {} without the phase", under(&out, 14.0), under(&plain, 14.0));
    assert!(lo >= lo0, "the worst tet is {lo}°, {lo0}° without the phase");
    assert!(hi <= hi0.max(158.0), "the largest angle grew to {hi}° (from {hi0}°)");
    // a mesh without tets under the phase's bound is left as the passes left it
    let good = with_hull_boundary(kuhn_cube(3, 0.0, 1));
    let mut kept = good.clone();
    let r = optimize(&mut kept, &OptimizeOptions::default().with_focus(Some(Focus { below_deg: 10.0, target_deg: 30.0 }))).unwrap();
    assert_eq!(kept, good);
    assert_eq!((r.focus_attempts, r.focus_dihedral_attempts, r.focus_repeat_attempts, r.searched_vertices), (0, 0, 0, 0));
}

#[test]
fn the_focus_repeats_only_while_its_rounds_make_progress() {
    let focus = Focus { below_deg: 14.0, target_deg: 30.0 };
    let corner = |p: DVec3| InputAngle { kind: crate::quality::input_angles::InputAngleKind::Corner, angle_deg: 5.0, at: [p.to_array(); 2], faces: [FaceId(1); 2], across: [FaceId(1); 2] };
    // the fixture of the focus test: slivers left at the hull after two passes
    let m = with_hull_boundary(random_box(400, 5));
    let mut hull: Vec<u32> = m.boundary.iter().flatten().copied().collect();
    hull.sort_unstable();
    hull.dedup();
    let hull: Vec<DVec3> = hull.iter().map(|&v| m.vertices[v as usize]).collect();
    let opts = OptimizeOptions::default().with_max_passes(2).with_polish(0.0).with_focus(Some(focus));
    let mut plain = m.clone();
    let r = optimize(&mut plain, &opts).unwrap();
    check_kept(&m, &plain, &r);
    // the slivers at the hull, unexplained, keep getting better: the rounds go on until none
    // is left under the bound (14 rounds here) or the cap stops them
    assert!(r.focus_rounds > 1 && r.focus_rounds <= FOCUS_SEARCH_ROUNDS, "{r:?}");
    assert!(r.focus_rounds == FOCUS_SEARCH_ROUNDS || r.min_dihedral_after >= focus.below_deg, "{r:?}");
    // an input angle at every hull vertex (they do not move) explains them: the same work
    // up to the end of the first search, and a mesh as sound
    let mut out = m.clone();
    let r1 = optimize_explained(&mut out, &opts, &|| hull.iter().map(|&p| corner(p)).collect(), None).unwrap();
    check_kept(&m, &out, &r1);
    assert!(r1.focus_rounds >= 1 && r1.focus_rounds <= FOCUS_SEARCH_ROUNDS, "{r1:?}");
    assert_eq!((r1.focus_attempts, r1.focus_dihedral_attempts), (r.focus_attempts, r.focus_dihedral_attempts));
    // angles far from every tet explain none: the same work as without them
    let mut far = m.clone();
    let r2 = optimize_explained(&mut far, &opts, &|| vec![corner(DVec3::splat(10.0))], None).unwrap();
    assert_eq!((far, r2.focus_rounds), (plain, r.focus_rounds));

    // beside a cube, a flat tet on its own, every face of it boundary and every vertex a
    // corner: nothing changes it, so after the first round and its search nothing got better
    // and the phase stops
    let mut cube = kuhn_cube(3, 0.0, 1);
    let n = cube.vertices.len() as u32;
    cube.vertices.extend([DVec3::new(5.0, 0.0, 0.0), DVec3::new(6.0, 0.0, 0.0), DVec3::new(5.5, 1.0, 0.0), DVec3::new(5.5, 0.3, 0.02)]);
    let p = [0, 1, 2, 3].map(|k| cube.vertices[(n + k) as usize]);
    cube.tets.push(if crate::core::predicates::orient3d(p[0], p[1], p[2], p[3]) == crate::core::Sign::Positive { [n, n + 1, n + 2, n + 3] } else { [n + 1, n, n + 2, n + 3] });
    cube.region_tags.push(cube.region_tags[0]);
    let cube = with_hull_boundary(cube);
    assert_eq!(cube.validate(), Ok(()));
    assert!(tet_min_max_dihedral(&p).0 < 14.0);
    let mut out = cube.clone();
    let r = optimize(&mut out, &OptimizeOptions::default().with_focus(Some(focus))).unwrap();
    check_kept(&cube, &out, &r);
    assert_eq!((r.focus_rounds, r.focus_repeat_attempts), (1, 0), "{r:?}");
}

#[test]
fn the_bad_tets_are_gathered_the_same_serially_and_in_parallel_chunks() {
    // scores under and over 1 in a scrambled order, with ties, and slots left out; more than
    // three chunks of the parallel scan, the last one short
    let n = 3 * crate::quality::summary::CHUNK as u64 + 17;
    let q: Vec<f64> = (0..n).map(|i| ((i * 7919) % 37) as f64 / 20.0).collect();
    let keep = |t: usize| t % 5 != 3;
    let mut want: Vec<(f64, u32)> = q.iter().enumerate().filter(|&(t, &x)| x < 1.0 && keep(t)).map(|(t, &x)| (x, t as u32)).collect();
    want.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    assert!(want.len() > 300 && want.windows(2).any(|w| w[0].0 == w[1].0), "ties are tested");
    assert_eq!(gather_bad(&q, keep, usize::MAX), want, "serial");
    assert_eq!(gather_bad(&q, keep, 0), want, "chunks in parallel");
    assert_eq!(gather_bad(&q, keep, q.len() - 1), want, "chunks in parallel, one slot over the serial bound");
    assert_eq!(gather_bad(&[], keep, 0), Vec::new());
}
