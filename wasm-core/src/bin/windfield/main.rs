//! `windfield`: the command-line face of the core.
//!
//! ```text
//! windfield generate --size 32 --epsilon 1 --k-inertial 4 --sigma 1 --seed 1 --out field.npy
//! windfield stats field.npy --json
//! windfield render scene.json --frames 0..240 --fps 24 --out frames/f%04d.png --shard 0/4
//! windfield wind scene.json --seconds 2 --box -1,0,-1,1,2,1 --n 32,64,32 --out wind.npy
//! windfield schema > ../public/scene.schema.json
//! windfield contract > ../web/src/generated/contract.js
//! ```
//!
//! Every command checks its flags and its input before it starts work; a refusal names the
//! flag or the JSON path and what is allowed (exit status 2; a failed read or write, a folder
//! given as an input file included, 1), and begins `windfield: error:`, the argument parser's
//! too (`messages`). On
//! success `simulate` and `render` end with one line on stderr: what was written, the blobs,
//! the simulated time and the wall time (`wrote still.png (640×480): 41,203 blobs at t =
//! 3.00 s, 2.4 s`). Numeric flags take negative numbers as values (`--seconds -1`), so that
//! the range check, not the argument parser, answers them.

mod claim;
mod exports;
mod messages;
mod output;
mod sequence;
mod wind;

use clap::{Args, Parser, Subcommand};
use serde::de::IgnoredAny;
use serde::{Deserialize, Deserializer};
use std::fs;
use std::hash::{BuildHasher, Hasher};
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;
use windfield::error::number;
use windfield::export::exr::ExrInfo;
use windfield::export::still::{self, StillFormat};
use windfield::export::vector_grid::VectorGrid;
use windfield::field::spectrum::{SpectrumLaw, SpectrumParams};
use windfield::field::{npy, statistics};
use windfield::field::{FieldParams, TurbulentField, MAX_SEED};
use windfield::render::{RenderOptions, Renderer};
use windfield::scene::blob_list::{Background, BlobList};
use windfield::scene::limits::{MAX_IMAGE_SIDE, MAX_SCENE_BYTES, MAX_SECONDS};
use windfield::scene::read::check_scene_size;
use windfield::{ParamError, Scene, Simulation};

#[derive(Parser)]
#[command(
    name = "windfield",
    version,
    about = "Turbulent wind fields for gaseous phenomena (Stam & Fiume 1993)"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Synthesise a small-scale turbulence field and write it as float32 .npy,
    /// shape (nt, nz, ny, nx, 3), C order, velocity in lattice units.
    Generate(GenerateArgs),
    /// Measure a field's statistics against the spectrum it should follow.
    Stats(StatsArgs),
    /// Simulate a scene and write the blob list (camera, lights, medium and blobs).
    Simulate(SimulateArgs),
    /// Render a still with the CPU reference renderer: a blob list, or a scene simulated first.
    /// An --out ending in .exr writes OpenEXR (half-float linear RGBA).
    Render(RenderArgs),
    /// Sample the scene's whole wind (m/s) at one time, at points or over a box of cells.
    Wind(wind::WindArgs),
    /// Render a scene's frames into one sprite sheet (PNG or EXR, with alpha) and its JSON.
    Flipbook(exports::FlipbookArgs),
    /// Write the gas's density (and emission) as an OpenVDB volume.
    Volume(exports::VolumeArgs),
    /// Print the JSON Schema of the scene format.
    Schema,
    /// Print the JavaScript module of the constants the core shares with the page's code
    /// (web/src/generated/contract.js).
    Contract,
}

