//! Where a tet sits in its mesh, for reports and requirement errors: its centroid, the nearest
//! tagged boundary face, the nearest feature edge of the boundary (an edge between two
//! boundary triangles of different tags, or, within one tag, a crease whose triangles turn by
//! more than [`CREASE_DEG`]) and the small input angle it touches, or else the nearest one
//! within its reach (see [`crate::quality::input_angles`]), and a narrow face at its vertices:
//! a sliver face of the part (a strip far narrower than the tet) explains bad tets as a small
//! angle does, without having one.
//!
//! Nearest means by Euclidean distance from the centroid, scanning every boundary triangle
//! (a report looks up one or two tets); ties keep the lowest index, so the answer does not
//! depend on the thread count.

use crate::core::FaceId;
use crate::core::closest::{closest_point_on_segment, closest_point_on_triangle};
use crate::mesh::TetMesh;
use crate::quality::between_sides::SideTags;
use crate::quality::input_angles::{InputAngle, InputAngleKind};
use crate::quality::tetrahedron::{TET_EDGES, tet_measures};
use glam::DVec3;
use serde::Serialize;

/// A small input angle that a tet does not touch is named with the tet's place when it lies
/// within this many of the tet's longest edges: a sliver flat against a wall a few tet
/// lengths from a knife edge of the part (where the gap between the walls is a fraction of
/// the tet) is there because of it, and the user is shown where it is and how far.
pub const NEAR_REACH: f64 = 4.0;

/// A tet touches an input angle when one of its vertices lies within this fraction of its
/// longest edge from the angle's edge or vertex (Steiner points on an input edge are on it up
/// to rounding).
pub const TOUCH_RELATIVE: f64 = 1e-6;

/// A face at a tet's vertices is narrow when its mean width (twice its area over its perimeter,
/// the width of a long strip) is under this fraction of the tet's longest edge.
pub const NARROW_RELATIVE: f64 = 0.1;

/// An edge between two boundary triangles of one tag is a crease (a feature edge) when their
/// normals differ by more than this, degrees.
pub const CREASE_DEG: f64 = 30.0;

/// The boundary face nearest to a point.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NearestFace {
    /// Its tag (the CAD face, or the input triangle's tag).
    pub face: FaceId,
    /// Its name, where known.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Its point nearest to the tet's centroid.
    pub point: [f64; 3],
    /// The distance from the centroid.
    pub distance: f64,
}

/// The feature edge of the boundary nearest to a point: a boundary edge whose triangles carry
/// different tags, or a crease of one face.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NearestEdge {
    /// The two faces it lies between (smaller tag first); the same face twice for a crease.
    pub faces: [FaceId; 2],
    /// Their names, where known.
    pub names: [Option<String>; 2],
    /// Its point nearest to the tet's centroid.
    pub point: [f64; 3],
    /// The distance from the centroid.
    pub distance: f64,
}

/// An input angle within reach of a tet.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NearAngle {
    /// The angle.
    #[serde(flatten)]
    pub angle: InputAngle,
    /// The names of its faces, where known.
    pub names: [Option<String>; 2],
    /// The distance from the tet's nearest vertex to the angle's edge or vertex.
    pub distance: f64,
    /// A vertex of the tet lies on it (within [`TOUCH_RELATIVE`] of the tet's longest edge).
    pub touches: bool,
    /// Not touching it, the tet lies between its two sides
    /// ([`crate::quality::between_sides`]).
    pub between_sides: bool,
}

/// A boundary face far narrower than a tet at its vertices.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NarrowFace {
    /// Its tag.
    pub face: FaceId,
    /// Its name, where known.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Its mean width: twice its area over its perimeter (the edges it shares with other tags,
    /// and open ones).
    pub width: f64,
}

/// Where a tet sits and what it is like.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TetPlace {
    /// The tet's index.
    pub tet: usize,
    /// Its centroid.
    pub point: [f64; 3],
    /// Its smallest dihedral angle, degrees.
    pub min_dihedral_deg: f64,
    /// Its largest dihedral angle, degrees.
    pub max_dihedral_deg: f64,
    /// Its radius-edge ratio.
    pub radius_edge: f64,
    /// Its longest edge.
    pub longest_edge: f64,
    /// The nearest tagged boundary face (none without a boundary).
    pub nearest_face: Option<NearestFace>,
    /// The nearest feature edge (none when the boundary has one tag).
    pub nearest_edge: Option<NearestEdge>,
    /// The smallest input angle the tet touches; else the smallest between whose sides it
    /// lies; else the nearest whose edge or vertex lies within `NEAR_REACH` times the tet's
    /// longest edge of one of its vertices (none when no small angle is that near).
    pub input_angle: Option<NearAngle>,
    /// The narrowest face at the tet's vertices, where its width is under
    /// `NARROW_RELATIVE` of the tet's longest edge.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub narrow_face: Option<NarrowFace>,
}

