//! Gas as Gaussian blobs (paper §4, Eqs. 13–16): born by emitters, advected through the wind
//! (Eq. 14, RK2 midpoint or Euler), diffused (σ² = σ0² + κ·age, Eq. 15), dissipated
//! (m = m0·exp(−α·age), Eq. 16), and split when too wide.
//!
//! The blobs themselves are [`super::blobs::Blobs`]; this module is what happens to them in a
//! step.

use crate::gas::blobs::{Blob, Blobs};
use crate::gas::emitter::EmitterState;
use crate::gas::random::{stream_seed, uniform};
use crate::lanes::{exp4, load3};
use crate::scene::scene_format::{Emitter, GasSettings, Integrator};
use crate::wind::{Wind, WindFrame};
use glam::{Quat, Vec3, Vec3A};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// Children per split: an octahedron of six blobs.
pub const SPLIT_CHILDREN: usize = 6;
/// Child σ over parent σ.
pub const SPLIT_SIGMA_RATIO: f32 = 0.5;
/// Child offset from the parent centre, in parent σ: with σ_c = σ/2, an octahedron of radius
/// 1.5σ keeps the per-axis variance σ_c² + (1.5σ)²/3 = σ² (the second moment).
pub const SPLIT_OFFSET: f32 = 1.5;

/// The blobs' own velocities, v0·exp(−age/τ) (m/s): birth times (s), v0 (xyz) and τ (s).
struct OwnVelocity<'a> {
    birth: &'a [f64],
    velocity0: &'a [f32],
    velocity_time: &'a [f32],
}

impl OwnVelocity<'_> {
    /// Calls `f(i, v, h)` for every blob in order, with its own velocity v at `t` and the factor
    /// h = exp(−dt/(2τ)) that takes v to t + dt/2: the exponentials of age four blobs at a time,
    /// h once for each run of equal τ.
    fn each(&self, t: f64, dt: f32, mut f: impl FnMut(usize, Vec3A, f32)) {
        let n = self.birth.len();
        let mut half_step = (f32::NAN, 1.0f32);
        for first in (0..n).step_by(4) {
            let lanes = (n - first).min(4);
            let mut exponent = [-1.0f32; 4];
            for (j, e) in exponent.iter_mut().enumerate().take(lanes) {
                let i = first + j;
                *e = -((t - self.birth[i]) as f32) / self.velocity_time[i];
            }
            let decay = exp4(exponent);
            for (j, &d) in decay.iter().enumerate().take(lanes) {
                let i = first + j;
                let tau = self.velocity_time[i];
                if tau != half_step.0 {
                    half_step = (tau, (-0.5 * dt / tau).exp());
                }
                let v0 = Vec3A::from_slice(&self.velocity0[3 * i..3 * i + 3]);
                f(i, v0 * d, half_step.1);
            }
        }
    }
}

/// Counts since the start, reported with the stats.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct GasCounts {
    pub emitted: u64,
    /// Parent blobs replaced by children.
    pub split: u64,
    /// Blobs removed below `min_mass`.
    pub dissipated: u64,
    /// Blobs removed (oldest first) to keep within `max_blobs`.
    pub capped: u64,
}

/// The gas of a scene.
#[derive(Debug, Clone)]
pub struct Gas {
    pub settings: GasSettings,
    pub blobs: Blobs,
    pub emitters: Vec<EmitterState>,
    pub counts: GasCounts,
    rng: Xoshiro256PlusPlus,
    /// Mass decay reference: `decayed[i] = m0·exp(−α(epoch − birth))`, so the mass at t is
    /// `decayed[i]·exp(−α(t − epoch))` with one exponential per step for all blobs.
    epoch: f64,
    decayed: Vec<f32>,
    /// When κ last changed (s; −∞ if never): a blob's σ0 is its σ at the later of its birth and
    /// this time, so Eq. 15 reads σ² = σ0² + κ·(t − max(birth, diffusion_epoch)).
    diffusion_epoch: f64,
    /// Whether the centres are advected elsewhere (on the GPU, [`crate::gas::slots`]): a step
    /// then leaves them as they are and does the rest.
    pub centres_elsewhere: bool,
    /// Whether newborns are advanced elsewhere too (the GPU, which steps the flow whose u_g
    /// their first part-step needs): a birth then stays where it is born, not pushed out of a
    /// solid, and its record carries its age to advance by ([`crate::frame::gpu_steps`]).
    pub newborns_elsewhere: bool,
    /// c (1/s), how fast each blob's heat is lost: h = h0·exp(−c·age) (the scene's
    /// `flow.cooling`; 0 without a flow).
    pub cooling: f64,
}

