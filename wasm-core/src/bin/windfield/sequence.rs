//! `windfield render SCENE --frames A..B --fps F --out PATTERN [--shard I/N] [--force]`
//! (DESIGN §7): one PNG per frame k in the half-open range A..B, the scene at t = k/F, written
//! to PATTERN with its one `%0Nd` replaced by k.
//!
//! A shard (`--shard I/N`) renders the frames with k mod N = I: it simulates once, from t = 0 to
//! its last frame that is not yet complete, rendering its frames as it passes them. The
//! simulation and the renderer are deterministic, so every shard writes exactly the bytes the
//! unsharded run would. A frame is written under a temporary name and renamed, so a killed run
//! leaves no half frame; frames already complete (a PNG of the right size under the final
//! name) are skipped unless `--force`. Every argument is checked before anything is written.

use super::{write_atomically, Failure};
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use windfield::render::{encode_png, RenderOptions, Renderer};
use windfield::{Scene, Simulation};

/// The frames A..B (half-open, A < B).
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
}

/// Shard I of N: the frames with k mod N = I.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shard {
    pub index: u64,
    pub count: u64,
}

impl Shard {
    /// Parses `I/N` with 0 ≤ I < N.
    pub fn parse(text: &str) -> Result<Self, String> {
        let bad = |why: &str| format!("--shard: expected I/N with 0 ≤ I < N ({why}; got {text:?})");
        let (i, n) = text.split_once('/').ok_or_else(|| bad("no '/'"))?;
        let number = |s: &str| {
            s.trim()
                .parse::<u64>()
                .map_err(|_| bad("not a whole number"))
        };
        let (index, count) = (number(i)?, number(n)?);
        if count == 0 || index >= count {
            return Err(bad("I must be below N"));
        }
        Ok(Self { index, count })
    }

    /// The whole run as one shard.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// This shard's frames of `range`, in order.
    pub fn frames(self, range: FrameRange) -> impl Iterator<Item = u64> {
        let first = range.start + (self.index + self.count - range.start % self.count) % self.count;
        (first..range.end).step_by(self.count as usize)
    }
}

/// What `render --frames` was asked for, checked.
pub struct Sequence {
    pub range: FrameRange,
    pub fps: f64,
    pub pattern: Pattern,
    pub shard: Shard,
    pub force: bool,
    pub size: Option<(u32, u32)>,
}

impl Sequence {
    /// Checks the flags; `frames` and `out` as given.
    pub fn parse(
        frames: &str,
        fps: Option<f64>,
        out: &Path,
        shard: Option<&str>,
        force: bool,
        size: Option<(u32, u32)>,
    ) -> Result<Self, Failure> {
        let input = Failure::Input;
        let range = FrameRange::parse(frames).map_err(input)?;
        let fps = fps.ok_or_else(|| {
            input("--fps: required with --frames (frames per second of the sequence)".into())
        })?;
        if !(fps.is_finite() && fps > 0.0 && fps <= 1e4) {
            return Err(input(format!(
                "--fps: must be a number greater than 0 and at most 10000 (got {fps})"
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
            size,
        })
    }

    /// Renders the shard's frames of `scene` (see the module's comment).
    pub fn run(&self, scene: Scene) -> Result<(), Failure> {
        let mut sim = Simulation::new(scene).map_err(|e| Failure::Input(e.to_string()))?;
        let seconds = |k: u64| k as f64 / self.fps;
        // The budget holds for the whole range, so that every shard of it runs or none does.
        let last = (self.range.end - 1) as f64 / self.fps;
        sim.budgeted_steps(last)
            .map_err(|e| Failure::Input(e.to_string()))?;
        let settings = sim.render_settings();
        let (width, height) = self
            .size
            .unwrap_or((settings.image.width, settings.image.height));
        // Checks the image size before anything is written.
        let mut probe = sim.blob_list();
        probe.image.width = width;
        probe.image.height = height;
        probe.blobs.clear();
        Renderer::new(&probe, None, RenderOptions::default()).map_err(|e| {
            Failure::Input(match e.path.as_str() {
                "image.width" => format!("--width: {e}"),
                "image.height" => format!("--height: {e}"),
                _ => e.to_string(),
            })
        })?;
        let frames: Vec<u64> = self.shard.frames(self.range).collect();
        let todo: Vec<u64> = frames
            .iter()
            .copied()
            .filter(|&k| self.force || !is_complete(&self.pattern.path(k), width, height))
            .collect();
        let done = frames.len() - todo.len();
        if todo.is_empty() {
            eprintln!(
                "all {} frames of this shard are complete (--force renders them again)",
                frames.len()
            );
            return Ok(());
        }
        for k in &todo {
            if let Some(dir) = self
                .pattern
                .path(*k)
                .parent()
                .filter(|d| !d.as_os_str().is_empty())
            {
                std::fs::create_dir_all(dir)
                    .map_err(|e| Failure::Io(format!("{}: {e}", dir.display())))?;
            }
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
        for &k in &todo {
            sim.run(sim.steps_for(seconds(k)) - sim.steps());
            let mut list = sim.blob_list();
            list.image.width = width;
            list.image.height = height;
            let renderer = Renderer::new(&list, None, RenderOptions::default())
                .map_err(|e| Failure::Input(e.to_string()))?;
            let image = renderer.render();
            let png = encode_png(width, height, &image.to_rgb8(list.image.encoding))
                .map_err(|e| Failure::Io(e.to_string()))?;
            let path = self.pattern.path(k);
            write_atomically(&path, |w| std::io::Write::write_all(w, &png))?;
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
            b.finish_with_message(format!("{} frames rendered", todo.len()));
        }
        Ok(())
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
                .all(|k| k % 4 == i));
        }
        all.sort_unstable();
        assert_eq!(all, (5..23).collect::<Vec<_>>());
        assert_eq!(Shard::ALL.frames(range).count(), 18);
    }
}
