//! The graded background of isosurface stuffing: a 2:1 balanced octree over the lattice's
//! cubes, fine (one cube) wherever the surface crosses a cube, coarser inside, and the
//! tetrahedra that join its cells (Labelle and Shewchuk 2007, section 6, in our own
//! construction).
//!
//! Stage: between the cut points and the stencils of the octree mesher, in graded mode.
//! Input: the fine [`Lattice`], the signs after warping and the vertices' positions (a
//! vertex snapping may move counts as outside). Output: [`Octree`], which gives
//! the background tets owned by each cube, marked BCC (two fine cells: the stencils cut them)
//! or graded (a coarser cell: whole, inside).
//!
//! # Invariants
//! - A cell is an aligned block of `2^L` cubes per side (level `L`): its low cube `x` has
//!   `(x + shift) % 2^L == 0` on each axis, for the one of the 8 shifts in `{0, 1}³` that
//!   leaves the fewest cells (in the first round below). Its corners and, for `L ≥ 1`, its
//!   centre are lattice corners, so the octree's vertices are lattice vertices and keep
//!   their ids, signs and positions.
//! - A cell coarser than one cube is *deep*: no lattice vertex in it, nor the centre of a
//!   cube beside it, is outside (sign `+1`), so no background tet of a coarse cell is cut:
//!   each is kept whole, and the surface's cut points and stencils touch only tets between
//!   two one-cube cells, the uniform lattice's, where the uniform angle bounds apply
//!   unchanged. A vertex warped onto the surface (sign `0`) may be a coarse tet's, but for a
//!   coarse cell's centre, where every such tet stays positive with its dihedral angles in
//!   [`WARPED_FLOOR`] at the warped positions: in rounds, the cubes of coarse cells within
//!   one cube of a warped vertex of a tet outside it are made fine and the octree rebuilt
//!   (one rebuild at most on five corpus parts at two cells, 0–123 cubes). The warped
//!   vertices in coarse cells' tets lie on faces of the uniform lattice's tets, so the
//!   boundary is the uniform mode's. (Against keeping every cube with a warped vertex fine:
//!   0–31 % fewer tets on the corpus at diagonal / 100.) Nor is a cube deep when a lattice
//!   tet across one of its faces has all four vertices on the surface: the stencils keep
//!   such a tet only when it is inside and not a sliver, and a coarse cell would fill the
//!   gap they leave (rabbit.obj at its default cell, four boundary triangles).
//! - Balance: cells sharing a face or an edge differ by at most one level. The
//!   midpoint of a cell's edge is a vertex exactly when a finer cell touches that edge.
//! - Background tets: for every face between two cells (the finer cell's face where they
//!   differ), the fan around the segment joining the two cells' centres over the face's
//!   boundary (its corners and the midpoints that are vertices). The segment pierces the face
//!   (through its centre between equal cells, a third of the way from the finer cell's centre
//!   between unequal ones), so each such bipyramid is the two pyramids from the centres over
//!   the face; these tile every cell and meet face to face. Their shapes: the BCC tet
//!   ([60°, 90°]), the BCC tet bisected at a midpoint ([45°, 90°]), and the tets between a
//!   cell and one twice its size ([30°, 135°]): all within the uniform bounds.
//! - Deterministic: levels are computed per cube in parallel and collected in index order;
//!   balancing splits, in rounds, exactly the cells that violate it (the coarsest balanced
//!   refinement, whatever the order).

use super::lattice::Lattice;
use crate::core::predicates::{orient3d, orient3d_int};
use crate::quality::tetrahedron::tet_min_max_dihedral;
use glam::DVec3;
use rayon::prelude::*;

/// The coarsest level a cell may take (`2^MAX_LEVEL` cubes per side).
pub const MAX_LEVEL: u8 = 12;

/// The dihedral angles (degrees) a coarse cell's tet may take with a vertex warped onto the
/// surface: feature snapping's floor, well inside the uniform bounds.
pub const WARPED_FLOOR: [f64; 2] = super::snap::FLOOR;

/// The balanced octree; see the module docs.
#[derive(Clone, Debug)]
pub struct Octree {
    /// Cubes per axis (the lattice's).
    n: [u32; 3],
    /// Per cube (lattice centre order): the level of the cell containing it.
    level: Vec<u8>,
    /// The alignment: a cell of level `L` starts at cube coordinates `x` with
    /// `(x + shift) % 2^L == 0` on each axis.
    shift: [u32; 3],
}

