//! The STEP instance (`#id`) a B-rep item came from.

use serde::Serialize;
use std::fmt;

/// The STEP instance an item came from (`#id`), for messages and reports.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(transparent)]
pub struct EntityRef(pub u64);

impl fmt::Display for EntityRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{}", self.0)
    }
}
