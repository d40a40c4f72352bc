//! Every file the command line writes, written atomically: to a temporary name in the same
//! folder first, then renamed, so a failure leaves no partial output and concurrent writers
//! (shards) never see each other's half-written files; a missing folder is made.
//!
//! Files written together ([`write_together`]) are all written or none, so that a failure
//! leaves the old ones as they were: `generate`'s field and the parameters beside it
//! (`field.npy`, `field.npy.json`) are one pair, and a field never sits beside another field's
//! parameters. Every file is written to a temporary name first (a failure there, a full disk
//! or a name too long, removes the temporary files and touches nothing). Then they are renamed
//! in order, the last one last; each one replaced is kept under a temporary name (a hard link)
//! until all are in place, so a rename that fails puts the earlier files back.

use super::failure::Failure;
use std::fs;
use std::hash::{BuildHasher, Hasher};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

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

/// Writes a file's bytes.
pub type Writer<'a> = Box<dyn Fn(&mut BufWriter<fs::File>) -> std::io::Result<()> + 'a>;

/// One file to write: its path and its bytes.
pub struct Output<'a> {
    pub path: &'a Path,
    pub write: Writer<'a>,
}

/// Writes `outputs` all or none (see the module's comment).
pub fn write_together(outputs: &[Output]) -> Result<(), Failure> {
    let io = |path: &Path, e: std::io::Error| Failure::Io(format!("{}: {e}", path.display()));
    let mut temporaries: Vec<PathBuf> = Vec::new();
    let cleanup = |paths: &[PathBuf]| {
        for p in paths {
            let _ = fs::remove_file(p);
        }
    };
    for out in outputs {
        create_parent(out.path)?;
        let tmp = temporary_path(out.path);
        let written = (|| {
            let mut w = BufWriter::new(fs::File::create(&tmp)?);
            (out.write)(&mut w)?;
            w.flush()?;
            w.into_inner().map_err(|e| e.into_error())?.sync_all()
        })();
        temporaries.push(tmp);
        if let Err(e) = written {
            cleanup(&temporaries);
            return Err(io(out.path, e));
        }
    }
    // Renames, each replaced file kept until all are in place.
    let mut done: Vec<(&Path, Option<PathBuf>)> = Vec::new();
    for (out, tmp) in outputs.iter().zip(&temporaries) {
        let backup = temporary_path(out.path);
        let kept = fs::hard_link(out.path, &backup).is_ok().then_some(backup);
        if let Err(e) = fs::rename(tmp, out.path) {
            for (path, kept) in done.iter().rev() {
                match kept {
                    Some(old) => {
                        let _ = fs::rename(old, path);
                    }
                    None => {
                        let _ = fs::remove_file(path);
                    }
                }
            }
            cleanup(&temporaries);
            if let Some(k) = kept {
                let _ = fs::remove_file(k);
            }
            return Err(io(out.path, e));
        }
        done.push((out.path, kept));
    }
    for (_, kept) in done {
        if let Some(k) = kept {
            let _ = fs::remove_file(k);
        }
    }
    Ok(())
}