/// A background tet and whether it is one of the uniform lattice's (both cells one cube).
pub type Background = ([u32; 4], bool);

impl Octree {
    /// The octree over `lattice` for the vertex signs `sign` (after warping) and the
    /// vertices' positions (warped or not).
    pub fn build(lattice: &Lattice, sign: &[i8], position: &(dyn Fn(u32) -> DVec3 + Sync)) -> Octree {
        let mut deep = Self::deep_cubes(lattice, sign);
        let mut tree = Self::fewest_cells(lattice.n, &deep);
        // rounds: the cubes of coarse cells beside a warped vertex that bends a tet of theirs
        // too far are made fine, until none does (the deep cubes only decrease, so this ends),
        // keeping the first round's alignment
        loop {
            let unfit = tree.unfit_cubes(lattice, sign, position);
            if unfit.is_empty() {
                return tree;
            }
            for i in unfit {
                deep[i] = false;
            }
            tree = Self::aligned(lattice.n, &deep, tree.shift);
        }
    }

    /// The balanced octree over the cubes `deep` allows, for the alignment that leaves the
    /// fewest cells (ties: the first in this order).
    fn fewest_cells(n: [u32; 3], deep: &[bool]) -> Octree {
        // (a cell of level 1 takes an aligned 2 × 2 × 2 block of deep cubes, so along the
        // fine band about half a layer of deep cubes stays fine whatever the alignment; which
        // half depends on it: 0.5–12 % fewer tets on the corpus at diagonal / 100 than the
        // lattice's own alignment, and trying the level-2 alignments too gains under 1 %)
        let trees: Vec<(usize, Octree)> = (0..8u32)
            .into_par_iter()
            .map(|k| {
                let tree = Self::aligned(n, deep, [k & 1, (k >> 1) & 1, k >> 2]);
                (tree.cells(), tree)
            })
            .collect();
        let mut best: Option<(usize, Octree)> = None;
        for (cells, tree) in trees {
            if best.as_ref().is_none_or(|b| cells < b.0) {
                best = Some((cells, tree));
            }
        }
        best.map_or_else(|| Octree { n, level: vec![0; deep.len()], shift: [0; 3] }, |b| b.1)
    }

    /// The cubes of coarse cells to make fine, in index order: for every background tet of
    /// a coarse cell with a vertex warped onto the surface that is not positive with its
    /// dihedral angles in [`WARPED_FLOOR`] at the warped positions, or whose coarse cell's
    /// centre was warped, the cubes of coarse cells whose centres lie within one cube of a
    /// warped vertex of it (at least one cube of the tet's coarse cell: the vertex is its
    /// centre, a corner of one of its cubes, or the centre of a cube beside it).
    fn unfit_cubes(&self, lattice: &Lattice, sign: &[i8], position: &(dyn Fn(u32) -> DVec3 + Sync)) -> Vec<usize> {
        let mut unfit: Vec<usize> = (0..self.level.len())
            .into_par_iter()
            .filter(|&i| self.level[i] > 0 || self.beside_coarser(i))
            .fold(
                || (Vec::new(), Vec::new()),
                |(mut background, mut unfit): (Vec<Background>, Vec<usize>), i| {
                    background.clear();
                    self.tets_of(lattice, i, &mut background);
                    for &(t, bcc) in &background {
                        if bcc || t.iter().all(|&v| sign[v as usize] == -1) {
                            continue;
                        }
                        // the first two vertices are the cells' centres; the second's cell
                        // is coarse, and so is the first's unless it is one cube
                        let coarse_centres_inside = sign[t[1] as usize] == -1 && (self.level[i] == 0 || sign[t[0] as usize] == -1);
                        let p = t.map(position);
                        let fits = coarse_centres_inside && t.iter().all(|&v| sign[v as usize] <= 0) && orient3d(p[0], p[1], p[2], p[3]).is_positive() && {
                            let (lo, hi) = tet_min_max_dihedral(&p);
                            lo >= WARPED_FLOOR[0] && hi <= WARPED_FLOOR[1]
                        };
                        if !fits {
                            for &v in t.iter().filter(|&&v| sign[v as usize] != -1) {
                                self.coarse_cubes_near(lattice.coords(v), &mut unfit);
                            }
                        }
                    }
                    (background, unfit)
                },
            )
            .map(|(_, unfit)| unfit)
            .reduce(Vec::new, |mut a, b| {
                a.extend(b);
                a
            });
        unfit.par_sort_unstable();
        unfit.dedup();
        unfit
    }

