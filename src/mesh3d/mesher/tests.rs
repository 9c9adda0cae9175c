use super::*;
use crate::core::size_field::UniformSize;
use crate::mesh::shapes::{plate_with_hole, torus};

fn cube(n: usize) -> TriSurface {
    // a cube [0,1]^3 with each side split into n×n squares (2 triangles each), tag per side
    let mut s = TriSurface::default();
    let mut vid = std::collections::HashMap::new();
    let mut id = |p: [i64; 3], s: &mut TriSurface| -> u32 {
        *vid.entry(p).or_insert_with(|| {
            s.vertices.push(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) / n as f64);
            (s.vertices.len() - 1) as u32
        })
    };
    let n = n as i64;
    for axis in 0..3 {
        for side in 0..2 {
            let tag = FaceId((axis * 2 + side + 1) as u32);
            for i in 0..n {
                for j in 0..n {
                    let corner = |di: i64, dj: i64| {
                        let mut p = [0i64; 3];
                        p[axis] = side as i64 * n;
                        p[(axis + 1) % 3] = i + di;
                        p[(axis + 2) % 3] = j + dj;
                        p
                    };
                    let q = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)].map(|p| id(p, &mut s));
                    // outward: counter-clockwise seen from outside
                    let t = if side == 1 { [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] } else { [[q[0], q[2], q[1]], [q[0], q[3], q[2]]] };
                    for tri in t {
                        s.triangles.push(tri);
                        s.face_tags.push(tag);
                    }
                }
            }
        }
    }
    s
}

fn check(mesh: &TetMesh, volume: f64) {
    mesh.validate().unwrap();
    assert!((mesh.volume() - volume).abs() < 1e-9 * volume, "volume {} vs {volume}", mesh.volume());
    let q = crate::quality::tet_mesh_quality(mesh);
    assert_eq!(q.inverted, 0);
    assert!(q.max_radius_edge < 1e3, "max radius-edge {}", q.max_radius_edge);
}

#[test]
fn cube_keeps_volume_and_tags() {
    let s = cube(3);
    let (m, r) = mesh_surface(&s, &Seeds::default(), &UniformSize(f64::INFINITY), &MeshOptions::default()).unwrap();
    check(&m, 1.0);
    assert_eq!(r.regions, 1);
    let mut tags = m.face_tags.clone();
    tags.sort();
    tags.dedup();
    assert_eq!(tags, (1..=6).map(FaceId).collect::<Vec<_>>());
    let q = crate::quality::tet_mesh_quality(&m);
    assert!(q.max_radius_edge <= 1.5 + 1e-9 || r.boundary_steiner_points > 0, "{}", q.max_radius_edge);
}

#[test]
fn an_abandoned_run_stops_and_a_copy_of_its_options_meshes_alike() {
    let s = cube(3);
    let size = UniformSize(0.3);
    let (m, _) = mesh_surface(&s, &Seeds::default(), &size, &MeshOptions::default()).unwrap();
    // the flag is no part of what the options ask for: unset, the same mesh
    let abandon = Abandon::default();
    let opts = MeshOptions::default().with_abandon(abandon.clone());
    assert_eq!(opts, MeshOptions::default());
    let (again, _) = mesh_surface(&s, &Seeds::default(), &size, &opts).unwrap();
    assert_eq!(again.tets, m.tets);
    assert_eq!(again.vertices, m.vertices);
    // set, the run stops at its first stage
    abandon.set();
    assert_eq!(mesh_surface(&s, &Seeds::default(), &size, &opts).map(|_| ()), Err(MeshingError::Abandoned));
    // a bad input's own error comes first
    let mut open = s.clone();
    open.triangles.pop();
    open.face_tags.pop();
    assert!(matches!(mesh_surface(&open, &Seeds::default(), &size, &opts), Err(MeshingError::Open { .. })));
}

