//! Our AP242 writer of tessellated geometry: a tagged [`TriSurface`] as a file holding one
//! `TESSELLATED_SOLID` (in a `TESSELLATED_SHAPE_REPRESENTATION`, millimetres) whose items are
//! one face per tag, named after the tag. It exists so that tests (and users) have
//! tessellated-only files whose content is known: the reader ([`super::tessellated`]) and
//! OpenCASCADE read them back.
//!
//! One `COORDINATES_LIST` holds every vertex. A face is a `TRIANGULATED_FACE` whose
//! `pnindex` numbers its own points, or (for the tags asked for) a
//! `COMPLEX_TRIANGULATED_FACE` indexing the coordinates directly, its triangles paired into
//! strips of two where they share an edge and the rest written as fans of one, in the
//! convention the reader documents (OpenCASCADE's). Deterministic: the same surface gives the
//! same bytes; written through `io::atomic`.

use super::write_geometry::real;
use super::writer::{StepWriteError, Writer, string};
use crate::core::FaceId;
use crate::io::IoError;
use crate::io::atomic::write_atomic;
use crate::mesh::TriSurface;
use rustc_hash::FxHashMap;
use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

/// The AP242 schema name written in the header.
pub const AP242_SCHEMA: &str = "AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF { 1 0 10303 442 1 1 4 }";

/// The surface as the text of an AP242 tessellated-only STEP file; the faces whose tags are in
/// `complex` are written as `COMPLEX_TRIANGULATED_FACE`s.
///
/// # Errors
/// [`StepWriteError::NotFinite`] for a non-finite coordinate, [`StepWriteError::BadIndex`]
/// for a triangle index out of range.
pub fn tessellated_to_string(surface: &TriSurface, name: &str, complex: &[FaceId]) -> Result<String, StepWriteError> {
    let nv = surface.vertices.len();
    if let Some(k) = surface.triangles.iter().position(|t| t.iter().any(|&v| v as usize >= nv)) {
        return Err(StepWriteError::BadIndex { what: format!("triangle {k}: vertex out of range") });
    }
    if surface.face_tags.len() != surface.triangles.len() {
        return Err(StepWriteError::BadIndex { what: "one face tag per triangle".into() });
    }
    let mut w = Writer::new();
    let mut pts = Vec::with_capacity(nv);
    for (k, p) in surface.vertices.iter().enumerate() {
        if !p.is_finite() {
            return Err(StepWriteError::NotFinite { what: format!("vertex {k}") });
        }
        pts.push(format!("({},{},{})", real(p.x), real(p.y), real(p.z)));
    }
    let coords = w.add(format!("COORDINATES_LIST('',{nv},({}))", pts.join(",")));
    let mut by_face: BTreeMap<FaceId, Vec<[u32; 3]>> = BTreeMap::new();
    for (t, &f) in surface.triangles.iter().zip(&surface.face_tags) {
        by_face.entry(f).or_default().push(*t);
    }
    let mut faces = Vec::with_capacity(by_face.len());
    for (face, tris) in &by_face {
        let n = string(surface.face_names.get(*face).unwrap_or(""));
        let text = if complex.contains(face) {
            let (strips, fans) = strips_and_fans(tris);
            let list = |l: &[Vec<u32>]| l.iter().map(|s| format!("({})", s.iter().map(|v| (v + 1).to_string()).collect::<Vec<_>>().join(","))).collect::<Vec<_>>().join(",");
            format!("COMPLEX_TRIANGULATED_FACE({n},#{coords},{nv},(),$,(),({}),({}))", list(&strips), list(&fans))
        } else {
            // pnindex: the face's own points, in order of first use
            let mut local: FxHashMap<u32, usize> = FxHashMap::default();
            let mut pnindex: Vec<u32> = Vec::new();
            let mut idx = Vec::with_capacity(tris.len());
            for t in tris {
                let l = t.map(|v| {
                    *local.entry(v).or_insert_with(|| {
                        pnindex.push(v);
                        pnindex.len()
                    })
                });
                idx.push(format!("({},{},{})", l[0], l[1], l[2]));
            }
            let pn: Vec<String> = pnindex.iter().map(|v| (v + 1).to_string()).collect();
            format!("TRIANGULATED_FACE({n},#{coords},{},(),$,({}),({}))", pn.len(), pn.join(","), idx.join(","))
        };
        faces.push(w.add(text));
    }
    let list: Vec<String> = faces.iter().map(|f| format!("#{f}")).collect();
    let solid = w.add(format!("TESSELLATED_SOLID({},({}),$)", string(name), list.join(",")));
    w.context_and_product(name, &[solid], "TESSELLATED_SHAPE_REPRESENTATION")?;
    Ok(w.file_text(name, AP242_SCHEMA))
}

