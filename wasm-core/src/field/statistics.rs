//! Measured statistics of a field against the paper's formulas: the shell-averaged energy
//! spectrum and its inertial-range slope (Eq. 9), the kinetic energy (Eq. 8, as the lattice sum
//! of the field in docs/FORMATS.md), the spectral divergence (Eq. 2), the energy per component (isotropy, Eq. 7),
//! the mean (zero), and the temporal spread per shell (Eq. 11).

use crate::field::fft4::{transform_columns, Planner64};
use crate::field::lattice::wave_number;
use crate::field::real_fft::RealTwiddles;
use crate::field::spectrum::SpectrumParams;
use crate::field::turbulent_field::TurbulentField;
use rustfft::num_complex::Complex64;
use rustfft::Fft;
use serde::Serialize;
use std::f64::consts::PI;
use std::sync::Arc;

/// One spherical shell of spatial wave numbers, |k| rounded to `k`.
#[derive(Debug, Clone, Serialize)]
pub struct Shell {
    pub k: usize,
    /// Number of spatial lattice modes in the shell.
    pub modes: usize,
    /// Mean |k| over the shell's modes.
    pub mean_k: f64,
    /// Shell average of 4π|k|² Σ_ω ½|û(k, ω)|²: an unbiased estimate of E(|k|).
    pub energy: f64,
    /// Shell average of E(|k|) from the law.
    pub energy_expected: f64,
    /// Measured RMS temporal wave number, energy-weighted over the shell.
    pub temporal_spread: f64,
    /// The same for the lattice-normalised G_k of the law (truncated at the Nyquist ω).
    pub temporal_spread_expected: f64,
    /// k·σ with the shell's energy-weighted RMS |k| (the untruncated Gaussian of Eq. 11).
    pub temporal_spread_nominal: f64,
}

/// Field statistics; see the module docs. Energies are in lattice units (½⟨|u|²⟩).
#[derive(Debug, Clone, Serialize)]
pub struct FieldStats {
    pub size: [usize; 4],
    pub spectrum: SpectrumParams,
    pub shells: Vec<Shell>,
    /// Least-squares slope of ln E against ln k over the shells in `fit_range`.
    pub slope: Option<f64>,
    pub slope_expected: f64,
    /// First and last shell used by the fit: every mode ≥ k_inertial, every shell complete.
    pub fit_range: [usize; 2],
    /// Measured ½⟨|u|²⟩ over the lattice.
    pub energy: f64,
    /// Σ over the lattice's spatial modes of E(|k|)/(4π|k|²).
    pub energy_expected: f64,
    pub energy_ratio: f64,
    /// Σ|k·û|² / Σ|k|²|û|²: zero for a divergence-free field, up to float rounding.
    pub divergence_ratio: f64,
    /// ½⟨u_c²⟩ per component.
    pub component_energy: [f64; 3],
    /// ⟨u_c⟩ per component.
    pub mean: [f64; 3],
    /// Root-mean-square speed sqrt(⟨|u|²⟩).
    pub rms_speed: f64,
}

/// Analyses `field` against the law `spectrum` (which need not be the one it was made with).
///
/// Works on the half spectrum kx = 0..=nx/2 (a real transform along x, [`crate::field::real_fft`]):
/// every other mode is the conjugate of one of these at (−k, −ω) and carries the same energy,
/// so each half-spectrum mode with 0 < kx < nx/2 counts twice. Memory: two half spectra in
/// double precision, about 16.5 bytes per lattice point.
pub fn analyse(field: &TurbulentField, spectrum: &SpectrumParams) -> FieldStats {
    let lattice = field.lattice;
    let modes = HalfModes::new(lattice.size);
    let sums = ModeSums::measure(field, &modes);
    let (shells, energy_expected) = shells(&modes, &sums, spectrum);

    let first = (spectrum.k_inertial + 0.5).ceil() as usize;
    let last = lattice.min_spatial_extent() / 2 - 1;
    let pts: Vec<(f64, f64)> = shells
        .iter()
        .filter(|s| s.k >= first && s.k <= last && s.energy > 0.0)
        .map(|s| (s.mean_k.ln(), s.energy.ln()))
        .collect();
    let slope = fit_slope(&pts);

    let energy = sums.component_energy.iter().sum::<f64>();
    FieldStats {
        size: lattice.size,
        spectrum: *spectrum,
        shells,
        slope,
        slope_expected: spectrum.law.slope(),
        fit_range: [first, last],
        energy,
        energy_expected,
        energy_ratio: energy / energy_expected,
        divergence_ratio: if sums.k2_energy > 0.0 {
            sums.div_energy / sums.k2_energy
        } else {
            0.0
        },
        component_energy: sums.component_energy,
        mean: sums.mean,
        rms_speed: (2.0 * energy).sqrt(),
    }
}

