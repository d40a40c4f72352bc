//! The `windfield` command line as a user meets it (docs/FORMATS.md, the command line): a still at the scene's
//! `render.time`, the summary line of every command that writes, the project's own message for
//! negative numbers and for every other refusal (`windfield: error:`, in a person's words),
//! budgets that refuse a hostile scene before it allocates (under an address-space limit, where
//! an allocation failure would abort), scene files bounded by size and by list length as they
//! are read, `.npy` files refused by their declared lengths before they are read, no silent NaN,
//! a field and its parameters written together, an `--out` naming a format its command does
//! not write refused before the work, and sequences whose shards never share a
//! temporary name, whose manifests keep two runs' frames apart whatever the pattern's spelling
//! (claimed under a folder lock, so two runs started at once never both pass), and whose shard
//! arithmetic does not wrap.
//!
//! The binary is the one Cargo builds for these tests; `WINDFIELD_TEST_BIN` names another
//! (to run the same checks against an older build).

use crate::support::{bin, Scratch};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn scratch(name: &str) -> Scratch {
    crate::support::scratch("cli", name)
}

fn run(args: &[&str]) -> Output {
    Command::new(bin()).args(args).output().unwrap()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Runs the CLI expecting success; its stderr.
fn ok(args: &[&str]) -> String {
    let out = run(args);
    assert!(out.status.success(), "{args:?} failed: {}", stderr(&out));
    stderr(&out)
}

/// Runs the CLI expecting a refusal of its input (exit status 2); its stderr.
fn refused(args: &[&str]) -> String {
    let out = run(args);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
    stderr(&out)
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn scene(name: &str) -> String {
    s(&root().join("public/scenes").join(name)).to_string()
}

/// Writes `json` to `dir/name` and returns its path.
fn write(dir: &Path, name: &str, json: &serde_json::Value) -> String {
    let path = dir.join(name);
    std::fs::write(&path, json.to_string()).unwrap();
    s(&path).to_string()
}

#[test]
fn a_still_without_seconds_is_the_scene_at_its_render_time() {
    let dir = scratch("render-time");
    let png = |name: &str| s(&dir.join(name)).to_string();
    let small = ["--width", "64", "--height", "48"];
    // No render.time: 3 s.
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(scene("default.json")).unwrap()).unwrap();
    v["render"].as_object_mut().unwrap().remove("time");
    let default = write(&dir, "untimed.json", &v);
    let a = png("a.png");
    ok(&[&["render", &default, "--out", &a][..], &small].concat());
    ok(&[
        &["render", &default, "--seconds", "3", "--out", &png("b.png")][..],
        &small,
    ]
    .concat());
    ok(&[
        &["render", &default, "--seconds", "0", "--out", &png("c.png")][..],
        &small,
    ]
    .concat());
    let bytes = |p: &str| std::fs::read(p).unwrap();
    assert!(
        bytes(&a) == bytes(&png("b.png")),
        "no --seconds is render.time's 3 s"
    );
    assert!(bytes(&a) != bytes(&png("c.png")), "t = 0 shows no gas yet");
    // A scene's own render.time.
    v["render"]["time"] = serde_json::json!(1.25);
    let timed = write(&dir, "timed.json", &v);
    let line = ok(&[&["render", &timed, "--out", &png("d.png")][..], &small].concat());
    ok(&[
        &[
            "render",
            &timed,
            "--seconds",
            "1.25",
            "--out",
            &png("e.png"),
        ][..],
        &small,
    ]
    .concat());
    assert!(
        bytes(&png("d.png")) == bytes(&png("e.png")),
        "render.time 1.25"
    );
    assert!(line.contains("at t = 1.25 s"), "{line}");
    // render.time is checked: a range, and the step budget of every run.
    v["render"]["time"] = serde_json::json!(-1);
    let bad = write(&dir, "bad.json", &v);
    assert!(refused(&["render", &bad, "--out", &png("f.png")]).contains("render.time: must be"));
    v["render"]["time"] = serde_json::json!(100);
    v["simulation"]["dt"] = serde_json::json!(1e-5);
    let long = write(&dir, "long.json", &v);
    let e = refused(&["simulate", &long, "--seconds", "1", "--out", &png("g.json")]);
    assert!(
        e.contains("simulation.dt") && e.contains("100 s of simulated time"),
        "{e}"
    );
}

#[test]
fn every_command_that_writes_says_what_it_wrote() {
    let dir = scratch("summary");
    let plume = s(&root().join("tests/fixtures/plume.json")).to_string();
    let blobs = s(&dir.join("blobs.json")).to_string();
    let line = ok(&["simulate", &plume, "--seconds", "2", "--out", &blobs]);
    let list: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&blobs).unwrap()).unwrap();
    let n = list["blobs"].as_array().unwrap().len();
    assert!(n > 0);
    let count = |n: usize| {
        let d = n.to_string();
        let mut out = String::new();
        for (i, c) in d.chars().enumerate() {
            if i > 0 && (d.len() - i) % 3 == 0 {
                out.push(',');
            }
            out.push(c);
        }
        out
    };
    let last = line.lines().last().unwrap();
    assert!(
        last.starts_with(&format!("wrote {blobs}: {} blobs at t = 2.00 s", count(n))),
        "{last}"
    );
    assert!(last.ends_with(" s"), "{last}");
    let still = s(&dir.join("still.png")).to_string();
    let last = ok(&[
        "render", &blobs, "--width", "40", "--height", "30", "--out", &still,
    ]);
    assert!(
        last.trim_end().starts_with(&format!(
            "wrote {still} (40×30): {} blobs from {blobs}, ",
            count(n)
        )),
        "{last}"
    );
    let frames = format!("{}/f%02d.png", s(&dir));
    let last = ok(&[
        "render", &plume, "--frames", "0..3", "--fps", "2", "--width", "40", "--height", "30",
        "--out", &frames,
    ]);
    let last = last.lines().last().unwrap();
    assert!(
        last.starts_with(&format!(
            "wrote 3 frames {frames} (40×30; frames 0..3 at 2 fps)"
        )),
        "{last}"
    );
    assert!(last.contains("at t = 1.00 s in the last"), "{last}");
    // Either side alone, as for a still: the other is the scene's (480 high by default).
    let narrow = format!("{}/g%02d.png", s(&dir));
    let last = ok(&[
        "render", &plume, "--frames", "0..2", "--fps", "2", "--width", "40", "--out", &narrow,
    ]);
    let last = last.lines().last().unwrap();
    assert!(
        last.starts_with(&format!(
            "wrote 2 frames {narrow} (40×480; frames 0..2 at 2 fps)"
        )),
        "{last}"
    );
}

