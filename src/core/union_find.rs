//! Disjoint sets over `0..n` (`u32` elements): the one union-find of the crate, used for
//! shells and vertex fans of a surface (`mesh/topology`), merged facets of the mesher's
//! surface model and face groups of the tessellation certificate.
//!
//! Rule: **the root of a set is its smallest element**, so roots (and everything numbered by
//! them) do not depend on the order of the unions. `find` halves paths as it walks; with the
//! smallest-root rule instead of union by rank a find costs `O(log n)` amortised, which is
//! plenty for the sizes here (triangles of a surface, faces of a model).
//!
//! [`ParityUnionFind`] is the same structure whose elements carry a parity (a bit) relative to
//! their root: a union states "`a` and `b` differ by `rel`" and reports a contradiction with
//! earlier unions (orientability of a surface: triangles flipped or not relative to their
//! neighbours).

use crate::core::ids::NONE;

/// Disjoint sets of `0..n` with path halving; the smallest element of a set is its root.
#[derive(Clone, Debug)]
pub(crate) struct UnionFind {
    parent: Vec<u32>,
    /// Elements of the set, valid at roots.
    size: Vec<u32>,
}

impl UnionFind {
    /// `n` singletons.
    pub fn new(n: usize) -> Self {
        debug_assert!(u32::try_from(n).is_ok());
        UnionFind { parent: (0..n as u32).collect(), size: vec![1; n] }
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.parent.len()
    }

    /// The root (smallest element) of the set of `x`.
    pub fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let g = self.parent[self.parent[x as usize] as usize];
            self.parent[x as usize] = g;
            x = g;
        }
        x
    }

    /// Joins the sets of `a` and `b`; false if they were one already.
    pub fn union(&mut self, a: u32, b: u32) -> bool {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return false;
        }
        let (root, child) = (ra.min(rb), ra.max(rb));
        self.parent[child as usize] = root;
        self.size[root as usize] += self.size[child as usize];
        true
    }

    /// Number of elements in the set of `x`.
    #[cfg(test)]
    pub fn size(&mut self, x: u32) -> u32 {
        let r = self.find(x);
        self.size[r as usize]
    }

    /// True if `x` is the root of its set (each set has exactly one).
    pub fn is_root(&self, x: u32) -> bool {
        self.parent[x as usize] == x
    }

    /// The set of every element numbered `0, 1, …` in order of its smallest element, and the
    /// number of sets.
    pub fn labels(&mut self) -> (Vec<u32>, usize) {
        let n = self.len();
        let mut label_of_root = vec![NONE; n];
        let mut labels = vec![0u32; n];
        let mut count = 0u32;
        for x in 0..n as u32 {
            let r = self.find(x) as usize;
            if label_of_root[r] == NONE {
                label_of_root[r] = count;
                count += 1;
            }
            labels[x as usize] = label_of_root[r];
        }
        (labels, count as usize)
    }
}

/// [`UnionFind`] whose elements carry a parity relative to their root (smallest element).
#[derive(Clone, Debug)]
pub(crate) struct ParityUnionFind {
    parent: Vec<u32>,
    /// Parity relative to the parent.
    parity: Vec<bool>,
}

impl ParityUnionFind {
    /// `n` singletons, each of parity 0.
    pub fn new(n: usize) -> Self {
        debug_assert!(u32::try_from(n).is_ok());
        ParityUnionFind { parent: (0..n as u32).collect(), parity: vec![false; n] }
    }

    /// The root of the set of `x` and the parity of `x` relative to it.
    pub fn find(&mut self, x: u32) -> (u32, bool) {
        let (mut r, mut p) = (x, false);
        while self.parent[r as usize] != r {
            p ^= self.parity[r as usize];
            r = self.parent[r as usize];
        }
        // compress: every node on the path points to the root with its own parity
        let (mut y, mut py) = (x, p);
        while self.parent[y as usize] != y {
            let next = self.parent[y as usize];
            let b = self.parity[y as usize];
            self.parent[y as usize] = r;
            self.parity[y as usize] = py;
            py ^= b;
            y = next;
        }
        (r, p)
    }

    /// Requires `parity(a) ^ parity(b) == rel`; false if that contradicts earlier unions
    /// (nothing changes then).
    pub fn union(&mut self, a: u32, b: u32, rel: bool) -> bool {
        let ((ra, pa), (rb, pb)) = (self.find(a), self.find(b));
        if ra == rb {
            return pa ^ pb == rel;
        }
        let (root, child) = (ra.min(rb), ra.max(rb));
        self.parent[child as usize] = root;
        self.parity[child as usize] = pa ^ pb ^ rel;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_are_smallest_elements_whatever_the_order() {
        for order in [[(5, 3), (3, 9), (9, 1)], [(9, 1), (5, 3), (3, 9)], [(1, 9), (9, 3), (3, 5)]] {
            let mut uf = UnionFind::new(10);
            for (a, b) in order {
                assert!(uf.union(a, b));
            }
            for x in [1, 3, 5, 9] {
                assert_eq!(uf.find(x), 1);
                assert_eq!(uf.size(x), 4);
            }
            assert!(!uf.union(5, 9));
            assert_eq!((0..10).filter(|&x| uf.is_root(x)).count(), 7);
            assert_eq!(uf.find(7), 7);
            assert_eq!(uf.size(7), 1);
        }
    }

    #[test]
    fn labels_follow_smallest_elements() {
        let mut uf = UnionFind::new(6);
        uf.union(4, 1);
        uf.union(5, 0);
        uf.union(2, 5);
        // sets {0, 2, 5}, {1, 4}, {3}
        assert_eq!(uf.labels(), (vec![0, 1, 0, 2, 1, 0], 3));
        assert_eq!(UnionFind::new(0).labels(), (vec![], 0));
    }

    #[test]
    fn long_chains_compress() {
        let n = 100_000u32;
        let mut uf = UnionFind::new(n as usize);
        for x in (1..n).rev() {
            uf.union(x, x - 1);
        }
        assert_eq!(uf.find(n - 1), 0);
        assert_eq!(uf.size(n / 2), n);
        // after one find the path is at most halved repeatedly: a second is short
        assert_eq!(uf.find(n - 1), 0);
    }

    #[test]
    fn parities_compose_and_contradictions_are_reported() {
        let mut uf = ParityUnionFind::new(5);
        assert!(uf.union(0, 1, true));
        assert!(uf.union(1, 2, true));
        assert!(uf.union(3, 2, false));
        assert_eq!(uf.find(2), (0, false));
        assert_eq!(uf.find(3), (0, false));
        assert_eq!(uf.find(1), (0, true));
        // consistent with what is known
        assert!(uf.union(0, 3, false));
        assert!(uf.union(1, 3, true));
        // contradicts it, and changes nothing
        assert!(!uf.union(0, 2, true));
        assert_eq!(uf.find(2), (0, false));
        // an odd cycle (a Möbius band's triangles) is a contradiction
        let mut odd = ParityUnionFind::new(3);
        assert!(odd.union(0, 1, true));
        assert!(odd.union(1, 2, true));
        assert!(!odd.union(2, 0, true));
        assert_eq!(uf.find(4), (4, false));
    }
}
