//! Stage 1 of element removal: the front, the boundary of the region not yet meshed.
//!
//! - Inputs: a valid [`Domain`]; its points become the first vertices (same indices).
//! - Output: [`Front`]: closed loops of nodes (a node is one occurrence of a vertex on the
//!   front; after a split or a merge one vertex can occur on several loops), the triangles
//!   cut so far, and a uniform grid over the nodes and the front edges so that every exact
//!   check of a cut looks only at the front near it.
//! - Invariants: every loop keeps the unmeshed region on its left; a loop of two nodes is
//!   a zero-area bridge and is dropped at once; the grid holds every live node and front
//!   edge (stale entries are skipped by checking the node is alive and still linked).
//! - Operations: [`Front::cut_ear`] (one triangle, the node's neighbours joined),
//!   [`Front::replace`] (two triangles with a new vertex that takes the node's place),
//!   [`Front::split`] (a diagonal between two nodes: one loop splits in two, or two loops
//!   merge). The checks ([`Front::segment_blocked`], [`Front::vertices_in`]) are exact.

use crate::core::predicates::orient2d;
use crate::core::Sign;
use crate::mesh2d::domain::{point_segment_distance, segments_intersect, Domain};
use glam::DVec2;

/// One occurrence of a vertex on the front.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Node {
    /// Its vertex.
    pub vertex: u32,
    /// The previous node on its loop.
    pub prev: u32,
    /// The next node on its loop.
    pub next: u32,
    /// Still on the front.
    pub alive: bool,
}

/// A uniform grid of node and edge entries (edges by their start node and end node).
struct Grid {
    lo: DVec2,
    cell: f64,
    nx: usize,
    ny: usize,
    nodes: Vec<Vec<u32>>,
    edges: Vec<Vec<[u32; 2]>>,
}

impl Grid {
    fn cells(&self, lo: DVec2, hi: DVec2) -> ([usize; 2], [usize; 2]) {
        let ix = |x: f64, n: usize| (((x / self.cell).floor().max(0.0)) as usize).min(n - 1);
        let (a, b) = ((lo - self.lo), (hi - self.lo));
        ([ix(a.x, self.nx), ix(b.x, self.nx)], [ix(a.y, self.ny), ix(b.y, self.ny)])
    }
}

/// The front and the triangles cut so far (see the module docs).
pub(crate) struct Front {
    /// Every vertex: the domain's points first, then the added ones.
    pub points: Vec<DVec2>,
    /// Every node ever made (dead ones stay, marked).
    pub nodes: Vec<Node>,
    /// Triangles cut, counter-clockwise.
    pub triangles: Vec<[u32; 3]>,
    /// Live nodes.
    pub live: usize,
    grid: Grid,
    mark: Vec<u32>,
    query: u32,
}

/// The domain's boundary could not be traced into loops.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Untraceable(pub u32);

