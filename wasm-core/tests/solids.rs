//! Solid objects (docs/CONVENTIONS.md, solid objects): a uniform wind past a sphere is the
//! potential flow around it; along every kind of solid every kind of wind (and the small-scale
//! field) has no component through the surface and, where the method is divergence-free, none
//! by the differences of the ramped curl; a plume under a ceiling spreads along it; no blob
//! ever ends a step inside a solid.

use glam::{Vec3, Vec3A};
use serde_json::{json, Value};
use windfield::scene::bodies::Body;
use windfield::wind::WindFrame;
use windfield::{Scene, Simulation};

fn scene(v: Value) -> Scene {
    let mut base = json!({"version": 1});
    base.as_object_mut()
        .unwrap()
        .extend(v.as_object().unwrap().clone());
    Scene::from_value(base).unwrap()
}

/// A fixed low-discrepancy sequence in [0, 1)³.
fn lds(i: usize) -> [f32; 3] {
    let f = |k: f64| (((i as f64) + 0.5) * k).fract() as f32;
    [
        f(0.754_877_666_246_692_7),
        f(0.569_840_290_998_053_3),
        f(0.430_159_709_001_946_7),
    ]
}

/// A unit vector from the sequence (uniform on the sphere).
fn direction(i: usize) -> Vec3 {
    let [u, v, _] = lds(i);
    let z = 2.0 * u - 1.0;
    let phi = std::f32::consts::TAU * v;
    let s = (1.0 - z * z).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

/// Potential flow around a sphere of radius `a` at the origin in the uniform wind `u`.
fn potential_flow(x: Vec3, a: f32, u: Vec3) -> Vec3 {
    let r = x.length();
    let n = x / r;
    u - (n * (3.0 * u.dot(n)) - u) * (0.5 * a * a * a / (r * r * r))
}

#[test]
fn a_uniform_wind_past_a_solid_sphere_is_the_potential_flow_around_it() {
    let a = 0.5;
    let u = Vec3::new(1.0, 0.0, 0.0);
    let s = scene(json!({
        "field": {"amplitude": 0},
        "wind": [{"type": "uniform", "velocity": [1, 0, 0]}],
        "render": {"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": a,
                                "color": [1, 1, 1], "solid": true}]}
    }));
    let sim = Simulation::new(s).unwrap();
    let frame = sim.wind.frame(0.0);
    // Everywhere outside r = 1.05 a (out to 4 a, where the doublet is exact, and on to 10 a,
    // through its fade).
    let mut worst: f32 = 0.0;
    for i in 0..4000 {
        let r = a * (1.05 + 8.95 * lds(i)[2]);
        let x = direction(i) * r;
        let err = (frame.velocity(x) - potential_flow(x, a, u)).length();
        worst = worst.max(err);
    }
    assert!(worst < 0.05, "largest difference {worst} m/s");
    // 1.5 U at the equator, 0 at the stagnation points, U (1 + a³/2r³) on the equator line.
    let on = |x: Vec3| frame.velocity(x);
    assert!((on(Vec3::new(0.0, a * 1.0001, 0.0)).x - 1.5).abs() < 0.01);
    assert!(on(Vec3::new(-a * 1.0001, 0.0, 0.0)).length() < 0.01);
    assert!(on(Vec3::new(a * 1.0001, 0.0, 0.0)).length() < 0.01);
    for k in 0..20 {
        let r = a * (1.05 + 0.15 * k as f32);
        let want = 1.0 + a * a * a / (2.0 * r * r * r);
        let got = on(Vec3::new(0.0, 0.0, r));
        assert!(
            (got.x - want).abs() < 0.05 && got.y.abs() < 0.05,
            "r = {r}: {got}"
        );
    }
}

