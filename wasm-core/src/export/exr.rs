//! OpenEXR stills and sheets (`.exr`), written with the `exr` crate (pure Rust, BSD-3-Clause;
//! it builds for wasm32 too, so the browser writes the same bytes): one scan-line part, ZIP
//! compression (16 lines a block), channels R, G, B, A as half floats, linear radiance,
//! premultiplied by alpha as OpenEXR expects (an opaque still has A = 1).
//!
//! Header attributes, beyond the required ones:
//!
//! - `worldToCamera` (m44f): world to camera space, OpenEXR's convention: row vectors
//!   (p′ = p·M), camera space left-handed with x right, y up and z along the view.
//! - `worldToNDC` (m44f): world to normalised device coordinates, (0, 0) the top left and
//!   (1, 1) the bottom right of the display window, after the division by w.
//! - `vFov`, `hFov` (float): the full vertical and horizontal angles of view (degrees).
//! - `windfieldTime` (float): the scene's time (s), when the image is one moment of a scene.
//! - `software`, `comments` (string): windfield's version; the camera in words.
//!
//! Attributes are written in a fixed order, and the angles computed with `libm` (as in
//! WebAssembly), so the same image gives the same bytes natively and in the browser.

use crate::scene::blob_list::Camera;
use exr::meta::attribute::{AttributeValue, Text};
use exr::prelude::{
    Blocks, Compression, Encoding, Image, Layer, LayerAttributes, LineOrder, SpecificChannels,
    Vec2, WritableImage,
};
use glam::Vec3;
use half::f16;

/// What the header says about the image: its camera and, for a scene, its time.
#[derive(Debug, Clone, PartialEq)]
pub struct ExrInfo {
    pub camera: Option<Camera>,
    pub time: Option<f64>,
    /// For sheets and sequences: frames per second.
    pub fps: Option<f64>,
    /// Free text for `comments`, after the camera.
    pub note: String,
}

/// Camera space as OpenEXR's `worldToCamera` wants it, row-major for row vectors.
pub fn world_to_camera(camera: &Camera) -> [f32; 16] {
    let o = Vec3::from_array(camera.position);
    let f = (Vec3::from_array(camera.target) - o).normalize();
    let r = f.cross(Vec3::from_array(camera.up)).normalize();
    let u = r.cross(f);
    [
        r.x,
        u.x,
        f.x,
        0.0,
        r.y,
        u.y,
        f.y,
        0.0,
        r.z,
        u.z,
        f.z,
        0.0,
        -r.dot(o),
        -u.dot(o),
        -f.dot(o),
        1.0,
    ]
}

/// World to NDC for an image of `aspect` = width/height: x_n = ½ + ½ x_c/(z_c tan(fx/2)),
/// y_n = ½ − ½ y_c/(z_c tan(fy/2)), z_n = 1, after dividing by w = z_c.
pub fn world_to_ndc(camera: &Camera, aspect: f32) -> [f32; 16] {
    let ty = libm::tanf(camera.fov_y_deg.to_radians() * 0.5);
    let tx = ty * aspect;
    let projection = [
        [0.5 / tx, 0.0, 0.0, 0.0],
        [0.0, -0.5 / ty, 0.0, 0.0],
        [0.5, 0.5, 1.0, 1.0],
        [0.0, 0.0, 0.0, 0.0],
    ];
    let m = world_to_camera(camera);
    let mut out = [0.0f32; 16];
    for row in 0..4 {
        for col in 0..4 {
            out[4 * row + col] = (0..4).map(|k| m[4 * row + k] * projection[k][col]).sum();
        }
    }
    out
}

/// The `.exr` bytes of a `width × height` image whose pixel (x, y) (row 0 at the top) has the
/// premultiplied linear RGBA `pixel(x, y)`, with `info` in the header.
pub fn write(
    width: u32,
    height: u32,
    pixel: impl Fn(usize, usize) -> [f32; 4] + Sync,
    info: &ExrInfo,
) -> Result<Vec<u8>, String> {
    let mut attributes = LayerAttributes {
        software_name: Some(Text::from(
            format!("windfield {}", env!("CARGO_PKG_VERSION")).as_str(),
        )),
        ..LayerAttributes::default()
    };
    let mut comments = String::new();
    if let Some(c) = &info.camera {
        let aspect = width as f32 / height as f32;
        attributes.world_to_camera = Some(world_to_camera(c));
        attributes.world_to_normalized_device = Some(world_to_ndc(c, aspect));
        attributes.vertical_field_of_view = Some(c.fov_y_deg);
        let h = 2.0 * libm::atanf(libm::tanf(c.fov_y_deg.to_radians() * 0.5) * aspect);
        attributes.horizontal_field_of_view = Some(h.to_degrees());
        comments = format!(
            "camera at {:?} looking at {:?}, up {:?}, vertical field of view {} degrees",
            c.position, c.target, c.up, c.fov_y_deg
        );
    }
    if let Some(t) = info.time {
        attributes
            .other
            .insert(Text::from("windfieldTime"), AttributeValue::F32(t as f32));
        comments = format!("t = {t} s; {comments}");
    }
    if let Some(fps) = info.fps {
        // A rational with a millionth's resolution.
        let den = 1_000_000u32;
        attributes.frames_per_second = Some(((fps * den as f64).round() as i32, den));
    }
    if !info.note.is_empty() {
        comments = format!("{comments}; {}", info.note);
    }
    if !comments.is_empty() {
        attributes.comments = Some(Text::from(comments.trim_start_matches("; ")));
    }
    let encoding = Encoding {
        compression: Compression::ZIP16,
        blocks: Blocks::ScanLines,
        line_order: LineOrder::Increasing,
    };
    let channels = SpecificChannels::rgba(|p: Vec2<usize>| {
        let v = pixel(p.x(), p.y());
        (
            f16::from_f32(v[0]),
            f16::from_f32(v[1]),
            f16::from_f32(v[2]),
            f16::from_f32(v[3]),
        )
    });
    let layer = Layer::new(
        (width as usize, height as usize),
        attributes,
        encoding,
        channels,
    );
    let image = Image::from_layer(layer);
    let mut out = std::io::Cursor::new(Vec::new());
    image
        .write()
        .non_parallel()
        .to_buffered(&mut out)
        .map_err(|e| format!("writing the EXR failed: {e}"))?;
    Ok(out.into_inner())
}

/// The size and premultiplied RGBA (f32, four a pixel, row 0 first) of an `.exr` written by
/// [`write`], or why not.
pub fn read_rgba(bytes: &[u8]) -> Result<(u32, u32, Vec<f32>), String> {
    use exr::prelude::{ReadChannels, ReadLayers};
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |size, _| (size, vec![0.0f32; 4 * size.area()]),
            |(size, data): &mut (Vec2<usize>, Vec<f32>),
             p: Vec2<usize>,
             (r, g, b, a): (f32, f32, f32, f32)| {
                let i = 4 * (p.y() * size.width() + p.x());
                data[i..i + 4].copy_from_slice(&[r, g, b, a]);
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(|e| format!("not a readable EXR: {e}"))?;
    let (size, data) = image.layer_data.channel_data.pixels;
    Ok((size.width() as u32, size.height() as u32, data))
}
