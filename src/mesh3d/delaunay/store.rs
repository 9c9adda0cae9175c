//! Where tets live: a plain vector for the serial insertion, and the same records in atomics
//! for the parallel one, where threads write disjoint (reserved) tets of one shared array.
//! Relaxed atomic loads and stores compile to plain moves; the rounds of the parallel
//! insertion are separated by rayon's joins, which order them.

use crate::core::ids::NONE;
use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

/// Vertex id marking a deleted tet slot (every vertex of a free slot is `DEAD`).
pub(crate) const DEAD: u32 = NONE - 1;
/// The ghost vertex (the point at infinity), vertex 3 of the ghost tets that close the hull.
/// The one definition, used by the Delaunay drivers and the mesher; it shares its value with
/// [`NONE`] (no index) but is a vertex, so it has its own name. Neither
/// leaves the crate.
pub(crate) const GHOST: u32 = NONE;

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

/// Frees slot `t`: its vertices become [`DEAD`] and it goes on `free` (reused last in, first
/// out). Nothing may refer to it any more.
#[inline]
pub(crate) fn free_slot<S: TetStore>(s: &mut S, free: &mut Vec<u32>, t: u32) {
    s.set_v(t, [DEAD; 4]);
    free.push(t);
}

/// The slots for re-triangulating a cavity, the one rule of every insertion (serial, parallel,
/// the mesher's walled one): the `m` new tets (one per boundary face) take the cavity's own
/// slots first, in cavity order, then slots popped from `free`, then slots from `new_slot`
/// (which appends or reserves a dead record in `s`, or says there is no room); `slots` gets
/// them in that order. Cavity slots left over are freed ([`free_slot`], in cavity order).
///
/// Returns false when `new_slot` ran out: then nothing is freed, and the slots taken beyond the
/// cavity's own go (in the order taken) onto `free`, so the caller can postpone the point.
pub(crate) fn cavity_slots<S: TetStore>(
    s: &mut S,
    cavity: &[u32],
    m: usize,
    free: &mut Vec<u32>,
    slots: &mut Vec<u32>,
    mut new_slot: impl FnMut(&mut S) -> Option<u32>,
) -> bool {
    let c = cavity.len();
    slots.clear();
    slots.extend_from_slice(&cavity[..c.min(m)]);
    while slots.len() < m {
        let t = match free.pop() {
            Some(t) => t,
            None => match new_slot(s) {
                Some(t) => t,
                None => {
                    free.extend(slots.drain(c.min(m)..));
                    return false;
                }
            },
        };
        slots.push(t);
    }
    for &t in &cavity[m.min(c)..] {
        free_slot(s, free, t);
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn store(n: usize) -> Vec<Tet> {
        (0..n as u32).map(|i| Tet { v: [i; 4], n: [0; 4] }).collect()
    }

    fn grow(s: &mut Vec<Tet>) -> Option<u32> {
        s.push(Tet { v: [DEAD; 4], n: [0; 4] });
        Some(s.len() as u32 - 1)
    }

    #[test]
    fn more_faces_than_cavity_tets_take_free_then_new_slots() {
        let mut s = store(6);
        let (mut free, mut slots) = (vec![4, 5], Vec::new());
        assert!(cavity_slots(&mut s, &[2, 1], 5, &mut free, &mut slots, grow));
        assert_eq!(slots, [2, 1, 5, 4, 6]);
        assert!(free.is_empty());
        assert_eq!(s.len(), 7);
    }

    #[test]
    fn fewer_faces_than_cavity_tets_free_the_rest() {
        let mut s = store(6);
        let (mut free, mut slots) = (vec![0], Vec::new());
        assert!(cavity_slots(&mut s, &[3, 1, 4, 2], 2, &mut free, &mut slots, grow));
        assert_eq!(slots, [3, 1]);
        assert_eq!(free, [0, 4, 2]);
        assert_eq!(s[4].v, [DEAD; 4]);
        assert_eq!(s[2].v, [DEAD; 4]);
        assert_eq!(s[3].v, [3; 4]);
        assert_eq!(s.len(), 6);
    }

    #[test]
    fn running_out_gives_the_slots_taken_back() {
        let mut s = store(6);
        let (mut free, mut slots) = (vec![5], Vec::new());
        let mut room = 1;
        let ok = cavity_slots(&mut s, &[1], 4, &mut free, &mut slots, |s| {
            (room > 0).then(|| {
                room -= 1;
                grow(s).unwrap()
            })
        });
        assert!(!ok);
        assert_eq!(free, [5, 6]);
        assert_eq!(s[1].v, [1; 4]);
    }
}
