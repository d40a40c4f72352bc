//! Exports (docs/FORMATS.md, exports): transparent stills against stills over a colour for
//! every preset, OpenEXR pixels and header against the renderer, flipbook tiles (and loops)
//! against stills, and the budgets refused before any work. The files' own readers (OpenEXR's
//! and OpenVDB's Python bindings) are held to the CLI's output in
//! `tests/pipeline-readers.test.js`.

#![allow(clippy::needless_range_loop)] // pixels and channels read best by index

use std::path::PathBuf;
use windfield::export::exr::{self, ExrInfo};
use windfield::export::flipbook::{FlipbookJob, FlipbookSpec, SettingNames};
use windfield::export::still::{self, StillFormat};
use windfield::export::volume::VolumeBuild;
use windfield::render::image::srgb_encode;
use windfield::render::{decode_png, LinearImage, RenderOptions, Renderer};
use windfield::scene::blob_list::{Background, BlobList, Encoding};
use windfield::{Scene, Simulation};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn scene(path: &str) -> Scene {
    Scene::from_json(&std::fs::read_to_string(root().join(path)).unwrap()).unwrap()
}

fn presets() -> Vec<(String, Scene)> {
    let mut out: Vec<(String, Scene)> = std::fs::read_dir(root().join("public/scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .map(|p| {
            let name = p.file_stem().unwrap().to_string_lossy().to_string();
            (
                name,
                Scene::from_json(&std::fs::read_to_string(&p).unwrap()).unwrap(),
            )
        })
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

fn render(list: &BlobList) -> LinearImage {
    Renderer::new(list, None, RenderOptions::default())
        .unwrap()
        .render()
}

/// The sRGB curve's inverse (IEC 61966-2-1) of a code value in [0, 1].
fn srgb_decode(v: f64) -> f64 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// The farthest a linear value coded as the 8-bit `b` of `encoding` lies from the code's own
/// value (half a step in `linear`; in `srgb` the larger side, the curve being convex).
fn half_step(b: u8, encoding: Encoding) -> f64 {
    match encoding {
        Encoding::Linear => 0.5 / 255.0,
        Encoding::Srgb => {
            let at = |c: f64| srgb_decode((c / 255.0).clamp(0.0, 1.0));
            let c = f64::from(b);
            (at(c + 0.5) - at(c)).max(at(c) - at(c - 0.5))
        }
    }
}

/// Decodes an 8-bit code to linear light.
fn decode(b: u8, encoding: Encoding) -> f64 {
    match encoding {
        Encoding::Linear => f64::from(b) / 255.0,
        Encoding::Srgb => srgb_decode(f64::from(b) / 255.0),
    }
}

/// For every preset: a still over a transparent background, composited over a colour c in
/// linear light, is the still rendered with background c. In floats the compositing is exact
/// (radiance = premultiplied colour + (1 − α) c, the extinction being grey in every preset);
/// through the 8-bit RGBA PNG, in the `linear` encoding the composite is within 1/255 of the
/// still's radiance, and in `srgb` within the PNG's own quantisation at that pixel (half an
/// 8-bit step of the straight colour, times α, plus half a step of α times |straight − c|).
#[test]
fn transparent_stills_composite_to_the_stills_over_a_colour_for_every_preset() {
    let c = [0.21f32, 0.47, 0.83];
    let all = presets();
    assert!(all.len() >= 10, "{} presets", all.len());
    let mut translucent_pixels = 0;
    for (name, mut scene) in all {
        scene.render.image.width = 48;
        scene.render.image.height = 36;
        let mut sim = Simulation::new(scene).unwrap();
        let steps = sim.steps_for(0.6);
        sim.run(steps);
        let mut over = sim.blob_list();
        assert!(!over.blobs.is_empty(), "{name}: no gas at 0.6 s");
        over.background = Background::Colour(c);
        let mut clear = over.clone();
        clear.background = Background::Transparent;
        let (opaque, transparent) = (render(&over), render(&clear));
        assert!(opaque.alpha.is_none());
        let alpha = transparent.alpha.as_ref().unwrap();
        // Gas over the sky is translucent; gas over a floor (car-exhaust) is not.
        let translucent = alpha.iter().filter(|&&a| a > 0.01 && a < 0.99).count();
        translucent_pixels += translucent;
        for p in 0..alpha.len() {
            for ch in 0..3 {
                let composite = transparent.data[3 * p + ch] + (1.0 - alpha[p]) * c[ch];
                let want = opaque.data[3 * p + ch];
                assert!(
                    (composite - want).abs() <= 1e-5 * want.max(1.0),
                    "{name}: pixel {p} channel {ch}: {composite} vs {want}"
                );
            }
        }
        for encoding in [Encoding::Linear, Encoding::Srgb] {
            let png = transparent.to_png(encoding).unwrap();
            let rgba = decode_rgba(&png);
            let mut worst = 0.0f64;
            let mut clipped = 0;
            for p in 0..alpha.len() {
                let a = f64::from(rgba[4 * p + 3]) / 255.0;
                for ch in 0..3 {
                    let s8 = rgba[4 * p + ch];
                    let s = decode(s8, encoding);
                    let want = f64::from(opaque.data[3 * p + ch].clamp(0.0, 1.0));
                    let straight = f64::from(transparent.data[3 * p + ch] / alpha[p].max(1e-30));
                    // PNG clips straight colour at 1 (EXR keeps it): the composite then lacks
                    // exactly α·(straight − 1).
                    let lost = if straight > 1.0 {
                        clipped += 1;
                        a * (straight - 1.0)
                    } else {
                        0.0
                    };
                    let composite = s * a + f64::from(c[ch]) * (1.0 - a);
                    // First-order accounting of the PNG's rounding: the straight colour's
                    // code (half a step, times α), α's code (its error times the distance
                    // from straight colour to c), and the clipping above.
                    let alpha_error = (f64::from(alpha[p]) - a).abs();
                    let tolerance = a * half_step(s8, encoding)
                        + alpha_error * (straight - f64::from(c[ch])).abs()
                        + lost
                        + 1e-6;
                    let err = (composite - want).abs();
                    assert!(
                        err <= tolerance,
                        "{name} ({encoding:?}): pixel {p} channel {ch}: composite {composite} vs still {want} (tolerance {tolerance})"
                    );
                    if lost == 0.0 {
                        worst = worst.max(err * 255.0);
                    }
                }
            }
            // Thin, brightly lit gas (morph) has straight colour above 1 where α is small.
            eprintln!("{name} ({encoding:?}): {clipped} channels clipped, worst {worst:.3}/255");
            // In the linear encoding that bound is at most 1/255 wherever the colour fits.
            if encoding == Encoding::Linear {
                assert!(worst <= 1.0 + 1e-3, "{name}: worst {worst}/255");
            }
        }
    }
    // Not only sky (α = 0) and objects (α = 1): gas over the sky, partly transparent.
    assert!(
        translucent_pixels >= 50,
        "{translucent_pixels} translucent pixels"
    );
}

/// Straight RGBA of an RGBA PNG.
fn decode_rgba(png: &[u8]) -> Vec<u8> {
    let decoder = png::Decoder::new(std::io::Cursor::new(png));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgba);
    buf.truncate(4 * (info.width * info.height) as usize);
    buf
}

