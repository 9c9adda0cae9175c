//! The mesher's working tetrahedralization: the Delaunay insertion of
//! [`crate::mesh3d::delaunay`] on points that grow (Steiner points), with walls (the subfaces
//! of the boundary, which cavities do not cross once the boundary is recovered), a tet at
//! every vertex for star queries, and a check that every new tet is positively oriented before
//! anything is written (cavity correction: tets whose boundary faces do not see the new point
//! are given back, so insertion stays valid in a mesh that is not exactly Delaunay).
//!
//! Tets are `Tet` records (4 vertices, 4 neighbour references `(tet << 2) | face`) with ghost
//! tets closing the convex hull, as in the Delaunay module. Wall flags are one bit per tet face.

use crate::core::Sign;
use crate::core::predicates::orient3d;
use crate::core::ids::NONE;
use crate::core::spatial_order::brio_order;
use crate::mesh::tet_mesh::{TET_FACES, sorted3};
use crate::mesh3d::delaunay::cavity::{Everything, IN, Located, Marks, OUT, Scratch, Walls, dig_walled, fill, link_star, locate, locate_walled};
use crate::mesh3d::delaunay::kernel::{FloatKernel, Kernel};
use crate::mesh3d::delaunay::store::{DEAD, GHOST, Tet, cavity_slots, free_slot};
use glam::DVec3;

/// Wall bits: bit `f` of `walls[t]` is set when face `f` of tet `t` is a subface.
struct WallBits<'a>(&'a [u8]);

impl Walls for WallBits<'_> {
    #[inline]
    fn wall(&self, t: u32, f: usize) -> bool {
        self.0[t as usize] >> f & 1 != 0
    }
}

/// What an insertion did.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Inserted {
    /// The point is a vertex now; one of its tets.
    Yes(u32),
    /// The point coincides with this vertex; nothing changed.
    Duplicate(u32),
    /// The point lies behind this wall (tet, face) seen from the start; nothing changed.
    Blocked(u32, usize),
    /// The caller's check turned the cavity down (it named this wall: tet, face).
    Rejected(u32, usize),
    /// The point could not be inserted without breaking a wall or a tet (nothing changed).
    Refused,
}

/// Why [`Tetra::new`] made no tetrahedralization.
#[derive(Copy, Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub(crate) enum TetraError {
    /// The points span no tetrahedron.
    #[error("the surface vertices span no tetrahedron (all coplanar)")]
    Flat,
    /// Two points coincide (the second is the one being inserted).
    #[error("vertices {0} and {1} coincide")]
    Coincide(u32, u32),
    /// A point could not be inserted (our bug).
    #[error("vertex {0} could not be inserted")]
    NotInserted(u32),
}

/// A growing, possibly constrained, Delaunay tetrahedralization.
pub(crate) struct Tetra {
    /// Points (input vertices first, then Steiner points); ties broken by index.
    pub k: FloatKernel,
    /// Tet slots (slot 0 is scratch, ghosts close the hull, `DEAD` marks free slots).
    pub tets: Vec<Tet>,
    /// Wall bits per tet.
    pub walls: Vec<u8>,
    mark: Vec<u8>,
    free: Vec<u32>,
    sc: Scratch,
    /// A tet incident to every vertex (kept current by every insertion).
    pub vtet: Vec<u32>,
    /// Whether insertions stop at walls.
    pub walled: bool,
    /// The last tet created: walks start there by default.
    hint: u32,
    /// Tets given back by the cavity correction of the current insertion.
    dropped: Vec<u32>,
    /// Slots written by insertions since the caller last cleared it.
    pub created: Vec<u32>,
    /// Visit stamps per slot for the cavity correction, and the current stamp.
    seen: Vec<u32>,
    stamp: u32,
    /// Boundary insertion ([`Tetra::insert_on_boundary`]): the subfaces (sorted vertices) that
    /// the new point, which lies in their plane, removes. Empty otherwise.
    vanish: rustc_hash::FxHashSet<[u32; 3]>,
}

