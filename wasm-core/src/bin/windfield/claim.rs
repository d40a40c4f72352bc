//! Which run the frames in a folder belong to (docs/SEQUENCES.md, the manifest).
//!
//! A run (one scene, frame rate, image size and windfield version: its *identity*) claims the
//! frame files it will write or skip, by name, in a manifest beside them: the pattern's name
//! with `.windfield.json` added (`f%04d.png.windfield.json`), holding the identity, the
//! pattern's file name and the frame ranges claimed. Claims are per file, not per spelling of
//! the pattern: `f%03d.png` and `f%d.png` both name `f100.png`, so a run through either is
//! checked against the manifests of both. The rule:
//!
//! - A run may write or skip only frame files that no other run's manifest claims; one that
//!   would is refused, naming both runs (`--force` takes those frames over: they are deleted
//!   and the other run's claim on them dropped, so that nothing skips them as complete).
//! - Runs of one identity share their claims: the same run resumed (after a crash, with any
//!   spelling of the pattern) and the shards of one run (`--shard I/N`, each claiming the whole
//!   range) skip each other's complete frames.
//! - A frame file in the run's range that no manifest claims (written by another tool, or
//!   whose manifest was removed) is refused too, unless `--force`: it is not known to be this
//!   run's.
//!
//! Claiming is atomic: a run reads the folder's manifests and writes its own while it holds
//! the folder's lock, `.windfield.lock`, created with create-new semantics and removed when
//! the claim is written (milliseconds). Two runs started at once therefore claim one after the
//! other, and the second sees the first's manifest. A lock left by a run that died holding it
//! is taken over by a run of the same identity (its resume, or another shard), or by any run on
//! the same host once the holder's process is gone; otherwise a run waits up to
//! [`LOCK_WAIT`] and then stops, saying which run holds the lock.

use super::atomic::write_atomically;
use super::failure::Failure;
use super::frames::{FrameRange, Names};
use serde::{Deserialize, Serialize};
use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The manifest's format.
pub const MANIFEST_FORMAT: &str = "windfield-sequence/2";

/// The name manifests end with.
const MANIFEST_SUFFIX: &str = ".windfield.json";

/// The folder lock's file name.
pub const LOCK_NAME: &str = ".windfield.lock";

/// How long a run waits for another run's claim to finish before it stops.
pub const LOCK_WAIT: Duration = Duration::from_secs(60);

fn is_zero(v: &u32) -> bool {
    *v == 0
}

/// What makes a sequence's bytes, and the frames it claims (see the module's comment).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// The manifest's own format, [`MANIFEST_FORMAT`].
    pub format: String,
    /// The version of windfield that rendered the frames.
    pub windfield: String,
    /// FNV-1a (128 bits) of the normalised scene's JSON, its image size set to the frames'
    /// and its `render.time` (which a sequence does not use) left out.
    pub scene: String,
    /// Frames per second: frame k is the scene at t = k / fps.
    pub fps: f64,
    /// Image size in pixels (absent, read as 0, for a sequence of volumes).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub width: u32,
    #[serde(default, skip_serializing_if = "is_zero")]
    pub height: u32,
    /// Voxel side in metres, for a sequence of volumes (`volume --frames`); absent for stills.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub voxel: Option<f64>,
    /// The frames' file names, spelled as `--out` takes them (`f%04d.png`).
    pub pattern: String,
    /// The frame numbers claimed: half-open ranges [A, B), sorted and disjoint.
    pub frames: Vec<[u64; 2]>,
    /// The input the run was started with, to name the run in messages.
    pub input: String,
}

impl Manifest {
    /// A run's manifest: its identity, and the frames `range` of `names` claimed.
    pub fn new(
        scene_fingerprint: String,
        fps: f64,
        (width, height): (u32, u32),
        names: &Names,
        range: FrameRange,
        input: &Path,
    ) -> Self {
        Self {
            format: MANIFEST_FORMAT.into(),
            windfield: env!("CARGO_PKG_VERSION").into(),
            scene: scene_fingerprint,
            fps,
            width,
            height,
            voxel: None,
            pattern: names.spelling(),
            frames: vec![[range.start, range.end]],
            input: input.display().to_string(),
        }
    }

