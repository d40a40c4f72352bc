//! A scene's flow (paper §7's physical large scales, docs/FORMATS.md, the flow) against the
//! classical results of buoyant plumes (Morton, Taylor & Turner 1956), ceiling jets (Alpert
//! 1972) and the persistence of momentum, run through the scene format and the simulation.

use windfield::gas::simulation::Simulation;
use windfield::scene::Scene;

/// A still-air scene: a point emitter at (0, 0.1, 0) of `temperature` K, a flow over a
/// 1.2 × 2.4 × 1.2 m box (cells of 7.5 cm) with `cooling` 1/s, no small scales; `extra` is
/// spliced into the scene's top level (a ceiling object, say).
fn plume(temperature: f64, cooling: f64, extra: &str) -> Simulation {
    let text = format!(
        r#"{{"version": 1, "seed": 3,
            "field": {{"size": [16, 16, 16, 16], "period": [1, 1, 1], "time_period": 2,
                       "amplitude": 0.15}},
            "emitters": [{{"shape": "disk", "radius": 0.05, "center": [0, 0.1, 0], "rate": 40,
                          "sigma0": 0.06, "mass0": 1, "temperature": {temperature}}}],
            "gas": {{"diffusion": 0.002, "dissipation": 0}},
            "simulation": {{"dt": 0.02}},
            "flow": {{"box": [-0.6, 0, -0.6, 0.6, 2.4, 0.6], "cells": [16, 32, 16],
                      "cooling": {cooling}}}{extra}}}"#
    );
    Simulation::new(Scene::from_json(&text).expect("valid scene")).expect("runs")
}

/// The mean height (m) and the mean horizontal distance from the axis (m) of the blobs born
/// at least `min_age` s ago.
fn height_and_spread(sim: &Simulation, min_age: f64) -> (f64, f64, usize) {
    let b = sim.blobs();
    let t = sim.time();
    let (mut y, mut r, mut n) = (0.0, 0.0, 0);
    for i in 0..b.len() {
        if t - b.birth[i] < min_age {
            continue;
        }
        let c = b.center(i);
        y += c.y as f64;
        r += ((c.x * c.x + c.z * c.z) as f64).sqrt();
        n += 1;
    }
    (y / n as f64, r / n as f64, n)
}

/// Mean of the wind's vertical component on the axis at heights 0.6–1.2 m (m/s).
fn axis_speed(sim: &Simulation) -> f64 {
    let frame = sim.wind_frames()[0].clone();
    (0..7)
        .map(|k| {
            frame
                .velocity(glam::Vec3::new(0.0, 0.6 + 0.1 * k as f32, 0.0))
                .y as f64
        })
        .sum::<f64>()
        / 7.0
}

/// The rms distance from the axis (m) of blobs in height bins of 0.2 m from `lo` m.
fn widths(sim: &Simulation, bins: &[f32]) -> Vec<f64> {
    let b = sim.blobs();
    bins.iter()
        .map(|&lo| {
            let (mut s, mut n) = (0.0, 0);
            for i in 0..b.len() {
                let c = b.center(i);
                if c.y >= lo && c.y < lo + 0.2 {
                    s += (c.x * c.x + c.z * c.z) as f64;
                    n += 1;
                }
            }
            (s / n.max(1) as f64).sqrt()
        })
        .collect()
}

#[test]
fn explore() {
    for (temperature, cooling) in [(0.0, 0.5), (100.0, 0.5), (30.0, 0.0), (60.0, 0.0)] {
        let mut sim = plume(temperature, cooling, "");
        sim.run(150);
        let (y, r, n) = height_and_spread(&sim, 0.0);
        let mut w = 0.0;
        for _ in 0..50 {
            sim.run(2);
            w += axis_speed(&sim) / 50.0;
        }
        let p = sim.projection().expect("a flow");
        println!("T {temperature} c {cooling}: mean height {y:.3} m, spread {r:.3} m over {n} blobs; axis w {w:.3}; widths {:?}; CG {} its, residual {:.2e}", widths(&sim, &[0.3, 0.6, 0.9, 1.2, 1.5]), p.iterations, p.residual);
    }
}
