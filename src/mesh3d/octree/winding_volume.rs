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
//!   its cell's volume. The points of a row of cells (same `j`, `k`) share their `y` and `z`
//!   (hashed per row), so they lie on one segment; each is still uniform in its cell.
//! - Along a row the winding number is counted, not summed: the surface closed into a cycle
//!   by its cap (`cap.rs`; itself where it is one) has exact integers there
//!   ([`Winding::along_row`]), and
//!   the surface's own number is that less the cap's solid angle (a few triangles, one per
//!   boundary edge). A degenerate row (through an edge, in a plane) sums the surface's solid
//!   angles at each point instead. Cost: a segment query per row, so near-linear in the
//!   surface for a closed one, dirty or not.
//! - With a cap, blocks of cells no triangle of the union comes near, whose cells count one
//!   integer and where that less the cap's solid angle agrees at the block's corners and
//!   centre, clear of one half, take that side without sampling the cap at every cell (it
//!   is harmonic and smooth there).
//! - A cell wholly inside or outside counts exactly; only cells the level set crosses carry
//!   an error, each at most its volume, with variance at most a quarter of its volume
//!   squared. `error` is three standard deviations over the cells whose judgement differs
//!   from a face neighbour's (those the level set crosses, as far as the sampling sees).

use super::winding::{INSIDE, Winding};
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

/// A well-mixed 64-bit hash (SplitMix64's finaliser).
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Cells per axis of a block judged as one where no triangle is near (see the code).
const BLOCK: usize = 4;

/// How far from one half the winding number must be at a far block's nine points.
const MARGIN: f64 = 0.1;

/// The block of cell `(i, j, k)`.
fn block_of(n: usize, i: usize, j: usize, k: usize) -> usize {
    let blocks = n.div_ceil(BLOCK);
    i / BLOCK + blocks * (j / BLOCK + blocks * (k / BLOCK))
}

/// With a cap: per block of `BLOCK³` cells, the side every cell takes, where no triangle of
/// the union comes within a cell of the block and its cells count one integer `u` (constant
/// there: the block is free of the cycle), and `u` less the cap's solid angle at the block's
/// corners and centre is on one side, clear of one half (the cap's is harmonic and smooth
/// there); `None` where the cells are judged one by one.
fn far_blocks(n: usize, lo: DVec3, cell: DVec3, union: &Winding, cap: &Winding, counted: &[Result<i32, f64>]) -> Vec<Option<bool>> {
    let blocks = n.div_ceil(BLOCK);
    (0..blocks * blocks * blocks)
        .into_par_iter()
        .map(|b| {
            let (bi, bj, bk) = (b % blocks, (b / blocks) % blocks, b / (blocks * blocks));
            let c0 = [bi, bj, bk].map(|x| x * BLOCK);
            let c1 = [bi, bj, bk].map(|x| ((x + 1) * BLOCK).min(n));
            let (p0, p1) = (lo + cell * DVec3::new(c0[0] as f64, c0[1] as f64, c0[2] as f64), lo + cell * DVec3::new(c1[0] as f64, c1[1] as f64, c1[2] as f64));
            if union.bvh().any_overlapping(&crate::core::aabb::Aabb { min: p0 - cell, max: p1 + cell }) {
                return None;
            }
            let Ok(u) = counted[c0[0] + n * (c0[1] + n * c0[2])] else { return None };
            let same = (c0[2]..c1[2]).all(|k| (c0[1]..c1[1]).all(|j| (c0[0]..c1[0]).all(|i| counted[i + n * (j + n * k)] == Ok(u))));
            if !same {
                return None;
            }
            let mut side = None;
            for k in 0..9 {
                let q = if k == 8 { 0.5 * (p0 + p1) } else { DVec3::new(if k & 1 == 0 { p0.x } else { p1.x }, if k & 2 == 0 { p0.y } else { p1.y }, if k & 4 == 0 { p0.z } else { p1.z }) };
                let v = u as f64 - cap.at(q);
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
        .collect()
}

/// Salts the rows' hashes apart from the cells'.
const ROW_SALT: u64 = 0x243f_6a88_85a3_08d3;

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
    let (rows_oracle, cap) = w.closed();
    let sample = |idx: usize| {
        let (i, r) = (idx % n, idx / n);
        let h = mix(r as u64 ^ ROW_SALT);
        let jitter = DVec3::new(unit(mix(idx as u64)), unit(h), unit(mix(h)));
        lo + cell * (DVec3::new(i as f64, (r % n) as f64, (r / n) as f64) + jitter)
    };
    // per cell, the cycle's integer counted along its row, or (a degenerate row) the
    // surface's winding number summed
    let counted: Vec<Result<i32, f64>> = (0..n * n)
        .into_par_iter()
        .flat_map_iter(|r| {
            // the row's start, outside the box (winding number 0), then one point per cell
            let first = sample(n * r);
            let points: Vec<DVec3> = std::iter::once(DVec3::new(lo.x, first.y, first.z)).chain((0..n).map(|i| sample(i + n * r))).collect();
            let values: Vec<Result<i32, f64>> = match rows_oracle.along_row(&points) {
                Some(u) => u[1..].iter().map(|&u| Ok(u)).collect(),
                None => points[1..].iter().map(|&q| Err(w.at(q))).collect(),
            };
            values
        })
        .collect();
    let far_side = match cap {
        Some(cap) => far_blocks(n, lo, cell, rows_oracle, cap, &counted),
        None => Vec::new(),
    };
    let inside: Vec<bool> = (0..n * n * n)
        .into_par_iter()
        .map(|idx| {
            let (i, j, k) = (idx % n, (idx / n) % n, idx / (n * n));
            if let Some(&Some(side)) = far_side.get(block_of(n, i, j, k)) {
                return side;
            }
            match counted[idx] {
                Ok(u) => u as f64 - cap.map_or(0.0, |c| c.at(sample(idx))) > INSIDE,
                Err(v) => v > INSIDE,
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

    /// A unit cube without its top (open: counted through its cap): inside, the missing
    /// face subtends less than a hemisphere, so `w > 1/2` is the cube; outside it is below.
    #[test]
    fn an_open_cube_encloses_the_cube() {
        let mut s = cube_at(DVec3::ZERO, 1.0);
        let top: Vec<usize> = (0..s.triangles.len()).filter(|&t| s.corners(t).iter().all(|p| p.z == 1.0)).collect();
        assert_eq!(top.len(), 2);
        for &t in top.iter().rev() {
            s.triangles.remove(t);
            s.face_tags.remove(t);
        }
        let wv = winding_volume(&s, 64).unwrap();
        assert!((wv.volume - 1.0).abs() <= wv.error && wv.error < 0.02, "{wv:?}");
    }
}
