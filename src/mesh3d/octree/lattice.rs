//! The body-centred cubic (BCC) lattice of isosurface stuffing: cube corners and cube
//! centres, and the tetrahedra made of them (Labelle and Shewchuk 2007, section 3).
//!
//! Stage: the background grid of the uniform octree mesher. Input: the box to cover and the
//! cell size `h` (the cube's edge). Output: [`Lattice`], which numbers the lattice vertices,
//! gives their positions and neighbours, and lists the background tets around each centre.
//!
//! # Invariants
//! - Vertices have *doubled* integer coordinates: corners all even, centres all odd; the
//!   position of `c` is `origin + c h / 2`. Corners are numbered first (`x` fastest), then
//!   centres.
//! - A lattice edge joins two corners or two centres one cell apart along an axis (a *long*
//!   edge, length `h`) or a corner and a centre of its cube (a *short* edge, `h √3 / 2`).
//! - Every background tet joins two centres one cell apart and the two ends of one edge of
//!   the square face between their cubes: 12 per cube, all congruent, two long and four short
//!   edges, dihedral angles 60° and 90°. [`Lattice::tets_around`] lists the 12 owned by a
//!   centre (the ones towards `+x`, `+y`, `+z` neighbours), each positively oriented, so that
//!   every tet of the lattice is listed exactly once.
//! - The origin is the box's low corner moved out by `(1 + φ) h` (`φ` an irrational-looking
//!   fraction), so that axis-aligned input faces at round coordinates do not fall on lattice
//!   planes, and at least one layer of lattice vertices lies outside the box on every side.

use crate::core::Aabb;
use crate::core::predicates::orient3d_int;
use glam::DVec3;
use serde::Serialize;

/// Offset of the lattice from the box, in cells, beyond the one cell of margin.
const PHI: [f64; 3] = [0.236_067_977_5, 0.302_775_637_7, 0.171_572_875_3];

/// Most lattice vertices the mesher builds (about 2 GiB of working memory).
pub const MAX_VERTICES: u64 = 120_000_000;

/// Why no lattice covers a box at a cell size ([`Lattice::covering`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error, Serialize)]
#[non_exhaustive]
pub enum LatticeError {
    /// The cell size is not a positive finite number.
    #[error("cell size {h} is not a positive number")]
    NotASize {
        /// The cell size.
        h: f64,
    },
    /// The box is empty: the surface has no vertices.
    #[error("the surface is empty: it has no vertices")]
    NoVertices,
    /// The lattice would have more than `MAX_VERTICES` vertices.
    #[error(
        "cell size {h:.4e} needs {count:.3e} lattice vertices over a box of {:.4e} x {:.4e} x {:.4e}; at most {MAX_VERTICES} (use a larger size)",
        extent[0],
        extent[1],
        extent[2]
    )]
    TooMany {
        /// The cell size.
        h: f64,
        /// The lattice vertices it needs.
        count: f64,
        /// The box's extent.
        extent: [f64; 3],
    },
}

/// The BCC lattice over a box; see the module docs.
#[derive(Clone, Debug)]
pub struct Lattice {
    /// Position of doubled coordinate `(0, 0, 0)`.
    pub origin: DVec3,
    /// Cell size: the edge of a cube, the length of a long edge.
    pub h: f64,
    /// Cubes per axis: corners `0..=n`, centres `0..n` per axis.
    pub n: [u32; 3],
}

/// Short-edge offsets (doubled coordinates) from a vertex to the 8 vertices of the other kind.
pub const SHORT: [[i32; 3]; 8] = [[-1, -1, -1], [1, -1, -1], [-1, 1, -1], [1, 1, -1], [-1, -1, 1], [1, -1, 1], [-1, 1, 1], [1, 1, 1]];

/// Long-edge offsets (doubled coordinates) to the 6 vertices of the same kind.
pub const LONG: [[i32; 3]; 6] = [[-2, 0, 0], [2, 0, 0], [0, -2, 0], [0, 2, 0], [0, 0, -2], [0, 0, 2]];

