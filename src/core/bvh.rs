//! Bounding-volume hierarchy over axis-aligned boxes.
//!
//! Input: items, each a `u32` index chosen by the caller and its [`Aabb`]. Output: a
//! [`Bvh`] answering which items' boxes overlap each other (every unordered pair once), a
//! query box, or a segment.
//!
//! # Invariants
//! - The nodes live in one flat array in depth-first order: an internal node's left child
//!   is the next node, its right child is stored in the node. Leaves hold at most
//!   [`Bvh::LEAF_SIZE`] items, contiguous in a permuted item array. Building allocates the
//!   node and item arrays once (no allocation per node).
//! - The tree is built by median splits along the longest axis of the box centres
//!   (`select_nth_unstable`, O(n log n) overall, depth about `log2(n / LEAF_SIZE)`), ties
//!   broken by item index, so the same input always gives the same tree.
//! - Every query reports items in the order of a fixed depth-first traversal: output order
//!   depends only on the input, never on timing or on the number of threads (the parallel
//!   traversal splits the work into the same tasks whatever the thread count and
//!   concatenates their results in task order).
//! - Box tests are exact comparisons on closed boxes (touching boxes overlap). Items whose
//!   box is empty (or has a NaN bound) are dropped.
//! - The segment query is conservative: it may report a box the segment misses by a
//!   relative margin of about `1e-9`, never miss one it touches. Callers decide with exact
//!   predicates.

use crate::core::Aabb;
use glam::DVec3;
use rayon::prelude::*;

/// One node of the flat tree.
#[derive(Copy, Clone, Debug)]
struct Node {
    bbox: Aabb,
    /// Leaf: index of its first item in `ids`/`boxes`; internal: index of the right child.
    first: u32,
    /// Leaf: number of items (at least 1); internal: 0.
    count: u32,
}

impl Node {
    #[inline]
    fn is_leaf(&self) -> bool {
        self.count > 0
    }
}

/// A unit of the pair traversal: the pairs inside one subtree, or between two subtrees.
#[derive(Copy, Clone, Debug)]
enum Task {
    Own(u32),
    Cross(u32, u32),
}

/// A bounding-volume hierarchy over caller-indexed boxes; see the module docs.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Item indices in leaf order.
    ids: Vec<u32>,
    /// Item boxes, parallel to `ids`.
    boxes: Vec<Aabb>,
}

/// Working record while building: a box centre and the item's input position.
#[derive(Copy, Clone)]
struct Prim {
    centre: DVec3,
    at: u32,
}

impl Bvh {
    /// Largest number of items in a leaf.
    pub const LEAF_SIZE: usize = 4;

    /// Depth to which the pair traversal is split into independent tasks (up to about
    /// `3^TASK_DEPTH` tasks, fewer where subtrees do not overlap).
    const TASK_DEPTH: u32 = 6;

    /// Builds the tree over `(item index, box)` pairs. Item indices need not be distinct
    /// or dense; empty boxes (and boxes with a NaN bound) are dropped. More items than
    /// a `u32` index can number give an empty tree.
    pub fn build(items: impl IntoIterator<Item = (u32, Aabb)>) -> Bvh {
        let (ids, boxes): (Vec<u32>, Vec<Aabb>) = items.into_iter().filter(|(_, b)| !b.is_empty()).unzip();
        let n = ids.len();
        if n == 0 || u32::try_from(n).is_err() {
            return Bvh::default();
        }
        let mut prims: Vec<Prim> = boxes.par_iter().enumerate().map(|(i, b)| Prim { centre: b.center(), at: i as u32 }).collect();
        let mut nodes = vec![Node { bbox: Aabb::EMPTY, first: 0, count: 0 }; subtree_nodes(n)];
        build_node(&mut prims, 0, &mut nodes, 0, &boxes);
        let ids = prims.iter().map(|p| ids[p.at as usize]).collect();
        let boxes = prims.iter().map(|p| boxes[p.at as usize]).collect();
        Bvh { nodes, ids, boxes }
    }

