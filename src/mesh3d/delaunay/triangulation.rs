//! The serial incremental Delaunay tetrahedralization.
//!
//! Storage: for tet slot `t`, `tets[t].v` holds 4 vertex ids and `tets[t].n` 4 neighbour
//! references `(tet << 2) | face`, face `k` being opposite vertex `k`; `mark[t]` is a one-byte
//! visit mark, set while a cavity is dug and cleared after. No allocation per tet: deleted
//! slots are reused; slot 0 is a scratch record. The convex hull is closed by ghost tets
//! `[a, b, c, GHOST]` whose finite face `(a, b, c)` is their face 3; the ghost vertex stands
//! for a point at infinity outside that face, so a ghost tet is "positively oriented" in the
//! sense that `orient3d(a, b, c, q) > 0` for points `q` beyond the hull face.
//!
//! Invariants after every insertion: finite tets are positively oriented (exactly), neighbour
//! references are symmetric, and every tet is Delaunay for the lifting perturbation by vertex
//! index (no point strictly or symbolically inside its circumsphere).

use crate::core::Sign;
use crate::mesh::tet_mesh::TET_FACES;
use crate::mesh3d::delaunay::cavity::{Everything, Located, Scratch, dig, fill, link_star, locate};
use crate::mesh3d::delaunay::kernel::Kernel;
use crate::mesh3d::delaunay::store::{DEAD, GHOST, Tet, cavity_slots};

/// An incremental Delaunay tetrahedralization over a kernel.
pub(crate) struct Triangulation<'k, K: Kernel> {
    pub(crate) kernel: &'k K,
    /// Every tet slot.
    pub tets: Vec<Tet>,
    /// Per tet: 0, or `IN` / `OUT` while the current cavity is being dug (reset after).
    mark: Vec<u8>,
    /// Free slots.
    pub(crate) free: Vec<u32>,
    sc: Scratch,
    /// Where the next walk starts: the last created tet.
    pub(crate) hint: u32,
}

impl<'k, K: Kernel> Triangulation<'k, K> {
    /// A triangulation of the positively oriented tet `t` and its four ghosts, with room for
    /// `capacity` tets.
    pub fn new(kernel: &'k K, t: [u32; 4], capacity: usize, seed: u64) -> Self {
        debug_assert_eq!(kernel.orient(t[0], t[1], t[2], t[3]), Sign::Positive);
        let mut tr = Triangulation {
            kernel,
            tets: Vec::with_capacity(capacity),
            mark: Vec::with_capacity(capacity),
            free: Vec::new(),
            sc: Scratch::new(seed),
            hint: 0,
        };
        tr.push([DEAD; 4]); // slot 0: the scratch record that NOWHERE points into
        let first = tr.push(t);
        let mut ghosts = [0u32; 4];
        for (k, f) in TET_FACES.iter().enumerate() {
            let g = tr.push([t[f[0]], t[f[1]], t[f[2]], GHOST]);
            tr.tets[first as usize].n[k] = (g << 2) | 3;
            tr.tets[g as usize].n[3] = (first << 2) | k as u32;
            ghosts[k] = g;
        }
        link_star(&mut tr.tets, &mut tr.sc, &ghosts, 3);
        tr.hint = first;
        tr
    }

    fn push(&mut self, v: [u32; 4]) -> u32 {
        let t = self.tets.len() as u32;
        self.tets.push(Tet { v, n: [0; 4] });
        self.mark.push(0);
        t
    }

    /// Inserts point `p`; returns the vertex it duplicates, if any (then nothing changes).
    pub fn insert(&mut self, p: u32) -> Option<u32> {
        let t0 = match locate(self.kernel, &self.tets, &Everything, &mut self.sc.rng, self.hint, p) {
            Located::Conflict(t) => t,
            Located::Duplicate(v) => return Some(v),
            Located::Blocked | Located::Wall(..) | Located::Lost => unreachable!("the serial insertion owns every tet and has no walls"),
        };
        dig(self.kernel, &self.tets, &Everything, &mut self.mark, &mut self.sc, t0, p);
        let mark = &mut self.mark;
        let new_slot = |tets: &mut Vec<Tet>| {
            tets.push(Tet { v: [DEAD; 4], n: [0; 4] });
            mark.push(0);
            Some(tets.len() as u32 - 1)
        };
        cavity_slots(&mut self.tets, &self.sc.cavity, self.sc.boundary.len(), &mut self.free, &mut self.sc.slots, new_slot);
        // clear the marks before the slots are rewritten
        for &t in &self.sc.cavity {
            self.mark[t as usize] = 0;
        }
        for &(_, outside) in &self.sc.boundary {
            self.mark[(outside >> 2) as usize] = 0;
        }
        let sc = &mut self.sc;
        self.hint = fill(&mut self.tets, &mut sc.edges, &sc.boundary, &sc.slots, p);
        None
    }
}
