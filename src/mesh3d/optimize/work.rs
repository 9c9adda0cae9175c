//! The optimiser's working mesh: tets with face adjacency, constrained faces, cached scores,
//! and one transactional operation, [`Work::replace`], through which every topological change
//! goes.
//!
//! Adjacency is built once from sorted face records. A face is *constrained* when it is a hull
//! face (one tet), a `boundary` triangle of the input, or lies between tets of different
//! regions; constrained faces are never removed, and their vertices (*fixed* vertices) never
//! move. Dead tet slots are kept on a free list and reused, so slot numbers are deterministic.

use crate::core::ids::NONE;
use crate::core::predicates::orient3d;
use crate::core::{BoundaryGeometry, RegionId, Sign};
use crate::mesh::tet_mesh::{TET_FACES, sorted3};
use crate::mesh::tri_surface::{check_finite, check_simplex};
use crate::mesh::{Element, MeshError, TetMesh};
use crate::mesh3d::optimize::measure::{Judged, Targets};
use crate::mesh3d::optimize::vertex_slide::{Fan, Slide};
use glam::DVec3;
use rayon::prelude::*;

/// The most tets the working mesh can hold: neighbour codes pack `tet << 2 | face`, and every
/// code stays below [`NONE`].
pub(crate) const MAX_TETS: usize = (NONE >> 2) as usize;

/// The working mesh; `'g` is the life of the boundary's geometry, if it has one.
pub(crate) struct Work<'g> {
    /// Vertex positions (inserted vertices appended).
    pub pts: Vec<DVec3>,
    /// Tets; a dead slot holds `[NONE; 4]`.
    pub tets: Vec<[u32; 4]>,
    /// Neighbour across face `k` (opposite vertex `k`) as `tet << 2 | face`, or [`NONE`].
    pub nbr: Vec<[u32; 4]>,
    /// Bit `k` set: face `k` is constrained.
    pub cons: Vec<u8>,
    /// Region of each tet.
    pub region: Vec<RegionId>,
    /// Cached score of each live tet.
    pub q: Vec<f64>,
    /// Cached judged measures of each live tet (the score's inputs).
    pub judged: Vec<Judged>,
    /// Dead slots, reused last-in first-out.
    free: Vec<u32>,
    /// One live tet at each vertex.
    pub v2t: Vec<u32>,
    /// Vertices of constrained faces: they never move, unless they may slide.
    pub fixed: Vec<bool>,
    /// How each fixed vertex may slide without changing the boundary
    /// ([`crate::mesh3d::optimize::slide`]); all `None` unless the options allow it.
    pub slide: Vec<Option<Slide>>,
    /// The geometry the boundary approximates, onto which vertices sliding on curved faces
    /// and edges go back ([`Slide::snap`]).
    pub geo: Option<&'g dyn BoundaryGeometry>,
    /// The boundary triangles at each vertex sliding on a curved face or edge, which its moves
    /// must keep in shape ([`Fan::keeps`]).
    pub fans: rustc_hash::FxHashMap<u32, Fan>,
    /// Per vertex, the [`Work::clock`] of the last change of a tet at it.
    pub touched: Vec<u32>,
    /// Counts the changes (topological or moves), from 1.
    pub clock: u32,
    /// Visit marks per tet slot, compared with `stamp`.
    mark: Vec<u32>,
    stamp: u32,
    /// The score targets.
    pub tg: Targets,
    // scratch for `replace`
    outer: Vec<FaceRec>,
    inner: Vec<FaceRec>,
    slots: Vec<u32>,
    stack: Vec<u32>,
}

/// A face in `replace`: sorted vertices, parity of the outward orientation relative to the
/// sorted order, and where it leads (a neighbour code, or a new tet's `index << 2 | face`).
#[derive(Copy, Clone, Debug)]
struct FaceRec {
    key: [u32; 3],
    even: bool,
    link: u32,
    constrained: bool,
}

/// The permutation parity of four distinct local indices: true if even.
#[inline]
pub(crate) fn even_perm(p: [usize; 4]) -> bool {
    let mut inv = 0;
    for i in 0..4 {
        for j in i + 1..4 {
            inv += usize::from(p[i] > p[j]);
        }
    }
    inv % 2 == 0
}

