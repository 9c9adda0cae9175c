//! The cell chosen where no size is given: fine enough for the mesh to hold the input's volume.
//!
//! Stage: around [`mesh_octree`](super::mesh_octree), for one solid (the pipeline calls it per
//! solid of an assembly, so each solid gets its own cell). Input: the surface, the size field whose
//! smallest size on the surface is the first cell, the options, a [`Resolve`]. Output: the
//! mesh and report of the last try, its tries in [`OctreeReport::cell_tries`].
//!
//! Why: isosurface stuffing keeps one cell everywhere, and a wall thinner than the cell holds
//! no lattice vertex, so it is lost. At the mesh path's default size (the diagonal over 25)
//! the corpus' crankshaft lost 30 % of its volume, a cylinder head 10 %, and three parts held
//! no lattice vertex at all. The cell shrinks by √2 until the solid holds lattice vertices and,
//! where its input volume is exact ([`OctreeReport::input_volume_exact`]), the mesh is within
//! [`Resolve::volume_error`] of it; or until the next try would build more than
//! [`Resolve::max_lattice_vertices`] or, by the last try's count, more than
//! [`Resolve::max_tets`]: then the last mesh is kept and its tries show how far it got. (Two
//! budgets: the lattice spans the solid's box, so a thin-walled part, a drawer or a casing
//! whose walls fill a few percent of its box, builds many lattice vertices for few tets.)
//! Where the volume holds but the Hausdorff bound is above the cell (sharp edges and thin
//! fins rounded off by about a cell: featuretype, wing_fuselage), up to
//! [`Resolve::bound_tries`] finer tries follow, and the one with the smallest bound over its
//! cell is kept (a dirty input's inner faces stay as far from the boundary whatever the cell:
//! there the first is kept, and the tries stop after two in a row whose bound in model units
//! is not a tenth below the best's). An input without an exact volume (open, overlapping) has its mesh
//! volume judged by how little it changes from one cell to the next (the stuffed volume
//! converges to the winding number's), for at most [`Resolve::change_tries`] tries after the
//! first with lattice vertices inside. Counts, never clocks: the same cells on any machine.

use super::rows::is_cycle;
use super::winding::Winding;
use super::{CellTry, Lattice, OctreeError, OctreeOptions, OctreeReport, cell_size, mesh_at};
use crate::core::SizeField;
use crate::mesh::{TetMesh, TriSurface};
use std::time::Instant;

/// How the default cell is chosen; see the module docs.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Resolve {
    /// The largest relative volume error accepted.
    pub volume_error: f64,
    /// The most lattice vertices a try may build (per solid).
    pub max_lattice_vertices: u64,
    /// The most tets a try may make (per solid), estimated from the try before (its count
    /// times `2√2`, the cell being `√2` finer).
    pub max_tets: u64,
    /// Tries after the first that holds the volume, while the Hausdorff bound is above the
    /// cell (sharp features rounded off by a cell); the one with the smallest bound over its
    /// cell is kept.
    pub bound_tries: usize,
    /// Tries at most, after the first with lattice vertices inside, for an input without an
    /// exact volume (open, overlapping), whose mesh volume is judged by how little it changes
    /// from one cell to the next.
    pub change_tries: usize,
}

/// The default: within 1 % of the volume, at most 2^25 lattice vertices and 2^25 tets a
/// solid (the tets bound a solid that fills its box, as 2^23 lattice vertices alone did; the
/// lattice vertices, a thin-walled part whose box is mostly empty: an outside drawer at
/// 33.2M lattice vertices and 8.5M tets peaks at 2.1 GB),
/// four tries for the Hausdorff bound (snapped boundaries hold the volume at a coarser cell
/// than before, so the tries for the bound start coarser: featuretype.STL needs the fourth),
/// five for an inexact volume to settle.
pub const RESOLVE: Resolve = Resolve { volume_error: 0.01, max_lattice_vertices: 1 << 25, max_tets: 1 << 25, bound_tries: 4, change_tries: 5 };

/// A try for the bound whose bound is above this fraction of the best's brings it no closer.
const STALL: f64 = 0.9;

/// Tries for the bound in a row that bring it no closer stop the tries (one is not enough:
/// `pins.glb`'s hairline gaps are sealed at a sixteenth of the cell, and the second finer
/// cell closes them).
const STALLS: usize = 2;

/// Each try's cell is the last one's over this.
const STEP: f64 = std::f64::consts::SQRT_2;

impl Resolve {
    /// Whether a try is accepted: lattice vertices inside, and the exact volume within bounds
    /// or, where the input has none, the mesh's volume within bounds of the try before.
    pub fn holds(&self, t: &CellTry) -> bool {
        !t.empty
            && match (t.volume_error, t.volume_change) {
                (Some(e), _) => e <= self.volume_error,
                (None, Some(c)) => c <= self.volume_error,
                (None, None) => false,
            }
    }
}