#[test]
fn negative_numbers_get_the_projects_message_naming_flag_and_range() {
    let dir = scratch("negative");
    let out = |name: &str| s(&dir.join(name)).to_string();
    let default = scene("default.json");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["simulate", &default, "--seconds", "-1"],
            "--seconds: must be a number, 0 or more (got -1)",
        ),
        (
            vec!["render", &default, "--seconds", "-1"],
            "--seconds: must be a number, 0 or more (got -1)",
        ),
        (
            vec!["render", &default, "--width", "-5"],
            "--width: must be an integer between 1 and 8192 (got -5)",
        ),
        (
            vec!["render", &default, "--height", "-5"],
            "--height: must be an integer between 1 and 8192 (got -5)",
        ),
        (
            vec!["render", &default, "--frames", "0..4", "--fps", "-24"],
            "--fps: must be a number greater than 0",
        ),
        (
            vec!["render", &default, "--frames", "-1..4", "--fps", "24"],
            "--frames: expected A..B",
        ),
        (
            vec![
                "render", &default, "--frames", "0..4", "--fps", "24", "--shard", "-1/3",
            ],
            "--shard: expected I/N",
        ),
        (
            vec!["generate", "--seed", "-1"],
            "--seed: must be an integer between 0 and 9007199254740992 (got -1)",
        ),
        (
            vec!["generate", "--sigma", "-1"],
            "--sigma: must be a finite number between 0 and 100 (got -1)",
        ),
        (
            vec!["generate", "--epsilon", "-2"],
            "--epsilon: must be a finite number greater than 0",
        ),
        (
            vec!["generate", "--size", "-8"],
            "--size: expected N or NX,NY,NZ,NT",
        ),
    ];
    for (args, message) in cases {
        let o = out("never.out");
        let f = out("f%02d.png");
        let target = if args.contains(&"--frames") { &f } else { &o };
        let e = refused(&[&args[..], &["--out", target]].concat());
        assert!(e.contains(message), "{args:?}: {e}");
        assert!(!e.contains("'--"), "{args:?}: clap's hint in {e}");
    }
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "nothing written"
    );
}