/// The solid bodies of the checks below, in one place each.
fn bodies() -> Vec<(&'static str, Value)> {
    vec![
        (
            "sphere",
            json!({"type": "sphere", "center": [0, 0.9, 0], "radius": 0.45, "color": [1, 1, 1], "solid": true}),
        ),
        (
            "plane",
            json!({"type": "plane", "point": [0, 0.5, 0], "normal": [0.1, 1, 0.05], "color": [1, 1, 1], "solid": true}),
        ),
        (
            "cylinder",
            json!({"type": "cylinder", "base": [0, 0.4, 0], "axis": [0.1, 1, 0], "radius": 0.35,
                   "height": 0.9, "color": [1, 1, 1], "solid": true}),
        ),
    ]
}

/// Points on the surface of `body`, `n` of them, from the sequence.
fn surface_points(body: &Body, n: usize) -> Vec<(Vec3A, Vec3A)> {
    (0..n)
        .map(|i| {
            let [u, v, w] = lds(i + 17);
            match *body {
                Body::Sphere { center, radius } => {
                    let d: Vec3A = direction(i + 17).into();
                    (center + d * radius, d)
                }
                Body::Plane { point, normal } => {
                    let e1 = windfield::scene::bodies::perpendicular(normal);
                    let e2 = normal.cross(e1);
                    (point + e1 * (2.0 * u - 1.0) + e2 * (2.0 * v - 1.0), normal)
                }
                Body::Cylinder {
                    base,
                    axis,
                    radius,
                    height,
                } => {
                    let e1 = windfield::scene::bodies::perpendicular(axis);
                    let e2 = axis.cross(e1);
                    let phi = std::f32::consts::TAU * v;
                    let radial = e1 * phi.cos() + e2 * phi.sin();
                    // Side and caps in proportion to their areas.
                    let side = 2.0 * radius * height;
                    let caps = 2.0 * radius * radius;
                    if u * (side + caps) < side {
                        (base + axis * (height * w) + radial * radius, radial)
                    } else {
                        let top = w < 0.5;
                        let r = radius * (2.0 * (w % 0.5)).sqrt();
                        let p = base + radial * r + if top { axis * height } else { Vec3A::ZERO };
                        (p, if top { axis } else { -axis })
                    }
                }
            }
        })
        .collect()
}

/// Whether `x` lies within `band` of a cylinder's rim, where its surface has no normal (the
/// wind sees the rims rounded by three difference steps; the checks leave out twice that).
fn near_rim(body: &Body, x: Vec3A, band: f32) -> bool {
    let Body::Cylinder {
        base,
        axis,
        radius,
        height,
    } = *body
    else {
        return false;
    };
    let s = (x - base).dot(axis);
    let rho = ((x - base) - axis * s).length();
    let from_cap = s.abs().min((s - height).abs());
    from_cap < band && (radius - rho) < band
}

/// The FD divergence and gradient (Frobenius) of the frame's wind at `x` with step `h`.
fn divergence_and_gradient(frame: &WindFrame, x: Vec3A, h: f32) -> (f32, f32) {
    let axes = [Vec3A::X, Vec3A::Y, Vec3A::Z];
    let mut div = 0.0;
    let mut grad2 = 0.0;
    for (i, e) in axes.iter().enumerate() {
        let d = (frame.velocity_a(x + *e * h) - frame.velocity_a(x - *e * h)) / (2.0 * h);
        div += d[i];
        grad2 += d.length_squared();
    }
    (div, grad2.sqrt())
}