/// [`mesh_octree`](super::mesh_octree) at the coarsest cell from `size`'s down by √2 that holds the volume; see
/// the module docs.
///
/// # Errors
/// As [`mesh_octree`](super::mesh_octree); [`OctreeError::EmptyWithin`] when no try within the budget holds a
/// lattice vertex.
pub fn mesh_octree_resolved(surface: &TriSurface, size: &dyn SizeField, opts: &OctreeOptions, r: Resolve) -> Result<(TetMesh, OctreeReport), OctreeError> {
    // the oracle and the cycle test do not depend on the cell: made once for every try
    let t = Instant::now();
    let (oracle, cycle) = rayon::join(|| Winding::new(surface), || is_cycle(surface));
    let prepared = t.elapsed().as_secs_f64();
    let bbox = surface.bbox();
    let count = |h: f64| Lattice::covering(&bbox, h).ok().map(|l| l.num_vertices());
    let mut h = cell_size(surface, size);
    let mut tries: Vec<CellTry> = Vec::new();
    // the try kept so far (its index in `tries`): the one that holds the volume with the
    // smallest bound over its cell; and the first try that holds (those after it are for
    // the bound)
    let mut best: Option<(usize, TetMesh, OctreeReport)> = None;
    let mut first_hold: Option<usize> = None;
    // the last mesh volume, and how many tries had lattice vertices inside
    let mut previous: Option<f64> = None;
    let mut inside = 0;
    // tries for the bound in a row that did not bring it closer
    let mut stalls = 0;
    loop {
        let result = mesh_at(&oracle, cycle, h, opts, prepared);
        let next = h / STEP;
        let tets = result.as_ref().map_or(0.0, |(m, _)| m.tets.len() as f64);
        let room = count(next).is_some_and(|n| n as u64 <= r.max_lattice_vertices) && tets * STEP.powi(3) <= r.max_tets as f64;
        match result {
            Ok((mesh, report)) => {
                let error = volume_error(&report);
                let change = previous.filter(|_| error.is_none()).map(|v| (report.volume / v - 1.0).abs());
                previous = Some(report.volume);
                inside += 1;
                let t = CellTry { cell: report.cell_size, lattice_vertices: report.lattice_vertices, volume_error: error, volume_change: change, bound_over_cell: report.bound_over_cell, ..CellTry::default() };
                let holds = r.holds(&t);
                // an inexact volume that does not settle: the last try stands
                let unsettled = error.is_none() && inside > r.change_tries;
                let within = t.bound_over_cell <= 1.0;
                tries.push(t);
                let k = tries.len() - 1;
                if holds {
                    first_hold.get_or_insert(k);
                }
                // a try for the bound whose bound, in model units, is not a tenth below the
                // best's: the finer cell did not bring the boundary closer (a dirty input's
                // inner walls, a soup); two in a row stop the tries
                if holds && first_hold.is_some_and(|f| f < k) && best.as_ref().is_some_and(|b| report.bound_over_cell * report.cell_size >= STALL * b.2.bound_over_cell * b.2.cell_size) {
                    stalls += 1;
                } else {
                    stalls = 0;
                }
                let stalled = stalls >= STALLS;
                if holds && best.as_ref().is_none_or(|b| report.bound_over_cell < b.2.bound_over_cell) {
                    best = Some((k, mesh, report));
                } else if best.is_none() && (!room || unsettled) {
                    // short of the volume at the budget: the last try
                    best = Some((k, mesh, report));
                }
                if best.is_some() {
                    let bound_tries = first_hold.map_or(0, |f| k - f);
                    if (holds && within) || bound_tries >= r.bound_tries || stalled || !room || unsettled {
                        let (k, mesh, mut report) = best.take().ok_or_else(|| OctreeError::Internal("no try kept".into()))?;
                        tries[k].kept = true;
                        report.cell_tries = tries;
                        super::add_winding_volume(&mut report, &oracle);
                        return Ok((mesh, report));
                    }
                }
            }
            Err(OctreeError::Empty(_)) if room => tries.push(CellTry { cell: h, lattice_vertices: count(h).unwrap_or(0), empty: true, ..CellTry::default() }),
            Err(OctreeError::Empty(_)) => return Err(OctreeError::EmptyWithin { h, budget: r.max_lattice_vertices }),
            Err(e) => return Err(e),
        }
        h = next;
    }
}

