//! Density: the mesh size, attached to CAD faces, edges, points and boxes, combined into one
//! [`SizeField`] that the tessellator (edge points, face refinement) and the volume mesher
//! (presizing, refinement) consume alike.
//!
//! Every entry gives a size `h` on a set `S` (a face, an edge, a point, a box) that grows
//! with the distance `d` from it, `min(h + g·d, cap)`; the field is the smallest of them and
//! of the global size, clamped to `[min, max]`. `g` is `grading - 1` (neighbouring elements
//! differ in size by at most the grading factor) unless an entry sets a smaller growth, so the
//! field is `g`-Lipschitz: graded by construction, with no smoothing pass.
//!
//! In a job file (lengths in the job's units):
//!
//! ```toml
//! [density]
//! size = 4.5                  # global size; default: the part's diagonal / 25 for CAD parts
//! grading = 1.3               # default 1.4
//! curvature = 6               # elements per radian on curved faces and edges (default off)
//! deviation = 1e-3            # largest distance from the CAD surface, over the diagonal
//! face = [{ faces = "holes", size = 2.25 }]
//! distance = [{ faces = "end_x", size = 1, growth = 0.2, max = 6 }]
//! point = [{ at = [40, 15, 8], size = 0.5, radius = 2 }]
//! box = [{ min = [0, 0, 0], max = [10, 30, 8], size = 1 }]
//! ```

use super::catalogue::FaceCatalogue;
use super::groups::Groups;
use super::selector::SelectError;
use super::source_tree::{Source, SourceTree};
use super::values::{BoxSpec, NonNegative, Positive};
use crate::core::{Aabb, SizeField};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// The grading factor when none is given.
pub const DEFAULT_GRADING: f64 = 1.4;

/// The density of a part, as a job file gives it. Lengths are in the job's units.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
#[non_exhaustive]
pub struct Density {
    /// Global size (the size wherever no other entry asks for less).
    pub size: Option<Positive>,
    /// Smallest size anywhere.
    pub min: Option<Positive>,
    /// Largest size anywhere.
    pub max: Option<Positive>,
    /// Largest ratio of neighbouring sizes (at least 1; default [`DEFAULT_GRADING`]).
    pub grading: Option<Grading>,
    /// Largest distance of the tessellation from the CAD surface, as a fraction of the part's
    /// diagonal (in `(0, 0.1]`).
    pub deviation: Option<Fraction>,
    /// Elements per radian on curved faces and edges: size `r / curvature` where the radius
    /// of curvature is `r`.
    pub curvature: Option<Positive>,
    /// Sizes on selected faces.
    #[serde(default)]
    pub face: Vec<FaceSize>,
    /// Sizes growing with the distance from selected faces.
    #[serde(default)]
    pub distance: Vec<DistanceSize>,
    /// Sizes around points.
    #[serde(default)]
    pub point: Vec<PointSize>,
    /// Sizes inside boxes.
    #[serde(default, rename = "box")]
    pub boxes: Vec<BoxSize>,
}

/// A grading factor, at least 1.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "f64")]
pub struct Grading(pub f64);

impl TryFrom<f64> for Grading {
    type Error = String;
    fn try_from(x: f64) -> Result<Self, String> {
        if x.is_finite() && x >= 1.0 { Ok(Grading(x)) } else { Err(format!("grading {x} must be a finite number >= 1")) }
    }
}

/// A relative tolerance in `(0, 0.1]`.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "f64")]
pub struct Fraction(pub f64);

impl Fraction {
    /// `x` as a relative tolerance: `None` outside `(0, 0.1]` (the one place that range is
    /// decided, for job files and the command line alike).
    pub fn new(x: f64) -> Option<Fraction> {
        (x.is_finite() && x > 0.0 && x <= 0.1).then_some(Fraction(x))
    }
}

impl TryFrom<f64> for Fraction {
    type Error = String;
    fn try_from(x: f64) -> Result<Self, String> {
        Fraction::new(x).ok_or_else(|| format!("{x} must be in (0, 0.1] (a fraction of the part's diagonal)"))
    }
}

/// A size on the faces a selector selects.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FaceSize {
    /// The selector's name.
    pub faces: String,
    /// The size.
    pub size: Positive,
}

/// `min(size + growth · d, max)` at distance `d` from the selected faces.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DistanceSize {
    /// The selector's name.
    pub faces: String,
    /// Size on the faces.
    pub size: Positive,
    /// Growth per unit of distance (default `grading - 1`; never more than it).
    pub growth: Option<NonNegative>,
    /// The largest size this entry asks for (default none: the global size).
    pub max: Option<Positive>,
}

/// A size within `radius` of a point, growing beyond.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointSize {
    /// The point.
    pub at: [f64; 3],
    /// The size.
    pub size: Positive,
    /// Radius of the ball of that size (default 0).
    pub radius: Option<NonNegative>,
}

