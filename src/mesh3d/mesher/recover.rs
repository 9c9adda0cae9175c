//! Boundary recovery by conforming Delaunay refinement: Steiner points are inserted on the
//! segments and facets until every subsegment is an edge and every subface a face of the
//! Delaunay tetrahedralization.
//!
//! Rules (as in Delaunay refinement of piecewise linear complexes): a missing subsegment is
//! split at its midpoint (or, next to an input vertex, on a concentric shell around it); a
//! missing subface gets a point at its circumcentre, unless that centre lies outside the facet
//! or inside the diametral sphere of one of the facet's subsegments, in which case that
//! subsegment is split instead. Steiner points carry the location (segment or facet) that
//! tags and the keep-surface stage need.

use crate::mesh::tet_mesh::TET_FACES;
use crate::mesh3d::mesher::MeshingError;
use crate::mesh3d::mesher::carve::Labels;
use crate::mesh3d::mesher::surface_model::SurfaceModel;
use crate::mesh3d::mesher::tetra::{Inserted, Tetra};
use crate::core::Sign;
use crate::core::predicates::orient2d;
use glam::{DVec2, DVec3};

/// What recovery did.
#[derive(Clone, Debug, Default)]
pub(crate) struct Recovery {
    /// Steiner points put on segments.
    pub segment_points: usize,
    /// Steiner points put inside facets.
    pub facet_points: usize,
    /// Rounds of the loop.
    pub rounds: usize,
}

/// Inserts a Steiner point at `p` that lies on the boundary; the walk starts at a tet of
/// `near`. Returns its index, or `None` when it coincides with a vertex (then nothing is added
/// to the model).
fn insert_point(tr: &mut Tetra, p: DVec3, near: &[u32]) -> Result<Option<u32>, SplitError> {
    // start in a tet holding the whole piece if there is one (then no wall lies between)
    let mut buf = Vec::new();
    let start = match *near {
        [a, b] => tr.edge_tet(a, b, &mut buf),
        [a, b, c] => tr.face_of(a, b, c, &mut buf).map(|x| x.0),
        _ => None,
    }
    .unwrap_or(tr.vtet[near[0] as usize]);
    let v = tr.add_point(p);
    match tr.insert_at(v, start) {
        Inserted::Yes(_) => Ok(Some(v)),
        Inserted::Duplicate(_) => {
            tr.remove_last_point();
            Ok(None)
        }
        other => {
            tr.remove_last_point();
            Err(SplitError::NotInserted { at: p, outcome: other, walled: tr.walled })
        }
    }
}

/// Why a split of a subsegment or a subface failed; [`recover`] turns it into a
/// [`MeshingError::Recovery`] naming the facet.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub(crate) enum SplitError {
    /// The Steiner point could not be inserted (a bug, or walls that block it).
    #[error("a Steiner point at {at} could not be inserted ({outcome:?}, walled {walled})")]
    NotInserted {
        /// The point.
        at: DVec3,
        /// What the insertion did instead.
        outcome: Inserted,
        /// Whether the tetrahedralization had its walls up.
        walled: bool,
    },
    /// The subsegment is already shorter than [`MIN_SPLIT`] of its segment: recovery would not
    /// end.
    #[error(
        "recovery does not end near {near}: an input edge there had to be cut into pieces under {MIN_SPLIT:e} of its length {length} (the surface comes nearer itself there than the mesher can separate)"
    )]
    TooShort {
        /// The middle of the subsegment.
        near: DVec3,
        /// The length of its segment.
        length: f64,
    },
    /// A facet without sides (no subsegment to split instead of its subface).
    #[error("facet {facet} has no sides")]
    NoSides {
        /// The facet.
        facet: u32,
    },
}

/// Recovery gives up when the missing subsegments grew by a quarter or more for this many
/// rounds in a row ...
const DIVERGING_ROUNDS: usize = 6;
/// ... while at least this many were missing.
const DIVERGING_MIN: usize = 50;
/// The most rounds of subsegment splitting (recoveries that end take 10 to 20).
const MAX_ROUNDS: usize = 256;

