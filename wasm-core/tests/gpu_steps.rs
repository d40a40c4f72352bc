//! The GPU stepper's inputs against the core: the frozen wind table, read as the GPU's step
//! shader reads it (quadrilinear on the raw lattice, then the primitives), gives the core's wind;
//! while the GPU advects the centres the core's bookkeeping (births, σ, mass, removal, the cap)
//! is the CPU run's, and every live blob holds its own slot.

use glam::Vec3;
use serde_json::json;
use windfield::frame::gpu_steps::{GpuSteps, BLOB_FLOATS};
use windfield::wind::wind_table::{
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
    sim.take_centres(&centres, false, None);
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

/// A hot gas under a solid sphere in a crosswind, its flow on 8 × 16 × 8 cells, the small
/// scales carried.
fn hot_past_sphere() -> Scene {
    Scene::from_value(json!({
        "version": 1, "seed": 3,
        "field": {"size": [8, 8, 8, 8], "spectrum": {"k_inertial": 2}, "period": [2, 2, 2],
                  "time_period": 4, "amplitude": 0.5, "carried": true, "carry_time": 0.4},
        "wind": [{"type": "uniform", "velocity": [0.15, 0.05, 0]}],
        "emitters": [{"shape": "disk", "center": [0, 0.05, 0], "normal": [0, 1, 0], "radius": 0.08,
                      "rate": 120, "sigma0": 0.03, "mass0": 0.004, "temperature": 300}],
        "gas": {"diffusion": 0.0015, "dissipation": 0.15, "max_blobs": 3000, "min_mass": 0.0001},
        "flow": {"box": [-0.4, -0.1, -0.4, 0.4, 1.5, 0.4], "cells": [8, 16, 8]},
        "render": {"objects": [{"type": "sphere", "center": [0.08, 0.6, 0.02], "radius": 0.17,
                                "color": [1, 1, 1], "solid": true}]}
    }))
    .unwrap()
}

#[test]
fn a_flow_goes_to_the_gpu_with_the_gas_and_comes_back() {
    let mut sim = Simulation::new(hot_past_sphere()).unwrap();
    sim.run(20);
    let before = sim.flow_grid().unwrap();
    sim.hand_centres_to_gpu().unwrap();
    assert!(sim.gas.newborns_elsewhere);
    let steps = GpuSteps::run(&mut sim, 5);
    // The flow here waits for the GPU's: not stepped while the GPU holds the gas.
    assert_eq!(sim.flow_grid().unwrap().velocity, before.velocity);
    // Newborns stay at their birth places on the emitter's disk, their records holding their
    // heat and, for their offsets, the phases' ages at the step's end.
    let ages = sim.wind.phases().unwrap().ages(sim.time());
    let births: Vec<&[f32]> = steps.births.chunks_exact(BLOB_FLOATS).collect();
    assert!(births.len() > 5, "{} births", births.len());
    let h0 = 300.0 * (2.0 * std::f64::consts::PI).powf(1.5) * 0.03f64.powi(3);
    for r in births.iter().rev().take(2) {
        assert!((r[1] - 0.05).abs() < 1e-6, "born at y = {}", r[1]);
        assert!(r[0].hypot(r[2]) <= 0.08 + 1e-6);
        assert!((r[7] as f64 - h0).abs() < 1e-6 * h0, "h0 {}", r[7]);
        assert_eq!(&r[20..22], &[ages[0] as f32, ages[1] as f32]);
        assert_eq!(&r[22..28], &[0.0; 6]);
    }
    // The GPU's flow comes back: a face array of the wrong size is refused, naming it.
    let faces = |a: usize| {
        let n = [9 * 16 * 8, 8 * 17 * 8, 8 * 16 * 9][a];
        (0..n).map(|i| 0.01 * (i % 7) as f32).collect::<Vec<f32>>()
    };
    let (u, v, w) = (faces(0), faces(1), faces(2));
    let e = sim.take_flow([&u, &v[1..], &w]).unwrap_err();
    assert_eq!(e.path, "v");
    sim.take_flow([&u, &v, &w]).unwrap();
    let slots = sim.slot_high_water() as usize;
    let centres = vec![0.0f32; 3 * slots];
    // The GPU's carried offsets come back by slot too.
    let offsets: Vec<f32> = (0..6 * slots).map(|i| 1e-3 * i as f32).collect();
    let slot_of: Vec<u32> = sim.gas.blobs.slot.clone();
    sim.take_centres(&centres, false, Some(&offsets));
    assert!(!sim.gas.newborns_elsewhere);
    for (i, &s) in slot_of.iter().enumerate() {
        let s = 6 * s as usize;
        assert_eq!(&sim.gas.blobs.carried[6 * i..6 * i + 6], &offsets[s..s + 6]);
    }
    let grid = sim.flow_grid().unwrap();
    // The cells' velocity is the mean of the faces handed back.
    assert!((grid.velocity[0] - 0.5 * (u[0] + u[1])).abs() < 1e-7);
    assert_eq!(grid.time, sim.time());
    // Stepped here again from the GPU's flow.
    sim.run(1);
    assert_ne!(sim.flow_grid().unwrap().velocity, grid.velocity);
}

#[test]
fn a_scene_without_a_flow_has_none_to_take() {
    let mut sim = Simulation::new(every_kind()).unwrap();
    sim.hand_centres_to_gpu().unwrap();
    assert!(!sim.gas.newborns_elsewhere);
    let e = sim.take_flow([&[], &[], &[]]).unwrap_err();
    assert_eq!(e.path, "flow");
}

/// The scene of every kind with solid objects (a sphere, a plane, a cylinder; the uniform wind's
/// doublets, the primitives' mirror images in the plane, the vortex turned by the ramped curl)
/// and the small scales carried by the large ones.
fn with_solids() -> Scene {
    let mut s = every_kind();
    s.field.carried = true;
    s.field.carry_time = Some(0.3);
    s.field.boundary_width = 0.15;
    // The vortex lies along the plane (so it is mirrored in it).
    if let windfield::scene::scene_format::Primitive::Vortex { axis, .. } = &mut s.wind[4] {
        *axis = [1.0, 0.0, 0.2];
    }
    s.render.objects = serde_json::from_value(json!([
        {"type": "plane", "point": [0, -0.3, 0], "normal": [0, 1, 0.1], "color": [1, 1, 1], "solid": true},
        {"type": "sphere", "center": [0.5, 0.9, 0.2], "radius": 0.25, "color": [1, 1, 1], "solid": true},
        {"type": "cylinder", "base": [-0.6, 0.3, -0.2], "axis": [0.2, 1, 0], "radius": 0.2, "height": 0.5,
         "color": [1, 1, 1], "solid": true}
    ]))
    .unwrap();
    s
}

/// The GPU's reading of a wind table with solids and carried offsets, and of the solids' grid:
/// `web/src/stepper/wind-glsl.js` (`windParts`, `pushOut`), function by function, in Rust.
mod table {
    use glam::Vec3;
    use windfield::wind::solid_grid::SOLID_GRID_HEADER;
    use windfield::wind::wall_set::EDGE_STEPS;
    use windfield::wind::walls::{
        CYLINDER_ZONE_INNER, CYLINDER_ZONE_OUTER, SPHERE_ZONE_INNER, SPHERE_ZONE_OUTER,
    };
    use windfield::wind::wind_table::{CYLINDER_SOLID_KIND, PLANE_SOLID_KIND, SPHERE_SOLID_KIND};
    use windfield::wind::wind_table::{
        VORTEX_KIND, WIND_TABLE_HEADER, WIND_TABLE_PRIMITIVE, WIND_TABLE_SOLID,
    };

    pub struct Table<'a> {
        pub t: &'a [f32],
        /// The solids' grid (`GpuSteps::solid_grid`).
        pub g: &'a [f32],
        pub u: &'a [f32],
        pub psi: &'a [f32],
        pub n: [usize; 4],
    }

    fn v(a: &[f32], i: usize) -> Vec3 {
        Vec3::new(a[i], a[i + 1], a[i + 2])
    }

    impl Table<'_> {
        fn texel(&self, i: usize) -> [f32; 4] {
            [
                self.t[4 * i],
                self.t[4 * i + 1],
                self.t[4 * i + 2],
                self.t[4 * i + 3],
            ]
        }
        fn xyz(&self, i: usize) -> Vec3 {
            v(self.t, 4 * i)
        }
        fn prim(&self, j: usize) -> usize {
            WIND_TABLE_HEADER / 4 + WIND_TABLE_PRIMITIVE / 4 * j
        }
        fn solid_at(&self, j: usize) -> usize {
            self.prim(self.texel(4)[3] as usize) + WIND_TABLE_SOLID / 4 * j
        }

        fn grid_texel(&self, i: usize) -> [f32; 4] {
            std::array::from_fn(|c| self.g[4 * i + c])
        }
        fn member(&self, k: usize) -> usize {
            let t = self.grid_texel(SOLID_GRID_HEADER / 4 + self.grid_texel(0)[3] as usize + k / 4);
            t[k % 4] as usize
        }
        fn planes(&self) -> usize {
            self.grid_texel(1)[3] as usize
        }
        /// `cellLists`: bounds of the layers, spheres and other solids of x's cell.
        fn cell_lists(&self, x: Vec3) -> [usize; 4] {
            let head = self.grid_texel(0);
            let dims = v(self.g, 8);
            let q = (x - v(self.g, 0)) * v(self.g, 4);
            if head[3] == 0.0 || !(q.cmpge(Vec3::ZERO).all() && q.cmplt(dims).all()) {
                return [0; 4];
            }
            let (c, n) = (q.as_ivec3(), dims.as_ivec3());
            let cell = (c.z * n.y + c.y) * n.x + c.x;
            self.grid_texel(SOLID_GRID_HEADER / 4 + cell as usize)
                .map(|b| b as usize)
        }
        /// `layerOrPlane` for every visit: the cell's layers list, then the planes.
        fn layers_and_planes(&self, cell: [usize; 4]) -> Vec<usize> {
            (cell[0]..cell[1])
                .chain(0..self.planes())
                .map(|k| self.member(k))
                .collect()
        }

        fn lattice(&self, data: &[f32], x: Vec3, scale: Vec3) -> Vec3 {
            let s = self.texel(0);
            let (i0, i1, f) = (s[1] as usize, s[2] as usize, s[3]);
            let q = (x - self.xyz(1)) * self.xyz(2);
            let fl = q.floor();
            let t = q - fl;
            let n = self.n;
            let at = |ix: i64, iy: i64, iz: i64, it: usize| {
                let (cx, cy, cz) = (
                    ix.rem_euclid(n[0] as i64) as usize,
                    iy.rem_euclid(n[1] as i64) as usize,
                    iz.rem_euclid(n[2] as i64) as usize,
                );
                v(data, 3 * (((it * n[2] + cz) * n[1] + cy) * n[0] + cx))
            };
            let corner = |dx: i64, dy: i64, dz: i64| {
                let (ix, iy, iz) = (fl.x as i64 + dx, fl.y as i64 + dy, fl.z as i64 + dz);
                let a = at(ix, iy, iz, i0);
                (a + (at(ix, iy, iz, i1) - a) * f) * scale
            };
            let along_x = |dy, dz| corner(0, dy, dz).lerp(corner(1, dy, dz), t.x);
            let lo = along_x(0, 0).lerp(along_x(1, 0), t.y);
            let hi = along_x(0, 1).lerp(along_x(1, 1), t.y);
            lo.lerp(hi, t.z)
        }

        fn blended(&self, data: &[f32], x: Vec3, scale: Vec3, o: [Vec3; 2]) -> Vec3 {
            let w = self.texel(7);
            if self.texel(5)[3] == 0.0 {
                return self.lattice(data, x, scale);
            }
            let n = Vec3::new(self.n[0] as f32, self.n[1] as f32, self.n[2] as f32);
            let shift = n * 0.5 / self.xyz(2);
            let mut u = Vec3::ZERO;
            if w[0] != 0.0 {
                u += self.lattice(data, x + o[0], scale) * w[0];
            }
            if w[1] != 0.0 {
                u += self.lattice(data, x + o[1] + shift, scale) * w[1];
            }
            u
        }

        fn small(&self, x: Vec3, o: [Vec3; 2]) -> Vec3 {
            if self.texel(0)[0] < 0.5 {
                return Vec3::ZERO;
            }
            self.blended(self.u, x, self.xyz(3), o)
        }

        fn primitive(&self, j: usize, x: Vec3) -> Vec3 {
            // As `primitiveWind` (and the first table test's `table_velocity`).
            let at = self.prim(j);
            let [kind, inv_decay, a, b] = self.texel(at);
            let origin = self.xyz(at + 1);
            let p = self.xyz(at + 2);
            let q = self.xyz(at + 3);
            let r = x - p;
            let u = if kind == 1.0 {
                let d2 = r.length_squared() + b;
                r * (a / (d2 * d2.sqrt()))
            } else if kind == 2.0 {
                let c = q.cross(r);
                c * (a / (c.length_squared() + b))
            } else if kind == 3.0 {
                let d = r.length();
                let n = if d > 1e-6 { r / d } else { Vec3::Y };
                if d < a {
                    q + n * b
                } else {
                    let s = a / d;
                    (n * (3.0 * q.dot(n)) - q) * (0.5 * s * s * s) + n * (b * s * s)
                }
            } else {
                p
            };
            if inv_decay > 0.0 {
                u * (-(x - origin).length() * inv_decay).exp()
            } else {
                u
            }
        }

        fn ramp(s: f32) -> f32 {
            let s = s.clamp(-1.0, 1.0);
            let s2 = s * s;
            s * (15.0 + s2 * (-10.0 + 3.0 * s2)) * 0.125
        }

        fn taper(s: f32) -> (f32, f32) {
            if s <= 0.0 {
                return (1.0, 0.0);
            }
            if s >= 1.0 {
                return (0.0, 0.0);
            }
            let s2 = s * s;
            (
                1.0 - s2 * s * (10.0 + s * (-15.0 + 6.0 * s)),
                -30.0 * s2 * (1.0 - s) * (1.0 - s),
            )
        }

        fn perpendicular(a: Vec3) -> Vec3 {
            let other = if a.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
            a.cross(other).normalize()
        }

        /// (normal, distance) of solid j at x, rims rounded by `edge`.
        pub fn distance(&self, j: usize, x: Vec3, edge: f32) -> (Vec3, f32) {
            let at = self.solid_at(j);
            let kind = self.texel(at)[0];
            let (a, radius) = (self.xyz(at + 1), self.texel(at + 1)[3]);
            let (b, height) = (self.xyz(at + 2), self.texel(at + 2)[3]);
            if kind == SPHERE_SOLID_KIND {
                let r = x - a;
                let len = r.length();
                return (if len > 1e-12 { r / len } else { Vec3::Y }, len - radius);
            }
            if kind == PLANE_SOLID_KIND {
                return (b, (x - a).dot(b));
            }
            assert_eq!(kind, CYLINDER_SOLID_KIND);
            let r = x - a;
            let s = r.dot(b);
            let radial = r - b * s;
            let rho = radial.length();
            let out = if rho > 1e-12 {
                radial / rho
            } else {
                Self::perpendicular(b)
            };
            if edge <= 0.0 {
                let dr = rho - radius;
                let (cap, ds) = if s > 0.5 * height {
                    (b, s - height)
                } else {
                    (-b, -s)
                };
                if dr > 0.0 && ds > 0.0 {
                    let d = (dr * dr + ds * ds).sqrt();
                    return ((out * dr + cap * ds) / d, d);
                }
                if dr > 0.0 {
                    return (out, dr);
                }
                if ds > 0.0 {
                    return (cap, ds);
                }
                return if dr > ds { (out, dr) } else { (cap, ds) };
            }
            let half = 0.5 * height;
            let cap = if s > half { b } else { -b };
            let e = edge.min(radius).min(half);
            let (qx, qy) = (rho - (radius - e), (s - half).abs() - (half - e));
            if qx > 0.0 && qy > 0.0 {
                let q = (qx * qx + qy * qy).sqrt();
                return ((out * qx + cap * qy) / q, q - e);
            }
            if qx > qy {
                (out, qx - e)
            } else {
                (cap, qy - e)
            }
        }

        fn edge(&self, j: usize) -> f32 {
            let s0 = self.texel(self.solid_at(j));
            if s0[0] == CYLINDER_SOLID_KIND {
                EDGE_STEPS * s0[1]
            } else {
                0.0
            }
        }

        fn doublet(&self, j: usize, x: Vec3) -> (Vec3, Vec3) {
            let at = self.solid_at(j);
            let s0 = self.texel(at);
            let (a, radius) = (self.xyz(at + 1), self.texel(at + 1)[3]);
            let (b, height) = (self.xyz(at + 2), self.texel(at + 2)[3]);
            let d = self.xyz(at + 3);
            if s0[2] == 1.0 {
                let r = x - a;
                let rho = r.length();
                let span = (SPHERE_ZONE_OUTER - SPHERE_ZONE_INNER) * radius;
                let (w, dw) = Self::taper((rho - SPHERE_ZONE_INNER * radius) / span);
                if w == 0.0 {
                    return (Vec3::ZERO, Vec3::ZERO);
                }
                let (p, u) = if rho >= radius {
                    let n = r / rho;
                    let q = radius / rho;
                    let q3 = 0.5 * q * q * q;
                    (d.cross(r) * -q3, (n * (3.0 * d.dot(n)) - d) * -q3)
                } else {
                    (d.cross(r) * -0.5, -d)
                };
                if dw == 0.0 {
                    return (p * w, u * w);
                }
                let grad = r * (dw / (span * rho));
                (p * w, u * w + grad.cross(p))
            } else if s0[2] == 2.0 {
                let r = x - a;
                let s = r.dot(b);
                let beyond = if s > height { s - height } else { -s };
                let w_axial = Self::taper(beyond / radius).0;
                if w_axial == 0.0 {
                    return (Vec3::ZERO, Vec3::ZERO);
                }
                let rv = r - b * s;
                let rho = rv.length();
                let span = (CYLINDER_ZONE_OUTER - CYLINDER_ZONE_INNER) * radius;
                let (wr, dwr) = Self::taper((rho - CYLINDER_ZONE_INNER * radius) / span);
                if wr == 0.0 {
                    return (Vec3::ZERO, Vec3::ZERO);
                }
                let r2 = radius * radius;
                let md = d.dot(rv);
                let (stream, grad) = if rho >= radius {
                    let inv2 = 1.0 / (rho * rho);
                    (-r2 * md * inv2, (d - rv * (2.0 * md * inv2)) * (-r2 * inv2))
                } else {
                    let q = rho * rho / r2;
                    let p = 1.0 + q * (3.0 + q * (-5.0 + 2.0 * q));
                    let dp = 3.0 + q * (-10.0 + 6.0 * q);
                    (-md * p, -(d * p + rv * (md * dp * 2.0 / r2)))
                };
                let mut g = grad * wr;
                if dwr != 0.0 {
                    g += rv * (stream * dwr / (span * rho));
                }
                (b * (stream * wr * w_axial), g.cross(b) * w_axial)
            } else {
                (Vec3::ZERO, Vec3::ZERO)
            }
        }

        fn projected(u: Vec3, n: Vec3, alpha: f32, keep: bool) -> Vec3 {
            let un = u.dot(n);
            let un = if keep { un.min(0.0) } else { un };
            u - n * ((1.0 - alpha) * un)
        }

        fn image_of(&self, j: usize) -> i64 {
            self.texel(self.prim(j) + 1)[3] as i64
        }

        fn exact_near(&self, n: usize, j: usize) -> bool {
            if self.texel(self.solid_at(n))[0] != PLANE_SOLID_KIND {
                return false;
            }
            let image = self.image_of(j);
            if image == n as i64 {
                return true;
            }
            let at = self.prim(j);
            let (first, count) = (self.texel(at + 2)[3] as i64, self.texel(at + 3)[3] as i64);
            image < 0 && (0..count).any(|k| self.image_of((first + k) as usize) == n as i64)
        }

        fn has_potential(&self, j: usize) -> bool {
            let head = self.texel(self.prim(j));
            head[0] == VORTEX_KIND && head[1] == 0.0
        }

        fn gauge(&self, n: usize, j: usize) -> Vec3 {
            let at = self.solid_at(n);
            let s0 = self.texel(at);
            let (a, b, h) = (self.xyz(at + 1), self.xyz(at + 2), self.texel(at + 2)[3]);
            if s0[0] == PLANE_SOLID_KIND {
                let q = self.xyz(self.prim(j) + 2);
                q - b * (q - a).dot(b)
            } else if s0[0] == CYLINDER_SOLID_KIND {
                a + b * (0.5 * h)
            } else {
                a
            }
        }

        fn vortex_potential(&self, j: usize, y: Vec3, gauge: Vec3) -> Vec3 {
            let at = self.prim(j);
            let head = self.texel(at);
            let (p, axis) = (self.xyz(at + 2), self.xyz(at + 3));
            let (c, c0) = (axis.cross(y - p), axis.cross(gauge - p));
            axis * (-0.5
                * head[2]
                * ((c.length_squared() + head[3]) / (c0.length_squared() + head[3])).ln())
        }

        /// `reachesStencil`: whether solid j's doublet may be other than zero within h of c.
        fn reaches_stencil(&self, j: usize, c: Vec3, h: f32) -> bool {
            let at = self.solid_at(j);
            if self.texel(at)[2] != 1.0 {
                return true;
            }
            let a = self.texel(at + 1);
            (c - Vec3::new(a[0], a[1], a[2])).length() <= SPHERE_ZONE_OUTER * a[3] + 1.01 * h
        }

        /// `rampedPotentials`: each solid's doublet at the six points in turn, then the vortices.
        fn ramped_potentials(
            &self,
            n: usize,
            lists: [usize; 4],
            c: Vec3,
            h: f32,
            points: &[Vec3; 6],
        ) -> [Vec3; 6] {
            let mut psi = [Vec3::ZERO; 6];
            for k in lists[1]..lists[3] {
                let j = self.member(k);
                if j == n || !self.reaches_stencil(j, c, h) {
                    continue;
                }
                for (p, y) in psi.iter_mut().zip(points) {
                    *p += self.doublet(j, *y).0;
                }
            }
            for j in 0..self.texel(4)[3] as usize {
                if !self.exact_near(n, j) && self.has_potential(j) {
                    let gauge = self.gauge(n, j);
                    for (p, y) in psi.iter_mut().zip(points) {
                        *p += self.vortex_potential(j, *y, gauge);
                    }
                }
            }
            psi
        }

        fn curl(a: &[Vec3; 6], points: &[Vec3; 6]) -> Vec3 {
            let span = Vec3::new(
                points[0].x - points[1].x,
                points[2].y - points[3].y,
                points[4].z - points[5].z,
            );
            let inv = span.recip();
            let (dx, dy, dz) = (
                (a[0] - a[1]) * inv.x,
                (a[2] - a[3]) * inv.y,
                (a[4] - a[5]) * inv.z,
            );
            Vec3::new(dy.z - dz.y, dz.x - dx.z, dx.y - dy.x)
        }

        fn near_solid(
            &self,
            n: usize,
            near: (Vec3, f32),
            x: Vec3,
            cell: [usize; 4],
            o: [Vec3; 2],
        ) -> (Vec3, Vec3) {
            let at = self.solid_at(n);
            let s0 = self.texel(at);
            let axis = self.xyz(at + 2);
            let width = self.texel(5)[1];
            let (nrm, dist) = near;
            let alpha = Self::ramp(dist / width);
            let plane = s0[0] == PLANE_SOLID_KIND;
            let u0 = self.xyz(4);
            let mut large = if s0[0] == SPHERE_SOLID_KIND {
                u0
            } else if s0[0] == CYLINDER_SOLID_KIND {
                let along = axis * u0.dot(axis);
                (u0 - along) + Self::projected(along, nrm, alpha, false)
            } else {
                Self::projected(u0, nrm, alpha, true)
            };
            if s0[2] > 0.0 {
                large += self.doublet(n, x).1;
            }
            let h = s0[1];
            let c = if dist < -h { x + nrm * (-h - dist) } else { x };
            let lists = if dist < -h { self.cell_lists(c) } else { cell };
            let others = (lists[1]..lists[3]).any(|k| self.member(k) != n);
            let mut vortices = false;
            for j in 0..self.texel(4)[3] as usize {
                if self.exact_near(n, j) {
                    large += self.primitive(j, x);
                } else if self.has_potential(j) {
                    vortices = true;
                } else {
                    large += Self::projected(self.primitive(j, x), nrm, alpha, plane);
                }
            }
            let has_field = self.texel(0)[0] > 0.5;
            let has_psi = self.texel(5)[2] > 0.5;
            let projected_small = |x: Vec3| {
                if has_field {
                    Self::projected(self.small(x, o), nrm, alpha, false)
                } else {
                    Vec3::ZERO
                }
            };
            if !(others || vortices || has_psi) {
                return (large, projected_small(x));
            }
            let edge = self.edge(n);
            let axes = [Vec3::X, Vec3::Y, Vec3::Z];
            let points: [Vec3; 6] = std::array::from_fn(|k| {
                c + axes[k / 2] * (if k % 2 == 0 { 1.0 } else { -1.0 } * h)
            });
            let geo: [(f32, Vec3); 6] = std::array::from_fn(|k| {
                let (n, d) = self.distance(n, points[k], edge);
                (Self::ramp(d / width), n)
            });
            let ramped = |psi: [Vec3; 6]| -> [Vec3; 6] {
                std::array::from_fn(|k| {
                    let (al, nk) = geo[k];
                    psi[k] * al + nk * ((1.0 - al) * nk.dot(psi[k]))
                })
            };
            if others || vortices {
                let psi = self.ramped_potentials(n, lists, c, h, &points);
                large += Self::curl(&ramped(psi), &points);
            }
            let small = if has_psi {
                // `blendedStencil` reads the lattice cell about c once, with `lattice`'s
                // arithmetic at each point: here each point is sampled alone.
                let scale = self.xyz(6);
                let psi = std::array::from_fn(|k| self.blended(self.psi, points[k], scale, o));
                Self::curl(&ramped(psi), &points)
            } else {
                projected_small(c)
            };
            (large, small)
        }

        /// `clearanceOf`: how far x surely lies from every solid, from the nearest one's
        /// rounded distance (the layer's width when none).
        fn clearance(&self, nearest: f32, x: Vec3) -> f32 {
            let d = nearest.min(self.texel(5)[1]);
            (d - self.texel(6)[3]) * 0.999 - 1e-6 * (1.0 + x.abs().max_element())
        }

        /// `windPartsAndClearance`.
        pub fn parts_and_clearance(&self, x: Vec3, o: [Vec3; 2]) -> (Vec3, Vec3, f32) {
            let width = self.texel(5)[1];
            let cell = self.cell_lists(x);
            let mut best: Option<(usize, (Vec3, f32))> = None;
            for j in self.layers_and_planes(cell) {
                let dn = self.distance(j, x, self.edge(j));
                if dn.1 < width && best.is_none_or(|b| dn.1 < b.1 .1) {
                    best = Some((j, dn));
                }
            }
            if let Some((n, near)) = best {
                let (large, small) = self.near_solid(n, near, x, cell, o);
                return (large, small, self.clearance(near.1, x));
            }
            let mut large = self.xyz(4);
            for k in cell[1]..cell[3] {
                large += self.doublet(self.member(k), x).1;
            }
            for j in 0..self.texel(4)[3] as usize {
                large += self.primitive(j, x);
            }
            (large, self.small(x, o), self.clearance(width, x))
        }

        fn inside(&self, x: Vec3) -> Option<(Vec3, f32)> {
            self.layers_and_planes(self.cell_lists(x))
                .into_iter()
                .map(|j| self.distance(j, x, 0.0))
                .find(|dn| dn.1 < 0.0)
        }

        pub fn push_out(&self, mut x: Vec3) -> Vec3 {
            let gap = 1e-4 * self.texel(5)[1];
            let (start, mut normal) = (x, Vec3::Y);
            for _ in 0..4 {
                let Some((n, d)) = self.inside(x) else {
                    return x;
                };
                let g = gap + 4.0 * 1.192_092_9e-7 * x.abs().max_element();
                x += n * (g - d);
                normal = n;
            }
            if self.inside(x).is_none() {
                return x;
            }
            // Overlapping solids: the shortest of seven ways out of them all.
            let ways = [
                normal,
                Vec3::X,
                -Vec3::X,
                Vec3::Y,
                -Vec3::Y,
                Vec3::Z,
                -Vec3::Z,
            ];
            let mut t = gap.max(1e-4);
            while t < 1e3 {
                if let Some(y) = ways
                    .iter()
                    .map(|&w| start + w * t)
                    .find(|&y| self.inside(y).is_none())
                {
                    return y;
                }
                t *= 1.25;
            }
            x
        }
    }
}

