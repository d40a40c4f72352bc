//! `windfield wind` (docs/FORMATS.md, the command line): the scene's whole wind at points and
//! over a box, read back with the formats' own readers and held to the potential flow around
//! a solid sphere; bad input refused naming the flag or the file, and no file left behind.

use crate::support::{bin, Scratch};
use std::path::Path;
use std::process::{Command, Output};
use windfield::field::npy;

fn scratch(name: &str) -> Scratch {
    crate::support::scratch("wind", name)
}

fn run(args: &[&str]) -> Output {
    Command::new(bin()).args(args).output().unwrap()
}

fn path(dir: &Scratch, name: &str) -> String {
    dir.0.join(name).display().to_string()
}

/// A solid sphere of radius 0.5 at the origin in a uniform wind of 1 m/s along x.
const SPHERE: &str = r#"{"version": 1, "field": {"amplitude": 0},
  "wind": [{"type": "uniform", "velocity": [1, 0, 0]}],
  "render": {"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 0.5,
                          "color": [1, 1, 1], "solid": true}]}}"#;

fn potential_flow(x: [f64; 3]) -> [f64; 3] {
    let r = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
    if r < 0.5 {
        return [0.0; 3];
    }
    let q = 0.5 * 0.125 / (r * r * r);
    let ur = x[0] / r;
    let mut u = [1.0, 0.0, 0.0];
    for (a, v) in u.iter_mut().enumerate() {
        let n = x[a] / r;
        *v -= q * (3.0 * ur * n - if a == 0 { 1.0 } else { 0.0 });
    }
    u
}

