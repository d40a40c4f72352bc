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

use super::claim::{self, Manifest, Names};
use super::{create_parent, grouped, wall, write_atomically, Failure};
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;
use windfield::export::exr::{self, ExrInfo};
use windfield::export::still::{self, StillFormat};
use windfield::export::vdb;
use windfield::export::volume::GasVolume;
use windfield::render::{RenderOptions, Renderer};
use windfield::{Scene, Simulation};

/// Most frames one range may hold (at 24 fps, eleven and a half hours).
pub const MAX_FRAMES: u64 = 1_000_000;

/// The frames A..B (half-open, A < B, at most [`MAX_FRAMES`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameRange {
    pub start: u64,
    pub end: u64,
}

impl FrameRange {
    /// Parses `A..B`.
    pub fn parse(text: &str) -> Result<Self, String> {
        let bad = |why: &str| {
            format!("--frames: expected A..B, whole frame numbers with A < B ({why}; got {text:?})")
        };
        let (a, b) = text.split_once("..").ok_or_else(|| bad("no '..'"))?;
        let number = |s: &str| {
            s.trim()
                .parse::<u64>()
                .map_err(|_| bad("not a whole number"))
        };
        let (start, end) = (number(a)?, number(b)?);
        if start >= end {
            return Err(bad("the range is empty"));
        }
        if end - start > MAX_FRAMES {
            return Err(bad(&format!("at most {MAX_FRAMES} frames in one range")));
        }
        Ok(Self { start, end })
    }
}

/// An output pattern: a path with one `%0Nd` (or `%d`) for the frame number; `%%` is a `%`.
#[derive(Debug, Clone, PartialEq)]
pub struct Pattern {
    prefix: String,
    width: usize,
    suffix: String,
}

impl Pattern {
    pub fn parse(text: &str) -> Result<Self, String> {
        let bad = |why: &str| {
            format!("--out: a frame pattern needs exactly one %0Nd (N from 1 to 9) or %d for the frame number, as in frames/f%04d.png ({why}; got {text:?})")
        };
        let mut prefix = String::new();
        let mut suffix = String::new();
        let mut width = None;
        let mut chars = text.chars().peekable();
        while let Some(c) = chars.next() {
            let out = if width.is_some() {
                &mut suffix
            } else {
                &mut prefix
            };
            if c != '%' {
                out.push(c);
                continue;
            }
            match chars.next() {
                Some('%') => out.push('%'),
                Some('d') if width.is_none() => width = Some(1),
                Some('0') if width.is_none() => {
                    let n = chars
                        .next()
                        .and_then(|d| d.to_digit(10))
                        .filter(|&d| (1..=9).contains(&d))
                        .ok_or_else(|| bad("a width must be one digit from 1 to 9"))?;
                    if chars.next() != Some('d') {
                        return Err(bad("the width must be followed by d"));
                    }
                    width = Some(n as usize);
                }
                Some('d' | '0') => return Err(bad("more than one frame number")),
                _ => return Err(bad("a % that is neither %0Nd, %d nor %%")),
            }
        }
        let width = width.ok_or_else(|| bad("no frame number"))?;
        if prefix.is_empty() && suffix.is_empty() {
            return Err(bad("no file name around it"));
        }
        if suffix.contains(std::path::is_separator) {
            return Err(bad(
                "the frame number must be in the file's name, not a folder's",
            ));
        }
        Ok(Self {
            prefix,
            width,
            suffix,
        })
    }

    /// The path of frame `k`.
    pub fn path(&self, k: u64) -> PathBuf {
        PathBuf::from(format!(
            "{}{k:0w$}{}",
            self.prefix,
            self.suffix,
            w = self.width
        ))
    }

    /// The pattern as a name, its frame number written `%0Nd` (`%d`), a `%%` as `%`.
    pub fn name(&self) -> String {
        let number = match self.width {
            1 => "%d".to_string(),
            w => format!("%0{w}d"),
        };
        format!("{}{number}{}", self.prefix, self.suffix)
    }

    /// The folder the frames lie in (`.` for none) and their file names there.
    pub fn folder_and_names(&self) -> (PathBuf, Names) {
        let split = self
            .prefix
            .rfind(std::path::is_separator)
            .map_or(0, |i| i + 1);
        let folder = match &self.prefix[..split] {
            "" => PathBuf::from("."),
            dir => PathBuf::from(dir),
        };
        let names = Names {
            prefix: self.prefix[split..].to_string(),
            width: self.width,
            suffix: self.suffix.clone(),
        };
        (folder, names)
    }
}

/// Shard I of N: the frames with k mod N = I. Any N a 128-bit integer holds (N above 2^63,
/// or above every frame number, included); k mod N is taken without overflow.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shard {
    pub index: u128,
    pub count: u128,
}