/// What each check puts in the wind (besides the solid), and whether the method keeps it
/// divergence-free along that solid (docs/CONVENTIONS.md lists what it does not: a source or
/// a repulsor along a curved solid is projected, as is a uniform wind into a plane or a cap).
fn winds() -> Vec<(&'static str, Value, Value, [bool; 3])> {
    let calm = json!({"amplitude": 0});
    vec![
        (
            "small-scale field",
            json!({"size": [16, 16, 16, 8], "period": [2, 2, 2], "time_period": 4,
                   "spectrum": {"k_inertial": 2}}),
            json!([]),
            [true, true, true],
        ),
        (
            "uniform wind across",
            calm.clone(),
            json!([{"type": "uniform", "velocity": [0.8, -0.08, 0]}]),
            [true, true, true],
        ),
        (
            "uniform wind into the plane and the caps",
            calm.clone(),
            json!([{"type": "uniform", "velocity": [0.3, -0.6, 0.2]}]),
            [true, false, false],
        ),
        (
            "source",
            calm.clone(),
            json!([{"type": "source", "position": [0.2, 1.6, 0.1], "strength": 0.8, "radius": 0.002}]),
            [false, true, false],
        ),
        (
            "sink",
            calm.clone(),
            json!([{"type": "source", "position": [-0.2, 1.5, 0.3], "strength": -0.8, "radius": 0.002}]),
            [false, true, false],
        ),
        (
            "vortex",
            calm.clone(),
            json!([{"type": "vortex", "position": [0.3, 1.5, 0.0], "axis": [1, -0.1, 0.3],
                    "strength": 0.9, "radius": 0.05}]),
            [true, true, true],
        ),
        (
            "repulsor",
            calm,
            json!([{"type": "repulsor", "radius": 0.2, "strength": 2,
                    "path": [[0, -0.5, 1.65, 0], [4, 0.5, 1.75, 0.2]]}]),
            [false, true, false],
        ),
    ]
}

#[test]
fn along_every_solid_every_wind_has_no_normal_component_and_no_divergence() {
    for (b, (body_name, object)) in bodies().into_iter().enumerate() {
        for (wind_name, field, wind, solenoidal) in winds() {
            let mut wind = wind;
            // The vortex lies parallel to the plane (so it is mirrored in it).
            if body_name == "plane" && wind_name == "vortex" {
                wind[0]["axis"] = json!([1, -0.1, 0]);
            }
            let s = scene(json!({
                "field": field,
                "wind": wind,
                "render": {"objects": [object]}
            }));
            let what = format!("{wind_name} along the {body_name}");
            let sim = Simulation::new(s).unwrap();
            let frame = sim.wind.frame(1.3);
            let walls = frame.walls().expect("a solid");
            let body = walls.solids.bodies[0];
            let h = frame.curl_step(0).unwrap();
            let width = walls.width;
            // The normal component at 1,000 surface points, against the local speed (at the
            // few points slower than a tenth of the surface's RMS speed, stagnation points,
            // against that tenth).
            let rim = 2.0 * walls.solids.edges[0];
            let samples: Vec<(f32, f32)> = surface_points(&body, 1000)
                .into_iter()
                .filter(|(x, _)| !near_rim(&body, *x, rim))
                .map(|(x, n)| {
                    let u = frame.velocity_a(x);
                    (u.dot(n).abs(), u.length())
                })
                .collect();
            assert!(samples.len() > 950, "{what}: {} points", samples.len());
            let rms =
                (samples.iter().map(|s| s.1 * s.1).sum::<f32>() / samples.len() as f32).sqrt();
            assert!(rms > 0.02, "{what}: a wind to check ({rms} m/s)");
            let worst = samples
                .iter()
                .map(|&(un, speed)| un / speed.max(0.1 * rms))
                .fold(0.0f32, f32::max);
            assert!(
                worst < 0.01,
                "{what}: normal component {worst} of the local speed"
            );
            if !solenoidal[b] {
                continue;
            }
            // The divergence in the layer by the curl's own differences, against |∇u|.
            let (mut div2, mut grad2) = (0.0f64, 0.0f64);
            for (i, (p, n)) in surface_points(&body, 1000).into_iter().enumerate() {
                let x = p + n * (width * (0.05 + 0.85 * lds(i + 3)[0]));
                let (div, grad) = divergence_and_gradient(&frame, x, h);
                div2 += (div as f64).powi(2);
                grad2 += (grad as f64).powi(2);
            }
            // (A uniform wind along a plane passes unchanged: no gradient, no divergence.)
            let ratio = if grad2 == 0.0 {
                div2.sqrt()
            } else {
                (div2 / grad2).sqrt()
            };
            assert!(ratio < 1e-3, "{what}: divergence {ratio} of |∇u|");
        }
    }
}

