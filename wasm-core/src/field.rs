//! The small-scale turbulence u_s: a periodic, divergence-free random vector field over 4-D
//! space-time, synthesised by filtering white noise in the Fourier domain and inverting it
//! (paper §3.3 and Appendix A, with the projection form of DESIGN §2).
//!
//! Per lattice mode (k, ω) the three components are `û = a(k, ω) · (W − k̂ (k̂·W))`, with `W`
//! three complex Gaussians of unit variance (E|W_i|² = 1) and `a² = E(|k|) G_k(ω) / (4π|k|²)`.
//! The projection onto the plane normal to k gives exactly the covariance of paper Eq. 7,
//! `⟨û_i* û_j⟩ = a² (δ_ij − k_i k_j / k²)`, with no special cases (Eq. 21's kernel is singular on
//! the axes). Modes come in Hermitian pairs `û(−k, −ω) = û(k, ω)*`, so the field is real; the
//! spatial k = 0 modes and every Nyquist plane are zero. White noise is drawn for every
//! non-Nyquist mode pair whatever its amplitude, so a seed fixes the noise and the spectrum
//! parameters only filter it.
//!
//! Two real components travel in one complex transform (`û₁ + i û₂`); the third takes a second.

use crate::error::ParamError;
use crate::fft4::Fft4;
use crate::lattice::{negated, wave_number, Lattice};
use crate::spectrum::SpectrumParams;
use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use rustfft::num_complex::{Complex, Complex32, Complex64};
use rustfft::FftDirection;
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_1_SQRT_2, TAU};

/// Largest seed accepted: integers up to 2^53 survive a round trip through JSON and JavaScript.
pub const MAX_SEED: u64 = 1 << 53;

/// Everything that determines a field: lattice extents, spectrum, seed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FieldParams {
    /// `[nx, ny, nz, nt]`, each a power of two in 4..=128.
    pub size: [usize; 4],
    pub spectrum: SpectrumParams,
    pub seed: u64,
}

impl Default for FieldParams {
    fn default() -> Self {
        Self {
            size: [32; 4],
            spectrum: SpectrumParams::default(),
            seed: 1,
        }
    }
}

impl FieldParams {
    /// Validates every parameter; errors use the scene paths `field.size[i]`,
    /// `field.spectrum.*` and `seed`.
    pub fn validate(&self) -> Result<Lattice, ParamError> {
        let lattice = Lattice::new(self.size, "field.size")?;
        let max_k = (lattice.min_spatial_extent() / 2 - 1) as f64;
        self.spectrum.validate("field.spectrum", max_k)?;
        if self.seed > MAX_SEED {
            return Err(ParamError::new(
                "seed",
                format!(
                    "must be an integer between 0 and {MAX_SEED} (got {})",
                    self.seed
                ),
            ));
        }
        Ok(lattice)
    }
}

/// Amplitude table a(k², ω) = sqrt(E(k) G_k(ω) / (4πk²)), indexed `[k² * nt + t]`;
/// zero on the Nyquist plane t = nt/2, which is left out of G's normalisation.
fn amplitude_table(lattice: &Lattice, spectrum: &SpectrumParams) -> (Vec<f64>, usize) {
    let [nx, ny, nz, nt] = lattice.size;
    let k2_max = [nx, ny, nz]
        .iter()
        .map(|&n| (n / 2 - 1).pow(2))
        .sum::<usize>();
    let omegas: Vec<f64> = (0..nt)
        .filter(|&t| t != nt / 2)
        .map(|t| wave_number(t, nt) as f64)
        .collect();
    let mut table = vec![0.0; (k2_max + 1) * nt];
    for k2 in 1..=k2_max {
        let k = (k2 as f64).sqrt();
        if spectrum.energy_spectrum(k) == 0.0 {
            continue;
        }
        let g = spectrum.temporal_spread(k, &omegas);
        let mut gi = g.iter();
        for t in 0..nt {
            if t == nt / 2 {
                continue;
            }
            let gt = *gi.next().expect("one weight per non-Nyquist ω");
            table[k2 * nt + t] = spectrum.mode_variance(k, gt).sqrt();
        }
    }
    (table, k2_max)
}

