//! `windfield generate`: synthesises a small-scale turbulence field (§3, Eqs. 9–14) and writes
//! it as float32 `.npy` in lattice units with its parameters beside it, or one time slice of
//! it as the world's wind (m/s): `.vdb` (a Vec3SGrid `wind`) or `.rgb32f` (a raw 3-D texture,
//! JSON beside it).

use super::atomic::{write_atomically, write_together, Output};
use super::failure::{input_error, Failure};
use super::formats::FIELDS;
use super::spectrum::{resolve_spectrum, sidecar, SpectrumArgs};
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;
use windfield::error::number;
use windfield::export::vector_grid::VectorGrid;
use windfield::field::lattice::{DEFAULT_EXTENT, MAX_EXTENT, MIN_EXTENT};
use windfield::field::npy;
use windfield::field::turbulent_field::DEFAULT_SEED;
use windfield::field::{FieldParams, TurbulentField, MAX_SEED};
use windfield::scene::limits::{MAX_SECONDS, WORLD_MAPPING};

#[derive(Args)]
pub struct GenerateArgs {
    /// Lattice size: N (for N,N,N,N) or NX,NY,NZ,NT; each an even number from 4 to 256 (powers
    /// of two are the fastest), at most 2^24 points in all.
    #[arg(long, default_value_t = DEFAULT_EXTENT.to_string(), allow_hyphen_values = true)]
    size: String,
    #[command(flatten)]
    spectrum: SpectrumArgs,
    /// Random seed (0 to 2^53).
    #[arg(long, default_value_t = DEFAULT_SEED as i64, allow_hyphen_values = true)]
    seed: i64,
    /// Output file: .npy (the lattice, lattice units), or one time slice of the world's wind
    /// (m/s): .vdb (a Vec3SGrid "wind") or .rgb32f (a raw 3-D texture, JSON beside it).
    #[arg(long)]
    out: PathBuf,
    /// For .vdb and .rgb32f: the moment (s) of the slice, 0 to 1000000 (default 0); linear in
    /// time between lattice times.
    #[arg(long, allow_hyphen_values = true)]
    time: Option<f64>,
    /// For .vdb and .rgb32f: world metres of one spatial period, L or LX,LY,LZ (default 4).
    #[arg(long, allow_hyphen_values = true)]
    period: Option<String>,
    /// For .vdb and .rgb32f: seconds of one temporal period (default 8).
    #[arg(long = "time-period", allow_hyphen_values = true)]
    time_period: Option<f64>,
    /// For .vdb and .rgb32f: the velocity scale A, 0 to 1000 (default 1).
    #[arg(long, allow_hyphen_values = true)]
    amplitude: Option<f64>,
}

fn parse_size(text: &str) -> Result<[usize; 4], Failure> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let bad = || {
        Failure::Input(format!(
            "--size: expected N or NX,NY,NZ,NT with each an even number between {MIN_EXTENT} and {MAX_EXTENT} (got {text:?})"
        ))
    };
    let nums = parts
        .iter()
        .map(|p| p.parse::<usize>().map_err(|_| bad()))
        .collect::<Result<Vec<_>, _>>()?;
    match nums.as_slice() {
        [n] => Ok([*n; 4]),
        [a, b, c, d] => Ok([*a, *b, *c, *d]),
        _ => Err(bad()),
    }
}

pub fn run(args: GenerateArgs) -> Result<(), Failure> {
    if !(0..=MAX_SEED as i64).contains(&args.seed) {
        return Err(Failure::Input(format!(
            "--seed: must be an integer between 0 and {MAX_SEED} (got {})",
            args.seed
        )));
    }
    let params = FieldParams {
        size: parse_size(&args.size)?,
        spectrum: resolve_spectrum(&args.spectrum, None)?,
        seed: args.seed as u64,
    };
    check_wind_mapping(&args)?;
    // Every flag is checked, the name of the output last, before the synthesis starts.
    params.validate().map_err(input_error)?;
    FIELDS.check(&args.out)?;
    let start = Instant::now();
    let field = TurbulentField::generate(&params).map_err(input_error)?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    // No silent NaN: a field that is not finite is never written.
    field
        .check_finite()
        .map_err(|e| Failure::Input(format!("the synthesised {e}")))?;
    let [nx, ny, nz, nt] = params.size;
    if let Some(grid) = wind_mapping(&args, &field)? {
        return write_wind_grid(&args.out, &grid, ms);
    }
    let meta = serde_json::to_string_pretty(&params).expect("parameters serialise");
    // The field and its parameters are one pair: written together, the parameters last.
    write_together(&[
        Output {
            path: &args.out,
            write: Box::new(|w| npy::write_f32(w, &[nt, nz, ny, nx, 3], &field.data)),
        },
        Output {
            path: &sidecar(&args.out),
            write: Box::new(|w| std::io::Write::write_all(w, meta.as_bytes())),
        },
    ])?;
    eprintln!(
        "wrote {} ({nx}x{ny}x{nz}x{nt}, 3 components) in {ms:.1} ms; parameters in {}",
        args.out.display(),
        sidecar(&args.out).display()
    );
    if !params.spectrum.has_energy_on(&field.lattice) {
        eprintln!(
            "note: no mode of this lattice has |k| >= k_inertial = {} (the largest is {:.3}), so the field is zero",
            number(params.spectrum.k_inertial),
            field.lattice.max_wave_number()
        );
    }
    Ok(())
}

