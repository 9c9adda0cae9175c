//! One model from several: [`Model::append`] adds another model's solids, shells and
//! everything below them, indices shifted, so that parts built or read apart form one
//! assembly (their solids side by side, numbered after this model's).

use super::Model;
use crate::core::FaceId;

impl Model {
    /// Appends `other`'s solids, shells, faces, loops, edges, vertices, surfaces, curves and
    /// dropped items (both models in millimetres: `other`'s units are not converted; this
    /// model's units and sewing report stay).
    ///
    /// ```
    /// let mut m = fepre::cad::parts::Bracket::default().build().unwrap();
    /// let (solids, faces) = (m.solids.len(), m.faces.len());
    /// m.append(&fepre::cad::parts::Flange::default().build().unwrap());
    /// assert_eq!(m.solids.len(), solids + 1);
    /// let last = m.shells[m.solids[solids].shells[0] as usize].faces[0];
    /// assert_eq!(last, fepre::core::FaceId::from_index(faces));
    /// ```
    pub fn append(&mut self, other: &Model) {
        let (solids, shells, faces, loops) = (self.solids.len() as u32, self.shells.len() as u32, self.faces.len(), self.loops.len() as u32);
        let (edges, vertices, surfaces, curves) = (self.edges.len() as u32, self.vertices.len() as u32, self.surfaces.len() as u32, self.curves.len() as u32);
        let face = |f: FaceId| f.index().map_or(f, |k| FaceId::from_index(k + faces));
        self.solids.extend(other.solids.iter().map(|s| {
            let mut s = s.clone();
            s.shells.iter_mut().for_each(|x| *x += shells);
            s
        }));
        self.shells.extend(other.shells.iter().map(|s| {
            let mut s = s.clone();
            s.faces.iter_mut().for_each(|f| *f = face(*f));
            s.solid = s.solid.map(|k| k + solids);
            s
        }));
        self.faces.extend(other.faces.iter().map(|f| {
            let mut f = f.clone();
            f.surface += surfaces;
            f.loops.iter_mut().for_each(|l| *l += loops);
            f.shell += shells;
            f
        }));
        self.loops.extend(other.loops.iter().map(|l| {
            let mut l = l.clone();
            l.face = face(l.face);
            l.coedges.iter_mut().for_each(|c| c.edge += edges);
            l.vertex = l.vertex.map(|v| v + vertices);
            l
        }));
        self.edges.extend(other.edges.iter().map(|e| {
            let mut e = e.clone();
            e.curve = e.curve.map(|c| c + curves);
            e.start += vertices;
            e.end += vertices;
            e
        }));
        self.vertices.extend(other.vertices.iter().cloned());
        self.surfaces.extend(other.surfaces.iter().cloned());
        self.curves.extend(other.curves.iter().cloned());
        self.dropped.extend(other.dropped.iter().cloned());
    }
}
