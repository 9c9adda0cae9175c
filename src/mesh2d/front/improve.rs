//! Improvement of the front's triangles: Lawson flips and smoothing of the interior points.
//!
//! - Stage: after the front is closed, before the output checks.
//! - Inputs: points (the domain's first, never moved), counter-clockwise triangles that
//!   tile the domain, the domain's segments (never flipped).
//! - Output: the same points (interior ones moved) and as many triangles, every one still
//!   counter-clockwise; counts of flips and moves.
//! - Flips: an interior edge that is no domain segment is flipped when the opposite vertex
//!   lies strictly inside the circumcircle of a triangle (exact `incircle`) and both new
//!   triangles are positive (exact); until none is left (a constrained Delaunay
//!   triangulation of the points), with a cap proportional to the triangle count.
//! - Smoothing: each point not on the boundary, in index order, moves to the mean of its
//!   neighbours (half way if that fails); a move is kept only if every triangle around the
//!   point stays positive (exact) and the smallest angle there increases; a point whose
//!   star still has an angle under 34° then gets a pattern search (eight directions, the
//!   step halved when none improves its smallest angle).

use crate::core::predicates::{incircle, orient2d};
use crate::core::Sign;
use crate::mesh2d::stars::Stars;
use glam::DVec2;
use rustc_hash::FxHashSet;

const NONE: u32 = u32::MAX;
/// Points whose star keeps an angle under this (degrees) after the Laplacian step get the
/// pattern search.
const SEARCH_BELOW: f64 = 34.0;

/// A triangulation with neighbours, for flips.
pub(crate) struct Improve<'a> {
    pub(crate) pts: &'a mut [DVec2],
    pub(crate) tris: &'a mut [[u32; 3]],
    /// `nbr[t][k]`: the triangle across edge `k` (`tris[t][k] -> tris[t][k + 1]`), or NONE.
    nbr: Vec<[u32; 3]>,
    fixed_edges: FxHashSet<(u32, u32)>,
    /// Points `0..boundary` never move.
    boundary: usize,
}

/// The smallest angle of a triangle, degrees.
pub(crate) fn min_angle(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    let ang = |p: DVec2, q: DVec2, r: DVec2| {
        let (u, v) = (q - p, r - p);
        u.perp_dot(v).abs().atan2(u.dot(v))
    };
    ang(a, b, c).min(ang(b, c, a)).min(ang(c, a, b)).to_degrees()
}

/// The smallest angle over all triangles, degrees (NaN for none).
pub(crate) fn worst_angle(pts: &[DVec2], tris: &[[u32; 3]]) -> f64 {
    tris.iter().map(|t| min_angle(pts[t[0] as usize], pts[t[1] as usize], pts[t[2] as usize])).fold(f64::NAN, f64::min)
}

fn key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

