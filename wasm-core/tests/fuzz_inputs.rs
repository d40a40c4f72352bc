//! A mutation fuzzer over everything the core reads from outside: scenes, blob lists and `.npy`
//! fields. Inputs are mutated from a corpus of real files (byte flips, insertions, deletions,
//! splices, and JSON-aware edits: extreme numbers, wrong types, missing and unknown keys,
//! long arrays, deep nesting) with a fixed seed. Every input must be accepted or refused with a
//! message; none may panic. Accepted scenes are built into simulations and stepped, accepted
//! blob lists rendered, so that what the parsers let through is safe to use too.
//!
//! The corpus includes the hostile inputs of `tests/hostile/` (floods of emitters, shapes and
//! kept steps, long lists, deep nesting, a vanishing temporal spread), each of which once made
//! the core allocate gigabytes, abort or fill a field with NaN; a test of its own checks that
//! each is still refused with its JSON path (or, for σ → 0, gives a finite field).
//!
//! `WINDFIELD_FUZZ_INPUTS` sets the number of inputs (default 120,000, shared between the
//! three targets; `npm run fuzz` runs 1,000,000 or more). The summary is printed on stdout.

use rand_xoshiro::rand_core::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use serde_json::Value;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use windfield::field::npy;
use windfield::field::spectrum::SpectrumParams;
use windfield::field::{FieldParams, TurbulentField};
use windfield::render::{RenderOptions, Renderer};
use windfield::scene::blob_list::BlobList;
use windfield::scene::limits::MAX_LIST_BLOBS;
use windfield::{Scene, Simulation};

const DEFAULT_INPUTS: usize = 120_000;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn read_dir_json(dir: &str) -> Vec<Vec<u8>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root().join(dir))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    files.iter().map(|p| std::fs::read(p).unwrap()).collect()
}

/// Scenes: the presets, the test fixtures and the hostile inputs.
fn scene_corpus() -> Vec<Vec<u8>> {
    let mut c = read_dir_json("public/scenes");
    c.extend(read_dir_json("tests/fixtures"));
    c.extend(read_dir_json("wasm-core/examples"));
    c.extend(read_dir_json("wasm-core/tests/hostile"));
    c
}

/// Blob lists: the golden inputs, and one simulated from a preset (first 40 blobs).
fn blob_list_corpus() -> Vec<Vec<u8>> {
    let mut c = read_dir_json("wasm-core/tests/golden");
    let scene = Scene::from_json(&String::from_utf8(scene_corpus()[0].clone()).unwrap()).unwrap();
    let mut sim = Simulation::new(scene).unwrap();
    sim.run(60);
    let mut list = sim.blob_list();
    list.blobs.truncate(40);
    c.push(serde_json::to_vec(&list).unwrap());
    c
}

/// The hostile `.npy` files of `tests/hostile/`.
fn hostile_npy() -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root().join("wasm-core/tests/hostile"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "npy"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| {
            let name = p.file_name().unwrap().to_str().unwrap().to_string();
            (name, std::fs::read(p).unwrap())
        })
        .collect()
}

/// `.npy` fields: small syntheses of a few shapes, one with a NaN in it, and the hostile ones.
fn npy_corpus() -> Vec<Vec<u8>> {
    let mut corpus: Vec<Vec<u8>> = [
        ([4, 4, 4, 4], None),
        ([8, 4, 4, 8], None),
        ([4, 4, 4, 4], Some(77)),
    ]
    .iter()
    .map(|&(size, nan)| {
        let mut params = FieldParams {
            size,
            ..FieldParams::default()
        };
        params.spectrum.k_inertial = 1.0;
        let mut field = TurbulentField::generate(&params).unwrap();
        if let Some(i) = nan {
            field.data[i] = f32::NAN;
        }
        let [nx, ny, nz, nt] = size;
        let mut bytes = Vec::new();
        npy::write_f32(&mut bytes, &[nt, nz, ny, nx, 3], &field.data).unwrap();
        bytes
    })
    .collect();
    corpus.extend(hostile_npy().into_iter().map(|(_, bytes)| bytes));
    corpus
}

