//! The small-scale turbulence u_s: a periodic, divergence-free random vector field over 4-D
//! space-time (paper §3), its parameters, and its quadrilinear sampling.
//!
//! The spectrum û is white noise filtered by Eq. 7 ([`crate::field::velocity_spectrum`]); the
//! staged [`crate::field::synthesis::Synthesis`] inverts it into the real field, and
//! `TurbulentField::generate` (beside it, in `synthesis`) runs it in one call. This module only
//! holds the result, so it needs nothing of the synthesis.

use crate::check;
use crate::error::ParamError;
use crate::field::lattice::{Lattice, DEFAULT_EXTENT};
use crate::field::spectrum::SpectrumParams;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// Most samples along either side of a [`TurbulentField::slice_xy`] (a plane of 4096² samples
/// is 192 MiB of f32).
pub const MAX_SLICE_SIDE: u32 = 4096;

/// Largest seed accepted: integers up to 2^53 survive a round trip through JSON and JavaScript.
pub const MAX_SEED: u64 = 1 << 53;
/// The seed where none is named.
pub const DEFAULT_SEED: u64 = 1;

/// Everything that determines a field: lattice extents, spectrum, seed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FieldParams {
    /// `[nx, ny, nz, nt]`, each an even number in 4..=256, at most 2^24 points in all.
    #[serde(deserialize_with = "crate::whole::list")]
    pub size: [usize; 4],
    pub spectrum: SpectrumParams,
    #[serde(deserialize_with = "crate::whole::number")]
    pub seed: u64,
}

impl Default for FieldParams {
    fn default() -> Self {
        Self {
            size: [DEFAULT_EXTENT; 4],
            spectrum: SpectrumParams::default(),
            seed: DEFAULT_SEED,
        }
    }
}

impl FieldParams {
    /// Validates every parameter; errors use the scene paths `field.size[i]`,
    /// `field.spectrum.*` and `seed`.
    pub fn validate(&self) -> Result<Lattice, ParamError> {
        let lattice = Lattice::new(self.size, "field.size")?;
        self.spectrum.validate("field.spectrum")?;
        check::integer("seed", self.seed, 0, MAX_SEED)?;
        Ok(lattice)
    }
}

/// Whether every value is finite (no early exit, so the loop vectorises).
fn all_finite(values: &[f32]) -> bool {
    values.iter().fold(true, |ok, v| ok & v.is_finite())
}

/// A synthesised field: velocity u (lattice units) at every lattice point, interleaved
/// `[t][z][y][x][component]` (NumPy shape `(nt, nz, ny, nx, 3)`, C order).
#[derive(Debug, Clone)]
pub struct TurbulentField {
    pub lattice: Lattice,
    pub params: FieldParams,
    pub data: Vec<f32>,
    /// The field's vector potential ψ (u = ∇ × ψ in field coordinates, ψ normal to every k),
    /// stored as `data`, when it was synthesised with it (a scene with solid objects turns the
    /// field along their surfaces through ψ).
    pub potential: Option<Vec<f32>>,
}

impl TurbulentField {
    /// Wraps existing lattice data (length `3 * points`), e.g. read from a `.npy` file; a
    /// non-finite value is refused with its place ([`Self::check_finite`]).
    pub fn from_data(params: FieldParams, data: Vec<f32>) -> Result<Self, ParamError> {
        let field = Self::from_data_unchecked(params, data)?;
        field.check_finite()?;
        Ok(field)
    }

    /// [`Self::from_data`] with the field's vector potential ψ (stored as `data`; none for a
    /// field without it), e.g. a field another WASM instance synthesised; ψ of another length
    /// is refused (path `potential`).
    pub fn from_lattice(
        params: FieldParams,
        data: Vec<f32>,
        potential: Option<Vec<f32>>,
    ) -> Result<Self, ParamError> {
        let mut field = Self::from_data(params, data)?;
        if let Some(psi) = &potential {
            if psi.len() != field.data.len() {
                return Err(ParamError::new(
                    "potential",
                    format!(
                        "expected {} values for the lattice, got {}",
                        field.data.len(),
                        psi.len()
                    ),
                ));
            }
        }
        field.potential = potential;
        Ok(field)
    }