/// The boundary of a tet mesh, indexed for [`BoundaryIndex::locate`].
#[derive(Clone, Debug)]
pub struct BoundaryIndex {
    /// Feature edges: endpoints and the two smallest different tags on them (a crease: its
    /// tag twice).
    features: Vec<([u32; 2], [FaceId; 2])>,
    /// The boundary's tags at each vertex, for the angles a tet lies between the sides of.
    sides: SideTags,
    /// Per tag (sorted): its area and its perimeter.
    extents: Vec<(FaceId, f64, f64)>,
}

impl BoundaryIndex {
    /// The boundary's tags at each vertex.
    pub fn sides(&self) -> &SideTags {
        &self.sides
    }

    /// The feature edges of `mesh`'s tagged boundary: edges between tags, and creases.
    pub fn new(mesh: &TetMesh) -> BoundaryIndex {
        // (edge, tag, triangle) for every side of every boundary triangle
        let mut on_edge: Vec<([u32; 2], FaceId, u32)> = Vec::with_capacity(3 * mesh.boundary.len());
        for (i, (t, tag)) in mesh.boundary.iter().zip(&mesh.face_tags).enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                on_edge.push(([a.min(b), a.max(b)], *tag, i as u32));
            }
        }
        on_edge.sort_unstable();
        let normal = |i: u32| {
            let [a, b, c] = mesh.boundary[i as usize].map(|v| mesh.vertices[v as usize]);
            (b - a).cross(c - a).normalize_or_zero()
        };
        let crease_cos = CREASE_DEG.to_radians().cos();
        let mut features = Vec::new();
        // each tag's area, and its perimeter: the sides it shares with no triangle of its own
        let mut extents: Vec<(FaceId, f64, f64)> = Vec::new();
        for (t, tag) in mesh.boundary.iter().zip(&mesh.face_tags) {
            let [a, b, c] = t.map(|v| mesh.vertices[v as usize]);
            extents.push((*tag, 0.5 * (b - a).cross(c - a).length(), 0.0));
        }
        for run in on_edge.chunk_by(|x, y| x.0 == y.0) {
            let (edge, first) = (run[0].0, run[0].1);
            let [a, b] = edge.map(|v| mesh.vertices[v as usize]);
            for x in run.iter().filter(|x| !run.iter().any(|y| y.2 != x.2 && y.1 == x.1)) {
                extents[x.2 as usize].2 += a.distance(b);
            }
            // tags are sorted within an edge: the first differing one is the second smallest
            if let Some(other) = run.iter().map(|x| x.1).find(|&t| t != first) {
                features.push((edge, [first, other]));
            } else if let [x, y] = run {
                let (nx, ny) = (normal(x.2), normal(y.2));
                // consistently oriented neighbours have opposite directions along the edge
                if nx != glam::DVec3::ZERO && ny != glam::DVec3::ZERO && nx.dot(ny) < crease_cos {
                    features.push((edge, [first, first]));
                }
            }
        }
        extents.sort_unstable_by_key(|x| x.0);
        let extents: Vec<(FaceId, f64, f64)> = extents.chunk_by(|x, y| x.0 == y.0).map(|r| (r[0].0, r.iter().map(|x| x.1).sum(), r.iter().map(|x| x.2).sum())).collect();
        BoundaryIndex { features, sides: SideTags::new(mesh), extents }
    }

    /// Where tet `t` of `mesh` sits: the nearest face and feature edge, and the smallest of
    /// `angles` (those under `bound` degrees, smallest first) that it touches, else the
    /// smallest between whose sides it lies (seen under `bound`), else the nearest within its
    /// reach; `name` names a face tag.
    ///
    /// # Panics
    /// `t` out of range, or indices out of range in `mesh` (validate untrusted meshes first).
    pub fn locate(&self, mesh: &TetMesh, t: usize, angles: &[InputAngle], bound: f64, name: &dyn Fn(FaceId) -> Option<String>) -> TetPlace {
        let p = mesh.tets[t].map(|v| mesh.vertices[v as usize]);
        let c = (p[0] + p[1] + p[2] + p[3]) / 4.0;
        // the measures the mesh reports use, so the figures agree to the bit
        let m = tet_measures(&p);
        let (lo, hi, re) = (m.min_dihedral, m.max_dihedral, m.radius_edge);
        let longest = TET_EDGES.iter().map(|[i, j]| p[*i].distance(p[*j])).fold(0.0, f64::max);
        let mut face: Option<(f64, usize, DVec3)> = None;
        for (k, tri) in mesh.boundary.iter().enumerate() {
            let q = closest_point_on_triangle(c, tri.map(|v| mesh.vertices[v as usize]));
            let d = q.distance(c);
            if face.is_none_or(|(best, _, _)| d < best) {
                face = Some((d, k, q));
            }
        }
        let nearest_face = face.map(|(d, k, q)| {
            let f = mesh.face_tags.get(k).copied().unwrap_or_default();
            NearestFace { face: f, name: name(f), point: q.to_array(), distance: d }
        });
        let mut edge: Option<(f64, usize, DVec3)> = None;
        for (k, ([a, b], _)) in self.features.iter().enumerate() {
            let q = closest_point_on_segment(c, mesh.vertices[*a as usize], mesh.vertices[*b as usize]);
            let d = q.distance(c);
            if edge.is_none_or(|(best, _, _)| d < best) {
                edge = Some((d, k, q));
            }
        }
        let nearest_edge = edge.map(|(d, k, q)| {
            let faces = self.features[k].1;
            NearestEdge { faces, names: faces.map(name), point: q.to_array(), distance: d }
        });
        // the smallest angle the tet touches (angles come smallest first), else the nearest
        // one within reach
        let near: Vec<(usize, f64)> = angles.iter().enumerate().map(|(k, a)| (k, p.iter().map(|&v| a.distance(v)).fold(f64::INFINITY, f64::min))).filter(|&(_, d)| d <= NEAR_REACH * longest).collect();
        let touch = near.iter().find(|&&(_, d)| d <= TOUCH_RELATIVE * longest).copied();
        // else the smallest angle between whose sides it lies, else the nearest in reach
        let between = || {
            self.sides.between_sides(mesh, mesh.tets[t], angles, bound).map(|k| (k, p.iter().map(|&v| angles[k].distance(v)).fold(f64::INFINITY, f64::min)))
        };
        let pick = touch.map(|x| (x, false)).or_else(|| between().map(|x| (x, true))).or_else(|| near.iter().min_by(|x, y| x.1.total_cmp(&y.1)).map(|&x| (x, false)));
        let input_angle = pick.map(|((k, d), between_sides)| {
            let a = &angles[k];
            NearAngle { angle: a.clone(), names: a.faces.map(name), distance: d, touches: d <= TOUCH_RELATIVE * longest, between_sides }
        });
        TetPlace {
            tet: t,
            point: c.to_array(),
            min_dihedral_deg: lo,
            max_dihedral_deg: hi,
            radius_edge: re,
            longest_edge: longest,
            nearest_face,
            nearest_edge,
            input_angle,
            narrow_face: self.narrow_face(mesh.tets[t], longest, name),
        }
    }

    /// The narrowest face at the vertices of `tet` (longest edge `longest`) if it is narrow
    /// ([`NARROW_RELATIVE`]); ties keep the smallest tag.
    fn narrow_face(&self, tet: [u32; 4], longest: f64, name: &dyn Fn(FaceId) -> Option<String>) -> Option<NarrowFace> {
        let mut best: Option<(f64, FaceId)> = None;
        for &v in &tet {
            for &f in self.sides.of(v) {
                let Ok(k) = self.extents.binary_search_by_key(&f, |x| x.0) else { continue };
                let (_, area, perimeter) = self.extents[k];
                let width = 2.0 * area / perimeter;
                if width.is_finite() && best.is_none_or(|(w, g)| width < w || (width == w && f < g)) {
                    best = Some((width, f));
                }
            }
        }
        best.filter(|&(w, _)| w < NARROW_RELATIVE * longest).map(|(width, face)| NarrowFace { face, name: name(face), width })
    }
}

