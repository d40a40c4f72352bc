//! What the command line's tests share: the binary under test and a scratch directory per test.

use std::path::{Path, PathBuf};

/// The `windfield` binary: `WINDFIELD_TEST_BIN`, else the one this build made.
pub fn bin() -> PathBuf {
    std::env::var_os("WINDFIELD_TEST_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_windfield")))
}

/// A fresh directory for one test, removed with everything in it when the test ends.
pub struct Scratch(pub PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The scratch directory `name` of the tests of `suite` (one per process, emptied first).
pub fn scratch(suite: &str, name: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("windfield-{suite}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
}
