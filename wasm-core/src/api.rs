//! The only door between JavaScript and the core: every `#[wasm_bindgen]` export lives here.
//!
//! Calls are few and fat: parameters cross as one JSON string, lattice data and slices cross
//! as whole `Float32Array`s. Bad input becomes a thrown `Error` whose message names the
//! parameter path; nothing panics across the boundary.

use crate::blob_list::{BlobList, Encoding};
use crate::field::{FieldParams, Synthesis, TurbulentField};
use crate::gas::Blob;
use crate::render::volume::{light_columns, splat, Towards, VoxelGrid};
use crate::render::{encode_png, merge_blobs, LinearImage, PackedFrame, RenderOptions, Renderer};
use crate::scene::Scene;
use crate::simulation::Simulation;
use crate::spectrum::SpectrumParams;
use crate::stats;
use glam::Vec3;
use std::sync::Arc;
use wasm_bindgen::prelude::*;

fn js_error(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

fn parse<T: serde::de::DeserializeOwned>(json: &str, what: &str) -> Result<T, JsError> {
    serde_json::from_str(json).map_err(|e| JsError::new(&format!("{what}: {e}")))
}

/// A field synthesis in progress; `step()` runs one stage so a worker can report progress.
#[wasm_bindgen]
pub struct FieldSynthesis {
    inner: Option<Synthesis>,
}

#[wasm_bindgen]
impl FieldSynthesis {
    /// `params_json`: `{"size": [nx,ny,nz,nt], "spectrum": {...}, "seed": n}`.
    #[wasm_bindgen(constructor)]
    pub fn new(params_json: &str) -> Result<FieldSynthesis, JsError> {
        let params: FieldParams = parse(params_json, "field")?;
        let inner = Synthesis::new(&params).map_err(|e| JsError::new(&e.to_string()))?;
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
            .map_or_else(|| "done".into(), |s| s.stage().label())
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

    /// Quadrilinear sample at lattice coordinates `(x, y, z, t)`: `[u1, u2, u3]`.
    pub fn sample(&self, x: f64, y: f64, z: f64, t: f64) -> Vec<f32> {
        self.inner.sample_lattice([x, y, z, t]).to_vec()
    }

    /// Samples the plane `z = z` (lattice units) at time `t` on a `width × height` grid that
    /// spans one period in x and y: `width*height*3` velocities, row-major from y = 0.
    pub fn slice_xy(&self, z: f64, t: f64, width: u32, height: u32) -> Vec<f32> {
        let [nx, ny, _, _] = self.inner.lattice.size;
        let (w, h) = (width.max(1) as usize, height.max(1) as usize);
        let mut out = Vec::with_capacity(w * h * 3);
        for j in 0..h {
            let y = j as f64 * ny as f64 / h as f64;
            for i in 0..w {
                let x = i as f64 * nx as f64 / w as f64;
                out.extend_from_slice(&self.inner.sample_lattice([x, y, z, t]));
            }
        }
        out
    }

    /// Statistics (JSON) of the field against `spectrum_json` (or its own spectrum if empty).
    pub fn stats(&self, spectrum_json: &str) -> Result<String, JsError> {
        let spectrum: SpectrumParams = if spectrum_json.is_empty() {
            self.inner.params.spectrum
        } else {
            parse(spectrum_json, "spectrum")?
        };
        let report = stats::analyse(&self.inner, &spectrum);
        serde_json::to_string(&report).map_err(|e| JsError::new(&e.to_string()))
    }
}

/// Checks a scene; returns it normalised (every default filled in) as JSON, or throws an
/// Error naming the offending path.
#[wasm_bindgen(js_name = validateScene)]
pub fn validate_scene(scene_json: &str) -> Result<String, JsError> {
    Ok(Scene::from_json(scene_json).map_err(js_error)?.to_json())
}

/// The field parameters (`{size, spectrum, seed}` JSON) a scene needs.
#[wasm_bindgen(js_name = sceneFieldParams)]
pub fn scene_field_params(scene_json: &str) -> Result<String, JsError> {
    let scene = Scene::from_json(scene_json).map_err(js_error)?;
    serde_json::to_string(&scene.field_params()).map_err(js_error)
}

/// A running scene: wind and gas advanced in fixed steps. Blob data comes out as whole typed
/// arrays: per frame one packed buffer (`packFrame`, see `render::frame`) and its description
/// (`frameInfo`).
#[wasm_bindgen]
pub struct SceneSimulation {
    inner: Simulation,
    /// `frameInfo()` of the last `packFrame()` or `marchFrame()`.
    info: Vec<f32>,
    /// The shadow grid of the last `marchFrame()`.
    grid: Vec<f32>,
}

#[wasm_bindgen]
impl SceneSimulation {
    /// Builds a simulation, synthesising the scene's field (skipped when its amplitude is 0).
    #[wasm_bindgen(constructor)]
    pub fn new(scene_json: &str) -> Result<SceneSimulation, JsError> {
        let scene = Scene::from_json(scene_json).map_err(js_error)?;
        let inner = Simulation::new(scene).map_err(js_error)?;
        Ok(Self::wrap(inner))
    }

    /// Builds a simulation on an existing field, which must have the scene's field parameters.
    #[wasm_bindgen(js_name = withField)]
    pub fn with_field(scene_json: &str, field: &WindField) -> Result<SceneSimulation, JsError> {
        let scene = Scene::from_json(scene_json).map_err(js_error)?;
        let field = (scene.field.amplitude > 0.0).then(|| field.inner.clone());
        let inner = Simulation::with_field(scene, field).map_err(js_error)?;
        Ok(Self::wrap(inner))
    }

    /// Runs `n` fixed steps.
    pub fn step(&mut self, n: u32) {
        self.inner.run(n as u64);
    }

    /// Refuses a run of `steps` fixed steps over the budget (DESIGN §7: 1,000,000), with an
    /// error naming `simulation.dt` and the time; `steps` must be a whole number, 0 or more.
    #[wasm_bindgen(js_name = checkSteps)]
    pub fn check_steps(&self, steps: f64) -> Result<(), JsError> {
        if !(steps.is_finite() && steps >= 0.0 && steps.fract() == 0.0) {
            return Err(JsError::new(&format!(
                "steps: must be a whole number, 0 or more (got {steps})"
            )));
        }
        let dt = self.inner.scene.simulation.dt;
        self.inner.budgeted_steps(steps * dt).map_err(js_error)?;
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

    /// Blob σ (m).
    pub fn sigma(&self) -> Vec<f32> {
        self.inner.blobs().sigma.clone()
    }

    /// Blob masses.
    pub fn mass(&self) -> Vec<f32> {
        self.inner.blobs().mass.clone()
    }

    /// Blob albedo, rgb interleaved; a negative red channel means the medium's albedo.
    pub fn albedo(&self) -> Vec<f32> {
        self.inner.blobs().albedo.clone()
    }

    /// Blob self-emission, rgb interleaved.
    pub fn emission(&self) -> Vec<f32> {
        self.inner.blobs().emission.clone()
    }

    /// Blob ages (s) at the current time.
    pub fn age(&self) -> Vec<f32> {
        let t = self.inner.time();
        self.inner
            .blobs()
            .birth
            .iter()
            .map(|b| (t - b) as f32)
            .collect()
    }

    /// The opaque objects at the current time (the scene's, and visible repulsor spheres), as
    /// DESIGN §4's `objects` JSON.
    pub fn objects(&self) -> String {
        serde_json::to_string(&self.inner.render_settings().objects).unwrap_or_default()
    }

    /// Adds blobs born now at `positions` (xyz interleaved) with σ0 and m0, medium albedo.
    #[wasm_bindgen(js_name = addBlobs)]
    pub fn add_blobs(&mut self, positions: &[f32], sigma0: f32, mass0: f32) -> Result<(), JsError> {
        if positions.len() % 3 != 0 || !(sigma0 > 0.0 && mass0 > 0.0) {
            return Err(JsError::new(
                "addBlobs: positions must be xyz triples, sigma0 and mass0 positive",
            ));
        }
        let birth = self.inner.time();
        for p in positions.chunks_exact(3) {
            let blob = Blob::new(Vec3::from_slice(p), sigma0, mass0, birth);
            self.inner.gas.blobs.push(&blob, sigma0, mass0);
        }
        Ok(())
    }

    /// Emitted, split, dissipated and capped counts since the start (JSON).
    pub fn counts(&self) -> String {
        serde_json::to_string(&self.inner.gas.counts).unwrap_or_default()
    }

    /// The blob list of DESIGN §4 for the current state (JSON).
    #[wasm_bindgen(js_name = blobList)]
    pub fn blob_list(&self) -> String {
        serde_json::to_string(&self.inner.blob_list()).unwrap_or_default()
    }

    /// The whole wind u = u_l + u_s (Eq. 3) now, on an `nu × nv` grid over the parallelogram
    /// `origin + a·u + b·v` (a, b in [0, 1], sampled at cell centres; metres): `3·nu·nv` m/s,
    /// u-index fastest.
    #[wasm_bindgen(js_name = windSlice)]
    pub fn wind_slice(
        &self,
        origin: &[f32],
        u: &[f32],
        v: &[f32],
        nu: u32,
        nv: u32,
    ) -> Result<Vec<f32>, JsError> {
        let vector = |a: &[f32], name: &str| match a {
            [x, y, z] if a.iter().all(|c| c.is_finite()) => Ok(Vec3::new(*x, *y, *z)),
            _ => Err(JsError::new(&format!(
                "windSlice: {name} must be 3 finite numbers"
            ))),
        };
        let (origin, u, v) = (vector(origin, "origin")?, vector(u, "u")?, vector(v, "v")?);
        if !(1..=256).contains(&nu) || !(1..=256).contains(&nv) {
            return Err(JsError::new(
                "windSlice: nu and nv must be between 1 and 256",
            ));
        }
        let frame = self.inner.wind.frame(self.inner.time());
        let mut out = Vec::with_capacity(3 * (nu * nv) as usize);
        for j in 0..nv {
            for i in 0..nu {
                let a = (i as f32 + 0.5) / nu as f32;
                let b = (j as f32 + 0.5) / nv as f32;
                out.extend_from_slice(&frame.velocity(origin + a * u + b * v).to_array());
            }
        }
        Ok(out)
    }

    /// The current blobs packed for the browser's views: `render::frame`'s eight words per blob,
    /// sorted into σ classes (`frameInfo()` describes them). One whole buffer per frame.
    #[wasm_bindgen(js_name = packFrame)]
    pub fn pack_frame(&mut self) -> Vec<u32> {
        let frame = self.packed();
        self.info = frame.info();
        frame.words
    }

    /// The last packed frame's description: `[count, lo.xyz, hi.xyz, emissive, σ_min, classes,
    /// then offset, count, σ_max per class]` (`PackedFrame::info`).
    #[wasm_bindgen(js_name = frameInfo)]
    pub fn frame_info(&self) -> Vec<f32> {
        self.info.clone()
    }

    /// The visible repulsor spheres now, `[x, y, z, radius, r, g, b]` each (m, linear colour), in
    /// the order they follow the scene's objects in `blobList()`.
    #[wasm_bindgen(js_name = movingSpheres)]
    pub fn moving_spheres(&self) -> Vec<f32> {
        self.inner
            .wind
            .visible_spheres(self.inner.time())
            .iter()
            .flat_map(|(c, r, rgb)| [c.x, c.y, c.z, *r, rgb[0], rgb[1], rgb[2]])
            .collect()
    }

    /// The exact march's input: the blobs merged as `marchList(fraction)` merges them, packed as
    /// `packFrame` packs (`frameInfo()` describes them), and the shadow grid at `res`³ (read with
    /// `marchGrid()`; 8 zeros without shadows or lights).
    #[wasm_bindgen(js_name = marchFrame)]
    pub fn march_frame(&mut self, fraction: f32, res: u32) -> Result<Vec<u32>, JsError> {
        let mut list = self.inner.blob_list();
        if fraction > 0.0 {
            list.blobs = merge_blobs(&list.blobs, list.medium.albedo, fraction);
        }
        self.grid = shadow_grid_of(&list, res)?;
        let frame = PackedFrame::of_list(&list);
        self.info = frame.info();
        Ok(frame.words)
    }

    /// The shadow grid of the last `marchFrame()` (`shadowGrid`'s layout).
    #[wasm_bindgen(js_name = marchGrid)]
    pub fn march_grid(&self) -> Vec<f32> {
        self.grid.clone()
    }

    /// The real-time view's density volume for the current blobs, as `render::volume` computes
    /// it on the grid of `dims` voxels of side `h` from `lo`: `[ρ, ρΩ_rgb]` per voxel, then
    /// `[ρ(1−Ω)Q_rgb, 0]` per voxel (x fastest). The twin the browser's GPU volume is tested against.
    #[wasm_bindgen(js_name = volumeTwin)]
    pub fn volume_twin(&self, lo: &[f32], h: f32, dims: &[u32]) -> Result<Vec<f32>, JsError> {
        let grid = Self::grid(lo, h, dims)?;
        let v = splat(&self.packed(), &grid);
        Ok([v.density, v.source].concat())
    }

    /// The light volume on the same grid: for each voxel of the half-resolution grid, the column
    /// ∫ρ ds towards each of the scene's first four lights (`render::volume::light_columns`,
    /// steps of `step × h`), four floats per voxel.
    #[wasm_bindgen(js_name = lightTwin)]
    pub fn light_twin(
        &self,
        lo: &[f32],
        h: f32,
        dims: &[u32],
        step: f32,
    ) -> Result<Vec<f32>, JsError> {
        let grid = Self::grid(lo, h, dims)?;
        if !(step.is_finite() && step > 0.0) {
            return Err(JsError::new("lightTwin: step must be positive"));
        }
        let lights: Vec<Towards> = self
            .inner
            .scene
            .render
            .lights
            .iter()
            .map(Towards::of)
            .collect();
        Ok(light_columns(&splat(&self.packed(), &grid), &lights, step).1)
    }

    /// The blob list for the GPU ray march (JSON): blobs closer than `fraction × σ` merged by
    /// moments (`render::lod`); `fraction` ≤ 0 gives the exact list.
    #[wasm_bindgen(js_name = marchList)]
    pub fn march_list(&self, fraction: f32) -> String {
        let mut list = self.inner.blob_list();
        if fraction > 0.0 {
            list.blobs = merge_blobs(&list.blobs, list.medium.albedo, fraction);
        }
        serde_json::to_string(&list).unwrap_or_default()
    }
}

impl SceneSimulation {
    fn wrap(inner: Simulation) -> Self {
        Self {
            inner,
            info: PackedFrame::default().info(),
            grid: Vec::new(),
        }
    }

    /// The current blobs packed for the GPU (albedo resolved against the medium's).
    fn packed(&self) -> PackedFrame {
        let medium = Vec3::from_array(self.inner.scene.render.medium.albedo);
        PackedFrame::of_blobs(&self.inner.blobs(), medium)
    }

    /// The voxel grid `lo` (3 numbers, m), `h` (m), `dims` (3 counts), checked.
    fn grid(lo: &[f32], h: f32, dims: &[u32]) -> Result<VoxelGrid, JsError> {
        match (lo, dims) {
            ([x, y, z], [nx, ny, nz])
                if lo.iter().all(|v| v.is_finite())
                    && h.is_finite()
                    && h > 0.0
                    && dims.iter().all(|&n| (1..=512).contains(&n)) =>
            {
                Ok(VoxelGrid {
                    lo: Vec3::new(*x, *y, *z),
                    h,
                    dims: [*nx as usize, *ny as usize, *nz as usize],
                })
            }
            _ => Err(JsError::new(
                "voxel grid: lo must be 3 finite numbers, h positive, dims 3 counts from 1 to 512",
            )),
        }
    }
}

/// A reference still in progress: the CPU renderer of DESIGN §4, a band of rows at a time so a
/// worker can report progress.
#[wasm_bindgen]
pub struct ReferenceRender {
    renderer: Renderer,
    encoding: Encoding,
    data: Vec<f32>,
    next_row: u32,
}

#[wasm_bindgen]
impl ReferenceRender {
    /// `blob_list_json`: a blob list (DESIGN §4); `width`/`height` of 0 keep the list's size.
    #[wasm_bindgen(constructor)]
    pub fn new(blob_list_json: &str, width: u32, height: u32) -> Result<ReferenceRender, JsError> {
        let value: serde_json::Value = serde_json::from_str(blob_list_json)
            .map_err(|e| JsError::new(&format!("blob list: {e}")))?;
        let list = BlobList::from_value(value).map_err(js_error)?;
        let size = (width > 0 && height > 0).then_some((width, height));
        let renderer = Renderer::new(&list, size, RenderOptions::default()).map_err(js_error)?;
        let data = vec![0.0; 3 * (renderer.width * renderer.height) as usize];
        Ok(Self {
            renderer,
            encoding: list.image.encoding,
            data,
            next_row: 0,
        })
    }

    /// Renders up to `rows` more rows; false once the image is complete.
    pub fn step(&mut self, rows: u32) -> bool {
        let row_len = 3 * self.renderer.width as usize;
        let end = (self.next_row + rows).min(self.renderer.height);
        for j in self.next_row..end {
            let start = j as usize * row_len;
            self.renderer
                .render_row(j, &mut self.data[start..start + row_len]);
        }
        self.next_row = end;
        self.next_row < self.renderer.height
    }

    /// Fraction of rows done, 0..1.
    pub fn progress(&self) -> f64 {
        self.next_row as f64 / self.renderer.height.max(1) as f64
    }

    pub fn width(&self) -> u32 {
        self.renderer.width
    }

    pub fn height(&self) -> u32 {
        self.renderer.height
    }

    /// The finished image as 8-bit RGB in the list's encoding (rows rendered so far).
    pub fn rgb(&self) -> Vec<u8> {
        self.image().to_rgb8(self.encoding)
    }

    /// The finished image as PNG bytes.
    pub fn png(&self) -> Result<Vec<u8>, JsError> {
        encode_png(self.renderer.width, self.renderer.height, &self.rgb()).map_err(js_error)
    }

    fn image(&self) -> LinearImage {
        LinearImage {
            width: self.renderer.width,
            height: self.renderer.height,
            data: self.data.clone(),
        }
    }
}

/// Shadow columns ∫ρ ds towards each light on a `res³` grid over the gas's bounds (padded by a
/// cell), for the exact march to interpolate: `[min.xyz, max.xyz, res, lights]` then
/// `lights × res³` columns (x fastest). Empty (8 zeros) without blobs, lights or shadows.
fn shadow_grid_of(list: &BlobList, res: u32) -> Result<Vec<f32>, JsError> {
    let renderer = Renderer::new(list, None, RenderOptions::default()).map_err(js_error)?;
    let res = res.clamp(2, 96) as usize;
    let lights = renderer.light_count();
    let bounds = renderer.gas_bounds().filter(|_| list.shadows && lights > 0);
    let Some((lo, hi)) = bounds else {
        return Ok(vec![0.0; 8]);
    };
    let pad = (hi - lo) / (res - 1) as f32;
    let (lo, hi) = (lo - pad, hi + pad);
    let cell = (hi - lo) / (res - 1) as f32;
    let mut out = vec![
        lo.x,
        lo.y,
        lo.z,
        hi.x,
        hi.y,
        hi.z,
        res as f32,
        lights as f32,
    ];
    out.reserve(lights * res * res * res);
    for k in 0..lights {
        for z in 0..res {
            for y in 0..res {
                for x in 0..res {
                    let p = lo + cell * Vec3::new(x as f32, y as f32, z as f32);
                    out.push(renderer.column_to_light(p, k));
                }
            }
        }
    }
    Ok(out)
}

/// The paper's Figure 1: a square of density in a 2-D wind, on a grid (Eq. 12) and as blobs.
#[wasm_bindgen(js_name = Figure1Demo)]
pub struct Figure1Demo {
    inner: crate::figure1::Figure1,
}

#[wasm_bindgen(js_class = Figure1Demo)]
impl Figure1Demo {
    /// `params_json`: [`crate::figure1::Figure1Params`] (any subset; the rest default).
    #[wasm_bindgen(constructor)]
    pub fn new(params_json: &str) -> Result<Figure1Demo, JsError> {
        let params: crate::figure1::Figure1Params = serde_json::from_str(params_json)
            .map_err(|e| JsError::new(&format!("Figure 1 setup: {e}")))?;
        Ok(Self {
            inner: crate::figure1::Figure1::new(params).map_err(js_error)?,
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
