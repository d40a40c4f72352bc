//! The two frames the page asks the engine for, each made whole in one call so that nothing
//! about a frame depends on the order of later calls: what the points and real-time volume views
//! draw ([`ViewFrame`]), and what the exact march draws ([`MarchFrame`]).

use crate::error::ParamError;
use crate::frame::lod::merged_list;
use crate::frame::packed::PackedFrame;
use crate::frame::shadow_grid::shadow_grid;
use crate::gas::simulation::Simulation;

/// Floats per moving sphere in [`ViewFrame::spheres`]: `[x, y, z, radius, r, g, b]`.
pub const SPHERE_FLOATS: usize = 7;

/// The points and volume views' frame: the gas now, packed, and the visible repulsor spheres.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewFrame {
    pub packed: PackedFrame,
    /// The visible repulsor spheres now, [`SPHERE_FLOATS`] each: centre (m), radius (m) and
    /// linear colour, in the order they follow the scene's objects in the blob list.
    pub spheres: Vec<f32>,
}

/// The visible repulsor spheres of `sim` now, [`SPHERE_FLOATS`] each.
pub fn sphere_floats(sim: &Simulation) -> Vec<f32> {
    sim.wind
        .visible_spheres(sim.time())
        .iter()
        .flat_map(|(c, r, rgb)| [c.x, c.y, c.z, *r, rgb[0], rgb[1], rgb[2]])
        .collect()
}

impl ViewFrame {
    /// The frame of `sim` now (albedo resolved against the medium's).
    pub fn of(sim: &Simulation) -> Self {
        Self {
            packed: PackedFrame::of_simulation(sim),
            spheres: sphere_floats(sim),
        }
    }
}

/// The exact march's frame: the blob list merged for the march ([`merged_list`]), packed as
/// every view's blobs are, and its shadow grid ([`shadow_grid`]).
#[derive(Debug, Clone, PartialEq)]
pub struct MarchFrame {
    pub packed: PackedFrame,
    pub shadow_grid: Vec<f32>,
}

impl MarchFrame {
    /// The frame of `sim` now: blobs closer than `fraction × σ` merged (`fraction` ≤ 0 keeps
    /// them all), the shadow grid at `res`³.
    pub fn of(sim: &Simulation, fraction: f32, res: u32) -> Result<Self, ParamError> {
        let list = merged_list(sim.blob_list(), fraction);
        Ok(Self {
            shadow_grid: shadow_grid(&list, res)?,
            packed: PackedFrame::of_list(&list),
        })
    }
}
