//! Shells (edge-connected components) and per-shell statistics, vertex fans, orientability.
//!
//! Input: the valid triangles and their [`EdgeTable`]. Output: [`Analysis`]: the shell of
//! every triangle (shells numbered by their smallest triangle), the triangles of each shell
//! (CSR), and per shell its counts, orientation, orientability, vertex-manifoldness, area,
//! signed volume, tags and box. Three union-finds over flat arrays: triangles across every
//! edge, corners across two-triangle edges (fans), and triangles with a flip parity across
//! two-triangle edges (orientability), all `core::union_find`.

use super::Prepared;
use super::edges::{EdgeTable, ends, forward};
use crate::core::union_find::{ParityUnionFind, UnionFind};
use crate::core::{Aabb, FaceId};
use crate::mesh::TriSurface;
use glam::DVec3;

/// Statistics of one shell.
#[derive(Clone, Debug)]
pub(crate) struct ShellStats {
    /// Smallest valid-triangle index.
    pub first_triangle: u32,
    pub triangles: usize,
    pub vertices: usize,
    pub edges: usize,
    pub open: usize,
    pub nonmanifold: usize,
    pub misoriented: usize,
    pub orientable: bool,
    pub vertex_manifold: bool,
    pub area: f64,
    pub volume: f64,
    pub tags: Vec<FaceId>,
    pub bbox: Aabb,
}

impl ShellStats {
    /// Every edge has exactly two triangles.
    pub fn closed(&self) -> bool {
        self.open == 0 && self.nonmanifold == 0
    }
}

/// Shells of a surface and vertex statistics.
pub(crate) struct Analysis {
    pub shells: Vec<ShellStats>,
    /// Shell of every valid triangle.
    pub shell_of: Vec<u32>,
    /// Triangles of shell `s`: `members[member_start[s]..member_start[s + 1]]`, increasing.
    member_start: Vec<usize>,
    members: Vec<u32>,
    pub used_vertices: usize,
    pub nonmanifold_vertices: usize,
}

impl Analysis {
    /// The valid triangles of shell `s`, increasing.
    pub fn members(&self, s: usize) -> &[u32] {
        &self.members[self.member_start[s]..self.member_start[s + 1]]
    }
}

/// Labels shells: the shell of every valid triangle, numbered by smallest triangle.
fn label_shells(tris: &[[u32; 3]], et: &EdgeTable) -> (Vec<u32>, usize) {
    let mut uf = UnionFind::new(tris.len());
    for e in 0..et.len() {
        let h = et.halves(e);
        for x in &h[1..] {
            uf.union(h[0].tri, x.tri);
        }
    }
    uf.labels()
}