/// The shortest piece of a segment, as a share of the segment, that recovery still splits.
const MIN_SPLIT: f64 = 1e-12;

/// [`split_subsegment_deferred`] with every facet it changed retriangulated at once.
#[cfg(test)]
pub(crate) fn split_subsegment(tr: &mut Tetra, sm: &mut SurfaceModel, s: u32, a: u32, b: u32) -> Result<bool, SplitError> {
    let split = split_subsegment_deferred(tr, sm, s, a, b);
    sm.flush(&tr.k.points);
    split
}

/// Splits subsegment `[a, b]` of segment `s` (at its midpoint or on a shell: [`split_point`]),
/// the facets around it left for [`SurfaceModel::flush_facet`]: recovery reads a facet's
/// subfaces only after flushing it, so a facet that several splits change in a round is
/// triangulated once (the same subfaces: they depend on its points alone).
///
/// # Errors
/// When the subsegment is already shorter than a millionth of a millionth of its segment
/// (two parts of the surface nearer each other there than splitting can separate: recovery
/// would not end), and when the split point cannot be inserted.
fn split_subsegment_deferred(tr: &mut Tetra, sm: &mut SurfaceModel, s: u32, a: u32, b: u32) -> Result<bool, SplitError> {
    let (pa, pb) = (tr.point(a), tr.point(b));
    // the segment's length: an input edge, straight between its two ends
    let ends = &sm.segments[s as usize].points;
    let whole = tr.point(ends[0]).distance(tr.point(ends[ends.len() - 1]));
    if pa.distance(pb) < MIN_SPLIT * whole {
        return Err(SplitError::TooShort { near: (pa + pb) * 0.5, length: whole });
    }
    let m = split_point(sm, s, a, b, pa, pb);
    match insert_point(tr, m, &[a, b])? {
        Some(v) => {
            sm.split_segment_deferred(s, a, b, v);
            Ok(true)
        }
        None => Ok(false),
    }
}

/// Where subsegment `[a, b]` of segment `s` is split: its midpoint, except on a piece that
/// has one end at an end of its segment (an input vertex) and the other inside. There the
/// point goes on the sphere around that vertex whose radius is the power of two nearest half
/// the piece (concentric shells, as in Delaunay refinement for domains with small angles):
/// segments that meet at a small angle are then cut at the same distances from their common
/// vertex, so that a point on one does not encroach a piece of the other, and splitting ends.
/// (Shells at every input vertex, not only at acute ones, measured better: featuretype.STL
/// 129 tets under 5° against 153, plate_holes.STL 207 against 213.)
pub(crate) fn split_point(sm: &SurfaceModel, s: u32, a: u32, b: u32, pa: DVec3, pb: DVec3) -> DVec3 {
    let pts = &sm.segments[s as usize].points;
    let is_end = |v: u32| pts.first() == Some(&v) || pts.last() == Some(&v);
    let (from, to) = match (is_end(a), is_end(b)) {
        (true, false) => (pa, pb),
        (false, true) => (pb, pa),
        _ => return pa + (pb - pa) * 0.5,
    };
    let len = from.distance(to);
    let r = (0.5 * len).log2().round().exp2();
    if !(r.is_finite() && r > 0.0 && r < len) {
        return pa + (pb - pa) * 0.5;
    }
    from + (to - from) * (r / len)
}

/// Circumcentre of triangle `(a, b, c)` (in its plane).
pub(crate) fn circumcenter(a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (u, v) = (b - a, c - a);
    let n = u.cross(v);
    let d = 2.0 * n.length_squared();
    if d == 0.0 {
        return (a + b + c) / 3.0;
    }
    a + (v.length_squared() * n.cross(u) + u.length_squared() * v.cross(n)) / d
}