/// The wind of `scene` at 400 points a table (a quarter of them pushed into the layer of one of
/// its solids, in turn), read from its tables and grid as the GPU reads them, against the core's;
/// and where each point is put back outside. Points in the box `lo` + [0, 1]³ · `size`. Returns
/// the points checked, those near a solid, and the carried phases' resets seen in the tables.
fn twin_against_core(scene: Scene, lo: Vec3, size: Vec3, rounds: usize) -> [usize; 3] {
    let mut sim = Simulation::new(scene).unwrap();
    sim.hand_centres_to_gpu().unwrap();
    let field = sim.field().unwrap().clone();
    let psi = field.potential.clone().expect("a field with its potential");
    let walls = sim.wind.walls().unwrap().solids.clone();
    let bodies = walls.bodies.len();
    let (mut checked, mut near, mut resets) = (0, 0, 0);
    let mut grid = Vec::new();
    for round in 0..rounds {
        let steps = GpuSteps::run(&mut sim, 3);
        // The grid comes with the first steps only: the solids stay the same.
        assert_eq!(steps.solid_grid.is_empty(), round > 0, "round {round}");
        if round == 0 {
            grid = steps.solid_grid.clone();
        }
        for (k, frame) in sim.wind_frames().iter().enumerate() {
            let at = steps.wind_offsets[steps.wind_offsets.len() - 2 + k] as usize;
            let t = table::Table {
                t: &steps.wind[at..],
                g: &grid,
                u: &field.data,
                psi: &psi,
                n: field.lattice.size,
            };
            resets += steps.wind[at + 30..at + 32]
                .iter()
                .filter(|&&r| r >= 0.0)
                .count();
            for j in 0..400 {
                let f = |k: f32| ((j as f32 + 0.5) * k).fract();
                let mut x = lo + size * Vec3::new(f(0.7548777), f(0.5698403), f(0.4301597));
                if j % 4 == 0 {
                    let b = j / 4 % bodies;
                    let (d, n) = walls.bodies[b].distance(x.into());
                    let width = sim.scene.field.boundary_width as f32;
                    x -= Vec3::from(n) * (d - width * f(0.1234567));
                    near += 1;
                }
                let o = [
                    Vec3::new(f(0.31), f(0.47), f(0.59)) * 0.3,
                    Vec3::new(f(0.67), f(0.71), f(0.83)) * 0.3,
                ];
                let (gl, gs, gc) = t.parts_and_clearance(x, o);
                let (cl, cs, cc) = frame.parts_and_clearance(x.into(), [o[0].into(), o[1].into()]);
                let (cl, cs) = (Vec3::from(cl), Vec3::from(cs));
                assert!((gc - cc).abs() <= 1e-6, "x = {x}: clearance {gc} vs {cc}");
                let tol = |w: Vec3| 2e-4 * w.length().max(1.0);
                assert!(
                    (gl - cl).length() <= tol(cl),
                    "t = {}, x = {x}: large {gl} vs {cl}",
                    frame.time
                );
                assert!(
                    (gs - cs).length() <= tol(cs),
                    "t = {}, x = {x}: small {gs} vs {cs}",
                    frame.time
                );
                let (gp, cp) = (
                    t.push_out(x),
                    Vec3::from(walls.push_out(x.into(), sim.wind.walls().unwrap().gap())),
                );
                assert!((gp - cp).length() < 1e-6, "push out {x}: {gp} vs {cp}");
                checked += 1;
            }
        }
    }
    [checked, near, resets]
}