/// The half spectrum's modes: spatial mode s = (kx, ky, kz) with kx in 0..=nx/2, stored
/// `[kz][ky][kx]`, and the ω of each time slab.
struct HalfModes {
    size: [usize; 4],
    /// nx/2 + 1 values of kx.
    half: usize,
    /// Spatial modes of the half spectrum.
    spatial: usize,
}

impl HalfModes {
    fn new(size: [usize; 4]) -> Self {
        let [nx, ny, nz, _] = size;
        let half = nx / 2 + 1;
        Self {
            size,
            half,
            spatial: half * ny * nz,
        }
    }

    /// How many lattice modes half-spectrum mode `i` stands for: itself and, unless kx is 0 or
    /// nx/2, its mirror.
    fn weight(&self, i: usize) -> f64 {
        match i % self.half {
            0 => 1.0,
            kx if kx == self.size[0] / 2 => 1.0,
            _ => 2.0,
        }
    }

    /// The wave number k of spatial mode `s`.
    fn k(&self, s: usize) -> [i64; 3] {
        let [nx, ny, nz, _] = self.size;
        let (x, y, z) = (s % self.half, s / self.half % ny, s / (self.half * ny));
        [wave_number(x, nx), wave_number(y, ny), wave_number(z, nz)]
    }
}

/// What the field's spectrum holds, summed per spatial mode and over the lattice.
struct ModeSums {
    /// Per half-spectrum spatial mode: Σ_ω ½|û|².
    e_mode: Vec<f64>,
    /// Per half-spectrum spatial mode: Σ_ω ω²·½|û|².
    w2_mode: Vec<f64>,
    /// ½⟨u_c²⟩ and ⟨u_c⟩ per component.
    component_energy: [f64; 3],
    mean: [f64; 3],
    /// Σ|k·û|² and Σ|k|²|û|² over the lattice (Eq. 2's divergence against its scale).
    div_energy: f64,
    k2_energy: f64,
}

impl ModeSums {
    /// One forward transform per component (Eq. 8's energy, Eq. 11's spread, Eq. 2's
    /// divergence, all from the same spectrum).
    fn measure(field: &TurbulentField, modes: &HalfModes) -> Self {
        let lattice = field.lattice;
        let nt = lattice.size[3];
        let inv_n = 1.0 / lattice.points() as f64;
        let half_points = modes.spatial * nt;
        let mut e_mode = vec![0.0f64; modes.spatial];
        let mut w2_mode = vec![0.0f64; modes.spatial];
        let mut div = vec![Complex64::new(0.0, 0.0); half_points];
        let mut buf = vec![Complex64::new(0.0, 0.0); half_points];
        let mut transform = HalfSpectrum::new(lattice.size);
        let mut component_energy = [0.0; 3];
        let mut mean = [0.0; 3];
        let mut k2_energy = 0.0;
        for c in 0..3 {
            let (sum, sum2) =
                field
                    .data
                    .iter()
                    .skip(c)
                    .step_by(3)
                    .fold((0.0, 0.0), |(s, s2), &v| {
                        let v = v as f64;
                        (s + v, s2 + v * v)
                    });
            mean[c] = sum * inv_n;
            component_energy[c] = 0.5 * sum2 * inv_n;
            transform.forward(&field.data, c, &mut buf);
            for (i, (u, d)) in buf.iter().zip(div.iter_mut()).enumerate() {
                let u = u * inv_n;
                let half_e = 0.5 * u.norm_sqr();
                let s = i % modes.spatial;
                let omega = wave_number(i / modes.spatial, nt) as f64;
                e_mode[s] += half_e;
                w2_mode[s] += omega * omega * half_e;
                let k = modes.k(s);
                *d += u * k[c] as f64;
                let k2 = (k[0] * k[0] + k[1] * k[1] + k[2] * k[2]) as f64;
                k2_energy += modes.weight(s) * k2 * u.norm_sqr();
            }
        }
        let div_energy: f64 = div
            .iter()
            .enumerate()
            .map(|(i, d)| modes.weight(i) * d.norm_sqr())
            .sum();
        Self {
            e_mode,
            w2_mode,
            component_energy,
            mean,
            div_energy,
            k2_energy,
        }
    }
}

