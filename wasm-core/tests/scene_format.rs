//! The scene format (docs/FORMATS.md): strict parsing with path-naming errors, defaults, versions,
//! and the shipped JSON Schema.

use windfield::scene::scene_format::{json_schema, Scene};

const GOOD: &str = r#"{
  "version": 1, "seed": 1,
  "field": {"size": [32, 32, 32, 32], "spectrum": {"law": "kolmogorov", "epsilon": 1, "k_inertial": 4, "sigma": 1},
            "period": [4, 4, 4], "time_period": 8, "amplitude": 1},
  "wind": [{"type": "uniform", "velocity": [0, 0.5, 0]},
           {"type": "source", "position": [0, 1, 0], "strength": -0.3},
           {"type": "vortex", "position": [0, 1, 0], "axis": [0, 1, 0], "strength": 0.5, "radius": 0.2, "decay": 1.5},
           {"type": "repulsor", "radius": 0.3, "strength": 1, "path": [[0, 0, 1, 0], [2, 1, 1, 0]], "enabled": false}],
  "emitters": [{"shape": "disk", "center": [0, 0, 0], "normal": [0, 1, 0], "radius": 0.1, "size": [0.1, 0.1, 0.1],
                "rate": 30, "sigma0": 0.05, "mass0": 1, "albedo": [1, 1, 1], "emission": [0, 0, 0], "velocity": [0, 0.2, 0]}],
  "gas": {"diffusion": 0.01, "dissipation": 0.1, "split_sigma": null, "max_blobs": 20000, "min_mass": 0.0001},
  "simulation": {"dt": 0.016666, "integrator": "rk2"},
  "render": {"camera": {"position": [0, 1, 4], "target": [0, 1, 0], "up": [0, 1, 0], "fov_y_deg": 40},
             "image": {"width": 640, "height": 480, "encoding": "srgb"},
             "medium": {"extinction": [1, 1, 1], "albedo": [0.9, 0.9, 0.9], "phase": {"type": "henyey-greenstein", "g": 0.4}},
             "lights": [{"type": "point", "position": [2, 3, 2], "color": [1, 1, 1]},
                        {"type": "directional", "direction": [0, -1, 0], "color": [0.5, 0.5, 0.5]}],
             "shadows": true, "background": [0, 0, 0],
             "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 0.5, "color": [0.8, 0.8, 0.8]},
                         {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "color": [0.5, 0.5, 0.5]},
                         {"type": "cylinder", "base": [0, 0, 0], "axis": [0, 1, 0], "radius": 0.2, "height": 0.3, "color": [1, 1, 1]}]}
}"#;

/// Applies `edit` to the good scene, parses it, and returns the error text.
fn error_of(edit: impl Fn(&mut serde_json::Value)) -> String {
    let mut v: serde_json::Value = serde_json::from_str(GOOD).unwrap();
    edit(&mut v);
    // Read from text and from a parsed value alike.
    let from_text = Scene::from_json(&v.to_string()).map_err(|e| e.to_string());
    let from_value = Scene::from_value(v).map_err(|e| e.to_string());
    assert_eq!(from_text.is_ok(), from_value.is_ok());
    match from_value {
        Ok(_) => "accepted".into(),
        Err(e) => {
            assert_eq!(from_text.unwrap_err(), e, "text and value read alike");
            e
        }
    }
}

#[test]
fn the_full_example_parses_and_round_trips() {
    let s = Scene::from_json(GOOD).unwrap();
    assert_eq!(s.wind.len(), 4);
    let again = Scene::from_json(&s.to_json()).unwrap();
    assert_eq!(s, again);
}

