//! The boundary band: boundary quadrants cut by the domain and triangulated conformingly.
//!
//! - Stage: fourth, after the templates (which fixed the interface).
//! - Inputs: the balanced [`Quadtree`], the [`Domain`], the vertex list holding the
//!   templates' lattice points, and the interface edges between interior and boundary leaves.
//! - Output: counter-clockwise triangles covering exactly the domain minus the interior
//!   leaves, and for every input segment the chain of vertex ids it was cut into.
//! - Invariants: polygon vertices are kept exactly; every input segment is a union of mesh
//!   edges (its pieces are constraint edges, never split after they are made); interface
//!   edges are constraint edges too, so the band meets the templates edge to edge.
//!
//! How (after Yerry and Shephard's cut boundary quadrants, with a constrained Delaunay
//! triangulation of the cut region instead of case tables):
//! 1. each input segment is cut into pieces about the size of the boundary leaves along it
//!    (the integral of `1 / size` along the segment, rounded);
//! 2. the corners and centres of boundary leaves farther than `keep · size` from every
//!    segment are kept, those closer are removed (the lecture's "remove lattice points close
//!    to the boundary", so that no sliver joins a lattice point to the boundary);
//! 3. everything goes into the project's CDT driver (`core::cdt`), segment pieces and
//!    interface edges as constraints, then spade's 25° refinement, constraint edges kept
//!    and outer faces excluded;
//!    then pieces of input segments encroached by the circumcentre of a triangle under
//!    [`SPLIT_BELOW_DEG`] (or an edge of one) are halved and step 3 repeated, a few rounds
//!    (spade would split them itself, but also the interface, which must stay whole);
//! 4. the faces an odd number of constraints away from the convex hull's outside are the
//!    band (inside the domain, outside the interior leaves).

use crate::mesh2d::domain::{point_segment_distance, Domain};
use super::tree::{lattice, Quadtree, Status, MAX_LEVEL};
use super::vertices::Vertices;
use super::QuadtreeError;
use crate::core::cdt;
use crate::core::ids::NONE;
use glam::DVec2;
use spade::{ConstrainedDelaunayTriangulation, HasPosition, Point2, Triangulation};
use std::collections::BTreeMap;

/// A vertex of the band's triangulation: its position and its id in the mesh (`NONE` for
/// points the refinement added).
#[derive(Clone, Copy, Debug)]
struct V {
    p: Point2<f64>,
    id: u32,
}

impl From<Point2<f64>> for V {
    fn from(p: Point2<f64>) -> V {
        V { p, id: NONE }
    }
}

impl HasPosition for V {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.p
    }
}

/// The band's triangles and the input segments' pieces.
#[derive(Clone, Debug, Default)]
pub struct Band {
    /// Counter-clockwise triangles.
    pub triangles: Vec<[u32; 3]>,
    /// Per input segment, its vertex ids from start to end.
    pub chains: Vec<Vec<u32>>,
    /// Points the quality refinement added.
    pub refinement_points: usize,
}

/// Band parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BandParams {
    /// Lattice points of boundary leaves closer than `keep · size` to a segment are removed.
    pub keep: f64,
    /// Whether spade's quality refinement (25°, constraint edges kept) runs on the band.
    pub refine: bool,
    /// Rounds of halving the segment pieces that bad triangles encroach.
    pub split_rounds: usize,
    /// Keep the domain's segments whole: no cut by the leaf size, no halving (a CAD face
    /// whose boundary points are shared with its neighbours).
    pub keep_boundary: bool,
}

impl Default for BandParams {
    fn default() -> BandParams {
        BandParams { keep: 0.35, refine: true, split_rounds: 6, keep_boundary: false }
    }
}

