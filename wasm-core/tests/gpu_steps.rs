//! The GPU stepper's inputs against the core: the frozen wind table, read as the GPU's step
//! shader reads it (quadrilinear on the raw lattice, then the primitives), gives the core's wind;
//! while the GPU advects the centres the core's bookkeeping (births, σ, mass, removal, the cap)
//! is the CPU run's, and every live blob holds its own slot.

use glam::Vec3;
use serde_json::json;
use windfield::frame::gpu_steps::{GpuSteps, BLOB_FLOATS};
use windfield::gas::wind::{
    REPULSOR_KIND, SOURCE_KIND, UNIFORM_KIND, VORTEX_KIND, WIND_TABLE_HEADER, WIND_TABLE_PRIMITIVE,
};
use windfield::{Scene, Simulation};

/// A scene with every primitive kind (one uniform with decay), an emitter of each shape and a
/// small-scale field carried by the wind.
fn every_kind() -> Scene {
    Scene::from_value(json!({
        "version": 1, "seed": 5,
        "field": {"size": [8, 8, 8, 8], "spectrum": {"k_inertial": 2}, "period": [1.5, 2, 2.5],
                  "time_period": 3, "amplitude": 1.2, "carried_by_wind": true},
        "wind": [
            {"type": "uniform", "velocity": [0.1, 0.3, 0]},
            {"type": "uniform", "velocity": [0, 0, 0.2], "position": [0.2, 0.5, 0], "decay": 0.5},
            {"type": "source", "position": [0.3, 0.2, 0.1], "strength": 0.4, "radius": 0.15},
            {"type": "source", "position": [-0.3, 0.8, 0], "strength": -0.2, "decay": 0.7},
            {"type": "vortex", "position": [0, 0.6, 0], "axis": [0.2, 1, 0.1], "strength": 0.6, "radius": 0.1},
            {"type": "repulsor", "radius": 0.2, "strength": 0.3,
             "path": [[0, -1, 0.5, 0], [2, 0.5, 0.6, 0.2], [4, 1, 0.4, 0]]}
        ],
        "emitters": [
            {"shape": "point", "center": [0, 0, 0], "rate": 200, "velocity": [0, 0.4, 0], "velocity_time": 0.3},
            {"shape": "disk", "center": [0.2, 0, 0], "radius": 0.1, "rate": 300, "mass0": 0.5},
            {"shape": "sphere", "center": [-0.2, 0.1, 0], "radius": 0.1, "rate": 250, "albedo": [0.9, 0.5, 0.2]},
            {"shape": "box", "center": [0, 0.2, 0.3], "size": [0.2, 0.1, 0.2], "rate": 150, "emission": [1, 0.5, 0.2]}
        ],
        "gas": {"diffusion": 0.002, "dissipation": 0.4, "min_mass": 0.3, "max_blobs": 600}
    }))
    .unwrap()
}

/// The wind at `x` as the GPU's step shader computes it from `table` and the raw lattice
/// `data` of size `n` (`[nx, ny, nz, nt]`, xyz per point, `[t][z][y][x]`).
fn table_velocity(table: &[f32], data: &[f32], n: [usize; 4], x: Vec3) -> Vec3 {
    let h = |i: usize| Vec3::new(table[i], table[i + 1], table[i + 2]);
    let mut u = h(16);
    if table[0] > 0.0 {
        let (i0, i1, f) = (table[1] as usize, table[2] as usize, table[3]);
        let q = (x - h(4)) * h(8);
        let fl = q.floor();
        let t = q - fl;
        let at = |ix: i64, iy: i64, iz: i64, it: usize| {
            let (cx, cy, cz) = (
                ix.rem_euclid(n[0] as i64) as usize,
                iy.rem_euclid(n[1] as i64) as usize,
                iz.rem_euclid(n[2] as i64) as usize,
            );
            let k = 3 * (((it * n[2] + cz) * n[1] + cy) * n[0] + cx);
            Vec3::new(data[k], data[k + 1], data[k + 2])
        };
        let corner = |dx: i64, dy: i64, dz: i64| {
            let (ix, iy, iz) = (fl.x as i64 + dx, fl.y as i64 + dy, fl.z as i64 + dz);
            let a = at(ix, iy, iz, i0);
            (a + (at(ix, iy, iz, i1) - a) * f) * h(12)
        };
        let along_x = |dy, dz| corner(0, dy, dz).lerp(corner(1, dy, dz), t.x);
        let lo = along_x(0, 0).lerp(along_x(1, 0), t.y);
        let hi = along_x(0, 1).lerp(along_x(1, 1), t.y);
        u += lo.lerp(hi, t.z);
    }
    for k in 0..table[19] as usize {
        let p = &table[WIND_TABLE_HEADER + k * WIND_TABLE_PRIMITIVE..];
        let v = |i: usize| Vec3::new(p[i], p[i + 1], p[i + 2]);
        let (kind, inv_decay, a, b) = (p[0], p[1], p[2], p[3]);
        let r = x - v(8);
        let w = if kind == UNIFORM_KIND {
            v(8)
        } else if kind == SOURCE_KIND {
            let d2 = r.length_squared() + b;
            r * (a / (d2 * d2.sqrt()))
        } else if kind == VORTEX_KIND {
            let c = v(12).cross(r);
            c * (a / (c.length_squared() + b))
        } else {
            assert_eq!(kind, REPULSOR_KIND);
            let (vel, radius, s) = (v(12), a, b);
            let d = r.length();
            let n = if d > 1e-6 { r / d } else { Vec3::Y };
            if d < radius {
                vel + n * s
            } else {
                let q = radius / d;
                (n * (3.0 * vel.dot(n)) - vel) * (0.5 * q * q * q) + n * (s * q * q)
            }
        };
        u += if inv_decay > 0.0 {
            w * (-(x - v(4)).length() * inv_decay).exp()
        } else {
            w
        };
    }
    u
}

