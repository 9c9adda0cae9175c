//! The triangles to pair: the domain triangulated at twice the quads' size, its boundary
//! points kept. The one switch to another triangle mesher (the advancing front, once it
//! lands) is [`triangulate`].
//!
//! - Stage: first, for [`super::mesh`] only.
//! - Inputs: a valid [`Domain`] and the quads' size `h(p)`.
//! - Output: a [`PlanarMesh`] of counter-clockwise triangles covering the domain exactly;
//!   domain point `i` is vertex `i`; every domain segment is one mesh edge (nothing is
//!   added on the boundary).
//!
//! How: the quadtree of the domain at size `2 h` gives its interior leaves (farther than
//! the clearance from every segment); their corners (a 2:1 graded square lattice, whose
//! squares pair into squares) are the seeds. The domain's points, its segments as
//! constraints and the seeds go into spade's CDT, which is refined to 25° without
//! splitting constraint edges (the band between the lattice and the boundary); the faces
//! spade finds inside the constraints (odd winding) are the triangles.

use super::Error;
use crate::core::cdt;
use crate::mesh::PlanarMesh;
use crate::mesh2d::domain::Domain;
use crate::mesh2d::quadtree::{build_tree, Params, QuadtreeError, Status};
use glam::DVec2;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

/// The quadtree's target over twice the size. Its leaves end in `(t/2, t]` for a target `t`:
/// at 1 the quads came out between half the size and the size (1.3 to 1.6 times gmsh's
/// Blossom count on the test regions at the same size); 1.2 brings them to gmsh's count
/// there, the median scaled Jacobian still at least gmsh's (`tools/bench_mesh2d_anchors.py`,
/// `docs/benchmarks.md`); from 1.25 the unit tests' star region jumps a tree level and
/// leaves 10.5 % of its triangles unpaired.
const TREE_FACTOR: f64 = 1.2;

/// Triangulates `domain` at twice the size `size`, its boundary points kept (see the
/// module docs).
///
/// # Errors
/// [`Error::Size`] for a bad size, [`Error::Triangulation`] when the tree or the CDT fails.
pub fn triangulate(domain: &Domain, size: &dyn Fn(DVec2) -> f64) -> Result<PlanarMesh, Error> {
    let double = |p: DVec2| 2.0 * TREE_FACTOR * size(p);
    let tree = build_tree(domain, &double, Params::default()).map_err(|e| match e {
        QuadtreeError::Size { x, y, size } => Error::Size { x, y, size: size / (2.0 * TREE_FACTOR) },
        other => Error::Triangulation(other.to_string()),
    })?;
    let mut seeds: Vec<(u32, u32)> = Vec::new();
    for i in tree.leaves() {
        let q = &tree.nodes[i as usize];
        if q.status == Status::Interior {
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                seeds.push(crate::mesh2d::quadtree::tree::lattice(q.level, q.x + dx, q.y + dy));
            }
        }
    }
    seeds.sort_unstable();
    seeds.dedup();
    let mut t: ConstrainedDelaunayTriangulation<Point2<f64>> = ConstrainedDelaunayTriangulation::new();
    let n = domain.points.len();
    let mut handles = Vec::with_capacity(n);
    for (i, &p) in domain.points.iter().enumerate() {
        let h = cdt::insert(&mut t, p, |q| q).map_err(|e| Error::Triangulation(format!("domain point {i}: {e}")))?;
        if h.index() != i {
            return Err(Error::Triangulation(format!("domain point {i} coincides with another after the coordinate guard")));
        }
        handles.push(h);
    }
    for (s, &[a, b]) in domain.segments.iter().enumerate() {
        if !cdt::constrain(&mut t, handles[a as usize], handles[b as usize]) {
            return Err(Error::Triangulation(format!("segment {s} crosses another")));
        }
    }
    if t.num_constraints() != domain.segments.len() {
        return Err(Error::Triangulation("a segment passes through a domain point".to_string()));
    }
    for &s in &seeds {
        let p = tree.point(s);
        cdt::insert(&mut t, p, |q| q).map_err(|e| Error::Triangulation(format!("seed ({}, {}): {e}", p.x, p.y)))?;
    }
    let added_limit = 4 * t.num_vertices() + 1000;
    let result = t.refine(cdt::quality_refinement(f64::NAN, added_limit));
    let mut outside = vec![false; t.num_all_faces()];
    for f in &result.excluded_faces {
        outside[f.index()] = true;
    }
    let mut remap: Vec<Option<u32>> = vec![None; t.num_vertices()];
    for (i, r) in remap.iter_mut().enumerate().take(n) {
        *r = Some(i as u32);
    }
    let mut vertices: Vec<DVec2> = domain.points.clone();
    let mut triangles = Vec::new();
    for f in t.inner_faces() {
        if outside[f.fix().index()] {
            continue;
        }
        let mut tri = [0u32; 3];
        for (k, v) in f.vertices().iter().enumerate() {
            let h = v.fix().index();
            tri[k] = *remap[h].get_or_insert_with(|| {
                let p = v.position();
                vertices.push(DVec2::new(p.x, p.y));
                (vertices.len() - 1) as u32
            });
        }
        triangles.push(tri);
    }
    let region = crate::core::RegionId(1);
    let mesh = PlanarMesh { vertices, triangle_tags: vec![region; triangles.len()], triangles, quads: Vec::new(), quad_tags: Vec::new(), region_names: Default::default() };
    let rel = (mesh.area() - domain.area()).abs() / domain.area();
    if rel > 1e-9 {
        return Err(Error::Triangulation(format!("the triangles cover {} of the domain's {}", mesh.area(), domain.area())));
    }
    Ok(mesh)
}