/// A size inside a box, growing outside.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawBoxSize")]
pub struct BoxSize {
    /// The box.
    pub region: BoxSpec,
    /// The size.
    pub size: Positive,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBoxSize {
    min: [f64; 3],
    max: [f64; 3],
    size: Positive,
}

impl TryFrom<RawBoxSize> for BoxSize {
    type Error = String;
    fn try_from(b: RawBoxSize) -> Result<Self, String> {
        Ok(BoxSize { region: BoxSpec::try_from_corners(b.min, b.max).map_err(|e| e.to_string())?, size: b.size })
    }
}

/// Why a density could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DensityError {
    /// A selector failed.
    #[error(transparent)]
    Select(#[from] SelectError),
    /// An entry is inconsistent (a box with min above max, min above max).
    #[error("{0}")]
    Invalid(String),
}

/// The size field of a [`Density`] on one part.
pub struct DensityField {
    global: f64,
    min: f64,
    max: f64,
    slope: f64,
    points: Vec<(DVec3, f64, f64)>,
    boxes: Vec<(Aabb, f64)>,
    tree: Option<SourceTree>,
    /// How many source triangles and segments the field has (for reports).
    pub sources: usize,
}

impl DensityField {
    /// The field of `density` on the part `cat`, lengths of `density` multiplied by `unit`
    /// (to the part's units); `default_size` is the global size where `density.size` is not
    /// given.
    ///
    /// # Errors
    /// A selector that fails or selects nothing, `min > max`, a box with `min > max`.
    pub fn build(density: &Density, groups: &Groups, cat: &FaceCatalogue, unit: f64, default_size: f64) -> Result<DensityField, DensityError> {
        let len = |p: Positive| p.get() * unit;
        let global = density.size.map_or(default_size, len);
        let min = density.min.map_or(0.0, len);
        let max = density.max.map_or(f64::INFINITY, len);
        if min > max {
            return Err(DensityError::Invalid(format!("density: min {} is above max {}", min / unit, max / unit)));
        }
        let slope = density.grading.map_or(DEFAULT_GRADING, |g| g.0) - 1.0;
        let mut items = Vec::new();
        let add_faces = |sel: &[crate::core::FaceId], h: f64, g: f64, cap: f64, items: &mut Vec<Source>| {
            for tri in cat.triangles_of(sel) {
                items.push(Source { tri, h, slope: g, cap });
            }
        };
        for f in &density.face {
            add_faces(groups.faces(&f.faces)?, len(f.size), slope, f64::INFINITY, &mut items);
        }
        for d in &density.distance {
            let g = d.growth.map_or(slope, |g| g.get().min(slope.max(0.0)));
            add_faces(groups.faces(&d.faces)?, len(d.size), g, d.max.map_or(f64::INFINITY, len), &mut items);
        }
        if let Some(n) = density.curvature {
            for info in &cat.faces {
                if info.min_radius.is_finite() {
                    let h = info.min_radius / n.get();
                    add_faces(&[info.id], h, slope, f64::INFINITY, &mut items);
                }
            }
            for (pts, r) in &cat.curved_edges {
                let h = r / n.get();
                for w in pts.windows(2) {
                    items.push(Source { tri: [w[0], w[1], w[1]], h, slope, cap: f64::INFINITY });
                }
            }
        }
        let points = density.point.iter().map(|p| (DVec3::from(p.at) * unit, p.radius.map_or(0.0, |r| r.get() * unit), len(p.size))).collect();
        let mut boxes = Vec::new();
        for b in &density.boxes {
            let a = b.region.aabb();
            boxes.push((Aabb { min: a.min * unit, max: a.max * unit }, len(b.size)));
        }
        let sources = items.len();
        Ok(DensityField { global, min, max, slope, points, boxes, tree: SourceTree::build(items), sources })
    }

    /// The global size (before clamping).
    pub fn global(&self) -> f64 {
        self.global
    }
}

impl SizeField for DensityField {
    fn size_at(&self, p: DVec3) -> f64 {
        let mut h = self.global;
        for &(c, r, s) in &self.points {
            h = h.min(s + self.slope * (p.distance(c) - r).max(0.0));
        }
        for (b, s) in &self.boxes {
            let d = (b.min - p).max(p - b.max).max(DVec3::ZERO).length();
            h = h.min(s + self.slope * d);
        }
        if let Some(t) = &self.tree {
            h = t.query(p, h);
        }
        h.clamp(self.min, self.max).max(f64::MIN_POSITIVE)
    }
}

/// A size field with a size per volume region on top (TetGen `.poly` region volume
/// constraints, per-solid sizes): inside region `r` the smaller of the two.
pub struct RegionSizes<'a> {
    base: &'a dyn SizeField,
    sizes: Vec<(crate::core::RegionId, f64)>,
}

impl<'a> RegionSizes<'a> {
    /// `base`, with `sizes` in their regions.
    pub fn new(base: &'a dyn SizeField, sizes: Vec<(crate::core::RegionId, f64)>) -> Self {
        RegionSizes { base, sizes }
    }
}

impl SizeField for RegionSizes<'_> {
    /// Where the region is not known (on the boundary, which the mesher cuts to this size
    /// first): the smallest of the region sizes, so that no region's tets are held back by a
    /// coarser boundary.
    fn size_at(&self, p: DVec3) -> f64 {
        self.sizes.iter().fold(self.base.size_at(p), |h, &(_, s)| h.min(s))
    }

    fn size_in(&self, p: DVec3, region: crate::core::RegionId) -> f64 {
        let h = self.base.size_in(p, region);
        self.sizes.iter().filter(|(r, _)| *r == region).fold(h, |h, &(_, s)| h.min(s))
    }
}
