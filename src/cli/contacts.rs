//! Printing the contacts between solids of a part (`fepre mesh`, `fepre run`).

use fepre::pipeline::{ContactReport, ContactSide};

/// One line per pair of touching faces: both solids and faces, the area, the shared area.
pub(crate) fn print(contacts: &[ContactReport]) {
    if contacts.is_empty() {
        return;
    }
    let conforming = contacts.iter().filter(|c| c.shared_area >= c.area * (1.0 - 1e-9)).count();
    outln!("contacts         {} pairs of touching faces of different solids ({conforming} conforming: nodes shared; the others need a tie)", contacts.len());
    for c in contacts {
        outln!("  {} | {}: area {:.6}, shared {:.6}", side(&c.a), side(&c.b), c.area, c.shared_area);
    }
}

fn side(s: &ContactSide) -> String {
    let mut out = format!("solid {}", s.solid);
    if let Some(n) = &s.solid_name {
        out.push_str(&format!(" {n:?}"));
    }
    out.push_str(&format!(" face {}", s.face.0));
    if let Some(n) = &s.face_name {
        out.push_str(&format!(" {n:?}"));
    }
    if let Some(id) = s.step_id {
        out.push_str(&format!(" ({id})"));
    }
    out
}
