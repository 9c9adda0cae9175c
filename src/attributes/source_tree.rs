//! The fastest way to evaluate `min_i min(h_i + g_i · d(p, T_i), c_i)` over many triangles
//! `T_i` (size sources on faces and edges): a bounding-volume tree whose nodes keep the
//! smallest `h`, `g` and `c` below them, searched branch and bound.

use super::selector::point_triangle_distance;
use crate::core::Aabb;
use glam::DVec3;

/// One source triangle (a segment is a triangle with two equal corners).
#[derive(Copy, Clone, Debug)]
pub struct Source {
    /// The corners.
    pub tri: [DVec3; 3],
    /// Size on the triangle.
    pub h: f64,
    /// Growth of the size with distance.
    pub slope: f64,
    /// Largest size the source asks for (infinite for none).
    pub cap: f64,
}

struct Node {
    bbox: Aabb,
    h: f64,
    slope: f64,
    cap: f64,
    /// Leaf: `items[start..end]`; inner: children at `left` and `left + 1`... stored as indices.
    kind: Kind,
}

enum Kind {
    Leaf(usize, usize),
    Inner(u32, u32),
}

/// The tree.
pub struct SourceTree {
    items: Vec<Source>,
    nodes: Vec<Node>,
}

const LEAF: usize = 8;

impl SourceTree {
    /// A tree over `items` (`None` for no items).
    pub fn build(mut items: Vec<Source>) -> Option<SourceTree> {
        if items.is_empty() {
            return None;
        }
        let mut nodes = Vec::with_capacity(2 * items.len() / LEAF + 2);
        let n = items.len();
        build(&mut items, 0, n, &mut nodes);
        Some(SourceTree { items, nodes })
    }

    /// `min_i min(h_i + g_i d(p, T_i), c_i)`, or `bound` if that is smaller.
    pub fn query(&self, p: DVec3, bound: f64) -> f64 {
        let mut best = bound;
        let mut stack = vec![0u32];
        while let Some(k) = stack.pop() {
            let node = &self.nodes[k as usize];
            let lb = (node.h + node.slope * box_distance(p, &node.bbox)).min(node.cap);
            if lb >= best {
                continue;
            }
            match node.kind {
                Kind::Leaf(s, e) => {
                    for it in &self.items[s..e] {
                        let v = (it.h + it.slope * point_triangle_distance(p, it.tri)).min(it.cap);
                        best = best.min(v);
                    }
                }
                Kind::Inner(a, b) => {
                    stack.push(b);
                    stack.push(a);
                }
            }
        }
        best
    }
}

fn build(items: &mut [Source], start: usize, end: usize, nodes: &mut Vec<Node>) -> u32 {
    let slice = &mut items[start..end];
    let mut bbox = Aabb::EMPTY;
    let (mut h, mut slope, mut cap) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
    for s in slice.iter() {
        for p in s.tri {
            bbox.grow(p);
        }
        h = h.min(s.h);
        slope = slope.min(s.slope);
        cap = cap.min(s.cap);
    }
    let me = nodes.len() as u32;
    nodes.push(Node { bbox, h, slope, cap, kind: Kind::Leaf(start, end) });
    if end - start > LEAF {
        let e = bbox.extent();
        let axis = if e.x >= e.y && e.x >= e.z { 0 } else if e.y >= e.z { 1 } else { 2 };
        let key = |s: &Source| (s.tri[0][axis] + s.tri[1][axis] + s.tri[2][axis]) / 3.0;
        let mid = slice.len() / 2;
        slice.select_nth_unstable_by(mid, |a, b| key(a).total_cmp(&key(b)));
        let a = build(items, start, start + mid, nodes);
        let b = build(items, start + mid, end, nodes);
        nodes[me as usize].kind = Kind::Inner(a, b);
    }
    me
}

fn box_distance(p: DVec3, b: &Aabb) -> f64 {
    let d = (b.min - p).max(p - b.max).max(DVec3::ZERO);
    d.length()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tree_gives_the_brute_force_minimum() {
        // sources on a grid of small triangles with varying sizes and slopes
        let mut items = Vec::new();
        for i in 0..20 {
            for j in 0..20 {
                let o = DVec3::new(i as f64, j as f64, ((i * 7 + j * 3) % 5) as f64);
                items.push(Source { tri: [o, o + DVec3::X * 0.5, o + DVec3::Y * 0.5], h: 0.1 + ((i + j) % 7) as f64 * 0.05, slope: 0.2 + (i % 3) as f64 * 0.1, cap: if j % 4 == 0 { 0.6 } else { f64::INFINITY } });
            }
        }
        let tree = SourceTree::build(items.clone()).unwrap();
        for k in 0..200 {
            let p = DVec3::new((k * 37 % 230) as f64 * 0.1 - 1.0, (k * 53 % 210) as f64 * 0.1 - 0.5, (k % 9) as f64 - 2.0);
            let brute = items.iter().map(|s| (s.h + s.slope * point_triangle_distance(p, s.tri)).min(s.cap)).fold(5.0, f64::min);
            assert_eq!(tree.query(p, 5.0), brute, "at {p}");
        }
    }
}
