//! Caps: triangles flat up to rounding whose vertex lies on their long side, as tessellators
//! make at a cone's apex. Two of a cap's edges meet at an angle of zero, which no mesher can
//! separate and which no input-angle report should name; [`repair_caps`] removes them.

use crate::mesh::TriSurface;
use glam::DVec3;
use rustc_hash::FxHashMap;

/// A vertex nearer an input triangle's opposite side than this share of the model's diagonal
/// makes the triangle a cap: flat up to rounding (a tessellator's triangle at a cone's apex
/// whose other two vertices lie on one generator).
const CAP_HEIGHT: f64 = 1e-10;

/// Repairs caps: triangles `(a, b, v)` whose vertex `v` lies on their side `(a, b)` (up to
/// [`CAP_HEIGHT`] of the diagonal, strictly between its ends). Such a triangle has no area but
/// makes two input edges meet at an angle of zero, which no boundary recovery can separate.
/// The cap and its neighbour across `(a, b)` become the two triangles of their union, split
/// at `v`: `(b, v, w)` and `(v, a, w)`, with the neighbour's tag. The surface stays closed and
/// covers the same set; the triangle count does not change. Returns the repaired surface and
/// the number of caps, or `None` where there are none (or where `s` has indices out of range,
/// tags that do not match its triangles, or points that are not finite: its checks name those).
pub fn repair_caps(s: &TriSurface) -> Option<(TriSurface, usize)> {
    // a surface that does not validate is left to the caller's checks
    let n = s.vertices.len();
    if s.face_tags.len() != s.triangles.len() || s.triangles.iter().flatten().any(|&v| v as usize >= n) || s.vertices.iter().any(|p| !p.is_finite()) {
        return None;
    }
    let (lo, hi) = s.vertices.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), &p| (l.min(p), h.max(p)));
    let tol = CAP_HEIGHT * lo.distance(hi);
    let p = |v: u32| s.vertices[v as usize];
    // the corner of `t` that lies on its opposite side, as (v, a, b)
    let cap = |t: [u32; 3]| {
        (0..3).find_map(|k| {
            let (v, a, b) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            let (pa, pb, pv) = (p(a), p(b), p(v));
            let e = pb - pa;
            let l2 = e.length_squared();
            let u = (pv - pa).dot(e) / l2;
            let h = e.cross(pv - pa).length() / l2.sqrt();
            (l2 > 0.0 && u > 0.0 && u < 1.0 && h <= tol).then_some((v, a, b))
        })
    };
    if !s.triangles.iter().any(|&t| cap(t).is_some()) {
        return None;
    }
    let mut out = s.clone();
    let mut repaired = 0;
    // a few rounds: a neighbour changed in one round is looked at again in the next
    for _ in 0..8 {
        let mut on_edge: FxHashMap<(u32, u32), u32> = Default::default();
        for (i, t) in out.triangles.iter().enumerate() {
            for k in 0..3 {
                on_edge.insert((t[k], t[(k + 1) % 3]), i as u32);
            }
        }
        let mut touched = vec![false; out.triangles.len()];
        let mut changed = false;
        for i in 0..out.triangles.len() {
            if touched[i] {
                continue;
            }
            let Some((v, a, b)) = cap(out.triangles[i]) else { continue };
            // the neighbour holds the side the other way round: (b, a, w)
            let Some(&j) = on_edge.get(&(b, a)) else { continue };
            let j = j as usize;
            if touched[j] || j == i {
                continue;
            }
            let tj = out.triangles[j];
            let k = (0..3).find(|&k| tj[k] == b && tj[(k + 1) % 3] == a).unwrap_or(0);
            let w = tj[(k + 2) % 3];
            if w == v || cap([b, v, w]).is_some() || cap([v, a, w]).is_some() {
                continue;
            }
            out.triangles[j] = [b, v, w];
            out.triangles[i] = [v, a, w];
            out.face_tags[i] = out.face_tags[j];
            touched[i] = true;
            touched[j] = true;
            repaired += 1;
            changed = true;
        }
        if !changed {
            break;
        }
    }
    (repaired > 0).then_some((out, repaired))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::core::FaceId;
    use crate::mesh::topology::open_edges_list;

    /// The unit tetrahedron whose bottom face has a point `m` on its edge (A, B), 1e-13 below
    /// it, that the side face (A, B, D) lacks: the gap is closed by the cap (B, A, m), as a
    /// tessellator leaves one at a cone's apex.
    pub(crate) fn capped_tetrahedron() -> TriSurface {
        let (a, b, c, d, m) = (0, 1, 2, 3, 4);
        TriSurface {
            vertices: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::new(0.5, 0.0, -1e-13)],
            triangles: vec![[a, c, m], [m, c, b], [a, b, d], [a, d, c], [b, c, d], [b, a, m]],
            face_tags: [1, 1, 2, 3, 4, 1].map(FaceId).to_vec(),
            ..Default::default()
        }
    }

    #[test]
    fn a_cap_and_its_neighbour_become_the_halves_of_their_union() {
        let s = capped_tetrahedron();
        assert!(open_edges_list(&s).is_empty());
        let (r, n) = repair_caps(&s).unwrap();
        assert_eq!(n, 1);
        assert_eq!(r.triangles.len(), s.triangles.len());
        assert!(open_edges_list(&r).is_empty());
        // the side face (A, B, D) is split at m, both halves keep its tag
        assert_eq!(r.triangles[2], [0, 4, 3]);
        assert_eq!(r.triangles[5], [4, 1, 3]);
        assert_eq!(r.face_tags[2], FaceId(2));
        assert_eq!(r.face_tags[5], FaceId(2));
        // no cap is left, and the area is the same
        assert!(repair_caps(&r).is_none());
        let area = |s: &TriSurface| s.triangles.iter().map(|t| { let [p, q, w] = t.map(|v| s.vertices[v as usize]); (q - p).cross(w - p).length() / 2.0 }).sum::<f64>();
        assert!((area(&r) - area(&s)).abs() < 1e-12);
    }

    #[test]
    fn a_surface_with_bad_indices_is_left_to_its_checks() {
        let mut s = capped_tetrahedron();
        s.triangles[0][0] = 99;
        assert!(repair_caps(&s).is_none());
    }

    #[test]
    fn a_thin_triangle_that_is_no_cap_stays() {
        // m 1e-6 below the edge: a thin triangle of the model, not rounding
        let mut s = capped_tetrahedron();
        s.vertices[4].z = -1e-6;
        assert!(repair_caps(&s).is_none());
    }
}
