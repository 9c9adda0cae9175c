//! Lines that say what a result means, for the text reports: how the octree's default cell
//! was chosen, whether refinement ended or which budget stopped it.

use super::summary::MeshSummary;
use crate::mesh3d::octree::{CellTry, OctreeReport, RESOLVE};
use crate::quality::worst_tet::fmt_num;

/// The try kept for each solid (for the part where its solids were not meshed one by one).
pub(crate) fn kept_tries(o: &OctreeReport) -> Vec<&CellTry> {
    o.cell_tries.iter().filter(|t| t.kept).collect()
}

/// The line that says how the octree's default cell was chosen; `None` where a size was
/// given.
pub fn cell_choice(o: &OctreeReport) -> Option<String> {
    let first = o.cell_tries.first()?;
    let last = kept_tries(o);
    let resolve = RESOLVE;
    let held = last.iter().filter(|t| resolve.holds(t)).count();
    let why = if held == last.len() && last.iter().all(|t| t.volume_error.is_some()) {
        format!("the volume within {} %", 100.0 * resolve.volume_error)
    } else if held == last.len() {
        // no exact reference: what was checked, and where the winding number's volume stands
        let against = o.winding_volume.map(|w| format!(", {:+.3} % from the winding number's", 100.0 * (o.volume / w.volume - 1.0))).unwrap_or_default();
        format!("the volume settled within {} % of the cell before{against}", 100.0 * resolve.volume_error)
    } else {
        format!("{} of {} stopped short of it (WARNING below)", last.len() - held, last.len())
    };
    let (lo, hi) = last.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), t| (lo.min(t.cell), hi.max(t.cell)));
    Some(if last.len() == 1 {
        format!("{} tries from {:.4e}, kept {:.4e}: {why}", o.cell_tries.len(), first.cell, lo)
    } else {
        format!("per solid, {} tries from {:.4e}, kept cells of {:.4e} to {:.4e}: {why}", o.cell_tries.len(), first.cell, lo, hi)
    })
}

/// Whether refinement ended, or which budget stopped it, and what is left above its bound.
pub fn refinement_text(m: &MeshSummary) -> String {
    let (r, above) = (m.radius_edge_bound, m.tets_above_radius_edge_bound);
    match &m.refinement_stop {
        Some(s) if s.budget == "points" => format!("stopped early: its point budget ({} points) ran out before every tet met radius-edge {r} (input angles too small for it to end); {above} tets are above it", s.max_points),
        Some(s) => format!("stopped early: its bound on the bad tets worked on ran out at {} points, before every tet met radius-edge {r}; {above} tets are above it", s.points),
        None if m.refinement_stopped => format!("stopped early at its budget before every tet met radius-edge {r}; {above} tets are above it"),
        None if above > 0 => format!("ended; {above} tets are above radius-edge {r} (refinement leaves tets under a tenth of the shortest boundary edge, and points that would crowd the boundary or come nearer a vertex than a share of the local feature size; the optimisation allows up to {})", fmt_num(r.max(2.0))),
        None => format!("ended: every tet meets radius-edge {r}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3d::mesher::RefinementStop;

    #[test]
    fn the_refinement_line_says_which_budget_stopped_it() {
        let mut m = MeshSummary { radius_edge_bound: 1.1, tets_above_radius_edge_bound: 12, ..MeshSummary::default() };
        m.refinement_stop = Some(RefinementStop { budget: "points", points: 29_305, max_points: 29_305 });
        m.refinement_stopped = true;
        let t = refinement_text(&m);
        assert!(t.starts_with("stopped early: its point budget (29305 points) ran out before every tet met radius-edge 1.1") && t.ends_with("; 12 tets are above it"), "{t}");
        m.refinement_stop = Some(RefinementStop { budget: "steps", points: 1_000, max_points: 29_305 });
        assert!(refinement_text(&m).starts_with("stopped early: its bound on the bad tets worked on ran out at 1000 points"));
        m.refinement_stop = None;
        m.refinement_stopped = false;
        assert!(refinement_text(&m).starts_with("ended; 12 tets are above radius-edge 1.1"));
        m.tets_above_radius_edge_bound = 0;
        assert_eq!(refinement_text(&m), "ended: every tet meets radius-edge 1.1");
    }
}
