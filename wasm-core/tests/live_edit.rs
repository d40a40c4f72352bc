//! Live edits (paper §6: "turbulent wind fields can be superposed interactively"): an edited
//! scene takes effect on the running simulation, which keeps its blobs and its time; σ, mass and
//! births stay continuous across the edit and then follow the new constants (Eqs. 15, 16).

use glam::Vec3;
use serde_json::{json, Value};
use windfield::gas::simulation::Edit;
use windfield::{Scene, Simulation};

/// A calm scene (no small-scale field) with `extra` merged in.
fn scene(extra: &Value) -> Scene {
    let mut v = json!({
        "version": 1,
        "field": {"amplitude": 0},
        "wind": [{"type": "uniform", "velocity": [0, 0.5, 0]}],
        "emitters": [{"shape": "disk", "center": [0, 0, 0], "radius": 0.1, "rate": 50, "sigma0": 0.02, "mass0": 1}],
        "gas": {"diffusion": 0.002, "dissipation": 0.2, "min_mass": 0, "max_blobs": 5000}
    });
    merge(&mut v, extra);
    Scene::from_value(v).unwrap()
}

fn merge(into: &mut Value, from: &Value) {
    match (into, from) {
        (Value::Object(a), Value::Object(b)) => {
            for (k, v) in b {
                merge(a.entry(k.clone()).or_insert(Value::Null), v);
            }
        }
        (a, b) => *a = b.clone(),
    }
}

fn centroid(sim: &Simulation) -> Vec3 {
    let b = sim.blobs();
    (0..b.len()).map(|i| b.center(i)).sum::<Vec3>() / b.len() as f32
}

#[test]
fn an_edit_that_changes_nothing_changes_nothing() {
    let s = scene(&json!({}));
    let mut edited = Simulation::new(s.clone()).unwrap();
    let mut plain = Simulation::new(s.clone()).unwrap();
    edited.run(60);
    plain.run(60);
    assert_eq!(edited.edit(s, None).unwrap(), Edit::Kept);
    edited.run(60);
    plain.run(60);
    assert_eq!(edited.blobs().position, plain.blobs().position);
    assert_eq!(edited.blobs().sigma, plain.blobs().sigma);
    assert_eq!(edited.blobs().mass, plain.blobs().mass);
    assert_eq!(edited.time(), plain.time());
}

#[test]
fn a_wind_edit_keeps_the_blobs_and_the_time_and_turns_the_wind() {
    let mut sim = Simulation::new(scene(&json!({}))).unwrap();
    sim.run(60);
    let (count, time, before) = (sim.blobs().len(), sim.time(), sim.blobs().position.clone());
    let c0 = centroid(&sim);
    let turned = scene(&json!({"wind": [{"type": "uniform", "velocity": [0.4, 0, 0]}]}));
    assert_eq!(sim.edit(turned, None).unwrap(), Edit::Kept);
    assert_eq!(sim.blobs().len(), count);
    assert_eq!(sim.time(), time);
    assert_eq!(sim.blobs().position, before);
    sim.run(30);
    // Blobs alive before the edit moved 0.4 m/s × 0.5 s along x and not at all along y.
    let b = sim.blobs();
    for i in 0..count.min(b.len()) {
        let d = b.center(i) - Vec3::from_slice(&before[3 * i..3 * i + 3]);
        assert!(
            (d - Vec3::new(0.2, 0.0, 0.0)).length() < 1e-4,
            "blob {i} moved {d}"
        );
    }
    assert!(centroid(&sim).x > c0.x + 0.1);
}

#[test]
fn an_emitter_edit_neither_bursts_nor_stalls() {
    let mut sim = Simulation::new(scene(&json!({}))).unwrap();
    sim.run(120); // 2 s at 50 blobs/s
    let emitted = sim.gas.counts.emitted;
    assert_eq!(emitted, 100);
    let faster = scene(
        &json!({"emitters": [{"shape": "disk", "center": [0.3, 0, 0], "radius": 0.1, "rate": 200, "sigma0": 0.02, "mass0": 1}]}),
    );
    sim.edit(faster, None).unwrap();
    sim.run(60); // 1 s at 200 blobs/s
    let born = sim.gas.counts.emitted - emitted;
    assert!(
        (199..=201).contains(&born),
        "{born} births in the second after the edit"
    );
    // The new births come from the moved disk.
    let b = sim.blobs();
    let newest = b.center(b.len() - 1);
    assert!((newest.x - 0.3).abs() < 0.11, "{newest}");
}

