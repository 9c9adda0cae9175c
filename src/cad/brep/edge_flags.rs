//! Seam and degenerate flags of edges, derived from the topology and the geometry once a
//! model is complete.

use super::model::Model;
use rustc_hash::FxHashMap;

/// Relative length (fraction of the model size) below which an edge is degenerate.
pub const DEGENERATE_RELATIVE: f64 = 1e-9;

impl Model {
    /// Sets [`Edge::seam`](super::Edge::seam) (an edge used twice by one face) and
    /// [`Edge::degenerate`](super::Edge::degenerate) (an edge shorter than
    /// [`DEGENERATE_RELATIVE`] times the model size).
    pub fn mark_edges(&mut self) {
        let mut uses: FxHashMap<(u32, u32), u32> = FxHashMap::default();
        for (k, f) in self.faces.iter().enumerate() {
            for &l in &f.loops {
                for c in &self.loops[l as usize].coedges {
                    *uses.entry((k as u32, c.edge)).or_insert(0) += 1;
                }
            }
        }
        for (&(_, e), &n) in &uses {
            if n >= 2 {
                self.edges[e as usize].seam = true;
            }
        }
        let tol = DEGENERATE_RELATIVE * self.size();
        for k in 0..self.edges.len() {
            let e = &self.edges[k];
            let len = match e.curve {
                Some(c) => {
                    let r = e.range;
                    if r.min.is_finite() && r.max.is_finite() { self.curves[c as usize].chord_length(r.min, r.max) } else { f64::INFINITY }
                }
                None => (self.vertices[e.start as usize].point - self.vertices[e.end as usize].point).length(),
            };
            self.edges[k].degenerate = len <= tol;
        }
    }
}
