//! Reading the two formats from JSON: the scene and the blob list (docs/FORMATS.md).
//!
//! Reading is strict, and bounded before it builds anything: a scene's text over
//! [`MAX_SCENE_BYTES`] is refused unread, and every list of either format is counted against
//! its budget in the text ([`super::list_budget`]) before serde builds it. Then serde refuses
//! unknown keys and wrong types, naming the JSON path in a person's words
//! ([`super::json_errors`]); an old scene version is migrated first; then the one validation
//! walk ([`super::validate`]) checks every value. What comes out of here is ready to simulate
//! or render.

use crate::error::ParamError;
use crate::scene::blob_list::{BlobList, Light, Object, Phase};
use crate::scene::json_errors::describe;
use crate::scene::limits::MAX_SCENE_BYTES;
use crate::scene::list_budget::{check_lists, BLOB_LIST_LISTS, SCENE_LISTS};
use crate::scene::scene_format::{Primitive, Scene, SCENE_VERSION};
use serde::{Deserialize, Deserializer};
use serde_json::Value;

/// A serde error as a [`ParamError`] at its JSON path (`root` for the document itself); `text`
/// is the JSON read, when it was text, `tree` the value read, when it was a value.
fn at_path(
    root: &str,
    e: serde_path_to_error::Error<serde_json::Error>,
    text: Option<&str>,
    tree: Option<&Value>,
) -> ParamError {
    // serde_path_to_error writes `.` for the document and `?` for a key it has not read.
    let path = e.path().to_string();
    let mut path = match path.trim_end_matches(".?") {
        "." | "?" | "" => root.to_string(),
        known => known.to_string(),
    };
    // A key left out is named below, by its element's path and its own; so is an unknown key
    // of an element chosen by its `type` (serde reads such an element whole, and names it).
    let (error, category) = (e.inner().to_string(), e.inner().classify());
    let left_out = error.starts_with("missing field `");
    let unknown = error
        .strip_prefix("unknown field `")
        .and_then(|m| m.split_once('`'))
        .map(|(key, _)| key.to_string());
    if let (Some(key), Some(_)) = (&unknown, tagged(&path)) {
        path = format!("{path}.{key}");
    } else if category == serde_json::error::Category::Data && !left_out && tagged(&path).is_some()
    {
        let parsed: Option<Value> = match tree {
            Some(_) => None,
            None => text.and_then(|t| serde_json::from_str(t).ok()),
        };
        if let Some(key) = tree.or(parsed.as_ref()).and_then(|t| key_within(&path, t)) {
            path = format!("{path}.{key}");
        }
    }
    let mut message = describe(e.inner(), text);
    // A required key left out is named by its own path, not its parent's.
    let missing = message
        .strip_prefix("missing field `")
        .and_then(|m| m.strip_suffix('`'));
    if let Some(key) = missing {
        path = match path == root {
            true => key.to_string(),
            false => format!("{path}.{key}"),
        };
        message = "missing: this key has no default".to_string();
    }
    // A key of named choices given another JSON type: serde_json's text reader refuses it as
    // though the document were not JSON, its value reader as `expected string or map`.
    let other_type = category == serde_json::error::Category::Syntax
        || (category == serde_json::error::Category::Data
            && error.contains(", expected string or map"));
    if other_type {
        if let Some(choices) = choices_of(root, &path, text, tree) {
            message = choices;
        }
    }
    // A list of a fixed length given more items: serde_json's text reader refuses the first
    // item too many as trailing characters, its value reader as `fewer elements`, and within an
    // element chosen by its `type` serde as `elements in sequence`.
    let too_long = (category == serde_json::error::Category::Syntax
        && error.starts_with("trailing characters"))
        || error.contains(", expected fewer elements in array")
        || error.contains(" elements in sequence");
    if too_long {
        if let Some(length) = length_of(root, &path, text, tree) {
            message = length;
        }
    }
    if category == serde_json::error::Category::Data {
        if let Some(range) = range_of(root, &path, text, tree) {
            if let Some((_, got)) = message.split_once(" (got ") {
                message = format!("{range} (got {got}");
            }
        }
    }
    ParamError::new(path, message)
}

/// The largest document (bytes of JSON) read again to word a refusal ([`range_of`],
/// [`choices_of`], [`length_of`]).
const RANGE_PROBE_BYTES: usize = 1 << 20;