/// Alpha is 1 on opaque objects and in the sky 0, and an opaque still's PNG stays 8-bit RGB.
#[test]
fn alpha_is_one_on_objects_and_zero_in_empty_sky() {
    let mut list = BlobList::from_value(serde_json::json!({
        "camera": {"position": [0, 0, 5], "target": [0, 0, 0]},
        "image": {"width": 16, "height": 8},
        "objects": [{"type": "sphere", "center": [-1.5, 0, 0], "radius": 0.8, "color": [0.5, 0.5, 0.5]}],
        "background": "transparent",
        "blobs": [{"center": [1.5, 0, 0], "sigma": 0.3, "mass": 0.2}]
    }))
    .unwrap();
    let image = render(&list);
    let alpha = image.alpha.as_ref().unwrap();
    let at = |i: usize, j: usize| alpha[j * 16 + i];
    assert_eq!(at(4, 4), 1.0, "the sphere");
    assert_eq!(at(0, 0), 0.0, "the sky");
    assert!(
        at(12, 4) > 0.05 && at(12, 4) < 1.0,
        "the gas: {}",
        at(12, 4)
    );
    // Where the sky is empty the colour is zero (premultiplied), so straight colour is 0 too.
    assert_eq!(&image.data[..3], &[0.0; 3]);
    list.background = Background::Colour([0.1, 0.2, 0.3]);
    let png = render(&list).to_png(Encoding::Srgb).unwrap();
    assert_eq!(decode_png(&png).unwrap().2.len(), 16 * 8 * 3);
    assert_eq!(png[25], 2, "colour type 2: RGB");
}

