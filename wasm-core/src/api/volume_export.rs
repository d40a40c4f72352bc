//! A volume for export: the blobs deposited on a voxel grid, as OpenVDB bytes
//! (`export::volume`).

use super::{js_error, known_time, parse};
use crate::export::volume::VolumeBuild;
use crate::scene::blob_list::BlobList;
use wasm_bindgen::prelude::*;

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
