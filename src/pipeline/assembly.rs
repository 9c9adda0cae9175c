//! A part made of several solids: which solid each triangle of the surface to mesh bounds,
//! the gap within which solids touch, and the contacts as reports list them (names and STEP
//! `#id`s from the face table).
//!
//! The solids of a CAD part are its B-rep solids, numbered from 1 in the order of
//! [`Model::solids`] (as the face table and the `solid` selector number them), named after
//! the solid where the file names it; the faces of a surface model's shells, which bound no
//! solid, form one more. The solids of a surface mesh without seeds are its closed outer
//! shells, each with the shells nested in it as voids (a shell inside an odd number of
//! others, meeting none of them), numbered in the order of the shells; a surface with region
//! seeds or holes (a `.poly` file) is meshed as one, its regions given by the seeds.

use crate::cad::brep::{EntityRef, FaceEntry, Model};
use crate::core::FaceId;
use crate::mesh::TriSurface;
use crate::mesh::topology::{ReportOptions, intersecting_pairs, surface_report, triangle_shells};
use crate::mesh3d::mesher::{Contact, SolidInfo, Solids};
use serde::Serialize;
use std::collections::BTreeSet;

/// The gap of a CAD part, in chord deviations: a point of a certified tessellation lies within
/// one chord of the B-rep, so where two solids share a face their tessellations reach at most
/// two chords into each other.
pub const GAP_CHORDS: f64 = 3.0;

/// The gap of a surface mesh, a fraction of its diagonal: its solids must touch exactly (to
/// rounding).
pub const GAP_RELATIVE: f64 = 1e-6;

/// One side of a contact.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ContactSide {
    /// The solid's number (its region tag).
    pub solid: u32,
    /// The solid's name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solid_name: Option<String>,
    /// The face's tag.
    pub face: FaceId,
    /// The face's unique name, as in the face table.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub face_name: Option<String>,
    /// The face's STEP `ADVANCED_FACE`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub step_id: Option<EntityRef>,
}

/// Two faces of different solids that touch, for a deck writer to tie.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ContactReport {
    /// The solid with the smaller number and its face.
    pub a: ContactSide,
    /// The other solid and its face.
    pub b: ContactSide,
    /// The area over which the faces touch (facing, within the gap).
    pub area: f64,
    /// Of it, the area where the mesh is conforming (the solids share nodes and faces there);
    /// the rest needs a tie.
    pub shared_area: f64,
}

/// The solids of `surface`, a part's surface to mesh: by the solids of `model` (a CAD part);
/// for a surface mesh by its shells, or one solid where it is `seeded` (holes, region seeds
/// or region sizes: a `.poly` file).
pub fn solids_of(model: Option<&Model>, seeded: bool, surface: &TriSurface) -> Solids {
    match model {
        Some(m) => cad_solids(m, surface),
        None if !seeded => shell_solids(surface),
        None => one_solid(surface),
    }
}

/// The gap within which a part's solids touch: `GAP_CHORDS` times `chord`, the chord
/// deviation of a CAD part's certified tessellation; otherwise `GAP_RELATIVE` of the
/// part's `diagonal`.
pub fn gap_of(chord: Option<f64>, diagonal: f64) -> f64 {
    match chord {
        Some(c) => GAP_CHORDS * c,
        None => GAP_RELATIVE * diagonal,
    }
}

fn one_solid(surface: &TriSurface) -> Solids {
    Solids { of_triangle: vec![0; surface.triangles.len()], solids: vec![SolidInfo { tag: crate::core::RegionId(1), name: None }] }
}

