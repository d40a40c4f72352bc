//! windfield: turbulent wind fields for gaseous phenomena, after Stam & Fiume,
//! "Turbulent Wind Fields for Gaseous Phenomena" (SIGGRAPH 1993).
//!
//! The core is plain Rust: [`field`] synthesises the small-scale turbulence (paper §3) on a
//! [`lattice`] from an energy [`spectrum`], [`stats`] measures it against the paper's formulas.
//! [`api`] is the one module that speaks to JavaScript.

pub mod api;
pub mod error;
pub mod fft4;
pub mod field;
pub mod lattice;
pub mod npy;
pub mod spectrum;
pub mod stats;

pub use error::ParamError;
pub use field::{FieldParams, Synthesis, TurbulentField};
pub use lattice::Lattice;
pub use spectrum::{SpectrumLaw, SpectrumParams};