impl Shard {
    /// Parses `I/N` with 0 ≤ I < N.
    pub fn parse(text: &str) -> Result<Self, String> {
        let bad = |why: &str| format!("--shard: expected I/N with 0 ≤ I < N ({why}; got {text:?})");
        let (i, n) = text.split_once('/').ok_or_else(|| bad("no '/'"))?;
        let number = |s: &str| {
            s.trim()
                .parse::<u128>()
                .map_err(|_| bad("not a whole number below 2^128"))
        };
        let (index, count) = (number(i)?, number(n)?);
        if count == 0 || index >= count {
            return Err(bad("I must be below N"));
        }
        Ok(Self { index, count })
    }

    /// The whole run as one shard.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// This shard's frames of `range`, in order: the first k ≥ A with k mod N = I, then every
    /// N-th, while below B.
    pub fn frames(self, range: FrameRange) -> impl Iterator<Item = u64> {
        let (start, end, n) = (range.start as u128, range.end as u128, self.count);
        let r = start % n;
        // The distance from A to the next k with k mod N = I, in [0, N).
        let ahead = if self.index >= r {
            self.index - r
        } else {
            n - (r - self.index)
        };
        let below_end = move |k: &u128| *k < end;
        let first = start.checked_add(ahead).filter(below_end);
        std::iter::successors(first, move |&k| k.checked_add(n).filter(below_end)).map(|k| k as u64)
    }

