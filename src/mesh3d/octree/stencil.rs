//! The stencils of isosurface stuffing: which tets fill the part of one background tet that
//! lies inside, given the signs of its four (possibly warped) vertices.
//!
//! Stage: after the cut points and warping of the octree mesher. Input: one background tet's
//! vertex signs (`-1` inside, `0` on the surface after warping, `+1` outside) and its
//! vertices' doubled lattice coordinates (see `lattice.rs`). Output: tets whose corners are
//! the tet's vertices or the cut points on its sign-changing edges, positively oriented in
//! the reference geometry.
//!
//! # Invariants
//! - The kept polytope is `P = {x : f(x) <= 0}` for the linear `f` taking the signs at the
//!   vertices: its corners are the `-` and `0` vertices and the cut points of the `-+` edges
//!   (midpoints of those edges in the reference geometry, where `P` is convex). Tets with no
//!   `-` vertex give nothing (the caller decides the all-zero tet); tets with no `+` vertex
//!   are kept whole. The stencils are the paper's (Labelle and Shewchuk 2007, section 3 and
//!   its figure of stencils): `-+++`, `-0++`, `-00+` one tet; `--0+` two (a pyramid);
//!   `--++` and `---+` three (prisms).
//! - The only choices are the diagonals of quadrilaterals, and they are the paper's:
//!   - a quadrilateral in a background face (the face's signs are `--+`) is cut by a rule
//!     that reads only that face, so both tets sharing it cut it alike and the mesh is
//!     conforming ([`diagonal_end`]). When the face's two `-` vertices are joined by a short
//!     edge, the diagonal joins the *apex* (the `-` vertex off the face's long edge) to the
//!     cut point on the long edge. When they are joined by the face's long edge, the
//!     *parity rule* picks the end: the apex's offset from that edge, in the two axes across
//!     it, has a sign product that alternates between the four faces around the edge, so the
//!     two such faces of one background tet always use opposite ends;
//!   - the `--++` prism's surface quadrilateral then has one diagonal that completes a
//!     triangulation without a new vertex (its other two quadrilaterals' diagonals never
//!     share a `-` vertex), and that is the one used; `---+` prisms never meet a cyclic
//!     choice (the apex rule makes the `-` vertex off the long edge a sink).
//! - Proven by the tests below, every cut point anywhere in its allowed range `[α, 1 - α]`
//!   (sampled: the ends and three inner points per cut, every combination, every sign
//!   pattern, 24 background tets of both parities and every orientation), every `0` vertex
//!   at its lattice position: every tet is positive with dihedral angles in
//!   [[`MIN_DIHEDRAL`], [`MAX_DIHEDRAL`]] = [10.7°, 164.8°], the paper's bounds (worst found
//!   12.73° and 154.87°).
//! - Not the paper's bound once `0` vertices are *displaced* by warping (each moved by up to
//!   `α` of one of its 14 lattice edges towards a cut point): there the tests find tets down
//!   to 9.32° and up to 161.64°, all positive. The shortfall is not the stencils': a `-00+`
//!   or `-000` background tet has exactly one possible tet, and a surface crossing a
//!   background tet's edges where one plane does (bending away from the `-` vertex's other
//!   edges, so that only two vertices warp) gives a `-00+` tet of 10.2° (test
//!   `warped_single_tet_case_falls_short`). Whether the paper's warping admits fewer
//!   displacements than ours (`cut.rs`) is not settled here. The caller measures every mesh
//!   and reports its extremes.
//! - Every tet produced is non-degenerate and positively oriented in the reference geometry
//!   (exact integer orientation); whether it stays positive at the warped positions and the
//!   true cut points is checked by the caller.
//!
//! [`MIN_DIHEDRAL`]: super::MIN_DIHEDRAL
//! [`MAX_DIHEDRAL`]: super::MAX_DIHEDRAL

use crate::core::predicates::orient3d_int;