/// The document a refusal came from, as a value to change and read again: `tree`, the value
/// read, or `text` parsed; None for a document that is not JSON or is longer than
/// [`RANGE_PROBE_BYTES`], which is not read twice.
fn document(text: Option<&str>, tree: Option<&Value>) -> Option<Value> {
    match (tree, text) {
        (Some(t), _) if compact_length_within(t, RANGE_PROBE_BYTES) => Some(t.clone()),
        (None, Some(t)) if t.len() <= RANGE_PROBE_BYTES => serde_json::from_str(t).ok(),
        _ => None,
    }
}

/// Why serde refuses `probe` as the format `root` names (`scene` or `blob_list`), at its path;
/// None where it reads.
fn refusal_of(root: &str, probe: &Value) -> Option<serde_path_to_error::Error<serde_json::Error>> {
    match root {
        "scene" => serde_path_to_error::deserialize::<_, Scene>(probe).err(),
        _ => serde_path_to_error::deserialize::<_, BlobList>(probe).err(),
    }
}

/// The range the one validation walk states for the key at `path` (`must be an even number
/// between 4 and 256`), so that a value of the wrong type is told the key's range as one of the
/// right type out of it is: the document is read again with a whole number far beyond every
/// range in the key's place (the largest of each unsigned width, the first that reads) and
/// validated. None where no such number reads (a string, a list, a flag), where the walk stops
/// at another key first, or where its message states no range; and for documents longer than
/// [`RANGE_PROBE_BYTES`], which are not read twice.
fn range_of(root: &str, path: &str, text: Option<&str>, tree: Option<&Value>) -> Option<String> {
    let tree = document(text, tree)?;
    let far = [u64::MAX, u32::MAX as u64, u16::MAX as u64, u8::MAX as u64];
    far.into_iter().find_map(|n| {
        let mut probe = tree.clone();
        *lookup_mut(&mut probe, path)? = Value::from(n);
        let refusal = match root {
            "scene" => Scene::deserialize(&probe).ok()?.validate().err()?,
            _ => BlobList::deserialize(&probe).ok()?.validate().err()?,
        };
        let (range, _) = refusal.message.split_once(" (got ")?;
        (refusal.path == path).then(|| range.to_string())
    })
}

/// What a key of a few named choices (`field.spectrum.law`, `simulation.integrator`) says of a
/// value of another JSON type (`3`, a list), which serde_json refuses as though the document
/// were not JSON (`expected value`): `must be "kolmogorov" or "paper-literal" (got 3)`. The
/// document, valid JSON, is read again with a string that is none of the choices in the key's
/// place, whose refusal lists them. `text` is the JSON read, when it was text, `tree` the value
/// read, when it was a value. None where the document is not JSON, is longer than
/// [`RANGE_PROBE_BYTES`], or the second reading stops elsewhere.
fn choices_of(root: &str, path: &str, text: Option<&str>, tree: Option<&Value>) -> Option<String> {
    let mut probe = document(text, tree)?;
    let got = got_of(lookup(&probe, path)?);
    const NONE_OF_THEM: &str = "\u{1}";
    *lookup_mut(&mut probe, path)? = Value::from(NONE_OF_THEM);
    let refusal = refusal_of(root, &probe)?.inner().to_string();
    let expected = refusal.strip_prefix(&format!("unknown variant `{NONE_OF_THEM}`, expected "))?;
    Some(format!(
        "must be {} (got {got})",
        expected.replace('`', "\"")
    ))
}

/// What a list of a fixed length (`field.size`, `field.period`, a colour) says of one with more
/// items, as it says of one with fewer: `must be a list of 4 numbers (got 5 items)`. The
/// document, valid JSON, is read again with the list emptied, whose refusal states the length.
/// None where the document is not JSON, is longer than [`RANGE_PROBE_BYTES`], the value there
/// is not a list, or the second reading stops elsewhere.
fn length_of(root: &str, path: &str, text: Option<&str>, tree: Option<&Value>) -> Option<String> {
    let mut probe = document(text, tree)?;
    let items = lookup(&probe, path)?.as_array()?.len();
    *lookup_mut(&mut probe, path)? = Value::Array(Vec::new());
    let refusal = refusal_of(root, &probe)?;
    // Within an element chosen by its `type`, serde names the element.
    let at = refusal.path().to_string();
    if at != path && !(tagged(&at).is_some() && path.starts_with(&format!("{at}."))) {
        return None;
    }
    let empty = describe(refusal.inner(), None);
    let stated = empty.strip_suffix(" (got 0 items)")?;
    Some(format!("{stated} (got {items} items)"))
}