impl Tetra {
    /// The Delaunay tetrahedralization of `points` (all distinct, spanning a tetrahedron).
    ///
    /// # Errors
    /// [`TetraError`] when the points span no tetrahedron or some coincide (the caller checked
    /// the surface, so this is a bug or degenerate input it could not see).
    /// `ranks` orders the points for the symbolic perturbation (a permutation of `0..n`).
    pub fn new(points: Vec<DVec3>, ranks: Vec<u32>, seed: u64) -> Result<Self, TetraError> {
        let n = points.len();
        let order = brio_order(&points, seed);
        let k = FloatKernel { ids: ranks, points };
        let first = first_tet(&k, &order).ok_or(TetraError::Flat)?;
        let mut tr = Tetra {
            k,
            tets: Vec::with_capacity(n * 8 + 64),
            walls: Vec::with_capacity(n * 8 + 64),
            mark: Vec::with_capacity(n * 8 + 64),
            free: Vec::new(),
            sc: Scratch::new(seed),
            vtet: vec![NONE; n],
            walled: false,
            hint: 1,
            dropped: Vec::new(),
            created: Vec::new(),
            seen: Vec::new(),
            stamp: 0,
            vanish: Default::default(),
        };
        tr.push([DEAD; 4]);
        let t0 = tr.push(first);
        let mut ghosts = [0u32; 4];
        for (f, fv) in TET_FACES.iter().enumerate() {
            let g = tr.push([first[fv[0]], first[fv[1]], first[fv[2]], GHOST]);
            tr.tets[t0 as usize].n[f] = (g << 2) | 3;
            tr.tets[g as usize].n[3] = (t0 << 2) | f as u32;
            ghosts[f] = g;
        }
        link_star(&mut tr.tets, &mut tr.sc, &ghosts, 3);
        for &v in &first {
            tr.vtet[v as usize] = t0;
        }
        for &p in &order {
            if first.contains(&p) {
                continue;
            }
            match tr.insert_at(p, NONE) {
                Inserted::Yes(_) => {}
                Inserted::Duplicate(v) => return Err(TetraError::Coincide(p, v)),
                _ => return Err(TetraError::NotInserted(p)),
            }
        }
        Ok(tr)
    }

    /// Whether point `p` lies strictly inside finite tet `t` (exact) and nearer than `floor`
    /// to one of its vertices.
    fn near_inside(&self, t: u32, p: u32, floor: f64) -> bool {
        let v = self.tets[t as usize].v;
        if v.contains(&GHOST) || v.contains(&DEAD) {
            return false;
        }
        let q = self.point(p);
        let [a, b, c, d] = v.map(|i| self.point(i));
        [a, b, c, d].iter().any(|x| x.distance(q) < floor)
            && [orient3d(q, b, c, d), orient3d(a, q, c, d), orient3d(a, b, q, d), orient3d(a, b, c, q)].iter().all(|&s| s == Sign::Positive)
    }

    fn push(&mut self, v: [u32; 4]) -> u32 {
        let t = self.tets.len() as u32;
        self.tets.push(Tet { v, n: [0; 4] });
        self.walls.push(0);
        self.mark.push(0);
        t
    }

    /// A live tet to start walks from when nothing nearer is known: the last tet created.
    fn default_start(&self) -> u32 {
        if self.tets.get(self.hint as usize).is_some_and(|t| t.v[0] != DEAD) {
            return self.hint;
        }
        (1..self.tets.len() as u32).rev().find(|&t| self.tets[t as usize].v[0] != DEAD).unwrap_or(1)
    }

    /// Appends a point; returns its index (not yet inserted).
    pub fn add_point(&mut self, p: DVec3) -> u32 {
        let i = self.k.points.len() as u32;
        self.k.points.push(p);
        self.k.ids.push(i);
        self.vtet.push(NONE);
        i
    }

    /// Removes the last point added if no tet uses it (a candidate that was not inserted).
    pub fn remove_last_point(&mut self) {
        if self.vtet.last() == Some(&NONE) {
            self.k.points.pop();
            self.k.ids.pop();
            self.vtet.pop();
        }
    }

    /// Number of points.
    pub fn num_points(&self) -> usize {
        self.k.points.len()
    }

    /// Position of point `v`.
    #[inline]
    pub fn point(&self, v: u32) -> DVec3 {
        self.k.points[v as usize]
    }

    /// True for a live finite tet.
    #[inline]
    pub fn finite(&self, t: u32) -> bool {
        let v = self.tets[t as usize].v;
        v[0] != DEAD && v[3] != GHOST
    }