/// Visits every non-zero mode pair once, in lattice order, drawing the white noise from the
/// seeded generator. `sink(idx, idx_neg, û)` receives the mode at linear index `idx` and the
/// index of its Hermitian partner (−k, −ω), which must receive `û*`.
pub fn for_each_mode(
    lattice: &Lattice,
    spectrum: &SpectrumParams,
    seed: u64,
    mut sink: impl FnMut(usize, usize, [Complex64; 3]),
) {
    let [nx, ny, nz, nt] = lattice.size;
    let (amp, _) = amplitude_table(lattice, spectrum);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut normal = move || -> f64 {
        let v: f64 = StandardNormal.sample(&mut rng);
        v * FRAC_1_SQRT_2
    };
    for t in (0..nt).filter(|&t| t != nt / 2) {
        for z in (0..nz).filter(|&z| z != nz / 2) {
            let kz = wave_number(z, nz);
            for y in (0..ny).filter(|&y| y != ny / 2) {
                let ky = wave_number(y, ny);
                let row = lattice.index(0, y, z, t);
                let row_neg = lattice.index(0, negated(y, ny), negated(z, nz), negated(t, nt));
                for x in (0..nx).filter(|&x| x != nx / 2) {
                    let idx = row + x;
                    let idx_neg = row_neg + negated(x, nx);
                    if idx_neg <= idx {
                        continue; // partner done already, or the self-conjugate origin
                    }
                    let w = [
                        Complex::new(normal(), normal()),
                        Complex::new(normal(), normal()),
                        Complex::new(normal(), normal()),
                    ];
                    let kx = wave_number(x, nx);
                    let k2 = (kx * kx + ky * ky + kz * kz) as usize;
                    let a = amp[k2 * nt + t];
                    if a == 0.0 {
                        continue;
                    }
                    let inv_k = 1.0 / (k2 as f64).sqrt();
                    let khat = [kx as f64 * inv_k, ky as f64 * inv_k, kz as f64 * inv_k];
                    let dot = w[0] * khat[0] + w[1] * khat[1] + w[2] * khat[2];
                    let u = [0, 1, 2].map(|c| (w[c] - dot * khat[c]) * a);
                    sink(idx, idx_neg, u);
                }
            }
        }
    }
}

/// The three Hermitian spectra û₁, û₂, û₃ on the whole lattice (f64), as synthesised.
/// For verification and analysis; [`Synthesis`] packs the same modes straight into its buffers.
pub fn hermitian_spectrum(params: &FieldParams) -> Result<[Vec<Complex64>; 3], ParamError> {
    let lattice = params.validate()?;
    let zero = vec![Complex64::new(0.0, 0.0); lattice.points()];
    let mut s = [zero.clone(), zero.clone(), zero];
    for_each_mode(&lattice, &params.spectrum, params.seed, |i, j, u| {
        for c in 0..3 {
            s[c][i] = u[c];
            s[c][j] = u[c].conj();
        }
    });
    Ok(s)
}

/// A stage of [`Synthesis`], for progress reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Filtering white noise into the spectrum.
    Spectrum,
    /// Inverse transform of buffer `0` (components 1 and 2) or `1` (component 3) along an axis.
    Transform {
        buffer: usize,
        axis: usize,
    },
    /// Interleaving into the finished field.
    Interleave,
    Done,
}

/// Number of stages a synthesis runs through (spectrum, 2 × 4 axis passes, interleave).
pub const STAGE_COUNT: usize = 10;

