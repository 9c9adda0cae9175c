//! Imprinting touching solids on each other, so that they mesh into one conforming mesh.
//!
//! The faces in contact (the [`Contact`]s) form components: faces joined where they touch. A
//! component whose faces lie in one plane is remade of one triangulation of that plane
//! ([`imprint_plane`]): where two solids' faces overlap they then have the same points and
//! triangles (the overlap is tessellated once, by the master face's points), and each face's
//! part outside the overlap is triangulated up to the overlap's border. A boundary edge of a
//! face that the imprint splits (where another solid's border meets it) is split in the
//! triangle across it too, so each solid stays closed. Each solid is then meshed on its own
//! with these faces kept, and the meshes merge where their boundary triangles coincide
//! ([`super::merge`]): a conforming interface, each solid a region.
//!
//! Each component is imprinted whole or not at all, and each solid checked again after: a
//! solid whose imprinted surface the mesher's input check refuses goes back to its own
//! surface (its contacts are then tied, as are components that cannot be imprinted: curved
//! contacts, faces not in one plane).

use super::imprint_plane::{self, Face};
use super::solid::SolidSurface;
use super::{Contact, Solids};
use crate::core::FaceId;
use crate::core::ids::NONE;
use crate::mesh::TriSurface;
use crate::core::intersection::is_degenerate;
use crate::core::union_find::UnionFind;
use crate::mesh3d::mesher::input;
use rustc_hash::FxHashMap;
use std::collections::BTreeSet;

/// What imprinting did.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct ImprintOutcome {
    /// Components of faces in contact.
    pub components: usize,
    /// Of them, the ones imprinted.
    pub imprinted: usize,
    /// Solids whose imprinted surface was refused, back to their own.
    pub reverted: Vec<usize>,
    /// The sum over the solids of how much imprinting changed the volume each encloses.
    pub volume: f64,
}

/// Imprints the faces in `contacts` on each other (see the module docs); `gap` is the
/// distance within which two solids' points are one.
pub(crate) fn imprint(parts: &mut [SolidSurface], contacts: &[Contact], solids: &Solids, gap: f64) -> ImprintOutcome {
    let index_of = |tag| solids.solids.iter().position(|s| s.tag == tag);
    let mut nodes: Vec<(usize, FaceId)> = Vec::new();
    let mut links = Vec::new();
    for c in contacts {
        let (Some(a), Some(b)) = (index_of(c.solid_a), index_of(c.solid_b)) else { continue };
        links.push(((a, c.face_a), (b, c.face_b)));
        nodes.push((a, c.face_a));
        nodes.push((b, c.face_b));
    }
    nodes.sort_unstable();
    nodes.dedup();
    let node = |x: &(usize, FaceId)| nodes.binary_search(x).expect("a node") as u32;
    let mut uf = UnionFind::new(nodes.len());
    for (x, y) in &links {
        uf.union(node(x), node(y));
    }
    // components in the order of their first node; nodes in (solid, face) order: the rank
    let mut members: FxHashMap<u32, Vec<usize>> = FxHashMap::default();
    for k in 0..nodes.len() {
        members.entry(uf.find(k as u32)).or_default().push(k);
    }
    let mut components: Vec<Vec<usize>> = members.into_values().collect();
    components.sort_unstable();
    let originals: Vec<_> = parts.iter().map(|p| p.surface.clone()).collect();
    let mut changed = BTreeSet::new();
    let mut out = ImprintOutcome { components: components.len(), ..ImprintOutcome::default() };
    for comp in &components {
        let faces: Vec<(usize, FaceId)> = comp.iter().map(|&k| nodes[k]).collect();
        if let Some(solids_touched) = imprint_component(parts, &faces, gap) {
            out.imprinted += 1;
            changed.extend(solids_touched);
        }
    }
    for s in changed {
        let p = &mut parts[s];
        let before = originals[s].signed_volume();
        if input::check(&p.surface).is_err() {
            p.surface = originals[s].clone();
            out.reverted.push(s);
        }
        out.volume += (p.surface.signed_volume() - before).abs();
        p.prepare();
    }
    out
}

