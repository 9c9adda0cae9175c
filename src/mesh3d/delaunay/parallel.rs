//! Parallel insertion by regions, in the manner of Gmsh's HXT (Marot, Pellerin and Remacle,
//! "One machine, one minute, three billion tetrahedra", 2019).
//!
//! The points carry their Hilbert rank as internal index, so a range of ranks is a compact
//! region of space. In a pass, the ranks are cut into one range per thread, and each thread
//! inserts the points of its range in Hilbert order, exactly as the serial insertion does, with
//! one restriction: it may only read or write tets whose finite vertices all lie in its range.
//! A point whose walk or cavity meets another tet is postponed, untouched. Passes repeat with
//! shifted ranges, so that the borders of one pass lie inside ranges of the next, until few
//! points remain; those are inserted with a single range covering everything.
//!
//! Why threads never disturb each other: a thread writes only tets it owns (cavity tets, the
//! tets just outside the cavity, the new star: all with vertices in its range), so any slot it
//! writes holds vertices of its range before and after; another thread reading that slot,
//! even half-written, sees a vertex outside its own range and backs off before using it. Free
//! slots are per thread; fresh slots come in chunks from an atomic counter. The tets are
//! atomics, as safe Rust requires for shared writes; relaxed loads and stores are plain moves.
//!
//! The result is the unique perturbed Delaunay tetrahedralization whatever the number of
//! threads, and it is put in canonical form afterwards.

use crate::core::ids::NONE;
use crate::core::spatial_order::brio_rounds;
use crate::mesh3d::delaunay::cavity::{Located, Marks, Owner, Scratch, dig, fill, locate};
use crate::mesh3d::delaunay::kernel::Kernel;
use crate::mesh3d::delaunay::store::{AtomicTet, DEAD, GHOST, SharedTets, Tet, TetStore, cavity_slots};
use crate::mesh3d::delaunay::triangulation::Triangulation;
use crate::mesh3d::delaunay::{DelaunayTimings, PassTiming};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU8, AtomicU32, AtomicUsize, Ordering::Relaxed};

/// Fresh slots a thread takes at a time.
const CHUNK: usize = 2048;

/// The ranks `[lo, hi)` a thread owns.
#[derive(Copy, Clone, Debug)]
struct Range {
    lo: u32,
    hi: u32,
}

impl Owner for Range {
    #[inline]
    fn owns(&self, v: &[u32; 4]) -> bool {
        v.iter().all(|&x| x == GHOST || (x >= self.lo && x < self.hi))
    }
}

/// Ownership by a region number per vertex (slabs of space in later passes).
#[derive(Copy, Clone)]
struct Region<'a> {
    of: &'a [u16],
    me: u16,
}

impl Owner for Region<'_> {
    #[inline]
    fn owns(&self, v: &[u32; 4]) -> bool {
        v.iter().all(|&x| x == GHOST || self.of.get(x as usize) == Some(&self.me))
    }
}

/// Visit marks shared by all threads: each thread marks only tets it owns.
struct SharedMarks<'a>(&'a [AtomicU8]);

impl Marks for SharedMarks<'_> {
    #[inline]
    fn get(&self, t: u32) -> u8 {
        self.0[t as usize].load(Relaxed)
    }
    #[inline]
    fn set(&mut self, t: u32, m: u8) {
        self.0[t as usize].store(m, Relaxed);
    }
}

/// What one thread did in one pass.
struct Outcome {
    postponed: Vec<u32>,
    duplicates: Vec<[u32; 2]>,
    free: Vec<u32>,
    /// The last tet created (live at the end of the pass), or `NONE`.
    last: u32,
}

/// The state shared by the threads of a pass.
struct Shared<'a, K: Kernel> {
    k: &'a K,
    tets: &'a [AtomicTet],
    marks: &'a [AtomicU8],
    near: &'a [AtomicU32],
    next_fresh: &'a AtomicUsize,
}

