//! The entity table of a parsed STEP file: `#id → (type, parameters)`, with the line each
//! instance starts on, for error messages.

use super::error::StepError;
use super::param::Param;
use rustc_hash::FxHashMap;
use std::path::{Path, PathBuf};

/// One `NAME(params)` record. A simple instance has one; a complex instance
/// `( A(..) B(..) )` has one per partial type, in the file's order (ISO 10303-21 requires
/// alphabetical order; the reader does not insist on it).
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// The type name, upper case.
    pub name: Box<str>,
    /// The parameters.
    pub params: Vec<Param>,
}

/// An entity instance `#id = ...;`.
#[derive(Clone, Debug, PartialEq)]
pub struct Entity {
    /// The instance id.
    pub id: u64,
    /// The 1-based line where `#id` is written.
    pub line: u32,
    /// One record, or several for a complex instance.
    pub records: Vec<Record>,
}

impl Entity {
    /// True for a complex instance `( A() B() )`.
    pub fn is_complex(&self) -> bool {
        self.records.len() > 1
    }

    /// The type name of a simple instance, or the first partial type of a complex one.
    pub fn type_name(&self) -> &str {
        self.records.first().map_or("", |r| &r.name)
    }

    /// The record of the given type (the only one of a simple instance, or the partial type of
    /// a complex one).
    pub fn record(&self, name: &str) -> Option<&Record> {
        self.records.iter().find(|r| &*r.name == name)
    }

    /// True when the instance is of this type (or has it as a partial type).
    pub fn has(&self, name: &str) -> bool {
        self.record(name).is_some()
    }

    /// The type as reports show it: `PLANE`, or `(A B C)` for a complex instance.
    pub fn display_type(&self) -> String {
        if self.is_complex() {
            let names: Vec<&str> = self.records.iter().map(|r| &*r.name).collect();
            format!("({})", names.join(" "))
        } else {
            self.type_name().to_string()
        }
    }
}

/// A parsed exchange file: header schema and the instances of its DATA sections.
#[derive(Clone, Debug)]
pub struct StepFile {
    /// The file (for messages).
    pub path: PathBuf,
    /// The schema names of `FILE_SCHEMA`, upper case (`AUTOMOTIVE_DESIGN`, `CONFIG_CONTROL_DESIGN`,
    /// `AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF`, ...).
    pub schemas: Vec<String>,
    /// `FILE_NAME`'s originating system, if given.
    pub originating_system: Option<String>,
    /// What was odd about the file as written but read anyway (a HEADER section missing or
    /// incomplete, a `FILE_NAME` of other than seven parameters).
    pub notes: Vec<String>,
    entities: Vec<Entity>,
    index: FxHashMap<u64, u32>,
}

impl StepFile {
    /// A table from parsed instances; fails on a repeated `#id`.
    pub fn new(path: &Path, schemas: Vec<String>, originating_system: Option<String>, entities: Vec<Entity>) -> Result<StepFile, StepError> {
        let mut index = FxHashMap::with_capacity_and_hasher(entities.len(), Default::default());
        for (k, e) in entities.iter().enumerate() {
            if let Some(first) = index.insert(e.id, k as u32) {
                return Err(StepError::DuplicateId { path: path.to_path_buf(), id: e.id, line: e.line, first_line: entities[first as usize].line });
            }
        }
        Ok(StepFile { path: path.to_path_buf(), schemas, originating_system, notes: Vec::new(), entities, index })
    }

    /// The instance `#id`.
    pub fn get(&self, id: u64) -> Option<&Entity> {
        self.index.get(&id).map(|&k| &self.entities[k as usize])
    }

    /// All instances, in the file's order.
    pub fn entities(&self) -> &[Entity] {
        &self.entities
    }

    /// Number of instances.
    pub fn len(&self) -> usize {
        self.entities.len()
    }

    /// True when the DATA sections are empty.
    pub fn is_empty(&self) -> bool {
        self.entities.is_empty()
    }

    /// The instances having `name` as their type or one of their partial types.
    pub fn of_type<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a Entity> + 'a {
        self.entities.iter().filter(move |e| e.has(name))
    }

    /// Checks that every reference names a defined instance.
    ///
    /// # Errors
    /// [`StepError::MissingEntity`] for the first dangling reference, naming both ids.
    pub fn check_references(&self) -> Result<(), StepError> {
        match self.dangling().first() {
            Some(&(from, line, id)) => Err(StepError::MissingEntity { path: self.path.clone(), id, from, line }),
            None => Ok(()),
        }
    }

    /// The references to instances the file does not define: `(from, its line, id)`, the
    /// first of each instance, in file order.
    pub fn dangling(&self) -> Vec<(u64, u32, u64)> {
        let mut out = Vec::new();
        for e in &self.entities {
            let mut missing = None;
            for r in &e.records {
                for p in &r.params {
                    p.for_each_ref(&mut |id| {
                        if missing.is_none() && !self.index.contains_key(&id) {
                            missing = Some(id);
                        }
                    });
                }
            }
            if let Some(id) = missing {
                out.push((e.id, e.line, id));
            }
        }
        out
    }
}