struct Mutator {
    rng: Xoshiro256PlusPlus,
}

/// Numbers at the edges of what parsers and arithmetic meet.
const INTERESTING: &[&str] = &[
    "0",
    "-0",
    "-1",
    "1",
    "2",
    "3",
    "7",
    "255",
    "256",
    "65536",
    "1e308",
    "-1e308",
    "1e-308",
    "1e999",
    "-1e999",
    "9007199254740993",
    "4294967296",
    "-2147483649",
    "0.5",
    "1e-45",
    "3.4e38",
    "1e6",
    "1e7",
    "1e12",
    "-3",
    "0.000001",
    "18446744073709551616",
];

impl Mutator {
    fn below(&mut self, n: usize) -> usize {
        (self.rng.next_u64() % n.max(1) as u64) as usize
    }

    /// One mutation of `input`; `corpus` is there to splice from.
    fn mutate(&mut self, input: &[u8], corpus: &[Vec<u8>], json: bool) -> Vec<u8> {
        if json && self.below(2) == 0 {
            if let Ok(mut v) = serde_json::from_slice::<Value>(input) {
                for _ in 0..1 + self.below(3) {
                    self.mutate_value(&mut v, 0);
                }
                return serde_json::to_vec(&v).unwrap_or_else(|_| input.to_vec());
            }
        }
        let mut out = input.to_vec();
        for _ in 0..1 + self.below(4) {
            let len = out.len().max(1);
            match self.below(7) {
                0 => {
                    let i = self.below(len);
                    if let Some(b) = out.get_mut(i) {
                        *b ^= 1 << self.below(8);
                    }
                }
                1 => {
                    let i = self.below(len + 1).min(out.len());
                    let bytes = b"{}[],:\"-.e9\\0 nulltruefalse\xff\x00";
                    let b = bytes[self.below(bytes.len())];
                    out.insert(i, b);
                }
                2 => {
                    let i = self.below(len).min(out.len());
                    let n = self.below(16).min(out.len() - i);
                    out.drain(i..i + n);
                }
                3 => {
                    let cut = self.below(len);
                    out.truncate(cut);
                }
                4 => {
                    let other = &corpus[self.below(corpus.len())];
                    let (i, j) = (
                        self.below(len).min(out.len()),
                        self.below(other.len().max(1)),
                    );
                    let n = self.below(64).min(other.len().saturating_sub(j));
                    out.splice(i..i, other[j..j + n].iter().copied());
                }
                5 => {
                    let i = self.below(len).min(out.len());
                    let n = self.below(32).min(out.len() - i);
                    let piece: Vec<u8> = out[i..i + n].to_vec();
                    out.splice(i..i, piece);
                }
                _ => {
                    // Replace a number-looking run with an interesting number.
                    let i = self.below(len).min(out.len());
                    if let Some(start) = out[i..].iter().position(|b| b.is_ascii_digit()) {
                        let s = i + start;
                        let end = s + out[s..]
                            .iter()
                            .position(|b| !(b.is_ascii_digit() || *b == b'.' || *b == b'e'))
                            .unwrap_or(out.len() - s);
                        let n = INTERESTING[self.below(INTERESTING.len())].as_bytes();
                        out.splice(s..end, n.iter().copied());
                    }
                }
            }
        }
        out
    }

