//! Planar faces of a tagged triangle surface as 2D domains, and the way back to 3D.
//!
//! - Stage: input preparation for [`super::quadtree`], for CAD parts.
//! - Inputs: a [`TriSurface`] (a CAD part's tessellation: its triangles carry their B-rep
//!   face's `FaceId`, and its edges on a face's boundary are exactly the discretised CAD
//!   edges), the triangles of one face, the plane's frame where known (from the B-rep's
//!   surface) and a tag for each boundary edge (for a CAD face the B-rep edge).
//! - Output: a [`PlanarFace`]: the face's boundary as a checked [`Domain`] in the plane's
//!   coordinates, the frame to lift points back, and the surface vertex of every domain
//!   point (so a lifted mesh meets the rest of the surface exactly on the face's boundary).
//! - Invariants: the frame is right-handed with the face's outward normal (the triangles'
//!   orientation) as its third axis, so the domain is on the left of its segments (outer
//!   loops counter-clockwise, holes clockwise); every vertex of the face is within the
//!   caller's tolerance (at least `1e-6` of the face's size) of the plane, otherwise the
//!   face is refused as not planar.

use super::domain::{Domain, DomainError};
use crate::core::FaceId;
use crate::mesh::TriSurface;
use glam::{DVec2, DVec3};
use std::collections::BTreeMap;

/// An orthonormal frame of a plane: `lift(u, v) = origin + u x + v y`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneFrame {
    /// A point of the plane.
    pub origin: DVec3,
    /// First axis (unit).
    pub x: DVec3,
    /// Second axis (unit, orthogonal to `x`); `x × y` is the face's outward normal.
    pub y: DVec3,
}

impl PlaneFrame {
    /// The point of the plane at `p`.
    #[inline]
    pub fn lift(&self, p: DVec2) -> DVec3 {
        self.origin + p.x * self.x + p.y * self.y
    }

    /// The plane coordinates of `p`'s projection.
    #[inline]
    pub fn project(&self, p: DVec3) -> DVec2 {
        let d = p - self.origin;
        DVec2::new(d.dot(self.x), d.dot(self.y))
    }

    /// The unit normal `x × y`.
    pub fn normal(&self) -> DVec3 {
        self.x.cross(self.y)
    }
}

/// Why a face could not be made a domain.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
#[non_exhaustive]
pub enum FaceError {
    /// The face has no triangles.
    #[error("{0} has no triangles")]
    NoTriangles(FaceId),
    /// A vertex is off the plane.
    #[error("{face} is not planar: a vertex is {distance:e} off its plane (tolerance {tolerance:e})")]
    NotPlanar {
        /// The face.
        face: FaceId,
        /// The largest distance.
        distance: f64,
        /// The tolerance.
        tolerance: f64,
    },
    /// An edge is used twice in the same direction, or more than twice, by the face.
    #[error("{face}: edge {a} - {b} is used by {uses} of its triangles or twice the same way")]
    NonManifold {
        /// The face.
        face: FaceId,
        /// Surface vertex.
        a: u32,
        /// Surface vertex.
        b: u32,
        /// How many triangles.
        uses: usize,
    },
    /// The projected boundary is not a valid domain.
    #[error("{face}: {source}")]
    Domain {
        /// The face.
        face: FaceId,
        /// Why.
        source: DomainError,
    },
}

/// A planar face as a domain.
#[derive(Clone, Debug)]
pub struct PlanarFace {
    /// The face.
    pub face: FaceId,
    /// Its boundary in plane coordinates.
    pub domain: Domain,
    /// The plane.
    pub frame: PlaneFrame,
    /// Per domain point, its vertex in the surface.
    pub surface_vertex: Vec<u32>,
}

