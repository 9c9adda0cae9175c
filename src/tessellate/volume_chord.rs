//! The chord of each face shrunk where its solid would lose too much volume, so that slender
//! and thin parts keep theirs.
//!
//! An inscribed mesh within `δ` of a curved face encloses about `(2/3) δ A` less than it (a
//! cylinder cut by chords of sagitta `δ` loses exactly that to first order). The model-wide
//! chord `δ = chord_relative × size` follows the diagonal, not the part's thickness: it is
//! 2 mm on a 10 m lever rod of radius 50 mm, which then loses 10 % of its volume. So after a
//! tessellation, each closed shell group `g` (a solid, or solids sewn together) whose
//! triangles enclose a volume off the B-rep's own (by [`super::quadrature`]) by more than
//! `η |V_g|` (`η` = [`super::TessellateOptions::volume_relative`]) is tessellated again with
//! the chord
//!
//! ```text
//! δ_g ← δ_g · a η |V_g| / |V_mesh,g − V_g|
//! ```
//!
//! on its faces (the loss is linear in the chord: this aims at `a η`, with `a` = 0.75 in
//! [`super::tessellate`] and 0.9 before a size field spaces the points), at most
//! [`ROUNDS`] times, never below `δ / MAX_SHRINK`, and only while the error is one chords
//! make (below [`MAX_LOSS`]; where the last shrink did not halve it, as on a thin curved
//! wall whose two sides' chords cut opposite ways, below the band and aimed at through it).
//! The quadrature is only done for groups whose band `Σ δ_f A_f` over their curved faces,
//! plus `δ_f` times the length of a plane's curved edges (the most chords within `δ_f` can
//! cut), exceeds `η |V_mesh,g|`: the others keep their volume whatever it says. `|V| / A` is a thickness (half a
//! plate's, half a rod's radius): the bound follows the local feature size of the part, not
//! its diagonal, and parts that keep their volume at `δ` are left as they are. An edge takes
//! the smallest chord of the faces that use it.

use super::Tessellation;
use super::certificate::face_groups;
use super::quadrature::{FaceIntegrals, SegmentIndex, oriented, surface_integrals};
use crate::cad::brep::Model;
use crate::cad::geom::Curve;
use crate::core::FaceId;
use glam::DVec3;
use rayon::prelude::*;

/// Tessellations again at most (after the first).
pub(super) const ROUNDS: usize = 2;
/// The chord of a face is never shrunk below the model-wide chord over this.
pub(super) const MAX_SHRINK: f64 = 100.0;
/// A volume error above this share is not the chords' doing: a slender part cut by chords
/// as coarse as the angle criterion allows (20° per segment) loses 2 %.
pub(super) const MAX_LOSS: f64 = 0.2;