/// Running sums of one shell, measured and expected (weights are lattice modes).
#[derive(Default, Clone)]
struct ShellSums {
    modes: f64,
    k: f64,
    e4pik2: f64,
    e_law: f64,
    e: f64,
    w2: f64,
    law_w: f64,
    law_w2: f64,
    law_k2: f64,
}

/// The shells of `sums` beside the law's expectations (G normalised over the non-Nyquist ω),
/// and Σ over the lattice's spatial modes of E(|k|)/(4π|k|²).
fn shells(modes: &HalfModes, sums: &ModeSums, spectrum: &SpectrumParams) -> (Vec<Shell>, f64) {
    let [nx, ny, nz, nt] = modes.size;
    let omegas: Vec<f64> = (0..nt)
        .filter(|&t| t != nt / 2)
        .map(|t| wave_number(t, nt) as f64)
        .collect();
    let k2_max = 3 * (nx.max(ny).max(nz) / 2).pow(2);
    let mut spread2_by_k2 = vec![f64::NAN; k2_max + 1];
    let shell_count = ((k2_max as f64).sqrt().round() as usize) + 1;
    let mut acc = vec![ShellSums::default(); shell_count];
    let mut energy_expected = 0.0;
    for s in 0..modes.spatial {
        let k = modes.k(s);
        if k.iter()
            .zip([nx, ny, nz])
            .any(|(&ki, n)| ki == -(n as i64) / 2)
        {
            continue; // Nyquist planes carry no modes
        }
        let k2 = (k[0] * k[0] + k[1] * k[1] + k[2] * k[2]) as usize;
        if k2 == 0 {
            continue;
        }
        let w = modes.weight(s);
        let kk = (k2 as f64).sqrt();
        let law = spectrum.energy_spectrum(kk);
        let mode_e = law / (4.0 * PI * kk * kk);
        energy_expected += w * mode_e;
        let spread2 = {
            let cached = spread2_by_k2[k2];
            if cached.is_nan() {
                let g = spectrum.temporal_spread(kk, &omegas);
                let v: f64 = g.iter().zip(&omegas).map(|(g, o)| g * o * o).sum();
                spread2_by_k2[k2] = v;
                v
            } else {
                cached
            }
        };
        let a = &mut acc[kk.round() as usize];
        a.modes += w;
        a.k += w * kk;
        a.e4pik2 += w * 4.0 * PI * kk * kk * sums.e_mode[s];
        a.e_law += w * law;
        a.e += w * sums.e_mode[s];
        a.w2 += w * sums.w2_mode[s];
        a.law_w += w * mode_e;
        a.law_w2 += w * mode_e * spread2;
        a.law_k2 += w * mode_e * kk * kk;
    }
    let shells = acc
        .iter()
        .enumerate()
        .filter(|(_, a)| a.modes > 0.0)
        .map(|(k, a)| {
            let m = a.modes;
            let ratio = |num: f64, den: f64| if den > 0.0 { (num / den).sqrt() } else { 0.0 };
            Shell {
                k,
                modes: a.modes as usize,
                mean_k: a.k / m,
                energy: a.e4pik2 / m,
                energy_expected: a.e_law / m,
                temporal_spread: ratio(a.w2, a.e),
                temporal_spread_expected: ratio(a.law_w2, a.law_w),
                temporal_spread_nominal: ratio(a.law_k2, a.law_w) * spectrum.sigma,
            }
        })
        .collect();
    (shells, energy_expected)
}

