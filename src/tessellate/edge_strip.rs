//! What the corner strips ([`super::corner_strips`]) ask of one edge's discretisation
//! ([`super::edge_points`]).

/// What the strips ask of one edge.
#[derive(Clone, Debug, Default)]
pub struct EdgeStrip {
    /// Curve parameters of the strips' points on the edge.
    pub params: Vec<f64>,
    /// Parameter intervals the strips cover (from a corner, or from where a strip enters the
    /// edge, to its last point on it): the size spaces only the rest.
    pub covered: Vec<(f64, f64)>,
    /// Of those, the tips: from a corner to the strip's first point, where only the chord's
    /// points go.
    pub tips: Vec<(f64, f64)>,
}