/// What `generate --out` writes: the lattice, or one time slice of the wind as a grid.
#[derive(Clone, Copy, PartialEq)]
enum FieldOutput {
    Npy,
    Vdb,
    Texture,
}

fn field_output(path: &Path) -> FieldOutput {
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("vdb") => FieldOutput::Vdb,
        Some(e) if e.eq_ignore_ascii_case("rgb32f") => FieldOutput::Texture,
        _ => FieldOutput::Npy,
    }
}

/// The world mapping flags of `generate` checked, and the slice they ask for (`None` for a
/// `.npy`, which stays in lattice units and takes none of them). Checked before synthesis by
/// [`check_wind_mapping`].
fn wind_mapping(
    args: &GenerateArgs,
    field: &TurbulentField,
) -> Result<Option<VectorGrid>, Failure> {
    let Some((period, time_period, amplitude, time)) = check_wind_mapping(args)? else {
        return Ok(None);
    };
    Ok(Some(VectorGrid::field_slice(
        field,
        period,
        time_period,
        amplitude,
        time,
    )))
}

/// `--period`, `--time-period`, `--amplitude`, `--time` for a grid output (defaults 4 m, 8 s,
/// 1, 0 s); refused for a `.npy`.
#[allow(clippy::type_complexity)]
fn check_wind_mapping(args: &GenerateArgs) -> Result<Option<([f64; 3], f64, f64, f64)>, Failure> {
    let given = [
        ("--time", args.time.is_some()),
        ("--period", args.period.is_some()),
        ("--time-period", args.time_period.is_some()),
        ("--amplitude", args.amplitude.is_some()),
    ];
    if field_output(&args.out) == FieldOutput::Npy {
        if let Some((flag, _)) = given.iter().find(|(_, on)| *on) {
            return Err(Failure::Input(format!(
                "{flag}: applies to a wind grid (--out ending in .vdb or .rgb32f); a .npy holds the lattice in lattice units"
            )));
        }
        return Ok(None);
    }
    let period = match &args.period {
        None => [4.0; 3],
        Some(text) => {
            let bad = || {
                Failure::Input(format!(
                    "--period: expected L or LX,LY,LZ, metres from {} to {} (got {text:?})",
                    WORLD_MAPPING.period[0], WORLD_MAPPING.period[1]
                ))
            };
            let v: Vec<f64> = text
                .split(',')
                .map(|p| p.trim().parse::<f64>().map_err(|_| bad()))
                .collect::<Result<_, _>>()?;
            let p = match v.as_slice() {
                [l] => [*l; 3],
                [x, y, z] => [*x, *y, *z],
                _ => return Err(bad()),
            };
            let [lo, hi] = WORLD_MAPPING.period;
            if !p.iter().all(|l| (lo..=hi).contains(l)) {
                return Err(bad());
            }
            p
        }
    };
    let time_period = args.time_period.unwrap_or(8.0);
    let [lo, hi] = WORLD_MAPPING.time_period;
    if !(lo..=hi).contains(&time_period) {
        return Err(Failure::Input(format!(
            "--time-period: must be seconds from {lo} to {hi} (got {time_period})"
        )));
    }
    let amplitude = args.amplitude.unwrap_or(1.0);
    let [lo, hi] = WORLD_MAPPING.amplitude;
    if !(lo..=hi).contains(&amplitude) {
        return Err(Failure::Input(format!(
            "--amplitude: must be a number from {lo} to {hi} (got {amplitude})"
        )));
    }
    let time = args.time.unwrap_or(0.0);
    if !(time.is_finite() && (0.0..=MAX_SECONDS).contains(&time)) {
        return Err(Failure::Input(format!(
            "--time: must be seconds from 0 to {MAX_SECONDS} (got {time})"
        )));
    }
    Ok(Some((period, time_period, amplitude, time)))
}

/// Writes a wind grid as `.vdb`, or as `.rgb32f` with its JSON description beside it.
fn write_wind_grid(out: &Path, grid: &VectorGrid, ms: f64) -> Result<(), Failure> {
    let [nx, ny, nz] = grid.dims;
    match field_output(out) {
        FieldOutput::Vdb => {
            let bytes = grid.to_vdb();
            write_atomically(out, |w| std::io::Write::write_all(w, &bytes))?;
            eprintln!(
                "wrote {} (a Vec3SGrid \"wind\", {nx}x{ny}x{nz} voxels of {:?} m, t = {} s, m/s); synthesis {ms:.1} ms",
                out.display(),
                grid.cell,
                grid.time
            );
        }
        _ => {
            let bytes = grid.to_rgb32f();
            write_atomically(out, |w| std::io::Write::write_all(w, &bytes))?;
            let text = serde_json::to_string_pretty(&grid.description())
                .expect("descriptions serialise")
                + "\n";
            write_atomically(&sidecar(out), |w| {
                std::io::Write::write_all(w, text.as_bytes())
            })?;
            eprintln!(
                "wrote {} (RGB32F, {nx}x{ny}x{nz} texels, t = {} s, m/s) and {}; synthesis {ms:.1} ms",
                out.display(),
                grid.time,
                sidecar(out).display()
            );
        }
    }
    Ok(())
}