    /// Whether `other` is the same run: the same scene, frame rate, size and version (the
    /// pattern, the frames and the input aside).
    pub fn same_run(&self, other: &Self) -> bool {
        self.differences(other).is_empty()
    }

    /// A key of the run's identity, for the folder lock.
    fn run_key(&self) -> String {
        format!(
            "{}/{}/{}x{}/{:?}/{}",
            self.scene, self.fps, self.width, self.height, self.voxel, self.windfield
        )
    }

    /// How `self` differs from `other` (what this run would write), in words.
    pub fn differences(&self, other: &Self) -> Vec<String> {
        let mut out = Vec::new();
        if self.scene != other.scene {
            out.push("another scene".to_string());
        }
        if self.fps != other.fps {
            out.push(format!("{} fps, not {}", self.fps, other.fps));
        }
        let size = |m: &Self| match m.voxel {
            Some(v) => format!("volumes of {v} m voxels"),
            None => format!("{}×{}", m.width, m.height),
        };
        if (self.width, self.height, self.voxel) != (other.width, other.height, other.voxel) {
            out.push(format!("{}, not {}", size(self), size(other)));
        }
        if self.windfield != other.windfield || self.format != other.format {
            out.push(format!(
                "windfield {}, not {}",
                self.windfield, other.windfield
            ));
        }
        out
    }

    /// Whether the manifest claims the file `name`.
    fn claims(&self, names: &Names, name: &str) -> bool {
        names.number(name).is_some_and(|k| self.holds(k))
    }

    /// Whether frame `k` lies in the claimed ranges.
    fn holds(&self, k: u64) -> bool {
        self.frames.iter().any(|&[a, b]| (a..b).contains(&k))
    }

    /// Adds `[a, b)` to the claimed ranges, keeping them sorted and disjoint.
    fn add(&mut self, a: u64, b: u64) {
        self.frames.push([a, b]);
        self.frames.sort_unstable();
        let mut merged: Vec<[u64; 2]> = Vec::with_capacity(self.frames.len());
        for &[a, b] in &self.frames {
            match merged.last_mut() {
                Some(last) if a <= last[1] => last[1] = last[1].max(b),
                _ => merged.push([a, b]),
            }
        }
        self.frames = merged;
    }

    /// Drops frames `ks` (sorted) from the claimed ranges.
    fn remove(&mut self, ks: &[u64]) {
        let mut out = Vec::new();
        for &[a, b] in &self.frames {
            let mut start = a;
            for &k in ks.iter().filter(|&&k| (a..b).contains(&k)) {
                if start < k {
                    out.push([start, k]);
                }
                start = k + 1;
            }
            if start < b {
                out.push([start, b]);
            }
        }
        self.frames = out;
    }

    /// The run in words: `b.json (24 fps, 48×36), frames 98..106 of d/f%d.png`.
    fn describe(&self, folder: &Path) -> String {
        let ranges: Vec<String> = self
            .frames
            .iter()
            .map(|[a, b]| format!("{a}..{b}"))
            .collect();
        let ranges = if ranges.is_empty() {
            "no frames".to_string()
        } else {
            format!("frames {}", ranges.join(", "))
        };
        let pattern = Names::parse(&self.pattern).map_or(self.pattern.clone(), |n| n.display());
        // A volume run is sized by its voxels, an image run by its pixels.
        let size = match self.voxel {
            Some(v) => format!("voxels of {v} m"),
            None => format!("{}×{}", self.width, self.height),
        };
        format!(
            "{} ({} fps, {size}), {ranges} of {}",
            self.input,
            self.fps,
            in_folder(folder, &pattern)
        )
    }
}