/// (2π)^{3/2}: a blob's heat per kelvin of its centre's temperature excess and m³ of σ0³
/// (h0 = temperature·(2π)^{3/2}·σ0³, so T at a newborn's centre is its emitter's temperature).
const HEAT_PER_KELVIN: f64 = 15.749_609_945_722_419;

/// Re-base the decay epoch once α(t − epoch) exceeds this (keeps factors well inside f32).
const MAX_DECAY_EXPONENT: f64 = 20.0;

impl Gas {
    pub fn new(settings: GasSettings, emitters: &[Emitter], seed: u64) -> Self {
        Self {
            settings,
            blobs: Blobs::default(),
            emitters: emitters
                .iter()
                .enumerate()
                .map(|(i, e)| EmitterState::new(e.clone(), seed, i))
                .collect(),
            counts: GasCounts::default(),
            rng: Xoshiro256PlusPlus::seed_from_u64(stream_seed(seed, 0x0053_504C_4954)),
            epoch: 0.0,
            decayed: Vec::new(),
            diffusion_epoch: f64::NEG_INFINITY,
            centres_elsewhere: false,
            newborns_elsewhere: false,
            cooling: 0.0,
        }
    }

    /// Each blob's heat at `t` (K·m³), h0·exp(−c·(t − birth)), into `heat`.
    pub fn heat_into(&self, t: f64, heat: &mut Vec<f32>) {
        let b = &self.blobs;
        heat.clear();
        heat.extend(b.heat0.iter().zip(&b.birth).map(|(&h0, &birth)| {
            if h0 == 0.0 {
                0.0
            } else {
                (h0 as f64 * (-self.cooling * (t - birth)).exp()) as f32
            }
        }));
    }

    /// Takes edited gas constants and emitters at time `t` (s), keeping every blob where it is
    /// with its σ and mass: from `t` on σ grows with the new κ (Eq. 15) and mass decays with the
    /// new α (Eq. 16). An emitter keeps its generator and birth clock when an old one had the
    /// same settings, else takes the clock of the one at its index, restarted at `t`
    /// ([`EmitterState::retune`]); added ones start at `t`. Splitting, removal and the cap
    /// apply from the next step.
    pub fn edit(&mut self, settings: GasSettings, emitters: &[Emitter], seed: u64, t: f64) {
        if settings.diffusion != self.settings.diffusion {
            let n = self.blobs.len();
            self.blobs.sigma0[..n].copy_from_slice(&self.blobs.sigma[..n]);
            self.diffusion_epoch = t;
        }
        if settings.dissipation != self.settings.dissipation {
            self.sync_decayed();
            self.decayed.copy_from_slice(&self.blobs.mass);
            self.epoch = t;
        }
        self.settings = settings;
        let mut old: Vec<Option<EmitterState>> = std::mem::take(&mut self.emitters)
            .into_iter()
            .map(Some)
            .collect();
        let same = |old: &[Option<EmitterState>], e: &Emitter| {
            old.iter()
                .position(|o| o.as_ref().is_some_and(|o| o.emitter == *e))
        };
        // Unchanged emitters first, so an edit elsewhere in the list leaves their blobs as they were.
        let mut kept: Vec<Option<EmitterState>> = emitters
            .iter()
            .map(|e| same(&old, e).and_then(|j| old[j].take()))
            .collect();
        for (i, e) in emitters.iter().enumerate() {
            if kept[i].is_none() {
                kept[i] = Some(match old.get_mut(i).and_then(Option::take) {
                    Some(mut state) => {
                        state.retune(e.clone(), t);
                        state
                    }
                    None => EmitterState::starting_at(e.clone(), seed, i, t),
                });
            }
        }
        self.emitters = kept.into_iter().flatten().collect();
    }

