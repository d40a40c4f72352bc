//! Wind and gas against closed-form cases (paper §2, §4): straight lines in uniform wind,
//! Eqs. 15–16 exactly, emission counts, vortex orbits, flux and circulation, splitting moments,
//! repulsion, plume spreading, determinism.

use glam::Vec3;
use serde_json::json;
use windfield::gas::{Blob, Gas};
use windfield::scene::scene_format::{Integrator, Scene};
use windfield::wind::Wind;
use windfield::Simulation;

fn scene(v: serde_json::Value) -> Scene {
    let mut base = json!({"version": 1});
    base.as_object_mut()
        .unwrap()
        .extend(v.as_object().unwrap().clone());
    Scene::from_value(base).unwrap()
}

fn calm(extra: serde_json::Value) -> Scene {
    let mut v = json!({"field": {"amplitude": 0}});
    v.as_object_mut()
        .unwrap()
        .extend(extra.as_object().unwrap().clone());
    scene(v)
}

#[test]
fn uniform_wind_moves_blobs_in_straight_lines() {
    let s = calm(json!({
        "wind": [{"type": "uniform", "velocity": [0.3, 0.5, -0.2]}],
        "emitters": [{"shape": "point", "center": [1, 2, 3], "rate": 10}],
        "gas": {"dissipation": 0, "min_mass": 0}
    }));
    let mut sim = Simulation::new(s).unwrap();
    sim.run(120);
    let list = sim.blob_list();
    assert_eq!(list.blobs.len(), 20);
    for b in &list.blobs {
        let age = b.age.unwrap() as f32;
        let want = Vec3::new(1.0, 2.0, 3.0) + Vec3::new(0.3, 0.5, -0.2) * age;
        assert!((Vec3::from_array(b.center) - want).length() < 1e-4, "{b:?}");
    }
}

#[test]
fn diffusion_and_dissipation_follow_eqs_15_and_16() {
    let s = calm(json!({
        "emitters": [{"rate": 7.3, "sigma0": 0.03, "mass0": 2.5}],
        "gas": {"diffusion": 0.004, "dissipation": 0.35, "min_mass": 0}
    }));
    let mut sim = Simulation::new(s).unwrap();
    sim.run(400);
    let list = sim.blob_list();
    assert!(list.blobs.len() > 40);
    for b in &list.blobs {
        let age = b.age.unwrap();
        let sigma = (0.03f64 * 0.03 + 0.004 * age).sqrt();
        let mass = 2.5 * (-0.35 * age).exp();
        assert!(
            (b.sigma as f64 / sigma - 1.0).abs() < 1e-4,
            "σ {} vs {sigma}",
            b.sigma
        );
        assert!(
            (b.mass as f64 / mass - 1.0).abs() < 1e-4,
            "m {} vs {mass}",
            b.mass
        );
    }
}

#[test]
fn emission_counts_match_rate_times_time() {
    for (rate, steps, dt) in [
        (30.0, 60, 1.0 / 60.0),
        (7.5, 100, 0.01),
        (1000.0, 33, 1.0 / 60.0),
        (0.4, 500, 0.02),
    ] {
        let s = calm(json!({
            "emitters": [{"rate": rate}],
            "gas": {"dissipation": 0, "min_mass": 0, "max_blobs": 100000},
            "simulation": {"dt": dt}
        }));
        let mut sim = Simulation::new(s).unwrap();
        sim.run(steps);
        let t = steps as f64 * dt;
        // Births at k / rate for k = 0, 1, ... strictly before t.
        let expected = (rate * t - 1e-9).ceil() as usize;
        assert_eq!(sim.gas.blobs.len(), expected, "rate {rate}, t {t}");
        assert!((sim.gas.blobs.len() as f64 - rate * t).abs() <= 1.0);
    }
}

