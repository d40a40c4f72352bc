//! A scene's flow (paper §7's physical large scales, docs/FORMATS.md, the flow) against the
//! classical results of buoyant plumes (Morton, Taylor & Turner 1956), ceiling jets (Alpert
//! 1972) and the persistence of momentum, run through the scene format and the simulation.

use windfield::gas::simulation::Simulation;
use windfield::scene::Scene;

/// A still-air scene: a point emitter at (0, 0.1, 0) of `temperature` K, a flow over a
/// 1.2 × 2.4 × 1.2 m box (cells of 7.5 cm) with `cooling` 1/s, no small scales; `extra` is
/// spliced into the scene's top level (a ceiling object, say).
fn plume_at(rate: f64, amplitude: f64, temperature: f64, cooling: f64, extra: &str) -> Simulation {
    let text = format!(
        r#"{{"version": 1, "seed": 3,
            "field": {{"size": [16, 16, 16, 16], "period": [1, 1, 1], "time_period": 2,
                       "amplitude": {amplitude}}},
            "emitters": [{{"shape": "disk", "radius": 0.05, "center": [0, 0.1, 0], "rate": {rate},
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

/// The rms distance from the axis (m) of the blobs between heights `lo` and `hi` (m), and
/// how many there are, and the highest blob's height (m).
fn band(sim: &Simulation, lo: f32, hi: f32) -> (f64, usize, f32) {
    let b = sim.blobs();
    let (mut s, mut n, mut top) = (0.0, 0, f32::NEG_INFINITY);
    for i in 0..b.len() {
        let c = b.center(i);
        top = top.max(c.y);
        if c.y >= lo && c.y < hi {
            s += (c.x * c.x + c.z * c.z) as f64;
            n += 1;
        }
    }
    ((s / n.max(1) as f64).sqrt(), n, top)
}

/// A hot emitter's gas rises by its heat in still air (mean height after 3 s at least 0.5 m
/// above the emitter); the same emitter without heat stays within 0.1 m of it.
#[test]
fn a_hot_plume_rises_by_its_heat_and_a_cold_one_stays() {
    for (temperature, lo, hi) in [(0.0, 0.0, 0.2), (40.0, 0.6, f64::INFINITY)] {
        let mut sim = plume_at(40.0, 0.15, temperature, 0.5, "");
        sim.run(150);
        let (y, _, n) = height_and_spread(&sim, 0.0);
        println!("T = {temperature} K: mean height {y:.3} m over {n} blobs");
        assert!(n > 100, "{n} blobs");
        assert!(y >= lo && y <= hi, "T = {temperature} K: mean height {y} m");
        if temperature > 0.0 {
            let p = sim.projection().expect("a flow");
            assert!(p.residual <= 1e-4, "{p:?}");
        }
    }
}

/// Plume theory (Morton, Taylor & Turner 1956): with no cooling the rise speed goes as the
/// buoyancy flux's cube root, w ∝ F^{1/3}, so doubling the heat raises it by 2^{1/3} ≈ 1.26
/// (within 1.1–1.45).
#[test]
fn doubling_the_heat_raises_the_rise_speed_by_the_cube_root_of_two() {
    let speed = |temperature: f64| {
        let mut sim = plume_at(40.0, 0.15, temperature, 0.0, "");
        sim.run(150);
        (0..50)
            .map(|_| {
                sim.run(2);
                axis_speed(&sim)
            })
            .sum::<f64>()
            / 50.0
    };
    let (w1, w2) = (speed(30.0), speed(60.0));
    let ratio = w2 / w1;
    println!("rise speed {w1:.3} → {w2:.3} m/s, ratio {ratio:.3}");
    assert!(w1 > 0.2, "{w1}");
    assert!((1.1..=1.45).contains(&ratio), "{ratio}");
}

/// The plume widens about linearly with height (MTT 1956's self-similar plume, b ∝ z − z_v from
/// a virtual origin z_v): the rms distance of its blobs from the axis, averaged over 5 s in
/// 0.2 m bands from 0.3 to 1.9 m, fits a line with r² ≥ 0.9 whose slope is a plume's spreading
/// rate (about 0.1 in experiments; 0.05–0.2 asked) and whose virtual origin lies within 0.5 m
/// of the source (a source of finite width puts it below; ten source radii asked).
#[test]
fn the_plume_widens_about_linearly_with_height() {
    let bins = [0.3f32, 0.5, 0.7, 0.9, 1.1, 1.3, 1.5, 1.7];
    let mut sim = plume_at(250.0, 2.0, 20.0, 0.0, "");
    sim.run(75);
    let mut acc = vec![(0.0f64, 0usize); bins.len()];
    for _ in 0..50 {
        sim.run(5);
        for (k, &lo) in bins.iter().enumerate() {
            let (r, n, _) = band(&sim, lo, lo + 0.2);
            acc[k].0 += r * r * n as f64;
            acc[k].1 += n;
        }
    }
    assert!(acc.iter().all(|&(_, n)| n > 100), "{acc:?}");
    // The bands' middles' heights above the source at 0.1 m.
    let z: Vec<f64> = bins.iter().map(|&lo| lo as f64).collect();
    let w: Vec<f64> = acc.iter().map(|&(s, n)| (s / n as f64).sqrt()).collect();
    let m = z.len() as f64;
    let (mz, mw) = (z.iter().sum::<f64>() / m, w.iter().sum::<f64>() / m);
    let szz: f64 = z.iter().map(|a| (a - mz).powi(2)).sum();
    let sww: f64 = w.iter().map(|b| (b - mw).powi(2)).sum();
    let szw: f64 = z.iter().zip(&w).map(|(a, b)| (a - mz) * (b - mw)).sum();
    let slope = szw / szz;
    let r2 = szw * szw / (szz * sww);
    let virtual_origin = mz - mw / slope;
    println!("widths {w:.3?}: slope {slope:.3}, r² {r2:.3}, virtual origin {virtual_origin:.2} m from the source");
    assert!(
        (0.05..=0.2).contains(&slope) && r2 >= 0.9,
        "slope {slope}, r² {r2}"
    );
    assert!(
        virtual_origin.abs() <= 0.5,
        "virtual origin {virtual_origin} m"
    );
}

/// A ceiling jet (Alpert 1972): the plume under a solid ceiling 1 m up leaves no blob above it
/// and runs out along it, its spread just under the ceiling (0.8–1 m) at least 3× the free
/// plume's at the same height.
#[test]
fn a_plume_under_a_ceiling_runs_out_along_it() {
    let spread = |extra: &str| {
        let mut sim = plume_at(40.0, 0.15, 60.0, 0.2, extra);
        sim.run(200);
        band(&sim, 0.8, 1.0)
    };
    let (free, _, _) = spread("");
    let (under, n, top) = spread(CEILING);
    println!("spread under the ceiling {under:.3} m ({n} blobs), free {free:.3} m; top {top:.3} m");
    assert!(top < 1.0, "a blob at {top} m");
    assert!(n > 50 && under >= 3.0 * free, "{under} vs {free}");
}

/// A solid ceiling 1 m up.
const CEILING: &str = r#", "render": {"objects": [{"type": "plane", "point": [0, 1.0, 0],
    "normal": [0, -1, 0], "color": [0.5, 0.5, 0.5], "solid": true}]}"#;

/// A stir's momentum persists in the flow: half the kinetic energy a half-second drag put in
/// is still there a second after the pointer stops, at air's viscosity.
#[test]
fn a_stir_keeps_turning_after_the_pointer_stops() {
    let text = r#"{"version": 1, "field": {"amplitude": 0}, "simulation": {"dt": 0.02},
        "flow": {"box": [-1, -1, -1, 1, 1, 1], "cells": [24, 24, 24]}}"#;
    let mut sim = Simulation::new(Scene::from_json(text).expect("valid")).expect("runs");
    let energy = |sim: &Simulation| {
        let f = sim.flow().expect("a flow");
        f.flow.u_g.kinetic_energy(&f.flow.grid)
    };
    for k in 0..25 {
        sim.stir_at([-0.3 + 0.024 * k as f32, 0.0, 0.0], [1.2, 0.0, 0.0], 0.15)
            .expect("a stir");
        sim.step();
    }
    sim.stir_at([0.0; 3], [0.0; 3], 0.0).expect("stops");
    let put_in = energy(&sim);
    sim.run(50);
    let left = energy(&sim);
    println!("stir: {put_in:.4e} → {left:.4e}, {:.3}", left / put_in);
    assert!(put_in > 1e-3, "{put_in}");
    assert!(left >= 0.5 * put_in, "{left} of {put_in}");
}

/// The same scene gives the same bytes: two runs of a hot plume under a ceiling agree bit for
/// bit, blobs and grid alike.
#[test]
fn a_flow_scene_gives_the_same_bytes_twice() {
    let run = || {
        let mut sim = plume_at(40.0, 0.15, 60.0, 0.5, CEILING);
        sim.run(40);
        (
            sim.blobs().position.clone(),
            sim.flow_grid().expect("a flow"),
        )
    };
    let (a, b) = (run(), run());
    assert_eq!(a.0, b.0);
    assert_eq!(a.1, b.1);
}

/// The exported grid's T is the gas's at the grid's time: Σ T h³ over the cells is the blobs'
/// heat then, Σ h0 exp(−c·age) (each blob's normalised Gaussian averaged over the cells sums to
/// 1 inside the box), after one step as after many, newborns included.
#[test]
fn the_exported_temperature_holds_the_blobs_heat_at_its_time() {
    let (temperature, cooling) = (60.0, 0.5);
    // plume_at's emitter, raised to 0.5 m so that no blob's Gaussian reaches past the box.
    let text = format!(
        r#"{{"version": 1, "seed": 3,
            "field": {{"size": [16, 16, 16, 16], "period": [1, 1, 1], "time_period": 2, "amplitude": 0}},
            "emitters": [{{"shape": "disk", "radius": 0.05, "center": [0, 0.5, 0], "rate": 200,
                          "sigma0": 0.06, "mass0": 1, "temperature": {temperature}}}],
            "gas": {{"diffusion": 0.002, "dissipation": 0}},
            "simulation": {{"dt": 0.02}},
            "flow": {{"box": [-0.6, 0, -0.6, 0.6, 2.4, 0.6], "cells": [16, 32, 16],
                      "cooling": {cooling}}}}}"#
    );
    let mut sim = Simulation::new(Scene::from_json(&text).expect("valid scene")).expect("runs");
    let sigma0 = 0.06f64;
    let h0 = temperature * (2.0 * std::f64::consts::PI).powf(1.5) * sigma0.powi(3);
    for steps in [1, 24] {
        sim.run(steps);
        let grid = sim.flow_grid().expect("a flow");
        let t = sim.time();
        let b = sim.blobs();
        let heat: f64 = (0..b.len())
            .map(|i| h0 * (-cooling * (t - b.birth[i])).exp())
            .sum();
        let cell = (grid.bounds[3] - grid.bounds[0]) / grid.cells[0] as f64;
        let held: f64 = grid.temperature.iter().map(|&v| f64::from(v)).sum::<f64>() * cell.powi(3);
        println!("after {steps} more steps, t = {t:.2} s: the grid holds {held:.5} K m³ of the blobs' {heat:.5}");
        assert!(!b.is_empty() && heat > 0.0);
        assert!((held / heat - 1.0).abs() < 1e-4, "{held} against {heat}");
    }
}