/// The leaf size at `p` (the leaf holding it; a point on a side takes either, by the fixed
/// descent).
fn leaf_size_at(tree: &Quadtree, p: DVec2) -> f64 {
    let n = (1u64 << MAX_LEVEL) as f64;
    let t = (p - tree.origin) / tree.side * n;
    let ix = t.x.clamp(0.0, n - 1.0) as u32;
    let iy = t.y.clamp(0.0, n - 1.0) as u32;
    let leaf = tree.locate(MAX_LEVEL, ix, iy);
    tree.size(tree.nodes[leaf as usize].level)
}

/// Parameters in `(0, 1)` cutting segment `a b` into pieces about the local leaf size.
fn cuts(tree: &Quadtree, a: DVec2, b: DVec2) -> Vec<f64> {
    let len = (b - a).length();
    // piecewise constant 1/size along the segment, stepping by the local size
    let mut knots = vec![(0.0f64, 0.0f64)];
    let mut t = 0.0;
    let mut integral = 0.0;
    while t < 1.0 {
        let s = leaf_size_at(tree, a + t * (b - a)).max(len * 1e-9);
        let dt = (s / len).min(1.0 - t);
        t += dt;
        integral += dt * len / s;
        knots.push((t.min(1.0), integral));
    }
    let n = integral.round().max(1.0) as usize;
    let mut out = Vec::with_capacity(n.saturating_sub(1));
    let mut k = 1;
    for j in 1..n {
        let target = integral * j as f64 / n as f64;
        while k + 1 < knots.len() && knots[k].1 < target {
            k += 1;
        }
        let (t0, i0) = knots[k - 1];
        let (t1, i1) = knots[k];
        let u = if i1 > i0 { (target - i0) / (i1 - i0) } else { 0.0 };
        out.push(t0 + u * (t1 - t0));
    }
    out
}

/// Triangulates the band (see the module docs).
///
/// # Errors
/// [`QuadtreeError::Band`] when a point or constraint cannot be placed (coordinates beyond
/// the driver's guard, or coincident or crossing pieces: an input the checks let through).
pub fn build(tree: &Quadtree, domain: &Domain, vertices: &mut Vertices, interface: &[[u32; 2]], params: BandParams) -> Result<Band, QuadtreeError> {
    // 1. polygon vertices and segment pieces
    let point_ids: Vec<u32> = domain.points.iter().map(|&p| vertices.push(p)).collect();
    let mut chains = Vec::with_capacity(domain.segments.len());
    for s in 0..domain.segments.len() {
        let [ia, ib] = domain.segments[s];
        let (a, b) = domain.ends(s);
        let mut chain = vec![point_ids[ia as usize]];
        if !params.keep_boundary {
            for t in cuts(tree, a, b) {
                chain.push(vertices.push(a + t * (b - a)));
            }
        }
        chain.push(point_ids[ib as usize]);
        chains.push(chain);
    }
    // 2. lattice points of boundary leaves, kept or removed by their clearance
    let mut keep: BTreeMap<(u32, u32), bool> = BTreeMap::new();
    for i in tree.leaves() {
        let q = &tree.nodes[i as usize];
        if q.status != Status::Boundary {
            continue;
        }
        let s = tree.size(q.level);
        let fine = q.level + 1;
        for (dx, dy) in [(0u32, 0u32), (2, 0), (2, 2), (0, 2), (1, 1)] {
            let key = lattice(fine, 2 * q.x + dx, 2 * q.y + dy);
            let p = tree.point(key);
            let clear = q.near.iter().all(|&seg| {
                let (a, b) = domain.ends(seg as usize);
                point_segment_distance(p, a, b) >= params.keep * s
            });
            let e = keep.entry(key).or_insert(true);
            *e = *e && clear;
        }
    }
    let mut lattice_ids = Vec::new();
    for (key, kept) in keep {
        if kept && vertices.lattice_id(key).is_none() {
            lattice_ids.push(vertices.lattice(tree, key));
        }
    }
    // 3. triangulate; pieces of input segments that bad triangles encroach are halved and
    // the band triangulated again (Ruppert's segment splitting, which spade may not do here
    // because the interface edges must stay whole)
    let mut round = 0;
    loop {
        let (cdt, refinement_points) = triangulate(vertices, &chains, interface, &lattice_ids, params)?;
        let parity = parity(&cdt)?;
        let split = if round < params.split_rounds && !params.keep_boundary { encroached_pieces(&cdt, &parity, vertices, &chains) } else { Vec::new() };
        if split.is_empty() {
            let triangles = extract(&cdt, &parity, vertices);
            return Ok(Band { triangles, chains, refinement_points });
        }
        for (s, k) in split.into_iter().rev() {
            let chain = &mut chains[s];
            let m = 0.5 * (vertices.positions[chain[k] as usize] + vertices.positions[chain[k + 1] as usize]);
            let id = vertices.push(m);
            chain.insert(k + 1, id);
        }
        round += 1;
    }
}