/// The subsegment of facet `f` whose diametral sphere holds `p` (the one whose midpoint is
/// nearest), if any.
fn encroached_subsegment(tr: &Tetra, sm: &SurfaceModel, f: u32, p: DVec3) -> Option<(u32, [u32; 2])> {
    let mut best: Option<(f64, u32, [u32; 2])> = None;
    for &s in &sm.facets[f as usize].sides {
        for [u, v] in sm.subsegments(s) {
            let (pu, pv) = (tr.point(u), tr.point(v));
            if (p - pu).dot(p - pv) < 0.0 {
                let d = p.distance_squared((pu + pv) * 0.5);
                if best.is_none_or(|b| d < b.0) {
                    best = Some((d, s, [u, v]));
                }
            }
        }
    }
    best.map(|b| (b.1, b.2))
}

/// The side subsegment of facet `f` that separates a point `g` inside it from `p` outside it:
/// of the subsegments that the segment from `g` to `p` meets (exact orientation tests in the
/// facet's plane), the one met first; where rounding leaves none, the one nearest `p`.
fn separating_subsegment(tr: &Tetra, sm: &SurfaceModel, f: u32, g: DVec3, p: DVec3) -> Option<(u32, [u32; 2])> {
    let (g2, p2) = (sm.to_plane(f, g), sm.to_plane(f, p));
    let mut first: Option<(f64, u32, [u32; 2])> = None;
    let mut nearest: Option<(f64, u32, [u32; 2])> = None;
    for &s in &sm.facets[f as usize].sides {
        for [u, v] in sm.subsegments(s) {
            let (u2, v2) = (sm.to_plane(f, tr.point(u)), sm.to_plane(f, tr.point(v)));
            let d = distance_to_segment(p2, u2, v2);
            if nearest.is_none_or(|b| d < b.0) {
                nearest = Some((d, s, [u, v]));
            }
            let (sg, sp) = (orient2d(u2, v2, g2), orient2d(u2, v2, p2));
            if sg == Sign::Zero || sg.times(sp) == Sign::Positive {
                continue;
            }
            if orient2d(g2, p2, u2).times(orient2d(g2, p2, v2)) == Sign::Positive {
                continue;
            }
            // where along g → p it meets the line of (u, v): only for ordering
            let (e, w) = (v2 - u2, p2 - g2);
            let den = w.perp_dot(e);
            let t = if den != 0.0 { (u2 - g2).perp_dot(e) / den } else { 0.0 };
            if first.is_none_or(|b| t < b.0) {
                first = Some((t, s, [u, v]));
            }
        }
    }
    first.or(nearest).map(|b| (b.1, b.2))
}

/// Distance from `p` to the segment `(a, b)` in a plane.
fn distance_to_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let e = b - a;
    let l = e.length_squared();
    let t = if l > 0.0 { ((p - a).dot(e) / l).clamp(0.0, 1.0) } else { 0.0 };
    p.distance(a + e * t)
}

/// Where Delaunay refinement splits a subface of facet `f` (recovery's missing subfaces, and
/// refinement's encroached ones).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum SubfaceSplit {
    /// At its circumcentre: it lies in the facet and encroaches no subsegment.
    Centre,
    /// This subsegment of the facet's sides instead.
    Subsegment(u32, [u32; 2]),
    /// The centre lies outside a facet that has no sides (no closed surface has one).
    NoSides,
}

/// Where subface `t` of facet `f`, of circumcentre `cc`, is split: the subsegment that `cc`
/// encroaches (the one whose midpoint is nearest); where `cc` lies outside the facet, the side
/// subsegment between the subface and it (one that the centre does not encroach is encroached
/// by a vertex of the facet, Ruppert's lemma, so splitting it is the rule for encroached
/// subsegments); else the centre itself.
pub(crate) fn subface_split(tr: &Tetra, sm: &SurfaceModel, f: u32, t: [u32; 3], cc: DVec3) -> SubfaceSplit {
    if let Some((s, e)) = encroached_subsegment(tr, sm, f, cc) {
        return SubfaceSplit::Subsegment(s, e);
    }
    if sm.inside(f, cc, &tr.k.points) {
        return SubfaceSplit::Centre;
    }
    let g = t.map(|v| tr.point(v)).iter().sum::<DVec3>() / 3.0;
    match separating_subsegment(tr, sm, f, g, cc) {
        Some((s, e)) => SubfaceSplit::Subsegment(s, e),
        None => SubfaceSplit::NoSides,
    }
}

