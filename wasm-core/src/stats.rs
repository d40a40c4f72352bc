//! Measured statistics of a field against the paper's formulas: the shell-averaged energy
//! spectrum and its inertial-range slope (Eq. 9), the kinetic energy (Eq. 8, as the lattice sum
//! of DESIGN §2), the spectral divergence (Eq. 2), the energy per component (isotropy, Eq. 7),
//! the mean (zero), and the temporal spread per shell (Eq. 11).

use crate::fft4::Fft4;
use crate::field::TurbulentField;
use crate::lattice::wave_number;
use crate::spectrum::SpectrumParams;
use rustfft::num_complex::Complex64;
use rustfft::FftDirection;
use serde::Serialize;
use std::f64::consts::PI;

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
pub fn analyse(field: &TurbulentField, spectrum: &SpectrumParams) -> FieldStats {
    let lattice = field.lattice;
    let [nx, ny, nz, nt] = lattice.size;
    let n = lattice.points();
    let spatial = nx * ny * nz;
    let inv_n = 1.0 / n as f64;

    // Per spatial mode: Σ_ω ½|û|², Σ_ω ω²·½|û|²; whole-lattice divergence sums.
    let mut e_mode = vec![0.0f64; spatial];
    let mut w2_mode = vec![0.0f64; spatial];
    let mut div = vec![Complex64::new(0.0, 0.0); n];
    let mut buf = vec![Complex64::new(0.0, 0.0); n];
    let mut fft = Fft4::<f64>::new(lattice, FftDirection::Forward);
    let mut component_energy = [0.0; 3];
    let mut mean = [0.0; 3];
    let kvec = |i: usize| {
        let (x, y, z) = (i % nx, i / nx % ny, i / (nx * ny) % nz);
        [wave_number(x, nx), wave_number(y, ny), wave_number(z, nz)]
    };
    let mut k2_energy = 0.0;
    for c in 0..3 {
        let mut sum = 0.0;
        let mut sum2 = 0.0;
        for (b, v) in buf.iter_mut().zip(field.data.iter().skip(c).step_by(3)) {
            let v = *v as f64;
            sum += v;
            sum2 += v * v;
            *b = Complex64::new(v, 0.0);
        }
        mean[c] = sum * inv_n;
        component_energy[c] = 0.5 * sum2 * inv_n;
        fft.process(&mut buf);
        for (i, u) in buf.iter().enumerate() {
            let u = u * inv_n;
            let half_e = 0.5 * u.norm_sqr();
            let s = i % spatial;
            let omega = wave_number(i / spatial, nt) as f64;
            e_mode[s] += half_e;
            w2_mode[s] += omega * omega * half_e;
            let k = kvec(s);
            div[i] += u * k[c] as f64;
            k2_energy += (k[0] * k[0] + k[1] * k[1] + k[2] * k[2]) as f64 * u.norm_sqr();
        }
    }
    let div_energy: f64 = div.iter().map(|d| d.norm_sqr()).sum();

    // Expected per-mode quantities from the law, with G normalised over non-Nyquist ω.
    let omegas: Vec<f64> = (0..nt)
        .filter(|&t| t != nt / 2)
        .map(|t| wave_number(t, nt) as f64)
        .collect();
    let k2_max = 3 * (nx.max(ny).max(nz) / 2).pow(2);
    let mut spread2_by_k2 = vec![f64::NAN; k2_max + 1];

    let shell_count = ((k2_max as f64).sqrt().round() as usize) + 1;
    #[derive(Default, Clone)]
    struct Acc {
        modes: usize,
        k: f64,
        e4pik2: f64,
        e_law: f64,
        e: f64,
        w2: f64,
        law_w: f64,
        law_w2: f64,
        law_k2: f64,
    }
    let mut acc = vec![Acc::default(); shell_count];
    let mut energy_expected = 0.0;
    for s in 0..spatial {
        let k = kvec(s);
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
        let kk = (k2 as f64).sqrt();
        let law = spectrum.energy_spectrum(kk);
        let mode_e = law / (4.0 * PI * kk * kk);
        energy_expected += mode_e;
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
        a.modes += 1;
        a.k += kk;
        a.e4pik2 += 4.0 * PI * kk * kk * e_mode[s];
        a.e_law += law;
        a.e += e_mode[s];
        a.w2 += w2_mode[s];
        a.law_w += mode_e;
        a.law_w2 += mode_e * spread2;
        a.law_k2 += mode_e * kk * kk;
    }
    let shells: Vec<Shell> = acc
        .iter()
        .enumerate()
        .filter(|(_, a)| a.modes > 0)
        .map(|(k, a)| {
            let m = a.modes as f64;
            let ratio = |num: f64, den: f64| if den > 0.0 { (num / den).sqrt() } else { 0.0 };
            Shell {
                k,
                modes: a.modes,
                mean_k: a.k / m,
                energy: a.e4pik2 / m,
                energy_expected: a.e_law / m,
                temporal_spread: ratio(a.w2, a.e),
                temporal_spread_expected: ratio(a.law_w2, a.law_w),
                temporal_spread_nominal: ratio(a.law_k2, a.law_w) * spectrum.sigma,
            }
        })
        .collect();

    let first = (spectrum.k_inertial + 0.5).ceil() as usize;
    let last = lattice.min_spatial_extent() / 2 - 1;
    let pts: Vec<(f64, f64)> = shells
        .iter()
        .filter(|s| s.k >= first && s.k <= last && s.energy > 0.0)
        .map(|s| (s.mean_k.ln(), s.energy.ln()))
        .collect();
    let slope = fit_slope(&pts);

    let energy = component_energy.iter().sum::<f64>();
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
        divergence_ratio: if k2_energy > 0.0 {
            div_energy / k2_energy
        } else {
            0.0
        },
        component_energy,
        mean,
        rms_speed: (2.0 * energy).sqrt(),
    }
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
            sp.epsilon,
            sp.k_inertial,
            sp.sigma
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
