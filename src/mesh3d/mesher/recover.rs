//! Boundary recovery by conforming Delaunay refinement: Steiner points are inserted on the
//! segments and facets until every subsegment is an edge and every subface a face of the
//! Delaunay tetrahedralization.
//!
//! Rules (as in Delaunay refinement of piecewise linear complexes): a missing subsegment is
//! split at its midpoint; a missing subface gets a point at its circumcentre, unless that
//! centre lies outside the facet or inside the diametral sphere of one of the facet's
//! subsegments, in which case that subsegment is split instead. Steiner points carry the
//! location (segment or facet) that tags and the keep-surface stage need.

use crate::mesh3d::mesher::MeshingError;
use crate::mesh3d::mesher::surface_model::SurfaceModel;
use crate::mesh3d::mesher::tetra::{Inserted, Tetra};
use glam::DVec3;

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
fn insert_point(tr: &mut Tetra, p: DVec3, near: &[u32]) -> Result<Option<u32>, String> {
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
            Err(format!("a Steiner point at {p} could not be inserted ({other:?}, walled {})", tr.walled))
        }
    }
}

/// Splits subsegment `[a, b]` of segment `s` at its midpoint.
pub(crate) fn split_subsegment(tr: &mut Tetra, sm: &mut SurfaceModel, s: u32, a: u32, b: u32) -> Result<bool, String> {
    let (pa, pb) = (tr.point(a), tr.point(b));
    let m = pa + (pb - pa) * 0.5;
    match insert_point(tr, m, &[a, b])? {
        Some(v) => {
            sm.split_segment(s, a, b, v, &tr.k.points);
            Ok(true)
        }
        None => Ok(false),
    }
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
pub(crate) fn encroached_subsegment(tr: &Tetra, sm: &SurfaceModel, f: u32, p: DVec3) -> Option<(u32, [u32; 2])> {
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

/// Splits subface `[a, b, c]` of facet `f`: at its circumcentre if that lies in the facet and
/// encroaches no subsegment, else the encroached (or nearest) subsegment.
pub(crate) fn split_subface(tr: &mut Tetra, sm: &mut SurfaceModel, f: u32, t: [u32; 3], stats: &mut Recovery) -> Result<bool, String> {
    let [pa, pb, pc] = t.map(|v| tr.point(v));
    let cc = circumcenter(pa, pb, pc);
    if let Some((s, [u, v])) = encroached_subsegment(tr, sm, f, cc) {
        stats.segment_points += 1;
        return split_subsegment(tr, sm, s, u, v);
    }
    if !sm.inside(f, cc, &tr.k.points) {
        // outside the facet without encroaching its sides' subsegments: cannot happen in exact
        // arithmetic; split the longest edge of the subface instead
        let e = [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]]
            .into_iter()
            .max_by(|x, y| tr.point(x[0]).distance(tr.point(x[1])).total_cmp(&tr.point(y[0]).distance(tr.point(y[1]))))
            .unwrap_or([t[0], t[1]]);
        for &s in &sm.facets[f as usize].sides {
            if sm.subsegments(s).any(|q| q == e || q == [e[1], e[0]]) {
                stats.segment_points += 1;
                return split_subsegment(tr, sm, s, e[0], e[1]);
            }
        }
        return Err(format!("facet {f}: a subface's circumcentre falls outside it"));
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
/// (`budget`) runs out (very small angles between input facets can make splitting go on).
pub(crate) fn recover(tr: &mut Tetra, sm: &mut SurfaceModel, budget: usize) -> Result<Recovery, MeshingError> {
    let mut stats = Recovery::default();
    let mut buf = Vec::new();
    loop {
        stats.rounds += 1;
        let mut changed = false;
        // subsegments first: a facet cannot be recovered while its sides are missing
        let missing: Vec<(u32, [u32; 2])> = sm.all_subsegments().filter(|&(_, [a, b])| tr.edge_tet(a, b, &mut buf).is_none()).collect();
        for (s, [a, b]) in missing {
            // the subsegment may have been split meanwhile
            if !sm.subsegments(s).any(|e| e == [a, b]) {
                continue;
            }
            stats.segment_points += 1;
            changed |= split_subsegment(tr, sm, s, a, b).map_err(|m| fail(sm, sm.segments[s as usize].facets[0], &m))?;
        }
        if !changed {
            let missing: Vec<(u32, [u32; 3])> =
                sm.subfaces().filter(|&(_, [a, b, c])| tr.face_of(a, b, c, &mut buf).is_none()).collect();
            for (f, t) in missing {
                if !sm.facets[f as usize].subfaces.contains(&t) {
                    continue;
                }
                changed |= split_subface(tr, sm, f, t, &mut stats).map_err(|m| fail(sm, f, &m))?;
            }
        }
        if !changed {
            // nothing could be split: every subface must be there now, or the facet is named
            if let Some((f, t)) = sm.subfaces().find(|&(_, [a, b, c])| tr.face_of(a, b, c, &mut buf).is_none()) {
                return Err(fail(sm, f, &format!("subface {t:?} could not be recovered (no Steiner point could be inserted for it)")));
            }
            return Ok(stats);
        }
        if stats.segment_points + stats.facet_points > budget {
            let f = sm.subfaces().find(|&(_, [a, b, c])| tr.face_of(a, b, c, &mut buf).is_none()).map_or(0, |x| x.0);
            return Err(fail(sm, f, &format!("more than {budget} Steiner points were needed")));
        }
    }
}

fn fail(sm: &SurfaceModel, f: u32, why: &str) -> MeshingError {
    let fc = &sm.facets[f as usize];
    MeshingError::Recovery { triangle: f as usize, tag: fc.tag, message: why.to_string() }
}
