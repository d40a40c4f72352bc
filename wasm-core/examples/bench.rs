//! Native benchmarks; one JSON object per line: `{"name": ..., "value": ..., "unit": ...}`.
//! Run through `npm run bench` (which adds the WASM figures) or
//! `cargo run --release --example bench`.

use glam::Vec3;
use std::time::Instant;
use windfield::field::{FieldParams, TurbulentField};
use windfield::frame::PackedFrame;
use windfield::gas::Blob;
use windfield::render::{RenderOptions, Renderer};
use windfield::wind::flow::{Faces, Flow, Grid, MacField};
use windfield::{Scene, Simulation};

/// The blob-step benchmark scene: a 32^4 field plus uniform, vortex and source primitives.
pub const BLOB_STEP_SCENE: &str = include_str!("blob-step-scene.json");

/// The coarse-grid flow's step (`wind::flow`) on `n`³ cells of an open 1.6 m box around one
/// solid sphere in a 1 m/s wind: advection, viscosity, the projection (its CG iterations
/// printed beside).
fn flow_step(n: usize, runs: usize) {
    let h = 1.6 / n as f32;
    let grid = Grid::new([0.0; 3], [n; 3], h);
    let mut flow = Flow::new(grid.clone(), Faces::OPEN);
    flow.solids.add_sphere(&grid, [0.8; 3], 0.3, [0.0; 3]);
    let u_p = MacField::from_fn(&grid, |_| [1.0, 0.0, 0.0]);
    let mut iterations = 0;
    let ms = median_ms(runs, || {
        iterations = flow.step(0.02, &u_p, None, &[]).iterations
    });
    eprintln!("flow step at {n}³: {iterations} CG iterations");
    emit(&format!("flow_step_{n}_native_ms"), ms, "ms");
}

/// `n` blobs spread over a 4 m box by a fixed low-discrepancy sequence (the same in
/// `scripts/bench.mjs`).
fn seed_blobs(sim: &mut Simulation, n: usize) {
    for i in 0..n {
        let f = |k: f32| ((i as f32 + 0.5) * k).fract() * 4.0 - 2.0;
        sim.gas.blobs.push(
            &Blob::new(
                Vec3::new(f(0.754_877_7), f(0.569_840_3) + 1.0, f(0.430_159_7)),
                0.03,
                1.0,
                0.0,
            ),
            0.03,
            1.0,
        );
    }
}

/// Median wall time in milliseconds of `runs` calls after one warm-up call.
fn median_ms(runs: usize, mut f: impl FnMut()) -> f64 {
    f();
    let mut t: Vec<f64> = (0..runs)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[runs / 2]
}

fn emit(name: &str, value: f64, unit: &str) {
    println!(
        "{}",
        serde_json::json!({ "name": name, "value": (value * 1000.0).round() / 1000.0, "unit": unit })
    );
}

/// Peak resident set size of this process in MiB (Linux), if known.
fn peak_rss_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

fn main() {
    // `cargo run --release --example bench -- solids`: the solid objects' figures alone.
    if std::env::args().any(|a| a == "solids") {
        solid_objects();
        return;
    }
    // `cargo run --release --example bench -- flow [N ...]`: the flow's step alone, at 32³ and
    // 64³ or at each N³ given.
    let args: Vec<String> = std::env::args().collect();
    if let Some(at) = args.iter().position(|a| a == "flow") {
        let sizes: Vec<usize> = args[at + 1..]
            .iter()
            .filter_map(|a| a.parse().ok())
            .collect();
        let sizes = if sizes.is_empty() {
            vec![32, 64]
        } else {
            sizes
        };
        for n in sizes {
            flow_step(n, if n <= 32 { 7 } else { 3 });
        }
        return;
    }
    field_generate(32, 7);
    let mut sim =
        Simulation::new(Scene::from_json(BLOB_STEP_SCENE).expect("valid")).expect("valid");
    seed_blobs(&mut sim, 200_000);
    let ms = median_ms(7, || sim.step());
    emit("blob_step_200k_native_ms", ms, "ms");
    worker_plume();
    solid_objects();
    field_generate_with_potential(32, 5);
    flow_step(32, 7);
    flow_step(64, 3);

    // The reference renderer: a simulated plume of 10,000 blobs, one point light, shadows.
    let plume = Scene::from_json(include_str!("render-plume-scene.json")).expect("valid");
    let mut sim = Simulation::new(plume).expect("valid");
    sim.run(sim.steps_for(10.0));
    let list = sim.blob_list();
    assert_eq!(list.blobs.len(), 10_000);
    let render = |size: Option<(u32, u32)>, use_tree: bool| {
        let options = RenderOptions {
            use_tree,
            ..Default::default()
        };
        std::hint::black_box(Renderer::new(&list, size, options).expect("valid").render());
    };
    emit(
        "render_reference_640x480_10k_ms",
        median_ms(3, || render(None, true)),
        "ms",
    );
    let small = Some((64, 48));
    let tree_ms = median_ms(9, || render(small, true));
    let brute_ms = median_ms(3, || render(small, false));
    eprintln!("tree {tree_ms:.1} ms, brute force {brute_ms:.1} ms");
    emit("render_reference_tree_speedup", brute_ms / tree_ms, "ratio");

    if let Some(mib) = peak_rss_mib() {
        emit("native_peak_rss_mib", mib, "MiB");
    }

    // The largest lattice, 2^24 points, last: its 192 MiB field would dominate the peak above.
    field_generate(64, 5);
    if let Some(mib) = peak_rss_mib() {
        emit("field_64_native_peak_rss_mib", mib, "MiB");
    }
}

