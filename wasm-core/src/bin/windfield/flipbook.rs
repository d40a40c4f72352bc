//! `windfield flipbook` (docs/FORMATS.md, flipbooks): a scene's frames as one sprite sheet
//! (PNG or EXR, with alpha) and its description beside it, made by the core's `export` module
//! (the browser's worker calls the same code).

use super::atomic::{write_together, Output};
use super::failure::Failure;
use super::formats::{image_format, IMAGES};
use super::frames::FrameRange;
use super::input::read_scene;
use super::summary::wall;
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;
use windfield::export::flipbook::{parse_pair, FlipbookJob, FlipbookSpec, SettingNames};
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

pub fn run(args: FlipbookArgs) -> Result<(), Failure> {
    let start = Instant::now();
    let range = FrameRange::parse(&args.frames).map_err(Failure::Input)?;
    let (columns, rows) = parse_pair(&args.grid, "--grid", "C×R", u32::MAX).map_err(input)?;
    let (tile_width, tile_height) =
        parse_pair(&args.tile, "--tile", "W×H", MAX_IMAGE_SIDE).map_err(input)?;
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
    IMAGES.check(Path::new(&name))?;
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
    write_together(&[
        Output {
            path: &args.out,
            write: Box::new(|w| std::io::Write::write_all(w, &bytes)),
        },
        Output {
            path: &json_path,
            write: Box::new(|w| std::io::Write::write_all(w, json.as_bytes())),
        },
        Output {
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