#[test]
fn plate_with_hole_and_torus_mesh() {
    let p = plate_with_hole(16, 40.0, 8.0, 8.0);
    let (m, _) = mesh_surface(&p, &Seeds::default(), &UniformSize(6.0), &MeshOptions::default()).unwrap();
    let vol = crate::mesh::topology::surface_report(&p, &Default::default()).volume;
    check(&m, vol);
    let t = torus(3.0, 1.0, 24, 12);
    let (m, _) = mesh_surface(&t, &Seeds::default(), &UniformSize(f64::INFINITY), &MeshOptions::default()).unwrap();
    let vol = crate::mesh::topology::surface_report(&t, &Default::default()).volume;
    check(&m, vol);
}

#[test]
fn refinement_splits_the_boundary_and_keeps_it() {
    // a plate with a hole at a size that leaves tets whose centres encroach the faces
    let p = plate_with_hole(16, 40.0, 8.0, 8.0);
    let opts = MeshOptions::default().with_optimize(false);
    let (m, r) = mesh_surface(&p, &Seeds::default(), &UniformSize(6.0), &opts).unwrap();
    let rep = crate::mesh::topology::surface_report(&p, &Default::default());
    check(&m, rep.volume);
    assert!(r.refinement_boundary_points > 0, "no boundary split: {r:?}");
    assert!(r.boundary_steiner_points >= r.refinement_boundary_points);
    // the boundary is the input surface: the same area, the input's tags only, closed
    let area: f64 = m.boundary.iter().map(|t| {
        let [a, b, c] = t.map(|i| m.vertices[i as usize]);
        0.5 * (b - a).cross(c - a).length()
    }).sum();
    assert!((area - rep.area).abs() < 1e-9 * rep.area, "area {area} vs {}", rep.area);
    let mut tags = p.face_tags.clone();
    tags.sort();
    tags.dedup();
    assert!(m.face_tags.iter().all(|t| tags.binary_search(t).is_ok()));
    let q = crate::quality::tet_mesh_quality(&m);
    assert!(q.max_radius_edge < 4.0, "max radius-edge {}", q.max_radius_edge);
    // keep-surface never splits it
    let (m, r) = mesh_surface(&cube(2), &Seeds::default(), &UniformSize(0.3), &opts.clone().with_keep_surface(true)).unwrap();
    check(&m, 1.0);
    assert_eq!((r.refinement_boundary_points, r.boundary_steiner_points), (0, 0));
}

#[test]
fn open_and_crossing_surfaces_are_refused() {
    let mut s = cube(1);
    s.triangles.pop();
    s.face_tags.pop();
    let tag = *s.face_tags.last().unwrap();
    let e = mesh_surface(&s, &Seeds::default(), &UniformSize(1.0), &MeshOptions::default()).unwrap_err();
    assert!(matches!(e, MeshingError::Open { count: 3, .. }), "{e}");
    // the message says where: the open edges' end points and the faces along them (the one
    // that lost a triangle, whose other triangle holds the diagonal, and the two beside it)
    let MeshingError::Open { at, faces, .. } = &e else { unreachable!() };
    assert_eq!(at.len(), 3);
    assert!(faces.iter().any(|f| f.0 == tag) && faces.len() == 3, "{e}");
    assert!(e.to_string().contains("along faces "), "{e}");
    let mut two = cube(1);
    let mut b = cube(1);
    for v in &mut b.vertices {
        *v += DVec3::splat(0.5);
    }
    two.append(&b);
    let e = mesh_surface(&two, &Seeds::default(), &UniformSize(1.0), &MeshOptions::default()).unwrap_err();
    assert!(matches!(e, MeshingError::SelfIntersecting { .. }), "{e}");
}

mod generated {
    //! Robustness on generated closed polyhedra: `validate()` passes and the volume is kept,
    //! or a clean error comes back; never a panic.
    use super::*;
    use proptest::prelude::*;

