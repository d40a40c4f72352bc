//! The initial blob sets' points (paper §6, "3-D morphing"): each set's points sampled from its
//! solid ([`crate::scene::shapes`]), each the centre of a blob born at time 0. A set may be
//! played in reverse: at time t it shows its own forward evolution at `reverse_from − t`, so it
//! condenses out of the turbulence into its shape while another set dissolves — the paper's
//! morph of one shape into another.

use crate::gas::random::{stream_seed, uniform};
use crate::scene::shapes::{Shape, Solid};
use glam::Vec3;
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use std::f32::consts::TAU;

impl Shape {
    /// The blob centres (m), drawn with a generator seeded by the scene seed and the set's
    /// index, so the same scene always yields the same points.
    pub fn centres(&self, seed: u64, index: usize) -> Vec<Vec3> {
        let mut rng =
            Xoshiro256PlusPlus::seed_from_u64(stream_seed(seed, 0x5348_4150 + index as u64));
        let mut u = || uniform(&mut rng);
        let c = Vec3::from_array(self.center);
        let axis = Vec3::from_array(self.axis).normalize();
        let (e1, e2) = axis.any_orthonormal_pair();
        // A point of the ring frame (e1, e2, axis) to world.
        let frame = |p: Vec3| c + e1 * p.x + e2 * p.y + axis * p.z;
        let (r, a) = (self.radius, self.thickness);
        let in_ball = |u: &mut dyn FnMut() -> f32| loop {
            let p = Vec3::new(2.0 * u() - 1.0, 2.0 * u() - 1.0, 2.0 * u() - 1.0);
            if p.length_squared() <= 1.0 {
                return p;
            }
        };
        match self.shape {
            Solid::Points => self
                .points
                .iter()
                .map(|&p| c + Vec3::from_array(p))
                .collect(),
            Solid::Sphere => (0..self.count).map(|_| c + in_ball(&mut u) * r).collect(),
            Solid::Cube => (0..self.count)
                .map(|_| c + Vec3::new(2.0 * u() - 1.0, 2.0 * u() - 1.0, 2.0 * u() - 1.0) * r)
                .collect(),
            Solid::Torus => (0..self.count)
                .map(|_| {
                    let phi = TAU * u();
                    let ring = Vec3::new(phi.cos(), phi.sin(), 0.0);
                    let d = in_ball(&mut u) * a;
                    frame(ring * r + d)
                })
                .collect(),
            Solid::Trefoil => (0..self.count)
                .map(|_| {
                    // (sin t + 2 sin 2t, cos t − 2 cos 2t, −sin 3t), scaled to radius / 3.
                    let t = TAU * u();
                    let k = Vec3::new(
                        t.sin() + 2.0 * (2.0 * t).sin(),
                        t.cos() - 2.0 * (2.0 * t).cos(),
                        -(3.0 * t).sin(),
                    ) * (r / 3.0);
                    frame(k + in_ball(&mut u) * a)
                })
                .collect(),
        }
    }
}
