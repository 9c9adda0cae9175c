//! Planar wires for the parts' profiles, built with truck's builder: circles (two half arcs,
//! since a truck edge joins two distinct vertices) and closed chains of lines and arcs.

use truck_modeling::{Point3, Vector3, Wire, builder};

/// A full circle of `radius` about `centre` in the plane with unit normal `normal`, running
/// counter-clockwise about it, starting at `centre + radius * x` (`x` a unit vector in the
/// plane).
pub(super) fn circle(centre: Point3, normal: Vector3, x: Vector3, radius: f64) -> Wire {
    let y = normal.cross(x);
    let a = builder::vertex(centre + radius * x);
    let b = builder::vertex(centre - radius * x);
    let first = builder::circle_arc(&a, &b, centre + radius * y);
    let second = builder::circle_arc(&b, &a, centre - radius * y);
    vec![first, second].into()
}

/// A piece of a closed profile: a straight segment to the next corner, or an arc through
/// `via` to it.
#[derive(Copy, Clone, Debug)]
pub(super) enum Segment {
    /// A line.
    Line,
    /// A circle arc through this point.
    Arc(Point3),
}

/// The closed wire through `corners`, with `segments[k]` joining corner `k` to corner `k + 1`
/// (and the last one back to the first).
pub(super) fn profile(corners: &[Point3], segments: &[Segment]) -> Wire {
    let v: Vec<_> = corners.iter().map(|&p| builder::vertex(p)).collect();
    let n = v.len();
    (0..n)
        .map(|k| match segments[k] {
            Segment::Line => builder::line(&v[k], &v[(k + 1) % n]),
            Segment::Arc(via) => builder::circle_arc(&v[k], &v[(k + 1) % n], via),
        })
        .collect::<Vec<_>>()
        .into()
}
