//! The only door between JavaScript and the core: every `#[wasm_bindgen]` export lives here,
//! and nothing else does. Each export converts its arguments from JavaScript's types to the
//! core's, calls the core, and converts the result back; errors become thrown `Error`s whose
//! message names the parameter (`field.size[1]: must be an even number between 4 and 256`).
//! Nothing panics across the boundary.
//!
//! Calls are few and fat: parameters cross as one JSON string, lattice data, slices and frames
//! as whole typed arrays. A frame crosses as one plain object made in one call
//! (`packFrame`, `marchFrame`), never as getters that depend on the order of calls.
//!
//! Compiled for wasm32 only: the native core and command line do not link wasm-bindgen.

#![deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use crate::classroom::figure1::{Figure1, Figure1Params};
use crate::export::exr::ExrInfo;
use crate::export::flipbook::{FlipbookJob, FlipbookSpec, SettingNames};
use crate::export::still::{self, StillFormat};
use crate::export::volume::VolumeBuild;
use crate::field::spectrum::SpectrumParams;
use crate::field::statistics;
use crate::field::{FieldParams, Synthesis, TurbulentField};
use crate::frame::gpu_steps::{gas_by_slot, GpuSteps};
use crate::frame::light_volume::light_twin;
use crate::frame::volume::{density_twin, VoxelGrid};
use crate::frame::{merged_list, MarchFrame, PackedFrame, ViewFrame};
use crate::gas::simulation::{Edit, Simulation};
use crate::render::{BandedRender, RenderOptions, Renderer};
use crate::scene::blob_list::Camera;
use crate::scene::blob_list::{BlobList, Encoding};
use crate::scene::Scene;
use crate::wind::wind_slice::SlicePlane;
use std::sync::Arc;
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
/** Steps for the GPU stepper (`frame::gpu_steps::GpuSteps`): newborn records and their slots,
 *  the emptied slots, per-step ranges, the frozen wind tables, and the gas's count, highest
 *  slot and σ range after the last step. */
/** Streamlines past a solid sphere (`gas::sphere_flow`): the core's wind and the closed form,
 *  `lines × points` (x, y) pairs each, in radii, and the largest gap between them. */
export interface SphereFlow { core: Float32Array; closedForm: Float32Array; lines: number;
  points: number; largestGap: number; }
export interface GpuSteps { births: Float32Array; birthSlots: Uint32Array; freed: Uint32Array;
  ranges: Uint32Array; wind: Float32Array; windOffsets: Uint32Array; solidGrid: Float32Array; count: number;
  highWater: number; sigmaRange: Float32Array; spheres: Float32Array; emissive: boolean;
  time: number; }
"#;

/// A plain JavaScript object of `entries` (name, value).
fn object(entries: Vec<(&str, JsValue)>) -> JsValue {
    let pairs = entries
        .into_iter()
        .map(|(k, v)| JsValue::from(vec![JsValue::from_str(k), v]))
        .collect();
    object_from_entries(pairs)
}

