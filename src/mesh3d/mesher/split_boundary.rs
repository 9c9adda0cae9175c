//! Boundary splits during refinement (Delaunay refinement of a piecewise linear complex): a
//! point put on a subsegment or inside a facet while the walls stand and the tets carry their
//! labels.
//!
//! Each facet changes locally: the subfaces whose circumcircle (in the facet's plane, exact
//! `incircle`) holds the new point, found by a flood from the subface it splits and never
//! across the facet's sides, are replaced by the fan from the point to their outline (2D
//! Bowyer-Watson; the outline must be star-shaped from the point). The exterior is gone by
//! then (the flat tets that a Delaunay tetrahedralization has on planar facets would stop the
//! point's cavity there), so the cavity lies on the material side: it grows from the tet on
//! the split subface, the removed subfaces get no new tet, and the new faces along their
//! outline, which look outside, are the new subfaces. The point goes in only if every removed
//! subface's tet is in the cavity and every new subface will be a face of the result (its
//! edge opposite the point is an edge of the cavity's outline); where a removed subface's tet
//! is not reached (walls near it, or a tetrahedralization short of Delaunay), the 2D cavity
//! keeps that subface and is tried again. Then the new subfaces become walls and the new tets
//! take the labels of their old neighbours. What cannot be made that way leaves everything as
//! it was, and the caller tries something else.

use crate::core::Sign;
use crate::core::predicates::{incircle, orient2d};
use crate::mesh3d::delaunay::store::{DEAD, GHOST};
use crate::mesh3d::mesher::carve::Labels;
use crate::mesh3d::mesher::recover::{SubfaceSplit, circumcenter, split_point, subface_split};
use crate::mesh3d::mesher::surface_model::{FacetEdit, SurfaceModel};
use crate::mesh3d::mesher::tetra::{Inserted, Tetra};
use glam::DVec3;
use rustc_hash::{FxHashMap, FxHashSet};

/// The subfaces of every facet by their directed edges: `(u, v, facet)` to `w` for each
/// subface `(u, v, w)` as stored (oriented like its facet).
pub(crate) struct FacetEdges(FxHashMap<(u32, u32, u32), u32>);

impl FacetEdges {
    /// The edges of every subface of `sm`.
    pub fn new(sm: &SurfaceModel) -> Self {
        let mut m = FxHashMap::default();
        for (f, t) in sm.subfaces() {
            for k in 0..3 {
                m.insert((t[k], t[(k + 1) % 3], f), t[(k + 2) % 3]);
            }
        }
        FacetEdges(m)
    }

    /// The subface of facet `f` with directed edge `(u, v)`, oriented as stored and turned
    /// so that its least vertex comes first (one form per subface).
    fn with(&self, f: u32, u: u32, v: u32) -> Option<[u32; 3]> {
        self.0.get(&(u, v, f)).map(|&w| least_first([u, v, w]))
    }

    /// The subface of `f` across edge `(u, v)` of a subface holding it in that direction.
    fn across(&self, f: u32, u: u32, v: u32) -> Option<[u32; 3]> {
        self.with(f, v, u)
    }

    /// Subface `t` (any vertex order) of facet `f` as stored.
    fn oriented(&self, f: u32, t: [u32; 3]) -> Option<[u32; 3]> {
        self.with(f, t[0], t[1]).filter(|s| s.contains(&t[2])).or_else(|| self.with(f, t[1], t[0]).filter(|s| s.contains(&t[2])))
    }

    fn apply(&mut self, f: u32, removed: &[[u32; 3]], added: &[[u32; 3]]) {
        for t in removed {
            for k in 0..3 {
                self.0.remove(&(t[k], t[(k + 1) % 3], f));
            }
        }
        for t in added {
            for k in 0..3 {
                self.0.insert((t[k], t[(k + 1) % 3], f), t[(k + 2) % 3]);
            }
        }
    }
}

/// The most subfaces one split may remove from a facet.
const MAX_CAVITY: usize = 64;


