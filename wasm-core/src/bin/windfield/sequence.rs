//! `windfield render SCENE --frames A..B --fps F --out PATTERN [--shard I/N] [--force]`
//! (docs/FORMATS.md, the command line): one still per frame k in the half-open range A..B, the
//! scene at t = k/F, written to PATTERN with its one `%0Nd` replaced by k: PNG, or OpenEXR when
//! the pattern ends in `.exr`. `windfield volume SCENE --frames …` writes one OpenVDB volume per
//! frame the same way.
//!
//! A shard (`--shard I/N`) renders the frames with k mod N = I: it simulates once, from t = 0 to
//! its last frame that is not yet complete, rendering its frames as it passes them. The
//! simulation and the renderer are deterministic, so every shard writes exactly the bytes the
//! unsharded run would. A frame is written under a temporary name and renamed, so a killed run
//! leaves no half frame; the temporary name is the frame's own name with the process id and
//! a random number, so shards in parallel never share one. Frames already complete (a PNG of
//! the right size under the final name) are skipped unless `--force`.
//!
//! Beside the frames a manifest, the pattern's name with `.windfield.json` added
//! (`frames/f%04d.png.windfield.json`), records what makes their bytes (a fingerprint of the
//! normalised scene, the frame rate, the image size and the windfield version) and the frames
//! the run claims. A run that would write or skip a frame file another run claims, through
//! any spelling of the pattern, is refused unless `--force`, so frames of two runs never mix;
//! the claim is made under a folder lock, so two runs started at once cannot both pass
//! ([`super::claim`]). Every argument is checked before anything is written.
//!
//! The flags that ask for a sequence, `--seconds` (one still instead), `--frames`, `--fps`,
//! `--shard` and `--force`, are one set ([`SequenceArgs`]), flattened into `render` and
//! `volume`; each command gives them its own words in `--help` ([`SequenceWords`]).

use super::atomic::{create_parent, write_atomically};
use super::claim::{self, Manifest};
use super::failure::Failure;
use super::frames::{check_fps, FrameRange, Pattern, Shard};
use super::summary::{grouped, wall};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::marker::PhantomData;
use std::path::Path;
use std::time::Instant;
use windfield::export::exr::{self, ExrInfo};
use windfield::export::still::{self, StillFormat};
use windfield::export::vdb;
use windfield::export::volume::GasVolume;
use windfield::render::{RenderOptions, Renderer};
use windfield::{Scene, Simulation};

/// What `--help` says of each sequence flag, in one command's words (`render` renders
/// frames, `volume` writes them).
pub trait SequenceWords {
    const SECONDS: &'static str;
    const FRAMES: &'static str;
    const FPS: &'static str;
    const SHARD: &'static str;
    const FORCE: &'static str;
}

/// The sequence flags: one moment (`--seconds`) or the frames of a sequence (`--frames` with
/// `--fps`, and `--shard`, `--force`), each checked when the sequence is read
/// ([`Sequence::parse`]); `W` gives their help.
#[derive(Args)]
pub struct SequenceArgs<W: SequenceWords> {
    #[arg(long, conflicts_with = "frames", allow_hyphen_values = true, help = W::SECONDS)]
    pub seconds: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = W::FRAMES)]
    pub frames: Option<String>,
    #[arg(long, requires = "frames", allow_hyphen_values = true, help = W::FPS)]
    pub fps: Option<f64>,
    #[arg(long, requires = "frames", allow_hyphen_values = true, help = W::SHARD)]
    pub shard: Option<String>,
    #[arg(long, requires = "frames", help = W::FORCE)]
    pub force: bool,
    #[arg(skip)]
    words: PhantomData<W>,
}

/// The fingerprint of a sequence's scene: FNV-1a (128 bits) of the normalised scene's JSON,
/// its image size set to the frames' and its `render.time` (which a sequence does not use)
/// left out.
pub fn scene_fingerprint(scene: &Scene, width: u32, height: u32) -> String {
    let mut scene = scene.clone();
    scene.render.time = None;
    scene.render.image.width = width;
    scene.render.image.height = height;
    claim::fingerprint(scene.to_json().as_bytes())
}

/// What each frame of a sequence is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Frame {
    /// A still of `size`, width and height (each default the scene's), PNG or OpenEXR.
    Image {
        size: [Option<u32>; 2],
        format: StillFormat,
    },
    /// The gas as an OpenVDB volume of voxels of `voxel` m.
    Volume { voxel: f64 },
}

