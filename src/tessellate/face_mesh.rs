//! Meshing one face in its parameter domain with spade's constrained Delaunay triangulation.
//!
//! Parameters are scaled by the surface's mean speeds (`|∂S/∂u|`, `|∂S/∂v|`) so that the
//! triangulation sees roughly isometric coordinates (radians against millimetres otherwise).

use super::TessellateOptions;
use super::edge_points::EdgePoints;
use super::face_error::FaceError;
use super::improve::Point;
use super::face_vertices::FaceVertices;
use super::surface_scales::surface_bends;
use super::uv_cdt::{V, constraint_parity};
use super::uv_loops::uv_loops;
use crate::cad::brep::Model;
use crate::cad::geom::Surface;
use crate::core::cdt;
use crate::core::ids::NONE;
use crate::core::{FaceId, SizeField};
use glam::DVec2;
use spade::handles::FixedVertexHandle;
use spade::{ConstrainedDelaunayTriangulation, Triangulation};

/// Even-odd test of `p` against all loops.
fn inside(loops: &[Vec<DVec2>], p: DVec2) -> bool {
    let mut odd = false;
    for l in loops {
        let n = l.len();
        for i in 0..n {
            let (a, b) = (l[i], l[(i + 1) % n]);
            if (a.y > p.y) != (b.y > p.y) {
                let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if p.x < x {
                    odd = !odd;
                }
            }
        }
    }
    odd
}

/// One face's triangulation: 3D triangles and the same triangles in the face's parameter
/// domain, with the boundary segments, for quadrature over the exact surface
/// ([`super::quadrature`]).
#[derive(Clone, Debug, Default)]
pub struct FaceMesh {
    /// Triangles with global vertex indices, oriented outward by the face's sense.
    pub triangles: Vec<[u32; 3]>,
    /// The parameter-domain triangles, counter-clockwise in `(u, v)` (periodic parameters
    /// unwrapped consistently within a triangle): `uv[k]` is `triangles[k]` for
    /// `k < triangles.len()`; the rest are triangles of the domain that collapse to a line or
    /// point in 3D (along a pole), kept so that the domain is complete.
    pub uv: Vec<[DVec2; 3]>,
    /// Boundary segments of the parameter-domain triangulation: `(a, b)` global vertex
    /// indices and their `(u, v)`, directed with the face on the left in `(u, v)`.
    pub boundary: Vec<([u32; 2], [DVec2; 2])>,
}

