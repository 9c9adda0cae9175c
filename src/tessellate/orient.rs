//! Closed shells written inside out. A file may orient a solid's outer shell so that it encloses
//! negative volume, or a void's shell (`BREP_WITH_VOIDS`, `ORIENTED_CLOSED_SHELL`) so that it
//! encloses positive volume: its face senses and orientation flags disagree with its geometry.
//! OpenCASCADE reads such files and turns the shells (`ShapeFix_Solid`); so does fepre, where
//! the triangles of the shell group close (then the sign of their volume is the shell's true
//! orientation), and says so: every face of the group has its sense turned in the model and
//! its triangles turned in the tessellation, and the group is listed in the certificate. A
//! group whose triangles do not close is left as it is (its certificate fails anyway).

use super::Tessellation;
use super::certificate::{Certificate, Reoriented, face_groups};
use crate::cad::brep::Model;

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