impl Front {
    /// The loops of `domain`: at a point with several segments out, the segment in is
    /// followed by the first segment out clockwise from it, so loops touching at a point stay
    /// apart. `cell`: the grid's cell side.
    pub fn new(domain: &Domain, cell: f64) -> Result<Front, Untraceable> {
        let n = domain.points.len();
        let mut outs: Vec<Vec<u32>> = vec![Vec::new(); n];
        for (s, &[a, _]) in domain.segments.iter().enumerate() {
            outs[a as usize].push(s as u32);
        }
        let mut nodes: Vec<Node> = domain.segments.iter().map(|&[a, _]| Node { vertex: a, prev: u32::MAX, next: u32::MAX, alive: true }).collect();
        for (s, &[a, b]) in domain.segments.iter().enumerate() {
            let (pa, pb) = (domain.points[a as usize], domain.points[b as usize]);
            let back = (pa - pb).to_angle();
            let turn = |o: u32| {
                let c = domain.points[domain.segments[o as usize][1] as usize];
                let mut t = back - (c - pb).to_angle();
                if t <= 0.0 {
                    t += std::f64::consts::TAU;
                }
                t
            };
            let next = outs[b as usize].iter().copied().min_by(|&x, &y| turn(x).total_cmp(&turn(y)).then(x.cmp(&y))).ok_or(Untraceable(b))?;
            if nodes[next as usize].prev != u32::MAX {
                return Err(Untraceable(b));
            }
            nodes[s].next = next;
            nodes[next as usize].prev = s as u32;
        }
        let (lo, hi) = domain.bounds();
        // at most about 4 cells per segment (and 4096), at most 2048 along a side
        let max_cells = (4 * domain.segments.len() + 4096) as f64;
        let cell = cell.max((hi - lo).max_element() / 2048.0).max(((hi.x - lo.x) * (hi.y - lo.y) / max_cells).sqrt()).max(f64::MIN_POSITIVE);
        let nx = (((hi.x - lo.x) / cell).floor() as usize + 1).max(1);
        let ny = (((hi.y - lo.y) / cell).floor() as usize + 1).max(1);
        let grid = Grid { lo, cell, nx, ny, nodes: vec![Vec::new(); nx * ny], edges: vec![Vec::new(); nx * ny] };
        let live = nodes.len();
        let mut f = Front { points: domain.points.clone(), nodes, triangles: Vec::new(), live, grid, mark: Vec::new(), query: 0 };
        for k in 0..f.nodes.len() as u32 {
            f.index_node(k);
            f.index_edge(k);
        }
        Ok(f)
    }

    /// The position of node `k`'s vertex.
    #[inline]
    pub fn pos(&self, k: u32) -> DVec2 {
        self.points[self.nodes[k as usize].vertex as usize]
    }

    /// The vertex of node `k`.
    #[inline]
    pub fn vert(&self, k: u32) -> u32 {
        self.nodes[k as usize].vertex
    }

    /// Node `k`'s neighbours `(prev, next)`.
    #[inline]
    pub fn around(&self, k: u32) -> (u32, u32) {
        (self.nodes[k as usize].prev, self.nodes[k as usize].next)
    }

    /// Whether node `k` is on a loop of three nodes.
    pub fn on_triangle(&self, k: u32) -> bool {
        let (p, n) = self.around(k);
        self.nodes[n as usize].next == p
    }

    /// The interior angle at node `k` in degrees, in `[0, 360)`; 360 at the tip of a
    /// dangling edge (both neighbours the same vertex).
    pub fn angle(&self, k: u32) -> f64 {
        let (p, n) = self.around(k);
        if self.vert(p) == self.vert(n) {
            return 360.0;
        }
        let v = self.pos(k);
        let (e1, e2) = (self.pos(p) - v, self.pos(n) - v);
        let mut a = e2.perp_dot(e1).atan2(e2.dot(e1)).to_degrees();
        if a < 0.0 {
            a += 360.0;
        }
        a
    }

    /// Whether `w` lies strictly inside the front's interior angle at node `k` (exact).
    pub fn in_sector(&self, k: u32, w: DVec2) -> bool {
        let (p, n) = self.around(k);
        let (pp, v, pn) = (self.pos(p), self.pos(k), self.pos(n));
        let left_out = orient2d(v, pn, w) == Sign::Positive;
        let left_in = orient2d(pp, v, w) == Sign::Positive;
        if orient2d(pp, v, pn) == Sign::Positive {
            left_out && left_in
        } else {
            left_out || left_in
        }
    }

    /// Adds a vertex (not yet on the front).
    pub fn add_point(&mut self, p: DVec2) -> u32 {
        self.points.push(p);
        (self.points.len() - 1) as u32
    }

    fn index_node(&mut self, k: u32) {
        let p = self.pos(k);
        let (cx, cy) = self.grid.cells(p, p);
        self.grid.nodes[cy[0] * self.grid.nx + cx[0]].push(k);
    }