    /// Advances from `t` to `t + dt`: advect, emit, diffuse, dissipate, split, remove, cap.
    /// `frames` are scratch frames reused between steps.
    pub fn step(
        &mut self,
        wind: &Wind,
        t: f64,
        dt: f64,
        integrator: Integrator,
        frames: &mut [WindFrame; 2],
    ) {
        let [f0, fh] = frames;
        let t1 = t + dt;
        wind.frame_into(t, f0);
        if integrator == Integrator::Rk2 {
            wind.frame_into(t + 0.5 * dt, fh);
        }
        let late = if integrator == Integrator::Rk2 {
            &*fh
        } else {
            &*f0
        };
        self.carry_offsets(wind, t, late);
        let factor = self.decay_factor(t1);
        let old = self.blobs.len();
        let mut flagged = self.advect_and_age(t, dt, integrator, f0, fh, factor);
        if !self.centres_elsewhere {
            self.reset_phases(wind, t, t1, late, 0);
        }
        self.emit(t1, wind, late);
        flagged |= self.age_from(old, t1, factor);
        if flagged || self.blobs.len() > self.settings.max_blobs {
            self.split_remove_cap(t1);
        }
    }

    /// Eq. 14 over one step for every blob, then σ (Eq. 15) and mass (Eq. 16) at the step's
    /// end. Returns whether any blob needs splitting or removal.
    fn advect_and_age(
        &mut self,
        t: f64,
        dt: f64,
        integrator: Integrator,
        f0: &WindFrame,
        fh: &WindFrame,
        factor: f32,
    ) -> bool {
        if !self.centres_elsewhere {
            self.advect(t, dt, integrator, f0, fh);
        }
        self.age_from(0, t + dt, factor)
    }

    /// Starts carrying offsets of carried coordinates when the wind carries its small scales
    /// (from the first step, or after an edit turned it on), each blob's as a newborn's there;
    /// stops when it no longer does.
    fn carry_offsets(&mut self, wind: &Wind, t: f64, frame: &WindFrame) {
        let carries = wind.phases().is_some();
        if carries == self.blobs.carries() {
            return;
        }
        let offsets: Vec<[f32; 6]> = match wind.phases() {
            Some(phases) => (0..self.blobs.len())
                .map(|i| newborn_offsets(phases.ages(t), frame, self.blobs.center(i).into()))
                .collect(),
            None => Vec::new(),
        };
        self.blobs.set_carries(carries, |i| offsets[i]);
    }

    /// The centres taken back from elsewhere (the GPU): carried offsets as a newborn's.
    pub fn offsets_as_newborn(&mut self, wind: &Wind, t: f64, frame: &WindFrame) {
        if let Some(phases) = wind.phases() {
            let offsets: Vec<[f32; 6]> = (0..self.blobs.len())
                .map(|i| newborn_offsets(phases.ages(t), frame, self.blobs.center(i).into()))
                .collect();
            self.blobs.set_carries(true, |i| offsets[i]);
        }
    }

