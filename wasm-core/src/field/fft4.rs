//! Four-dimensional FFT of an array in `[t][z][y][x]` order, built from rustfft's 1-D
//! transforms, one axis pass at a time.
//!
//! Normalisation: none in either direction (rustfft's convention). The inverse transform is
//! `u(x) = Σ_k û(k) exp(+i k·x)`, the synthesis of paper §3.3; the forward transform is
//! `Σ_x u(x) exp(-i k·x)`, so forward-then-inverse multiplies by the number of points.
//!
//! The x axis is contiguous and transformed in place. The strided axes (y, z, t) are gathered a
//! batch of [`BATCH`] neighbouring columns at a time into a small contiguous buffer, transformed
//! together and scattered back, so every memory access reads whole cache lines
//! ([`transform_columns`], which the field synthesis uses too).

use rustfft::num_complex::Complex;
use rustfft::{Fft, FftDirection, FftNum};
use std::sync::Arc;

/// Columns gathered per batch on the strided axes.
pub const BATCH: usize = 16;

/// rustfft's planners for `f32` and `f64` (natively AVX, SSE or scalar, chosen at run time; in
/// WASM the SIMD planner alone), compiled once in `fft-plans/`.
pub use fft_plans::{Planner32, Planner64};

/// The float types of the compiled planners.
pub trait Planned: FftNum {
    /// The plans of the lengths `lens` in `direction`, from one planner (equal lengths share
    /// a plan).
    fn plans<const N: usize>(lens: [usize; N], direction: FftDirection) -> [Arc<dyn Fft<Self>>; N];
}

impl Planned for f32 {
    fn plans<const N: usize>(lens: [usize; N], direction: FftDirection) -> [Arc<dyn Fft<f32>>; N] {
        let mut planner = Planner32::new();
        lens.map(|n| planner.plan_fft(n, direction))
    }
}

impl Planned for f64 {
    fn plans<const N: usize>(lens: [usize; N], direction: FftDirection) -> [Arc<dyn Fft<f64>>; N] {
        let mut planner = Planner64::new();
        lens.map(|n| planner.plan_fft(n, direction))
    }
}

/// Transforms every column of `data` with `fft` (of length n): `data` is a sequence of blocks of
/// `n * stride` values, and column j of a block holds its values j, j + stride, ….
/// `columns` is a work buffer (grown as needed) and `scratch` must hold at least
/// `fft.get_inplace_scratch_len()` values.
pub fn transform_columns<T: FftNum>(
    fft: &dyn Fft<T>,
    data: &mut [Complex<T>],
    stride: usize,
    columns: &mut Vec<Complex<T>>,
    scratch: &mut [Complex<T>],
) {
    if stride == 1 {
        fft.process_with_scratch(data, scratch);
    } else {
        transform_column_range(fft, data, stride, 0..stride, columns, scratch);
    }
}

/// [`transform_columns`] for the columns `range` of each block only (a cache-sized share).
pub fn transform_column_range<T: FftNum>(
    fft: &dyn Fft<T>,
    data: &mut [Complex<T>],
    stride: usize,
    range: std::ops::Range<usize>,
    columns: &mut Vec<Complex<T>>,
    scratch: &mut [Complex<T>],
) {
    let n = fft.len();
    let block = n * stride;
    assert_eq!(data.len() % block, 0, "data is not whole blocks");
    assert!(range.end <= stride, "columns beyond the stride");
    columns.resize(
        n * BATCH.min(range.len()),
        Complex::new(T::zero(), T::zero()),
    );
    for block_data in data.chunks_exact_mut(block) {
        for c0 in range.clone().step_by(BATCH) {
            let width = BATCH.min(range.end - c0);
            let columns = &mut columns[..width * n];
            gather(block_data, stride, c0, columns, n);
            fft.process_with_scratch(columns, scratch);
            scatter(columns, n, block_data, stride, c0);
        }
    }
}

