//! A synthesised small-scale field (`field::TurbulentField`): its lattice, samples and slices;
//! in the full build also the field as the world's wind (`windGrid`), its statistics, and a
//! field made from a lattice another instance synthesised (`fromLattice`).

use super::{js_error, parse};
use crate::field::{FieldParams, TurbulentField};
use std::sync::Arc;
use wasm_bindgen::prelude::*;
#[cfg(feature = "full")]
use {
    crate::export::vector_grid::{GridFormat, SliceMapping, VectorGrid},
    crate::field::spectrum::SpectrumParams,
    crate::field::statistics,
};

/// A synthesised small-scale field.
#[wasm_bindgen]
pub struct WindField {
    pub(super) inner: Arc<TurbulentField>,
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

    /// The plane z = `z` at time `t` (lattice units) on a `width × height` grid over one
    /// period in x and y (`TurbulentField::slice_xy`).
    pub fn slice_xy(&self, z: f64, t: f64, width: u32, height: u32) -> Result<Vec<f32>, JsError> {
        self.inner.slice_xy(z, t, width, height).map_err(js_error)
    }
}

#[cfg(feature = "full")]
#[wasm_bindgen]
impl WindField {
    /// A field of the lattice `data` (and its vector potential ψ, `potential`, empty for
    /// none) another instance synthesised for `params_json` (as `FieldSynthesis` takes it):
    /// the field's own values, so that exports made on it give the bytes the field would give.
    #[wasm_bindgen(js_name = fromLattice)]
    pub fn from_lattice(
        params_json: &str,
        data: Vec<f32>,
        potential: Vec<f32>,
    ) -> Result<WindField, JsError> {
        let mut value: serde_json::Value = parse(params_json, "field")?;
        if let Some(o) = value.as_object_mut() {
            o.remove("potential");
        }
        let params: FieldParams =
            serde_json::from_value(value).map_err(|e| JsError::new(&format!("field: {e}")))?;
        let potential = (!potential.is_empty()).then_some(potential);
        let field = TurbulentField::from_lattice(params, data, potential).map_err(js_error)?;
        Ok(Self {
            inner: Arc::new(field),
        })
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
        let format = GridFormat::parse(format, "format").map_err(js_error)?;
        let grid = self.wind_slice(&period, time_period, amplitude, t)?;
        Ok(grid.to_file(format))
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

#[cfg(feature = "full")]
impl WindField {
    /// The slice behind `windGrid` and `windGridDescription`, its mapping checked by the core
    /// (`SliceMapping`).
    fn wind_slice(
        &self,
        period: &[f64],
        time_period: f64,
        amplitude: f64,
        t: f64,
    ) -> Result<VectorGrid, JsError> {
        let m = SliceMapping::new(period, time_period, amplitude, t).map_err(js_error)?;
        Ok(VectorGrid::field_slice(
            &self.inner,
            m.period,
            m.time_period,
            m.amplitude,
            m.t,
        ))
    }
}