/// The plume of the ceiling check: an updraft of 1 m/s, turbulence, a small disk of gas at
/// the floor; with `ceiling` a solid plane 0.8 m above it (the half-space above it solid).
fn plume(ceiling: bool) -> Scene {
    let objects = if ceiling {
        json!([{"type": "plane", "point": [0, 0.8, 0], "normal": [0, -1, 0], "color": [1, 1, 1], "solid": true}])
    } else {
        json!([])
    };
    scene(json!({
        "seed": 3,
        "field": {"size": [16, 16, 16, 16], "period": [2, 2, 2], "time_period": 4, "amplitude": 1,
                  "spectrum": {"k_inertial": 2}},
        "wind": [{"type": "uniform", "velocity": [0, 1, 0]}],
        "emitters": [{"shape": "disk", "center": [0, 0, 0], "radius": 0.05, "rate": 400, "sigma0": 0.02}],
        "gas": {"dissipation": 0, "min_mass": 0, "max_blobs": 5000, "diffusion": 0.0001},
        "render": {"objects": objects}
    }))
}

/// The horizontal spread (RMS distance from the vertical through their mean, m) of the blobs
/// between `low` and `high` (m), and their count.
fn horizontal_spread(sim: &Simulation, low: f32, high: f32) -> (f32, usize) {
    let b = &sim.gas.blobs;
    let band: Vec<Vec3> = (0..b.len())
        .map(|i| b.center(i))
        .filter(|c| c.y >= low && c.y <= high)
        .collect();
    let n = band.len() as f32;
    let mean = band.iter().copied().sum::<Vec3>() / n;
    let var = band
        .iter()
        .map(|c| (c.x - mean.x).powi(2) + (c.z - mean.z).powi(2))
        .sum::<f32>()
        / n;
    (var.sqrt(), band.len())
}

/// The updraft into the ceiling stops in its layer (a uniform wind into a plane is projected,
/// docs/CONVENTIONS.md) and the gas it brings stays there, spread along the ceiling by the
/// eddies, which the layer turns along it; without the ceiling the same gas passes the same
/// height in a narrow column.
#[test]
fn a_plume_under_a_solid_ceiling_spreads_along_it() {
    let mut open = Simulation::new(plume(false)).unwrap();
    let mut closed = Simulation::new(plume(true)).unwrap();
    open.run(open.steps_for(5.0));
    closed.run(closed.steps_for(5.0));
    let b = &closed.gas.blobs;
    let highest = (0..b.len()).map(|i| b.center(i).y).fold(f32::MIN, f32::max);
    assert!(highest <= 0.8, "a blob above the ceiling, at y = {highest}");
    // The gas in the 20 cm under the ceiling's height, with and without it.
    let (spread_open, n_open) = horizontal_spread(&open, 0.6, 0.8);
    let (spread_closed, n_closed) = horizontal_spread(&closed, 0.6, 0.8);
    assert!(n_open > 30 && n_closed > 1000, "{n_open}, {n_closed}");
    eprintln!("spread {spread_closed} m under the ceiling ({n_closed} blobs), {spread_open} m without ({n_open})");
    assert!(
        spread_closed >= 3.0 * spread_open,
        "spread under the ceiling {spread_closed} m, without it {spread_open} m"
    );
}

/// The steam-mug preset with the mug's body solid (as it ships): 1,000 steps, and after each
/// no blob centre inside the mug (or below the floor).
#[test]
fn a_thousand_steps_of_the_steam_mug_leave_no_blob_inside_the_mug() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../public/scenes/steam-mug.json"
    ))
    .unwrap();
    let mut s = Scene::from_json(&text).unwrap();
    for o in &mut s.render.objects {
        if let windfield::scene::blob_list::Object::Cylinder { solid, .. } = o {
            *solid = true;
        }
    }
    // A smaller field and a tenth of the blobs keep the check quick; the mug, the wind and the
    // emitter's place are as they ship.
    s.field.size = [16, 16, 16, 16];
    s.emitters[0].rate /= 10.0;
    let mut sim = Simulation::new(s).unwrap();
    let walls = sim.wind.walls().expect("the mug is solid").solids.clone();
    let mut checked = 0;
    for step in 0..1000 {
        sim.step();
        let b = &sim.gas.blobs;
        for i in 0..b.len() {
            let c: Vec3A = b.center(i).into();
            if let Some(j) = walls.inside(c) {
                panic!("step {step}: blob {i} at {c} inside solid {j}");
            }
        }
        checked += b.len();
    }
    assert!(checked > 2_000_000, "{checked} blob-steps checked");
}