    /// Whether the one-cube cell `i` shares a face with a coarser cell (it owns the
    /// background tets across that face, not the lattice's).
    fn beside_coarser(&self, i: usize) -> bool {
        let c = cube_coords(self.n, i).map(i64::from);
        (0..6).any(|k| {
            let mut q = c;
            q[k / 2] += if k % 2 == 0 { -1 } else { 1 };
            cube_index(self.n, q).is_some_and(|j| self.level[j] > 0)
        })
    }

    /// Appends the cubes of coarse cells whose centres lie within one cube, on every axis,
    /// of the lattice vertex at doubled coordinates `p`.
    fn coarse_cubes_near(&self, p: [i32; 3], out: &mut Vec<usize>) {
        // a cube `k` has its centre at `2k + 1`: within one cube when `|2k + 1 − p| ≤ 2`
        let range = |x: i32| (x - 3).div_euclid(2)..=(x + 1).div_euclid(2);
        for z in range(p[2]) {
            for y in range(p[1]) {
                for x in range(p[0]) {
                    let c = [x, y, z].map(i64::from);
                    if (0..3).all(|a| (2 * c[a] + 1 - i64::from(p[a])).abs() <= 2) {
                        if let Some(j) = cube_index(self.n, c).filter(|&j| self.level[j] > 0) {
                            out.push(j);
                        }
                    }
                }
            }
        }
    }

    /// Per cube: whether it is deep (see the module docs), so that it may lie in a coarse
    /// cell.
    fn deep_cubes(lattice: &Lattice, sign: &[i8]) -> Vec<bool> {
        let n = lattice.n;
        let cubes = lattice.num_centres();
        // a cube is inside when its 8 corners and its centre are not outside
        let inside: Vec<bool> = (0..cubes)
            .into_par_iter()
            .map(|i| {
                let c = cube_coords(n, i);
                let centre = lattice.num_corners() as u32 + i as u32;
                sign[centre as usize] <= 0
                    && (0..8).all(|k| {
                        let q = [2 * (c[0] + (k & 1)), 2 * (c[1] + ((k >> 1) & 1)), 2 * (c[2] + (k >> 2))];
                        lattice.id(q.map(|x| x as i32)).is_some_and(|v| sign[v as usize] <= 0)
                    })
            })
            .collect();
        // deep: the cube is inside and the centres of the 6 cubes beside it are not outside
        // (every background tet of a coarse cell joins its centre, its corners, the midpoints
        // on its faces and the centres of the cells beside it), and no lattice tet across
        // one of its faces has its four vertices on the surface (the stencils keep such a
        // tet only when inside and not a sliver: a coarse cell would fill what they leave)
        let nc = lattice.num_corners();
        let on_surface = |q: [i64; 3]| lattice.id(q.map(|x| x as i32)).is_some_and(|v| sign[v as usize] == 0);
        // an edge of cube `c`'s face towards `d` with both ends on the surface
        let edge_on_surface = |c: [i64; 3], d: [i64; 3]| {
            let axis = (0..3).find(|&a| d[a] != 0).unwrap_or(0);
            let ring = face_corners(c, 1, axis, d[axis]).map(on_surface);
            (0..4).any(|k| ring[k] && ring[(k + 1) % 4])
        };
        (0..cubes)
            .into_par_iter()
            .map(|i| {
                let c = cube_coords(n, i).map(|x| x as i64);
                inside[i]
                    && neighbours26().filter(|d| d.iter().filter(|&&x| x != 0).count() == 1).all(|d| {
                        let q = [c[0] + d[0], c[1] + d[1], c[2] + d[2]];
                        cube_index(n, q).is_some_and(|j| {
                            let four_on_surface = sign[nc + i] == 0 && sign[nc + j] == 0 && edge_on_surface(c, d);
                            sign[nc + j] <= 0 && !four_on_surface
                        })
                    })
            })
            .collect()
    }