/// The 2D cavity of point `p` (vertex `v`) in facet `f`, from `seed` across edges that are
/// not `cut` (the subsegment `p` splits): the subfaces whose circumcircle holds `p` strictly,
/// and the fan from `v` to their outline. `None` where the outline is not star-shaped from
/// `p` (the facet is not Delaunay there) or the cavity is larger than [`MAX_CAVITY`].
#[allow(clippy::too_many_arguments)]
fn cavity(sm: &SurfaceModel, edges: &FacetEdges, points: &[DVec3], f: u32, p: DVec3, v: u32, seed: [u32; 3], cut: Option<(u32, u32)>, keep: &FxHashSet<[u32; 3]>) -> Option<FacetEdit> {
    if keep.contains(&sorted(seed)) {
        return None;
    }
    let q = |x: u32| sm.to_plane(f, points[x as usize]);
    let p2 = sm.to_plane(f, p);
    let is_cut = |a: u32, b: u32| cut.is_some_and(|(x, y)| (x == a && y == b) || (x == b && y == a));
    let ccw = orient2d(q(seed[0]), q(seed[1]), q(seed[2]));
    if ccw == Sign::Zero {
        return None;
    }
    let mut removed = vec![seed];
    let mut i = 0;
    while i < removed.len() {
        let t = removed[i];
        i += 1;
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if is_cut(a, b) {
                continue;
            }
            let Some(n) = edges.across(f, a, b) else { continue };
            if removed.contains(&n) || keep.contains(&sorted(n)) {
                continue;
            }
            if incircle(q(n[0]), q(n[1]), q(n[2]), p2).times(ccw) == Sign::Positive {
                removed.push(n);
                if removed.len() > MAX_CAVITY {
                    return None;
                }
            }
        }
    }
    let mut added = Vec::new();
    for t in &removed {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if is_cut(a, b) || edges.across(f, a, b).is_some_and(|n| removed.contains(&n)) {
                continue;
            }
            if orient2d(q(a), q(b), p2) != ccw {
                return None;
            }
            added.push([a, b, v]);
        }
    }
    // every vertex of the cavity stays on the surface
    if removed.iter().flatten().any(|x| !added.iter().any(|t| t.contains(x))) {
        return None;
    }
    Some((f, removed, added))
}

/// The smallest dihedral angle (degrees) of a new tet on a subface that a boundary split
/// leaves: below it the split is not made (a flat tet between two facets that meet at an angle
/// near 180°, as on a tessellated curved face, which no later step can remove).
const WALL_MIN_DIHEDRAL: f64 = 3.0;

/// True if the tet of face `f` (oriented towards `p`) and `p` is not positive or has a
/// dihedral angle under `bound` degrees.
fn poor(tr: &Tetra, f: [u32; 3], p: DVec3, bound: f64) -> bool {
    let [a, b, d] = f.map(|x| tr.point(x));
    if (b - a).dot((d - a).cross(p - a)) <= 0.0 {
        return true;
    }
    crate::quality::tetrahedron::tet_min_max_dihedral(&[a, b, d, p]).0 < bound
}

/// Where a boundary point goes.
#[derive(Copy, Clone, Debug)]
enum At {
    /// On segment `s`, between its consecutive points `a` and `b`.
    Segment { s: u32, a: u32, b: u32 },
    /// Inside facet `f`, in the cavity of its subface `seed` (as stored).
    Facet { f: u32, seed: [u32; 3] },
}

/// Tries with smaller 2D cavities when the 3D cavity leaves some removed subface on its
/// outline (walls nearby, or a tetrahedralization short of Delaunay, keep it from some tets
/// that the subface's circumcircle says conflict): those subfaces stay, at most this many times.
const SHRINKS: usize = 3;

