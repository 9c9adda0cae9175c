//! Where tets live: a plain vector for the serial insertion, and the same records in atomics
//! for the parallel one, where threads write disjoint (reserved) tets of one shared array.
//! Relaxed atomic loads and stores compile to plain moves; the rounds of the parallel
//! insertion are separated by rayon's joins, which order them.

use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

/// Vertex id marking a deleted tet slot (every vertex of a free slot is `DEAD`).
pub(crate) const DEAD: u32 = u32::MAX - 1;
/// The ghost vertex (the point at infinity), vertex 3 of the ghost tets that close the hull.
/// The one definition, used by the Delaunay drivers and the mesher; it shares its value with
/// [`NONE`](crate::core::ids::NONE) (no index) but is a vertex, so it has its own name. Neither
/// leaves the crate.
pub(crate) const GHOST: u32 = u32::MAX;

/// One tet: its vertices and its neighbour references, in one 32-byte record so that a visit
/// touches one half cache line.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[repr(C, align(32))]
pub(crate) struct Tet {
    /// Vertex ids (`GHOST` at position 3 for ghost tets, `DEAD` for free slots).
    pub v: [u32; 4],
    /// Neighbour references `(tet << 2) | face`, face `k` opposite vertex `k`.
    pub n: [u32; 4],
}

/// A [`Tet`] whose fields threads may read and write through a shared reference.
#[repr(C, align(32))]
pub(crate) struct AtomicTet {
    v: [AtomicU32; 4],
    n: [AtomicU32; 4],
}

impl AtomicTet {
    /// An atomic copy of `t`.
    pub fn new(t: Tet) -> Self {
        AtomicTet { v: t.v.map(AtomicU32::new), n: t.n.map(AtomicU32::new) }
    }

    /// A plain copy.
    pub fn get(&self) -> Tet {
        Tet { v: self.v.each_ref().map(|x| x.load(Relaxed)), n: self.n.each_ref().map(|x| x.load(Relaxed)) }
    }
}

/// Access to tet records by slot.
pub(crate) trait TetStore {
    /// The vertices of tet `t`.
    fn v(&self, t: u32) -> [u32; 4];
    /// The neighbour reference across face `k` of tet `t`.
    fn n(&self, t: u32, k: usize) -> u32;
    /// Sets the vertices of tet `t`.
    fn set_v(&mut self, t: u32, v: [u32; 4]);
    /// Sets the neighbour reference across face `k` of tet `t`.
    fn set_n(&mut self, t: u32, k: usize, r: u32);
}

impl TetStore for Vec<Tet> {
    #[inline]
    fn v(&self, t: u32) -> [u32; 4] {
        self[t as usize].v
    }
    #[inline]
    fn n(&self, t: u32, k: usize) -> u32 {
        self[t as usize].n[k]
    }
    #[inline]
    fn set_v(&mut self, t: u32, v: [u32; 4]) {
        self[t as usize].v = v;
    }
    #[inline]
    fn set_n(&mut self, t: u32, k: usize, r: u32) {
        self[t as usize].n[k] = r;
    }
}

/// A shared view of atomic tets: reads and writes through `&`, so several threads can hold
/// one; the parallel insertion guarantees that no two write the same tet in a round.
#[derive(Copy, Clone)]
pub(crate) struct SharedTets<'a>(pub &'a [AtomicTet]);

impl TetStore for SharedTets<'_> {
    #[inline]
    fn v(&self, t: u32) -> [u32; 4] {
        let r = &self.0[t as usize].v;
        [r[0].load(Relaxed), r[1].load(Relaxed), r[2].load(Relaxed), r[3].load(Relaxed)]
    }
    #[inline]
    fn n(&self, t: u32, k: usize) -> u32 {
        self.0[t as usize].n[k].load(Relaxed)
    }
    #[inline]
    fn set_v(&mut self, t: u32, v: [u32; 4]) {
        let r = &self.0[t as usize].v;
        for k in 0..4 {
            r[k].store(v[k], Relaxed);
        }
    }
    #[inline]
    fn set_n(&mut self, t: u32, k: usize, r: u32) {
        self.0[t as usize].n[k].store(r, Relaxed);
    }
}

/// True for a live finite tet (not a ghost, not a free slot).
#[inline]
pub(crate) fn is_finite(v: &[u32; 4]) -> bool {
    v[3] != GHOST && v[0] != DEAD
}