/// A corner of an output tet, local to one background tet.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Local {
    /// Vertex `i` (0..4) of the background tet.
    Vertex(u8),
    /// The cut point on the edge between vertices `i < j`.
    Cut(u8, u8),
}

/// True for a long lattice edge (two corners or two centres) between doubled coordinates.
fn is_long(a: [i32; 3], b: [i32; 3]) -> bool {
    (a[0] ^ b[0]) & 1 == 0
}

/// The diagonal of the quadrilateral that the background face `(u, v, w)` keeps when `u`
/// and `v` are inside and `w` is outside (doubled lattice coordinates): `true` when it joins
/// `u` to the cut point on `v w`, `false` when it joins `v` to the cut point on `u w`. A
/// function of the face alone (symmetric in `u`, `v`); see the module docs.
pub fn diagonal_end(u: [i32; 3], v: [i32; 3], w: [i32; 3]) -> bool {
    if is_long(u, v) {
        // the parity rule: along the long edge's axis `k`, the lower end when the apex's
        // offsets across the edge have the same sign, else the upper end
        let k = (0..3).find(|&k| u[k] != v[k]).unwrap_or(0);
        let (a, b) = ((k + 1) % 3, (k + 2) % 3);
        let lower = (w[a] - u[a]) * (w[b] - u[b]) > 0;
        (u[k] < v[k]) == lower
    } else {
        // the apex rule: `u` is the apex when `v w` is the face's long edge
        is_long(v, w)
    }
}

/// The three tets of the prism with triangles `p`, `q` (`p[i] q[i]` its lateral edges) whose
/// lateral quadrilateral `(i, j)` has the diagonal `p[i] q[j]` when `before[i][j]` (and
/// `p[j] q[i]` otherwise), or `None` when the diagonals are cyclic.
fn prism(p: [Local; 3], q: [Local; 3], before: [[bool; 3]; 3]) -> Option<[[Local; 4]; 3]> {
    let a = (0..3).find(|&a| (0..3).all(|j| j == a || before[a][j]))?;
    let (b, c) = ((a + 1) % 3, (a + 2) % 3);
    let (b, c) = if before[b][c] { (b, c) } else { (c, b) };
    Some([[p[a], p[b], p[c], q[c]], [p[a], p[b], q[b], q[c]], [p[a], q[a], q[b], q[c]]])
}

