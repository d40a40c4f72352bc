//! The DFT û of the small-scale velocity (paper §3.3): white noise filtered so that every mode
//! has the cross-spectral density of paper Eq. 7 (docs/FORMATS.md, the field), one spatial column — one wave
//! vector k, every temporal wave number ω — at a time.
//!
//! Per mode (k, ω): `û = a(k, ω) (X₁ e₁ + X₂ e₂)`, with X₁, X₂ independent complex Gaussians
//! (E|X|² = 1, [`crate::field::noise`]), e₁, e₂ an orthonormal basis of the plane normal to k, and
//! `a² = E(|k|) G_k(ω) / (4π|k|²)`. Then `⟨û_i* û_j⟩ = a² (e₁ᵢe₁ⱼ + e₂ᵢe₂ⱼ) = a² (δ_ij − k_i k_j / k²)`:
//! exactly Eq. 7, the covariance of three-component white noise projected onto that plane, drawn
//! with two Gaussians per mode instead of three. The basis is built from k and the coordinate
//! axis least aligned with it, so no k is a special case (Eq. 21's kernel divides by zero where k
//! lies on an axis).
//!
//! Real output needs `û(−k, −ω) = û(k, ω)*`. Columns with kx > 0, and with kx = 0 and
//! (ky, kz) > 0 in lexicographic order, draw their own noise; every other column is the mirror
//! of the column of −k. The spatial k = 0 column, every Nyquist plane (a wave number equal to
//! −n/2) and the Nyquist ω are zero. Noise is drawn for every non-Nyquist mode of a drawn column
//! whatever its amplitude, so a seed fixes the white noise and the spectrum parameters only
//! filter it.

use crate::error::ParamError;
use crate::field::lattice::{wave_number, Lattice};
use crate::field::noise::{ColumnNoise, Ziggurat};
use crate::field::spectrum::SpectrumParams;
use glam::Vec4;
use rustfft::num_complex::{Complex32, Complex64};

/// The filter and the noise of one field: everything that determines û.
#[derive(Debug, Clone)]
pub struct VelocitySpectrum {
    size: [usize; 4],
    seed: u64,
    ziggurat: Ziggurat,
    /// a(k², ω)/√2 indexed `[k² * nt + t]` (the √2 turns a pair of standard normal deviates
    /// into a complex Gaussian with E|X|² = 1); zero at the Nyquist ω (t = nt/2), which is
    /// left out of G's normalisation.
    amplitude: Vec<f32>,
    /// Whether the columns are those of the vector potential ψ̂ = i k × û / |k|² (so that
    /// u = ∇ × ψ, with k·ψ̂ = 0) rather than of û itself, from the same noise.
    potential: bool,
}

impl VelocitySpectrum {
    /// The amplitudes a(k, ω) for every |k|² the lattice holds, normalising G_k over the
    /// lattice's non-Nyquist ω (Eq. 10); computed in double precision, kept in single.
    pub fn new(lattice: &Lattice, spectrum: &SpectrumParams, seed: u64) -> Self {
        let [nx, ny, nz, nt] = lattice.size;
        let k2_max: usize = [nx, ny, nz].iter().map(|&n| (n / 2 - 1).pow(2)).sum();
        let omegas: Vec<f64> = (0..nt)
            .filter(|&t| t != nt / 2)
            .map(|t| wave_number(t, nt) as f64)
            .collect();
        let mut amplitude = vec![0.0; (k2_max + 1) * nt];
        for k2 in 1..=k2_max {
            let k = (k2 as f64).sqrt();
            if spectrum.energy_spectrum(k) == 0.0 {
                continue;
            }
            let g = spectrum.temporal_spread(k, &omegas);
            let row = &mut amplitude[k2 * nt..(k2 + 1) * nt];
            let non_nyquist = (0..nt).filter(|&t| t != nt / 2);
            for (t, gt) in non_nyquist.zip(g) {
                row[t] = (spectrum.mode_variance(k, gt) / 2.0).sqrt() as f32;
            }
        }
        Self {
            size: lattice.size,
            seed,
            ziggurat: Ziggurat::new(),
            amplitude,
            potential: false,
        }
    }

