//! windfield: turbulent wind fields for gaseous phenomena, after Stam & Fiume, "Turbulent Wind
//! Fields for Gaseous Phenomena" (SIGGRAPH 1993).
//!
//! The folders are the architecture. Data flows one way, down this list; a module uses only
//! those above it and the shared helpers:
//!
//! ```text
//! field/      §3          the small-scale turbulence u_s: energy spectrum (Eqs. 9, 10), 4-D
//!                         lattice, the spectral synthesis (noise, Eq. 7 filter, inverse FFT),
//!                         statistics
//! scene/                  the formats and their checks, knowing no physics: the scene format,
//!                         the blob list, their limits, reading and the one validation walk;
//!                         the initial sets and the solid objects as data (docs/FORMATS.md)
//! wind/       §2, §7      the wind u = u_l + u_s (Eq. 3): the small-scale sample, the
//!                         primitives and their paths, the solids, their grid, walls, doublets
//!                         and mirror images, carried turbulence, the frozen wind and its GPU
//!                         table, the wind on a plane
//! gas/        §4, §6      the blobs (Eq. 13), emitters and initial sets, the blob gas
//!                         (Eqs. 14–16), the simulation and its hand-off to the GPU stepper
//! render/     §5, App. B  the CPU reference renderer of a blob list (Eqs. 22–28)
//! frame/                  the browser's GPU frame: blobs packed for the shaders, the exact
//!                         march's level of detail and shadow grid, the real-time view's twin
//! export/                 files for other pipelines: stills with alpha, OpenEXR, flipbooks,
//!                         OpenVDB volumes, the wind as a vector grid
//! classroom/              the paper's Figure 1 (Eq. 12 on a grid beside the blobs) and the flow
//!                         past a sphere beside the potential flow
//! contract                the numbers shared with the page's code, written to JavaScript
//! api/        (wasm32)    the one door to JavaScript: conversions and errors only; a first
//!                         module for the player and the full one (`--features full`)
//! ```
//!
//! `render/` reads the scene's formats alone: it draws a blob list and knows nothing of the
//! wind or the gas that made it (`tests/architecture.rs` holds the folders to this order, and
//! no file to importing one that imports it back).
//!
//! Shared helpers: [`error`] (the error that names a parameter by its path), [`check`] (the
//! per-value checks), [`lanes`] (four-wide SIMD helpers), [`whole`] (whole numbers as JSON
//! writes them, `32` or `32.0`).
//!
//! The core is plain Rust. The native command line (`src/bin/windfield`) and the WASM build
//! use the same core; only the WASM build compiles `api` and links wasm-bindgen.

#[cfg(target_arch = "wasm32")]
pub mod api;
pub mod check;
pub mod classroom;
pub mod contract;
pub mod error;
pub mod export;
pub mod field;
pub mod frame;
pub mod gas;
pub mod lanes;
pub mod render;
pub mod scene;
pub mod whole;
pub mod wind;

pub use error::ParamError;
pub use field::lattice::Lattice;
pub use field::spectrum::{SpectrumLaw, SpectrumParams};
pub use field::{FieldParams, Synthesis, TurbulentField};
pub use gas::Simulation;
pub use scene::Scene;