/// Appends to `out` the tets filling the inside part of the background tet with vertex signs
/// `s` and doubled lattice coordinates `refs` (see the module docs). Returns the number of
/// tets that came out degenerate in the reference geometry (0 unless the signs are
/// inconsistent with a linear field, which cannot happen).
pub fn stuff(s: [i8; 4], refs: [[i32; 3]; 4], out: &mut Vec<[Local; 4]>) -> usize {
    use Local::Vertex as V;
    if !s.contains(&-1) {
        return 0;
    }
    let oriented = |t: [Local; 4]| -> Option<[Local; 4]> {
        let p = t.map(|c| reference(c, &refs));
        let o = orient3d_int(p[0], p[1], p[2], p[3]);
        if o.is_positive() {
            Some(t)
        } else if o.is_negative() {
            Some([t[1], t[0], t[2], t[3]])
        } else {
            None
        }
    };
    let cut = |i: u8, j: u8| if i < j { Local::Cut(i, j) } else { Local::Cut(j, i) };
    let of = |x: i8| -> Vec<u8> { (0..4u8).filter(|&i| s[i as usize] == x).collect() };
    let (neg, zero, pos) = (of(-1), of(0), of(1));
    // `u` and `v` inside, `w` outside: `u` takes the diagonal of face `(u, v, w)`
    let takes = |u: u8, v: u8, w: u8| diagonal_end(refs[u as usize], refs[v as usize], refs[w as usize]);
    let mut tets: Vec<[Local; 4]> = Vec::with_capacity(3);
    let mut degenerate = 0;
    match (neg.len(), pos.len()) {
        (_, 0) => tets.push([V(0), V(1), V(2), V(3)]),
        (1, _) => {
            let u = neg[0];
            let mut t = [V(u); 4];
            for (k, i) in (0..4u8).filter(|&i| i != u).enumerate() {
                t[k + 1] = if s[i as usize] == 0 { V(i) } else { cut(u, i) };
            }
            tets.push(t);
        }
        (2, 1) => {
            // a pyramid over the quadrilateral of face (u, v, w), apex the `0` vertex
            let (u, v, w, z) = (neg[0], neg[1], pos[0], zero[0]);
            let (x, y) = if takes(u, v, w) { (u, v) } else { (v, u) };
            tets.push([V(z), V(x), V(y), cut(y, w)]);
            tets.push([V(z), V(x), cut(y, w), cut(x, w)]);
        }
        (2, 2) => {
            // a prism: triangles at `u` and `v`; quadrilaterals in faces (u, v, w), (u, v, x)
            // and on the surface
            let (u, v, w, x) = (neg[0], neg[1], pos[0], pos[1]);
            let p = [V(u), cut(u, w), cut(u, x)];
            let q = [V(v), cut(v, w), cut(v, x)];
            let (b01, b02) = (takes(u, v, w), takes(u, v, x));
            // the surface diagonal completing them (the diagonals in the background faces
            // never share a `-` vertex; were they to, either would do)
            let b12 = if b01 == b02 { true } else { b02 };
            let before = [[false, b01, b02], [!b01, false, b12], [!b02, !b12, false]];
            match prism(p, q, before) {
                Some(t) => tets.extend(t),
                None => degenerate += 3,
            }
        }
        (3, 1) => {
            // a prism: the inside face and the surface triangle; quadrilaterals in the faces
            // through the outside vertex
            let x = pos[0];
            let p = [V(neg[0]), V(neg[1]), V(neg[2])];
            let q = [cut(neg[0], x), cut(neg[1], x), cut(neg[2], x)];
            let before: [[bool; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| i != j && takes(neg[i], neg[j], x)));
            match prism(p, q, before) {
                Some(t) => tets.extend(t),
                None => degenerate += 3,
            }
        }
        _ => unreachable!("a sign pattern with a `-` and a `+` has at most three of either"),
    }
    for t in tets {
        match oriented(t) {
            Some(t) => out.push(t),
            None => degenerate += 1,
        }
    }
    degenerate
}

