//! The field's synthesis in stages (`field::Synthesis`), so that a worker can report progress.

use super::wind_field::WindField;
use super::{js_error, parse};
use crate::field::{FieldParams, Synthesis};
use std::sync::Arc;
use wasm_bindgen::prelude::*;

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
