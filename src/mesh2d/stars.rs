//! The triangles around each point of a triangle mesh (compressed rows, in triangle order),
//! shared by the methods' smoothing passes.

/// For each point, the indices of the triangles having it as a corner.
pub(crate) struct Stars {
    start: Vec<u32>,
    tris: Vec<u32>,
}

impl Stars {
    /// The stars of `n` points under `triangles` (every index below `n`).
    pub(crate) fn new(n: usize, triangles: &[[u32; 3]]) -> Stars {
        let mut start = vec![0u32; n + 1];
        for t in triangles {
            for &v in t {
                start[v as usize + 1] += 1;
            }
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut tris = vec![0u32; start[n] as usize];
        for (k, t) in triangles.iter().enumerate() {
            for &v in t {
                tris[fill[v as usize] as usize] = k as u32;
                fill[v as usize] += 1;
            }
        }
        Stars { start, tris }
    }

    /// The triangles around point `v`, in triangle order.
    pub(crate) fn of(&self, v: usize) -> &[u32] {
        &self.tris[self.start[v] as usize..self.start[v + 1] as usize]
    }
}