    /// The same filter and noise giving the vector potential's columns: with û = a (X₁ e₁ +
    /// X₂ e₂) and k × e₁ = |k| e₂, k × e₂ = −|k| e₁, ψ̂ = i k × û / |k|² = i a (X₁ e₂ − X₂ e₁)
    /// / |k|, so that i k × ψ̂ = û exactly and ψ̂ is normal to k (the Coulomb gauge).
    pub fn potential(mut self) -> Self {
        self.potential = true;
        self
    }

    /// û(k, ω) for the spatial wave vector `k` (integer wave numbers, each in `-n/2..n/2` for
    /// its axis) at every temporal index t (ω = `wave_number(t, nt)`), written to `u[c][t]`
    /// for the three components c (each of length nt).
    pub fn column(&self, k: [i64; 3], u: [&mut [Complex32]; 3]) {
        let mut normals = vec![[0.0; 4]; self.size[3]];
        self.column_with(k, u, &mut normals);
    }

    /// [`Self::column`] for every kx = 0..nx/2 − 1 of the spatial row (ky, kz): column kx at
    /// `u[c][kx·nt..(kx + 1)·nt]`. `normals` is work space. The row's columns draw their noise
    /// two at a time ([`ColumnNoise::fill_two`]).
    pub fn row(&self, [ky, kz]: [i64; 2], u: [&mut [Complex32]; 3], normals: &mut Vec<[f32; 4]>) {
        let nt = self.size[3];
        let m = self.size[0] / 2;
        assert!(u.iter().all(|uc| uc.len() == m * nt), "one column per kx");
        normals.resize(2 * nt, [0.0; 4]);
        let (na, nb) = normals.split_at_mut(nt);
        let [u1, u2, u3] = u;
        let mut columns = u1
            .chunks_exact_mut(nt)
            .zip(u2.chunks_exact_mut(nt))
            .zip(u3.chunks_exact_mut(nt))
            .enumerate()
            .filter_map(|(kx, ((u1, u2), u3))| {
                let k = [kx as i64, ky, kz];
                let stream = match self.source(k) {
                    Source::Zero => {
                        [u1, u2, u3]
                            .into_iter()
                            .for_each(|uc| uc.fill(Complex32::new(0.0, 0.0)));
                        return None;
                    }
                    Source::Own => (k, false),
                    Source::Mirror => (k.map(|v| -v), true),
                };
                Some((stream, [u1, u2, u3]))
            });
        let (half, rest) = (nt / 2, nt / 2 + 1);
        while let Some(((ka, mirror_a), ua)) = columns.next() {
            let Some(((kb, mirror_b), ub)) = columns.next() else {
                self.normals(ka, na);
                self.filter_into(ka, na, ua, mirror_a);
                break;
            };
            let mut noise_a = ColumnNoise::new(self.seed, ka, &self.ziggurat);
            let mut noise_b = ColumnNoise::new(self.seed, kb, &self.ziggurat);
            ColumnNoise::fill_two(&mut noise_a, &mut noise_b, &mut na[..half], &mut nb[..half]);
            ColumnNoise::fill_two(&mut noise_a, &mut noise_b, &mut na[rest..], &mut nb[rest..]);
            self.filter_into(ka, na, ua, mirror_a);
            self.filter_into(kb, nb, ub, mirror_b);
        }
    }

    /// Where the values of the column of `k` come from.
    fn source(&self, k: [i64; 3]) -> Source {
        let nyquist = (0..3).any(|a| k[a] == -(self.size[a] as i64) / 2);
        if nyquist || k == [0, 0, 0] {
            Source::Zero
        } else if draws_its_own_noise(k) {
            Source::Own
        } else {
            Source::Mirror
        }
    }

    /// [`Self::column`] with `normals` (nt entries) as work space.
    fn column_with(&self, k: [i64; 3], u: [&mut [Complex32]; 3], normals: &mut [[f32; 4]]) {
        let nt = self.size[3];
        assert!(u.iter().all(|uc| uc.len() == nt), "one value per ω");
        let (stream, mirror) = match self.source(k) {
            Source::Zero => {
                u.into_iter()
                    .for_each(|uc| uc.fill(Complex32::new(0.0, 0.0)));
                return;
            }
            Source::Own => (k, false),
            Source::Mirror => (k.map(|v| -v), true),
        };
        self.normals(stream, normals);
        self.filter_into(stream, normals, u, mirror);
    }

