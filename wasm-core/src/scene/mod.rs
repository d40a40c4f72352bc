//! The formats and their checks (docs/FORMATS.md), knowing no physics: what a scene says and
//! what a renderer is handed, read strictly and checked in one walk.
//!
//! - [`scene_format`]: the scene format, version 1 — the field's settings and its world
//!   mapping (paper §3), the large-scale wind primitives u_l (Eq. 3), the emitters (§6), the
//!   gas constants (Eqs. 12, 15, 16), the simulation's step and the render settings — with its
//!   types, defaults and JSON Schema.
//! - [`flow_settings`]: the scene's `flow`, the coarse grid of the physical large scales
//!   (§7) and its constants.
//! - [`shapes`]: the initial blob sets (§6, "3-D morphing") as the scene writes them;
//!   [`bodies`]: the solid objects as shapes (signed distance and normal).
//! - [`blob_list`]: the blob list, the one moment a renderer draws (§5: the blobs' centres,
//!   σ and masses, Eq. 13, with the view). It lives here, beside the scene, because it is the
//!   scene's `render` section plus the blobs the gas made: the two formats share their view
//!   settings, their bounds and their validation, and the renderers downstream read it without
//!   knowing of scenes.
//! - [`limits`]: the bounds and memory guards of both formats.
//! - [`read`]: parsing from JSON (errors at their JSON path, version migration), bounded
//!   first by [`list_budget`] (every list counted in the text before it is built); serde's
//!   errors in a person's words by [`json_errors`].
//! - [`validate`]: the one validation walk of each format.

pub mod blob_list;
pub mod bodies;
pub mod flow_settings;
pub mod json_errors;
pub mod limits;
pub mod list_budget;
pub mod read;
pub mod scene_format;
pub mod shapes;
pub mod validate;

pub use blob_list::BlobList;
pub use scene_format::Scene;
