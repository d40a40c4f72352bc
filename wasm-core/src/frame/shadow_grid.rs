//! The exact GPU march's shadow grid: the optical column ∫ρ ds from a point towards each light
//! (S_k of paper Eq. 25 is exp(−κ_t ∫ρ ds)), computed by the reference renderer's exact line
//! integrals on a grid over the gas, for the march to interpolate trilinearly per step instead
//! of marching a shadow ray. The columns are the gas's alone; where an opaque object blocks a
//! light the march finds it by the exact ray test of [`crate::render::occluded`] (in GLSL), as
//! the reference renderer does, and the objects' material reads these columns at surfaces.

use crate::error::ParamError;
use crate::render::{RenderOptions, Renderer};
use crate::scene::blob_list::BlobList;
use glam::Vec3;

/// Floats before the columns: `[lo.xyz, hi.xyz, res, lights]`.
pub const SHADOW_GRID_HEADER: usize = 8;
/// Fewest and most grid points along each axis.
pub const SHADOW_GRID_RES: [u32; 2] = [2, 96];

/// The shadow grid of `list` at `res`³ points (clamped to [`SHADOW_GRID_RES`]) over the gas's
/// bounds padded by a cell: `[lo.xyz, hi.xyz, res, lights]` (m, then counts), then `lights ×
/// res³` columns ∫ρ ds (mass per m²), x fastest, then y, z and the light. Without blobs, lights
/// or shadows, the header alone, all zeros. Errors are the list's ([`BlobList::validate`]).
pub fn shadow_grid(list: &BlobList, res: u32) -> Result<Vec<f32>, ParamError> {
    let renderer = Renderer::new(list, None, RenderOptions::default())?;
    let res = res.clamp(SHADOW_GRID_RES[0], SHADOW_GRID_RES[1]) as usize;
    let lights = renderer.light_count();
    let bounds = renderer.gas_bounds().filter(|_| list.shadows && lights > 0);
    let Some((lo, hi)) = bounds else {
        return Ok(vec![0.0; SHADOW_GRID_HEADER]);
    };
    let pad = (hi - lo) / (res - 1) as f32;
    let (lo, hi) = (lo - pad, hi + pad);
    let cell = (hi - lo) / (res - 1) as f32;
    let mut out = Vec::with_capacity(SHADOW_GRID_HEADER + lights * res * res * res);
    out.extend(lo.to_array().into_iter().chain(hi.to_array()));
    out.extend([res as f32, lights as f32]);
    for k in 0..lights {
        for z in 0..res {
            for y in 0..res {
                for x in 0..res {
                    let p = lo + cell * Vec3::new(x as f32, y as f32, z as f32);
                    out.push(renderer.column_to_light(p, k));
                }
            }
        }
    }
    Ok(out)
}