/// Writes the surface to `path` as [`tessellated_to_string`] does, through a temporary file.
///
/// # Errors
/// As [`tessellated_to_string`], and [`StepWriteError::Io`].
pub fn write_tessellated(path: &Path, surface: &TriSurface, name: &str, complex: &[FaceId]) -> Result<(), StepWriteError> {
    let text = tessellated_to_string(surface, name, complex)?;
    write_atomic(path, |f| f.write_all(text.as_bytes()).map_err(|source| IoError::Write { path: path.to_path_buf(), source }))?;
    Ok(())
}

/// Triangles as strips and fans (0-based vertex indices). A strip `s1 s2 s3 s4` is read as
/// `(s1, s3, s2)`, `(s2, s3, s4)`, a fan `f1 f2 f3` as `(f1, f3, f2)`: a triangle `(a, b, c)`
/// followed across its edge `b c` by `(c, b, d)` is the strip `a c b d`; a triangle alone is
/// the fan `a c b`. Greedy in triangle order.
fn strips_and_fans(tris: &[[u32; 3]]) -> (Vec<Vec<u32>>, Vec<Vec<u32>>) {
    // directed edge -> triangle
    let mut edge: FxHashMap<(u32, u32), usize> = FxHashMap::default();
    for (k, t) in tris.iter().enumerate() {
        for i in 0..3 {
            edge.entry((t[i], t[(i + 1) % 3])).or_insert(k);
        }
    }
    let mut used = vec![false; tris.len()];
    let (mut strips, mut fans) = (Vec::new(), Vec::new());
    for (k, t) in tris.iter().enumerate() {
        if used[k] {
            continue;
        }
        used[k] = true;
        let mut paired = false;
        for r in 0..3 {
            let (a, b, c) = (t[r], t[(r + 1) % 3], t[(r + 2) % 3]);
            if let Some(&j) = edge.get(&(c, b)) {
                if !used[j] {
                    let u = tris[j];
                    let Some(d) = u.iter().copied().find(|&x| x != b && x != c) else { continue };
                    used[j] = true;
                    strips.push(vec![a, c, b, d]);
                    paired = true;
                    break;
                }
            }
        }
        if !paired {
            fans.push(vec![t[0], t[2], t[1]]);
        }
    }
    (strips, fans)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reader's rule for strips and fans, applied to the writer's output.
    fn expand(strips: &[Vec<u32>], fans: &[Vec<u32>]) -> Vec<[u32; 3]> {
        let mut out = Vec::new();
        for s in strips {
            for k in 2..s.len() {
                out.push(if k % 2 == 0 { [s[k - 2], s[k], s[k - 1]] } else { [s[k - 2], s[k - 1], s[k]] });
            }
        }
        for f in fans {
            for k in 2..f.len() {
                out.push([f[0], f[k], f[k - 1]]);
            }
        }
        out
    }

    fn canonical(t: [u32; 3]) -> [u32; 3] {
        let r = (0..3).min_by_key(|&i| t[i]).unwrap_or(0);
        [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]
    }

    #[test]
    fn strips_and_fans_give_back_the_triangles_with_their_orientation() {
        // a square (two triangles) and a lone triangle
        let tris = vec![[0, 1, 2], [0, 2, 3], [4, 5, 6]];
        let (strips, fans) = strips_and_fans(&tris);
        assert_eq!(strips.len(), 1);
        assert_eq!(fans.len(), 1);
        let mut got: Vec<[u32; 3]> = expand(&strips, &fans).into_iter().map(canonical).collect();
        let mut want: Vec<[u32; 3]> = tris.into_iter().map(canonical).collect();
        got.sort_unstable();
        want.sort_unstable();
        assert_eq!(got, want);
    }
}
