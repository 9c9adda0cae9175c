//! A small open-addressing table that pairs up the faces of a new star around their edges:
//! every key arrives exactly twice, and the second arrival meets the first.
//!
//! Slots carry the stamp of the star they belong to, so emptying the table is one increment;
//! only the part sized for the current star is probed, so small stars stay in a few cache
//! lines after a large one grew the allocation.

#[derive(Copy, Clone)]
struct Slot {
    key: u64,
    val: u32,
    stamp: u32,
}

/// Keys are edges `(a << 32) | b` with `a < b`; values are face references.
pub(crate) struct EdgeTable {
    slots: Vec<Slot>,
    mask: usize,
    shift: u32,
    stamp: u32,
}

impl EdgeTable {
    /// An empty table.
    pub fn new() -> Self {
        EdgeTable { slots: Vec::new(), mask: 0, shift: 64, stamp: 0 }
    }

    /// Empties the table and makes room for `entries` keys at a load of at most 1/4.
    pub fn reset(&mut self, entries: usize) {
        let want = (entries.max(8) * 4).next_power_of_two();
        if want > self.slots.len() {
            self.slots = vec![Slot { key: 0, val: 0, stamp: 0 }; want];
            self.stamp = 0;
        }
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.slots.iter_mut().for_each(|s| s.stamp = 0);
            self.stamp = 1;
        }
        self.mask = want - 1;
        self.shift = 64 - want.trailing_zeros();
    }

    /// Stores `val` under `key` and returns what was stored there before, or `none` if the
    /// key is new: callers use the result without branching on it.
    #[inline]
    pub fn swap(&mut self, key: u64, val: u32, none: u32) -> u32 {
        let mut i = (key.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> self.shift) as usize;
        loop {
            let s = self.slots[i];
            let fresh = s.stamp != self.stamp;
            if fresh || s.key == key {
                self.slots[i] = Slot { key, val, stamp: self.stamp };
                return if fresh { none } else { s.val };
            }
            i = (i + 1) & self.mask;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::ids::NONE;

    #[test]
    fn pairs_meet() {
        let mut t = EdgeTable::new();
        t.reset(100);
        for k in 0..100u64 {
            assert_eq!(t.swap(k << 32 | (k + 1), k as u32, NONE), NONE);
        }
        for k in 0..100u64 {
            assert_eq!(t.swap(k << 32 | (k + 1), 7, NONE), k as u32);
        }
        t.reset(10);
        assert_eq!(t.swap(5 << 32 | 6, 1, NONE), NONE);
    }
}
