//! What crosses to the page's GPU stepper while the GPU advects the gas (Eq. 14): per step the
//! newborn blobs with their slots, the slots that emptied, and the wind frozen at the step's
//! start and middle; once, the whole gas (when the GPU takes it over). The core keeps the rest
//! of the gas ([`crate::gas::slots`]), so nothing else crosses per step.
//!
//! A blob record ([`BLOB_FLOATS`] floats, five vec4):
//!
//! | vec4 | content |
//! |---|---|
//! | 0 | centre x, y, z (m), σ² (m²) |
//! | 1 | mass, age (s), τ of the own velocity (s), heat at birth h0 (K·m³; 0 without heat) |
//! | 2 | own velocity at birth v0 x, y, z (m/s), 0 |
//! | 3 | albedo Ω r, g, b (a negative r: the medium's), 0 |
//! | 4 | emission Q r, g, b, 0 |
//! | 5 | carried offset of phase a x, y, z (m), 0 (zeros unless the field is carried) |
//! | 6 | carried offset of phase b x, y, z (m), 0 |
//!
//! While the GPU steps a flow, newborns are left at their birth places
//! ([`crate::gas::blob_gas::Gas::newborns_elsewhere`]): the GPU advances each by its age
//! (vec4 1's second float) through its own u_g, as the core would through its own, and
//! their vec4 5 holds the carried phases' ages at the step's end (s; a, b, 0, 0) from which
//! the GPU makes their offsets; vec4 6 is zeros.

use crate::frame::views::sphere_floats;
use crate::gas::blobs::Blobs;
use crate::gas::simulation::Simulation;
use crate::gas::slots::SlotChanges;
use crate::scene::scene_format::Integrator;
use crate::wind::wind_table::{NO_RESET, RESET_AT};

/// Floats per blob record.
pub const BLOB_FLOATS: usize = 28;
/// Where a record's carried offsets start (vec4 5, then vec4 6 to its end).
const CARRIED_AT: usize = 20;

/// Steps for the GPU, whole buffers: `steps` steps' worth, one after another.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GpuSteps {
    /// The newborns' records ([`BLOB_FLOATS`] each), step after step.
    pub births: Vec<f32>,
    /// Their slots, in the same order.
    pub birth_slots: Vec<u32>,
    /// The slots that emptied, step after step.
    pub freed: Vec<u32>,
    /// Per step `[first birth, births, first freed, freed]` (indices into the lists above).
    pub ranges: Vec<u32>,
    /// Per step the wind tables at the step's start and middle
    /// ([`crate::wind::WindFrame::write_gpu_table`]), and per step the offset of each.
    pub wind: Vec<f32>,
    pub wind_offsets: Vec<u32>,
    /// The solids' grid and planes ([`Simulation::solid_grid_for_gpu`]), when the GPU has not
    /// got this scene's yet; else empty.
    pub solid_grid: Vec<f32>,
    /// Live blobs after the last step.
    pub count: u32,
    /// One past the highest slot in use after the last step.
    pub high_water: u32,
    /// Narrowest and widest σ (m) after the last step (0 without blobs).
    pub sigma_range: [f32; 2],
    /// The visible repulsor spheres after the last step, as a view frame has them
    /// ([`crate::frame::views::SPHERE_FLOATS`] each).
    pub spheres: Vec<f32>,
    /// Whether any live blob emits light (a view then adds its source).
    pub emissive: bool,
}

/// The record of blob `i` of `blobs` at time `t` (s), appended to `out`.
pub fn write_blob(blobs: &Blobs, i: usize, t: f64, out: &mut Vec<f32>) {
    let s = blobs.sigma[i];
    let rgb = |v: &[f32]| [v[3 * i], v[3 * i + 1], v[3 * i + 2], 0.0];
    out.extend_from_slice(&blobs.position[3 * i..3 * i + 3]);
    out.push(s * s);
    out.extend_from_slice(&[
        blobs.mass[i],
        (t - blobs.birth[i]) as f32,
        blobs.velocity_time[i],
        blobs.heat0[i],
    ]);
    out.extend_from_slice(&rgb(&blobs.velocity0));
    out.extend_from_slice(&rgb(&blobs.albedo));
    out.extend_from_slice(&rgb(&blobs.emission));
    if blobs.carries() {
        let o = &blobs.carried[6 * i..6 * i + 6];
        out.extend_from_slice(&[o[0], o[1], o[2], 0.0, o[3], o[4], o[5], 0.0]);
    } else {
        out.extend_from_slice(&[0.0; 8]);
    }
}

