//! Closed shells written inside out. A file may orient a solid's outer shell so that it encloses
//! negative volume, or a void's shell (`BREP_WITH_VOIDS`, `ORIENTED_CLOSED_SHELL`) so that it
//! encloses positive volume: its face senses and orientation flags disagree with its geometry.
//! OpenCASCADE reads such files and turns the shells (`ShapeFix_Solid`); so does fepre, where
//! the triangles of the shell group close (then the sign of their volume is the shell's true
//! orientation), and says so: every face of the group has its sense turned in the model and
//! its triangles turned in the tessellation, and the group is listed in the certificate. A
//! group whose triangles do not close is left as it is (its certificate fails anyway).
//!
//! Single faces written against their shell. A face whose triangles run along most of its
//! shared mesh edges in the same direction as its neighbours' (its sense disagrees with its
//! loops: small B-spline fillets of a SolidWorks export, 4 of 402 faces) is turned, as
//! OpenCASCADE's `ShapeFix_Shell` orients faces by their neighbours: one face at a time, the
//! one with the most such edges over the agreeing ones first (ties: the lower face), while
//! one has more; each turn lowers the count of misoriented edges, so it ends. Only where
//! every face with such edges lies on an open surface: on a closed one (a torus band between
//! two circles) the disagreement says fepre took the wrong side of its loops, and a turned
//! face would close the shell around the wrong volume (a SparkFun switch: 4 % short of
//! OpenCASCADE's solid), so nothing is turned there and the certificate fails.

use super::Tessellation;
use super::certificate::{Certificate, Reoriented, face_groups};
use crate::cad::brep::Model;
use crate::core::FaceId;
use rustc_hash::FxHashMap;

/// The shell groups of `c` that close and enclose volume of the wrong sign; turns them in
/// `model` and `t` (`c` must be the certificate of `t`). Returns what was turned.
pub fn turn_inside_out_shells(model: &mut Model, t: &mut Tessellation, c: &Certificate) -> Vec<Reoriented> {
    let (group, ngroups) = face_groups(model);
    if ngroups != c.shells.len() {
        return Vec::new();
    }
    let turn: Vec<bool> = c
        .shells
        .iter()
        .map(|x| {
            let wrong = if x.void { x.volume_mesh > 0.0 } else { x.volume_mesh < 0.0 };
            x.brep_closed && x.mesh_closed && x.mesh_components == 1 && wrong
        })
        .collect();
    if !turn.contains(&true) {
        return Vec::new();
    }
    for (f, face) in model.faces.iter_mut().enumerate() {
        if turn[group[f] as usize] {
            face.same_sense = !face.same_sense;
        }
    }
    let s = &mut t.surface;
    for (tri, tag) in s.triangles.iter_mut().zip(&s.face_tags) {
        if tag.index().is_some_and(|f| f < group.len() && turn[group[f] as usize]) {
            tri.swap(1, 2);
        }
    }
    c.shells
        .iter()
        .zip(&turn)
        .filter(|(_, t)| **t)
        .map(|(x, _)| Reoriented { brep_shells: x.brep_shells.clone(), void: x.void, faces: x.faces, volume_as_written: x.volume_mesh })
        .collect()
}

/// Turns the faces of `t` whose triangles disagree with their neighbours' across more shared
/// mesh edges than they agree (see the module docs), in `model` and `t`; returns them.
pub fn turn_misoriented_faces(model: &mut Model, t: &mut Tessellation) -> Vec<FaceId> {
    let nf = model.faces.len();
    let mut turned = Vec::new();
    for _ in 0..nf {
        let s = &t.surface;
        let mut uses: FxHashMap<(u32, u32), Vec<(bool, usize)>> = FxHashMap::default();
        for (tri, tag) in s.triangles.iter().zip(&s.face_tags) {
            let Some(f) = tag.index().filter(|&f| f < nf) else { continue };
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                uses.entry((a.min(b), a.max(b))).or_default().push((a < b, f));
            }
        }
        // per face: shared edges where it runs against its neighbour (agree) or with it
        let mut count = vec![(0i64, 0i64); nf];
        for u in uses.values() {
            if let [(da, fa), (db, fb)] = u.as_slice()
                && fa != fb
            {
                let c = if da == db { (0, 1) } else { (1, 0) };
                for &f in [fa, fb] {
                    count[f].0 += c.0;
                    count[f].1 += c.1;
                }
            }
        }
        // a face on a closed surface (a torus band between two circles) that runs against its
        // neighbours has likely been given the wrong side of its loops, which no turn mends:
        // nothing is turned, and the certificate fails
        if (0..nf).any(|f| count[f].1 > 0 && closed_surface(model, f)) {
            break;
        }
        let worst = (0..nf).filter(|&f| count[f].1 > count[f].0).max_by_key(|&f| (count[f].1 - count[f].0, std::cmp::Reverse(f)));
        let Some(f) = worst else { break };
        model.faces[f].same_sense = !model.faces[f].same_sense;
        let s = &mut t.surface;
        for (tri, tag) in s.triangles.iter_mut().zip(&s.face_tags) {
            if tag.index() == Some(f) {
                tri.swap(1, 2);
            }
        }
        turned.push(FaceId::from_index(f));
    }
    turned.sort_unstable();
    turned
}

/// True when face `f`'s surface closes on itself in `u` or `v`.
fn closed_surface(model: &Model, f: usize) -> bool {
    let d = model.surfaces[model.faces[f].surface as usize].domain();
    d.u_closed || d.v_closed
}
