//! The only door between JavaScript and the core: every `#[wasm_bindgen]` export lives here.
//!
//! Calls are few and fat: parameters cross as one JSON string, lattice data and slices cross
//! as whole `Float32Array`s. Bad input becomes a thrown `Error` whose message names the
//! parameter path; nothing panics across the boundary.

use crate::field::{FieldParams, Synthesis, TurbulentField};
use crate::spectrum::SpectrumParams;
use crate::stats;
use wasm_bindgen::prelude::*;

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
        Ok(WindField { inner: s.finish() })
    }
}

/// A synthesised small-scale field.
#[wasm_bindgen]
pub struct WindField {
    inner: TurbulentField,
}

#[wasm_bindgen]
impl WindField {
    /// Generates a field in one call (see [`FieldSynthesis`] for the staged form).
    pub fn generate(params_json: &str) -> Result<WindField, JsError> {
        let params: FieldParams = parse(params_json, "field")?;
        let inner = TurbulentField::generate(&params).map_err(|e| JsError::new(&e.to_string()))?;
        Ok(Self { inner })
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
