//! The classroom's demonstrations: the paper's Figure 1 (`classroom::figure1`) and the wind past a
//! solid sphere (`classroom::sphere_flow`).

use super::{js_error, object, parse};
use crate::classroom::figure1::{Figure1, Figure1Params};
use wasm_bindgen::prelude::*;

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
    pub fn step(&mut self, seconds: f64) -> Result<(), JsError> {
        self.inner.step(seconds).map_err(js_error)
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