/// Least-squares slope of y against x; None with fewer than two distinct points.
pub fn fit_slope(pts: &[(f64, f64)]) -> Option<f64> {
    if pts.len() < 2 {
        return None;
    }
    let m = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / m;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / m;
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// The forward 4-D transform of one component of a field onto the half spectrum
/// kx = 0..=nx/2, in double precision: a real transform along x, then complex ones along y, z
/// and t. Output order `[t][z][y][kx]`, unnormalised (rustfft's convention).
struct HalfSpectrum {
    size: [usize; 4],
    x_half: Arc<dyn Fft<f64>>,
    x_twiddles: RealTwiddles<f64>,
    axes: [Arc<dyn Fft<f64>>; 3],
    scratch: Vec<Complex64>,
    columns: Vec<Complex64>,
    packed: Vec<Complex64>,
}

impl HalfSpectrum {
    /// Rows packed and transformed along x together.
    const ROWS: usize = 64;

    fn new(size: [usize; 4]) -> Self {
        let mut planner = Planner64::new();
        let x_half = planner.plan_fft_forward(size[0] / 2);
        let axes = [1, 2, 3].map(|a| planner.plan_fft_forward(size[a]));
        let scratch_len = axes
            .iter()
            .chain([&x_half])
            .map(|f| f.get_inplace_scratch_len())
            .max()
            .unwrap_or(0);
        let zero = Complex64::new(0.0, 0.0);
        Self {
            size,
            x_half,
            x_twiddles: RealTwiddles::new(size[0]),
            axes,
            scratch: vec![zero; scratch_len],
            columns: Vec::new(),
            packed: vec![zero; Self::ROWS * size[0] / 2],
        }
    }

    /// Transforms component `c` of the interleaved field `data` (`[t][z][y][x][c]`) into `out`.
    fn forward(&mut self, data: &[f32], c: usize, out: &mut [Complex64]) {
        let [nx, ny, nz, _] = self.size;
        let (m, half) = (nx / 2, nx / 2 + 1);
        let row_floats = 3 * nx;
        for (block, out_rows) in data
            .chunks(Self::ROWS * row_floats)
            .zip(out.chunks_mut(Self::ROWS * half))
        {
            let packed = &mut self.packed[..block.len() / row_floats * m];
            for (z, row) in packed
                .chunks_exact_mut(m)
                .zip(block.chunks_exact(row_floats))
            {
                for (zj, pair) in z.iter_mut().zip(row.chunks_exact(6)) {
                    *zj = Complex64::new(pair[c] as f64, pair[3 + c] as f64);
                }
            }
            self.x_half.process_with_scratch(packed, &mut self.scratch);
            for (z, spectrum) in packed.chunks_exact(m).zip(out_rows.chunks_exact_mut(half)) {
                self.x_twiddles.unpack_forward(z, spectrum);
            }
        }
        let strides = [half, half * ny, half * ny * nz];
        for (fft, stride) in self.axes.iter().zip(strides) {
            transform_columns(&**fft, out, stride, &mut self.columns, &mut self.scratch);
        }
    }
}

/// A parameter as written: plainly (`0.5`, `4`), or in scientific notation when that would
/// take more than a dozen digits (`1e-200`).
fn number(v: f64) -> String {
    if v == 0.0 || (1e-4..1e12).contains(&v.abs()) {
        v.to_string()
    } else {
        format!("{v:e}")
    }
}

impl FieldStats {
    /// A human-readable report.
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        let sp = &self.spectrum;
        s += &format!(
            "lattice {}x{}x{}x{}  law {}  epsilon {}  k_inertial {}  sigma {}\n",
            self.size[0],
            self.size[1],
            self.size[2],
            self.size[3],
            sp.law.name(),
            number(sp.epsilon),
            number(sp.k_inertial),
            number(sp.sigma)
        );
        s += &format!(
            "energy ½<|u|²> {:.6}  expected {:.6}  ratio {:.4}\n",
            self.energy, self.energy_expected, self.energy_ratio
        );
        match self.slope {
            Some(v) => {
                s += &format!(
                    "inertial slope {v:.4} (expected {:.4}) over shells {}..={}\n",
                    self.slope_expected, self.fit_range[0], self.fit_range[1]
                )
            }
            None => s += "inertial slope: too few complete shells to fit\n",
        }
        s += &format!("spectral divergence ratio {:.3e}\n", self.divergence_ratio);
        s += &format!(
            "component energy {:.6} {:.6} {:.6}   mean {:.2e} {:.2e} {:.2e}\n",
            self.component_energy[0],
            self.component_energy[1],
            self.component_energy[2],
            self.mean[0],
            self.mean[1],
            self.mean[2]
        );
        s += "shell  modes   mean_k     E(k)        expected    spread_w  expected  k*sigma\n";
        for sh in &self.shells {
            s += &format!(
                "{:5} {:6} {:8.3} {:11.5e} {:11.5e} {:9.3} {:9.3} {:8.3}\n",
                sh.k,
                sh.modes,
                sh.mean_k,
                sh.energy,
                sh.energy_expected,
                sh.temporal_spread,
                sh.temporal_spread_expected,
                sh.temporal_spread_nominal
            );
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::fft4::Fft4;
    use crate::field::turbulent_field::FieldParams;
    use rustfft::FftDirection;

    /// The half-spectrum analysis against the whole complex spectrum of each component, on a
    /// small lattice whose extents are not powers of two.
    #[test]
    fn half_spectrum_sums_equal_whole_spectrum_sums() {
        let params = FieldParams {
            size: [6, 10, 8, 6],
            spectrum: SpectrumParams {
                k_inertial: 1.0,
                ..Default::default()
            },
            seed: 3,
        };
        let field = TurbulentField::generate(&params).unwrap();
        let st = analyse(&field, &params.spectrum);
        let [nx, ny, nz, nt] = params.size;
        let n = nx * ny * nz * nt;
        let spatial = nx * ny * nz;
        let mut e = vec![0.0; spatial];
        let mut w2 = vec![0.0; spatial];
        let mut div = vec![Complex64::new(0.0, 0.0); n];
        let mut fft = Fft4::<f64>::new(params.size, FftDirection::Forward);
        for c in 0..3 {
            let mut u: Vec<Complex64> = field
                .data
                .iter()
                .skip(c)
                .step_by(3)
                .map(|&v| Complex64::new(v as f64, 0.0))
                .collect();
            fft.process(&mut u);
            for (i, v) in u.iter().enumerate() {
                let v = v / n as f64;
                let s = i % spatial;
                let k = [
                    wave_number(s % nx, nx),
                    wave_number(s / nx % ny, ny),
                    wave_number(s / (nx * ny), nz),
                ];
                let omega = wave_number(i / spatial, nt) as f64;
                e[s] += 0.5 * v.norm_sqr();
                w2[s] += omega * omega * 0.5 * v.norm_sqr();
                div[i] += v * k[c] as f64;
            }
        }
        // Shell 2 by hand: the modes with round(|k|) = 2 off the Nyquist planes.
        let (mut modes, mut energy, mut weighted_w2, mut sum_e) = (0, 0.0, 0.0, 0.0);
        for s in 0..spatial {
            let k = [
                wave_number(s % nx, nx),
                wave_number(s / nx % ny, ny),
                wave_number(s / (nx * ny), nz),
            ];
            let nyquist = k
                .iter()
                .zip([nx, ny, nz])
                .any(|(&ki, n)| ki == -(n as i64) / 2);
            let kk = ((k[0] * k[0] + k[1] * k[1] + k[2] * k[2]) as f64).sqrt();
            if nyquist || kk.round() != 2.0 {
                continue;
            }
            modes += 1;
            energy += 4.0 * PI * kk * kk * e[s];
            weighted_w2 += w2[s];
            sum_e += e[s];
        }
        let shell = st.shells.iter().find(|s| s.k == 2).unwrap();
        assert_eq!(shell.modes, modes);
        assert!((shell.energy / (energy / modes as f64) - 1.0).abs() < 1e-10);
        assert!((shell.temporal_spread / (weighted_w2 / sum_e).sqrt() - 1.0).abs() < 1e-10);
        let total: f64 = e.iter().sum();
        assert!((st.energy / total - 1.0).abs() < 1e-9, "Parseval");
        assert!(st.divergence_ratio < 1e-12 && div.iter().all(|d| d.norm() < 1e-6));
    }
}