/// The triangles of one face, with global vertex indices (new interior vertices appended to
/// `vertices`, the face's own), oriented outward by the face's sense.
///
/// # Errors
/// Why the face could not be meshed: crossing boundary segments, or a message.
#[allow(clippy::too_many_arguments)]
pub fn mesh_face(model: &Model, fid: FaceId, edges: &[EdgePoints], tol: f64, max_straight: f64, opts: &TessellateOptions, size: Option<&dyn SizeField>, vertices: &mut FaceVertices) -> Result<FaceMesh, FaceError> {
    let face = model.face(fid);
    let surf = model.surface(face.surface);
    let loops = uv_loops(model, fid, edges, tol, max_straight, size, vertices)?;
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for (p, _) in loops.iter().flatten() {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return Err(FaceError::NonFiniteParameters);
    }
    let (su, sv, [ku, kv]) = surface_bends(surf, lo, hi);
    // interior grid steps: from the largest bend, or on a cylinder without a size field along
    // each parameter from its own bend (its generators are straight: one step along them)
    let ruled = matches!(surf, Surface::Cylinder(_)) && size.is_none();
    let ext = (hi - lo) * DVec2::new(su, sv);
    let (ku, kv) = if ruled { (ku, kv) } else { (ku.max(kv), ku.max(kv)) };
    let step = |k: f64, len: f64| if k > 0.0 { (8.0 * tol / k).sqrt() } else { len };
    // (along the generators at most four pieces of a straight edge on a curved face: the
    // triangles stay shorter than the sides they lie along, a cylinder cut by its own seam
    // has rows along it)
    let along = if max_straight > 0.0 { 4.0 * max_straight } else { f64::INFINITY };
    let (hu, hv) = if ruled { (step(ku, ext.x).min(ext.x).min(along), step(kv, ext.y).min(ext.y).min(along)) } else { (step(ku, ext.x), step(kv, ext.y)) };
    let steps = |len: f64, h: f64| if h > 0.0 { ((len / h).ceil() as usize).clamp(1, opts.max_grid) } else { 1 };
    let (nu, nv) = (steps(ext.x, hu), steps(ext.y, hv));
    // without a size field, spade triangulates a cylinder in a metric where those steps are
    // equal: the triangles stretch along its straight generators (it becomes a strip between
    // its two circles, as long as it is) instead of filling them with points. Not with a
    // size field (it needs lengths near 3D lengths), nor on other surfaces (a cone's apex, an
    // extrusion's pole: the fans there fold; wing_fuselage.step)
    let (su, sv) = match size {
        None if ruled && hu > 0.0 && hv > 0.0 => {
            let h = hu.min(hv);
            (su * h / hu, sv * h / hv)
        }
        _ => (su, sv),
    };
    // flushed as spade will see them (`core::cdt`'s guard), for the inside tests too
    let scale = |p: DVec2| DVec2::new(cdt::flush(p.x * su), cdt::flush(p.y * sv));
    let scaled: Vec<Vec<DVec2>> = loops.iter().map(|l| l.iter().map(|(p, _)| scale(*p)).collect()).collect();

    let mut tri: ConstrainedDelaunayTriangulation<V> = ConstrainedDelaunayTriangulation::new();
    let mut handles: Vec<Vec<FixedVertexHandle>> = Vec::new();
    for (l, sl) in loops.iter().zip(&scaled) {
        let mut hs = Vec::with_capacity(l.len());
        for ((uv, id), s) in l.iter().zip(sl) {
            let h = cdt::insert(&mut tri, *s, |p| V { p, id: Some(*id), uv: *uv, p3: vertices[*id as usize] }).map_err(|e| FaceError::Insert { point: "boundary point", reason: e.to_string() })?;
            hs.push(h);
        }
        handles.push(hs);
    }
    for hs in &handles {
        let n = hs.len();
        for i in 0..n {
            let (a, b) = (hs[i], hs[(i + 1) % n]);
            if a == b {
                continue;
            }
            if tri.try_add_constraint(a, b).is_empty() && !tri.exists_constraint(a, b) {
                let ids: Vec<Vec<u32>> = loops.iter().map(|l| l.iter().map(|(_, id)| *id).collect()).collect();
                let mut segs = super::crossings::crossing_segments(&scaled, &ids);
                if segs.is_empty() {
                    // spade refused it for a reason the exact test does not see: this segment
                    let (ia, ib) = (tri.vertex(a).data().id, tri.vertex(b).data().id);
                    segs.extend(ia.zip(ib).map(|(x, y)| [x, y]));
                }
                return Err(FaceError::Crossing(segs));
            }
        }
    }
    // interior grid where the surface bends, spaced along each parameter by its own bend
    if ku.max(kv) > 0.0 {
        let (slo, shi) = (scale(lo), scale(hi));
        if nu >= 2 || nv >= 2 {
            let (nu, nv) = (nu.max(1), nv.max(1));
            let cell = DVec2::new((shi.x - slo.x) / nu as f64, (shi.y - slo.y) / nv as f64);
            let clear = Clearance::new(&scaled, slo, cell, nu, nv);
            for i in 0..nu {
                for j in 0..nv {
                    let s = DVec2::new(slo.x + (shi.x - slo.x) * (i as f64 + 0.5) / nu as f64, slo.y + (shi.y - slo.y) * (j as f64 + 0.5) / nv as f64);
                    // a grid point on or next to a boundary segment would split it (spade
                    // splits constraints through inserted points) or make slivers
                    if inside(&scaled, s) && clear.far(s, 0.3 * cell.min_element()) {
                        let uv = DVec2::new(s.x / su, s.y / sv);
                        cdt::insert(&mut tri, s, |p| V { p, id: None, uv, p3: surf.point(uv.x, uv.y) }).map_err(|e| FaceError::Insert { point: "interior point", reason: e.to_string() })?;
                    }
                }
            }
        }
    }
    super::refine::refine(&mut tri, surf, tol, opts)?;
    if let Some(size) = size {
        // well-shaped triangles of the local size, after the deviation's refinement, whose
        // centroids make thin triangles that this mends
        super::sizing::refine_face(&mut tri, surf, su, sv, size);
    }
    // the triangles inside the loops (an odd number of constraint edges crossed from the
    // outside: exact, unlike a point-in-polygon test on thin triangles along nearly straight
    // boundaries), their boundary segments, as points and indices
    let inside_faces = constraint_parity(&tri);
    let mut pts: Vec<Point> = tri.vertices().map(|v| {
        let d = v.data();
        Point { s: DVec2::new(d.p.x, d.p.y), uv: d.uv, p3: d.p3, id: d.id }
    }).collect();
    let mut tris: Vec<[u32; 3]> = Vec::new();
    let mut segments: Vec<[u32; 2]> = Vec::new();
    for f in tri.inner_faces() {
        if !inside_faces[f.fix().index()] {
            continue;
        }
        // boundary segments: constraint edges with the outside (or the outer face) beyond
        for e in f.adjacent_edges() {
            let beyond = e.rev().face().as_inner().is_none_or(|g| !inside_faces[g.fix().index()]);
            if e.is_constraint_edge() && beyond {
                segments.push([e.from().fix().index() as u32, e.to().fix().index() as u32]);
            }
        }
        tris.push(f.vertices().map(|v| v.fix().index() as u32));
    }
    let removed = match size {
        Some(size) => {
            let cos_max = (2.0 * opts.max_angle_deg).to_radians().cos();
            super::improve::improve(&mut pts, &mut tris, &segments, surf, su, sv, size, tol, cos_max).removed
        }
        None => vec![false; pts.len()],
    };
    // the shape improvement takes a triangle turned up to 90° from the surface: an ear flat
    // in (u, v) across an edge's bulge passes it
    super::flat_ears::flip_flat_ears(&pts, &mut tris, &segments);
    // lift: boundary points have their global index, the others get one
    let ids: Vec<u32> = pts.iter().zip(&removed).map(|(p, &gone)| match p.id {
        Some(id) => id,
        None if gone => NONE,
        None => vertices.push(p.p3),
    }).collect();
    let mut out = FaceMesh::default();
    for &[a, b] in &segments {
        out.boundary.push(([ids[a as usize], ids[b as usize]], [pts[a as usize].uv, pts[b as usize].uv]));
    }
    for t in &tris {
        let uv = t.map(|i| pts[i as usize].uv);
        let [a, b, cc] = t.map(|i| ids[i as usize]);
        if a == b || b == cc || a == cc {
            // a triangle collapsed in 3D (along a pole line): zero area, but part of the domain
            out.uv.push(uv);
            out.triangles.push([NONE; 3]);
            continue;
        }
        out.uv.push(uv);
        out.triangles.push(if face.same_sense { [a, b, cc] } else { [a, cc, b] });
    }
    // collapsed triangles: kept in the domain for quadrature only
    let keep: Vec<bool> = out.triangles.iter().map(|t| t[0] != NONE).collect();
    let domain_only: Vec<[DVec2; 3]> = out.uv.iter().zip(&keep).filter(|(_, k)| !**k).map(|(u, _)| *u).collect();
    let mut k = 0;
    out.triangles.retain(|t| t[0] != NONE);
    out.uv.retain(|_| {
        k += 1;
        keep[k - 1]
    });
    out.uv.extend(domain_only);
    if out.triangles.is_empty() {
        return Err(FaceError::NoTriangle);
    }
    Ok(out)
}

