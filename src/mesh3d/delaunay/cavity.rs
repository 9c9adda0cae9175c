//! The three steps of one Bowyer–Watson insertion, shared by the serial and the parallel
//! drivers: locate the point (visibility walk), dig its cavity (the connected tets whose
//! perturbed circumsphere holds it) and fill the cavity with the star of the point.
//!
//! Conventions: see [`crate::mesh3d::delaunay::triangulation`]. Generic over the kernel, the
//! tet store (plain or atomic) and the visit marks (a byte per tet, or a small table).

use crate::core::Sign;
use crate::core::spatial_order::XorShift;
use crate::mesh::tet_mesh::TET_FACES;
use crate::mesh3d::delaunay::edge_table::EdgeTable;
use crate::mesh3d::delaunay::kernel::Kernel;
use crate::mesh3d::delaunay::store::{GHOST, TetStore};

/// Mark of a tet in the cavity being dug.
pub(crate) const IN: u8 = 1;
/// Mark of a tet tested and found outside the cavity being dug.
pub(crate) const OUT: u8 = 2;

/// A face reference into the scratch slot 0: links to it are written and forgotten, so that
/// star linking needs no branch on whether a partner exists yet.
pub(crate) const NOWHERE: u32 = 0;

/// `OTHER[i][j]`: the two positions of `0..4` other than `i` and `j` (for `i != j`).
const OTHER: [[(usize, usize); 4]; 4] = {
    let mut t = [[(0, 0); 4]; 4];
    let mut i = 0;
    while i < 4 {
        let mut j = 0;
        while j < 4 {
            let mut o = [0usize; 2];
            let mut n = 0;
            let mut k = 0;
            while k < 4 {
                if k != i && k != j && n < 2 {
                    o[n] = k;
                    n += 1;
                }
                k += 1;
            }
            t[i][j] = (o[0], o[1]);
            j += 1;
        }
        i += 1;
    }
    t
};

/// `AROUND[apex]`: the three faces `k != apex` with the positions `(i, j)` of the edge that
/// face shares with the others around the apex.
const AROUND: [[(usize, usize, usize); 3]; 4] = {
    let mut t = [[(0, 0, 0); 3]; 4];
    let mut a = 0;
    while a < 4 {
        let mut n = 0;
        let mut k = 0;
        while k < 4 {
            if k != a {
                t[a][n] = (k, OTHER[k][a].0, OTHER[k][a].1);
                n += 1;
            }
            k += 1;
        }
        a += 1;
    }
    t
};

/// Visit marks of the tets near one insertion.
pub(crate) trait Marks {
    /// The mark of tet `t` (0 if unvisited).
    fn get(&self, t: u32) -> u8;
    /// Marks tet `t`.
    fn set(&mut self, t: u32, m: u8);
}

/// One byte per tet slot; the serial driver clears what it marked after each insertion.
impl Marks for Vec<u8> {
    #[inline]
    fn get(&self, t: u32) -> u8 {
        self[t as usize]
    }
    #[inline]
    fn set(&mut self, t: u32, m: u8) {
        self[t as usize] = m;
    }
}

/// Which tets an insertion may touch: all of them when inserting serially; in the parallel
/// insertion, the tets whose finite vertices all lie in the thread's region.
pub(crate) trait Owner {
    /// True if the tet with vertices `v` may be read and written.
    fn owns(&self, v: &[u32; 4]) -> bool;
}

/// Faces an insertion's cavity may not cross: the subfaces of a constrained tetrahedralization.
pub(crate) trait Walls {
    /// True if face `f` of tet `t` is a wall.
    fn wall(&self, t: u32, f: usize) -> bool;
}

/// No walls: plain Delaunay insertion.
pub(crate) struct NoWalls;

impl Walls for NoWalls {
    #[inline(always)]
    fn wall(&self, _t: u32, _f: usize) -> bool {
        false
    }
}

/// The serial insertion owns every tet.
pub(crate) struct Everything;

impl Owner for Everything {
    #[inline(always)]
    fn owns(&self, _v: &[u32; 4]) -> bool {
        true
    }
}

/// Where a point lies.
pub(crate) enum Located {
    /// A tet in conflict with the point.
    Conflict(u32),
    /// The point coincides with this vertex.
    Duplicate(u32),
    /// The walk reached a tet the insertion may not touch.
    Blocked,
    /// The point lies behind this wall (tet, face) seen from the start ([`locate_walled`]).
    Wall(u32, usize),
    /// The walk took more steps than it was allowed (walls can make it cycle).
    Lost,
}

