//! The selection evaluated once: each selector's name and the CAD faces it selects. The
//! density field and the FE model both take [`Groups`]; nothing evaluates a selector again.

use super::catalogue::FaceCatalogue;
use super::selector::{SelectError, Selection, Selector};
use crate::core::FaceId;
use std::collections::BTreeMap;

/// Selector name → the faces it selects (ascending, never empty).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Groups(BTreeMap<String, Vec<FaceId>>);

impl Groups {
    /// Evaluates every selector of `selectors` on `cat` (one that selects nothing is an error
    /// even when nothing uses it).
    ///
    /// # Errors
    /// The first selector, in name order, that fails.
    pub fn evaluate(selectors: &BTreeMap<String, Selector>, cat: &FaceCatalogue) -> Result<Groups, SelectError> {
        let mut sel = Selection::new(selectors, cat);
        let mut out = BTreeMap::new();
        for name in selectors.keys() {
            out.insert(name.clone(), sel.faces(name)?.into_iter().collect());
        }
        Ok(Groups(out))
    }

    /// The faces `name` selects (ascending).
    ///
    /// # Errors
    /// [`SelectError::Unknown`] where no selector is called `name`.
    pub fn faces(&self, name: &str) -> Result<&[FaceId], SelectError> {
        self.0.get(name).map(Vec::as_slice).ok_or_else(|| SelectError::Unknown { name: String::new(), missing: name.to_string() })
    }

    /// Each name with its faces.
    pub fn as_map(&self) -> &BTreeMap<String, Vec<FaceId>> {
        &self.0
    }
}