/// What `render --frames` (or `volume --frames`) was asked for, checked.
pub struct Sequence {
    pub range: FrameRange,
    pub fps: f64,
    pub pattern: Pattern,
    pub shard: Shard,
    pub force: bool,
    pub frame: Frame,
}

impl Sequence {
    /// Checks the sequence flags of `args` (`frames` its `--frames`) and the pattern `out`.
    pub fn parse<W: SequenceWords>(
        frames: &str,
        args: &SequenceArgs<W>,
        out: &Path,
        frame: Frame,
    ) -> Result<Self, Failure> {
        let input = Failure::Input;
        let range = FrameRange::parse(frames).map_err(input)?;
        let fps = args.fps.ok_or_else(|| {
            input("--fps: required with --frames (frames per second of the sequence)".into())
        })?;
        let fps = check_fps(fps).map_err(input)?;
        let text = out
            .to_str()
            .ok_or_else(|| input("--out: the pattern must be valid UTF-8".into()))?;
        let pattern = Pattern::parse(text).map_err(input)?;
        let shard = args
            .shard
            .as_deref()
            .map(Shard::parse)
            .transpose()
            .map_err(input)?
            .unwrap_or(Shard::ALL);
        Ok(Self {
            range,
            fps,
            pattern,
            shard,
            force: args.force,
            frame,
        })
    }

    /// Renders the shard's frames of `scene`, read from `input` (see the module's comment),
    /// and says what it wrote; `start` is when the command began (for the wall time).
    pub fn run(&self, scene: Scene, input: &Path, start: Instant) -> Result<(), Failure> {
        let manifest_scene = scene.clone();
        let mut sim = Simulation::new(scene).map_err(|e| Failure::Input(e.to_string()))?;
        let seconds = |k: u64| k as f64 / self.fps;
        // The budget holds for the whole range, so that every shard of it runs or none does.
        let last = (self.range.end - 1) as f64 / self.fps;
        sim.budgeted_steps(last)
            .map_err(|e| Failure::Input(e.to_string()))?;
        let settings = sim.render_settings();
        let size = match self.frame {
            Frame::Image {
                size: [width, height],
                ..
            } => {
                let image = &settings.image;
                Some((width.unwrap_or(image.width), height.unwrap_or(image.height)))
            }
            Frame::Volume { .. } => None,
        };
        let frames: Vec<u64> = self.shard.frames(self.range).collect();
        let what = format!(
            "{} ({}; frames {}..{} at {} fps{})",
            self.pattern.name(),
            match (size, self.frame) {
                (Some((w, h)), _) => format!("{w}×{h}"),
                (_, Frame::Volume { voxel }) => format!("voxels of {voxel} m"),
                _ => String::new(),
            },
            self.range.start,
            self.range.end,
            self.fps,
            self.shard.label()
        );
        if frames.is_empty() {
            eprintln!("nothing to write: no frame k of {what} has k mod N = I");
            return Ok(());
        }
        let voxel = match self.frame {
            Frame::Volume { voxel } => Some(voxel),
            Frame::Image { .. } => None,
        };
        self.claim(&manifest_scene, size.unwrap_or((0, 0)), voxel, input)?;
        let todo: Vec<u64> = frames
            .iter()
            .copied()
            .filter(|&k| self.force || !self.is_complete(&self.pattern.path(k), size))
            .collect();
        let done = frames.len() - todo.len();
        if todo.is_empty() {
            eprintln!(
                "nothing to write: all {} frames of {what} are complete (--force writes them again), {}",
                frames.len(),
                wall(start)
            );
            return Ok(());
        }
        for k in &todo {
            create_parent(&self.pattern.path(*k))?;
        }
        let bar = progress(todo.len() as u64);
        if done > 0 {
            let line = format!(
                "{done} of {} frames already complete, skipped",
                frames.len()
            );
            match &bar {
                Some(b) => b.println(line),
                None => eprintln!("{line}"),
            }
        }
        let mut blobs = 0;
        for &k in &todo {
            sim.run(sim.steps_for(seconds(k)) - sim.steps());
            let mut list = sim.blob_list();
            blobs = list.blobs.len();
            let bytes = match self.frame {
                Frame::Image { format, .. } => {
                    if let Some((width, height)) = size {
                        list.image.width = width;
                        list.image.height = height;
                    }
                    let renderer = Renderer::new(&list, None, RenderOptions::default())
                        .map_err(|e| Failure::Input(e.to_string()))?;
                    let image = renderer.render();
                    let info = ExrInfo {
                        camera: Some(list.camera.clone()),
                        time: Some(sim.time()),
                        fps: Some(self.fps),
                        note: format!("frame {k}"),
                    };
                    still::encode(&image, format, list.image.encoding, &info)
                        .map_err(Failure::Io)?
                }
                Frame::Volume { voxel } => GasVolume::of(&list, voxel, "--voxel")
                    .map_err(|e| {
                        Failure::Input(format!("frame {k} (t = {:.4} s): {e}", sim.time()))
                    })?
                    .to_vdb(Some(sim.time())),
            };
            let path = self.pattern.path(k);
            write_atomically(&path, |w| std::io::Write::write_all(w, &bytes))?;
            let line = format!(
                "frame {k} (t = {:.4} s, {} blobs) -> {}",
                sim.time(),
                list.blobs.len(),
                path.display()
            );
            match &bar {
                Some(b) => {
                    b.set_message(line);
                    b.inc(1);
                }
                None => eprintln!("{line}"),
            }
        }
        if let Some(b) = bar {
            b.finish_and_clear();
        }
        let skipped = match done {
            0 => String::new(),
            n => format!(", {n} complete ones skipped"),
        };
        let plural = if todo.len() == 1 { "" } else { "s" };
        eprintln!(
            "wrote {} frame{plural} {what}{skipped}: {} blobs at t = {:.2} s in the last, {}",
            todo.len(),
            grouped(blobs),
            sim.time(),
            wall(start)
        );
        Ok(())
    }