/// Whether the tet with corners `p` touches one of `angles` (smallest first, as
/// [`crate::quality::input_angles::small_input_angles`] lists them) smaller than `below`
/// degrees: one of its vertices lies on the angle's edge or vertex, within [`TOUCH_RELATIVE`]
/// of the tet's longest edge. There the input itself bounds the tet's angles.
pub fn touches_angle_below(p: &[DVec3; 4], angles: &[InputAngle], below: f64) -> bool {
    let longest = TET_EDGES.iter().map(|[i, j]| p[*i].distance(p[*j])).fold(0.0, f64::max);
    angles.iter().take_while(|a| a.angle_deg < below).any(|a| p.iter().any(|&v| a.distance(v) <= TOUCH_RELATIVE * longest))
}

/// A length or coordinate with six significant digits, without trailing zeros.
pub fn fmt_num(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x == 0.0 {
        return "0".into();
    }
    let digits = (5 - x.abs().log10().floor() as i32).clamp(0, 15) as usize;
    let s = format!("{x:.digits$}");
    let s = if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s };
    if s == "-0" { "0".into() } else { s }
}

/// `(x, y, z)` with [`fmt_num`].
pub fn fmt_point(p: [f64; 3]) -> String {
    format!("({}, {}, {})", fmt_num(p[0]), fmt_num(p[1]), fmt_num(p[2]))
}

