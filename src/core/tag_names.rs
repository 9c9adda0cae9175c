//! Names of tags: [`TagNames`], the one table type beside every tag array
//! (`TriSurface::face_names`, `TetMesh::face_names`, `TetMesh::region_names`,
//! `PlanarMesh::region_names`), and [`make_unique`], the one place names are made unique for
//! output.
//!
//! Names need not be unique in memory (a STEP file may call two faces `hole_1`); every writer
//! that writes names (MSH physical names, OBJ groups, ASCII STL solids) and every report that
//! lists them goes through [`TagNames::unique`] or [`make_unique`], so a name stands for one
//! tag in every file fepre writes: the first tag keeps its name, later ones get `.2`, `.3`, …
//! (a suffix no other name has).

use crate::core::{FaceId, RegionId};
use std::collections::{BTreeMap, HashMap, HashSet};

/// Names of tags `T` ([`FaceId`] or [`RegionId`]), at most one per tag, iterated in tag order.
///
/// ```
/// use fepre::core::{FaceId, FaceNames};
/// let mut names = FaceNames::new();
/// names.insert(FaceId(9), "hole_1");
/// names.insert(FaceId(10), "hole_1");
/// let written = names.unique([FaceId(9), FaceId(10), FaceId(11)], |t, n| Some(n.map_or(format!("tag_{}", t.0), str::to_string)));
/// assert_eq!(written[&FaceId(10)], "hole_1.2");
/// assert_eq!(written[&FaceId(11)], "tag_11");
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct TagNames<T>(BTreeMap<T, String>);

/// Names of face tags.
pub type FaceNames = TagNames<FaceId>;

/// Names of region tags.
pub type RegionNames = TagNames<RegionId>;

impl<T> Default for TagNames<T> {
    fn default() -> Self {
        TagNames(BTreeMap::new())
    }
}

impl<T: Copy + Ord> TagNames<T> {
    /// An empty table.
    pub fn new() -> Self {
        Self::default()
    }

    /// The name of `tag`, if it has one.
    pub fn get(&self, tag: T) -> Option<&str> {
        self.0.get(&tag).map(String::as_str)
    }

    /// Names `tag`, returning its previous name.
    pub fn insert(&mut self, tag: T, name: impl Into<String>) -> Option<String> {
        self.0.insert(tag, name.into())
    }

    /// Removes the name of `tag`, returning it.
    pub fn remove(&mut self, tag: T) -> Option<String> {
        self.0.remove(&tag)
    }

    /// True when `tag` has a name.
    pub fn contains(&self, tag: T) -> bool {
        self.0.contains_key(&tag)
    }

    /// Number of named tags.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// True when no tag has a name.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// `(tag, name)` in increasing tag order.
    pub fn iter(&self) -> impl Iterator<Item = (T, &str)> + '_ {
        self.0.iter().map(|(t, n)| (*t, n.as_str()))
    }

    /// The names in increasing tag order.
    pub fn names(&self) -> impl Iterator<Item = &str> + '_ {
        self.0.values().map(String::as_str)
    }

    /// Adds the names of `other` for tags that have none here (what appending a mesh does).
    pub fn extend_missing(&mut self, other: &Self) {
        for (t, n) in &other.0 {
            self.0.entry(*t).or_insert_with(|| n.clone());
        }
    }

    /// The names to write for `tags`, unique: each tag (sorted, once) gets `name(tag, its
    /// name here)`, where the writer cleans the name for its format and picks a fallback for
    /// tags without one (`None`: the tag is written unnamed); then `make_unique` in tag
    /// order. Clean before, not after: cleaning can make two names equal.
    pub fn unique(&self, tags: impl IntoIterator<Item = T>, name: impl Fn(T, Option<&str>) -> Option<String>) -> BTreeMap<T, String> {
        let mut tags: Vec<T> = tags.into_iter().collect();
        tags.sort_unstable();
        tags.dedup();
        let mut out: Vec<(T, String)> = tags.into_iter().filter_map(|t| name(t, self.get(t)).map(|n| (t, n))).collect();
        make_unique(out.iter_mut().map(|(_, n)| n));
        out.into_iter().collect()
    }
}

