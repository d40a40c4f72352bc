//! The energy spectrum E(k) (paper Eq. 9) and the temporal spread G_k(ω) (Eqs. 10–11).
//!
//! Units are those of the field lattice: wave numbers k and ω are integers (one period 2π per
//! lattice), ε is the energy-cascade rate, σ the temporal-spread factor (standard deviation kσ).

use crate::check;
use crate::error::ParamError;
use serde::{Deserialize, Serialize};

/// Kolmogorov constant C in E(k) = C ε^(2/3) k^(-5/3).
pub const KOLMOGOROV_C: f64 = 1.5;

/// Which energy spectrum law to use.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum SpectrumLaw {
    /// E(k) = 1.5 ε^(2/3) k^(-5/3) for k ≥ k_inertial (the physical Kolmogorov law).
    #[default]
    Kolmogorov,
    /// E(k) = 1.5 ε^(3/2) k^(-5/2) for k ≥ k_inertial: Eq. 9 exactly as printed (a misprint).
    PaperLiteral,
}

impl SpectrumLaw {
    /// Parses `kolmogorov` or `paper-literal`.
    pub fn parse(name: &str, path: &str) -> Result<Self, ParamError> {
        match name {
            "kolmogorov" => Ok(Self::Kolmogorov),
            "paper-literal" => Ok(Self::PaperLiteral),
            other => Err(ParamError::new(
                path,
                format!("must be \"kolmogorov\" or \"paper-literal\" (got \"{other}\")"),
            )),
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Self::Kolmogorov => "kolmogorov",
            Self::PaperLiteral => "paper-literal",
        }
    }

    /// Exponent of k in the inertial range.
    pub fn slope(self) -> f64 {
        match self {
            Self::Kolmogorov => -5.0 / 3.0,
            Self::PaperLiteral => -5.0 / 2.0,
        }
    }
}

/// Statistical parameters of the small-scale turbulence (paper §3.2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SpectrumParams {
    pub law: SpectrumLaw,
    /// Energy-cascade rate ε (> 0).
    #[schemars(range(max = MAX_EPSILON), extend("exclusiveMinimum" = 0))]
    pub epsilon: f64,
    /// Inertial wave number: E(k) = 0 below it (lattice units, > 0, at most 256). Above a
    /// lattice's largest |k|, √(Σ (n/2 − 1)²) over nx, ny and nz, no mode carries energy and
    /// the field is calm.
    #[schemars(range(max = MAX_K_INERTIAL), extend("exclusiveMinimum" = 0))]
    pub k_inertial: f64,
    /// Temporal spread: G_k is a Gaussian in ω with standard deviation kσ (σ ≥ 0; 0 freezes time).
    #[schemars(range(min = 0, max = MAX_SIGMA))]
    pub sigma: f64,
}

impl Default for SpectrumParams {
    /// The paper's statistics (§6): ε = 1, k_inertial = 4, σ = 1.
    fn default() -> Self {
        Self {
            law: SpectrumLaw::Kolmogorov,
            epsilon: DEFAULT_EPSILON,
            k_inertial: DEFAULT_K_INERTIAL,
            sigma: DEFAULT_SIGMA,
        }
    }
}

/// ε where none is named (the paper's statistics, §6).
pub const DEFAULT_EPSILON: f64 = 1.0;
/// k_inertial where none is named (the paper's statistics, §6).
pub const DEFAULT_K_INERTIAL: f64 = 4.0;
/// σ where none is named (the paper's statistics, §6).
pub const DEFAULT_SIGMA: f64 = 1.0;

/// Largest ε accepted.
pub const MAX_EPSILON: f64 = 1.0e6;
/// Largest k_inertial accepted: beyond the modes of the largest lattice (127·√3).
pub const MAX_K_INERTIAL: f64 = 256.0;
/// Largest σ accepted.
pub const MAX_SIGMA: f64 = 100.0;

impl SpectrumParams {
    /// Checks ranges. Errors are named `{path}.name`. A `k_inertial` above every mode of a
    /// lattice ([`crate::field::lattice::Lattice::max_wave_number`]) is allowed: E(k) = 0
    /// there, and the field is calm.
    pub fn validate(&self, path: &str) -> Result<(), ParamError> {
        check::positive(&format!("{path}.epsilon"), self.epsilon, MAX_EPSILON)?;
        check::positive(
            &format!("{path}.k_inertial"),
            self.k_inertial,
            MAX_K_INERTIAL,
        )?;
        check::range(&format!("{path}.sigma"), self.sigma, 0.0, MAX_SIGMA)
    }

    /// Whether some mode of `lattice` carries energy (|k| ≥ `k_inertial`).
    pub fn has_energy_on(&self, lattice: &crate::field::lattice::Lattice) -> bool {
        self.k_inertial <= lattice.max_wave_number()
    }

    /// E(k), paper Eq. 9 (with the corrected exponents for [`SpectrumLaw::Kolmogorov`]).
    pub fn energy_spectrum(&self, k: f64) -> f64 {
        if k < self.k_inertial || k <= 0.0 {
            return 0.0;
        }
        match self.law {
            SpectrumLaw::Kolmogorov => {
                KOLMOGOROV_C * self.epsilon.powf(2.0 / 3.0) * k.powf(-5.0 / 3.0)
            }
            SpectrumLaw::PaperLiteral => KOLMOGOROV_C * self.epsilon.powf(1.5) * k.powf(-2.5),
        }
    }