    /// A phase that reset between `t0` and `t1` starts again from every blob from index
    /// `first` on: its offset is −u_l(x)·τ, u_l the large-scale wind of `frame` (the step's
    /// middle) at the blob's new place, τ the phase's age at `t1`.
    fn reset_phases(&mut self, wind: &Wind, t0: f64, t1: f64, frame: &WindFrame, first: usize) {
        let Some(phases) = wind.phases() else {
            return;
        };
        let (before, after) = (phases.resets(t0), phases.resets(t1));
        let ages = phases.ages(t1);
        for k in 0..2 {
            if before[k] == after[k] {
                continue;
            }
            let tau = ages[k] as f32;
            let b = &mut self.blobs;
            for i in first..b.len() {
                let x = Vec3A::from_slice(&b.position[3 * i..3 * i + 3]);
                let o = frame.parts(x, [Vec3A::ZERO; 2]).0 * -tau;
                b.carried[6 * i + 3 * k..6 * i + 3 * k + 3].copy_from_slice(&o.to_array());
            }
        }
    }

    /// Eq. 14: every centre from t to t + dt through the wind plus the blob's own relaxing
    /// velocity, by Euler or the RK2 midpoint rule.
    fn advect(&mut self, t: f64, dt: f64, integrator: Integrator, f0: &WindFrame, fh: &WindFrame) {
        if !f0.is_plain() {
            self.advect_deflected(t, dt, integrator, f0, fh);
            return;
        }
        let b = &mut self.blobs;
        let n = b.len();
        let own_velocity = b.has_own_velocity();
        let position = &mut b.position[..3 * n];
        let x_at = |p: &[f32], i: usize| load3(p, 3 * i);
        let dtf = dt as f32;
        let own = OwnVelocity {
            birth: &b.birth[..n],
            velocity0: &b.velocity0[..3 * n],
            velocity_time: &b.velocity_time[..n],
        };
        match (integrator, own_velocity) {
            (Integrator::Euler, false) => (0..n).for_each(|i| {
                let x = x_at(position, i);
                (x + f0.velocity_a(x) * dtf).write_to_slice(&mut position[3 * i..3 * i + 3]);
            }),
            (Integrator::Euler, true) => own.each(t, dtf, |i, v, _| {
                let x = x_at(position, i);
                let k1 = f0.velocity_a(x) + v;
                (x + k1 * dtf).write_to_slice(&mut position[3 * i..3 * i + 3]);
            }),
            (Integrator::Rk2, false) => (0..n).for_each(|i| {
                let x = x_at(position, i);
                let xm = x + f0.velocity_a(x) * (0.5 * dtf);
                (x + fh.velocity_a(xm) * dtf).write_to_slice(&mut position[3 * i..3 * i + 3]);
            }),
            (Integrator::Rk2, true) => own.each(t, dtf, |i, v, to_half| {
                let x = x_at(position, i);
                let xm = x + (f0.velocity_a(x) + v) * (0.5 * dtf);
                let k2 = fh.velocity_a(xm) + v * to_half;
                (x + k2 * dtf).write_to_slice(&mut position[3 * i..3 * i + 3]);
            }),
        }
    }

