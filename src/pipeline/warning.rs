//! Warnings as data: what a run made but would rather not have (a volume off the CAD solids',
//! tets under 1°, an octree boundary farther from the input than a cell, solids left out),
//! each with its kind, its message and, where it has one, its place.
//!
//! The library judges; every report carries its `warnings`, which the binary prints on
//! standard error (`WARNING: ` and the message) and `--json` carries as they are. A batch
//! runner, a binding or a test that calls the library gets the same warnings.

use super::plan::Interface;
use super::describe::kept_tries;
use super::summary::MeshSummary;
use crate::mesh3d::octree::{CellTry, OctreeReport, RESOLVE};
use crate::quality::worst_tet::{fmt_num, fmt_point};
use serde::Serialize;

/// What a warning is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum WarningKind {
    /// The mesh's volume is more than [`VOLUME_WARNING`] off the CAD solids'.
    VolumeOff,
    /// Tets with a dihedral angle under 1° (each at an input angle that small, or accepted by
    /// the requirement the run set).
    TetsUnder1Deg,
    /// Solids of an assembly the octree mesher left out: no lattice vertex inside.
    OctreeSolidsLeftOut,
    /// Solids of an assembly that overlap, each meshed on its own by the octree mesher.
    OctreeSolidsOverlap,
    /// A surface whose triangles face inward, meshed turned outward.
    OctreeTurnedOutward,
    /// The volume the winding number encloses reaches the lattice's box (an open surface).
    OctreeReachesBox,
    /// The default cell stopped before the volume was within the tolerance.
    OctreeCellStoppedShort,
    /// The boundary strays farther from the input than the cell size (sampled or bounded), or
    /// feature edges lie farther than a cell from it.
    OctreeBoundaryStrays,
    /// A 2D mesh whose smallest angle is under the one asked (near a smaller input angle, or
    /// a boundary kept as given).
    MinAngle2d,
    /// Faces meshed in 2D whose boundary points are not shared with their neighbours.
    FacesNotConforming,
}

/// Where a warning points.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum Place {
    /// A point of the model.
    Point([f64; 3]),
    /// A face (its tag).
    Face(crate::core::FaceId),
    /// A solid (its tag).
    Solid(u32),
}

/// A warning: its kind, its message (what the binary prints after `WARNING: `) and where it
/// points, if anywhere.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Warning {
    /// What it is about.
    pub kind: WarningKind,
    /// The text, without the `WARNING: ` the binary prints before it.
    pub message: String,
    /// Where, where it says.
    pub place: Option<Place>,
}

impl Warning {
    pub(crate) fn new(kind: WarningKind, message: String, place: Option<Place>) -> Warning {
        Warning { kind, message, place }
    }
}

impl std::fmt::Display for Warning {
    /// `WARNING: ` and the message, as the binary prints it on standard error.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "WARNING: {}", self.message)
    }
}

/// A mesh whose volume is farther than this fraction from the CAD solids' gets a warning.
pub const VOLUME_WARNING: f64 = 0.01;

/// The warnings of a meshed run: the octree mesher's first (solids left out, a boundary
/// farther than a cell from the input, ...), then the mesh's (a volume more than 1 % off the
/// CAD solids', tets under 1°).
pub fn run_warnings(m: Option<&MeshSummary>, octree: Option<&OctreeReport>, interface: Interface) -> Vec<Warning> {
    let mut out = octree_warnings(octree);
    if let Some(m) = m {
        out.extend(mesh_warnings(m, octree.is_some(), interface));
    }
    out
}

/// A volume more than [`VOLUME_WARNING`] off the CAD solids', and tets under 1° (`interface`
/// names the option that makes the latter an error), with where the worst one sits.
/// `octree`: the octree mesher made the mesh (its cells are a cause too).
pub fn mesh_warnings(m: &MeshSummary, octree: bool, interface: Interface) -> Vec<Warning> {
    let mut out = Vec::new();
    if let Some(e) = m.volume_error.filter(|e| e.abs() > VOLUME_WARNING) {
        let cause = if octree {
            "the tessellation's chords cut the curved faces, and octree cells miss what is thinner than a cell"
        } else {
            "the tessellation's chords cut the curved faces, and at this size a slender or thin part's circles have few sides"
        };
        let message = format!(
            "the mesh's volume is {:+.2}% off the CAD solids' ({cause}; give a smaller size, a curvature size or a smaller deviation); --require-volume-error F makes this an error",
            100.0 * e
        );
        out.push(Warning::new(WarningKind::VolumeOff, message, None));
    }
    if m.tets_under_1_deg == 0 {
        return out;
    }
    let at = m.worst_tet.as_ref().map(|w| {
        let face = w.nearest_face.as_ref().map(|f| format!(", near face {}{}", f.face.0, f.name.as_ref().map(|n| format!(" \"{n}\"")).unwrap_or_default())).unwrap_or_default();
        format!(" (the smallest {}° at {}{face})", fmt_num(w.min_dihedral_deg), fmt_point(w.point))
    });
    let why = if m.tets_under_1_deg_unexplained == 0 { ", each touching an input angle under 1°" } else { "" };
    let message = format!("{} tets have a dihedral angle under 1°{}{why}; {} makes this an error", m.tets_under_1_deg, at.unwrap_or_default(), interface.require_min_dihedral());
    out.push(Warning::new(WarningKind::TetsUnder1Deg, message, m.worst_tet.as_ref().map(|w| Place::Point(w.point))));
    out
}