/// The CDT of the band's points with the pieces and the interface as constraints, refined;
/// with the number of points the refinement added.
fn triangulate(vertices: &Vertices, chains: &[Vec<u32>], interface: &[[u32; 2]], lattice_ids: &[u32], params: BandParams) -> Result<(ConstrainedDelaunayTriangulation<V>, usize), QuadtreeError> {
    let mut cdt: ConstrainedDelaunayTriangulation<V> = ConstrainedDelaunayTriangulation::new();
    let mut handles: BTreeMap<u32, spade::handles::FixedVertexHandle> = BTreeMap::new();
    let mut put = |cdt: &mut ConstrainedDelaunayTriangulation<V>, id: u32| -> Result<(), QuadtreeError> {
        if handles.contains_key(&id) {
            return Ok(());
        }
        let p = vertices.positions[id as usize];
        let before = cdt.num_vertices();
        let h = cdt::insert(cdt, p, |q| V { p: q, id }).map_err(|e| QuadtreeError::Band(format!("point ({}, {}): {e}", p.x, p.y)))?;
        if cdt.num_vertices() == before {
            return Err(QuadtreeError::Band(format!("point ({}, {}) coincides with another", p.x, p.y)));
        }
        handles.insert(id, h);
        Ok(())
    };
    for &id in chains.iter().flatten().chain(interface.iter().flatten()).chain(lattice_ids) {
        put(&mut cdt, id)?;
    }
    for (s, chain) in chains.iter().enumerate() {
        for w in chain.windows(2) {
            if !cdt::constrain(&mut cdt, handles[&w[0]], handles[&w[1]]) {
                return Err(QuadtreeError::Band(format!("a piece of boundary segment {s} crosses another constraint")));
            }
        }
    }
    for e in interface {
        if !cdt::constrain(&mut cdt, handles[&e[0]], handles[&e[1]]) {
            return Err(QuadtreeError::Band(format!("interface edge {} {} crosses another constraint", e[0], e[1])));
        }
    }
    let before = cdt.num_vertices();
    if params.refine {
        cdt.refine(cdt::quality_refinement(f64::NAN, 4 * before + 1000));
    }
    let added = cdt.num_vertices() - before;
    Ok((cdt, added))
}

/// The band's triangles (faces of odd parity), new points numbered in face order.
fn extract(cdt: &ConstrainedDelaunayTriangulation<V>, parity: &[Option<bool>], vertices: &mut Vertices) -> Vec<[u32; 3]> {
    let mut ids: Vec<u32> = cdt.vertices().map(|v| v.data().id).collect();
    let mut triangles = Vec::new();
    for f in cdt.inner_faces() {
        if parity[f.fix().index()] != Some(true) {
            continue;
        }
        let mut tri = [0u32; 3];
        for (k, v) in f.vertices().iter().enumerate() {
            let h = v.fix().index();
            if ids[h] == NONE {
                let p = v.position();
                ids[h] = vertices.push(DVec2::new(p.x, p.y));
            }
            tri[k] = ids[h];
        }
        triangles.push(tri);
    }
    triangles
}

