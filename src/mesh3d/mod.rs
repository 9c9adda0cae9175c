//! Layer 4: volume meshing. Sees points, surfaces with tags and size fields, never CAD types.

pub mod delaunay;
pub mod mesher;
pub mod octree;
pub mod optimize;