#[test]
fn render_time_is_optional_and_kept_as_given() {
    let s = Scene::from_json(r#"{"version": 1}"#).unwrap();
    assert_eq!((s.render.time, s.render.still_time()), (None, 3.0));
    assert!(
        !s.to_json().contains("\"time\""),
        "no time is written when none was given"
    );
    let t = Scene::from_json(r#"{"version": 1, "render": {"time": 0}}"#).unwrap();
    assert_eq!(t.render.still_time(), 0.0);
    assert_eq!(Scene::from_json(&t.to_json()).unwrap(), t);
    // A blob list made from the scene is one moment: it carries no time.
    let list = windfield::scene::blob_list::BlobList::new(t.render.clone(), Vec::new());
    assert!(!serde_json::to_string(&list).unwrap().contains("\"time\""));
}

#[test]
fn a_minimal_scene_takes_the_paper_defaults() {
    let s = Scene::from_json(r#"{"version": 1}"#).unwrap();
    assert_eq!(s.field.size, [32; 4]);
    assert_eq!(s.field.spectrum.epsilon, 1.0);
    assert_eq!(s.field.spectrum.k_inertial, 4.0);
    assert_eq!(s.field.spectrum.sigma, 1.0);
    assert_eq!(s.seed, 1);
    let partial =
        Scene::from_json(r#"{"version": 1, "field": {"spectrum": {"sigma": 0.5}}}"#).unwrap();
    assert_eq!(partial.field.spectrum.k_inertial, 4.0);
    assert_eq!(partial.field.spectrum.sigma, 0.5);
}

type Edit = Box<dyn Fn(&mut serde_json::Value)>;

#[test]
fn any_even_lattice_within_the_memory_guard_is_a_valid_scene() {
    for size in [
        [24, 48, 48, 16],
        [6, 10, 4, 8],
        [256, 256, 16, 16],
        [64, 64, 64, 64],
    ] {
        let text = format!(
            r#"{{"version": 1, "field": {{"size": {size:?}, "spectrum": {{"k_inertial": 1}}}}}}"#
        );
        let s = Scene::from_json(&text).unwrap_or_else(|e| panic!("{size:?}: {e}"));
        assert_eq!(s.field.size, size);
    }
}

fn set(pointer: &'static str, value: serde_json::Value) -> Edit {
    Box::new(move |v| {
        *v.pointer_mut(pointer)
            .unwrap_or_else(|| panic!("{pointer}")) = value.clone()
    })
}

fn insert(pointer: &'static str, key: &'static str, value: serde_json::Value) -> Edit {
    Box::new(move |v| {
        v.pointer_mut(pointer)
            .unwrap()
            .as_object_mut()
            .unwrap()
            .insert(key.into(), value.clone());
    })
}

fn remove(key: &'static str) -> Edit {
    Box::new(move |v| {
        v.as_object_mut().unwrap().remove(key);
    })
}

/// JSON has one number type: a program that writes every number as a float (`32.0`) writes the
/// same scene as one that writes integers, and a fraction is still refused.
#[test]
fn whole_numbers_written_as_floats_read_as_integers() {
    let ints = r#"{"version": 1, "seed": 7, "field": {"size": [16, 32, 16, 8]},
        "gas": {"max_blobs": 500}, "shapes": [{"shape": "torus", "count": 40}],
        "render": {"image": {"width": 64, "height": 48}}}"#;
    let floats = r#"{"version": 1.0, "seed": 7.0, "field": {"size": [16.0, 3.2e1, 16, 8.0]},
        "gas": {"max_blobs": 500.0}, "shapes": [{"shape": "torus", "count": 40.0}],
        "render": {"image": {"width": 64.0, "height": 4.8e1}}}"#;
    let a = Scene::from_json(ints).unwrap();
    assert_eq!(a, Scene::from_json(floats).unwrap());
    assert_eq!(
        a,
        Scene::from_value(serde_json::from_str(floats).unwrap()).unwrap()
    );
    let e = Scene::from_json(&floats.replace("3.2e1", "32.5"))
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "field.size[1]: must be an even number between 4 and 256 (got 32.5)"
    );
}

/// A value of the wrong type is told the key's own range, in the words the validation walk
/// uses for a number of the right type out of it, whatever the type met.
#[test]
fn a_wrong_type_is_told_the_keys_range() {
    use serde_json::json;
    for (pointer, wrong, out_of_range) in [
        ("/field/size/1", json!(-1), json!(33)),
        ("/field/size/1", json!("32"), json!(258)),
        ("/field/size/1", json!(32.5), json!(2)),
        ("/seed", json!(1.5), json!(9007199254740993u64)),
        ("/gas/max_blobs", json!(-1), json!(0)),
        ("/field/period/0", json!("far"), json!(0)),
        ("/wind/1/strength", json!("strong"), json!(2e6)),
        ("/render/image/width", json!(-5), json!(0)),
        ("/render/medium/phase/g", json!(null), json!(1)),
        ("/emitters/0/albedo/1", json!(true), json!(1.5)),
    ] {
        let set = |value: &serde_json::Value| {
            let value = value.clone();
            move |v: &mut serde_json::Value| *v.pointer_mut(pointer).unwrap() = value.clone()
        };
        let said = error_of(set(&wrong));
        let expected = error_of(set(&out_of_range));
        let range = |e: &str| e.split_once(" (got ").map(|(r, _)| r.to_string());
        assert!(range(&said).is_some(), "{pointer} = {wrong}: {said}");
        assert_eq!(range(&said), range(&expected), "{pointer} = {wrong}");
    }
    assert_eq!(
        error_of(|v| v["field"]["size"][1] = json!(-1)),
        "field.size[1]: must be an even number between 4 and 256 (got -1)"
    );
    // Where no number reads (a list for a flag), serde's own words stay.
    assert_eq!(
        error_of(|v| v["render"]["shadows"] = json!([1])),
        "render.shadows: must be true or false (got a list)"
    );
}

#[test]
fn malformed_scenes_are_rejected_with_their_path() {
    use serde_json::json;
    let cases: Vec<(Edit, &str, &str)> = vec![
        (remove("version"), "version", "missing"),
        (set("/version", json!(2)), "version", "unsupported"),
        (
            set("/version", json!("one")),
            "version",
            "must be the number 1 (got the string \"one\")",
        ),
        (insert("", "colour", json!(1)), "colour", "unknown field"),
        // A key of named choices given another JSON type is told its choices, not that the
        // document is not JSON.
        (
            set("/field/spectrum/law", json!(3)),
            "field.spectrum.law",
            "must be \"kolmogorov\" or \"paper-literal\" (got 3)",
        ),
        (
            set("/simulation/integrator", json!([2])),
            "simulation.integrator",
            "must be \"rk2\" or \"euler\" (got a list)",
        ),
        // A required key left out is named by its own path.
        (
            set("/wind/0", json!({"type": "uniform"})),
            "wind[0].velocity",
            "missing: this key has no default",
        ),
        // ... beside keys that were given, and within an element chosen by its type an unknown
        // key and a list of the wrong length are named by their own paths too.
        (
            set("/wind/0", json!({"type": "source", "position": [0, 0, 0]})),
            "wind[0].strength",
            "missing: this key has no default",
        ),
        (
            set(
                "/wind/0",
                json!({"type": "uniform", "velocity": [0, 0, 0], "speed": 1}),
            ),
            "wind[0].speed",
            "unknown field `speed`",
        ),
        (
            set(
                "/wind/0",
                json!({"type": "uniform", "velocity": [0, 0, 0, 0]}),
            ),
            "wind[0].velocity",
            "must be a list of 3 numbers (got 4 items)",
        ),
        // An isotropic phase has no keys but its type.
        (
            set(
                "/render/medium/phase",
                json!({"type": "isotropic", "g": 0.5}),
            ),
            "render.medium.phase.g",
            "unknown field `g`",
        ),
        // A value kept in single precision is echoed in its own digits; one extinction for all
        // channels is named without an index.
        (
            set("/emitters/0/albedo", json!([1.1, 0.5, 0.5])),
            "emitters[0].albedo[0]",
            "must be a finite number between 0 and 1 (got 1.1)",
        ),
        (
            set("/render/medium/extinction", json!(-1)),
            "render.medium.extinction",
            "must be a finite number between 0 and 1000000 (got -1)",
        ),
        // A list of a fixed length given more items is told its length, as one given fewer.
        (
            set("/field/size", json!([16, 16, 16, 16, 16])),
            "field.size",
            "must be a list of 4 numbers (got 5 items)",
        ),
        (
            set("/field/size", json!([16, 16, 16])),
            "field.size",
            "must be a list of 4 numbers (got 3 items)",
        ),
        (
            set("/seed", json!(-1)),
            "seed",
            "must be an integer between 0 and 9007199254740992 (got -1)",
        ),
        (
            set("/seed", json!(9007199254740993u64)),
            "seed",
            "between 0 and",
        ),
        (
            set("/field/size/1", json!(33)),
            "field.size[1]",
            "must be an even number between 4 and 256 (got 33 for ny)",
        ),
        (
            set("/field/size/3", json!(258)),
            "field.size[3]",
            "even number between 4 and 256 (got 258 for nt)",
        ),
        (
            set("/field/size/2", json!(2)),
            "field.size[2]",
            "(got 2 for nz)",
        ),
        (
            set("/field/size", json!([128, 128, 128, 128])),
            "field.size",
            "at most",
        ),
        (
            set("/field/size", json!([32, 32, 32])),
            "field.size",
            "must be a list of 4 numbers (got 3 items)",
        ),
        (
            set("/field/size/0", json!("32")),
            "field.size[0]",
            "must be an even number between 4 and 256 (got the string \"32\")",
        ),
        (
            set("/field/spectrum/law", json!("kolmogoroff")),
            "field.spectrum.law",
            "must be \"kolmogorov\" or \"paper-literal\" (got \"kolmogoroff\")",
        ),
        (
            set("/field/spectrum/epsilon", json!(-1)),
            "field.spectrum.epsilon",
            "greater than 0",
        ),
        (
            set("/field/spectrum/k_inertial", json!(300)),
            "field.spectrum.k_inertial",
            "at most 256",
        ),
        (
            set("/field/spectrum/sigma", json!(-0.5)),
            "field.spectrum.sigma",
            "between 0 and 100",
        ),
        (
            insert("/field/spectrum", "c", json!(1.5)),
            "field.spectrum.c",
            "unknown field",
        ),
        (
            set("/field/period/2", json!(0)),
            "field.period[2]",
            "between 0.001 and 10000",
        ),
        (
            set("/field/time_period", json!(-8)),
            "field.time_period",
            "between 0.001 and 1000000 ",
        ),
        (
            set("/field/amplitude", json!(-1)),
            "field.amplitude",
            "between 0",
        ),
        (
            set("/wind/0/type", json!("tornado")),
            "wind[0].type",
            "must be one of \"uniform\", ",
        ),
        (
            insert("/wind/0", "speed", json!(1)),
            "wind[0].speed",
            "unknown field `speed`",
        ),
        (
            set("/wind/0/velocity", json!([0, 1])),
            "wind[0].velocity",
            "must be a list of 3 numbers (got 2 items)",
        ),
        (
            set("/wind/1/strength", json!("strong")),
            "wind[1].strength",
            "must be a finite number between -1000000 and 1000000 (got the string \"strong\")",
        ),
        (
            insert("/render/objects/0", "solid", json!("yes")),
            "render.objects[0].solid",
            "must be true or false (got the string \"yes\")",
        ),
        (
            insert("/render/objects/2", "solid", json!(1)),
            "render.objects[2].solid",
            "must be true or false (got 1)",
        ),
        (
            set("/render/lights/0/position", json!("up")),
            "render.lights[0].position",
            "(got the string \"up\")",
        ),
        (
            set("/render/medium/phase/g", json!(null)),
            "render.medium.phase.g",
            "must be strictly between -1 and 1 (got null)",
        ),
        (
            insert("/wind/1", "radius", json!(0)),
            "wind[1].radius",
            "greater than 0",
        ),
        (
            set("/wind/2/axis", json!([0, 0, 0])),
            "wind[2].axis",
            "non-zero direction",
        ),
        (
            set("/wind/2/decay", json!(-1)),
            "wind[2].decay",
            "greater than 0",
        ),
        (
            set("/wind/3/path", json!([])),
            "wind[3].path",
            "at least one key",
        ),
        (
            set("/wind/3/path/1/0", json!(0)),
            "wind[3].path[1][0]",
            "increase strictly",
        ),
        (
            set("/wind/3/strength", json!(-1)),
            "wind[3].strength",
            "between 0",
        ),
        (
            set("/emitters/0/shape", json!("cone")),
            "emitters[0].shape",
            "(got \"cone\")",
        ),
        (
            set("/emitters/0/rate", json!(-3)),
            "emitters[0].rate",
            "between 0",
        ),
        (
            set("/emitters/0/sigma0", json!(0)),
            "emitters[0].sigma0",
            "greater than 0",
        ),
        (
            set("/emitters/0/albedo/1", json!(1.5)),
            "emitters[0].albedo[1]",
            "between 0 and 1",
        ),
        (
            set("/emitters/0/normal", json!([0, 0, 0])),
            "emitters[0].normal",
            "non-zero",
        ),
        (
            set("/gas/max_blobs", json!(0)),
            "gas.max_blobs",
            "between 1 and",
        ),
        (
            set("/gas/max_blobs", json!(5_000_000)),
            "gas.max_blobs",
            "between 1 and",
        ),
        (
            set("/gas/split_sigma", json!(0)),
            "gas.split_sigma",
            "greater than 0",
        ),
        (
            set("/gas/diffusion", json!(1e300)),
            "gas.diffusion",
            "between 0",
        ),
        (
            set("/simulation/dt", json!(0)),
            "simulation.dt",
            "greater than 0",
        ),
        (
            set("/simulation/integrator", json!("rk4")),
            "simulation.integrator",
            "must be \"rk2\" or \"euler\" (got \"rk4\")",
        ),
        (
            set("/render/camera/fov_y_deg", json!(180)),
            "render.camera.fov_y_deg",
            "between",
        ),
        (
            set("/render/camera/target", json!([0, 1, 4])),
            "render.camera.target",
            "must differ",
        ),
        (
            set("/render/image/width", json!(0)),
            "render.image.width",
            "between 1 and",
        ),
        (
            set("/render/image/encoding", json!("gamma")),
            "render.image.encoding",
            "(got \"gamma\")",
        ),
        (
            set("/render/medium/phase/g", json!(1)),
            "render.medium.phase.g",
            "strictly between -1 and 1",
        ),
        (
            set("/render/medium/albedo/0", json!(2)),
            "render.medium.albedo[0]",
            "between 0 and 1",
        ),
        (
            set("/render/lights/1/direction", json!([0, 0, 0])),
            "render.lights[1].direction",
            "non-zero",
        ),
        (
            set("/render/objects/0/radius", json!(-1)),
            "render.objects[0].radius",
            "greater than 0",
        ),
        (
            set("/render/shadows", json!("yes")),
            "render.shadows",
            "must be true or false (got the string \"yes\")",
        ),
        (
            insert("/render", "time", json!(-1)),
            "render.time",
            "between 0 and 1000000",
        ),
        (
            insert("/render", "time", json!("soon")),
            "render.time",
            "must be a finite number between 0 and 1000000 (got the string \"soon\")",
        ),
        (
            insert("/render", "time", json!(20_000)),
            "simulation.dt",
            "20000 s of simulated time",
        ),
    ];
    assert!(cases.len() >= 20);
    for (edit, path, text) in cases {
        let e = error_of(edit);
        assert!(
            e.starts_with(&format!("{path}: ")),
            "expected path {path}, got: {e}"
        );
        assert!(e.contains(text), "expected '{text}' in: {e}");
    }
    // Not JSON at all, and not an object.
    let e = Scene::from_json("{").unwrap_err().to_string();
    assert!(e.starts_with("scene: not valid JSON"), "{e}");
    assert!(Scene::from_json("[1]")
        .unwrap_err()
        .to_string()
        .starts_with("scene: must be a JSON object"));
}

#[test]
fn the_shipped_schema_is_the_generated_one() {
    let shipped = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../public/scene.schema.json"))
        .expect("public/scene.schema.json exists: regenerate with `windfield schema > public/scene.schema.json`");
    assert_eq!(
        shipped,
        json_schema(),
        "regenerate with `windfield schema > public/scene.schema.json`"
    );
    let v: serde_json::Value = serde_json::from_str(&shipped).unwrap();
    assert_eq!(v["required"], serde_json::json!(["version"]));
    assert_eq!(v["additionalProperties"], serde_json::json!(false));
}
