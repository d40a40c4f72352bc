//! Slots: where each blob lives in the page's GPU state while the GPU steps the gas. The GPU
//! then advects every blob (Eq. 14); the core keeps the rest of the gas (births, Eqs. 15–16,
//! removal under `min_mass`, the cap), which needs no wind and costs little. A slot is one texel
//! of the GPU's state textures: a newborn takes a free slot, a removed blob frees its own, and
//! only the newborns and the slots that emptied cross to the GPU each step.
//!
//! A slot freed in a step is reused from the next step on, so that within one step the slots
//! to empty and the slots to fill never meet.

use crate::gas::blobs::{Blobs, NO_SLOT};

/// The slots of a gas.
#[derive(Debug, Clone, Default)]
pub struct SlotTable {
    /// Slots handed out and still held, in no order.
    held: Vec<u32>,
    /// Slots free for reuse (the last freed is the first reused).
    free: Vec<u32>,
    /// One past the highest slot ever handed out: the GPU state holds at least this many.
    high_water: u32,
    /// Per slot, the last `generation` in which a blob held it.
    mark: Vec<u32>,
    generation: u32,
}

/// What one reconciliation found.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SlotChanges {
    /// Slots whose blob has gone (removed under `min_mass`, capped, or split).
    pub freed: Vec<u32>,
    /// Indices (into the blobs) of the blobs that took a slot: the newborns.
    pub filled: Vec<usize>,
}

impl SlotTable {
    /// Slots for every blob of `blobs`, in order (blob i in slot i).
    pub fn new(blobs: &mut Blobs) -> Self {
        let mut table = Self::default();
        blobs.slot.iter_mut().for_each(|s| *s = NO_SLOT);
        table.reconcile(blobs);
        table
    }

    /// One past the highest slot handed out.
    pub fn high_water(&self) -> u32 {
        self.high_water
    }

    /// After a step: frees the slots no blob holds any more, then gives a slot to every blob
    /// without one (newborns, split children), from the free slots first.
    pub fn reconcile(&mut self, blobs: &mut Blobs) -> SlotChanges {
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.mark.iter_mut().for_each(|m| *m = u32::MAX);
            self.generation = 1;
        }
        let generation = self.generation;
        for &s in blobs.slot.iter().filter(|&&s| s != NO_SLOT) {
            self.mark[s as usize] = generation;
        }
        let mark = &self.mark;
        let mut freed = Vec::new();
        self.held.retain(|&s| {
            let kept = mark[s as usize] == generation;
            if !kept {
                freed.push(s);
            }
            kept
        });
        let mut filled = Vec::new();
        for (i, slot) in blobs.slot.iter_mut().enumerate() {
            if *slot != NO_SLOT {
                continue;
            }
            let s = self.free.pop().unwrap_or_else(|| {
                self.high_water += 1;
                self.mark.push(0);
                self.high_water - 1
            });
            self.mark[s as usize] = generation;
            *slot = s;
            self.held.push(s);
            filled.push(i);
        }
        // Reused from the next step on.
        self.free.extend_from_slice(&freed);
        SlotChanges { freed, filled }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gas::blobs::Blob;
    use glam::Vec3;

    fn blobs(n: usize) -> Blobs {
        let mut b = Blobs::default();
        for i in 0..n {
            b.push(&Blob::new(Vec3::splat(i as f32), 0.01, 1.0, 0.0), 0.01, 1.0);
        }
        b
    }

    #[test]
    fn births_take_free_slots_after_the_step_that_freed_them() {
        let mut b = blobs(4);
        let mut table = SlotTable::new(&mut b);
        assert_eq!(b.slot, [0, 1, 2, 3]);
        // Blob 1 goes, two are born: they take new slots, not the one freed in this step.
        b.retain(&[true, false, true, true]);
        b.push(&Blob::new(Vec3::ZERO, 0.01, 1.0, 1.0), 0.01, 1.0);
        b.push(&Blob::new(Vec3::ZERO, 0.01, 1.0, 1.0), 0.01, 1.0);
        let changes = table.reconcile(&mut b);
        assert_eq!(changes.freed, [1]);
        assert_eq!(changes.filled, [3, 4]);
        assert_eq!(b.slot, [0, 2, 3, 4, 5]);
        // Next step: the oldest two go, one is born and takes slot 1, freed a step before.
        b.drop_oldest(2);
        b.push(&Blob::new(Vec3::ZERO, 0.01, 1.0, 2.0), 0.01, 1.0);
        let changes = table.reconcile(&mut b);
        assert_eq!(changes.freed.len(), 2);
        assert_eq!(b.slot, [3, 4, 5, 1]);
        assert_eq!(table.high_water(), 6);
        // Every held slot is one blob's, and no two blobs share one.
        let mut held = b.slot.clone();
        held.sort();
        held.dedup();
        assert_eq!(held.len(), b.len());
    }
}