#[derive(Args)]
struct RenderArgs {
    /// A blob list (JSON), or a scene (JSON with "version").
    input: PathBuf,
    /// Output PNG (8-bit RGB, in the input's image encoding; RGBA with --alpha), or OpenEXR
    /// for a name ending in .exr; default for one still: the input's name with .png, in this
    /// folder. With --frames (then required), a pattern with one %0Nd for the frame number
    /// (frames/f%04d.png).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Image width in pixels, 1 to 8192 (overrides the input's).
    #[arg(long, allow_hyphen_values = true)]
    width: Option<i64>,
    /// Image height in pixels, 1 to 8192 (overrides the input's).
    #[arg(long, allow_hyphen_values = true)]
    height: Option<i64>,
    /// For a scene: seconds to simulate before rendering, 0 or more, at most 1,000,000 steps of
    /// simulation.dt (default: the scene's render.time, 3 when it has none).
    #[arg(long, conflicts_with = "frames", allow_hyphen_values = true)]
    seconds: Option<f64>,
    /// For a scene: a sequence, frames k in the half-open range A..B, frame k at t = k/fps.
    #[arg(long, allow_hyphen_values = true)]
    frames: Option<String>,
    /// With --frames: frames per second of the sequence.
    #[arg(long, requires = "frames", allow_hyphen_values = true)]
    fps: Option<f64>,
    /// With --frames: render only the frames with k mod N = I (I/N, 0 ≤ I < N).
    #[arg(long, requires = "frames", allow_hyphen_values = true)]
    shard: Option<String>,
    /// With --frames: render frames that are already complete again, and over frames that
    /// another run (another scene, frame rate or size) left under the pattern.
    #[arg(long, requires = "frames")]
    force: bool,
    /// A transparent background (render.background = "transparent"): the image gets an alpha
    /// channel, 1 − T(∞) over the gas and 1 on objects.
    #[arg(long)]
    alpha: bool,
    /// For a blob list: the moment it shows (s), recorded in an EXR's header (a scene's
    /// still records the time it was simulated to).
    #[arg(long, conflicts_with_all = ["seconds", "frames"], allow_hyphen_values = true)]
    time: Option<f64>,
}

#[derive(Args)]
struct SimulateArgs {
    /// Scene file (JSON, format version 1).
    scene: PathBuf,
    /// Simulated time in seconds, 0 or more (rounded to whole steps of simulation.dt, at most
    /// 1,000,000 of them).
    #[arg(long, allow_hyphen_values = true)]
    seconds: f64,
    /// Output blob list (JSON).
    #[arg(long)]
    out: PathBuf,
}

