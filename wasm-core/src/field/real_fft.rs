//! Transforms of real sequences of even length n, built on one complex transform of length
//! m = n/2: the even and odd samples travel as the real and imaginary parts of one complex
//! sequence `z_j = x_{2j} + i x_{2j+1}`. Batched: the caller packs many sequences into one
//! buffer and runs the complex transform over all of them in one call.
//!
//! Convention (rustfft's, unnormalised): the spectrum of a real `x` is
//! `X_k = Σ_j x_j exp(−2πi jk/n)`, k = 0..=m (the rest follows from `X_{n−k} = X_k*`), and the
//! inverse is `x_j = Σ_{k=0}^{n−1} X_k exp(+2πi jk/n)`.
//!
//! (The `realfft` crate does the same one sequence at a time; it plans through rustfft's
//! general planner, which would link rustfft's scalar algorithms into the WASM module.)

use rustfft::num_complex::Complex;
use rustfft::FftNum;

/// The twiddles of a real transform of length n: `w^k = exp(+2πi k/n)`, k = 0..n/2.
#[derive(Debug, Clone)]
pub struct RealTwiddles<T> {
    twiddles: Vec<Complex<T>>,
}

impl<T: FftNum> RealTwiddles<T> {
    /// For real sequences of even length `n` ≥ 2.
    pub fn new(n: usize) -> Self {
        assert!(n >= 2 && n % 2 == 0, "real transforms need an even length");
        let twiddles = (0..n / 2)
            .map(|k| {
                let (s, c) = (std::f64::consts::TAU * k as f64 / n as f64).sin_cos();
                Complex::new(T::from_f64(c).unwrap(), T::from_f64(s).unwrap())
            })
            .collect();
        Self { twiddles }
    }

    /// m = n/2, the length of the complex transform.
    pub fn half(&self) -> usize {
        self.twiddles.len()
    }

    /// Inverse, before the transform: from `X_0..X_{m−1}` (`spectrum[k * stride]`) and the
    /// Nyquist coefficient `X_m`, writes `Z_k = (X_k + X_{m−k}*) + i w^k (X_k − X_{m−k}*)` into
    /// `z` (length m). The imaginary parts of X_0 and X_m, zero for a real sequence, are
    /// ignored. An inverse complex transform of length m then gives `z_j = x_{2j} + i x_{2j+1}`.
    #[inline]
    pub fn pack_inverse(
        &self,
        spectrum: &[Complex<T>],
        stride: usize,
        nyquist: Complex<T>,
        z: &mut [Complex<T>],
    ) {
        let m = self.half();
        let i = Complex::new(T::zero(), T::one());
        let (x0, xm) = (spectrum[0].re, nyquist.re);
        z[0] = Complex::new(x0 + xm, x0 - xm);
        #[allow(unused_mut)]
        let mut k = 1;
        #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
        if stride == 1 && std::mem::size_of::<T>() == 4 {
            assert!(spectrum.len() >= m && z.len() >= m);
            // SAFETY: T is f32 (FftNum is f32 or f64), so the slices are f32 pairs.
            k = unsafe {
                simd::pack_inverse(
                    spectrum.as_ptr().cast(),
                    self.twiddles.as_ptr().cast(),
                    z.as_mut_ptr().cast(),
                    m,
                )
            };
        }
        for k in k..m {
            let a = spectrum[k * stride];
            let b = spectrum[(m - k) * stride].conj();
            z[k] = (a + b) + i * self.twiddles[k] * (a - b);
        }
    }

    /// Forward, after the transform: from `Z = DFT_m(z)` of `z_j = x_{2j} + i x_{2j+1}`, writes
    /// `X_0..=X_m` into `spectrum` (length m + 1):
    /// `X_k = E_k + w^{−k} O_k`, `E_k = (Z_k + Z_{m−k}*)/2`, `O_k = (Z_k − Z_{m−k}*)/(2i)`.
    #[inline]
    pub fn unpack_forward(&self, z: &[Complex<T>], spectrum: &mut [Complex<T>]) {
        let m = self.half();
        let half = T::from_f64(0.5).unwrap();
        for k in 0..=m {
            let a = z[k % m];
            let b = z[(m - k) % m].conj();
            let even = (a + b) * half;
            let odd = (a - b) * Complex::new(T::zero(), -half);
            let w = if k < m {
                self.twiddles[k].conj()
            } else {
                Complex::new(-T::one(), T::zero())
            };
            spectrum[k] = even + w * odd;
        }
    }
}

/// [`RealTwiddles::pack_inverse`] in single precision, two coefficients per 128-bit vector.
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
mod simd {
    use core::arch::wasm32::*;

