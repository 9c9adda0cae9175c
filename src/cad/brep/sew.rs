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
//!
//! **T-junctions.** Where one side cut a boundary into more edges than the other (one long
//! free edge against two shorter ones meeting at a vertex in the middle of it), the long edge
//! is first split at that vertex: a free edge is split at the end vertex of another free edge
//! that lies on its curve within `tol`, strictly inside it, when that other edge runs along it
//! (its other end on the edge too, its middle within `tol` of the curve). The split edge's
//! curve range is cut at the vertex's projection, and every loop that used the edge uses the
//! pieces in its place. Splitting repeats until nothing more is split; then the pieces are
//! sewn as above. Each split is reported ([`EdgeSplit`]).
//!
//! **Holes.** The free edges left are grouped into holes (edges joined at shared vertices),
//! each with its edge count, length, a point and the faces around it ([`Hole`],
//! [`Model::holes`]).

use super::model::{Coedge, Model, Shell};
use super::sew_report::{EdgeSplit, Hole, SewReport};
use crate::core::FaceId;
use crate::core::ids::NONE;
use glam::DVec3;
use rustc_hash::FxHashMap;

/// Sewing tolerance as a fraction of the model size.
pub const SEW_RELATIVE: f64 = 1e-6;

/// Interior sample points compared per edge pair.
pub const SAMPLES: usize = 5;

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

    /// How many coedges use each edge.
    fn edge_uses(&self) -> Vec<u32> {
        let mut uses = vec![0u32; self.edges.len()];
        for l in &self.loops {
            for c in &l.coedges {
                uses[c.edge as usize] += 1;
            }
        }
        uses
    }

    /// Number of edges used by exactly one coedge.
    fn free_edge_count(&self) -> usize {
        self.edge_uses().iter().filter(|&&u| u == 1).count()
    }

    /// Length of edge `e` and the integral of position along it (for a centre): its curve
    /// as 512 chords, or the segment between its vertices.
    fn edge_moments(&self, e: usize) -> (f64, DVec3) {
        let edge = &self.edges[e];
        let pts: Vec<DVec3> = match edge.curve {
            Some(c) if edge.range.min.is_finite() && edge.range.max.is_finite() => {
                let (c, a, b) = (self.curve(c), edge.range.min, edge.range.max);
                let n = 512;
                (0..=n).map(|k| c.point(a + (b - a) * k as f64 / n as f64)).collect()
            }
            _ => vec![self.vertices[edge.start as usize].point, self.vertices[edge.end as usize].point],
        };
        pts.windows(2).fold((0.0, DVec3::ZERO), |(l, m), w| {
            let d = (w[1] - w[0]).length();
            (l + d, m + d * 0.5 * (w[0] + w[1]))
        })
    }

    /// Where `p` projects on edge `e`: its curve parameter (for an edge without a curve the
    /// fraction of the way from `start` to `end`) and the distance, when the parameter falls
    /// within the edge's range (`slack` beyond its ends allowed, as a fraction of the range).
    fn project_on_edge(&self, e: usize, p: DVec3, slack: f64) -> Option<(f64, f64)> {
        let edge = &self.edges[e];
        let (a, b) = (edge.range.min, edge.range.max);
        match edge.curve {
            Some(ci) => {
                if !(a.is_finite() && b.is_finite()) {
                    return None;
                }
                let c = self.curve(ci);
                let t = c.project_near(p, 0.5 * (a + b));
                let s = slack * (b - a);
                (t >= a - s && t <= b + s).then(|| (t, (c.point(t) - p).length()))
            }
            None => {
                let (q0, q1) = (self.vertices[edge.start as usize].point, self.vertices[edge.end as usize].point);
                let d = q1 - q0;
                if d.length_squared() == 0.0 {
                    return None;
                }
                let t = (p - q0).dot(d) / d.length_squared();
                (t >= -slack && t <= 1.0 + slack).then(|| (t, (q0 + t * d - p).length()))
            }
        }
    }

    /// A box around edge `e` (points along it, widened by the gap between them and `tol`).
    fn edge_box(&self, e: usize, tol: f64) -> (DVec3, DVec3) {
        let edge = &self.edges[e];
        let ends = [self.vertices[edge.start as usize].point, self.vertices[edge.end as usize].point];
        let samples = self.edge_samples(e, 31);
        let mut gap: f64 = samples.windows(2).map(|w| (w[1] - w[0]).length()).fold(0.0, f64::max);
        if let (Some(&f), Some(&l)) = (samples.first(), samples.last()) {
            for q in ends {
                gap = gap.max((q - f).length().min((q - l).length()));
            }
        }
        let mut pts = ends.to_vec();
        pts.extend(samples);
        let (lo, hi) = pts.iter().fold((pts[0], pts[0]), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        let w = DVec3::splat(gap + tol);
        (lo - w, hi + w)
    }

    /// Splits free edges of open shells at the end vertices of other free edges running
    /// along them (T-junctions; see the module docs), once. Returns the splits made.
    fn split_t_junctions(&mut self, open_edge: &mut Vec<bool>, tol: f64) -> Vec<EdgeSplit> {
        let uses = self.edge_uses();
        let free: Vec<usize> = (0..self.edges.len()).filter(|&e| open_edge[e] && uses[e] == 1 && !self.edges[e].degenerate).collect();
        // free edges at each vertex
        let mut at_vertex: FxHashMap<u32, Vec<usize>> = FxHashMap::default();
        for &e in &free {
            let edge = &self.edges[e];
            at_vertex.entry(edge.start).or_default().push(e);
            if edge.end != edge.start {
                at_vertex.entry(edge.end).or_default().push(e);
            }
        }
        let mut cand: Vec<u32> = at_vertex.keys().copied().collect();
        cand.sort_unstable_by(|&a, &b| self.vertices[a as usize].point.x.total_cmp(&self.vertices[b as usize].point.x).then(a.cmp(&b)));
        let xs: Vec<f64> = cand.iter().map(|&v| self.vertices[v as usize].point.x).collect();
        // edge -> where it is cut: (parameter, vertex, distance)
        type Cut = (f64, u32, f64);
        let mut cuts: Vec<(usize, Vec<Cut>)> = Vec::new();
        for &e in &free {
            let (lo, hi) = self.edge_box(e, tol);
            let (s, t) = (self.edges[e].start, self.edges[e].end);
            let first = xs.partition_point(|&x| x < lo.x);
            let mut here = Vec::new();
            for &v in cand[first..].iter().take_while(|&&v| self.vertices[v as usize].point.x <= hi.x) {
                let p = self.vertices[v as usize].point;
                if v == s || v == t || p.cmplt(lo).any() || p.cmpgt(hi).any() {
                    continue;
                }
                let Some((tv, dist)) = self.project_on_edge(e, p, 0.0) else { continue };
                let (ps, pt) = (self.vertices[s as usize].point, self.vertices[t as usize].point);
                if dist > tol || (p - ps).length() <= tol || (p - pt).length() <= tol {
                    continue;
                }
                // another free edge from v runs along e: its other end on e, its middle too
                let along = at_vertex[&v].iter().any(|&g| {
                    if g == e {
                        return false;
                    }
                    let ge = &self.edges[g];
                    let w = if ge.start == v { ge.end } else { ge.start };
                    let w_on = w == s || w == t || self.project_on_edge(e, self.vertices[w as usize].point, 0.0).is_some_and(|(_, d)| d <= tol);
                    let mid = self.edge_samples(g, 1).first().copied().unwrap_or(0.5 * (p + self.vertices[w as usize].point));
                    w_on && w != v && self.project_on_edge(e, mid, 0.0).is_some_and(|(_, d)| d <= tol)
                });
                if along {
                    here.push((tv, v, dist));
                }
            }
            if !here.is_empty() {
                here.sort_by(|a, b| a.0.total_cmp(&b.0));
                here.dedup_by_key(|x| x.1);
                cuts.push((e, here));
            }
        }
        let mut splits = Vec::new();
        // edge -> its pieces from its start to its end
        let mut pieces_of: FxHashMap<u32, Vec<u32>> = FxHashMap::default();
        for (e, here) in cuts {
            let edge = self.edges[e].clone();
            let (a, b) = match edge.curve {
                Some(_) => (edge.range.min, edge.range.max),
                None => (0.0, 1.0),
            };
            // vertices and parameters in increasing parameter order
            let (va, vb) = if edge.same_sense || edge.curve.is_none() { (edge.start, edge.end) } else { (edge.end, edge.start) };
            let mut ts = vec![a];
            let mut vs = vec![va];
            for &(t, v, dist) in &here {
                ts.push(t);
                vs.push(v);
                let p = self.vertices[v as usize].point;
                splits.push(EdgeSplit { edge: edge.source, vertex: self.vertices[v as usize].source, at: p.to_array(), distance: dist });
            }
            ts.push(b);
            vs.push(vb);
            let mut pieces = Vec::new();
            for i in 0..ts.len() - 1 {
                let mut piece = edge.clone();
                if edge.curve.is_some() {
                    piece.range = crate::cad::geom::Interval::new(ts[i], ts[i + 1]);
                }
                (piece.start, piece.end) = if edge.same_sense || edge.curve.is_none() { (vs[i], vs[i + 1]) } else { (vs[i + 1], vs[i]) };
                piece.closed = piece.start == piece.end;
                let k = if i == 0 {
                    self.edges[e] = piece;
                    e as u32
                } else {
                    self.edges.push(piece);
                    open_edge.push(true);
                    self.edges.len() as u32 - 1
                };
                pieces.push(k);
            }
            // pieces are in parameter order; from start to end they run reversed when the
            // edge runs against its curve
            if !(edge.same_sense || edge.curve.is_none()) {
                pieces.reverse();
            }
            pieces_of.insert(e as u32, pieces);
        }
        if !pieces_of.is_empty() {
            for l in &mut self.loops {
                if !l.coedges.iter().any(|c| pieces_of.contains_key(&c.edge)) {
                    continue;
                }
                let mut out = Vec::with_capacity(l.coedges.len() + 2);
                for c in &l.coedges {
                    match pieces_of.get(&c.edge) {
                        Some(p) if c.forward => out.extend(p.iter().map(|&k| Coedge { edge: k, forward: true })),
                        Some(p) => out.extend(p.iter().rev().map(|&k| Coedge { edge: k, forward: false })),
                        None => out.push(*c),
                    }
                }
                l.coedges = out;
            }
        }
        splits
    }

    /// The free edges (used by one face, not degenerate) of the faces whose shell `keep`
    /// accepts, grouped into holes: edges joined at shared vertices. Largest first.
    pub fn holes(&self, keep: impl Fn(&Shell) -> bool) -> Vec<Hole> {
        let uses = self.edge_uses();
        // the face of each free edge
        let mut face_of: FxHashMap<u32, usize> = FxHashMap::default();
        for (f, face) in self.faces.iter().enumerate() {
            if !keep(&self.shells[face.shell as usize]) {
                continue;
            }
            for &l in &face.loops {
                for c in &self.loops[l as usize].coedges {
                    let e = c.edge as usize;
                    if uses[e] == 1 && !self.edges[e].degenerate {
                        face_of.insert(c.edge, f);
                    }
                }
            }
        }
        let mut free: Vec<u32> = face_of.keys().copied().collect();
        free.sort_unstable();
        let mut uf = crate::core::union_find::UnionFind::new(self.vertices.len());
        for &e in &free {
            let edge = &self.edges[e as usize];
            uf.union(edge.start, edge.end);
        }
        let mut by_root: FxHashMap<u32, Vec<u32>> = FxHashMap::default();
        for &e in &free {
            by_root.entry(uf.find(self.edges[e as usize].start)).or_default().push(e);
        }
        let mut holes: Vec<Hole> = by_root
            .into_values()
            .map(|edges| {
                let (mut length, mut moment) = (0.0, DVec3::ZERO);
                let mut degree: FxHashMap<u32, u32> = FxHashMap::default();
                let (mut faces, mut shells, mut step_edges) = (Vec::new(), Vec::new(), Vec::new());
                for &e in &edges {
                    let edge = &self.edges[e as usize];
                    let (l, m) = self.edge_moments(e as usize);
                    length += l;
                    moment += m;
                    *degree.entry(edge.start).or_insert(0) += 1;
                    *degree.entry(edge.end).or_insert(0) += 1;
                    let f = face_of[&e];
                    faces.push(FaceId::from_index(f));
                    shells.push(self.shells[self.faces[f].shell as usize].source);
                    step_edges.push(edge.source);
                }
                faces.sort_unstable();
                faces.dedup();
                shells.sort_unstable();
                shells.dedup();
                step_edges.sort_unstable();
                step_edges.dedup();
                Hole {
                    edges: edges.len(),
                    length,
                    near: if length > 0.0 { (moment / length).to_array() } else { self.vertices[self.edges[edges[0] as usize].start as usize].point.to_array() },
                    step_faces: faces.iter().map(|&f| self.face(f).source).collect(),
                    faces,
                    step_edges,
                    shells,
                    closed_ring: degree.values().all(|&d| d == 2),
                }
            })
            .collect();
        holes.sort_by(|a, b| b.length.total_cmp(&a.length).then(a.near.partial_cmp(&b.near).unwrap_or(std::cmp::Ordering::Equal)));
        holes
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
        // T-junctions: free edges split at the other side's vertices, until none is
        let mut splits = Vec::new();
        for _ in 0..16 {
            let more = self.split_t_junctions(&mut open_edge, tol);
            if more.is_empty() {
                break;
            }
            splits.extend(more);
        }
        // free edges of open shells by their (merged) end vertices
        let uses = self.edge_uses();
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
        let holes = self.holes(|s| !s.closed);
        Some(SewReport { tolerance: tol, merged_vertices, merged_edges, free_edges_before, free_edges_after: self.free_edge_count(), splits, holes })
    }

    /// Drops edges no coedge uses and vertices no edge or loop uses, renumbering the rest.
    fn compact(&mut self) {
        let mut used_edge = vec![false; self.edges.len()];
        for l in &self.loops {
            for c in &l.coedges {
                used_edge[c.edge as usize] = true;
            }
        }
        let mut edge_map = vec![NONE; self.edges.len()];
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
        let mut vertex_map = vec![NONE; self.vertices.len()];
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cad::brep::{Edge, EntityRef, Face, Loop, Shell, Vertex};
    use crate::cad::geom::{Curve, Frame, Interval, Line, Plane, Surface};
    use crate::tessellate::certificate::{CertifyOptions, certify};
    use crate::tessellate::{TessellateOptions, tessellate};

    /// A surface model of planar polygons (outward counter-clockwise), each face with its own
    /// vertices and line edges, all in one `OPEN_SHELL`, as some CAD systems write them.
    fn polygons(faces: &[Vec<DVec3>]) -> Model {
        let mut m = Model::default();
        m.shells.push(Shell { faces: Vec::new(), closed: false, solid: None, void: false, source: EntityRef(1) });
        for (k, poly) in faces.iter().enumerate() {
            let v0 = m.vertices.len() as u32;
            for (i, &point) in poly.iter().enumerate() {
                m.vertices.push(Vertex { point, source: EntityRef(1000 + 100 * k as u64 + i as u64) });
            }
            let mut coedges = Vec::new();
            for i in 0..poly.len() {
                let j = (i + 1) % poly.len();
                m.curves.push(Curve::Line(Line { origin: poly[i], direction: poly[j] - poly[i] }));
                m.edges.push(Edge {
                    curve: Some(m.curves.len() as u32 - 1),
                    start: v0 + i as u32,
                    end: v0 + j as u32,
                    range: Interval::new(0.0, 1.0),
                    same_sense: true,
                    closed: false,
                    seam: false,
                    degenerate: false,
                    source: EntityRef(2000 + 100 * k as u64 + i as u64),
                });
                coedges.push(Coedge { edge: m.edges.len() as u32 - 1, forward: true });
            }
            let n = (poly[1] - poly[0]).cross(poly[2] - poly[0]);
            m.surfaces.push(Surface::Plane(Plane { frame: Frame::from_axes(poly[0], Some(n), Some(poly[1] - poly[0])).unwrap() }));
            let fid = FaceId::from_index(k);
            m.loops.push(Loop { face: fid, outer: true, orientation: true, coedges, vertex: None, source: EntityRef(3000 + k as u64) });
            m.faces.push(Face { surface: k as u32, same_sense: true, loops: vec![k as u32], shell: 0, name: None, colour: None, source: EntityRef(4000 + k as u64) });
            m.shells[0].faces.push(fid);
        }
        m.mark_edges();
        m
    }

    fn p(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    /// The 10 mm cube's faces, the top one (z = 10) last.
    fn cube_sides() -> Vec<Vec<DVec3>> {
        vec![
            vec![p(0., 0., 0.), p(0., 10., 0.), p(10., 10., 0.), p(10., 0., 0.)],
            vec![p(0., 0., 0.), p(10., 0., 0.), p(10., 0., 10.), p(0., 0., 10.)],
            vec![p(0., 10., 0.), p(0., 10., 10.), p(10., 10., 10.), p(10., 10., 0.)],
            vec![p(0., 0., 0.), p(0., 0., 10.), p(0., 10., 10.), p(0., 10., 0.)],
            vec![p(10., 0., 0.), p(10., 10., 0.), p(10., 10., 10.), p(10., 0., 10.)],
        ]
    }

    #[test]
    fn a_t_junction_is_split_sewn_and_reported() {
        // the top cut in two halves at x = 5; the sides y = 0 and y = 10 keep one top edge
        // each, against two edges of the halves meeting at (5, 0, 10) and (5, 10, 10)
        let mut faces = cube_sides();
        faces.push(vec![p(0., 0., 10.), p(5., 0., 10.), p(5., 10., 10.), p(0., 10., 10.)]);
        faces.push(vec![p(5., 0., 10.), p(10., 0., 10.), p(10., 10., 10.), p(5., 10., 10.)]);
        let mut m = polygons(&faces);
        let r = m.sew().expect("an open shell");
        assert_eq!(r.splits.len(), 2, "{r:?}");
        let mut at: Vec<[f64; 3]> = r.splits.iter().map(|s| s.at).collect();
        at.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(at, vec![[5., 0., 10.], [5., 10., 10.]]);
        // the split edges are the sides' top edges (faces 2 and 3)
        let mut split_edges: Vec<EntityRef> = r.splits.iter().map(|s| s.edge).collect();
        split_edges.sort();
        assert_eq!(split_edges, vec![EntityRef(2102), EntityRef(2201)]);
        assert!(r.splits.iter().all(|s| s.distance <= r.tolerance));
        assert_eq!(r.free_edges_before, 4 * 5 + 2 * 4);
        assert_eq!(r.free_edges_after, 0, "{r:?}");
        assert!(r.holes.is_empty());
        // 12 cube edges, 2 pieces more, 1 between the halves
        assert_eq!(m.edges.len(), 15);
        assert_eq!(m.vertices.len(), 10);
        assert!(m.issues(1e-9).is_empty(), "{:?}", m.issues(1e-9));
        // watertight where sewn: the tessellation closes and passes its certificate
        let t = tessellate(&m, &TessellateOptions::default());
        let c = certify(&m, &t, &CertifyOptions::default());
        assert!(c.passed, "{:?}", c.failures);
        assert!(c.watertight(), "{c:?}");
        assert_eq!(c.shells.len(), 1);
        assert!(c.shells[0].brep_closed);
        assert!((c.volume[0] - 1000.0).abs() < 1e-9, "{:?}", c.volume);
    }

    #[test]
    fn a_t_junction_with_three_pieces_and_a_reversed_edge() {
        // the side y = 0 in two pieces at x = 4, the top in three strips at x = 3 and x = 7:
        // the top's front edge pieces cross the side's, both sides are split to match
        let mut faces = cube_sides();
        faces[1] = vec![p(0., 0., 0.), p(10., 0., 0.), p(10., 0., 10.), p(4., 0., 10.), p(0., 0., 10.)];
        faces.push(vec![p(0., 0., 10.), p(3., 0., 10.), p(3., 10., 10.), p(0., 10., 10.)]);
        faces.push(vec![p(3., 0., 10.), p(7., 0., 10.), p(7., 10., 10.), p(3., 10., 10.)]);
        faces.push(vec![p(7., 0., 10.), p(10., 0., 10.), p(10., 10., 10.), p(7., 10., 10.)]);
        let mut m = polygons(&faces);
        let r = m.sew().expect("an open shell");
        // y = 0: its piece (10,0,10)-(4,0,10) split at x = 7, (4,0,10)-(0,0,10) at x = 3; the
        // top strip (3..7) split at x = 4; y = 10: its top edge at x = 3 and x = 7
        assert_eq!(r.splits.len(), 5, "{:?}", r.splits);
        assert_eq!(r.free_edges_after, 0, "{r:?}");
        assert!(m.issues(1e-9).is_empty(), "{:?}", m.issues(1e-9));
        let t = tessellate(&m, &TessellateOptions::default());
        let c = certify(&m, &t, &CertifyOptions::default());
        assert!(c.passed && c.watertight(), "{:?}", c.failures);
        assert!((c.volume[0] - 1000.0).abs() < 1e-9, "{:?}", c.volume);
    }

    #[test]
    fn a_missing_face_is_one_hole_with_its_size() {
        let mut m = polygons(&cube_sides());
        let r = m.sew().expect("an open shell");
        assert!(r.splits.is_empty());
        assert_eq!(r.free_edges_after, 4);
        assert_eq!(r.holes.len(), 1, "{:?}", r.holes);
        let h = &r.holes[0];
        assert_eq!(h.edges, 4);
        assert!((h.length - 40.0).abs() < 1e-9, "{h:?}");
        assert!((DVec3::from_array(h.near) - p(5., 5., 10.)).length() < 1e-9, "{h:?}");
        assert!(h.closed_ring);
        assert_eq!(h.step_faces, vec![EntityRef(4001), EntityRef(4002), EntityRef(4003), EntityRef(4004)]);
        assert!(h.describe().starts_with("4 free edges, 40.000000 mm around, near (5.000000, 5.000000, 10.000000), faces #4001"), "{}", h.describe());
        // an open surface model: certified open along its hole, not watertight
        let t = tessellate(&m, &TessellateOptions::default());
        let c = certify(&m, &t, &CertifyOptions::default());
        assert!(c.passed, "{:?}", c.failures);
        assert!(!c.watertight());
        assert!(c.open_solids.is_empty());
    }

    #[test]
    fn a_solid_left_open_fails_its_certificate_naming_the_hole() {
        let mut m = polygons(&cube_sides());
        m.shells[0].closed = true;
        m.shells[0].solid = Some(0);
        m.solids.push(crate::cad::brep::Solid { shells: vec![0], name: Some("box".into()), instance: 0, source: EntityRef(7) });
        assert!(m.sew().is_none(), "closed shells are not sewn");
        let t = tessellate(&m, &TessellateOptions::default());
        let c = certify(&m, &t, &CertifyOptions::default());
        assert!(!c.passed && !c.watertight());
        assert_eq!(c.open_solids.len(), 5, "every face its own copies: 5 holes of 4 edges");
        let f = &c.failures[0];
        assert_eq!((f.check, f.step_id), ("open_solid", Some(EntityRef(7))));
        assert!(f.message.starts_with("solid #7 'box' (CLOSED_SHELL #1) does not close: a hole of 4 free edges"), "{}", f.message);
    }
}