/// Analyses the shells of the prepared surface; `tags` are the surface's face tags (indexed
/// by original triangle; missing tags read as the default).
pub(crate) fn analyse(m: &Prepared, et: &EdgeTable, tags: &[FaceId]) -> Analysis {
    let tris: &[[u32; 3]] = &m.tris;
    let (shell_of, ns) = label_shells(tris, et);

    // members (counting sort keeps triangles increasing within each shell)
    let mut member_start = vec![0usize; ns + 1];
    for &s in &shell_of {
        member_start[s as usize + 1] += 1;
    }
    for s in 0..ns {
        member_start[s + 1] += member_start[s];
    }
    let mut cursor = member_start.clone();
    let mut members = vec![0u32; tris.len()];
    for (t, &s) in shell_of.iter().enumerate() {
        members[cursor[s as usize]] = t as u32;
        cursor[s as usize] += 1;
    }

    let mut shells: Vec<ShellStats> = (0..ns)
        .map(|s| ShellStats {
            first_triangle: members[member_start[s]],
            triangles: member_start[s + 1] - member_start[s],
            vertices: 0,
            edges: 0,
            open: 0,
            nonmanifold: 0,
            misoriented: 0,
            orientable: true,
            vertex_manifold: true,
            area: 0.0,
            volume: 0.0,
            tags: Vec::new(),
            bbox: Aabb::EMPTY,
        })
        .collect();

    // edges: counts, orientation, and the unions for fans and orientability
    let mut corners = UnionFind::new(3 * tris.len());
    let mut flips = ParityUnionFind::new(tris.len());
    for e in 0..et.len() {
        let h = et.halves(e);
        let st = &mut shells[shell_of[h[0].tri as usize] as usize];
        st.edges += 1;
        match h.len() {
            1 => st.open += 1,
            2 => {}
            _ => st.nonmanifold += 1,
        }
        if !et.consistent(tris, e) {
            st.misoriented += 1;
        }
        if h.len() == 2 {
            let (u, _) = ends(tris, &h[0]);
            let (t1, k1, t2, k2) = (h[0].tri, h[0].k as u32, h[1].tri, h[1].k as u32);
            let (c1u, c1w) = (3 * t1 + k1, 3 * t1 + (k1 + 1) % 3);
            let (c2a, c2b) = (3 * t2 + k2, 3 * t2 + (k2 + 1) % 3);
            let same_direction = forward(tris, &h[0]) == forward(tris, &h[1]);
            // in t2 the edge starts at u iff both run the same way
            let (c2u, c2w) = if ends(tris, &h[1]).0 == u { (c2a, c2b) } else { (c2b, c2a) };
            corners.union(c1u, c2u);
            corners.union(c1w, c2w);
            if !flips.union(t1, t2, same_direction) {
                st.orientable = false;
            }
        }
    }

    // fans: a root corner is one fan of its vertex
    let nv = m.verts.len();
    let mut fans = vec![0u32; nv];
    for c in 0..3 * tris.len() {
        if corners.is_root(c as u32) {
            let v = tris[c / 3][c % 3] as usize;
            fans[v] += 1;
            shells[shell_of[c / 3] as usize].vertices += 1;
        }
    }
    let used_vertices = fans.iter().filter(|&&f| f > 0).count();
    let nonmanifold_vertices = fans.iter().filter(|&&f| f > 1).count();
    if nonmanifold_vertices > 0 {
        // several fans of one vertex: within one shell they are a non-manifold vertex of
        // that shell and count as one vertex of it
        let mut pairs: Vec<(u32, u32)> = (0..3 * tris.len())
            .filter(|&c| corners.is_root(c as u32) && fans[tris[c / 3][c % 3] as usize] > 1)
            .map(|c| (tris[c / 3][c % 3], shell_of[c / 3]))
            .collect();
        pairs.sort_unstable();
        for w in pairs.windows(2) {
            if w[0] == w[1] {
                let st = &mut shells[w[0].1 as usize];
                st.vertices -= 1;
                st.vertex_manifold = false;
            }
        }
    }

    // area, signed volume (about the box centre, for accuracy), box
    let o = Aabb::from_points(m.verts).center();
    let o = if o.is_finite() { o } else { DVec3::ZERO };
    for (t, &s) in shell_of.iter().enumerate() {
        let [a, b, c] = m.corners(t);
        let st = &mut shells[s as usize];
        st.area += 0.5 * (b - a).cross(c - a).length();
        st.volume += (a - o).dot((b - o).cross(c - o)) / 6.0;
        st.bbox = st.bbox.union(&Aabb::from_points(&[a, b, c]));
    }

    // tags
    let mut keys: Vec<u64> = shell_of
        .iter()
        .enumerate()
        .map(|(t, &s)| ((s as u64) << 32) | tags.get(m.orig(t) as usize).copied().unwrap_or_default().0 as u64)
        .collect();
    keys.sort_unstable();
    keys.dedup();
    for k in keys {
        shells[(k >> 32) as usize].tags.push(FaceId(k as u32));
    }

    Analysis { shells, shell_of, member_start, members, used_vertices, nonmanifold_vertices }
}

/// The shell (edge-connected component, numbered as in the report) of every triangle;
/// `None` for invalid triangles.
pub fn triangle_shells(s: &TriSurface) -> Vec<Option<u32>> {
    let m = Prepared::new(s);
    let et = EdgeTable::build(&m.tris, m.verts.len());
    let (shell_of, _) = label_shells(&m.tris, &et);
    let mut out = vec![None; s.triangles.len()];
    for (t, &sh) in shell_of.iter().enumerate() {
        out[m.orig(t) as usize] = Some(sh);
    }
    out
}