    /// Inserts point `p` (already added), starting the walk at tet `start` (any live tet; a
    /// tet near `p` makes it fast).
    pub fn insert_at(&mut self, p: u32, start: u32) -> Inserted {
        self.insert_checked(p, start, |_, _| None)
    }

    /// [`Tetra::insert_at`] with a check before anything is written: `check` sees the faces
    /// on the cavity's boundary (as (outside tet, face) references, the face vertices oriented
    /// towards `p`) and may turn the insertion down by naming one of them.
    pub fn insert_checked<F>(&mut self, p: u32, start: u32, check: F) -> Inserted
    where
        F: FnOnce(&Tetra, &[([u32; 3], u32)]) -> Option<(u32, usize)>,
    {
        self.insert_checked_near(p, start, None, check)
    }

    /// [`Tetra::insert_checked`] for a check that turns the point down, as `verdict`, where a
    /// vertex of the cavity's outline lies nearer than `floor` (`near: Some((floor,
    /// verdict))`): where the point lies strictly inside the tet the walk finds and nearer than
    /// `floor` to one of that tet's vertices, it is turned down so without digging the cavity.
    /// That tet holds the point, so it stays in the cavity and its vertices are on the
    /// outline: the check would turn it down (or the correction refuse it). The walk is the
    /// same either way, so what follows is the same.
    pub fn insert_checked_near<F>(&mut self, p: u32, start: u32, near: Option<(f64, (u32, usize))>, check: F) -> Inserted
    where
        F: FnOnce(&Tetra, &[([u32; 3], u32)]) -> Option<(u32, usize)>,
    {
        let start = if start != NONE && (start as usize) < self.tets.len() && self.tets[start as usize].v[0] != DEAD {
            start
        } else {
            self.default_start()
        };
        let walls = WallBits(&self.walls);
        let located = if !self.vanish.is_empty() {
            Located::Conflict(start) // a boundary insertion starts in a tet it conflicts with
        } else if self.walled {
            locate_walled(&self.k, &self.tets, &Everything, &walls, &mut self.sc.rng, start, p, 4 * self.tets.len() + 16)
        } else {
            locate(&self.k, &self.tets, &Everything, &mut self.sc.rng, start, p)
        };
        let t0 = match located {
            Located::Conflict(t) => t,
            Located::Duplicate(v) => return Inserted::Duplicate(v),
            Located::Wall(t, f) => return Inserted::Blocked(t, f),
            Located::Blocked | Located::Lost => return Inserted::Refused,
        };
        if let Some((floor, (t, f))) = near {
            if self.near_inside(t0, p, floor) {
                return Inserted::Rejected(t, f);
            }
        }
        let ok = if self.walled {
            dig_walled(&self.k, &self.tets, &Everything, &walls, &mut self.mark, &mut self.sc, t0, p)
        } else {
            dig_walled(&self.k, &self.tets, &Everything, &crate::mesh3d::delaunay::cavity::NoWalls, &mut self.mark, &mut self.sc, t0, p)
        };
        debug_assert!(ok);
        // every tet dig marked, so that all marks get cleared whatever the correction drops
        self.dropped.extend_from_slice(&self.sc.cavity);
        self.dropped.extend(self.sc.boundary.iter().map(|&(_, r)| r >> 2));
        let visible = self.correct_cavity(t0, p);
        self.clear_marks();
        if !visible {
            return Inserted::Refused;
        }
        let boundary = std::mem::take(&mut self.sc.boundary);
        let verdict = check(self, &boundary);
        self.sc.boundary = boundary;
        if let Some((t, f)) = verdict {
            return Inserted::Rejected(t, f);
        }
        if !self.vanish.is_empty() {
            // the subfaces the point removes get no new tet: the new faces on their outline
            // stay unpaired and look at slot 0 (outside) once filled
            let vanish = &self.vanish;
            self.sc.boundary.retain(|(f, r)| r >> 2 != 0 || !vanish.contains(&sorted3(*f).0));
        }
        let m = self.sc.boundary.len();
        let c = self.sc.cavity.len();
        // the walls of the boundary faces, read before the cavity slots are reused
        let mut wall_of: Vec<bool> = Vec::with_capacity(m);
        for &(_, r) in &self.sc.boundary {
            wall_of.push(self.walls[(r >> 2) as usize] >> (r & 3) & 1 != 0);
        }
        let (walls, mark) = (&mut self.walls, &mut self.mark);
        let new_slot = |tets: &mut Vec<Tet>| {
            tets.push(Tet { v: [DEAD; 4], n: [0; 4] });
            walls.push(0);
            mark.push(0);
            Some(tets.len() as u32 - 1)
        };
        cavity_slots(&mut self.tets, &self.sc.cavity, m, &mut self.free, &mut self.sc.slots, new_slot);
        for &t in &self.sc.cavity[m.min(c)..] {
            self.walls[t as usize] = 0;
        }
        let sc = &mut self.sc;
        let last = fill(&mut self.tets, &mut sc.edges, &sc.boundary, &sc.slots, p);
        // walls: a new tet's face opposite p is the old boundary face, a wall if it was one
        for (i, &t) in self.sc.slots.iter().enumerate() {
            let ip = self.tets[t as usize].v.iter().position(|&v| v == p).unwrap_or(3);
            self.walls[t as usize] = if wall_of[i] { 1 << ip } else { 0 };
            for v in self.tets[t as usize].v {
                if v != GHOST {
                    self.vtet[v as usize] = t;
                }
            }
        }
        self.created.extend_from_slice(&self.sc.slots);
        self.hint = last;
        Inserted::Yes(last)
    }

