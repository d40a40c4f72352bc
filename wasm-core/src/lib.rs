//! windfield: turbulent wind fields for gaseous phenomena, after Stam & Fiume, "Turbulent Wind
//! Fields for Gaseous Phenomena" (SIGGRAPH 1993).
//!
//! The folders are the architecture. Data flows one way, down this list; a module uses only
//! those above it and the shared helpers:
//!
//! ```text
//! field/    §3          the small-scale turbulence u_s: energy spectrum, 4-D lattice, the
//!                       spectral synthesis (noise, Eq. 7 filter, inverse FFT), statistics
//! gas/      §4, §6      the scene format, the wind u = u_l + u_s (Eq. 3), emitters and initial
//!                       blob sets, the blob gas (Eqs. 12–16), the simulation, and the blob list
//!                       it hands over (docs/FORMATS.md: the scene format, the blob list)
//! render/   §5, App. B  the CPU reference renderer of a blob list
//! frame/                the browser's GPU frame: blobs packed for the shaders, the exact
//!                       march's level of detail and shadow grid, the real-time view's twin
//! export/               files for other pipelines: stills with alpha, OpenEXR, flipbooks,
//!                       OpenVDB volumes, the wind as a vector grid
//! contract              the numbers shared with the page's code, written to JavaScript
//! api       (wasm32)    the one door to JavaScript: conversions and errors only
//! ```
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
pub mod contract;
pub mod error;
pub mod export;
pub mod field;
pub mod frame;
pub mod gas;
pub mod lanes;
pub mod render;
pub mod whole;

pub use error::ParamError;
pub use field::lattice::Lattice;
pub use field::spectrum::{SpectrumLaw, SpectrumParams};
pub use field::{FieldParams, Synthesis, TurbulentField};
pub use gas::{Scene, Simulation};
