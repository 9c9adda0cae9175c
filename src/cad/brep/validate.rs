//! Consistency checks of a [`Model`]: indices in range, loops closed (each coedge ends where
//! the next begins), and edge geometry agreeing with the vertices (the curve at the ends of
//! an edge's range lies on its vertices, within a tolerance relative to the model size).

use super::model::Model;

/// Relative tolerance (fraction of [`Model::size`]) for vertices on their edge's curve.
pub const VERTEX_ON_CURVE_RELATIVE: f64 = 1e-5;

impl Model {
    /// Problems found, each naming the item (empty for a consistent model). `rel_tol` is the
    /// allowed distance of a vertex from its edge's curve, as a fraction of the model size
    /// ([`VERTEX_ON_CURVE_RELATIVE`] is a good default; files carry their own precision).
    pub fn issues(&self, rel_tol: f64) -> Vec<String> {
        let mut out = Vec::new();
        let tol = rel_tol * self.size();
        let nv = self.vertices.len() as u32;
        for (k, e) in self.edges.iter().enumerate() {
            if e.start >= nv || e.end >= nv {
                out.push(format!("edge {k} ({}): vertex index out of range", e.source));
                continue;
            }
            let Some(c) = e.curve else { continue };
            let Some(curve) = self.curves.get(c as usize) else {
                out.push(format!("edge {k} ({}): curve index out of range", e.source));
                continue;
            };
            if !(e.range.min <= e.range.max) {
                out.push(format!("edge {k} ({}): range {:?} not increasing", e.source, e.range));
                continue;
            }
            let (a, b) = if e.same_sense { (e.start, e.end) } else { (e.end, e.start) };
            for (t, v) in [(e.range.min, a), (e.range.max, b)] {
                let d = (curve.point(t) - self.vertices[v as usize].point).length();
                if !(d <= tol) {
                    out.push(format!("edge {k} ({}): vertex {} is {d:.3e} mm from the curve end (tolerance {tol:.3e})", e.source, self.vertices[v as usize].source));
                }
            }
        }
        for (k, l) in self.loops.iter().enumerate() {
            let n = l.coedges.len();
            for i in 0..n {
                let (c, d) = (l.coedges[i], l.coedges[(i + 1) % n]);
                let (Some(ec), Some(ed)) = (self.edges.get(c.edge as usize), self.edges.get(d.edge as usize)) else {
                    out.push(format!("loop {k} ({}): edge index out of range", l.source));
                    break;
                };
                let end = if c.forward { ec.end } else { ec.start };
                let start = if d.forward { ed.start } else { ed.end };
                if end != start {
                    out.push(format!("loop {k} ({}): edge {} does not end where edge {} starts", l.source, ec.source, ed.source));
                }
            }
        }
        for (k, f) in self.faces.iter().enumerate() {
            if f.surface as usize >= self.surfaces.len() || f.loops.iter().any(|&l| l as usize >= self.loops.len()) {
                out.push(format!("face {} ({}): index out of range", k + 1, f.source));
            }
        }
        out
    }
}
