//! Which tets under an angle the input explains: those that touch an input angle as small
//! ([`crate::quality::worst_tet::touches_angle_below`]), and of the others those that lie
//! between its two sides ([`crate::quality::between_sides`]). The mesh summaries and
//! `fepre inspect` count them.

use crate::mesh::TetMesh;
use crate::quality::between_sides::SideTags;
use crate::quality::input_angles::InputAngle;
use crate::quality::tetrahedron::tet_min_max_dihedral;
use crate::quality::worst_tet::touches_angle_below;

/// Tets under 1°, 5°, 10° and a bound: how many, and how many of them touch no input angle
/// as small.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Explained {
    /// Under 1°, 5°, 10° and the bound: (tets, of those the ones that touch no input angle as
    /// small).
    pub under: [(usize, usize); 4],
    /// Of the tets under 10° and under the bound that touch no input angle as small, those
    /// between the two sides of one.
    pub between: [usize; 2],
    /// Under 1°, 5°, 10° and the bound, of the tets that touch no input angle as small, the
    /// smallest angle's: (angle, tet); the first tet on a tie.
    pub worst: [Option<(f64, usize)>; 4],
}

/// The counts of [`Explained`] for `mesh`, `sides` its boundary's tags
/// ([`crate::quality::worst_tet::BoundaryIndex::sides`]); `angles` smallest first, every input
/// angle under 10° and under `bound` among them. In parallel; the same result for any thread
/// count.
pub fn explained(mesh: &TetMesh, sides: &SideTags, angles: &[InputAngle], bound: f64) -> Explained {
    explained_among(mesh, None, sides, angles, bound)
}

/// [`explained`] over the tets `among` only (indices, ascending), or all where `None`: the
/// tets under 10° and under `bound`, where an earlier pass listed them
/// ([`TetExtremes::low`](crate::quality::extremes::TetExtremes::low)), give the same counts.
pub fn explained_among(mesh: &TetMesh, among: Option<&[usize]>, sides: &SideTags, angles: &[InputAngle], bound: f64) -> Explained {
    let limits = [1.0, 5.0, 10.0, bound];
    let n = among.map_or(mesh.tets.len(), <[usize]>::len);
    let index = |i: usize| among.map_or(i, |a| a[i]);
    // counts, summed over chunks in parallel
    crate::quality::summary::chunked_reduce(
        n,
        Explained::default(),
        |a, b| {
            let mut out = Explained::default();
            for t in (a..b).map(index) {
                let tet = mesh.tets[t];
                let p = tet.map(|v| mesh.vertices[v as usize]);
                let lo = tet_min_max_dihedral(&p).0;
                for (k, &limit) in limits.iter().enumerate() {
                    if lo < limit {
                        out.under[k].0 += 1;
                        if !touches_angle_below(&p, angles, limit) {
                            out.under[k].1 += 1;
                            if k >= 2 && sides.between_sides(mesh, tet, angles, limit).is_some() {
                                out.between[k - 2] += 1;
                            }
                            if out.worst[k].is_none_or(|(w, _)| lo < w) {
                                out.worst[k] = Some((lo, t));
                            }
                        }
                    }
                }
            }
            out
        },
        |acc, part| {
            for (x, y) in acc.under.iter_mut().zip(part.under) {
                x.0 += y.0;
                x.1 += y.1;
            }
            for (x, y) in acc.between.iter_mut().zip(part.between) {
                *x += y;
            }
            // chunks come in order: a later one wins only with a smaller angle
            for (x, y) in acc.worst.iter_mut().zip(part.worst) {
                if let Some((w, t)) = y {
                    if x.is_none_or(|(v, _)| w < v) {
                        *x = Some((w, t));
                    }
                }
            }
        },
    )
}

