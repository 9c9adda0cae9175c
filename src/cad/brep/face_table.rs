//! The table of faces a report lists: for each face id its name (unique, as the writers write
//! it), colour, STEP `#id` and solid, where known. [`Model::face_table`] builds it from a
//! B-rep; [`face_table_of_names`] from a mesh file's face names alone.

use super::{EntityRef, Model};
use crate::core::{FaceId, FaceNames};
use serde::Serialize;

/// One face of a [`Model::face_table`] or [`face_table_of_names`]; unknown fields are left out
/// of the JSON.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FaceEntry {
    /// The face's tag.
    pub face: FaceId,
    /// Its name, made unique over the table ([`FaceNames::unique`]: the first keeps it,
    /// later ones get `.2`, `.3`, …), as the MSH writer names its physical group.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// RGB in `[0, 1]`, from the STEP file's styled items.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub colour: Option<[f32; 3]>,
    /// The STEP `ADVANCED_FACE` (or `FACE_SURFACE`) it came from.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub step_id: Option<EntityRef>,
    /// The solid it bounds: its number, 1-based in the order of [`Model::solids`] (as the
    /// `solid` selector counts); none for a face of a surface model's shell.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solid: Option<u32>,
}

impl Model {
    /// Every face in id order with its unique name, colour, STEP `#id` and solid.
    ///
    /// ```
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let model = fepre::cad::parts::Bracket::default().build()?;
    /// let table = model.face_table();
    /// assert_eq!(table.len(), model.faces.len());
    /// assert_eq!(table[0].face, fepre::core::FaceId(1));
    /// # Ok(())
    /// # }
    /// ```
    pub fn face_table(&self) -> Vec<FaceEntry> {
        let names: FaceNames = self.face_ids().filter_map(|id| Some((id, self.face(id).name.clone()?))).collect();
        let mut unique = names.unique(self.face_ids(), |_, n| n.map(str::to_string));
        self.face_ids()
            .map(|id| {
                let f = self.face(id);
                FaceEntry {
                    face: id,
                    name: unique.remove(&id),
                    colour: f.colour,
                    step_id: Some(f.source),
                    solid: self.shells.get(f.shell as usize).and_then(|s| s.solid).map(|k| k + 1),
                }
            })
            .collect()
    }
}

/// The table of a mesh file's faces: each tag of `tags` (sorted, once) with its name from
/// `names` made unique, nothing else being known.
///
/// ```
/// use fepre::core::{FaceId, FaceNames};
/// let names: FaceNames = [(FaceId(1), "wall"), (FaceId(2), "wall")].into_iter().collect();
/// let t = fepre::cad::brep::face_table_of_names(&names, [FaceId(2), FaceId(1), FaceId(3)]);
/// let got: Vec<Option<&str>> = t.iter().map(|e| e.name.as_deref()).collect();
/// assert_eq!(got, [Some("wall"), Some("wall.2"), None]);
/// ```
pub fn face_table_of_names(names: &FaceNames, tags: impl IntoIterator<Item = FaceId>) -> Vec<FaceEntry> {
    let mut tags: Vec<FaceId> = tags.into_iter().collect();
    tags.sort_unstable();
    tags.dedup();
    let mut unique = names.unique(tags.iter().copied(), |_, n| n.map(str::to_string));
    tags.into_iter().map(|face| FaceEntry { face, name: unique.remove(&face), colour: None, step_id: None, solid: None }).collect()
}
