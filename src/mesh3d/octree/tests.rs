//! Tests of the octree mesher as a whole (the stages test themselves beside their code).

use super::*;
use crate::core::size_field::UniformSize;
use crate::mesh::shapes;

/// The unit cube's boundary, each face split into `n × n` squares of two triangles,
/// outward.
pub(crate) fn cube_surface(n: usize) -> TriSurface {
    let mut s = shapes::kuhn_cube(n, 0.0, 0).boundary_surface();
    s.remove_unused_vertices();
    s
}

/// The cube `[lo, lo + size]³`: [`cube_surface`]`(1)`, twelve triangles, outward.
pub(crate) fn cube_at(lo: DVec3, size: f64) -> TriSurface {
    let mut s = cube_surface(1);
    s.vertices.iter_mut().for_each(|p| *p = lo + *p * size);
    s
}

/// The surfaces one after the other (overlapping or nested shells).
pub(crate) fn together(parts: &[TriSurface]) -> TriSurface {
    let mut s = parts[0].clone();
    parts[1..].iter().for_each(|p| s.append(p));
    s
}

fn sphere(n: usize) -> TriSurface {
    // a cube's boundary pushed onto the sphere of radius 1 around its centre
    let mut s = cube_surface(n);
    for p in &mut s.vertices {
        *p = (*p - DVec3::splat(0.5)).normalize();
    }
    s
}

fn check(mesh: &TetMesh, report: &OctreeReport) {
    mesh.validate().unwrap();
    assert!(report.dihedral[0] >= MIN_DIHEDRAL && report.dihedral[1] <= MAX_DIHEDRAL, "{:?}", report.dihedral);
}

#[test]
fn cube_meshes_within_the_bounds() {
    let s = cube_surface(4);
    let (mesh, r) = mesh_octree(&s, &UniformSize(0.1), &OctreeOptions::default()).unwrap();
    check(&mesh, &r);
    assert!((r.input_volume - 1.0).abs() < 1e-12);
    // a cube's corners and edges are cut off by up to a cell
    assert!((r.volume - 1.0).abs() < 0.05, "{}", r.volume);
    assert!(r.deviation.hausdorff <= r.cell_size, "{:?}", r.deviation);
    assert_eq!(r.deviation.feature_edges, 12 * 4);
    let tags = s.tags();
    assert!(mesh.face_tags.iter().all(|t| tags.contains(t)));
}

#[test]
fn sphere_meshes_within_the_bounds_at_many_offsets() {
    let s = sphere(12);
    for k in 0..6 {
        let h = 0.13 + 0.011 * k as f64;
        let (mesh, r) = mesh_octree(&s, &UniformSize(h), &OctreeOptions::default()).unwrap();
        check(&mesh, &r);
        assert!((r.volume - r.input_volume).abs() < 0.03 * r.input_volume, "{} vs {}", r.volume, r.input_volume);
    }
}

#[test]
fn open_cube_meshes() {
    let mut s = cube_surface(4);
    let keep: Vec<usize> = (0..s.triangles.len()).filter(|&t| !s.corners(t).iter().all(|p| (p.z - 1.0).abs() < 1e-12)).collect();
    s.triangles = keep.iter().map(|&t| s.triangles[t]).collect();
    s.face_tags = vec![crate::core::FaceId(1); s.triangles.len()];
    let (mesh, r) = mesh_octree(&s, &UniformSize(0.1), &OctreeOptions::default()).unwrap();
    check(&mesh, &r);
    assert!(r.bisected_cut_points > 0);
    assert!((r.volume - 1.0).abs() < 0.05, "{}", r.volume);
}

#[test]
fn same_bytes_for_any_thread_count() {
    let s = sphere(8);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| mesh_octree(&s, &UniformSize(0.12), &OctreeOptions::default()).unwrap().0)
    };
    let (a, b) = (run(1), run(3));
    assert_eq!(a, b);
}

