//! The presets at scale: each simulated to its still's time (hundreds of thousands of blobs, the
//! showcase a million) and rendered, the still held to its golden image as in `render_golden`.
//! The longest tests of the binary, so their module's name sorts first among the long ones: the
//! harness starts tests in the order of their names, and these then run beside the short ones
//! rather than after them.

use crate::render_golden::{compare, presets_dir, PRESET_SIZE};
use windfield::render::{RenderOptions, Renderer};
use windfield::{Scene, Simulation};

/// The phenomena the paper names (§1), at scale: each preset and the time of its still (the
/// scene's `render.time`), where it holds at least [`AT_SCALE_BLOBS`] blobs.
pub const PRESETS_AT_SCALE: [(&str, f64); 4] = [
    ("mist", 6.0),
    ("dust-swirl", 6.0),
    ("car-exhaust", 6.0),
    ("chimney", 8.0),
];
/// Fewest blobs a preset at scale holds at its still's time.
const AT_SCALE_BLOBS: usize = 250_000;

/// The presets at scale hold at least 250,000 blobs at their still's time (the showcase a
/// million), and their stills match their golden images. One test each, so that they run side
/// by side.
fn golden_at_scale(name: &str) {
    let seconds = PRESETS_AT_SCALE
        .iter()
        .find(|(n, _)| *n == name)
        .expect("a preset at scale")
        .1;
    let path = presets_dir().join(format!("{name}.json"));
    let scene = Scene::from_json(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert_eq!(scene.render.time, Some(seconds), "{name}: render.time");
    let mut sim = Simulation::new(scene).unwrap();
    sim.run(sim.steps_for(seconds));
    let n = sim.blobs().len();
    assert!(n >= AT_SCALE_BLOBS, "{name}: {n} blobs at t = {seconds} s");
    if name == "chimney" {
        assert_eq!(n, 1_000_000);
    }
    let list = sim.blob_list();
    let image = Renderer::new(&list, Some(PRESET_SIZE), RenderOptions::default())
        .unwrap()
        .render();
    let rgb = image.to_rgb8(list.image.encoding);
    compare(&format!("preset-{name}"), image.width, image.height, &rgb);
}

#[test]
fn golden_mist_at_scale() {
    golden_at_scale("mist");
}

#[test]
fn golden_dust_swirl_at_scale() {
    golden_at_scale("dust-swirl");
}

#[test]
fn golden_car_exhaust_at_scale() {
    golden_at_scale("car-exhaust");
}

#[test]
fn golden_chimney_at_scale() {
    golden_at_scale("chimney");
}

/// Every preset at scale has its test above.
#[test]
fn every_preset_at_scale_is_tested() {
    let source = include_str!("at_scale.rs");
    for (name, _) in PRESETS_AT_SCALE {
        let call = format!("golden_at_scale(\"{name}\")");
        assert!(source.contains(&call), "{name} has no test");
    }
}