    /// The balanced octree whose cells are aligned by `shift`, coarse where `deep` allows.
    fn aligned(n: [u32; 3], deep: &[bool], shift: [u32; 3]) -> Octree {
        // per level `l` (blocks of `s = 2^l` cubes a side), a grid of blocks: block `k` has
        // its low cube at `k·s − shift` on each axis, and is allowed when it lies in the
        // lattice and its 8 halves, blocks `2k + {0, 1}` of the level below, are (level 0:
        // the cube at `k − shift`, when deep)
        let index = |m: [u32; 3], k: [u32; 3]| k[0] as usize + m[0] as usize * (k[1] as usize + m[1] as usize * k[2] as usize);
        let dims0 = [0, 1, 2].map(|a| n[a] + shift[a]);
        let grid0: Vec<bool> = (0..dims0.iter().map(|&x| x as usize).product::<usize>())
            .into_par_iter()
            .map(|i| {
                let k = cube_coords(dims0, i);
                (0..3).all(|a| k[a] >= shift[a]) && deep[cube_index(n, [0, 1, 2].map(|a| (k[a] - shift[a]) as i64)).unwrap_or(0)]
            })
            .collect();
        let mut grids: Vec<([u32; 3], Vec<bool>)> = vec![(dims0, grid0)];
        for l in 1..=MAX_LEVEL {
            let s = 1u32 << l;
            if n.iter().any(|&x| x < s) {
                break;
            }
            let (below_dims, below) = &grids[grids.len() - 1];
            let dims = [0, 1, 2].map(|a| (n[a] + shift[a]) / s + 1);
            let grid: Vec<bool> = (0..dims.iter().map(|&x| x as usize).product::<usize>())
                .into_par_iter()
                .map(|i| {
                    let k = cube_coords(dims, i);
                    let inside = (0..3).all(|a| k[a] * s >= shift[a] && k[a] * s - shift[a] + s <= n[a]);
                    inside
                        && (0..8u32).all(|d| {
                            let h = [2 * k[0] + (d & 1), 2 * k[1] + ((d >> 1) & 1), 2 * k[2] + (d >> 2)];
                            (0..3).all(|a| h[a] < below_dims[a]) && below[index(*below_dims, h)]
                        })
                })
                .collect();
            if !grid.contains(&true) {
                break;
            }
            grids.push((dims, grid));
        }
        // a cube's level: the coarsest whose block holding it is allowed (a block is allowed
        // only where its halves are, so the levels allowed are 1 up to some level)
        let level: Vec<u8> = (0..deep.len())
            .into_par_iter()
            .map(|i| {
                let c = cube_coords(n, i);
                let mut lv = 0u8;
                for (l, (dims, grid)) in grids.iter().enumerate().skip(1) {
                    let k = [0, 1, 2].map(|a| (c[a] + shift[a]) >> l);
                    if !grid[index(*dims, k)] {
                        break;
                    }
                    lv = l as u8;
                }
                lv
            })
            .collect();
        let mut tree = Octree { n, level, shift };
        tree.balance();
        tree
    }

    /// Splits cells that have a neighbour across a face or an edge two or more levels finer,
    /// in rounds, until none has. (Cells meeting at a corner only share no face or edge of a
    /// background tet, so they need no balance.)
    fn balance(&mut self) {
        loop {
            let n = self.n;
            let level = &self.level;
            // the origins of the cells to split this round: a cell of level 2 or more with a
            // cube two levels finer across a face or an edge (the shell of cubes around the
            // cell, less its 8 corner cubes, which touch it at a corner only)
            let mut split: Vec<usize> = (0..level.len())
                .into_par_iter()
                .filter_map(|i| {
                    let l = level[i];
                    if l < 2 || self.origin(i).1 != i {
                        return None;
                    }
                    let o = cube_coords(n, i).map(|x| x as i64);
                    let s = 1i64 << l;
                    let finer = |d: [i64; 3]| {
                        let out = d.iter().filter(|&&x| x < 0 || x >= s).count();
                        (out == 1 || out == 2) && cube_index(n, [o[0] + d[0], o[1] + d[1], o[2] + d[2]]).is_some_and(|j| level[j] + 1 < l)
                    };
                    // where y and z are inside the cell only x = -1 and x = s are outside it
                    let inside = |x: i64| (0..s).contains(&x);
                    (-1..=s)
                        .any(|z| {
                            (-1..=s).any(|y| {
                                if inside(y) && inside(z) {
                                    finer([-1, y, z]) || finer([s, y, z])
                                } else {
                                    (-1..=s).any(|x| finer([x, y, z]))
                                }
                            })
                        })
                        .then_some(i)
                })
                .collect();
            if split.is_empty() {
                return;
            }
            split.par_sort_unstable();
            split.dedup();
            for o in split {
                let l = self.level[o];
                let s = 1u32 << l;
                let c = cube_coords(self.n, o);
                for z in 0..s {
                    for y in 0..s {
                        for x in 0..s {
                            let q = [c[0] + x, c[1] + y, c[2] + z].map(|v| v as i64);
                            if let Some(j) = cube_index(self.n, q) {
                                self.level[j] = l - 1;
                            }
                        }
                    }
                }
            }
        }
    }