fn face_text(f: FaceId, name: &Option<String>) -> String {
    match name {
        Some(n) => format!("{} \"{n}\"", f.0),
        None => f.0.to_string(),
    }
}

impl TetPlace {
    /// The description as `(label, text)` lines: the tet (labelled "worst tet": reports
    /// locate the worst), its nearest face and feature edge, the input angle in reach.
    pub fn lines(&self) -> Vec<(&'static str, String)> {
        let mut out = vec![(
            "worst tet",
            format!(
                "#{} at {}: min dihedral {}°, max dihedral {}°, radius-edge {}, longest edge {}",
                self.tet,
                fmt_point(self.point),
                fmt_num(self.min_dihedral_deg),
                fmt_num(self.max_dihedral_deg),
                fmt_num(self.radius_edge),
                fmt_num(self.longest_edge)
            ),
        )];
        if let Some(f) = &self.nearest_face {
            out.push(("nearest face", format!("{} at {}, {} away", face_text(f.face, &f.name), fmt_point(f.point), fmt_num(f.distance))));
        }
        match &self.nearest_edge {
            Some(e) if e.faces[0] == e.faces[1] => {
                out.push(("nearest edge", format!("a crease of face {} at {}, {} away", face_text(e.faces[0], &e.names[0]), fmt_point(e.point), fmt_num(e.distance))));
            }
            Some(e) => out.push((
                "nearest edge",
                format!("between faces {} and {} at {}, {} away", face_text(e.faces[0], &e.names[0]), face_text(e.faces[1], &e.names[1]), fmt_point(e.point), fmt_num(e.distance)),
            )),
            None => out.push(("nearest edge", "none (the boundary has no feature edge)".to_string())),
        }
        if let Some(n) = &self.narrow_face {
            out.push((
                "narrow face",
                format!(
                    "{} is {} wide (twice its area over its perimeter), under a tenth of the tet's longest edge: a sliver face of the part, whose triangles no tet beside them spans well; widen it or merge it into a neighbour in the CAD model",
                    face_text(n.face, &n.name),
                    fmt_num(n.width)
                ),
            ));
        }
        if let Some(a) = &self.input_angle {
            let what = match a.angle.kind {
                InputAngleKind::Dihedral => format!(
                    "the input dihedral angle between faces {} and {} at the edge {} to {}",
                    face_text(a.angle.faces[0], &a.names[0]),
                    face_text(a.angle.faces[1], &a.names[1]),
                    fmt_point(a.angle.at[0]),
                    fmt_point(a.angle.at[1])
                ),
                InputAngleKind::Corner => format!("an input corner angle of face {} at {}", face_text(a.angle.faces[0], &a.names[0]), fmt_point(a.angle.at[0])),
            };
            if a.touches {
                out.push(("input angle", format!("{}° is {what}; the tet touches it", fmt_num(a.angle.angle_deg))));
            } else if a.between_sides {
                out.push(("input angle", format!("none that the tet touches; it lies between the two sides of {}°, {what}, {} from the tet", fmt_num(a.angle.angle_deg), fmt_num(a.distance))));
            } else {
                out.push(("input angle", format!("none that the tet touches; the nearest small one: {}°, {what}, {} from the tet", fmt_num(a.angle.angle_deg), fmt_num(a.distance))));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quality::input_angles::small_input_angles;

    #[test]
    fn numbers_print_six_significant_digits() {
        assert_eq!(fmt_num(0.0), "0");
        assert_eq!(fmt_num(1.0), "1");
        assert_eq!(fmt_num(0.311345678), "0.311346");
        assert_eq!(fmt_num(12345.678), "12345.7");
        assert_eq!(fmt_num(-2.5e-9), "-0.0000000025");
        assert_eq!(fmt_point([1.0, -0.5, 100.0]), "(1, -0.5, 100)");
    }

    #[test]
    fn a_tet_at_a_knife_edge_names_its_faces_edge_and_angle() {
        // one tet with a 3° dihedral angle at the edge from (0,0,0) to (0,0,1), each of its
        // faces a tag of its own
        let a = 3f64.to_radians();
        let vertices = vec![DVec3::ZERO, DVec3::X, DVec3::new(a.cos(), a.sin(), 0.0), DVec3::Z];
        let tets = vec![[0, 1, 2, 3]];
        let boundary = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
        let face_tags = [1, 3, 4, 5].map(FaceId).to_vec();
        let mesh = TetMesh { vertices: vertices.clone(), tets, region_tags: vec![Default::default()], boundary: boundary.clone(), face_tags: face_tags.clone(), ..Default::default() };
        let surface = crate::mesh::TriSurface { vertices, triangles: boundary, face_tags, ..Default::default() };
        let angles = small_input_angles(&surface, 10.0, true);
        let index = BoundaryIndex::new(&mesh);
        assert_eq!(index.features.len(), 6);
        let names = |f: FaceId| match f.0 {
            3 => Some("side_a".to_string()),
            5 => Some("side_c".to_string()),
            _ => None,
        };
        let place = index.locate(&mesh, 0, &angles, 10.0, &names);
        assert!(place.min_dihedral_deg < 3.0 + 1e-9);
        let f = place.nearest_face.as_ref().unwrap();
        assert!(f.distance < 0.25);
        let e = place.nearest_edge.as_ref().unwrap();
        assert!(e.distance < 0.5);
        // the knife edge (3°) is listed; the smallest angle the tet touches is the corner of
        // its slanted face at the apex (2.12°)
        assert!(angles.iter().any(|x| x.kind == InputAngleKind::Dihedral && (x.angle_deg - 3.0).abs() < 1e-9 && x.faces == [FaceId(3), FaceId(5)]), "{angles:?}");
        let near = place.input_angle.as_ref().expect("the knife edge is in reach");
        assert!(near.touches && near.angle == angles[0], "{near:?}");
        let text: Vec<String> = place.lines().into_iter().map(|(l, t)| format!("{l}: {t}")).collect();
        assert!(text.iter().any(|l| l.starts_with("input angle: 2.1212°") && l.ends_with("the tet touches it")), "{text:?}");
        // the nearest face is one of the two at the knife edge (the centroid is as near both)
        assert!(text.iter().any(|l| l.starts_with("nearest face: 3 \"side_a\"") || l.starts_with("nearest face: 5 \"side_c\"")), "{text:?}");
    }

    #[test]
    fn a_tet_beside_a_sliver_face_names_it_and_its_width() {
        // a 2 × 2 × 2 Kuhn cube whose middle plane x = 0.5 is moved to x = 0.02: the bottom's
        // strip 0 < x < 0.02 is a face of its own, 0.02 wide, under tets a unit long
        let mut mesh = crate::mesh::shapes::kuhn_cube(2, 0.0, 1);
        for p in &mut mesh.vertices {
            if (p.x - 0.5).abs() < 1e-12 {
                p.x = 0.02;
            }
        }
        crate::mesh::shapes::tag_hull(&mut mesh, |n, m| if n.z < -0.5 && m.x < 0.02 { 7 } else { crate::mesh::shapes::side_tag(n) });
        assert_eq!(mesh.validate(), Ok(()));
        let index = BoundaryIndex::new(&mesh);
        let strip = |t: &[u32; 4]| t.iter().filter(|&&v| mesh.vertices[v as usize].x < 0.5 && mesh.vertices[v as usize].z < 0.5).count() >= 3;
        let t = (0..mesh.tets.len()).find(|&t| strip(&mesh.tets[t]) && mesh.tets[t].iter().any(|&v| index.sides().of(v).contains(&FaceId(7)))).expect("a tet on the strip");
        let name = |f: FaceId| (f.0 == 7).then(|| "step".to_string());
        let place = index.locate(&mesh, t, &[], 10.0, &name);
        let n = place.narrow_face.as_ref().expect("the strip is named");
        assert_eq!(n.face, FaceId(7));
        assert!((n.width - 2.0 * 0.02 / 2.04).abs() < 1e-12, "{}", n.width);
        let text: Vec<String> = place.lines().into_iter().map(|(l, t)| format!("{l}: {t}")).collect();
        assert!(text.iter().any(|l| l.starts_with("narrow face: 7 \"step\" is 0.0196078 wide")), "{text:?}");
        // a tet of the upper half touches no narrow face
        let far = (0..mesh.tets.len()).find(|&t| mesh.tets[t].iter().all(|&v| mesh.vertices[v as usize].z > 0.25)).expect("a tet off the strip");
        assert_eq!(index.locate(&mesh, far, &[], 10.0, &name).narrow_face, None);
    }
}
