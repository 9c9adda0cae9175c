//! The size a solid's thickness asks for: at each vertex of a sized tessellation, the distance
//! through the solid to the nearest wall facing it (a plate's other side, a rib between two
//! pockets, the web between a hole and a face, the other side of a wedge).
//!
//! `feature_size` measures widths along a face (between the edges of one face); this measures
//! across the solid. Without it, a wall thinner than the size gets tets as long as the size
//! and as high as the wall: the flat tets of 166° to 169° at the walls of the corpus'
//! `abc-0000` and at `wing_fuselage`'s trailing edges. TetGen reaches such sizes by
//! splitting the subfaces its refinement encroaches, later and with more points.

use crate::core::aabb::Aabb;
use crate::core::bvh::Bvh;
use crate::core::closest::closest_point_on_triangle;
use crate::core::SizeField;
use crate::core::union_find::UnionFind;
use crate::mesh::TriSurface;
use glam::DVec3;
use rayon::prelude::*;

/// A wall `d` thick asks for a size of `WALL_FACTOR · d`: two to three tets across it.
const WALL_FACTOR: f64 = 1.5;

/// Walls at least this share of the size asked for ask for nothing (a tet of the size then
/// already has a height of a third of it across the wall).
const THICK: f64 = 1.0 / 3.0;

/// The size never falls under this share of the size asked for (as for narrow faces).
const FLOOR: f64 = 1.0 / 64.0;

/// Walls under this many chords thick ask for nothing: the gap between two chords of one
/// curved surface, the last stretch of a wedge towards its edge (whose angle no size
/// removes), or a wall that is a rounding error of the CAD model.
pub(super) const MIN_CHORDS: f64 = 2.0;

/// Two triangles face each other when their unit normals make more than 120°.
const FACING: f64 = -0.5;

/// Samples `(point, size)` where a wall of the solid is thinner than a third of the size
/// asked for: at the vertices of `surface` (closed shells, outward), the size `1.5 d` for the
/// wall thickness `d`, floored at 1/64 of the size.
///
/// A vertex is measured against the triangles of its shell that face it (normals more than
/// 120° apart), lie inward from it and have it on their inner side: a plate's other side, a
/// pin's far side, and the two sides of a wedge (a wing's trailing edge, a sharp fold), which
/// grade towards their edge down to two chords. Faces that meet at an angle over 60° (a
/// plate's sides and top) never face each other.
pub(super) fn wall_samples(surface: &TriSurface, inner: &dyn SizeField, chord: f64) -> Vec<(DVec3, f64)> {
    let (v, tris) = (&surface.vertices, &surface.triangles);
    if tris.is_empty() {
        return Vec::new();
    }
    // shells: vertices joined by triangles
    let mut shells = UnionFind::new(v.len());
    for t in tris {
        shells.union(t[0], t[1]);
        shells.union(t[0], t[2]);
    }
    let (shell_of, _) = shells.labels();
    // unit normals and area-weighted vertex normals
    let mut normal = Vec::with_capacity(tris.len());
    let mut vn = vec![DVec3::ZERO; v.len()];
    for t in tris {
        let [a, b, c] = t.map(|k| v[k as usize]);
        let n = (b - a).cross(c - a);
        normal.push(n.normalize_or_zero());
        for &k in t {
            vn[k as usize] += n;
        }
    }
    let bvh = Bvh::build(tris.iter().enumerate().map(|(i, t)| (i as u32, Aabb::from_points(t.map(|k| v[k as usize]).iter()))));
    // each vertex on its own (in vertex order, whatever the threads): the nearest triangle that
    // faces it, branch and bound within a third of the size
    (0..v.len())
        .into_par_iter()
        .filter_map(|p_id| {
            let p = v[p_id];
            let n = vn[p_id].normalize_or_zero();
            if n == DVec3::ZERO {
                return None;
            }
            let h = inner.size_at(p);
            if !(h.is_finite() && h > 0.0) {
                return None;
            }
            let r = THICK * h;
            if r <= MIN_CHORDS * chord {
                return None;
            }
            let shell = shell_of[p_id];
            let facing = |i: u32| -> f64 {
                let i = i as usize;
                let t = tris[i];
                if normal[i].dot(n) > FACING || t.contains(&(p_id as u32)) || shell_of[t[0] as usize] != shell {
                    return f64::INFINITY;
                }
                let dc = closest_point_on_triangle(p, t.map(|k| v[k as usize])) - p;
                // inward from p, and p on the triangle's inner side
                if dc.dot(n) < 0.0 && dc.dot(normal[i]) > 0.0 { dc.length() } else { f64::INFINITY }
            };
            let (_, d) = bvh.nearest_within(p, r, facing)?;
            (d > MIN_CHORDS * chord).then(|| (p, (WALL_FACTOR * d).max(FLOOR * h)))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cad::brep::Model;
    use crate::core::size_field::UniformSize;

    fn samples(m: &Model, h: f64) -> Vec<(DVec3, f64)> {
        let t = super::super::tessellate_sized(m, &super::super::TessellateOptions::default(), &UniformSize(h));
        wall_samples(&t.surface, &UniformSize(h), t.chord)
    }

    #[test]
    fn a_thin_wall_asks_for_its_thickness_across_the_solid() {
        // a tube with a wall 1 thick, at size 6: bore and outer face see each other 1 apart
        let tube = crate::cad::parts::Tube { inner_radius: 10.0, outer_radius: 11.0, length: 40.0, angle_deg: 360.0 }.build().unwrap();
        let s = samples(&tube, 6.0);
        assert!(s.len() > 100, "{}", s.len());
        for &(p, h) in &s {
            let r = (p.x * p.x + p.y * p.y).sqrt();
            // on the bore or the outer face (not the ends, 40 apart), 1.5 times the wall: less
            // by the chords, more at the rims (their normals lean on the ends' and the wall
            // is measured aslant)
            assert!((r - 10.0).abs() < 0.05 || (r - 11.0).abs() < 0.05, "{p}");
            assert!((1.45..1.75).contains(&h), "{h} at {p}");
        }
        // a plate 0.3 thick: only its two large faces, at 1.5 x 0.3
        let slab = crate::cad::parts::Block::new(40.0, 10.0, 0.3).build().unwrap();
        let s = samples(&slab, 5.0);
        assert!(!s.is_empty());
        assert!(s.iter().all(|&(p, h)| (p.z.abs() < 1e-9 || (p.z - 0.3).abs() < 1e-9) && (h - 0.45).abs() < 1e-6), "{s:?}");
    }

    #[test]
    fn thick_walls_and_faces_that_meet_square_ask_for_nothing() {
        // walls of 10 at size 6 (over a third of it); the sides meet the top at edges
        let tube = crate::cad::parts::Tube { inner_radius: 10.0, outer_radius: 20.0, length: 40.0, angle_deg: 360.0 }.build().unwrap();
        assert!(samples(&tube, 6.0).is_empty());
        let block = crate::cad::parts::Block::new(40.0, 10.0, 10.0).build().unwrap();
        assert!(samples(&block, 5.0).is_empty());
    }
}
