//! The FE model as VTK XML (`.vtu`) for ParaView: the elements (quadratic tets as VTK type
//! 24), then each element-face surface's faces as triangles (corners); point data: one
//! array per node set (1 on its nodes, 0 elsewhere); cell data: one array per element set and
//! per surface (1 on its cells), `region` (the solid of a tet, 0 on triangles) and
//! `cell_kind` (3 for a tet, 2 for a triangle).

use crate::fe::build::{ALL_ELEMENTS, ALL_NODES};
use crate::fe::element::face_corners_outward;
use crate::fe::FeModel;
use crate::io::vtu::{Grid, write_grid_with_data};
use crate::io::{IoError, WriteOptions};
use std::path::Path;

/// Writes `m` as a VTU with its sets.
///
/// # Errors
/// [`IoError::NotRepresentable`] where the model fails [`FeModel::validate`]; [`IoError::Write`].
pub fn write_vtu(path: &Path, m: &FeModel) -> Result<(), IoError> {
    m.validate().map_err(|e| IoError::NotRepresentable { path: path.to_path_buf(), format: "VTU", what: e.to_string() })?;
    let ne = m.element_count();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut surface_of: Vec<usize> = Vec::new();
    for (k, faces) in m.surfaces.values().enumerate() {
        for f in faces {
            let el = m.element(f.element as usize);
            triangles.push(face_corners_outward(f.face).map(|c| el[c]));
            surface_of.push(k);
        }
    }
    let cells = ne + triangles.len();
    let mut point_arrays: Vec<(String, Vec<f64>)> = Vec::new();
    for (name, set) in m.node_sets.iter().filter(|(n, _)| n.as_str() != ALL_NODES) {
        let mut v = vec![0.0; m.nodes.len()];
        set.iter().for_each(|&n| v[n as usize] = 1.0);
        point_arrays.push((name.clone(), v));
    }
    let mut cell_arrays: Vec<(String, Vec<f64>)> = Vec::new();
    for (name, set) in m.element_sets.iter().filter(|(n, _)| n.as_str() != ALL_ELEMENTS) {
        let mut v = vec![0.0; cells];
        set.iter().for_each(|&e| v[e as usize] = 1.0);
        cell_arrays.push((name.clone(), v));
    }
    for (k, name) in m.surfaces.keys().enumerate() {
        let mut v = vec![0.0; cells];
        surface_of.iter().enumerate().filter(|(_, s)| **s == k).for_each(|(i, _)| v[ne + i] = 1.0);
        cell_arrays.push((name.clone(), v));
    }
    let mut region: Vec<i32> = m.element_regions.iter().map(|r| r.0.min(i32::MAX as u32) as i32).collect();
    region.resize(cells, 0);
    let kind: Vec<i32> = (0..cells).map(|i| if i < ne { 3 } else { 2 }).collect();
    let mut grid = Grid::new(&m.nodes, &m.elements, m.kind.nodes()).with_triangles(&triangles).with_cell_ints("region", &region).with_cell_ints("cell_kind", &kind);
    for (name, v) in &point_arrays {
        grid = grid.with_point_data(name, 1, v);
    }
    for (name, v) in &cell_arrays {
        grid = grid.with_cell_data(name, 1, v);
    }
    write_grid_with_data(path, &grid, &WriteOptions::default())
}