#[test]
fn rk2_orbits_in_a_vortex_keep_their_radius() {
    let radius_drift = |integrator: &str| {
        let s = calm(json!({
            "wind": [{"type": "vortex", "position": [0, 0, 0], "axis": [0, 1, 0], "strength": 2.0, "radius": 0.05}],
            "simulation": {"dt": 0.01, "integrator": integrator},
            "gas": {"dissipation": 0, "min_mass": 0}
        }));
        let mut sim = Simulation::new(s).unwrap();
        sim.gas
            .blobs
            .push(&blob(Vec3::new(0.5, 0.3, 0.0)), 0.05, 1.0);
        // ω = Γ/(2π(ρ² + a²)) ≈ 1.27 rad/s: 1000 steps is two turns.
        sim.run(1000);
        let p = sim.gas.blobs.center(0);
        assert!((p.y - 0.3).abs() < 1e-5, "height kept");
        (Vec3::new(p.x, 0.0, p.z).length() - 0.5).abs() / 0.5
    };
    let rk2 = radius_drift("rk2");
    let euler = radius_drift("euler");
    assert!(rk2 < 1e-4, "RK2 radius drift {rk2}");
    assert!(euler > 10.0 * rk2, "Euler drifts more ({euler} vs {rk2})");
}

fn blob(p: Vec3) -> Blob {
    Blob::new(p, 0.05, 1.0, 0.0)
}

#[test]
fn source_flux_and_vortex_circulation_match_their_strengths() {
    let s = calm(
        json!({"wind": [{"type": "source", "position": [1, 1, 1], "strength": 3.0, "radius": 0.01}]}),
    );
    let wind = Wind::new(&s, None);
    // Flux through a sphere of radius 1 (midpoint quadrature in θ, φ).
    let (nt, np) = (200, 400);
    let mut flux = 0.0f64;
    for i in 0..nt {
        let th = (i as f64 + 0.5) * std::f64::consts::PI / nt as f64;
        for j in 0..np {
            let ph = (j as f64 + 0.5) * std::f64::consts::TAU / np as f64;
            let n = Vec3::new(
                (th.sin() * ph.cos()) as f32,
                th.cos() as f32,
                (th.sin() * ph.sin()) as f32,
            );
            let u = wind.velocity(Vec3::ONE + n, 0.0);
            flux += u.dot(n) as f64
                * th.sin()
                * (std::f64::consts::PI / nt as f64)
                * (std::f64::consts::TAU / np as f64);
        }
    }
    assert!((flux / 3.0 - 1.0).abs() < 1e-3, "flux {flux}");

    let s = calm(
        json!({"wind": [{"type": "vortex", "position": [0, 0, 0], "axis": [0, 0, 2], "strength": 1.5, "radius": 0.01}]}),
    );
    let wind = Wind::new(&s, None);
    let n = 1000;
    let mut circ = 0.0f64;
    for j in 0..n {
        let a = (j as f64 + 0.5) * std::f64::consts::TAU / n as f64;
        let p = Vec3::new(a.cos() as f32, a.sin() as f32, 0.7);
        let tangent = Vec3::new(-a.sin() as f32, a.cos() as f32, 0.0);
        circ += wind.velocity(p, 0.0).dot(tangent) as f64 * std::f64::consts::TAU / n as f64;
    }
    // Γ ρ²/(ρ² + a²) at ρ = 1.
    assert!(
        (circ - 1.5 / (1.0 + 1e-4)).abs() < 1e-4,
        "circulation {circ}"
    );
}

#[test]
fn decay_multiplies_by_exp_of_minus_distance_over_l() {
    let s = calm(
        json!({"wind": [{"type": "uniform", "velocity": [1, 0, 0], "position": [0, 1, 0], "decay": 0.5}]}),
    );
    let wind = Wind::new(&s, None);
    for d in [0.0f32, 0.3, 1.0, 2.5] {
        let u = wind.velocity(Vec3::new(0.0, 1.0 + d, 0.0), 0.0);
        assert!((u.x - (-d / 0.5).exp()).abs() < 1e-6);
    }
}