/// The engine worker's work per frame at 100,000 blobs (as `scripts/bench.mjs` measures it in
/// WASM): the dense plume emitting 20,000 blobs a second for 5 s up to its cap, then one fixed
/// step and the frame's packing, medians of 31 (step and pack together, and the pack alone).
fn worker_plume() {
    let mut scene =
        Scene::from_json(include_str!("../../tests/fixtures/dense-plume.json")).expect("valid");
    scene.emitters[0].rate = 20_000.0;
    scene.gas.max_blobs = 100_000;
    let medium = Vec3::from_array(scene.render.medium.albedo);
    let mut sim = Simulation::new(scene).expect("valid");
    sim.run(sim.steps_for(5.0));
    let pack = |sim: &Simulation| {
        std::hint::black_box(PackedFrame::of_blobs(&sim.blobs(), medium));
    };
    let step_ms = median_ms(31, || sim.step());
    let pack_ms = median_ms(31, || pack(&sim));
    let k = (sim.blobs().len() + 500) / 1000;
    emit(
        &format!("worker_step_{k}k_native_ms"),
        step_ms + pack_ms,
        "ms",
    );
    emit(&format!("worker_pack_{k}k_native_ms"), pack_ms, "ms");
}

/// `count` solid spheres of radius 8 cm over the blob-step benchmark's 4 m box (another
/// low-discrepancy sequence), as scene objects.
pub fn solid_spheres(count: usize) -> Vec<windfield::scene::blob_list::Object> {
    (0..count)
        .map(|i| {
            let f = |k: f32| ((i as f32 + 0.5) * k).fract() * 3.6 - 1.8;
            windfield::scene::blob_list::Object::Sphere {
                center: [f(0.618_034), f(0.414_213_6) + 1.0, f(0.732_050_8)],
                radius: 0.08,
                color: [0.5; 3],
                solid: true,
            }
        })
        .collect()
}

/// The median wall time (ms) of one step of each of `sims` over 7 rounds, each round a step of
/// every one in turn (after a warm-up round), so a machine's changing load falls on all alike.
fn interleaved_medians<const N: usize>(sims: &mut [Simulation; N]) -> [f64; N] {
    sims.iter_mut().for_each(Simulation::step);
    let mut times = [[0.0; 7]; N];
    for round in 0..7 {
        for (sim, t) in sims.iter_mut().zip(&mut times) {
            let s = Instant::now();
            sim.step();
            t[round] = s.elapsed().as_secs_f64() * 1e3;
        }
    }
    times.map(|mut t| {
        t.sort_by(f64::total_cmp);
        t[3]
    })
}

/// `count` solid spheres of radius 1.2 cm through the dense plume's region (x, z within
/// 0.3 m of its axis, 0.15 to 1.2 m up; another low-discrepancy sequence), as scene objects.
pub fn plume_spheres(count: usize) -> Vec<windfield::scene::blob_list::Object> {
    (0..count)
        .map(|i| {
            let f = |k: f32| ((i as f32 + 0.5) * k).fract();
            windfield::scene::blob_list::Object::Sphere {
                center: [
                    0.6 * f(0.618_034) - 0.3,
                    1.05 * f(0.414_213_6) + 0.15,
                    0.6 * f(0.732_050_8) - 0.3,
                ],
                radius: 0.012,
                color: [0.5; 3],
                solid: true,
            }
        })
        .collect()
}

/// `{scene}_100k_solids_{count}_native_ms` for each of `sims` (the scene among `counts` solid
/// spheres, medians of 7 interleaved rounds), then the most solids' step over none's.
fn emit_solid_steps(scene: &str, counts: [usize; 3], sims: &mut [Simulation; 3]) {
    let ms = interleaved_medians(sims);
    for (count, ms) in counts.iter().zip(ms) {
        emit(&format!("{scene}_100k_solids_{count}_native_ms"), ms, "ms");
    }
    let most = counts[2];
    emit(
        &format!("{scene}_{most}_solids_over_none"),
        ms[2] / ms[0],
        "ratio",
    );
}

