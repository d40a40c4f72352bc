//! `windfield`: the command-line face of the core.
//!
//! ```text
//! windfield generate --size 32 --epsilon 1 --k-inertial 4 --sigma 1 --seed 1 --out field.npy
//! windfield stats field.npy --json
//! windfield render scene.json --frames 0..240 --fps 24 --out frames/f%04d.png --shard 0/4
//! ```

mod sequence;

use clap::{Args, Parser, Subcommand};
use std::fs;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use windfield::blob_list::BlobList;
use windfield::field::{FieldParams, TurbulentField};
use windfield::render::{encode_png, RenderOptions, Renderer};
use windfield::spectrum::{SpectrumLaw, SpectrumParams};
use windfield::{npy, stats, ParamError, Scene, Simulation};

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
    Render(RenderArgs),
    /// Print the JSON Schema of the scene format.
    Schema,
}

#[derive(Args)]
struct RenderArgs {
    /// A blob list (JSON), or a scene (JSON with "version").
    input: PathBuf,
    /// Output PNG (8-bit RGB, in the input's image encoding); with --frames, a pattern with one
    /// %0Nd for the frame number (frames/f%04d.png).
    #[arg(long)]
    out: PathBuf,
    /// Image width in pixels (overrides the input's).
    #[arg(long)]
    width: Option<u32>,
    /// Image height in pixels (overrides the input's).
    #[arg(long)]
    height: Option<u32>,
    /// For a scene: seconds to simulate before rendering (default 0).
    #[arg(long, conflicts_with = "frames")]
    seconds: Option<f64>,
    /// For a scene: a sequence, frames k in the half-open range A..B, frame k at t = k/fps.
    #[arg(long)]
    frames: Option<String>,
    /// With --frames: frames per second of the sequence.
    #[arg(long, requires = "frames")]
    fps: Option<f64>,
    /// With --frames: render only the frames with k mod N = I (I/N, 0 ≤ I < N).
    #[arg(long, requires = "frames")]
    shard: Option<String>,
    /// With --frames: render frames that are already complete again.
    #[arg(long, requires = "frames")]
    force: bool,
}

#[derive(Args)]
struct SimulateArgs {
    /// Scene file (JSON, format version 1).
    scene: PathBuf,
    /// Simulated time in seconds (rounded to whole steps of simulation.dt).
    #[arg(long)]
    seconds: f64,
    /// Output blob list (JSON).
    #[arg(long)]
    out: PathBuf,
}

#[derive(Args, Clone)]
struct SpectrumArgs {
    /// Energy-cascade rate ε (> 0). Default 1, or the value stored beside the file.
    #[arg(long)]
    epsilon: Option<f64>,
    /// Inertial wave number: no energy below it. Default 4, or the value stored beside the file.
    #[arg(long = "k-inertial")]
    k_inertial: Option<f64>,
    /// Temporal spread σ: G_k(ω) has standard deviation kσ (0 freezes time). Default 1.
    #[arg(long)]
    sigma: Option<f64>,
    /// Energy spectrum law: kolmogorov (k^-5/3) or paper-literal (Eq. 9 as printed, k^-5/2).
    #[arg(long)]
    law: Option<String>,
}