/// Position of `v` in `t`, if any.
#[inline]
pub(crate) fn local(t: &[u32; 4], v: u32) -> Option<usize> {
    t.iter().position(|&x| x == v)
}

/// A face record of [`adjacency`], in the bucket of the face's smallest vertex: the other two
/// vertices (`b << 32 | c`, `b < c`), the face as `tet << 2 | face`, and whether its outward
/// orientation is an even permutation of the sorted vertices.
#[derive(Copy, Clone, Default)]
struct Rec {
    bc: u64,
    code: u32,
    even: bool,
}

/// Face adjacency (`tet << 2 | face` codes, [`NONE`] on the hull) and constrained-face bits of
/// `mesh`, whose indices are already checked: face records are bucketed by their smallest vertex
/// (a counting sort) and each small bucket is sorted on its own.
///
/// # Errors
/// [`MeshError::NonManifold`] for a face of more than two tets, [`MeshError::Overlap`] for two
/// tets on the same side of a face, [`MeshError::BoundaryNotAFace`].
/// A tet mesh's adjacency as the optimiser keeps it: per tet and face (face `k` opposite
/// vertex `k`, [`TET_FACES`]), the neighbour's index and face (`j << 2 | k'`, [`NONE`] where
/// there is none), and a bit per constrained face (on the boundary of the mesh, between two
/// regions, or a listed boundary triangle).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Adjacency {
    pub nbr: Vec<[u32; 4]>,
    pub cons: Vec<u8>,
}

/// The adjacency of `mesh` by sorting its faces, checking that each face has at most two tets,
/// on opposite sides, and that each boundary triangle is a face.
pub(crate) fn adjacency(mesh: &TetMesh) -> Result<Adjacency, MeshError> {
    let (nt, nv) = (mesh.tets.len(), mesh.vertices.len());
    let start = mesh.face_bucket_starts();
    let mut rec = vec![Rec::default(); 4 * nt];
    let mut fill = start.clone();
    for (t, tet) in mesh.tets.iter().enumerate() {
        for (k, f) in TET_FACES.iter().enumerate() {
            let (key, even) = sorted3([tet[f[0]], tet[f[1]], tet[f[2]]]);
            let i = &mut fill[key[0] as usize];
            rec[*i] = Rec { bc: u64::from(key[1]) << 32 | u64::from(key[2]), code: (t as u32) << 2 | k as u32, even };
            *i += 1;
        }
    }
    drop(fill);
    crate::core::bucket_sort::sort_buckets_by(&mut rec, &start, |x, y| (x.bc, x.code).cmp(&(y.bc, y.code)));
    let key_of = |a: usize, r: &Rec| [a as u32, (r.bc >> 32) as u32, r.bc as u32];
    // the first record of each listed face
    let mut listed = vec![false; rec.len()];
    for (i, tri) in mesh.boundary.iter().enumerate() {
        let key = sorted3(*tri).0;
        let (lo, hi) = (start[key[0] as usize], start[key[0] as usize + 1]);
        let bc = u64::from(key[1]) << 32 | u64::from(key[2]);
        let first = lo + rec[lo..hi].partition_point(|r| r.bc < bc);
        if first == hi || rec[first].bc != bc {
            return Err(MeshError::BoundaryNotAFace { triangle: i, vertices: *tri });
        }
        listed[first] = true;
    }
    let mut nbr = vec![[NONE; 4]; nt];
    let mut cons = vec![0u8; nt];
    for a in 0..nv {
        let (mut i, hi) = (start[a], start[a + 1]);
        while i < hi {
            let mut j = i + 1;
            while j < hi && rec[j].bc == rec[i].bc {
                j += 1;
            }
            let r = rec[i];
            let (t0, k0) = ((r.code >> 2) as usize, (r.code & 3) as usize);
            if j - i > 2 {
                return Err(MeshError::NonManifold {
                    entity: key_of(a, &r).to_vec(),
                    elements: rec[i..j].iter().map(|r| Element::Tet((r.code >> 2) as usize)).collect(),
                });
            }
            if j - i == 2 {
                let s = rec[i + 1];
                let (t1, k1) = ((s.code >> 2) as usize, (s.code & 3) as usize);
                if r.even == s.even {
                    return Err(MeshError::Overlap {
                        entity: key_of(a, &r).to_vec(),
                        first: Element::Tet(t0),
                        second: Element::Tet(t1),
                    });
                }
                nbr[t0][k0] = s.code;
                nbr[t1][k1] = r.code;
                if listed[i] || mesh.region_tags[t0] != mesh.region_tags[t1] {
                    cons[t0] |= 1 << k0;
                    cons[t1] |= 1 << k1;
                }
            } else {
                cons[t0] |= 1 << k0;
            }
            i = j;
        }
    }
    Ok(Adjacency { nbr, cons })
}