/// Buffers reused by every insertion of one thread.
pub(crate) struct Scratch {
    /// The cavity's tets.
    pub cavity: Vec<u32>,
    stack: Vec<u32>,
    /// Cavity boundary: the face oriented so that `[a, b, c, p]` is positive, and the reference
    /// of the tet face outside it.
    pub boundary: Vec<([u32; 3], u32)>,
    /// The slots the star's tets go to, one per boundary face.
    pub slots: Vec<u32>,
    /// Pairs the star's faces.
    pub edges: EdgeTable,
    /// The walk's coin.
    pub rng: XorShift,
}

impl Scratch {
    /// Empty buffers; `seed` drives the walk's random face order.
    pub fn new(seed: u64) -> Self {
        Scratch {
            cavity: Vec::new(),
            stack: Vec::new(),
            boundary: Vec::new(),
            slots: Vec::new(),
            edges: EdgeTable::new(),
            rng: XorShift::new(seed),
        }
    }
}

/// Visibility walk from tet `start` to a tet in conflict with `p` (the finite tet whose
/// closure holds it, or the ghost beyond whose hull face it lies), or the vertex it duplicates.
pub(crate) fn locate<K: Kernel, S: TetStore, O: Owner>(k: &K, s: &S, o: &O, rng: &mut XorShift, start: u32, p: u32) -> Located {
    locate_walled(k, s, o, &NoWalls, rng, start, p, usize::MAX)
}

/// [`locate`] that stops at walls, and after `max_steps` steps (in a walled triangulation,
/// which need not be Delaunay, a visibility walk can cycle).
#[allow(clippy::too_many_arguments)]
pub(crate) fn locate_walled<K: Kernel, S: TetStore, O: Owner, W: Walls>(
    k: &K,
    s: &S,
    o: &O,
    walls: &W,
    rng: &mut XorShift,
    start: u32,
    p: u32,
    max_steps: usize,
) -> Located {
    let mut t = start;
    if s.v(t)[3] == GHOST {
        t = s.n(t, 3) >> 2;
    }
    let mut came_from = 4usize;
    for _ in 0..max_steps {
        let w = s.v(t);
        if !o.owns(&w) {
            return Located::Blocked;
        }
        let r = (rng.next_u64() >> 62) as usize;
        let mut next = None;
        for j in 0..4 {
            let f = (r + j) & 3;
            if f == came_from {
                continue;
            }
            // p is beyond face f when replacing vertex f by p gives a negative tet
            let mut q = w;
            q[f] = p;
            if k.orient(q[0], q[1], q[2], q[3]) == Sign::Negative {
                next = Some(f);
                break;
            }
        }
        match next {
            Some(f) => {
                if walls.wall(t, f) {
                    return Located::Wall(t, f);
                }
                let r = s.n(t, f);
                let n = r >> 2;
                let nv = s.v(n);
                if nv[3] == GHOST {
                    return if o.owns(&nv) { Located::Conflict(n) } else { Located::Blocked };
                }
                came_from = (r & 3) as usize;
                t = n;
            }
            None => {
                if let Some(&v) = w.iter().find(|&&v| k.same(v, p)) {
                    return Located::Duplicate(v);
                }
                return Located::Conflict(t);
            }
        }
    }
    Located::Lost
}

/// True if `p` lies inside the (perturbed) circumsphere of tet `t`; for a ghost tet, beyond
/// its hull face, or on its plane and in conflict with the finite tet behind it.
#[inline]
pub(crate) fn conflict<K: Kernel, S: TetStore>(k: &K, s: &S, t: u32, p: u32) -> bool {
    let w = s.v(t);
    if w[3] != GHOST {
        return k.insphere(w, p) == Sign::Positive;
    }
    match k.orient(w[0], w[1], w[2], p) {
        Sign::Positive => true,
        Sign::Negative => false,
        Sign::Zero => k.insphere(s.v(s.n(t, 3) >> 2), p) == Sign::Positive,
    }
}