/// `name` in `folder`, as the user wrote the folder (`d/f%d.png`, or `f%d.png` for `.`).
fn in_folder(folder: &Path, name: &str) -> String {
    if folder == Path::new(".") {
        name.to_string()
    } else {
        folder.join(name).display().to_string()
    }
}

/// The manifest path of a pattern whose frames are `names` in `folder`.
pub fn manifest_path(folder: &Path, names: &Names) -> PathBuf {
    folder.join(format!("{}{MANIFEST_SUFFIX}", names.display()))
}

/// A manifest found in the folder.
struct Found {
    path: PathBuf,
    manifest: Manifest,
    names: Names,
}

/// Claims frames `range` of `names` in `folder` for `run` (see the module's comment):
/// refused if another run's manifest claims any of their files, or any exists unclaimed,
/// unless `force`, which takes them over. On success the run's manifest claims the range.
pub fn claim_frames(
    folder: &Path,
    names: &Names,
    range: FrameRange,
    run: &Manifest,
    force: bool,
) -> Result<(), Failure> {
    create_folder(folder)?;
    let _lock = FolderLock::acquire(folder, &run.run_key())?;
    let mine_path = manifest_path(folder, names);
    let mine = |name: &str| {
        names
            .number(name)
            .filter(|k| (range.start..range.end).contains(k))
    };
    let mut found = Vec::new();
    for path in manifests_in(folder)? {
        match read_manifest(&path) {
            Ok((manifest, theirs)) => found.push(Found {
                path,
                manifest,
                names: theirs,
            }),
            Err(_) if force => remove(&path)?,
            Err(why) => {
                return Err(Failure::Input(format!(
                    "--out: {} cannot be read ({why}), so the frames it claims are not known; \
                     if no run uses it, remove it, or use --force to render over it",
                    path.display()
                )))
            }
        }
    }
    // Other runs' claims on this run's files.
    let mut kept = Vec::new();
    for other in found {
        let at_mine = other.path == mine_path;
        if other.manifest.same_run(run) {
            kept.push(other);
            continue;
        }
        let overlap = overlap(&other, names, range);
        if overlap.is_empty() && !at_mine {
            kept.push(other);
            continue;
        }
        if !force {
            return Err(conflict(folder, run, names, range, &other, &overlap));
        }
        take_over(folder, other, &overlap, at_mine, &mut kept)?;
    }
    // Files of this run's range that no manifest claims.
    let claimed = |name: &str| kept.iter().any(|f| f.manifest.claims(&f.names, name));
    let mut unclaimed: Vec<String> = file_names(folder)?
        .into_iter()
        .filter(|name| mine(name).is_some() && !claimed(name))
        .collect();
    unclaimed.sort_by_key(|name| mine(name));
    if !unclaimed.is_empty() {
        if !force {
            return Err(Failure::Input(format!(
                "--out: {} of this run's frames ({}) exist but no manifest claims them (another \
                 tool wrote them, or their manifest was removed), so they are not known to be \
                 this run's; use another --out, or --force to render over them",
                unclaimed.len(),
                span(folder, &unclaimed)
            )));
        }
        for name in &unclaimed {
            remove(&folder.join(name))?;
        }
    }
    // This run's manifest: the range added to what it claimed already.
    let mut manifest = match kept.into_iter().find(|f| f.path == mine_path) {
        Some(f) => f.manifest,
        None => run.clone(),
    };
    let before = manifest.frames.clone();
    manifest.add(range.start, range.end);
    if manifest.frames != before || !mine_path.exists() {
        write_manifest(&mine_path, &manifest)?;
    }
    Ok(())
}

