//! Winding numbers of a closed surface at the lattice vertices, by counting crossings along
//! the lattice's rows: exact integers at a fraction of the cost of summing solid angles.
//!
//! Stage: the octree mesher's inside/outside oracle, where the surface is a closed 2-cycle.
//! Input: the [`Lattice`], the [`Winding`] oracle of the surface. Output: the winding number
//! of every lattice vertex (`None` for a surface that is not a cycle).
//!
//! # Invariants
//! - A surface is a *cycle* when every edge is used as often in one direction as in the
//!   other (closed, consistently oriented; shells may meet and cross). Its winding number is
//!   then an integer, 0 outside its box, and goes up by one across a triangle from its front
//!   to its back.
//! - A row is the lattice vertices with the same `y` and `z` (corners, or centres); its
//!   first vertex lies in the lattice's margin, outside the surface's box. Each triangle the
//!   row's segment crosses is found and placed between two vertices by exact predicates
//!   (the triangle's plane against the vertices, monotone along the row), and the winding
//!   number of each vertex is the sum of the jumps before it. The sum is the same integer
//!   whatever the order, so the result does not depend on the thread count.
//! - A row whose segment meets a triangle's edge or vertex, lies in a triangle's plane, or
//!   has a vertex on a triangle's plane where it crosses it (a vertex on the surface) is
//!   *degenerate*: its vertices are evaluated by the winding number's sum instead (the
//!   caller's `fallback`), as for a surface that is not a cycle.

use super::lattice::Lattice;
use super::winding::Winding;
use crate::mesh::TriSurface;
use glam::DVec3;
use rayon::prelude::*;

/// True when every edge of `s` is used as often in each direction: a closed, consistently
/// oriented surface (see the module docs).
pub fn is_cycle(s: &TriSurface) -> bool {
    if s.triangles.is_empty() {
        return false;
    }
    let mut edges: Vec<(u32, u32, i32)> = Vec::with_capacity(3 * s.triangles.len());
    for t in &s.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.push(if a < b { (a, b, 1) } else { (b, a, -1) });
        }
    }
    edges.par_sort_unstable();
    let mut i = 0;
    while i < edges.len() {
        let mut sum = 0;
        let mut j = i;
        while j < edges.len() && (edges[j].0, edges[j].1) == (edges[i].0, edges[i].1) {
            sum += edges[j].2;
            j += 1;
        }
        if sum != 0 {
            return false;
        }
        i = j;
    }
    true
}

/// The winding number at every lattice vertex of a cycle's lattice, row by row; degenerate
/// rows through `fallback(vertex)`. See the module docs.
pub fn winding_by_rows(lattice: &Lattice, oracle: &Winding, fallback: &(dyn Fn(u32) -> f64 + Sync)) -> Vec<f64> {
    let mut w = vec![0.0; lattice.num_vertices()];
    let nc = lattice.num_corners();
    let (corners, centres) = w.split_at_mut(nc);
    let corner_row = lattice.n[0] as usize + 1;
    let centre_row = lattice.n[0] as usize;
    corners.par_chunks_mut(corner_row).enumerate().for_each(|(r, out)| row(lattice, oracle, (r * corner_row) as u32, out, fallback));
    centres.par_chunks_mut(centre_row).enumerate().for_each(|(r, out)| row(lattice, oracle, (nc + r * centre_row) as u32, out, fallback));
    w
}

/// Fills `out` with the winding numbers of the row of vertices `first..first + out.len()`.
fn row(lattice: &Lattice, oracle: &Winding, first: u32, out: &mut [f64], fallback: &(dyn Fn(u32) -> f64 + Sync)) {
    let points: Vec<DVec3> = (0..out.len()).map(|k| lattice.position(first + k as u32)).collect();
    match oracle.along_row(&points) {
        Some(w) => out.iter_mut().zip(w).for_each(|(o, w)| *o = w as f64),
        None => fill_fallback(first, out, fallback),
    }
}

fn fill_fallback(first: u32, out: &mut [f64], fallback: &(dyn Fn(u32) -> f64 + Sync)) {
    for (k, o) in out.iter_mut().enumerate() {
        *o = fallback(first + k as u32);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a sphere and a cube with a cube-shaped void, the rows give the winding number's
    /// own integers at every lattice vertex.
    #[test]
    fn rows_agree_with_the_solid_angles() {
        let mut sphere = super::super::tests::cube_surface(8);
        for p in &mut sphere.vertices {
            *p = (*p - DVec3::splat(0.5)).normalize();
        }
        let mut void = super::super::tests::cube_surface(2);
        for p in &mut void.vertices {
            *p = (*p - DVec3::splat(0.5)) * 0.6;
        }
        for t in &mut void.triangles {
            t.swap(1, 2);
        }
        let mut hollow = sphere.clone();
        let off = hollow.vertices.len() as u32;
        hollow.vertices.extend(&void.vertices);
        hollow.triangles.extend(void.triangles.iter().map(|t| t.map(|v| v + off)));
        hollow.face_tags.extend(&void.face_tags);
        for s in [&sphere, &hollow] {
            assert!(is_cycle(s));
            let oracle = Winding::new(s);
            let l = Lattice::covering(&s.bbox(), 0.173).unwrap();
            let w = winding_by_rows(&l, &oracle, &|v| oracle.at(l.position(v)));
            let mut inside = 0;
            for v in 0..l.num_vertices() as u32 {
                let exact = oracle.at(l.position(v));
                assert!((w[v as usize] - exact).abs() < 0.05, "{v}: {} {exact}", w[v as usize]);
                inside += (w[v as usize] > 0.5) as usize;
            }
            assert!(inside > 100);
        }
        let mut open = sphere.clone();
        open.triangles.pop();
        open.face_tags.pop();
        assert!(!is_cycle(&open));
    }

    /// A row through a triangle's edge falls back to the solid angles.
    #[test]
    fn degenerate_rows_fall_back() {
        let s = super::super::tests::cube_surface(1);
        let oracle = Winding::new(&s);
        let l = Lattice::covering(&s.bbox(), 0.25).unwrap();
        // a lattice whose rows run along the cube's diagonal edges: shift it onto them
        let l = Lattice { origin: DVec3::new(l.origin.x, -0.25, -0.25), ..l };
        let calls = std::sync::atomic::AtomicUsize::new(0);
        let w = winding_by_rows(&l, &oracle, &|v| {
            calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            oracle.at(l.position(v))
        });
        assert!(calls.into_inner() > 0);
        for v in 0..l.num_vertices() as u32 {
            assert!((w[v as usize] - oracle.at(l.position(v))).abs() < 0.05);
        }
    }
}
