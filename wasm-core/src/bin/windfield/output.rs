//! Files written together, so that a failure leaves the old ones as they were: `generate`'s
//! field and the parameters beside it (`field.npy`, `field.npy.json`) are one pair, and a
//! field never sits beside another field's parameters.
//!
//! Every file is written to a temporary name first (a failure there, a full disk or a name
//! too long, removes the temporary files and touches nothing). Then they are renamed in
//! order, the last one last; each one replaced is kept under a temporary name (a hard link)
//! until all are in place, so a rename that fails puts the earlier files back.

use super::{create_parent, temporary_path, Failure};
use std::fs;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

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
