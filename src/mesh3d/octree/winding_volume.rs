//! The volume a surface encloses by its winding number: the measure of `w > 1/2`, what
//! isosurface stuffing meshes. For a clean closed surface it is the divergence theorem's
//! volume; for an open one (a scan with holes) or a self-intersecting one (overlapping
//! bodies, an inverted shell) the divergence theorem's figure is not a volume (it depends on
//! the origin, or counts overlaps twice), and this is the reference a dirty input's mesh is
//! judged against.
//!
//! Stage: a reference value for reports and tests (`fepre inspect`). Input: a
//! [`TriSurface`]. Output: [`WindingVolume`].
//!
//! # Invariants
//! - Stratified sampling: the surface's box, grown by a hundredth of its diagonal, is cut
//!   into `n³` cells; each cell is judged at one point placed in it by a hash of its index
//!   (no clock, no thread count: the same figure on every run), and an inside point counts
//!   its cell's volume.
//! - Blocks of cells far from every triangle (no triangle's box within a cell of theirs) whose
//!   corners and centre agree, clear of one half, take that side without sampling: exact off a
//!   closed surface, where the winding number is constant between its sheets.
//! - A cell wholly inside or outside counts exactly; only cells the level set crosses carry
//!   an error, each at most its volume, with variance at most a quarter of its volume
//!   squared. `error` is three standard deviations over the cells whose judgement differs
//!   from a face neighbour's (those the level set crosses, as far as the sampling sees).

use super::winding::{Winding, FAR_BETA, INSIDE};
use crate::mesh::TriSurface;
use glam::DVec3;
use rayon::prelude::*;

/// The measure of `w > 1/2` and its sampling error; see the module docs.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct WindingVolume {
    /// The estimated volume.
    pub volume: f64,
    /// Three standard deviations of the estimate.
    pub error: f64,
    /// Cells per axis.
    pub cells_per_axis: usize,
}

/// Cells per axis of a block judged as one where no triangle is near (see the code).
const BLOCK: usize = 4;

/// How far from one half the winding number must be at a far block's nine points.
const MARGIN: f64 = 0.1;

/// A well-mixed 64-bit hash (SplitMix64's finaliser).
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A number in `[0, 1)` from a hash.
fn unit(h: u64) -> f64 {
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// The measure of `w > 1/2` of `surface` on `n³` cells (see the module docs); `None` for a
/// surface without triangles or with a flat box, or `n` of 0.
pub fn winding_volume(surface: &TriSurface, n: usize) -> Option<WindingVolume> {
    winding_volume_of(&Winding::new(surface), n)
}

/// [`winding_volume`] with the surface's oracle made by the caller.
pub(super) fn winding_volume_of(w: &Winding, n: usize) -> Option<WindingVolume> {
    let surface = w.surface();
    if surface.triangles.is_empty() || n == 0 {
        return None;
    }
    let bbox = surface.bbox();
    let pad = 0.01 * bbox.diagonal();
    let (lo, size) = (bbox.min - DVec3::splat(pad), bbox.max - bbox.min + DVec3::splat(2.0 * pad));
    if !(size.min_element() > 0.0) || !size.is_finite() {
        return None;
    }
    let cell = size / n as f64;
    let cell_volume = cell.x * cell.y * cell.z;
    // blocks of BLOCK³ cells: one whose box (grown by a cell) meets no triangle's box is judged
    // at its corners and centre; where all nine agree, clear of one half, every cell takes
    // that side (the winding number is constant there off a closed surface, harmonic and
    // smooth off an open one); the other blocks are judged cell by cell
    let blocks = n.div_ceil(BLOCK);
    let far_side: Vec<Option<bool>> = (0..blocks * blocks * blocks)
        .into_par_iter()
        .map(|b| {
            let (bi, bj, bk) = (b % blocks, (b / blocks) % blocks, b / (blocks * blocks));
            let c0 = DVec3::new((bi * BLOCK) as f64, (bj * BLOCK) as f64, (bk * BLOCK) as f64);
            let c1 = DVec3::new(((bi + 1) * BLOCK).min(n) as f64, ((bj + 1) * BLOCK).min(n) as f64, ((bk + 1) * BLOCK).min(n) as f64);
            let (p0, p1) = (lo + cell * c0, lo + cell * c1);
            let grown = crate::core::aabb::Aabb { min: p0 - cell, max: p1 + cell };
            if w.bvh().any_overlapping(&grown) {
                return None;
            }
            let mut side = None;
            for k in 0..9 {
                let q = if k == 8 { 0.5 * (p0 + p1) } else { DVec3::new(if k & 1 == 0 { p0.x } else { p1.x }, if k & 2 == 0 { p0.y } else { p1.y }, if k & 4 == 0 { p0.z } else { p1.z }) };
                let v = w.at(q);
                if (v - INSIDE).abs() < MARGIN {
                    return None;
                }
                match side {
                    None => side = Some(v > INSIDE),
                    Some(s) if s != (v > INSIDE) => return None,
                    _ => {}
                }
            }
            side
        })
        .collect();
    let inside: Vec<bool> = (0..n * n * n)
        .into_par_iter()
        .map(|idx| {
            let (i, j, k) = (idx % n, (idx / n) % n, idx / (n * n));
            if let Some(side) = far_side[(i / BLOCK) + blocks * ((j / BLOCK) + blocks * (k / BLOCK))] {
                return side;
            }
            let h = mix(idx as u64);
            let jitter = DVec3::new(unit(h), unit(mix(h)), unit(mix(h ^ 0x5851_f42d_4c95_7f2d)));
            let q = lo + cell * (DVec3::new(i as f64, j as f64, k as f64) + jitter);
            // farther than a cell from every triangle's box: the coarser far field, as the
            // octree mesher judges such points
            if w.bvh().any_overlapping(&crate::core::aabb::Aabb { min: q - cell, max: q + cell }) {
                w.inside(q)
            } else {
                w.at_with(q, FAR_BETA) > INSIDE
            }
        })
        .collect();
    let count = inside.iter().filter(|&&b| b).count();
    // cells judged differently from a face neighbour: where the level set passes
    let mixed = (0..n * n * n)
        .into_par_iter()
        .filter(|&idx| {
            let (i, j, k) = (idx % n, (idx / n) % n, idx / (n * n));
            let me = inside[idx];
            (i > 0 && inside[idx - 1] != me)
                || (i + 1 < n && inside[idx + 1] != me)
                || (j > 0 && inside[idx - n] != me)
                || (j + 1 < n && inside[idx + n] != me)
                || (k > 0 && inside[idx - n * n] != me)
                || (k + 1 < n && inside[idx + n * n] != me)
        })
        .count();
    Some(WindingVolume { volume: count as f64 * cell_volume, error: 3.0 * 0.5 * cell_volume * (mixed as f64).sqrt(), cells_per_axis: n })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3d::octree::tests::{cube_at, together};

    /// Two unit cubes overlapping by half: the divergence theorem counts the overlap twice
    /// (2), the winding number's volume is the union's (1.5).
    #[test]
    fn overlapping_cubes_count_once() {
        let s = together(&[cube_at(DVec3::ZERO, 1.0), cube_at(DVec3::new(0.5, 0.0, 0.0), 1.0)]);
        assert!((s.signed_volume() - 2.0).abs() < 1e-12);
        let wv = winding_volume(&s, 64).unwrap();
        assert!((wv.volume - 1.5).abs() <= wv.error && wv.error < 0.02, "{wv:?}");
        // the same figure every time
        assert_eq!(winding_volume(&s, 64), Some(wv));
        assert_eq!(winding_volume(&s, 0), None);
    }
}