/// The EXR holds the renderer's premultiplied radiance in half floats, alpha 1 when opaque,
/// and its header the camera: worldToCamera takes the camera to the origin and the target
/// onto +z, worldToNDC the target to the image's centre.
#[test]
fn exr_pixels_are_the_radiance_in_half_floats_and_the_header_holds_the_camera() {
    let mut sim = Simulation::new(scene("tests/fixtures/small-plume.json")).unwrap();
    sim.run(90);
    let mut list = sim.blob_list();
    list.image.width = 40;
    list.image.height = 30;
    for background in [Background::Transparent, Background::Colour([0.3, 0.2, 0.1])] {
        list.background = background;
        let image = render(&list);
        let info = ExrInfo {
            camera: Some(list.camera.clone()),
            time: Some(sim.time()),
            fps: None,
            note: String::new(),
        };
        let bytes = still::encode(&image, StillFormat::Exr, Encoding::Srgb, &info).unwrap();
        let (w, h, rgba) = exr::read_rgba(&bytes).unwrap();
        assert_eq!((w, h), (40, 30));
        for p in 0..(w * h) as usize {
            let want = still::premultiplied(&image, p);
            for ch in 0..4 {
                assert_eq!(
                    rgba[4 * p + ch],
                    half::f16::from_f32(want[ch]).to_f32(),
                    "pixel {p} channel {ch}"
                );
            }
        }
        assert_eq!(
            background.is_transparent(),
            rgba.chunks(4).any(|px| px[3] < 1.0)
        );
        // The same image, the same bytes.
        let again = still::encode(&image, StillFormat::Exr, Encoding::Srgb, &info).unwrap();
        assert_eq!(bytes, again);
    }
    let camera = &list.camera;
    let row = |m: &[f32; 16], p: [f32; 3]| -> [f32; 4] {
        let v = [p[0], p[1], p[2], 1.0];
        [0, 1, 2, 3].map(|c| (0..4).map(|r| v[r] * m[4 * r + c]).sum())
    };
    let m = exr::world_to_camera(camera);
    let origin = row(&m, camera.position);
    assert!(origin[..3].iter().all(|v| v.abs() < 1e-5), "{origin:?}");
    let target = row(&m, camera.target);
    let distance = (0..3)
        .map(|a| (camera.target[a] - camera.position[a]).powi(2))
        .sum::<f32>()
        .sqrt();
    assert!(target[0].abs() < 1e-5 && target[1].abs() < 1e-5);
    assert!((target[2] - distance).abs() < 1e-5, "{target:?}");
    let ndc = row(&exr::world_to_ndc(camera, 4.0 / 3.0), camera.target);
    assert!((ndc[0] / ndc[3] - 0.5).abs() < 1e-6 && (ndc[1] / ndc[3] - 0.5).abs() < 1e-6);
    // A point up and to the right of the target lands up and right in NDC (y down).
    let up_right = row(
        &exr::world_to_ndc(camera, 4.0 / 3.0),
        [
            camera.target[0] + 0.3,
            camera.target[1] + 0.2,
            camera.target[2],
        ],
    );
    assert!(up_right[0] / up_right[3] > 0.5 && up_right[1] / up_right[3] < 0.5);
}

const NAMES: SettingNames = SettingNames {
    frames: "--frames",
    fps: "--fps",
    grid: "--grid",
    tile: "--tile",
    fade: "--fade",
};

fn spec(start: u64, end: u64, fade: u32) -> FlipbookSpec {
    FlipbookSpec {
        start,
        end,
        fps: 12.0,
        columns: 3,
        rows: 2,
        tile_width: 40,
        tile_height: 30,
        fade,
    }
}

/// The still of frame k as a flipbook tile: simulated from 0 to k/fps, transparent, tile size.
fn tile_still(k: u64, fps: f64) -> LinearImage {
    let mut sim = Simulation::new(scene("tests/fixtures/small-plume.json")).unwrap();
    let steps = sim.steps_for(k as f64 / fps);
    sim.run(steps);
    let mut list = sim.blob_list();
    list.background = Background::Transparent;
    list.image.width = 40;
    list.image.height = 30;
    render(&list)
}

fn sheet_tile(sheet: &[u8], sheet_w: usize, k: usize) -> Vec<u8> {
    let (x0, y0) = (40 * (k % 3), 30 * (k / 3));
    (0..30)
        .flat_map(|y| {
            let at = 4 * ((y0 + y) * sheet_w + x0);
            sheet[at..at + 160].to_vec()
        })
        .collect()
}