    /// [`Self::filter`] for the column whose noise is the stream of `k`: the column of `k`
    /// itself, or, if `mirror`, the column of −k, û(−k, ω) = û(k, −ω)* (reversed in ω and
    /// conjugated).
    fn filter_into(
        &self,
        k: [i64; 3],
        normals: &[[f32; 4]],
        [u1, u2, u3]: [&mut [Complex32]; 3],
        mirror: bool,
    ) {
        self.filter(k, normals, [&mut *u1, &mut *u2, &mut *u3]);
        if mirror {
            for uc in [u1, u2, u3] {
                uc[1..].reverse();
                uc.iter_mut().for_each(|v| *v = v.conj());
            }
        }
    }

    /// The deviates of the column of `k`'s own stream, four per ω: `normals[t]` for every
    /// non-Nyquist t in order (X₁ = (g₀ + i g₁)/√2, X₂ = (g₂ + i g₃)/√2); the entry of the
    /// Nyquist ω is left as it was.
    #[inline]
    fn normals(&self, k: [i64; 3], normals: &mut [[f32; 4]]) {
        let half = self.size[3] / 2;
        let mut noise = ColumnNoise::new(self.seed, k, &self.ziggurat);
        noise.fill(&mut normals[..half]);
        noise.fill(&mut normals[half + 1..]);
    }

    /// `û(k, ω) = a(k, ω) (X₁ e₁ + X₂ e₂)` from the column's deviates, written to `u[c][t]`;
    /// zero at the Nyquist ω.
    #[inline]
    fn filter(&self, k: [i64; 3], normals: &[[f32; 4]], u: [&mut [Complex32]; 3]) {
        let nt = self.size[3];
        let k2 = k.iter().map(|ki| ki * ki).sum::<i64>() as usize;
        let amplitude = &self.amplitude[k2 * nt..(k2 + 1) * nt];
        let [e1, e2] = plane_basis(k);
        // Component c in four lanes, [g₀a·e₁, g₁a·e₁, g₂a·e₂, g₃a·e₂] (rounded as complex
        // arithmetic would: X₁e₁ + X₂e₂ with √2·X = g a), then the pairs summed. The potential
        // takes the deviates pairwise swapped, [g₁, g₀, g₃, g₂], against
        // [−e₂, e₂, e₁, −e₁]/|k|: re = (g₃e₁ − g₁e₂)a/|k|, im = (g₀e₂ − g₂e₁)a/|k|, which is
        // i(X₁e₂ − X₂e₁)a/|k|.
        let swap = self.potential;
        let weights = if swap {
            let inv = 1.0 / (k2 as f64).sqrt();
            [0, 1, 2].map(|c| {
                let (a, b) = ((e1[c] * inv) as f32, (e2[c] * inv) as f32);
                Vec4::new(-b, b, a, -a)
            })
        } else {
            let [e1, e2] = [e1, e2].map(|e| e.map(|v| v as f32));
            [0, 1, 2].map(|c| Vec4::new(e1[c], e1[c], e2[c], e2[c]))
        };
        let [u1, u2, u3] = u;
        assert!(normals.len() == nt && [&u1, &u2, &u3].iter().all(|uc| uc.len() == nt));
        #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
        {
            use core::arch::wasm32::*;
            let [w1, w2, w3] = weights.map(|w| f32x4(w.x, w.y, w.z, w.w));
            let (o1, o2, o3) = (u1.as_mut_ptr(), u2.as_mut_ptr(), u3.as_mut_ptr());
            let g = normals.as_ptr() as *const v128;
            for (t, &a) in amplitude.iter().enumerate() {
                // SAFETY: t < nt, the length of normals and of each component (asserted).
                unsafe {
                    let g = v128_load(g.add(t));
                    let g = if swap {
                        i32x4_shuffle::<1, 0, 3, 2>(g, g)
                    } else {
                        g
                    };
                    let x = f32x4_mul(g, f32x4_splat(a));
                    let (p1, p2, p3) = (f32x4_mul(x, w1), f32x4_mul(x, w2), f32x4_mul(x, w3));
                    // Lanes 0, 1: (re, im) = (p.x + p.z, p.y + p.w).
                    let sum = |p: v128| f32x4_add(p, i64x2_shuffle::<1, 1>(p, p));
                    v128_store64_lane::<0>(sum(p1), o1.add(t) as *mut u64);
                    v128_store64_lane::<0>(sum(p2), o2.add(t) as *mut u64);
                    v128_store64_lane::<0>(sum(p3), o3.add(t) as *mut u64);
                }
            }
        }
        #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
        {
            let rows = u1.iter_mut().zip(u2.iter_mut()).zip(u3.iter_mut());
            for ((((v1, v2), v3), &a), g) in rows.zip(amplitude).zip(normals) {
                let g = if swap { [g[1], g[0], g[3], g[2]] } else { *g };
                let x = Vec4::from_array(g) * a;
                let [p1, p2, p3] = weights.map(|w| {
                    let p = x * w;
                    Complex32::new(p.x + p.z, p.y + p.w)
                });
                (*v1, *v2, *v3) = (p1, p2, p3);
            }
        }
        let zero = Complex32::new(0.0, 0.0);
        (u1[nt / 2], u2[nt / 2], u3[nt / 2]) = (zero, zero, zero);
    }
}

