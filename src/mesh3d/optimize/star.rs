//! A movable vertex's star as smoothing and the search see it: the live tets around the
//! vertex, and the vertex's place in each, so that a tet can be judged with the vertex moved.

use crate::mesh3d::optimize::work::{Work, local};
use glam::DVec3;

/// The star of one vertex, reused across vertices.
#[derive(Default)]
pub(crate) struct Star {
    /// Its live tets (slots).
    pub tets: Vec<u32>,
    /// The vertex's place (0..4) in each of `tets`.
    at: Vec<u8>,
}

impl Star {
    /// Loads the star of `v`; false if `v` may not move or has no star.
    pub(crate) fn load(&mut self, w: &mut Work, v: u32) -> bool {
        if !w.movable(v) || !w.star(v, &mut self.tets) {
            return false;
        }
        self.at.clear();
        for &t in &self.tets {
            self.at.push(local(&w.tets[t as usize], v).unwrap_or(0) as u8);
        }
        true
    }

    /// Puts the tets in the order of `key`, ties by slot.
    pub(crate) fn order_by(&mut self, key: impl Fn(u32) -> f64) {
        let mut both: Vec<(u32, u8)> = self.tets.iter().copied().zip(self.at.iter().copied()).collect();
        both.sort_by(|a, b| key(a.0).total_cmp(&key(b.0)).then(a.0.cmp(&b.0)));
        (self.tets, self.at) = both.into_iter().unzip();
    }

    /// The number of tets.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.tets.len()
    }

    /// The vertex's place in tet `s` of the star.
    #[inline]
    pub(crate) fn at(&self, s: usize) -> usize {
        self.at[s] as usize
    }

    /// Tet `s` of the star with the vertex at `x`.
    #[inline]
    pub(crate) fn corners_at(&self, w: &Work, s: usize, x: DVec3) -> [DVec3; 4] {
        let mut p = w.corners(&w.tets[self.tets[s] as usize]);
        p[self.at[s] as usize] = x;
        p
    }

    /// A length scale: the mean distance from `x0` to the star's other vertices.
    pub(crate) fn scale(&self, w: &Work, x0: DVec3) -> f64 {
        let mut scale = 0.0;
        for s in 0..self.tets.len() {
            let p = self.corners_at(w, s, x0);
            scale += (0..4).map(|i| p[i].distance(x0)).sum::<f64>() / 3.0;
        }
        scale / self.tets.len() as f64
    }
}