/// A value as a refusal echoes it: a number or a string as written, `a list`, `an object`.
fn got_of(value: &Value) -> String {
    match value {
        Value::Array(_) => "a list".to_string(),
        Value::Object(_) => "an object".to_string(),
        other => other.to_string(),
    }
}

/// Whether `value` written as compact JSON is at most `limit` bytes (counted, not written).
fn compact_length_within(value: &Value, limit: usize) -> bool {
    struct Count(usize, usize);
    impl std::io::Write for Count {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            self.0 += bytes.len();
            if self.0 > self.1 {
                return Err(std::io::Error::other("over the limit"));
            }
            Ok(bytes.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    serde_json::to_writer(Count(0, limit), value).is_ok()
}

/// The internally tagged element (`"type": …`) a path ends at, if it does: a wind primitive,
/// an object, a light or the phase function, in a scene or a blob list.
#[derive(Clone, Copy)]
enum Tagged {
    Primitive,
    Object,
    Light,
    Phase,
}

fn tagged(path: &str) -> Option<Tagged> {
    if path == "medium.phase" || path == "render.medium.phase" {
        return Some(Tagged::Phase);
    }
    let list = path.strip_suffix(']')?.rsplit_once('[')?.0;
    match list {
        "wind" => Some(Tagged::Primitive),
        "objects" | "render.objects" => Some(Tagged::Object),
        "lights" | "render.lights" => Some(Tagged::Light),
        _ => None,
    }
}

/// The value at a path as serde_path_to_error writes it (`render.objects[2]`).
fn lookup<'a>(root: &'a Value, path: &str) -> Option<&'a Value> {
    let mut at = root;
    for part in path.split('.') {
        let (key, indices) = part.split_once('[').unwrap_or((part, ""));
        if !key.is_empty() {
            at = at.get(key)?;
        }
        for index in indices.split('[').filter(|i| !i.is_empty()) {
            at = at.get(index.strip_suffix(']')?.parse::<usize>().ok()?)?;
        }
    }
    Some(at)
}

/// [`lookup`], for writing.
fn lookup_mut<'a>(root: &'a mut Value, path: &str) -> Option<&'a mut Value> {
    let mut at = root;
    for part in path.split('.') {
        let (key, indices) = part.split_once('[').unwrap_or((part, ""));
        if !key.is_empty() {
            at = at.get_mut(key)?;
        }
        for index in indices.split('[').filter(|i| !i.is_empty()) {
            at = at.get_mut(index.strip_suffix(']')?.parse::<usize>().ok()?)?;
        }
    }
    Some(at)
}

/// The key within a tagged element whose value serde refused. serde reads such an element whole
/// before it picks the variant, so its error's path ends at the element; each key but `type`
/// is left out in turn, and the one whose absence cures the element (or leaves only that key
/// missing) is the one named. None when no single key is to blame.
fn key_within(path: &str, root: &Value) -> Option<String> {
    let kind = tagged(path)?;
    let element = lookup(root, path)?.as_object()?;
    let cured_without = |key: &str| {
        let mut rest = element.clone();
        rest.remove(key);
        let rest = Value::Object(rest);
        let read = match kind {
            Tagged::Primitive => Primitive::deserialize(&rest).map(drop),
            Tagged::Object => Object::deserialize(&rest).map(drop),
            Tagged::Light => Light::deserialize(&rest).map(drop),
            Tagged::Phase => Phase::deserialize(&rest).map(drop),
        };
        match read {
            Ok(()) => true,
            Err(e) => e.to_string() == format!("missing field `{key}`"),
        }
    };
    let mut culprits = element.keys().filter(|k| *k != "type" && cured_without(k));
    match (culprits.next(), culprits.next()) {
        (Some(key), None) => Some(key.clone()),
        _ => None,
    }
}

