//! The only door between JavaScript and the core: every `#[wasm_bindgen]` export lives under
//! `api/`, one file a bound class, and nothing else does; this file holds the conversions they
//! share and the TypeScript types of the frames. Each export converts its arguments from
//! JavaScript's types to the core's, calls the core, and converts the result back; the checks
//! are the core's, and its errors become thrown `Error`s whose message names the parameter
//! (`field.size[1]: must be an even number between 4 and 256`). Nothing panics across the
//! boundary.
//!
//! Calls are few and fat: parameters cross as one JSON string, lattice data, slices and frames
//! as whole typed arrays. A frame crosses as one plain object made in one call
//! (`packFrame`, `marchFrame`), never as getters that depend on the order of calls.
//!
//! Compiled for wasm32 only: the native core and command line do not link wasm-bindgen. Two
//! modules are built from it (scripts/build-wasm.sh): the first, which a player fetches
//! (the field's synthesis, its samples and slices, the scene's reading and simulation, frames),
//! and the full one (`--features full`: everything, adding the exports, the reference renderer,
//! the field's statistics and wind grid, and the classroom), fetched on first use.

#![deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

pub mod field_synthesis;
pub mod scene_simulation;
pub mod wind_field;

// The full build's bindings (`--features full`): exports, the reference renderer and the
// classroom. The first module the player fetches leaves them out.
#[cfg(feature = "full")]
pub mod classroom;
#[cfg(feature = "full")]
pub mod flipbook_export;
#[cfg(feature = "full")]
pub mod reference_render;
#[cfg(feature = "full")]
pub mod still_export;
#[cfg(feature = "full")]
pub mod volume_export;

use wasm_bindgen::prelude::*;

#[wasm_bindgen]
extern "C" {
    /// JavaScript's `Object.fromEntries`: a plain object from `[key, value]` pairs.
    #[wasm_bindgen(js_namespace = Object, js_name = fromEntries)]
    fn object_from_entries(entries: Vec<JsValue>) -> JsValue;
}

#[wasm_bindgen(typescript_custom_section)]
const FRAME_TYPES: &str = r#"
/** The points and volume views' frame (`frame::ViewFrame`): the packed blobs
 *  (`frame::packed`), their description (`PackedFrame::info`) and the moving spheres. */
export interface ViewFrame { words: Uint32Array; info: Float32Array; spheres: Float32Array; }
/** The exact march's frame (`frame::MarchFrame`): the merged blobs packed, their description
 *  and the shadow grid (`frame::shadow_grid`). */
export interface MarchFrame { words: Uint32Array; info: Float32Array; grid: Float32Array; }
/** The flow's grid at one time (`exportFlow`): the box (m), the cells, the time (s), u_g at the
 *  cells' centres (m/s, (nz, ny, nx, 3), x fastest) and the temperature excess (K, (nz, ny, nx)). */
export interface FlowGrid { box: number[]; cells: Uint32Array; time: number;
  velocity: Float32Array; temperature: Float32Array; }
/** The flow's u_g on each component's faces (`flowFaces`, m/s, x fastest): `u` across x,
 *  `v` across y, `w` across z. */
export interface FlowFaces { u: Float32Array; v: Float32Array; w: Float32Array; }
/** Streamlines past a solid sphere (`classroom::sphere_flow`): the core's wind and the closed form,
 *  `lines × points` (x, y) pairs each, in radii, and the largest gap between them. */
export interface SphereFlow { core: Float32Array; closedForm: Float32Array; lines: number;
  points: number; largestGap: number; }
/** Steps for the GPU stepper (`frame::gpu_steps::GpuSteps`): newborn records and their slots,
 *  the emptied slots, per-step ranges, the frozen wind tables, and the gas's count, highest
 *  slot and σ range after the last step. */
export interface GpuSteps { births: Float32Array; birthSlots: Uint32Array; freed: Uint32Array;
  ranges: Uint32Array; wind: Float32Array; windOffsets: Uint32Array; solidGrid: Float32Array; count: number;
  highWater: number; sigmaRange: Float32Array; spheres: Float32Array; emissive: boolean;
  time: number; }
"#;

/// A plain JavaScript object of `entries` (name, value).
pub(crate) fn object(entries: Vec<(&str, JsValue)>) -> JsValue {
    let pairs = entries
        .into_iter()
        .map(|(k, v)| JsValue::from(vec![JsValue::from_str(k), v]))
        .collect();
    object_from_entries(pairs)
}

pub(crate) fn js_error(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

pub(crate) fn parse<T: serde::de::DeserializeOwned>(json: &str, what: &str) -> Result<T, JsError> {
    serde_json::from_str(json).map_err(|e| JsError::new(&format!("{what}: {e}")))
}

/// Three numbers from a typed array; another length reads as not finite, so that the core's
/// check refuses it with its own message.
pub(crate) fn xyz(a: &[f32]) -> [f32; 3] {
    <[f32; 3]>::try_from(a).unwrap_or([f32::NAN; 3])
}

/// Three counts from a typed array; another length reads as zeros (refused by the core).
pub(crate) fn counts3(a: &[u32]) -> [u32; 3] {
    <[u32; 3]>::try_from(a).unwrap_or([0; 3])
}
#[cfg(feature = "full")]
/// The time a still or volume shows, from JavaScript: a finite number, or none (NaN).
pub(crate) fn known_time(t: f64) -> Option<f64> {
    t.is_finite().then_some(t)
}