    /// A JSON-aware edit somewhere in `v`.
    fn mutate_value(&mut self, v: &mut Value, depth: usize) {
        let descend = match v {
            Value::Object(m) if !m.is_empty() => self.below(3) > 0,
            Value::Array(a) if !a.is_empty() => self.below(3) > 0,
            _ => false,
        };
        if descend && depth < 12 {
            match v {
                Value::Object(m) => {
                    let keys: Vec<String> = m.keys().cloned().collect();
                    let k = &keys[self.below(keys.len())];
                    match self.below(8) {
                        0 => {
                            m.remove(k);
                        }
                        1 => {
                            m.insert(format!("{k}_unknown"), Value::Null);
                        }
                        _ => self.mutate_value(m.get_mut(k).unwrap(), depth + 1),
                    }
                }
                Value::Array(a) => {
                    let i = self.below(a.len());
                    match self.below(8) {
                        0 => {
                            a.remove(i);
                        }
                        1 => {
                            let copy = a[i].clone();
                            let n = [2, 10, 300][self.below(3)];
                            a.extend(std::iter::repeat_n(copy, n));
                        }
                        _ => self.mutate_value(&mut a[i], depth + 1),
                    }
                }
                _ => unreachable!(),
            }
            return;
        }
        *v = match self.below(9) {
            0 => Value::Null,
            1 => Value::Bool(self.below(2) == 0),
            2 => Value::String("∞".repeat(self.below(3))),
            3 => Value::Array(Vec::new()),
            4 => Value::Object(Default::default()),
            5 => {
                // Deep nesting.
                let mut x = Value::Null;
                for _ in 0..[10, 200, 5000][self.below(3)] {
                    x = Value::Array(vec![x]);
                }
                x
            }
            _ => serde_json::from_str(INTERESTING[self.below(INTERESTING.len())])
                .unwrap_or(Value::Null),
        };
    }
}

/// Tally of one target.
#[derive(Default, Debug)]
struct Tally {
    inputs: usize,
    accepted: usize,
    refused: usize,
}

