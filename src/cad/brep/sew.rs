//! Sewing of surface models: free edges of open shells that are the same curve become one
//! edge, so their faces share it (and the tessellation shares its points).
//!
//! Input: a [`Model`] with open shells (`OPEN_SHELL`s of a `SHELL_BASED_SURFACE_MODEL`, or
//! faces written with their own copies of every edge). Output: the model with coincident
//! vertices merged and matching free edges merged, and a [`SewReport`] saying what was sewn.
//!
//! Two free edges (used by one coedge each) match when their end vertices coincide within
//! `tol` and the curves do: [`SAMPLES`] interior points of each lie within `tol` of the other
//! curve. The tolerance is [`SEW_RELATIVE`] times the model size. Only vertices and edges of
//! open shells are touched; closed shells are left as they are.

use super::model::{Coedge, Model};
use glam::DVec3;
use rustc_hash::FxHashMap;
use serde::Serialize;

/// Sewing tolerance as a fraction of the model size.
pub const SEW_RELATIVE: f64 = 1e-6;

/// Interior sample points compared per edge pair.
pub const SAMPLES: usize = 5;

/// What [`Model::sew`] did.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SewReport {
    /// The tolerance used, mm.
    pub tolerance: f64,
    /// Vertices merged into another.
    pub merged_vertices: usize,
    /// Edges merged into another.
    pub merged_edges: usize,
    /// Edges used by one face only, before and after.
    pub free_edges_before: usize,
    /// After sewing.
    pub free_edges_after: usize,
}

impl Model {
    /// Points of edge `e` at `n` interior parameters (start to end), or none without a curve.
    fn edge_samples(&self, e: usize, n: usize) -> Vec<DVec3> {
        let edge = &self.edges[e];
        let Some(ci) = edge.curve else { return Vec::new() };
        let (a, b) = (edge.range.min, edge.range.max);
        if !(a.is_finite() && b.is_finite()) {
            return Vec::new();
        }
        let c = self.curve(ci);
        (1..=n).map(|k| c.point(a + (b - a) * k as f64 / (n + 1) as f64)).collect()
    }

