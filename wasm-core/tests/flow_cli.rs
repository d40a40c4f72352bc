//! The flow on the command line (docs/FORMATS.md, the flow's exports): `windfield flow` writes
//! the grid the simulation holds at T, as `.npy`, `.vdb` and `.json`, and refuses a scene
//! without a flow; `windfield wind --frames A..B --fps F` is one simulation, each frame the
//! bytes of `--seconds k/F`, the flow included.

use crate::support::{bin, Scratch};
use std::path::Path;
use std::process::{Command, Output};
use windfield::field::npy;
use windfield::{Scene, Simulation};

fn scratch(name: &str) -> Scratch {
    crate::support::scratch("flow-cli", name)
}

fn run(args: &[&str]) -> Output {
    Command::new(bin()).args(args).output().unwrap()
}

fn ok(args: &[&str]) {
    let o = run(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

fn path(dir: &Scratch, name: &str) -> String {
    dir.0.join(name).display().to_string()
}

/// A hot point emitter (60 K) under a flow of 8³ cells of 0.1 m, with a uniform breeze and a
/// small field; `flow` is spliced in as the scene's `flow`'s extra keys.
fn plume(flow: &str) -> String {
    format!(
        r#"{{"version": 1, "seed": 5,
          "field": {{"size": [8, 8, 8, 8], "period": [1, 1, 1], "time_period": 2,
                     "amplitude": 0.1}},
          "wind": [{{"type": "uniform", "velocity": [0.05, 0, 0]}}],
          "emitters": [{{"center": [0, 0.15, 0], "rate": 50, "sigma0": 0.06,
                        "temperature": 60}}],
          "gas": {{"dissipation": 0}},
          "simulation": {{"dt": 0.02}},
          "flow": {{"box": [-0.4, 0, -0.4, 0.4, 0.8, 0.4], "cells": [8, 8, 8]{flow}}}}}"#
    )
}

/// The grid of the scene `text` run in-process to `seconds`.
fn grid_in_process(text: &str, seconds: f64) -> windfield::wind::flow::FlowGrid {
    let mut sim = Simulation::new(Scene::from_json(text).unwrap()).unwrap();
    let steps = sim.budgeted_steps(seconds).unwrap();
    sim.run(steps);
    sim.flow_grid().expect("a flow")
}

/// The grids a `.vdb` holds, as (name, tree type), read from its grid descriptors (the
/// layout `windfield::export::vdb` writes: header, file metadata, then each grid's name, type
/// and parent with its stream positions).
fn vdb_grids(bytes: &[u8]) -> Vec<(String, String)> {
    let mut at = 8 + 4 + 8 + 1 + 36;
    let u32_at = |at: &mut usize| {
        let v = u32::from_le_bytes(bytes[*at..*at + 4].try_into().unwrap());
        *at += 4;
        v as usize
    };
    let string = |at: &mut usize| {
        let n = u32_at(at);
        let s = String::from_utf8(bytes[*at..*at + n].to_vec()).unwrap();
        *at += n;
        s
    };
    for _ in 0..u32_at(&mut at) {
        string(&mut at);
        string(&mut at);
        string(&mut at);
    }
    let count = u32_at(&mut at);
    (0..count)
        .map(|_| {
            let name = string(&mut at);
            let tree = string(&mut at);
            string(&mut at);
            let end = u64::from_le_bytes(bytes[at + 16..at + 24].try_into().unwrap());
            at = end as usize;
            (name, tree)
        })
        .collect()
}

/// The translation and scale of the first `UniformScaleTranslateMap` in `bytes` (m).
fn uniform_translate_map(bytes: &[u8]) -> ([f64; 3], [f64; 3]) {
    let key = b"UniformScaleTranslateMap";
    let at = bytes
        .windows(key.len())
        .position(|w| w == key)
        .expect("a uniform translated transform")
        + key.len();
    let f = |i: usize| f64::from_le_bytes(bytes[at + 8 * i..at + 8 * i + 8].try_into().unwrap());
    ([f(0), f(1), f(2)], [f(3), f(4), f(5)])
}