/// B-rep solids by the faces' shells; a surface model's faces as one more solid.
fn cad_solids(m: &Model, surface: &TriSurface) -> Solids {
    let key = |f: FaceId| m.try_face(f).and_then(|face| m.shells.get(face.shell as usize)).and_then(|s| s.solid);
    let mut used = vec![false; m.solids.len()];
    let mut free = false;
    for &f in &surface.face_tags {
        match key(f) {
            Some(k) => used[k as usize] = true,
            None => free = true,
        }
    }
    let mut index = vec![crate::core::ids::NONE; m.solids.len()];
    let mut solids = Vec::new();
    for (k, s) in m.solids.iter().enumerate() {
        if used[k] {
            index[k] = solids.len() as u32;
            solids.push(SolidInfo { tag: crate::core::RegionId(k as u32 + 1), name: s.name.clone() });
        }
    }
    let free_index = solids.len() as u32;
    if free {
        solids.push(SolidInfo { tag: crate::core::RegionId(m.solids.len() as u32 + 1), name: None });
    }
    let of_triangle = surface.face_tags.iter().map(|&f| key(f).map_or(free_index, |k| index[k as usize])).collect();
    Solids { of_triangle, solids }
}

/// Closed outer shells with their voids; one solid when a shell is open (the input check
/// then says what is wrong, as for any surface). A shell inside an odd number of others is a
/// void of the innermost one, unless their triangles meet: then it is a solid of its own (two
/// solids that overlap, or touch from inside, which the mesher then refuses by name), as is a
/// shell whose nesting is undecided (every vertex on another shell: a duplicate).
fn shell_solids(surface: &TriSurface) -> Solids {
    let of_shell = triangle_shells(surface);
    if !of_shell.iter().any(|s| s.is_some_and(|s| s > 0)) {
        return one_solid(surface);
    }
    let report = surface_report(surface, &ReportOptions::default().with_self_intersections(false));
    let shells = &report.shells;
    if shells.iter().any(|s| !s.closed) {
        return one_solid(surface);
    }
    let mut meeting: BTreeSet<(usize, usize)> = BTreeSet::new();
    for [a, b] in intersecting_pairs(surface) {
        if let (Some(x), Some(y)) = (of_shell[a as usize], of_shell[b as usize]) {
            if x != y {
                meeting.insert((x.min(y) as usize, x.max(y) as usize));
            }
        }
    }
    // the outer shell of each shell's solid: itself, or for a void its container
    let mut root: Vec<usize> = (0..shells.len()).collect();
    for (k, s) in shells.iter().enumerate() {
        if let (Some(d), Some(p)) = (s.depth, s.parent) {
            if d % 2 == 1 && !meeting.contains(&(k.min(p), k.max(p))) {
                root[k] = p;
            }
        }
    }
    let mut index = vec![crate::core::ids::NONE; shells.len()];
    let mut solids = Vec::new();
    for k in 0..shells.len() {
        if root[k] == k {
            index[k] = solids.len() as u32;
            solids.push(SolidInfo { tag: crate::core::RegionId(solids.len() as u32 + 1), name: None });
        }
    }
    if solids.len() < 2 {
        return one_solid(surface);
    }
    let of_triangle = of_shell.iter().map(|s| s.map_or(0, |s| index[root[s as usize]])).collect();
    Solids { of_triangle, solids }
}

/// The mesher's contacts with the names and STEP `#id`s of the face table.
pub fn contact_reports(contacts: &[Contact], faces: &[FaceEntry], solids: &[SolidInfo]) -> Vec<ContactReport> {
    let side = |solid: crate::core::RegionId, face: FaceId| {
        let entry = faces.iter().find(|e| e.face == face);
        ContactSide {
            solid: solid.0,
            solid_name: solids.iter().find(|s| s.tag == solid).and_then(|s| s.name.clone()),
            face,
            face_name: entry.and_then(|e| e.name.clone()),
            step_id: entry.and_then(|e| e.step_id),
        }
    };
    contacts.iter().map(|c| ContactReport { a: side(c.solid_a, c.face_a), b: side(c.solid_b, c.face_b), area: c.area, shared_area: c.shared_area }).collect()
}

/// The STEP `#id` of `face` in the face table.
pub fn step_id(faces: &[FaceEntry], face: FaceId) -> Option<EntityRef> {
    faces.iter().find(|e| e.face == face).and_then(|e| e.step_id)
}
