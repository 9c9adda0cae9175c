//! Tie-breaking that favours the input's diagonals.
//!
//! Where four surface vertices are coplanar and cocircular (a square of a grid, a rectangle of
//! a cylinder's wall), the Delaunay tetrahedralization may take either diagonal; the symbolic
//! perturbation decides, by vertex rank: the largest perturbation belongs to the largest rank,
//! and the diagonal taken is the one that avoids the quad's highest-ranked vertex. Taking the
//! input's own diagonal saves a Steiner point on the boundary (and, with keep-surface, the
//! work of removing it again). This module finds the input's cocircular quads exactly and
//! orders the vertices so that, wherever it can, each quad's highest-ranked vertex is off its
//! diagonal.

use glam::DVec3;
use rustc_hash::FxHashMap;

/// A cocircular quad: its diagonal (the shared input edge) and its two other corners.
struct Quad {
    diagonal: [u32; 2],
    off: [u32; 2],
}

/// The input's coplanar, cocircular pairs of triangles.
fn quads(points: &[DVec3], triangles: &[[u32; 3]]) -> Vec<Quad> {
    let mut opposite: FxHashMap<(u32, u32), Vec<u32>> = FxHashMap::default();
    for t in triangles {
        for k in 0..3 {
            let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            opposite.entry((a.min(b), a.max(b))).or_default().push(c);
        }
    }
    let mut out = Vec::new();
    for (&(a, c), opp) in &opposite {
        let &[b, d] = opp.as_slice() else { continue };
        if b != d && nearly_cocircular([a, b, c, d].map(|i| points[i as usize])) {
            out.push(Quad { diagonal: [a, c], off: [b, d] });
        }
    }
    out.sort_unstable_by_key(|q| (q.diagonal, q.off));
    out
}

/// True when the four points are coplanar and cocircular up to rounding. Only a preference
/// hangs on it (ranks matter for exact ties alone), so floating point serves; the exact
/// predicates' zero cases would cost more than the whole tetrahedralization.
fn nearly_cocircular(p: [DVec3; 4]) -> bool {
    let [a, b, c, d] = p;
    let (u, v, w) = (b - a, c - a, d - a);
    let scale = u.length().max(v.length()).max(w.length());
    if scale == 0.0 {
        return false;
    }
    let tol = 1e-10;
    if u.cross(v).dot(w).abs() > tol * scale * scale * scale {
        return false;
    }
    // the circle through a, b, c: its centre in the plane
    let n = u.cross(v);
    let nn = n.length_squared();
    if nn <= tol * scale.powi(4) {
        return false;
    }
    let centre = a + (v.length_squared() * n.cross(u) + u.length_squared() * v.cross(n)) / (2.0 * nn);
    let r = centre.distance(a);
    (centre.distance(d) - r).abs() <= tol * scale
}

/// A rank per vertex (a permutation of `0..points.len()`), for the symbolic perturbation.
pub(crate) fn ranks(points: &[DVec3], triangles: &[[u32; 3]]) -> Vec<u32> {
    let n = points.len();
    let quads = quads(points, triangles);
    if quads.is_empty() {
        return (0..n as u32).collect();
    }
    // per vertex: the quads it is a diagonal corner of, and those it is an off corner of
    let mut diag_of: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut off_of: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (i, q) in quads.iter().enumerate() {
        for v in q.diagonal {
            diag_of[v as usize].push(i as u32);
        }
        for v in q.off {
            off_of[v as usize].push(i as u32);
        }
    }
    let mut open: Vec<bool> = vec![true; quads.len()];
    let mut pending: Vec<u32> = diag_of.iter().map(|d| d.len() as u32).collect();
    let mut placed = vec![false; n];
    // highest rank first: a vertex may take the next-highest rank once no open quad has it on
    // its diagonal; taking it closes the quads it is an off corner of
    let mut order: Vec<u32> = Vec::with_capacity(n);
    let mut ready: Vec<u32> = (0..n as u32).rev().filter(|&v| pending[v as usize] == 0).collect();
    while order.len() < n {
        let v = match ready.pop() {
            Some(v) if !placed[v as usize] => v,
            Some(_) => continue,
            None => {
                // stuck (the constraints form a cycle): the least-constrained vertex goes next
                match (0..n as u32).filter(|&v| !placed[v as usize]).min_by_key(|&v| (pending[v as usize], v)) {
                    Some(v) => v,
                    None => break,
                }
            }
        };
        placed[v as usize] = true;
        order.push(v);
        for &q in off_of[v as usize].iter().chain(&diag_of[v as usize]) {
            if !open[q as usize] {
                continue;
            }
            open[q as usize] = false;
            for w in quads[q as usize].diagonal {
                pending[w as usize] -= 1;
                if pending[w as usize] == 0 && !placed[w as usize] {
                    ready.push(w);
                }
            }
        }
    }
    let mut rank = vec![0u32; n];
    for (i, &v) in order.iter().enumerate() {
        rank[v as usize] = (n - 1 - i) as u32;
    }
    rank
}
