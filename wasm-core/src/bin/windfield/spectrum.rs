//! The flags of the energy spectrum (Eq. 9) that `generate` synthesises a field with and
//! `stats` measures one against, and the parameters stored beside a field (`field.npy.json`).

use super::failure::{input_error, Failure};
use clap::Args;
use std::path::{Path, PathBuf};
use windfield::field::spectrum::{SpectrumLaw, SpectrumParams};

#[derive(Args, Clone)]
pub struct SpectrumArgs {
    /// Energy-cascade rate ε (> 0). Default 1 (`stats`: the value stored beside the file first).
    #[arg(long, allow_hyphen_values = true)]
    epsilon: Option<f64>,
    /// Inertial wave number: no energy below it. Default 4 (`stats`: the value stored beside the
    /// file first).
    #[arg(long = "k-inertial", allow_hyphen_values = true)]
    k_inertial: Option<f64>,
    /// Temporal spread σ, 0 to 100: G_k(ω) has standard deviation kσ (0 freezes time; any
    /// positive σ too small for kσ to be told from 0 gives the same frozen field). Default 1.
    #[arg(long, allow_hyphen_values = true)]
    sigma: Option<f64>,
    /// Energy spectrum law: kolmogorov (k^-5/3) or paper-literal (Eq. 9 as printed, k^-5/2).
    #[arg(long)]
    law: Option<String>,
}

/// The parameters' file beside the field `path`: its whole name with `.json` after it.
pub fn sidecar(path: &Path) -> PathBuf {
    let mut s = path.as_os_str().to_owned();
    s.push(".json");
    PathBuf::from(s)
}

/// Flags first, then the parameters stored beside the file, then the paper's defaults.
pub fn resolve_spectrum(
    args: &SpectrumArgs,
    stored: Option<SpectrumParams>,
) -> Result<SpectrumParams, Failure> {
    let base = stored.unwrap_or_default();
    let law = match &args.law {
        Some(name) => SpectrumLaw::parse(name, "law").map_err(input_error)?,
        None => base.law,
    };
    Ok(SpectrumParams {
        law,
        epsilon: args.epsilon.unwrap_or(base.epsilon),
        k_inertial: args.k_inertial.unwrap_or(base.k_inertial),
        sigma: args.sigma.unwrap_or(base.sigma),
    })
}
