//! Blob birth (paper §6): evenly spaced births at `rate` per second, positions drawn from the
//! emitter's region with a seeded generator of its own (so adding an emitter leaves the others'
//! blobs unchanged).

use crate::scene::{Emitter, EmitterShape};
use glam::Vec3;
use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::rand_core::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// Mixes a seed with a stream tag (SplitMix64 finaliser), for independent generators.
pub fn stream_seed(seed: u64, tag: u64) -> u64 {
    let mut z = seed ^ tag.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Uniform in [0, 1).
pub fn uniform(rng: &mut Xoshiro256PlusPlus) -> f32 {
    (rng.next_u32() >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// An emitter with its birth clock and generator.
#[derive(Debug, Clone)]
pub struct EmitterState {
    pub emitter: Emitter,
    rng: Xoshiro256PlusPlus,
    /// Births so far; birth k happens at time k / rate.
    pub births: u64,
}

impl EmitterState {
    pub fn new(emitter: Emitter, seed: u64, index: usize) -> Self {
        Self {
            emitter,
            rng: Xoshiro256PlusPlus::seed_from_u64(stream_seed(seed, 0x454D_4954 + index as u64)),
            births: 0,
        }
    }

    /// Time (s) of the next birth, or infinity if the emitter is off.
    pub fn next_birth(&self) -> f64 {
        if !self.emitter.enabled || self.emitter.rate <= 0.0 {
            f64::INFINITY
        } else {
            self.births as f64 / self.emitter.rate
        }
    }

    /// Draws a birth position.
    pub fn sample_position(&mut self) -> Vec3 {
        let e = self.emitter;
        let c = Vec3::from_array(e.center);
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