    /// Inserts point `p` (already added), which lies on the boundary in the plane of the
    /// subfaces `vanish` (sorted vertices) that it removes, once the exterior is gone (those
    /// subfaces face slot 0). The cavity grows from `start`, a material tet on one of them
    /// whose circumsphere holds `p`; the subfaces get no new tet, and the new faces along
    /// their outline look at slot 0 (the caller makes them walls). `check` as for
    /// [`Tetra::insert_checked`].
    pub fn insert_on_boundary<F>(&mut self, p: u32, start: u32, vanish: rustc_hash::FxHashSet<[u32; 3]>, check: F) -> Inserted
    where
        F: FnOnce(&Tetra, &[([u32; 3], u32)]) -> Option<(u32, usize)>,
    {
        if vanish.is_empty() {
            return Inserted::Refused;
        }
        self.vanish = vanish;
        let res = self.insert_checked(p, start, check);
        self.vanish.clear();
        res
    }

    /// Gives back cavity tets whose boundary faces `p` does not see strictly (their new tet
    /// would be flat or inverted), until every boundary face is visible or the tet holding `p`
    /// itself would go. Rebuilds the boundary list. Returns false in the latter case.
    fn correct_cavity(&mut self, t0: u32, p: u32) -> bool {
        loop {
            // every cavity tet behind a boundary face that p does not see strictly, and every
            // cavity tet with a wall to another cavity tet, goes (all at once)
            let mut bad: Vec<u32> = Vec::new();
            for &(f, r) in &self.sc.boundary {
                if f.contains(&GHOST) || (r >> 2 == 0 && !self.vanish.is_empty() && self.vanish.contains(&sorted3(f).0)) {
                    continue;
                }
                if self.k.orient(f[0], f[1], f[2], p) != Sign::Positive {
                    // the cavity tet on the inner side of this face: the outside tet's
                    // neighbour across it, or (the outside may be slot 0, which many faces
                    // share once the exterior is gone) found by its vertices
                    let (out, g) = ((r >> 2) as usize, (r & 3) as usize);
                    let across = if out != 0 { Some(self.tets[out].n[g] >> 2).filter(|&c| self.mark[c as usize] == IN) } else { None };
                    let inner = across.or_else(|| self.sc.cavity.iter().copied().find(|&c| f.iter().all(|x| self.tets[c as usize].v.contains(x))));
                    bad.push(inner.unwrap_or(t0));
                }
            }
            for &t in &self.sc.cavity {
                for f in 0..4 {
                    if self.walls[t as usize] >> f & 1 != 0 && self.mark[(self.tets[t as usize].n[f] >> 2) as usize] == IN {
                        bad.push(t);
                    }
                }
            }
            if bad.is_empty() {
                return true;
            }
            if bad.contains(&t0) {
                return false;
            }
            for &b in &bad {
                self.mark[b as usize] = OUT;
            }
            // keep the part of the cavity connected to t0 only (through non-wall faces)
            self.stamp = self.stamp.wrapping_add(1);
            if self.seen.len() < self.tets.len() {
                self.seen.resize(self.tets.len(), 0);
            }
            let stamp = self.stamp;
            let mut keep = vec![t0];
            self.seen[t0 as usize] = stamp;
            let mut i = 0;
            while i < keep.len() {
                let t = keep[i];
                for f in 0..4 {
                    let n = self.tets[t as usize].n[f] >> 2;
                    if self.mark[n as usize] == IN && self.seen[n as usize] != stamp && self.walls[t as usize] >> f & 1 == 0 {
                        self.seen[n as usize] = stamp;
                        keep.push(n);
                    }
                }
                i += 1;
            }
            for &t in &self.sc.cavity {
                if self.seen[t as usize] != stamp {
                    self.mark[t as usize] = OUT;
                    // tets dropped from the cavity are remembered so that their marks get cleared
                    self.dropped.push(t);
                }
            }
            self.sc.cavity = keep;
            // rebuild the boundary from the cavity
            self.sc.boundary.clear();
            for i in 0..self.sc.cavity.len() {
                let t = self.sc.cavity[i];
                let w = self.tets[t as usize].v;
                for (f, fv) in TET_FACES.iter().enumerate() {
                    let r = self.tets[t as usize].n[f];
                    if self.mark[(r >> 2) as usize] != IN {
                        self.sc.boundary.push(([w[fv[0]], w[fv[2]], w[fv[1]]], r));
                    }
                }
            }
        }
    }

