//! The small-scale turbulence u_s (paper §3): a periodic, divergence-free random vector field
//! over 4-D space-time, synthesised once per field settings.
//!
//! In the order the synthesis uses them:
//!
//! - [`spectrum`]: the energy spectrum E(k) (Eq. 9) and the temporal spread G_k(ω) (Eq. 10).
//! - [`lattice`]: the 4-D lattice, one period 2π along x, y, z and t; wave numbers.
//! - [`noise`]: the seeded complex white noise the spectrum filters.
//! - [`velocity_spectrum`]: û, the noise filtered by Eq. 7 and projected normal to k.
//! - [`fft4`], [`real_fft`]: the 4-D inverse transform (complex along t, z, y; real along x).
//! - [`synthesis`]: the staged synthesis from û to the field, in the field's own memory.
//! - [`turbulent_field`]: the synthesised field, its parameters and its quadrilinear sampling.
//! - [`statistics`]: the field measured against the paper's formulas (docs/FORMATS.md, statistics).
//! - [`npy`]: NumPy `.npy` files, how the command line reads and writes fields.
//!
//! Nothing here knows of scenes, blobs or renderers.

pub mod fft4;
pub mod lattice;
pub mod noise;
pub mod npy;
pub mod real_fft;
pub mod spectrum;
pub mod statistics;
pub mod synthesis;
pub mod turbulent_field;
pub mod velocity_spectrum;

pub use synthesis::{Stage, Synthesis};
pub use turbulent_field::{FieldParams, TurbulentField, MAX_SEED};
pub use velocity_spectrum::{hermitian_potential_spectrum, hermitian_spectrum};