/// Imprints one component (faces as (solid, face tag), in rank order); the solids it changed,
/// or `None` where it could not be imprinted (nothing changed).
fn imprint_component(parts: &mut [SolidSurface], nodes: &[(usize, FaceId)], gap: f64) -> Option<Vec<usize>> {
    let faces: Vec<Face> = nodes
        .iter()
        .map(|&(s, f)| {
            let surface = &parts[s].surface;
            let triangles = surface.triangles.iter().zip(&surface.face_tags).filter(|(_, t)| **t == f).map(|(t, _)| *t).collect();
            Face { solid: s, triangles, vertices: &surface.vertices }
        })
        .collect();
    if faces.iter().any(|f| f.triangles.is_empty()) {
        return None;
    }
    let imprinted = imprint_plane::imprint(&faces, gap)?;
    let mut touched: Vec<usize> = nodes.iter().map(|n| n.0).collect();
    touched.sort_unstable();
    touched.dedup();
    let mut remade = Vec::with_capacity(touched.len());
    for &s in &touched {
        remade.push((s, remake(&parts[s].surface, s, nodes, &imprinted)?));
    }
    for (s, (surface, triangle_from, vertex_from)) in remade {
        let p = &mut parts[s];
        p.triangle_of = triangle_from.iter().map(|&t| p.triangle_of[t as usize]).collect();
        p.vertex_of = vertex_from.iter().map(|&v| if v == NONE { NONE } else { p.vertex_of[v as usize] }).collect();
        p.surface = surface;
    }
    Some(touched)
}

/// Solid `s`'s surface with its faces of the component replaced by their imprinted
/// triangles and the triangles across split edges split, the vertices no triangle uses left
/// out (the points of a face that another solid's face covers); with it, the triangle each
/// triangle comes from (a face's first for its new ones) and the vertex each vertex was
/// ([`NONE`] for new points). `None` if a new triangle has zero area.
fn remake(surface: &TriSurface, s: usize, nodes: &[(usize, FaceId)], im: &imprint_plane::Imprinted) -> Option<(TriSurface, Vec<u32>, Vec<u32>)> {
    let mut out = surface.clone();
    let mine: Vec<usize> = (0..nodes.len()).filter(|&k| nodes[k].0 == s).collect();
    let my_faces: Vec<FaceId> = mine.iter().map(|&k| nodes[k].1).collect();
    // every point this solid uses: its own vertex, or a new one
    let mut local: FxHashMap<u32, u32> = FxHashMap::default();
    let mut used: BTreeSet<u32> = BTreeSet::new();
    for &k in &mine {
        used.extend(im.faces[k].iter().flatten().copied());
        for (_, chain) in &im.chains[k] {
            used.extend(chain.iter().copied());
        }
    }
    for &p in &used {
        let point = &im.points[p as usize];
        let id = match point.of.iter().find(|o| o.0 == s) {
            Some(&(_, v)) => v,
            None => {
                out.vertices.push(point.p3);
                out.vertices.len() as u32 - 1
            }
        };
        local.insert(p, id);
    }
    // a point several solids use stands at one place in all of them
    for (&p, &v) in &local {
        out.vertices[v as usize] = im.points[p as usize].p3;
    }
    let mut triangles = Vec::with_capacity(out.triangles.len());
    let mut tags = Vec::with_capacity(out.triangles.len());
    let mut from: Vec<u32> = Vec::with_capacity(out.triangles.len());
    let mut first_of: FxHashMap<FaceId, u32> = FxHashMap::default();
    for (i, (t, &f)) in out.triangles.iter().zip(&out.face_tags).enumerate() {
        if !my_faces.contains(&f) {
            triangles.push(*t);
            tags.push(f);
            from.push(i as u32);
        } else {
            first_of.entry(f).or_insert(i as u32);
        }
    }
    let kept = triangles.len();
    for &k in &mine {
        for t in &im.faces[k] {
            triangles.push(t.map(|p| local[&p]));
            tags.push(nodes[k].1);
            from.push(first_of.get(&nodes[k].1).copied().unwrap_or(0));
        }
    }
    // the triangles across split boundary edges (not faces of the component: those are
    // remade already), split at the chain's points
    let mut edge: FxHashMap<(u32, u32), usize> = FxHashMap::default();
    for (i, t) in triangles.iter().enumerate().take(kept) {
        for j in 0..3 {
            edge.insert((t[j], t[(j + 1) % 3]), i);
        }
    }
    let mut split = Vec::new();
    for &k in &mine {
        for ([a, b], chain) in &im.chains[k] {
            if chain.len() <= 2 {
                continue;
            }
            let Some(&first) = edge.get(&(*b, *a)) else { continue };
            if first >= kept {
                continue;
            }
            // insert the chain's points from a's end: each splits the edge b -> prev
            let mut prev = *a;
            for &p in &chain[1..chain.len() - 1] {
                let x = local[&p];
                let &t = edge.get(&(*b, prev))?;
                let tri = triangles[t];
                let r = (0..3).find(|&j| tri[j] == *b && tri[(j + 1) % 3] == prev)?;
                let z = tri[(r + 2) % 3];
                triangles[t] = [*b, x, z];
                split.push(t);
                triangles.push([x, prev, z]);
                tags.push(tags[t]);
                from.push(from[t]);
                let n = triangles.len() - 1;
                edge.remove(&(*b, prev));
                edge.insert((*b, x), t);
                edge.insert((x, z), t);
                edge.insert((z, *b), t);
                edge.insert((x, prev), n);
                edge.insert((prev, z), n);
                edge.insert((z, x), n);
                prev = x;
            }
        }
    }
    let new_split: Vec<usize> = (kept + im_count(&mine, im)..triangles.len()).collect();
    split.extend(new_split);
    flip_fans(&mut triangles, &tags, &mut edge, &out.vertices, &split);
    for t in triangles.iter().skip(kept).chain(split.iter().map(|&i| &triangles[i])) {
        if is_degenerate(out.vertices[t[0] as usize], out.vertices[t[1] as usize], out.vertices[t[2] as usize]) {
            return None;
        }
    }
    // the vertices in use, in their order
    let mut new_index = vec![NONE; out.vertices.len()];
    for t in &triangles {
        for &v in t {
            new_index[v as usize] = 0;
        }
    }
    let old_count = surface.vertices.len() as u32;
    let mut vertices = Vec::with_capacity(out.vertices.len());
    let mut vertex_from = Vec::with_capacity(out.vertices.len());
    for (v, slot) in new_index.iter_mut().enumerate() {
        if *slot == 0 {
            *slot = vertices.len() as u32;
            vertices.push(out.vertices[v]);
            vertex_from.push(if (v as u32) < old_count { v as u32 } else { NONE });
        }
    }
    out.vertices = vertices;
    out.triangles = triangles.into_iter().map(|t| t.map(|v| new_index[v as usize])).collect();
    out.face_tags = tags;
    Some((out, from, vertex_from))
}


