//! The browser's GPU frame: what the engine worker hands the page's GPU views per frame, and
//! the core's twins of what those views compute, so that tests can hold the GPU to the twins
//! and the twins to the CPU reference renderer ([`crate::render`]).
//!
//! - [`packed`]: every blob (Eq. 13: its centre, σ and mass, with its albedo and emission) in
//!   eight 32-bit words, sorted into σ classes, with the gas's bounds: the one buffer every GPU
//!   view draws from.
//! - [`lod`]: the exact march's level of detail, blobs much closer than their width merged by
//!   their moments.
//! - [`shadow_grid`](mod@shadow_grid): the exact march's shadow columns towards each light
//!   (the transmittance of Eq. 25).
//! - [`volume`]: the real-time view's density volume, computed as its shaders do;
//!   [`light_volume`]: its light volume, the columns towards each light.
//! - [`views`]: the two frames the page asks for, each made whole in one call.
//! - [`gpu_steps`]: what crosses to the page's GPU stepper while the GPU advects the gas.
//!
//! The numbers this format shares with the page's shaders are written once, here and in the
//! renderer, and handed to JavaScript by [`crate::contract`].

pub mod gpu_steps;
pub mod light_volume;
pub mod lod;
pub mod packed;
pub mod shadow_grid;
pub mod views;
pub mod volume;

pub use lod::{merge_blobs, merged_list};
pub use packed::PackedFrame;
pub use shadow_grid::shadow_grid;
pub use views::{MarchFrame, ViewFrame};
