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
    let mut tags = m.boundary_tags.clone();
    tags.sort();
    tags.dedup();
    assert_eq!(tags, (1..=6).map(FaceId).collect::<Vec<_>>());
    let q = crate::quality::tet_mesh_quality(&m);
    assert!(q.max_radius_edge <= 1.5 + 1e-9 || r.boundary_steiner_points > 0, "{}", q.max_radius_edge);
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
fn open_and_crossing_surfaces_are_refused() {
    let mut s = cube(1);
    s.triangles.pop();
    s.face_tags.pop();
    let e = mesh_surface(&s, &Seeds::default(), &UniformSize(1.0), &MeshOptions::default()).unwrap_err();
    assert!(matches!(e, MeshingError::Open { count: 3, .. }), "{e}");
    let mut two = cube(1);
    let mut b = cube(1);
    for v in &mut b.vertices {
        *v += DVec3::splat(0.5);
    }
    two.append(&b);
    let e = mesh_surface(&two, &Seeds::default(), &UniformSize(1.0), &MeshOptions::default()).unwrap_err();
    assert!(matches!(e, MeshingError::SelfIntersecting { .. }), "{e}");
}
