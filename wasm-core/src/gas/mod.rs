//! The animation system (paper §4 and §6): a scene, its wind, and the gas of Gaussian blobs the
//! wind carries, stepped in fixed steps; out of it comes the blob list a renderer takes.
//!
//! The formats, read strictly and checked in one walk:
//!
//! - [`scene`]: the scene format (docs/FORMATS.md), its types, defaults and JSON Schema.
//! - [`blob_list`]: the blob list (docs/FORMATS.md), the one moment a renderer draws. It lives here,
//!   beside the scene, because it is the scene's `render` section plus the blobs the gas made:
//!   the two formats share their view settings, their bounds and their validation, and the
//!   renderers downstream read it without knowing of scenes.
//! - [`limits`]: the bounds and memory guards of both formats.
//! - [`read`]: parsing from JSON (errors at their JSON path, version migration), bounded
//!   first by [`list_budget`] (every list counted in the text before it is built); serde's
//!   errors in a person's words by [`json_errors`].
//! - [`validate`]: the one validation walk of each format.
//!
//! The physics, in the order a step uses it:
//!
//! - [`wind`]: the wind u = u_l + u_s (Eq. 3), the large-scale primitives over the
//!   small-scale field ([`crate::field`]); [`spline`] moves the repulsors; [`wind_slice`]
//!   samples it on a plane; [`frozen`] holds the primitives frozen at one time and
//!   [`wind_table`] the frozen wind as the GPU reads it. [`solids`]: the solid objects it
//!   goes round (found among many by [`solid_grid`]), and [`walls`] how it goes round them
//!   ([`doublets`]: the spheres' doublets summed four at a time); [`carried`]: the small
//!   scales carried by the large ones (§7).
//! - [`emitter`], [`shapes`]: where blobs are born (§6), drawing from [`random`].
//! - [`blobs`]: the blobs' state (Eq. 13); [`blob_gas`]: advection (Eq. 14), diffusion
//!   (Eq. 15), dissipation (Eq. 16) and splitting, one step at a time.
//! - [`simulation`]: the scene's field, wind and gas advanced together, live edits, and the
//!   blob list of the current state; [`slots`]: where each blob lives while the GPU advects it.
//! - [`figure1`]: the paper's Figure 1, a grid solution of Eq. 12 beside the blob model;
//!   [`sphere_flow`]: streamlines past a solid sphere beside the potential flow.

pub mod blob_gas;
pub mod blob_list;
pub mod blobs;
pub mod carried;
pub mod doublets;
pub mod emitter;
pub mod figure1;
pub mod frozen;
pub mod json_errors;
pub mod limits;
pub mod list_budget;
pub mod random;
pub mod read;
pub mod scene;
pub mod shapes;
pub mod simulation;
pub mod slots;
pub mod solid_grid;
pub mod solids;
pub mod sphere_flow;
pub mod spline;
pub mod validate;
pub mod walls;
pub mod wind;
pub mod wind_slice;
pub mod wind_table;

pub use blob_gas::{Gas, GasCounts};
pub use blob_list::BlobList;
pub use blobs::{Blob, Blobs};
pub use scene::Scene;
pub use simulation::{Edit, Simulation};