/// Tile k of a sheet is the still of frame A + k, byte for byte; a tile past the last frame is
/// transparent black. With a loop, the first L tiles are the blend of frame A + k and frame
/// B + k with weights w_k = (k + 1)/(L + 1) and 1 − w_k, and the rest are the stills.
#[test]
fn flipbook_tiles_are_the_stills_of_their_frames_and_loops_blend_the_wrap() {
    let small = scene("tests/fixtures/small-plume.json");
    let names = &NAMES;
    let (bytes, description) = FlipbookJob::new(
        small.clone(),
        None,
        spec(10, 15, 0),
        StillFormat::Png,
        None,
        names,
    )
    .unwrap()
    .finish("sheet.png")
    .unwrap();
    assert_eq!(
        (description.sheet_width, description.sheet_height),
        (120, 60)
    );
    assert_eq!(description.frame_count, 5);
    assert_eq!(description.frame_times.len(), 5);
    let sheet = decode_rgba(&bytes);
    for k in 0..5u64 {
        let still = tile_still(10 + k, 12.0).to_rgba8(Encoding::Srgb);
        assert!(
            sheet_tile(&sheet, 120, k as usize) == still,
            "tile {k} differs from the still of frame {}",
            10 + k
        );
    }
    assert!(sheet_tile(&sheet, 120, 5).iter().all(|&b| b == 0));

    let (looped, description) =
        FlipbookJob::new(small, None, spec(10, 14, 2), StillFormat::Png, None, names)
            .unwrap()
            .finish("sheet.png")
            .unwrap();
    let l = description.looped.unwrap();
    assert_eq!(l.fade_frames, 2);
    assert!((l.field_periods - 4.0 / 12.0 / 8.0).abs() < 1e-12);
    let sheet = decode_rgba(&looped);
    for k in 0..4u64 {
        let head = tile_still(10 + k, 12.0);
        let want = if k < 2 {
            let tail = tile_still(14 + k, 12.0);
            let w = (k + 1) as f32 / 3.0;
            let mix = |a: &[f32], b: &[f32]| -> Vec<f32> {
                a.iter()
                    .zip(b)
                    .map(|(&a, &b)| w * a + (1.0 - w) * b)
                    .collect()
            };
            LinearImage {
                width: 40,
                height: 30,
                data: mix(&head.data, &tail.data),
                alpha: Some(mix(
                    head.alpha.as_ref().unwrap(),
                    tail.alpha.as_ref().unwrap(),
                )),
            }
        } else {
            head
        };
        assert!(
            sheet_tile(&sheet, 120, k as usize) == want.to_rgba8(Encoding::Srgb),
            "looped tile {k}"
        );
    }
}

/// The settings are checked before any work, each refusal naming the setting to change.
#[test]
fn flipbooks_and_volumes_over_their_budgets_are_refused_naming_the_setting() {
    let small = scene("tests/fixtures/small-plume.json");
    let refuse = |s: FlipbookSpec| {
        FlipbookJob::new(small.clone(), None, s, StillFormat::Png, None, &NAMES)
            .err()
            .expect("refused")
    };
    let e = refuse(spec(0, 7, 0));
    assert_eq!(e.path, "--grid");
    assert!(e.message.contains("cannot hold the 7 frames"), "{e}");
    let e = refuse(FlipbookSpec {
        columns: 64,
        rows: 1,
        tile_width: 512,
        ..spec(0, 4, 0)
    });
    assert!(
        e.path.contains("--tile") && e.message.contains("16384"),
        "{e}"
    );
    let e = refuse(FlipbookSpec {
        fps: 0.0,
        ..spec(0, 4, 0)
    });
    assert_eq!(e.path, "--fps");
    let e = refuse(spec(0, 4, 4));
    assert_eq!(e.path, "--fade");
    // A last frame past the step budget (10⁶ steps of 1/60 s).
    let e = refuse(FlipbookSpec {
        start: 24_000_000,
        end: 24_000_004,
        ..spec(0, 4, 0)
    });
    assert!(e.to_string().contains("simulation.dt"), "{e}");

    // A volume whose box would hold more than 2^28 voxels.
    let mut sim = Simulation::new(small).unwrap();
    sim.run(60);
    let list = sim.blob_list();
    let e = VolumeBuild::new(&list, 1e-4, "voxel")
        .err()
        .expect("refused");
    assert_eq!(e.path, "voxel");
    assert!(
        e.message.contains("2^28") && e.message.contains("use voxels of at least"),
        "{e}"
    );
    assert!(VolumeBuild::new(&list, 0.01, "voxel").is_ok());
}

/// Straight colour in the PNG is the premultiplied colour over alpha, encoded.
#[test]
fn png_alpha_carries_straight_colour() {
    let image = LinearImage {
        width: 2,
        height: 1,
        data: vec![0.25, 0.1, 0.0, 0.0, 0.0, 0.0],
        alpha: Some(vec![0.5, 0.0]),
    };
    let rgba = image.to_rgba8(Encoding::Srgb);
    let code = |v: f32| (255.0 * srgb_encode(v)).round() as u8;
    assert_eq!(rgba, vec![code(0.5), code(0.2), 0, 128, 0, 0, 0, 0]);
    assert_eq!(image.to_rgba8(Encoding::Linear)[..4], [128, 51, 0, 128]);
}