/// Field synthesis, run one stage at a time so a caller can report progress.
pub struct Synthesis {
    params: FieldParams,
    lattice: Lattice,
    fft: Fft4<f32>,
    /// û₁ + i û₂, then u₁ + i u₂.
    a: Vec<Complex32>,
    /// û₃, then u₃ (+ i times an independent field left unused).
    b: Vec<Complex32>,
    next: usize,
}

impl Synthesis {
    /// Validates `params` and allocates the two transform buffers.
    pub fn new(params: &FieldParams) -> Result<Self, ParamError> {
        let lattice = params.validate()?;
        let n = lattice.points();
        Ok(Self {
            params: *params,
            lattice,
            fft: Fft4::new(lattice, FftDirection::Inverse),
            a: vec![Complex32::new(0.0, 0.0); n],
            b: vec![Complex32::new(0.0, 0.0); n],
            next: 0,
        })
    }

    /// The stage [`Self::run_stage`] will run next.
    pub fn stage(&self) -> Stage {
        match self.next {
            0 => Stage::Spectrum,
            i @ 1..=8 => Stage::Transform {
                buffer: (i - 1) / 4,
                axis: (i - 1) % 4,
            },
            9 => Stage::Interleave,
            _ => Stage::Done,
        }
    }

    /// Fraction of stages completed, in [0, 1].
    pub fn progress(&self) -> f64 {
        self.next.min(STAGE_COUNT) as f64 / STAGE_COUNT as f64
    }

    /// Runs the next stage except the final interleave (done by [`Self::finish`]).
    /// Returns false once only the interleave is left.
    pub fn run_stage(&mut self) -> bool {
        match self.stage() {
            Stage::Spectrum => {
                let (a, b) = (&mut self.a, &mut self.b);
                for_each_mode(
                    &self.lattice,
                    &self.params.spectrum,
                    self.params.seed,
                    |i, j, u| {
                        let [u1, u2, u3] = u;
                        // û₁ + i û₂ at (k, ω) and û₁* + i û₂* at (−k, −ω).
                        a[i] = to32(u1 + Complex64::i() * u2);
                        a[j] = to32(u1.conj() + Complex64::i() * u2.conj());
                        b[i] = to32(u3);
                        b[j] = to32(u3.conj());
                    },
                );
            }
            Stage::Transform { buffer, axis } => {
                let data = if buffer == 0 {
                    &mut self.a
                } else {
                    &mut self.b
                };
                self.fft.process_axis(data, axis);
            }
            Stage::Interleave | Stage::Done => return false,
        }
        self.next += 1;
        self.next < STAGE_COUNT - 1
    }

    /// Runs the remaining stages and returns the field.
    pub fn finish(mut self) -> TurbulentField {
        while self.run_stage() {}
        let mut data = vec![0.0f32; 3 * self.lattice.points()];
        for ((v, a), b) in data.chunks_exact_mut(3).zip(&self.a).zip(&self.b) {
            v[0] = a.re;
            v[1] = a.im;
            v[2] = b.re;
        }
        TurbulentField {
            lattice: self.lattice,
            params: self.params,
            data,
        }
    }
}

fn to32(c: Complex64) -> Complex32 {
    Complex32::new(c.re as f32, c.im as f32)
}

/// A synthesised field: velocity u (lattice units) at every lattice point, interleaved
/// `[t][z][y][x][component]` (NumPy shape `(nt, nz, ny, nx, 3)`, C order).
#[derive(Debug, Clone)]
pub struct TurbulentField {
    pub lattice: Lattice,
    pub params: FieldParams,
    pub data: Vec<f32>,
}

impl TurbulentField {
    /// Synthesises the field for `params` in one call.
    pub fn generate(params: &FieldParams) -> Result<Self, ParamError> {
        Ok(Synthesis::new(params)?.finish())
    }

    /// Wraps existing lattice data (length `3 * points`), e.g. read from a `.npy` file.
    pub fn from_data(params: FieldParams, data: Vec<f32>) -> Result<Self, ParamError> {
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
}
