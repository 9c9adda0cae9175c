//! One report for a part whose solids were meshed one by one: counts summed, extremes kept.
//!
//! Stage: after the octree mesher ran on each solid of an assembly. Input: the solids'
//! [`OctreeReport`]s in solid order. Output: one [`OctreeReport`] (seconds summed per stage
//! name, in the order they first appear).

use super::{Deviation, OctreeReport, WindingVolume};

impl OctreeReport {
    /// The report of several solids meshed one by one; see the module docs. `None` for no
    /// report.
    pub fn merged(reports: &[OctreeReport]) -> Option<OctreeReport> {
        let (first, rest) = reports.split_first()?;
        let mut out = first.clone();
        for r in rest {
            out.cell_size = out.cell_size.min(r.cell_size);
            out.lattice_vertices += r.lattice_vertices;
            if out.cells_per_level.len() < r.cells_per_level.len() {
                out.cells_per_level.resize(r.cells_per_level.len(), 0);
            }
            for (o, n) in out.cells_per_level.iter_mut().zip(&r.cells_per_level) {
                *o += n;
            }
            out.coarse_tets += r.coarse_tets;
            out.coarsened = match (out.coarsened, r.coarsened) {
                (None, None) => None,
                (a, b) => {
                    let (a, b) = (a.unwrap_or_default(), b.unwrap_or_default());
                    Some(super::coarsen::Coarsened { vertices: a.vertices + b.vertices, tets: a.tets + b.tets, passes: a.passes.max(b.passes) })
                }
            };
            out.crossing_edges += r.crossing_edges;
            out.cut_points += r.cut_points;
            out.bisected_cut_points += r.bisected_cut_points;
            out.warped_vertices += r.warped_vertices;
            out.snapped.corners += r.snapped.corners;
            out.snapped.edge_vertices += r.snapped.edge_vertices;
            out.snapped.refused += r.snapped.refused;
            out.all_zero_tets += r.all_zero_tets;
            out.tets += r.tets;
            out.nodes += r.nodes;
            out.boundary_triangles += r.boundary_triangles;
            out.dihedral = [out.dihedral[0].min(r.dihedral[0]), out.dihedral[1].max(r.dihedral[1])];
            out.volume += r.volume;
            out.input_volume += r.input_volume;
            out.input_volume_exact &= r.input_volume_exact;
            out.input_crossings = match (out.input_crossings, r.input_crossings) {
                (None, None) => None,
                (a, b) => Some(a.unwrap_or(0) + b.unwrap_or(0)),
            };
            // a sum only where every solid has one
            out.winding_volume = match (out.winding_volume, r.winding_volume) {
                (Some(a), Some(b)) => Some(WindingVolume { volume: a.volume + b.volume, error: a.error + b.error, ..a }),
                _ => None,
            };
            out.turned_outward |= r.turned_outward;
            out.reaches_box |= r.reaches_box;
            out.cell_tries.extend(r.cell_tries.iter().cloned());
            out.hausdorff_over_cell = out.hausdorff_over_cell.max(r.hausdorff_over_cell);
            out.bound_over_cell = out.bound_over_cell.max(r.bound_over_cell);
            out.deviation = merged_deviation(&out.deviation, &r.deviation);
            for (stage, s) in &r.stage_seconds {
                match out.stage_seconds.iter_mut().find(|(n, _)| n == stage) {
                    Some((_, t)) => *t += s,
                    None => out.stage_seconds.push((stage.clone(), *s)),
                }
            }
        }
        out.solids = reports.len();
        Some(out)
    }
}

/// The deviation of two solids' boundaries together: the larger distances (and seal), the
/// counts and areas summed.
fn merged_deviation(a: &Deviation, b: &Deviation) -> Deviation {
    let mut examples = a.unresolved_examples.clone();
    examples.extend(b.unresolved_examples.iter().take(super::deviation::EXAMPLES.saturating_sub(examples.len())));
    Deviation {
        mesh_to_input: a.mesh_to_input.max(b.mesh_to_input),
        input_to_mesh: a.input_to_mesh.max(b.input_to_mesh),
        hausdorff: a.hausdorff.max(b.hausdorff),
        hausdorff_at: if b.hausdorff > a.hausdorff { b.hausdorff_at } else { a.hausdorff_at },
        hausdorff_bound: a.hausdorff_bound.max(b.hausdorff_bound),
        samples: a.samples + b.samples,
        seal: a.seal.max(b.seal),
        sealed_area: a.sealed_area + b.sealed_area,
        feature_angle_deg: a.feature_angle_deg,
        feature_edges: a.feature_edges + b.feature_edges,
        unresolved_feature_edges: a.unresolved_feature_edges + b.unresolved_feature_edges,
        feature_max_distance: a.feature_max_distance.max(b.feature_max_distance),
        unresolved_examples: examples,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_add_and_extremes_keep() {
        let a = OctreeReport { tets: 10, volume: 1.0, input_volume: 1.1, dihedral: [20.0, 140.0], cells_per_level: vec![5, 1], coarse_tets: 4, solids: 1, ..OctreeReport::default() };
        let mut b = OctreeReport { tets: 7, volume: 2.0, input_volume: 2.0, dihedral: [15.0, 130.0], cells_per_level: vec![3, 2, 1], coarse_tets: 3, solids: 1, ..OctreeReport::default() };
        b.deviation.hausdorff = 0.5;
        b.stage_seconds = vec![("winding".into(), 1.0)];
        let m = OctreeReport::merged(&[a, b]).unwrap();
        assert_eq!((m.tets, m.solids), (17, 2));
        assert_eq!(m.dihedral, [15.0, 140.0]);
        assert_eq!((m.cells_per_level, m.coarse_tets), (vec![8, 3, 1], 7));
        assert!((m.volume - 3.0).abs() < 1e-12 && (m.input_volume - 3.1).abs() < 1e-12);
        assert_eq!(m.deviation.hausdorff, 0.5);
        assert_eq!(m.stage_seconds, vec![("winding".to_string(), 1.0)]);
        assert!(OctreeReport::merged(&[]).is_none());
    }

    /// The winding number's volumes add where every solid has one; one exact solid leaves
    /// the assembly without one.
    #[test]
    fn winding_volumes_add_where_every_solid_has_one() {
        let w = |v: f64, e: f64| Some(WindingVolume { volume: v, error: e, cells_per_axis: 64 });
        let r = |wv| OctreeReport { winding_volume: wv, ..OctreeReport::default() };
        let m = OctreeReport::merged(&[r(w(1.0, 0.1)), r(w(2.0, 0.2))]).unwrap();
        assert_eq!(m.winding_volume, w(3.0, 0.30000000000000004));
        assert_eq!(OctreeReport::merged(&[r(w(1.0, 0.1)), r(None)]).unwrap().winding_volume, None);
        assert_eq!(OctreeReport::merged(&[r(None), r(w(1.0, 0.1))]).unwrap().winding_volume, None);
    }
}