    /// Builds the tree over `boxes`, item `i` being `boxes[i]`.
    pub fn from_boxes(boxes: &[Aabb]) -> Bvh {
        Bvh::build(boxes.iter().enumerate().map(|(i, b)| (i as u32, *b)))
    }

    /// Number of items held.
    pub fn len(&self) -> usize {
        self.ids.len()
    }

    /// True when no item is held.
    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    /// The box of all items (empty for an empty tree).
    pub fn bbox(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| n.bbox)
    }

    /// Number of nodes (for statistics and tests).
    pub fn num_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// Calls `f(a, b)` with `a < b` for every unordered pair of items whose boxes overlap
    /// (pairs of equal item indices are skipped), in traversal order.
    pub fn for_each_overlapping_pair(&self, mut f: impl FnMut(u32, u32)) {
        if !self.nodes.is_empty() {
            self.run_task(Task::Own(0), &mut f);
        }
    }

    /// Every unordered pair `[a, b]`, `a < b`, of items whose boxes overlap, sorted.
    pub fn overlapping_pairs(&self) -> Vec<[u32; 2]> {
        let mut out = Vec::new();
        self.for_each_overlapping_pair(|a, b| out.push([a, b]));
        out.sort_unstable();
        out
    }

    /// The pair traversal of [`Bvh::for_each_overlapping_pair`] run in parallel: the
    /// traversal is cut into a fixed list of tasks; each task gets a fresh accumulator from
    /// `init` and `visit(&mut acc, a, b)` for each of its pairs. Returns the accumulators in
    /// task order, so that folding them in order gives the same result for any number of
    /// threads (and the same pairs in the same order as the serial traversal).
    pub fn par_fold_overlapping_pairs<A, I, V>(&self, init: I, visit: V) -> Vec<A>
    where
        A: Send,
        I: Fn() -> A + Sync,
        V: Fn(&mut A, u32, u32) + Sync,
    {
        if self.nodes.is_empty() {
            return Vec::new();
        }
        let mut tasks = Vec::new();
        self.split_task(Task::Own(0), Self::TASK_DEPTH, &mut tasks);
        tasks
            .par_iter()
            .map(|&t| {
                let mut acc = init();
                self.run_task(t, &mut |a, b| visit(&mut acc, a, b));
                acc
            })
            .collect()
    }

    /// The pairs for which `f` returns `Some`, computed in parallel, in serial traversal
    /// order (independent of the thread count).
    pub fn par_filter_map_overlapping_pairs<T, F>(&self, f: F) -> Vec<T>
    where
        T: Send,
        F: Fn(u32, u32) -> Option<T> + Sync,
    {
        let parts = self.par_fold_overlapping_pairs(Vec::new, |acc: &mut Vec<T>, a, b| {
            if let Some(x) = f(a, b) {
                acc.push(x);
            }
        });
        let mut out = Vec::with_capacity(parts.iter().map(Vec::len).sum());
        for p in parts {
            out.extend(p);
        }
        out
    }

    /// Calls `f(item)` for every item whose box overlaps the closed box `q`, in traversal
    /// order.
    pub fn for_each_overlapping(&self, q: &Aabb, mut f: impl FnMut(u32)) {
        self.walk(|b| b.overlaps(q), |b| b.overlaps(q), &mut f);
    }

    /// The items whose boxes overlap `q`, in traversal order.
    pub fn overlapping(&self, q: &Aabb) -> Vec<u32> {
        let mut out = Vec::new();
        self.for_each_overlapping(q, |i| out.push(i));
        out
    }

    /// Calls `f(item)` for every item whose box the closed segment `p`–`q` may touch
    /// (conservative, see the module docs), in traversal order.
    pub fn for_each_on_segment(&self, p: DVec3, q: DVec3, mut f: impl FnMut(u32)) {
        let Some(root) = self.nodes.first() else { return };
        let scale = p
            .abs()
            .max_element()
            .max(q.abs().max_element())
            .max(root.bbox.min.abs().max_element())
            .max(root.bbox.max.abs().max_element());
        let margin = 1e-9 * scale + f64::MIN_POSITIVE;
        let seg = SegmentProbe::new(p, q, margin);
        self.walk(|b| seg.hits(b), |b| seg.hits(b), &mut f);
    }

    /// True when some item's box overlaps the closed box `q` (stops at the first).
    pub fn any_overlapping(&self, q: &Aabb) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let mut stack: Vec<u32> = Vec::with_capacity(64);
        stack.push(0);
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n as usize];
            if !node.bbox.overlaps(q) {
                continue;
            }
            if node.is_leaf() {
                let r = node.first as usize..(node.first + node.count) as usize;
                if self.boxes[r].iter().any(|b| b.overlaps(q)) {
                    return true;
                }
            } else {
                stack.push(node.first);
                stack.push(n + 1);
            }
        }
        false
    }

    /// The root node (`None` for an empty tree). With [`Bvh::node`], for traversals that keep
    /// their own data per node (the fast winding number's dipoles): node indices are
    /// `0..num_nodes()`, and both children of a node have larger indices than the node, so a
    /// reverse sweep over the indices visits children before parents.
    pub fn root(&self) -> Option<u32> {
        (!self.nodes.is_empty()).then_some(0)
    }

    /// Node `n` (see [`Bvh::root`]).
    ///
    /// # Panics
    /// `n` out of range (`n >= num_nodes()`).
    pub fn node(&self, n: u32) -> NodeView<'_> {
        let node = &self.nodes[n as usize];
        if node.is_leaf() {
            let r = node.first as usize..(node.first + node.count) as usize;
            NodeView::Leaf { bbox: node.bbox, items: &self.ids[r] }
        } else {
            let (left, right) = self.children(n);
            NodeView::Internal { bbox: node.bbox, left, right }
        }
    }

    /// The item nearest to `p` by `dist(item)` (a distance no smaller than the distance from
    /// `p` to the item's box, such as the distance to the triangle the box bounds), and that
    /// distance: branch and bound over the boxes, ties to the smaller item index, so the
    /// answer depends only on the input. `None` for an empty tree.
    pub fn nearest(&self, p: DVec3, dist: impl Fn(u32) -> f64) -> Option<(u32, f64)> {
        self.nearest_from(p, None, dist)
    }

    /// [`Bvh::nearest`], starting from the item `hint` (an item of this tree, such as the
    /// answer for a point nearby): its distance bounds the search from the start, so far
    /// branches are never opened. The answer is the same as without a hint.
    pub fn nearest_from(&self, p: DVec3, hint: Option<u32>, dist: impl Fn(u32) -> f64) -> Option<(u32, f64)> {
        let best = hint.map(|h| (h, dist(h)));
        self.nearest_bounded(p, best, f64::INFINITY, dist)
    }

    /// [`Bvh::nearest`] among the items nearer than `max`: boxes farther are never opened
    /// (`dist` may return infinity for items to pass over). `None` when none is nearer.
    pub fn nearest_within(&self, p: DVec3, max: f64, dist: impl Fn(u32) -> f64) -> Option<(u32, f64)> {
        self.nearest_bounded(p, None, max, dist)
    }

    /// The search of [`Bvh::nearest_from`] and [`Bvh::nearest_within`]: from `best`, and
    /// without a start only items nearer than `max` taken (any item when `max` is infinite).
    fn nearest_bounded(&self, p: DVec3, mut best: Option<(u32, f64)>, max: f64, dist: impl Fn(u32) -> f64) -> Option<(u32, f64)> {
        if self.nodes.is_empty() {
            return None;
        }
        // boxes are compared by squared distance against the best distance squared, grown a
        // little so that rounding never prunes a box at exactly the best distance (pruning
        // stays conservative: the answer is the one the unsquared comparison gives)
        let limit = |bd: f64| bd * bd * (1.0 + 8.0 * f64::EPSILON);
        let mut best_sq = best.map_or(limit(max), |(_, bd)| limit(bd.min(max)));
        // a stack on the stack: no allocation per query (spills past its size)
        let mut stack = SmallStack::<(u32, f64)>::new();
        stack.push((0, box_distance_sq(&self.nodes[0].bbox, p)));
        while let Some((n, d)) = stack.pop() {
            if d > best_sq {
                continue;
            }
            let node = &self.nodes[n as usize];
            if node.is_leaf() {
                let r = node.first as usize..(node.first + node.count) as usize;
                for (&id, b) in self.ids[r.clone()].iter().zip(&self.boxes[r]) {
                    // an item's distance is no smaller than its box's
                    if box_distance_sq(b, p) > best_sq {
                        continue;
                    }
                    let di = dist(id);
                    let better = match best {
                        None => max == f64::INFINITY || di < max,
                        Some((bi, bd)) => di < bd || (di == bd && id < bi),
                    };
                    if better {
                        best = Some((id, di));
                        best_sq = limit(di);
                    }
                }
            } else {
                let (l, r) = self.children(n);
                let (dl, dr) = (box_distance_sq(&self.nodes[l as usize].bbox, p), box_distance_sq(&self.nodes[r as usize].bbox, p));
                // the nearer child is popped first
                if dl <= dr {
                    stack.push((r, dr));
                    stack.push((l, dl));
                } else {
                    stack.push((l, dl));
                    stack.push((r, dr));
                }
            }
        }
        best
    }

    /// Depth-first walk visiting nodes whose box passes `node_ok` and reporting items whose
    /// box passes `item_ok`.
    fn walk(&self, node_ok: impl Fn(&Aabb) -> bool, item_ok: impl Fn(&Aabb) -> bool, f: &mut impl FnMut(u32)) {
        if self.nodes.is_empty() {
            return;
        }
        // a stack on the stack: no allocation per walk (spills past its size)
        let mut stack = SmallStack::<u32>::new();
        stack.push(0);
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n as usize];
            if !node_ok(&node.bbox) {
                continue;
            }
            if node.is_leaf() {
                let r = node.first as usize..(node.first + node.count) as usize;
                for (id, b) in self.ids[r.clone()].iter().zip(&self.boxes[r]) {
                    if item_ok(b) {
                        f(*id);
                    }
                }
            } else {
                // right pushed first so that the left subtree is visited first
                stack.push(node.first);
                stack.push(n + 1);
            }
        }
    }

    #[inline]
    fn children(&self, n: u32) -> (u32, u32) {
        (n + 1, self.nodes[n as usize].first)
    }

    /// Cuts `t` into sub-tasks down to `depth` levels, in traversal order.
    fn split_task(&self, t: Task, depth: u32, out: &mut Vec<Task>) {
        match t {
            Task::Own(n) if depth > 0 && !self.nodes[n as usize].is_leaf() => {
                let (l, r) = self.children(n);
                self.split_task(Task::Own(l), depth - 1, out);
                self.split_task(Task::Own(r), depth - 1, out);
                self.split_task(Task::Cross(l, r), depth - 1, out);
            }
            Task::Cross(a, b) if depth > 0 => {
                let (na, nb) = (&self.nodes[a as usize], &self.nodes[b as usize]);
                if !na.bbox.overlaps(&nb.bbox) {
                    return;
                }
                if na.is_leaf() && nb.is_leaf() {
                    out.push(t);
                } else if !split_first(na, nb) {
                    let (l, r) = self.children(b);
                    self.split_task(Task::Cross(a, l), depth - 1, out);
                    self.split_task(Task::Cross(a, r), depth - 1, out);
                } else {
                    let (l, r) = self.children(a);
                    self.split_task(Task::Cross(l, b), depth - 1, out);
                    self.split_task(Task::Cross(r, b), depth - 1, out);
                }
            }
            _ => out.push(t),
        }
    }

    fn run_task(&self, t: Task, f: &mut impl FnMut(u32, u32)) {
        match t {
            Task::Own(n) => self.own_pairs(n, f),
            Task::Cross(a, b) => self.cross_pairs(a, b, f),
        }
    }

    #[inline]
    fn emit(&self, i: usize, j: usize, f: &mut impl FnMut(u32, u32)) {
        let (a, b) = (self.ids[i], self.ids[j]);
        if a != b && self.boxes[i].overlaps(&self.boxes[j]) {
            f(a.min(b), a.max(b));
        }
    }

    fn own_pairs(&self, n: u32, f: &mut impl FnMut(u32, u32)) {
        let node = self.nodes[n as usize];
        if node.is_leaf() {
            let (s, e) = (node.first as usize, (node.first + node.count) as usize);
            for i in s..e {
                for j in i + 1..e {
                    self.emit(i, j, f);
                }
            }
        } else {
            let (l, r) = self.children(n);
            self.own_pairs(l, f);
            self.own_pairs(r, f);
            self.cross_pairs(l, r, f);
        }
    }

    fn cross_pairs(&self, a: u32, b: u32, f: &mut impl FnMut(u32, u32)) {
        let (na, nb) = (self.nodes[a as usize], self.nodes[b as usize]);
        if !na.bbox.overlaps(&nb.bbox) {
            return;
        }
        if na.is_leaf() && nb.is_leaf() {
            for i in na.first..na.first + na.count {
                for j in nb.first..nb.first + nb.count {
                    self.emit(i as usize, j as usize, f);
                }
            }
        } else if !split_first(&na, &nb) {
            let (l, r) = self.children(b);
            self.cross_pairs(a, l, f);
            self.cross_pairs(a, r, f);
        } else {
            let (l, r) = self.children(a);
            self.cross_pairs(l, b, f);
            self.cross_pairs(r, b, f);
        }
    }
}