/// Boundary segments bucketed on the interior grid's cells, for the distance test of grid
/// points.
struct Clearance<'a> {
    loops: &'a [Vec<DVec2>],
    lo: DVec2,
    cell: DVec2,
    nu: usize,
    nv: usize,
    /// Per cell: (loop, segment) pairs whose box, grown by one cell, covers it.
    buckets: Vec<Vec<(u32, u32)>>,
}

impl<'a> Clearance<'a> {
    fn new(loops: &'a [Vec<DVec2>], lo: DVec2, cell: DVec2, nu: usize, nv: usize) -> Clearance<'a> {
        let mut buckets = vec![Vec::new(); nu * nv];
        let idx = |p: f64, lo: f64, c: f64, n: usize| (((p - lo) / c).floor().max(0.0) as usize).min(n - 1);
        for (li, l) in loops.iter().enumerate() {
            let n = l.len();
            for si in 0..n {
                let (a, b) = (l[si], l[(si + 1) % n]);
                let (mn, mx) = (a.min(b) - cell, a.max(b) + cell);
                let (i0, i1) = (idx(mn.x, lo.x, cell.x, nu), idx(mx.x, lo.x, cell.x, nu));
                let (j0, j1) = (idx(mn.y, lo.y, cell.y, nv), idx(mx.y, lo.y, cell.y, nv));
                for i in i0..=i1 {
                    for j in j0..=j1 {
                        buckets[i * nv + j].push((li as u32, si as u32));
                    }
                }
            }
        }
        Clearance { loops, lo, cell, nu, nv, buckets }
    }

    /// True when `p` is farther than `d` from every boundary segment.
    fn far(&self, p: DVec2, d: f64) -> bool {
        let i = (((p.x - self.lo.x) / self.cell.x).floor().max(0.0) as usize).min(self.nu - 1);
        let j = (((p.y - self.lo.y) / self.cell.y).floor().max(0.0) as usize).min(self.nv - 1);
        self.buckets[i * self.nv + j].iter().all(|&(li, si)| {
            let l = &self.loops[li as usize];
            let (a, b) = (l[si as usize], l[(si as usize + 1) % l.len()]);
            let ab = b - a;
            let t = if ab.length_squared() > 0.0 { ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
            (a + t * ab - p).length() > d
        })
    }
}
