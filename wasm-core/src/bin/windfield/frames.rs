//! How the frames of a sequence are numbered and named (docs/SEQUENCES.md): the range `A..B`
//! of `--frames`, the pattern of `--out` with its one `%0Nd`, the shard `I/N` of `--shard`,
//! and the file names a pattern gives in its folder (what a manifest claims: `claim`).

use std::path::{Path, PathBuf};
use windfield::scene::limits::MAX_FPS;

/// Most frames one range may hold (at 24 fps, eleven and a half hours).
pub const MAX_FRAMES: u64 = 1_000_000;

/// A frame rate `--fps` (frames a second): greater than 0 and at most [`MAX_FPS`].
pub fn check_fps(fps: f64) -> Result<f64, String> {
    if fps.is_finite() && fps > 0.0 && fps <= MAX_FPS {
        Ok(fps)
    } else {
        Err(format!(
            "--fps: must be a number greater than 0 and at most {MAX_FPS} (got {})",
            windfield::error::number(fps)
        ))
    }
}

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
    pub fn label(self) -> String {
        if self == Self::ALL {
            String::new()
        } else {
            format!(" of shard {}/{}", self.index, self.count)
        }
    }
}

/// Frame file names in one folder: `prefix`, the frame number zero-padded to `width` digits,
/// `suffix` (the file-name part of a pattern).
#[derive(Debug, Clone, PartialEq)]
pub struct Names {
    pub prefix: String,
    pub width: usize,
    pub suffix: String,
}

impl Names {
    /// The file name of frame `k`.
    pub fn name(&self, k: u64) -> String {
        format!("{}{k:0w$}{}", self.prefix, self.suffix, w = self.width)
    }

    /// The frame whose file this name is, if it is one: the name read back exactly.
    pub fn number(&self, name: &str) -> Option<u64> {
        let digits = name
            .strip_prefix(&self.prefix)?
            .strip_suffix(&self.suffix)?;
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let k: u64 = digits.parse().ok()?;
        (format!("{k:0w$}", w = self.width) == digits).then_some(k)
    }

    /// The pattern spelled as `--out` takes it (`f%04d.png`, a literal `%` as `%%`).
    pub fn spelling(&self) -> String {
        let number = match self.width {
            1 => "%d".to_string(),
            w => format!("%0{w}d"),
        };
        let escape = |s: &str| s.replace('%', "%%");
        format!("{}{number}{}", escape(&self.prefix), escape(&self.suffix))
    }

    /// The pattern as a name (`f%04d.png`, a `%` written once): its manifest's name without
    /// the suffix.
    pub fn display(&self) -> String {
        let number = match self.width {
            1 => "%d".to_string(),
            w => format!("%0{w}d"),
        };
        format!("{}{number}{}", self.prefix, self.suffix)
    }

    /// Reads a spelling back (a manifest's `pattern`).
    pub fn parse(spelling: &str) -> Option<Self> {
        let pattern = Pattern::parse(spelling).ok()?;
        let (folder, names) = pattern.folder_and_names();
        (folder == Path::new(".")).then_some(names)
    }
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
    fn names_read_back_only_their_own_spelling() {
        let padded = Names {
            prefix: "f".into(),
            width: 3,
            suffix: ".png".into(),
        };
        let plain = Names {
            prefix: "f".into(),
            width: 1,
            suffix: ".png".into(),
        };
        assert_eq!(padded.name(7), "f007.png");
        assert_eq!(padded.number("f007.png"), Some(7));
        assert_eq!(padded.number("f7.png"), None);
        assert_eq!(padded.number("f1234.png"), Some(1234));
        assert_eq!(plain.number("f007.png"), None);
        assert_eq!(plain.number("f100.png"), Some(100));
        assert_eq!(padded.number("f100.png"), Some(100));
        for bad in ["f.png", "g007.png", "f007.jpg", "f0x7.png", "f+07.png"] {
            assert_eq!(padded.number(bad), None, "{bad}");
        }
        let percent = Names {
            prefix: "50%".into(),
            width: 2,
            suffix: "".into(),
        };
        assert_eq!(percent.spelling(), "50%%%02d");
        assert_eq!(Names::parse(&percent.spelling()), Some(percent));
    }
}