/// Whether the pair traversal descends into the first of two nodes (not both leaves): the
/// internal one, or the larger box.
#[inline]
fn split_first(a: &Node, b: &Node) -> bool {
    if a.is_leaf() || b.is_leaf() {
        return b.is_leaf();
    }
    let size = |n: &Node| n.bbox.extent().element_sum();
    size(a) >= size(b)
}

/// Number of nodes of the subtree over `n` items (median splits). Subtree sizes at depth
/// `d` are `floor(n / 2^d)` or one more (`r` of them, `n = q 2^d + r`); the first depth whose
/// smaller size fits a leaf holds all leaves except that nodes of `LEAF_SIZE + 1` items split
/// once more.
fn subtree_nodes(n: usize) -> usize {
    const L: usize = Bvh::LEAF_SIZE;
    if n <= L {
        return 1;
    }
    let mut d = 0;
    while (n >> d) > L {
        d += 1;
    }
    let q = n >> d;
    let r = n - (q << d);
    let leaves = if q < L || r == 0 { 1usize << d } else { (1usize << d) + r };
    2 * leaves - 1
}

/// Builds the subtree over `prims` into `nodes` (exactly its nodes, the root first, whose
/// global index is `base`); `offset` is the position of `prims[0]` in the final item order.
/// The halves are built in parallel above a size threshold; the result does not depend on it.
fn build_node(prims: &mut [Prim], offset: usize, nodes: &mut [Node], base: u32, boxes: &[Aabb]) {
    let n = prims.len();
    if n <= Bvh::LEAF_SIZE {
        let bbox = prims.iter().fold(Aabb::EMPTY, |b, p| b.union(&boxes[p.at as usize]));
        nodes[0] = Node { bbox, first: offset as u32, count: n as u32 };
        return;
    }
    let mut cb = Aabb::EMPTY;
    for p in prims.iter() {
        cb.grow(p.centre);
    }
    let e = cb.extent();
    let axis = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    let mid = n / 2;
    // one comparator per axis, so that the key load is not a run-time index
    match axis {
        0 => prims.select_nth_unstable_by(mid, |a, b| a.centre.x.total_cmp(&b.centre.x).then(a.at.cmp(&b.at))),
        1 => prims.select_nth_unstable_by(mid, |a, b| a.centre.y.total_cmp(&b.centre.y).then(a.at.cmp(&b.at))),
        _ => prims.select_nth_unstable_by(mid, |a, b| a.centre.z.total_cmp(&b.centre.z).then(a.at.cmp(&b.at))),
    };
    let (left, right) = prims.split_at_mut(mid);
    let left_nodes = subtree_nodes(mid);
    let (root, rest) = nodes.split_at_mut(1);
    let (ln, rn) = rest.split_at_mut(left_nodes);
    let right_base = base + 1 + left_nodes as u32;
    if n > 8192 {
        rayon::join(|| build_node(left, offset, ln, base + 1, boxes), || build_node(right, offset + mid, rn, right_base, boxes));
    } else {
        build_node(left, offset, ln, base + 1, boxes);
        build_node(right, offset + mid, rn, right_base, boxes);
    }
    root[0] = Node { bbox: ln[0].bbox.union(&rn[0].bbox), first: right_base, count: 0 };
}