/// The step among 0, 16 and 256 solid spheres, two ways, medians of 7 interleaved rounds:
///
/// - the blob-step scene's 100,000 blobs spread through its 4 m box in no order, among spheres
///   of radius 8 cm through its 3.6 m box (each a doublet in the uniform wind, its layer
///   0.1 m);
/// - the worker's dense plume at 100,000 blobs (as [`worker_plume`], the blobs in the order
///   they were born), among spheres of radius 1.2 cm through the plume (layer 2 cm).
///
/// Then what finding the solids costs: the nearest solid per blob with the grid and with every
/// solid visited, and one signed distance per blob and solid; the wind among the 256 spheres of
/// the blob-step scene per point, against the wind without them; and the grid's size.
fn solid_objects() {
    let counts = [0, 16, 256];
    let mut sims = counts.map(|count| {
        let mut scene = Scene::from_json(BLOB_STEP_SCENE).expect("valid");
        scene.render.objects = solid_spheres(count);
        let mut sim = Simulation::new(scene).expect("valid");
        seed_blobs(&mut sim, 100_000);
        // The first step puts the blobs seeded inside a sphere out.
        sim.step();
        sim
    });
    emit_solid_steps("blob_step", counts, &mut sims);
    let mut sims = counts.map(|count| {
        let mut scene =
            Scene::from_json(include_str!("../../tests/fixtures/dense-plume.json")).expect("valid");
        scene.emitters[0].rate = 20_000.0;
        scene.gas.max_blobs = 100_000;
        scene.field.boundary_width = 0.02;
        scene.render.objects = plume_spheres(count);
        let mut sim = Simulation::new(scene).expect("valid");
        sim.run(sim.steps_for(5.0));
        sim
    });
    emit_solid_steps("worker_step", counts, &mut sims);
    let mut scene = Scene::from_json(BLOB_STEP_SCENE).expect("valid");
    let plain = Simulation::new(scene.clone()).expect("valid");
    scene.render.objects = solid_spheres(256);
    let sim = Simulation::new(scene).expect("valid");
    let walls = sim.wind.walls().expect("solids");
    let solids = &walls.solids;
    let points: Vec<glam::Vec3A> = (0..100_000)
        .map(|i| {
            let f = |k: f32| ((i as f32 + 0.5) * k).fract() * 4.0 - 2.0;
            glam::Vec3A::new(f(0.754_877_7), f(0.569_840_3) + 1.0, f(0.430_159_7))
        })
        .collect();
    let per_point = |runs: usize, f: &dyn Fn(glam::Vec3A)| {
        median_ms(runs, || points.iter().for_each(|&x| f(x))) * 1e6 / points.len() as f64
    };
    emit(
        "solid_nearest_256_per_blob_ns",
        per_point(7, &|x| {
            std::hint::black_box(solids.nearest(x));
        }),
        "ns",
    );
    let every = solids.every_solid_visited();
    emit(
        "solid_nearest_256_every_solid_per_blob_ns",
        per_point(3, &|x| {
            std::hint::black_box(every.nearest(x));
        }),
        "ns",
    );
    emit(
        "solid_distance_per_blob_and_solid_ns",
        per_point(3, &|x| {
            for b in &solids.bodies {
                std::hint::black_box(b.distance(x));
            }
        }) / solids.len() as f64,
        "ns",
    );
    let (with, without) = (sim.wind.frame(0.0), plain.wind.frame(0.0));
    emit(
        "wind_256_solids_per_point_ns",
        per_point(7, &|x| {
            std::hint::black_box(with.velocity_a(x));
        }),
        "ns",
    );
    emit(
        "wind_no_solids_per_point_ns",
        per_point(7, &|x| {
            std::hint::black_box(without.velocity_a(x));
        }),
        "ns",
    );
    if let Some((cells, entries)) = solids.grid_size() {
        emit("solid_grid_256_cells", cells as f64, "cells");
        emit("solid_grid_256_entries", entries as f64, "entries");
    }
    preset_step(
        "bridge_smoke",
        include_str!("../../public/scenes/bridge-smoke.json"),
    );
    preset_step(
        "dust_swirl",
        include_str!("../../public/scenes/dust-swirl.json"),
    );
}

/// `{name}_step_{k}k_native_ms`: one step of a preset whose wind goes round its solids, 5 s
/// in (k thousand blobs then), the median of 7.
fn preset_step(name: &str, json: &str) {
    let mut sim = Simulation::new(Scene::from_json(json).expect("valid")).expect("valid");
    sim.run(sim.steps_for(5.0));
    let ms = median_ms(7, || sim.step());
    let k = (sim.blobs().len() + 500) / 1000;
    emit(&format!("{name}_step_{k}k_native_ms"), ms, "ms");
}

/// The field with its vector potential (a scene with solid objects), against the field alone.
fn field_generate_with_potential(n: usize, runs: usize) {
    let params = FieldParams {
        size: [n; 4],
        ..FieldParams::default()
    };
    let ms = median_ms(runs, || {
        std::hint::black_box(TurbulentField::generate_with_potential(&params).expect("valid"));
    });
    emit(
        &format!("field_generate_{n}x{n}x{n}x{n}_with_potential_native_ms"),
        ms,
        "ms",
    );
}

/// Median time of the paper's field (ε = 1, k_inertial = 4, σ = 1, seed 1) on an n^4 lattice.
fn field_generate(n: usize, runs: usize) {
    let params = FieldParams {
        size: [n; 4],
        ..FieldParams::default()
    };
    let ms = median_ms(runs, || {
        std::hint::black_box(TurbulentField::generate(&params).expect("valid"));
    });
    emit(
        &format!("field_generate_{n}x{n}x{n}x{n}_native_ms"),
        ms,
        "ms",
    );
}