/// The frames of `other` whose files are among this run's (`names` over `range`), as
/// `other`'s frame numbers, sorted.
fn overlap(other: &Found, names: &Names, range: FrameRange) -> Vec<u64> {
    let theirs = &other.names;
    let ours = |k: u64| (range.start..range.end).contains(&k);
    if theirs == names {
        let mut out = Vec::new();
        for &[a, b] in &other.manifest.frames {
            out.extend(a.max(range.start)..b.min(range.end));
        }
        return out;
    }
    let claimed: u64 = other.manifest.frames.iter().map(|[a, b]| b - a).sum();
    let mut out: Vec<u64> = if claimed <= range.end - range.start {
        other
            .manifest
            .frames
            .iter()
            .flat_map(|&[a, b]| a..b)
            .filter(|&k| names.number(&theirs.name(k)).is_some_and(ours))
            .collect()
    } else {
        (range.start..range.end)
            .filter_map(|k| theirs.number(&names.name(k)))
            .filter(|&k| other.manifest.holds(k))
            .collect()
    };
    out.sort_unstable();
    out
}

/// The refusal of a run whose frames another run claims, naming both.
fn conflict(
    folder: &Path,
    run: &Manifest,
    names: &Names,
    range: FrameRange,
    other: &Found,
    overlap: &[u64],
) -> Failure {
    let mut this = run.clone();
    this.frames = vec![[range.start, range.end]];
    this.pattern = names.spelling();
    let files: Vec<String> = overlap.iter().map(|&k| other.names.name(k)).collect();
    let what = if files.is_empty() {
        format!(
            "its frames' pattern {} belongs to another run",
            in_folder(folder, &names.display())
        )
    } else {
        format!(
            "{} of its frames ({}) belong to another run",
            files.len(),
            span(folder, &files)
        )
    };
    Failure::Input(format!(
        "--out: this run, {}, would write or skip frames of another run: {what}, {} (see {}); \
         they are of {}. Use another --out, or --force to render over them",
        this.describe(folder),
        other.manifest.describe(folder),
        other.path.display(),
        other.manifest.differences(run).join(", ")
    ))
}

/// `--force` over another run's claim: its frames among this run's files are deleted (so no
/// shard of this run skips them as complete) and its claim on them dropped; its manifest is
/// rewritten, or removed when it claims nothing more or lies where this run's goes.
fn take_over(
    folder: &Path,
    mut other: Found,
    overlap: &[u64],
    at_mine: bool,
    kept: &mut Vec<Found>,
) -> Result<(), Failure> {
    for &k in overlap {
        remove(&folder.join(other.names.name(k)))?;
    }
    other.manifest.remove(overlap);
    if at_mine || other.manifest.frames.is_empty() {
        remove(&other.path)
    } else {
        write_manifest(&other.path, &other.manifest)?;
        kept.push(other);
        Ok(())
    }
}

/// `d/f0003.png … d/f0007.png`, or the one name.
fn span(folder: &Path, names: &[String]) -> String {
    match names {
        [] => String::new(),
        [one] => in_folder(folder, one),
        [first, .., last] => format!("{} … {}", in_folder(folder, first), last),
    }
}

fn create_folder(folder: &Path) -> Result<(), Failure> {
    std::fs::create_dir_all(folder).map_err(|e| Failure::Io(format!("{}: {e}", folder.display())))
}

fn remove(path: &Path) -> Result<(), Failure> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != ErrorKind::NotFound => {
            Err(Failure::Io(format!("{}: {e}", path.display())))
        }
        _ => Ok(()),
    }
}

/// The names of the files in `folder`.
fn file_names(folder: &Path) -> Result<Vec<String>, Failure> {
    let io = |e: std::io::Error| Failure::Io(format!("{}: {e}", folder.display()));
    let mut out = Vec::new();
    for entry in std::fs::read_dir(folder).map_err(io)? {
        if let Some(name) = entry.map_err(io)?.file_name().to_str() {
            out.push(name.to_string());
        }
    }
    Ok(out)
}

/// The manifests in `folder`.
fn manifests_in(folder: &Path) -> Result<Vec<PathBuf>, Failure> {
    let mut out: Vec<PathBuf> = file_names(folder)?
        .into_iter()
        .filter(|n| n.ends_with(MANIFEST_SUFFIX) && !n.ends_with(".partial"))
        .map(|n| folder.join(n))
        .collect();
    out.sort();
    Ok(out)
}

