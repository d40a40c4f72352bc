//! A still for export: PNG or OpenEXR bytes of a blob list (`export::still`).

use super::{js_error, known_time, parse};
use crate::export::exr::ExrInfo;
use crate::export::still::{self, StillFormat};
use crate::render::{BandedRender, RenderOptions, Renderer};
use crate::scene::blob_list::{BlobList, Encoding};
use wasm_bindgen::prelude::*;

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