/// Runs the CLI under an address-space limit of 3 GB (`ulimit -v 3000000`, in KiB).
fn run_limited(args: &[&str]) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(r#"ulimit -v 3000000 && exec "$0" "$@""#)
        .arg(bin())
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn hostile_scenes_are_refused_under_3_gb_not_aborted() {
    let dir = scratch("hostile");
    let hostile = |name: &str| s(&root().join("wasm-core/tests/hostile").join(name)).to_string();
    for (file, path) in [
        ("emitter-flood.json", "emitters: "),
        ("shape-flood.json", "shapes: "),
        ("reversed-steps-flood.json", "shapes: "),
        ("reversed-split-flood.json", "shapes: "),
    ] {
        for command in ["simulate", "render"] {
            let out = s(&dir.join("out")).to_string();
            let o = run_limited(&[command, &hostile(file), "--seconds", "2", "--out", &out]);
            let e = stderr(&o);
            assert_eq!(
                o.status.code(),
                Some(2),
                "{command} {file}: {:?} {e}",
                o.status
            );
            assert!(e.contains(path), "{command} {file}: {e}");
        }
    }
    // Blob lists too: one blob past the limit is refused as it is read.
    let blob = r#"{"center":[0,0,0],"sigma":1,"mass":1}"#;
    let n = windfield::scene::limits::MAX_LIST_BLOBS + 1;
    let list = dir.join("flood.json");
    std::fs::write(
        &list,
        format!("{{\"blobs\":[{}]}}", vec![blob; n].join(",")),
    )
    .unwrap();
    let o = run_limited(&["render", s(&list), "--out", s(&dir.join("flood.png"))]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{:?} {e}", o.status);
    assert!(e.contains("blobs") && e.contains("at most"), "{e}");
}

#[test]
fn a_vanishing_sigma_gives_the_frozen_field_and_a_nan_field_is_refused_with_its_place() {
    let dir = scratch("sigma");
    let npy = |name: &str| s(&dir.join(name)).to_string();
    let field = [
        "generate",
        "--size",
        "8",
        "--k-inertial",
        "1",
        "--seed",
        "5",
    ];
    ok(&[
        &field[..],
        &["--sigma", "1e-200", "--out", &npy("tiny.npy")],
    ]
    .concat());
    ok(&[&field[..], &["--sigma", "0", "--out", &npy("frozen.npy")]].concat());
    let tiny = std::fs::read(npy("tiny.npy")).unwrap();
    assert!(
        tiny == std::fs::read(npy("frozen.npy")).unwrap(),
        "σ = 1e-200 is σ = 0"
    );
    let (shape, data) = windfield::field::npy::read_f32(&tiny[..]).unwrap();
    assert_eq!(shape, vec![8, 8, 8, 8, 3]);
    assert!(data.iter().all(|v| v.is_finite()) && data.iter().any(|&v| v != 0.0));
    // Its statistics are sane: divergence-free, the expected energy, no temporal spread.
    let out = run(&["stats", &npy("tiny.npy"), "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(
        report["divergence_ratio"].as_f64().unwrap() < 1e-10,
        "{report}"
    );
    let ratio = report["energy_ratio"].as_f64().unwrap();
    assert!((0.5..2.0).contains(&ratio), "{report}");
    for shell in report["shells"].as_array().unwrap() {
        assert!(shell["temporal_spread"].as_f64().unwrap() < 1e-3, "{shell}");
    }
    // A NaN at (t, z, y, x, component) = (1, 2, 3, 4, 1): flat index ((((1·8+2)·8+3)·8+4)·3+1.
    let mut bad = data.clone();
    let flat = (((8 + 2) * 8 + 3) * 8 + 4) * 3 + 1;
    bad[flat] = f32::NAN;
    let mut bytes = Vec::new();
    windfield::field::npy::write_f32(&mut bytes, &shape, &bad).unwrap();
    std::fs::write(npy("nan.npy"), bytes).unwrap();
    let nan = npy("nan.npy");
    for args in [
        vec!["stats", &nan, "--k-inertial", "1"],
        vec!["stats", &nan, "--k-inertial", "1", "--json"],
    ] {
        let out = run(&args);
        assert_eq!(
            out.status.code(),
            Some(2),
            "{}",
            String::from_utf8_lossy(&out.stdout)
        );
        let e = stderr(&out);
        assert!(
            e.contains(&format!("value {flat} ")) && e.contains("(1, 2, 3, 4, 1) is NaN"),
            "{e}"
        );
        assert!(out.stdout.is_empty());
    }
}

/// A sequence of the default scene into `pattern`, with `extra` flags.
fn sequence(pattern: &str, fps: &str, extra: &[&str]) -> Command {
    let mut c = Command::new(bin());
    c.args([
        "render",
        &scene("default.json"),
        "--frames",
        "0..16",
        "--fps",
        fps,
        "--width",
        "48",
        "--height",
        "36",
        "--out",
        pattern,
    ])
    .args(extra);
    c
}

/// Name → bytes of the frames (not the manifest) in `dir`.
fn frames(dir: &Path) -> std::collections::BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| !p.to_str().unwrap().ends_with(".windfield.json"))
        .map(|p| {
            (
                p.file_name().unwrap().to_str().unwrap().to_string(),
                std::fs::read(&p).unwrap(),
            )
        })
        .collect()
}

#[test]
fn parallel_shards_into_a_pattern_without_extension_write_the_unsharded_bytes() {
    let dir = scratch("shards");
    let whole = format!("{}/whole/frame.%03d", s(&dir));
    assert!(sequence(&whole, "24", &[])
        .output()
        .unwrap()
        .status
        .success());
    let want = frames(&dir.join("whole"));
    assert_eq!(want.len(), 16);
    for attempt in 0..3 {
        let pattern = format!("{}/sharded{attempt}/frame.%03d", s(&dir));
        let children: Vec<_> = (0..2)
            .map(|i| {
                sequence(&pattern, "24", &["--shard", &format!("{i}/2")])
                    .stderr(std::process::Stdio::piped())
                    .spawn()
                    .unwrap()
            })
            .collect();
        for child in children {
            let out = child.wait_with_output().unwrap();
            assert!(out.status.success(), "attempt {attempt}: {}", stderr(&out));
        }
        let got = frames(&dir.join(format!("sharded{attempt}")));
        assert!(
            got.keys().eq(want.keys()),
            "attempt {attempt}: {:?}",
            got.keys()
        );
        for (name, bytes) in &got {
            assert!(bytes == &want[name], "attempt {attempt}: {name} differs");
        }
    }
}

#[test]
fn a_resume_into_another_runs_frames_is_refused_unless_forced() {
    let dir = scratch("manifest");
    let pattern = format!("{}/f%02d.png", s(&dir));
    let first = sequence(&pattern, "24", &[]).output().unwrap();
    assert!(first.status.success(), "{}", stderr(&first));
    let manifest = dir.join("f%02d.png.windfield.json");
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&manifest).unwrap()).unwrap();
    assert_eq!(
        (m["fps"].as_f64(), m["width"].as_u64(), m["height"].as_u64()),
        (Some(24.0), Some(48), Some(36))
    );
    let before = frames(&dir);
    // The same run again: every frame is complete, nothing is written.
    let again = sequence(&pattern, "24", &[]).output().unwrap();
    assert!(
        again.status.success() && stderr(&again).contains("nothing to write"),
        "{}",
        stderr(&again)
    );
    // Another frame rate into the same frames: refused, nothing touched.
    let other = sequence(&pattern, "30", &[]).output().unwrap();
    assert_eq!(other.status.code(), Some(2), "{}", stderr(&other));
    let e = stderr(&other);
    assert!(
        e.contains("another run") && e.contains("24 fps, not 30") && e.contains("--force"),
        "{e}"
    );
    assert!(frames(&dir) == before, "a refused run touched the frames");
    // Another scene (another seed), the same fps and size: refused too.
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(scene("default.json")).unwrap()).unwrap();
    v["seed"] = serde_json::json!(99);
    let elsewhere = scratch("manifest-scene");
    let reseeded = write(&elsewhere, "reseeded.json", &v);
    let other = Command::new(bin())
        .args([
            "render", &reseeded, "--frames", "0..16", "--fps", "24", "--width", "48", "--height",
            "36", "--out", &pattern,
        ])
        .output()
        .unwrap();
    assert_eq!(other.status.code(), Some(2), "{}", stderr(&other));
    assert!(
        stderr(&other).contains("another scene"),
        "{}",
        stderr(&other)
    );
    // With --force it renders over them, and the manifest is the new run's.
    let forced = sequence(&pattern, "30", &["--force"]).output().unwrap();
    assert!(forced.status.success(), "{}", stderr(&forced));
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&manifest).unwrap()).unwrap();
    assert_eq!(m["fps"].as_f64(), Some(30.0));
    assert!(frames(&dir) != before, "--force rendered over the frames");
    let resumed = sequence(&pattern, "30", &[]).output().unwrap();
    assert!(resumed.status.success(), "{}", stderr(&resumed));
}

#[test]
fn shards_of_more_than_2_to_the_63_render_their_own_frames() {
    let dir = scratch("huge-shards");
    let whole = format!("{}/whole/f%02d.png", s(&dir));
    assert!(sequence(&whole, "24", &[])
        .output()
        .unwrap()
        .status
        .success());
    let want = frames(&dir.join("whole"));
    for (i, (shard, expect)) in [
        (format!("5/{}", u64::MAX), vec!["f05.png"]),
        (format!("9/{}", (1u128 << 63) + 7), vec!["f09.png"]),
        (format!("3/{}", 1u128 << 64), vec!["f03.png"]),
        (format!("{}/{}", u64::MAX - 1, u64::MAX), vec![]),
    ]
    .into_iter()
    .enumerate()
    {
        let sub = dir.join(format!("shard{i}"));
        let pattern = format!("{}/f%02d.png", s(&sub));
        let out = sequence(&pattern, "24", &["--shard", &shard])
            .output()
            .unwrap();
        assert!(out.status.success(), "{shard}: {}", stderr(&out));
        let got = if sub.exists() {
            frames(&sub)
        } else {
            Default::default()
        };
        assert_eq!(got.keys().collect::<Vec<_>>(), expect, "{shard}");
        for (name, bytes) in &got {
            assert!(bytes == &want[name], "{shard}: {name} differs");
        }
    }
}