/// The reference position of a corner: twice the doubled coordinates of a vertex, the sum
/// of both ends' for a cut point (its edge's midpoint).
pub fn reference(c: Local, refs: &[[i32; 3]; 4]) -> [i32; 3] {
    match c {
        Local::Vertex(i) => refs[i as usize].map(|x| 2 * x),
        Local::Cut(i, j) => {
            let (a, b) = (refs[i as usize], refs[j as usize]);
            [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{ALPHA_LONG, ALPHA_SHORT, Lattice, MAX_DIHEDRAL, MIN_DIHEDRAL};
    use super::*;
    use crate::quality::tetrahedron::{tet_min_max_dihedral, tet_volume};
    use glam::DVec3;
    use std::collections::HashMap;

    /// The faces of a tet `(v0, v1, v2, v3)`.
    const FACES: [[u8; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

    /// Allowance for rounding in the angle computations, degrees.
    const EPS: f64 = 1e-6;

    /// A BCC background tet in doubled coordinates: centres (1,1,1), (3,1,1); the edge
    /// (2,0,0)-(2,2,0) of the face between them; positively oriented.
    fn bcc() -> [[i32; 3]; 4] {
        let t = [[1, 1, 1], [3, 1, 1], [2, 0, 0], [2, 2, 0]];
        if orient3d_int(t[0], t[1], t[2], t[3]).is_positive() { t } else { [t[1], t[0], t[2], t[3]] }
    }

    fn lattice() -> Lattice {
        Lattice { origin: DVec3::ZERO, h: 1.0, n: [4, 4, 4] }
    }

    /// The 24 background tets owned by two neighbouring interior centres (one of each parity):
    /// every orientation of a background tet, doubled coordinates.
    fn sample_tets() -> Vec<[[i32; 3]; 4]> {
        let l = lattice();
        let mut out = Vec::new();
        for c in [[3, 3, 3], [5, 3, 3]] {
            let mut t = Vec::new();
            l.tets_around(l.id(c).unwrap() as usize - l.num_corners(), &mut t);
            assert_eq!(t.len(), 12);
            out.extend(t.iter().map(|t| t.map(|v| l.coords(v))));
        }
        out
    }

    fn point(c: [i32; 3]) -> DVec3 {
        DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64)
    }

    /// Every sign pattern of a tet's four vertices.
    fn patterns() -> impl Iterator<Item = [i8; 4]> {
        (0..81).map(|k: i32| [0, 1, 2, 3].map(|i| ((k / 3i32.pow(i)) % 3) as i8 - 1))
    }

    /// Geometry of a corner with cut points at parameter `tc` from the lower-indexed end.
    fn place(c: Local, p: &[DVec3; 4], tc: f64) -> DVec3 {
        match c {
            Local::Vertex(i) => p[i as usize],
            Local::Cut(i, j) => p[i as usize] + tc * (p[j as usize] - p[i as usize]),
        }
    }

    fn expected_count(s: [i8; 4]) -> usize {
        let neg = s.iter().filter(|&&x| x == -1).count();
        let pos = s.iter().filter(|&&x| x == 1).count();
        match (neg, pos) {
            (_, 0) => 1,
            (1, _) => 1,
            (2, 1) => 2,
            (2, 2) | (3, 1) => 3,
            _ => unreachable!(),
        }
    }

    /// Every sign pattern with a `-` (all permutations, zeros included), every orientation
    /// and both parities of background tet: the count is the paper's, every tet is positive
    /// at the reference midpoints, and the inside stencil with the outside one (the stencil
    /// of the negated signs) fills exactly the background tet's volume.
    #[test]
    fn all_cases_fill_their_polytope() {
        let mut cases = 0;
        for refs in sample_tets() {
            let p = refs.map(point);
            let whole = tet_volume(&p);
            assert!(whole > 0.0);
            let volume = |o: &[[Local; 4]]| o.iter().map(|t| tet_volume(&t.map(|c| place(c, &p, 0.5)))).sum::<f64>();
            for s in patterns().filter(|s| s.contains(&-1)) {
                let mut out = Vec::new();
                assert_eq!(stuff(s, refs, &mut out), 0, "{s:?}");
                assert_eq!(out.len(), expected_count(s), "{s:?} {refs:?}");
                for t in &out {
                    assert!(tet_volume(&t.map(|c| place(c, &p, 0.5))) > 0.0, "{s:?} {refs:?}");
                }
                let mut outside = Vec::new();
                assert_eq!(stuff(s.map(|x| -x), refs, &mut outside), 0, "{s:?}");
                let (vin, vout) = (volume(&out), volume(&outside));
                assert!(vin > 0.0);
                assert!((vin + vout - whole).abs() <= 1e-12 * whole, "{s:?} {refs:?}: {vin} + {vout} != {whole}");
                cases += 1;
            }
        }
        assert_eq!(cases, 24 * 65);
    }

    /// Conformity: over random signs on a small lattice, the two background tets sharing a
    /// face cut it into the same triangles.
    #[test]
    fn both_tets_of_a_face_cut_it_alike() {
        let l = lattice();
        let mut tets = Vec::new();
        for i in 0..l.num_centres() {
            l.tets_around(i, &mut tets);
        }
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut shared = 0;
        for trial in 0..200 {
            let sign: Vec<i8> = (0..l.num_vertices())
                .map(|_| {
                    seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
                    // more zeros and fewer of one sign in some trials
                    let r = (seed >> 33) % 7;
                    match trial % 3 {
                        0 => (r % 3) as i8 - 1,
                        1 => [-1, -1, -1, 0, 1, 1, 1][r as usize],
                        _ => [-1, 0, 0, 0, 1, -1, 1][r as usize],
                    }
                })
                .collect();
            let mut faces: HashMap<[u32; 3], Vec<Vec<[(u32, u32); 3]>>> = HashMap::new();
            for t in &tets {
                let s = t.map(|v| sign[v as usize]);
                let mut out = Vec::new();
                assert_eq!(stuff(s, t.map(|v| l.coords(v)), &mut out), 0);
                let global = |c: Local| match c {
                    Local::Vertex(i) => (t[i as usize], t[i as usize]),
                    Local::Cut(i, j) => (t[i as usize].min(t[j as usize]), t[i as usize].max(t[j as usize])),
                };
                for f in FACES {
                    let fv = f.map(|k| t[k as usize]);
                    // a face of three `0` vertices is the surface (one side keeps it, the
                    // other not); every other face's kept part is read off its signs
                    if fv.iter().all(|&v| sign[v as usize] == 0) {
                        continue;
                    }
                    let mut tris = Vec::new();
                    for o in &out {
                        let g = o.map(global);
                        for skip in 0..4 {
                            let mut tri: Vec<(u32, u32)> = (0..4).filter(|&k| k != skip).map(|k| g[k]).collect();
                            if tri.iter().all(|c| fv.contains(&c.0) && fv.contains(&c.1)) {
                                tri.sort_unstable();
                                tris.push([tri[0], tri[1], tri[2]]);
                            }
                        }
                    }
                    tris.sort_unstable();
                    let mut key = fv;
                    key.sort_unstable();
                    faces.entry(key).or_default().push(tris);
                }
            }
            for (k, v) in &faces {
                if v.len() == 2 {
                    assert_eq!(v[0], v[1], "face {k:?}, trial {trial}");
                    shared += 1;
                }
            }
        }
        assert!(shared > 1000);
    }

    /// `α` of the edge between doubled coordinates `a` and `b`.
    fn alpha(a: [i32; 3], b: [i32; 3]) -> f64 {
        if is_long(a, b) { ALPHA_LONG } else { ALPHA_SHORT }
    }

    /// The worst dihedral angles `(min, max)` of the stencil tets `out` of signs `s` over every
    /// combination of cut parameters `ts` (fractions of each cut's allowed range `[α, 1 - α]`,
    /// from its `-` end), the vertices at `p`; panics on a tet that is not positive.
    fn sweep(s: [i8; 4], refs: [[i32; 3]; 4], p: &[DVec3; 4], out: &[[Local; 4]], ts: &[f64]) -> (f64, f64) {
        let cuts: Vec<(usize, usize)> =
            (0..4).flat_map(|i| (i + 1..4).map(move |j| (i, j))).filter(|&(i, j)| s[i] * s[j] == -1).collect();
        let mut worst = (180.0f64, 0.0f64);
        let mut at = [[DVec3::ZERO; 4]; 4];
        for k in 0..ts.len().pow(cuts.len() as u32) {
            for (e, &(i, j)) in cuts.iter().enumerate() {
                let t = ts[(k / ts.len().pow(e as u32)) % ts.len()];
                let a = alpha(refs[i], refs[j]);
                let x = a + (1.0 - 2.0 * a) * t;
                let (m, q) = if s[i] == -1 { (i, j) } else { (j, i) };
                let c = p[m] + x * (p[q] - p[m]);
                at[i][j] = c;
                at[j][i] = c;
            }
            for t in out {
                let q = t.map(|c| match c {
                    Local::Vertex(i) => p[i as usize],
                    Local::Cut(i, j) => at[i as usize][j as usize],
                });
                assert!(tet_volume(&q) > 0.0, "{s:?} {refs:?} {p:?} {t:?}");
                let (lo, hi) = tet_min_max_dihedral(&q);
                worst = (worst.0.min(lo), worst.1.max(hi));
            }
        }
        worst
    }

    /// The paper's bounds with every cut point anywhere in its allowed range `[α, 1 - α]`
    /// (both ends and three inner points per cut, every combination) and the `0` vertices at
    /// their lattice positions, for every sign pattern with a `-` and every orientation and
    /// parity of background tet: every tet is positive with dihedral angles
    /// in [10.7°, 164.8°] (worst found 12.73° and 154.87°).
    #[test]
    fn stencils_keep_the_papers_bounds_at_allowed_cut_points() {
        let ts = [0.0, 0.25, 0.5, 0.75, 1.0];
        let mut worst = (180.0f64, 0.0f64);
        for refs in sample_tets() {
            let p = refs.map(point);
            for s in patterns().filter(|s| s.contains(&-1)) {
                let mut out = Vec::new();
                stuff(s, refs, &mut out);
                let (lo, hi) = sweep(s, refs, &p, &out, &ts);
                assert!(lo >= MIN_DIHEDRAL - EPS && hi <= MAX_DIHEDRAL + EPS, "{s:?} {refs:?}: [{lo}, {hi}]");
                worst = (worst.0.min(lo), worst.1.max(hi));
            }
        }
        eprintln!("stencil extremes at allowed cut points: [{:.4}, {:.4}]", worst.0, worst.1);
        assert!(worst.0 >= MIN_DIHEDRAL - EPS && worst.1 <= MAX_DIHEDRAL + EPS);
    }

    /// The lattice neighbour offsets (doubled coordinates): 6 long, 8 short.
    fn offsets() -> Vec<[i32; 3]> {
        let mut d = vec![[2, 0, 0], [-2, 0, 0], [0, 2, 0], [0, -2, 0], [0, 0, 2], [0, 0, -2]];
        for k in 0..8 {
            d.push([0, 1, 2].map(|b| if (k >> b) & 1 == 0 { -1 } else { 1 }));
        }
        d
    }

    /// Warping: every sign pattern, every `0` vertex either at its lattice position or moved
    /// towards any of its 14 lattice neighbours by half or all (less 1e-9) of that edge's `α`,
    /// as far as the moves are consistent (a vertex moves towards a neighbour of the other
    /// original sign, so two `0` vertices never move towards each other along their edge);
    /// cut points at the ends and the middle of their ranges. Every tet stays positive. The
    /// paper's 10.7° is not kept here, by any stencil (see the next test): the extremes found
    /// are pinned, [9.317°, 161.643°] (the minimum in a `--0+` pyramid whose apex moved, the
    /// maximum in a kept `-000` tet).
    #[test]
    fn stencils_stay_positive_with_warped_vertices() {
        let ts = [0.0, 0.5, 1.0];
        let dirs = offsets();
        let mut worst = (180.0f64, 0.0f64);
        for refs in sample_tets() {
            for s in patterns().filter(|s| s.contains(&-1) && s.contains(&0)) {
                let mut out = Vec::new();
                stuff(s, refs, &mut out);
                let zeros: Vec<usize> = (0..4).filter(|&i| s[i] == 0).collect();
                // per zero vertex: no move, or (direction, fraction of α)
                let moves: Vec<Option<(usize, f64)>> =
                    std::iter::once(None).chain((0..dirs.len()).flat_map(|d| [0.5, 1.0 - 1e-9].map(|f| Some((d, f))))).collect();
                for k in 0..moves.len().pow(zeros.len() as u32) {
                    let pick: Vec<Option<(usize, f64)>> =
                        (0..zeros.len()).map(|z| moves[(k / moves.len().pow(z as u32)) % moves.len()]).collect();
                    // the vertex of this tet each zero moves towards, if any
                    let towards: Vec<Option<usize>> = zeros
                        .iter()
                        .zip(&pick)
                        .map(|(&z, m)| {
                            m.and_then(|(d, _)| {
                                let q = [0, 1, 2].map(|a| refs[z][a] + dirs[d][a]);
                                (0..4).find(|&w| refs[w] == q)
                            })
                        })
                        .collect();
                    // an edge's one cut point is within `α < 1/2` of at most one end, and some
                    // original signs of the zeros must make every move cross a sign change
                    let mutual = zeros.iter().zip(&towards).any(|(&z, w)| {
                        w.is_some_and(|w| zeros.iter().position(|&y| y == w).is_some_and(|k| towards[k] == Some(z)))
                    });
                    let consistent = !mutual && (0..1u32 << zeros.len()).any(|bits| {
                        let orig = |v: usize| match zeros.iter().position(|&z| z == v) {
                            Some(k) => if (bits >> k) & 1 == 0 { -1 } else { 1 },
                            None => s[v],
                        };
                        zeros.iter().zip(&towards).all(|(&z, w)| w.is_none_or(|w| orig(w) == -orig(z)))
                    });
                    if !consistent {
                        continue;
                    }
                    let mut p = refs.map(point);
                    for (&z, m) in zeros.iter().zip(&pick) {
                        if let Some((d, f)) = *m {
                            let q = [0, 1, 2].map(|a| refs[z][a] + dirs[d][a]);
                            p[z] += f * alpha(refs[z], q) * (point(q) - point(refs[z]));
                        }
                    }
                    let (lo, hi) = sweep(s, refs, &p, &out, &ts);
                    worst = (worst.0.min(lo), worst.1.max(hi));
                }
            }
        }
        eprintln!("stencil extremes with warped vertices: [{:.4}, {:.4}]", worst.0, worst.1);
        assert!(worst.0 >= 9.31 && worst.1 <= 161.65, "{worst:?}");
    }

    /// Why the previous test cannot ask for the paper's 10.7°: a surface that crosses the
    /// edges of the background tet `(A, B, C, D)` where the plane through the point at `0.25`
    /// of `AB` from `A` and the points at `0.41` of `CB` and `DB` from `C` and `D` does (and
    /// bends away from `A`'s other lattice edges, which the plane itself would cut within
    /// `α_short` of `A`): `C` and `D` are closer than `α_short = 0.41189` to those cut points
    /// and warp onto them, `A` and `B` are not violated, and the `-+00` background tet has one
    /// possible tet, whose smallest dihedral angle is 10.2°.
    #[test]
    fn warped_single_tet_case_falls_short() {
        let refs = bcc();
        let p = refs.map(point);
        let (a, b, c, d) = (p[0], p[1], p[2], p[3]);
        let x = a + 0.25 * (b - a);
        let (cw, dw) = (c + 0.41 * (b - c), d + 0.41 * (b - d));
        let n = (cw - x).cross(dw - x);
        let f = |q: DVec3| n.dot(q - x);
        let n = if f(b) > 0.0 { n } else { -n };
        let f = |q: DVec3| n.dot(q - x);
        assert!(f(a) < 0.0 && f(b) > 0.0 && f(c) < 0.0 && f(d) < 0.0);
        // the cut points on the tet's edges: C and D are violated, A and B are not
        let t = |u: DVec3, v: DVec3| f(u) / (f(u) - f(v));
        assert!((t(c, b) - 0.41).abs() < 1e-12 && t(c, b) < ALPHA_SHORT);
        assert!((t(d, b) - 0.41).abs() < 1e-12 && t(a, b) > ALPHA_LONG && 1.0 - t(a, b) > ALPHA_LONG);
        let s = [-1, 1, 0, 0];
        let mut out = Vec::new();
        stuff(s, refs, &mut out);
        assert_eq!(out.len(), 1);
        let q = out[0].map(|k| match k {
            Local::Vertex(2) => cw,
            Local::Vertex(3) => dw,
            Local::Vertex(i) => p[i as usize],
            Local::Cut(..) => x,
        });
        let (lo, _) = tet_min_max_dihedral(&q);
        assert!(lo > 10.0 && lo < MIN_DIHEDRAL, "{lo}");
    }
}