#[test]
fn the_wind_table_with_solids_and_carried_scales_read_as_the_gpu_reads_it_is_the_cores_wind() {
    let lo = Vec3::new(-1.2, -0.5, -0.8);
    let [checked, near, resets] =
        twin_against_core(with_solids(), lo, Vec3::new(2.4, 2.0, 1.6), 30);
    assert!(
        checked == 24_000 && near > 5000,
        "{checked} points, {near} near solids"
    );
    assert!(
        resets > 5,
        "{resets} resets of the carried phases in the tables"
    );
}

/// [`with_solids`] among 150 more small solid spheres through its box, so most points' cells list
/// a few of the many solids and the GPU must walk the grid as the core does.
fn among_many_spheres() -> Scene {
    let mut s = with_solids();
    s.field.boundary_width = 0.04;
    let mut objects = serde_json::to_value(&s.render.objects).unwrap();
    for i in 0..150 {
        let f = |k: f64| ((i as f64 + 0.5) * k).fract();
        let c = [
            2.4 * f(0.7548777) - 1.2,
            2.0 * f(0.5698403) - 0.5,
            1.6 * f(0.4301597) - 0.8,
        ];
        objects.as_array_mut().unwrap().push(json!(
            {"type": "sphere", "center": c, "radius": 0.04 + 0.03 * f(0.618034), "color": [1, 1, 1], "solid": true}
        ));
    }
    s.render.objects = serde_json::from_value(objects).unwrap();
    // No emitter inside a sphere.
    s.emitters.truncate(1);
    s.emitters[0].center = [0.0, -0.25, 0.0];
    s
}