fn js_error(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

fn parse<T: serde::de::DeserializeOwned>(json: &str, what: &str) -> Result<T, JsError> {
    serde_json::from_str(json).map_err(|e| JsError::new(&format!("{what}: {e}")))
}

/// Three numbers from a typed array; another length reads as not finite, so that the core's
/// check refuses it with its own message.
fn xyz(a: &[f32]) -> [f32; 3] {
    <[f32; 3]>::try_from(a).unwrap_or([f32::NAN; 3])
}

/// Three counts from a typed array; another length reads as zeros (refused by the core).
fn counts3(a: &[u32]) -> [u32; 3] {
    <[u32; 3]>::try_from(a).unwrap_or([0; 3])
}

/// A field synthesis in progress; `step()` runs one stage so a worker can report progress.
#[wasm_bindgen]
pub struct FieldSynthesis {
    inner: Option<Synthesis>,
}

#[wasm_bindgen]
impl FieldSynthesis {
    /// `params_json`: `{"size": [nx,ny,nz,nt], "spectrum": {...}, "seed": n}`, and
    /// `"potential": true` to synthesise the field's vector potential with it (a scene with
    /// solid objects: `sceneFieldParams` says so).
    #[wasm_bindgen(constructor)]
    pub fn new(params_json: &str) -> Result<FieldSynthesis, JsError> {
        let mut value: serde_json::Value = parse(params_json, "field")?;
        let potential = value
            .as_object_mut()
            .and_then(|o| o.remove("potential"))
            .is_some_and(|p| p == serde_json::Value::Bool(true));
        let params: FieldParams =
            serde_json::from_value(value).map_err(|e| JsError::new(&format!("field: {e}")))?;
        let inner = if potential {
            Synthesis::with_potential(&params)
        } else {
            Synthesis::new(&params)
        }
        .map_err(js_error)?;
        Ok(Self { inner: Some(inner) })
    }

    /// Runs one stage; false once only `finish()` is left.
    pub fn step(&mut self) -> bool {
        self.inner.as_mut().is_some_and(|s| s.run_stage())
    }

    /// What the next `step()` does, for progress displays.
    pub fn stage(&self) -> String {
        self.inner
            .as_ref()
            .map_or_else(|| "done".into(), |s| s.describe())
    }

    /// Fraction of the work done, 0..1.
    pub fn progress(&self) -> f64 {
        self.inner.as_ref().map_or(1.0, |s| s.progress())
    }

    /// Completes the synthesis; may be called once.
    pub fn finish(&mut self) -> Result<WindField, JsError> {
        let s = self
            .inner
            .take()
            .ok_or_else(|| JsError::new("synthesis already finished"))?;
        Ok(WindField {
            inner: Arc::new(s.finish()),
        })
    }
}

/// A synthesised small-scale field.
#[wasm_bindgen]
pub struct WindField {
    inner: Arc<TurbulentField>,
}

#[wasm_bindgen]
impl WindField {
    /// Generates a field in one call (see [`FieldSynthesis`] for the staged form).
    pub fn generate(params_json: &str) -> Result<WindField, JsError> {
        let params: FieldParams = parse(params_json, "field")?;
        let inner = TurbulentField::generate(&params).map_err(js_error)?;
        Ok(Self {
            inner: Arc::new(inner),
        })
    }

    /// `[nx, ny, nz, nt]`.
    pub fn size(&self) -> Vec<u32> {
        self.inner.lattice.size.iter().map(|&n| n as u32).collect()
    }

    /// A copy of the lattice data, `(nt, nz, ny, nx, 3)` in C order.
    pub fn data(&self) -> Vec<f32> {
        self.inner.data.clone()
    }

    /// A copy of the vector potential ψ's lattice (as `data`), empty when the field was
    /// synthesised without it.
    pub fn potential(&self) -> Vec<f32> {
        self.inner.potential.clone().unwrap_or_default()
    }

    /// Quadrilinear sample at lattice coordinates `(x, y, z, t)`: `[u1, u2, u3]`.
    pub fn sample(&self, x: f64, y: f64, z: f64, t: f64) -> Vec<f32> {
        self.inner.sample_lattice([x, y, z, t]).to_vec()
    }

    /// One time slice of this field as the world's wind (`export::vector_grid::VectorGrid::
    /// field_slice`): `period` (m, three), `time_period` (s), `amplitude` and the time `t` (s)
    /// map it as a scene's `field` does. `format` is `"vdb"` (a Vec3SGrid `wind`, the bytes
    /// `windfield generate --out wind.vdb` writes) or `"rgb32f"` (the raw texture); its JSON
    /// description (the `.rgb32f.json` beside a texture) is `windGridDescription`.
    #[wasm_bindgen(js_name = windGrid)]
    pub fn wind_grid(
        &self,
        period: Vec<f64>,
        time_period: f64,
        amplitude: f64,
        t: f64,
        format: &str,
    ) -> Result<Vec<u8>, JsError> {
        let grid = self.wind_slice(&period, time_period, amplitude, t)?;
        match format {
            "vdb" => Ok(grid.to_vdb()),
            "rgb32f" => Ok(grid.to_rgb32f()),
            _ => Err(JsError::new(&format!(
                "format: must be 'vdb' or 'rgb32f' (got {format:?})"
            ))),
        }
    }

    /// The JSON description of `windGrid`'s raw texture for the same arguments.
    #[wasm_bindgen(js_name = windGridDescription)]
    pub fn wind_grid_description(
        &self,
        period: Vec<f64>,
        time_period: f64,
        amplitude: f64,
        t: f64,
    ) -> Result<String, JsError> {
        let grid = self.wind_slice(&period, time_period, amplitude, t)?;
        serde_json::to_string_pretty(&grid.description())
            .map(|text| text + "\n")
            .map_err(|e| JsError::new(&e.to_string()))
    }

    /// The plane z = `z` at time `t` (lattice units) on a `width × height` grid over one
    /// period in x and y (`TurbulentField::slice_xy`).
    pub fn slice_xy(&self, z: f64, t: f64, width: u32, height: u32) -> Vec<f32> {
        self.inner.slice_xy(z, t, width, height)
    }

    /// Statistics (JSON) of the field against `spectrum_json` (or its own spectrum if empty).
    pub fn stats(&self, spectrum_json: &str) -> Result<String, JsError> {
        let spectrum: SpectrumParams = if spectrum_json.is_empty() {
            self.inner.params.spectrum
        } else {
            let asked: SpectrumParams = parse(spectrum_json, "spectrum")?;
            // The ranges a scene's field.spectrum has, on this field's lattice.
            asked.validate("spectrum").map_err(js_error)?;
            asked
        };
        let report = statistics::analyse(&self.inner, &spectrum);
        serde_json::to_string(&report).map_err(js_error)
    }
}

impl WindField {
    /// The checked slice behind `windGrid` and `windGridDescription`.
    fn wind_slice(
        &self,
        period: &[f64],
        time_period: f64,
        amplitude: f64,
        t: f64,
    ) -> Result<crate::export::vector_grid::VectorGrid, JsError> {
        let period: [f64; 3] = period
            .try_into()
            .map_err(|_| JsError::new("period: must be three lengths in metres"))?;
        let ok = |v: f64, lo: f64, hi: f64| v.is_finite() && v >= lo && v <= hi;
        if !period.iter().all(|&l| ok(l, 1e-3, 1e4)) {
            return Err(JsError::new("period: each must be from 0.001 to 10000 m"));
        }
        if !ok(time_period, 1e-3, 1e6) || !ok(amplitude, 0.0, 1e3) || !ok(t, 0.0, 1e5) {
            return Err(JsError::new(
                "time_period (0.001 to 10⁶ s), amplitude (0 to 1000) and t (0 to 10⁵ s) must be in range",
            ));
        }
        Ok(crate::export::vector_grid::VectorGrid::field_slice(
            &self.inner,
            period,
            time_period,
            amplitude,
            t,
        ))
    }
}

/// The classroom's solid sphere: `lines` streamlines of `points` points (x, y in radii) of the
/// core's wind past a solid sphere of unit radius in a unit wind along x, and the same of the
/// potential flow around it, with the largest gap between the two (`classroom::sphere_flow`).
#[wasm_bindgen(js_name = sphereFlow, unchecked_return_type = "SphereFlow")]
pub fn sphere_flow(lines: u32, points: u32) -> JsValue {
    let flow = crate::classroom::sphere_flow::sphere_flow(lines as usize, points as usize);
    object(vec![
        ("core", flow.core.into()),
        ("closedForm", flow.closed_form.into()),
        ("lines", (flow.lines as u32).into()),
        ("points", (flow.points as u32).into()),
        ("largestGap", flow.largest_gap.into()),
    ])
}

/// Checks a scene; returns it normalised (every default filled in) as JSON, or throws an
/// Error naming the offending path.
#[wasm_bindgen(js_name = validateScene)]
pub fn validate_scene(scene_json: &str) -> Result<String, JsError> {
    Ok(Scene::from_json(scene_json).map_err(js_error)?.to_json())
}

/// The field parameters (`{size, spectrum, seed}` JSON) a scene needs, with `"potential":
/// true` when it needs the field's vector potential too (solid objects): the key of the
/// field's synthesis.
#[wasm_bindgen(js_name = sceneFieldParams)]
pub fn scene_field_params(scene_json: &str) -> Result<String, JsError> {
    let scene = Scene::from_json(scene_json).map_err(js_error)?;
    let mut value = serde_json::to_value(scene.field_params()).map_err(js_error)?;
    if scene.needs_potential() {
        if let Some(o) = value.as_object_mut() {
            o.insert("potential".into(), true.into());
        }
    }
    Ok(value.to_string())
}

/// A running scene: wind and gas advanced in fixed steps. Frames come out whole, as one object
/// of typed arrays per call (`packFrame`, `marchFrame`).
#[wasm_bindgen]
pub struct SceneSimulation {
    inner: Simulation,
}

#[wasm_bindgen]
impl SceneSimulation {
    /// Builds a simulation, synthesising the scene's field (skipped when its amplitude is 0).
    #[wasm_bindgen(constructor)]
    pub fn new(scene_json: &str) -> Result<SceneSimulation, JsError> {
        let scene = Scene::from_json(scene_json).map_err(js_error)?;
        let inner = Simulation::new(scene).map_err(js_error)?;
        Ok(Self { inner })
    }

    /// Builds a simulation on an existing field, which must have the scene's field parameters.
    #[wasm_bindgen(js_name = withField)]
    pub fn with_field(scene_json: &str, field: &WindField) -> Result<SceneSimulation, JsError> {
        let scene = Scene::from_json(scene_json).map_err(js_error)?;
        let inner = Simulation::with_field(scene, Some(field.inner.clone())).map_err(js_error)?;
        Ok(Self { inner })
    }

    /// Applies an edited scene to the running simulation, keeping its blobs and time
    /// (`Simulation::edit`), on the small-scale field in use (the scene's is synthesised
    /// meanwhile and swapped in with `setField`). True when the edit restarted the scene
    /// instead (its `shapes` changed).
    pub fn edit(&mut self, scene_json: &str) -> Result<bool, JsError> {
        let field = self.inner.field().cloned();
        self.edit_on(scene_json, field)
    }

    /// [`Self::edit`] on `field`, which has the edited scene's field settings.
    #[wasm_bindgen(js_name = editWithField)]
    pub fn edit_with_field(
        &mut self,
        scene_json: &str,
        field: &WindField,
    ) -> Result<bool, JsError> {
        self.edit_on(scene_json, Some(field.inner.clone()))
    }

    /// Swaps in the small-scale field synthesised for the scene's field settings.
    #[wasm_bindgen(js_name = setField)]
    pub fn set_field(&mut self, field: &WindField) -> Result<(), JsError> {
        self.inner
            .set_field(Some(field.inner.clone()))
            .map_err(js_error)
    }

    /// Stirs the gas from the next step on (`Simulation::stir_at`): a wind of `velocity` (m/s,
    /// xyz) at `position` (m, xyz), falling off as exp(−distance/`radius`); `radius` 0 stops it.
    pub fn stir(&mut self, position: &[f32], velocity: &[f32], radius: f32) -> Result<(), JsError> {
        self.inner
            .stir_at(xyz(position), xyz(velocity), radius)
            .map_err(js_error)
    }

    /// Runs `n` fixed steps.
    pub fn step(&mut self, n: u32) {
        self.inner.run(n as u64);
    }

    /// Refuses a run of `steps` fixed steps that is not a whole number or is over the budget
    /// (`Simulation::check_steps`).
    #[wasm_bindgen(js_name = checkSteps)]
    pub fn check_steps(&self, steps: f64) -> Result<(), JsError> {
        self.inner.check_steps(steps).map_err(js_error)?;
        Ok(())
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.inner.time()
    }

    /// Live blob count.
    pub fn count(&self) -> u32 {
        self.inner.blobs().len() as u32
    }

    /// Blob centres, xyz interleaved (m).
    pub fn positions(&self) -> Vec<f32> {
        self.inner.blobs().position.clone()
    }

    /// Adds blobs born now at `positions` (xyz interleaved) with σ0 and m0, medium albedo
    /// (`Simulation::add_blobs`).
    #[wasm_bindgen(js_name = addBlobs)]
    pub fn add_blobs(&mut self, positions: &[f32], sigma0: f32, mass0: f32) -> Result<(), JsError> {
        self.inner
            .add_blobs(positions, sigma0, mass0)
            .map_err(js_error)
    }

    /// The blob list (docs/FORMATS.md) for the current state (JSON).
    #[wasm_bindgen(js_name = blobList)]
    pub fn blob_list(&self) -> Result<String, JsError> {
        serde_json::to_string(&self.inner.blob_list()).map_err(js_error)
    }

    /// The whole wind u = u_l + u_s (Eq. 3) now on the parallelogram `origin + a·u + b·v` (m),
    /// sampled at the centres of `nu × nv` cells: `3·nu·nv` m/s, u-index fastest
    /// (`SlicePlane`).
    #[wasm_bindgen(js_name = windSlice)]
    pub fn wind_slice(
        &self,
        origin: &[f32],
        u: &[f32],
        v: &[f32],
        nu: u32,
        nv: u32,
    ) -> Result<Vec<f32>, JsError> {
        let plane = SlicePlane::new(xyz(origin), xyz(u), xyz(v), nu, nv).map_err(js_error)?;
        Ok(self.inner.wind_slice(&plane))
    }

    /// Hands the centres to the GPU (`Simulation::hand_centres_to_gpu`): the whole gas as blob
    /// records in slot order (`frame::gpu_steps`), what the GPU starts from. Throws for a
    /// scene that splits blobs or plays a shape in reverse.
    #[wasm_bindgen(js_name = handCentresToGpu)]
    pub fn hand_centres_to_gpu(&mut self) -> Result<Vec<f32>, JsError> {
        self.inner.hand_centres_to_gpu().map_err(js_error)?;
        Ok(gas_by_slot(&self.inner))
    }

    /// `n` steps while the GPU advects the centres, whole (`frame::gpu_steps::GpuSteps`):
    /// `{births, birthSlots, freed, ranges, wind, windOffsets, solidGrid, count, highWater, sigmaRange,
    /// spheres, emissive, time}`.
    #[wasm_bindgen(js_name = stepForGpu, unchecked_return_type = "GpuSteps")]
    pub fn step_for_gpu(&mut self, n: u32) -> JsValue {
        let steps = GpuSteps::run(&mut self.inner, n);
        object(vec![
            ("births", steps.births.into()),
            ("birthSlots", steps.birth_slots.into()),
            ("freed", steps.freed.into()),
            ("ranges", steps.ranges.into()),
            ("wind", steps.wind.into()),
            ("windOffsets", steps.wind_offsets.into()),
            ("solidGrid", steps.solid_grid.into()),
            ("count", steps.count.into()),
            ("highWater", steps.high_water.into()),
            ("sigmaRange", steps.sigma_range.to_vec().into()),
            ("spheres", steps.spheres.into()),
            ("emissive", steps.emissive.into()),
            ("time", self.inner.time().into()),
        ])
    }

    /// Takes the GPU's centres (xyz per slot, m) as the blobs' own; with `keepOnGpu` false the
    /// core steps them again from now on.
    #[wasm_bindgen(js_name = takeCentres)]
    pub fn take_centres(&mut self, centres: &[f32], keep_on_gpu: bool) {
        self.inner.take_centres(centres, keep_on_gpu);
    }

    /// Whether the GPU advects the centres.
    #[wasm_bindgen(js_name = centresOnGpu)]
    pub fn centres_on_gpu(&self) -> bool {
        self.inner.centres_on_gpu()
    }

    /// The current frame for the points and volume views, whole (`frame::ViewFrame`):
    /// `{words, info, spheres}`, the blobs packed eight words each in σ classes, their
    /// description (`PackedFrame::info`) and the moving spheres.
    #[wasm_bindgen(js_name = packFrame, unchecked_return_type = "ViewFrame")]
    pub fn pack_frame(&self) -> JsValue {
        let frame = ViewFrame::of(&self.inner);
        object(vec![
            ("info", frame.packed.info().into()),
            ("words", frame.packed.words.into()),
            ("spheres", frame.spheres.into()),
        ])
    }

    /// The exact march's frame, whole (`frame::MarchFrame`): `{words, info, grid}`, the blobs
    /// merged as `marchList(fraction)` merges them and packed as `packFrame` packs, and the
    /// shadow grid at `res`³ (`frame::shadow_grid`).
    #[wasm_bindgen(js_name = marchFrame, unchecked_return_type = "MarchFrame")]
    pub fn march_frame(&self, fraction: f32, res: u32) -> Result<JsValue, JsError> {
        let frame = MarchFrame::of(&self.inner, fraction, res).map_err(js_error)?;
        Ok(object(vec![
            ("info", frame.packed.info().into()),
            ("words", frame.packed.words.into()),
            ("grid", frame.shadow_grid.into()),
        ]))
    }

    /// The real-time view's density volume for the current blobs on the grid of `dims` voxels
    /// of side `h` from `lo` (`frame::volume::density_twin`): the twin the browser's GPU volume
    /// is tested against.
    #[wasm_bindgen(js_name = volumeTwin)]
    pub fn volume_twin(&self, lo: &[f32], h: f32, dims: &[u32]) -> Result<Vec<f32>, JsError> {
        let grid = VoxelGrid::new(xyz(lo), h, counts3(dims)).map_err(js_error)?;
        Ok(density_twin(
            &PackedFrame::of_simulation(&self.inner),
            &grid,
        ))
    }

    /// The light volume on the same grid towards the scene's first lights, in steps of
    /// `step × h` (`frame::light_volume::light_twin`).
    #[wasm_bindgen(js_name = lightTwin)]
    pub fn light_twin(
        &self,
        lo: &[f32],
        h: f32,
        dims: &[u32],
        step: f32,
    ) -> Result<Vec<f32>, JsError> {
        let grid = VoxelGrid::new(xyz(lo), h, counts3(dims)).map_err(js_error)?;
        let packed = PackedFrame::of_simulation(&self.inner);
        light_twin(&packed, &grid, &self.inner.scene.render.lights, step).map_err(js_error)
    }

    /// The blob list for the GPU ray march (JSON): blobs closer than `fraction × σ` merged by
    /// moments (`frame::lod`); `fraction` ≤ 0 gives the exact list.
    #[wasm_bindgen(js_name = marchList)]
    pub fn march_list(&self, fraction: f32) -> Result<String, JsError> {
        serde_json::to_string(&merged_list(self.inner.blob_list(), fraction)).map_err(js_error)
    }
}

impl SceneSimulation {
    fn edit_on(
        &mut self,
        scene_json: &str,
        field: Option<Arc<TurbulentField>>,
    ) -> Result<bool, JsError> {
        let scene = Scene::from_json(scene_json).map_err(js_error)?;
        let outcome = self.inner.edit(scene, field).map_err(js_error)?;
        Ok(outcome == Edit::Restarted)
    }
}

/// A reference still in progress: the CPU renderer of the rendering model (docs/FORMATS.md), a band of rows at a time so a
/// worker can report progress (`render::BandedRender`).
#[wasm_bindgen]
pub struct ReferenceRender {
    inner: BandedRender,
    encoding: Encoding,
}

#[wasm_bindgen]
impl ReferenceRender {
    /// `blob_list_json`: a blob list (docs/FORMATS.md); `width`/`height` of 0 keep the list's size.
    #[wasm_bindgen(constructor)]
    pub fn new(blob_list_json: &str, width: u32, height: u32) -> Result<ReferenceRender, JsError> {
        let value: serde_json::Value = parse(blob_list_json, "blob list")?;
        let list = BlobList::from_value(value).map_err(js_error)?;
        let size = (width > 0 && height > 0).then_some((width, height));
        let renderer = Renderer::new(&list, size, RenderOptions::default()).map_err(js_error)?;
        Ok(Self {
            inner: BandedRender::new(renderer),
            encoding: list.image.encoding,
        })
    }

    /// Renders up to `rows` more rows; false once the image is complete.
    pub fn step(&mut self, rows: u32) -> bool {
        self.inner.step(rows)
    }

    /// Fraction of rows done, 0..1.
    pub fn progress(&self) -> f64 {
        self.inner.progress()
    }

    pub fn width(&self) -> u32 {
        self.inner.width()
    }

    pub fn height(&self) -> u32 {
        self.inner.height()
    }

    /// The image as 8-bit RGB in the list's encoding (rows rendered so far).
    pub fn rgb(&self) -> Vec<u8> {
        self.inner.image().to_rgb8(self.encoding)
    }

    /// The image as PNG bytes (RGBA with straight colour over a transparent background).
    pub fn png(&self) -> Result<Vec<u8>, JsError> {
        self.inner.image().to_png(self.encoding).map_err(js_error)
    }
}

/// The time a still or volume shows, from JavaScript: a finite number, or none (NaN).
fn known_time(t: f64) -> Option<f64> {
    t.is_finite().then_some(t)
}

/// A still for export (`exportStill`): the reference renderer a band of rows at a time, then
/// PNG or OpenEXR bytes, exactly what `windfield render LIST --out still.png|.exr` writes.
#[wasm_bindgen]
pub struct StillExport {
    inner: BandedRender,
    encoding: Encoding,
    format: StillFormat,
    info: ExrInfo,
}

#[wasm_bindgen]
impl StillExport {
    /// `blob_list_json` at its own size; `format` `png` or `exr`; `time` (s) the moment it
    /// shows, written into the EXR header (NaN for none).
    #[wasm_bindgen(constructor)]
    pub fn new(blob_list_json: &str, format: &str, time: f64) -> Result<StillExport, JsError> {
        let format = StillFormat::parse(format, "format").map_err(js_error)?;
        let value: serde_json::Value = parse(blob_list_json, "blob list")?;
        let list = BlobList::from_value(value).map_err(js_error)?;
        let renderer = Renderer::new(&list, None, RenderOptions::default()).map_err(js_error)?;
        Ok(Self {
            inner: BandedRender::new(renderer),
            encoding: list.image.encoding,
            format,
            info: ExrInfo {
                camera: Some(list.camera.clone()),
                time: known_time(time),
                fps: None,
                note: String::new(),
            },
        })
    }

    /// Renders up to `rows` more rows; false once the image is complete.
    pub fn step(&mut self, rows: u32) -> bool {
        self.inner.step(rows)
    }

    /// Fraction of rows done, 0..1.
    pub fn progress(&self) -> f64 {
        self.inner.progress()
    }

    pub fn height(&self) -> u32 {
        self.inner.height()
    }

    /// The file's bytes (call once every row is rendered).
    pub fn bytes(&self) -> Result<Vec<u8>, JsError> {
        still::encode(&self.inner.image(), self.format, self.encoding, &self.info)
            .map_err(|e| JsError::new(&e))
    }
}

/// What `exportFlipbook` asks for (JSON).
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct FlipbookRequest {
    frames: [u64; 2],
    fps: f64,
    grid: [u32; 2],
    tile: [u32; 2],
    /// Frames blended across the wrap; 0 for none.
    fade: u32,
    format: String,
    camera: Option<Camera>,
}

/// The names of the settings of `exportFlipbook`, for its messages.
const FLIPBOOK_NAMES: SettingNames = SettingNames {
    frames: "frames",
    fps: "fps",
    grid: "grid",
    tile: "tile",
    fade: "loop",
};

/// A flipbook for export (`exportFlipbook`): the scene simulated from t = 0 on the running
/// field, each frame rendered a band of rows at a time, then the sheet's bytes and its
/// description; what `windfield flipbook` writes.
#[wasm_bindgen]
pub struct FlipbookExport {
    inner: Option<FlipbookJob>,
}

impl FlipbookExport {
    fn make(
        scene_json: &str,
        request_json: &str,
        field: Option<Option<Arc<TurbulentField>>>,
    ) -> Result<FlipbookExport, JsError> {
        let scene = Scene::from_json(scene_json).map_err(js_error)?;
        let r: FlipbookRequest = parse(request_json, "exportFlipbook")?;
        let format = StillFormat::parse(&r.format, "format").map_err(js_error)?;
        let spec = FlipbookSpec {
            start: r.frames[0],
            end: r.frames[1],
            fps: r.fps,
            columns: r.grid[0],
            rows: r.grid[1],
            tile_width: r.tile[0],
            tile_height: r.tile[1],
            fade: r.fade,
        };
        let job = FlipbookJob::new(scene, field, spec, format, r.camera, &FLIPBOOK_NAMES)
            .map_err(js_error)?;
        Ok(Self { inner: Some(job) })
    }
}

#[wasm_bindgen]
impl FlipbookExport {
    /// `request_json`: `{frames: [A, B], fps, grid: [C, R], tile: [W, H], fade, format,
    /// camera}`; the scene's field is synthesised (see `withField`).
    #[wasm_bindgen(constructor)]
    pub fn new(scene_json: &str, request_json: &str) -> Result<FlipbookExport, JsError> {
        Self::make(scene_json, request_json, None)
    }

    /// As `new`, on `field` (the scene's own, already synthesised).
    #[wasm_bindgen(js_name = withField)]
    pub fn with_field(
        scene_json: &str,
        request_json: &str,
        field: &WindField,
    ) -> Result<FlipbookExport, JsError> {
        Self::make(scene_json, request_json, Some(Some(field.inner.clone())))
    }

    /// Renders up to `rows` more rows; false once every frame is in.
    pub fn step(&mut self, rows: u32) -> Result<bool, JsError> {
        match &mut self.inner {
            Some(job) => job.step(rows).map_err(js_error),
            None => Ok(false),
        }
    }

    /// Share of the work done, 0..1.
    pub fn progress(&self) -> f64 {
        self.inner.as_ref().map_or(1.0, FlipbookJob::progress)
    }

    /// The sheet's bytes and its description (JSON), `image` its file name:
    /// `{sheet, description}`. May be called once.
    pub fn finish(&mut self, image: &str) -> Result<JsValue, JsError> {
        let job = self
            .inner
            .take()
            .ok_or_else(|| JsError::new("the flipbook was finished already"))?;
        let (bytes, description) = job.finish(image).map_err(|e| JsError::new(&e))?;
        let json = serde_json::to_string(&description).map_err(js_error)?;
        Ok(object(vec![
            ("sheet", bytes.into()),
            ("description", json.into()),
        ]))
    }
}

/// A volume for export (`exportVolume`): the blobs deposited a share at a time, then the
/// `.vdb` bytes `windfield volume LIST --voxel H` writes.
#[wasm_bindgen]
pub struct VolumeExport {
    inner: Option<VolumeBuild>,
    time: Option<f64>,
}

#[wasm_bindgen]
impl VolumeExport {
    /// The blobs of `blob_list_json` at voxels of `voxel` m; `time` (s) the moment they show
    /// (NaN for none). Refused over the voxel budget, naming `voxel`.
    #[wasm_bindgen(constructor)]
    pub fn new(blob_list_json: &str, voxel: f64, time: f64) -> Result<VolumeExport, JsError> {
        let value: serde_json::Value = parse(blob_list_json, "blob list")?;
        let list = BlobList::from_value(value).map_err(js_error)?;
        let build = VolumeBuild::new(&list, voxel, "voxel").map_err(js_error)?;
        Ok(Self {
            inner: Some(build),
            time: known_time(time),
        })
    }

    /// Deposits up to `blobs` more blobs; false once all are in.
    pub fn step(&mut self, blobs: u32) -> bool {
        self.inner.as_mut().is_some_and(|b| b.step(blobs as usize))
    }

    /// Share of the blobs deposited, 0..1.
    pub fn progress(&self) -> f64 {
        self.inner.as_ref().map_or(1.0, VolumeBuild::progress)
    }

    /// The `.vdb` bytes. May be called once.
    pub fn finish(&mut self) -> Result<Vec<u8>, JsError> {
        let build = self
            .inner
            .take()
            .ok_or_else(|| JsError::new("the volume was finished already"))?;
        Ok(build.finish().to_vdb(self.time))
    }
}

/// The paper's Figure 1: a square of density in a 2-D wind, on a grid (Eq. 12) and as blobs.
#[wasm_bindgen(js_name = Figure1Demo)]
pub struct Figure1Demo {
    inner: Figure1,
}

#[wasm_bindgen(js_class = Figure1Demo)]
impl Figure1Demo {
    /// `params_json`: [`Figure1Params`] (any subset; the rest default).
    #[wasm_bindgen(constructor)]
    pub fn new(params_json: &str) -> Result<Figure1Demo, JsError> {
        let params: Figure1Params = parse(params_json, "Figure 1 setup")?;
        Ok(Self {
            inner: Figure1::new(params).map_err(js_error)?,
        })
    }

    /// Advances both models by `seconds`.
    pub fn step(&mut self, seconds: f64) {
        self.inner.step(seconds);
    }

    pub fn time(&self) -> f64 {
        self.inner.time
    }

    /// Cells per side.
    pub fn n(&self) -> u32 {
        self.inner.params.n as u32
    }

    /// The grid's density, row-major from y = 0.
    pub fn grid(&self) -> Vec<f32> {
        self.inner.rho.iter().map(|&v| v as f32).collect()
    }

    /// The blobs' density averaged over the same cells.
    pub fn blobs(&self) -> Vec<f32> {
        self.inner
            .blob_density()
            .iter()
            .map(|&v| v as f32)
            .collect()
    }

    #[wasm_bindgen(js_name = gridMass)]
    pub fn grid_mass(&self) -> f64 {
        self.inner.grid_mass()
    }

    #[wasm_bindgen(js_name = blobMass)]
    pub fn blob_mass(&self) -> f64 {
        self.inner.blob_mass()
    }
}