    fn clear_marks(&mut self) {
        for &t in &self.sc.cavity {
            self.mark.set(t, 0);
        }
        for &(_, r) in &self.sc.boundary {
            self.mark.set(r >> 2, 0);
        }
        for &t in &self.dropped {
            self.mark.set(t, 0);
        }
        self.dropped.clear();
    }

    /// The tets incident to vertex `v` (finite and ghost), by a walk around it.
    pub fn star(&self, v: u32, out: &mut Vec<u32>) {
        self.star_find(v, out, |_| false);
    }

    /// Walks the star of `v` as [`Tetra::star`] does, in the same order, and stops at the first
    /// tet for which `found` holds (then `out` holds the star only up to there).
    fn star_find(&self, v: u32, out: &mut Vec<u32>, found: impl Fn(u32) -> bool) -> Option<u32> {
        out.clear();
        let t0 = self.vtet[v as usize];
        if t0 == NONE {
            return None;
        }
        out.push(t0);
        // a linear search while the star is small, a set once it is large (the star of a
        // pole vertex holds thousands of tets)
        const SMALL: usize = 48;
        let mut seen: rustc_hash::FxHashSet<u32> = Default::default();
        let mut i = 0;
        while i < out.len() {
            let t = out[i];
            if found(t) {
                return Some(t);
            }
            let tv = self.tets[t as usize].v;
            for (f, &tf) in tv.iter().enumerate() {
                if tf == v {
                    continue; // the face opposite v does not contain it
                }
                let n = self.tets[t as usize].n[f] >> 2;
                if n == 0 {
                    continue;
                }
                if out.len() < SMALL {
                    if !out.contains(&n) {
                        out.push(n);
                    }
                } else {
                    if seen.is_empty() {
                        seen.extend(out.iter().copied());
                    }
                    if seen.insert(n) {
                        out.push(n);
                    }
                }
            }
            i += 1;
        }
        None
    }

    /// A tet holding edge `(a, b)`, if it is an edge of the tetrahedralization: the first in
    /// the walk around `a`.
    pub fn edge_tet(&self, a: u32, b: u32, buf: &mut Vec<u32>) -> Option<u32> {
        self.star_find(a, buf, |t| self.tets[t as usize].v.contains(&b))
    }

    /// Whether `(a, b, c)` is a face of the tetrahedralization: [`Tetra::face_of`]`.is_some()`
    /// (see [`Tetra::face_tet`]).
    pub fn has_face(&self, a: u32, b: u32, c: u32, buf: &mut Vec<u32>) -> bool {
        self.face_tet(a, b, c, buf).is_some()
    }