#[test]
fn the_flow_command_writes_the_grid_the_simulation_holds_as_npy_vdb_and_json() {
    let dir = scratch("grid");
    let text = plume("");
    let scene = path(&dir, "plume.json");
    std::fs::write(&scene, &text).unwrap();
    let (npy_out, vdb_out, json_out) = (
        path(&dir, "flow.npy"),
        path(&dir, "flow.vdb"),
        path(&dir, "flow.json"),
    );
    for out in [&npy_out, &vdb_out, &json_out] {
        ok(&["flow", &scene, "--seconds", "0.3", "--out", out]);
    }
    let want = grid_in_process(&text, 0.3);
    assert_eq!(want.cells, [8, 8, 8]);
    // .npy: float32 (nz, ny, nx, 4), u, v, w then T, the simulation's grid bit for bit.
    let (shape, data) = npy::read_f32(std::fs::File::open(&npy_out).unwrap()).unwrap();
    assert_eq!(shape, vec![8, 8, 8, 4]);
    let header = std::fs::read(&npy_out).unwrap();
    assert!(String::from_utf8_lossy(&header[..128]).contains("'descr': '<f4'"));
    for n in 0..512 {
        for a in 0..3 {
            assert_eq!(
                data[4 * n + a].to_bits(),
                want.velocity[3 * n + a].to_bits(),
                "cell {n} u[{a}]"
            );
        }
        assert_eq!(data[4 * n + 3].to_bits(), want.temperature[n].to_bits());
    }
    assert!(data.iter().all(|v| v.is_finite()));
    assert!(want.temperature.iter().any(|&t| t > 0.1), "the plume heats");
    let rising = (0..512).map(|n| data[4 * n + 1]).fold(f32::MIN, f32::max);
    assert!(rising > 0.0, "hot air rises: largest v {rising}");
    // .vdb: a Vec3SGrid `velocity` and a FloatGrid `temperature`, cells of 0.1 m, voxel
    // (0, 0, 0) at the first cell's centre.
    let vdb = std::fs::read(&vdb_out).unwrap();
    assert!(windfield::export::vdb::is_complete(&vdb));
    assert_eq!(
        vdb_grids(&vdb),
        vec![
            ("velocity".into(), "Tree_vec3s_5_4_3".into()),
            ("temperature".into(), "Tree_float_5_4_3".into())
        ]
    );
    let (translation, scale) = uniform_translate_map(&vdb);
    for a in 0..3 {
        assert!((scale[a] - 0.1).abs() < 1e-12, "{scale:?}");
        let lo = [-0.4, 0.0, -0.4][a];
        assert!(
            (translation[a] - (lo + 0.05)).abs() < 1e-12,
            "{translation:?}"
        );
    }
    // .json: the box, the cells, the time and the arrays in the .npy's order.
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json_out).unwrap()).unwrap();
    let keys: Vec<&str> = json
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    assert_eq!(
        keys.len(),
        5,
        "box, cells, time, velocity, temperature: {keys:?}"
    );
    assert_eq!(
        json["box"],
        serde_json::json!([-0.4, 0.0, -0.4, 0.4, 0.8, 0.4])
    );
    assert_eq!(json["cells"], serde_json::json!([8, 8, 8]));
    assert!((json["time"].as_f64().unwrap() - 0.3).abs() < 1e-12);
    let velocity: Vec<[f32; 3]> = serde_json::from_value(json["velocity"].clone()).unwrap();
    let temperature: Vec<f32> = serde_json::from_value(json["temperature"].clone()).unwrap();
    assert_eq!((velocity.len(), temperature.len()), (512, 512));
    for n in 0..512 {
        assert_eq!(&velocity[n][..], &data[4 * n..4 * n + 3], "cell {n}");
        assert_eq!(temperature[n], data[4 * n + 3], "cell {n}");
    }
    // At t = 0 the flow is at rest and cold.
    let rest = path(&dir, "rest.npy");
    ok(&["flow", &scene, "--seconds", "0", "--out", &rest]);
    let (_, data) = npy::read_f32(std::fs::File::open(&rest).unwrap()).unwrap();
    assert!(data.iter().all(|&v| v == 0.0));
}

