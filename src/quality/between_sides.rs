//! Tets that lie between the two sides of a small input angle without touching its vertex or
//! edge: a vertex on each side, the two seen from the angle's vertex (or across its edge)
//! under the angle bound.
//!
//! Where two sides meet at a small angle, a point on one side forces the region between them
//! to be meshed, and for any angle bound some inputs cannot be meshed there without new small
//! angles (Shewchuk's negative result on quality triangulations, after Mitchell's bound on the
//! grading of a segment's subsegments). Delaunay refiners leave such elements between the two
//! sides (Triangle: "small angles between input segments cannot be eliminated"), and
//! protecting balls leave them on the balls' surface, off the apex itself. The reports count
//! these tets on their own, beside those that touch the angle
//! ([`crate::quality::worst_tet::touches_angle_below`]), so that a user sees which bad tets a
//! thin wedge, a sliver face or a knife edge of the part explains.
//!
//! Sides are recognised by face tags: a corner of face `F` between the edges to faces `G` and
//! `H` (its [`InputAngle::across`]) has one vertex of the tet on both `F` and `G` and another
//! on both `F` and `H`; a dihedral angle between faces `X` and `Y` has one on `X` only and
//! another on `Y` only, their feet on the angle's edge. Plain floating point: a figure for
//! reports.

use crate::core::FaceId;
use crate::mesh::TetMesh;
use crate::quality::input_angles::{InputAngle, InputAngleKind};
use glam::DVec3;

/// The face tags of every vertex of a tet mesh's boundary, for [`SideTags::between_sides`].
#[derive(Clone, Debug)]
pub struct SideTags {
    /// `tags[start[v]..start[v + 1]]`: vertex `v`'s tags, sorted.
    start: Vec<u32>,
    tags: Vec<FaceId>,
}

impl SideTags {
    /// The tags of `mesh`'s boundary triangles at each vertex.
    pub fn new(mesh: &TetMesh) -> SideTags {
        let mut pairs: Vec<(u32, FaceId)> = Vec::with_capacity(3 * mesh.boundary.len());
        for (k, tri) in mesh.boundary.iter().enumerate() {
            let f = mesh.face_tags.get(k).copied().unwrap_or_default();
            pairs.extend(tri.iter().map(|&v| (v, f)));
        }
        pairs.sort_unstable();
        pairs.dedup();
        let n = mesh.vertices.len();
        let mut start = vec![0u32; n + 1];
        for &(v, _) in &pairs {
            if (v as usize) < n {
                start[v as usize + 1] += 1;
            }
        }
        for k in 0..n {
            start[k + 1] += start[k];
        }
        let tags = pairs.into_iter().filter(|&(v, _)| (v as usize) < n).map(|(_, f)| f).collect();
        SideTags { start, tags }
    }

    /// The tags of the boundary triangles at vertex `v`, sorted.
    pub(crate) fn of(&self, v: u32) -> &[FaceId] {
        match (self.start.get(v as usize), self.start.get(v as usize + 1)) {
            (Some(&a), Some(&b)) => &self.tags[a as usize..b as usize],
            _ => &[],
        }
    }

    fn has(&self, v: u32, f: FaceId) -> bool {
        self.of(v).binary_search(&f).is_ok()
    }