impl<T: Copy + Ord, S: Into<String>> FromIterator<(T, S)> for TagNames<T> {
    fn from_iter<I: IntoIterator<Item = (T, S)>>(iter: I) -> Self {
        TagNames(iter.into_iter().map(|(t, n)| (t, n.into())).collect())
    }
}

impl<T: Copy + Ord, S: Into<String>> Extend<(T, S)> for TagNames<T> {
    fn extend<I: IntoIterator<Item = (T, S)>>(&mut self, iter: I) {
        self.0.extend(iter.into_iter().map(|(t, n)| (t, n.into())));
    }
}

/// Makes `names` unique, in order: the first of equal names keeps it, each later one gets the
/// smallest suffix `.2`, `.3`, … that gives a name no other entry has (before or after
/// renaming). Returns how many were renamed.
///
/// ```
/// let mut names = vec!["hole_1".to_string(), "hole_1".into(), "hole_1.2".into(), "hole_1".into()];
/// assert_eq!(fepre::core::make_unique(names.iter_mut()), 2);
/// assert_eq!(names, ["hole_1", "hole_1.3", "hole_1.2", "hole_1.4"]);
/// ```
pub fn make_unique<'a>(names: impl IntoIterator<Item = &'a mut String>) -> usize {
    let mut names: Vec<&mut String> = names.into_iter().collect();
    let original: HashSet<String> = names.iter().map(|n| n.to_string()).collect();
    let mut used: HashSet<String> = HashSet::with_capacity(names.len());
    let mut next: HashMap<String, u64> = HashMap::new();
    let mut renamed = 0;
    for n in &mut names {
        if used.insert(n.to_string()) {
            continue;
        }
        let k = next.entry(n.to_string()).or_insert(2);
        let fresh = loop {
            let c = format!("{n}.{k}");
            *k += 1;
            if !original.contains(&c) && !used.contains(&c) {
                break c;
            }
        };
        used.insert(fresh.clone());
        **n = fresh;
        renamed += 1;
    }
    renamed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_keeps_its_name_and_suffixes_skip_taken_names() {
        let mut v: Vec<String> = ["a", "b", "a", "a.2", "a", "a.3", "b"].iter().map(|s| s.to_string()).collect();
        assert_eq!(make_unique(v.iter_mut()), 3);
        assert_eq!(v, ["a", "b", "a.4", "a.2", "a.5", "a.3", "b.2"]);
        let set: HashSet<&String> = v.iter().collect();
        assert_eq!(set.len(), v.len());
    }

    #[test]
    fn unique_cleans_before_and_falls_back() {
        let mut names = FaceNames::new();
        names.insert(FaceId(1), "top lid");
        names.insert(FaceId(2), "top_lid");
        names.insert(FaceId(4), "tag_3");
        let clean = |t: FaceId, n: Option<&str>| Some(n.map_or(format!("tag_{}", t.0), |n| n.replace(' ', "_")));
        let w = names.unique([FaceId(4), FaceId(3), FaceId(2), FaceId(1), FaceId(2)], clean);
        let got: Vec<(u32, &str)> = w.iter().map(|(t, n)| (t.0, n.as_str())).collect();
        assert_eq!(got, [(1, "top_lid"), (2, "top_lid.2"), (3, "tag_3"), (4, "tag_3.2")]);
        // unnamed tags may stay unnamed
        assert_eq!(names.unique([FaceId(3)], |_, n| n.map(str::to_string)).len(), 0);
    }

    #[test]
    fn extend_missing_keeps_existing_names() {
        let mut a: FaceNames = [(FaceId(1), "x")].into_iter().collect();
        let b: FaceNames = [(FaceId(1), "y"), (FaceId(2), "z")].into_iter().collect();
        a.extend_missing(&b);
        assert_eq!(a.iter().collect::<Vec<_>>(), [(FaceId(1), "x"), (FaceId(2), "z")]);
    }
}