    /// " of shard I/N", or nothing for the whole run.
    fn label(self) -> String {
        if self == Self::ALL {
            String::new()
        } else {
            format!(" of shard {}/{}", self.index, self.count)
        }
    }
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
pub enum Output {
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
    pub output: Output,
}

impl Sequence {
    /// Checks the flags; `frames` and `out` as given.
    pub fn parse(
        frames: &str,
        fps: Option<f64>,
        out: &Path,
        shard: Option<&str>,
        force: bool,
        output: Output,
    ) -> Result<Self, Failure> {
        let input = Failure::Input;
        let range = FrameRange::parse(frames).map_err(input)?;
        let fps = fps.ok_or_else(|| {
            input("--fps: required with --frames (frames per second of the sequence)".into())
        })?;
        if !(fps.is_finite() && fps > 0.0 && fps <= 1e4) {
            return Err(input(format!(
                "--fps: must be a number greater than 0 and at most 10000 (got {})",
                windfield::error::number(fps)
            )));
        }
        let text = out
            .to_str()
            .ok_or_else(|| input("--out: the pattern must be valid UTF-8".into()))?;
        let pattern = Pattern::parse(text).map_err(input)?;
        let shard = shard
            .map(Shard::parse)
            .transpose()
            .map_err(input)?
            .unwrap_or(Shard::ALL);
        Ok(Self {
            range,
            fps,
            pattern,
            shard,
            force,
            output,
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
        let size = match self.output {
            Output::Image {
                size: [width, height],
                ..
            } => {
                let image = &settings.image;
                Some((width.unwrap_or(image.width), height.unwrap_or(image.height)))
            }
            Output::Volume { .. } => None,
        };
        let frames: Vec<u64> = self.shard.frames(self.range).collect();
        let what = format!(
            "{} ({}; frames {}..{} at {} fps{})",
            self.pattern.name(),
            match (size, self.output) {
                (Some((w, h)), _) => format!("{w}×{h}"),
                (_, Output::Volume { voxel }) => format!("voxels of {voxel} m"),
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
        let voxel = match self.output {
            Output::Volume { voxel } => Some(voxel),
            Output::Image { .. } => None,
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
                "nothing to write: all {} frames of {what} are complete (--force renders them again), {}",
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
            let bytes = match self.output {
                Output::Image { format, .. } => {
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
                Output::Volume { voxel } => GasVolume::of(&list, voxel, "--voxel")
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
        match (self.output, size) {
            (Output::Volume { .. }, _) => {
                std::fs::read(path).is_ok_and(|bytes| vdb::is_complete(&bytes))
            }
            (
                Output::Image {
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

/// Whether `path` holds a whole PNG of `width × height` (what a completed frame is).
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
    reader.next_frame(&mut buf).is_ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_patterns_and_shards_parse_or_say_why_not() {
        assert_eq!(
            FrameRange::parse("3..10"),
            Ok(FrameRange { start: 3, end: 10 })
        );
        for bad in ["10..3", "4..4", "a..b", "3-10", "-1..2", "1.5..3"] {
            assert!(
                FrameRange::parse(bad).unwrap_err().starts_with("--frames:"),
                "{bad}"
            );
        }
        let p = Pattern::parse("out/f%04d.png").unwrap();
        assert_eq!(p.path(7), PathBuf::from("out/f0007.png"));
        assert_eq!(p.path(12345), PathBuf::from("out/f12345.png"));
        assert_eq!(
            Pattern::parse("f%d.png").unwrap().path(42),
            PathBuf::from("f42.png")
        );
        assert_eq!(
            Pattern::parse("100%%/f%03d.png").unwrap().path(5),
            PathBuf::from("100%/f005.png")
        );
        for bad in [
            "f.png",
            "f%04d%04d.png",
            "f%4d.png",
            "f%010d.png",
            "f%s.png",
            "%d",
            "f%04x.png",
            "f%",
        ] {
            assert!(
                Pattern::parse(bad).unwrap_err().starts_with("--out:"),
                "{bad}"
            );
        }
        assert_eq!(Shard::parse("2/4"), Ok(Shard { index: 2, count: 4 }));
        for bad in ["4/4", "1/0", "x/2", "2", "-1/3"] {
            assert!(
                Shard::parse(bad).unwrap_err().starts_with("--shard:"),
                "{bad}"
            );
        }
    }

    #[test]
    fn the_shards_of_a_range_are_its_frames_once_each() {
        let range = FrameRange { start: 5, end: 23 };
        let mut all: Vec<u64> = (0..4)
            .flat_map(|i| Shard { index: i, count: 4 }.frames(range))
            .collect();
        for i in 0..4 {
            assert!(Shard { index: i, count: 4 }
                .frames(range)
                .all(|k| k as u128 % 4 == i));
        }
        all.sort_unstable();
        assert_eq!(all, (5..23).collect::<Vec<_>>());
        assert_eq!(Shard::ALL.frames(range).count(), 18);
    }

    #[test]
    fn shard_counts_beyond_2_to_the_63_neither_wrap_nor_skip() {
        let max = u64::MAX as u128;
        for (text, range, want) in [
            // I + N overflowed 64 bits: shard 5 of 2^64 − 1 took frame 4.
            (format!("5/{max}"), (0, 12), vec![5]),
            (format!("{}/{max}", max - 1), (0, 12), vec![]),
            (format!("3/{}", 1u128 << 64), (0, 12), vec![3]),
            (format!("0/{}", (1u128 << 63) + 1), (1, 12), vec![]),
            (
                format!("{}/{}", u64::MAX - 1, max),
                (u64::MAX - 3, u64::MAX),
                vec![u64::MAX - 1],
            ),
            (format!("1/{}", u128::MAX), (0, 3), vec![1]),
            (
                "2/3".to_string(),
                (u64::MAX - 5, u64::MAX),
                vec![u64::MAX - 4, u64::MAX - 1],
            ),
        ] {
            let shard = Shard::parse(&text).unwrap();
            let range = FrameRange {
                start: range.0,
                end: range.1,
            };
            assert_eq!(shard.frames(range).collect::<Vec<_>>(), want, "{text}");
        }
        assert!(Shard::parse(&format!("0/{}", u128::MAX as f64 * 2.0)).is_err());
    }

    #[test]
    fn a_range_holds_at_most_a_million_frames() {
        assert!(FrameRange::parse("0..1000000").is_ok());
        let e = FrameRange::parse("5..1000006").unwrap_err();
        assert!(e.contains("at most 1000000 frames"), "{e}");
        assert!(FrameRange::parse(&format!("0..{}", u64::MAX)).is_err());
    }

    #[test]
    fn the_manifest_lies_beside_the_frames_and_fingerprints_differ() {
        let manifest = |p: &str| {
            let (folder, names) = Pattern::parse(p).unwrap().folder_and_names();
            claim::manifest_path(&folder, &names)
        };
        assert_eq!(
            manifest("seq/frame.%03d"),
            PathBuf::from("seq/frame.%03d.windfield.json")
        );
        assert_eq!(
            manifest("100%%/f%d.png"),
            PathBuf::from("100%/f%d.png.windfield.json")
        );
        assert_ne!(
            claim::fingerprint(b"{\"seed\": 1}"),
            claim::fingerprint(b"{\"seed\": 2}")
        );
        assert_eq!(claim::fingerprint(b""), "6c62272e07bb014262b821756295c58d");
        let (folder, names) = Pattern::parse("a/b/f%04d.png").unwrap().folder_and_names();
        assert_eq!(
            (folder, names.spelling()),
            (PathBuf::from("a/b/"), "f%04d.png".into())
        );
        let (folder, names) = Pattern::parse("x%d").unwrap().folder_and_names();
        assert_eq!(folder, PathBuf::from("."));
        assert_eq!(names.name(3), "x3");
        assert!(Pattern::parse("frames%d/f.png")
            .unwrap_err()
            .contains("not a folder's"));
    }
}