    /// Claims the range's frame files for this run, its identity that of `scene` at the
    /// sequence's rate and `size` ([`claim::claim_frames`]): the whole range, whatever the
    /// shard, so the shards of one run share the claim.
    pub fn claim(
        &self,
        scene: &Scene,
        size: (u32, u32),
        voxel: Option<f64>,
        input: &Path,
    ) -> Result<(), Failure> {
        let (folder, names) = self.pattern.folder_and_names();
        let mut run = Manifest::new(
            scene_fingerprint(scene, size.0, size.1),
            self.fps,
            size,
            &names,
            self.range,
            input,
        );
        run.voxel = voxel;
        claim::claim_frames(&folder, &names, self.range, &run, self.force)
    }
}

/// A progress bar with an ETA on stderr when it is a terminal; none otherwise (one line a frame).
fn progress(len: u64) -> Option<ProgressBar> {
    if !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = ProgressBar::new(len);
    let style = ProgressStyle::with_template(
        "{bar:30} {pos}/{len} frames, {elapsed} elapsed, ETA {eta}  {msg}",
    )
    .expect("the template is valid");
    bar.set_style(style);
    Some(bar)
}

impl Sequence {
    /// Whether `path` holds a completed frame: a whole still of `size` (PNG or OpenEXR), or a
    /// whole OpenVDB file.
    fn is_complete(&self, path: &Path, size: Option<(u32, u32)>) -> bool {
        match (self.frame, size) {
            (Frame::Volume { .. }, _) => {
                std::fs::read(path).is_ok_and(|bytes| vdb::is_complete(&bytes))
            }
            (
                Frame::Image {
                    format: StillFormat::Exr,
                    ..
                },
                Some((w, h)),
            ) => std::fs::read(path)
                .is_ok_and(|bytes| exr::read_rgba(&bytes).is_ok_and(|(a, b, _)| (a, b) == (w, h))),
            (_, Some((w, h))) => is_complete(path, w, h),
            _ => false,
        }
    }
}

/// Whether `path` holds a whole PNG of `width × height` (what a completed frame is): its image
/// data and every chunk after it, to the closing IEND, read without an error.
pub fn is_complete(path: &Path, width: u32, height: u32) -> bool {
    let Ok(file) = std::fs::File::open(path) else {
        return false;
    };
    let decoder = png::Decoder::new(std::io::BufReader::new(file));
    let Ok(mut reader) = decoder.read_info() else {
        return false;
    };
    let info = reader.info();
    if (info.width, info.height) != (width, height) {
        return false;
    }
    let mut buf = vec![0; reader.output_buffer_size().unwrap_or(0)];
    reader.next_frame(&mut buf).is_ok() && reader.finish().is_ok()
}