    fn index_edge(&mut self, k: u32) {
        let n = self.nodes[k as usize].next;
        let (a, b) = (self.pos(k), self.pos(n));
        let (cx, cy) = self.grid.cells(a.min(b), a.max(b));
        for y in cy[0]..=cy[1] {
            for x in cx[0]..=cx[1] {
                self.grid.edges[y * self.grid.nx + x].push([k, n]);
            }
        }
    }

    fn link(&mut self, a: u32, b: u32) {
        self.nodes[a as usize].next = b;
        self.nodes[b as usize].prev = a;
        self.index_edge(a);
    }

    fn new_node(&mut self, vertex: u32) -> u32 {
        self.nodes.push(Node { vertex, prev: u32::MAX, next: u32::MAX, alive: true });
        let k = (self.nodes.len() - 1) as u32;
        self.live += 1;
        self.index_node(k);
        k
    }

    /// Drops a loop of two nodes starting at `k` (a zero-area bridge), if it is one.
    fn drop_bridge(&mut self, k: u32) {
        let (p, n) = self.around(k);
        if p == n && self.nodes[k as usize].alive {
            self.nodes[k as usize].alive = false;
            self.nodes[n as usize].alive = false;
            self.live -= 2;
        }
    }

    /// Cuts the triangle `(prev, k, next)` and joins `prev` to `next`; returns them.
    pub fn cut_ear(&mut self, k: u32) -> (u32, u32) {
        let (p, n) = self.around(k);
        self.triangles.push([self.vert(p), self.vert(k), self.vert(n)]);
        self.nodes[k as usize].alive = false;
        self.live -= 1;
        self.link(p, n);
        self.drop_bridge(p);
        (p, n)
    }

    /// Cuts the triangles `(prev, k, x)` and `(k, next, x)` with vertex `x` and puts a node
    /// of `x` in `k`'s place; returns it.
    pub fn replace(&mut self, k: u32, x: u32) -> u32 {
        let (p, n) = self.around(k);
        let (vp, vk, vn) = (self.vert(p), self.vert(k), self.vert(n));
        self.triangles.push([vp, vk, x]);
        self.triangles.push([vk, vn, x]);
        self.nodes[k as usize].alive = false;
        self.live -= 1;
        let m = self.new_node(x);
        self.link(p, m);
        self.link(m, n);
        m
    }

    /// The diagonal from node `a` to node `b`: `a` then goes on to `b`, and copies `a2`,
    /// `b2` close the other side (`b`'s old predecessor, `b2`, `a2`, `a`'s old successor).
    /// One loop splits in two, or two loops merge. Returns `(a2, b2)`.
    pub fn split(&mut self, a: u32, b: u32) -> (u32, u32) {
        let an = self.nodes[a as usize].next;
        let bp = self.nodes[b as usize].prev;
        let a2 = self.new_node(self.vert(a));
        let b2 = self.new_node(self.vert(b));
        self.link(a, b);
        self.link(a2, an);
        self.link(b2, a2);
        self.link(bp, b2);
        (a2, b2)
    }

    fn next_query(&mut self) -> u32 {
        if self.mark.len() < self.nodes.len() {
            self.mark.resize(self.nodes.len(), 0);
        }
        self.query = self.query.wrapping_add(1);
        if self.query == 0 {
            self.mark.iter_mut().for_each(|m| *m = 0);
            self.query = 1;
        }
        self.query
    }