/// One node of a [`Bvh`], read only.
#[derive(Copy, Clone, Debug)]
pub enum NodeView<'a> {
    /// A leaf: its box and its items (at most [`Bvh::LEAF_SIZE`]).
    Leaf {
        /// The box of its items.
        bbox: Aabb,
        /// The caller's item indices.
        items: &'a [u32],
    },
    /// An internal node: its box and its two children.
    Internal {
        /// The box of its subtree.
        bbox: Aabb,
        /// The left child's index.
        left: u32,
        /// The right child's index.
        right: u32,
    },
}

/// A LIFO stack of up to 64 entries in place, spilling into a vector beyond: for traversals
/// of the tree that keep their own per-node data ([`Bvh::node`]).
pub(crate) struct SmallStack<T: Copy + Default> {
    items: [T; 64],
    len: usize,
    spill: Vec<T>,
}

impl<T: Copy + Default> SmallStack<T> {
    /// An empty stack.
    pub(crate) fn new() -> Self {
        SmallStack { items: [T::default(); 64], len: 0, spill: Vec::new() }
    }

    /// Pushes `x`.
    pub(crate) fn push(&mut self, x: T) {
        if self.len < self.items.len() {
            self.items[self.len] = x;
            self.len += 1;
        } else {
            self.spill.push(x);
        }
    }