/// The relative volume error of a mesh whose input volume is exact.
pub fn volume_error(r: &OctreeReport) -> Option<f64> {
    (r.input_volume_exact && r.input_volume > 0.0).then(|| (r.volume / r.input_volume - 1.0).abs())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::size_field::UniformSize;

    /// The tries' invariants: none holds before the first that does, exactly one is kept,
    /// it holds and is the mesh's cell, and at most [`Resolve::bound_tries`] follow the first
    /// that holds, the last of them only where the kept one's bound is above its cell.
    pub(crate) fn check_tries(tries: &[CellTry], cell: f64) {
        let first = tries.iter().position(|t| RESOLVE.holds(t)).unwrap_or_else(|| panic!("none holds: {tries:?}"));
        let kept: Vec<&CellTry> = tries.iter().filter(|t| t.kept).collect();
        assert_eq!(kept.len(), 1, "{tries:?}");
        assert!(RESOLVE.holds(kept[0]) && kept[0].cell == cell, "{tries:?}");
        assert!(tries.len() - 1 - first <= RESOLVE.bound_tries, "{tries:?}");
        if kept[0].bound_over_cell <= 1.0 {
            assert!(std::ptr::eq(kept[0], tries.last().unwrap()), "{tries:?}");
        } else {
            let best = tries[first..].iter().filter(|t| RESOLVE.holds(t)).map(|t| t.bound_over_cell).fold(f64::INFINITY, f64::min);
            assert_eq!(kept[0].bound_over_cell, best, "{tries:?}");
        }
    }

    #[test]
    fn the_volume_error_counts_exact_inputs_only() {
        let r = OctreeReport { volume: 0.98, input_volume: 1.0, input_volume_exact: true, ..OctreeReport::default() };
        assert!((volume_error(&r).unwrap() - 0.02).abs() < 1e-12);
        assert_eq!(volume_error(&OctreeReport { input_volume_exact: false, ..r.clone() }), None);
        assert!(!RESOLVE.holds(&CellTry { empty: true, ..CellTry::default() }));
        assert!(RESOLVE.holds(&CellTry { volume_error: Some(0.01), ..CellTry::default() }));
        assert!(!RESOLVE.holds(&CellTry { volume_error: Some(0.0101), ..CellTry::default() }));
        assert!(!RESOLVE.holds(&CellTry::default()), "no exact volume and nothing to compare with");
        assert!(RESOLVE.holds(&CellTry { volume_change: Some(0.004), ..CellTry::default() }));
        assert!(!RESOLVE.holds(&CellTry { volume_change: Some(0.04), ..CellTry::default() }));
        assert!(!RESOLVE.holds(&CellTry { volume_error: Some(0.02), volume_change: Some(0.001), ..CellTry::default() }), "the exact volume decides");
    }

    /// A plate 0.05 thick and 1 across with a hole: nothing inside at the first cell (0.1),
    /// then finer cells until the volume holds; each try √2 finer.
    #[test]
    fn a_thin_plate_gets_a_cell_that_holds_its_volume() {
        let s = crate::mesh::shapes::plate_with_hole(16, 1.0, 0.05, 0.2);
        let (mesh, report) = mesh_octree_resolved(&s, &UniformSize(0.1), &OctreeOptions::default(), RESOLVE).unwrap();
        mesh.validate().unwrap();
        let tries = &report.cell_tries;
        assert!(tries[0].empty && (tries[0].cell - 0.1).abs() < 1e-12, "{tries:?}");
        assert!(tries.windows(2).all(|w| (w[0].cell / w[1].cell - STEP).abs() < 1e-9), "{tries:?}");
        check_tries(tries, report.cell_size);
        assert!(volume_error(&report).unwrap() <= 0.01);
        // a budget too small for any try that holds: the error names the last cell
        let small = Resolve { max_lattice_vertices: 2_000, ..RESOLVE };
        match mesh_octree_resolved(&s, &UniformSize(0.1), &OctreeOptions::default(), small) {
            Err(OctreeError::EmptyWithin { h, budget }) => assert!(budget == 2_000 && h <= 0.1 && Lattice::covering(&s.bbox(), h / STEP).unwrap().num_vertices() > 2_000),
            Ok((_, r)) => assert!(r.cell_tries.iter().all(|t| !RESOLVE.holds(t)) && r.cell_tries.last().unwrap().kept, "{:?}", r.cell_tries),
            Err(e) => panic!("{e}"),
        }
        // a budget of tets: the try after the first with tets inside would pass it, so that
        // one is the last, kept short of the volume
        let first = tries.iter().position(|t| !t.empty).unwrap();
        let few = Resolve { max_tets: 1, ..RESOLVE };
        let (_, r) = mesh_octree_resolved(&s, &UniformSize(0.1), &OctreeOptions::default(), few).unwrap();
        assert_eq!(r.cell_tries.len(), first + 1, "{:?}", r.cell_tries);
        assert!(r.cell_tries[first].kept && !RESOLVE.holds(&r.cell_tries[first]), "{:?}", r.cell_tries);
    }
}
