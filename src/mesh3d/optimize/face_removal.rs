//! Face removal by the 2-3 flip: two tets sharing an unconstrained face `(a, b, c)`, with apexes
//! `d` and `e`, become the three tets around the new edge `(d, e)`. The flip is possible exactly
//! when the segment `de` crosses the interior of the triangle, i.e. when all three new tets are
//! positively oriented (decided exactly in [`Work::replace`]).
//!
//! With `(a, b, c)` listed outward from the tet of apex `d`, the new tets are `(a, b, d, e)`,
//! `(b, c, d, e)` and `(c, a, d, e)`.

use crate::core::Sign;
use crate::core::ids::NONE;
use crate::mesh::tet_mesh::TET_FACES;
use crate::mesh3d::optimize::measure::flip_radius_edge_bound;
use crate::mesh3d::optimize::work::Work;
use crate::quality::tetrahedron::tet_radius_edge;

/// Tries the 2-3 flip of face `k` of live tet `t`; true if done (the old tets' least score was
/// beaten and the radius-edge bound kept).
pub(crate) fn try_flip23(w: &mut Work, t: u32, k: usize, max_re: f64) -> bool {
    if w.constrained(t, k) {
        return false;
    }
    let code = w.nbr[t as usize][k];
    if code == NONE {
        return false;
    }
    let u = code >> 2;
    let tet = w.tets[t as usize];
    let [a, b, c] = TET_FACES[k].map(|i| tet[i]);
    let d = tet[k];
    let e = w.tets[u as usize][(code & 3) as usize];
    let new = [[a, b, d, e], [b, c, d, e], [c, a, d, e]];
    let old_min = w.q[t as usize].min(w.q[u as usize]);
    let mut new_min = f64::INFINITY;
    for n in &new {
        if w.orient(n) != Sign::Positive {
            return false;
        }
        new_min = new_min.min(w.score_of(n));
        if new_min <= old_min {
            return false;
        }
    }
    let bound = flip_radius_edge_bound([w.corners(&tet), w.corners(&w.tets[u as usize])], max_re);
    if new.iter().any(|n| tet_radius_edge(&w.corners(n)) > bound) {
        return false;
    }
    let region = w.region[t as usize];
    w.replace(&[t, u], &new, region)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::RegionId;
    use crate::mesh::TetMesh;
    use crate::mesh3d::optimize::measure::Targets;
    use glam::DVec3;

    #[test]
    fn flip23_of_a_flat_pair() {
        // two flat tets on a wide triangle, apexes close to it on either side: the 2-3 flip
        // gives three tets around the short edge between the apexes, twice as good
        let m = TetMesh {
            vertices: vec![
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(0.5, 0.9, 0.0),
                DVec3::new(0.5, 0.3, -0.05),
                DVec3::new(0.5, 0.3, 0.05),
            ],
            tets: vec![[0, 2, 1, 3], [0, 1, 2, 4]],
            region_tags: vec![RegionId(1); 2],
            ..Default::default()
        };
        assert_eq!(m.validate(), Ok(()));
        let mut w = Work::build(&m, Targets::new(15.0, 160.0)).unwrap();
        let k = (0..4).find(|&k| !w.constrained(0, k)).unwrap();
        let before = w.q[0].min(w.q[1]);
        // the new tets' radius-edge ratio (5.98) exceeds both the bound and the old (5.97)
        assert!(!try_flip23(&mut w, 0, k, 2.0));
        assert_eq!(w.live(), 2);
        assert!(try_flip23(&mut w, 0, k, 6.0));
        assert_eq!(w.live(), 3);
        let after = w.live_slots().map(|s| w.q[s as usize]).fold(f64::INFINITY, f64::min);
        assert!(after > 1.5 * before, "{before} -> {after}");
        let mut out = m.clone();
        w.write_back(&mut out);
        assert_eq!(out.validate(), Ok(()));
        assert!((out.volume() - m.volume()).abs() < 1e-15);
        // a pair that is already better than its flip is left alone
        let mut far = m.clone();
        far.vertices[3].z = -0.8;
        far.vertices[4].z = 0.8;
        let mut w = Work::build(&far, Targets::new(15.0, 160.0)).unwrap();
        assert!(!try_flip23(&mut w, 0, k, 2.0));
        assert_eq!(w.live(), 2);
        // the reverse is an edge removal (3-2), which must not undo an improvement
        let mut w = Work::build(&out, Targets::new(15.0, 160.0)).unwrap();
        let mut er = crate::mesh3d::optimize::edge_removal::EdgeRemoval::default();
        assert_eq!(er.try_remove(&mut w, 0, 3, 4, 2.0), None);
    }
}
