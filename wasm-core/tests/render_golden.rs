//! Golden stills: fixed inputs rendered and compared with committed PNGs at PSNR ≥ 45 dB (the
//! tolerance allows float differences between machines, not changes of behaviour).
//! Regenerate after an intended change with `npm run goldens` (sets WINDFIELD_REGENERATE=1).
//! The presets at scale have theirs in `at_scale`.

use std::path::PathBuf;
use windfield::render::{decode_png, encode_png, psnr, RenderOptions, Renderer};
use windfield::scene::blob_list::BlobList;
use windfield::{Scene, Simulation};

/// PSNR a still must reach against its golden image.
const TOLERANCE_DB: f64 = 45.0;

fn golden_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// The paper's scenes (§6), shipped in `public/scenes/`, with the time of their golden still,
/// and its remedy of §7 (smoke carried round a solid bridge).
pub const PRESETS: [(&str, f64); 6] = [
    ("steam-mug", 3.0),
    ("psychedelic-steam", 3.0),
    ("cigarette", 3.0),
    ("sphere-smoke", 4.0),
    ("morph", 1.5),
    ("bridge-smoke", 3.0),
];
/// Preset stills are compared at this size (the scenes' own size, 640×480, is for people).
pub const PRESET_SIZE: (u32, u32) = (160, 120);

pub fn presets_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../public/scenes")
}

/// Renders `name.json` (a blob list, or a scene simulated for `seconds`) to 8-bit RGB.
fn render(name: &str, seconds: f64) -> (u32, u32, Vec<u8>) {
    let list = read_list(&golden_dir().join(format!("{name}.json")), seconds);
    render_list(&list, None)
}

/// The blob list of a file: a blob list as it is, a scene simulated for `seconds`.
fn read_list(path: &std::path::Path, seconds: f64) -> BlobList {
    let text = std::fs::read_to_string(path).unwrap();
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    if value.get("version").is_some() {
        let mut sim = Simulation::new(Scene::from_value(value).unwrap()).unwrap();
        sim.run(sim.steps_for(seconds));
        sim.blob_list()
    } else {
        BlobList::from_value(value).unwrap()
    }
}

/// The reference still of `list` in 8-bit RGB.
fn render_list(list: &BlobList, size: Option<(u32, u32)>) -> (u32, u32, Vec<u8>) {
    let image = Renderer::new(list, size, RenderOptions::default())
        .unwrap()
        .render();
    (
        image.width,
        image.height,
        image.to_rgb8(list.image.encoding),
    )
}

fn check(name: &str, seconds: f64) {
    let (w, h, rgb) = render(name, seconds);
    compare(name, w, h, &rgb);
}

/// Compares with (or, when regenerating, writes) `tests/golden/NAME.png`.
pub fn compare(name: &str, w: u32, h: u32, rgb: &[u8]) {
    let path = golden_dir().join(format!("{name}.png"));
    if std::env::var_os("WINDFIELD_REGENERATE").is_some() {
        std::fs::write(&path, encode_png(w, h, rgb).unwrap()).unwrap();
        return;
    }
    let bytes = std::fs::read(&path)
        .unwrap_or_else(|_| panic!("{} missing: run `npm run goldens`", path.display()));
    let (gw, gh, golden) = decode_png(&bytes).unwrap();
    assert_eq!((gw, gh), (w, h), "{name}: size changed");
    let p = psnr(rgb, &golden);
    assert!(
        p >= TOLERANCE_DB,
        "{name}: PSNR {p:.1} dB against the golden still (need {TOLERANCE_DB})"
    );
}

#[test]
fn golden_plume() {
    check("plume", 4.0);
}

#[test]
fn golden_colours() {
    check("colours", 0.0);
}

/// Every preset validates, simulates and renders a still that is not blank (its pixels vary,
/// and the gas changes the image: PSNR against the same frame without blobs below 30 dB), and
/// the still matches its golden image.
#[test]
fn golden_presets() {
    for (name, seconds) in PRESETS {
        let path = presets_dir().join(format!("{name}.json"));
        let mut list = read_list(&path, seconds);
        let (w, h, rgb) = render_list(&list, Some(PRESET_SIZE));
        list.blobs.clear();
        let (_, _, bare) = render_list(&list, Some(PRESET_SIZE));
        let p = psnr(&rgb, &bare);
        assert!(
            p < 30.0,
            "{name}: the gas barely shows ({p:.1} dB from the bare frame)"
        );
        let n = rgb.len() as f64;
        let mean = rgb.iter().map(|&v| v as f64).sum::<f64>() / n;
        let var = rgb.iter().map(|&v| (v as f64 - mean).powi(2)).sum::<f64>() / n;
        assert!(
            var.sqrt() > 8.0,
            "{name}: the still is nearly flat (sd {:.1})",
            var.sqrt()
        );
        compare(&format!("preset-{name}"), w, h, &rgb);
    }
}

/// The plumes are many small blobs (the paper's look): each holds at least 20,000 blobs at
/// t = 4 s, and the morph's two shapes together hold as many.
#[test]
fn presets_hold_many_blobs() {
    for (name, _) in PRESETS {
        let path = presets_dir().join(format!("{name}.json"));
        let value: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        let mut sim = Simulation::new(Scene::from_value(value).unwrap()).unwrap();
        let seconds = if name == "morph" { 0.0 } else { 4.0 };
        sim.run(sim.steps_for(seconds));
        let count = sim.blobs().len();
        println!("{name}: {count} blobs at t = {seconds} s");
        assert!(count >= 20_000, "{name}: {count} blobs at t = {seconds} s");
    }
}