#[test]
fn wind_frames_equal_the_quadrilinear_reference() {
    // Powers of two and not: the frame's periodic wrap must agree with the reference's.
    for size in [[16, 16, 16, 8], [12, 10, 6, 6]] {
        let s = scene(json!({
            "field": {"size": size, "period": [2, 3, 4], "time_period": 5, "amplitude": 1.3, "carried_by_wind": true,
                      "spectrum": {"k_inertial": 1}},
            "wind": [
                {"type": "uniform", "velocity": [0.2, 0.1, 0]},
                {"type": "vortex", "position": [0, 0, 0], "axis": [1, 1, 0], "strength": 0.7},
                {"type": "repulsor", "radius": 0.3, "strength": 0.5, "path": [[0, -1, 0, 0], [2, 1, 0.5, 0], [4, 0, 1, 1]]}
            ]
        }));
        let sim = Simulation::new(s).unwrap();
        for (k, t) in [0.0, 0.37, 1.9, 7.3].into_iter().enumerate() {
            let frame = sim.wind.frame(t);
            for i in 0..60 {
                // Mostly within a few periods of the origin, every fifth one tens of periods out.
                let far = if i % 5 == 0 { 40.0 } else { 1.0 };
                let x = Vec3::new(
                    ((i * 37 + k) % 101) as f32 / 17.0 - 3.0,
                    ((i * 53) % 97) as f32 / 19.0 - 2.5,
                    ((i * 71 + 3 * k) % 89) as f32 / 23.0 - 2.0,
                ) * far;
                let a = frame.velocity(x);
                let b = sim.wind.velocity(x, t);
                assert!(
                    (a - b).length() < 1e-4 * (1.0 + b.length()),
                    "{size:?} t {t} x {x}: {a} vs {b}"
                );
            }
        }
    }
}

#[test]
fn turbulence_is_carried_by_the_mean_wind_when_asked() {
    let make = |carried: bool| {
        scene(json!({
            "field": {"size": [16, 16, 16, 16], "carried_by_wind": carried},
            "wind": [{"type": "uniform", "velocity": [0.5, 0, 0]}]
        }))
    };
    let carried = Simulation::new(make(true)).unwrap();
    let fixed = Simulation::new(make(false)).unwrap();
    let u = Vec3::new(0.5, 0.0, 0.0);
    let x = Vec3::new(0.3, -0.2, 1.1);
    for t in [0.0, 0.8, 2.6] {
        // Carried small scale at (x + U t, t) equals the fixed one at (x, t).
        let a = carried.wind.velocity(x + u * t as f32, t) - u;
        let b = fixed.wind.velocity(x, t) - u;
        assert!((a - b).length() < 1e-5, "t {t}: {a} vs {b}");
    }
}

fn second_moments(gas: &Gas) -> (f64, Vec3, [[f64; 3]; 3]) {
    let b = &gas.blobs;
    let m: f64 = b.total_mass();
    let mut mean = Vec3::ZERO;
    for i in 0..b.len() {
        mean += b.center(i) * (b.mass[i] as f64 / m) as f32;
    }
    let mut cov = [[0.0f64; 3]; 3];
    for i in 0..b.len() {
        let d = b.center(i) - mean;
        let w = b.mass[i] as f64 / m;
        for r in 0..3 {
            for c in 0..3 {
                let s2 = if r == c {
                    (b.sigma[i] as f64).powi(2)
                } else {
                    0.0
                };
                cov[r][c] += w * (d[r] as f64 * d[c] as f64 + s2);
            }
        }
    }
    (m, mean, cov)
}