/// Graded and uniform at the same cell size: the same boundary triangles and volume, the
/// same angle bounds, at most a third of the tets from the octree alone and fewer again
/// coarsened, conforming (every face of one tet only is a boundary triangle), and the same
/// bytes for any thread count.
#[test]
fn graded_keeps_the_boundary_with_a_third_of_the_tets() {
    let s = sphere(16);
    let h = 0.04;
    let (u, ru) = mesh_octree(&s, &UniformSize(h), &OctreeOptions::default()).unwrap();
    let opts = OctreeOptions { grading: Grading::Graded, ..OctreeOptions::default() };
    let run = |threads: usize, opts: &OctreeOptions| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| mesh_octree(&s, &UniformSize(h), opts).unwrap())
    };
    // coarsened
    let (c, rc) = run(2, &opts);
    check(&c, &rc);
    let collapsed = rc.coarsened.expect("graded mode coarsens");
    assert!(collapsed.vertices > 0 && rc.tets + collapsed.tets == run(1, &OctreeOptions { coarsen: false, ..opts.clone() }).1.tets);
    assert!((rc.volume - ru.volume).abs() < 1e-9 * ru.volume, "{} {}", rc.volume, ru.volume);
    assert_eq!(boundary_triangles(&c), boundary_triangles(&u));
    assert_eq!(run(1, &opts).0, c);
    // the octree alone
    let opts = OctreeOptions { coarsen: false, ..opts };
    let (g, rg) = run(2, &opts);
    check(&g, &rg);
    assert_eq!(rg.grading, "graded");
    assert!(rg.coarsened.is_none());
    assert!(rg.cells_per_level.len() >= 3, "{:?}", rg.cells_per_level);
    assert!(3 * g.tets.len() <= u.tets.len(), "{} graded against {} uniform", g.tets.len(), u.tets.len());
    assert!(2 * c.tets.len() <= g.tets.len(), "{} coarsened against {} graded", c.tets.len(), g.tets.len());
    assert!((rg.volume - ru.volume).abs() < 1e-9 * ru.volume, "{} {}", rg.volume, ru.volume);
    assert_eq!(boundary_triangles(&g), boundary_triangles(&u));
    // the tets of coarse cells are the graded mesh's tets that the uniform mesh lacks; the
    // others are the uniform mesh's own
    let key = |m: &TetMesh, t: &[u32; 4]| {
        let mut c = t.map(|v| m.vertices[v as usize].to_array().map(f64::to_bits));
        c.sort_unstable();
        c
    };
    let uniform: std::collections::HashSet<[[u64; 3]; 4]> = u.tets.iter().map(|t| key(&u, t)).collect();
    let not_uniform = g.tets.iter().filter(|t| !uniform.contains(&key(&g, t))).count();
    assert_eq!(ru.coarse_tets, 0);
    assert!(rg.coarse_tets > 0 && rg.coarse_tets == not_uniform, "{} reported, {not_uniform} not the uniform mesh's", rg.coarse_tets);
    let open = g.faces().iter().filter(|f| f.neighbor.is_none()).count();
    assert_eq!(open, g.boundary.len());
    let open = c.faces().iter().filter(|f| f.neighbor.is_none()).count();
    assert_eq!(open, c.boundary.len());
    assert_eq!(run(1, &opts).0, g);
}

/// The boundary triangles of `m` by their corners' bits, sorted.
fn boundary_triangles(m: &TetMesh) -> Vec<[[u64; 3]; 3]> {
    let mut t: Vec<[[u64; 3]; 3]> = m
        .boundary
        .iter()
        .map(|f| {
            let mut c = f.map(|v| m.vertices[v as usize].to_array().map(f64::to_bits));
            c.sort_unstable();
            c
        })
        .collect();
    t.sort_unstable();
    t
}

