//! Reading the two formats from JSON: the scene and the blob list (docs/FORMATS.md).
//!
//! Reading is strict: serde refuses unknown keys and wrong types, naming the JSON path; an old
//! scene version is migrated first; then the one validation walk ([`super::validate`]) checks
//! every value. What comes out of here is ready to simulate or render.

use crate::error::ParamError;
use crate::gas::blob_list::BlobList;
use crate::gas::scene::{Scene, SCENE_VERSION};

/// A serde error as a [`ParamError`] at its JSON path (`root` for the document itself).
fn at_path(root: &str, e: serde_path_to_error::Error<serde_json::Error>) -> ParamError {
    let path = e.path().to_string();
    let path = if path == "." { root.to_string() } else { path };
    ParamError::new(path, e.inner().to_string())
}

impl Scene {
    /// Parses and validates a scene from JSON text; errors name the JSON path.
    pub fn from_json(text: &str) -> Result<Self, ParamError> {
        let value: serde_json::Value = serde_json::from_str(text)
            .map_err(|e| ParamError::new("scene", format!("not valid JSON: {e}")))?;
        Self::from_value(value)
    }

    /// Validates a parsed JSON value, migrating older versions first.
    pub fn from_value(value: serde_json::Value) -> Result<Self, ParamError> {
        let value = migrate(value)?;
        let scene: Scene =
            serde_path_to_error::deserialize(value).map_err(|e| at_path("scene", e))?;
        scene.validate()?;
        Ok(scene)
    }
}

/// Brings an older scene up to the current version (version 1 is the first, so only checks).
fn migrate(value: serde_json::Value) -> Result<serde_json::Value, ParamError> {
    let obj = value
        .as_object()
        .ok_or_else(|| ParamError::new("scene", "must be a JSON object"))?;
    match obj.get("version") {
        None => Err(ParamError::new(
            "version",
            format!("missing: a scene names its format version (current: {SCENE_VERSION})"),
        )),
        Some(v) if v.as_u64() == Some(SCENE_VERSION as u64) => Ok(value),
        Some(v) => Err(ParamError::new(
            "version",
            format!("unsupported scene version {v}; this build reads version {SCENE_VERSION}"),
        )),
    }
}

impl BlobList {
    /// Parses and validates a blob list from a JSON value; errors name the JSON path.
    pub fn from_value(value: serde_json::Value) -> Result<Self, ParamError> {
        Self::checked(serde_path_to_error::deserialize(value))
    }

    /// Parses and validates a blob list straight from JSON text, without the intermediate
    /// `serde_json::Value` (a tenth of the memory for a long list); errors name the JSON path.
    pub fn from_json(text: &str) -> Result<Self, ParamError> {
        let mut de = serde_json::Deserializer::from_str(text);
        let list = Self::checked(serde_path_to_error::deserialize(&mut de))?;
        de.end()
            .map_err(|e| ParamError::new("blob_list", format!("not valid JSON: {e}")))?;
        Ok(list)
    }

    /// A deserialised list, validated, or the error at its JSON path.
    fn checked(
        list: Result<Self, serde_path_to_error::Error<serde_json::Error>>,
    ) -> Result<Self, ParamError> {
        let list = list.map_err(|e| at_path("blob_list", e))?;
        list.validate()?;
        Ok(list)
    }
}