impl Lattice {
    /// The lattice of cell size `h` covering `bbox` with a margin.
    ///
    /// # Errors
    /// [`LatticeError`]: `h` is not positive and finite, the box is empty, or the lattice would
    /// have more than `MAX_VERTICES` vertices.
    pub fn covering(bbox: &Aabb, h: f64) -> Result<Lattice, LatticeError> {
        // an empty surface first: its default size is no number either
        if bbox.is_empty() {
            return Err(LatticeError::NoVertices);
        }
        if !(h.is_finite() && h > 0.0) {
            return Err(LatticeError::NotASize { h });
        }
        let origin = bbox.min - DVec3::new(1.0 + PHI[0], 1.0 + PHI[1], 1.0 + PHI[2]) * h;
        let e = bbox.max - origin;
        let n = [e.x, e.y, e.z].map(|x| (x / h).ceil() + 2.0);
        let count = (n[0] + 1.0) * (n[1] + 1.0) * (n[2] + 1.0) + n[0] * n[1] * n[2];
        if !count.is_finite() || count > MAX_VERTICES as f64 {
            return Err(LatticeError::TooMany { h, count, extent: bbox.extent().to_array() });
        }
        Ok(Lattice { origin, h, n: n.map(|x| x as u32) })
    }

    /// Number of cube corners.
    pub fn num_corners(&self) -> usize {
        let [a, b, c] = self.n.map(|x| x as usize + 1);
        a * b * c
    }

    /// Number of cube centres.
    pub fn num_centres(&self) -> usize {
        let [a, b, c] = self.n.map(|x| x as usize);
        a * b * c
    }

    /// Number of lattice vertices.
    pub fn num_vertices(&self) -> usize {
        self.num_corners() + self.num_centres()
    }

    /// Doubled coordinates of vertex `v`.
    #[inline]
    pub fn coords(&self, v: u32) -> [i32; 3] {
        let v = v as usize;
        let nc = self.num_corners();
        if v < nc {
            let [a, b, _] = self.n.map(|x| x as usize + 1);
            let (x, y, z) = (v % a, (v / a) % b, v / (a * b));
            [2 * x as i32, 2 * y as i32, 2 * z as i32]
        } else {
            let v = v - nc;
            let [a, b, _] = self.n.map(|x| x as usize);
            let (x, y, z) = (v % a, (v / a) % b, v / (a * b));
            [2 * x as i32 + 1, 2 * y as i32 + 1, 2 * z as i32 + 1]
        }
    }

    /// Whether vertex `v`'s star of background tets stops at the lattice's box: a corner on
    /// the box's faces, or the centre of a cube at them (doubled coordinates 0, 1, 2n - 1,
    /// 2n on some axis).
    pub fn on_outer_layer(&self, v: u32) -> bool {
        let c = self.coords(v);
        (0..3).any(|k| c[k] <= 1 || c[k] + 1 >= 2 * self.n[k] as i32)
    }

    /// The vertex at doubled coordinates `c`, if it is in the lattice.
    #[inline]
    pub fn id(&self, c: [i32; 3]) -> Option<u32> {
        let odd = c[0] & 1;
        if c.iter().any(|&x| x & 1 != odd || x < 0) {
            return None;
        }
        let [x, y, z] = c.map(|x| (x >> 1) as usize);
        if odd == 0 {
            let [a, b, cc] = self.n.map(|x| x as usize + 1);
            (x < a && y < b && z < cc).then(|| (x + a * (y + b * z)) as u32)
        } else {
            let [a, b, cc] = self.n.map(|x| x as usize);
            (x < a && y < b && z < cc).then(|| (self.num_corners() + x + a * (y + b * z)) as u32)
        }
    }

    /// True for a cube centre.
    #[inline]
    pub fn is_centre(&self, v: u32) -> bool {
        v as usize >= self.num_corners()
    }

