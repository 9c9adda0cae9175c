//! A surface of triangles and quads as a CalculiX/Abaqus mesh (`.inp`): `*NODE` and one
//! `*ELEMENT` block per tag and element kind, its `ELSET` named after the tag. A planar mesh
//! (every z = 0: a 2D region) gets plane-stress elements `CPS3`/`CPS4` and two coordinates
//! per node; a 3D one (a part's faces) gets shell elements `S3`/`S4`. The mesh only: the
//! sections, materials and steps of 2D and shell models are the FE model's.

use crate::core::FaceId;
use crate::deck::inp::num;
use crate::io::IoError;
use crate::io::atomic::{write_atomic, write_err};
use crate::mesh::MixedSurface;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

/// Writes `s` as an Abaqus/CalculiX mesh (see the module docs); `title` is the heading.
///
/// # Errors
/// [`IoError::Invalid`] for a surface that fails `validate()`; [`IoError::Write`].
pub fn write_inp_faces(path: &Path, s: &MixedSurface, title: &str) -> Result<(), IoError> {
    s.validate().map_err(|source| IoError::Invalid { path: path.to_path_buf(), source })?;
    let text = inp_faces_text(s, title);
    write_atomic(path, |w| w.write_all(text.as_bytes()).map_err(write_err(path)))
}

/// The text [`write_inp_faces`] writes.
pub fn inp_faces_text(s: &MixedSurface, title: &str) -> String {
    let planar = s.vertices.iter().all(|p| p.z == 0.0);
    let mut out = String::new();
    let _ = writeln!(out, "** written by fepre {}: {} triangles, {} quads", env!("CARGO_PKG_VERSION"), s.triangles.len(), s.quads.len());
    let _ = writeln!(out, "*HEADING\n{}", title.replace(['\n', '\r'], " "));
    let _ = writeln!(out, "*NODE");
    for (i, p) in s.vertices.iter().enumerate() {
        if planar {
            let _ = writeln!(out, "{}, {}, {}", i + 1, num(p.x), num(p.y));
        } else {
            let _ = writeln!(out, "{}, {}, {}, {}", i + 1, num(p.x), num(p.y), num(p.z));
        }
    }
    let prefix = if planar { "REGION" } else { "FACE" };
    let name = |t: FaceId| -> String {
        s.face_names.get(t).map(clean).filter(|n| !n.is_empty()).unwrap_or_else(|| format!("{prefix}_{}", t.0))
    };
    let mut id = 1usize;
    let mut block = |out: &mut String, kind: &str, elements: &[&[u32]], tags: &[FaceId]| {
        let mut by_tag: BTreeMap<FaceId, Vec<usize>> = BTreeMap::new();
        for (e, &t) in tags.iter().enumerate() {
            by_tag.entry(t).or_default().push(e);
        }
        for (t, list) in by_tag {
            let _ = writeln!(out, "*ELEMENT, TYPE={kind}, ELSET={}", name(t));
            for e in list {
                let _ = write!(out, "{id}");
                for v in elements[e] {
                    let _ = write!(out, ", {}", v + 1);
                }
                let _ = writeln!(out);
                id += 1;
            }
        }
    };
    let tris: Vec<&[u32]> = s.triangles.iter().map(|t| t.as_slice()).collect();
    let quads: Vec<&[u32]> = s.quads.iter().map(|q| q.as_slice()).collect();
    block(&mut out, if planar { "CPS3" } else { "S3" }, &tris, &s.triangle_tags);
    block(&mut out, if planar { "CPS4" } else { "S4" }, &quads, &s.quad_tags);
    out
}

/// A set name Abaqus takes: letters, digits and `_`, upper case, starting with a letter, at
/// most 80 characters.
fn clean(n: &str) -> String {
    let mut c: String = n.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_uppercase() } else { '_' }).take(80).collect();
    if !c.starts_with(|ch: char| ch.is_ascii_alphabetic()) && !c.is_empty() {
        c.insert(0, 'R');
        c.truncate(80);
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::RegionId;
    use crate::mesh::PlanarMesh;
    use glam::DVec2;

    #[test]
    fn planar_quads_are_cps4_in_their_region_sets() {
        let m = PlanarMesh {
            vertices: vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y, DVec2::new(2.0, 0.5)],
            triangles: vec![[1, 4, 2]],
            triangle_tags: vec![RegionId(2)],
            quads: vec![[0, 1, 2, 3]],
            quad_tags: vec![RegionId(1)],
            region_names: [(RegionId(1), "web plate")].into_iter().collect(),
        };
        let t = inp_faces_text(&MixedSurface::from_planar(&m), "t");
        assert!(t.contains("*ELEMENT, TYPE=CPS3, ELSET=REGION_2\n1, 2, 5, 3\n"), "{t}");
        assert!(t.contains("*ELEMENT, TYPE=CPS4, ELSET=WEB_PLATE\n2, 1, 2, 3, 4\n"), "{t}");
        assert!(t.contains("*NODE\n1, 0.0, 0.0\n"), "{t}");
        let mut lifted = MixedSurface::from_planar(&m);
        lifted.vertices[4].z = 1.0;
        let t = inp_faces_text(&lifted, "t");
        assert!(t.contains("TYPE=S4") && t.contains("TYPE=S3") && t.contains("5, 2.0, 0.5, 1.0"), "{t}");
    }
}