/// Copies the columns `c0..c0 + columns.len() / n` of a block (rows of `stride`) into
/// contiguous columns of length n, two rows at a time (two neighbouring values of a column are
/// one 16-byte store for f32).
#[inline]
fn gather<T: FftNum>(
    block: &[Complex<T>],
    stride: usize,
    c0: usize,
    columns: &mut [Complex<T>],
    n: usize,
) {
    let width = columns.len() / n;
    let pairs = n / 2;
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    if std::mem::size_of::<Complex<T>>() == 8 && n % 2 == 0 {
        return pairs8::gather(block, stride, c0, columns, n);
    }
    for p in 0..pairs {
        let r0 = &block[2 * p * stride + c0..][..width];
        let r1 = &block[(2 * p + 1) * stride + c0..][..width];
        for ((column, a), b) in columns.chunks_exact_mut(n).zip(r0).zip(r1) {
            let pair = &mut column[2 * p..2 * p + 2];
            pair[0] = *a;
            pair[1] = *b;
        }
    }
    if n % 2 == 1 {
        let row = &block[(n - 1) * stride + c0..][..width];
        for (column, v) in columns.chunks_exact_mut(n).zip(row) {
            column[n - 1] = *v;
        }
    }
}

/// The inverse of [`gather`].
#[inline]
fn scatter<T: FftNum>(
    columns: &[Complex<T>],
    n: usize,
    block: &mut [Complex<T>],
    stride: usize,
    c0: usize,
) {
    let width = columns.len() / n;
    let pairs = n / 2;
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    if std::mem::size_of::<Complex<T>>() == 8 && n % 2 == 0 {
        return pairs8::scatter(columns, n, block, stride, c0);
    }
    for p in 0..pairs {
        let (head, tail) = block.split_at_mut((2 * p + 1) * stride);
        let r0 = &mut head[2 * p * stride + c0..][..width];
        let r1 = &mut tail[c0..][..width];
        for ((column, a), b) in columns.chunks_exact(n).zip(r0).zip(r1) {
            let pair = &column[2 * p..2 * p + 2];
            *a = pair[0];
            *b = pair[1];
        }
    }
    if n % 2 == 1 {
        let row = &mut block[(n - 1) * stride + c0..][..width];
        for (column, v) in columns.chunks_exact(n).zip(row) {
            *v = column[n - 1];
        }
    }
}

/// [`gather`] and [`scatter`] for 8-byte values (single-precision complex) and an even n in
/// WASM: two rows and two columns at a time, a 2×2 transpose in two 16-byte loads and two
/// 16-byte stores.
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
pub(crate) mod pairs8 {
    use core::arch::wasm32::*;

    /// [`super::gather`]: columns `c0..` of the block's rows into contiguous columns of n.
    pub(crate) fn gather<V>(block: &[V], stride: usize, c0: usize, columns: &mut [V], n: usize) {
        assert_eq!(std::mem::size_of::<V>(), 8, "8-byte values");
        let width = columns.len() / n;
        assert!(n % 2 == 0 && c0 + width <= stride && n * stride <= block.len());
        let (src, dst) = (
            block.as_ptr() as *const u64,
            columns.as_mut_ptr() as *mut u64,
        );
        for p in (0..n).step_by(2) {
            // SAFETY: rows p and p + 1 of the block hold stride values from c0 + c < stride,
            // and column c holds n values from row p < n (asserted above).
            unsafe {
                let (r0, r1) = (src.add(p * stride + c0), src.add((p + 1) * stride + c0));
                let mut c = 0;
                while c + 2 <= width {
                    let (a, b) = (v128_load(r0.add(c).cast()), v128_load(r1.add(c).cast()));
                    v128_store(dst.add(c * n + p).cast(), i64x2_shuffle::<0, 2>(a, b));
                    v128_store(dst.add((c + 1) * n + p).cast(), i64x2_shuffle::<1, 3>(a, b));
                    c += 2;
                }
                if c < width {
                    dst.add(c * n + p)
                        .write_unaligned(r0.add(c).read_unaligned());
                    dst.add(c * n + p + 1)
                        .write_unaligned(r1.add(c).read_unaligned());
                }
            }
        }
    }

