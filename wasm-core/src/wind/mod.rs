//! The wind u = u_l + u_s (paper Eq. 3) of a scene, in world units (m, s, m/s): the
//! large-scale primitives superposed on the small-scale field ([`crate::field`], §3), turned
//! along the scene's solid objects, and frozen at one time for the gas to sample.
//!
//! - [`small_scale`]: u_s, the field with its world mapping; [`field_slice`]: one time slice
//!   of it, sampled trilinearly.
//! - [`large`]: a primitive of u_l as the wind keeps it, a repulsor moved along its path by
//!   [`spline`]; [`frozen`]: the primitives frozen at one time (and their mirror images in the
//!   solid planes).
//! - [`solids`]: the solid objects as the wind and the gas meet them, found among many by
//!   [`solid_grid`]; [`walls`]: how the wind goes round them (the layer's ramp and projection,
//!   the ramped curl, the doublets), [`doublets`]: the doublets summed four at a time;
//!   [`wall_set`]: the scene's solids, steps and doublets together.
//! - [`carried`]: the small scales carried by the large ones (§7).
//! - [`scene_wind`]: the whole wind of a scene ([`Wind`]); [`wind_frame`]: the wind frozen at
//!   one time ([`WindFrame`]), what a step samples; [`wind_table`]: the frozen wind as the
//!   GPU stepper reads it; [`wind_slice`]: the wind sampled on a plane.

pub mod carried;
pub mod doublets;
pub mod field_slice;
pub mod flow;
pub mod frozen;
pub mod large;
pub mod scene_wind;
pub mod small_scale;
pub mod solid_grid;
pub mod solids;
pub mod spline;
pub mod wall_set;
pub mod walls;
pub mod wind_frame;
pub mod wind_slice;
pub mod wind_table;

pub use scene_wind::Wind;
pub use wind_frame::WindFrame;