/// Splits subface `[a, b, c]` of facet `f`: at its circumcentre if that lies in the facet and
/// encroaches no subsegment, else the encroached subsegment, or where the centre lies outside
/// the facet, the side subsegment between the subface and the centre.
pub(crate) fn split_subface(tr: &mut Tetra, sm: &mut SurfaceModel, f: u32, t: [u32; 3], stats: &mut Recovery) -> Result<bool, SplitError> {
    let [pa, pb, pc] = t.map(|v| tr.point(v));
    let cc = circumcenter(pa, pb, pc);
    match subface_split(tr, sm, f, t, cc) {
        SubfaceSplit::Subsegment(s, [u, v]) => {
            stats.segment_points += 1;
            return split_subsegment_deferred(tr, sm, s, u, v);
        }
        SubfaceSplit::NoSides => return Err(SplitError::NoSides { facet: f }),
        SubfaceSplit::Centre => {}
    }
    // where rounding puts the centre on a vertex, the subface's centroid serves
    let centroid = (pa + pb + pc) / 3.0;
    for p in [cc, centroid] {
        if let Some(v) = insert_point(tr, p, &t)? {
            stats.facet_points += 1;
            sm.add_to_facet(f, v, &tr.k.points);
            return Ok(true);
        }
    }
    Ok(false)
}

