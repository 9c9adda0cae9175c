//! The converter from an entity table to a [`Model`]: shared state (caches per placed
//! instance, the current representation's units and placement, the stack that detects
//! reference cycles) and typed access to an instance's parameters.
//!
//! Geometry is read in the file's units, scaled to millimetres as it is read (lengths only:
//! parameters of B-splines and lines keep their values, angles are converted to radians) and
//! moved by the placement of the assembly instance being expanded.

use super::error::StepError;
use super::param::Param;
use super::table::{Entity, StepFile};
use crate::cad::brep::{Dropped, EntityRef, Model};
use crate::cad::geom::Rigid;
use rustc_hash::FxHashMap;

/// Why an item could not be converted: drop it (and say so), or stop reading.
pub(super) enum Fail {
    /// Leave the item out; the caller records it.
    Drop(Dropped),
    /// A problem with the file as a whole.
    Fatal(StepError),
}

impl From<StepError> for Fail {
    fn from(e: StepError) -> Fail {
        Fail::Fatal(e)
    }
}

pub(super) type R<T> = Result<T, Fail>;

/// The representation instance being converted.
#[derive(Copy, Clone, Debug)]
pub(super) struct Ctx {
    /// Millimetres per file length unit.
    pub scale: f64,
    /// Radians per file angle unit.
    pub angle: f64,
    /// Placement of this instance in the world.
    pub place: Rigid,
    /// Instance number (keys the caches).
    pub instance: u32,
}

/// The state of one conversion.
pub(super) struct Converter<'f> {
    pub file: &'f StepFile,
    pub model: Model,
    pub ctx: Ctx,
    pub next_instance: u32,
    /// `#id` currently being converted, outermost first (cycle detection).
    pub stack: Vec<u64>,
    pub vertices: FxHashMap<(u64, u32), u32>,
    pub edges: FxHashMap<(u64, u32), u32>,
    /// Curve index and whether the stored curve runs against the STEP curve.
    pub curves: FxHashMap<(u64, u32), Option<(u32, bool)>>,
    pub surfaces: FxHashMap<(u64, u32), u32>,
    /// How many times each solid entity has been placed so far.
    pub solid_instances: FxHashMap<u64, u32>,
    /// Dropped items already reported, by id (an item used by several faces or instances is
    /// reported once).
    pub reported: FxHashMap<u64, ()>,
    /// Tessellated geometry (AP242), read beside the B-rep.
    pub tess: super::tessellated::TessBuilder,
}

impl<'f> Converter<'f> {
    pub fn new(file: &'f StepFile) -> Converter<'f> {
        Converter {
            file,
            model: Model::default(),
            ctx: Ctx { scale: 1.0, angle: 1.0, place: Rigid::IDENTITY, instance: 0 },
            next_instance: 0,
            stack: Vec::new(),
            vertices: FxHashMap::default(),
            edges: FxHashMap::default(),
            curves: FxHashMap::default(),
            surfaces: FxHashMap::default(),
            solid_instances: FxHashMap::default(),
            reported: FxHashMap::default(),
            tess: Default::default(),
        }
    }

    /// The instance `#id`; a reference the file does not define fails here, where it is
    /// needed (parsing lists such references and goes on).
    pub fn entity(&self, id: u64) -> R<&'f Entity> {
        self.file.get(id).ok_or_else(|| {
            let from = self.stack.last().copied().unwrap_or(0);
            let line = self.file.get(from).map_or(0, |e| e.line);
            Fail::Fatal(StepError::MissingEntity { path: self.file.path.clone(), id, from, line })
        })
    }

    /// Runs `f` with `id` on the stack; a second visit of `id` inside is a cycle.
    pub fn within<T>(&mut self, id: u64, f: impl FnOnce(&mut Self) -> R<T>) -> R<T> {
        if let Some(k) = self.stack.iter().position(|&s| s == id) {
            let chain: Vec<String> = self.stack[k..].iter().chain(std::iter::once(&id)).map(|i| format!("#{i}")).collect();
            let line = self.file.get(id).map_or(0, |e| e.line);
            return Err(Fail::Fatal(StepError::Cycle { path: self.file.path.clone(), id, line, chain: chain.join(" -> ") }));
        }
        self.stack.push(id);
        let r = f(self);
        self.stack.pop();
        r
    }

