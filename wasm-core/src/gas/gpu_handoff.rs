//! The simulation's hand-off to the GPU stepper: while the GPU advects the blobs' centres
//! (Eq. 14, in the page's step shader), the core keeps doing the rest of each step (births, σ,
//! mass, removal, the cap) and says what changed in the GPU's slots ([`crate::gas::slots`]);
//! the solids' grid crosses once a scene, and the centres come back on demand.

use crate::error::ParamError;
use crate::gas::blobs::NO_SLOT;
use crate::gas::simulation::Simulation;
use crate::gas::slots::{SlotChanges, SlotTable};
use std::sync::Arc;

impl Simulation {
    /// Hands the centres to the GPU: from now on a step leaves them where they are (the GPU
    /// advects them, Eq. 14) and does the rest (births, σ, mass, removal, the cap), and every
    /// blob has a slot in the GPU's state ([`crate::gas::slots`]). A scene's flow goes with
    /// them: the GPU steps it beside the blobs (it needs their centres for the heat), and the
    /// flow here stays as it was until [`Self::take_flow`] brings the GPU's back. Refused for a
    /// scene that splits blobs or plays a shape in reverse: those are stepped here.
    pub fn hand_centres_to_gpu(&mut self) -> Result<(), ParamError> {
        if self.scene.gas.split_sigma.is_some() {
            return Err(ParamError::new(
                "gas.split_sigma",
                "a scene that splits blobs is stepped by the worker, not on the GPU",
            ));
        }
        if !self.reversed.is_empty() {
            return Err(ParamError::new(
                "shapes",
                "a scene that plays a shape in reverse is stepped by the worker, not on the GPU",
            ));
        }
        self.gas.centres_elsewhere = true;
        self.gas.newborns_elsewhere = self.flow.is_some();
        self.slots = Some(SlotTable::new(&mut self.gas.blobs));
        self.gpu_walls = None;
        Ok(())
    }

    /// The solids' grid and planes as the GPU stepper reads them
    /// ([`crate::wind::solids::Solids::write_gpu_grid`]), appended to `out` when the GPU has not
    /// been handed these solids since it took the centres (a new scene, an edit or a new field
    /// builds them anew); else nothing.
    pub fn solid_grid_for_gpu(&mut self, out: &mut Vec<f32>) {
        let walls = self.wind.shared_walls();
        if walls.as_ref().map(Arc::as_ptr) != self.gpu_walls.as_ref().map(Arc::as_ptr) {
            if let Some(w) = &walls {
                w.solids.write_gpu_grid(out);
            }
            self.gpu_walls = walls;
        }
    }

    /// Whether the GPU advects the centres.
    pub fn centres_on_gpu(&self) -> bool {
        self.slots.is_some()
    }

    /// One past the highest GPU slot in use (0 while the centres are here).
    pub fn slot_high_water(&self) -> u32 {
        self.slots.as_ref().map_or(0, SlotTable::high_water)
    }

    /// Takes the GPU's centres (`xyz` per slot, m) as the blobs' own: for an export, a still, or
    /// to step here again (`keep_on_gpu` false). Slots beyond `centres` leave their blob as it
    /// is. Stepping here again, a carried field takes the GPU's carried `offsets` (per slot
    /// phase a xyz then phase b xyz, m) where given, else starts each blob's as a newborn's.
    pub fn take_centres(&mut self, centres: &[f32], keep_on_gpu: bool, offsets: Option<&[f32]>) {
        let b = &mut self.gas.blobs;
        for (i, &s) in b.slot.iter().enumerate() {
            let s = s as usize;
            if let Some(c) = centres.get(3 * s..3 * s + 3) {
                b.position[3 * i..3 * i + 3].copy_from_slice(c);
            }
        }
        if !keep_on_gpu {
            self.slots = None;
            self.gas.centres_elsewhere = false;
            self.gas.newborns_elsewhere = false;
            let from_gpu = offsets.filter(|_| self.wind.phases().is_some()).map(|o| {
                b.slot
                    .iter()
                    .map(|&s| {
                        let at = 6 * s as usize;
                        o.get(at..at + 6)
                            .map_or([0.0; 6], |v| std::array::from_fn(|k| v[k]))
                    })
                    .collect::<Vec<[f32; 6]>>()
            });
            b.slot.iter_mut().for_each(|s| *s = NO_SLOT);
            match from_gpu {
                Some(o) => b.set_carries(true, |i| o[i]),
                None => {
                    // Without the GPU's offsets: start them again here as a newborn's.
                    let t = self.time();
                    let frame = self.wind.large_frame(t);
                    self.gas.offsets_as_newborn(&self.wind, t, &frame);
                }
            }
        }
    }

    /// Takes the flow the GPU stepped (`u_g` on each component's faces, m/s,
    /// [`crate::wind::flow::SceneFlow::take_u_g`]) as this scene's flow now, to step it here again or to edit
    /// it. Refused for a scene without a flow, and for arrays of the wrong size.
    pub fn take_flow(&mut self, u_g: [&[f32]; 3]) -> Result<(), ParamError> {
        let t = self.time();
        let Some(flow) = &mut self.flow else {
            return Err(ParamError::new("flow", "the scene has no flow to take"));
        };
        flow.take_u_g(u_g, t)?;
        self.wind.set_flow(Some(flow.frozen()));
        Ok(())
    }

    /// One fixed step while the GPU advects the centres: what changed in the GPU's slots (the
    /// newborns to write, the slots to empty). The wind the GPU steps through is
    /// [`Self::wind_frames`]. Without slots it is a plain step.
    pub fn step_for_gpu(&mut self) -> SlotChanges {
        self.step();
        match &mut self.slots {
            Some(table) => table.reconcile(&mut self.gas.blobs),
            None => SlotChanges::default(),
        }
    }
}