#[test]
fn an_emitter_inside_a_solid_is_refused_naming_both() {
    let e = Scene::from_value(json!({
        "version": 1,
        "emitters": [{"center": [0, 0.5, 0]}, {"center": [0.1, 0.85, 0.1]}],
        "render": {"objects": [
            {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 1, 1], "solid": true},
            {"type": "cylinder", "base": [0, 0, 0], "axis": [0, 1, 0], "radius": 0.4, "height": 0.9,
             "color": [1, 1, 1], "solid": true}
        ]}
    }))
    .unwrap_err();
    assert_eq!(e.path, "emitters[0].center");
    assert!(
        e.message.contains("render.objects[1]") && e.message.contains("cylinder"),
        "{e}"
    );
    // Not solid, nothing to refuse; a moving emitter is checked at every key.
    assert!(Scene::from_value(json!({
        "version": 1,
        "emitters": [{"center": [0, 0.5, 0]}],
        "render": {"objects": [{"type": "sphere", "center": [0, 0.5, 0], "radius": 0.2, "color": [1, 1, 1]}]}
    }))
    .is_ok());
    let e = Scene::from_value(json!({
        "version": 1,
        "emitters": [{"path": [[0, 0, 1, 0], [1, 0, -1, 0]]}],
        "render": {"objects": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 1, 1], "solid": true}]}
    }))
    .unwrap_err();
    assert_eq!(e.path, "emitters[0].path[1]");
    assert!(
        e.message.contains("render.objects[0]") && e.message.contains("plane"),
        "{e}"
    );
}

#[test]
fn a_boundary_width_outside_its_range_is_refused_with_its_path() {
    for w in [json!(0), json!(-0.1), json!(2.5), json!(1e9)] {
        let e = Scene::from_value(
            json!({"version": 1, "field": {"period": [5, 4, 6], "boundary_width": w}}),
        )
        .unwrap_err();
        assert_eq!(e.path, "field.boundary_width", "{w}: {e}");
    }
    assert!(Scene::from_value(
        json!({"version": 1, "field": {"period": [5, 4, 6], "boundary_width": 2}})
    )
    .is_ok());
    let e = Scene::from_value(json!({"version": 1, "field": {"carry_time": 0}})).unwrap_err();
    assert_eq!(e.path, "field.carry_time");
}

/// A scene without `solid` keys plays exactly as before: the same blobs as with every object
/// explicitly not solid, and its normalised form has no `solid` key either.
#[test]
fn objects_without_solid_play_exactly_as_before() {
    let base = json!({
        "version": 1, "seed": 4,
        "field": {"size": [8, 8, 8, 8], "spectrum": {"k_inertial": 2}},
        "wind": [{"type": "uniform", "velocity": [0, 0.3, 0]}],
        "emitters": [{"center": [0, 0.1, 0], "rate": 200}],
        "render": {"objects": [
            {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 1, 1]},
            {"type": "sphere", "center": [0, 1, 0], "radius": 0.3, "color": [1, 1, 1]}
        ]}
    });
    let mut explicit = base.clone();
    for o in explicit["render"]["objects"].as_array_mut().unwrap() {
        o["solid"] = json!(false);
    }
    let a = Scene::from_value(base).unwrap();
    let b = Scene::from_value(explicit).unwrap();
    assert!(!a.to_json().contains("solid"));
    let (mut sa, mut sb) = (Simulation::new(a).unwrap(), Simulation::new(b).unwrap());
    sa.run(240);
    sb.run(240);
    assert_eq!(sa.gas.blobs.position, sb.gas.blobs.position);
    // And the blobs go through the sphere, as they always did (it is not solid).
    let b = &sa.gas.blobs;
    assert!((0..b.len()).any(|i| (b.center(i) - Vec3::Y).length() < 0.3));
}