/// A scene that simulates and renders in milliseconds: an 8⁴ lattice, one small plume.
fn tiny_scene(dir: &Path, name: &str, seed: u64) -> String {
    let v = serde_json::json!({
        "version": 1,
        "seed": seed,
        "field": {"size": [8, 8, 8, 8], "spectrum": {"k_inertial": 1}, "period": [2, 2, 2]},
        "emitters": [{"shape": "disk", "center": [0, 0, 0], "normal": [0, 1, 0], "radius": 0.1,
                      "rate": 120, "sigma0": 0.05, "mass0": 0.01}],
        "wind": [{"type": "uniform", "velocity": [0, 0.4, 0]}],
        "gas": {"max_blobs": 400},
        "render": {"camera": {"position": [0, 0.5, 2.5], "target": [0, 0.5, 0]}}
    });
    write(dir, name, &v)
}

/// `render INPUT --frames RANGE --fps 240 --width 32 --height 24 --out PATTERN EXTRA…`.
fn frames_of(input: &str, range: &str, pattern: &str, extra: &[&str]) -> Command {
    let mut c = Command::new(bin());
    c.args([
        "render", input, "--frames", range, "--fps", "240", "--width", "32", "--height", "24",
        "--out", pattern,
    ])
    .args(extra);
    c
}

/// The manifests in `dir`.
fn manifests(dir: &Path) -> Vec<String> {
    let mut out: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".windfield.json"))
        .collect();
    out.sort();
    out
}

#[test]
fn frames_reached_through_another_spelling_of_the_pattern_stay_with_their_run() {
    let dir = scratch("spellings");
    let a = tiny_scene(&dir, "a.json", 1);
    let b = tiny_scene(&dir, "b.json", 2);
    let d = dir.join("d");
    let padded = format!("{}/f%03d.png", s(&d));
    let plain = format!("{}/f%d.png", s(&d));
    let first = frames_of(&a, "100..106", &padded, &[]).output().unwrap();
    assert!(first.status.success(), "{}", stderr(&first));
    let before = frames(&d);
    assert_eq!(before.len(), 6);
    // Another scene through the other spelling would skip f100.png … f105.png: refused, both
    // runs named, nothing touched.
    let other = frames_of(&b, "98..106", &plain, &[]).output().unwrap();
    let e = stderr(&other);
    assert_eq!(other.status.code(), Some(2), "{e}");
    assert!(e.starts_with("windfield: error: --out: "), "{e}");
    for words in [
        "b.json",
        "frames 98..106 of",
        "f%d.png",
        "a.json",
        "frames 100..106 of",
        "f%03d.png",
        "6 of its frames",
        "f100.png … f105.png",
        "another scene",
        "--force",
    ] {
        assert!(e.contains(words), "{words:?} in {e}");
    }
    assert!(frames(&d) == before, "a refused run touched the frames");
    assert_eq!(manifests(&d), ["f%03d.png.windfield.json"]);
    // The same run through the other spelling shares its claim: the six are skipped.
    let again = frames_of(&a, "98..106", &plain, &[]).output().unwrap();
    let e = stderr(&again);
    assert!(again.status.success(), "{e}");
    assert!(e.contains("6 of 8 frames already complete"), "{e}");
    let now = frames(&d);
    assert_eq!(now.len(), 8);
    assert!(before.iter().all(|(name, bytes)| &now[name] == bytes));
    // --force takes the frames over from run a; then run a is refused on them.
    let forced = frames_of(&b, "98..106", &plain, &["--force"])
        .output()
        .unwrap();
    assert!(forced.status.success(), "{}", stderr(&forced));
    let taken = frames(&d);
    assert_eq!(taken.len(), 8);
    assert!(taken["f100.png"] != before["f100.png"], "run b's frame");
    assert_eq!(manifests(&d), ["f%d.png.windfield.json"]);
    let back = frames_of(&a, "100..106", &padded, &[]).output().unwrap();
    assert_eq!(back.status.code(), Some(2), "{}", stderr(&back));
    assert!(frames(&d) == taken);
    // A frame file of the range that no manifest claims is not taken for this run's.
    std::fs::copy(d.join("f100.png"), d.join("f107.png")).unwrap();
    let stray = frames_of(&b, "98..108", &plain, &[]).output().unwrap();
    let e = stderr(&stray);
    assert_eq!(stray.status.code(), Some(2), "{e}");
    assert!(
        e.contains("f107.png") && e.contains("no manifest claims"),
        "{e}"
    );
    let forced = frames_of(&b, "98..108", &plain, &["--force"])
        .output()
        .unwrap();
    assert!(forced.status.success(), "{}", stderr(&forced));
    assert!(
        frames(&d)["f107.png"] != taken["f100.png"],
        "rendered, not kept"
    );
}

#[test]
fn two_runs_started_at_once_into_one_folder_never_both_claim_it() {
    let dir = scratch("race");
    let a = tiny_scene(&dir, "a.json", 1);
    let b = tiny_scene(&dir, "b.json", 2);
    let reference = |input: &str, name: &str| {
        let pattern = format!("{}/{name}/f%03d.png", s(&dir));
        let out = frames_of(input, "100..104", &pattern, &[])
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", stderr(&out));
        frames(&dir.join(name))
    };
    let want = [reference(&a, "ref-a"), reference(&b, "ref-b")];
    for trial in 0..6 {
        let d = dir.join(format!("trial{trial}"));
        // Even trials spell the pattern the same way twice; odd ones differently.
        let patterns = [
            format!("{}/f%03d.png", s(&d)),
            format!("{}/f{}.png", s(&d), ["%03d", "%d"][trial % 2]),
        ];
        let children: Vec<_> = [&a, &b]
            .iter()
            .zip(&patterns)
            .map(|(input, pattern)| {
                frames_of(input, "100..104", pattern, &[])
                    .stderr(std::process::Stdio::piped())
                    .spawn()
                    .unwrap()
            })
            .collect();
        let outs: Vec<Output> = children
            .into_iter()
            .map(|c| c.wait_with_output().unwrap())
            .collect();
        let won: Vec<usize> = (0..2).filter(|&i| outs[i].status.success()).collect();
        assert_eq!(
            won.len(),
            1,
            "trial {trial}: {} / {}",
            stderr(&outs[0]),
            stderr(&outs[1])
        );
        let (w, l) = (won[0], 1 - won[0]);
        assert_eq!(outs[l].status.code(), Some(2), "trial {trial}");
        assert!(
            stderr(&outs[l]).contains("another run"),
            "{}",
            stderr(&outs[l])
        );
        let mut got = frames(&d);
        assert!(got.keys().all(|n| n.ends_with(".png")), "{:?}", got.keys());
        got.retain(|n, _| n.ends_with(".png"));
        assert!(got == want[w], "trial {trial}: the folder mixes two runs");
        assert_eq!(manifests(&d).len(), 1, "trial {trial}");
        assert!(!d.join(".windfield.lock").exists(), "trial {trial}");
    }
}