/// Collects into `sc` the cavity of `p` (the connected tets in conflict, from `t0`) and its
/// boundary, marking visited tets `IN` or `OUT`. Returns false, having changed nothing but
/// marks (listed in the cavity and boundary buffers), as soon as a tet to visit is not owned.
pub(crate) fn dig<K: Kernel, S: TetStore, M: Marks, O: Owner>(
    k: &K,
    s: &S,
    o: &O,
    marks: &mut M,
    sc: &mut Scratch,
    t0: u32,
    p: u32,
) -> bool {
    dig_walled(k, s, o, &NoWalls, marks, sc, t0, p)
}

/// [`dig`] that does not cross walls: a wall face is a boundary face of the cavity whatever
/// lies behind it.
#[allow(clippy::too_many_arguments)]
pub(crate) fn dig_walled<K: Kernel, S: TetStore, M: Marks, O: Owner, W: Walls>(
    k: &K,
    s: &S,
    o: &O,
    walls: &W,
    marks: &mut M,
    sc: &mut Scratch,
    t0: u32,
    p: u32,
) -> bool {
    sc.cavity.clear();
    sc.boundary.clear();
    sc.stack.clear();
    marks.set(t0, IN);
    sc.cavity.push(t0);
    sc.stack.push(t0);
    while let Some(t) = sc.stack.pop() {
        for (f, fv) in TET_FACES.iter().enumerate() {
            let r = s.n(t, f);
            let n = r >> 2;
            let m = marks.get(n);
            if m == IN {
                continue;
            }
            if walls.wall(t, f) {
                let w = s.v(t);
                sc.boundary.push(([w[fv[0]], w[fv[2]], w[fv[1]]], r));
                continue;
            }
            if m != OUT {
                if !o.owns(&s.v(n)) {
                    return false;
                }
                if conflict(k, s, n, p) {
                    marks.set(n, IN);
                    sc.cavity.push(n);
                    sc.stack.push(n);
                    continue;
                }
                marks.set(n, OUT);
            }
            let w = s.v(t);
            // TET_FACES[f] turns outward from t; reversed, with p it makes a positive tet
            sc.boundary.push(([w[fv[0]], w[fv[2]], w[fv[1]]], r));
        }
    }
    true
}

/// Builds the star of `p` over a cavity boundary, the i-th boundary face's tet in `slots[i]`,
/// linked to the tet outside that face and to its neighbours in the star. Returns one of the
/// new tets.
pub(crate) fn fill<S: TetStore>(s: &mut S, edges: &mut EdgeTable, boundary: &[([u32; 3], u32)], slots: &[u32], p: u32) -> u32 {
    debug_assert_eq!(slots.len(), boundary.len());
    edges.reset(boundary.len() * 3 / 2);
    let mut last = 0;
    for (&(f, outside), &t) in boundary.iter().zip(slots) {
        let mut w = [f[0], f[1], f[2], p];
        let mut ip = 3;
        if let Some(g) = f.iter().position(|&v| v == GHOST) {
            // keep the ghost at position 3 by an even permutation
            w.swap(g, 3);
            ip = g;
            let (a, b) = OTHER[g][3];
            w.swap(a, b);
        }
        s.set_v(t, w);
        s.set_n(t, ip, outside);
        s.set_n(outside >> 2, (outside & 3) as usize, (t << 2) | ip as u32);
        for &(face, x, y) in &AROUND[ip] {
            let (a, b) = (w[x].min(w[y]), w[x].max(w[y]));
            let key = ((a as u64) << 32) | b as u64;
            let me = (t << 2) | face as u32;
            // the partner, if it came first; else NOWHERE, and the partner will write ours
            let r = edges.swap(key, me, NOWHERE);
            s.set_n(t, face, r);
            s.set_n(r >> 2, (r & 3) as usize, me);
        }
        last = t;
    }
    last
}

/// Links the faces around position `apex` of the given tets with each other (for the ghosts
/// around the first tet).
pub(crate) fn link_star<S: TetStore>(s: &mut S, sc: &mut Scratch, tets: &[u32], apex: usize) {
    sc.edges.reset(tets.len() * 3 / 2);
    for &t in tets {
        let w = s.v(t);
        for &(f, i, j) in &AROUND[apex] {
            let (a, b) = (w[i].min(w[j]), w[i].max(w[j]));
            let key = ((a as u64) << 32) | b as u64;
            let me = (t << 2) | f as u32;
            let r = sc.edges.swap(key, me, NOWHERE);
            s.set_n(t, f, r);
            s.set_n(r >> 2, (r & 3) as usize, me);
        }
    }
}