    /// The last entry pushed, removed.
    pub(crate) fn pop(&mut self) -> Option<T> {
        if let Some(x) = self.spill.pop() {
            return Some(x);
        }
        self.len = self.len.checked_sub(1)?;
        Some(self.items[self.len])
    }
}

/// The squared distance from `p` to the closed box `b` (0 inside, infinite for an empty box).
pub(crate) fn box_distance_sq(b: &Aabb, p: DVec3) -> f64 {
    let d = (b.min - p).max(p - b.max).max(DVec3::ZERO);
    d.length_squared()
}

/// A segment prepared for conservative slab tests against boxes.
struct SegmentProbe {
    p: DVec3,
    d: DVec3,
    inv: DVec3,
    sbox: Aabb,
    margin: f64,
}

impl SegmentProbe {
    fn new(p: DVec3, q: DVec3, margin: f64) -> Self {
        let d = q - p;
        let mut sbox = Aabb::from_points(&[p, q]);
        sbox.min -= DVec3::splat(margin);
        sbox.max += DVec3::splat(margin);
        SegmentProbe { p, d, inv: d.recip(), sbox, margin }
    }

    /// True unless the segment certainly misses `b` (inflated by the margin).
    fn hits(&self, b: &Aabb) -> bool {
        if !self.sbox.overlaps(b) {
            return false;
        }
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for k in 0..3 {
            let (lo, hi) = (b.min[k] - self.margin, b.max[k] + self.margin);
            if self.d[k] == 0.0 {
                if self.p[k] < lo || self.p[k] > hi {
                    return false;
                }
                continue;
            }
            let ta = (lo - self.p[k]) * self.inv[k];
            let tb = (hi - self.p[k]) * self.inv[k];
            t0 = t0.max(ta.min(tb));
            t1 = t1.min(ta.max(tb));
            if t0 > t1 {
                return false;
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rng(seed: &mut u64) -> f64 {
        *seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((*seed >> 11) as f64) / ((1u64 << 53) as f64)
    }

    fn random_boxes(n: usize, seed: u64) -> Vec<Aabb> {
        let mut s = seed;
        (0..n)
            .map(|_| {
                let c = DVec3::new(rng(&mut s), rng(&mut s), rng(&mut s)) * 10.0;
                let h = DVec3::new(rng(&mut s), rng(&mut s), rng(&mut s)) * 0.6;
                Aabb { min: c - h, max: c + h }
            })
            .collect()
    }

    /// A random query point around the boxes of [`random_boxes`].
    fn query_point(s: &mut u64) -> DVec3 {
        DVec3::new(rng(s), rng(s), rng(s)) * 12.0 - DVec3::ONE
    }

    #[test]
    fn nearest_and_any_overlapping_match_brute_force() {
        let boxes = random_boxes(500, 7);
        let bvh = Bvh::from_boxes(&boxes);
        let mut s = 99u64;
        for _ in 0..200 {
            let p = query_point(&mut s);
            // the distance to a box's centre is at least the distance to the box
            let d = |i: u32| boxes[i as usize].center().distance(p);
            let want = (0..boxes.len() as u32).map(|i| (i, d(i))).min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0))).unwrap();
            assert_eq!(bvh.nearest(p, d), Some(want));
            let q = Aabb { min: p - DVec3::splat(0.3), max: p + DVec3::splat(0.3) };
            assert_eq!(bvh.any_overlapping(&q), boxes.iter().any(|b| b.overlaps(&q)));
        }
        assert_eq!(Bvh::default().nearest(DVec3::ZERO, |_| 0.0), None);
        assert!(!Bvh::default().any_overlapping(&boxes[0]));
    }