    /// Whether the segment between vertices `i` and `j` meets a live front edge anywhere
    /// but at a shared end (an edge between the same two vertices does not count; one that
    /// shares an end counts only when it runs along the segment). Exact.
    pub fn segment_blocked(&mut self, i: u32, j: u32) -> bool {
        let (pi, pj) = (self.points[i as usize], self.points[j as usize]);
        let (cx, cy) = self.grid.cells(pi.min(pj), pi.max(pj));
        for y in cy[0]..=cy[1] {
            for x in cx[0]..=cx[1] {
                for &[k, n] in &self.grid.edges[y * self.grid.nx + x] {
                    let (nk, nn) = (&self.nodes[k as usize], &self.nodes[n as usize]);
                    if !nk.alive || !nn.alive || nk.next != n {
                        continue;
                    }
                    let (r, s) = (nk.vertex, nn.vertex);
                    if (r == i && s == j) || (r == j && s == i) {
                        continue;
                    }
                    let (pr, ps) = (self.points[r as usize], self.points[s as usize]);
                    let shared = if r == i || r == j { Some((r, ps)) } else if s == i || s == j { Some((s, pr)) } else { None };
                    let hit = match shared {
                        Some((e, other)) => {
                            let pe = self.points[e as usize];
                            let t = if e == i { pj } else { pi };
                            orient2d(pe, t, other) == Sign::Zero && (t - pe).dot(other - pe) > 0.0
                        }
                        None => segments_intersect(pi, pj, pr, ps),
                    };
                    if hit {
                        return true;
                    }
                }
            }
        }
        false
    }

    /// The live nodes whose vertex lies in the closed triangle `t` (counter-clockwise
    /// vertex ids), other than its corners; exact. Appended to `out`, each once.
    pub fn vertices_in(&mut self, t: [u32; 3], out: &mut Vec<u32>) {
        let p = t.map(|v| self.points[v as usize]);
        let q = self.next_query();
        let (cx, cy) = self.grid.cells(p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]));
        for y in cy[0]..=cy[1] {
            for x in cx[0]..=cx[1] {
                for &k in &self.grid.nodes[y * self.grid.nx + x] {
                    let node = self.nodes[k as usize];
                    if !node.alive || self.mark[k as usize] == q || t.contains(&node.vertex) {
                        continue;
                    }
                    self.mark[k as usize] = q;
                    let w = self.points[node.vertex as usize];
                    if (0..3).all(|e| orient2d(p[e], p[(e + 1) % 3], w) != Sign::Negative) {
                        out.push(k);
                    }
                }
            }
        }
    }

    /// Live nodes near `x`: those within `rv`, and the ends of live edges within `re`,
    /// other than the vertices `skip`, by distance to `x` then node id.
    pub fn near(&mut self, x: DVec2, rv: f64, re: f64, skip: [u32; 3]) -> Vec<(f64, u32)> {
        let r = rv.max(re);
        let q = self.next_query();
        let (cx, cy) = self.grid.cells(x - DVec2::splat(r), x + DVec2::splat(r));
        let mut out = Vec::new();
        for y in cy[0]..=cy[1] {
            for cxx in cx[0]..=cx[1] {
                let c = y * self.grid.nx + cxx;
                for &k in &self.grid.nodes[c] {
                    let node = self.nodes[k as usize];
                    if node.alive && self.mark[k as usize] != q && !skip.contains(&node.vertex) && self.points[node.vertex as usize].distance(x) < rv {
                        self.mark[k as usize] = q;
                        out.push((self.points[node.vertex as usize].distance(x), k));
                    }
                }
                for &[k, n] in &self.grid.edges[c] {
                    let (nk, nn) = (self.nodes[k as usize], self.nodes[n as usize]);
                    if !nk.alive || !nn.alive || nk.next != n {
                        continue;
                    }
                    let (a, b) = (self.points[nk.vertex as usize], self.points[nn.vertex as usize]);
                    if point_segment_distance(x, a, b) >= re {
                        continue;
                    }
                    for m in [k, n] {
                        let v = self.nodes[m as usize].vertex;
                        if self.mark[m as usize] != q && !skip.contains(&v) {
                            self.mark[m as usize] = q;
                            out.push((self.points[v as usize].distance(x), m));
                        }
                    }
                }
            }
        }
        out.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        out
    }
}
