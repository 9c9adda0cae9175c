//! STEP topology (ISO 10303-42 §5) → the arena: solids, shells, faces, loops, edges and
//! vertices. A face that cannot be converted (unsupported surface, malformed bound) is left
//! out of its shell and reported; an edge whose curve cannot be converted keeps its vertices
//! and is reported (its curve is `None`).

use super::convert::{Args, Converter, Fail, R, drop_entity};
use crate::cad::brep::{Coedge, Edge, EntityRef, Face, Loop, Shell, Solid, Vertex};
use crate::cad::geom::{Curve, Interval, wrap_into};
use crate::core::FaceId;
use glam::DVec3;

impl Converter<'_> {
    /// `MANIFOLD_SOLID_BREP`, `BREP_WITH_VOIDS` or `FACETED_BREP`.
    pub(super) fn solid(&mut self, id: u64) -> R<()> {
        let e = self.entity(id)?;
        let name = e.type_name().to_string();
        let a = Args::of(e, &name)?;
        let outer = a.id(1)?;
        let voids = if name == "BREP_WITH_VOIDS" { a.ids(2)? } else { Vec::new() };
        let inst = self.solid_instances.entry(id).or_insert(0);
        let instance = *inst;
        *inst += 1;
        let solid = self.model.solids.len() as u32;
        self.model.solids.push(Solid { shells: Vec::new(), name: a.name(0), instance, source: EntityRef(id) });
        let s = self.shell(outer, Some(solid), false, false)?;
        self.model.solids[solid as usize].shells.push(s);
        for v in voids {
            let r = self.shell(v, Some(solid), true, false);
            if let Some(s) = self.soft(r)? {
                self.model.solids[solid as usize].shells.push(s);
            }
        }
        Ok(())
    }

    /// `SHELL_BASED_SURFACE_MODEL`: its shells, without a solid.
    pub(super) fn surface_model(&mut self, id: u64) -> R<()> {
        let e = self.entity(id)?;
        let a = Args::of(e, "SHELL_BASED_SURFACE_MODEL")?;
        for s in a.ids(1)? {
            let r = self.shell(s, None, false, false);
            self.soft(r)?;
        }
        Ok(())
    }

    /// `CLOSED_SHELL`, `OPEN_SHELL` or their `ORIENTED_` forms; returns its index.
    pub(super) fn shell(&mut self, id: u64, solid: Option<u32>, void: bool, flip: bool) -> R<u32> {
        let e = self.entity(id)?;
        let name = e.type_name();
        if name == "ORIENTED_CLOSED_SHELL" || name == "ORIENTED_OPEN_SHELL" {
            let a = Args::of(e, name)?;
            let inner = a.id(2)?;
            let flip = flip ^ !a.bool_or(3, true);
            return self.within(id, |c| c.shell(inner, solid, void, flip));
        }
        if name != "CLOSED_SHELL" && name != "OPEN_SHELL" {
            return Err(drop_entity(e, "expected CLOSED_SHELL or OPEN_SHELL"));
        }
        let a = Args::of(e, name)?;
        let faces = a.ids(1)?;
        let shell = self.model.shells.len() as u32;
        self.model.shells.push(Shell { faces: Vec::new(), closed: name == "CLOSED_SHELL", solid, void, source: EntityRef(id) });
        for f in faces {
            let r = self.face(f, shell, flip);
            if let Some(fid) = self.soft(r)? {
                self.model.shells[shell as usize].faces.push(fid);
            }
        }
        Ok(shell)
    }

    /// `ADVANCED_FACE`, `FACE_SURFACE` or `ORIENTED_FACE`.
    fn face(&mut self, id: u64, shell: u32, flip: bool) -> R<FaceId> {
        let e = self.entity(id)?;
        let name = e.type_name();
        if name == "ORIENTED_FACE" {
            let a = Args::of(e, name)?;
            let inner = a.id(2)?;
            let flip = flip ^ !a.bool_or(3, true);
            return self.within(id, |c| c.face(inner, shell, flip));
        }
        let rec = if e.has("ADVANCED_FACE") {
            "ADVANCED_FACE"
        } else if e.has("FACE_SURFACE") {
            "FACE_SURFACE"
        } else {
            return Err(drop_entity(e, "unsupported face type"));
        };
        let a = Args::of(e, rec)?;
        let bounds = a.ids(1)?;
        let geometry = a.id(2)?;
        let same_sense = a.bool_or(3, true) ^ flip;
        let surface = match self.surface_index(geometry) {
            Ok(s) => s,
            Err(Fail::Drop(d)) => {
                let why = format!("its surface {} ({}) was not converted: {}", d.id, d.kind, d.why);
                return Err(drop_entity(e, why));
            }
            Err(f) => return Err(f),
        };
        let fid = FaceId::from_index(self.model.faces.len());
        let mut loops = Vec::with_capacity(bounds.len());
        for b in bounds {
            let be = self.entity(b)?;
            let outer = be.has("FACE_OUTER_BOUND");
            let bname = if outer { "FACE_OUTER_BOUND" } else { "FACE_BOUND" };
            let ba = Args::of(be, bname)?;
            let lp = self.loop_(ba.id(1)?, fid, outer, ba.bool_or(2, true)).map_err(|f| match f {
                Fail::Drop(d) => drop_entity(e, format!("bound {}: {} {}: {}", b, d.kind, d.id, d.why)),
                f => f,
            })?;
            loops.push(lp);
        }
        // a single bound is the outer one; put the outer one first
        if loops.len() == 1 {
            let l = loops[0];
            self.model.loops[l as usize].outer = true;
        }
        if let Some(k) = loops.iter().position(|&l| self.model.loops[l as usize].outer) {
            loops[..=k].rotate_right(1);
        }
        self.model.faces.push(Face { surface, same_sense, loops, shell, name: a.name(0), colour: None, source: EntityRef(id) });
        Ok(fid)
    }

    /// `EDGE_LOOP` or `VERTEX_LOOP`; returns its index.
    fn loop_(&mut self, id: u64, face: FaceId, outer: bool, orientation: bool) -> R<u32> {
        let e = self.entity(id)?;
        let mut lp = Loop { face, outer, orientation, coedges: Vec::new(), vertex: None, source: EntityRef(id) };
        match e.type_name() {
            "EDGE_LOOP" => {
                let a = Args::of(e, "EDGE_LOOP")?;
                for oe in a.ids(1)? {
                    let oee = self.entity(oe)?;
                    let (edge, forward) = if oee.type_name() == "ORIENTED_EDGE" {
                        let oa = Args::of(oee, "ORIENTED_EDGE")?;
                        (oa.id(3)?, oa.bool_or(4, true))
                    } else {
                        (oe, true)
                    };
                    let ei = self.edge(edge)?;
                    lp.coedges.push(Coedge { edge: ei, forward });
                }
                if lp.coedges.is_empty() {
                    return Err(drop_entity(e, "empty edge loop"));
                }
            }
            "VERTEX_LOOP" => {
                let a = Args::of(e, "VERTEX_LOOP")?;
                lp.vertex = Some(self.vertex(a.id(1)?)?);
            }
            _ => return Err(drop_entity(e, "unsupported loop type (fepre reads EDGE_LOOP and VERTEX_LOOP)")),
        }
        self.model.loops.push(lp);
        Ok(self.model.loops.len() as u32 - 1)
    }

    /// `VERTEX_POINT`, placed; cached per instance.
    fn vertex(&mut self, id: u64) -> R<u32> {
        let key = (id, self.ctx.instance);
        if let Some(&v) = self.vertices.get(&key) {
            return Ok(v);
        }
        let e = self.entity(id)?;
        let a = Args::of(e, "VERTEX_POINT")?;
        let p = self.point(a.id(1)?)?;
        let point = self.ctx.place.apply_point(p);
        self.model.vertices.push(Vertex { point, source: EntityRef(id) });
        let k = self.model.vertices.len() as u32 - 1;
        self.vertices.insert(key, k);
        Ok(k)
    }

    /// `EDGE_CURVE`, placed; cached per instance.
    fn edge(&mut self, id: u64) -> R<u32> {
        let key = (id, self.ctx.instance);
        if let Some(&k) = self.edges.get(&key) {
            return Ok(k);
        }
        let e = self.entity(id)?;
        if e.type_name() != "EDGE_CURVE" {
            return Err(drop_entity(e, "unsupported edge type (fepre reads EDGE_CURVE)"));
        }
        let a = Args::of(e, "EDGE_CURVE")?;
        let start = self.vertex(a.id(1)?)?;
        let end = self.vertex(a.id(2)?)?;
        let same = a.bool_or(4, true);
        let curve = self.curve_index(a.id(3)?)?;
        let (ps, pe) = (self.model.vertices[start as usize].point, self.model.vertices[end as usize].point);
        let closed = start == end;
        let (curve, range, same_sense) = match curve {
            Some((c, reversed)) => {
                let same_sense = same ^ reversed;
                let curve = &self.model.curves[c as usize];
                let (a_pt, b_pt) = if same_sense { (ps, pe) } else { (pe, ps) };
                (Some(c), edge_range(curve, a_pt, b_pt, closed), same_sense)
            }
            None => (None, Interval::new(0.0, 1.0), true),
        };
        self.model.edges.push(Edge { curve, start, end, range, same_sense, closed, seam: false, degenerate: false, source: EntityRef(id) });
        let k = self.model.edges.len() as u32 - 1;
        self.edges.insert(key, k);
        Ok(k)
    }
}

