//! The front: directed edges with the unmeshed region on their left, in a priority queue by
//! length (shortest first), found by their end points and by place.
//!
//! - Stage: the state of the advancing front (`step` takes an edge from it, adds a triangle,
//!   and updates it).
//! - Inputs: the domain's segments (the initial front) and the points.
//! - Output: the next edge to advance ([`Front::pop`]), the edges and vertices near a place
//!   ([`Front::edges_in`], [`Front::vertices_in`]).
//! - Invariants: an edge id is never reused (a removed edge stays dead); the map holds
//!   exactly the live edges; ties in length go to the smaller id; every query answers in an
//!   order fixed by the input (the grid's cell order), each edge or vertex once.

use super::grid::Grid;
use glam::DVec2;
use rustc_hash::FxHashMap;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// The advancing front.
pub(crate) struct Front {
    /// Every edge ever on the front, `[from, to]`, the unmeshed region on its left.
    pub(crate) edges: Vec<[u32; 2]>,
    /// Whether each edge is still on the front.
    pub(crate) alive: Vec<bool>,
    /// Live edges by their directed end points.
    map: FxHashMap<(u32, u32), u32>,
    /// Live (and some dead) edges by length bits then id, shortest first.
    heap: BinaryHeap<Reverse<(u64, u32)>>,
    grid: Grid,
    /// Per edge and per vertex: the query that last returned it (to return each once).
    edge_seen: Vec<u32>,
    vertex_seen: Vec<u32>,
    tick: u32,
    /// Live edges.
    pub(crate) live: usize,
}

impl Front {
    /// An empty front over a grid.
    pub(crate) fn new(grid: Grid) -> Front {
        Front { edges: Vec::new(), alive: Vec::new(), map: FxHashMap::default(), heap: BinaryHeap::new(), grid, edge_seen: Vec::new(), vertex_seen: Vec::new(), tick: 0, live: 0 }
    }

    /// Adds the edge `a -> b` (points `pts`) to the front and returns its id.
    pub(crate) fn add(&mut self, a: u32, b: u32, pts: &[DVec2]) -> u32 {
        let id = self.edges.len() as u32;
        let (pa, pb) = (pts[a as usize], pts[b as usize]);
        self.edges.push([a, b]);
        self.alive.push(true);
        self.edge_seen.push(0);
        self.map.insert((a, b), id);
        self.heap.push(Reverse((pa.distance(pb).to_bits(), id)));
        self.grid.insert(id, pa, pb);
        self.live += 1;
        id
    }

    /// Takes edge `id` off the front.
    pub(crate) fn remove(&mut self, id: u32) {
        if self.alive[id as usize] {
            self.alive[id as usize] = false;
            let [a, b] = self.edges[id as usize];
            self.map.remove(&(a, b));
            self.live -= 1;
        }
    }

    /// The live edge `a -> b`, if any.
    pub(crate) fn find(&self, a: u32, b: u32) -> Option<u32> {
        self.map.get(&(a, b)).copied()
    }

    /// The shortest live edge (ties: the smallest id), taken off the queue but left on the
    /// front; `None` when the queue is empty.
    pub(crate) fn pop(&mut self) -> Option<u32> {
        while let Some(Reverse((_, id))) = self.heap.pop() {
            if self.alive[id as usize] {
                return Some(id);
            }
        }
        None
    }

    /// Puts a live edge back on the queue (after a deferral).
    pub(crate) fn requeue(&mut self, id: u32, pts: &[DVec2]) {
        let [a, b] = self.edges[id as usize];
        self.heap.push(Reverse((pts[a as usize].distance(pts[b as usize]).to_bits(), id)));
    }

    fn next_tick(&mut self, vertices: usize) {
        if self.vertex_seen.len() < vertices {
            self.vertex_seen.resize(vertices, 0);
        }
        self.tick = self.tick.wrapping_add(1);
        if self.tick == 0 {
            self.edge_seen.iter_mut().for_each(|s| *s = 0);
            self.vertex_seen.iter_mut().for_each(|s| *s = 0);
            self.tick = 1;
        }
    }

    /// The live edges listed in the cells that meet the box `[lo, hi]`, each once, in `out`.
    pub(crate) fn edges_in(&mut self, lo: DVec2, hi: DVec2, vertices: usize, out: &mut Vec<u32>) {
        out.clear();
        self.next_tick(vertices);
        let (seen, tick) = (&mut self.edge_seen, self.tick);
        self.grid.query(lo, hi, &self.alive, |e| {
            if seen[e as usize] != tick {
                seen[e as usize] = tick;
                out.push(e);
            }
        });
    }

    /// The end points of the live edges listed in the cells that meet the box `[lo, hi]`,
    /// each once, in `out` (they may lie a little outside the box).
    pub(crate) fn vertices_in(&mut self, lo: DVec2, hi: DVec2, vertices: usize, out: &mut Vec<u32>) {
        out.clear();
        self.next_tick(vertices);
        let (seen, tick, edges) = (&mut self.vertex_seen, self.tick, &self.edges);
        self.grid.query(lo, hi, &self.alive, |e| {
            for v in edges[e as usize] {
                if seen[v as usize] != tick {
                    seen[v as usize] = tick;
                    out.push(v);
                }
            }
        });
    }
}