#[test]
fn the_wind_table_read_as_the_gpu_reads_it_is_the_cores_wind() {
    let mut sim = Simulation::new(every_kind()).unwrap();
    sim.hand_centres_to_gpu().unwrap();
    let field = sim.field().unwrap().clone();
    let mut checked = 0;
    for _ in 0..40 {
        let steps = GpuSteps::run(&mut sim, 3);
        // The last step's two frames: its start and its middle.
        for (k, frame) in sim.wind_frames().iter().enumerate() {
            let at = steps.wind_offsets[steps.wind_offsets.len() - 2 + k] as usize;
            let table = &steps.wind[at..];
            for j in 0..25 {
                let x = Vec3::new(
                    -1.3 + 0.11 * j as f32,
                    -0.4 + 0.07 * j as f32,
                    0.9 - 0.09 * j as f32,
                );
                let want = frame.velocity(x);
                let got = table_velocity(table, &field.data, field.lattice.size, x);
                assert!(
                    (got - want).length() <= 1e-5 * want.length().max(1.0),
                    "t = {}, x = {x}: table {got}, core {want}",
                    frame.time
                );
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 2000);
}

#[test]
fn while_the_gpu_advects_the_centres_the_rest_of_the_gas_is_the_cpu_runs() {
    let mut cpu = Simulation::new(every_kind()).unwrap();
    let mut gpu = Simulation::new(every_kind()).unwrap();
    cpu.run(30);
    gpu.run(30);
    gpu.hand_centres_to_gpu().unwrap();
    let mut emitted = 0;
    let mut freed = 0;
    for _ in 0..100 {
        cpu.run(2);
        let steps = GpuSteps::run(&mut gpu, 2);
        assert_eq!(steps.births.len(), BLOB_FLOATS * steps.birth_slots.len());
        emitted += steps.birth_slots.len();
        freed += steps.freed.len();
        let (c, g) = (&cpu.gas.blobs, &gpu.gas.blobs);
        assert_eq!(c.len(), g.len());
        assert_eq!(c.mass, g.mass);
        assert_eq!(c.sigma, g.sigma);
        assert_eq!(c.birth, g.birth);
        assert_eq!(steps.count as usize, g.len());
        // Every live blob has a slot of its own, below the high-water mark.
        let mut slots = g.slot.clone();
        slots.sort_unstable();
        slots.dedup();
        assert_eq!(slots.len(), g.len());
        assert!(slots.iter().all(|&s| s < steps.high_water));
    }
    // The cap (600) and min_mass both removed blobs; the slots cycled.
    assert!(
        emitted > 1000 && freed > 1000,
        "{emitted} born, {freed} freed"
    );
    assert!(gpu.slot_high_water() < 700);
    // The centres stayed where the GPU was to move them: at birth, not advected here.
    assert_ne!(cpu.gas.blobs.position, gpu.gas.blobs.position);
}

#[test]
fn the_centres_come_back_by_slot() {
    let mut sim = Simulation::new(every_kind()).unwrap();
    sim.run(20);
    let before = sim.gas.blobs.position.clone();
    sim.hand_centres_to_gpu().unwrap();
    let records = windfield::frame::gpu_steps::gas_by_slot(&sim);
    // The GPU's state after a "step": each slot's record holds its blob's centre first; here
    // the step turns the axes (x, y, z) → (z, x, y), exactly.
    let centres: Vec<f32> = records
        .chunks_exact(BLOB_FLOATS)
        .flat_map(|r| [r[2], r[0], r[1]])
        .collect();
    sim.take_centres(&centres, false);
    assert!(!sim.centres_on_gpu());
    for (a, b) in sim.gas.blobs.position.chunks(3).zip(before.chunks(3)) {
        assert_eq!(a, [b[2], b[0], b[1]]);
    }
}

#[test]
fn a_scene_that_splits_is_stepped_here() {
    let mut s = every_kind();
    s.gas.split_sigma = Some(0.05);
    let mut sim = Simulation::new(s).unwrap();
    let e = sim.hand_centres_to_gpu().unwrap_err();
    assert_eq!(e.path, "gas.split_sigma");
    assert!(!sim.centres_on_gpu());
}