    /// Unnormalised Gaussian weight exp(-ω²/(2k²σ²)) of paper Eq. 11, exactly 1 at ω = 0.
    /// As kσ → 0 the Gaussian narrows to a Kronecker δ at ω = 0 (the frozen field of σ = 0),
    /// and so it is where 2k²σ² underflows: the weight of ω ≠ 0 is exp(−∞) = 0, never the
    /// −0/0 that ω = 0 would otherwise meet.
    fn spread_weight(&self, k: f64, omega: f64) -> f64 {
        if omega == 0.0 {
            return 1.0;
        }
        let s = k * self.sigma;
        if s == 0.0 {
            return 0.0;
        }
        (-(omega * omega) / (2.0 * s * s)).exp()
    }

    /// G_k(ω) over the lattice's temporal wave numbers `omegas`: the Gaussian of Eq. 11
    /// normalised so that Σ_ω G_k(ω) = 1 (the discrete form of Eq. 10), so every spatial
    /// mode keeps exactly its energy. With ω = 0 among `omegas` the sum is at least 1, so the
    /// normalisation is finite for every σ ≥ 0, however small.
    pub fn temporal_spread(&self, k: f64, omegas: &[f64]) -> Vec<f64> {
        let w: Vec<f64> = omegas.iter().map(|&o| self.spread_weight(k, o)).collect();
        let total: f64 = w.iter().sum();
        if total > 0.0 {
            w.iter().map(|x| x / total).collect()
        } else {
            w
        }
    }

    /// Variance of one spatial mode's spectral density before the projection:
    /// E(k) G_k(ω) / (4π k²) (the scalar factor of paper Eq. 7 with Eq. 10's split).
    pub fn mode_variance(&self, k: f64, g: f64) -> f64 {
        if k <= 0.0 {
            return 0.0;
        }
        self.energy_spectrum(k) * g / (4.0 * std::f64::consts::PI * k * k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kolmogorov_law_values() {
        let p = SpectrumParams::default();
        assert_eq!(p.energy_spectrum(3.9), 0.0);
        assert!((p.energy_spectrum(8.0) - 1.5 * 8f64.powf(-5.0 / 3.0)).abs() < 1e-15);
        let q = SpectrumParams { epsilon: 8.0, ..p };
        // ε^(2/3) = 4.
        assert!((q.energy_spectrum(8.0) / p.energy_spectrum(8.0) - 4.0).abs() < 1e-12);
        let lit = SpectrumParams {
            law: SpectrumLaw::PaperLiteral,
            epsilon: 4.0,
            ..p
        };
        assert!((lit.energy_spectrum(4.0) - 1.5 * 8.0 * 4f64.powf(-2.5)).abs() < 1e-12);
    }

    #[test]
    fn temporal_spread_is_normalised_gaussian() {
        let p = SpectrumParams::default();
        let omegas: Vec<f64> = (-15..16).map(|o| o as f64).collect();
        let g = p.temporal_spread(2.0, &omegas);
        assert!((g.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        // Ratio of neighbours follows exp(-ω²/(2k²σ²)).
        let i0 = 15;
        assert!((g[i0 + 1] / g[i0] - (-1.0f64 / 8.0).exp()).abs() < 1e-14);
        let frozen = SpectrumParams { sigma: 0.0, ..p };
        let g0 = frozen.temporal_spread(5.0, &omegas);
        assert_eq!(g0[i0], 1.0);
        assert_eq!(g0.iter().sum::<f64>(), 1.0);
    }

    #[test]
    fn a_vanishing_spread_is_the_frozen_field_not_nan() {
        let omegas: Vec<f64> = (-15..16).map(|o| o as f64).collect();
        let frozen = SpectrumParams {
            sigma: 0.0,
            ..SpectrumParams::default()
        }
        .temporal_spread(4.0, &omegas);
        // 2k²σ² underflows below σ ≈ 1.6e-162 at k = 4; before, ω = 0 met −0/0.
        for sigma in [1e-300, 1e-200, 1.6e-162, 1e-160, 1e-155, 5e-324] {
            let p = SpectrumParams {
                sigma,
                ..SpectrumParams::default()
            };
            for k in [1.0, 4.0, 221.0] {
                let g = p.temporal_spread(k, &omegas);
                assert!(g.iter().all(|v| v.is_finite()), "σ = {sigma:e}, k = {k}");
                assert_eq!(g.iter().sum::<f64>(), 1.0, "σ = {sigma:e}, k = {k}");
            }
            assert_eq!(p.temporal_spread(4.0, &omegas), frozen, "σ = {sigma:e}");
        }
    }

    #[test]
    fn validation_names_parameters() {
        let p = SpectrumParams::default();
        assert!(p.validate("s").is_ok());
        let e = SpectrumParams { epsilon: 0.0, ..p }
            .validate("s")
            .unwrap_err();
        assert_eq!(e.path, "s.epsilon");
        let e = SpectrumParams {
            k_inertial: 300.0,
            ..p
        }
        .validate("s")
        .unwrap_err();
        assert_eq!(e.path, "s.k_inertial");
        let e = SpectrumParams {
            sigma: f64::NAN,
            ..p
        }
        .validate("s")
        .unwrap_err();
        assert_eq!(e.path, "s.sigma");
        let e = SpectrumParams { sigma: -1.0, ..p }
            .validate("s")
            .unwrap_err();
        assert_eq!(e.path, "s.sigma");
        assert_eq!(SpectrumLaw::parse("x", "s.law").unwrap_err().path, "s.law");
    }
}