    #[test]
    fn nearest_within_matches_brute_force_and_passes_over_infinite_items() {
        let boxes = random_boxes(500, 11);
        let bvh = Bvh::from_boxes(&boxes);
        let mut s = 5u64;
        for k in 0..200 {
            let p = query_point(&mut s);
            // every third item passed over; a bound from 0.2 to 2
            let d = |i: u32| if i % 3 == 0 { f64::INFINITY } else { boxes[i as usize].center().distance(p) };
            let max = 0.2 + 1.8 * (k as f64 / 200.0);
            let want = (0..boxes.len() as u32).map(|i| (i, d(i))).filter(|&(_, x)| x < max).min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
            assert_eq!(bvh.nearest_within(p, max, d), want);
        }
        assert_eq!(Bvh::default().nearest_within(DVec3::ZERO, 1.0, |_| 0.0), None);
    }

    fn brute_pairs(b: &[Aabb]) -> Vec<[u32; 2]> {
        let mut out = Vec::new();
        for i in 0..b.len() {
            for j in i + 1..b.len() {
                if b[i].overlaps(&b[j]) {
                    out.push([i as u32, j as u32]);
                }
            }
        }
        out
    }

    #[test]
    fn pairs_match_brute_force() {
        for (n, seed) in [(0, 1), (1, 2), (5, 3), (37, 4), (500, 5)] {
            let b = random_boxes(n, seed);
            let bvh = Bvh::from_boxes(&b);
            assert_eq!(bvh.len(), n);
            assert_eq!(bvh.overlapping_pairs(), brute_pairs(&b), "n = {n}");
            let mut par: Vec<[u32; 2]> = bvh.par_filter_map_overlapping_pairs(|a, b| Some([a, b]));
            let mut ser = Vec::new();
            bvh.for_each_overlapping_pair(|a, b| ser.push([a, b]));
            assert_eq!(par, ser, "parallel order equals serial order");
            par.sort_unstable();
            assert_eq!(par, brute_pairs(&b));
        }
    }

