//! The gas (paper §4 and §6): Gaussian blobs born by emitters and initial sets, carried by the
//! wind ([`crate::wind`]) and stepped in fixed steps; out of it comes the blob list
//! ([`crate::scene::blob_list`]) a renderer takes.
//!
//! - [`emitter`], [`shape_sampling`]: where blobs are born (§6: an emitter's region and rate,
//!   an initial set's points), drawing from [`random`].
//! - [`blobs`]: the blobs' state, each a density m·G(x − c, σ) (Eq. 13); [`blob_gas`]:
//!   advection of the centres by the wind (Eq. 14), diffusion σ² += κ dt (Eq. 15),
//!   dissipation m ∝ e^(−α t) (Eq. 16) and splitting, one step at a time.
//! - [`simulation`]: the scene's field, wind and gas advanced together, live edits, and the
//!   blob list of the current state; [`gpu_handoff`]: the same steps while the GPU advects the
//!   centres, [`slots`]: where each blob lives there.

pub mod blob_gas;
pub mod blobs;
pub mod emitter;
pub mod gpu_handoff;
pub mod random;
pub mod shape_sampling;
pub mod simulation;
pub mod slots;

pub use blob_gas::{Gas, GasCounts};
pub use blobs::{Blob, Blobs};
pub use simulation::{Edit, Simulation};
