//! Graded mode's last stage: the mesh coarsened inside by collapsing interior vertices onto a
//! neighbour, the boundary kept as it is.
//!
//! Stage: after the stencils and feature snapping of a graded octree mesh, before its
//! boundary is measured. Input: a valid [`TetMesh`] with its boundary triangles. Output: the
//! same mesh with fewer vertices and tets, and [`Coarsened`].
//!
//! The octree can coarsen only aligned blocks of cubes at least a cube away from the surface,
//! so along the surface it keeps a band of uniform cells two to three cubes deep, and the
//! transitions between levels; on thin walls that band is the whole mesh. A collapse works
//! at any vertex off the boundary: vertex `v` goes onto its neighbour `w`, the tets at edge
//! `vw` go, and the other tets at `v` take `w` in its place; where `w` is off the boundary
//! too, both may go onto their midpoint instead (`w` moves there; 5–15 % fewer tets on the
//! corpus at diagonal / 100 than onto `w` alone, for 1.7 times the time of this stage).
//!
//! # Invariants
//! - The boundary is the same: a vertex on a boundary triangle, on a face of one tet only,
//!   or at tets of two regions never moves nor goes, so every boundary triangle stays a face
//!   of the mesh, by the same vertices at the same positions (the same boundary resolution as
//!   the uniform mesh at the cell).
//! - A collapse is made only where every tet it makes or moves is positive by the exact
//!   [`orient3d`] and has its dihedral angles in [`FLOOR`] (feature snapping's, inside the
//!   paper's uniform bounds), and where the link condition holds (Dey, Edelsbrunner, Guha
//!   and Nekhayev 1999: the vertices and edges linked to both `v` and `w` are those linked to
//!   the edge `vw`). The new tets then fill the stars of `v` and `w` as the old ones did
//!   (their outer vertices stay): the mesh stays a valid triangulation of the same volume,
//!   every tet in one region.
//! - Of the collapses allowed, `v` takes the one whose new tets' worst angle, measured against
//!   the floor, is best (ties: the lowest index of `w`, onto `w` before the midpoint).
//! - Deterministic: passes go over the vertices in index order, a collapse made at once; a
//!   vertex is tried again in the next pass only where a tet at it or at a neighbour changed
//!   (what its try read), until a pass collapses nothing or after [`MAX_PASSES`] (a count,
//!   never a time). The vertices left keep their order.
//! - Parallel: a mesh of more than [`SLAB_VERTICES`] vertices is cut by vertex position into
//!   slabs across its longest axis, one per that many vertices (the cut depends on the mesh
//!   alone, never on the threads); each slab's tets are coarsened on their own, in parallel,
//!   a vertex of a tet across two slabs neither moving nor collapsed onto (its star is not
//!   all in the slab); then again with the slabs shifted by half a slab, for what was to be
//!   tried beside the first cut; last, serially over the whole mesh, what was to be tried
//!   beside the second. The same bytes for any number of threads (fandisk at about diagonal
//!   / 250, 1.5 million tets: this stage 6.6 s in one piece, 4.5 s in slabs on two cores,
//!   0.1 % more tets left).

use crate::core::ids::NONE;
use crate::core::predicates::orient3d;
use crate::mesh::TetMesh;
use crate::quality::tetrahedron::{dihedrals_of_extreme_cosines, tet_extreme_dihedral_cosines};
use glam::DVec3;
use rayon::prelude::*;
use serde::Serialize;

/// The dihedral angles (degrees) every tet a collapse makes must have.
pub const FLOOR: [f64; 2] = super::snap::FLOOR;

/// The most passes over the vertices (on the corpus, a pass after the third collapses under
/// 1 % of what the first did).
pub const MAX_PASSES: usize = 8;

/// What coarsening did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Coarsened {
    /// Interior vertices collapsed.
    pub vertices: usize,
    /// Tets removed.
    pub tets: usize,
    /// Passes made: those over the whole mesh, and before them, where the mesh was cut into
    /// slabs, in each round of slabs those of the slab that made the most.
    pub passes: usize,
}

