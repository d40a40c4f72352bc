//! Golden stills: fixed inputs rendered and compared with committed PNGs at PSNR ≥ 45 dB (the
//! tolerance allows float differences between machines, not changes of behaviour).
//! Regenerate after an intended change with `npm run goldens` (sets WINDFIELD_REGENERATE=1).

use std::path::PathBuf;
use windfield::blob_list::BlobList;
use windfield::render::{decode_png, encode_png, psnr, RenderOptions, Renderer};
use windfield::{Scene, Simulation};

/// PSNR a still must reach against its golden image.
const TOLERANCE_DB: f64 = 45.0;

fn golden_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// Renders `name.json` (a blob list, or a scene simulated for `seconds`) to 8-bit RGB.
fn render(name: &str, seconds: f64) -> (u32, u32, Vec<u8>) {
    let text = std::fs::read_to_string(golden_dir().join(format!("{name}.json"))).unwrap();
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    let list = if value.get("version").is_some() {
        let mut sim = Simulation::new(Scene::from_value(value).unwrap()).unwrap();
        sim.run(sim.steps_for(seconds));
        sim.blob_list()
    } else {
        BlobList::from_value(value).unwrap()
    };
    let image = Renderer::new(&list, None, RenderOptions::default())
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
    let path = golden_dir().join(format!("{name}.png"));
    if std::env::var_os("WINDFIELD_REGENERATE").is_some() {
        std::fs::write(&path, encode_png(w, h, &rgb).unwrap()).unwrap();
        return;
    }
    let bytes = std::fs::read(&path)
        .unwrap_or_else(|_| panic!("{} missing: run `npm run goldens`", path.display()));
    let (gw, gh, golden) = decode_png(&bytes).unwrap();
    assert_eq!((gw, gh), (w, h), "{name}: size changed");
    let p = psnr(&rgb, &golden);
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
