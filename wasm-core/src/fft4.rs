//! Four-dimensional FFT over a [`Lattice`] in `[t][z][y][x]` order, built from rustfft's 1-D
//! transforms, one axis pass at a time.
//!
//! Normalisation: none in either direction (rustfft's convention). The inverse transform is
//! `u(x) = Σ_k û(k) exp(+i k·x)`, the synthesis of paper §3.3; the forward transform is
//! `Σ_x u(x) exp(-i k·x)`, so forward-then-inverse multiplies by the number of points.
//!
//! The x axis is contiguous and transformed in place. The strided axes (y, z, t) are gathered a
//! batch of [`BATCH`] neighbouring columns at a time into a small contiguous buffer, transformed
//! together and scattered back, so every memory access reads whole cache lines.

use crate::lattice::Lattice;
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftDirection, FftNum};
use std::sync::Arc;

/// Columns gathered per batch on the strided axes.
pub const BATCH: usize = 16;

/// rustfft's planner. In WASM (always built with SIMD) the SIMD planner alone, so the scalar
/// planner's algorithms stay out of the module.
#[cfg(not(target_arch = "wasm32"))]
fn planner<T: FftNum>() -> rustfft::FftPlanner<T> {
    rustfft::FftPlanner::new()
}

#[cfg(target_arch = "wasm32")]
fn planner<T: FftNum>() -> rustfft::FftPlannerWasmSimd<T> {
    rustfft::FftPlannerWasmSimd::new().expect("the WASM build enables simd128")
}

/// A planned 4-D transform in one direction.
pub struct Fft4<T: FftNum> {
    lattice: Lattice,
    axes: [Arc<dyn Fft<T>>; 4],
    scratch: Vec<Complex<T>>,
    columns: Vec<Complex<T>>,
}

impl<T: FftNum> Fft4<T> {
    pub fn new(lattice: Lattice, direction: FftDirection) -> Self {
        let mut planner = planner::<T>();
        let axes = lattice.size.map(|n| planner.plan_fft(n, direction));
        let scratch_len = axes
            .iter()
            .map(|f| f.get_inplace_scratch_len())
            .max()
            .unwrap_or(0);
        let longest = *lattice.size.iter().max().unwrap_or(&1);
        Self {
            lattice,
            axes,
            scratch: vec![Complex::new(T::zero(), T::zero()); scratch_len],
            columns: vec![Complex::new(T::zero(), T::zero()); longest * BATCH],
        }
    }

    /// Transforms `data` (length `lattice.points()`) along every axis.
    pub fn process(&mut self, data: &mut [Complex<T>]) {
        for axis in 0..4 {
            self.process_axis(data, axis);
        }
    }