#[test]
fn the_wind_at_points_and_over_a_box_is_the_potential_flow_past_the_sphere() {
    let dir = scratch("sphere");
    let scene = path(&dir, "sphere.json");
    std::fs::write(&scene, SPHERE).unwrap();
    // Points: the equator (1.5 U), a stagnation point (0), the equator line at r = 1.
    let points = path(&dir, "points.json");
    std::fs::write(
        &points,
        "[[0, 0.5001, 0], [-0.5001, 0, 0], [0, 0, 1], [0.3, -0.7, 0.2]]",
    )
    .unwrap();
    let out = path(&dir, "at.json");
    let o = run(&[
        "wind",
        &scene,
        "--seconds",
        "1",
        "--points",
        &points,
        "--out",
        &out,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let u: Vec<[f64; 3]> = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(u.len(), 4);
    assert!((u[0][0] - 1.5).abs() < 0.01 && u[1][0].abs() < 0.01);
    assert!((u[2][0] - (1.0 + 0.125 / 2.0)).abs() < 0.01);
    let want = potential_flow([0.3, -0.7, 0.2]);
    assert!(
        (0..3).all(|a| (u[3][a] - want[a]).abs() < 0.05),
        "{:?} vs {want:?}",
        u[3]
    );
    // A box of 12 × 8 × 6 cells: float32 .npy of shape (6, 8, 12, 3), x fastest; the same
    // values as .json, in the same order.
    let npy_out = path(&dir, "box.npy");
    let json_out = path(&dir, "box.json");
    for out in [&npy_out, &json_out] {
        let o = run(&[
            "wind",
            &scene,
            "--seconds",
            "1",
            "--box",
            "-1.5,-1,-0.75,1.5,1,0.75",
            "--n",
            "12,8,6",
            "--out",
            out,
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let (shape, data) = npy::read_f32(std::fs::File::open(&npy_out).unwrap()).unwrap();
    assert_eq!(shape, vec![6, 8, 12, 3]);
    let listed: Vec<[f32; 3]> =
        serde_json::from_str(&std::fs::read_to_string(&json_out).unwrap()).unwrap();
    assert_eq!(listed.len(), 6 * 8 * 12);
    for (i, v) in listed.iter().enumerate() {
        assert_eq!(&data[3 * i..3 * i + 3], v, "cell {i}");
    }
    for z in 0..6 {
        for y in 0..8 {
            for x in 0..12 {
                let c = [
                    -1.5 + 0.25 * (x as f64 + 0.5),
                    -1.0 + 0.25 * (y as f64 + 0.5),
                    -0.75 + 0.25 * (z as f64 + 0.5),
                ];
                let r = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
                let i = 3 * ((z * 8 + y) * 12 + x);
                let want = potential_flow(c);
                if !(0.5..=0.525).contains(&r) {
                    for a in 0..3 {
                        assert!(
                            (data[i + a] as f64 - want[a]).abs() < 0.05,
                            "{c:?}: {:?} vs {want:?}",
                            &data[i..i + 3]
                        );
                    }
                }
            }
        }
    }
}

fn refused(args: &[&str], flag: &str, out: &Path) {
    let o = run(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert!(
        err.contains("windfield: error:") && err.contains(flag),
        "{args:?}: {err}"
    );
    assert!(!out.exists(), "{args:?} left {}", out.display());
    let leftovers: Vec<_> = std::fs::read_dir(out.parent().unwrap())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains("partial"))
        .collect();
    assert!(leftovers.is_empty());
}

#[test]
fn bad_input_is_refused_naming_the_flag_or_the_file() {
    let dir = scratch("bad");
    let scene = path(&dir, "sphere.json");
    std::fs::write(&scene, SPHERE).unwrap();
    let points = path(&dir, "points.json");
    std::fs::write(&points, "[[0, 1, 0], [0, \"two\", 0]]").unwrap();
    let nan = path(&dir, "nan.json");
    std::fs::write(&nan, "[[0, 1, 0], [0, 2e6, 0]]").unwrap();
    let out_json = path(&dir, "out.json");
    let out_npy = path(&dir, "out.npy");
    let out_vdb = path(&dir, "out.vdb");
    let b = ["--box", "-1,-1,-1,1,1,1", "--n", "4,4,4"];
    let with = |extra: &[&str], out: &str| {
        let mut a = vec!["wind", &scene, "--seconds", "1"];
        a.extend_from_slice(extra);
        a.extend_from_slice(&["--out", out]);
        a.iter().map(|s| s.to_string()).collect::<Vec<_>>()
    };
    let check = |args: Vec<String>, flag: &str, out: &str| {
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&refs, flag, Path::new(out));
    };
    check(
        with(&["--points", &points], &out_vdb),
        "--out: the wind at --points is written as .json",
        &out_vdb,
    );
    check(
        with(&b, &path(&dir, "out.txt")),
        "--out",
        &path(&dir, "out.txt"),
    );
    check(with(&["--points", &points], &out_npy), "--out", &out_npy);
    check(
        with(&["--points", &points], &out_json),
        "points.json",
        &out_json,
    );
    check(with(&["--points", &nan], &out_json), "[1][1]", &out_json);
    check(
        with(&["--box", "1,1,1,-1,-1,-1", "--n", "4,4,4"], &out_npy),
        "--box",
        &out_npy,
    );
    check(
        with(&["--box", "-1,-1,-1,1,1", "--n", "4,4,4"], &out_npy),
        "--box",
        &out_npy,
    );
    check(
        with(&["--box", "-1,-1,-1,1,1,1", "--n", "4,0,4"], &out_npy),
        "--n",
        &out_npy,
    );
    check(
        with(
            &["--box", "-1,-1,-1,1,1,1", "--n", "4096,4096,4096"],
            &out_npy,
        ),
        "--n",
        &out_npy,
    );
    let mut neg = with(&b, &out_npy);
    neg[3] = "-2".into();
    check(neg, "--seconds", &out_npy);
    // A scene refused by the core names its file and path.
    let broken = path(&dir, "broken.json");
    std::fs::write(
        &broken,
        SPHERE.replace("\"radius\": 0.5", "\"radius\": -0.5"),
    )
    .unwrap();
    let mut a = with(&b, &out_npy);
    a[1] = broken.clone();
    check(a, "render.objects[0].radius", &out_npy);
}