    /// [`Self::advect`] where the wind goes round solids or carries its small scales: each
    /// blob's carried coordinates move with it less the large-scale wind, so its offsets by
    /// −u_l dt ([`crate::wind::carried`]), and a blob a step carried into a solid is put back on
    /// its surface, just outside.
    fn advect_deflected(
        &mut self,
        t: f64,
        dt: f64,
        integrator: Integrator,
        f0: &WindFrame,
        fh: &WindFrame,
    ) {
        let b = &mut self.blobs;
        let n = b.len();
        let carries = b.carries();
        let own_velocity = b.has_own_velocity();
        let dtf = dt as f32;
        let walls = f0.walls();
        let own = OwnVelocity {
            birth: &b.birth[..n],
            velocity0: &b.velocity0[..3 * n],
            velocity_time: &b.velocity_time[..n],
        };
        let position = &mut b.position[..3 * n];
        let carried = &mut b.carried;
        let mut advance = |i: usize, v: Vec3A, to_half: f32| {
            let x = load3(position, 3 * i);
            let mut o = [Vec3A::ZERO; 2];
            if carries {
                o = [0, 1].map(|k| Vec3A::from_slice(&carried[6 * i + 3 * k..6 * i + 3 * k + 3]));
            }
            // The carried coordinates X = x + o move with the blob less the large-scale wind,
            // so the offsets move against the large-scale wind: o ← o − u_l dt.
            // `clear`: how far x surely lies from every solid.
            let (l, s, clear) = f0.parts_and_clearance(x, o);
            let (x1, moved) = match integrator {
                Integrator::Euler => (x + (l + s + v) * dtf, l * -dtf),
                Integrator::Rk2 => {
                    let half = l * (-0.5 * dtf);
                    let xm = x + (l + s + v) * (0.5 * dtf);
                    let (lm, sm) = fh.parts(xm, [o[0] + half, o[1] + half]);
                    let vh = v * to_half;
                    (x + (lm + sm + vh) * dtf, lm * -dtf)
                }
            };
            let x1 = match walls {
                Some(w) => w.solids.push_out_after(x, clear, x1, w.gap()),
                None => x1,
            };
            x1.write_to_slice(&mut position[3 * i..3 * i + 3]);
            if carries {
                for k in 0..2 {
                    (o[k] + moved).write_to_slice(&mut carried[6 * i + 3 * k..6 * i + 3 * k + 3]);
                }
            }
        };
        // Without own velocities every v is zero: no exponentials.
        if own_velocity {
            own.each(t, dtf, advance);
        } else {
            (0..n).for_each(|i| advance(i, Vec3A::ZERO, 1.0));
        }
    }

    /// κ, the split σ (or infinity) and the removal mass, in f32.
    fn limits(&self) -> (f64, f32, f32) {
        let s = &self.settings;
        (
            s.diffusion,
            s.split_sigma.map_or(f32::INFINITY, |v| v as f32),
            s.min_mass as f32,
        )
    }

    /// Births in [t1 − dt, t1): each blob is advanced from its birth time to `t1` by one
    /// Euler step in `frame`, put back outside a solid it was born in or carried into, and
    /// given carried offsets as the large-scale wind at its birth place makes them (with
    /// [`Self::newborns_elsewhere`] it stays at its birth place: the GPU advances it).
    fn emit(&mut self, t1: f64, wind: &Wind, frame: &WindFrame) {
        let phases = wind.phases().copied();
        let walls = frame.walls();
        for e in 0..self.emitters.len() {
            while self.emitters[e].next_birth() < t1 {
                let birth = self.emitters[e].next_birth();
                let state = &mut self.emitters[e];
                state.births += 1;
                let x = state.sample_position(birth);
                let em = &state.emitter;
                let v0 = Vec3::from_array(em.velocity);
                let age = (t1 - birth) as f32;
                let carried = match &phases {
                    Some(p) => newborn_offsets(p.ages(t1), frame, x.into()),
                    None => [0.0; 6],
                };
                let u = if frame.is_plain() {
                    frame.velocity(x)
                } else {
                    let o = [0, 1].map(|k| Vec3A::from_slice(&carried[3 * k..3 * k + 3]));
                    let (l, s) = frame.parts(x.into(), o);
                    Vec3::from(l + s)
                };
                let mut position = x + (u + v0) * age;
                if self.newborns_elsewhere {
                    position = x;
                } else if let Some(w) = walls {
                    position = w.solids.push_out(position.into(), w.gap()).into();
                }
                let blob = Blob {
                    velocity0: v0,
                    velocity_time: em.velocity_time,
                    heat0: (em.temperature * HEAT_PER_KELVIN * (em.sigma0 as f64).powi(3)) as f32,
                    carried,
                    ..Blob::new(position, em.sigma0, em.mass0, birth)
                }
                .coloured(em.albedo, em.emission);
                self.blobs.push(&blob, em.sigma0, em.mass0);
                self.counts.emitted += 1;
            }
        }
    }