    /// The first of `angles` (smallest first) under `below` degrees between whose two sides
    /// tet `tet` of `mesh` lies (see the module documentation), as its index.
    pub fn between_sides(&self, mesh: &TetMesh, tet: [u32; 4], angles: &[InputAngle], below: f64) -> Option<usize> {
        let p = |v: u32| mesh.vertices.get(v as usize).copied().unwrap_or(DVec3::NAN);
        let under = |u: DVec3, w: DVec3| u.length_squared() > 0.0 && w.length_squared() > 0.0 && u.angle_between(w).to_degrees() < below;
        angles.iter().take_while(|a| a.angle_deg < below).position(|a| {
            let pairs = (0..4).flat_map(|i| (0..4).filter(move |&j| j != i).map(move |j| (tet[i], tet[j])));
            match a.kind {
                InputAngleKind::Corner => {
                    let (f, [g, h]) = (a.faces[0], a.across);
                    if g == h || g == f || h == f {
                        return false;
                    }
                    let c = DVec3::from_array(a.at[0]);
                    pairs.into_iter().any(|(x, y)| {
                        self.has(x, f) && self.has(x, g) && self.has(y, f) && self.has(y, h) && under(p(x) - c, p(y) - c)
                    })
                }
                InputAngleKind::Dihedral => {
                    let [fx, fy] = a.faces;
                    if fx == fy {
                        return false;
                    }
                    let [ea, eb] = a.at.map(DVec3::from_array);
                    let len = ea.distance(eb);
                    if len == 0.0 {
                        return false;
                    }
                    let e = (eb - ea) / len;
                    pairs.into_iter().any(|(x, y)| {
                        if !(self.has(x, fx) && !self.has(x, fy) && self.has(y, fy) && !self.has(y, fx)) {
                            return false;
                        }
                        let (px, py) = (p(x), p(y));
                        let s = ((px + py) * 0.5 - ea).dot(e);
                        (0.0..=len).contains(&s) && under((px - ea).reject_from_normalized(e), (py - ea).reject_from_normalized(e))
                    })
                }
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::TriSurface;
    use crate::quality::input_angles::small_input_angles;

    /// A plate 1 thick whose top face (tag 1) is a wedge of `deg` degrees, 10 long, at the
    /// origin, between the side faces 3 (y = 0) and 4; bottom 2, end 5.
    fn wedge_plate(deg: f64) -> TriSurface {
        let a = deg.to_radians();
        let base = [DVec3::ZERO, DVec3::new(10.0, 0.0, 0.0), DVec3::new(10.0 * a.cos(), 10.0 * a.sin(), 0.0)];
        let mut vertices: Vec<DVec3> = base.iter().map(|p| *p + DVec3::Z).collect();
        vertices.extend(base);
        // top 0 1 2, bottom 3 4 5; outward
        let triangles = vec![[0, 1, 2], [3, 5, 4], [0, 3, 4], [0, 4, 1], [2, 5, 3], [2, 3, 0], [1, 4, 5], [1, 5, 2]];
        let face_tags = [1, 2, 3, 3, 4, 4, 5, 5].map(FaceId).to_vec();
        TriSurface { vertices, triangles, face_tags, ..Default::default() }
    }

    /// A mesh whose vertices are `points` and whose boundary tags them: each point with the
    /// tags given (as degenerate boundary triangles of one vertex, enough for the index).
    fn tagged(points: &[(DVec3, &[u32])]) -> TetMesh {
        let mut m = TetMesh { vertices: points.iter().map(|p| p.0).collect(), ..Default::default() };
        for (v, (_, tags)) in points.iter().enumerate() {
            for &t in tags.iter() {
                m.boundary.push([v as u32; 3]);
                m.face_tags.push(FaceId(t));
            }
        }
        m
    }

    #[test]
    fn a_corner_knows_the_faces_across_its_sides() {
        let angles = small_input_angles(&wedge_plate(4.0), 10.0, true);
        let top: Vec<&InputAngle> = angles.iter().filter(|a| a.kind == InputAngleKind::Corner && a.faces[0] == FaceId(1)).collect();
        assert_eq!(top.len(), 1, "{angles:?}");
        let mut across = top[0].across;
        across.sort();
        assert_eq!(across, [FaceId(3), FaceId(4)]);
        let knife: Vec<&InputAngle> = angles.iter().filter(|a| a.kind == InputAngleKind::Dihedral).collect();
        assert_eq!(knife.len(), 1, "{angles:?}");
        assert_eq!(knife[0].across, knife[0].faces);
    }

    #[test]
    fn a_tet_with_a_vertex_on_each_side_of_a_thin_wedge_lies_between_them() {
        let angles = small_input_angles(&wedge_plate(4.0), 10.0, true);
        let a = 4f64.to_radians();
        let d = 5.0;
        // on the top's two edges 5 from the corner, and two points above the plate's middle
        let m = tagged(&[
            (DVec3::new(d, 0.0, 1.0), &[1, 3]),
            (DVec3::new(d * a.cos(), d * a.sin(), 1.0), &[1, 4]),
            (DVec3::new(d, 0.1, 0.5), &[]),
            (DVec3::new(d + 0.5, 0.1, 0.5), &[]),
            (DVec3::new(d, 0.0, 0.0), &[2, 3]),
            (DVec3::new(8.0, 3.0, 1.0), &[1]),
        ]);
        let tags = SideTags::new(&m);
        // the wedge's walls make a 4° knife edge too, which comes first on the tie
        let k = tags.between_sides(&m, [0, 1, 2, 3], &angles, 10.0).expect("between the top's sides");
        assert!((angles[k].angle_deg - 4.0).abs() < 1e-9);
        let corners: Vec<InputAngle> = angles.iter().filter(|a| a.kind == InputAngleKind::Corner).cloned().collect();
        let k = tags.between_sides(&m, [0, 1, 2, 3], &corners, 10.0).expect("between the top corner's sides");
        assert_eq!(corners[k].faces[0], FaceId(1));
        // not under a bound below the wedge's angle; not with one side only; not from the
        // face's inside, which is on neither side
        assert_eq!(tags.between_sides(&m, [0, 1, 2, 3], &angles, 3.0), None);
        assert_eq!(tags.between_sides(&m, [0, 4, 2, 3], &corners, 10.0), None);
        assert_eq!(tags.between_sides(&m, [0, 5, 2, 3], &corners, 10.0), None);
    }

    #[test]
    fn a_tet_across_a_knife_edge_lies_between_its_faces_only_beside_the_edge() {
        let angles = small_input_angles(&wedge_plate(4.0), 10.0, true);
        let a = 4f64.to_radians();
        // the knife edge runs from (0,0,0) to (0,0,1) between faces 3 and 4
        let m = tagged(&[
            (DVec3::new(0.3, 0.0, 0.5), &[3]),
            (DVec3::new(0.3 * a.cos(), 0.3 * a.sin(), 0.5), &[4]),
            (DVec3::new(0.3, 0.01, 0.3), &[]),
            (DVec3::new(0.3, 0.01, 0.7), &[]),
            (DVec3::new(0.3 * a.cos(), 0.3 * a.sin(), 5.0), &[4]),
        ]);
        let tags = SideTags::new(&m);
        let k = tags.between_sides(&m, [0, 1, 2, 3], &angles, 10.0).expect("between the knife's faces");
        assert_eq!(angles[k].kind, InputAngleKind::Dihedral);
        // feet beyond the edge's ends
        assert_eq!(tags.between_sides(&m, [0, 4, 2, 3], &angles, 10.0), None);
    }
}