    /// [`super::scatter`]: contiguous columns of n back into columns `c0..` of the rows.
    pub(crate) fn scatter<S, D>(
        columns: &[S],
        n: usize,
        block: &mut [D],
        stride: usize,
        c0: usize,
    ) {
        let eight = std::mem::size_of::<S>() == 8 && std::mem::size_of::<D>() == 8;
        assert!(eight, "8-byte values");
        let width = columns.len() / n;
        assert!(n % 2 == 0 && c0 + width <= stride && n * stride <= block.len());
        let (src, dst) = (
            columns.as_ptr() as *const u64,
            block.as_mut_ptr() as *mut u64,
        );
        for p in (0..n).step_by(2) {
            // SAFETY: as in `gather`, with the roles of block and columns exchanged.
            unsafe {
                let (r0, r1) = (dst.add(p * stride + c0), dst.add((p + 1) * stride + c0));
                let mut c = 0;
                while c + 2 <= width {
                    let a = v128_load(src.add(c * n + p).cast());
                    let b = v128_load(src.add((c + 1) * n + p).cast());
                    v128_store(r0.add(c).cast(), i64x2_shuffle::<0, 2>(a, b));
                    v128_store(r1.add(c).cast(), i64x2_shuffle::<1, 3>(a, b));
                    c += 2;
                }
                if c < width {
                    r0.add(c)
                        .write_unaligned(src.add(c * n + p).read_unaligned());
                    r1.add(c)
                        .write_unaligned(src.add(c * n + p + 1).read_unaligned());
                }
            }
        }
    }
}

/// A planned 4-D transform in one direction of arrays of extents `[nx, ny, nz, nt]`
/// (any lengths rustfft takes).
pub struct Fft4<T: Planned> {
    shape: [usize; 4],
    axes: [Arc<dyn Fft<T>>; 4],
    scratch: Vec<Complex<T>>,
    columns: Vec<Complex<T>>,
}

impl<T: Planned> Fft4<T> {
    pub fn new(shape: [usize; 4], direction: FftDirection) -> Self {
        let axes = T::plans(shape, direction);
        let scratch_len = axes
            .iter()
            .map(|f| f.get_inplace_scratch_len())
            .max()
            .unwrap_or(0);
        Self {
            shape,
            axes,
            scratch: vec![Complex::new(T::zero(), T::zero()); scratch_len],
            columns: Vec::new(),
        }
    }

    /// Transforms `data` (length `nx*ny*nz*nt`) along every axis.
    pub fn process(&mut self, data: &mut [Complex<T>]) {
        for axis in 0..4 {
            self.process_axis(data, axis);
        }
    }

    /// Transforms `data` along one axis: 0 = x, 1 = y, 2 = z, 3 = t.
    pub fn process_axis(&mut self, data: &mut [Complex<T>], axis: usize) {
        assert_eq!(
            data.len(),
            self.shape.iter().product::<usize>(),
            "buffer does not match the shape"
        );
        let stride: usize = self.shape[..axis].iter().product();
        transform_columns(
            &*self.axes[axis],
            data,
            stride,
            &mut self.columns,
            &mut self.scratch,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::lattice::{wave_number, Lattice};

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
            Fft4::<f64>::new(l.size, dir).process(&mut fast);
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
        Fft4::<f64>::new(l.size, FftDirection::Forward).process(&mut v);
        Fft4::<f64>::new(l.size, FftDirection::Inverse).process(&mut v);
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
        Fft4::<f64>::new(l.size, FftDirection::Forward).process(&mut w);
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