    /// A tet holding face `(a, b, c)` and the face's index in it, if it is a face of the
    /// tetrahedralization: either of the two sides, where [`Tetra::face_of`] gives the first
    /// in the walk around `a`. Found by walking the star of `a` only to the first tet on edge
    /// `(a, b)` and then around that edge (the face is held by two of the tets around it, the
    /// edge by all of them, so the walk stops sooner).
    pub fn face_tet(&self, a: u32, b: u32, c: u32, buf: &mut Vec<u32>) -> Option<(u32, usize)> {
        let t0 = self.edge_tet(a, b, buf)?;
        let at = |t: u32| {
            let v = self.tets[t as usize].v;
            if v.contains(&c) { v.iter().position(|&w| w != a && w != b && w != c).map(|k| (t, k)) } else { None }
        };
        if let Some(x) = at(t0) {
            return Some(x);
        }
        // the tets around edge (a, b) in both directions from t0: leaving a tet across the
        // face opposite `opp`, the next tet is left across the face opposite the vertex the
        // two share besides a and b
        let v0 = self.tets[t0 as usize].v;
        let mut others = v0.iter().copied().filter(|&x| x != a && x != b);
        let (x, y) = (others.next()?, others.next()?);
        for (first, shared) in [(x, y), (y, x)] {
            let (mut t, mut opp, mut keep) = (t0, first, shared);
            // the most steps: the tets around an edge (a bound against a broken structure)
            for _ in 0..self.tets.len() {
                let f = self.tets[t as usize].v.iter().position(|&w| w == opp)?;
                let n = self.tets[t as usize].n[f] >> 2;
                if n == 0 {
                    break; // the hull: the other direction
                }
                if n == t0 {
                    return None; // all the way round
                }
                if let Some(x) = at(n) {
                    return Some(x);
                }
                let nv = self.tets[n as usize].v;
                (opp, keep) = (keep, nv.iter().copied().find(|&w| w != a && w != b && w != keep).unwrap_or(keep));
                t = n;
            }
        }
        None
    }

    /// The tet and face index of face `(a, b, c)`, if it is a face of the tetrahedralization
    /// (one of the two sides).
    pub fn face_of(&self, a: u32, b: u32, c: u32, buf: &mut Vec<u32>) -> Option<(u32, usize)> {
        let t = self.star_find(a, buf, |t| {
            let v = self.tets[t as usize].v;
            v.contains(&b) && v.contains(&c)
        })?;
        let v = self.tets[t as usize].v;
        let f = (0..4).find(|&i| v[i] != a && v[i] != b && v[i] != c)?;
        Some((t, f))
    }

    /// Sets or clears the wall flag of face `f` of tet `t` and of the same face seen from its
    /// neighbour.
    pub fn set_wall(&mut self, t: u32, f: usize, on: bool) {
        let r = self.tets[t as usize].n[f];
        let (n, g) = ((r >> 2) as usize, (r & 3) as usize);
        if on {
            self.walls[t as usize] |= 1 << f;
            self.walls[n] |= 1 << g;
        } else {
            self.walls[t as usize] &= !(1 << f);
            self.walls[n] &= !(1 << g);
        }
    }

    /// Frees slot `t` (its tet is gone; nothing may refer to it any more).
    pub fn free_slot(&mut self, t: u32) {
        free_slot(&mut self.tets, &mut self.free, t);
        self.walls[t as usize] = 0;
    }

    /// The live finite tets.
    pub fn live(&self) -> impl Iterator<Item = u32> + '_ {
        (1..self.tets.len() as u32).filter(|&t| self.finite(t))
    }
}