/// A size in bytes as the limits are stated: `64 MiB`, `210.0 MiB`.
fn mebibytes(bytes: usize) -> String {
    match bytes % (1 << 20) {
        0 => format!("{} MiB", bytes >> 20),
        _ => format!("{:.1} MiB", bytes as f64 / (1u64 << 20) as f64),
    }
}

/// A scene of `len` bytes is refused over [`MAX_SCENE_BYTES`], before it is read.
pub fn check_scene_size(len: u64) -> Result<(), ParamError> {
    if len <= MAX_SCENE_BYTES as u64 {
        return Ok(());
    }
    Err(ParamError::new(
        "scene",
        format!(
            "{} of JSON, over the limit of {} for a scene",
            mebibytes(len.min(usize::MAX as u64) as usize),
            mebibytes(MAX_SCENE_BYTES)
        ),
    ))
}

/// The document's `version`, whatever its value, every other key skipped unread.
#[derive(Deserialize)]
struct VersionProbe {
    #[serde(default, deserialize_with = "present")]
    version: Option<Value>,
}

fn present<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Value>, D::Error> {
    Value::deserialize(d).map(Some)
}

/// Refuses text whose document is not a JSON object (serde would read a struct's fields from
/// a list by position), naming `root`.
fn require_object(text: &str, root: &str) -> Result<(), ParamError> {
    if text.trim_start().starts_with('{') {
        return Ok(());
    }
    match serde_json::from_str::<serde::de::IgnoredAny>(text) {
        Ok(_) => Err(ParamError::new(root, "must be a JSON object")),
        Err(e) => Err(ParamError::new(root, describe(&e, Some(text)))),
    }
}

impl Scene {
    /// Parses and validates a scene from JSON text; errors name the JSON path. The text is
    /// bounded first (its size, its lists), then read straight into the scene, without an
    /// intermediate JSON tree.
    pub fn from_json(text: &str) -> Result<Self, ParamError> {
        check_scene_size(text.len() as u64)?;
        require_object(text, "scene")?;
        // The version first, every other key skipped unread (nothing is built, so no list needs
        // its budget yet): a document that is no scene, a blob list say, is told so before any
        // of its lists is counted against a scene's budgets. Text that is not JSON is left to
        // the reading below, which names the path where it breaks.
        match serde_json::from_str::<VersionProbe>(text) {
            Ok(probe) => check_version(probe.version.as_ref())?,
            Err(e) if e.classify() == serde_json::error::Category::Data => {
                return Err(ParamError::new("scene", "must be a JSON object"))
            }
            // Nesting past serde_json's limit is the document's fault, wherever it lies.
            Err(e) if e.to_string().starts_with("recursion limit exceeded") => {
                return Err(ParamError::new("scene", describe(&e, Some(text))))
            }
            Err(_) => {}
        }
        check_lists(text, SCENE_LISTS, "scene")?;
        let mut de = serde_json::Deserializer::from_str(text);
        let scene = read_scene(&mut de, text)?;
        de.end()
            .map_err(|e| ParamError::new("scene", describe(&e, Some(text))))?;
        scene.validate()?;
        Ok(scene)
    }

    /// Validates a parsed JSON value, migrating older versions first.
    pub fn from_value(value: Value) -> Result<Self, ParamError> {
        let value = migrate(value)?;
        let scene: Scene = serde_path_to_error::deserialize(&value)
            .map_err(|e| at_path("scene", e, None, Some(&value)))?;
        scene.validate()?;
        Ok(scene)
    }
}

/// The path a scene that serde refuses is given by the player's first WebAssembly module. That
/// module reads scenes without tracking where it is in them (the tracking is a sixth of its
/// bytes), so the worker asks the full module, which names the path, for the message
/// (`web/src/engine/session.js`); the refusal itself is the same.
pub const PATH_UNREAD: &str = "scene (path unread)";

/// The scene serde reads from `de` (over `text`), refused at its JSON path.
#[cfg(any(not(target_arch = "wasm32"), feature = "full"))]
fn read_scene(
    de: &mut serde_json::Deserializer<serde_json::de::StrRead<'_>>,
    text: &str,
) -> Result<Scene, ParamError> {
    serde_path_to_error::deserialize(de).map_err(|e| at_path("scene", e, Some(text), None))
}