/// The increasing curve interval from the point `a` to the point `b` (in the curve's
/// direction); for a closed edge one whole period or the whole bounded domain.
///
/// On a curve closed in space but not periodic (a closed B-spline, its first and last control
/// points one), the joint has two parameters, the domain's ends: an edge that starts there
/// starts at the first, one that ends there ends at the last. (Two edges that split such a
/// curve at a vertex, one of them running from the other vertex to the joint: nearest-point
/// projection gives the joint the first parameter for both, and the two edges took the same
/// half of the curve.)
pub(super) fn edge_range(curve: &Curve, a: DVec3, b: DVec3, closed: bool) -> Interval {
    let dom = curve.domain();
    let ta = curve.project(a);
    if let Some(per) = dom.period {
        let mut tb = wrap_into(curve.project(b), ta, per);
        if closed || tb - ta <= 1e-12 * per {
            tb = ta + per;
        }
        return Interval::new(ta, tb);
    }
    if closed && dom.range.is_bounded() {
        return dom.range;
    }
    let tb = curve.project(b);
    if dom.closed && dom.range.is_bounded() {
        let (lo, hi) = (dom.range.min, dom.range.max);
        let joint = curve.point(lo);
        let size = (1..8).map(|k| curve.point(lo + (hi - lo) * k as f64 / 8.0).distance(joint)).fold(0.0, f64::max);
        let at_joint = |p: DVec3| p.distance(joint) <= JOINT_RELATIVE * size;
        let ta = if at_joint(a) { lo } else { ta };
        let tb = if at_joint(b) { hi } else { tb };
        if ta < tb {
            return Interval::new(ta, tb);
        }
    }
    Interval::new(ta.min(tb), ta.max(tb))
}