fn refused(args: &[&str], words: &str, out: &str) {
    let o = run(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert!(
        err.starts_with("windfield: error:") && err.contains(words),
        "{args:?}: {err}"
    );
    assert!(!Path::new(out).exists(), "{args:?} left {out}");
}

#[test]
fn a_scene_without_an_enabled_flow_and_bad_flags_are_refused() {
    let dir = scratch("refused");
    let still = path(&dir, "still.json");
    std::fs::write(&still, r#"{"version": 1, "field": {"amplitude": 0}}"#).unwrap();
    let off = path(&dir, "off.json");
    std::fs::write(&off, plume(r#", "enabled": false"#)).unwrap();
    let scene = path(&dir, "plume.json");
    std::fs::write(&scene, plume("")).unwrap();
    let out = path(&dir, "flow.npy");
    refused(
        &["flow", &still, "--seconds", "1", "--out", &out],
        "flow: the scene has no flow",
        &out,
    );
    refused(
        &["flow", &off, "--seconds", "1", "--out", &out],
        "flow.enabled",
        &out,
    );
    refused(
        &["flow", &scene, "--seconds", "-1", "--out", &out],
        "--seconds",
        &out,
    );
    let txt = path(&dir, "flow.txt");
    refused(
        &["flow", &scene, "--seconds", "1", "--out", &txt],
        "--out: windfield writes the flow's grid as NumPy, OpenVDB or JSON, not .txt",
        &txt,
    );
    // Over the flow's cell-step budget (2^21 cells × 5,000 steps): refused naming flow.cells
    // before the solver is built.
    let big = path(&dir, "big.json");
    std::fs::write(
        &big,
        r#"{"version": 1, "field": {"amplitude": 0}, "simulation": {"dt": 0.01},
            "flow": {"box": [0, 0, 0, 12.8, 12.8, 12.8], "cells": [128, 128, 128]}}"#,
    )
    .unwrap();
    refused(
        &["flow", &big, "--seconds", "50", "--out", &out],
        "flow.cells",
        &out,
    );
    refused(
        &[
            "wind",
            &big,
            "--seconds",
            "50",
            "--box",
            "0,0,0,1,1,1",
            "--n",
            "2,2,2",
            "--out",
            &out,
        ],
        "flow.cells",
        &out,
    );
}

/// `windfield wind SCENE` at `when` (`--seconds T` or `--frames A..B --fps F`) at three
/// points; the file's text.
fn wind_at(dir: &Scratch, scene: &str, when: &[&str], name: &str) -> String {
    let points = path(dir, "points.json");
    std::fs::write(&points, "[[0, 0.3, 0], [0.1, 0.5, -0.05], [2, 2, 2]]").unwrap();
    let out = path(dir, name);
    let mut args = vec!["wind", scene];
    args.extend_from_slice(when);
    args.extend_from_slice(&["--points", &points, "--out", &out]);
    ok(&args);
    std::fs::read_to_string(&out).unwrap()
}

#[test]
fn a_wind_series_is_one_simulation_each_frame_the_wind_at_its_time() {
    let dir = scratch("series");
    let scene = path(&dir, "plume.json");
    std::fs::write(&scene, plume("")).unwrap();
    let off = path(&dir, "off.json");
    std::fs::write(&off, plume(r#", "enabled": false"#)).unwrap();
    for (input, tag) in [(&scene, "flow"), (&off, "none")] {
        let series = wind_at(
            &dir,
            input,
            &["--frames", "0..4", "--fps", "10"],
            &format!("{tag}.json"),
        );
        let frames: Vec<Vec<[f32; 3]>> = serde_json::from_str(&series).unwrap();
        assert_eq!(frames.len(), 4);
        assert!(frames.iter().all(|f| f.len() == 3));
        // Frame k is, byte for byte, the wind at k/10 s: its own run of --seconds.
        let singles: Vec<String> = (0..4)
            .map(|k| {
                let t = format!("{}", k as f64 / 10.0);
                wind_at(&dir, input, &["--seconds", &t], &format!("{tag}-{k}.json"))
            })
            .collect();
        assert_eq!(series, format!("[{}]", singles.join(",")), "{tag}");
    }
    // The flow is in the wind: a hot plume's wind at 0.3 s is not the wind without it, and the
    // point far outside the box sees no flow.
    let with: Vec<Vec<[f32; 3]>> =
        serde_json::from_str(&std::fs::read_to_string(path(&dir, "flow.json")).unwrap()).unwrap();
    let without: Vec<Vec<[f32; 3]>> =
        serde_json::from_str(&std::fs::read_to_string(path(&dir, "none.json")).unwrap()).unwrap();
    assert_ne!(with[3][0], without[3][0]);
    assert_eq!(with[3][2], without[3][2]);
    assert_eq!(with[0], without[0], "at rest before the first step");
    // A box over frames: one array of its cells a frame.
    let out = path(&dir, "box.json");
    ok(&[
        "wind",
        &scene,
        "--frames",
        "2..4",
        "--fps",
        "10",
        "--box",
        "-0.4,0,-0.4,0.4,0.8,0.4",
        "--n",
        "4,4,2",
        "--out",
        &out,
    ]);
    let frames: Vec<Vec<[f32; 3]>> =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!((frames.len(), frames[0].len()), (2, 32));
}

#[test]
fn a_wind_series_is_refused_with_seconds_without_fps_and_outside_json() {
    let dir = scratch("series-refused");
    let scene = path(&dir, "plume.json");
    std::fs::write(&scene, plume("")).unwrap();
    let points = path(&dir, "points.json");
    std::fs::write(&points, "[[0, 0.3, 0]]").unwrap();
    let json = path(&dir, "out.json");
    let npy = path(&dir, "out.npy");
    let b = ["--box", "0,0,0,1,1,1", "--n", "2,2,2"];
    let wind = |when: &[&str], place: &[&str], out: &str, words: &str| {
        let mut args = vec!["wind", scene.as_str()];
        args.extend_from_slice(when);
        args.extend_from_slice(place);
        args.extend_from_slice(&["--out", out]);
        refused(&args, words, out);
    };
    let p = ["--points", points.as_str()];
    wind(
        &["--seconds", "1", "--frames", "0..4", "--fps", "10"],
        &p,
        &json,
        "--frames: a series samples the times of its frames, --seconds one time",
    );
    wind(
        &["--frames", "0..4"],
        &p,
        &json,
        "--fps: required with --frames",
    );
    wind(&["--frames", "0..4", "--fps", "0"], &p, &json, "--fps");
    wind(&["--frames", "4..4", "--fps", "10"], &p, &json, "--frames");
    wind(
        &["--frames", "0..4", "--fps", "10"],
        &b,
        &npy,
        "--out: a series (--frames) is written as .json",
    );
    wind(&[], &p, &json, "give --seconds T, or --frames A..B");
}