    /// The shared decay factor exp(−α(t − epoch)) of Eq. 16 at time `t`, re-basing the epoch
    /// when it grows large, and the per-blob factors of blobs added from outside a step.
    fn decay_factor(&mut self, t: f64) -> f32 {
        let alpha = self.settings.dissipation;
        if alpha * (t - self.epoch) > MAX_DECAY_EXPONENT {
            let f = (-alpha * (t - self.epoch)).exp() as f32;
            self.decayed.iter_mut().for_each(|d| *d *= f);
            self.epoch = t;
        }
        self.sync_decayed();
        (-alpha * (t - self.epoch)).exp() as f32
    }

    /// Per-blob decay factors m0·exp(−α(epoch − birth)) for blobs that lack one.
    fn sync_decayed(&mut self) {
        let alpha = self.settings.dissipation;
        for i in self.decayed.len()..self.blobs.len() {
            let d =
                self.blobs.mass0[i] as f64 * (-alpha * (self.epoch - self.blobs.birth[i])).exp();
            self.decayed.push(d as f32);
        }
    }

    /// σ and mass at `t` of the blobs from index `first` on (the newly born).
    fn age_from(&mut self, first: usize, t: f64, factor: f32) -> bool {
        self.sync_decayed();
        let (kappa, split, min_mass) = self.limits();
        let epoch = self.diffusion_epoch;
        let b = &mut self.blobs;
        let mut flagged = false;
        let ages = b.sigma0[first..].iter().zip(&b.birth[first..]);
        let decayed = &self.decayed[first..b.len()];
        for (((sigma, mass), (&s0, &birth)), &d) in b.sigma[first..]
            .iter_mut()
            .zip(b.mass[first..].iter_mut())
            .zip(ages)
            .zip(decayed)
        {
            *sigma = (s0 * s0 + (kappa * (t - birth.max(epoch))) as f32).sqrt();
            *mass = d * factor;
            flagged |= (*sigma > split) | (*mass < min_mass);
        }
        flagged
    }

    /// Splitting levels a blob of σ needs so no child exceeds `split_sigma`.
    fn split_levels(&self, sigma: f32) -> u32 {
        match self.settings.split_sigma {
            Some(limit) => {
                let mut levels = 0;
                let mut s = sigma as f64;
                while s > limit && levels < 32 {
                    s *= SPLIT_SIGMA_RATIO as f64;
                    levels += 1;
                }
                levels
            }
            None => 0,
        }
    }

    /// How many blobs one of σ and mass becomes: 6^levels children, none when a child would
    /// fall below `min_mass`, `max_blobs + 1` when there would be more than `max_blobs`.
    fn children(&self, sigma: f32, mass: f32) -> usize {
        let levels = self.split_levels(sigma);
        let children = (SPLIT_CHILDREN as f64).powi(levels as i32);
        let child_mass = mass as f64 / children;
        let max = self.settings.max_blobs;
        if child_mass < self.settings.min_mass {
            0
        } else if children > max as f64 {
            max + 1
        } else {
            children as usize
        }
    }

    /// The number of oldest blobs to drop (possibly 0) when capping is all there is to do:
    /// none of the newest `max_blobs` splits or dissipates, and the newest blob beyond them
    /// would not dissipate (else the blob-by-blob pass would reach further back). None
    /// otherwise. Dropping them gives exactly what [`Self::split_remove_cap_each`] gives.
    fn cap_only(&self) -> Option<usize> {
        let n = self.blobs.len();
        let kept = n.min(self.settings.max_blobs);
        let b = &self.blobs;
        let unchanged = |i: usize| self.children(b.sigma[i], b.mass[i]) == 1;
        if !(n - kept..n).all(unchanged) {
            return None;
        }
        let cutoff = n - kept;
        match cutoff {
            0 => Some(0),
            _ => (self.children(b.sigma[cutoff - 1], b.mass[cutoff - 1]) >= 1).then_some(cutoff),
        }
    }

    /// Replaces wide blobs by children, removes light ones, and keeps the newest within
    /// `max_blobs`. Never holds more than `max_blobs` blobs, whatever the split depth.
    fn split_remove_cap(&mut self, t: f64) {
        match self.cap_only() {
            Some(cutoff) => {
                self.counts.capped += cutoff as u64;
                self.blobs.drop_oldest(cutoff);
                self.decayed.drain(..cutoff);
            }
            None => self.split_remove_cap_each(t),
        }
    }