#[test]
fn among_many_solids_the_gpu_walks_the_cores_grid() {
    let scene = among_many_spheres();
    let sim = Simulation::new(scene.clone()).unwrap();
    let (cells, members) = sim.wind.walls().unwrap().solids.grid_size().unwrap();
    assert!(
        cells > 1000 && members < 20 * cells,
        "{cells} cells, {members} members"
    );
    let lo = Vec3::new(-1.2, -0.5, -0.8);
    let [checked, near, _] = twin_against_core(scene, lo, Vec3::new(2.4, 2.0, 1.6), 8);
    assert!(
        checked == 6400 && near > 1500,
        "{checked} points, {near} near solids"
    );
}

/// The grid crosses again once an edit builds the solids anew, and not before.
#[test]
fn the_solids_grid_crosses_once_per_set_of_solids() {
    let scene = with_solids();
    let mut sim = Simulation::new(scene.clone()).unwrap();
    sim.hand_centres_to_gpu().unwrap();
    let first = GpuSteps::run(&mut sim, 2).solid_grid;
    assert!(!first.is_empty());
    assert!(GpuSteps::run(&mut sim, 2).solid_grid.is_empty());
    let mut edited = scene.clone();
    edited.render.objects.truncate(2);
    let field = sim.field().cloned();
    sim.edit(edited, field.clone()).unwrap();
    let again = GpuSteps::run(&mut sim, 1).solid_grid;
    assert!(!again.is_empty() && again != first);
    // Without solids there is no grid to hand.
    let mut bare = scene;
    bare.render.objects.clear();
    sim.edit(bare, field).unwrap();
    assert!(GpuSteps::run(&mut sim, 1).solid_grid.is_empty());
}