    /// Ok if every velocity component is finite; else an error (path `field`) naming the
    /// first other value by its flat index and its place (t, z, y, x, component) in the
    /// `(nt, nz, ny, nx, 3)` array.
    pub fn check_finite(&self) -> Result<(), ParamError> {
        // Whole chunks first: the common, finite case stays a vectorised scan.
        let chunk = 4096;
        let Some(first) = self.data.chunks(chunk).position(|c| !all_finite(c)) else {
            return Ok(());
        };
        let i = first * chunk
            + self.data[first * chunk..]
                .iter()
                .position(|v| !v.is_finite())
                .expect("the chunk holds a non-finite value");
        let [nx, ny, nz, _] = self.lattice.size;
        let (c, p) = (i % 3, i / 3);
        let (x, y, z, t) = (p % nx, p / nx % ny, p / (nx * ny) % nz, p / (nx * ny * nz));
        Err(ParamError::new(
            "field",
            format!(
                "the velocity must be finite everywhere, but value {i} (t, z, y, x, \
                 component) = ({t}, {z}, {y}, {x}, {c}) is {}",
                self.data[i]
            ),
        ))
    }

    fn from_data_unchecked(params: FieldParams, data: Vec<f32>) -> Result<Self, ParamError> {
        let lattice = Lattice::new(params.size, "field.size")?;
        if data.len() != 3 * lattice.points() {
            return Err(ParamError::new(
                "field",
                format!(
                    "expected {} values for the lattice, got {}",
                    3 * lattice.points(),
                    data.len()
                ),
            ));
        }
        Ok(Self {
            lattice,
            params,
            data,
            potential: None,
        })
    }

    /// Velocity at lattice point `(x, y, z, t)`.
    #[inline]
    pub fn at(&self, x: usize, y: usize, z: usize, t: usize) -> [f32; 3] {
        let i = 3 * self.lattice.index(x, y, z, t);
        [self.data[i], self.data[i + 1], self.data[i + 2]]
    }

    /// Quadrilinear interpolation at `p = (x, y, z, t)` in lattice units (lattice point i at
    /// coordinate i), periodic along all four axes; exact at lattice points.
    pub fn sample_lattice(&self, p: [f64; 4]) -> [f32; 3] {
        let mut i0 = [0usize; 4];
        let mut i1 = [0usize; 4];
        let mut f = [0f32; 4];
        for a in 0..4 {
            let n = self.lattice.size[a];
            let fl = p[a].floor();
            f[a] = (p[a] - fl) as f32;
            let i = (fl as i64).rem_euclid(n as i64) as usize;
            i0[a] = i;
            i1[a] = (i + 1) % n;
        }
        let mut out = [0f32; 3];
        for corner in 0..16 {
            let mut w = 1.0f32;
            let mut idx = [0usize; 4];
            for a in 0..4 {
                if corner >> a & 1 == 1 {
                    w *= f[a];
                    idx[a] = i1[a];
                } else {
                    w *= 1.0 - f[a];
                    idx[a] = i0[a];
                }
            }
            if w == 0.0 {
                continue;
            }
            let v = self.at(idx[0], idx[1], idx[2], idx[3]);
            for c in 0..3 {
                out[c] += w * v[c];
            }
        }
        out
    }

    /// Quadrilinear sample at field coordinates (radians: one period is 2π along each axis).
    pub fn sample(&self, x: f64, y: f64, z: f64, t: f64) -> [f32; 3] {
        let s = self.lattice.size;
        self.sample_lattice([
            x * s[0] as f64 / TAU,
            y * s[1] as f64 / TAU,
            z * s[2] as f64 / TAU,
            t * s[3] as f64 / TAU,
        ])
    }

    /// Samples the plane z = `z` (lattice units) at time `t` (lattice units) on a `width ×
    /// height` grid spanning one period in x and y: `3·width·height` velocity components
    /// (lattice units), row-major from y = 0, x fastest. A side of 0 counts as 1; a side over
    /// [`MAX_SLICE_SIDE`] is refused, naming `width` or `height`.
    pub fn slice_xy(
        &self,
        z: f64,
        t: f64,
        width: u32,
        height: u32,
    ) -> Result<Vec<f32>, ParamError> {
        check::integer("width", width.into(), 0, MAX_SLICE_SIDE.into())?;
        check::integer("height", height.into(), 0, MAX_SLICE_SIDE.into())?;
        let [nx, ny, _, _] = self.lattice.size;
        let (w, h) = (width.max(1) as usize, height.max(1) as usize);
        let mut out = Vec::with_capacity(w * h * 3);
        for j in 0..h {
            let y = j as f64 * ny as f64 / h as f64;
            for i in 0..w {
                let x = i as f64 * nx as f64 / w as f64;
                out.extend_from_slice(&self.sample_lattice([x, y, z, t]));
            }
        }
        Ok(out)
    }
}
