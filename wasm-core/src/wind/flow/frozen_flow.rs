//! The flow's velocity u_g frozen for a step, as the blobs and the wind's samplers read it
//! (docs/CONVENTIONS.md, the flow): trilinear on the MAC faces inside the box; beyond the box
//! the value at the nearest point of the box, faded to 0 across one cell by a smoothstep in
//! each axis's distance, so a blob leaving the box sees no jump. Inside the box u_g is the
//! solver's, divergence-free; in the fade layer outside it is not.

use super::grid::Grid;
use super::mac::{FaceSampler, MacField};
use glam::Vec3A;

/// The fade across one cell beyond the box, at a point `outside` cells beyond it along each
/// axis (0 inside): 1 in the box, 0 a cell or more out, Π_a s²(3 − 2s) with s = 1 − outside_a.
#[inline]
pub fn fade_beyond(outside: Vec3A) -> f32 {
    if outside == Vec3A::ZERO {
        return 1.0;
    }
    let s = (Vec3A::ONE - outside).max(Vec3A::ZERO);
    let fade = s * s * (Vec3A::splat(3.0) - 2.0 * s);
    fade.x * fade.y * fade.z
}

/// u_g for a step, m/s.
#[derive(Debug, Clone)]
pub struct FrozenFlow {
    u_g: MacField,
    sampler: FaceSampler,
    lo: Vec3A,
    hi: Vec3A,
    inv_h: f32,
}

impl FrozenFlow {
    /// u_g on `grid`.
    pub fn new(grid: &Grid, u_g: MacField) -> Self {
        let lo = Vec3A::from_array(grid.origin);
        let n = Vec3A::new(
            grid.cells[0] as f32,
            grid.cells[1] as f32,
            grid.cells[2] as f32,
        );
        Self {
            u_g,
            sampler: FaceSampler::new(grid),
            lo,
            hi: lo + n * grid.h,
            inv_h: 1.0 / grid.h,
        }
    }

    /// How much of u_g acts at `x` (m): 1 in the box, 0 a cell or more outside it.
    #[inline]
    pub fn weight(&self, x: Vec3A) -> f32 {
        fade_beyond((self.lo - x).max(x - self.hi).max(Vec3A::ZERO) * self.inv_h)
    }

    /// u_g at `x` (m), m/s, faded outside the box.
    #[inline]
    pub fn velocity(&self, x: Vec3A) -> Vec3A {
        let (w, u) = self.weighted(x);
        u * w
    }

    /// [`Self::weight`] at `x` (m) and u_g unfaded there (m/s, the value at the box's nearest
    /// point; zero where the weight is).
    #[inline]
    pub fn weighted(&self, x: Vec3A) -> (f32, Vec3A) {
        let w = self.weight(x);
        if w == 0.0 {
            return (0.0, Vec3A::ZERO);
        }
        let inside = x.clamp(self.lo, self.hi);
        (
            w,
            Vec3A::from_array(self.sampler.at(&self.u_g, inside.to_array())),
        )
    }
}
