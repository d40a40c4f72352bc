//! The scene's solid objects as the wind meets them: the bodies with their grid, the layer's
//! width, the ramped curl's difference steps and the spheres' and cylinders' doublets
//! (docs/CONVENTIONS.md, solid objects).

use crate::scene::bodies::Body;
use crate::scene::scene_format::{Primitive, Scene};
use crate::wind::doublets::Doublets;
use crate::wind::solids::Solids;
use crate::wind::walls::Doublet;
use glam::Vec3A;

/// The scene's solid objects as the wind meets them: the bodies with their grid, the layer's
/// width d₀, each body's difference step h for the ramped curl, and each body's doublet in the
/// uniform wind U (the sum of the uniform winds without decay).
#[derive(Debug, Clone)]
pub struct WallSet {
    pub solids: Solids,
    pub width: f32,
    pub steps: Vec<f32>,
    pub uniform: Vec3A,
    pub doublets: Doublets,
}

/// Of a difference step for the ramped curl: this fraction of the smallest of the layer's
/// width, the field's lattice spacing and the solid's size, the scales the potential varies
/// over.
pub const CURL_STEP_FRACTION: f32 = 1.0 / 64.0;

/// The rounding of a cylinder's rims the wind sees, in difference steps.
pub const EDGE_STEPS: f32 = 3.0;

impl WallSet {
    pub(super) fn new(scene: &Scene, spacing: f32) -> Option<Self> {
        let bodies: Vec<Body> = scene.render.objects.iter().filter_map(Body::of).collect();
        if bodies.is_empty() {
            return None;
        }
        let width = scene.field.boundary_width as f32;
        let uniform: Vec3A = scene
            .wind
            .iter()
            .filter_map(|w| match w {
                Primitive::Uniform {
                    velocity,
                    decay: None,
                    enabled: true,
                    ..
                } => Some(Vec3A::from_array(*velocity)),
                _ => None,
            })
            .sum();
        let doublets: Vec<Option<Doublet>> =
            bodies.iter().map(|b| Doublet::of(b, uniform)).collect();
        let steps: Vec<f32> = bodies
            .iter()
            .map(|b| CURL_STEP_FRACTION * width.min(spacing).min(b.size()))
            .collect();
        // A doublet reaches the stencils of the ramped curl about points it reaches, a step
        // farther.
        let step = steps.iter().copied().fold(0.0, f32::max);
        let reach: Vec<Option<f32>> = bodies
            .iter()
            .zip(&doublets)
            .map(|(b, d)| d.map(|_| Doublet::reach(b) + step))
            .collect();
        // A cylinder's rims rounded by three difference steps: no stencil about a point
        // outside (or less than a step inside) reaches across the jump of the normal inside.
        let edges = bodies
            .iter()
            .zip(&steps)
            .map(|(b, h)| match b {
                Body::Cylinder { .. } => EDGE_STEPS * h,
                _ => 0.0,
            })
            .collect();
        Some(Self {
            solids: Solids::with_edges(bodies, edges, width, &reach),
            width,
            steps,
            uniform,
            doublets: Doublets::new(doublets, uniform),
        })
    }

    /// The gap (m) a blob put back on a surface keeps from it.
    pub fn gap(&self) -> f32 {
        1e-4 * self.width
    }
}
