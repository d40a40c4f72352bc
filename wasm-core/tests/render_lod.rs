//! The GPU ray march's level of detail (`frame::lod`) against the exact blob list: the
//! reference renderer draws both, and the merged list must stay within a PSNR well above the
//! 30 dB the browser's ray march is held to, while a dense plume shrinks to a count that grows
//! far more slowly than its blob count.

use windfield::frame::lod::DEFAULT_FRACTION;
use windfield::frame::merge_blobs;
use windfield::render::{psnr, RenderOptions, Renderer};
use windfield::scene::blob_list::BlobList;
use windfield::{Scene, Simulation};

/// PSNR the merged list's still must reach against the exact list's.
const LOD_TOLERANCE_DB: f64 = 40.0;
const SIZE: (u32, u32) = (160, 120);

fn scenes_dir() -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../public/scenes")
}

fn scene_file(name: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(scenes_dir().join(format!("{name}.json"))).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn simulate(scene: serde_json::Value, seconds: f64) -> BlobList {
    let mut sim = Simulation::new(Scene::from_value(scene).unwrap()).unwrap();
    sim.run(sim.steps_for(seconds));
    sim.blob_list()
}

/// A dense plume: the small plume (a disk at the origin, `tests/fixtures/small-plume.json`)
/// emitting `n` blobs in its first half second, without dissipation.
fn bench_plume(n: usize) -> BlobList {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/fixtures/small-plume.json"),
    )
    .unwrap();
    let mut scene: serde_json::Value = serde_json::from_str(&text).unwrap();
    scene["emitters"][0]["rate"] = (2 * n).into();
    scene["gas"]["max_blobs"] = n.into();
    scene["gas"]["dissipation"] = 0.into();
    scene["gas"]["min_mass"] = 0.into();
    let mut list = simulate(scene, 0.55);
    // Close up: the plume fills the frame.
    list.camera.position = [0.0, 0.15, 0.7];
    list.camera.target = [0.0, 0.12, 0.0];
    list
}

fn still(list: &BlobList) -> Vec<u8> {
    Renderer::new(list, Some(SIZE), RenderOptions::default())
        .unwrap()
        .render()
        .to_rgb8(list.image.encoding)
}

/// Renders `list` exact and merged; returns (PSNR, merged count).
fn compare(list: &BlobList, fraction: f32) -> (f64, usize) {
    let mut merged = list.clone();
    merged.blobs = merge_blobs(&list.blobs, list.medium.albedo, fraction);
    (psnr(&still(list), &still(&merged)), merged.blobs.len())
}

#[test]
fn dense_plumes_merge_to_a_nearly_constant_count_and_look_the_same() {
    let mut counts = Vec::new();
    for n in [1000, 16000] {
        let list = bench_plume(n);
        assert_eq!(list.blobs.len(), n);
        let (p, merged) = compare(&list, DEFAULT_FRACTION);
        eprintln!("plume {n}: {merged} merged blobs, {p:.1} dB");
        assert!(p >= LOD_TOLERANCE_DB, "plume {n}: {p:.1} dB");
        counts.push(merged);
    }
    // 16× the blobs in the same volume: the merged count grows by far less.
    assert!(counts[1] < 4 * counts[0], "{counts:?}");
}

#[test]
fn presets_merge_within_tolerance() {
    for (name, seconds) in [
        ("steam-mug", 3.0),
        ("psychedelic-steam", 3.0),
        ("cigarette", 3.0),
        ("sphere-smoke", 4.0),
        ("morph", 1.5),
    ] {
        let list = simulate(scene_file(name), seconds);
        let (p, merged) = compare(&list, DEFAULT_FRACTION);
        eprintln!("{name}: {} → {merged} blobs, {p:.1} dB", list.blobs.len());
        assert!(p >= LOD_TOLERANCE_DB, "{name}: {p:.1} dB");
    }
}