impl<'a> Improve<'a> {
    /// Builds the neighbours; `segments` are never flipped, points `0..boundary` never move.
    pub(crate) fn new(pts: &'a mut [DVec2], tris: &'a mut [[u32; 3]], segments: &[[u32; 2]], boundary: usize) -> Improve<'a> {
        let fixed_edges = segments.iter().map(|s| key(s[0], s[1])).collect();
        let mut imp = Improve { pts, tris, nbr: Vec::new(), fixed_edges, boundary };
        imp.link();
        imp
    }

    /// Recomputes the neighbours from the triangles (sorted half-edges: deterministic).
    fn link(&mut self) {
        let mut half: Vec<((u32, u32), u32, u8)> = Vec::with_capacity(3 * self.tris.len());
        for (t, tri) in self.tris.iter().enumerate() {
            for k in 0..3 {
                half.push((key(tri[k], tri[(k + 1) % 3]), t as u32, k as u8));
            }
        }
        half.sort_unstable();
        self.nbr = vec![[NONE; 3]; self.tris.len()];
        for w in half.windows(2) {
            if w[0].0 == w[1].0 {
                self.nbr[w[0].1 as usize][w[0].2 as usize] = w[1].1;
                self.nbr[w[1].1 as usize][w[1].2 as usize] = w[0].1;
            }
        }
    }

    /// Flips until the triangulation is constrained Delaunay (see the module docs); returns
    /// the number of flips.
    pub(crate) fn flip_all(&mut self) -> usize {
        let mut stack: Vec<(u32, u8)> = Vec::with_capacity(3 * self.tris.len());
        for t in (0..self.tris.len() as u32).rev() {
            for k in (0..3).rev() {
                stack.push((t, k));
            }
        }
        let cap = 50 * self.tris.len() + 1000;
        let mut flips = 0;
        while let Some((t, k)) = stack.pop() {
            if flips >= cap {
                break;
            }
            if let Some(u) = self.flip(t, k as usize) {
                flips += 1;
                stack.extend([(t, 0), (t, 1), (u, 0), (u, 1)]);
            }
        }
        flips
    }

    /// Flips edge `k` of triangle `t` if it is not Delaunay; returns the other triangle.
    fn flip(&mut self, t: u32, k: usize) -> Option<u32> {
        let u = self.nbr[t as usize][k];
        if u == NONE {
            return None;
        }
        let tri = self.tris[t as usize];
        let (a, b, c) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
        if self.fixed_edges.contains(&key(a, b)) {
            return None;
        }
        let other = self.tris[u as usize];
        let j = (0..3).find(|&j| other[j] == b && other[(j + 1) % 3] == a)?;
        let d = other[(j + 2) % 3];
        let p = |i: u32| self.pts[i as usize];
        if incircle(p(a), p(b), p(c), p(d)) != Sign::Positive || orient2d(p(c), p(a), p(d)) != Sign::Positive || orient2d(p(d), p(b), p(c)) != Sign::Positive {
            return None;
        }
        let (n_ca, n_bc) = (self.nbr[t as usize][(k + 2) % 3], self.nbr[t as usize][(k + 1) % 3]);
        let (n_ad, n_db) = (self.nbr[u as usize][(j + 1) % 3], self.nbr[u as usize][(j + 2) % 3]);
        self.tris[t as usize] = [c, a, d];
        self.tris[u as usize] = [d, b, c];
        self.nbr[t as usize] = [n_ca, n_ad, u];
        self.nbr[u as usize] = [n_db, n_bc, t];
        self.relink(n_ad, u, t);
        self.relink(n_bc, t, u);
        Some(u)
    }

    /// In triangle `n`, the neighbour `old` becomes `new`.
    fn relink(&mut self, n: u32, old: u32, new: u32) {
        if n != NONE {
            for x in &mut self.nbr[n as usize] {
                if *x == old {
                    *x = new;
                }
            }
        }
    }

    /// One smoothing sweep over the interior points (see the module docs); returns the
    /// number of points moved.
    pub(crate) fn smooth(&mut self) -> usize {
        let n = self.pts.len();
        let stars = Stars::new(n, self.tris);
        let mut moves = 0;
        for v in self.boundary..n {
            let around = stars.of(v);
            if around.is_empty() {
                continue;
            }
            let mut mean = DVec2::ZERO;
            for &t in around {
                for &w in &self.tris[t as usize] {
                    if w as usize != v {
                        mean += self.pts[w as usize];
                    }
                }
            }
            // each neighbour of an interior point is counted twice (two triangles share it)
            mean /= (2 * around.len()) as f64;
            let old = self.pts[v];
            let before = self.star_angle(around);
            let mut moved = false;
            for target in [mean, 0.5 * (old + mean)] {
                self.pts[v] = target;
                if self.star_positive(around) && self.star_angle(around) > before {
                    moved = true;
                    break;
                }
                self.pts[v] = old;
            }
            if self.star_angle(around) < SEARCH_BELOW {
                moved |= self.search(v, around, mean);
            }
            moves += usize::from(moved);
        }
        moves
    }

    /// The optimisation-based step for a point whose worst angle is still small: a pattern
    /// search over eight directions, the step halved when none improves the smallest angle
    /// of the star; returns whether the point moved.
    fn search(&mut self, v: usize, around: &[u32], mean: DVec2) -> bool {
        let reach = around.iter().flat_map(|&t| self.tris[t as usize]).map(|w| self.pts[w as usize].distance(mean)).fold(0.0, f64::max);
        let mut step = 0.1 * reach;
        let mut best = self.star_angle(around);
        let mut moved = false;
        for _ in 0..12 {
            let here = self.pts[v];
            let mut found: Option<(f64, DVec2)> = None;
            for k in 0..8 {
                let q = here + step * DVec2::from_angle(k as f64 * std::f64::consts::FRAC_PI_4);
                self.pts[v] = q;
                if self.star_positive(around) {
                    let a = self.star_angle(around);
                    if a > found.map_or(best, |f| f.0) {
                        found = Some((a, q));
                    }
                }
            }
            match found {
                Some((a, q)) => {
                    self.pts[v] = q;
                    best = a;
                    moved = true;
                }
                None => {
                    self.pts[v] = here;
                    step *= 0.5;
                }
            }
        }
        moved
    }

    fn star_positive(&self, around: &[u32]) -> bool {
        around.iter().all(|&t| {
            let tri = self.tris[t as usize];
            orient2d(self.pts[tri[0] as usize], self.pts[tri[1] as usize], self.pts[tri[2] as usize]) == Sign::Positive
        })
    }

    fn star_angle(&self, around: &[u32]) -> f64 {
        around.iter().map(|&t| {
            let tri = self.tris[t as usize];
            min_angle(self.pts[tri[0] as usize], self.pts[tri[1] as usize], self.pts[tri[2] as usize])
        }).fold(f64::INFINITY, f64::min)
    }
}