/// The imprinted faces' triangles of this solid.
fn im_count(mine: &[usize], im: &imprint_plane::Imprinted) -> usize {
    mine.iter().map(|&k| im.faces[k].len()).sum()
}

/// Lawson flips in the planar faces beside the imprint, from the triangles split there
/// (`split`): a split fans a triangle from its far corner onto the chain's points, long thin
/// triangles the tet mesher would turn into slivers. An edge between two coplanar triangles
/// of one face is flipped where the angles facing it add up to more than π (the Delaunay
/// test) and the quadrilateral is convex; at most a count of flips proportional to the
/// split triangles.
fn flip_fans(triangles: &mut [[u32; 3]], tags: &[FaceId], edge: &mut FxHashMap<(u32, u32), usize>, vertices: &[glam::DVec3], split: &[usize]) {
    let p = |v: u32| vertices[v as usize];
    let normal = |t: [u32; 3]| (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0]));
    let third = |t: [u32; 3], a: u32, b: u32| t.into_iter().find(|&v| v != a && v != b);
    let angle = |at: u32, x: u32, y: u32| (p(x) - p(at)).angle_between(p(y) - p(at));
    let mut stack: Vec<(u32, u32)> = split.iter().flat_map(|&t| {
        let t = triangles[t];
        [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]
    }).collect();
    let mut budget = 20 * split.len() + 100;
    while let Some((a, b)) = stack.pop() {
        if budget == 0 {
            break;
        }
        budget -= 1;
        let (Some(&t1), Some(&t2)) = (edge.get(&(a, b)), edge.get(&(b, a))) else { continue };
        if t1 == t2 || tags[t1] != tags[t2] {
            continue;
        }
        let (Some(w1), Some(w2)) = (third(triangles[t1], a, b), third(triangles[t2], b, a)) else { continue };
        if w1 == w2 || edge.contains_key(&(w1, w2)) || edge.contains_key(&(w2, w1)) {
            continue;
        }
        let (n1, n2) = (normal(triangles[t1]), normal(triangles[t2]));
        if n1.normalize_or_zero().dot(n2.normalize_or_zero()) < 1.0 - 1e-12 {
            continue;
        }
        if angle(w1, a, b) + angle(w2, b, a) <= std::f64::consts::PI + 1e-12 {
            continue;
        }
        let (x, y) = ([a, w2, w1], [w2, b, w1]);
        if normal(x).dot(n1) <= 0.0 || normal(y).dot(n1) <= 0.0 {
            continue;
        }
        triangles[t1] = x;
        triangles[t2] = y;
        edge.remove(&(a, b));
        edge.remove(&(b, a));
        for (t, tri) in [(t1, x), (t2, y)] {
            for j in 0..3 {
                edge.insert((tri[j], tri[(j + 1) % 3]), t);
            }
        }
        stack.extend([(a, w2), (w2, b), (b, w1), (w1, a)]);
    }
}
