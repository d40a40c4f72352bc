//! `windfield flipbook` and `windfield volume` (docs/FORMATS.md, exports): a scene's frames as
//! one sprite sheet, and the gas as OpenVDB volumes, made by the core's `export` module (the
//! browser's worker calls the same code).

use super::{
    check_list_time, check_seconds, grouped, image_format, read_input, read_scene, simulated, wall,
    write_atomically, Failure, Input,
};
use crate::output;
use crate::sequence::{Output, Sequence};
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;
use windfield::export::flipbook::{parse_pair, FlipbookJob, FlipbookSpec, SettingNames};
use windfield::export::volume::{GasVolume, VolumeBuild};
use windfield::scene::limits::MAX_IMAGE_SIDE;
use windfield::ParamError;

#[derive(Args)]
pub struct FlipbookArgs {
    /// Scene file (JSON, format version 1).
    scene: PathBuf,
    /// Frames k in the half-open range A..B, frame k the scene at t = k/fps.
    #[arg(long, allow_hyphen_values = true)]
    frames: String,
    /// Frames per second.
    #[arg(long, allow_hyphen_values = true)]
    fps: f64,
    /// Tiles per row and rows, C×R (or CxR): row-major from the top left, frame A first.
    #[arg(long, allow_hyphen_values = true)]
    grid: String,
    /// A tile's size in pixels, W×H (or WxH).
    #[arg(long, allow_hyphen_values = true)]
    tile: String,
    /// The sheet: .png (8-bit RGBA, straight alpha) or .exr (half-float RGBA, premultiplied);
    /// its description goes beside it with .json in place of the extension.
    #[arg(long)]
    out: PathBuf,
    /// Make a seamless loop: the first tiles cross-fade into the frames after B (the gas's own
    /// continuation); best when (B − A)/fps is a whole number of the field's time periods.
    #[arg(long = "loop")]
    looped: bool,
    /// With --loop: how many tiles cross-fade (default a quarter of the frames).
    #[arg(long, requires = "looped", allow_hyphen_values = true)]
    fade: Option<i64>,
}

const FLAGS: SettingNames = SettingNames {
    frames: "--frames",
    fps: "--fps",
    grid: "--grid",
    tile: "--tile",
    fade: "--fade",
};

fn input(e: ParamError) -> Failure {
    Failure::Input(e.to_string())
}

/// The description's path: the sheet's with `.json` in place of its extension.
pub fn description_path(sheet: &Path) -> PathBuf {
    sheet.with_extension("json")
}

/// The same description's second name: the sheet's whole name with `.json` after it (the way
/// `generate` names its parameters), so a pipeline that looks either way finds it.
pub fn description_alias(sheet: &Path) -> PathBuf {
    let mut name = sheet.as_os_str().to_owned();
    name.push(".json");
    PathBuf::from(name)
}

pub fn flipbook(args: FlipbookArgs) -> Result<(), Failure> {
    let start = Instant::now();
    let range = crate::sequence::FrameRange::parse(&args.frames).map_err(Failure::Input)?;
    let (columns, rows) = parse_pair(&args.grid, "--grid", u32::MAX).map_err(input)?;
    let (tile_width, tile_height) =
        parse_pair(&args.tile, "--tile", MAX_IMAGE_SIDE).map_err(input)?;
    let frames = range.end - range.start;
    let fade = match (args.looped, args.fade) {
        (false, _) => 0,
        (true, None) => FlipbookSpec::default_fade(frames),
        (true, Some(f)) if f >= 1 && f < frames as i64 => f as u32,
        (true, Some(f)) => {
            return Err(Failure::Input(format!(
                "--fade: must be a whole number of frames from 1 to {} (got {f})",
                frames.saturating_sub(1)
            )))
        }
    };
    let spec = FlipbookSpec {
        start: range.start,
        end: range.end,
        fps: args.fps,
        columns,
        rows,
        tile_width,
        tile_height,
        fade,
    };
    spec.check(&FLAGS).map_err(input)?;
    let name = args
        .out
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .ok_or_else(|| Failure::Input("--out: must name a file".into()))?;
    let format = image_format(Path::new(&name))?;
    let scene = read_scene(&args.scene)?;
    let period = scene.field.time_period;
    let bad = |e: ParamError| Failure::Input(format!("{}: {e}", args.scene.display()));
    let job = FlipbookJob::new(scene, None, spec, format, None, &FLAGS).map_err(bad)?;
    if fade > 0 {
        let periods = frames as f64 / spec.fps / period;
        if (periods - periods.round()).abs() > 1e-9 || periods.round() < 1.0 {
            let whole = (frames as f64 / spec.fps / period).round().max(1.0);
            eprintln!(
                "note: the loop lasts {:.4} s, {periods:.3} of the field's time period ({period} s): \
                 {:.0} frames (or --fps {:.4}) would wrap in the same wind",
                frames as f64 / spec.fps,
                whole * period * spec.fps,
                frames as f64 / (whole * period)
            );
        }
    }
    let (bytes, description) = job.finish(&name).map_err(Failure::Io)?;
    let json = serde_json::to_string_pretty(&description).expect("descriptions serialise") + "\n";
    let json_path = description_path(&args.out);
    let alias = description_alias(&args.out);
    output::write_together(&[
        output::Output {
            path: &args.out,
            write: Box::new(|w| std::io::Write::write_all(w, &bytes)),
        },
        output::Output {
            path: &json_path,
            write: Box::new(|w| std::io::Write::write_all(w, json.as_bytes())),
        },
        output::Output {
            path: &alias,
            write: Box::new(|w| std::io::Write::write_all(w, json.as_bytes())),
        },
    ])?;
    eprintln!(
        "wrote {} ({}×{}: {} frames in {columns}×{rows} tiles of {tile_width}×{tile_height}{}) and {}, {}",
        args.out.display(),
        description.sheet_width,
        description.sheet_height,
        frames,
        if fade > 0 {
            format!(", a loop fading {fade} frames")
        } else {
            String::new()
        },
        json_path.display(),
        wall(start)
    );
    Ok(())
}