/// This machine's name as the CLI reads it for its folder lock.
fn host() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .map(|h| h.trim().to_string())
        .unwrap_or_default()
}

#[test]
fn a_claim_lock_left_by_a_dead_run_is_taken_over_and_a_live_one_waited_for() {
    let dir = scratch("lock");
    let a = tiny_scene(&dir, "a.json", 1);
    let lock = |d: &Path, pid: u32| {
        std::fs::create_dir_all(d).unwrap();
        let holder =
            serde_json::json!({"pid": pid, "host": host(), "run": "another", "token": "t"});
        std::fs::write(d.join(".windfield.lock"), holder.to_string()).unwrap();
    };
    // A process that has ended held it.
    let mut gone = Command::new("true").spawn().unwrap();
    let dead = gone.id();
    gone.wait().unwrap();
    let d = dir.join("dead");
    lock(&d, dead);
    let out = frames_of(&a, "0..2", &format!("{}/f%02d.png", s(&d)), &[])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(frames(&d).len(), 2);
    assert!(!d.join(".windfield.lock").exists());
    // A live process of another run holds it: nothing is claimed or written until it is gone.
    let d = dir.join("live");
    lock(&d, std::process::id());
    let child = frames_of(&a, "0..2", &format!("{}/f%02d.png", s(&d)), &[])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(400));
    assert!(
        frames(&d).keys().eq([".windfield.lock"]) && manifests(&d).is_empty(),
        "claimed or written while another run held the lock: {:?}",
        frames(&d).keys()
    );
    std::fs::remove_file(d.join(".windfield.lock")).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(frames(&d).len(), 2);
}

/// The files in `dir` whose names end with `.partial` (temporary files left behind).
fn partials(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".partial"))
        .collect()
}

#[test]
fn a_failed_generate_leaves_the_old_field_beside_its_own_parameters() {
    let dir = scratch("generate-pair");
    let npy = dir.join("field.npy");
    let side = dir.join("field.npy.json");
    let generate = |seed: &str, epsilon: &str, out: &Path| {
        run(&[
            "generate",
            "--size",
            "8",
            "--k-inertial",
            "1",
            "--seed",
            seed,
            "--epsilon",
            epsilon,
            "--out",
            s(out),
        ])
    };
    let first = generate("1", "1", &npy);
    assert!(first.status.success(), "{}", stderr(&first));
    let (old_npy, old_side) = (std::fs::read(&npy).unwrap(), std::fs::read(&side).unwrap());
    // The parameters cannot be written (a folder holds their name): the new field must not
    // replace the old one.
    std::fs::remove_file(&side).unwrap();
    std::fs::create_dir_all(side.join("in-the-way")).unwrap();
    let failed = generate("2", "16", &npy);
    let e = stderr(&failed);
    assert_eq!(failed.status.code(), Some(1), "{e}");
    assert!(
        e.starts_with("windfield: error: ") && e.contains("field.npy.json"),
        "{e}"
    );
    assert!(
        std::fs::read(&npy).unwrap() == old_npy,
        "the field was replaced"
    );
    assert!(partials(&dir).is_empty(), "{:?}", partials(&dir));
    // Put back, the pair is the old one: stats measures the energy its parameters predict.
    std::fs::remove_dir_all(&side).unwrap();
    std::fs::write(&side, &old_side).unwrap();
    let stats = run(&["stats", s(&npy), "--json"]);
    assert!(stats.status.success(), "{}", stderr(&stats));
    let report: serde_json::Value = serde_json::from_slice(&stats.stdout).unwrap();
    let ratio = report["energy_ratio"].as_f64().unwrap();
    assert!((0.5..2.0).contains(&ratio), "{report}");
    // A name whose parameters' name is too long for the file system: the same.
    let long = dir.join(format!("{}.npy", "f".repeat(248)));
    std::fs::write(&long, &old_npy).unwrap();
    let failed = generate("2", "16", &long);
    assert_eq!(failed.status.code(), Some(1), "{}", stderr(&failed));
    assert!(
        std::fs::read(&long).unwrap() == old_npy,
        "the field was replaced"
    );
    assert!(partials(&dir).is_empty(), "{:?}", partials(&dir));
}