    fn rotate(s: &mut TriSurface, angles: [f64; 3]) {
        let r = glam::DMat3::from_euler(glam::EulerRot::XYZ, angles[0], angles[1], angles[2]);
        for v in &mut s.vertices {
            *v = r * *v;
        }
    }

    fn run(s: &TriSurface, keep: bool) {
        let opts = MeshOptions::default().with_keep_surface(keep);
        match mesh_surface(s, &Seeds::default(), &UniformSize(f64::INFINITY), &opts) {
            Ok((m, _)) => {
                assert_eq!(m.validate(), Ok(()));
                let vol = crate::mesh::topology::surface_report(s, &Default::default()).volume;
                assert!((m.volume() - vol).abs() <= 1e-9 * vol.abs(), "volume {} vs {vol}", m.volume());
            }
            Err(e) => {
                // a clean error, with a message
                assert!(!e.to_string().is_empty());
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

        /// Rotated grids, stretched into thin slabs.
        #[test]
        fn rotated_slabs(n in 1usize..4, sx in 0.01f64..10.0, sy in 0.1f64..10.0, a in proptest::array::uniform3(-3.2f64..3.2), keep in any::<bool>()) {
            let mut s = cube(n);
            for v in &mut s.vertices {
                v.x *= sx;
                v.y *= sy;
            }
            rotate(&mut s, a);
            run(&s, keep);
        }

        /// Plates with a hole (a through hole: genus 1), rotated.
        #[test]
        fn plates_with_holes(k in 1usize..3, r in 0.5f64..9.0, thick in 0.3f64..10.0, a in proptest::array::uniform3(-3.2f64..3.2)) {
            let mut s = plate_with_hole(8 * k, 20.0, thick, r);
            rotate(&mut s, a);
            run(&s, false);
        }

        /// Near-coplanar facets: the top of a subdivided cube bent by tiny amounts.
        #[test]
        fn near_coplanar(n in 2usize..4, eps in proptest::collection::vec(-1e-9f64..1e-9, 16)) {
            let mut s = cube(n);
            let mut k = 0;
            for v in &mut s.vertices {
                if v.z == 1.0 && v.x > 0.0 && v.x < 1.0 && v.y > 0.0 && v.y < 1.0 {
                    v.z += eps[k % eps.len()];
                    k += 1;
                }
            }
            run(&s, false);
            run(&s, true);
        }
    }
}

#[test]
fn a_cap_in_the_input_is_repaired_and_the_volume_meshes() {
    // a tessellator's flat triangle with a vertex on its long side: two input edges at an
    // angle of zero, which recovery cannot separate
    let s = crate::mesh::caps::tests::capped_tetrahedron();
    let (m, r) = mesh_surface(&s, &Seeds::default(), &UniformSize(f64::INFINITY), &MeshOptions::default()).unwrap();
    m.validate().unwrap();
    assert_eq!(r.input_caps_repaired, 1);
    assert!((m.volume() - 1.0 / 6.0).abs() < 1e-12, "{}", m.volume());
}

#[test]
fn tets_on_a_thin_boundary_triangle_trade_radius_edge_for_dihedral_angles() {
    // a unit cube whose top is a fan from a point near its side y = 1: the fan's triangle to
    // that side has a corner of 168°, and with the surface kept every tet on it has a
    // radius-edge ratio far above the bound. Two tets stayed at 6.4° without the focus
    // phase's second round (dihedral angles alone, radius-edge ratios up to FOCUS_RADIUS_EDGE
    // times the bound) and with it at the usual radius-edge rule; with it they reached 11.4°
    // (at three times the bound)
    let mut s = TriSurface::default();
    for k in 0..8 {
        s.vertices.push(DVec3::new((k & 1) as f64, ((k >> 1) & 1) as f64, (k >> 2) as f64));
    }
    s.vertices.push(DVec3::new(0.3, 0.95, 1.0));
    // the corner (x, y, z) is vertex x + 2 y + 4 z; the sides outward, counter-clockwise
    let sides: [([u32; 4], u32); 5] = [([0, 2, 3, 1], 1), ([0, 1, 5, 4], 2), ([3, 2, 6, 7], 3), ([0, 4, 6, 2], 4), ([1, 3, 7, 5], 5)];
    for (q, tag) in sides {
        for tri in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            s.triangles.push(tri);
            s.face_tags.push(FaceId(tag));
        }
    }
    let top = [4, 5, 7, 6];
    for i in 0..4 {
        s.triangles.push([8, top[i], top[(i + 1) % 4]]);
        s.face_tags.push(FaceId(6));
    }
    let opts = MeshOptions::default().with_keep_surface(true);
    let (m, r) = mesh_surface(&s, &Seeds::default(), &UniformSize(f64::INFINITY), &opts).unwrap();
    check(&m, 1.0);
    let q = crate::quality::tet_mesh_quality(&m);
    let o = r.optimize.unwrap();
    assert!(o.focus_dihedral_attempts > 0, "{o:?}");
    assert!(q.min_dihedral_deg >= 10.0, "smallest dihedral angle {}° ({o:?})", q.min_dihedral_deg);
    assert!(q.max_dihedral_deg < 170.0, "largest dihedral angle {}°", q.max_dihedral_deg);
}

#[test]
fn a_step_narrower_than_the_tolerance_is_closed_up_before_meshing() {
    // a unit box whose top steps up by 1e-5 halfway: at the default tolerance (1e-4 of the
    // diagonal) the step's face is closed up and the tets are as good as a box's
    let s = crate::mesh::narrow::tests::stepped_box(1e-5);
    let (m, r) = mesh_surface(&s, &Seeds::default(), &UniformSize(0.25), &MeshOptions::default()).unwrap();
    m.validate().unwrap();
    let n = r.narrow.as_ref().expect("the step is closed up");
    assert!(n.faces.iter().any(|&(f, _)| f == FaceId(4)), "{n:?}");
    assert!(!m.face_tags.contains(&FaceId(4)));
    let q = crate::quality::tet_mesh_quality(&m);
    assert!(q.min_dihedral_deg >= 10.0, "{}", q.min_dihedral_deg);
    assert!((m.volume() - 1.0).abs() < 1e-4, "{}", m.volume());
    // with the tolerance at zero the step is meshed as it is
    let (m0, r0) = mesh_surface(&s, &Seeds::default(), &UniformSize(0.25), &MeshOptions::default().with_narrow_tolerance(Some(0.0))).unwrap();
    m0.validate().unwrap();
    assert!(r0.narrow.is_none());
    assert!(m0.face_tags.contains(&FaceId(4)));
}

/// The surface the mesher took (the step closed up) comes with its report, is what the
/// report's steps make again, and stands only for the input it was made from.
#[test]
fn the_prepared_surface_comes_with_the_report_for_its_input_only() {
    let s = crate::mesh::narrow::tests::stepped_box(1e-5);
    let (_, r) = mesh_surface(&s, &Seeds::default(), &UniformSize(0.25), &MeshOptions::default()).unwrap();
    let kept = prepared_surface(&s, &r).expect("the step is closed up");
    assert!(matches!(kept, std::borrow::Cow::Borrowed(_)));
    let again = made_again(&s, &r).expect("made again");
    assert_eq!(kept.vertices, again.vertices);
    assert_eq!(kept.triangles, again.triangles);
    assert_eq!(kept.face_tags, again.face_tags);
    // another input (one vertex moved) is prepared anew
    let mut other = s.clone();
    other.vertices[0].x += 1e-9;
    assert!(matches!(prepared_surface(&other, &r), Some(std::borrow::Cow::Owned(_))));
    // a surface meshed as it is has none
    let (_, r0) = mesh_surface(&s, &Seeds::default(), &UniformSize(0.25), &MeshOptions::default().with_narrow_tolerance(Some(0.0))).unwrap();
    assert!(r0.prepared.is_none());
}
