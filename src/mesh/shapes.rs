//! Structured meshes of simple shapes, generated exactly: for fixtures, tests and benchmarks.

use crate::core::{FaceId, RegionId};
use crate::mesh::{TetMesh, TriSurface};
use glam::DVec3;
use std::f64::consts::TAU;

/// A closed, outward-oriented torus around the z axis: `n` segments around the axis, `m`
/// around the tube, `2nm` triangles tagged `FaceId(1)`, genus 1.
///
/// # Panics
/// If `n < 3` or `m < 3`.
pub fn torus(major: f64, minor: f64, n: usize, m: usize) -> TriSurface {
    assert!(n >= 3 && m >= 3, "a torus needs at least 3 × 3 segments");
    let mut v = Vec::with_capacity(n * m);
    for i in 0..n {
        for j in 0..m {
            let (u, w) = (TAU * i as f64 / n as f64, TAU * j as f64 / m as f64);
            let r = major + minor * w.cos();
            v.push(DVec3::new(r * u.cos(), r * u.sin(), minor * w.sin()));
        }
    }
    let id = |i: usize, j: usize| ((i % n) * m + j % m) as u32;
    let mut t = Vec::with_capacity(2 * n * m);
    for i in 0..n {
        for j in 0..m {
            t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriSurface::with_single_tag(v, t, FaceId(1))
}

/// Sets `mesh`'s boundary to its hull faces, each tagged `tag(unit outward normal, centroid)`:
/// for tests on tagged boundaries.
#[cfg(test)]
pub(crate) fn tag_hull(mesh: &mut TetMesh, tag: impl Fn(DVec3, DVec3) -> u32) {
    mesh.boundary = mesh.hull_faces();
    let tags = mesh
        .boundary
        .iter()
        .map(|f| {
            let [a, b, c] = f.map(|v| mesh.vertices[v as usize]);
            FaceId(tag((b - a).cross(c - a).normalize(), (a + b + c) / 3.0))
        })
        .collect();
    mesh.face_tags = tags;
}

/// One tag per side of an axis-aligned box, by the outward normal `n`'s axis and sign (1 to 6).
#[cfg(test)]
pub(crate) fn side_tag(n: DVec3) -> u32 {
    let axis = (0..3).max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs())).unwrap_or(0);
    1 + 2 * axis as u32 + u32::from(n[axis] > 0.0)
}

/// The unit cube split into `n³` cells of six tets each (Kuhn subdivision along the main
/// diagonal of every cell), `6n³` positively oriented tets in `RegionId(1)`. Interior vertices
/// move by up to `jitter / n` (a fraction of the cell, below 0.5 to keep every tet positive)
/// with a deterministic pseudo-random sequence from `seed`; the boundary stays flat.
///
/// # Panics
/// If `n == 0` or `jitter` is not in `[0, 0.5)`.
pub fn kuhn_cube(n: usize, jitter: f64, seed: u64) -> TetMesh {
    assert!(n > 0 && (0.0..0.5).contains(&jitter), "kuhn_cube needs n > 0 and 0 <= jitter < 0.5");
    let id = |i: usize, j: usize, k: usize| (i + (n + 1) * (j + (n + 1) * k)) as u32;
    let mut state = seed | 1;
    let mut rnd = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let mut vertices = Vec::with_capacity((n + 1).pow(3));
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                let inner = [i, j, k].iter().all(|&x| x > 0 && x < n);
                let d = if inner && jitter > 0.0 { DVec3::new(rnd(), rnd(), rnd()) * jitter } else { DVec3::ZERO };
                vertices.push((DVec3::new(i as f64, j as f64, k as f64) + d) / n as f64);
            }
        }
    }
    let mut tets = Vec::with_capacity(6 * n * n * n);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let c = |b: usize| id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
                for [a, b] in [[1, 3], [1, 5], [2, 3], [2, 6], [4, 5], [4, 6]] {
                    let mut t = [c(0), c(a), c(b), c(7)];
                    let [p, q, r, s] = t.map(|v| vertices[v as usize]);
                    if (q - p).dot((r - p).cross(s - p)) < 0.0 {
                        t.swap(1, 2);
                    }
                    tets.push(t);
                }
            }
        }
    }
    let region_tags = vec![RegionId(1); tets.len()];
    TetMesh { vertices, tets, region_tags, ..Default::default() }
}

