//! `windfield stats`: measures a `.npy` field against the spectrum it should follow
//! (docs/CONVENTIONS.md, statistics): the flags, else the parameters stored beside the file,
//! else the paper's defaults.

use super::failure::{flag_for, input_error, print_out, Failure};
use super::input::open_input;
use super::spectrum::{resolve_spectrum, sidecar, SpectrumArgs};
use clap::Args;
use std::fs;
use std::path::PathBuf;
use windfield::field::{npy, statistics};
use windfield::field::{FieldParams, TurbulentField};

#[derive(Args)]
pub struct StatsArgs {
    /// A .npy field of shape (nt, nz, ny, nx, 3).
    file: PathBuf,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    spectrum: SpectrumArgs,
}

pub fn run(args: StatsArgs) -> Result<(), Failure> {
    let name = args.file.display();
    let (file, len) = open_input(&args.file)?;
    let (shape, data) =
        npy::read_f32_sized(std::io::BufReader::new(file), len).map_err(|e| match e.kind() {
            std::io::ErrorKind::InvalidData | std::io::ErrorKind::UnexpectedEof => {
                Failure::Input(format!("{name}: {e}"))
            }
            _ => Failure::Io(format!("{name}: {e}")),
        })?;
    let size = match shape.as_slice() {
        [nt, nz, ny, nx, 3] => [*nx, *ny, *nz, *nt],
        _ => {
            return Err(Failure::Input(format!(
                "{name}: expected shape (nt, nz, ny, nx, 3), got {shape:?}"
            )))
        }
    };
    let stored: Option<FieldParams> = fs::read_to_string(sidecar(&args.file))
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok())
        .filter(|p: &FieldParams| p.size == size);
    let spectrum = resolve_spectrum(&args.spectrum, stored.map(|p| p.spectrum))?;
    let params = FieldParams {
        size,
        spectrum,
        seed: stored.map_or(0, |p| p.seed),
    };
    // The lattice is the file's shape, not a flag: its refusal names the file.
    params
        .validate()
        .map_err(|e| match flag_for(&e.path) == "--size" {
            true => Failure::Input(format!("{name}: its shape {shape:?}: {}", e.message)),
            false => input_error(e),
        })?;
    let field = TurbulentField::from_data(params, data)
        .map_err(|e| Failure::Input(format!("{}: {e}", args.file.display())))?;
    let report = statistics::analyse(&field, &spectrum);
    if args.json {
        let json = serde_json::to_string(&report).expect("stats serialise");
        print_out(&format!("{json}\n"))
    } else {
        print_out(&report.to_text())
    }
}
