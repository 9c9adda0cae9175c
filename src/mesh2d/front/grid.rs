//! The uniform grid that finds front edges near a point in near-constant time.
//!
//! - Stage: bookkeeping of the advancing front (used by `queue` and `step`).
//! - Inputs: the domain's bounding box and a cell side (about the boundary's median edge
//!   length, grown so the cell count stays proportional to the expected element count).
//! - Output: per cell, the ids of the front edges that pass through it (in insertion order),
//!   and box queries over them.
//! - Invariants: an edge is listed in every cell its segment passes through (conservatively:
//!   a little more, never less, so that no crossing test misses an edge); queries visit cells
//!   row by row and each cell's list in order, so the order of what they return depends only
//!   on the input. Removed edges are dropped from a cell's list lazily, when a query visits it.

use glam::DVec2;

/// A uniform grid of cells, each listing front edge ids.
pub(crate) struct Grid {
    origin: DVec2,
    cell: f64,
    nx: usize,
    ny: usize,
    cells: Vec<Vec<u32>>,
}

impl Grid {
    /// A grid over the box `[lo, hi]` with cells of side about `cell`, at most `max_cells`
    /// cells (the side grows to respect it).
    pub(crate) fn new(lo: DVec2, hi: DVec2, cell: f64, max_cells: usize) -> Grid {
        let ext = (hi - lo).max(DVec2::splat(f64::MIN_POSITIVE));
        let mut cell = if cell.is_finite() && cell > 0.0 { cell } else { ext.max_element() };
        let count = |c: f64| ((ext.x / c).ceil().max(1.0), (ext.y / c).ceil().max(1.0));
        loop {
            let (nx, ny) = count(cell);
            if nx * ny <= max_cells.max(1) as f64 {
                break;
            }
            cell *= 1.5;
        }
        let (nx, ny) = count(cell);
        let (nx, ny) = (nx as usize, ny as usize);
        Grid { origin: lo, cell, nx, ny, cells: vec![Vec::new(); nx * ny] }
    }

    fn column(&self, x: f64) -> usize {
        (((x - self.origin.x) / self.cell).floor().max(0.0) as usize).min(self.nx - 1)
    }

    fn row(&self, y: f64) -> usize {
        (((y - self.origin.y) / self.cell).floor().max(0.0) as usize).min(self.ny - 1)
    }

    /// Lists edge `id` from `a` to `b` in every cell its segment passes through (with a
    /// margin of a millionth of a cell against rounding).
    pub(crate) fn insert(&mut self, id: u32, a: DVec2, b: DVec2) {
        let eps = 1e-6 * self.cell;
        let (lo, hi) = (a.min(b), a.max(b));
        let (c0, c1) = (self.column(lo.x - eps), self.column(hi.x + eps));
        for i in c0..=c1 {
            // the part of the segment within this column (the whole of it when vertical)
            let x0 = (self.origin.x + i as f64 * self.cell - eps).max(lo.x);
            let x1 = (self.origin.x + (i + 1) as f64 * self.cell + eps).min(hi.x);
            let (y0, y1) = if b.x != a.x && x0 <= x1 {
                let y_at = |x: f64| a.y + (b.y - a.y) * ((x - a.x) / (b.x - a.x)).clamp(0.0, 1.0);
                let (u, v) = (y_at(x0), y_at(x1));
                (u.min(v), u.max(v))
            } else {
                (lo.y, hi.y)
            };
            let (r0, r1) = (self.row(y0 - eps), self.row(y1 + eps));
            for j in r0..=r1 {
                self.cells[j * self.nx + i].push(id);
            }
        }
    }

    /// Calls `visit` on every edge listed in the cells that meet the box `[lo, hi]` (an edge
    /// may come more than once), dropping the ids for which `alive` is false.
    pub(crate) fn query(&mut self, lo: DVec2, hi: DVec2, alive: &[bool], mut visit: impl FnMut(u32)) {
        let (c0, c1) = (self.column(lo.x), self.column(hi.x));
        let (r0, r1) = (self.row(lo.y), self.row(hi.y));
        for j in r0..=r1 {
            for i in c0..=c1 {
                let list = &mut self.cells[j * self.nx + i];
                list.retain(|&e| alive[e as usize]);
                for &e in list.iter() {
                    visit(e);
                }
            }
        }
    }
}