/// Runs the CLI under an address-space limit of `kib` KiB (`ulimit -v`).
fn run_under(kib: u64, args: &[&str]) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(format!(r#"ulimit -v {kib} && exec "$0" "$@""#))
        .arg(bin())
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn npy_files_are_refused_by_their_declared_lengths_before_they_are_read() {
    let dir = scratch("npy");
    let hostile = |name: &str| s(&root().join("wasm-core/tests/hostile").join(name)).to_string();
    for (file, words) in [
        ("fortran-order.npy", "unknown key 'note'"),
        ("fortran-order-plain.npy", "Fortran-ordered"),
        ("header-4gib.npy", "at most 10000"),
        ("shape-4tib.npy", "needs 4398046511104 bytes"),
    ] {
        let o = run_limited(&["stats", &hostile(file)]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{file}: {:?} {e}", o.status);
        assert!(
            e.starts_with("windfield: error: ") && e.contains(words),
            "{file}: {e}"
        );
    }
    // A valid field with a 6 GiB tail (a sparse file): refused by its size, unread.
    let field = dir.join("field.npy");
    assert!(run(&[
        "generate",
        "--size",
        "4",
        "--k-inertial",
        "1",
        "--out",
        s(&field)
    ])
    .status
    .success());
    let len = std::fs::metadata(&field).unwrap().len();
    let tailed = dir.join("tailed.npy");
    std::fs::copy(&field, &tailed).unwrap();
    std::fs::OpenOptions::new()
        .write(true)
        .open(&tailed)
        .unwrap()
        .set_len(len + (6 << 30))
        .unwrap();
    let o = run_limited(&["stats", s(&tailed)]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{:?} {e}", o.status);
    assert!(e.contains("6442450944 bytes after the 3072"), "{e}");
}

/// `{"version": 1, "emitters": [{}, {}, …]}` with `n` emitters.
fn emitter_flood(path: &Path, n: usize) {
    let mut text = String::with_capacity(30 + 3 * n);
    text.push_str(r#"{"version": 1, "emitters": ["#);
    for i in 0..n {
        text.push_str(if i == 0 { "{}" } else { ",{}" });
    }
    text.push_str("]}");
    std::fs::write(path, text).unwrap();
}

#[test]
fn scene_files_are_bounded_by_size_unread_and_by_list_length_as_they_are_read() {
    let dir = scratch("scene-flood");
    // Ten million emitters in 30 MB: refused with the count, in a few times the file's memory
    // (the whole file read at once grew past 1.6 GB before).
    let flood = dir.join("flood.json");
    emitter_flood(&flood, 10_000_000);
    for command in ["simulate", "render"] {
        let o = run_under(
            400_000,
            &[
                command,
                s(&flood),
                "--seconds",
                "1",
                "--out",
                s(&dir.join("x")),
            ],
        );
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{command}: {:?} {e}", o.status);
        assert!(
            e.contains("emitters: must hold at most 256 emitters (got 10000000)"),
            "{command}: {e}"
        );
    }
    // Over 64 MiB: refused before it is read (a sparse file of 210 MB: a scene's start, then
    // nothing).
    let huge = dir.join("huge.json");
    std::fs::write(&huge, r#"{"version": 1, "emitters": ["#).unwrap();
    std::fs::OpenOptions::new()
        .write(true)
        .open(&huge)
        .unwrap()
        .set_len(210_000_000)
        .unwrap();
    for args in [
        vec!["simulate", s(&huge), "--seconds", "1"],
        vec!["render", s(&huge)],
        vec!["render", s(&huge), "--frames", "0..2", "--fps", "24"],
    ] {
        let out = s(&dir.join(if args.contains(&"--frames") {
            "f%d.png"
        } else {
            "x"
        }))
        .to_string();
        let o = run_under(400_000, &[&args[..], &["--out", &out]].concat());
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {:?} {e}", o.status);
        assert!(
            e.contains("200.3 MiB of JSON, over the limit of 64 MiB"),
            "{args:?}: {e}"
        );
    }
}

#[test]
fn every_refusal_starts_with_windfield_and_says_what_a_person_would() {
    let dir = scratch("messages");
    let out = s(&dir.join("o.json")).to_string();
    let scene_with = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        s(&path).to_string()
    };
    let cases = [
        (
            r#"{"version": "1"}"#,
            r#"version: must be the number 1 (got the string "1")"#,
        ),
        (
            r#"{"version": 1, "gas": {"max_blobs": -1}}"#,
            "gas.max_blobs: must be an integer between 1 and 1000000 (got -1)",
        ),
        (
            r#"{"version": 1, "seed": 1.5}"#,
            "seed: must be an integer between 0 and 9007199254740992 (got 1.5)",
        ),
        (
            r#"{"version": 1, "simulation": {"dt": 1e308}}"#,
            "simulation.dt: must be a finite number greater than 0 and at most 1 (got 1e308)",
        ),
        (
            r#"{"version": 1, "simulation": {"dt": 1e999}}"#,
            "simulation.dt: a number beyond ±1.8e308",
        ),
        (
            r#"{"version": 1, "simulation": {"dt": NaN}}"#,
            "simulation.dt: NaN is not a number JSON can hold",
        ),
        (
            r#"{"version": 1, "simulation": {"dt": null}}"#,
            "simulation.dt: must be a finite number greater than 0 and at most 1 (got null): JSON has no NaN or infinity",
        ),
        (
            r#"{"version": 1, "render": {"shadows": "yes"}}"#,
            r#"render.shadows: must be true or false (got the string "yes")"#,
        ),
        (
            r#"{"version": 1, "field": {"size": [8, 8, 8]}}"#,
            "field.size: must be a list of 4 numbers (got 3 items)",
        ),
        (
            r#"{"version": 1, "simulation": {"dt": 1e-300}, "render": {"time": 100}}"#,
            "simulation.dt: 100 s of simulated time at dt = 1e-300 s is 9.999999999999999e301 steps",
        ),
        (
            r#"{"version": 1, "simulation": {"integrator": "rk4"}}"#,
            r#"simulation.integrator: must be "rk2" or "euler" (got "rk4")"#,
        ),
    ];
    for (i, (text, want)) in cases.iter().enumerate() {
        let path = scene_with(&format!("s{i}.json"), text);
        let e = refused(&["simulate", &path, "--seconds", "1", "--out", &out]);
        assert!(
            e.starts_with(&format!("windfield: error: {path}: {want}")),
            "{text}: {e}"
        );
        for rust in ["usize", "u64", "f64", "invalid type", "0000000000"] {
            assert!(!e.contains(rust), "{text}: {e}");
        }
    }
    let list = scene_with(
        "list.json",
        r#"{"blobs": [{"center": [0, 0, "a"], "sigma": 1, "mass": 1}]}"#,
    );
    let e = refused(&["render", &list, "--out", &out]);
    assert!(
        e.contains(
            r#"blobs[0].center[2]: must be a finite number between -1000000 and 1000000 (got the string "a")"#
        ),
        "{e}"
    );
    // The flags, as clap reads them.
    let default = scene("default.json");
    for (args, want) in [
        (
            vec!["render", &default, "--width", "abc", "--out", &out],
            r#"--width: must be a whole number (got "abc")"#,
        ),
        (
            vec!["render", &default, "--seconds", "soon", "--out", &out],
            r#"--seconds: must be a number (got "soon")"#,
        ),
        (
            vec!["generate", "--seed", "1.5", "--out", &out],
            r#"--seed: must be a whole number (got "1.5")"#,
        ),
        (
            vec!["simulate", &default, "--seconds", "1"],
            "the following required arguments were not provided",
        ),
        (vec!["paint"], "unrecognized subcommand 'paint'"),
        (
            vec!["render", &default, "--out", "still.JPG"],
            "--out: windfield writes PNG or OpenEXR images, not .jpg",
        ),
        (
            vec![
                "render",
                &default,
                "--frames",
                "0..2",
                "--fps",
                "10",
                "--out",
                "f%02d.webp",
            ],
            "--out: windfield writes PNG or OpenEXR images, not .webp",
        ),
        (
            vec![
                "flipbook",
                &default,
                "--frames",
                "0..4",
                "--fps",
                "10",
                "--grid",
                "2x2",
                "--tile",
                "8x8",
                "--out",
                "sheet.jpeg",
            ],
            "--out: windfield writes PNG or OpenEXR images, not .jpeg",
        ),
        (
            vec!["simulate", &default, "--seconds", "1e308", "--out", &out],
            "simulation.dt: 1e308 s of simulated time at dt = ",
        ),
    ] {
        let e = refused(&args);
        assert!(
            e.starts_with(&format!("windfield: error: {want}")),
            "{args:?}: {e}"
        );
    }
    let bare = refused(&[]);
    assert!(
        bare.starts_with("windfield: error: a subcommand is needed"),
        "{bare}"
    );
    let help = run(&["render", "--help"]);
    assert!(help.status.success() && String::from_utf8_lossy(&help.stdout).contains("--frames"));
    // A field's shape is the file's, not a flag's.
    let odd = dir.join("odd.npy");
    let mut bytes = Vec::new();
    windfield::field::npy::write_f32(&mut bytes, &[4, 4, 4, 5, 3], &vec![0.0; 960]).unwrap();
    std::fs::write(&odd, bytes).unwrap();
    let e = refused(&["stats", s(&odd)]);
    assert!(
        e.contains("odd.npy: its shape [4, 4, 4, 5, 3]: must be an even number"),
        "{e}"
    );
    assert!(!e.contains("--size"), "{e}");
    // A folder given as input is a failed read (exit 1), as a missing file is.
    for args in [
        vec!["stats", s(&dir)],
        vec!["simulate", s(&dir), "--seconds", "1", "--out", &out],
        vec!["render", s(&dir), "--out", &out],
        vec![
            "render",
            s(&dir),
            "--frames",
            "0..2",
            "--fps",
            "24",
            "--out",
            "f%d.png",
        ],
    ] {
        let o = run(&args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert!(
            e.starts_with("windfield: error: ") && e.contains("directory"),
            "{args:?}: {e}"
        );
    }
}

#[test]
fn every_command_makes_the_folder_it_writes_into() {
    let dir = scratch("folders");
    let a = tiny_scene(&dir, "a.json", 1);
    let still = dir.join("stills/new/x.png");
    ok(&[
        "render",
        &a,
        "--width",
        "16",
        "--height",
        "12",
        "--out",
        s(&still),
    ]);
    let png = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(&still).unwrap(),
    ))
    .read_info()
    .unwrap();
    assert_eq!((png.info().width, png.info().height), (16, 12));
    let list = dir.join("lists/l.json");
    ok(&["simulate", &a, "--seconds", "0.1", "--out", s(&list)]);
    assert!(list.exists());
    let field = dir.join("fields/f.npy");
    ok(&[
        "generate",
        "--size",
        "4",
        "--k-inertial",
        "1",
        "--out",
        s(&field),
    ]);
    assert!(field.exists() && dir.join("fields/f.npy.json").exists());
}

#[test]
fn a_still_without_out_is_written_beside_as_the_scenes_name_and_a_sequence_needs_a_pattern() {
    let dir = scratch("no-out");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(scene("default.json")).unwrap()).unwrap();
    v["render"]["image"]["width"] = 32.into();
    v["render"]["image"]["height"] = 24.into();
    let input = write(&dir, "small-smoke.json", &v);
    let out = Command::new(bin())
        .args(["render", &input, "--seconds", "0.5"])
        .current_dir(&*dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let png = dir.join("small-smoke.png");
    assert!(stderr(&out).contains("small-smoke.png"), "{}", stderr(&out));
    let with_out = dir.join("with-out.png");
    ok(&["render", &input, "--seconds", "0.5", "--out", s(&with_out)]);
    assert_eq!(
        std::fs::read(&png).unwrap(),
        std::fs::read(&with_out).unwrap()
    );
    let message = refused(&["render", &input, "--frames", "0..2", "--fps", "4"]);
    assert!(
        message.contains("--out: a sequence needs a pattern"),
        "{message}"
    );
}

#[test]
fn an_out_naming_a_format_its_command_does_not_write_is_refused_before_any_work() {
    let dir = scratch("other-formats");
    let out = |name: &str| s(&dir.join(name)).to_string();
    let inputs = scratch("other-formats-inputs");
    let a = tiny_scene(&inputs, "a.json", 1);
    let [gas, gas_frames, still, frames, sheet, blobs, field, wind] = [
        "gas.txt",
        "vdb/gas.%04d.JSON",
        "still.txt",
        "f%02d.npy",
        "sheet.vdb",
        "blobs.png",
        "field.txt",
        "wind.txt",
    ]
    .map(out);
    let images = "--out: windfield writes PNG or OpenEXR images";
    let cases: Vec<(Vec<&str>, String)> = vec![
        (
            vec!["volume", &a, "--voxel", "0.05", "--out", &gas],
            "--out: windfield writes OpenVDB volumes, not .txt (name the file .vdb)".into(),
        ),
        (
            vec![
                "volume",
                &a,
                "--frames",
                "0..2",
                "--fps",
                "24",
                "--voxel",
                "0.05",
                "--out",
                &gas_frames,
            ],
            "--out: windfield writes OpenVDB volumes, not .json (name the file .vdb)".into(),
        ),
        (
            vec!["render", &a, "--out", &still],
            format!("{images}, not .txt (name the file .png or .exr)"),
        ),
        (
            vec![
                "render", &a, "--frames", "0..2", "--fps", "24", "--out", &frames,
            ],
            format!("{images}, not .npy (name the file .png or .exr)"),
        ),
        (
            vec![
                "flipbook", &a, "--frames", "0..4", "--fps", "10", "--grid", "2x2", "--tile",
                "8x8", "--out", &sheet,
            ],
            format!("{images}, not .vdb (name the file .png or .exr)"),
        ),
        (
            vec!["simulate", &a, "--seconds", "1", "--out", &blobs],
            "--out: windfield writes blob lists as JSON, not .png (name the file .json)".into(),
        ),
        (
            vec!["generate", "--size", "4", "--out", &field],
            "--out: windfield writes fields as NumPy .npy and the wind as OpenVDB or RGB32F, \
             not .txt (name the file .npy, .vdb or .rgb32f)"
                .into(),
        ),
        (
            vec![
                "wind",
                &a,
                "--seconds",
                "1",
                "--box",
                "0,0,0,1,1,1",
                "--n",
                "2,2,2",
                "--out",
                &wind,
            ],
            "--out: windfield writes the wind as JSON, NumPy or OpenVDB, not .txt \
             (name the file .json, .npy or .vdb)"
                .into(),
        ),
    ];
    for (args, want) in &cases {
        let e = refused(args);
        assert!(
            e.starts_with(&format!("windfield: error: {want}")),
            "{args:?}: {e}"
        );
    }
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "nothing written"
    );
    // A missing input is told first (a failed read, exit 1).
    let missing = out("missing.json");
    let o = run(&["volume", &missing, "--voxel", "0.05", "--out", &gas]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    // The formats each command writes, and names without an extension, are written as before.
    for (args, file) in [
        (
            vec!["volume", &a, "--seconds", "0.1", "--voxel", "0.05", "--out"],
            "gas.VDB",
        ),
        (vec!["simulate", &a, "--seconds", "0.1", "--out"], "blobs"),
        (
            vec!["render", &a, "--width", "8", "--height", "6", "--out"],
            "still",
        ),
    ] {
        let path = out(file);
        ok(&[&args[..], &[path.as_str()]].concat());
        assert!(dir.join(file).exists(), "{file}");
    }
}

/// A reader that closed the pipe before the output came (`windfield schema | head -c 0`) ends
/// the output quietly: exit status 0 and no panic, as other tools do.
#[test]
fn output_into_a_closed_pipe_ends_quietly() {
    for args in [&["schema"][..], &["contract"][..]] {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let out = Command::new(bin())
            .args(args)
            .stdout(writer)
            .output()
            .unwrap();
        assert!(out.status.success(), "{args:?}: {}", stderr(&out));
        assert_eq!(stderr(&out), "", "{args:?}");
    }
}

/// Input that is not what a command reads is refused as input (status 2), in words about the
/// input: bytes that are not UTF-8; a blob list where a scene belongs, told it is no scene
/// before its blobs are counted against a scene's lists. A flipbook's tile is asked for as
/// W×H. The wind at any time is a number: past single precision's range too.
#[test]
fn input_that_is_not_a_scene_is_told_so_and_the_wind_at_any_time_is_finite() {
    let dir = scratch("not-a-scene");
    let bytes = dir.join("bytes.json");
    std::fs::write(&bytes, [0xff, 0xfe, 0x00, b'{']).unwrap();
    let out = dir.join("out.json");
    let e = refused(&["simulate", s(&bytes), "--seconds", "0", "--out", s(&out)]);
    assert!(e.contains("valid UTF-8"), "{e}");
    let blobs: Vec<serde_json::Value> = (0..50)
        .map(|i| serde_json::json!({"center": [i as f64 * 0.01, 0, 0], "sigma": 0.1, "mass": 1}))
        .collect();
    let list = write(&dir, "list.json", &serde_json::json!({ "blobs": blobs }));
    let e = refused(&["simulate", &list, "--seconds", "0", "--out", s(&out)]);
    assert!(e.contains("version: missing"), "{e}");
    let sheet = dir.join("sheet.png");
    let e = refused(&[
        "flipbook",
        &scene("default.json"),
        "--frames",
        "0..2",
        "--fps",
        "10",
        "--grid",
        "2x1",
        "--tile",
        "9000x12",
        "--out",
        s(&sheet),
    ]);
    assert!(
        e.contains("--tile: expected two whole numbers from 1 to 8192 as W×H"),
        "{e}"
    );
    let points = write(
        &dir,
        "points.json",
        &serde_json::json!([[0, 1, 0], [0.5, 1, 0.2]]),
    );
    let wind = dir.join("wind.json");
    ok(&[
        "wind",
        &scene("default.json"),
        "--seconds",
        "1e300",
        "--points",
        &points,
        "--out",
        s(&wind),
    ]);
    let w: Vec<[f64; 3]> = serde_json::from_str(&std::fs::read_to_string(&wind).unwrap()).unwrap();
    assert!(
        w.iter().flatten().all(|v| v.is_finite()) && w.iter().flatten().any(|&v| v != 0.0),
        "{w:?}"
    );
}

/// A points file for `wind --points` that is not an array of [x, y, z] is refused naming the
/// point at fault, as a scene names its path.
#[test]
fn a_bad_point_is_named() {
    let dir = scratch("bad-points");
    let out = dir.join("wind.json");
    for (points, want) in [
        (
            serde_json::json!([[0, 0]]),
            "[0]: must be a point [x, y, z] of 3 numbers (got 2 items)",
        ),
        (
            serde_json::json!([[0, 0, 0], [1, 2, 3, 4]]),
            "[1]: must be a point [x, y, z] of 3 numbers (got 4 items)",
        ),
        (
            serde_json::json!([[0, 0, 0], [1, "a", 3]]),
            "[1][1]: invalid type: string \"a\"",
        ),
        (
            serde_json::json!([[0, 0, 0], [1, 2, 2e6]]),
            "[1][2]: must be a finite number within ±1000000 m (got 2000000)",
        ),
    ] {
        let file = write(&dir, "points.json", &points);
        let e = refused(&[
            "wind",
            &scene("default.json"),
            "--seconds",
            "0",
            "--points",
            &file,
            "--out",
            s(&out),
        ]);
        assert!(
            e.starts_with(&format!("windfield: error: {file}: {want}")),
            "{points}: {e}"
        );
    }
    assert!(!out.exists());
}

/// A flipbook whose range ends near 2^64 with a loop's fade is refused by the step budget
/// (its last frame saturates rather than wrapping round to a small one and running forever).
#[test]
fn a_flipbook_ending_near_two_to_the_64_meets_the_step_budget() {
    let dir = scratch("far-flipbook");
    let sheet = dir.join("sheet.png");
    let e = refused(&[
        "flipbook",
        &scene("default.json"),
        "--frames",
        "18446744073709551610..18446744073709551615",
        "--fps",
        "10",
        "--grid",
        "8x1",
        "--tile",
        "8x8",
        "--loop",
        "--fade",
        "4",
        "--out",
        s(&sheet),
    ]);
    assert!(
        e.contains("simulation.dt: ") && e.contains("over the limit of 1000000"),
        "{e}"
    );
    assert!(!sheet.exists());
}
