//! Axis-aligned bounding boxes.

use glam::DVec3;

/// An axis-aligned box `[min, max]`. An empty box has `min > max` on every axis.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Aabb {
    /// Lower corner.
    pub min: DVec3,
    /// Upper corner.
    pub max: DVec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Aabb::EMPTY
    }
}

impl Aabb {
    /// The empty box, neutral for [`Aabb::union`].
    pub const EMPTY: Aabb = Aabb { min: DVec3::splat(f64::INFINITY), max: DVec3::splat(f64::NEG_INFINITY) };

    /// The box of a point set (empty for no points).
    pub fn from_points<'a>(points: impl IntoIterator<Item = &'a DVec3>) -> Aabb {
        let mut b = Aabb::EMPTY;
        for p in points {
            b.grow(*p);
        }
        b
    }

    /// True if the box holds no point.
    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y && self.min.z <= self.max.z)
    }

    /// Extends the box to hold `p`.
    #[inline]
    pub fn grow(&mut self, p: DVec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    /// The smallest box holding both.
    #[inline]
    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb { min: self.min.min(o.min), max: self.max.max(o.max) }
    }

    /// True if the closed boxes share a point (exact: only comparisons).
    #[inline]
    pub fn overlaps(&self, o: &Aabb) -> bool {
        self.min.x <= o.max.x
            && o.min.x <= self.max.x
            && self.min.y <= o.max.y
            && o.min.y <= self.max.y
            && self.min.z <= o.max.z
            && o.min.z <= self.max.z
    }

    /// Edge lengths (zero for an empty box).
    pub fn extent(&self) -> DVec3 {
        if self.is_empty() { DVec3::ZERO } else { self.max - self.min }
    }

    /// Length of the diagonal: the model size that relative tolerances scale with.
    pub fn diagonal(&self) -> f64 {
        self.extent().length()
    }

    /// Centre of the box.
    pub fn center(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }

    /// `[[xmin, ymin, zmin], [xmax, ymax, zmax]]`, or `None` for an empty box.
    pub fn to_array(&self) -> Option<[[f64; 3]; 2]> {
        if self.is_empty() { None } else { Some([self.min.to_array(), self.max.to_array()]) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grow_union_overlap() {
        let a = Aabb::from_points(&[DVec3::ZERO, DVec3::ONE]);
        let b = Aabb::from_points(&[DVec3::ONE, DVec3::splat(2.0)]);
        assert!(a.overlaps(&b));
        assert_eq!(a.union(&b).diagonal(), 12f64.sqrt());
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(Aabb::EMPTY.diagonal(), 0.0);
        assert!(!a.overlaps(&Aabb::from_points(&[DVec3::splat(1.5)])));
    }
}