/// Four points spanning a positive tet, in insertion order.
fn first_tet(k: &FloatKernel, order: &[u32]) -> Option<[u32; 4]> {
    let a = *order.first()?;
    let b = *order.iter().find(|&&i| !k.same(i, a))?;
    let c = *order.iter().find(|&&i| !k.collinear(a, b, i))?;
    let d = *order.iter().find(|&&i| !k.orient(a, b, c, i).is_zero())?;
    Some(if k.orient(a, b, c, d) == Sign::Positive { [a, b, c, d] } else { [b, a, c, d] })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point strictly inside a tet and near one of its vertices is turned down as the check
    /// would turn it down, without a cavity dug, the walk's generator left where the check's
    /// call leaves it; elsewhere the check decides.
    #[test]
    fn a_point_near_a_vertex_of_its_tet_is_turned_down_as_the_check_would() {
        let points: Vec<DVec3> = (0..40u32).map(|i| DVec3::new((i * 7 % 11) as f64, (i * 5 % 13) as f64 * 0.9, (i * 3 % 17) as f64 * 0.7 + 0.01 * i as f64)).collect();
        let n = points.len() as u32;
        let build = || Tetra::new(points.clone(), (0..n).collect(), 11).unwrap();
        let (mut a, mut b) = (build(), build());
        let tets: Vec<u32> = a.live().filter(|&t| a.finite(t)).collect();
        let (mut near, mut far) = (0, 0);
        for (i, t) in tets.into_iter().enumerate() {
            let v = a.tets[t as usize].v;
            let p = v.map(|i| a.point(i));
            let q = p[0] * 0.7 + (p[1] + p[2] + p[3]) * 0.1;
            let floor = 1.5 * q.distance(p[0]);
            // start the walk from another tet now and then: the tet it finds decides
            let start = if i % 3 == 0 { 1 } else { t };
            let check = |tr: &Tetra, faces: &[([u32; 3], u32)]| faces.iter().flat_map(|x| x.0).filter(|&x| x != GHOST).any(|x| tr.point(x).distance(q) < floor).then_some((7, 2));
            let before = a.tets.clone();
            let (ia, ib) = (a.add_point(q), b.add_point(q));
            let ra = a.insert_checked(ia, start, check);
            let rb = b.insert_checked_near(ib, start, Some((floor, (7, 2))), check);
            let inside = b.near_inside(t, ib, floor);
            a.remove_last_point();
            b.remove_last_point();
            assert!(matches!(ra, Inserted::Rejected(7, 2) | Inserted::Refused), "tet {t}: {ra:?}");
            assert!(matches!(rb, Inserted::Rejected(7, 2) | Inserted::Refused), "tet {t}: {rb:?}");
            if inside {
                near += 1;
            } else {
                far += 1;
            }
            assert_eq!(a.tets, before);
            assert_eq!(b.tets, before);
            assert_eq!(a.sc.rng.clone().next_u64(), b.sc.rng.clone().next_u64(), "tet {t}");
        }
        assert!(near >= 20 && far >= 1, "{near} near, {far} not (flat tets)");
    }

    /// `has_face` and `face_tet` answer as `face_of` does for every triple of points of a
    /// tetrahedralization with hull edges and cospherical points (a grid), both present faces
    /// and absent ones.
    #[test]
    fn has_face_agrees_with_face_of() {
        let mut points = Vec::new();
        for i in 0..3 {
            for j in 0..3 {
                for k in 0..3 {
                    points.push(DVec3::new(i as f64, j as f64, k as f64 + 0.1 * ((i * j) % 2) as f64));
                }
            }
        }
        let n = points.len() as u32;
        let tr = Tetra::new(points, (0..n).collect(), 3).unwrap();
        let mut buf = Vec::new();
        let (mut present, mut absent) = (0, 0);
        for a in 0..n {
            for b in 0..n {
                for c in 0..n {
                    if a == b || b == c || a == c {
                        continue;
                    }
                    let want = tr.face_of(a, b, c, &mut buf);
                    let got = tr.face_tet(a, b, c, &mut buf);
                    assert_eq!(got.is_some(), want.is_some(), "face ({a}, {b}, {c})");
                    assert_eq!(tr.has_face(a, b, c, &mut buf), want.is_some());
                    if let (Some((t, k)), Some((u, l))) = (got, want) {
                        // the same tet or the one across the face, the face opposite k
                        let v = tr.tets[t as usize].v;
                        assert!(![a, b, c].contains(&v[k]) && [a, b, c].iter().all(|x| v.contains(x)));
                        assert!(t == u || tr.tets[u as usize].n[l] >> 2 == t, "face ({a}, {b}, {c})");
                    }
                    let want = want.is_some();
                    if want {
                        present += 1;
                    } else {
                        absent += 1;
                    }
                }
            }
        }
        assert!(present > 100 && absent > 1000, "{present} present, {absent} absent");
    }
}