/// Recovers every subsegment and subface, inserting boundary Steiner points.
///
/// # Errors
/// [`MeshingError::Recovery`] naming the facet and its tag when the budget of Steiner points
/// (`budget`) runs out (very small angles between input facets can make splitting go on),
/// when the missing subsegments grow by a quarter for [`DIVERGING_ROUNDS`] rounds in a row,
/// after [`MAX_ROUNDS`] rounds, or when a piece falls under [`MIN_SPLIT`] of its segment.
pub(crate) fn recover(tr: &mut Tetra, sm: &mut SurfaceModel, budget: usize) -> Result<Recovery, MeshingError> {
    let mut stats = Recovery::default();
    let mut buf = Vec::new();
    // subsegments missing in the last rounds, and for how many rounds in a row that grew
    let (mut last_missing, mut growing) = (usize::MAX, 0);
    // an edge or face found present stays so while no tet with one of its vertices is made (an
    // edge that goes has its ends on the outline of the cavity that took it, so they are
    // vertices of the new tets): `touched[v]` is the round before whose checks a tet with `v`
    // was last made, and a present edge or face remembers the round it was found in
    let mut touched: Vec<usize> = Vec::new();
    let mut present: rustc_hash::FxHashMap<[u32; 2], usize> = Default::default();
    let mut faces_present: rustc_hash::FxHashMap<[u32; 3], usize> = Default::default();
    loop {
        stats.rounds += 1;
        let round = stats.rounds;
        let mut changed = false;
        touched.resize(tr.num_points(), 0);
        for &t in &tr.created {
            for v in tr.tets[t as usize].v {
                if let Some(x) = touched.get_mut(v as usize) {
                    *x = round;
                }
            }
        }
        tr.created.clear();
        let fresh = |touched: &[usize], v: &[u32], since: Option<&usize>| since.is_some_and(|&r| v.iter().all(|&x| touched.get(x as usize).is_some_and(|&t| t <= r)));
        // subsegments first: a facet cannot be recovered while its sides are missing
        let missing: Vec<(u32, [u32; 2])> = sm
            .all_subsegments()
            .filter(|&(_, e)| {
                if fresh(&touched, &e, present.get(&e)) {
                    return false;
                }
                let here = tr.edge_tet(e[0], e[1], &mut buf).is_some();
                if here {
                    present.insert(e, round);
                }
                !here
            })
            .collect();
        // splitting that makes more missing pieces each round does not end (pieces of
        // the surface too near each other for midpoints to separate): stop while it is cheap
        growing = if missing.len() >= DIVERGING_MIN && 4 * missing.len() >= 5 * last_missing { growing + 1 } else { 0 };
        last_missing = missing.len();
        let endless = if stats.rounds > MAX_ROUNDS && !missing.is_empty() {
            Some(format!("does not end: {} input edges still missing after {MAX_ROUNDS} rounds", missing.len()))
        } else if growing >= DIVERGING_ROUNDS {
            Some(format!("does not converge: {} input edges missing after {} rounds, a quarter more each round", missing.len(), stats.rounds))
        } else {
            None
        };
        if let Some(why) = endless {
            let (s, [a, b]) = missing[0];
            let near = (tr.point(a) + tr.point(b)) * 0.5;
            return Err(fail(sm, sm.segments[s as usize].facets[0], &format!("segment recovery {why}, near {near} (parts of the surface too near each other)")));
        }
        for (s, [a, b]) in missing {
            // the subsegment may have been split meanwhile
            if !sm.subsegments(s).any(|e| e == [a, b]) {
                continue;
            }
            stats.segment_points += 1;
            changed |= split_subsegment_deferred(tr, sm, s, a, b).map_err(|e| fail(sm, sm.segments[s as usize].facets[0], &e.to_string()))?;
        }
        // the facets the round's splits changed, triangulated once each
        sm.flush(&tr.k.points);
        if !changed {
            let missing: Vec<(u32, [u32; 3])> = sm
                .subfaces()
                .filter(|&(_, t)| {
                    if fresh(&touched, &t, faces_present.get(&t)) {
                        return false;
                    }
                    let here = tr.has_face(t[0], t[1], t[2], &mut buf);
                    if here {
                        faces_present.insert(t, round);
                    }
                    !here
                })
                .collect();
            for (f, t) in missing {
                // a facet is triangulated again only when its subfaces are read: the facets
                // across the sides that splits cut wait until their own subfaces come up
                sm.flush_facet(f, &tr.k.points);
                if !sm.has_subface(f, t) {
                    continue;
                }
                changed |= split_subface(tr, sm, f, t, &mut stats).map_err(|e| fail(sm, f, &e.to_string()))?;
            }
            sm.flush(&tr.k.points);
        }
        if !changed {
            // nothing could be split: every subface must be there now, or the facet is named
            if let Some((f, t)) = sm.subfaces().find(|&(_, [a, b, c])| !tr.has_face(a, b, c, &mut buf)) {
                return Err(fail(sm, f, &format!("subface {t:?} could not be recovered (no Steiner point could be inserted for it)")));
            }
            return Ok(stats);
        }
        if stats.segment_points + stats.facet_points > budget {
            let f = sm.subfaces().find(|&(_, [a, b, c])| !tr.has_face(a, b, c, &mut buf)).map_or(0, |x| x.0);
            return Err(fail(sm, f, &format!("more than {budget} Steiner points were needed")));
        }
    }
}

/// Flat tets on planar facets, after carving: a material tet two of whose walls are subfaces
/// of one facet, across an edge inside it (no subsegment). Its four vertices lie in the
/// facet's plane (up to the flatness merged facets allow: a grid's rectangle rounded off its
/// plane); both diagonals of their quad are edges, its walls on the first face the exterior and
/// its other two faces, on the second, the material. No refinement splits it (its four vertices
/// are on the boundary and its radius-edge ratio may be good) and no flip removes it where the
/// ring around the inner diagonal has no valid retriangulation. The facet, which may be
/// retriangulated freely, takes the other diagonal instead: the tet's two inner faces become
/// the walls and the tet joins the exterior. Only where the quad is convex in the facet's
/// plane (exact orientations there) and both walls face the exterior. Returns the tets removed.
pub(crate) fn unfold_flat_tets(tr: &mut Tetra, sm: &mut SurfaceModel, labels: &mut Labels) -> usize {
    let mut removed = 0;
    loop {
        let mut changed = false;
        for t in tr.live().collect::<Vec<_>>() {
            if labels.get(t) == 0 || tr.walls[t as usize] == 0 {
                continue;
            }
            if unfold(tr, sm, labels, t) {
                removed += 1;
                changed = true;
            }
        }
        if !changed {
            return removed;
        }
    }
}