/// A manifest and the file names it claims, or why it cannot be read.
fn read_manifest(path: &Path) -> Result<(Manifest, Names), String> {
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    let value: serde_json::Value = serde_json::from_str(&text).map_err(|e| e.to_string())?;
    match value.get("format").and_then(|f| f.as_str()) {
        Some(MANIFEST_FORMAT) => {}
        Some(other) => return Err(format!("its format is {other}, from another windfield")),
        None => return Err("it has no format".into()),
    }
    let manifest: Manifest = serde_json::from_value(value).map_err(|e| e.to_string())?;
    let names = Names::parse(&manifest.pattern)
        .ok_or_else(|| format!("its pattern {:?} is not a frame pattern", manifest.pattern))?;
    Ok((manifest, names))
}

fn write_manifest(path: &Path, manifest: &Manifest) -> Result<(), Failure> {
    let text = serde_json::to_string_pretty(manifest).expect("manifests serialise") + "\n";
    write_atomically(path, |w| std::io::Write::write_all(w, text.as_bytes()))
}

/// The folder's lock, held while a run claims frames; removed when dropped (if still its own).
struct FolderLock {
    path: PathBuf,
    token: String,
}

/// Who holds a lock.
#[derive(Serialize, Deserialize)]
struct Holder {
    pid: u32,
    host: String,
    run: String,
    token: String,
}

impl FolderLock {
    /// Creates `folder/.windfield.lock` (create-new), taking over a lock left by a run that
    /// died holding it (see the module's comment), waiting up to [`LOCK_WAIT`] for a live one.
    fn acquire(folder: &Path, run: &str) -> Result<Self, Failure> {
        let path = folder.join(LOCK_NAME);
        let io = |e: std::io::Error| Failure::Io(format!("{}: {e}", path.display()));
        let holder = Holder {
            pid: std::process::id(),
            host: host(),
            run: run.to_string(),
            token: unique_token(),
        };
        let body = serde_json::to_string(&holder).expect("holders serialise");
        let deadline = Instant::now() + LOCK_WAIT;
        let mut pause = 1;
        loop {
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&path)
            {
                Ok(mut file) => {
                    std::io::Write::write_all(&mut file, body.as_bytes()).map_err(io)?;
                    return Ok(Self {
                        path,
                        token: holder.token,
                    });
                }
                Err(e) if e.kind() == ErrorKind::AlreadyExists => {}
                Err(e) => return Err(io(e)),
            }
            let theirs = std::fs::read_to_string(&path)
                .ok()
                .and_then(|t| serde_json::from_str::<Holder>(&t).ok());
            if let Some(h) = &theirs {
                let dead = h.host == holder.host && !alive(h.pid);
                if h.run == holder.run || dead {
                    remove(&path)?;
                    continue;
                }
            }
            if Instant::now() >= deadline {
                let who = theirs.map_or("a run that is still writing it".to_string(), |h| {
                    format!("process {} on {}", h.pid, h.host)
                });
                return Err(Failure::Io(format!(
                    "{}: held by {who} for over {} s; if no windfield run is claiming frames in \
                     {}, remove it",
                    path.display(),
                    LOCK_WAIT.as_secs(),
                    folder.display()
                )));
            }
            std::thread::sleep(Duration::from_millis(pause));
            pause = (pause * 2).min(50);
        }
    }
}

