//! What the refinement reports: the small input angles, the triangles that kept an angle
//! under the bound and why, the smallest angles, each segment's chain of vertices.
//!
//! - Stage: last, on the refined triangulation.
//! - Inputs: the domain, the [`Tri`], the angle bound and whether segments could be split.
//! - Output: [`SmallAngle`]s, [`Below`] counts, the smallest angles, the chains.
//! - Definitions: the input angle at a domain point, for each segment leaving it, is the
//!   angle inside the domain from that segment counter-clockwise to the next segment at the
//!   point; it is small under 60°. A triangle is *at a small input angle* when one of its
//!   vertices is such a point, or two of its vertices lie on (or end) two different segments
//!   that meet at such a point.

use super::tri::{Tri, NONE};
use crate::mesh2d::Domain;
use glam::DVec2;

/// An input angle under 60°.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct SmallAngle {
    /// The domain point (its index, also its mesh vertex).
    pub vertex: u32,
    /// The angle inside the domain, degrees.
    pub degrees: f64,
}

/// Triangles whose smallest angle stayed under the bound, by cause.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Below {
    /// At a small input angle (the terminator's doing; see the module docs of `report`).
    pub at_small_input_angle: usize,
    /// Touching the boundary while segments are protected (`split_segments = false`).
    pub protected_boundary: usize,
    /// Anything else (a refused insertion; expected 0).
    pub other: usize,
}

/// The input angles under 60° (see the module docs), by vertex.
pub(crate) fn small_input_angles(domain: &Domain) -> Vec<SmallAngle> {
    let n = domain.points.len();
    let mut at: Vec<Vec<(DVec2, bool)>> = vec![Vec::new(); n];
    for &[a, b] in &domain.segments {
        let d = domain.points[b as usize] - domain.points[a as usize];
        at[a as usize].push((d, true));
        at[b as usize].push((-d, false));
    }
    let mut out = Vec::new();
    for (v, dirs) in at.iter().enumerate() {
        for &(d, leaving) in dirs {
            if !leaving {
                continue;
            }
            let mut best = 360.0f64;
            for &(e, _) in dirs {
                if e == d {
                    continue;
                }
                let mut ang = d.perp_dot(e).atan2(d.dot(e)).to_degrees();
                if ang <= 0.0 {
                    ang += 360.0;
                }
                best = best.min(ang);
            }
            if best < 60.0 {
                out.push(SmallAngle { vertex: v as u32, degrees: best });
            }
        }
    }
    out
}

/// The smallest angle of a triangle, degrees.
pub(crate) fn smallest_angle(p: [DVec2; 3]) -> f64 {
    // the smallest angle is opposite the shortest edge (one arctangent, not three)
    let l = |k: usize| (p[(k + 2) % 3] - p[(k + 1) % 3]).length_squared();
    let k = if l(0) <= l(1) && l(0) <= l(2) { 0 } else if l(1) <= l(2) { 1 } else { 2 };
    let (u, w) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
    u.perp_dot(w).abs().atan2(u.dot(w)).to_degrees()
}

/// The counts under `min_angle` by cause, the smallest angle over all triangles and over
/// those not at a small input angle.
pub(crate) fn below(tri: &Tri, domain: &Domain, small: &[SmallAngle], min_angle: f64, split_segments: bool) -> (Below, f64, f64) {
    let n = tri.inputs;
    let mut is_small = vec![false; n];
    for s in small {
        is_small[s.vertex as usize] = true;
    }
    let mut ends: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (s, &[a, b]) in domain.segments.iter().enumerate() {
        ends[a as usize].push(s as u32);
        ends[b as usize].push(s as u32);
    }
    let segs_of = |v: u32| -> Vec<u32> {
        if (v as usize) < n {
            ends[v as usize].clone()
        } else if tri.on_seg[v as usize] != NONE {
            vec![tri.on_seg[v as usize]]
        } else {
            Vec::new()
        }
    };
    let meet_small = |s1: u32, s2: u32| -> bool {
        let (a, b) = (domain.segments[s1 as usize], domain.segments[s2 as usize]);
        a.iter().any(|&j| (b[0] == j || b[1] == j) && is_small[j as usize])
    };
    let mut counts = Below::default();
    let (mut all, mut away) = (180.0f64, 180.0f64);
    for (t, v) in tri.tv.iter().enumerate() {
        let ang = smallest_angle(tri.corners(t as u32));
        all = all.min(ang);
        let at_small = !small.is_empty()
            && (v.iter().any(|&x| (x as usize) < n && is_small[x as usize])
                || (0..3).any(|k| {
                    let (s1, s2) = (segs_of(v[k]), segs_of(v[(k + 1) % 3]));
                    s1.iter().any(|&a| s2.iter().any(|&b| a != b && meet_small(a, b)))
                }));
        if !at_small {
            away = away.min(ang);
        }
        if ang >= min_angle {
            continue;
        }
        if at_small {
            counts.at_small_input_angle += 1;
        } else if !split_segments && v.iter().any(|&x| (x as usize) < n) {
            counts.protected_boundary += 1;
        } else {
            counts.other += 1;
        }
    }
    (counts, all, away)
}

/// Each domain segment's vertices from its start to its end.
pub(crate) fn chains(tri: &Tri, domain: &Domain) -> Vec<Vec<u32>> {
    let mut on: Vec<Vec<u32>> = vec![Vec::new(); domain.segments.len()];
    for v in tri.inputs..tri.pts.len() {
        let s = tri.on_seg[v];
        if s != NONE {
            on[s as usize].push(v as u32);
        }
    }
    domain.segments.iter().zip(on).map(|(&[a, b], mut mid)| {
        let (pa, pb) = (tri.pts[a as usize], tri.pts[b as usize]);
        let key = |v: u32| (tri.pts[v as usize] - pa).dot(pb - pa);
        mid.sort_by(|&x, &y| key(x).total_cmp(&key(y)).then(x.cmp(&y)));
        let mut c = vec![a];
        c.extend(mid);
        c.push(b);
        c
    }).collect()
}