/// Pieces `(segment, index in its chain)` to halve: those whose diametral circle holds the
/// circumcentre of a band triangle with an angle under [`SPLIT_BELOW_DEG`] (Ruppert's
/// encroachment rule; sorted, deduplicated).
fn encroached_pieces(cdt: &ConstrainedDelaunayTriangulation<V>, parity: &[Option<bool>], vertices: &Vertices, chains: &[Vec<u32>]) -> Vec<(usize, usize)> {
    let mut centres = Vec::new();
    for f in cdt.inner_faces() {
        if parity[f.fix().index()] != Some(true) {
            continue;
        }
        let p = f.vertices().map(|v| DVec2::new(v.position().x, v.position().y));
        let a = super::check::triangle_angles(p);
        if a.iter().cloned().fold(f64::INFINITY, f64::min) < SPLIT_BELOW_DEG {
            centres.push(circumcentre(p));
        }
    }
    let mut out = Vec::new();
    if centres.is_empty() {
        return out;
    }
    for (s, chain) in chains.iter().enumerate() {
        for k in 0..chain.len() - 1 {
            let (u, w) = (vertices.positions[chain[k] as usize], vertices.positions[chain[k + 1] as usize]);
            let (m, r2) = (0.5 * (u + w), 0.25 * (w - u).length_squared());
            if centres.iter().any(|c| (*c - m).length_squared() < r2) {
                out.push((s, k));
            }
        }
    }
    out
}

/// Band triangles with an angle under this many degrees get their encroached pieces split.
pub const SPLIT_BELOW_DEG: f64 = 20.0;

/// The circumcentre of a triangle.
fn circumcentre(p: [DVec2; 3]) -> DVec2 {
    let (b, c) = (p[1] - p[0], p[2] - p[0]);
    let d = 2.0 * b.perp_dot(c);
    let (b2, c2) = (b.length_squared(), c.length_squared());
    p[0] + DVec2::new(c.y * b2 - b.y * c2, b.x * c2 - c.x * b2) / d
}

/// Per face index: `Some(true)` when an odd number of constraint edges separates it from
/// the outside of the convex hull (a breadth-first search over face adjacency).
///
/// # Errors
/// [`QuadtreeError::Band`] if two paths give a face different parities (constraints that do
/// not close).
fn parity(cdt: &ConstrainedDelaunayTriangulation<V>) -> Result<Vec<Option<bool>>, QuadtreeError> {
    let mut par: Vec<Option<bool>> = vec![None; cdt.num_all_faces()];
    let mut stack = Vec::new();
    let set = |par: &mut Vec<Option<bool>>, stack: &mut Vec<_>, k: usize, p: bool| -> Result<(), QuadtreeError> {
        match par[k] {
            None => {
                par[k] = Some(p);
                stack.push(k);
                Ok(())
            }
            Some(q) if q == p => Ok(()),
            Some(_) => Err(QuadtreeError::Band("the constraints do not enclose the band consistently".to_string())),
        }
    };
    for e in cdt.convex_hull() {
        if let Some(inner) = e.rev().face().as_inner() {
            set(&mut par, &mut stack, inner.fix().index(), e.is_constraint_edge())?;
        }
    }
    let faces: Vec<_> = cdt.fixed_inner_faces().collect();
    let mut by_index = vec![usize::MAX; par.len()];
    for (k, f) in faces.iter().enumerate() {
        by_index[f.index()] = k;
    }
    while let Some(k) = stack.pop() {
        let f = cdt.face(faces[by_index[k]]);
        let p = par[k].unwrap_or(false);
        for e in f.adjacent_edges() {
            let Some(nb) = e.rev().face().as_inner() else { continue };
            set(&mut par, &mut stack, nb.fix().index(), p ^ e.is_constraint_edge())?;
        }
    }
    Ok(par)
}
