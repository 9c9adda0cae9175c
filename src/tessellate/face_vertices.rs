//! The vertices one face's mesh reads and adds: the shared points of the model's vertices and
//! edges (read only, so faces can be meshed side by side) and the face's own new points,
//! numbered after the shared ones. [`FaceVertices::renumber`] moves a face's own ids to where
//! its points land in the tessellation's vertex list, face after face in order: the same ids
//! as meshing the faces one after the other into one list.

use glam::DVec3;

/// Shared points and the face's own.
pub struct FaceVertices<'a> {
    shared: &'a [DVec3],
    own: Vec<DVec3>,
}

impl<'a> FaceVertices<'a> {
    /// No own points yet.
    pub fn new(shared: &'a [DVec3]) -> FaceVertices<'a> {
        FaceVertices { shared, own: Vec::new() }
    }

    /// Adds a point of the face; its id.
    pub fn push(&mut self, p: DVec3) -> u32 {
        self.own.push(p);
        (self.shared.len() + self.own.len() - 1) as u32
    }

    /// The face's own points, in id order.
    pub fn into_own(self) -> Vec<DVec3> {
        self.own
    }

    /// The id `id` had in a face meshed on `shared` shared points, once that face's own points
    /// start at `start` in the whole list.
    pub fn renumber(id: u32, shared: usize, start: usize) -> u32 {
        if (id as usize) < shared { id } else { (id as usize - shared + start) as u32 }
    }
}

impl std::ops::Index<usize> for FaceVertices<'_> {
    type Output = DVec3;

    fn index(&self, i: usize) -> &DVec3 {
        match i.checked_sub(self.shared.len()) {
            Some(k) => &self.own[k],
            None => &self.shared[i],
        }
    }
}