#[derive(Args)]
struct GenerateArgs {
    /// Lattice size: N (for N,N,N,N) or NX,NY,NZ,NT; each an even number from 4 to 256 (powers
    /// of two are the fastest), at most 2^24 points in all.
    #[arg(long, default_value = "32")]
    size: String,
    #[command(flatten)]
    spectrum: SpectrumArgs,
    /// Random seed (0 to 2^53).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Output file (.npy).
    #[arg(long)]
    out: PathBuf,
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

fn sidecar(path: &Path) -> PathBuf {
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

/// Writes through a temporary file and renames it, so a failure leaves no partial output.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<fs::File>) -> std::io::Result<()>,
) -> Result<(), Failure> {
    let tmp = path.with_extension("partial");
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
    let params = FieldParams {
        size: parse_size(&args.size)?,
        spectrum: resolve_spectrum(&args.spectrum, None)?,
        seed: args.seed,
    };
    let start = std::time::Instant::now();
    let field = TurbulentField::generate(&params).map_err(input_error)?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    let [nx, ny, nz, nt] = params.size;
    write_atomically(&args.out, |w| {
        npy::write_f32(w, &[nt, nz, ny, nx, 3], &field.data)
    })?;
    let meta = serde_json::to_string_pretty(&params).expect("parameters serialise");
    write_atomically(&sidecar(&args.out), |w| {
        std::io::Write::write_all(w, meta.as_bytes())
    })?;
    eprintln!(
        "wrote {} ({nx}x{ny}x{nz}x{nt}, 3 components) in {ms:.1} ms; parameters in {}",
        args.out.display(),
        sidecar(&args.out).display()
    );
    Ok(())
}

fn stats_cmd(args: StatsArgs) -> Result<(), Failure> {
    let file = fs::File::open(&args.file)
        .map_err(|e| Failure::Io(format!("{}: {e}", args.file.display())))?;
    let (shape, data) = npy::read_f32(std::io::BufReader::new(file))
        .map_err(|e| Failure::Input(format!("{}: {e}", args.file.display())))?;
    let size = match shape.as_slice() {
        [nt, nz, ny, nx, 3] => [*nx, *ny, *nz, *nt],
        _ => {
            return Err(Failure::Input(format!(
                "{}: expected shape (nt, nz, ny, nx, 3), got {shape:?}",
                args.file.display()
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
    params.validate().map_err(input_error)?;
    let field = TurbulentField::from_data(params, data).map_err(input_error)?;
    let report = stats::analyse(&field, &spectrum);
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

/// Reads and validates a scene file.
fn read_scene(path: &Path) -> Result<Scene, Failure> {
    let text =
        fs::read_to_string(path).map_err(|e| Failure::Io(format!("{}: {e}", path.display())))?;
    Scene::from_json(&text).map_err(|e| Failure::Input(format!("{}: {e}", path.display())))
}

fn check_seconds(seconds: f64) -> Result<(), Failure> {
    if seconds.is_finite() && (0.0..=1e5).contains(&seconds) {
        Ok(())
    } else {
        Err(Failure::Input(format!(
            "--seconds: must be between 0 and 100000 (got {seconds})"
        )))
    }
}

fn simulate(args: SimulateArgs) -> Result<(), Failure> {
    check_seconds(args.seconds)?;
    let scene = read_scene(&args.scene)?;
    let mut sim = Simulation::new(scene).map_err(|e| Failure::Input(e.to_string()))?;
    let steps = sim
        .budgeted_steps(args.seconds)
        .map_err(|e| Failure::Input(e.to_string()))?;
    let start = std::time::Instant::now();
    sim.run(steps);
    let list = sim.blob_list();
    let text = serde_json::to_string(&list).expect("blob lists serialise");
    write_atomically(&args.out, |w| std::io::Write::write_all(w, text.as_bytes()))?;
    let c = sim.gas.counts;
    eprintln!(
        "simulated {:.3} s in {} steps ({:.0} ms): {} blobs (emitted {}, split {}, dissipated {}, capped {}) -> {}",
        sim.time(),
        sim.steps(),
        start.elapsed().as_secs_f64() * 1e3,
        list.blobs.len(),
        c.emitted,
        c.split,
        c.dissipated,
        c.capped,
        args.out.display()
    );
    Ok(())
}

/// The blob list to render: read directly, or simulated from a scene.
fn blob_list_for(args: &RenderArgs) -> Result<BlobList, Failure> {
    let path = &args.input;
    let text =
        fs::read_to_string(path).map_err(|e| Failure::Io(format!("{}: {e}", path.display())))?;
    let bad = |e: ParamError| Failure::Input(format!("{}: {e}", path.display()));
    let value: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| Failure::Input(format!("{}: not valid JSON: {e}", path.display())))?;
    if value.get("version").is_some() {
        let seconds = args.seconds.unwrap_or(0.0);
        check_seconds(seconds)?;
        let scene = Scene::from_value(value).map_err(bad)?;
        let mut sim = Simulation::new(scene).map_err(bad)?;
        let steps = sim.budgeted_steps(seconds).map_err(bad)?;
        sim.run(steps);
        Ok(sim.blob_list())
    } else {
        if args.seconds.is_some() {
            return Err(Failure::Input(
                "--seconds: applies to scenes only; this input is a blob list".into(),
            ));
        }
        BlobList::from_value(value).map_err(bad)
    }
}

/// `render --frames`: a scene's sequence (the `sequence` module).
fn render_sequence(args: &RenderArgs, frames: &str) -> Result<(), Failure> {
    let size = match (args.width, args.height) {
        (None, None) => None,
        (Some(w), Some(h)) => Some((w, h)),
        _ => {
            return Err(Failure::Input(
                "--width, --height: give both or neither with --frames".into(),
            ))
        }
    };
    let job = sequence::Sequence::parse(
        frames,
        args.fps,
        &args.out,
        args.shard.as_deref(),
        args.force,
        size,
    )?;
    let path = &args.input;
    let text =
        fs::read_to_string(path).map_err(|e| Failure::Io(format!("{}: {e}", path.display())))?;
    let value: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| Failure::Input(format!("{}: not valid JSON: {e}", path.display())))?;
    if value.get("version").is_none() {
        return Err(Failure::Input(format!(
            "--frames: needs a scene to simulate; {} is a blob list",
            path.display()
        )));
    }
    let scene =
        Scene::from_value(value).map_err(|e| Failure::Input(format!("{}: {e}", path.display())))?;
    job.run(scene)
}

fn render_cmd(args: RenderArgs) -> Result<(), Failure> {
    if let Some(frames) = &args.frames {
        return render_sequence(&args, frames);
    }
    let list = blob_list_for(&args)?;
    let size = match (args.width, args.height) {
        (None, None) => None,
        (w, h) => Some((
            w.unwrap_or(list.image.width),
            h.unwrap_or(list.image.height),
        )),
    };
    let start = std::time::Instant::now();
    let renderer = Renderer::new(&list, size, RenderOptions::default()).map_err(|e| {
        let flag = match e.path.as_str() {
            "image.width" => "--width: ".to_string(),
            "image.height" => "--height: ".to_string(),
            _ => format!("{}: ", args.input.display()),
        };
        Failure::Input(format!("{flag}{e}"))
    })?;
    let image = renderer.render();
    let png = encode_png(
        image.width,
        image.height,
        &image.to_rgb8(list.image.encoding),
    )
    .map_err(|e| Failure::Io(e.to_string()))?;
    write_atomically(&args.out, |w| std::io::Write::write_all(w, &png))?;
    eprintln!(
        "rendered {}x{} from {} blobs in {:.0} ms -> {}",
        image.width,
        image.height,
        list.blobs.len(),
        start.elapsed().as_secs_f64() * 1e3,
        args.out.display()
    );
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Generate(a) => generate(a),
        Command::Stats(a) => stats_cmd(a),
        Command::Simulate(a) => simulate(a),
        Command::Render(a) => render_cmd(a),
        Command::Schema => {
            print!("{}", windfield::scene::json_schema());
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
