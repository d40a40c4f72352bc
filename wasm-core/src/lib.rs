//! windfield: turbulent wind fields for gaseous phenomena, after Stam & Fiume,
//! "Turbulent Wind Fields for Gaseous Phenomena" (SIGGRAPH 1993).
//!
//! The core is plain Rust. [`field`] synthesises the small-scale turbulence (paper §3) on a
//! [`lattice`] from an energy [`spectrum`]; [`stats`] measures it against the paper's formulas.
//! [`scene`] reads the scene format; [`wind`] superposes the large-scale primitives on the field
//! (Eq. 3); [`gas`] animates Gaussian blobs born by [`emitter`]s (§4); [`simulation`] drives
//! them and exports the [`blob_list`] that [`render`] turns into verified stills. [`api`] is the one module that speaks
//! to JavaScript.

pub mod api;
pub mod blob_list;
pub mod check;
pub mod emitter;
pub mod error;
pub mod fft4;
pub mod field;
pub mod figure1;
pub mod gas;
pub mod lanes;
pub mod lattice;
pub mod noise;
pub mod npy;
pub mod real_fft;
pub mod render;
pub mod scene;
pub mod shapes;
pub mod simulation;
pub mod spectrum;
pub mod spline;
pub mod stats;
pub mod synthesis;
pub mod velocity_spectrum;
pub mod wind;

pub use error::ParamError;
pub use field::{FieldParams, Synthesis, TurbulentField};
pub use lattice::Lattice;
pub use scene::Scene;
pub use simulation::Simulation;
pub use spectrum::{SpectrumLaw, SpectrumParams};