/// A vertex lies at the joint of a closed, non-periodic curve when it is within this share of
/// the curve's size (its farthest sample from the joint) of it: STEP vertices sit on their
/// curves to about 1e-7 mm.
const JOINT_RELATIVE: f64 = 1e-6;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cad::geom::BSplineCurve;

    /// A closed, clamped quadratic B-spline about the origin: its first and last control points
    /// are one (the joint, at (1, 0, 0)), its domain [0, 4], not periodic.
    fn closed_spline() -> Curve {
        let p = [(1.0, 0.0), (1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0), (1.0, 0.0)].map(|(x, y)| DVec3::new(x, y, 0.0));
        let knots = vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 4.0];
        Curve::BSpline(BSplineCurve::new(2, knots, p.to_vec(), None).unwrap())
    }

    #[test]
    fn edges_that_split_a_closed_spline_at_a_vertex_take_its_two_parts() {
        let c = closed_spline();
        let dom = c.domain();
        assert!(dom.closed && dom.period.is_none());
        let (joint, mid) = (c.point(0.0), c.point(2.0));
        assert!(joint.distance(DVec3::new(1.0, 0.0, 0.0)) < 1e-12);
        // from the joint to the vertex: the first part; from the vertex to the joint: the rest
        let first = edge_range(&c, joint, mid, false);
        let rest = edge_range(&c, mid, joint, false);
        assert!(first.min.abs() < 1e-9 && (first.max - 2.0).abs() < 1e-6, "{first:?}");
        assert!((rest.min - 2.0).abs() < 1e-6 && (rest.max - 4.0).abs() < 1e-9, "{rest:?}");
        // the whole curve as one closed edge, and an edge between two inner points
        let whole = edge_range(&c, joint, joint, true);
        assert_eq!((whole.min, whole.max), (0.0, 4.0));
        let inner = edge_range(&c, c.point(1.0), c.point(3.0), false);
        assert!((inner.min - 1.0).abs() < 1e-6 && (inner.max - 3.0).abs() < 1e-6, "{inner:?}");
        // a joint vertex written a hair along the curve (1e-8 of its size) is still the joint
        let near = c.point(1e-8);
        let rest = edge_range(&c, mid, near, false);
        assert!((rest.min - 2.0).abs() < 1e-6 && (rest.max - 4.0).abs() < 1e-9, "{rest:?}");
    }
}