    /// The cell holding cube `i`: its low cube's coordinates and its index.
    #[inline]
    fn origin(&self, i: usize) -> ([u32; 3], usize) {
        let l = self.level[i];
        if l == 0 {
            return (cube_coords(self.n, i), i);
        }
        let c = cube_coords(self.n, i);
        // a coarse cell lies in the lattice, so its low cube's coordinates are not negative
        let mask = (1u32 << l) - 1;
        let o = [0, 1, 2].map(|a| c[a].saturating_sub((c[a] + self.shift[a]) & mask));
        let [a, b] = [self.n[0] as usize, self.n[1] as usize];
        (o, o[0] as usize + a * (o[1] as usize + b * o[2] as usize))
    }

    /// Number of cells.
    fn cells(&self) -> usize {
        self.cells_per_level().iter().sum()
    }

    /// Number of cells per level, finest first.
    pub fn cells_per_level(&self) -> Vec<usize> {
        let mut out = (0..self.level.len())
            .into_par_iter()
            .filter(|&i| self.origin(i).1 == i)
            .fold(
                || vec![0usize; MAX_LEVEL as usize + 1],
                |mut acc, i| {
                    acc[self.level[i] as usize] += 1;
                    acc
                },
            )
            .reduce(|| vec![0usize; MAX_LEVEL as usize + 1], |a, b| a.iter().zip(&b).map(|(x, y)| x + y).collect());
        while out.len() > 1 && out.last() == Some(&0) {
            out.pop();
        }
        out
    }

    /// Whether the lattice corner at doubled coordinates `p` is a corner of some cell.
    fn is_vertex(&self, p: [i64; 3]) -> bool {
        let q = p.map(|x| x / 2);
        (0..8).any(|k| {
            let c = [q[0] - (k & 1), q[1] - ((k >> 1) & 1), q[2] - (k >> 2)];
            let Some(j) = cube_index(self.n, c) else { return false };
            let (o, _) = self.origin(j);
            let s = 1i64 << self.level[j];
            (0..3).all(|a| q[a] == o[a] as i64 || q[a] == o[a] as i64 + s)
        })
    }

    /// Appends the background tets owned by the cell whose low cube is `i` (nothing when
    /// `i` is not a cell's low cube): one fan per face shared with an equal cell in `+x`,
    /// `+y`, `+z`, or with a coarser cell on any side. Positively oriented at the lattice
    /// positions; the first two vertices are the two cells' centres (this cell's first).
    pub fn tets_of(&self, lattice: &Lattice, i: usize, out: &mut Vec<Background>) {
        let (o, oi) = self.origin(i);
        if oi != i {
            return;
        }
        let l = self.level[i];
        let s = 1i64 << l;
        let o = o.map(|x| x as i64);
        let centre = |o: [i64; 3], s: i64| o.map(|x| 2 * x + s);
        let c = centre(o, s);
        for axis in 0..3 {
            for dir in [1i64, -1] {
                let mut probe = o;
                probe[axis] += if dir > 0 { s } else { -1 };
                let Some(j) = cube_index(self.n, probe) else { continue };
                let lj = self.level[j];
                let same = lj == l;
                if !(same && dir > 0 || lj == l + 1) {
                    continue;
                }
                let (oj, _) = self.origin(j);
                let c2 = centre(oj.map(|x| x as i64), 1i64 << lj);
                // the face's ring: corners and the midpoints that are vertices
                let corners = face_corners(o, s, axis, dir);
                let mut ring = Vec::with_capacity(8);
                for k in 0..4 {
                    let (p, q) = (corners[k], corners[(k + 1) % 4]);
                    ring.push(p);
                    if l >= 1 {
                        let m = [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2];
                        if self.is_vertex(m) {
                            ring.push(m);
                        }
                    }
                }
                let bcc = l == 0 && same;
                let id = |p: [i64; 3]| lattice.id(p.map(|x| x as i32));
                let (Some(vc), Some(vc2)) = (id(c), id(c2)) else { continue };
                let (pc, pc2) = (c.map(|x| x as i32), c2.map(|x| x as i32));
                for k in 0..ring.len() {
                    let (r0, r1) = (ring[k], ring[(k + 1) % ring.len()]);
                    let (Some(v0), Some(v1)) = (id(r0), id(r1)) else { continue };
                    let (p0, p1) = (r0.map(|x| x as i32), r1.map(|x| x as i32));
                    let t = if orient3d_int(pc, pc2, p0, p1).is_positive() { [vc, vc2, v0, v1] } else { [vc, vc2, v1, v0] };
                    out.push((t, bcc));
                }
            }
        }
    }
}