impl Drop for FolderLock {
    fn drop(&mut self) {
        let ours = std::fs::read_to_string(&self.path).is_ok_and(|t| t.contains(&self.token));
        if ours {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

/// A string no other lock holds: the process id and a random number.
fn unique_token() -> String {
    use std::hash::{BuildHasher, Hasher};
    let random = std::collections::hash_map::RandomState::new()
        .build_hasher()
        .finish();
    format!("{}-{random:016x}", std::process::id())
}

/// FNV-1a with 128 bits, in hex: a fingerprint that tells scenes apart (not a defence
/// against forgery).
pub fn fingerprint(bytes: &[u8]) -> String {
    const OFFSET: u128 = 0x6c62_272e_07bb_0142_62b8_2175_6295_c58d;
    const PRIME: u128 = 0x0000_0000_0100_0000_0000_0000_0000_013b;
    let hash = bytes
        .iter()
        .fold(OFFSET, |h, &b| (h ^ b as u128).wrapping_mul(PRIME));
    format!("{hash:032x}")
}

/// This machine's name (Linux), or nothing where it cannot be read.
fn host() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .map(|h| h.trim().to_string())
        .unwrap_or_default()
}

/// Whether process `pid` of this machine lives; true where that cannot be told (no /proc).
fn alive(pid: u32) -> bool {
    !Path::new("/proc/self").exists() || Path::new(&format!("/proc/{pid}")).exists()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::Pattern;

    #[test]
    fn a_lock_is_taken_over_by_its_own_run_or_from_a_process_that_is_gone() {
        let dir = std::env::temp_dir().join(format!("windfield-lock-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let hold = |pid: u32, host: &str, run: &str| {
            let h = Holder {
                pid,
                host: host.into(),
                run: run.into(),
                token: "theirs".into(),
            };
            std::fs::write(dir.join(LOCK_NAME), serde_json::to_string(&h).unwrap()).unwrap();
        };
        // The same run, from another machine (a resumed shard): taken over at once.
        hold(1, "elsewhere", "run-a");
        let lock = FolderLock::acquire(&dir, "run-a").unwrap_or_else(|_| panic!("not acquired"));
        assert!(std::fs::read_to_string(dir.join(LOCK_NAME))
            .unwrap()
            .contains(&lock.token));
        drop(lock);
        assert!(!dir.join(LOCK_NAME).exists(), "released");
        // Another run whose process on this machine is gone: taken over at once.
        hold(u32::MAX - 1, &host(), "run-b");
        drop(FolderLock::acquire(&dir, "run-a").unwrap_or_else(|_| panic!("not acquired")));
        // A lock that is no longer its holder's is left alone when the holder lets go.
        let lock = FolderLock::acquire(&dir, "run-a").unwrap_or_else(|_| panic!("not acquired"));
        hold(std::process::id(), &host(), "run-c");
        drop(lock);
        assert!(dir.join(LOCK_NAME).exists(), "another's lock removed");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn claimed_ranges_merge_and_split() {
        let mut m = Manifest::new(
            "x".into(),
            24.0,
            (4, 3),
            &Names::parse("f%02d.png").unwrap(),
            FrameRange { start: 10, end: 20 },
            Path::new("a.json"),
        );
        m.add(30, 40);
        m.add(20, 25);
        assert_eq!(m.frames, vec![[10, 25], [30, 40]]);
        m.remove(&[10, 12, 24, 35]);
        assert_eq!(m.frames, vec![[11, 12], [13, 24], [30, 35], [36, 40]]);
        assert!(m.holds(13) && !m.holds(12) && !m.holds(40));
    }

    #[test]
    fn the_manifest_lies_beside_the_frames_and_fingerprints_differ() {
        let manifest = |p: &str| {
            let (folder, names) = Pattern::parse(p).unwrap().folder_and_names();
            manifest_path(&folder, &names)
        };
        assert_eq!(
            manifest("seq/frame.%03d"),
            PathBuf::from("seq/frame.%03d.windfield.json")
        );
        assert_eq!(
            manifest("100%%/f%d.png"),
            PathBuf::from("100%/f%d.png.windfield.json")
        );
        assert_ne!(fingerprint(b"{\"seed\": 1}"), fingerprint(b"{\"seed\": 2}"));
        assert_eq!(fingerprint(b""), "6c62272e07bb014262b821756295c58d");
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