impl<'g> Work<'g> {
    /// [`Work::build_with`], the adjacency found by sorting the faces.
    #[cfg(test)]
    pub(crate) fn build(mesh: &TetMesh, tg: Targets) -> Result<Work<'g>, MeshError> {
        Work::build_with(mesh, tg, None)
    }

    /// Builds the working mesh, checking what the optimiser relies on: array lengths, finite
    /// coordinates, indices, exact positive orientation of every tet, at most two tets per face
    /// and from opposite sides, and every boundary triangle a face. Where the caller gives the
    /// adjacency (the mesher, from its tetrahedralization's links, [`Adjacency`]), it is taken
    /// as it is: the last two checks are the caller's.
    ///
    /// # Errors
    /// The first violation, as [`MeshError`] (the same variants as [`TetMesh::validate`]).
    pub(crate) fn build_with(mesh: &TetMesh, tg: Targets, given: Option<Adjacency>) -> Result<Work<'g>, MeshError> {
        let nt = mesh.tets.len();
        if mesh.region_tags.len() != nt {
            return Err(MeshError::LengthMismatch { what: "region_tags", found: mesh.region_tags.len(), expected: nt });
        }
        if mesh.face_tags.len() != mesh.boundary.len() {
            return Err(MeshError::LengthMismatch {
                what: "face_tags",
                found: mesh.face_tags.len(),
                expected: mesh.boundary.len(),
            });
        }
        check_finite(&mesh.vertices)?;
        let nv = mesh.vertices.len();
        for (t, tet) in mesh.tets.iter().enumerate() {
            check_simplex(Element::Tet(t), tet, nv)?;
        }
        for (t, tri) in mesh.boundary.iter().enumerate() {
            check_simplex(Element::BoundaryTriangle(t), tri, nv)?;
        }
        let pts = mesh.vertices.clone();
        let orient = |t: &[u32; 4]| {
            let [a, b, c, d] = t.map(|i| pts[i as usize]);
            orient3d(a, b, c, d)
        };
        // the adjacency (serial: a bucket sort and a scan) beside the orientation check and the
        // tets' measures (in parallel); an orientation error is reported first, as the checks
        // are listed
        let (adjacent, (inverted, judged)) = rayon::join(
            || match given {
                Some(a) if a.nbr.len() == mesh.tets.len() && a.cons.len() == mesh.tets.len() => Ok(a),
                _ => adjacency(mesh),
            },
            || {
                let inverted = mesh.tets.par_iter().position_first(|t| orient(t) != Sign::Positive);
                let judged: Vec<Judged> = if inverted.is_some() {
                    Vec::new()
                } else {
                    mesh.tets.par_iter().with_min_len(1024).map(|t| Judged::of(&t.map(|i| pts[i as usize]))).collect()
                };
                (inverted, judged)
            },
        );
        if let Some(t) = inverted {
            return Err(MeshError::BadOrientation {
                element: Element::Tet(t),
                vertices: mesh.tets[t].to_vec(),
                orientation: orient(&mesh.tets[t]),
            });
        }
        let Adjacency { nbr, cons } = adjacent?;
        let mut fixed = vec![false; nv];
        let mut v2t = vec![NONE; nv];
        for (t, tet) in mesh.tets.iter().enumerate() {
            if cons[t] != 0 {
                for (k, f) in TET_FACES.iter().enumerate() {
                    if cons[t] & (1 << k) != 0 {
                        for &l in f {
                            fixed[tet[l] as usize] = true;
                        }
                    }
                }
            }
            for &v in tet {
                v2t[v as usize] = t as u32;
            }
        }
        let q = judged.par_iter().with_min_len(4096).map(|j| j.score(&tg)).collect();
        Ok(Work {
            pts,
            tets: mesh.tets.clone(),
            nbr,
            cons,
            region: mesh.region_tags.clone(),
            q,
            judged,
            free: Vec::new(),
            v2t,
            touched: vec![0; nv],
            clock: 1,
            fixed,
            slide: vec![None; nv],
            geo: None,
            fans: rustc_hash::FxHashMap::default(),
            mark: vec![0; nt],
            stamp: 0,
            tg,
            outer: Vec::new(),
            inner: Vec::new(),
            slots: Vec::new(),
            stack: Vec::new(),
        })
    }

    /// Writes the live tets (in slot order), their regions and the vertices back into `mesh`.
    pub(crate) fn write_back(self, mesh: &mut TetMesh) {
        let mut tets = Vec::with_capacity(self.tets.len() - self.free.len());
        let mut regions = Vec::with_capacity(tets.capacity());
        for (t, r) in self.tets.iter().zip(&self.region) {
            if t[0] != NONE {
                tets.push(*t);
                regions.push(*r);
            }
        }
        mesh.vertices = self.pts;
        mesh.tets = tets;
        mesh.region_tags = regions;
    }

    /// Whether vertex `v` may move: on no constrained face, or allowed to slide.
    #[inline]
    pub(crate) fn movable(&self, v: u32) -> bool {
        !self.fixed[v as usize] || self.slide[v as usize].is_some()
    }

    /// Whether slot `t` holds a live tet.
    #[inline]
    pub(crate) fn alive(&self, t: u32) -> bool {
        (t as usize) < self.tets.len() && self.tets[t as usize][0] != NONE
    }

    /// The corner positions of the tet `t`.
    #[inline]
    pub(crate) fn corners(&self, t: &[u32; 4]) -> [DVec3; 4] {
        t.map(|i| self.pts[i as usize])
    }

    /// Exact orientation of the vertex quadruple `t`.
    #[inline]
    pub(crate) fn orient(&self, t: &[u32; 4]) -> Sign {
        let [a, b, c, d] = self.corners(t);
        orient3d(a, b, c, d)
    }

    /// Score of the vertex quadruple `t` (assumed positively oriented).
    #[inline]
    pub(crate) fn score_of(&self, t: &[u32; 4]) -> f64 {
        Judged::of(&self.corners(t)).score(&self.tg)
    }

    /// Recomputes the cached measures and score of live tet `t` (after it or a vertex changed).
    #[inline]
    pub(crate) fn rescore(&mut self, t: u32) {
        let j = Judged::of(&self.corners(&self.tets[t as usize]));
        self.q[t as usize] = j.score(&self.tg);
        self.judged[t as usize] = j;
    }

    /// Scores every live tet again under the targets `tg`, which later work uses.
    pub(crate) fn retarget(&mut self, tg: Targets) {
        self.tg = tg;
        for t in 0..self.tets.len() {
            if self.tets[t][0] != NONE {
                self.q[t] = self.judged[t].score(&tg);
            }
        }
    }

    /// Counts a move of a vertex: call before [`Work::touch`]ing the tets it changed.
    #[inline]
    pub(crate) fn tick(&mut self) {
        self.clock += 1;
    }

    /// Moves vertex `v` to `x`, its star `star` (checked positive there by the caller):
    /// counts the move, rescores and touches the star's tets.
    pub(crate) fn move_vertex(&mut self, v: u32, x: DVec3, star: &[u32]) {
        self.pts[v as usize] = x;
        self.tick();
        for &t in star {
            self.rescore(t);
            self.touch(t);
        }
    }

    /// Marks the vertices of live tet `t` as touched now (its shape changed).
    #[inline]
    pub(crate) fn touch(&mut self, t: u32) {
        for v in self.tets[t as usize] {
            self.touched[v as usize] = self.clock;
        }
    }

    /// Whether a tet at a vertex of live tet `t` changed after clock `since`. Every operation
    /// on `t` (edge removal around its edges, flips of its faces, moves of its vertices) depends
    /// only on tets that share a vertex with it, so one that failed at `since` fails again unless
    /// this holds.
    #[inline]
    pub(crate) fn touched_after(&self, t: u32, since: u32) -> bool {
        self.tets[t as usize].iter().any(|&v| self.touched[v as usize] > since)
    }

    /// The worst judged measures over the live tets.
    pub(crate) fn worst(&self) -> Judged {
        self.live_slots().map(|t| self.judged[t as usize]).fold(Judged { lo: 180.0, hi: 0.0, re: 0.0 }, Judged::worst)
    }

    /// Whether face `k` of live tet `t` is constrained.
    #[inline]
    pub(crate) fn constrained(&self, t: u32, k: usize) -> bool {
        self.cons[t as usize] & (1 << k) != 0
    }

    /// Starts a new visit: afterwards [`Work::visit`] marks each slot once.
    #[inline]
    pub(crate) fn new_visit(&mut self) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.mark.iter_mut().for_each(|m| *m = 0);
            self.stamp = 1;
        }
    }

    /// Marks slot `t`; false if it was already marked in this visit.
    #[inline]
    pub(crate) fn visit(&mut self, t: u32) -> bool {
        let m = &mut self.mark[t as usize];
        if *m == self.stamp {
            false
        } else {
            *m = self.stamp;
            true
        }
    }

    /// Whether slot `t` is marked in this visit.
    #[inline]
    pub(crate) fn visited(&self, t: u32) -> bool {
        self.mark[t as usize] == self.stamp
    }

    /// The live tets containing vertex `v` (its star), into `out`; false (and `out`
    /// unspecified) if `v` has no tet.
    pub(crate) fn star(&mut self, v: u32, out: &mut Vec<u32>) -> bool {
        out.clear();
        let start = self.v2t[v as usize];
        if start == NONE || !self.alive(start) || local(&self.tets[start as usize], v).is_none() {
            return false;
        }
        self.new_visit();
        self.visit(start);
        out.push(start);
        let mut i = 0;
        while i < out.len() {
            let t = out[i] as usize;
            i += 1;
            let m = local(&self.tets[t], v).unwrap_or(0);
            for k in 0..4 {
                if k == m {
                    continue;
                }
                let n = self.nbr[t][k];
                if n != NONE && self.visit(n >> 2) {
                    out.push(n >> 2);
                }
            }
        }
        true
    }

    /// Replaces the live tets `old` (distinct, all in `region`, no constrained face between
    /// two of them) by the tets `new`, in `region`, if the new tets fill exactly the same cavity: every new tet positively oriented (exact), and the
    /// new tets' boundary equal to the old tets' boundary as oriented faces, each new interior
    /// face shared by exactly two new tets from opposite sides. Outer faces keep their
    /// neighbours and constraint marks. Returns false, changing nothing, otherwise.
    pub(crate) fn replace(&mut self, old: &[u32], new: &[[u32; 4]], region: RegionId) -> bool {
        if new.iter().any(|t| self.orient(t) != Sign::Positive) {
            return false;
        }
        self.new_visit();
        for &t in old {
            if !self.alive(t) || !self.visit(t) || self.region[t as usize] != region {
                return false;
            }
        }
        let mut outer = std::mem::take(&mut self.outer);
        let mut inner = std::mem::take(&mut self.inner);
        outer.clear();
        inner.clear();
        for &t in old {
            let tet = self.tets[t as usize];
            for (k, f) in TET_FACES.iter().enumerate() {
                let n = self.nbr[t as usize][k];
                if n != NONE && self.visited(n >> 2) {
                    if self.constrained(t, k) {
                        // a constrained face would be removed
                        self.outer = outer;
                        self.inner = inner;
                        return false;
                    }
                    continue;
                }
                let (key, even) = sorted3([tet[f[0]], tet[f[1]], tet[f[2]]]);
                outer.push(FaceRec { key, even, link: n, constrained: self.constrained(t, k) });
            }
        }
        for (i, tet) in new.iter().enumerate() {
            for (k, f) in TET_FACES.iter().enumerate() {
                let (key, even) = sorted3([tet[f[0]], tet[f[1]], tet[f[2]]]);
                inner.push(FaceRec { key, even, link: (i as u32) << 2 | k as u32, constrained: false });
            }
        }
        outer.sort_unstable_by_key(|a| a.key);
        inner.sort_unstable_by(|a, b| a.key.cmp(&b.key).then(a.link.cmp(&b.link)));
        // check: new faces pair up among themselves or with exactly one outer face
        let mut ok = outer.windows(2).all(|w| w[0].key != w[1].key);
        let mut matched = 0;
        let mut i = 0;
        while ok && i < inner.len() {
            let r = inner[i];
            if i + 1 < inner.len() && inner[i + 1].key == r.key {
                let s = inner[i + 1];
                ok = r.even != s.even
                    && (i + 2 >= inner.len() || inner[i + 2].key != r.key)
                    && outer.binary_search_by(|o| o.key.cmp(&r.key)).is_err();
                i += 2;
            } else {
                match outer.binary_search_by(|o| o.key.cmp(&r.key)) {
                    Ok(j) if outer[j].even == r.even => matched += 1,
                    _ => ok = false,
                }
                i += 1;
            }
        }
        ok &= matched == outer.len();
        if !ok || self.tets.len() - self.free.len() - old.len() + new.len() > MAX_TETS {
            self.outer = outer;
            self.inner = inner;
            return false;
        }
        // commit: free the old slots, then take slots for the new tets
        self.clock += 1;
        for &t in old {
            self.tets[t as usize] = [NONE; 4];
            self.free.push(t);
        }
        let mut slots = std::mem::take(&mut self.slots);
        slots.clear();
        for tet in new {
            let s = match self.free.pop() {
                Some(s) => s,
                None => {
                    self.tets.push([NONE; 4]);
                    self.nbr.push([NONE; 4]);
                    self.cons.push(0);
                    self.region.push(region);
                    self.q.push(0.0);
                    self.judged.push(Judged::default());
                    self.mark.push(0);
                    (self.tets.len() - 1) as u32
                }
            };
            let su = s as usize;
            self.tets[su] = *tet;
            self.nbr[su] = [NONE; 4];
            self.cons[su] = 0;
            self.region[su] = region;
            self.rescore(s);
            for &v in tet {
                self.v2t[v as usize] = s;
                self.touched[v as usize] = self.clock;
            }
            slots.push(s);
        }
        let code = |link: u32| slots[(link >> 2) as usize] << 2 | (link & 3);
        let mut i = 0;
        while i < inner.len() {
            let r = inner[i];
            let a = code(r.link);
            if i + 1 < inner.len() && inner[i + 1].key == r.key {
                let b = code(inner[i + 1].link);
                self.nbr[(a >> 2) as usize][(a & 3) as usize] = b;
                self.nbr[(b >> 2) as usize][(b & 3) as usize] = a;
                i += 2;
            } else {
                let o = outer[outer.binary_search_by(|o| o.key.cmp(&r.key)).unwrap_or(0)];
                let (at, ak) = ((a >> 2) as usize, (a & 3) as usize);
                self.nbr[at][ak] = o.link;
                if o.link != NONE {
                    self.nbr[(o.link >> 2) as usize][(o.link & 3) as usize] = a;
                }
                if o.constrained {
                    self.cons[at] |= 1 << ak;
                }
                i += 1;
            }
        }
        self.outer = outer;
        self.inner = inner;
        self.slots = slots;
        true
    }

    /// Appends a vertex (not yet in any tet) and returns its index.
    pub(crate) fn push_vertex(&mut self, p: DVec3) -> u32 {
        self.pts.push(p);
        self.v2t.push(NONE);
        self.touched.push(self.clock);
        self.fixed.push(false);
        self.slide.push(None);
        (self.pts.len() - 1) as u32
    }

    /// Removes the last vertex, if it is `v` and in no tet (an insertion that was undone).
    pub(crate) fn pop_vertex(&mut self, v: u32) {
        if v as usize + 1 == self.pts.len() && self.v2t[v as usize] == NONE {
            self.pts.pop();
            self.v2t.pop();
            self.touched.pop();
            self.fixed.pop();
            self.slide.pop();
        }
    }

    /// Scratch stack for callers that need one (taken and given back).
    pub(crate) fn take_stack(&mut self) -> Vec<u32> {
        let mut s = std::mem::take(&mut self.stack);
        s.clear();
        s
    }

    /// Gives back the scratch stack.
    pub(crate) fn give_stack(&mut self, s: Vec<u32>) {
        self.stack = s;
    }

    /// Number of live tets.
    #[cfg(test)]
    pub(crate) fn live(&self) -> usize {
        self.tets.len() - self.free.len()
    }

    /// The live tets' slots.
    pub(crate) fn live_slots(&self) -> impl Iterator<Item = u32> + '_ {
        self.tets.iter().enumerate().filter(|(_, t)| t[0] != NONE).map(|(i, _)| i as u32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::FaceId;

    fn two_tets() -> TetMesh {
        TetMesh {
            vertices: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::new(1.0, 1.0, 1.0)],
            tets: vec![[0, 1, 2, 3], [1, 4, 2, 3]],
            region_tags: vec![RegionId(1); 2],
            ..Default::default()
        }
    }

    #[test]
    fn adjacency_and_constraints() {
        let mut m = two_tets();
        m.boundary = vec![[0, 2, 1]];
        m.face_tags = vec![FaceId(1)];
        let w = Work::build(&m, Targets::new(15.0, 160.0)).unwrap();
        // shared face (1, 2, 3) is face 0 of tet 0 and face 1 of tet 1 (opposite vertex 4)
        assert_eq!(w.nbr[0][0], 1 << 2 | 1);
        assert_eq!(w.nbr[1][1], 0);
        assert_eq!(w.cons[0] & 1, 0, "interior face free");
        assert_eq!(w.cons[0] & !1, 0b1110, "hull faces constrained");
        assert!(w.fixed.iter().all(|&f| f), "every vertex is on the hull");
        m.region_tags[1] = RegionId(2);
        let w = Work::build(&m, Targets::new(15.0, 160.0)).unwrap();
        assert_eq!(w.cons[0], 0b1111, "an interface is constrained");
    }

    #[test]
    fn build_rejects_bad_meshes() {
        let mut m = two_tets();
        m.tets[1] = [1, 2, 4, 3];
        assert!(matches!(
            Work::build(&m, Targets::new(15.0, 160.0)),
            Err(MeshError::BadOrientation { element: Element::Tet(1), .. })
        ));
        let mut m = two_tets();
        m.boundary = vec![[0, 1, 4]];
        m.face_tags = vec![FaceId(1)];
        assert!(matches!(Work::build(&m, Targets::new(15.0, 160.0)), Err(MeshError::BoundaryNotAFace { .. })));
        let mut m = two_tets();
        m.region_tags.pop();
        assert!(matches!(Work::build(&m, Targets::new(15.0, 160.0)), Err(MeshError::LengthMismatch { .. })));
    }

    #[test]
    fn replace_checks_the_cavity() {
        let m = two_tets();
        let mut w = Work::build(&m, Targets::new(15.0, 160.0)).unwrap();
        // a wrong replacement: one tet only
        assert!(!w.replace(&[0, 1], &[[0, 1, 2, 3]], RegionId(1)));
        assert_eq!(w.tets, m.tets);
        // an inverted tet
        assert!(!w.replace(&[0], &[[0, 2, 1, 3]], RegionId(1)));
        // the identity is a valid replacement
        assert!(w.replace(&[0, 1], &[[1, 4, 2, 3], [0, 1, 2, 3]], RegionId(1)));
        assert_eq!(w.live(), 2);
        let mut out = Vec::new();
        assert!(w.star(0, &mut out));
        assert_eq!(out.len(), 1);
        assert!(w.star(1, &mut out));
        assert_eq!(out.len(), 2);
    }
}