#[test]
fn splitting_conserves_mass_and_moments_and_bounds_sigma() {
    let s = calm(json!({
        "gas": {"diffusion": 0.05, "dissipation": 0, "split_sigma": 0.1, "min_mass": 0, "max_blobs": 1000000},
        "simulation": {"dt": 0.05}
    }));
    let mut sim = Simulation::new(s).unwrap();
    // One blob just under the limit; wide blobs split several levels at once.
    sim.gas.blobs.push(
        &Blob {
            sigma0: 0.099,
            mass0: 3.0,
            ..blob(Vec3::new(1.0, 2.0, 3.0))
        },
        0.099,
        3.0,
    );
    sim.gas.blobs.push(
        &Blob {
            sigma0: 0.7,
            mass0: 1.0,
            ..blob(Vec3::new(-1.0, 0.0, 0.5))
        },
        0.7,
        1.0,
    );
    let before = {
        // The same two blobs diffused one step without splitting.
        let mut g = Gas::new(sim.gas.settings.clone(), &[], 1);
        let (s1, s2) = (
            (0.099f64.powi(2) + 0.05 * 0.05).sqrt() as f32,
            (0.49f64 + 0.05 * 0.05).sqrt() as f32,
        );
        g.blobs.push(&blob(Vec3::new(1.0, 2.0, 3.0)), s1, 3.0);
        g.blobs.push(&blob(Vec3::new(-1.0, 0.0, 0.5)), s2, 1.0);
        second_moments(&g)
    };
    sim.step();
    let after = second_moments(&sim.gas);
    assert!(sim.gas.blobs.len() > 2 && sim.gas.counts.split == 2);
    assert!(
        (after.0 - before.0).abs() < 1e-5 * before.0,
        "mass {} vs {}",
        after.0,
        before.0
    );
    assert!(
        (after.1 - before.1).length() < 1e-5,
        "centre {} vs {}",
        after.1,
        before.1
    );
    for r in 0..3 {
        for c in 0..3 {
            assert!(
                (after.2[r][c] - before.2[r][c]).abs() < 1e-4,
                "moment [{r}][{c}]: {} vs {}",
                after.2[r][c],
                before.2[r][c]
            );
        }
    }
    for _ in 0..10 {
        sim.step();
        assert!(
            sim.gas.blobs.sigma.iter().all(|&s| s <= 0.1 + 1e-6),
            "σ above split_sigma"
        );
        assert_eq!(sim.gas.counts.capped, 0);
        assert!((sim.gas.blobs.total_mass() - 4.0).abs() < 1e-3);
    }
}

#[test]
fn max_blobs_caps_the_count_oldest_first_and_reports_it() {
    let s = calm(json!({
        "emitters": [{"rate": 100}],
        "gas": {"dissipation": 0, "min_mass": 0, "max_blobs": 50, "diffusion": 0.2, "split_sigma": 0.08}
    }));
    let mut sim = Simulation::new(s).unwrap();
    for _ in 0..200 {
        sim.step();
        assert!(sim.gas.blobs.len() <= 50);
    }
    assert!(sim.gas.counts.capped > 0);
    // The newest survive: the youngest blob is at most one step old.
    let youngest = sim.gas.blobs.birth.iter().cloned().fold(f64::MIN, f64::max);
    assert!(sim.time() - youngest <= 1.0 / 60.0 + 1e-9);
}

#[test]
fn repulsor_keeps_gas_out_of_a_moving_sphere() {
    let s = calm(json!({
        "wind": [
            {"type": "uniform", "velocity": [0, 0.3, 0]},
            {"type": "repulsor", "radius": 0.4, "strength": 1.0, "path": [[0, -1.5, 1.0, 0], [3, 0, 1.6, 0.2], [6, 1.5, 1.0, 0]]}
        ],
        "emitters": [{"shape": "box", "center": [0, 0.2, 0], "size": [3, 0.3, 1], "rate": 400, "sigma0": 0.03}],
        "gas": {"dissipation": 0, "min_mass": 0, "max_blobs": 50000}
    }));
    let mut sim = Simulation::new(s).unwrap();
    let mut closest = f32::MAX;
    let mut near = 0;
    for _ in 0..360 {
        sim.step();
        let spheres = sim.wind.visible_spheres(sim.time());
        assert!(spheres.is_empty(), "no colour: invisible");
        let c = {
            let (p, _) = windfield::wind::spline::Path::new(&[
                [0.0, -1.5, 1.0, 0.0],
                [3.0, 0.0, 1.6, 0.2],
                [6.0, 1.5, 1.0, 0.0],
            ])
            .at(sim.time());
            p.as_vec3()
        };
        for i in 0..sim.gas.blobs.len() {
            let d = (sim.gas.blobs.center(i) - c).length();
            closest = closest.min(d);
            if d < 0.6 {
                near += 1;
            }
        }
    }
    assert!(near > 100, "the sphere does meet the smoke ({near})");
    assert!(
        closest > 0.4 * 0.95,
        "a blob came within {closest} of the centre"
    );
}