    /// Records a dropped item once.
    pub fn report(&mut self, d: Dropped) {
        if self.reported.insert(d.id.0, ()).is_none() {
            self.model.dropped.push(d);
        }
    }

    /// Turns a `Drop` into a report and `None`; passes fatal errors on.
    pub fn soft<T>(&mut self, r: R<T>) -> Result<Option<T>, StepError> {
        match r {
            Ok(x) => Ok(Some(x)),
            Err(Fail::Drop(d)) => {
                self.report(d);
                Ok(None)
            }
            Err(Fail::Fatal(e)) => Err(e),
        }
    }
}

/// A dropped-item failure for instance `e`.
pub(super) fn drop_entity(e: &Entity, why: impl Into<String>) -> Fail {
    Fail::Drop(Dropped { kind: e.display_type(), id: EntityRef(e.id), why: why.into() })
}

/// The parameters of one record of an instance, with accessors that fail with a message
/// naming the instance and the parameter.
pub(super) struct Args<'f> {
    pub e: &'f Entity,
    pub params: &'f [Param],
}

impl<'f> Args<'f> {
    /// The parameters of record `name` of `e`.
    pub fn of(e: &'f Entity, name: &str) -> R<Args<'f>> {
        match e.record(name) {
            Some(r) => Ok(Args { e, params: &r.params }),
            None => Err(drop_entity(e, format!("expected {name}"))),
        }
    }

    fn bad(&self, k: usize, what: &str) -> Fail {
        let found = match self.params.get(k) {
            None => "nothing (too few parameters)".to_string(),
            Some(p) => format!("{p:?}"),
        };
        drop_entity(self.e, format!("parameter {}: expected {what}, found {found}", k + 1))
    }

    pub fn f64(&self, k: usize) -> R<f64> {
        self.params.get(k).and_then(Param::as_f64).filter(|x| x.is_finite()).ok_or_else(|| self.bad(k, "a number"))
    }

    pub fn i64(&self, k: usize) -> R<i64> {
        self.params.get(k).and_then(Param::as_i64).ok_or_else(|| self.bad(k, "an integer"))
    }

    pub fn id(&self, k: usize) -> R<u64> {
        self.params.get(k).and_then(Param::as_ref_id).ok_or_else(|| self.bad(k, "a reference"))
    }

    /// A reference, or `None` when unset (`$`).
    pub fn opt_id(&self, k: usize) -> R<Option<u64>> {
        match self.params.get(k) {
            None | Some(Param::Unset) => Ok(None),
            Some(Param::Ref(id)) => Ok(Some(*id)),
            Some(_) => Err(self.bad(k, "a reference or $")),
        }
    }

    pub fn list(&self, k: usize) -> R<&'f [Param]> {
        self.params.get(k).and_then(Param::as_list).ok_or_else(|| self.bad(k, "a list"))
    }

    /// A logical; unset or unknown counts as `default`.
    pub fn bool_or(&self, k: usize, default: bool) -> bool {
        self.params.get(k).and_then(Param::as_bool).unwrap_or(default)
    }

    /// A non-empty string.
    pub fn name(&self, k: usize) -> Option<String> {
        self.params.get(k).and_then(Param::as_str).map(str::trim).filter(|s| !s.is_empty()).map(str::to_string)
    }

    /// The references of a list.
    pub fn ids(&self, k: usize) -> R<Vec<u64>> {
        let l = self.list(k)?;
        l.iter().map(|p| p.as_ref_id().ok_or_else(|| self.bad(k, "a list of references"))).collect()
    }

    /// The numbers of a list.
    pub fn f64s(&self, k: usize) -> R<Vec<f64>> {
        let l = self.list(k)?;
        l.iter().map(|p| p.as_f64().filter(|x| x.is_finite()).ok_or_else(|| self.bad(k, "a list of numbers"))).collect()
    }

    /// The integers of a list.
    pub fn i64s(&self, k: usize) -> R<Vec<i64>> {
        let l = self.list(k)?;
        l.iter().map(|p| p.as_i64().ok_or_else(|| self.bad(k, "a list of integers"))).collect()
    }
}
