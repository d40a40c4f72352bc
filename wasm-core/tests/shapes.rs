//! Initial blob sets (the morph of paper §6): points inside their solids, seeded and
//! repeatable, and reversed sets that replay their own forward run backwards in time.

use glam::Vec3;
use serde_json::json;
use windfield::scene::shapes::{Shape, Solid};
use windfield::{Scene, Simulation};

fn scene(v: serde_json::Value) -> Scene {
    let mut base = json!({"version": 1, "seed": 7, "field": {"size": [16, 16, 16, 16]},
                          "gas": {"diffusion": 0.002, "dissipation": 0.3, "min_mass": 0}});
    base.as_object_mut()
        .unwrap()
        .extend(v.as_object().unwrap().clone());
    Scene::from_value(base).unwrap()
}

fn centres(sim: &Simulation) -> Vec<Vec3> {
    let b = sim.blobs();
    (0..b.len()).map(|i| b.center(i)).collect()
}

#[test]
fn points_lie_inside_their_solids() {
    let axis = Vec3::new(1.0, 1.0, 0.0).normalize();
    let c = Vec3::new(0.5, 1.0, -0.2);
    let shape = |solid| Shape {
        shape: solid,
        center: c.to_array(),
        axis: axis.to_array(),
        radius: 0.6,
        thickness: 0.1,
        count: 2000,
        ..Default::default()
    };
    let ball = shape(Solid::Sphere).centres(1, 0);
    assert_eq!(ball.len(), 2000);
    assert!(ball.iter().all(|p| (*p - c).length() <= 0.6 + 1e-5));
    // A uniform ball has mean square radius 3/5 r².
    let ms = ball.iter().map(|p| (*p - c).length_squared()).sum::<f32>() / 2000.0;
    assert!((ms / (0.6 * 0.36) - 1.0).abs() < 0.05, "{ms}");
    let cube = shape(Solid::Cube).centres(1, 0);
    assert!(cube
        .iter()
        .all(|p| (*p - c).abs().max_element() <= 0.6 + 1e-5));
    for p in shape(Solid::Torus).centres(1, 0) {
        let d = p - c;
        let along = d.dot(axis);
        let ring = (d - axis * along).length();
        let tube = ((ring - 0.6).powi(2) + along * along).sqrt();
        assert!(tube <= 0.1 + 1e-5, "torus point {tube} from the ring");
    }
    let trefoil = shape(Solid::Trefoil).centres(1, 0);
    assert!(trefoil
        .iter()
        .all(|p| (*p - c).length() <= 0.6 + 0.1 + 1e-5));
    let listed = Shape {
        shape: Solid::Points,
        center: [1.0, 0.0, 0.0],
        points: vec![[0.0, 1.0, 0.0], [0.0, 0.0, 2.0]],
        ..Default::default()
    };
    assert_eq!(
        listed.centres(3, 0),
        vec![Vec3::new(1.0, 1.0, 0.0), Vec3::new(1.0, 0.0, 2.0)]
    );
}

#[test]
fn the_same_seed_gives_the_same_points_and_another_seed_others() {
    let s = Shape {
        shape: Solid::Torus,
        ..Default::default()
    };
    assert_eq!(s.centres(5, 1), s.centres(5, 1));
    assert_ne!(s.centres(5, 1), s.centres(6, 1));
    assert_ne!(s.centres(5, 1), s.centres(5, 2));
}

#[test]
fn a_reversed_set_replays_its_forward_run_backwards() {
    let set = json!({"shape": "trefoil", "radius": 0.5, "thickness": 0.08, "count": 300,
                     "sigma0": 0.03, "mass0": 0.01, "albedo": [0, 0, 0], "emission": [1, 0.6, 0.2]});
    let mut reversed_set = set.clone();
    reversed_set["reverse_from"] = json!(1.0);
    let dt = 1.0 / 60.0;
    let steps: usize = 60;
    let mut forward = Simulation::new(scene(json!({"shapes": [set]}))).unwrap();
    let mut states = vec![(centres(&forward), forward.blob_list())];
    for _ in 0..steps {
        forward.step();
        states.push((centres(&forward), forward.blob_list()));
    }
    let mut reversed = Simulation::new(scene(json!({"shapes": [reversed_set]}))).unwrap();
    assert!((reversed.scene.simulation.dt - dt).abs() < 1e-4);
    for k in 0..=steps + 5 {
        let mirrored = steps.saturating_sub(k);
        let (want, list) = &states[mirrored];
        assert_eq!(&centres(&reversed), want, "step {k}");
        // σ, mass and age are those of the mirrored forward state.
        let got = reversed.blob_list();
        for (a, b) in got.blobs.iter().zip(&list.blobs) {
            assert_eq!((a.sigma, a.mass), (b.sigma, b.mass));
            assert!((a.age.unwrap() - b.age.unwrap()).abs() < 1e-9);
            assert_eq!(a.emission, Some([1.0, 0.6, 0.2]));
            assert_eq!(a.albedo, Some([0.0, 0.0, 0.0]));
        }
        reversed.step();
    }
}

#[test]
fn a_morph_fades_one_set_out_as_the_other_condenses() {
    let sim_at = |k: u64| {
        let mut sim = Simulation::new(scene(json!({"shapes": [
            {"shape": "torus", "radius": 0.5, "count": 400, "emission": [1, 0.3, 0.1], "albedo": [0, 0, 0]},
            {"shape": "sphere", "radius": 0.4, "count": 400, "emission": [0.1, 0.4, 1], "albedo": [0, 0, 0], "reverse_from": 2.0}
        ]})))
        .unwrap();
        sim.run(k);
        sim
    };
    let mass_of = |sim: &Simulation, blue: bool| -> f64 {
        let l = sim.blob_list();
        l.blobs
            .iter()
            .filter(|b| (b.emission.unwrap()[2] > 0.5) == blue)
            .map(|b| b.mass as f64)
            .sum()
    };
    let (start, end) = (sim_at(0), sim_at(120));
    assert_eq!(start.blobs().len(), 800);
    // α = 0.3/s over 2 s: each set's mass moves between m and m·e^−0.6.
    let full = 400.0 * 0.01;
    let faded = full * (-0.6f64).exp();
    for (got, want) in [
        (mass_of(&start, false), full),
        (mass_of(&start, true), faded),
        (mass_of(&end, false), faded),
        (mass_of(&end, true), full),
    ] {
        assert!((got / want - 1.0).abs() < 1e-4, "{got} vs {want}");
    }
}

#[test]
fn bad_sets_are_rejected_with_their_path() {
    for (set, path) in [
        (json!({"shape": "torus", "count": 0}), "shapes[0].count"),
        (json!({"shape": "cube", "radius": -1}), "shapes[0].radius"),
        (
            json!({"shape": "sphere", "reverse_from": -2}),
            "shapes[0].reverse_from",
        ),
        (json!({"shape": "sphere", "sigma0": 0}), "shapes[0].sigma0"),
        (json!({"shape": "blob"}), "shapes[0].shape"),
        (
            json!({"shape": "points", "points": [[0, "a", 0]]}),
            "shapes[0].points[0][1]",
        ),
        (
            json!({"shape": "sphere", "count": 100000, "reverse_from": 100}),
            "shapes",
        ),
    ] {
        let v = json!({"version": 1, "shapes": [set]});
        let err = Scene::from_json(&v.to_string()).unwrap_err().to_string();
        assert!(err.starts_with(path), "{err} should name {path}");
    }
}
