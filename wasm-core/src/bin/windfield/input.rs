//! What the commands read: input files that must be files, scenes (bounded by size before
//! they are read) and blob lists (read straight into their blobs), told apart by a scene's
//! `version`.

use super::failure::Failure;
use serde::de::IgnoredAny;
use serde::{Deserialize, Deserializer};
use std::fs;
use std::path::Path;
use windfield::scene::blob_list::BlobList;
use windfield::scene::limits::MAX_SCENE_BYTES;
use windfield::scene::read::check_scene_size;
use windfield::{ParamError, Scene};

/// Opens an input file that must be a file (a folder is a failed read, exit 1); its size.
pub fn open_input(path: &Path) -> Result<(fs::File, u64), Failure> {
    let io = |e: std::io::Error| Failure::Io(format!("{}: {e}", path.display()));
    let file = fs::File::open(path).map_err(io)?;
    let meta = file.metadata().map_err(io)?;
    if meta.is_dir() {
        return Err(Failure::Io(format!(
            "{}: is a directory, not a file",
            path.display()
        )));
    }
    Ok((file, meta.len()))
}

/// Reads a file as text.
pub fn read_text(path: &Path) -> Result<String, Failure> {
    let (mut file, len) = open_input(path)?;
    let mut text = String::with_capacity(len as usize);
    std::io::Read::read_to_string(&mut file, &mut text).map_err(|e| {
        let message = format!("{}: {e}", path.display());
        // Bytes that are not UTF-8 are the input's fault (status 2), not a failed read.
        match e.kind() {
            std::io::ErrorKind::InvalidData => Failure::Input(message),
            _ => Failure::Io(message),
        }
    })?;
    Ok(text)
}

/// Reads and validates a scene file; one over `MAX_SCENE_BYTES` is refused unread.
pub fn read_scene(path: &Path) -> Result<Scene, Failure> {
    let (_, len) = open_input(path)?;
    check_scene_size(len).map_err(|e| Failure::Input(format!("{}: {e}", path.display())))?;
    Scene::from_json(&read_text(path)?)
        .map_err(|e| Failure::Input(format!("{}: {e}", path.display())))
}

/// What `render` reads: a scene, or a blob list.
pub enum Input {
    Scene(Box<Scene>),
    List(BlobList),
}

/// Whether a JSON object has a key, whatever its value (null included), read without keeping it.
#[derive(Default)]
struct Present(bool);

impl<'de> Deserialize<'de> for Present {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        IgnoredAny::deserialize(d).map(|_| Present(true))
    }
}

/// An object's `version`, the mark of a scene; every other key is skipped unread.
#[derive(Deserialize)]
struct Probe {
    #[serde(default)]
    version: Present,
}

/// The keys of a scene that a blob list does not have: met at the top of a file too long for
/// a scene, they make it one.
const SCENE_ONLY_KEYS: [&str; 8] = [
    "version",
    "seed",
    "field",
    "wind",
    "emitters",
    "shapes",
    "gas",
    "simulation",
];

/// Reads a scene (JSON with "version") or a blob list. A blob list is read straight into its
/// blobs, at most `blob_list::MAX_LIST_BLOBS` of them, with no intermediate JSON tree. A file
/// over `MAX_SCENE_BYTES` can only be a blob list: it is read as one from the file, never held
/// whole, and refused unread past its first scene key if it is a scene.
pub fn read_input(path: &Path) -> Result<Input, Failure> {
    let bad = |e: ParamError| Failure::Input(format!("{}: {e}", path.display()));
    let (file, len) = open_input(path)?;
    if len > MAX_SCENE_BYTES as u64 {
        return match BlobList::from_reader(std::io::BufReader::new(file)) {
            Ok(list) => Ok(Input::List(list)),
            Err(e)
                if SCENE_ONLY_KEYS.contains(&e.path.as_str())
                    && e.message.starts_with("unknown field") =>
            {
                Err(bad(check_scene_size(len).unwrap_err()))
            }
            Err(e) => Err(bad(e)),
        };
    }
    let text = read_text(path)?;
    match serde_json::from_str::<Probe>(&text) {
        Ok(Probe {
            version: Present(true),
        }) => Ok(Input::Scene(Box::new(
            Scene::from_json(&text).map_err(bad)?,
        ))),
        // Not JSON: read as what it looks like, so the error names where it breaks.
        Err(e) if (e.is_syntax() || e.is_eof()) && text.contains("\"version\"") => Ok(
            Input::Scene(Box::new(Scene::from_json(&text).map_err(bad)?)),
        ),
        _ => Ok(Input::List(BlobList::from_json(&text).map_err(bad)?)),
    }
}