impl std::ops::AddAssign for Coarsened {
    /// What two stages did, one after the other.
    fn add_assign(&mut self, o: Coarsened) {
        self.vertices += o.vertices;
        self.tets += o.tets;
        self.passes += o.passes;
    }
}

/// Vertices per slab, about, where the mesh is cut into slabs coarsened in parallel.
pub const SLAB_VERTICES: usize = 40_000;

/// Coarsens `mesh` inside; see the module docs.
pub fn coarsen(mesh: &mut TetMesh) -> Coarsened {
    coarsen_with(mesh, SLAB_VERTICES)
}

/// [`coarsen`] with slabs of about `slab_vertices` vertices.
fn coarsen_with(mesh: &mut TetMesh, slab_vertices: usize) -> Coarsened {
    let fixed = fixed_vertices(mesh);
    let n = mesh.vertices.len();
    let slabs = (n / slab_vertices.max(1)).clamp(1, 256);
    let mut stale: Vec<bool> = (0..n).map(|v| !fixed[v]).collect();
    let mut done = Coarsened::default();
    if slabs > 1 {
        // the slabs, then slabs shifted by half a slab for what lay at their borders
        for shift in [0.0, 0.5] {
            let d;
            (d, stale) = coarsen_slabs(mesh, &fixed, slabs, shift, &stale);
            done += d;
        }
    }
    // the whole mesh: what the slabs left (all of it, for one slab)
    done += run(mesh, &fixed, &vec![false; n], stale);
    if done.vertices > 0 {
        mesh.remove_unused_vertices();
    }
    done
}

/// Vertices that never move nor go: on a boundary triangle, on a face of one tet, or on a
/// face between two regions.
fn fixed_vertices(mesh: &TetMesh) -> Vec<bool> {
    let mut fixed = vec![false; mesh.vertices.len()];
    for tri in &mesh.boundary {
        for &v in tri {
            fixed[v as usize] = true;
        }
    }
    for f in mesh.faces() {
        let other_region = f.neighbor.is_some_and(|u| mesh.region_tags[u as usize] != mesh.region_tags[f.tet as usize]);
        if f.neighbor.is_none() || other_region {
            for v in f.vertices {
                fixed[v as usize] = true;
            }
        }
    }
    fixed
}