    /// Distance from `p` to edge `e`'s curve (or its chord when it has none).
    fn distance_to_edge(&self, e: usize, p: DVec3) -> f64 {
        let edge = &self.edges[e];
        match edge.curve {
            Some(ci) => {
                let c = self.curve(ci);
                let mid = 0.5 * (edge.range.min + edge.range.max);
                let t = c.project_near(p, if mid.is_finite() { mid } else { 0.0 });
                (c.point(t) - p).length()
            }
            None => {
                let (a, b) = (self.vertices[edge.start as usize].point, self.vertices[edge.end as usize].point);
                let ab = b - a;
                let t = if ab.length_squared() > 0.0 { ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
                (a + t * ab - p).length()
            }
        }
    }

    /// Direction of edge `e` from its start to its end at its first sample (for closed edges).
    fn edge_direction(&self, e: usize) -> Option<DVec3> {
        let edge = &self.edges[e];
        let c = self.curve(edge.curve?);
        let t = edge.range.min + 0.25 * edge.range.length();
        let d = c.derivative(t);
        Some(if edge.same_sense { d } else { -d })
    }

    /// Number of edges used by exactly one coedge.
    fn free_edge_count(&self) -> usize {
        let mut uses = vec![0u32; self.edges.len()];
        for l in &self.loops {
            for c in &l.coedges {
                uses[c.edge as usize] += 1;
            }
        }
        uses.iter().filter(|&&u| u == 1).count()
    }

    /// Sews the open shells (see the module docs). Returns `None` when the model has no open
    /// shell.
    pub fn sew(&mut self) -> Option<SewReport> {
        if !self.shells.iter().any(|s| !s.closed) {
            return None;
        }
        let tol = SEW_RELATIVE * self.size();
        let free_edges_before = self.free_edge_count();
        // vertices and edges of open shells
        let mut open_edge = vec![false; self.edges.len()];
        for f in &self.faces {
            if self.shells[f.shell as usize].closed {
                continue;
            }
            for &l in &f.loops {
                for c in &self.loops[l as usize].coedges {
                    open_edge[c.edge as usize] = true;
                }
            }
        }
        let mut open_vertex = vec![false; self.vertices.len()];
        for (e, edge) in self.edges.iter().enumerate() {
            if open_edge[e] {
                open_vertex[edge.start as usize] = true;
                open_vertex[edge.end as usize] = true;
            }
        }
        // merge coincident vertices: cells of size tol, neighbours checked
        let cell = |p: DVec3| ((p / tol.max(f64::MIN_POSITIVE)).floor()).as_i64vec3();
        let mut grid: FxHashMap<glam::I64Vec3, Vec<u32>> = FxHashMap::default();
        let mut rep: Vec<u32> = (0..self.vertices.len() as u32).collect();
        let mut merged_vertices = 0;
        for v in 0..self.vertices.len() {
            if !open_vertex[v] {
                continue;
            }
            let p = self.vertices[v].point;
            let c = cell(p);
            let mut found = None;
            'search: for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        if let Some(list) = grid.get(&(c + glam::I64Vec3::new(dx, dy, dz))) {
                            if let Some(&w) = list.iter().find(|&&w| (self.vertices[w as usize].point - p).length() <= tol) {
                                found = Some(w);
                                break 'search;
                            }
                        }
                    }
                }
            }
            match found {
                Some(w) => {
                    rep[v] = w;
                    merged_vertices += 1;
                }
                None => grid.entry(c).or_default().push(v as u32),
            }
        }
        for e in &mut self.edges {
            e.start = rep[e.start as usize];
            e.end = rep[e.end as usize];
        }
        for l in &mut self.loops {
            if let Some(v) = l.vertex {
                l.vertex = Some(rep[v as usize]);
            }
        }
        // free edges of open shells by their (merged) end vertices
        let mut uses = vec![0u32; self.edges.len()];
        for l in &self.loops {
            for c in &l.coedges {
                uses[c.edge as usize] += 1;
            }
        }
        let mut by_ends: FxHashMap<(u32, u32), Vec<u32>> = FxHashMap::default();
        for (e, edge) in self.edges.iter().enumerate() {
            if open_edge[e] && uses[e] == 1 && !edge.degenerate {
                by_ends.entry((edge.start.min(edge.end), edge.start.max(edge.end))).or_default().push(e as u32);
            }
        }
        // edge -> (the edge it merges into, reversed)
        let mut into: Vec<Option<(u32, bool)>> = vec![None; self.edges.len()];
        let mut keys: Vec<_> = by_ends.keys().copied().collect();
        keys.sort_unstable();
        for k in keys {
            let list = &by_ends[&k];
            let mut taken = vec![false; list.len()];
            for i in 0..list.len() {
                if taken[i] {
                    continue;
                }
                for j in i + 1..list.len() {
                    if taken[j] {
                        continue;
                    }
                    let (a, b) = (list[i] as usize, list[j] as usize);
                    let same = self.edge_samples(a, SAMPLES).iter().all(|&p| self.distance_to_edge(b, p) <= tol)
                        && self.edge_samples(b, SAMPLES).iter().all(|&p| self.distance_to_edge(a, p) <= tol);
                    if !same {
                        continue;
                    }
                    let (ea, eb) = (&self.edges[a], &self.edges[b]);
                    let reversed = if ea.start != ea.end {
                        eb.start != ea.start
                    } else {
                        match (self.edge_direction(a), self.edge_direction(b)) {
                            (Some(da), Some(db)) => da.dot(db) < 0.0,
                            _ => continue,
                        }
                    };
                    into[b] = Some((a as u32, reversed));
                    taken[i] = true;
                    taken[j] = true;
                    break;
                }
            }
        }
        let merged_edges = into.iter().filter(|x| x.is_some()).count();
        for l in &mut self.loops {
            for c in &mut l.coedges {
                if let Some((a, reversed)) = into[c.edge as usize] {
                    *c = Coedge { edge: a, forward: c.forward != reversed };
                }
            }
        }
        self.compact();
        self.mark_edges();
        Some(SewReport { tolerance: tol, merged_vertices, merged_edges, free_edges_before, free_edges_after: self.free_edge_count() })
    }

    /// Drops edges no coedge uses and vertices no edge or loop uses, renumbering the rest.
    fn compact(&mut self) {
        let mut used_edge = vec![false; self.edges.len()];
        for l in &self.loops {
            for c in &l.coedges {
                used_edge[c.edge as usize] = true;
            }
        }
        let mut edge_map = vec![u32::MAX; self.edges.len()];
        let mut edges = Vec::new();
        for (e, edge) in self.edges.iter().enumerate() {
            if used_edge[e] {
                edge_map[e] = edges.len() as u32;
                edges.push(edge.clone());
            }
        }
        for l in &mut self.loops {
            for c in &mut l.coedges {
                c.edge = edge_map[c.edge as usize];
            }
        }
        self.edges = edges;
        let mut used_vertex = vec![false; self.vertices.len()];
        for e in &self.edges {
            used_vertex[e.start as usize] = true;
            used_vertex[e.end as usize] = true;
        }
        for l in &self.loops {
            if let Some(v) = l.vertex {
                used_vertex[v as usize] = true;
            }
        }
        let mut vertex_map = vec![u32::MAX; self.vertices.len()];
        let mut vertices = Vec::new();
        for (v, vx) in self.vertices.iter().enumerate() {
            if used_vertex[v] {
                vertex_map[v] = vertices.len() as u32;
                vertices.push(vx.clone());
            }
        }
        for e in &mut self.edges {
            e.start = vertex_map[e.start as usize];
            e.end = vertex_map[e.end as usize];
        }
        for l in &mut self.loops {
            if let Some(v) = l.vertex {
                l.vertex = Some(vertex_map[v as usize]);
            }
        }
        self.vertices = vertices;
    }
}
