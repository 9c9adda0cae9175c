//! Removal of the exterior and the cavities: the subfaces become walls; the tets are grouped
//! into components connected through non-wall faces; the component of the ghost tets is the
//! exterior (depth 0), and crossing a wall adds one to the depth. Odd depth is material, even
//! depth a cavity; hole seeds empty their component; region seeds name theirs, the others are
//! numbered by first appearance.

use crate::core::ids::NONE;
use crate::core::{RegionId, Sign};
use crate::mesh3d::delaunay::kernel::Kernel;
use crate::mesh3d::delaunay::store::{DEAD, GHOST};
use crate::mesh3d::mesher::surface_model::SurfaceModel;
use crate::mesh3d::mesher::tetra::Tetra;
use crate::mesh3d::mesher::{MeshingError, Seeds};
use crate::mesh::tet_mesh::TET_FACES;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::VecDeque;

/// Region labels per tet slot: 0 outside the material, `r ≥ 1` region `r`.
pub(crate) struct Labels {
    /// Label per tet slot (grows with the slots).
    pub of: Vec<u32>,
    /// Number of regions.
    pub regions: usize,
    /// The tag of region `r` at index `r - 1`.
    pub tags: Vec<RegionId>,
}

impl Labels {
    /// The label of tet `t` (0 for slots beyond the array).
    #[inline]
    pub fn get(&self, t: u32) -> u32 {
        self.of.get(t as usize).copied().unwrap_or(0)
    }

    /// Sets the label of tet `t`.
    pub fn set(&mut self, t: u32, r: u32) {
        if self.of.len() <= t as usize {
            self.of.resize(t as usize + 1, 0);
        }
        self.of[t as usize] = r;
    }
}

/// Makes every subface a wall: each tet's faces are looked up among the subfaces (in
/// parallel), so a subface is found from both of its sides, twice in all. Where fewer are
/// found, the missing subface is named.
fn wall_subfaces(tr: &mut Tetra, sm: &SurfaceModel) -> Result<(), MeshingError> {
    let found: Vec<u8> = tr
        .tets
        .par_iter()
        .with_min_len(4096)
        .map(|tet| {
            let v = tet.v;
            if v[0] == DEAD {
                return 0;
            }
            (0..4).filter(|&k| sm.facet_of(TET_FACES[k].map(|i| v[i])).is_some()).fold(0u8, |bits, k| bits | 1 << k)
        })
        .collect();
    let sides: usize = found.iter().map(|b| b.count_ones() as usize).sum();
    if sides != 2 * sm.subfaces().count() {
        let mut buf = Vec::new();
        if let Some((_, [a, b, c])) = sm.subfaces().find(|&(_, [a, b, c])| tr.face_tet(a, b, c, &mut buf).is_none()) {
            return Err(MeshingError::Internal(format!("subface ({a}, {b}, {c}) is missing after recovery")));
        }
        return Err(MeshingError::Internal(format!("{sides} tet faces are subfaces, against {} subfaces", sm.subfaces().count())));
    }
    for (w, bits) in tr.walls.iter_mut().zip(found) {
        *w |= bits;
    }
    Ok(())
}

/// Walls the subfaces and labels the tets.
///
/// # Errors
/// [`MeshingError::Internal`] if a subface is not a face of the tetrahedralization (recovery
/// guarantees it is).
pub(crate) fn carve(tr: &mut Tetra, sm: &SurfaceModel, seeds: &Seeds) -> Result<Labels, MeshingError> {
    wall_subfaces(tr, sm)?;
    let n = tr.tets.len();
    let dead = |t: usize| tr.tets[t].v[0] == DEAD;
    // components through non-wall faces
    let mut comp = vec![NONE; n];
    let mut ncomp = 0u32;
    let mut queue = VecDeque::new();
    for s in 1..n {
        if dead(s) || comp[s] != NONE {
            continue;
        }
        comp[s] = ncomp;
        queue.push_back(s as u32);
        while let Some(t) = queue.pop_front() {
            for f in 0..4 {
                if tr.walls[t as usize] >> f & 1 != 0 {
                    continue;
                }
                let nb = (tr.tets[t as usize].n[f] >> 2) as usize;
                if comp[nb] == NONE {
                    comp[nb] = ncomp;
                    queue.push_back(nb as u32);
                }
            }
        }
        ncomp += 1;
    }
    // depth of every component from the exterior
    let ghost = (1..n).find(|&t| !dead(t) && tr.tets[t].v[3] == GHOST).ok_or_else(|| MeshingError::Internal("no ghost tet".into()))?;
    let mut depth = vec![NONE; ncomp as usize];
    depth[comp[ghost] as usize] = 0;
    // breadth-first over components: scan wall faces repeatedly (few components)
    let mut changed = true;
    while changed {
        changed = false;
        for t in 1..n {
            if dead(t) {
                continue;
            }
            let ct = comp[t] as usize;
            if depth[ct] == NONE {
                continue;
            }
            for f in 0..4 {
                if tr.walls[t] >> f & 1 == 0 {
                    continue;
                }
                let nb = (tr.tets[t].n[f] >> 2) as usize;
                let cn = comp[nb] as usize;
                if depth[cn] == NONE {
                    depth[cn] = depth[ct] + 1;
                    changed = true;
                }
            }
        }
    }
    // material: odd depth, minus the components holding a hole seed
    let mut material = vec![false; ncomp as usize];
    for c in 0..ncomp as usize {
        material[c] = depth[c] != NONE && depth[c] % 2 == 1;
    }
    for &h in &seeds.holes {
        if let Some(t) = containing_tet(tr, h) {
            material[comp[t as usize] as usize] = false;
        }
    }
    // regions: seeded ones first, then the others in order of their first tet
    let mut region_of_comp = vec![0u32; ncomp as usize];
    let mut tags: Vec<RegionId> = Vec::new();
    for s in &seeds.regions {
        if let Some(t) = containing_tet(tr, s.point) {
            let c = comp[t as usize] as usize;
            if material[c] && region_of_comp[c] == 0 {
                tags.push(s.tag);
                region_of_comp[c] = tags.len() as u32;
            }
        }
    }
    let used: Vec<u32> = tags.iter().map(|t| t.0).collect();
    let mut next = 1u32;
    for t in 1..n {
        if dead(t) {
            continue;
        }
        let c = comp[t] as usize;
        if material[c] && region_of_comp[c] == 0 {
            while used.contains(&next) {
                next += 1;
            }
            tags.push(RegionId(next));
            next += 1;
            region_of_comp[c] = tags.len() as u32;
        }
    }
    let mut labels = Labels { of: vec![0; n], regions: tags.len(), tags };
    for t in 1..n {
        if !dead(t) && tr.tets[t].v[3] != GHOST {
            labels.of[t] = region_of_comp[comp[t] as usize];
        }
    }
    tr.walled = true;
    Ok(labels)
}

/// A finite tet whose closure holds `p` (brute force: for the few seed points).
fn containing_tet(tr: &Tetra, p: DVec3) -> Option<u32> {
    let q = crate::core::predicates::orient3d;
    tr.live().find(|&t| {
        let v = tr.tets[t as usize].v.map(|i| tr.point(i));
        let inside = |a: DVec3, b: DVec3, c: DVec3, d: DVec3| q(a, b, c, d) != Sign::Negative;
        inside(p, v[1], v[2], v[3]) && inside(v[0], p, v[2], v[3]) && inside(v[0], v[1], p, v[3]) && inside(v[0], v[1], v[2], p)
    })
    .filter(|_| tr.k.len() > 0)
}
