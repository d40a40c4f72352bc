//! A flipbook for export: a sheet of frames and its description (`export::flipbook`).

use super::wind_field::WindField;
use super::{js_error, object, parse};
use crate::export::flipbook::{FlipbookJob, FlipbookSpec, SettingNames};
use crate::export::still::StillFormat;
use crate::field::TurbulentField;
use crate::scene::blob_list::Camera;
use crate::scene::Scene;
use std::sync::Arc;
use wasm_bindgen::prelude::*;

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