/// The mesh cut into `slabs` slabs across its longest axis by vertex position (so the cut
/// does not depend on the threads): each slab's tets, those whose four vertices lie in it,
/// coarsened on their own in parallel, where a vertex of a tet across two slabs (its star
/// is not all there) neither moves nor is collapsed onto; the results put back in slab order,
/// then the tets across slabs. Only the vertices `stale_in` are tried. Returns what was done
/// and the vertices to try again (in the shifted slabs, then on the whole mesh): those of
/// `stale_in` on a tet at such a vertex.
fn coarsen_slabs(mesh: &mut TetMesh, fixed: &[bool], slabs: usize, shift: f64, stale_in: &[bool]) -> (Coarsened, Vec<bool>) {
    let (lo, hi) = mesh.vertices.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(a, b), &p| (a.min(p), b.max(p)));
    let extent = hi - lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z { 0 } else if extent.y >= extent.z { 1 } else { 2 };
    let slab_of: Vec<u32> = mesh.vertices.iter().map(|p| (((p[axis] - lo[axis]) / extent[axis].max(f64::MIN_POSITIVE) * slabs as f64 + shift) as usize).min(slabs) as u32).collect();
    let slabs = slabs + 1;
    let n = mesh.vertices.len();
    let mut inside: Vec<Vec<u32>> = vec![Vec::new(); slabs];
    let mut across = Vec::new();
    let mut pinned = vec![false; n];
    for (t, tet) in mesh.tets.iter().enumerate() {
        let k = slab_of[tet[0] as usize];
        if tet.iter().all(|&v| slab_of[v as usize] == k) {
            inside[k as usize].push(t as u32);
        } else {
            across.push(t as u32);
            for &v in tet {
                pinned[v as usize] = true;
            }
        }
    }
    let mesh_ref = &*mesh;
    let results: Vec<(Vec<u32>, TetMesh, Coarsened)> = inside
        .par_iter()
        .map(|tets| {
            // the slab's vertices, in index order, and its tets
            let mut global: Vec<u32> = tets.iter().flat_map(|&t| mesh_ref.tets[t as usize]).collect();
            global.par_sort_unstable();
            global.dedup();
            let local = |v: u32| global.binary_search(&v).map_or(0, |i| i as u32);
            let mut sub = TetMesh {
                vertices: global.iter().map(|&v| mesh_ref.vertices[v as usize]).collect(),
                tets: tets.iter().map(|&t| mesh_ref.tets[t as usize].map(local)).collect(),
                region_tags: tets.iter().map(|&t| mesh_ref.region_tags[t as usize]).collect(),
                ..TetMesh::default()
            };
            let sub_fixed: Vec<bool> = global.iter().map(|&v| fixed[v as usize] || pinned[v as usize]).collect();
            let no_target: Vec<bool> = global.iter().map(|&v| pinned[v as usize]).collect();
            let stale = global.iter().zip(&sub_fixed).map(|(&v, &f)| !f && stale_in[v as usize]).collect();
            let done = run(&mut sub, &sub_fixed, &no_target, stale);
            (global, sub, done)
        })
        .collect();
    let mut done = Coarsened::default();
    let mut tets = Vec::with_capacity(mesh.tets.len());
    let mut regions = Vec::with_capacity(mesh.tets.len());
    for (global, sub, d) in &results {
        done.vertices += d.vertices;
        done.tets += d.tets;
        done.passes = done.passes.max(d.passes);
        for (l, &g) in global.iter().enumerate() {
            mesh.vertices[g as usize] = sub.vertices[l];
        }
        tets.extend(sub.tets.iter().map(|t| t.map(|v| global[v as usize])));
        regions.extend_from_slice(&sub.region_tags);
    }
    tets.extend(across.iter().map(|&t| mesh.tets[t as usize]));
    regions.extend(across.iter().map(|&t| mesh.region_tags[t as usize]));
    mesh.tets = tets;
    mesh.region_tags = regions;
    // to try again: what was to be tried at a vertex of a tet at a pinned vertex
    let mut stale = vec![false; n];
    for tet in mesh.tets.iter().filter(|t| t.iter().any(|&v| pinned[v as usize])) {
        for &v in tet {
            stale[v as usize] = !fixed[v as usize] && stale_in[v as usize];
        }
    }
    (done, stale)
}

/// The serial passes over `mesh` (see the module docs) from the vertices `stale`; `fixed`
/// vertices never move nor go, and nothing is collapsed onto a `no_target` one. Removes the
/// tets collapsed; the vertices stay (unused ones too).
fn run(mesh: &mut TetMesh, fixed: &[bool], no_target: &[bool], mut stale: Vec<bool>) -> Coarsened {
    let mut c = Collapser::new(mesh, fixed, no_target);
    let mut done = Coarsened::default();
    let n = mesh.vertices.len();
    let (mut nbrs, mut nbrs2, mut scratch) = (Vec::new(), Vec::new(), Scratch::default());
    while done.passes < MAX_PASSES && stale.contains(&true) {
        done.passes += 1;
        let before = done.vertices;
        for v in 0..n as u32 {
            if !stale[v as usize] || c.star[v as usize].is_empty() {
                continue;
            }
            stale[v as usize] = false;
            c.neighbours(mesh, v, &mut nbrs);
            let Some((w, q)) = c.best_target(mesh, v, &nbrs, &mut scratch) else { continue };
            // a try reads the tets at its vertex and at the vertex's neighbours: those of
            // every vertex within two of `v` change or may (and of `w`, where it moves)
            let moved = q != mesh.vertices[w as usize];
            if moved {
                c.neighbours(mesh, w, &mut nbrs2);
                nbrs.extend_from_slice(&nbrs2);
            }
            for &x in &nbrs {
                for &t in &c.star[x as usize] {
                    for y in mesh.tets[t as usize] {
                        stale[y as usize] = !c.fixed[y as usize];
                    }
                }
            }
            done.tets += c.collapse(mesh, v, w);
            mesh.vertices[w as usize] = q;
            done.vertices += 1;
        }
        if done.vertices == before {
            break;
        }
    }
    if done.tets > 0 {
        let mut keep = 0;
        for t in 0..mesh.tets.len() {
            if c.alive[t] {
                mesh.tets[keep] = mesh.tets[t];
                mesh.region_tags[keep] = mesh.region_tags[t];
                keep += 1;
            }
        }
        mesh.tets.truncate(keep);
        mesh.region_tags.truncate(keep);
    }
    done
}