/// The whole gas of `sim` as records in slot order (`high_water` records; empty slots are
/// zeros, i.e. blobs without mass): what the GPU starts from.
pub fn gas_by_slot(sim: &Simulation) -> Vec<f32> {
    let b = &sim.gas.blobs;
    let mut out = vec![0.0; BLOB_FLOATS * sim.slot_high_water() as usize];
    let mut one = Vec::with_capacity(BLOB_FLOATS);
    for (i, &slot) in b.slot.iter().enumerate() {
        one.clear();
        write_blob(b, i, sim.time(), &mut one);
        let at = BLOB_FLOATS * slot as usize;
        out[at..at + BLOB_FLOATS].copy_from_slice(&one);
    }
    out
}

impl GpuSteps {
    /// Runs `steps` fixed steps of `sim` (whose centres are on the GPU) and gathers what the
    /// GPU needs to take the same steps.
    pub fn run(sim: &mut Simulation, steps: u32) -> Self {
        let mut out = Self::default();
        for _ in 0..steps {
            let SlotChanges { freed, filled } = sim.step_for_gpu();
            let t = sim.time();
            out.ranges.extend_from_slice(&[
                out.birth_slots.len() as u32,
                filled.len() as u32,
                out.freed.len() as u32,
                freed.len() as u32,
            ]);
            let b = &sim.gas.blobs;
            // Newborns the GPU advances (through its flow) take their phases' ages at the
            // step's end in place of offsets: the GPU makes their offsets as the core would.
            let ages = sim.wind.phases().map(|p| p.ages(t)).unwrap_or_default();
            for &i in &filled {
                let at = out.births.len();
                write_blob(b, i, t, &mut out.births);
                if sim.gas.newborns_elsewhere {
                    out.births[at + CARRIED_AT..at + BLOB_FLOATS].copy_from_slice(&[
                        ages[0] as f32,
                        ages[1] as f32,
                        0.0,
                        0.0,
                        0.0,
                        0.0,
                        0.0,
                        0.0,
                    ]);
                }
                out.birth_slots.push(b.slot[i]);
            }
            out.freed.extend_from_slice(&freed);
            // The carried phases that reset during the step, with their ages at its end, in
            // the table whose large-scale wind restarts them (the middle's; Euler: the start's).
            let resets = sim.wind.phases().map(|p| {
                let (before, after) = (p.resets(sim.wind_frames()[0].time), p.resets(t));
                let ages = p.ages(t);
                [0, 1].map(|k| {
                    if before[k] != after[k] {
                        ages[k] as f32
                    } else {
                        NO_RESET
                    }
                })
            });
            let late = match sim.scene.simulation.integrator {
                Integrator::Rk2 => 1,
                Integrator::Euler => 0,
            };
            for (k, frame) in sim.wind_frames().iter().enumerate() {
                let at = out.wind.len();
                out.wind_offsets.push(at as u32);
                frame.write_gpu_table(&mut out.wind);
                if let (Some(r), true) = (resets, k == late) {
                    out.wind[at + RESET_AT..at + RESET_AT + 2].copy_from_slice(&r);
                }
            }
        }
        if steps > 0 {
            sim.solid_grid_for_gpu(&mut out.solid_grid);
        }
        out.spheres = sphere_floats(sim);
        let b = &sim.gas.blobs;
        out.emissive = b.emission.iter().any(|&q| q != 0.0);
        out.count = b.len() as u32;
        out.high_water = sim.slot_high_water();
        out.sigma_range = if b.is_empty() {
            [0.0; 2]
        } else {
            b.sigma
                .iter()
                .fold([f32::INFINITY, 0.0], |[lo, hi], &s| [lo.min(s), hi.max(s)])
        };
        out
    }
}