/// The chords of the next tessellation, from `t` made with the chords `chords` (index
/// `FaceId - 1`, `tol` the model-wide one): `None` when every closed shell group of `t` is
/// within `eta` of its B-rep volume, or no chord can shrink further (module docs).
///
/// `aim` is the share of `eta` aimed at (0.75; 0.9 before a size field); `prev_loss` holds
/// each group's volume error in the last round (empty before the first). Also the faces'
/// integrals it computed for `t` ([`Tessellation::quadrature`]; `None` elsewhere).
pub(super) fn shrink_chords(model: &Model, t: &Tessellation, chords: &[f64], tol: f64, eta: f64, aim: f64, prev_loss: &mut Vec<Option<f64>>) -> (Option<Vec<f64>>, Vec<Option<FaceIntegrals>>) {
    if !(eta > 0.0 && tol > 0.0) || chords.len() != model.faces.len() {
        return (None, vec![None; model.faces.len()]);
    }
    let (group, ngroups) = face_groups(model);
    let mut closed = vec![false; ngroups];
    let mut meshed = vec![true; ngroups];
    for (f, face) in model.faces.iter().enumerate() {
        let g = group[f] as usize;
        if let Some(sh) = model.shells.get(face.shell as usize) {
            closed[g] |= sh.closed || sh.solid.is_some();
        }
        meshed[g] &= t.domains.get(f).is_some_and(Option::is_some);
    }
    let centre = model.bounds().map_or(DVec3::ZERO, |(lo, hi)| 0.5 * (lo + hi));
    let index = SegmentIndex::new(&t.edges);
    let s = &t.surface;
    // per group: the triangles' volume, and the band `Σ δ_f A_f` over its curved faces
    // that bounds what the chords can cut
    let mut volume = vec![[0.0f64; 2]; ngroups];
    let mut band = vec![0.0f64; ngroups];
    for (f, dom) in t.domains.iter().enumerate() {
        let Some(dom) = dom else { continue };
        let g = group[f] as usize;
        if !(closed[g] && meshed[g]) {
            continue;
        }
        let curved = !matches!(model.surface(model.faces[f].surface), crate::cad::geom::Surface::Plane(_));
        if !curved {
            // a plane's chords cut only along its curved edges: the slivers there
            band[g] += chords[f] * curved_edge_length(model, t, f);
        }
        for tr in s.triangles.get(dom.triangles.clone()).unwrap_or(&[]) {
            let [a, b, c] = tr.map(|i| s.vertices.get(i as usize).copied().unwrap_or(DVec3::NAN) - centre);
            volume[g][0] += a.dot(b.cross(c)) / 6.0;
            if curved {
                band[g] += chords[f] * (b - a).cross(c - a).length() / 2.0;
            }
        }
    }
    // the B-rep's volume by quadrature, only where the band could cut more than `eta` (or
    // is not a number)
    let suspect: Vec<bool> = (0..ngroups).map(|g| !(band[g] <= eta * volume[g][0].abs())).collect();
    // face by face on every core, summed in face order (the same bits for any thread count)
    let quadrature: Vec<Option<FaceIntegrals>> = t
        .domains
        .par_iter()
        .enumerate()
        .map(|(f, dom)| {
            let g = group[f] as usize;
            let dom = dom.as_ref().filter(|_| closed[g] && meshed[g] && suspect[g])?;
            Some(surface_integrals(model, FaceId::from_index(f), dom, &t.edges, &index, centre))
        })
        .collect();
    for (f, q) in quadrature.iter().enumerate() {
        if let Some(q) = q {
            volume[group[f] as usize][1] += oriented(model, FaceId::from_index(f), *q).volume;
        }
    }
    prev_loss.resize(ngroups, None);
    let floor = tol / MAX_SHRINK;
    let factor: Vec<f64> = volume
        .into_iter()
        .enumerate()
        .map(|(g, [mesh, brep])| {
            let loss = (mesh - brep).abs();
            // a loss the last smaller chords halved is linear in them; one they did not (a
            // thin curved wall: the chords of its two sides cut opposite ways and their
            // segment counts jump apart) is aimed at through the band, the most the chords
            // can cut, which shrinks with them whatever the sides do
            let halved = prev_loss[g].is_none_or(|p| loss <= 0.5 * p);
            let f = aim * eta * brep.abs() / if halved { loss } else { band[g] };
            // a loss the chords cannot make (a solid whose faces do not close it, cross or
            // fold: more than the band, or than MAX_LOSS) is not theirs to mend
            let chords_made_it = loss <= MAX_LOSS * brep.abs() && (halved || loss <= band[g]);
            if suspect[g] {
                prev_loss[g] = Some(loss);
            }
            if suspect[g] && closed[g] && meshed[g] && loss > eta * brep.abs() && f.is_finite() && chords_made_it { f } else { 1.0 }
        })
        .collect();
    let next: Vec<f64> = chords.iter().enumerate().map(|(f, &d)| (d * factor[group[f] as usize]).max(floor).min(d)).collect();
    (next.iter().zip(chords).any(|(n, d)| n < d).then_some(next), quadrature)
}

/// The length of face `f`'s edges that are not straight lines, along their points.
fn curved_edge_length(model: &Model, t: &Tessellation, f: usize) -> f64 {
    let mut length = 0.0;
    for &l in &model.faces[f].loops {
        for c in &model.loops[l as usize].coedges {
            let straight = model.edges[c.edge as usize].curve.is_none_or(|ci| matches!(model.curve(ci), Curve::Line(_)));
            if straight {
                continue;
            }
            if let Some(ep) = t.edges.get(c.edge as usize) {
                let at = |i: u32| t.surface.vertices.get(i as usize).copied().unwrap_or(DVec3::NAN);
                length += ep.ids.windows(2).map(|w| at(w[0]).distance(at(w[1]))).sum::<f64>();
            }
        }
    }
    length
}

/// The chord of every edge: the smallest of the faces that use it, `tol` for an edge no face
/// uses.
pub(super) fn edge_chords(model: &Model, face_chord: &[f64], tol: f64) -> Vec<f64> {
    let mut out = vec![tol; model.edges.len()];
    for (face, &d) in model.faces.iter().zip(face_chord) {
        for &l in &face.loops {
            for c in &model.loops[l as usize].coedges {
                if let Some(e) = out.get_mut(c.edge as usize) {
                    *e = e.min(d);
                }
            }
        }
    }
    out
}