/// A tilted cube, whose edges and corners feature snapping moves boundary vertices onto:
/// graded and uniform keep the same boundary triangles and snap alike, while tets of coarse
/// cells reach vertices warped onto the surface (they do, away from the features).
#[test]
fn graded_snaps_as_uniform_does_with_warped_vertices_in_coarse_cells() {
    // (at this tilt and cell, a graded octree whose coarse cells took the vertices that
    // snapping moves would snap one vertex fewer than uniform: checked by hand)
    let mut s = cube_at(DVec3::splat(0.055), 1.0);
    let turn = glam::DMat3::from_axis_angle(DVec3::new(1.0, 3.8, 3.0).normalize(), 0.75);
    s.vertices.iter_mut().for_each(|p| *p = turn * *p);
    let h = 0.06;
    let (u, ru) = mesh_octree(&s, &UniformSize(h), &OctreeOptions::default()).unwrap();
    let opts = OctreeOptions { grading: Grading::Graded, ..OctreeOptions::default() };
    let (g, rg) = mesh_octree(&s, &UniformSize(h), &opts).unwrap();
    check(&g, &rg);
    assert!(ru.snapped.corners == 8 && ru.snapped.edge_vertices > 0, "{:?}", ru.snapped);
    assert_eq!(rg.snapped, ru.snapped);
    assert_eq!(boundary_triangles(&g), boundary_triangles(&u));
    assert!((rg.volume - ru.volume).abs() < 1e-9 * ru.volume, "{} {}", rg.volume, ru.volume);
    assert!(g.tets.len() < u.tets.len(), "{} graded against {} uniform", g.tets.len(), u.tets.len());
    // tets of coarse cells (not the uniform mesh's) with a boundary vertex
    let key = |m: &TetMesh, t: &[u32; 4]| {
        let mut c = t.map(|v| m.vertices[v as usize].to_array().map(f64::to_bits));
        c.sort_unstable();
        c
    };
    let uniform: std::collections::HashSet<[[u64; 3]; 4]> = u.tets.iter().map(|t| key(&u, t)).collect();
    let mut on_boundary = vec![false; g.vertices.len()];
    g.boundary.iter().flatten().for_each(|&v| on_boundary[v as usize] = true);
    let reaching = g.tets.iter().filter(|t| !uniform.contains(&key(&g, t)) && t.iter().any(|&v| on_boundary[v as usize])).count();
    assert!(reaching > 0);
}

/// The boundary is every face of one tet only, where the stuffed volume is a solid's and
/// where it reaches the lattice's outer faces: two equal squares 0.05 apart, facing the same
/// way, have a winding number near 1 just behind them out to the lattice's faces (a surface
/// model, not a solid).
#[test]
fn the_boundary_is_every_face_of_one_tet() {
    let square = |z: f64| {
        let v = vec![DVec3::new(0.0, 0.0, z), DVec3::new(1.0, 0.0, z), DVec3::new(1.0, 1.0, z), DVec3::new(0.0, 1.0, z)];
        TriSurface::with_single_tag(v, vec![[0, 1, 2], [0, 2, 3]], crate::core::FaceId(1))
    };
    let sheets = together(&[square(0.0), square(0.05)]);
    for (s, name) in [(sheets, "two sheets"), (sphere(8), "sphere")] {
        let (mesh, report) = mesh_octree(&s, &UniformSize(0.1), &OctreeOptions::default()).unwrap();
        mesh.validate().unwrap();
        // the sheets' volume reaches the lattice's box; the sphere's does not
        assert_eq!(report.reaches_box, name == "two sheets", "{name}");
        let key = |f: &[u32; 3]| {
            let mut k = *f;
            k.sort_unstable();
            k
        };
        let mut once: Vec<[u32; 3]> = mesh.faces().iter().filter(|f| f.neighbor.is_none()).map(|f| key(&f.vertices)).collect();
        let mut boundary: Vec<[u32; 3]> = mesh.boundary.iter().map(key).collect();
        once.sort_unstable();
        boundary.sort_unstable();
        assert!(!boundary.is_empty(), "{name}");
        assert_eq!(boundary, once, "{name}");
    }
}