#[test]
fn turbulence_spreads_a_plume() {
    let spread = |amplitude: f64| {
        let s = scene(json!({
            "seed": 4,
            "field": {"size": [16, 16, 16, 16], "amplitude": amplitude, "period": [2, 2, 2]},
            "wind": [{"type": "uniform", "velocity": [0, 0.5, 0]}],
            "emitters": [{"shape": "point", "rate": 40, "sigma0": 0.02}],
            "gas": {"dissipation": 0, "min_mass": 0}
        }));
        let mut sim = Simulation::new(s).unwrap();
        sim.run(240);
        let b = &sim.gas.blobs;
        let n = b.len() as f32;
        let mean_x = (0..b.len()).map(|i| b.center(i).x).sum::<f32>() / n;
        ((0..b.len())
            .map(|i| (b.center(i).x - mean_x).powi(2))
            .sum::<f32>()
            / n)
            .sqrt()
    };
    let calm_spread = spread(0.0);
    let turbulent = spread(1.0);
    assert!(
        calm_spread < 1e-6,
        "no lateral spread without turbulence ({calm_spread})"
    );
    // About 0.1 m/s of turbulent velocity over a few seconds: centimetres of spread.
    assert!(
        turbulent > 0.01,
        "turbulence spreads the plume ({turbulent} m)"
    );
}

#[test]
fn same_scene_gives_identical_blob_lists() {
    let make = || {
        scene(json!({
            "seed": 9,
            "field": {"size": [16, 16, 16, 8]},
            "wind": [{"type": "uniform", "velocity": [0, 0.4, 0]}, {"type": "source", "position": [0, 1, 0], "strength": -0.2}],
            "emitters": [{"shape": "sphere", "radius": 0.2, "rate": 50}, {"shape": "disk", "center": [1, 0, 0], "rate": 20, "albedo": [1, 0.5, 0.2]}],
            "gas": {"split_sigma": 0.1, "diffusion": 0.01}
        }))
    };
    let run = || {
        let mut sim = Simulation::new(make()).unwrap();
        sim.run(90);
        serde_json::to_string(&sim.blob_list()).unwrap()
    };
    let (a, b) = (run(), run());
    assert_eq!(a, b);
    let mut other = make();
    other.seed = 10;
    let mut sim = Simulation::new(other).unwrap();
    sim.run(90);
    assert_ne!(a, serde_json::to_string(&sim.blob_list()).unwrap());
}

#[test]
fn integrator_names_parse() {
    let s = calm(json!({"simulation": {"integrator": "euler"}}));
    assert_eq!(s.simulation.integrator, Integrator::Euler);
}

#[test]
fn a_moving_source_lays_its_blobs_along_its_path() {
    // No wind: each blob stays where it was born, at the path's point at its birth time.
    let s = calm(json!({
        "emitters": [{"shape": "point", "rate": 20, "path": [[0, 0, 0, 0], [2, 2, 0, -1]]}],
        "gas": {"dissipation": 0, "min_mass": 0}
    }));
    let mut sim = Simulation::new(s).unwrap();
    sim.run(120);
    let list = sim.blob_list();
    assert_eq!(list.blobs.len(), 40);
    for b in &list.blobs {
        let birth = (2.0 - b.age.unwrap()) as f32;
        let want = Vec3::new(birth, 0.0, -0.5 * birth);
        assert!((Vec3::from_array(b.center) - want).length() < 1e-4, "{b:?}");
    }
    // A path's times must increase, as a repulsor's.
    let bad =
        serde_json::json!({"version": 1, "emitters": [{"path": [[1, 0, 0, 0], [1, 1, 0, 0]]}]});
    let e = Scene::from_value(bad).unwrap_err();
    assert_eq!(e.path, "emitters[0].path[1][0]");
}