/// Every new key is checked, naming its path; a flow too large for memory or time is refused
/// before any work.
#[test]
fn the_flows_keys_are_checked_and_budgeted() {
    let scene = |flow: &str, extra: &str| {
        format!(r#"{{"version": 1, "field": {{"amplitude": 0}}, "flow": {flow}{extra}}}"#)
    };
    let unit = r#""box": [0, 0, 0, 1, 1, 1]"#;
    let refused = [
        (format!("{{{unit}}}"), "flow"),
        (format!(r#"{{{unit}, "cells": [8, 8]}}"#), "flow.cells"),
        (
            format!(r#"{{{unit}, "cells": [4, 8, 8]}}"#),
            "flow.cells[0]",
        ),
        (
            format!(r#"{{{unit}, "cells": [8, 8, 300]}}"#),
            "flow.cells[2]",
        ),
        (
            format!(r#"{{{unit}, "cells": [8, 8, 8.5]}}"#),
            "flow.cells[2]",
        ),
        (format!(r#"{{{unit}, "cells": [8, 8, 16]}}"#), "flow.cells"),
        (
            format!(r#"{{{unit}, "cells": [256, 256, 256]}}"#),
            "flow.cells",
        ),
        (
            r#"{"box": [0, 0, 0, 1, 0, 1], "cells": [8, 8, 8]}"#.into(),
            "flow.box[4]",
        ),
        (
            r#"{"box": [0, 0, 0, 1, 1, 1e9], "cells": [8, 8, 8]}"#.into(),
            "flow.box[5]",
        ),
        (
            format!(r#"{{{unit}, "cells": [8, 8, 8], "viscosity": -1}}"#),
            "flow.viscosity",
        ),
        (
            format!(r#"{{{unit}, "cells": [8, 8, 8], "viscosity": 10}}"#),
            "flow.viscosity",
        ),
        (
            format!(r#"{{{unit}, "cells": [8, 8, 8], "buoyancy": 2}}"#),
            "flow.buoyancy",
        ),
        (
            format!(r#"{{{unit}, "cells": [8, 8, 8], "cooling": -0.1}}"#),
            "flow.cooling",
        ),
        (
            format!(r#"{{{unit}, "cells": [8, 8, 8], "gravity": [0, 1e4, 0]}}"#),
            "flow.gravity[1]",
        ),
        (
            format!(r#"{{{unit}, "cells": [8, 8, 8], "faces": "ajar"}}"#),
            "flow.faces: must be",
        ),
        (
            format!(r#"{{{unit}, "cells": [8, 8, 8], "faces": {{"y": "ajar"}}}}"#),
            "flow.faces.y: must be",
        ),
        (
            format!(r#"{{{unit}, "cells": [8, 8, 8], "faces": {{"w": "open"}}}}"#),
            "flow.faces.w:",
        ),
        (
            format!(r#"{{{unit}, "cells": [8, 8, 8], "faces": {{"x": 1}}}}"#),
            r#"flow.faces.x: must be "open" or "closed" (got 1)"#,
        ),
        (
            format!(r#"{{{unit}, "cells": [8, 8, 8], "swirl": 1}}"#),
            "flow",
        ),
    ];
    for (flow, path) in &refused {
        let e = Scene::from_json(&scene(flow, "")).expect_err(flow);
        assert!(e.to_string().starts_with(path), "{flow}: {e}");
    }
    let small = format!(r#"{{{unit}, "cells": [8, 8, 8]}}"#);
    let hot = r#", "emitters": [{"temperature": 2e4}]"#;
    let e = Scene::from_json(&scene(&small, hot)).expect_err("too hot");
    assert!(e.to_string().starts_with("emitters[0].temperature"), "{e}");
    // Time: 2^19 cells for 30,000 steps is over the run's budget, refused before a step.
    let big = r#"{"box": [0, 0, 0, 2, 2, 0.5], "cells": [128, 128, 32]}"#;
    let sim = Simulation::new(Scene::from_json(&scene(big, "")).expect("valid")).expect("runs");
    let e = sim.budgeted_steps(3e4 / 60.0).expect_err("over the budget");
    assert!(e.to_string().starts_with("flow.cells"), "{e}");
    let e = Scene::from_json(&scene(big, r#", "render": {"time": 600}"#)).expect_err("render.time");
    assert!(e.to_string().starts_with("flow.cells"), "{e}");
    // A disabled flow is kept and does nothing.
    let off = format!(r#"{{{unit}, "cells": [8, 8, 8], "enabled": false}}"#);
    let sim = Simulation::new(Scene::from_json(&scene(&off, "")).expect("valid")).expect("runs");
    assert!(sim.flow().is_none());
    // The faces across each axis: an axis not named is open; the six alike in one word.
    for (faces, closed) in [
        (r#""closed""#, [true; 3]),
        (r#"{"y": "closed"}"#, [false, true, false]),
        (
            r#"{"x": "closed", "y": "open", "z": "closed"}"#,
            [true, false, true],
        ),
    ] {
        let flow = format!(r#"{{{unit}, "cells": [8, 8, 8], "faces": {faces}}}"#);
        let read = Scene::from_json(&scene(&flow, "")).expect(faces);
        assert_eq!(read.flow.expect("a flow").faces.closed(), closed, "{faces}");
    }
}

/// An edit keeps the flow's u_g while its grid and its solid objects' shapes stay: a new
/// colour for the ceiling, or a new object that is not solid, keeps it; a ceiling moved starts
/// the flow again at rest.
#[test]
fn an_edit_keeps_the_flow_unless_its_solids_change() {
    let mut sim = plume_at(40.0, 0.0, 60.0, 0.5, CEILING);
    sim.run(30);
    let energy = |sim: &Simulation| {
        let f = sim.flow().expect("a flow");
        f.flow.u_g.kinetic_energy(&f.flow.grid)
    };
    let before = energy(&sim);
    assert!(before > 0.0);
    let edit = |sim: &mut Simulation, change: &dyn Fn(&mut serde_json::Value)| {
        let mut value = serde_json::to_value(&sim.scene).expect("a scene writes");
        change(&mut value);
        let scene = Scene::from_value(value).expect("a valid edit");
        sim.edit(scene, None).expect("applies");
    };
    edit(&mut sim, &|v| {
        v["render"]["objects"][0]["color"] = serde_json::json!([0.9, 0.2, 0.2])
    });
    assert_eq!(energy(&sim), before, "a new colour keeps u_g");
    edit(&mut sim, &|v| {
        let sphere = serde_json::json!({"type": "sphere", "center": [0.3, 0.5, 0], "radius": 0.1,
            "color": [1, 1, 1]});
        v["render"]["objects"]
            .as_array_mut()
            .expect("a list")
            .push(sphere);
    });
    assert_eq!(
        energy(&sim),
        before,
        "an object that is not solid keeps u_g"
    );
    edit(&mut sim, &|v| {
        v["render"]["objects"][0]["point"] = serde_json::json!([0, 1.2, 0])
    });
    assert_eq!(energy(&sim), 0.0, "a moved ceiling starts the flow at rest");
}