/// The octree mesher's warnings: solids left out, solids that overlap, a surface turned
/// outward or open to the lattice's box, a default cell that stopped short of the volume, and
/// a boundary farther from the input than the cell size (where, and the first feature edge it
/// misses).
pub fn octree_warnings(o: Option<&OctreeReport>) -> Vec<Warning> {
    let Some(o) = o else { return Vec::new() };
    let mut out = Vec::new();
    if let Some(first) = o.empty_solids.first() {
        let names: Vec<String> = o.empty_solids.iter().map(|e| format!("{}{} ({:.4e})", e.solid, e.name.as_ref().map(|n| format!(" {n:?}")).unwrap_or_default(), e.volume)).collect();
        let message = format!(
            "{} solids left out, thinner than the cell size {:.4e} (no lattice vertex inside; a smaller size reaches them): {}",
            o.empty_solids.len(),
            o.cell_size,
            names.join(", ")
        );
        out.push(Warning::new(WarningKind::OctreeSolidsLeftOut, message, Some(Place::Solid(first.solid))));
    }
    if let Some(m) = &o.overlap {
        let message = format!("{m}; each solid was meshed on its own (isosurface stuffing), so the overlap is meshed in both and no contacts are listed");
        out.push(Warning::new(WarningKind::OctreeSolidsOverlap, message, None));
    }
    if o.turned_outward {
        out.push(Warning::new(WarningKind::OctreeTurnedOutward, "the surface encloses a negative volume (its triangles face inward): meshed turned outward".to_string(), None));
    }
    if o.reaches_box {
        let message = "the volume the surface's winding number encloses reaches the lattice's box: the surface does not close it (a surface model, or an open sheet), so the mesh is cut off by the box and its boundary there is not the input's";
        out.push(Warning::new(WarningKind::OctreeReachesBox, message.to_string(), None));
    }
    let resolve = RESOLVE;
    let short_tries: Vec<&CellTry> = kept_tries(o).into_iter().filter(|t| !resolve.holds(t)).collect();
    let short: Vec<String> = short_tries
        .iter()
        .map(|t| {
            let solid = t.solid.map(|s| format!("solid {s} ")).unwrap_or_default();
            let what = match (t.empty, t.volume_error, t.volume_change) {
                (true, _, _) => "no lattice vertex inside".to_string(),
                (false, Some(e), _) => format!("{:.3} % off", 100.0 * e),
                (false, None, Some(c)) => format!("its volume still changing by {:.3} % from the cell before", 100.0 * c),
                (false, None, None) => "one cell only".to_string(),
            };
            // what stopped it: the tries an inexact volume gets, or the budget
            let inside = o.cell_tries.iter().filter(|u| u.solid == t.solid && !u.empty).count();
            let why = if !t.empty && t.volume_error.is_none() && inside > resolve.change_tries {
                format!("the last of {inside} tries for a volume without an exact reference")
            } else {
                format!("the next cell would pass the budget of {} lattice vertices or {} tets a solid", resolve.max_lattice_vertices, resolve.max_tets)
            };
            format!("{solid}at {:.4e}, {what} ({why})", t.cell)
        })
        .collect();
    if !short.is_empty() {
        let message = format!("the default cell stopped before the volume was within {} %: {}; give --size for a finer cell", 100.0 * resolve.volume_error, short.join(", "));
        let place = short_tries.first().and_then(|t| t.solid).map(Place::Solid);
        out.push(Warning::new(WarningKind::OctreeCellStoppedShort, message, place));
    }
    let d = &o.deviation;
    // the bound, not only the sample: it is what the default cell is chosen by
    if o.hausdorff_over_cell > 1.0 || o.bound_over_cell > 1.0 || d.unresolved_feature_edges > 0 {
        let mut w = format!("the boundary strays {:.4e} from the input at {} (sampled), {:.3} times the cell size there", d.hausdorff, fmt_point(d.hausdorff_at), o.hausdorff_over_cell);
        w += &format!(" (at most {:.3} times)", o.bound_over_cell);
        if let Some([a, b]) = d.unresolved_examples.first() {
            w += &format!("; {} of {} feature edges are farther than a cell from it, the first from {} to {}", d.unresolved_feature_edges, d.feature_edges, fmt_point(*a), fmt_point(*b));
        }
        w += ": walls or features thinner or sharper than a cell; a smaller size follows them closer";
        if let Some(n) = o.input_crossings.filter(|&n| n > 0) {
            w += &format!(" (but {n} input triangles cross or touch others: the gaps between crossing walls may be thinner than any cell; `fepre inspect` lists them)");
        }
        out.push(Warning::new(WarningKind::OctreeBoundaryStrays, w, Some(Place::Point(d.hausdorff_at))));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::describe::cell_choice;

    /// The messages of the octree warnings, as the binary prints them.
    fn octree_lines(o: Option<&OctreeReport>) -> Vec<String> {
        octree_warnings(o).iter().map(Warning::to_string).collect()
    }

    #[test]
    fn octree_warnings_name_the_place() {
        let mut o = OctreeReport { cell_size: 1.0, hausdorff_over_cell: 0.5, ..OctreeReport::default() };
        o.deviation.hausdorff = 0.5;
        assert!(octree_lines(Some(&o)).is_empty(), "within the cell");
        assert!(octree_lines(None).is_empty());
        // the sample within the cell, its bound not: said, with the bound
        o.bound_over_cell = 1.2;
        let w = octree_lines(Some(&o));
        assert!(w.len() == 1 && w[0].contains("0.500 times the cell size there (at most 1.200 times)"), "{w:?}");
        o.deviation.hausdorff = 2.5;
        o.hausdorff_over_cell = 2.5;
        o.deviation.hausdorff_at = [1.0, 2.0, 3.0];
        o.deviation.feature_edges = 9;
        o.deviation.unresolved_feature_edges = 2;
        o.deviation.unresolved_examples = vec![[[0.0, 0.0, 0.0], [4.0, 0.0, 0.0]]];
        let w = octree_lines(Some(&o));
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(w[0].starts_with("WARNING: the boundary strays 2.5000e0 from the input at (1, 2, 3) (sampled), 2.500 times the cell size there"), "{}", w[0]);
        assert!(w[0].contains("2 of 9 feature edges are farther than a cell from it, the first from (0, 0, 0) to (4, 0, 0)"), "{}", w[0]);
        assert!(!w[0].contains("cross"), "{}", w[0]);
        let data = octree_warnings(Some(&o));
        assert_eq!((data[0].kind, data[0].place.clone()), (WarningKind::OctreeBoundaryStrays, Some(Place::Point([1.0, 2.0, 3.0]))));
        // an input whose triangles cross: said, since a smaller size may not help
        o.input_crossings = Some(12);
        let w = octree_lines(Some(&o));
        assert!(w[0].ends_with("a smaller size follows them closer (but 12 input triangles cross or touch others: the gaps between crossing walls may be thinner than any cell; `fepre inspect` lists them)"), "{}", w[0]);
    }

    #[test]
    fn octree_warnings_say_where_the_default_cell_stopped() {
        use crate::mesh3d::octree::CellTry;
        let mut o = OctreeReport { cell_size: 1.0, ..OctreeReport::default() };
        assert_eq!(cell_choice(&o), None, "a size given");
        o.turned_outward = true;
        assert_eq!(octree_lines(Some(&o)), vec!["WARNING: the surface encloses a negative volume (its triangles face inward): meshed turned outward".to_string()]);
        o.turned_outward = false;
        o.reaches_box = true;
        assert_eq!(octree_lines(Some(&o)), vec!["WARNING: the volume the surface's winding number encloses reaches the lattice's box: the surface does not close it (a surface model, or an open sheet), so the mesh is cut off by the box and its boundary there is not the input's".to_string()]);
        o.reaches_box = false;
        o.overlap = Some("a.step: solid 1 and solid 2 overlap".into());
        assert_eq!(octree_lines(Some(&o)), vec!["WARNING: a.step: solid 1 and solid 2 overlap; each solid was meshed on its own (isosurface stuffing), so the overlap is meshed in both and no contacts are listed".to_string()]);
        o.overlap = None;
        o.cell_tries = vec![CellTry { cell: 2.0, empty: true, ..CellTry::default() }, CellTry { cell: 1.0, volume_error: Some(0.004), kept: true, ..CellTry::default() }];
        assert!(octree_lines(Some(&o)).is_empty(), "the last try holds");
        assert_eq!(cell_choice(&o).unwrap(), "2 tries from 2.0000e0, kept 1.0000e0: the volume within 1 %");
        o.cell_tries[1].volume_error = Some(0.0234);
        let w = octree_lines(Some(&o));
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[0], "WARNING: the default cell stopped before the volume was within 1 %: at 1.0000e0, 2.340 % off (the next cell would pass the budget of 33554432 lattice vertices or 33554432 tets a solid); give --size for a finer cell");
        o.cell_tries[1] = CellTry { cell: 1.0, volume_change: Some(0.05), kept: true, ..CellTry::default() };
        assert!(octree_lines(Some(&o))[0].contains(": at 1.0000e0, its volume still changing by 5.000 % from the cell before (the next cell would pass the budget of"));
        // an inexact volume stopped by its tries, not the budget: said so
        let tries = o.cell_tries.clone();
        o.cell_tries = (0..7).map(|k| CellTry { cell: 1.0 / (k + 1) as f64, volume_change: (k > 0).then_some(0.05), kept: k == 6, ..CellTry::default() }).collect();
        assert!(octree_lines(Some(&o))[0].contains(": at 1.4286e-1, its volume still changing by 5.000 % from the cell before (the last of 7 tries for a volume without an exact reference); give --size"));
        o.cell_tries = tries;
        // an inexact volume that settled: said so, with the winding number's figure
        o.cell_tries[1].volume_change = Some(0.004);
        (o.volume, o.winding_volume) = (0.99, Some(crate::mesh3d::octree::WindingVolume { volume: 1.0, error: 0.001, cells_per_axis: 64 }));
        assert_eq!(cell_choice(&o).unwrap(), "2 tries from 2.0000e0, kept 1.0000e0: the volume settled within 1 % of the cell before, -1.000 % from the winding number's");
        o.cell_tries[1] = CellTry { cell: 1.0, volume_error: Some(0.0234), kept: true, ..CellTry::default() };
        // solid by solid: the last try of each
        o.cell_tries = vec![
            CellTry { solid: Some(1), cell: 2.0, volume_error: Some(0.2), ..CellTry::default() },
            CellTry { solid: Some(1), cell: 1.0, volume_error: Some(0.002), kept: true, ..CellTry::default() },
            CellTry { solid: Some(1), cell: 0.7, volume_error: Some(0.001), ..CellTry::default() },
            CellTry { solid: Some(2), cell: 2.0, empty: true, kept: true, ..CellTry::default() },
        ];
        assert!(octree_lines(Some(&o))[0].ends_with("before the volume was within 1 %: solid 2 at 2.0000e0, no lattice vertex inside (the next cell would pass the budget of 33554432 lattice vertices or 33554432 tets a solid); give --size for a finer cell"));
        assert_eq!(octree_warnings(Some(&o))[0].place, Some(Place::Solid(2)));
        assert_eq!(cell_choice(&o).unwrap(), "per solid, 4 tries from 2.0000e0, kept cells of 1.0000e0 to 2.0000e0: 1 of 2 stopped short of it (WARNING below)");
    }

    #[test]
    fn the_volume_and_the_tets_under_one_degree_are_warned_of() {
        let mut m = MeshSummary { volume_error: Some(-0.0123), ..MeshSummary::default() };
        let w = mesh_warnings(&m, false, Interface::CommandLine);
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[0].kind, WarningKind::VolumeOff);
        assert!(w[0].to_string().starts_with("WARNING: the mesh's volume is -1.23% off the CAD solids' (the tessellation's chords cut the curved faces, and at this size"), "{}", w[0]);
        m.volume_error = Some(0.009);
        assert!(mesh_warnings(&m, true, Interface::CommandLine).is_empty(), "within 1 %");
        m.tets_under_1_deg = 3;
        let w = mesh_warnings(&m, false, Interface::JobFile);
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!((w[0].kind, &w[0].message[..]), (WarningKind::TetsUnder1Deg, "3 tets have a dihedral angle under 1°, each touching an input angle under 1°; [require] min_dihedral makes this an error"));
    }
}