/// [`unfold_flat_tets`] for tet `t`: true when it was removed.
fn unfold(tr: &mut Tetra, sm: &mut SurfaceModel, labels: &mut Labels, t: u32) -> bool {
    let v = tr.tets[t as usize].v;
    // two walls on one facet at least (a lookup by hash; the subfaces as stored only then)
    let facets: Vec<(usize, u32)> = (0..4).filter(|&i| tr.walls[t as usize] >> i & 1 != 0).filter_map(|i| sm.facet_of(TET_FACES[i].map(|k| v[k])).map(|f| (i, f))).collect();
    if !facets.iter().enumerate().any(|(x, a)| facets[x + 1..].iter().any(|b| b.1 == a.1)) {
        return false;
    }
    let mut on: Vec<(usize, u32, [u32; 3])> = Vec::new();
    for &(i, _) in &facets {
        if let Some((f, s)) = sm.subface(TET_FACES[i].map(|k| v[k])) {
            on.push((i, f, s));
        }
    }
    for x in 0..on.len() {
        for y in x + 1..on.len() {
            let ((i, f, a), (j, g, b)) = (on[x], on[y]);
            if f != g {
                continue;
            }
            // a = (p, q, r) and b = (q, p, s) around their shared edge (p, q)
            let Some(k) = (0..3).find(|&k| !b.contains(&a[k])) else { continue };
            let [p, q, r] = [a[(k + 1) % 3], a[(k + 2) % 3], a[k]];
            let Some(m) = (0..3).find(|&m| b[m] == q && b[(m + 1) % 3] == p) else { continue };
            let s = b[(m + 2) % 3];
            if is_subsegment(sm, f, p, q) {
                continue;
            }
            // both walls face the exterior
            let outside = |face: usize| labels.get(tr.tets[t as usize].n[face] >> 2) == 0;
            if !outside(i) || !outside(j) {
                continue;
            }
            // the quad (q, r, p, s) convex in the facet's plane: the new triangles turn as the
            // old ones
            let at = |w: u32| sm.to_plane(f, tr.point(w));
            let ccw = |x: u32, y: u32, z: u32| orient2d(at(x), at(y), at(z)) == Sign::Positive;
            if !(ccw(p, q, r) && ccw(q, p, s) && ccw(r, p, s) && ccw(s, q, r)) {
                continue;
            }
            // the tet's other faces: (r, s, p) and (r, s, q)
            let inner: Vec<usize> = (0..4).filter(|&e| e != i && e != j).collect();
            sm.replace_subfaces(f, [a, b], [[r, p, s], [s, q, r]]);
            tr.set_wall(t, i, false);
            tr.set_wall(t, j, false);
            for e in inner {
                tr.set_wall(t, e, true);
            }
            labels.set(t, 0);
            return true;
        }
    }
    false
}

/// True when `(p, q)` is a subsegment of one of facet `f`'s sides.
fn is_subsegment(sm: &SurfaceModel, f: u32, p: u32, q: u32) -> bool {
    sm.facets[f as usize].sides.iter().any(|&s| sm.subsegments(s).any(|e| e == [p, q] || e == [q, p]))
}

