//! `windfield render`: a still from the CPU reference renderer (the image model of Eqs. 22–28,
//! docs/FORMATS.md), of a blob list or of a scene simulated first, as PNG or OpenEXR; with
//! `--frames`, a scene's sequence of them ([`super::sequence`]).

use super::atomic::write_atomically;
use super::failure::Failure;
use super::formats::{image_format, IMAGES};
use super::input::{read_input, Input};
use super::moment::{blob_list_at, check_seconds};
use super::sequence::{Frame, Sequence, SequenceArgs, SequenceWords};
use super::summary::{grouped, wall};
use clap::Args;
use std::path::PathBuf;
use std::time::Instant;
use windfield::export::exr::ExrInfo;
use windfield::export::still;
use windfield::render::{RenderOptions, Renderer};
use windfield::scene::blob_list::Background;
use windfield::scene::limits::MAX_IMAGE_SIDE;

#[derive(Args)]
pub struct RenderArgs {
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
    #[command(flatten)]
    sequence: SequenceArgs<Render>,
    /// A transparent background (render.background = "transparent"): the image gets an alpha
    /// channel, 1 − T(∞) over the gas and 1 on objects.
    #[arg(long)]
    alpha: bool,
    /// For a blob list: the moment it shows (s), recorded in an EXR's header (a scene's
    /// still records the time it was simulated to).
    #[arg(long, conflicts_with_all = ["seconds", "frames"], allow_hyphen_values = true)]
    time: Option<f64>,
}

/// `render`'s words for the sequence flags.
pub struct Render;

impl SequenceWords for Render {
    const SECONDS: &'static str = "For a scene: seconds to simulate before rendering, 0 or more, \
        at most 1,000,000 steps of simulation.dt (default: the scene's render.time, 3 when it \
        has none)";
    const FRAMES: &'static str =
        "For a scene: a sequence, frames k in the half-open range A..B, frame k at t = k/fps";
    const FPS: &'static str = "With --frames: frames per second of the sequence";
    const SHARD: &'static str =
        "With --frames: render only the frames with k mod N = I (I/N, 0 ≤ I < N)";
    const FORCE: &'static str = "With --frames: render frames that are already complete again, \
        and over frames that another run (another scene, frame rate or size) left under the \
        pattern";
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
    let job = Sequence::parse(frames, &args.sequence, out, Frame::Image { size, format })?;
    let input = read_input(&args.input)?;
    IMAGES.check(out)?;
    match input {
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

pub fn run(args: RenderArgs) -> Result<(), Failure> {
    let start = Instant::now();
    if let Some(frames) = &args.sequence.frames {
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
    if let Some(seconds) = args.sequence.seconds {
        check_seconds(seconds)?;
    }
    let input = read_input(&args.input)?;
    IMAGES.check(&out)?;
    let (list, time) = blob_list_at(
        input,
        &args.input,
        args.sequence.seconds,
        args.time,
        "still",
        args.alpha,
    )?;
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