#[derive(Args)]
pub struct VolumeArgs {
    /// A scene (JSON with "version") or a blob list.
    input: PathBuf,
    /// Voxel side H in metres: voxel (i, j, k) is centred at (i, j, k)·H.
    #[arg(long, allow_hyphen_values = true)]
    voxel: f64,
    /// Output .vdb; with --frames, a pattern with one %0Nd for the frame number.
    #[arg(long)]
    out: PathBuf,
    /// For a scene: seconds to simulate, 0 or more, at most 1,000,000 steps of simulation.dt
    /// (default: the scene's render.time).
    #[arg(long, conflicts_with = "frames", allow_hyphen_values = true)]
    seconds: Option<f64>,
    /// For a scene: a sequence, frames k in the half-open range A..B at t = k/fps.
    #[arg(long, allow_hyphen_values = true)]
    frames: Option<String>,
    /// With --frames: frames per second.
    #[arg(long, requires = "frames", allow_hyphen_values = true)]
    fps: Option<f64>,
    /// With --frames: write only the frames with k mod N = I (I/N, 0 ≤ I < N).
    #[arg(long, requires = "frames", allow_hyphen_values = true)]
    shard: Option<String>,
    /// With --frames: write complete frames again, and over another run's.
    #[arg(long, requires = "frames")]
    force: bool,
    /// For a blob list: the moment it shows (s), recorded in the grids' metadata (a scene's
    /// volume records the time it was simulated to).
    #[arg(long, conflicts_with_all = ["seconds", "frames"], allow_hyphen_values = true)]
    time: Option<f64>,
}

pub fn volume(args: VolumeArgs) -> Result<(), Failure> {
    let start = Instant::now();
    if !(args.voxel.is_finite() && args.voxel > 0.0) {
        return Err(Failure::Input(format!(
            "--voxel: must be a voxel side in metres, greater than 0 (got {})",
            args.voxel
        )));
    }
    if let Some(frames) = &args.frames {
        let job = Sequence::parse(
            frames,
            args.fps,
            &args.out,
            args.shard.as_deref(),
            args.force,
            Output::Volume { voxel: args.voxel },
        )?;
        return match read_input(&args.input)? {
            Input::Scene(scene) => job.run(*scene, &args.input, start),
            Input::List(_) => Err(Failure::Input(format!(
                "--frames: needs a scene to simulate; {} is a blob list",
                args.input.display()
            ))),
        };
    }
    if let Some(s) = args.seconds {
        check_seconds(s)?;
    }
    let path = &args.input;
    let (list, time) = match read_input(path)? {
        Input::Scene(_) if args.time.is_some() => {
            return Err(Failure::Input(
                "--time: applies to blob lists; a scene's volume records the time it is simulated to (--seconds)".into(),
            ))
        }
        Input::Scene(scene) => {
            let seconds = args.seconds.unwrap_or(scene.render.still_time());
            let bad = |e: ParamError| Failure::Input(format!("{}: {e}", path.display()));
            let sim = simulated(*scene, seconds, bad)?;
            (sim.blob_list(), Some(sim.time()))
        }
        Input::List(_) if args.seconds.is_some() => {
            return Err(Failure::Input(
                "--seconds: applies to scenes only; this input is a blob list".into(),
            ))
        }
        Input::List(list) => {
            if let Some(t) = args.time {
                check_list_time(t)?;
            }
            (list, args.time)
        }
    };
    let build = VolumeBuild::new(&list, args.voxel, "--voxel").map_err(input)?;
    let volume: GasVolume = build.finish();
    let bytes = volume.to_vdb(time);
    write_atomically(&args.out, |w| std::io::Write::write_all(w, &bytes))?;
    let when = match time {
        Some(t) => format!("at t = {t:.2} s"),
        None => format!("from {}", path.display()),
    };
    eprintln!(
        "wrote {}: density{} of {} blobs {when}, {} active voxels of {} m, mass on the grid {:.6} of {:.6} ({} bytes), {}",
        args.out.display(),
        if volume.emission.is_some() { " and emission" } else { "" },
        grouped(list.blobs.len()),
        grouped(volume.active_voxels() as usize),
        args.voxel,
        volume.grid_mass(),
        volume.mass,
        grouped(bytes.len()),
        wall(start)
    );
    let lost = (volume.grid_mass() / volume.mass - 1.0).abs();
    if volume.mass > 0.0 && lost > 0.01 {
        eprintln!(
            "note: the grid holds {:.1} % {} mass than the blobs: voxels of {} m are too coarse for the narrowest blobs; a smaller --voxel samples them faithfully",
            100.0 * lost,
            if volume.grid_mass() < volume.mass { "less" } else { "more" },
            args.voxel
        );
    }
    Ok(())
}
