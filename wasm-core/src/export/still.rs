//! A rendered still in a file format: PNG (8-bit, the image's encoding; RGBA with straight
//! colour when it carries alpha) or OpenEXR (half-float linear RGBA, premultiplied).

use super::exr::{self, ExrInfo};
use crate::render::LinearImage;
use crate::scene::blob_list::Encoding;

/// The file formats of stills and sheets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StillFormat {
    Png,
    Exr,
}

impl StillFormat {
    /// Bytes a channel of a pixel takes while the image is made: 8-bit PNG, half-float EXR.
    pub fn bytes_per_channel(self) -> u64 {
        match self {
            Self::Png => 1,
            Self::Exr => 2,
        }
    }

    /// The format a file name asks for: `.exr` (any case) is OpenEXR, everything else PNG.
    pub fn of_name(name: &str) -> Self {
        if name.to_ascii_lowercase().ends_with(".exr") {
            Self::Exr
        } else {
            Self::Png
        }
    }

    /// `png` or `exr`, as the browser API names them.
    pub fn parse(name: &str, what: &str) -> Result<Self, crate::ParamError> {
        match name {
            "png" => Ok(Self::Png),
            "exr" => Ok(Self::Exr),
            _ => Err(crate::ParamError::new(
                what,
                format!("must be \"png\" or \"exr\" (got {name:?})"),
            )),
        }
    }
}

/// Premultiplied linear RGBA of pixel `p` of `image` (alpha 1 when it carries none).
pub fn premultiplied(image: &LinearImage, p: usize) -> [f32; 4] {
    let c = &image.data[3 * p..3 * p + 3];
    let a = image.alpha.as_ref().map_or(1.0, |a| a[p]);
    [c[0], c[1], c[2], a]
}

/// The file bytes of `image` in `format` (`encoding` for PNG, `info` for the EXR header).
pub fn encode(
    image: &LinearImage,
    format: StillFormat,
    encoding: Encoding,
    info: &ExrInfo,
) -> Result<Vec<u8>, String> {
    match format {
        StillFormat::Png => image.to_png(encoding).map_err(|e| e.to_string()),
        StillFormat::Exr => {
            let w = image.width as usize;
            exr::write(
                image.width,
                image.height,
                |x, y| premultiplied(image, y * w + x),
                info,
            )
        }
    }
}