    /// [`Self::split_remove_cap`] blob by blob, whatever each one becomes.
    fn split_remove_cap_each(&mut self, t: f64) {
        let n = self.blobs.len();
        let max = self.settings.max_blobs;
        // Pass 1, newest to oldest: how many blobs each becomes; where the budget runs out.
        let mut counts = vec![0usize; n];
        let mut total = 0usize;
        let mut cutoff = 0;
        let mut changed = false;
        for i in (0..n).rev() {
            let c = self.children(self.blobs.sigma[i], self.blobs.mass[i]);
            if c != 1 {
                changed = true;
            }
            if total + c > max {
                cutoff = i + 1;
                changed = true;
                break;
            }
            total += c;
            counts[i] = c;
        }
        if !changed {
            return;
        }
        self.counts.capped += cutoff as u64;
        if counts[cutoff..].iter().all(|&c| c <= 1) {
            // Removal and capping only: compact in place.
            let keep: Vec<bool> = (0..n).map(|i| i >= cutoff && counts[i] == 1).collect();
            self.counts.dissipated += keep[cutoff..].iter().filter(|&&k| !k).count() as u64;
            self.blobs.retain(&keep);
            let mut to = 0;
            for (i, &k) in keep.iter().enumerate() {
                if k {
                    self.decayed[to] = self.decayed[i];
                    to += 1;
                }
            }
            self.decayed.truncate(to);
            return;
        }
        let old = std::mem::take(&mut self.blobs);
        let old_decayed = std::mem::take(&mut self.decayed);
        // A child's factor is its mass now, carried back to the epoch.
        let to_epoch = (self.settings.dissipation * (t - self.epoch)).exp() as f32;
        let mut out = Blobs::default();
        out.set_carries(old.carries(), |_| [0.0; 6]);
        for (i, &c) in counts.iter().enumerate().skip(cutoff) {
            match c {
                0 => self.counts.dissipated += 1,
                1 => {
                    out.push(&old.get(i), old.sigma[i], old.mass[i]);
                    // A blob that stays keeps its place on the GPU; children take new ones.
                    if let Some(slot) = out.slot.last_mut() {
                        *slot = old.slot[i];
                    }
                    self.decayed.push(old_decayed[i]);
                }
                _ => {
                    self.counts.split += 1;
                    let levels = self.split_levels(old.sigma[i]);
                    let first = out.len();
                    let mut parent = old.get(i);
                    // The children share the parent's heat now, as its mass: h0 at their birth t.
                    let children = (SPLIT_CHILDREN as f64).powi(levels as i32);
                    parent.heat0 = (parent.heat0 as f64
                        * (-self.cooling * (t - parent.birth)).exp()
                        / children) as f32;
                    self.split_into(&parent, old.sigma[i], old.mass[i], levels, t, &mut out);
                    self.decayed
                        .extend(out.mass[first..].iter().map(|m| m * to_epoch));
                }
            }
        }
        self.blobs = out;
    }

    /// Splits a blob of current σ and mass `levels` times (6^levels children), each level an
    /// octahedron at a random orientation: mass, centre of mass and second moments are kept.
    fn split_into(
        &mut self,
        parent: &Blob,
        sigma: f32,
        mass: f32,
        levels: u32,
        t: f64,
        out: &mut Blobs,
    ) {
        if levels == 0 {
            let child = Blob {
                sigma0: sigma,
                mass0: mass,
                birth: t,
                ..*parent
            };
            out.push(&child, sigma, mass);
            return;
        }
        let q = self.random_rotation();
        let offset = SPLIT_OFFSET * sigma;
        let axes = [
            Vec3::X,
            Vec3::NEG_X,
            Vec3::Y,
            Vec3::NEG_Y,
            Vec3::Z,
            Vec3::NEG_Z,
        ];
        for a in axes {
            let child = Blob {
                position: parent.position + q * a * offset,
                ..*parent
            };
            self.split_into(
                &child,
                sigma * SPLIT_SIGMA_RATIO,
                mass / SPLIT_CHILDREN as f32,
                levels - 1,
                t,
                out,
            );
        }
    }

