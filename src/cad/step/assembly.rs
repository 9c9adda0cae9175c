//! Shape representations and assemblies: which representations hold the geometry, how they
//! are placed in one another, and the expansion of every placed instance.
//!
//! Representations linked without a transform (`SHAPE_REPRESENTATION_RELATIONSHIP` between a
//! part's `SHAPE_REPRESENTATION` and its `ADVANCED_BREP_SHAPE_REPRESENTATION`) form one
//! group. Groups are placed in groups by `REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION`
//! (with `ITEM_DEFINED_TRANSFORMATION`; the child is `rep_1` unless the
//! `CONTEXT_DEPENDENT_SHAPE_REPRESENTATION`'s `NEXT_ASSEMBLY_USAGE_OCCURRENCE` says `rep_1` is
//! the assembly, as OpenCASCADE checks too) and by `MAPPED_ITEM`s. The roots are the shape
//! representations (`SHAPE_DEFINITION_REPRESENTATION` of a `PRODUCT_DEFINITION_SHAPE`) of the
//! products that are no assembly's component; a file without products has every group that
//! is nobody's child as a root. Representations of validation properties, PMI and
//! presentation (draughting models) are not shapes and are not read. Expanding a root visits each child once per placement, composing the
//! placements, so a part used ten times gives ten solids in world coordinates.

use super::convert::{Args, Converter, Ctx, Fail, R, drop_entity};
use super::error::StepError;
use super::param::Param;
use super::units::context_units;
use crate::cad::brep::{Dropped, EntityRef};
use crate::cad::geom::Rigid;
use rustc_hash::{FxHashMap, FxHashSet};

/// A placement of one representation in another.
struct Placement {
    child: u64,
    /// The relationship entity (for cycle messages).
    via: u64,
    /// Frames: the placement maps `from` (in the child) onto `to` (in the parent).
    from: u64,
    to: u64,
}

/// The representation graph of a file.
pub(super) struct Graph {
    /// Shape representations in file order.
    reps: Vec<u64>,
    /// Identity links (both directions).
    same: FxHashMap<u64, Vec<u64>>,
    /// Placements by parent representation.
    children: FxHashMap<u64, Vec<Placement>>,
    /// Representations placed somewhere (children of a transform or a mapped item).
    placed: FxHashSet<u64>,
    /// Shape representations of products that are no assembly's component (the roots, as
    /// OpenCASCADE takes them), in file order.
    product_roots: Vec<u64>,
}

fn is_shape_rep(e: &super::table::Entity) -> bool {
    e.records.iter().any(|r| r.name.ends_with("SHAPE_REPRESENTATION")) && rep_record(e).is_some()
}

/// The record holding `(name, items, context)`.
fn rep_record(e: &super::table::Entity) -> Option<&super::table::Record> {
    e.records.iter().find(|r| r.name.ends_with("REPRESENTATION") && r.params.len() >= 3 && r.params[1].as_list().is_some())
}