    /// Position of vertex `v`.
    #[inline]
    pub fn position(&self, v: u32) -> DVec3 {
        let [x, y, z] = self.coords(v);
        self.origin + DVec3::new(x as f64, y as f64, z as f64) * (0.5 * self.h)
    }

    /// The lattice neighbours of `v` (long edges first, then short ones), with `true` for a
    /// long edge.
    pub fn neighbours(&self, v: u32) -> impl Iterator<Item = (u32, bool)> + '_ {
        let c = self.coords(v);
        let long = LONG.iter().map(move |d| (d, true));
        let short = SHORT.iter().map(move |d| (d, false));
        long.chain(short).filter_map(move |(d, is_long)| self.id([c[0] + d[0], c[1] + d[1], c[2] + d[2]]).map(|u| (u, is_long)))
    }

    /// The 12 background tets owned by centre number `i` (`0..num_centres()`), positively
    /// oriented, in a fixed order; fewer at the lattice's high faces.
    pub fn tets_around(&self, i: usize, out: &mut Vec<[u32; 4]>) {
        let c = self.num_corners() as u32 + i as u32;
        let p = self.coords(c);
        for axis in 0..3 {
            let mut q = p;
            q[axis] += 2;
            let Some(c2) = self.id(q) else { continue };
            let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
            // the square face between the two cubes, its corners in cyclic order
            let corner = |sa: i32, sb: i32| {
                let mut r = p;
                r[axis] += 1;
                r[a] += sa;
                r[b] += sb;
                r
            };
            let ring = [corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1)];
            for k in 0..4 {
                let (r0, r1) = (ring[k], ring[(k + 1) % 4]);
                let (Some(v0), Some(v1)) = (self.id(r0), self.id(r1)) else { continue };
                let t = if orient3d_int(p, q, r0, r1).is_positive() { [c, c2, v0, v1] } else { [c, c2, v1, v0] };
                out.push(t);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quality::tetrahedron::tet_min_max_dihedral;

    #[test]
    fn an_empty_surface_is_named_before_its_size() {
        // an empty surface's default cell is no number: the emptiness is the fact to report
        assert_eq!(Lattice::covering(&Aabb::from_points(&[]), f64::INFINITY).unwrap_err(), LatticeError::NoVertices);
        assert!(matches!(Lattice::covering(&Aabb::from_points(&[DVec3::ZERO, DVec3::ONE]), f64::INFINITY), Err(LatticeError::NotASize { .. })));
    }

    #[test]
    fn numbering_round_trips() {
        let l = Lattice::covering(&Aabb::from_points(&[DVec3::ZERO, DVec3::new(1.0, 2.0, 0.5)]), 0.25).unwrap();
        for v in 0..l.num_vertices() as u32 {
            assert_eq!(l.id(l.coords(v)), Some(v));
        }
        assert_eq!(l.id([1, 2, 1]), None);
        assert_eq!(l.id([-2, 0, 0]), None);
    }

    #[test]
    fn tets_are_bcc_and_tile_the_lattice() {
        let l = Lattice::covering(&Aabb::from_points(&[DVec3::ZERO, DVec3::ONE]), 0.3).unwrap();
        let mut tets = Vec::new();
        for i in 0..l.num_centres() {
            l.tets_around(i, &mut tets);
        }
        let h3 = l.h * l.h * l.h;
        for t in &tets {
            let p = t.map(|v| l.position(v));
            let (lo, hi) = tet_min_max_dihedral(&p);
            assert!((lo - 60.0).abs() < 1e-6 && (hi - 90.0).abs() < 1e-6, "{lo} {hi}");
            let vol = crate::quality::tetrahedron::tet_volume(&p);
            assert!((vol - h3 / 12.0).abs() < 1e-9 * h3, "{vol}");
        }
        // four tets per pair of neighbouring centres
        let [a, b, c] = l.n.map(|x| x as usize);
        assert_eq!(tets.len(), 4 * ((a - 1) * b * c + a * (b - 1) * c + a * b * (c - 1)));
    }
}