impl<K: Kernel> Shared<'_, K> {
    /// A live tet owned by `range` near `p`: recorded at a vertex close to `p` in rank.
    fn start<O: Owner>(&self, range: &O, p: u32, hints: [u32; 2]) -> Option<u32> {
        let s = SharedTets(self.tets);
        if let Some(&h) = hints.iter().find(|&&h| h != NONE && range.owns(&s.v(h))) {
            return Some(h);
        }
        let n = self.near.len() as u32;
        for d in 1..=256u32 {
            for u in [p.wrapping_sub(d), p.saturating_add(d)] {
                if u >= n {
                    continue;
                }
                let t = self.near[u as usize].load(Relaxed);
                if t != NONE {
                    let v = s.v(t);
                    if v.contains(&u) && range.owns(&v) {
                        return Some(t);
                    }
                }
            }
        }
        None
    }

    /// Inserts the points `pts` (sorted by rank, all in `range`) one after the other, touching
    /// only tets `range` owns; returns what could not be inserted.
    fn work<O: Owner>(&self, range: O, pts: &[u32], mut free: Vec<u32>, seed: u64, fallback: u32) -> Outcome {
        let k = self.k;
        let mut s = SharedTets(self.tets);
        let mut marks = SharedMarks(self.marks);
        let mut sc = Scratch::new(seed);
        let mut out = Outcome { postponed: Vec::new(), duplicates: Vec::new(), free: Vec::new(), last: NONE };
        let (mut fresh, mut fresh_end) = (0usize, 0usize);
        let mut hint = NONE;
        for (i, &p) in pts.iter().enumerate() {
            let Some(start) = self.start(&range, p, [hint, fallback]) else {
                out.postponed.push(p);
                continue;
            };
            let t0 = match locate(k, &s, &range, &mut sc.rng, start, p) {
                Located::Conflict(t) => t,
                Located::Duplicate(v) => {
                    out.duplicates.push([p, v]);
                    continue;
                }
                Located::Blocked | Located::Wall(..) | Located::Lost => {
                    out.postponed.push(p);
                    continue;
                }
            };
            let ok = dig(k, &s, &range, &mut marks, &mut sc, t0, p);
            // slots: the cavity's own, then this thread's free ones, then fresh chunks; when
            // they run out, the slots go back and the point waits for later
            let enough = ok && {
                let new_slot = |_: &mut SharedTets<'_>| {
                    if fresh == fresh_end {
                        let at = self.next_fresh.fetch_add(CHUNK, Relaxed);
                        if at >= self.tets.len() {
                            return None;
                        }
                        fresh = at;
                        fresh_end = (at + CHUNK).min(self.tets.len());
                    }
                    fresh += 1;
                    Some(fresh as u32 - 1)
                };
                cavity_slots(&mut s, &sc.cavity, sc.boundary.len(), &mut free, &mut sc.slots, new_slot)
            };
            for &t in &sc.cavity {
                marks.set(t, 0);
            }
            for &(_, r) in &sc.boundary {
                marks.set(r >> 2, 0);
            }
            if !enough {
                out.postponed.push(p);
                if !ok {
                    continue;
                }
                out.postponed.extend_from_slice(&pts[i + 1..]);
                break;
            }
            hint = fill(&mut s, &mut sc.edges, &sc.boundary, &sc.slots, p);
            self.near[p as usize].store(hint, Relaxed);
        }
        // fresh slots taken but not used stay free for later passes
        free.extend((fresh..fresh_end).map(|t| t as u32));
        out.free = free;
        out.last = hint;
        out
    }
}

/// `free` cut into `parts` lists (each thread reuses the slots of its list first).
fn split_free(free: &mut Vec<u32>, parts: usize) -> Vec<Vec<u32>> {
    let per = free.len().div_ceil(parts.max(1));
    (0..parts).map(|_| free.split_off(free.len() - per.min(free.len()))).collect()
}