/// Inserts boundary point `p` at `at`. Returns the new vertex, or `None` when nothing changed.
/// New tets are listed in `tr.created` (cleared first) with their labels set.
fn insert(tr: &mut Tetra, sm: &mut SurfaceModel, edges: &mut FacetEdges, labels: &mut Labels, p: DVec3, at: At) -> Option<u32> {
    let v = tr.add_point(p);
    let mut keep: FxHashSet<[u32; 3]> = FxHashSet::default();
    let mut buf = Vec::new();
    for _ in 0..=SHRINKS {
        let Some(plan) = plan_cavities(sm, edges, &tr.k.points, p, v, at, &keep) else { break };
        // the material tet on every subface that goes (the exterior is gone: one tet each)
        let mut start = None;
        let mut all = true;
        for (_, removed, _) in &plan {
            for &t in removed {
                match tr.face_of(t[0], t[1], t[2], &mut buf) {
                    Some((tt, _)) => {
                        start.get_or_insert(tt);
                    }
                    None => all = false,
                }
            }
        }
        let removed_keys: FxHashSet<[u32; 3]> = plan.iter().flat_map(|e| e.1.iter().map(|&t| sorted(t))).collect();
        let added: Vec<[u32; 3]> = plan.iter().flat_map(|e| e.2.iter().copied()).collect();
        let mut stays: Vec<[u32; 3]> = Vec::new();
        tr.created.clear();
        let res = match start.filter(|_| all) {
            Some(start) => tr.insert_on_boundary(v, start, removed_keys.clone(), |t, boundary| {
                let mut outline: FxHashSet<(u32, u32)> = FxHashSet::default();
                let mut gone: FxHashSet<[u32; 3]> = FxHashSet::default();
                for &(f, r) in boundary {
                    let key = sorted(f);
                    if r >> 2 == 0 && removed_keys.contains(&key) {
                        gone.insert(key);
                        continue;
                    }
                    for k in 0..3 {
                        let (x, y) = (f[k], f[(k + 1) % 3]);
                        outline.insert((x.min(y), x.max(y)));
                    }
                }
                // a removed subface whose tet the cavity does not reach would stay
                stays.extend(removed_keys.iter().filter(|k| !gone.contains(*k)).copied());
                if !stays.is_empty() {
                    stays.sort_unstable();
                    return Some((0, 0));
                }
                for t in &added {
                    let (x, y) = (t[0], t[1]);
                    if !outline.contains(&(x.min(y), x.max(y))) {
                        return Some((0, 0)); // a new subface would be missing
                    }
                }
                // nor a flat tet on a subface that stays (one in the point's plane, of a
                // coplanar facet beside, or a facet at a small angle)
                if boundary.iter().any(|&(f, r)| !(r >> 2 == 0 && removed_keys.contains(&sorted(f))) && t.walls[(r >> 2) as usize] >> (r & 3) & 1 != 0 && poor(t, f, p, WALL_MIN_DIHEDRAL)) {
                    return Some((0, 0));
                }
                None
            }),
            None => Inserted::Refused,
        };
        if matches!(res, Inserted::Yes(_)) {
            for t in &added {
                match tr.face_tet(t[0], t[1], t[2], &mut buf) {
                    Some((tt, k)) => tr.set_wall(tt, k, true),
                    None => debug_assert!(false, "new subface {t:?} missing after the checked insertion"),
                }
            }
            let (segment, inside) = match at {
                At::Segment { s, a, b } => (Some((s, a, b)), None),
                At::Facet { f, .. } => (None, Some(f)),
            };
            let placed = sm.apply_split(v, segment, inside, &plan);
            debug_assert!(placed, "the split subsegment is no longer one");
            for (f, removed, added) in &plan {
                edges.apply(*f, removed, added);
            }
            label_new(tr, labels);
            return Some(v);
        }
        if stays.is_empty() {
            break;
        }
        keep.extend(stays);
    }
    tr.remove_last_point();
    None
}

/// The 2D cavities of a boundary point in every facet it goes into (see [`cavity`]).
fn plan_cavities(sm: &SurfaceModel, edges: &FacetEdges, points: &[DVec3], p: DVec3, v: u32, at: At, keep: &FxHashSet<[u32; 3]>) -> Option<Vec<FacetEdit>> {
    let plan: Option<Vec<FacetEdit>> = match at {
        At::Segment { s, a, b } => sm.segments[s as usize]
            .facets
            .iter()
            .map(|&f| {
                let seed = edges.with(f, a, b).or_else(|| edges.with(f, b, a))?;
                cavity(sm, edges, points, f, p, v, seed, Some((a, b)), keep)
            })
            .collect(),
        At::Facet { f, seed } => cavity(sm, edges, points, f, p, v, seed, None, keep).map(|e| vec![e]),
    };
    if plan.as_ref().is_none_or(|x| x.is_empty()) {
        return None;
    }
    plan
}

