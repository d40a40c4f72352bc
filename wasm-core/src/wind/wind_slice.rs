//! The whole wind u = u_l + u_s (paper Eq. 3) sampled on a plane at one time: what the page's
//! wind-slice overlay draws as arrows.

use crate::error::ParamError;
use crate::wind::WindFrame;
use glam::Vec3;

/// Most samples along either side of a slice.
pub const MAX_SLICE_SIDE: u32 = 256;

/// The parallelogram `origin + a·u + b·v` (m), a and b in [0, 1], cut into `nu × nv` cells
/// that are sampled at their centres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlicePlane {
    pub origin: Vec3,
    pub u: Vec3,
    pub v: Vec3,
    pub nu: u32,
    pub nv: u32,
}

impl SlicePlane {
    /// A plane, checked: `origin`, `u` and `v` finite, `nu` and `nv` from 1 to
    /// [`MAX_SLICE_SIDE`]. Errors name the argument (`wind slice: u must be 3 finite numbers`).
    pub fn new(
        origin: [f32; 3],
        u: [f32; 3],
        v: [f32; 3],
        nu: u32,
        nv: u32,
    ) -> Result<Self, ParamError> {
        let vector = |a: [f32; 3], name: &str| {
            if a.iter().all(|c| c.is_finite()) {
                Ok(Vec3::from_array(a))
            } else {
                Err(ParamError::new(
                    "wind slice",
                    format!("{name} must be 3 finite numbers"),
                ))
            }
        };
        let (origin, u, v) = (vector(origin, "origin")?, vector(u, "u")?, vector(v, "v")?);
        let sides = 1..=MAX_SLICE_SIDE;
        if !sides.contains(&nu) || !sides.contains(&nv) {
            return Err(ParamError::new(
                "wind slice",
                format!("nu and nv must be between 1 and {MAX_SLICE_SIDE}"),
            ));
        }
        Ok(Self {
            origin,
            u,
            v,
            nu,
            nv,
        })
    }

    /// The wind of `frame` at every cell centre: `3·nu·nv` velocity components (m/s), xyz
    /// interleaved, u-index fastest.
    pub fn sample(&self, frame: &WindFrame) -> Vec<f32> {
        let mut out = Vec::with_capacity(3 * (self.nu * self.nv) as usize);
        for j in 0..self.nv {
            for i in 0..self.nu {
                let a = (i as f32 + 0.5) / self.nu as f32;
                let b = (j as f32 + 0.5) / self.nv as f32;
                let x = self.origin + a * self.u + b * self.v;
                out.extend_from_slice(&frame.velocity(x).to_array());
            }
        }
        out
    }
}