/// The three vertices of `tet` but `v` (one of its four).
fn opposite(tet: [u32; 4], v: u32) -> [u32; 3] {
    let k = tet.iter().position(|&x| x == v).unwrap_or(3);
    [tet[(k + 1) % 4], tet[(k + 2) % 4], tet[(k + 3) % 4]]
}

/// The tets at each vertex, which tets are left, and which vertices stay.
struct Collapser<'a> {
    /// Per vertex: the slots of the tets at it.
    star: Vec<Vec<u32>>,
    alive: Vec<bool>,
    /// Vertices that never move nor go.
    fixed: &'a [bool],
    /// Vertices nothing is collapsed onto.
    no_target: &'a [bool],
}

/// Buffers of the link condition.
#[derive(Default)]
struct Scratch {
    /// Vertices and edges linked to the edge `vw`.
    edge_vertices: Vec<u32>,
    edge_edges: Vec<[u32; 2]>,
    /// Neighbours of `w`, and edges linked to `w`.
    w_nbrs: Vec<u32>,
    w_edges: Vec<[u32; 2]>,
}

impl<'a> Collapser<'a> {
    fn new(mesh: &TetMesh, fixed: &'a [bool], no_target: &'a [bool]) -> Collapser<'a> {
        let mut star = vec![Vec::new(); mesh.vertices.len()];
        for (t, tet) in mesh.tets.iter().enumerate() {
            for &v in tet {
                star[v as usize].push(t as u32);
            }
        }
        Collapser { star, alive: vec![true; mesh.tets.len()], fixed, no_target }
    }

    /// The vertices sharing a tet with `v`, sorted.
    fn neighbours(&self, mesh: &TetMesh, v: u32, out: &mut Vec<u32>) {
        out.clear();
        for &t in &self.star[v as usize] {
            out.extend(mesh.tets[t as usize].into_iter().filter(|&x| x != v));
        }
        out.sort_unstable();
        out.dedup();
    }

    /// The neighbour `v` goes onto and where `w` then lies, if any collapse may be made (see the
    /// module docs).
    fn best_target(&self, mesh: &TetMesh, v: u32, nbrs: &[u32], scratch: &mut Scratch) -> Option<(u32, DVec3)> {
        // a candidate's score: its new tets' extreme angles against the floor at both ends,
        // `min(θ_min / FLOOR[0], (180° − θ_max) / (180° − FLOOR[1]))`, at least 1 within it;
        // the cosines (the angle is non-decreasing in them) folded over its tets, a candidate
        // given up once they pass what it needs (with a margin: the angles decide)
        let mut best: Option<(f64, u32, DVec3)> = None;
        let thresholds = |need: f64| {
            let lo = -(FLOOR[0] * need).to_radians().cos() - 1e-12;
            let hi = -(180.0 - (180.0 - FLOOR[1]) * need).to_radians().cos() + 1e-12;
            (lo, hi)
        };
        let (mut t_lo, mut t_hi) = thresholds(1.0);
        let mut hint = NONE;
        for &w in nbrs.iter().filter(|&&w| !self.no_target[w as usize]) {
            // onto `w`, and where `w` may move too, both onto their midpoint
            for at_mid in [false, true] {
                if at_mid && self.fixed[w as usize] {
                    continue;
                }
                let q = if at_mid { 0.5 * (mesh.vertices[v as usize] + mesh.vertices[w as usize]) } else { mesh.vertices[w as usize] };
                let Some((c_lo, c_hi)) = self.fold(mesh, v, w, q, at_mid, (t_lo, t_hi), &mut hint) else { continue };
                let (lo, hi) = dihedrals_of_extreme_cosines(c_lo, c_hi);
                let score = (lo / FLOOR[0]).min((180.0 - hi) / (180.0 - FLOOR[1]));
                if lo < FLOOR[0] || hi > FLOOR[1] || best.is_some_and(|(b, _, _)| score <= b) {
                    continue;
                }
                if self.link_condition(mesh, v, w, nbrs, scratch) {
                    best = Some((score, w, q));
                    (t_lo, t_hi) = thresholds(score);
                }
            }
        }
        best.map(|(_, w, q)| (w, q))
    }

    /// The extreme cosines of the tets `v` onto `w` at `q` makes (with `moved`, also those at
    /// `w` moved to `q`), or `None` where one is not positive or they pass `limits`. `hint`:
    /// the slot of the tet at `v` that failed last ([`NONE`]: none), judged first, and set
    /// to the one that fails (fandisk at about diagonal / 250: this stage 12 % faster).
    fn fold(&self, mesh: &TetMesh, v: u32, w: u32, q: DVec3, moved: bool, limits: (f64, f64), hint: &mut u32) -> Option<(f64, f64)> {
        let (mut c_lo, mut c_hi) = (f64::INFINITY, f64::NEG_INFINITY);
        // one tet judged: whether it passes, its cosines folded in
        let mut judge = |tet: [u32; 4], a: u32| {
            let p = tet.map(|x| if x == a { q } else { mesh.vertices[x as usize] });
            if !orient3d(p[0], p[1], p[2], p[3]).is_positive() {
                return false;
            }
            let Some((lo, hi)) = tet_extreme_dihedral_cosines(&p) else { return false };
            (c_lo, c_hi) = (c_lo.min(lo), c_hi.max(hi));
            c_lo >= limits.0 && c_hi <= limits.1
        };
        // the tet of `v`'s star that failed the last candidate first: it fails most others
        // (the order judged changes nothing but the time: every tet must pass, and the
        // extremes are folded)
        let first = *hint;
        if first != NONE {
            let tet = mesh.tets[first as usize];
            if !tet.contains(&w) && !judge(tet, v) {
                return None;
            }
        }
        for &t in &self.star[v as usize] {
            let tet = mesh.tets[t as usize];
            if t != first && !tet.contains(&w) && !judge(tet, v) {
                *hint = t;
                return None;
            }
        }
        if moved {
            for &t in &self.star[w as usize] {
                let tet = mesh.tets[t as usize];
                if !tet.contains(&v) && !judge(tet, w) {
                    return None;
                }
            }
        }
        // no new tet: not at an interior vertex
        (c_lo <= c_hi).then_some((c_lo, c_hi))
    }

    /// Whether the vertices and edges linked to both `v` and `w` are those linked to the edge
    /// `vw` (`nbrs`: the neighbours of `v`).
    fn link_condition(&self, mesh: &TetMesh, v: u32, w: u32, nbrs: &[u32], s: &mut Scratch) -> bool {
        let sorted = |a: u32, b: u32| if a < b { [a, b] } else { [b, a] };
        s.edge_vertices.clear();
        s.edge_edges.clear();
        for &t in &self.star[v as usize] {
            let tet = mesh.tets[t as usize];
            if tet.contains(&w) {
                let mut o = tet.into_iter().filter(|&x| x != v && x != w);
                if let (Some(a), Some(b)) = (o.next(), o.next()) {
                    s.edge_vertices.extend([a, b]);
                    s.edge_edges.push(sorted(a, b));
                }
            }
        }
        s.edge_vertices.sort_unstable();
        s.edge_vertices.dedup();
        s.edge_edges.sort_unstable();
        s.w_nbrs.clear();
        s.w_edges.clear();
        for &t in &self.star[w as usize] {
            let tet = mesh.tets[t as usize];
            s.w_nbrs.extend(tet.into_iter().filter(|&x| x != w));
            if !tet.contains(&v) {
                let f = opposite(tet, w);
                s.w_edges.extend([sorted(f[0], f[1]), sorted(f[1], f[2]), sorted(f[0], f[2])]);
            }
        }
        s.w_nbrs.sort_unstable();
        s.w_nbrs.dedup();
        s.w_edges.sort_unstable();
        s.w_edges.dedup();
        // vertices: the common neighbours (but `v` and `w`) are the edge's
        let mut common = nbrs.iter().copied().filter(|&x| x != w && s.w_nbrs.binary_search(&x).is_ok());
        if !common.by_ref().eq(s.edge_vertices.iter().copied()) {
            return false;
        }
        // edges: an edge linked to `v` by a tet without `w` and linked to `w` is the edge's
        for &t in &self.star[v as usize] {
            let tet = mesh.tets[t as usize];
            if tet.contains(&w) {
                continue;
            }
            let f = opposite(tet, v);
            for e in [sorted(f[0], f[1]), sorted(f[1], f[2]), sorted(f[0], f[2])] {
                if s.w_edges.binary_search(&e).is_ok() && s.edge_edges.binary_search(&e).is_err() {
                    return false;
                }
            }
        }
        true
    }

    /// Collapses `v` onto `w`; returns the tets removed.
    fn collapse(&mut self, mesh: &mut TetMesh, v: u32, w: u32) -> usize {
        let star = std::mem::take(&mut self.star[v as usize]);
        let mut removed = 0;
        for t in star {
            let tet = &mut mesh.tets[t as usize];
            if tet.contains(&w) {
                self.alive[t as usize] = false;
                removed += 1;
                for x in *tet {
                    if x != v {
                        let s = &mut self.star[x as usize];
                        if let Some(k) = s.iter().position(|&u| u == t) {
                            s.swap_remove(k);
                        }
                    }
                }
            } else {
                for x in tet.iter_mut() {
                    if *x == v {
                        *x = w;
                    }
                }
                self.star[w as usize].push(t);
            }
        }
        removed
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::RegionId;
    use crate::mesh::shapes;
    use crate::quality::tetrahedron::{tet_min_max_dihedral, tet_volume};
    use glam::DVec3;

    /// The faces of `m` between two tets of different regions, or of one tet, by their
    /// corners' bits and the region (or regions) beside them, sorted.
    fn constrained(m: &TetMesh) -> Vec<([[u64; 3]; 3], u32, Option<u32>)> {
        let mut out: Vec<_> = m
            .faces()
            .iter()
            .filter(|f| f.neighbor.is_none_or(|u| m.region_tags[u as usize] != m.region_tags[f.tet as usize]))
            .map(|f| {
                let mut c = f.vertices.map(|v| m.vertices[v as usize].to_array().map(f64::to_bits));
                c.sort_unstable();
                let mut r = [Some(m.region_tags[f.tet as usize].0), f.neighbor.map(|u| m.region_tags[u as usize].0)];
                r.sort_unstable();
                (c, r[1].unwrap_or(0), r[0])
            })
            .collect();
        out.sort_unstable();
        out
    }

    fn region_volumes(m: &TetMesh) -> [f64; 3] {
        let mut v = [0.0; 3];
        for (t, r) in m.tets.iter().zip(&m.region_tags) {
            v[r.0 as usize] += tet_volume(&t.map(|x| m.vertices[x as usize]));
        }
        v
    }

    /// A jittered cube of two regions: coarsening keeps every face on the boundary and
    /// between the regions (the same corners, bit for bit), each region's volume and the
    /// regions of the tets, leaves a valid mesh whose new tets lie within the floor, removes
    /// most interior vertices, and gives the same mesh again; in one piece, and cut into
    /// slabs coarsened in parallel (the same mesh for any number of threads).
    #[test]
    fn keeps_the_boundary_and_the_interfaces_and_removes_most_interior_vertices() {
        for slab_vertices in [SLAB_VERTICES, 150] {
            let run = |threads: usize| {
                let mut m = two_regions();
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let done = pool.install(|| coarsen_with(&mut m, slab_vertices));
                (m, done)
            };
            let (m, done) = run(2);
            check(&two_regions(), &m, done);
            assert_eq!(run(1), (m.clone(), done));
            assert_eq!(run(3), (m, done));
        }
    }

    /// A jittered 10 × 10 × 10 Kuhn cube, the tets past a slanted plane in region 2.
    fn two_regions() -> TetMesh {
        let mut m = shapes::kuhn_cube(10, 0.2, 7);
        for t in 0..m.tets.len() {
            let c = m.tets[t].iter().map(|&v| m.vertices[v as usize]).sum::<DVec3>() / 4.0;
            if c.x + 0.3 * c.y > 0.61 {
                m.region_tags[t] = RegionId(2);
            }
        }
        m
    }

    /// The invariants of coarsening `before` into `m`, `done`.
    fn check(before: &TetMesh, m: &TetMesh, done: Coarsened) {
        let old: std::collections::HashSet<[[u64; 3]; 4]> = before.tets.iter().map(|t| key(before, t)).collect();
        m.validate().unwrap();
        assert_eq!(constrained(m), constrained(before));
        let (a, b) = (region_volumes(m), region_volumes(before));
        for r in 1..3 {
            assert!((a[r] - b[r]).abs() < 1e-12, "{a:?} {b:?}");
        }
        assert_eq!(done.tets, before.tets.len() - m.tets.len());
        assert_eq!(done.vertices, before.vertices.len() - m.vertices.len());
        let interior = 9usize.pow(3);
        assert!(2 * done.vertices > interior, "{done:?} of {interior}");
        for t in &m.tets {
            if !old.contains(&key(m, t)) {
                let (lo, hi) = tet_min_max_dihedral(&t.map(|v| m.vertices[v as usize]));
                assert!(lo >= FLOOR[0] && hi <= FLOOR[1], "{lo} {hi}");
            }
        }
    }

    fn key(m: &TetMesh, t: &[u32; 4]) -> [[u64; 3]; 4] {
        let mut c = t.map(|v| m.vertices[v as usize].to_array().map(f64::to_bits));
        c.sort_unstable();
        c
    }

    /// Three tets around the edge `ab`, `(v, w, a, b)`, `(v, a, b, c)` and `(w, a, b, c)`:
    /// `c` is linked to both `v` and `w` but not to the edge `vw`, and `v` onto `w` would
    /// make `(v, a, b, c)` a second `(w, a, b, c)`; the link condition refuses it. With the
    /// third tet gone, it holds.
    #[test]
    fn the_link_condition_refuses_a_collapse_that_would_double_a_tet() {
        let p = [DVec3::new(0.0, 0.0, 1.0), DVec3::new(0.0, 0.0, -1.0), DVec3::new(1.0, 0.0, 0.0), DVec3::new(-1.0, 1.0, 0.0), DVec3::new(-1.0, -1.0, 0.0)];
        let [a, b, v, w, c] = [0u32, 1, 2, 3, 4];
        let tets = vec![[v, w, a, b], [v, a, b, c], [w, a, b, c]];
        let mesh = TetMesh { vertices: p.to_vec(), region_tags: vec![RegionId(1); tets.len()], tets, ..TetMesh::default() };
        let free = vec![false; 5];
        let coll = Collapser::new(&mesh, &free, &free);
        let mut nbrs = Vec::new();
        coll.neighbours(&mesh, v, &mut nbrs);
        assert!(!coll.link_condition(&mesh, v, w, &nbrs, &mut Scratch::default()));
        let two = TetMesh { tets: mesh.tets[..2].to_vec(), region_tags: vec![RegionId(1); 2], ..mesh.clone() };
        let coll = Collapser::new(&two, &free, &free);
        coll.neighbours(&two, v, &mut nbrs);
        assert!(coll.link_condition(&two, v, w, &nbrs, &mut Scratch::default()));
    }
}