    /// A uniformly distributed rotation (Shoemake's method).
    fn random_rotation(&mut self) -> Quat {
        let (u1, u2, u3) = (
            uniform(&mut self.rng),
            uniform(&mut self.rng),
            uniform(&mut self.rng),
        );
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        let tau = std::f32::consts::TAU;
        Quat::from_xyzw(
            a * (tau * u2).sin(),
            a * (tau * u2).cos(),
            b * (tau * u3).sin(),
            b * (tau * u3).cos(),
        )
        .normalize()
    }
}

/// The carried offsets of a blob at `x` whose phases are `ages` old (s): −u_l(x)·τ for each,
/// u_l the large-scale wind of `frame` ([`crate::wind::carried`]).
fn newborn_offsets(ages: [f64; 2], frame: &WindFrame, x: Vec3A) -> [f32; 6] {
    let u = frame.parts(x, [Vec3A::ZERO; 2]).0;
    let (a, b) = (u * -(ages[0] as f32), u * -(ages[1] as f32));
    [a.x, a.y, a.z, b.x, b.y, b.z]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A gas of `n` blobs, σ and mass growing with the index, and `max_blobs` of `max`.
    fn gas(n: usize, max: usize, min_mass: f64) -> Gas {
        let settings = GasSettings {
            max_blobs: max,
            min_mass,
            split_sigma: Some(0.5),
            ..GasSettings::default()
        };
        let mut g = Gas::new(settings, &[], 7);
        for i in 0..n {
            let x = i as f32;
            let blob = Blob::new(
                Vec3::new(x, -x, 0.5 * x),
                0.01 + 1e-4 * x,
                1.0 + x,
                -x as f64,
            );
            g.blobs.push(&blob, blob.sigma0, blob.mass0);
        }
        g.sync_decayed();
        g
    }

    fn same(a: &Gas, b: &Gas) {
        let (x, y) = (&a.blobs, &b.blobs);
        assert_eq!(x.position, y.position);
        assert_eq!(x.sigma, y.sigma);
        assert_eq!(x.mass, y.mass);
        assert_eq!(x.albedo, y.albedo);
        assert_eq!(x.emission, y.emission);
        assert_eq!(x.sigma0, y.sigma0);
        assert_eq!(x.mass0, y.mass0);
        assert_eq!(x.birth, y.birth);
        assert_eq!(x.velocity0, y.velocity0);
        assert_eq!(x.velocity_time, y.velocity_time);
        assert_eq!(a.decayed, b.decayed);
        assert_eq!(a.counts, b.counts);
    }

    #[test]
    fn capping_alone_drops_the_oldest_as_the_blob_by_blob_pass_does() {
        for (n, max, min_mass) in [
            (120, 100, 0.0),
            (100, 100, 0.0),
            (60, 100, 0.0),
            (120, 100, 5.5),
        ] {
            let mut fast = gas(n, max, min_mass);
            let mut each = fast.clone();
            fast.split_remove_cap(1.0);
            each.split_remove_cap_each(1.0);
            same(&fast, &each);
            assert_eq!(fast.blobs.len(), n.min(max));
        }
    }

    #[test]
    fn splits_and_removals_take_the_blob_by_blob_pass() {
        // The newest blob splits; the oldest would be removed below min_mass.
        let mut g = gas(50, 100, 0.0);
        g.blobs.sigma[49] = 0.8;
        assert_eq!(g.cap_only(), None);
        let mut g = gas(120, 100, 1.5);
        assert_eq!(g.cap_only(), Some(20));
        g.blobs.mass[19] = 1.0;
        assert_eq!(g.cap_only(), None);
    }
}