/// The grid over the solids is only a way to find them: among 120 spheres and cylinders of
/// mixed sizes above a solid floor, with a vortex and the field's small scales, the wind at
/// points all over the scene (a third of them in the solids' layers) and every point put back
/// outside are those of the same wind with every solid visited at every point, the wind up to
/// the rounding of the doublets' sums (summed in another order).
#[test]
fn the_grid_over_many_solids_gives_the_wind_of_visiting_every_solid() {
    let objects: Vec<Value> = (0..120)
        .map(|i| {
            let [u, v, w] = lds(i + 7);
            let c = [3.0 * u - 1.5, 0.2 + 1.6 * v, 3.0 * w - 1.5];
            let radius = 0.03 + 0.05 * lds(3 * i)[0];
            if i % 3 == 2 {
                let axis = direction(i);
                json!({"type": "cylinder", "base": c, "axis": [axis.x, axis.y, axis.z],
                       "radius": radius, "height": 0.25, "color": [1, 1, 1], "solid": true})
            } else {
                json!({"type": "sphere", "center": c, "radius": radius, "color": [1, 1, 1], "solid": true})
            }
        })
        .chain([json!({"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 1, 1], "solid": true})])
        .collect();
    let s = scene(json!({
        "seed": 5,
        "field": {"size": [16, 16, 16, 8], "period": [2, 2, 2], "time_period": 4, "amplitude": 0.5,
                  "boundary_width": 0.06},
        "wind": [{"type": "uniform", "velocity": [0.4, 0.3, -0.2]},
                 {"type": "vortex", "position": [0.2, 1, 0.1], "axis": [0, 1, 0], "strength": 0.5, "radius": 0.3}],
        "render": {"objects": objects}
    }));
    let sim = Simulation::new(s).unwrap();
    let every = sim.wind.every_solid_visited();
    let (grid, brute) = (sim.wind.frame(0.7), every.frame(0.7));
    let walls = sim.wind.walls().unwrap();
    let brute_walls = every.walls().unwrap();
    let cells = walls.solids.grid_size().expect("a grid").0;
    assert!(
        brute_walls.solids.grid_size().is_none() && cells > 1000,
        "{cells} cells"
    );
    let (mut near, mut among) = (0, 0);
    for i in 0..30_000 {
        let [u, v, w] = lds(i);
        let mut x = Vec3A::new(3.6 * u - 1.8, 2.2 * v - 0.1, 3.6 * w - 1.8);
        if i % 3 == 0 {
            // Into the layer of one of the solids (or just inside it).
            let b = &walls.solids.bodies[i / 3 % walls.solids.len()];
            let (d, n) = b.distance(x);
            x -= n * (d - 0.07 * lds(i + 1)[2] + 0.01);
        }
        let o = [Vec3A::ZERO; 2];
        let ((gl, gs), (bl, bs)) = (grid.parts(x, o), brute.parts(x, o));
        let tol = |w: Vec3A| 1e-5 * w.length().max(1.0);
        assert!((gl - bl).length() <= tol(bl), "x = {x}: large {gl} vs {bl}");
        assert!((gs - bs).length() <= tol(bs), "x = {x}: small {gs} vs {bs}");
        let gap = walls.gap();
        assert_eq!(
            walls.solids.push_out(x, gap),
            brute_walls.solids.push_out(x, gap),
            "put back from {x}"
        );
        near += walls.solids.nearest(x).is_some() as usize;
        let around = walls.solids.around(x);
        among += (around.spheres.len() + around.others.len() > 3) as usize;
    }
    assert!(
        near > 8000 && among > 5000,
        "{near} near a solid, {among} among many"
    );
}