/// Where a spectral column's values come from.
enum Source {
    /// A Nyquist column or k = 0: zero.
    Zero,
    /// Its own noise stream.
    Own,
    /// The stream of −k, mirrored.
    Mirror,
}

/// Whether the column of `k` draws noise (the half space kx > 0, then kx = 0 with (ky, kz) > 0
/// lexicographically) rather than mirroring the column of −k.
pub fn draws_its_own_noise(k: [i64; 3]) -> bool {
    k[0] > 0 || (k[0] == 0 && (k[1] > 0 || (k[1] == 0 && k[2] > 0)))
}

/// An orthonormal basis e₁, e₂ of the plane normal to `k` ≠ 0: e₁ = k × â / |k × â| with â the
/// coordinate axis of k's smallest component (so |k × â|² ≥ ⅔|k|²), e₂ = k̂ × e₁.
pub fn plane_basis(k: [i64; 3]) -> [[f64; 3]; 2] {
    let kf = k.map(|v| v as f64);
    let norm = kf.iter().map(|v| v * v).sum::<f64>().sqrt();
    let khat = kf.map(|v| v / norm);
    let a = (0..3)
        .min_by(|&i, &j| khat[i].abs().total_cmp(&khat[j].abs()))
        .expect("three axes");
    let mut axis = [0.0; 3];
    axis[a] = 1.0;
    let e1 = normalise(cross(khat, axis));
    let e2 = cross(khat, e1);
    [e1, e2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalise(v: [f64; 3]) -> [f64; 3] {
    let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    v.map(|x| x / n)
}

/// The three Hermitian spectra û₁, û₂, û₃ on the whole lattice (storage order `[t][z][y][x]`),
/// exactly the values the synthesis transforms. For verification and analysis.
pub fn hermitian_spectrum(
    params: &crate::field::turbulent_field::FieldParams,
) -> Result<[Vec<Complex64>; 3], ParamError> {
    spectrum_of(params, false)
}

/// The three Hermitian spectra of the vector potential, ψ̂ = i k × û / |k|², as
/// [`hermitian_spectrum`] gives û's.
pub fn hermitian_potential_spectrum(
    params: &crate::field::turbulent_field::FieldParams,
) -> Result<[Vec<Complex64>; 3], ParamError> {
    spectrum_of(params, true)
}

fn spectrum_of(
    params: &crate::field::turbulent_field::FieldParams,
    potential: bool,
) -> Result<[Vec<Complex64>; 3], ParamError> {
    let lattice = params.validate()?;
    let [nx, ny, nz, nt] = lattice.size;
    let mut spectrum = VelocitySpectrum::new(&lattice, &params.spectrum, params.seed);
    spectrum.potential = potential;
    let zero = vec![Complex64::new(0.0, 0.0); lattice.points()];
    let mut s = [zero.clone(), zero.clone(), zero];
    let mut column = vec![Complex32::new(0.0, 0.0); 3 * nt];
    for z in 0..nz {
        for y in 0..ny {
            for x in 0..nx {
                let k = [wave_number(x, nx), wave_number(y, ny), wave_number(z, nz)];
                let (u1, rest) = column.split_at_mut(nt);
                let (u2, u3) = rest.split_at_mut(nt);
                spectrum.column(k, [u1, u2, u3]);
                for (c, uc) in column.chunks_exact(nt).enumerate() {
                    for (t, v) in uc.iter().enumerate() {
                        s[c][lattice.index(x, y, z, t)] = Complex64::new(v.re as f64, v.im as f64);
                    }
                }
            }
        }
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_basis_is_orthonormal_and_normal_to_k_on_and_off_the_axes() {
        for k in [
            [1, 0, 0],
            [0, -3, 0],
            [0, 0, 7],
            [2, 2, 2],
            [-5, 1, 3],
            [1, 1, 0],
        ] {
            let [e1, e2] = plane_basis(k);
            let dot = |a: [f64; 3], b: [f64; 3]| a.iter().zip(&b).map(|(x, y)| x * y).sum::<f64>();
            let kf = k.map(|v| v as f64);
            assert!(
                dot(e1, kf).abs() < 1e-14 && dot(e2, kf).abs() < 1e-14,
                "{k:?}"
            );
            assert!((dot(e1, e1) - 1.0).abs() < 1e-14 && (dot(e2, e2) - 1.0).abs() < 1e-14);
            assert!(dot(e1, e2).abs() < 1e-14);
        }
    }

    #[test]
    fn every_wave_vector_but_zero_is_drawn_or_mirrored_exactly_once() {
        for kx in -3i64..=3 {
            for ky in -3i64..=3 {
                for kz in -3i64..=3 {
                    let k = [kx, ky, kz];
                    let m = [-kx, -ky, -kz];
                    if k == [0, 0, 0] {
                        assert!(!draws_its_own_noise(k));
                    } else {
                        assert_ne!(draws_its_own_noise(k), draws_its_own_noise(m), "{k:?}");
                    }
                }
            }
        }
    }

    /// A row's columns, drawn in pairs, equal the columns drawn one at a time: odd and even
    /// numbers of columns per row, mirrored kx = 0 columns, Nyquist rows and k = 0.
    #[test]
    fn a_row_equals_its_columns() {
        for size in [[10, 6, 4, 14], [12, 8, 6, 8], [6, 4, 4, 4]] {
            let lattice = Lattice::new(size, "size").unwrap();
            let params = SpectrumParams {
                k_inertial: 1.0,
                ..SpectrumParams::default()
            };
            let spectrum = VelocitySpectrum::new(&lattice, &params, 7);
            let [nx, ny, nz, nt] = size;
            let m = nx / 2;
            let mut normals = Vec::new();
            let zero = Complex32::new(0.0, 0.0);
            for (y, z) in (0..ny).flat_map(|y| (0..nz).map(move |z| (y, z))) {
                let (ky, kz) = (wave_number(y, ny), wave_number(z, nz));
                let mut row = vec![Complex32::new(f32::NAN, 0.0); 3 * m * nt];
                let (u1, rest) = row.split_at_mut(m * nt);
                let (u2, u3) = rest.split_at_mut(m * nt);
                spectrum.row([ky, kz], [u1, u2, u3], &mut normals);
                for kx in 0..m {
                    let mut column = vec![zero; 3 * nt];
                    let (c1, rest) = column.split_at_mut(nt);
                    let (c2, c3) = rest.split_at_mut(nt);
                    spectrum.column([kx as i64, ky, kz], [c1, c2, c3]);
                    for c in 0..3 {
                        let got = &row[(c * m + kx) * nt..][..nt];
                        let want = &column[c * nt..][..nt];
                        let same = got.iter().zip(want).all(|(a, b)| {
                            a.re.to_bits() == b.re.to_bits() && a.im.to_bits() == b.im.to_bits()
                        });
                        assert!(same, "{size:?} k ({kx}, {ky}, {kz}) component {c}");
                    }
                }
            }
        }
    }
}
