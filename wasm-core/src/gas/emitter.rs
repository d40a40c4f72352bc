//! Blob birth (paper §6): evenly spaced births at `rate` per second, positions drawn from the
//! emitter's region with a seeded generator of its own (so adding an emitter leaves the others'
//! blobs unchanged).

use crate::gas::random::{stream_seed, uniform};
use crate::scene::scene_format::{Emitter, EmitterShape};
use crate::wind::spline::Path;
use glam::Vec3;
use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// An emitter with its birth clock and generator.
#[derive(Debug, Clone)]
pub struct EmitterState {
    pub emitter: Emitter,
    /// The centre's path of a moving source.
    path: Option<Path>,
    rng: Xoshiro256PlusPlus,
    /// Births so far.
    pub births: u64,
    /// The birth clock: birth k happens at `origin + (k − births_at_origin) / rate` (s). Both
    /// are 0 from the start; an edit of the emitter restarts the clock at the edit's time.
    origin: f64,
    births_at_origin: u64,
}

impl EmitterState {
    pub fn new(emitter: Emitter, seed: u64, index: usize) -> Self {
        Self {
            path: (!emitter.path.is_empty()).then(|| Path::new(&emitter.path)),
            emitter,
            rng: Xoshiro256PlusPlus::seed_from_u64(stream_seed(seed, 0x454D_4954 + index as u64)),
            births: 0,
            origin: 0.0,
            births_at_origin: 0,
        }
    }

    /// An emitter added at time `now` (s): its first birth is at `now`.
    pub fn starting_at(emitter: Emitter, seed: u64, index: usize, now: f64) -> Self {
        let mut state = Self::new(emitter, seed, index);
        state.origin = now;
        state
    }

    /// Takes the edited settings `emitter` at time `now` (s), keeping the generator and the
    /// births so far; unchanged settings keep the birth clock as it is, changed ones restart it
    /// at `now` (so a new rate neither bursts nor stalls).
    pub fn retune(&mut self, emitter: Emitter, now: f64) {
        if emitter == self.emitter {
            return;
        }
        self.path = (!emitter.path.is_empty()).then(|| Path::new(&emitter.path));
        self.emitter = emitter;
        self.origin = now;
        self.births_at_origin = self.births;
    }

    /// Time (s) of the next birth, or infinity if the emitter is off.
    pub fn next_birth(&self) -> f64 {
        if !self.emitter.enabled || self.emitter.rate <= 0.0 {
            f64::INFINITY
        } else {
            self.origin + (self.births - self.births_at_origin) as f64 / self.emitter.rate
        }
    }

    /// Draws the position of a birth at time `t` (s): in the region about the centre, which a
    /// moving source takes from its path at `t`.
    pub fn sample_position(&mut self, t: f64) -> Vec3 {
        let e = &self.emitter;
        let c = match &self.path {
            Some(path) => path.at(t).0.as_vec3(),
            None => Vec3::from_array(e.center),
        };
        match e.shape {
            EmitterShape::Point => c,
            EmitterShape::Disk => {
                let n = Vec3::from_array(e.normal).normalize();
                let (u, v) = n.any_orthonormal_pair();
                let r = e.radius * uniform(&mut self.rng).sqrt();
                let a = std::f32::consts::TAU * uniform(&mut self.rng);
                c + (u * a.cos() + v * a.sin()) * r
            }
            EmitterShape::Sphere => {
                let d = loop {
                    let g = Vec3::new(
                        normal(&mut self.rng),
                        normal(&mut self.rng),
                        normal(&mut self.rng),
                    );
                    if g.length_squared() > 1e-12 {
                        break g.normalize();
                    }
                };
                c + d * (e.radius * uniform(&mut self.rng).cbrt())
            }
            EmitterShape::Box => {
                let s = Vec3::from_array(e.size);
                let u = Vec3::new(
                    uniform(&mut self.rng),
                    uniform(&mut self.rng),
                    uniform(&mut self.rng),
                );
                c + (u - 0.5) * s
            }
        }
    }
}

fn normal(rng: &mut Xoshiro256PlusPlus) -> f32 {
    StandardNormal.sample(rng)
}