fn fail(sm: &SurfaceModel, f: u32, why: &str) -> MeshingError {
    let fc = &sm.facets[f as usize];
    MeshingError::Recovery { triangle: f as usize, tag: fc.tag, message: why.to_string() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::FaceId;
    use crate::core::size_field::UniformSize;
    use crate::mesh::TriSurface;
    use crate::mesh3d::mesher::{MeshOptions, Seeds, mesh_surface};

    /// A thin planar strip (a chamfer between a long side and a finely split one), as one
    /// merged facet, with an apex above it so that the points span a tetrahedron.
    fn strip() -> (Tetra, SurfaceModel) {
        let xy = [(0.0, 0.0), (2.06, 0.0), (0.549, 0.246), (1.129, 0.246), (1.709, 0.246), (2.289, 0.246), (2.609, 0.246)];
        let mut points: Vec<DVec3> = xy.iter().map(|&(x, y)| DVec3::new(x, y, 0.0)).collect();
        points.push(DVec3::new(1.0, 0.1, 1.0));
        // A = 0, B = 1, E = 2, T1 = 3, T2 = 4, T3 = 5, F = 6: counter-clockwise about +z
        let triangles = [[0, 1, 4], [0, 4, 3], [0, 3, 2], [1, 5, 4], [1, 6, 5]];
        let sm = SurfaceModel::new(&points, &triangles, &[FaceId(1); 5], true);
        let ranks = (0..points.len() as u32).collect();
        let tr = Tetra::new(points, ranks, 1).unwrap();
        (tr, sm)
    }

    #[test]
    fn a_centre_outside_the_facet_splits_the_side_between() {
        let (mut tr, mut sm) = strip();
        assert_eq!(sm.facets.len(), 1);
        let seg = |sm: &SurfaceModel, a: u32, b: u32| sm.segments.iter().position(|s| s.points.first() == Some(&a) && s.points.last() == Some(&b)).unwrap() as u32;
        // a Steiner point on the short end side (A, E) makes the subface (A, m, T1), obtuse at
        // m (164°): its circumcentre lies beyond the diagonal (A, T1) and beyond the long side
        // (A, B), outside the facet, and inside no side's diametral circle; (A, B) is
        // encroached by T1 and E instead
        let ae = seg(&sm, 0, 2);
        assert!(split_subsegment(&mut tr, &mut sm, ae, 0, 2).unwrap());
        let m = sm.segments[ae as usize].points[1];
        let t = sm.facets[0].subfaces.iter().find(|t| t.contains(&0) && t.contains(&m) && t.contains(&3)).unwrap();
        let [pa, pb, pc] = t.map(|v| tr.point(v));
        let cc = circumcenter(pa, pb, pc);
        assert!(!sm.inside(0, cc, &tr.k.points));
        assert!(encroached_subsegment(&tr, &sm, 0, cc).is_none());
        assert_eq!(separating_subsegment(&tr, &sm, 0, (pa + pb + pc) / 3.0, cc), Some((seg(&sm, 0, 1), [0, 1])));
        let mut stats = Recovery::default();
        // before the rule: "a subface's circumcentre falls outside it"
        assert_eq!(split_subface(&mut tr, &mut sm, 0, t, &mut stats), Ok(true));
        assert_eq!(stats.segment_points, 1);
        assert_eq!(stats.facet_points, 0);
        let ab = &sm.segments[seg(&sm, 0, 1) as usize].points;
        assert_eq!(ab.len(), 3);
        assert!(tr.point(ab[1]).distance(DVec3::new(1.03, 0.0, 0.0)) < 1e-12);
    }

    #[test]
    fn a_piece_next_to_an_input_vertex_is_split_on_a_power_of_two_shell() {
        let (mut tr, mut sm) = strip();
        let seg = |sm: &SurfaceModel, a: u32, b: u32| sm.segments.iter().position(|s| s.points.first() == Some(&a) && s.points.last() == Some(&b)).unwrap() as u32;
        let ab = seg(&sm, 0, 1);
        // both ends input vertices: the midpoint, 1.03
        assert!(split_subsegment(&mut tr, &mut sm, ab, 0, 1).unwrap());
        let m = sm.segments[ab as usize].points[1];
        assert!(tr.point(m).distance(DVec3::new(1.03, 0.0, 0.0)) < 1e-12);
        // (A, m), 1.03 long: on the shell of radius 0.5 around A (not at 0.515)
        assert!(split_subsegment(&mut tr, &mut sm, ab, 0, m).unwrap());
        let p = sm.segments[ab as usize].points[1];
        assert!(tr.point(p).distance(DVec3::new(0.5, 0.0, 0.0)) < 1e-12, "{}", tr.point(p));
        // (m, B), 1.03 long, ends at B = (2.06, 0, 0): 0.5 from B
        assert!(split_subsegment(&mut tr, &mut sm, ab, m, 1).unwrap());
        let q = sm.segments[ab as usize].points[3];
        assert!(tr.point(q).distance(DVec3::new(1.56, 0.0, 0.0)) < 1e-12, "{}", tr.point(q));
        // (p, m): no end of the segment, its midpoint
        assert!(split_subsegment(&mut tr, &mut sm, ab, p, m).unwrap());
        let r = sm.segments[ab as usize].points[2];
        assert!(tr.point(r).distance(DVec3::new(0.765, 0.0, 0.0)) < 1e-12, "{}", tr.point(r));
    }

    /// A pyramid whose top is a rectangle bent by 1e-9 along its input diagonal (p, q), a
    /// ridge: one merged facet. Its apex lies outside the sphere of the top's four corners, so
    /// the Delaunay tetrahedralization holds the flat tet (p, q, r, s) under the top, with both
    /// diagonals, in the material.
    fn bent_pyramid() -> TriSurface {
        let e = 1e-9;
        let (p, r, q, s, x) = (0, 1, 2, 3, 4);
        let mut t = TriSurface::default();
        t.vertices = vec![DVec3::new(-1.0, -1.0, e), DVec3::new(1.0, -1.0, 0.0), DVec3::new(1.0, 1.0, e), DVec3::new(-1.0, 1.0, 0.0), DVec3::new(0.0, 0.0, -2.0)];
        t.triangles = vec![[p, r, q], [p, q, s], [r, p, x], [q, r, x], [s, q, x], [p, s, x]];
        t.face_tags = vec![FaceId(1), FaceId(1), FaceId(2), FaceId(3), FaceId(4), FaceId(5)];
        t
    }

    #[test]
    fn a_flat_tet_under_a_planar_facet_leaves_the_material() {
        let s = bent_pyramid();
        let points = s.vertices.clone();
        let mut sm = SurfaceModel::new(&points, &s.triangles, &s.face_tags, true);
        assert_eq!(sm.facets.len(), 5);
        let mut tr = Tetra::new(points, (0..5).collect(), 1).unwrap();
        recover(&mut tr, &mut sm, 100).unwrap();
        let mut labels = crate::mesh3d::mesher::carve::carve(&mut tr, &sm, &Seeds::default()).unwrap();
        let flat = |tr: &Tetra, labels: &Labels| tr.live().filter(|&t| labels.get(t) != 0 && [0, 1, 2, 3].iter().all(|v| tr.tets[t as usize].v.contains(v))).count();
        // before the rule: the flat tet is material, and nothing later removes it (its
        // radius-edge ratio is 0.7)
        assert_eq!(flat(&tr, &labels), 1);
        assert_eq!(unfold_flat_tets(&mut tr, &mut sm, &mut labels), 1);
        assert_eq!(flat(&tr, &labels), 0);
        // the top now has the other diagonal (r, s)
        let top = sm.subfaces().filter(|&(f, _)| sm.facets[f as usize].tag == FaceId(1)).map(|(_, t)| t).collect::<Vec<_>>();
        assert_eq!(top.len(), 2);
        assert!(top.iter().all(|t| t.contains(&1) && t.contains(&3)), "{top:?}");
        // the whole mesher: no flat tet, the volume kept (up to the 1e-9 bend)
        let opts = MeshOptions::default().with_optimize(false).with_presize(false);
        let (m, _) = mesh_surface(&s, &Seeds::default(), &UniformSize(f64::INFINITY), &opts).unwrap();
        m.validate().unwrap();
        let q = crate::quality::tet_mesh_quality(&m);
        assert!(q.min_dihedral_deg > 5.0, "min dihedral {}", q.min_dihedral_deg);
        assert!((m.volume() - 8.0 / 3.0).abs() < 1e-8, "{}", m.volume());
    }
}