/// `t` turned (orientation kept) so that its least vertex comes first.
fn least_first(t: [u32; 3]) -> [u32; 3] {
    let k = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
    [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
}

fn sorted(t: [u32; 3]) -> [u32; 3] {
    crate::mesh::tet_mesh::sorted3(t).0
}

/// Labels the tets in `tr.created`: from old neighbours across faces that are no walls, then
/// from each other the same way; ghosts are outside.
fn label_new(tr: &Tetra, labels: &mut Labels) {
    let created: FxHashSet<u32> = tr.created.iter().copied().collect();
    let mut known: FxHashSet<u32> = FxHashSet::default();
    let mut todo: Vec<u32> = Vec::new();
    for &s in &tr.created {
        let t = &tr.tets[s as usize];
        if t.v.contains(&GHOST) {
            labels.set(s, 0);
            known.insert(s);
            continue;
        }
        let got = (0..4).find_map(|f| {
            let n = t.n[f] >> 2;
            let open = tr.walls[s as usize] >> f & 1 == 0;
            if !open || created.contains(&n) || tr.tets[n as usize].v[0] == DEAD {
                return None;
            }
            Some(if tr.tets[n as usize].v.contains(&GHOST) { 0 } else { labels.get(n) })
        });
        match got {
            Some(l) => {
                labels.set(s, l);
                known.insert(s);
            }
            None => todo.push(s),
        }
    }
    let mut changed = true;
    while changed && !todo.is_empty() {
        changed = false;
        todo.retain(|&s| {
            for f in 0..4 {
                let n = tr.tets[s as usize].n[f] >> 2;
                if tr.walls[s as usize] >> f & 1 == 0 && known.contains(&n) {
                    labels.set(s, labels.get(n));
                    known.insert(s);
                    changed = true;
                    return false;
                }
            }
            true
        });
    }
}

/// Splits subface `face` (a wall of `tr`) as Delaunay refinement does
/// ([`subface_split`]): at its circumcentre, or the subsegment that centre encroaches or that
/// lies between the subface and it (at its midpoint, or on a shell around an input vertex).
/// Nothing is split whose new point would come nearer its neighbours than `floor` times the
/// local feature size there (`size_at(tr, neighbours, point)`), nor a subface with a
/// circumradius or a subsegment with half a length of at most `r_min`: that bounds the work
/// near small input angles. Returns the new vertex and its local feature size.
#[allow(clippy::too_many_arguments)]
pub(crate) fn split_wall(tr: &mut Tetra, sm: &mut SurfaceModel, edges: &mut FacetEdges, labels: &mut Labels, size_at: &dyn Fn(&Tetra, &[u32], DVec3) -> f64, face: [u32; 3], floor: f64, r_min: f64) -> Option<(u32, f64)> {
    if face.contains(&GHOST) || face.contains(&DEAD) {
        return None;
    }
    let f = sm.facet_of(face)?;
    let seed = edges.oriented(f, face)?;
    let [pa, pb, pc] = seed.map(|x| tr.point(x));
    let cc = circumcenter(pa, pb, pc);
    let r = cc.distance(pa);
    if !cc.is_finite() || r <= r_min || r < floor * size_at(tr, &seed, cc) {
        return None;
    }
    let (p, at, near) = match subface_split(tr, sm, f, seed, cc) {
        SubfaceSplit::Subsegment(s, [a, b]) => {
            let (qa, qb) = (tr.point(a), tr.point(b));
            let m = split_point(sm, s, a, b, qa, qb);
            let half = m.distance(qa).min(m.distance(qb));
            if half <= r_min || half < floor * size_at(tr, &[a, b], m) {
                return None;
            }
            (m, At::Segment { s, a, b }, vec![a, b])
        }
        SubfaceSplit::Centre => (cc, At::Facet { f, seed }, seed.to_vec()),
        SubfaceSplit::NoSides => return None,
    };
    let size = size_at(tr, &near, p);
    let v = insert(tr, sm, edges, labels, p, at)?;
    Some((v, size))
}