/// Inserts the points of `order[done..]` (the insertion order: BRIO rounds of ranks) into `tr`
/// by parallel passes on the current rayon pool; returns the tets and appends the duplicates,
/// `(point, vertex)` in internal numbering. `skip` lists points already inserted.
pub(crate) fn insert_parallel<K: Kernel>(
    tr: Triangulation<'_, K>,
    order: &[u32],
    done: usize,
    skip: &[u32; 4],
    seed: u64,
    duplicates: &mut Vec<[u32; 2]>,
    timings: &mut DelaunayTimings,
) -> Vec<AtomicTet> {
    let clock = std::time::Instant::now();
    let k = tr.kernel;
    let n = k.len();
    let threads = rayon::current_num_threads().max(1);
    // all slots up front (about 6.7 tets per point), so that threads can take fresh ones
    let capacity = (n * 7 + 4096).max(tr.tets.len() + 4096);
    let in_use = tr.tets.len();
    let dead = Tet { v: [DEAD; 4], n: [0; 4] };
    // built in parallel: the first touch of these pages is most of the cost
    let mut tets: Vec<AtomicTet> = (0..capacity)
        .into_par_iter()
        .with_min_len(1 << 14)
        .map(|t| AtomicTet::new(if t < in_use { tr.tets[t] } else { dead }))
        .collect();
    let mut marks: Vec<AtomicU8> = (0..capacity).into_par_iter().with_min_len(1 << 16).map(|_| AtomicU8::new(0)).collect();
    let near: Vec<AtomicU32> = (0..n).into_par_iter().with_min_len(1 << 16).map(|_| AtomicU32::new(NONE)).collect();
    for (t, tet) in tr.tets.iter().enumerate() {
        for &v in &tet.v {
            if (v as usize) < n {
                near[v as usize].store(t as u32, Relaxed);
            }
        }
    }
    let mut free = tr.free.clone();
    // a live tet to start from when nothing nearer is known
    let mut fallback = tr.hint;
    drop(tr);
    let next_fresh = AtomicUsize::new(in_use);
    let mut region_of: Vec<u16> = if threads > 1 { vec![0; n] } else { Vec::new() };
    timings.parallel_setup = clock.elapsed().as_secs_f64();
    for (s, e) in brio_rounds(order.len(), 1024) {
        if e <= done {
            continue;
        }
        let mut pts: Vec<u32> = order[s.max(done)..e].iter().copied().filter(|p| !skip.contains(p)).collect();
        pts.sort_unstable();
        let mut pass = 0u32;
        let mut used_axes: Vec<usize> = Vec::new();
        let mut stalled = false;
        while !pts.is_empty() {
            let clock = std::time::Instant::now();
            let offered = pts.len();
            let shared = Shared { k, tets: &tets, marks: &marks, near: &near, next_fresh: &next_fresh };
            let pass_seed = seed.wrapping_add(pass as u64);
            // enough points per part that most of a part is far from its borders
            let parts_wanted = if pass == 0 { pts.len() / 20_000 } else { pts.len() / 8_000 }.clamp(1, threads);
            let parallel = parts_wanted > 1 && !stalled;
            let outcomes: Vec<Outcome> = if parallel && pass == 0 {
                // one range of Hilbert ranks per part: compact blobs of space
                let parts = parts_wanted as u64;
                let w = (n as u64).div_ceil(parts);
                let mut cuts: Vec<u32> = (0..=parts).map(|j| (j * w).min(n as u64) as u32).collect();
                cuts.dedup();
                let mut parts = Vec::with_capacity(cuts.len());
                let mut rest: &[u32] = &pts;
                for c in cuts.windows(2) {
                    let at = rest.partition_point(|&p| p < c[1]);
                    let (mine, tail) = rest.split_at(at);
                    parts.push((Range { lo: c[0], hi: c[1] }, mine));
                    rest = tail;
                }
                let frees = split_free(&mut free, parts.len());
                parts.into_par_iter().zip(frees).map(|((r, mine), f)| shared.work(r, mine, f, pass_seed, fallback)).collect()
            } else if parallel && pass <= 6 {
                // slabs across the axis along which the postponed points spread most (not one
                // used before): the borders they sit near are then crossed by the slabs, not
                // parallel to them, and most of those points are now inside a slab
                let mut lo = [f64::INFINITY; 3];
                let mut hi = [f64::NEG_INFINITY; 3];
                for &p in &pts {
                    for a in 0..3 {
                        let x = k.coord(p, a);
                        lo[a] = lo[a].min(x);
                        hi[a] = hi[a].max(x);
                    }
                }
                let fresh: Vec<usize> = (0..3).filter(|a| used_axes.len() >= 3 || !used_axes.contains(a)).collect();
                let last = used_axes.last().copied();
                let axis = fresh
                    .iter()
                    .copied()
                    .filter(|&a| Some(a) != last)
                    .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
                    .unwrap_or(0);
                used_axes.push(axis);
                let threads = parts_wanted;
                let mut xs: Vec<f64> = pts.iter().map(|&p| k.coord(p, axis)).collect();
                xs.par_sort_unstable_by(f64::total_cmp);
                let cuts: Vec<f64> = (1..threads).map(|j| xs[j * xs.len() / threads]).collect();
                region_of.par_iter_mut().enumerate().with_min_len(4096).for_each(|(v, r)| {
                    let x = k.coord(v as u32, axis);
                    *r = cuts.partition_point(|&c| c <= x) as u16;
                });
                let mut groups: Vec<Vec<u32>> = vec![Vec::new(); threads];
                for &p in &pts {
                    groups[region_of[p as usize] as usize].push(p);
                }
                let frees = split_free(&mut free, groups.len());
                let of = &region_of;
                groups
                    .par_iter()
                    .zip(frees)
                    .enumerate()
                    .map(|(j, (g, f))| shared.work(Region { of, me: j as u16 }, g, f, pass_seed, fallback))
                    .collect()
            } else {
                // what is left, in one range that owns everything
                let all = Range { lo: 0, hi: n as u32 };
                vec![shared.work(all, &pts, std::mem::take(&mut free), pass_seed, fallback)]
            };
            let mut postponed = Vec::new();
            for o in outcomes {
                postponed.extend(o.postponed);
                duplicates.extend(o.duplicates);
                free.extend(o.free);
                if o.last != NONE {
                    fallback = o.last;
                }
            }
            if next_fresh.load(Relaxed) >= tets.len() {
                // out of fresh slots: grow (no thread holds a reference now); every slot below
                // the old length has been handed out
                let old = tets.len();
                let more = old / 4 + 4096;
                tets.extend((0..more).map(|_| AtomicTet::new(Tet { v: [DEAD; 4], n: [0; 4] })));
                marks.extend((0..more).map(|_| AtomicU8::new(0)));
                next_fresh.store(old, Relaxed);
            }
            postponed.sort_unstable();
            let split = match (parallel, pass, used_axes.last()) {
                (true, 0, _) => "ranks",
                (true, 1..=6, Some(0)) => "x slabs",
                (true, 1..=6, Some(1)) => "y slabs",
                (true, 1..=6, Some(2)) => "z slabs",
                _ => "all",
            };
            // a pass that leaves nine tenths behind is not worth another: finish in one part
            stalled = parallel && pass > 0 && postponed.len() * 10 >= offered * 9;
            timings.passes.push(PassTiming { split, points: offered, postponed: postponed.len(), seconds: clock.elapsed().as_secs_f64() });
            pts = postponed;
            pass += 1;
        }
    }
    tets
}
