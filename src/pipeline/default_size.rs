//! The default-size rule: what a run does where the job gives no global size. Said here
//! once; the density field's global size, the octree's choice of cell and the 2D mesher's
//! size all come from [`default_size`].

use super::job::Method;
use crate::mesh3d::octree::{RESOLVE, Resolve};

/// Without a size, a CAD part's elements are about its diagonal over this.
pub const DEFAULT_DIVISIONS: f64 = 25.0;

/// What "no size given" means for one part.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DefaultSize {
    /// The global size, in part units.
    pub global: f64,
    /// How the octree chooses each solid's cell, from `global` down (method octree only).
    pub resolve: Option<Resolve>,
}

/// The rule for a part whose box has `diagonal`: a CAD part (`cad`) gets elements of about
/// the diagonal over [`DEFAULT_DIVISIONS`], and so does a surface mesh meshed by octree (a
/// lattice needs a size); a surface mesh meshed by Delaunay gets the diagonal itself (no size:
/// as coarse as quality allows). With the octree, each solid's cell then shrinks from the
/// global size until its mesh holds its volume ([`RESOLVE`]).
pub fn default_size(diagonal: f64, cad: bool, method: Method) -> DefaultSize {
    let octree = method == Method::Octree;
    let global = if cad || octree { diagonal / DEFAULT_DIVISIONS } else { diagonal };
    DefaultSize { global, resolve: octree.then_some(RESOLVE) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rule() {
        assert_eq!(default_size(50.0, true, Method::Delaunay).global, 2.0);
        assert_eq!(default_size(50.0, false, Method::Delaunay).global, 50.0);
        assert_eq!(default_size(50.0, false, Method::Octree).global, 2.0);
        assert!(default_size(50.0, true, Method::Delaunay).resolve.is_none());
        assert!(default_size(50.0, true, Method::Octree).resolve.is_some());
    }
}
