//! Linear RGB images, their 8-bit encodings (docs/FORMATS.md: `linear` or the sRGB curve), PNG
//! files, and the PSNR the tests compare with. An image rendered over a transparent background
//! carries its coverage α; its colour is then premultiplied (the radiance over nothing), and its
//! PNG is RGBA with straight colour, as PNG expects.

use crate::scene::blob_list::Encoding;

/// Linear radiance, RGB interleaved, row 0 at the top; with `alpha`, premultiplied colour over
/// a transparent background and its coverage, one float a pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearImage {
    pub width: u32,
    pub height: u32,
    pub data: Vec<f32>,
    /// Coverage α in [0, 1] per pixel (1 − T(∞) over the gas, 1 on objects), or `None` for an
    /// opaque image (a background colour).
    pub alpha: Option<Vec<f32>>,
}

/// The sRGB transfer curve (IEC 61966-2-1) of a linear value in [0, 1]. The power is `libm`'s
/// `powf`, the one `f32::powf` is in WebAssembly, so that the native and the browser's stills
/// round every pixel the same way (the platform's own `powf` differs in the last bit now and
/// then, which moves a byte where a value sits on a rounding boundary).
pub fn srgb_encode(v: f32) -> f32 {
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * libm::powf(v, 1.0 / 2.4) - 0.055
    }
}

impl LinearImage {
    /// 8-bit RGB: byte = round(255·clamp(v)), after the sRGB curve for `Encoding::Srgb`.
    pub fn to_rgb8(&self, encoding: Encoding) -> Vec<u8> {
        self.data
            .iter()
            .map(|&v| {
                let v = v.clamp(0.0, 1.0);
                let v = match encoding {
                    Encoding::Srgb => srgb_encode(v),
                    Encoding::Linear => v,
                };
                (255.0 * v).round() as u8
            })
            .collect()
    }

    /// 8-bit RGBA with straight (un-premultiplied) colour: each channel c/α (0 where α = 0)
    /// encoded as [`Self::to_rgb8`] encodes it, α as round(255·α) (α is always linear). An
    /// opaque image gets α = 255.
    pub fn to_rgba8(&self, encoding: Encoding) -> Vec<u8> {
        let ones;
        let alpha = match &self.alpha {
            Some(a) => a,
            None => {
                ones = vec![1.0; (self.width * self.height) as usize];
                &ones
            }
        };
        let straight = LinearImage {
            width: self.width,
            height: self.height,
            data: self
                .data
                .chunks_exact(3)
                .zip(alpha)
                .flat_map(|(c, &a)| {
                    let inv = if a > 0.0 { 1.0 / a } else { 0.0 };
                    [c[0] * inv, c[1] * inv, c[2] * inv]
                })
                .collect(),
            alpha: None,
        };
        straight
            .to_rgb8(encoding)
            .chunks_exact(3)
            .zip(alpha)
            .flat_map(|(c, &a)| [c[0], c[1], c[2], (255.0 * a.clamp(0.0, 1.0)).round() as u8])
            .collect()
    }

    /// The still as PNG bytes: 8-bit RGB when opaque, 8-bit RGBA (straight colour) when it
    /// carries alpha.
    pub fn to_png(&self, encoding: Encoding) -> Result<Vec<u8>, png::EncodingError> {
        match self.alpha {
            None => encode_png(self.width, self.height, &self.to_rgb8(encoding)),
            Some(_) => encode_png_rgba(self.width, self.height, &self.to_rgba8(encoding)),
        }
    }
}

/// Encodes 8-bit RGB as PNG bytes.
pub fn encode_png(width: u32, height: u32, rgb: &[u8]) -> Result<Vec<u8>, png::EncodingError> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header()?;
        writer.write_image_data(rgb)?;
    }
    Ok(out)
}

/// Encodes 8-bit RGBA (straight colour) as PNG bytes.
pub fn encode_png_rgba(
    width: u32,
    height: u32,
    rgba: &[u8],
) -> Result<Vec<u8>, png::EncodingError> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, width, height);
        enc.set_color(png::ColorType::Rgba);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header()?;
        writer.write_image_data(rgba)?;
    }
    Ok(out)
}

/// Decodes an 8-bit RGB or RGBA PNG into (width, height, RGB bytes).
pub fn decode_png(bytes: &[u8]) -> Result<(u32, u32, Vec<u8>), String> {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().map_err(|e| e.to_string())?;
    let mut buf = vec![0; reader.output_buffer_size().ok_or("image too large")?];
    let info = reader.next_frame(&mut buf).map_err(|e| e.to_string())?;
    if info.bit_depth != png::BitDepth::Eight {
        return Err("only 8-bit PNGs are supported".into());
    }
    let px = (info.width * info.height) as usize;
    let rgb = match info.color_type {
        png::ColorType::Rgb => buf[..3 * px].to_vec(),
        png::ColorType::Rgba => buf[..4 * px]
            .chunks_exact(4)
            .flat_map(|c| [c[0], c[1], c[2]])
            .collect(),
        other => return Err(format!("unsupported PNG colour type {other:?}")),
    };
    Ok((info.width, info.height, rgb))
}

/// Peak signal-to-noise ratio (dB) of two 8-bit images; infinity when equal.
pub fn psnr(a: &[u8], b: &[u8]) -> f64 {
    assert_eq!(a.len(), b.len(), "images differ in size");
    let mse = a
        .iter()
        .zip(b)
        .map(|(&x, &y)| (x as f64 - y as f64).powi(2))
        .sum::<f64>()
        / a.len() as f64;
    if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (255.0f64 * 255.0 / mse).log10()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encodings_and_png_round_trip() {
        let img = LinearImage {
            width: 2,
            height: 1,
            data: vec![0.0, 0.5, 1.0, 0.2, 2.0, -1.0],
            alpha: None,
        };
        assert_eq!(img.to_rgb8(Encoding::Linear), vec![0, 128, 255, 51, 255, 0]);
        assert_eq!(img.to_rgb8(Encoding::Srgb), vec![0, 188, 255, 124, 255, 0]);
        let bytes = encode_png(2, 1, &img.to_rgb8(Encoding::Srgb)).unwrap();
        assert_eq!(
            decode_png(&bytes).unwrap(),
            (2, 1, vec![0, 188, 255, 124, 255, 0])
        );
        assert!(psnr(&[10, 20], &[10, 20]).is_infinite());
        assert!((psnr(&[0, 0], &[0, 255]) - 10.0 * 2f64.log10()).abs() < 1e-9);
    }
}
