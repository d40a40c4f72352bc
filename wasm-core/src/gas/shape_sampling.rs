//! Initial blob sets (paper §6, "3-D morphing"): point sets sampled from simple solids, each
//! point the centre of a blob born at time 0. A set may be played in reverse: at time t it shows
//! its own forward evolution at `reverse_from − t`, so it condenses out of the turbulence into
//! its shape while another set dissolves — the paper's morph of one shape into another.

use crate::gas::limits::{MAX_COORD, MAX_SHAPE_BLOBS};
use crate::gas::random::{stream_seed, uniform};
use glam::Vec3;
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::f32::consts::TAU;

/// The solid a set's points are drawn from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Solid {
    /// A ball of `radius`.
    Sphere,
    /// A ring of major radius `radius` and tube radius `thickness`, about `axis`.
    Torus,
    /// A trefoil knot of scale `radius` and tube radius `thickness`, about `axis`.
    Trefoil,
    /// A cube of half-side `radius`.
    Cube,
    /// The listed `points`, offset by `center`.
    Points,
}

/// One initial blob set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Shape {
    pub shape: Solid,
    #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
    pub center: [f32; 3],
    /// Axis of the torus and the trefoil (need not be unit length).
    #[schemars(inner(range(min = -1e6, max = 1e6)))]
    pub axis: [f32; 3],
    /// Size (m): ball radius, torus major radius, trefoil scale, cube half-side.
    #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
    pub radius: f32,
    /// Tube radius of the torus and the trefoil (m).
    #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
    pub thickness: f32,
    /// Number of blobs (ignored for `points`).
    #[schemars(range(min = 1, max = MAX_SHAPE_BLOBS))]
    #[serde(deserialize_with = "crate::whole::number")]
    pub count: usize,
    /// Blob centres relative to `center`, for `points`.
    #[schemars(length(max = MAX_SHAPE_BLOBS), inner(inner(range(min = -MAX_COORD, max = MAX_COORD))))]
    pub points: Vec<[f32; 3]>,
    /// σ0 (m) and m0 of every blob.
    #[schemars(range(max = 1e4), extend("exclusiveMinimum" = 0))]
    pub sigma0: f32,
    #[schemars(range(max = 1e12), extend("exclusiveMinimum" = 0))]
    pub mass0: f32,
    /// Albedo colour; none uses the medium's. Zero lights the set by its emission alone.
    #[schemars(inner(range(min = 0, max = 1)))]
    pub albedo: Option<[f32; 3]>,
    /// Self-emission colour Q.
    #[schemars(inner(range(min = 0, max = 1e6)))]
    pub emission: Option<[f32; 3]>,
    /// Play this set backwards from this time (s): at time t it shows its forward state at
    /// max(reverse_from − t, 0).
    #[schemars(range(max = 1e4), extend("exclusiveMinimum" = 0))]
    pub reverse_from: Option<f64>,
}

impl Default for Shape {
    fn default() -> Self {
        Self {
            shape: Solid::Sphere,
            center: [0.0; 3],
            axis: [0.0, 1.0, 0.0],
            radius: 0.5,
            thickness: 0.15,
            count: 500,
            points: Vec::new(),
            sigma0: 0.04,
            mass0: 0.01,
            albedo: None,
            emission: None,
            reverse_from: None,
        }
    }
}

impl Shape {
    /// Number of blobs the set makes.
    pub fn blob_count(&self) -> usize {
        match self.shape {
            Solid::Points => self.points.len(),
            _ => self.count,
        }
    }

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
