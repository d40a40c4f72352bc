//! The CPU reference renderer of a blob list, for the page's reference still.

use super::{js_error, parse};
use crate::render::{BandedRender, RenderOptions, Renderer};
use crate::scene::blob_list::{BlobList, Encoding};
use wasm_bindgen::prelude::*;

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
