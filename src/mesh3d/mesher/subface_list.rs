//! A facet's subfaces in the order they came, with removal in constant time.
//!
//! Refinement splits a subface of a large flat facet thousands of times; taking the split ones
//! out of a plain list walked all of the facet's subfaces each time. Here a removed subface
//! leaves a hole in its slot, reading skips holes, and the list is squeezed (in order) once
//! the holes outnumber the subfaces. The order read is the order a plain list would keep
//! (removals keep the rest in order, additions go at the end), so the mesh does not change.

use crate::core::ids::NONE;

/// What a removed subface leaves in its slot.
const HOLE: [u32; 3] = [NONE; 3];

/// A facet's subfaces, each in a slot that stays put until the list is squeezed.
#[derive(Clone, Debug, Default)]
pub(crate) struct SubfaceList {
    slots: Vec<[u32; 3]>,
    holes: usize,
}

impl SubfaceList {
    /// The list of `subfaces`, in slots 0, 1, ...
    pub fn new(subfaces: Vec<[u32; 3]>) -> Self {
        SubfaceList { slots: subfaces, holes: 0 }
    }

    /// The subfaces, in order.
    pub fn iter(&self) -> impl Iterator<Item = [u32; 3]> + '_ {
        self.slots.iter().copied().filter(|t| *t != HOLE)
    }

    /// The subfaces with their slots, in order.
    pub fn slotted(&self) -> impl Iterator<Item = (u32, [u32; 3])> + '_ {
        self.slots.iter().copied().enumerate().filter(|(_, t)| *t != HOLE).map(|(i, t)| (i as u32, t))
    }

    /// How many subfaces there are.
    pub fn len(&self) -> usize {
        self.slots.len() - self.holes
    }

    /// The subface in `slot`, if there is one.
    pub fn get(&self, slot: u32) -> Option<[u32; 3]> {
        self.slots.get(slot as usize).copied().filter(|t| *t != HOLE)
    }

    /// Adds `t` at the end; returns its slot.
    pub fn push(&mut self, t: [u32; 3]) -> u32 {
        self.slots.push(t);
        (self.slots.len() - 1) as u32
    }

    /// Takes the subface out of `slot` (nothing if it is empty).
    pub fn remove(&mut self, slot: u32) {
        if let Some(t) = self.slots.get_mut(slot as usize).filter(|t| **t != HOLE) {
            *t = HOLE;
            self.holes += 1;
        }
    }

    /// Puts `t` in place of the subface in `slot` (which must hold one).
    pub fn replace(&mut self, slot: u32, t: [u32; 3]) {
        if let Some(s) = self.slots.get_mut(slot as usize).filter(|s| **s != HOLE) {
            *s = t;
        }
    }

    /// Whether holes outnumber the subfaces (and there are enough of them to be worth a pass).
    pub fn worth_squeezing(&self) -> bool {
        self.holes >= 64 && self.holes > self.len()
    }

    /// Closes the holes, keeping the order; returns the subfaces with their new slots.
    pub fn squeeze(&mut self) -> impl Iterator<Item = (u32, [u32; 3])> + '_ {
        self.slots.retain(|t| *t != HOLE);
        self.holes = 0;
        self.slots.iter().copied().enumerate().map(|(i, t)| (i as u32, t))
    }

    /// Takes every subface out, in order, leaving the list empty.
    pub fn take(&mut self) -> Vec<[u32; 3]> {
        let mut out = std::mem::take(&mut self.slots);
        if self.holes > 0 {
            out.retain(|t| *t != HOLE);
        }
        self.holes = 0;
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Removals by slot, additions and squeezes read back as a plain list edited by
        /// `retain` and `push` does.
        #[test]
        fn reads_as_a_plain_list(ops in proptest::collection::vec((0u8..3, 0u32..200), 0..600)) {
            let mut list = SubfaceList::new((0..50).map(|i| [i, i + 1, i + 2]).collect());
            let mut plain: Vec<[u32; 3]> = list.iter().collect();
            let mut next = 1000;
            for (op, k) in ops {
                match op {
                    0 => {
                        next += 1;
                        list.push([next, 0, 0]);
                        plain.push([next, 0, 0]);
                    }
                    1 => {
                        let slots: Vec<(u32, [u32; 3])> = list.slotted().collect();
                        if let Some(&(slot, t)) = slots.get(k as usize % slots.len().max(1)) {
                            list.remove(slot);
                            plain.retain(|s| *s != t);
                            prop_assert_eq!(list.get(slot), None);
                        }
                    }
                    _ => {
                        if list.worth_squeezing() || k % 7 == 0 {
                            for (slot, t) in list.squeeze().collect::<Vec<_>>() {
                                prop_assert_eq!(list.get(slot), Some(t));
                            }
                        }
                    }
                }
                prop_assert_eq!(list.len(), plain.len());
                prop_assert_eq!(list.iter().collect::<Vec<_>>(), plain.clone());
            }
            prop_assert_eq!(list.take(), plain);
            prop_assert_eq!(list.len(), 0);
        }
    }
}