/// A square plate `width × width × thickness` with a centred through-hole of `radius`,
/// polygonal with `n` segments (a multiple of 8, so that the plate's corners are vertices).
/// Closed, outward, genus 1, `8n` triangles tagged per CAD face: 1 top, 2 bottom, 3–6 the
/// sides at x = 0, x = width, y = 0, y = width, 7 the hole, with those names.
///
/// # Panics
/// If `n` is not a positive multiple of 8 or `radius` does not fit inside the plate.
pub fn plate_with_hole(n: usize, width: f64, thickness: f64, radius: f64) -> TriSurface {
    assert!(n > 0 && n % 8 == 0 && radius > 0.0 && radius < width / 2.0, "plate_with_hole: bad parameters");
    let h = width / 2.0;
    let c = DVec3::new(h, h, 0.0);
    let mut v = Vec::with_capacity(4 * n);
    // rings: 0 inner bottom, 1 inner top, 2 outer bottom, 3 outer top
    for ring in 0..4 {
        let z = if ring % 2 == 0 { 0.0 } else { thickness };
        for k in 0..n {
            let t = 2.0 * std::f64::consts::PI * k as f64 / n as f64;
            let (s, co) = t.sin_cos();
            let p = if ring < 2 {
                DVec3::new(radius * co, radius * s, 0.0)
            } else {
                // where the ray at angle t leaves the square [-h, h]²
                let m = co.abs().max(s.abs());
                DVec3::new(h * co / m, h * s / m, 0.0)
            };
            let mut p = c + p;
            // exact square corners and sides despite rounding
            if ring >= 2 {
                for a in 0..2 {
                    if (p[a] - 0.0).abs() < 1e-9 * width {
                        p[a] = 0.0;
                    }
                    if (p[a] - width).abs() < 1e-9 * width {
                        p[a] = width;
                    }
                }
            }
            v.push(DVec3::new(p.x, p.y, z));
        }
    }
    let id = |ring: usize, k: usize| (ring * n + k % n) as u32;
    let mut s = TriSurface::default();
    let mut push = |t: [u32; 3], tag: u32| {
        s.triangles.push(t);
        s.face_tags.push(FaceId(tag));
    };
    for k in 0..n {
        let k1 = k + 1;
        // top (z = thickness), counter-clockwise seen from above
        push([id(1, k), id(3, k), id(3, k1)], 1);
        push([id(1, k), id(3, k1), id(1, k1)], 1);
        // bottom, reversed
        push([id(0, k), id(2, k1), id(2, k)], 2);
        push([id(0, k), id(0, k1), id(2, k1)], 2);
        // outer side: the tag of the side the segment lies on
        let mid = 0.5 * (v[id(2, k) as usize] + v[id(2, k1) as usize]);
        let side = if mid.x == 0.0 {
            3
        } else if mid.x == width {
            4
        } else if mid.y == 0.0 {
            5
        } else {
            6
        };
        push([id(2, k), id(2, k1), id(3, k1)], side);
        push([id(2, k), id(3, k1), id(3, k)], side);
        // hole wall, facing the axis
        push([id(0, k), id(1, k), id(1, k1)], 7);
        push([id(0, k), id(1, k1), id(0, k1)], 7);
    }
    s.vertices = v;
    for (tag, name) in [(1, "top"), (2, "bottom"), (3, "side_xmin"), (4, "side_xmax"), (5, "side_ymin"), (6, "side_ymax"), (7, "hole")] {
        s.face_names.insert(FaceId(tag), name.to_string());
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_are_valid() {
        let m = kuhn_cube(4, 0.3, 7);
        assert_eq!(m.tets.len(), 384);
        assert_eq!(m.validate(), Ok(()));
        assert!((m.volume() - 1.0).abs() < 1e-12);
        let t = torus(3.0, 1.0, 12, 8);
        assert_eq!(t.validate(), Ok(()));
        assert_eq!(t.triangles.len(), 192);
    }
}
