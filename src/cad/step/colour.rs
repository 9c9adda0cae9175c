//! Face colours from presentation (`STYLED_ITEM` → ... → `COLOUR_RGB` or a
//! `DRAUGHTING_PRE_DEFINED_COLOUR`): a face takes its own colour, else its shell's, else its
//! solid's. Only the first colour found under each styled item is used (surface and curve
//! styles are not told apart).

use super::param::Param;
use super::table::StepFile;
use crate::cad::brep::Model;
use rustc_hash::FxHashMap;

/// The colour reachable from instance `id` within a few references.
fn find_colour(file: &StepFile, id: u64, depth: usize) -> Option<[f32; 3]> {
    if depth > 10 {
        return None;
    }
    let e = file.get(id)?;
    if let Some(r) = e.record("COLOUR_RGB") {
        let c: Vec<f64> = r.params.iter().skip(1).filter_map(Param::as_f64).collect();
        if c.len() == 3 {
            return Some([c[0] as f32, c[1] as f32, c[2] as f32]);
        }
    }
    if let Some(r) = e.record("DRAUGHTING_PRE_DEFINED_COLOUR") {
        let name = r.params.first().and_then(Param::as_str).unwrap_or("").to_ascii_lowercase();
        let c = match name.as_str() {
            "red" => [1.0, 0.0, 0.0],
            "green" => [0.0, 1.0, 0.0],
            "blue" => [0.0, 0.0, 1.0],
            "yellow" => [1.0, 1.0, 0.0],
            "magenta" => [1.0, 0.0, 1.0],
            "cyan" => [0.0, 1.0, 1.0],
            "black" => [0.0, 0.0, 0.0],
            "white" => [1.0, 1.0, 1.0],
            _ => return None,
        };
        return Some(c);
    }
    let mut out = None;
    for r in &e.records {
        for p in &r.params {
            p.for_each_ref(&mut |child| {
                if out.is_none() {
                    out = find_colour(file, child, depth + 1);
                }
            });
            if out.is_some() {
                return out;
            }
        }
    }
    out
}

/// Sets [`Face::colour`](crate::cad::brep::Face::colour) from the file's styled items.
pub(super) fn assign(file: &StepFile, model: &mut Model) {
    let mut by_item: FxHashMap<u64, [f32; 3]> = FxHashMap::default();
    for e in file.entities() {
        let Some(r) = e.records.iter().find(|r| r.name.ends_with("STYLED_ITEM")) else { continue };
        let (Some(styles), Some(item)) = (r.params.get(1), r.params.get(2).and_then(Param::as_ref_id)) else { continue };
        let mut colour = None;
        styles.for_each_ref(&mut |s| {
            if colour.is_none() {
                colour = find_colour(file, s, 0);
            }
        });
        if let Some(c) = colour {
            // an over-riding style written later wins
            by_item.insert(item, c);
        }
    }
    if by_item.is_empty() {
        return;
    }
    for k in 0..model.faces.len() {
        let f = &model.faces[k];
        let shell = &model.shells[f.shell as usize];
        let solid = shell.solid.map(|s| model.solids[s as usize].source.0);
        let c = by_item.get(&f.source.0).or_else(|| by_item.get(&shell.source.0)).or_else(|| solid.and_then(|s| by_item.get(&s))).copied();
        model.faces[k].colour = c;
    }
}
