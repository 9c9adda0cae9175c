//! Surface sizing before volume meshing (when the boundary may change): input triangles
//! larger than the size field wants are subdivided, conformingly, each piece keeping its
//! tag, so that the volume mesh is graded to the size at the boundary too.
//!
//! Every input edge is cut into equal pieces no longer than the size at its midpoint (the
//! same points for both triangles on it); each triangle is then meshed in its own plane by
//! spade's constrained Delaunay refinement (angle limit 25°, area from the size), with its
//! sides kept as they were cut. Triangles already small enough are copied unchanged.

use crate::core::SizeField;
use crate::mesh::TriSurface;
use glam::{DVec2, DVec3};
use rustc_hash::FxHashMap;
use spade::{AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation};

/// The most pieces one input edge is cut into, and the most points one triangle gets: bounds
/// on the work for a size far below the model's.
const MAX_EDGE_PIECES: usize = 4096;
const MAX_TRIANGLE_POINTS: usize = 200_000;

/// `surface` with its triangles subdivided to `size` (capped by `max_size`). Returns `None`
/// when no triangle needs it.
pub(crate) fn presize(surface: &TriSurface, size: &dyn SizeField, max_size: Option<f64>) -> Option<TriSurface> {
    let h = |p: DVec3| {
        let mut s = size.size_at(p);
        if let Some(m) = max_size {
            s = s.min(m);
        }
        if s.is_finite() && s > 0.0 { s } else { f64::INFINITY }
    };
    let v = &surface.vertices;
    // pieces per edge
    let mut pieces: FxHashMap<(u32, u32), usize> = FxHashMap::default();
    for t in &surface.triangles {
        for k in 0..3 {
            let (a, b) = (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]));
            pieces.entry((a, b)).or_insert_with(|| {
                let (pa, pb) = (v[a as usize], v[b as usize]);
                let n = (pa.distance(pb) / h((pa + pb) * 0.5)).ceil();
                if n.is_finite() { (n as usize).clamp(1, MAX_EDGE_PIECES) } else { 1 }
            });
        }
    }
    let needs = |t: &[u32; 3]| -> bool {
        let p = t.map(|i| v[i as usize]);
        let area = (p[1] - p[0]).cross(p[2] - p[0]).length() * 0.5;
        let hh = h((p[0] + p[1] + p[2]) / 3.0);
        (0..3).any(|k| pieces[&(t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))] > 1) || area > 0.6 * hh * hh
    };
    if !surface.triangles.iter().any(needs) {
        return None;
    }
    let mut out = TriSurface { vertices: v.clone(), triangles: Vec::new(), face_tags: Vec::new(), tag_names: surface.tag_names.clone() };
    // the inner points of every cut edge, from its smaller vertex to its larger
    let mut edge_points: FxHashMap<(u32, u32), Vec<u32>> = FxHashMap::default();
    let mut keys: Vec<(u32, u32)> = pieces.keys().copied().collect();
    keys.sort_unstable();
    for (a, b) in keys {
        let n = pieces[&(a, b)];
        let (pa, pb) = (v[a as usize], v[b as usize]);
        let ids = (1..n)
            .map(|k| {
                out.vertices.push(pa + (pb - pa) * (k as f64 / n as f64));
                (out.vertices.len() - 1) as u32
            })
            .collect();
        edge_points.insert((a, b), ids);
    }
    for (t, &tag) in surface.triangles.iter().zip(&surface.face_tags) {
        if !needs(t) {
            out.triangles.push(*t);
            out.face_tags.push(tag);
            continue;
        }
        // the boundary loop of the triangle, in its order
        let mut ring: Vec<u32> = Vec::new();
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            ring.push(a);
            let inner = &edge_points[&(a.min(b), a.max(b))];
            if a < b {
                ring.extend(inner.iter().copied());
            } else {
                ring.extend(inner.iter().rev().copied());
            }
        }
        let [pa, pb, pc] = t.map(|i| v[i as usize]);
        let normal = (pb - pa).cross(pc - pa);
        let e1 = (pb - pa).normalize_or_zero();
        let e2 = normal.normalize_or_zero().cross(e1);
        let to2 = |p: DVec3| {
            let d = p - pa;
            DVec2::new(d.dot(e1), d.dot(e2))
        };
        let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> = ConstrainedDelaunayTriangulation::new();
        let mut ids: Vec<u32> = Vec::new();
        let mut handles = Vec::with_capacity(ring.len());
        let mut failed = false;
        for &r in &ring {
            let q = to2(out.vertices[r as usize]);
            match cdt.insert(Point2::new(q.x, q.y)) {
                Ok(hd) => {
                    if hd.index() == ids.len() {
                        ids.push(r);
                    }
                    handles.push(hd);
                }
                Err(_) => failed = true,
            }
        }
        if !failed {
            for i in 0..handles.len() {
                let (x, y) = (handles[i], handles[(i + 1) % handles.len()]);
                if x != y && cdt.can_add_constraint(x, y) {
                    cdt.add_constraint(x, y);
                } else {
                    failed = true;
                }
            }
        }
        if failed {
            // degenerate in its plane (a sliver triangle): leave it, with its sides cut
            fan(&ring, tag, &mut out);
            continue;
        }
        let hh = h((pa + pb + pc) / 3.0);
        let params = RefinementParameters::<f64>::new()
            .with_angle_limit(AngleLimit::from_deg(25.0))
            .with_max_allowed_area(0.5 * hh * hh)
            .keep_constraint_edges()
            .exclude_outer_faces(true)
            .with_max_additional_vertices(MAX_TRIANGLE_POINTS);
        let result = cdt.refine(params);
        for vh in cdt.vertices().skip(ids.len()) {
            let p = vh.position();
            out.vertices.push(pa + e1 * p.x + e2 * p.y);
            ids.push((out.vertices.len() - 1) as u32);
        }
        for face in cdt.inner_faces() {
            if result.excluded_faces.contains(&face.fix()) {
                continue;
            }
            let tri = face.vertices().map(|x| ids[x.fix().index()]);
            out.triangles.push(tri);
            out.face_tags.push(tag);
        }
    }
    Some(out)
}

/// The triangle given by its boundary loop `ring` (corners and side points), fanned from a
/// new point at its centroid: used only where the plane mapping failed.
fn fan(ring: &[u32], tag: crate::core::FaceId, out: &mut TriSurface) {
    let c = ring.iter().map(|&i| out.vertices[i as usize]).sum::<DVec3>() / ring.len() as f64;
    out.vertices.push(c);
    let ci = (out.vertices.len() - 1) as u32;
    for i in 0..ring.len() {
        out.triangles.push([ci, ring[i], ring[(i + 1) % ring.len()]]);
        out.face_tags.push(tag);
    }
}
