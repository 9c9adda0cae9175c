//! Independent validation of a Delaunay tetrahedralization: adjacency is rebuilt from the tets
//! alone, and every property is decided with the exact predicates.

use crate::core::predicates::{insphere, insphere_sos, orient3d};
use crate::core::Sign;
use crate::mesh::tet_mesh::TET_FACES;
use crate::mesh3d::delaunay::Delaunay;
use glam::DVec3;
use rayon::prelude::*;

/// The first property of a Delaunay tetrahedralization found violated.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DelaunayViolation {
    /// A tet refers to a point that does not exist.
    #[error("tet {tet} {verts:?} refers to a point beyond the {count} input points")]
    IndexOutOfRange {
        /// The tet.
        tet: usize,
        /// Its vertices.
        verts: [u32; 4],
        /// Number of points.
        count: usize,
    },
    /// A tet is flat or inverted.
    #[error("tet {tet} {verts:?} is not positively oriented ({sign:?})")]
    NotPositive {
        /// The tet.
        tet: usize,
        /// Its vertices.
        verts: [u32; 4],
        /// Its exact orientation.
        sign: Sign,
    },
    /// A face belongs to more than two tets, or two tets share it from the same side.
    #[error("face {face:?} is shared by tets {tets:?} incorrectly (more than two, or from the same side)")]
    BadFace {
        /// The face (sorted).
        face: [u32; 3],
        /// The tets sharing it.
        tets: Vec<usize>,
    },
    /// A point is inside the circumsphere of a tet across an interior face.
    #[error("point {point} lies inside the circumsphere of tet {tet} {verts:?} ({})", if *exact { "exactly" } else { "under the perturbation" })]
    NotDelaunay {
        /// The tet.
        tet: usize,
        /// Its vertices.
        verts: [u32; 4],
        /// The offending point.
        point: u32,
        /// True if inside exactly, false if only under the symbolic perturbation.
        exact: bool,
    },
    /// The boundary is not convex: a hull face sees a vertex of its neighbour across an edge.
    #[error("the hull is not convex at face {face:?} (point {point} beyond it)")]
    NotConvex {
        /// An outward hull face.
        face: [u32; 3],
        /// A vertex beyond its plane.
        point: u32,
    },
    /// The boundary is not closed: an edge of this hull face is on no other hull face.
    #[error("the hull is not closed at face {face:?}")]
    HullOpen {
        /// An outward hull face.
        face: [u32; 3],
    },
    /// A point is neither a vertex nor a listed duplicate of one.
    #[error("point {point} is missing from the tetrahedralization")]
    MissingPoint {
        /// The point.
        point: usize,
    },
    /// A listed duplicate does not coincide with its kept point, or is itself used.
    #[error("duplicate pair {pair:?} is wrong (not coincident, or the left-out point is used)")]
    BadDuplicate {
        /// The pair `(left out, kept)`.
        pair: [u32; 2],
    },
}