impl Graph {
    pub(super) fn build(c: &Converter<'_>) -> Graph {
        let file = c.file;
        let mut g = Graph { reps: Vec::new(), same: FxHashMap::default(), children: FxHashMap::default(), placed: FxHashSet::default(), product_roots: Vec::new() };
        // representation -> product definition, for the direction check
        let mut pd_of_rep: FxHashMap<u64, u64> = FxHashMap::default();
        let mut product_reps: Vec<u64> = Vec::new();
        let mut component_pds: FxHashSet<u64> = FxHashSet::default();
        for e in file.entities() {
            if is_shape_rep(e) {
                g.reps.push(e.id);
            }
            if let Some(r) = e.records.iter().find(|r| r.name.contains("ASSEMBLY_USAGE_OCCURRENCE") || r.name.as_ref() == "PRODUCT_DEFINITION_USAGE") {
                if let Some(child) = r.params.get(4).and_then(Param::as_ref_id) {
                    component_pds.insert(child);
                }
            }
            if let Some(r) = e.record("SHAPE_DEFINITION_REPRESENTATION") {
                let (Some(pds), Some(rep)) = (r.params.first().and_then(Param::as_ref_id), r.params.get(1).and_then(Param::as_ref_id)) else {
                    continue;
                };
                // only shapes of product definitions (not of validation properties or usages)
                let pd = file.get(pds).and_then(|p| p.record("PRODUCT_DEFINITION_SHAPE")).and_then(|r| r.params.get(2)).and_then(Param::as_ref_id);
                if let Some(pd) = pd.filter(|&pd| file.get(pd).is_some_and(|e| e.records.iter().any(|r| r.name.starts_with("PRODUCT_DEFINITION") && !r.name.contains("USAGE") && !r.name.contains("RELATIONSHIP")))) {
                    pd_of_rep.insert(rep, pd);
                    product_reps.push(rep);
                }
            }
        }
        // relationship -> (parent product definition) from CDSR + NAUO
        let mut parent_pd_of_rel: FxHashMap<u64, u64> = FxHashMap::default();
        for e in file.of_type("CONTEXT_DEPENDENT_SHAPE_REPRESENTATION") {
            let Some(r) = e.record("CONTEXT_DEPENDENT_SHAPE_REPRESENTATION") else { continue };
            let (Some(rel), Some(pds)) = (r.params.first().and_then(Param::as_ref_id), r.params.get(1).and_then(Param::as_ref_id)) else {
                continue;
            };
            let nauo = file.get(pds).and_then(|p| p.record("PRODUCT_DEFINITION_SHAPE")).and_then(|r| r.params.get(2)).and_then(Param::as_ref_id);
            if let Some(n) = nauo.and_then(|n| file.get(n)) {
                if let Some(parent) = n.records.iter().find(|r| r.name.contains("ASSEMBLY_USAGE_OCCURRENCE") || r.name.as_ref() == "PRODUCT_DEFINITION_USAGE" || r.name.as_ref() == "PRODUCT_DEFINITION_RELATIONSHIP").and_then(|r| r.params.get(3)).and_then(Param::as_ref_id) {
                    parent_pd_of_rel.insert(rel, parent);
                }
            }
        }
        for e in file.entities() {
            let Some(rr) = e.record("REPRESENTATION_RELATIONSHIP").or_else(|| e.record("SHAPE_REPRESENTATION_RELATIONSHIP")) else { continue };
            let (Some(r1), Some(r2)) = (rr.params.get(2).and_then(Param::as_ref_id), rr.params.get(3).and_then(Param::as_ref_id)) else { continue };
            match e.record("REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION") {
                None => {
                    g.same.entry(r1).or_default().push(r2);
                    g.same.entry(r2).or_default().push(r1);
                }
                Some(t) => {
                    let Some(idt) = t.params.first().and_then(Param::as_ref_id).and_then(|i| file.get(i)) else { continue };
                    let Some(ir) = idt.record("ITEM_DEFINED_TRANSFORMATION") else { continue };
                    let (Some(i1), Some(i2)) = (ir.params.get(2).and_then(Param::as_ref_id), ir.params.get(3).and_then(Param::as_ref_id)) else {
                        continue;
                    };
                    let reversed = parent_pd_of_rel.get(&e.id).is_some_and(|parent| pd_of_rep.get(&r1) == Some(parent));
                    let p = if reversed {
                        (r1, Placement { child: r2, via: e.id, from: i2, to: i1 })
                    } else {
                        (r2, Placement { child: r1, via: e.id, from: i1, to: i2 })
                    };
                    g.placed.insert(p.1.child);
                    g.children.entry(p.0).or_default().push(p.1);
                }
            }
        }
        g.product_roots = product_reps.into_iter().filter(|r| !pd_of_rep.get(r).is_some_and(|pd| component_pds.contains(pd))).collect();
        for e in file.of_type("REPRESENTATION_MAP") {
            if let Some(rep) = e.record("REPRESENTATION_MAP").and_then(|r| r.params.get(1)).and_then(Param::as_ref_id) {
                g.placed.insert(rep);
            }
        }
        g
    }

    /// The identity-linked group of `rep`, in file order of discovery.
    fn group(&self, rep: u64) -> Vec<u64> {
        let mut out = vec![rep];
        let mut k = 0;
        while k < out.len() {
            if let Some(n) = self.same.get(&out[k]) {
                for &m in n {
                    if !out.contains(&m) {
                        out.push(m);
                    }
                }
            }
            k += 1;
        }
        out
    }
}