    #[test]
    fn same_order_for_any_thread_count() {
        let b = random_boxes(3000, 9);
        let bvh = Bvh::from_boxes(&b);
        let run = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map(|pool| pool.install(|| bvh.par_filter_map_overlapping_pairs(|a, b| Some([a, b]))))
                .unwrap_or_default()
        };
        let one = run(1);
        assert!(!one.is_empty());
        assert_eq!(one, run(3));
        assert_eq!(one, run(8));
    }

    #[test]
    fn box_and_segment_queries() {
        let b = random_boxes(800, 11);
        let bvh = Bvh::from_boxes(&b);
        let q = Aabb { min: DVec3::new(2.0, 3.0, 1.0), max: DVec3::new(4.0, 5.5, 6.0) };
        let mut got = bvh.overlapping(&q);
        got.sort_unstable();
        let want: Vec<u32> = (0..b.len() as u32).filter(|&i| b[i as usize].overlaps(&q)).collect();
        assert_eq!(got, want);
        // segment: every box the segment really crosses (sampled densely) must be reported
        let (p, r) = (DVec3::new(-1.0, 0.5, 2.0), DVec3::new(11.0, 9.0, 7.5));
        let mut seg = Vec::new();
        bvh.for_each_on_segment(p, r, |i| seg.push(i));
        for (i, bx) in b.iter().enumerate() {
            let crossed = (0..=4000).any(|k| {
                let x = p + (r - p) * (k as f64 / 4000.0);
                bx.overlaps(&Aabb { min: x, max: x })
            });
            if crossed {
                assert!(seg.contains(&(i as u32)), "box {i} missed");
            }
        }
        assert!(seg.len() < b.len() / 2, "segment query prunes");
        // axis-parallel segment on a box face still reports it
        let unit = Bvh::from_boxes(&[Aabb { min: DVec3::ZERO, max: DVec3::ONE }]);
        let mut hit = false;
        unit.for_each_on_segment(DVec3::new(-1.0, 1.0, 0.5), DVec3::new(2.0, 1.0, 0.5), |_| hit = true);
        assert!(hit);
        let mut miss = false;
        unit.for_each_on_segment(DVec3::new(-1.0, 1.5, 0.5), DVec3::new(2.0, 1.5, 0.5), |_| miss = true);
        assert!(!miss);
    }

    #[test]
    fn node_count_formula() {
        fn count(n: usize) -> usize {
            if n <= Bvh::LEAF_SIZE { 1 } else { 1 + count(n / 2) + count(n - n / 2) }
        }
        for n in 1..3000 {
            assert_eq!(subtree_nodes(n), count(n), "n = {n}");
        }
        let b = random_boxes(20_000, 3);
        assert_eq!(Bvh::from_boxes(&b).num_nodes(), count(20_000));
    }

    #[test]
    fn degenerate_inputs() {
        // identical boxes: balanced tree anyway, all pairs reported once
        let b = vec![Aabb { min: DVec3::ZERO, max: DVec3::ONE }; 50];
        let bvh = Bvh::from_boxes(&b);
        assert_eq!(bvh.overlapping_pairs().len(), 50 * 49 / 2);
        assert!(bvh.num_nodes() < 50);
        // empty and NaN boxes are dropped
        let nan = Aabb { min: DVec3::splat(f64::NAN), max: DVec3::splat(f64::NAN) };
        let bvh = Bvh::build([(7, Aabb::EMPTY), (8, nan), (9, b[0]), (10, b[0])]);
        assert_eq!(bvh.len(), 2);
        assert_eq!(bvh.overlapping_pairs(), vec![[9, 10]]);
        // repeated item indices never pair with themselves
        let bvh = Bvh::build([(3, b[0]), (3, b[0])]);
        assert!(bvh.overlapping_pairs().is_empty());
        assert!(Bvh::from_boxes(&[]).overlapping(&b[0]).is_empty());
    }
}