/// The corners, in doubled coordinates and in order around it, of the face towards `dir`
/// (`+1` or `-1`) along `axis` of the cell of `s` cubes a side whose low cube is at `o`.
fn face_corners(o: [i64; 3], s: i64, axis: usize, dir: i64) -> [[i64; 3]; 4] {
    let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
    let at = |ua: i64, ub: i64| {
        let mut r = [0i64; 3];
        r[axis] = 2 * (o[axis] + if dir > 0 { s } else { 0 });
        r[a] = 2 * o[a] + ua;
        r[b] = 2 * o[b] + ub;
        r
    };
    let e = 2 * s;
    [at(0, 0), at(e, 0), at(e, e), at(0, e)]
}

/// Coordinates of cube `i` (lattice centre order, `x` fastest).
fn cube_coords(n: [u32; 3], i: usize) -> [u32; 3] {
    let (a, b) = (n[0] as usize, n[1] as usize);
    [(i % a) as u32, ((i / a) % b) as u32, (i / (a * b)) as u32]
}

/// The index of the cube at `c`, if it is in the lattice.
fn cube_index(n: [u32; 3], c: [i64; 3]) -> Option<usize> {
    if c.iter().zip(n).any(|(&x, m)| x < 0 || x >= m as i64) {
        return None;
    }
    let [a, b] = [n[0] as usize, n[1] as usize];
    Some(c[0] as usize + a * (c[1] as usize + b * c[2] as usize))
}

/// The 26 offsets to the cubes sharing a face, an edge or a corner.
fn neighbours26() -> impl Iterator<Item = [i64; 3]> {
    (0..27).filter(|&k| k != 13).map(|k| [k % 3 - 1, (k / 3) % 3 - 1, k / 9 - 1])
}