/// Runs `n` mutated inputs of `corpus` through `target` (Ok: accepted; Err: the refusal's
/// message); panics if the target panics or refuses without a message.
fn fuzz(
    name: &str,
    corpus: &[Vec<u8>],
    json: bool,
    n: usize,
    seed: u64,
    mut target: impl FnMut(&[u8]) -> Result<(), String>,
) -> Tally {
    let mut m = Mutator {
        rng: Xoshiro256PlusPlus::seed_from_u64(seed),
    };
    let mut tally = Tally::default();
    let start = std::time::Instant::now();
    let mut current = corpus[0].clone();
    for i in 0..n {
        // Mostly fresh mutations of the corpus, sometimes stacked on the last input.
        let base = if m.below(4) == 0 {
            current.clone()
        } else {
            corpus[i % corpus.len()].clone()
        };
        let input = m.mutate(&base, corpus, json);
        match catch_unwind(AssertUnwindSafe(|| target(&input))) {
            Ok(Ok(())) => tally.accepted += 1,
            Ok(Err(message)) => {
                assert!(
                    !message.trim().is_empty(),
                    "{name}: refused without a message: {}",
                    String::from_utf8_lossy(&input)
                );
                tally.refused += 1;
            }
            Err(_) => panic!(
                "{name}: input {i} panicked (seed {seed}): {}",
                String::from_utf8_lossy(&input[..input.len().min(2000)])
            ),
        }
        tally.inputs += 1;
        current = input;
    }
    println!(
        "{name}: {tally:?} in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    tally
}

/// A scene: parsed; if accepted and small, built and stepped.
fn scene_target(bytes: &[u8]) -> Result<(), String> {
    let text = std::str::from_utf8(bytes).map_err(|e| e.to_string())?;
    let scene = Scene::from_json(text).map_err(|e| e.to_string())?;
    let [nx, ny, nz, nt] = scene.field.size;
    let dt = scene.simulation.dt;
    let kept_steps: f64 = scene
        .shapes
        .iter()
        .filter_map(|s| s.reverse_from)
        .map(|t| t / dt)
        .sum();
    let cheap = nx * ny * nz * nt <= 16usize.pow(4)
        && scene.gas.max_blobs <= 5_000
        && scene.emitters.iter().all(|e| e.rate <= 1e4)
        && dt >= 1e-3
        && scene.shapes.iter().map(|s| s.blob_count()).sum::<usize>() <= 5_000
        && kept_steps <= 2_000.0;
    if cheap {
        let mut sim = Simulation::new(scene).map_err(|e| e.to_string())?;
        sim.run(3);
        let list = sim.blob_list();
        assert!(list
            .blobs
            .iter()
            .all(|b| b.center.iter().all(|c| c.is_finite()) && b.sigma.is_finite()));
    }
    Ok(())
}

/// A blob list: parsed; if accepted and small, rendered at 6 × 4.
fn blob_list_target(bytes: &[u8]) -> Result<(), String> {
    let value: Value = serde_json::from_slice(bytes).map_err(|e| e.to_string())?;
    let list = BlobList::from_value(value).map_err(|e| e.to_string())?;
    if list.blobs.len() <= 500 {
        let renderer = Renderer::new(&list, Some((6, 4)), RenderOptions::default())
            .map_err(|e| e.to_string())?;
        let image = renderer.render();
        assert!(image.data.iter().all(|v| v.is_finite()));
    }
    Ok(())
}

/// A `.npy` field: read, as a stream and as a file of its size, the two readers agreeing;
/// the reader refuses what it cannot take. A field's shape on a valid lattice becomes a field,
/// which refuses values that are not finite.
fn npy_target(bytes: &[u8]) -> Result<(), String> {
    let sized = npy::read_f32_sized(bytes, bytes.len() as u64);
    let streamed = npy::read_f32(bytes);
    assert_eq!(
        sized.as_ref().ok().map(|(s, d)| (s, d.len())),
        streamed.as_ref().ok().map(|(s, d)| (s, d.len())),
        "the two readers disagree"
    );
    let (shape, data) = streamed.map_err(|e| e.to_string())?;
    if let [nt, nz, ny, nx, 3] = shape[..] {
        let params = FieldParams {
            size: [nx, ny, nz, nt],
            ..FieldParams::default()
        };
        if params.validate().is_ok() {
            TurbulentField::from_data(params, data).map_err(|e| e.to_string())?;
        }
    }
    Ok(())
}

/// Parses a scene file of `tests/hostile/`: its refusal's text, or None when it is accepted.
fn hostile(name: &str) -> Option<String> {
    let text = std::fs::read_to_string(root().join("wasm-core/tests/hostile").join(name)).unwrap();
    Scene::from_json(&text).err().map(|e| e.to_string())
}

#[test]
fn hostile_scenes_stay_refused_before_any_work_with_their_path() {
    for (name, start, words) in [
        (
            "emitter-flood.json",
            "emitters: ",
            "100000000 births a step, over the limit of 100000",
        ),
        (
            "shape-flood.json",
            "shapes: ",
            "40000000 blobs, over the limit of 1000000",
        ),
        (
            "reversed-split-flood.json",
            "shapes: ",
            "reversed sets keep every step",
        ),
        (
            "reversed-steps-flood.json",
            "shapes: ",
            "the steps, reverse_from / dt + 1,",
        ),
        (
            "long-lists.json",
            "wind: ",
            "at most 256 primitives (got 300)",
        ),
        (
            "many-lights.json",
            "render.lights: ",
            "at most 64 lights (got 65)",
        ),
        (
            "render-time-flood.json",
            "simulation.dt: ",
            "100 s of simulated time",
        ),
        ("deep-nesting.json", "scene: ", "recursion limit exceeded"),
    ] {
        let e = hostile(name).unwrap_or_else(|| panic!("{name} was accepted"));
        assert!(e.starts_with(start) && e.contains(words), "{name}: {e}");
    }
}

#[test]
fn hostile_npy_files_stay_refused_before_they_are_read() {
    let want = [
        ("fortran-order-plain.npy", "Fortran-ordered"),
        ("fortran-order.npy", "unknown key 'note'"),
        ("header-4gib.npy", "at most 10000"),
        ("shape-4tib.npy", "needs 4398046511104 bytes"),
    ];
    let files = hostile_npy();
    assert_eq!(files.len(), want.len(), "a hostile .npy without its check");
    for ((name, bytes), (want_name, words)) in files.iter().zip(want) {
        assert_eq!(name, want_name);
        let e = npy::read_f32_sized(&bytes[..], bytes.len() as u64).unwrap_err();
        assert!(e.to_string().contains(words), "{name}: {e}");
        assert!(npy::read_f32(&bytes[..]).is_err(), "{name}");
    }
}

#[test]
fn every_list_is_refused_one_past_its_limit_and_accepted_at_it() {
    use serde_json::json;
    let repulsor = |n: usize| {
        let path: Vec<Value> = (0..n).map(|t| json!([t, 0, 0, 0])).collect();
        json!({"type": "repulsor", "radius": 0.1, "strength": 1, "path": path})
    };
    let light = json!({"type": "directional", "direction": [0, -1, 0], "color": [0.1, 0.1, 0.1]});
    let object = json!({"type": "sphere", "center": [0, 0, 0], "radius": 0.1, "color": [1, 1, 1]});
    let shape = json!({"shape": "points", "points": [[0, 0, 0]]});
    let emitter = json!({"rate": 1});
    let wind = json!({"type": "uniform", "velocity": [0, 0, 0]});
    type Case = (&'static str, usize, Box<dyn Fn(usize) -> Value>);
    let cases: Vec<Case> = vec![
        (
            "wind",
            256,
            Box::new(move |n| json!({"wind": vec![wind.clone(); n]})),
        ),
        (
            "emitters",
            256,
            Box::new(move |n| json!({"emitters": vec![emitter.clone(); n]})),
        ),
        (
            "shapes",
            256,
            Box::new(move |n| json!({"shapes": vec![shape.clone(); n]})),
        ),
        (
            "render.lights",
            64,
            Box::new(move |n| json!({"render": {"lights": vec![light.clone(); n]}})),
        ),
        (
            "render.objects",
            256,
            Box::new(move |n| json!({"render": {"objects": vec![object.clone(); n]}})),
        ),
        (
            "wind[0].path",
            10_000,
            Box::new(move |n| json!({"wind": [repulsor(n)]})),
        ),
    ];
    for (path, limit, scene) in cases {
        let parse = |n: usize| {
            let mut v = scene(n);
            v["version"] = json!(1);
            Scene::from_value(v)
        };
        assert!(
            parse(limit).is_ok(),
            "{path} at {limit}: {:?}",
            parse(limit).err()
        );
        let e = parse(limit + 1).unwrap_err();
        assert_eq!(e.path, path, "{e}");
        assert!(e.message.contains(&format!("at most {limit}")), "{e}");
    }
    // Shapes: 200,000 blobs a set, 1,000,000 for all sets together (exactly that is valid).
    let sets = |counts: &[usize]| {
        let shapes: Vec<Value> = counts
            .iter()
            .map(|c| json!({"shape": "cube", "count": c}))
            .collect();
        Scene::from_value(json!({"version": 1, "shapes": shapes}))
    };
    assert!(sets(&[200_000; 5]).is_ok());
    assert_eq!(
        sets(&[200_000, 200_000, 200_000, 200_000, 200_000, 1])
            .unwrap_err()
            .path,
        "shapes"
    );
    // Births: Σ rate × dt over the enabled emitters; disabled ones do not count.
    let births = |rates: &[(f64, bool)], dt: f64| {
        let emitters: Vec<Value> = rates
            .iter()
            .map(|&(r, on)| json!({"rate": r, "enabled": on}))
            .collect();
        Scene::from_value(json!({"version": 1, "emitters": emitters, "simulation": {"dt": dt}}))
    };
    assert!(births(&[(1e6, true), (1e6, false)], 0.1).is_ok());
    assert_eq!(
        births(&[(1e6, true), (1e6, true)], 0.1).unwrap_err().path,
        "emitters"
    );
    // max_blobs: a showcase of exactly 1,000,000 is valid, one more is not.
    let gas = |n: usize| Scene::from_value(json!({"version": 1, "gas": {"max_blobs": n}}));
    assert!(gas(1_000_000).is_ok());
    assert_eq!(gas(1_000_001).unwrap_err().path, "gas.max_blobs");
}

#[test]
fn blob_lists_are_refused_past_their_limits_as_they_are_read() {
    let blob = r#"{"center":[0,0,0],"sigma":1,"mass":1}"#;
    let list = |n: usize| format!("{{\"blobs\":[{}]}}", vec![blob; n].join(","));
    let e = BlobList::from_json(&list(MAX_LIST_BLOBS + 1)).unwrap_err();
    assert!(e.path.starts_with("blobs"), "{e}");
    assert!(
        e.message
            .contains(&format!("at most {MAX_LIST_BLOBS} blobs")),
        "{e}"
    );
    let e =
        BlobList::from_value(serde_json::from_str(&list(MAX_LIST_BLOBS + 1)).unwrap()).unwrap_err();
    assert!(e.path.starts_with("blobs"), "{e}");
    assert_eq!(BlobList::from_json(&list(3)).unwrap().blobs.len(), 3);
    // A blob list is one moment: it has no `time` (a scene's render section has).
    let e = BlobList::from_json(r#"{"time": 3, "blobs": []}"#).unwrap_err();
    assert!(e.to_string().contains("unknown field `time`"), "{e}");
    let light = r#"{"type":"point","position":[0,3,0],"color":[1,1,1]}"#;
    let lights = format!("{{\"lights\":[{}]}}", vec![light; 65].join(","));
    assert_eq!(BlobList::from_json(&lights).unwrap_err().path, "lights");
}

#[test]
fn a_vanishing_temporal_spread_gives_the_frozen_field_not_nan() {
    assert_eq!(hostile("tiny-sigma.json"), None);
    let params = |sigma: f64| FieldParams {
        size: [8; 4],
        spectrum: SpectrumParams {
            sigma,
            k_inertial: 1.0,
            ..SpectrumParams::default()
        },
        seed: 3,
    };
    let frozen = TurbulentField::generate(&params(0.0)).unwrap();
    for sigma in [1e-300, 1e-200, 1e-162, 1e-150] {
        let field = TurbulentField::generate(&params(sigma)).unwrap();
        field.check_finite().unwrap();
        assert_eq!(field.data, frozen.data, "σ = {sigma:e}");
    }
    let text =
        std::fs::read_to_string(root().join("wasm-core/tests/hostile/tiny-sigma.json")).unwrap();
    let mut sim = Simulation::new(Scene::from_json(&text).unwrap()).unwrap();
    sim.run(30);
    let list = sim.blob_list();
    assert!(!list.blobs.is_empty());
    assert!(list
        .blobs
        .iter()
        .all(|b| b.center.iter().all(|c| c.is_finite())));
}

#[test]
fn no_input_panics_and_every_refusal_has_a_message() {
    let total: usize = std::env::var("WINDFIELD_FUZZ_INPUTS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(DEFAULT_INPUTS);
    let start = std::time::Instant::now();
    let scenes = fuzz(
        "scenes",
        &scene_corpus(),
        true,
        total * 2 / 5,
        1,
        scene_target,
    );
    let lists = fuzz(
        "blob lists",
        &blob_list_corpus(),
        true,
        total * 2 / 5,
        2,
        blob_list_target,
    );
    let fields = fuzz("npy", &npy_corpus(), false, total / 5, 3, npy_target);
    let inputs = scenes.inputs + lists.inputs + fields.inputs;
    println!(
        "{inputs} inputs in {:.1} s, 0 panics",
        start.elapsed().as_secs_f64()
    );
    // The mutations reach both sides of each parser.
    for t in [&scenes, &lists, &fields] {
        assert!(t.accepted > 0 && t.refused > 0, "{t:?}");
    }
}