/// The scene serde reads from `de` (over `text`), in the first WebAssembly module: refused at
/// [`PATH_UNREAD`].
#[cfg(all(target_arch = "wasm32", not(feature = "full")))]
fn read_scene(
    de: &mut serde_json::Deserializer<serde_json::de::StrRead<'_>>,
    text: &str,
) -> Result<Scene, ParamError> {
    Scene::deserialize(de).map_err(|e| ParamError::new(PATH_UNREAD, describe(&e, Some(text))))
}

/// Checks a scene's `version` (None: missing): this build reads version 1, the first, so
/// there is nothing older to migrate.
fn check_version(version: Option<&Value>) -> Result<(), ParamError> {
    let bad = |message: String| Err(ParamError::new("version", message));
    match version {
        None => bad(format!(
            "missing: a scene names its format version (current: {SCENE_VERSION})"
        )),
        // 1 or 1.0: JSON has one kind of number.
        Some(v) if v.as_f64() == Some(SCENE_VERSION as f64) => Ok(()),
        Some(Value::Number(n)) => bad(format!(
            "unsupported scene version {n}; this build reads version {SCENE_VERSION}"
        )),
        Some(v) => {
            let got = match v {
                Value::String(_) => format!("the string {v}"),
                Value::Array(_) => "a list".into(),
                Value::Object(_) => "an object".into(),
                other => other.to_string(),
            };
            bad(format!("must be the number {SCENE_VERSION} (got {got})"))
        }
    }
}

/// Brings an older scene up to the current version (version 1 is the first, so only checks).
fn migrate(value: Value) -> Result<Value, ParamError> {
    let obj = value
        .as_object()
        .ok_or_else(|| ParamError::new("scene", "must be a JSON object"))?;
    check_version(obj.get("version"))?;
    Ok(value)
}

impl BlobList {
    /// Parses and validates a blob list from a JSON value; errors name the JSON path.
    pub fn from_value(value: Value) -> Result<Self, ParamError> {
        let list = serde_path_to_error::deserialize(&value)
            .map_err(|e| at_path("blob_list", e, None, Some(&value)));
        Self::checked(list)
    }

    /// Parses and validates a blob list straight from JSON text, without the intermediate
    /// `serde_json::Value` (a tenth of the memory for a long list), its lists counted against
    /// their budgets first; errors name the JSON path.
    pub fn from_json(text: &str) -> Result<Self, ParamError> {
        require_object(text, "blob_list")?;
        check_lists(text, BLOB_LIST_LISTS, "blob_list")?;
        let mut de = serde_json::Deserializer::from_str(text);
        let list = serde_path_to_error::deserialize(&mut de)
            .map_err(|e| at_path("blob_list", e, Some(text), None));
        let list = Self::checked(list)?;
        de.end()
            .map_err(|e| ParamError::new("blob_list", describe(&e, Some(text))))?;
        Ok(list)
    }

    /// Parses and validates a blob list from a stream, never holding its text (for files too
    /// long to read whole); the blobs are bounded as they are read. Errors name the JSON path.
    pub fn from_reader(mut reader: impl std::io::BufRead) -> Result<Self, ParamError> {
        // The document must be an object (serde would read a struct from a list by position).
        loop {
            let io = |e: std::io::Error| ParamError::new("blob_list", e.to_string());
            let buf = reader.fill_buf().map_err(io)?;
            match buf.iter().position(|b| !b.is_ascii_whitespace()) {
                Some(i) if buf[i] == b'{' => break,
                Some(_) => return Err(ParamError::new("blob_list", "must be a JSON object")),
                None if buf.is_empty() => break,
                None => {
                    let n = buf.len();
                    reader.consume(n);
                }
            }
        }
        let mut de = serde_json::Deserializer::from_reader(reader);
        let list = serde_path_to_error::deserialize(&mut de)
            .map_err(|e| at_path("blob_list", e, None, None));
        let list = Self::checked(list)?;
        de.end()
            .map_err(|e| ParamError::new("blob_list", describe(&e, None)))?;
        Ok(list)
    }

    /// A deserialised list, validated, or the error at its JSON path.
    fn checked(list: Result<Self, ParamError>) -> Result<Self, ParamError> {
        let list = list?;
        list.validate()?;
        Ok(list)
    }
}