/// See [`Delaunay::validate`].
pub(crate) fn validate(d: &Delaunay, points: &[DVec3]) -> Result<(), DelaunayViolation> {
    let n = points.len();
    let p = |i: u32| points[i as usize];
    // 1. indices and orientation
    for (t, w) in d.tets.iter().enumerate() {
        if w.iter().any(|&v| v as usize >= n) {
            return Err(DelaunayViolation::IndexOutOfRange { tet: t, verts: *w, count: n });
        }
    }
    if let Some((t, s)) = d
        .tets
        .par_iter()
        .enumerate()
        .map(|(t, w)| (t, orient3d(p(w[0]), p(w[1]), p(w[2]), p(w[3]))))
        .find_first(|(_, s)| *s != Sign::Positive)
    {
        return Err(DelaunayViolation::NotPositive { tet: t, verts: d.tets[t], sign: s });
    }
    // 2. faces: (sorted face, tet, opposite vertex, outward face as listed)
    let mut faces: Vec<([u32; 3], u32, u32, [u32; 3])> = d
        .tets
        .par_iter()
        .enumerate()
        .flat_map_iter(|(t, w)| {
            TET_FACES.iter().enumerate().map(move |(k, f)| {
                let o = [w[f[0]], w[f[1]], w[f[2]]];
                let mut s = o;
                s.sort_unstable();
                (s, t as u32, w[k], o)
            })
        })
        .collect();
    faces.par_sort_unstable_by_key(|f| (f.0, f.1));
    let mut hull: Vec<[u32; 3]> = Vec::new();
    let mut interior: Vec<(u32, u32)> = Vec::new(); // (tet, opposite vertex of the other tet)
    let mut i = 0;
    while i < faces.len() {
        let mut j = i + 1;
        while j < faces.len() && faces[j].0 == faces[i].0 {
            j += 1;
        }
        match j - i {
            1 => hull.push(faces[i].3),
            2 => {
                // from opposite sides: the two outward orientations are opposite cycles
                let (a, b) = (faces[i].3, faces[i + 1].3);
                let same_cycle = (0..3).any(|r| [a[r], a[(r + 1) % 3], a[(r + 2) % 3]] == b);
                if same_cycle {
                    return Err(DelaunayViolation::BadFace { face: faces[i].0, tets: vec![faces[i].1 as usize, faces[i + 1].1 as usize] });
                }
                interior.push((faces[i].1, faces[i + 1].2));
            }
            _ => {
                return Err(DelaunayViolation::BadFace { face: faces[i].0, tets: faces[i..j].iter().map(|f| f.1 as usize).collect() });
            }
        }
        i = j;
    }
    drop(faces);
    // 3. local Delaunay across every interior face, exactly and under the perturbation
    let bad = interior.par_iter().find_map_first(|&(t, v)| {
        let w = d.tets[t as usize];
        let exact = insphere(p(w[0]), p(w[1]), p(w[2]), p(w[3]), p(v));
        if exact == Sign::Positive {
            return Some((t, v, true));
        }
        let sos = insphere_sos([p(w[0]), p(w[1]), p(w[2]), p(w[3]), p(v)], [w[0], w[1], w[2], w[3], v]);
        (sos != Sign::Negative).then_some((t, v, false))
    });
    if let Some((t, v, exact)) = bad {
        return Err(DelaunayViolation::NotDelaunay { tet: t as usize, verts: d.tets[t as usize], point: v, exact });
    }
    // 4. the hull: closed, and convex at every edge
    let mut edges: Vec<([u32; 2], u32)> = Vec::with_capacity(hull.len() * 3);
    for (h, f) in hull.iter().enumerate() {
        for r in 0..3 {
            edges.push(([f[r], f[(r + 1) % 3]], h as u32));
        }
    }
    edges.sort_unstable();
    for &([a, b], h) in &edges {
        let Ok(k) = edges.binary_search_by(|e| e.0.cmp(&[b, a])) else {
            return Err(DelaunayViolation::HullOpen { face: hull[h as usize] });
        };
        let g = hull[edges[k].1 as usize];
        let v = g.iter().copied().find(|&x| x != a && x != b).unwrap_or(a);
        let f = hull[h as usize];
        if orient3d(p(f[0]), p(f[1]), p(f[2]), p(v)) == Sign::Positive {
            return Err(DelaunayViolation::NotConvex { face: f, point: v });
        }
    }
    // 5. every point is a vertex or a listed duplicate of a coincident vertex
    let mut used = vec![false; n];
    for w in &d.tets {
        for &v in w {
            used[v as usize] = true;
        }
    }
    for &[gone, kept] in &d.duplicates {
        if gone as usize >= n || kept as usize >= n || used[gone as usize] || !used[kept as usize] || p(gone) != p(kept) {
            return Err(DelaunayViolation::BadDuplicate { pair: [gone, kept] });
        }
        used[gone as usize] = true;
    }
    if let Some(i) = used.iter().position(|u| !u) {
        return Err(DelaunayViolation::MissingPoint { point: i });
    }
    Ok(())
}