    /// Transforms `data` along one axis: 0 = x, 1 = y, 2 = z, 3 = t.
    pub fn process_axis(&mut self, data: &mut [Complex<T>], axis: usize) {
        assert_eq!(
            data.len(),
            self.lattice.points(),
            "buffer does not match the lattice"
        );
        let n = self.lattice.size[axis];
        let stride: usize = self.lattice.size[..axis].iter().product();
        let fft = &self.axes[axis];
        if stride == 1 {
            fft.process_with_scratch(data, &mut self.scratch);
            return;
        }
        let block = n * stride;
        for start in (0..data.len()).step_by(block) {
            let block_data = &mut data[start..start + block];
            for c0 in (0..stride).step_by(BATCH) {
                let width = BATCH.min(stride - c0);
                let columns = &mut self.columns[..width * n];
                for j in 0..n {
                    let row = &block_data[j * stride + c0..j * stride + c0 + width];
                    for (col, v) in row.iter().enumerate() {
                        columns[col * n + j] = *v;
                    }
                }
                fft.process_with_scratch(columns, &mut self.scratch);
                for j in 0..n {
                    let row = &mut block_data[j * stride + c0..j * stride + c0 + width];
                    for (col, v) in row.iter_mut().enumerate() {
                        *v = columns[col * n + j];
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lattice::wave_number;

    /// Slow, obviously-right 4-D DFT: Σ_x u(x) exp(sign · 2πi Σ_a k_a x_a / n_a).
    fn naive_dft4(l: &Lattice, u: &[Complex<f64>], sign: f64) -> Vec<Complex<f64>> {
        let [nx, ny, nz, nt] = l.size;
        let mut out = vec![Complex::new(0.0, 0.0); u.len()];
        for (ko, o) in out.iter_mut().enumerate() {
            let (kx, ky, kz, kt) = (
                ko % nx,
                ko / nx % ny,
                ko / (nx * ny) % nz,
                ko / (nx * ny * nz),
            );
            for (xi, v) in u.iter().enumerate() {
                let (x, y, z, t) = (
                    xi % nx,
                    xi / nx % ny,
                    xi / (nx * ny) % nz,
                    xi / (nx * ny * nz),
                );
                let phase = 2.0
                    * std::f64::consts::PI
                    * ((kx * x) as f64 / nx as f64
                        + (ky * y) as f64 / ny as f64
                        + (kz * z) as f64 / nz as f64
                        + (kt * t) as f64 / nt as f64);
                *o += v * Complex::from_polar(1.0, sign * phase);
            }
        }
        out
    }

    fn test_signal(n: usize) -> Vec<Complex<f64>> {
        (0..n)
            .map(|i| {
                let a = (i as f64 * 0.7361).sin() + 0.25 * (i as f64 * 0.113).cos();
                let b = (i as f64 * 1.937).cos() - 0.5 * ((i * i) as f64 * 0.0019).sin();
                Complex::new(a, b)
            })
            .collect()
    }

    #[test]
    fn matches_naive_dft_on_anisotropic_lattice() {
        let l = Lattice::new([8, 4, 4, 8], "s").unwrap();
        let u = test_signal(l.points());
        for (dir, sign) in [(FftDirection::Forward, -1.0), (FftDirection::Inverse, 1.0)] {
            let mut fast = u.clone();
            Fft4::<f64>::new(l, dir).process(&mut fast);
            let slow = naive_dft4(&l, &u, sign);
            let err = fast
                .iter()
                .zip(&slow)
                .map(|(a, b)| (a - b).norm())
                .fold(0.0, f64::max);
            assert!(err < 1e-10, "{dir:?}: max error {err}");
        }
    }

    #[test]
    fn batches_wider_than_one_block_are_exact() {
        // stride 32*32 on the t axis exercises several batches per block.
        let l = Lattice::new([32, 32, 4, 4], "s").unwrap();
        let u = test_signal(l.points());
        let mut v = u.clone();
        Fft4::<f64>::new(l, FftDirection::Forward).process(&mut v);
        Fft4::<f64>::new(l, FftDirection::Inverse).process(&mut v);
        let n = l.points() as f64;
        let err = u
            .iter()
            .zip(&v)
            .map(|(a, b)| (a - b / n).norm())
            .fold(0.0, f64::max);
        assert!(err < 1e-12, "round trip error {err}");
        // A single plane wave lands on exactly one coefficient.
        let (kx, ky, kz, kt) = (3usize, 30usize, 1usize, 2usize);
        let mut w: Vec<Complex<f64>> = (0..l.points())
            .map(|i| {
                let [nx, ny, nz, nt] = l.size;
                let (x, y, z, t) = (i % nx, i / nx % ny, i / (nx * ny) % nz, i / (nx * ny * nz));
                let ph = 2.0
                    * std::f64::consts::PI
                    * (wave_number(kx, nx) as f64 * x as f64 / nx as f64
                        + wave_number(ky, ny) as f64 * y as f64 / ny as f64
                        + wave_number(kz, nz) as f64 * z as f64 / nz as f64
                        + wave_number(kt, nt) as f64 * t as f64 / nt as f64);
                Complex::from_polar(1.0, ph)
            })
            .collect();
        Fft4::<f64>::new(l, FftDirection::Forward).process(&mut w);
        let peak = l.index(kx, ky, kz, kt);
        for (i, c) in w.iter().enumerate() {
            let want = if i == peak { n } else { 0.0 };
            assert!(
                (c - Complex::new(want, 0.0)).norm() < 1e-8,
                "coefficient {i}"
            );
        }
    }
}