    /// `Z_k` for k = 1, 2, … in pairs while k + 1 < m, as the scalar loop computes them
    /// (complex values as f32 pairs); returns the first k not written.
    ///
    /// # Safety
    /// `x` holds the m coefficients X_0..X_{m−1}, `w` the m twiddles and `z` m values.
    #[inline]
    pub(super) unsafe fn pack_inverse(
        x: *const f32,
        w: *const f32,
        z: *mut f32,
        m: usize,
    ) -> usize {
        // Negates the imaginary parts (lanes 1 and 3).
        let conj = f32x4(0.0, -0.0, 0.0, -0.0);
        let negate_re = f32x4(-0.0, 0.0, -0.0, 0.0);
        let mut k = 1;
        while k + 1 < m {
            let a = v128_load(x.add(2 * k).cast());
            // X_{m−k}*, X_{m−k−1}*.
            let mirrored = v128_load(x.add(2 * (m - k - 1)).cast());
            let b = v128_xor(i64x2_shuffle::<1, 0>(mirrored, mirrored), conj);
            let (sum, d) = (f32x4_add(a, b), f32x4_sub(a, b));
            // i w^k = (−Im w, Re w) =: (p, q); (p + iq)(d_re + i d_im).
            let tw = v128_load(w.add(2 * k).cast());
            let p = f32x4_neg(i32x4_shuffle::<1, 1, 3, 3>(tw, tw));
            let q = i32x4_shuffle::<0, 0, 2, 2>(tw, tw);
            let swapped = i32x4_shuffle::<1, 0, 3, 2>(d, d);
            let rotated = f32x4_add(f32x4_mul(p, d), v128_xor(f32x4_mul(q, swapped), negate_re));
            v128_store(z.add(2 * k).cast(), f32x4_add(sum, rotated));
            k += 2;
        }
        k
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::fft4::Planner64;
    use rustfft::FftDirection;

    fn naive(x: &[Complex<f64>], sign: f64) -> Vec<Complex<f64>> {
        let n = x.len();
        (0..n)
            .map(|k| {
                x.iter()
                    .enumerate()
                    .map(|(j, v)| {
                        let ph = sign * std::f64::consts::TAU * (j * k) as f64 / n as f64;
                        v * Complex::from_polar(1.0, ph)
                    })
                    .sum()
            })
            .collect()
    }

    fn signal(n: usize) -> Vec<f64> {
        (0..n)
            .map(|j| (j as f64 * 0.731).sin() + 0.3 * (j as f64 * 2.17).cos())
            .collect()
    }

    #[test]
    fn forward_and_inverse_match_the_naive_dft_for_every_small_even_length() {
        for n in (2..=40).step_by(2) {
            let m = n / 2;
            let tw = RealTwiddles::<f64>::new(n);
            let x = signal(n);
            let xc: Vec<Complex<f64>> = x.iter().map(|&v| Complex::new(v, 0.0)).collect();
            let want = naive(&xc, -1.0);
            let mut planner = Planner64::new();
            // Forward.
            let mut z: Vec<Complex<f64>> = (0..m)
                .map(|j| Complex::new(x[2 * j], x[2 * j + 1]))
                .collect();
            planner.plan_fft(m, FftDirection::Forward).process(&mut z);
            let mut spectrum = vec![Complex::new(0.0, 0.0); m + 1];
            tw.unpack_forward(&z, &mut spectrum);
            for k in 0..=m {
                assert!(
                    (spectrum[k] - want[k]).norm() < 1e-12 * n as f64,
                    "n {n} k {k}"
                );
            }
            // Inverse of the same spectrum gives n·x (unnormalised).
            let mut z = vec![Complex::new(0.0, 0.0); m];
            tw.pack_inverse(&spectrum[..m], 1, spectrum[m], &mut z);
            planner.plan_fft(m, FftDirection::Inverse).process(&mut z);
            for j in 0..m {
                assert!((z[j].re - n as f64 * x[2 * j]).abs() < 1e-11 * n as f64);
                assert!((z[j].im - n as f64 * x[2 * j + 1]).abs() < 1e-11 * n as f64);
            }
        }
    }

    #[test]
    fn strided_inverse_reads_every_stride_th_value() {
        let n = 12;
        let tw = RealTwiddles::<f64>::new(n);
        let x = signal(n);
        let xc: Vec<Complex<f64>> = x.iter().map(|&v| Complex::new(v, 0.0)).collect();
        let spectrum = naive(&xc, -1.0);
        let mut strided = vec![Complex::new(9.0, 9.0); 3 * (n / 2)];
        for k in 0..n / 2 {
            strided[3 * k] = spectrum[k];
        }
        let (mut a, mut b) = (
            vec![Complex::default(); n / 2],
            vec![Complex::default(); n / 2],
        );
        tw.pack_inverse(&strided, 3, spectrum[n / 2], &mut a);
        tw.pack_inverse(&spectrum, 1, spectrum[n / 2], &mut b);
        assert_eq!(a, b);
    }
}