#[test]
fn an_added_emitter_starts_now_and_an_unchanged_one_keeps_its_clock() {
    let base = scene(&json!({}));
    let mut edited = Simulation::new(base.clone()).unwrap();
    let mut plain = Simulation::new(base.clone()).unwrap();
    edited.run(30);
    plain.run(30);
    let mut two = base.clone();
    let mut second = two.emitters[0].clone();
    second.center = [1.0, 0.0, 0.0];
    two.emitters.push(second);
    edited.edit(two, None).unwrap();
    edited.run(60);
    plain.run(60);
    // 50 blobs/s more for one second, and the first emitter's blobs as they would have been.
    assert_eq!(edited.gas.counts.emitted, plain.gas.counts.emitted + 50);
    let first = |s: &Simulation| {
        let b = s.blobs();
        (0..b.len())
            .filter(|&i| b.center(i).x < 0.5)
            .map(|i| b.center(i).to_array())
            .collect::<Vec<_>>()
    };
    assert_eq!(first(&edited), first(&plain));
}

#[test]
fn diffusion_and_dissipation_edits_are_continuous_then_follow_the_new_constants() {
    // One blob at a time (the cap keeps the newest), born once a second.
    let mut s = scene(&json!({"emitters": [{"rate": 1}]}));
    s.gas.max_blobs = 1;
    let mut sim = Simulation::new(s).unwrap();
    sim.run(60);
    let (sigma, mass) = (sim.blobs().sigma[0] as f64, sim.blobs().mass[0] as f64);
    let mut edited =
        scene(&json!({"emitters": [{"rate": 1}], "gas": {"diffusion": 0.01, "dissipation": 1.0}}));
    edited.gas.max_blobs = 1;
    // Stop births so the one blob stays the one we follow.
    edited.emitters[0].rate = 0.0;
    sim.edit(edited, None).unwrap();
    assert_eq!(sim.blobs().sigma[0] as f64, sigma);
    assert_eq!(sim.blobs().mass[0] as f64, mass);
    sim.run(60); // one second
    let (s1, m1) = (sim.blobs().sigma[0] as f64, sim.blobs().mass[0] as f64);
    assert!(
        ((s1 * s1 - sigma * sigma) / 0.01 - 1.0).abs() < 1e-3,
        "σ² grew by {}",
        s1 * s1 - sigma * sigma
    );
    assert!(
        (m1 / mass - (-1.0f64).exp()).abs() < 1e-5,
        "mass ratio {}",
        m1 / mass
    );
}

#[test]
fn a_time_step_edit_keeps_the_clock_running() {
    let mut sim = Simulation::new(scene(&json!({}))).unwrap();
    sim.run(60);
    let t = sim.time();
    sim.edit(scene(&json!({"simulation": {"dt": 0.01}})), None)
        .unwrap();
    assert_eq!(sim.time(), t);
    sim.run(50);
    assert!((sim.time() - (t + 0.5)).abs() < 1e-12);
}

#[test]
fn a_shapes_edit_restarts_the_scene() {
    let mut sim = Simulation::new(scene(&json!({}))).unwrap();
    sim.run(30);
    let shaped = scene(
        &json!({"shapes": [{"shape": "sphere", "center": [0, 1, 0], "radius": 0.2, "count": 50}]}),
    );
    assert_eq!(sim.edit(shaped, None).unwrap(), Edit::Restarted);
    assert_eq!(sim.time(), 0.0);
    assert_eq!(sim.blobs().len(), 50);
}

#[test]
fn a_bad_edit_is_refused_and_changes_nothing() {
    let mut sim = Simulation::new(scene(&json!({}))).unwrap();
    sim.run(30);
    let before = sim.blobs().position.clone();
    let mut bad = scene(&json!({}));
    bad.simulation.dt = -1.0;
    assert!(sim.edit(bad, None).is_err());
    assert_eq!(sim.blobs().position, before);
}

#[test]
fn stirring_moves_the_gas_near_the_pointer_more_than_the_gas_far_from_it() {
    let still = scene(
        &json!({"wind": [], "emitters": [{"shape": "box", "center": [0, 0, 0], "size": [2, 0.2, 0.2], "rate": 2000}]}),
    );
    let mut sim = Simulation::new(still).unwrap();
    sim.run(30);
    let before = sim.blobs().position.clone();
    let n = sim.blobs().len();
    sim.stir(Some(windfield::scene::scene_format::Primitive::Uniform {
        velocity: [0.0, 1.0, 0.0],
        position: [-0.8, 0.0, 0.0],
        decay: Some(0.1),
        enabled: true,
    }));
    sim.run(10);
    let moved = |lo: f32, hi: f32| {
        let b = sim.blobs();
        let picked: Vec<f32> = (0..n)
            .filter(|&i| (lo..hi).contains(&before[3 * i]))
            .map(|i| (b.center(i) - Vec3::from_slice(&before[3 * i..3 * i + 3])).length())
            .collect();
        picked.iter().sum::<f32>() / picked.len() as f32
    };
    let (near, far) = (moved(-1.0, -0.6), moved(0.6, 1.0));
    assert!(near > 20.0 * far, "near {near} m, far {far} m");
    sim.stir(None);
    let at = sim.blobs().position.clone();
    sim.run(10);
    assert_eq!(&sim.blobs().position[..3 * n], &at[..3 * n]);
}
