//! A running scene (`gas::simulation::Simulation`) and the scene's reading: `validateScene`,
//! `sceneFieldParams`.

use super::wind_field::WindField;
use super::{counts3, js_error, object, xyz};
use crate::field::TurbulentField;
use crate::frame::gpu_steps::{gas_by_slot, GpuSteps};
use crate::frame::light_volume::light_twin;
use crate::frame::volume::{density_twin, VoxelGrid};
use crate::frame::{merged_list, MarchFrame, PackedFrame, ViewFrame};
use crate::gas::simulation::{Edit, Simulation};
use crate::scene::Scene;
use crate::wind::wind_slice::SlicePlane;
use std::sync::Arc;
use wasm_bindgen::prelude::*;

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
    /// The last flow step's time (ms; 0 without a flow).
    flow_ms: f64,
}

#[wasm_bindgen]
extern "C" {
    /// The page's or the worker's clock (`performance.now()`, ms).
    #[wasm_bindgen(js_namespace = performance, js_name = now)]
    fn performance_now() -> f64;
}

#[wasm_bindgen]
impl SceneSimulation {
    /// Builds a simulation, synthesising the scene's field (skipped when its amplitude is 0).
    #[wasm_bindgen(constructor)]
    pub fn new(scene_json: &str) -> Result<SceneSimulation, JsError> {
        let scene = Scene::from_json(scene_json).map_err(js_error)?;
        let inner = Simulation::new(scene).map_err(js_error)?;
        Ok(Self {
            inner,
            flow_ms: 0.0,
        })
    }

    /// Builds a simulation on an existing field, which must have the scene's field parameters.
    #[wasm_bindgen(js_name = withField)]
    pub fn with_field(scene_json: &str, field: &WindField) -> Result<SceneSimulation, JsError> {
        let scene = Scene::from_json(scene_json).map_err(js_error)?;
        let inner = Simulation::with_field(scene, Some(field.inner.clone())).map_err(js_error)?;
        Ok(Self {
            inner,
            flow_ms: 0.0,
        })
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

    /// Runs `n` fixed steps, timing the flow's part of each (`flowMs`; an edit that leaves no
    /// flow sets it to 0).
    pub fn step(&mut self, n: u32) {
        if self.inner.flow().is_none() {
            self.inner.run(n as u64);
            return;
        }
        for _ in 0..n {
            let start = performance_now();
            self.inner.step_flow();
            self.flow_ms = performance_now() - start;
            self.inner.step_gas();
        }
    }

    /// How long the last flow step took (ms), 0 without a flow.
    #[wasm_bindgen(js_name = flowMs)]
    pub fn flow_ms(&self) -> f64 {
        self.flow_ms
    }

    /// Whether the scene has an enabled flow (stepped here, in the worker).
    #[wasm_bindgen(js_name = hasFlow)]
    pub fn has_flow(&self) -> bool {
        self.inner.flow().is_some()
    }

    /// The flow's grid now, or undefined without a flow: `{box, cells, time, velocity,
    /// temperature}`, velocity u_g at the cells' centres (m/s, (nz, ny, nx, 3), x fastest) and
    /// temperature T (K, (nz, ny, nx)), as `windfield flow` writes them.
    #[wasm_bindgen(js_name = exportFlow, unchecked_return_type = "FlowGrid | undefined")]
    pub fn export_flow(&self) -> JsValue {
        let Some(g) = self.inner.flow_grid() else {
            return JsValue::UNDEFINED;
        };
        object(vec![
            ("box", g.bounds.to_vec().into()),
            (
                "cells",
                g.cells
                    .iter()
                    .map(|&n| n as u32)
                    .collect::<Vec<u32>>()
                    .into(),
            ),
            ("time", g.time.into()),
            ("velocity", g.velocity.into()),
            ("temperature", g.temperature.into()),
        ])
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
    /// core steps them again from now on, with the GPU's carried `offsets` (per slot phase a
    /// xyz, phase b xyz, m) where given.
    #[wasm_bindgen(js_name = takeCentres)]
    pub fn take_centres(&mut self, centres: &[f32], keep_on_gpu: bool, offsets: Option<Vec<f32>>) {
        self.inner
            .take_centres(centres, keep_on_gpu, offsets.as_deref());
    }

    /// Takes the flow the GPU stepped, u_g on each component's faces (m/s; `u` across x, `v`
    /// across y, `w` across z, each x fastest: `Simulation::take_flow`). Throws for a scene
    /// without a flow and for arrays of the wrong size.
    #[wasm_bindgen(js_name = takeFlow)]
    pub fn take_flow(&mut self, u: &[f32], v: &[f32], w: &[f32]) -> Result<(), JsError> {
        self.inner.take_flow([u, v, w]).map_err(js_error)
    }

    /// The flow's u_g on each component's faces (m/s, `{u, v, w}`, each x fastest: what the
    /// GPU starts its flow from), or undefined without a flow.
    #[wasm_bindgen(js_name = flowFaces, unchecked_return_type = "FlowFaces | undefined")]
    pub fn flow_faces(&self) -> JsValue {
        let Some(flow) = self.inner.flow() else {
            return JsValue::UNDEFINED;
        };
        let [u, v, w] = flow.faces().clone();
        object(vec![("u", u.into()), ("v", v.into()), ("w", w.into())])
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
        if self.inner.flow().is_none() {
            self.flow_ms = 0.0;
        }
        Ok(outcome == Edit::Restarted)
    }
}