#[derive(Args, Clone)]
struct SpectrumArgs {
    /// Energy-cascade rate ε (> 0). Default 1, or the value stored beside the file.
    #[arg(long, allow_hyphen_values = true)]
    epsilon: Option<f64>,
    /// Inertial wave number: no energy below it. Default 4, or the value stored beside the file.
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

#[derive(Args)]
struct GenerateArgs {
    /// Lattice size: N (for N,N,N,N) or NX,NY,NZ,NT; each an even number from 4 to 256 (powers
    /// of two are the fastest), at most 2^24 points in all.
    #[arg(long, default_value = "32", allow_hyphen_values = true)]
    size: String,
    #[command(flatten)]
    spectrum: SpectrumArgs,
    /// Random seed (0 to 2^53).
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
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

#[derive(Args)]
struct StatsArgs {
    /// A .npy field of shape (nt, nz, ny, nx, 3).
    file: PathBuf,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    spectrum: SpectrumArgs,
}

/// A failure: bad input (exit 2) or a failed read or write (exit 1).
pub enum Failure {
    Input(String),
    Io(String),
}

fn flag_for(path: &str) -> String {
    let name = path
        .split('[')
        .next()
        .unwrap_or(path)
        .rsplit('.')
        .next()
        .unwrap_or(path);
    format!("--{}", name.replace('_', "-"))
}

fn input_error(e: ParamError) -> Failure {
    Failure::Input(format!("{}: {}", flag_for(&e.path), e.message))
}

fn parse_size(text: &str) -> Result<[usize; 4], Failure> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let bad = || {
        Failure::Input(format!(
            "--size: expected N or NX,NY,NZ,NT with each an even number between 4 and 256 (got {text:?})"
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

pub(crate) fn sidecar(path: &Path) -> PathBuf {
    let mut s = path.as_os_str().to_owned();
    s.push(".json");
    PathBuf::from(s)
}

/// Flags first, then the parameters stored beside the file, then the paper's defaults.
fn resolve_spectrum(
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

/// A temporary name for `path` in its directory (so renaming it is atomic), unique to this
/// write: the file's own name, the process id and a random number (`f0007.png.4242-
/// 9c0f….partial`). Shards in containers often share a process id (1), and frames without
/// an extension share a stem, so neither alone would do.
fn temporary_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_os_string())
        .unwrap_or_else(|| "windfield".into());
    let random = std::collections::hash_map::RandomState::new()
        .build_hasher()
        .finish();
    let tail = format!(".{}-{random:016x}.partial", std::process::id());
    // A name near the file system's limit (255 bytes) is shortened, so that its temporary
    // name can be made wherever the name itself can.
    let mut name = name.to_string_lossy().into_owned();
    while name.len() + tail.len() > 255 {
        name.pop();
    }
    path.with_file_name(name + &tail)
}

/// Creates the directory `path` lies in, if it has one and it is missing.
pub fn create_parent(path: &Path) -> Result<(), Failure> {
    match path.parent().filter(|d| !d.as_os_str().is_empty()) {
        Some(dir) => {
            fs::create_dir_all(dir).map_err(|e| Failure::Io(format!("{}: {e}", dir.display())))
        }
        None => Ok(()),
    }
}

/// Writes through a temporary file and renames it, so a failure leaves no partial output and
/// concurrent writers (shards) never see each other's half-written files. A missing folder
/// is made.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<fs::File>) -> std::io::Result<()>,
) -> Result<(), Failure> {
    create_parent(path)?;
    let tmp = temporary_path(path);
    let io = |e: std::io::Error| Failure::Io(format!("{}: {e}", path.display()));
    let result = (|| {
        let mut w = BufWriter::new(fs::File::create(&tmp)?);
        write(&mut w)?;
        w.into_inner().map_err(|e| e.into_error())?.sync_all()?;
        fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result.map_err(io)
}

fn generate(args: GenerateArgs) -> Result<(), Failure> {
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
    output::write_together(&[
        output::Output {
            path: &args.out,
            write: Box::new(|w| npy::write_f32(w, &[nt, nz, ny, nx, 3], &field.data)),
        },
        output::Output {
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

/// Opens an input file that must be a file (a folder is a failed read, exit 1); its size.
fn open_input(path: &Path) -> Result<(fs::File, u64), Failure> {
    let io = |e: std::io::Error| Failure::Io(format!("{}: {e}", path.display()));
    let file = fs::File::open(path).map_err(io)?;
    let meta = file.metadata().map_err(io)?;
    if meta.is_dir() {
        return Err(Failure::Io(format!(
            "{}: is a directory, not a file",
            path.display()
        )));
    }
    Ok((file, meta.len()))
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
                    "--period: expected L or LX,LY,LZ, metres from 0.001 to 10000 (got {text:?})"
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
            if !p.iter().all(|l| (0.001..=1e4).contains(l)) {
                return Err(bad());
            }
            p
        }
    };
    let time_period = args.time_period.unwrap_or(8.0);
    if !(0.001..=1e6).contains(&time_period) {
        return Err(Failure::Input(format!(
            "--time-period: must be seconds from 0.001 to 1000000 (got {time_period})"
        )));
    }
    let amplitude = args.amplitude.unwrap_or(1.0);
    if !(0.0..=1000.0).contains(&amplitude) {
        return Err(Failure::Input(format!(
            "--amplitude: must be a number from 0 to 1000 (got {amplitude})"
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

fn stats_cmd(args: StatsArgs) -> Result<(), Failure> {
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
        println!(
            "{}",
            serde_json::to_string(&report).expect("stats serialise")
        );
    } else {
        print!("{}", report.to_text());
    }
    Ok(())
}

/// Reads a file as text.
fn read_text(path: &Path) -> Result<String, Failure> {
    let (mut file, len) = open_input(path)?;
    let mut text = String::with_capacity(len as usize);
    std::io::Read::read_to_string(&mut file, &mut text)
        .map_err(|e| Failure::Io(format!("{}: {e}", path.display())))?;
    Ok(text)
}

/// Reads and validates a scene file; one over `MAX_SCENE_BYTES` is refused unread.
pub(crate) fn read_scene(path: &Path) -> Result<Scene, Failure> {
    let (_, len) = open_input(path)?;
    check_scene_size(len).map_err(|e| Failure::Input(format!("{}: {e}", path.display())))?;
    Scene::from_json(&read_text(path)?)
        .map_err(|e| Failure::Input(format!("{}: {e}", path.display())))
}

/// What `render` reads: a scene, or a blob list.
pub(crate) enum Input {
    Scene(Box<Scene>),
    List(BlobList),
}

/// Whether a JSON object has a key, whatever its value (null included), read without keeping it.
#[derive(Default)]
struct Present(bool);

impl<'de> Deserialize<'de> for Present {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        IgnoredAny::deserialize(d).map(|_| Present(true))
    }
}

/// An object's `version`, the mark of a scene; every other key is skipped unread.
#[derive(Deserialize)]
struct Probe {
    #[serde(default)]
    version: Present,
}

/// The keys of a scene that a blob list does not have: met at the top of a file too long for
/// a scene, they make it one.
const SCENE_ONLY_KEYS: [&str; 8] = [
    "version",
    "seed",
    "field",
    "wind",
    "emitters",
    "shapes",
    "gas",
    "simulation",
];

/// Reads a scene (JSON with "version") or a blob list. A blob list is read straight into its
/// blobs, at most `blob_list::MAX_LIST_BLOBS` of them, with no intermediate JSON tree. A file
/// over `MAX_SCENE_BYTES` can only be a blob list: it is read as one from the file, never held
/// whole, and refused unread past its first scene key if it is a scene.
pub(crate) fn read_input(path: &Path) -> Result<Input, Failure> {
    let bad = |e: ParamError| Failure::Input(format!("{}: {e}", path.display()));
    let (file, len) = open_input(path)?;
    if len > MAX_SCENE_BYTES as u64 {
        return match BlobList::from_reader(std::io::BufReader::new(file)) {
            Ok(list) => Ok(Input::List(list)),
            Err(e)
                if SCENE_ONLY_KEYS.contains(&e.path.as_str())
                    && e.message.starts_with("unknown field") =>
            {
                Err(bad(check_scene_size(len).unwrap_err()))
            }
            Err(e) => Err(bad(e)),
        };
    }
    let text = read_text(path)?;
    match serde_json::from_str::<Probe>(&text) {
        Ok(Probe {
            version: Present(true),
        }) => Ok(Input::Scene(Box::new(
            Scene::from_json(&text).map_err(bad)?,
        ))),
        // Not JSON: read as what it looks like, so the error names where it breaks.
        Err(e) if (e.is_syntax() || e.is_eof()) && text.contains("\"version\"") => Ok(
            Input::Scene(Box::new(Scene::from_json(&text).map_err(bad)?)),
        ),
        _ => Ok(Input::List(BlobList::from_json(&text).map_err(bad)?)),
    }
}

/// Seconds of simulated time asked for with `--seconds`: a number, 0 or more. How many the
/// scene may take is the step budget's to say (`Simulation::budgeted_steps`, which names
/// `simulation.dt` and the time).
pub(crate) fn check_seconds(seconds: f64) -> Result<(), Failure> {
    if seconds.is_finite() && seconds >= 0.0 {
        Ok(())
    } else {
        Err(Failure::Input(format!(
            "--seconds: must be a number, 0 or more (got {})",
            number(seconds)
        )))
    }
}

/// Extensions of image formats windfield does not write: an `--out` naming one is refused
/// rather than given PNG bytes under that name.
const OTHER_IMAGE_FORMATS: [&str; 10] = [
    "jpg", "jpeg", "webp", "gif", "bmp", "tif", "tiff", "avif", "heic", "tga",
];

/// The image format an `--out` names: `.exr` OpenEXR, anything else PNG, but another image
/// format's extension (`.jpg`, …) is an error.
pub(crate) fn image_format(out: &Path) -> Result<StillFormat, Failure> {
    let extension = out
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if let Some(e) = extension.filter(|e| OTHER_IMAGE_FORMATS.contains(&e.as_str())) {
        return Err(Failure::Input(format!(
            "--out: windfield writes PNG or OpenEXR images, not .{e} (name the file .png or .exr)"
        )));
    }
    Ok(StillFormat::of_name(&out.to_string_lossy()))
}

/// A blob list's time given with `--time`: 0 to `gas::limits::MAX_SECONDS`.
pub(crate) fn check_list_time(time: f64) -> Result<(), Failure> {
    if time.is_finite() && (0.0..=MAX_SECONDS).contains(&time) {
        Ok(())
    } else {
        Err(Failure::Input(format!(
            "--time: must be a number between 0 and {MAX_SECONDS} (got {})",
            number(time)
        )))
    }
}

/// An image side given as `flag`: a whole number of pixels from 1 to `MAX_IMAGE_SIDE`.
fn pixels(flag: &str, value: Option<i64>) -> Result<Option<u32>, Failure> {
    match value {
        Some(v) if !(1..=MAX_IMAGE_SIDE as i64).contains(&v) => Err(Failure::Input(format!(
            "{flag}: must be an integer between 1 and {MAX_IMAGE_SIDE} (got {v})"
        ))),
        v => Ok(v.map(|v| v as u32)),
    }
}

/// `n` with its thousands grouped: 41,203.
pub fn grouped(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// Wall time since `start`, for the summary lines: "2.4 s".
pub fn wall(start: Instant) -> String {
    format!("{:.1} s", start.elapsed().as_secs_f64())
}

/// A scene simulated to `seconds` (refused over the step budget before it starts).
pub(crate) fn simulated(
    scene: Scene,
    seconds: f64,
    bad: impl Fn(ParamError) -> Failure,
) -> Result<Simulation, Failure> {
    let mut sim = Simulation::new(scene).map_err(&bad)?;
    let steps = sim.budgeted_steps(seconds).map_err(&bad)?;
    sim.run(steps);
    Ok(sim)
}

fn simulate(args: SimulateArgs) -> Result<(), Failure> {
    let start = Instant::now();
    check_seconds(args.seconds)?;
    let scene = read_scene(&args.scene)?;
    let sim = simulated(scene, args.seconds, |e| Failure::Input(e.to_string()))?;
    let list = sim.blob_list();
    let text = serde_json::to_string(&list).expect("blob lists serialise");
    write_atomically(&args.out, |w| std::io::Write::write_all(w, text.as_bytes()))?;
    let c = sim.gas.counts;
    eprintln!(
        "wrote {}: {} blobs at t = {:.2} s ({} steps; {} emitted, {} split, {} dissipated, {} capped), {}",
        args.out.display(),
        grouped(list.blobs.len()),
        sim.time(),
        sim.steps(),
        grouped(c.emitted as usize),
        grouped(c.split as usize),
        grouped(c.dissipated as usize),
        grouped(c.capped as usize),
        wall(start)
    );
    Ok(())
}

/// The blob list to render and, for a scene, the time it was simulated to.
fn blob_list_for(args: &RenderArgs) -> Result<(BlobList, Option<f64>), Failure> {
    if let Some(seconds) = args.seconds {
        check_seconds(seconds)?;
    }
    let path = &args.input;
    match read_input(path)? {
        Input::Scene(_) if args.time.is_some() => Err(Failure::Input(
            "--time: applies to blob lists; a scene's still records the time it is simulated to (--seconds)".into(),
        )),
        Input::Scene(mut scene) => {
            if args.alpha {
                scene.render.background = Background::Transparent;
            }
            let seconds = args.seconds.unwrap_or(scene.render.still_time());
            let bad = |e: ParamError| Failure::Input(format!("{}: {e}", path.display()));
            let sim = simulated(*scene, seconds, bad)?;
            Ok((sim.blob_list(), Some(sim.time())))
        }
        Input::List(_) if args.seconds.is_some() => Err(Failure::Input(
            "--seconds: applies to scenes only; this input is a blob list".into(),
        )),
        Input::List(mut list) => {
            if args.alpha {
                list.background = Background::Transparent;
            }
            if let Some(t) = args.time {
                check_list_time(t)?;
            }
            Ok((list, args.time))
        }
    }
}

/// `render --frames`: a scene's sequence (the `sequence` module).
fn render_sequence(args: &RenderArgs, frames: &str, start: Instant) -> Result<(), Failure> {
    let size = [
        pixels("--width", args.width)?,
        pixels("--height", args.height)?,
    ];
    let Some(out) = &args.out else {
        return Err(Failure::Input(
            "--out: a sequence needs a pattern with one %0Nd for the frame number (frames/f%04d.png)"
                .into(),
        ));
    };
    let format = image_format(out)?;
    let job = sequence::Sequence::parse(
        frames,
        args.fps,
        out,
        args.shard.as_deref(),
        args.force,
        sequence::Output::Image { size, format },
    )?;
    match read_input(&args.input)? {
        Input::Scene(mut scene) => {
            if args.alpha {
                scene.render.background = Background::Transparent;
            }
            job.run(*scene, &args.input, start)
        }
        Input::List(_) => Err(Failure::Input(format!(
            "--frames: needs a scene to simulate; {} is a blob list",
            args.input.display()
        ))),
    }
}

fn render_cmd(args: RenderArgs) -> Result<(), Failure> {
    let start = Instant::now();
    if let Some(frames) = &args.frames {
        return render_sequence(&args, frames, start);
    }
    let (width, height) = (
        pixels("--width", args.width)?,
        pixels("--height", args.height)?,
    );
    // One still without --out: the input's name with .png, in the current folder.
    let out = args.out.clone().unwrap_or_else(|| {
        let stem = args.input.file_stem().unwrap_or_default();
        PathBuf::from(stem).with_extension("png")
    });
    let format = image_format(&out)?;
    let (list, time) = blob_list_for(&args)?;
    let size = match (width, height) {
        (None, None) => None,
        (w, h) => Some((
            w.unwrap_or(list.image.width),
            h.unwrap_or(list.image.height),
        )),
    };
    let renderer = Renderer::new(&list, size, RenderOptions::default())
        .map_err(|e| Failure::Input(format!("{}: {e}", args.input.display())))?;
    let image = renderer.render();
    let info = ExrInfo {
        camera: Some(list.camera.clone()),
        time,
        fps: None,
        note: String::new(),
    };
    let bytes = still::encode(&image, format, list.image.encoding, &info).map_err(Failure::Io)?;
    write_atomically(&out, |w| std::io::Write::write_all(w, &bytes))?;
    let when = match time {
        Some(t) => format!("at t = {t:.2} s"),
        None => format!("from {}", args.input.display()),
    };
    eprintln!(
        "wrote {} ({}×{}): {} blobs {when}, {}",
        out.display(),
        image.width,
        image.height,
        grouped(list.blobs.len()),
        wall(start)
    );
    Ok(())
}

fn main() -> ExitCode {
    let cli = match messages::parse_args::<Cli>() {
        Ok(cli) => cli,
        Err(code) => return code,
    };
    let result = match cli.command {
        Command::Generate(a) => generate(a),
        Command::Stats(a) => stats_cmd(a),
        Command::Simulate(a) => simulate(a),
        Command::Render(a) => render_cmd(a),
        Command::Wind(a) => wind::run(a),
        Command::Flipbook(a) => exports::flipbook(a),
        Command::Volume(a) => exports::volume(a),
        Command::Schema => {
            print!("{}", windfield::scene::scene_format::json_schema());
            Ok(())
        }
        Command::Contract => {
            print!("{}", windfield::contract::javascript());
            Ok(())
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Input(m)) => {
            eprintln!("windfield: error: {m}");
            ExitCode::from(2)
        }
        Err(Failure::Io(m)) => {
            eprintln!("windfield: error: {m}");
            ExitCode::from(1)
        }
    }
}