/// The domain of face `face` whose triangles (indices into `surface.triangles`) are
/// `triangles`. `frame` is the plane's `(origin, x axis)` where known (a B-rep plane's
/// frame; `None`: the first vertex and an axis along the first boundary edge); the normal
/// always comes from the triangles' orientation. `tag(a, b)` tags the boundary edge between
/// surface vertices `a` and `b`. `tolerance` is the distance off the plane a vertex may have
/// (absolute; at least `1e-6` of the face's size is allowed): for a tessellation, its chord
/// tolerance, since the CAD edges on a plane are only as planar as the file's curves.
///
/// # Errors
/// [`FaceError`], naming the face.
pub fn planar_face(surface: &TriSurface, face: FaceId, triangles: &[u32], frame: Option<(DVec3, DVec3)>, tolerance: f64, tag: &dyn Fn(u32, u32) -> u32) -> Result<PlanarFace, FaceError> {
    if triangles.is_empty() {
        return Err(FaceError::NoTriangles(face));
    }
    let v = &surface.vertices;
    let tri = |t: u32| surface.triangles[t as usize];
    // the outward normal, area weighted
    let mut n = DVec3::ZERO;
    for &t in triangles {
        let [a, b, c] = tri(t).map(|i| v[i as usize]);
        n += (b - a).cross(c - a);
    }
    let n = n.normalize_or_zero();
    // boundary: directed edges whose reverse the face does not use
    let mut uses: BTreeMap<(u32, u32), (usize, [u32; 2])> = BTreeMap::new();
    for &t in triangles {
        let ids = tri(t);
        for k in 0..3 {
            let (a, b) = (ids[k], ids[(k + 1) % 3]);
            let e = uses.entry((a.min(b), a.max(b))).or_insert((0, [a, b]));
            if e.0 == 1 && e.1 == [a, b] {
                return Err(FaceError::NonManifold { face, a, b, uses: 2 });
            }
            e.0 += 1;
        }
    }
    let mut edges: Vec<[u32; 2]> = Vec::new();
    for (&(a, b), &(count, dir)) in &uses {
        match count {
            1 => edges.push(dir),
            2 => {}
            c => return Err(FaceError::NonManifold { face, a, b, uses: c }),
        }
    }
    let Some(first) = edges.first().copied() else {
        return Err(FaceError::Domain { face, source: DomainError::TooSmall(0) });
    };
    let (origin, xdir) = frame.unwrap_or((v[first[0] as usize], v[first[1] as usize] - v[first[0] as usize]));
    let x = (xdir - xdir.dot(n) * n).normalize_or_zero();
    let frame = PlaneFrame { origin, x, y: n.cross(x) };
    // planarity, relative to the face's size
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for &t in triangles {
        for i in tri(t) {
            lo = lo.min(v[i as usize]);
            hi = hi.max(v[i as usize]);
        }
    }
    let tolerance = (1e-6 * (hi - lo).length()).max(tolerance);
    let mut distance = 0.0f64;
    for &t in triangles {
        for i in tri(t) {
            distance = distance.max((v[i as usize] - origin).dot(n).abs());
        }
    }
    if !(distance <= tolerance) || n == DVec3::ZERO {
        return Err(FaceError::NotPlanar { face, distance, tolerance });
    }
    let mut index: BTreeMap<u32, u32> = BTreeMap::new();
    let mut points = Vec::new();
    let mut surface_vertex = Vec::new();
    let mut segments = Vec::with_capacity(edges.len());
    let mut tags = Vec::with_capacity(edges.len());
    for &[a, b] in &edges {
        let mut id = |s: u32| {
            *index.entry(s).or_insert_with(|| {
                points.push(frame.project(v[s as usize]));
                surface_vertex.push(s);
                (points.len() - 1) as u32
            })
        };
        let (ia, ib) = (id(a), id(b));
        segments.push([ia, ib]);
        tags.push(tag(a, b));
    }
    let domain = Domain::new(points, segments, tags).map_err(|source| FaceError::Domain { face, source })?;
    Ok(PlanarFace { face, domain, frame, surface_vertex })
}