/// The 18 offsets to the cubes sharing a face or an edge (the tests' check of balance).
#[cfg(test)]
fn neighbours18() -> impl Iterator<Item = [i64; 3]> {
    neighbours26().filter(|d| d.iter().filter(|&&x| x != 0).count() < 3)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::Aabb;
    use crate::quality::tetrahedron::{tet_min_max_dihedral, tet_volume};
    use glam::DVec3;

    /// Signs of a ball of radius `r` around the box's centre on the lattice (no cuts).
    fn ball(l: &Lattice, r: f64) -> Vec<i8> {
        let mid = l.origin + DVec3::new(l.n[0] as f64, l.n[1] as f64, l.n[2] as f64) * (0.5 * l.h);
        (0..l.num_vertices() as u32).map(|v| if (l.position(v) - mid).length() < r { -1 } else { 1 }).collect()
    }

    fn lattice(size: f64, h: f64) -> Lattice {
        Lattice::covering(&Aabb::from_points(&[DVec3::ZERO, DVec3::splat(size)]), h).unwrap()
    }

    #[test]
    fn balanced_and_deep() {
        let l = lattice(1.0, 1.0 / 64.0);
        let sign = ball(&l, 0.5);
        let t = Octree::build(&l, &sign, &|v| l.position(v));
        let levels = t.cells_per_level();
        assert!(levels.len() >= 4, "{levels:?}");
        // inside, the cells one cube wide are a band along the surface: under a sixth
        let inside = |i: usize| sign[l.num_corners() + i] == -1;
        let fine_inside = (0..t.level.len()).filter(|&i| inside(i) && t.level[i] == 0).count();
        let all_inside = (0..t.level.len()).filter(|&i| inside(i)).count();
        assert!(6 * fine_inside < all_inside, "{fine_inside} of {all_inside}");
        for i in 0..t.level.len() {
            let c = cube_coords(t.n, i).map(|x| x as i64);
            for d in neighbours18() {
                if let Some(j) = cube_index(t.n, [c[0] + d[0], c[1] + d[1], c[2] + d[2]]) {
                    assert!(t.level[i] <= t.level[j] + 1, "{i} {j}");
                }
            }
            if t.level[i] > 0 {
                // no lattice vertex of a coarse cell is outside, nor the centre of a cube
                // beside it
                assert!(sign[l.num_corners() + i] <= 0);
                for d in neighbours26().filter(|d| d.iter().filter(|&&x| x != 0).count() == 1) {
                    let j = cube_index(t.n, [c[0] + d[0], c[1] + d[1], c[2] + d[2]]).unwrap();
                    assert!(sign[l.num_corners() + j] <= 0);
                }
            }
        }
    }

    /// A lattice tet of four vertices on the surface keeps both its cubes fine (the stencils
    /// may leave it out), and the cubes around it may still be coarse.
    #[test]
    fn a_tet_of_four_surface_vertices_keeps_its_cubes_fine() {
        let l = lattice(1.0, 1.0 / 24.0);
        let mut sign = ball(&l, 0.45);
        // two cubes beside each other at the middle, x and x + 1, and the edge of their
        // shared face from its low corner along y
        let k = l.n.map(|x| x / 2);
        let cube = |c: [u32; 3]| c[0] as usize + l.n[0] as usize * (c[1] as usize + l.n[1] as usize * c[2] as usize);
        let (a, b) = (cube(k), cube([k[0] + 1, k[1], k[2]]));
        let nc = l.num_corners();
        let before = Octree::deep_cubes(&l, &sign);
        assert!(before[a] && before[b]);
        let corner = |c: [u32; 3]| l.id(c.map(|x| 2 * x as i32)).unwrap() as usize;
        for v in [nc + a, nc + b, corner([k[0] + 1, k[1], k[2]]), corner([k[0] + 1, k[1] + 1, k[2]])] {
            sign[v] = 0;
        }
        let after = Octree::deep_cubes(&l, &sign);
        assert!(!after[a] && !after[b]);
        // a cube beside them with one of those vertices as a corner, and `a`'s centre beside
        // it, makes no such tet with them: it stays deep
        assert!(after[cube([k[0], k[1] - 1, k[2]])]);
        // three of the four on the surface make no such tet: both stay deep
        sign[corner([k[0] + 1, k[1] + 1, k[2]])] = -1;
        let three = Octree::deep_cubes(&l, &sign);
        assert!(three[a] && three[b]);
    }

    /// Vertices warped onto the surface join coarse cells where the tets at them stay positive
    /// and within the warped floor, and only there: a ball whose vertices within `reach` of
    /// the sphere are warped radially onto it (`reach` a third of a cube's diagonal: some of
    /// the moves bend the tets too far).
    #[test]
    fn warped_vertices_join_coarse_cells_only_within_the_floor() {
        let l = lattice(1.0, 1.0 / 40.0);
        let mid = l.origin + DVec3::new(l.n[0] as f64, l.n[1] as f64, l.n[2] as f64) * (0.5 * l.h);
        let (r, reach) = (0.43, l.h * 3f64.sqrt() / 3.0);
        let mut sign = ball(&l, r);
        let mut warped = std::collections::HashMap::new();
        for v in 0..l.num_vertices() as u32 {
            let p = l.position(v);
            if sign[v as usize] == -1 && (p - mid).length() > r - reach {
                sign[v as usize] = 0;
                warped.insert(v, mid + (p - mid).normalize() * r);
            }
        }
        let position = |v: u32| warped.get(&v).copied().unwrap_or_else(|| l.position(v));
        let t = Octree::build(&l, &sign, &position);
        let mut tets = Vec::new();
        for i in 0..l.num_centres() {
            t.tets_of(&l, i, &mut tets);
        }
        let mut at_warped = 0;
        for &(tet, bcc) in &tets {
            if bcc || !tet.iter().any(|&v| sign[v as usize] == 0) {
                continue;
            }
            at_warped += 1;
            assert!(tet.iter().all(|&v| sign[v as usize] <= 0), "{tet:?}");
            let p = tet.map(position);
            assert!(orient3d(p[0], p[1], p[2], p[3]).is_positive());
            let (lo, hi) = tet_min_max_dihedral(&p);
            assert!(lo >= WARPED_FLOOR[0] && hi <= WARPED_FLOOR[1], "{lo} {hi}");
        }
        assert!(at_warped > 0);
        // without the check, some tets of coarse cells at warped vertices leave the floor
        let deep = Octree::deep_cubes(&l, &sign);
        let unchecked = Octree::aligned(l.n, &deep, t.shift);
        assert!(!unchecked.unfit_cubes(&l, &sign, &position).is_empty());
    }

    /// The background tets tile the lattice's box: positive, their volumes sum to the box's,
    /// every interior face is shared by two tets, and the shapes are the three of the module
    /// docs.
    #[test]
    fn background_tiles_the_box() {
        let l = lattice(1.0, 1.0 / 24.0);
        let sign = ball(&l, 0.45);
        let t = Octree::build(&l, &sign, &|v| l.position(v));
        assert!(t.cells_per_level().len() >= 3);
        tiles(&l, &t);
    }

    /// Every alignment gives a background that tiles the box (the ball off the lattice's
    /// centre, so the alignments differ), and the octree built keeps the fewest cells.
    #[test]
    fn every_alignment_tiles_the_box_and_the_fewest_cells_are_kept() {
        let l = lattice(1.0, 1.0 / 28.0);
        let mid = DVec3::new(0.47, 0.52, 0.55);
        let sign: Vec<i8> = (0..l.num_vertices() as u32).map(|v| if (l.position(v) - mid).length() < 0.41 { -1 } else { 1 }).collect();
        let built = Octree::build(&l, &sign, &|v| l.position(v));
        let deep = Octree::deep_cubes(&l, &sign);
        let mut counts = Vec::new();
        for k in 0..8u32 {
            let shift = [k & 1, (k >> 1) & 1, k >> 2];
            let t = Octree::aligned(l.n, &deep, shift);
            assert!(t.cells_per_level().len() >= 3, "{shift:?}");
            tiles(&l, &t);
            counts.push(t.cells());
        }
        assert_eq!(built.cells(), *counts.iter().min().unwrap());
        assert!(counts.iter().any(|&c| c != counts[0]), "{counts:?}");
    }

    fn tiles(l: &Lattice, t: &Octree) {
        let mut tets = Vec::new();
        for i in 0..l.num_centres() {
            t.tets_of(l, i, &mut tets);
        }
        let mut vol = 0.0;
        let (mut lo, mut hi) = (180.0f64, 0.0f64);
        for (tet, _) in &tets {
            let p = tet.map(|v| l.position(v));
            let v = tet_volume(&p);
            assert!(v > 0.0);
            vol += v;
            let (a, b) = tet_min_max_dihedral(&p);
            lo = lo.min(a);
            hi = hi.max(b);
        }
        assert!(lo >= 30.0 - 1e-9 && hi <= 135.0 + 1e-9, "{lo} {hi}");
        // the box less one pyramid (a sixth of a cube) over each cube face on its boundary
        let [x, y, z] = l.n.map(|v| v as f64);
        let want = (x * y * z - (x * y + y * z + z * x) / 3.0) * l.h.powi(3);
        assert!((vol - want).abs() < 1e-9 * want, "{vol} {want}");
        // conformity: every face once or twice, twice with opposite senses
        let mesh = crate::mesh::TetMesh {
            vertices: (0..l.num_vertices() as u32).map(|v| l.position(v)).collect(),
            tets: tets.iter().map(|t| t.0).collect(),
            region_tags: vec![crate::core::RegionId(1); tets.len()],
            ..Default::default()
        };
        mesh.validate().unwrap();
        // the open faces are the missing pyramids' sides (two corners on the box's boundary),
        // but for those over the box's edges, between two missing pyramids
        let faces = mesh.faces();
        let open: Vec<_> = faces.iter().filter(|f| f.neighbor.is_none()).collect();
        let [x, y, z] = l.n.map(|v| v as usize);
        assert_eq!(open.len(), 8 * (x * y + y * z + z * x) - 8 * (x + y + z));
        for f in open {
            let on = f.vertices.iter().filter(|&&v| {
                let c = l.coords(v);
                (0..3).any(|a| c[a] == 0 || c[a] == 2 * l.n[a] as i32)
            });
            assert_eq!(on.count(), 2, "{:?}", f.vertices);
        }
    }
}
