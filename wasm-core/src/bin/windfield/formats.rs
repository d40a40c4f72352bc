//! What an `--out` names by its extension, and the refusal of a name whose extension is not
//! one of the formats the command writes: the bytes of one format are never written under the
//! name of another (PNG under `.jpg`, OpenVDB under `.txt`). A name without an extension takes
//! the command's own format; so does a frame pattern whose last dot comes before its frame
//! number (`seq/frame.%03d`).
//!
//! The extension of another image format (`.jpg`, …) is refused with the flags
//! ([`image_format`]); any other extension a command does not write, once its input is read and
//! before the work starts ([`Writes::check`]), so that a missing or bad input is told first.

use super::failure::Failure;
use std::path::Path;
use windfield::export::still::StillFormat;

/// The formats a command writes, in words and by their extensions (lower case).
pub struct Writes {
    formats: &'static str,
    extensions: &'static [&'static str],
}

/// `render` and `flipbook`: PNG, or OpenEXR for a name ending in `.exr`.
pub const IMAGES: Writes = Writes {
    formats: "PNG or OpenEXR images",
    extensions: &["png", "exr"],
};

/// `volume`: OpenVDB.
pub const VOLUMES: Writes = Writes {
    formats: "OpenVDB volumes",
    extensions: &["vdb"],
};

/// `simulate`: the blob list as JSON.
pub const BLOB_LISTS: Writes = Writes {
    formats: "blob lists as JSON",
    extensions: &["json"],
};

/// `generate`: the lattice as NumPy, or one time slice of the wind as OpenVDB or a raw texture.
pub const FIELDS: Writes = Writes {
    formats: "fields as NumPy .npy and the wind as OpenVDB or RGB32F",
    extensions: &["npy", "vdb", "rgb32f"],
};

impl Writes {
    /// Refuses an `out` whose extension names a format other than these.
    pub fn check(&self, out: &Path) -> Result<(), Failure> {
        match extension(out) {
            Some(e) if !self.extensions.contains(&e.as_str()) => Err(self.refusal(&e)),
            _ => Ok(()),
        }
    }

    /// The refusal of an `--out` ending in `.extension`.
    fn refusal(&self, extension: &str) -> Failure {
        Failure::Input(format!(
            "--out: windfield writes {}, not .{extension} (name the file {})",
            self.formats,
            self.names()
        ))
    }

    /// The extensions as a person lists them: `.png or .exr`, `.npy, .vdb or .rgb32f`.
    fn names(&self) -> String {
        let dotted: Vec<String> = self.extensions.iter().map(|e| format!(".{e}")).collect();
        match dotted.split_last() {
            Some((last, [])) => last.clone(),
            Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
            None => String::new(),
        }
    }
}

/// The extension of `out`, in lower case; none for a name without one, or when what follows
/// the last dot is a frame number's `%0Nd`.
pub fn extension(out: &Path) -> Option<String> {
    out.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .filter(|e| !e.contains('%'))
}

/// Extensions of image formats windfield does not write: an `--out` naming one is refused
/// with the flags, rather than given PNG bytes under that name.
const OTHER_IMAGE_FORMATS: [&str; 10] = [
    "jpg", "jpeg", "webp", "gif", "bmp", "tif", "tiff", "avif", "heic", "tga",
];

/// The image format an `--out` names: `.exr` OpenEXR, anything else PNG, but another image
/// format's extension (`.jpg`, …) is an error; [`IMAGES`] refuses the rest once the input is
/// read.
pub fn image_format(out: &Path) -> Result<StillFormat, Failure> {
    match extension(out) {
        Some(e) if OTHER_IMAGE_FORMATS.contains(&e.as_str()) => Err(IMAGES.refusal(&e)),
        _ => Ok(StillFormat::of_name(&out.to_string_lossy())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_out_is_refused_by_an_extension_its_command_does_not_write() {
        let refusal = |w: &Writes, name: &str| match w.check(Path::new(name)) {
            Err(Failure::Input(m)) => Some(m),
            _ => None,
        };
        assert_eq!(
            refusal(&IMAGES, "still.JPG").as_deref(),
            Some("--out: windfield writes PNG or OpenEXR images, not .jpg (name the file .png or .exr)")
        );
        assert_eq!(
            refusal(&VOLUMES, "gas.txt").as_deref(),
            Some("--out: windfield writes OpenVDB volumes, not .txt (name the file .vdb)")
        );
        assert!(refusal(&FIELDS, "f.json")
            .unwrap()
            .ends_with("(name the file .npy, .vdb or .rgb32f)"));
        for (w, name) in [
            (&IMAGES, "still.png"),
            (&IMAGES, "SHEET.EXR"),
            (&IMAGES, "frames/f%04d"),
            (&IMAGES, "seq/frame.%03d"),
            (&VOLUMES, "vdb/gas.%04d.vdb"),
            (&VOLUMES, "gas"),
            (&BLOB_LISTS, "blobs.json"),
            (&FIELDS, "wind.rgb32f"),
        ] {
            assert_eq!(refusal(w, name), None, "{name}");
        }
    }
}