impl Converter<'_> {
    /// Converts every root group and, through it, every placed instance.
    pub(super) fn convert_all(&mut self) -> Result<(), StepError> {
        let g = Graph::build(self);
        let mut done: FxHashSet<u64> = FxHashSet::default();
        let mut any_root = false;
        // the shapes of top-level products; without products, every shape representation that
        // is not placed in another
        let by_product = !g.product_roots.is_empty();
        let candidates = if by_product { &g.product_roots } else { &g.reps };
        for &rep in candidates {
            if done.contains(&rep) {
                continue;
            }
            let group = g.group(rep);
            done.extend(group.iter().copied());
            if !by_product && group.iter().any(|r| g.placed.contains(r)) {
                continue;
            }
            any_root = true;
            let r = self.expand(&g, rep, Rigid::IDENTITY);
            match r {
                Ok(()) => {}
                Err(Fail::Drop(d)) => self.report(d),
                Err(Fail::Fatal(e)) => return Err(e),
            }
        }
        if !any_root && !g.reps.is_empty() {
            // every representation is placed in another: a cycle of placements
            let id = g.reps[0];
            return Err(StepError::Cycle {
                path: self.file.path.clone(),
                id,
                line: self.file.get(id).map_or(0, |e| e.line),
                chain: "every shape representation is placed in another one".into(),
            });
        }
        Ok(())
    }

    /// Converts the group of `rep` placed by `place`, then its children.
    fn expand(&mut self, g: &Graph, rep: u64, place: Rigid) -> R<()> {
        let group = g.group(rep);
        self.next_instance += 1;
        let instance = self.next_instance;
        for &r in &group {
            self.within(r, |c| c.representation(g, r, place, instance))?;
        }
        Ok(())
    }

    /// The items of one representation, then the representations placed in it.
    fn representation(&mut self, g: &Graph, rep: u64, place: Rigid, instance: u32) -> R<()> {
        let e = self.entity(rep)?;
        let rr = rep_record(e).ok_or_else(|| drop_entity(e, "not a representation"))?;
        let a = Args { e, params: &rr.params };
        let items = a.ids(1)?;
        let units = a.opt_id(2)?.map(|ctx| context_units(self.file, ctx)).unwrap_or_default();
        let saved = self.ctx;
        self.ctx = Ctx { scale: units.to_mm, angle: units.to_rad, place, instance };
        let r = self.items(g, &items, &units);
        let r = r.and_then(|_| {
            if let Some(children) = g.children.get(&rep) {
                for p in children {
                    let t = self.placement_between(p.from, p.child, p.to, rep)?;
                    let child_place = place.compose(&t);
                    self.within(p.via, |c| c.expand(g, p.child, child_place))?;
                }
            }
            Ok(())
        });
        self.ctx = saved;
        r
    }

    fn items(&mut self, g: &Graph, items: &[u64], units: &crate::cad::brep::Units) -> R<()> {
        for &item in items {
            let e = self.entity(item)?;
            let kind = e.type_name();
            let r = match kind {
                "MANIFOLD_SOLID_BREP" | "BREP_WITH_VOIDS" | "FACETED_BREP" => {
                    self.set_units(units);
                    self.solid(item)
                }
                "SHELL_BASED_SURFACE_MODEL" => {
                    self.set_units(units);
                    self.surface_model(item)
                }
                "MAPPED_ITEM" => self.mapped_item(g, item),
                k if super::read_tessellated::is_tessellated(k) => self.tessellated_item(item, units),
                "AXIS2_PLACEMENT_3D" | "AXIS2_PLACEMENT_2D" | "AXIS1_PLACEMENT" | "CARTESIAN_POINT" | "DIRECTION" => Ok(()),
                _ => {
                    self.report(Dropped {
                        kind: e.display_type(),
                        id: EntityRef(item),
                        why: "a representation item that is not a solid, shell model or tessellated geometry".into(),
                    });
                    Ok(())
                }
            };
            match r {
                Ok(()) => {}
                Err(Fail::Drop(d)) => self.report(d),
                Err(f) => return Err(f),
            }
        }
        Ok(())
    }

    fn set_units(&mut self, units: &crate::cad::brep::Units) {
        if self.model.solids.is_empty() && self.model.shells.is_empty() {
            self.model.units = units.clone();
        }
    }

    /// `MAPPED_ITEM(name, REPRESENTATION_MAP(origin, rep), target)`.
    fn mapped_item(&mut self, g: &Graph, id: u64) -> R<()> {
        let e = self.entity(id)?;
        let a = Args::of(e, "MAPPED_ITEM")?;
        let map = self.entity(a.id(1)?)?;
        let ma = Args::of(map, "REPRESENTATION_MAP")?;
        let (origin, rep, target) = (ma.id(0)?, ma.id(1)?, a.id(2)?);
        let parent_place = self.ctx.place;
        let target_frame = self.placement(target)?;
        // the origin is in the mapped representation's units
        let origin_frame = self.with_units_of(rep, |c| c.placement(origin))?;
        let t = Rigid::between(&origin_frame, &target_frame);
        let place = parent_place.compose(&t);
        let saved = self.ctx;
        let r = self.within(id, |c| c.expand(g, rep, place));
        self.ctx = saved;
        r
    }

    /// The motion mapping frame `from` (in representation `child`) onto `to` (in `parent`),
    /// each read in its representation's units.
    fn placement_between(&mut self, from: u64, child: u64, to: u64, parent: u64) -> R<Rigid> {
        let f = self.with_units_of(child, |c| c.placement(from))?;
        let t = self.with_units_of(parent, |c| c.placement(to))?;
        Ok(Rigid::between(&f, &t))
    }

    fn with_units_of<T>(&mut self, rep: u64, f: impl FnOnce(&mut Self) -> R<T>) -> R<T> {
        let e = self.entity(rep)?;
        let units = rep_record(e).and_then(|r| r.params.get(2)).and_then(Param::as_ref_id).map(|ctx| context_units(self.file, ctx)).unwrap_or_default();
        let saved = self.ctx;
        self.ctx.scale = units.to_mm;
        self.ctx.angle = units.to_rad;
        let r = f(self);
        self.ctx = saved;
        r
    }
}
