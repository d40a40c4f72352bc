//! The flow (the paper's Eqs. 1–2 on a coarse grid) against closed forms: the projection leaves
//! no divergence and no flux through a solid; rest stays rest; a uniform wind past a sphere
//! becomes potential flow, and the wind entering an open box stays the wind; a Taylor–Green cellular flow decays at the rate its viscosity gives;
//! the advection carries a pattern with the wind (its centroid within 0.05 cells of u_p·t,
//! every value within 10 % of the peak: the clamp flattens the peak a little each step).

use std::f32::consts::PI;
use windfield::wind::flow::advect::{maccormack, Lattice};
use windfield::wind::flow::boundary::fixed_normal;
use windfield::wind::flow::{Faces, Flow, Grid, MacField};

/// A fixed-seed uniform deviate in [−1, 1) (a 64-bit LCG's top bits).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
    }
}

fn random_field(grid: &Grid, seed: u64) -> MacField {
    let mut rng = Lcg(seed);
    let mut u = MacField::zeros(grid);
    for comp in &mut u.u {
        for v in comp.iter_mut() {
            *v = rng.next();
        }
    }
    u
}

fn uniform(grid: &Grid, v: [f32; 3]) -> MacField {
    MacField::from_fn(grid, |_| v)
}

/// Every face open, every face closed, and walls across y alone (a post's ends).
const FACES: [Faces; 3] = [
    Faces::OPEN,
    Faces::CLOSED,
    Faces {
        closed: [false, true, false],
    },
];

/// A flow with a still sphere and a moving box, a random u_g, under a uniform u_p.
fn stirred(faces: Faces) -> (Flow, MacField) {
    let grid = Grid::new([0.0; 3], [24, 20, 22], 0.1);
    let mut flow = Flow::new(grid.clone(), faces);
    flow.solids
        .add_sphere(&grid, [0.8, 1.0, 1.1], 0.35, [0.0; 3]);
    flow.solids.add(&grid, [0.3, -0.2, 0.1], |x| {
        (1.5..1.9).contains(&x[0]) && (0.4..0.9).contains(&x[1]) && (0.5..1.6).contains(&x[2])
    });
    // A solid touching the box's face.
    flow.solids
        .add(&grid, [0.0; 3], |x| x[0] > 2.2 && x[1] > 1.5 && x[2] < 0.5);
    flow.u_g = random_field(&grid, 7);
    (flow, uniform(&grid, [0.5, 0.2, 0.0]))
}

#[test]
fn a_step_leaves_no_divergence_and_no_flux_through_solids() {
    for faces in FACES {
        let (mut flow, u_p) = stirred(faces);
        let report = flow.step(0.02, &u_p, None, &[]);
        let g = &flow.grid;
        let total = u_p.plus(&flow.u_g);
        let umax = total.max_abs();
        let div = flow.u_g.divergence(g);
        let worst = div
            .iter()
            .zip(&flow.solids.solid)
            .filter(|(_, &s)| !s)
            .fold(0.0f32, |m, (&d, _)| m.max(d.abs()));
        let relative = worst * g.h / umax;
        println!(
            "{faces:?}: {} CG iterations, residual {:.1e}, max|∇·u| = {relative:.2e} max|u|/h",
            report.iterations, report.residual
        );
        assert!(relative <= 1e-4, "{faces:?}: divergence {relative:e}");
        let mut fixed = 0;
        for a in 0..3 {
            let d = g.face_dims(a);
            for k in 0..d[2] {
                for j in 0..d[1] {
                    for i in 0..d[0] {
                        if let Some(v) = fixed_normal(g, &flow.solids, faces, a, [i, j, k]) {
                            fixed += 1;
                            let got = total.u[a][g.face(a, i, j, k)];
                            assert!(
                                (got - v).abs() <= 1e-6 * umax,
                                "{faces:?}: face {a} {i} {j} {k} carries {got}, not {v}"
                            );
                        }
                    }
                }
            }
        }
        assert!(fixed > 500, "{faces:?}: {fixed} fixed faces");
    }
}

#[test]
fn rest_stays_rest() {
    let grid = Grid::new([0.0; 3], [16; 3], 0.1);
    let mut flow = Flow::new(grid.clone(), Faces::CLOSED);
    flow.solids.add_sphere(&grid, [0.8; 3], 0.3, [0.0; 3]);
    let still = MacField::zeros(&grid);
    for _ in 0..1000 {
        flow.step(0.02, &still, None, &[]);
    }
    let rest = flow.u_g.max_abs();
    assert!(rest <= 1e-6, "still air moves at {rest} m/s");

    // Heat spread evenly in a closed box: the buoyancy is a gradient the pressure holds
    // (hydrostatic), so the air stays still.
    let mut flow = Flow::new(grid.clone(), Faces::CLOSED);
    flow.solids.add_sphere(&grid, [0.8; 3], 0.3, [0.0; 3]);
    let warm = vec![10.0; grid.cell_count()];
    for _ in 0..250 {
        flow.step(0.02, &still, Some(&warm), &[]);
    }
    let held = flow.u_g.max_abs();
    println!("still air, and evenly warm air in a closed box, after 1,000 and 250 steps: {rest:.1e} and {held:.1e} m/s");
    assert!(held <= 1e-6, "evenly warm air moves at {held} m/s");

    let wind = 2.0;
    let mut flow = Flow::new(grid.clone(), Faces::OPEN);
    let u_p = uniform(&grid, [wind, 0.0, 0.0]);
    for _ in 0..100 {
        flow.step(0.02, &u_p, None, &[]);
    }
    let response = flow.u_g.max_abs();
    println!(
        "a uniform wind of {wind} m/s in an open box, after 100 steps: |u_g| ≤ {response:.1e} m/s"
    );
    assert!(
        response <= 1e-3 * wind,
        "a uniform wind stirs u_g to {response} m/s"
    );
}

/// The potential flow past a sphere of radius `r0` at the origin in a uniform wind `u` along
/// x: u = U + (R³/2)(U/r³ − 3(U·x)x/r⁵).
fn doublet(u: f32, r0: f32, x: [f32; 3]) -> [f32; 3] {
    let r2: f32 = x.iter().map(|v| v * v).sum();
    let r = r2.sqrt();
    let c = r0.powi(3) / 2.0;
    let ux = u * x[0];
    std::array::from_fn(|a| {
        let e = if a == 0 { u } else { 0.0 };
        e + c * (e / r.powi(3) - 3.0 * ux * x[a] / r.powi(5))
    })
}

#[test]
fn a_uniform_wind_past_a_sphere_becomes_potential_flow() {
    let n = 72;
    let h = 0.125;
    let r0 = 8.0 * h;
    let half = n as f32 * h / 2.0;
    let grid = Grid::new([-half; 3], [n; 3], h);
    let mut flow = Flow::new(grid.clone(), Faces::OPEN);
    flow.solids.add_sphere(&grid, [0.0; 3], r0, [0.0; 3]);
    let wind = 1.0;
    let u_p = uniform(&grid, [wind, 0.0, 0.0]);
    let report = flow.step(0.01, &u_p, None, &[]);
    let s = 1.0 / 3f32.sqrt();
    let t = 1.0 / 2f32.sqrt();
    let directions = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [t, t, 0.0],
        [-t, 0.0, t],
        [s, s, s],
        [-s, s, -s],
        [s, -s, -s],
    ];
    let mut worst = 0.0f32;
    for d in directions {
        for radii in [1.5, 2.0, 2.5, 3.0] {
            let x: [f32; 3] = std::array::from_fn(|a| d[a] * radii * r0);
            let got = flow.velocity_at(&u_p, x);
            let want = doublet(wind, r0, x);
            let err = (0..3)
                .map(|a| (got[a] - want[a]).powi(2))
                .sum::<f32>()
                .sqrt();
            worst = worst.max(err / wind);
        }
    }
    println!(
        "potential flow past a sphere of 8 cells: {} CG iterations, worst |u − u_exact| = {:.2} % of U at 1.5–3 radii",
        report.iterations,
        100.0 * worst
    );
    assert!(worst <= 0.08, "potential flow off by {worst} U");
}

/// A uniform wind past a sphere in an open box, 4 s (two and a half passages of the air through
/// the box): the air entering the box is the wind's, undisturbed (a trace from beyond an open
/// face brings no u_g), so the sphere's drag does not slow the whole box. Where traces from
/// beyond the box took u_g's value at the face, the inflow took the interior's slowing with it
/// and the whole box fell behind the wind: the mean u at the inflow face and the wind beside
/// the sphere far across it then drop.
#[test]
fn the_wind_entering_an_open_box_stays_the_wind() {
    let (n, h) = ([32, 16, 16], 0.05);
    let grid = Grid::new([0.0; 3], n, h);
    let mut flow = Flow::new(grid.clone(), Faces::OPEN);
    flow.viscosity = 1e-3;
    flow.eddies = true;
    flow.solids
        .add_sphere(&grid, [0.5, 0.4, 0.4], 0.15, [0.0; 3]);
    let wind = 1.0;
    let u_p = uniform(&grid, [wind, 0.0, 0.0]);
    for _ in 0..200 {
        flow.step(0.02, &u_p, None, &[]);
    }
    // The faces across x at the inflow (i = 0), u_p + u_g.
    let d = grid.face_dims(0);
    let inflow: Vec<f32> = (0..d[2])
        .flat_map(|k| (0..d[1]).map(move |j| (j, k)))
        .map(|(j, k)| wind + flow.u_g.u[0][grid.face(0, 0, j, k)])
        .collect();
    let mean = inflow.iter().sum::<f32>() / inflow.len() as f32;
    // Beside the sphere, 5 radii across the wind from its centre.
    let beside = flow.velocity_at(&u_p, [0.5, 0.4, 0.4 + 0.75 - 0.05])[0];
    println!("a wind of 1 m/s past a sphere in an open box, 4 s: the inflow's mean u {mean:.4} m/s, beside the sphere {beside:.4} m/s");
    assert!(mean >= 0.97 * wind, "the inflow fell to {mean} m/s");
    assert!(beside >= 0.95 * wind, "beside the sphere {beside} m/s");
}

/// The cellular flow u = A(sin x cos y, −cos x sin y, 0) in the closed box [0, π]³ (k = 1),
/// stepped for 1 s at viscosity `nu`: returns the rate of its kinetic energy's decay (1/s).
fn taylor_green_rate(nu: f32, amplitude: f32) -> f32 {
    let n = 32;
    let grid = Grid::new([0.0; 3], [n; 3], PI / n as f32);
    let mut flow = Flow::new(grid.clone(), Faces::CLOSED);
    flow.viscosity = nu;
    flow.u_g = MacField::from_fn(&grid, |x| {
        [
            amplitude * x[0].sin() * x[1].cos(),
            -amplitude * x[0].cos() * x[1].sin(),
            0.0,
        ]
    });
    let still = MacField::zeros(&grid);
    let e0 = flow.u_g.kinetic_energy(&grid);
    let steps = 20;
    let dt = 1.0 / steps as f32;
    for _ in 0..steps {
        flow.step(dt, &still, None, &[]);
    }
    let e1 = flow.u_g.kinetic_energy(&grid);
    (-(e1 / e0).ln()) as f32
}

#[test]
fn a_taylor_green_flow_decays_at_its_viscous_rate() {
    // The cellular flow has |k|² = 2k² = 2: its energy decays as exp(−2ν|k|²t) = exp(−4νt).
    let nu = 0.05;
    let rate = taylor_green_rate(nu, 0.1);
    let want = 4.0 * nu;
    let error = rate / want - 1.0;
    println!(
        "Taylor–Green at ν = {nu}: decay rate {rate:.5}/s, exp(−4νt) gives {want:.5}/s ({:+.2} %)",
        100.0 * error
    );
    assert!(error.abs() <= 0.05, "decay rate off by {error}");

    // At ν = 0 the flow is steady; what decays is the scheme's own viscosity.
    let amplitude = 1.0;
    let numerical = taylor_green_rate(0.0, amplitude) / 4.0;
    let h = PI / 32.0;
    println!(
        "numerical viscosity at ν = 0, A = {amplitude} m/s, h = {h:.4} m, CFL 0.5: {numerical:.2e} m²/s ({:.2e} h·A)",
        numerical / (h * amplitude)
    );
    // Plain semi-Lagrangian advection (no correction) measures 0.20 h·A on this flow; the
    // clamped MacCormack correction 0.06 h·A.
    assert!(
        numerical < 0.12 * h * amplitude,
        "numerical viscosity {numerical}"
    );
}

#[test]
fn the_advection_carries_a_pattern_with_the_wind() {
    let n = 32;
    let grid = Grid::new([0.0; 3], [n; 3], 1.0);
    let wind = [0.6, 0.3, -0.2];
    let velocity = uniform(&grid, wind);
    let sigma = 3.0;
    let start = [10.0, 12.0, 18.0];
    let gaussian = |x: [f32; 3], c: [f32; 3]| {
        let q: f32 = (0..3).map(|a| (x[a] - c[a]).powi(2)).sum();
        (-q / (2.0 * sigma * sigma)).exp()
    };
    let centres: Vec<[f32; 3]> = (0..grid.cell_count())
        .map(|c| grid.centre(c % n, (c / n) % n, c / (n * n)))
        .collect();
    let mut q: Vec<f32> = centres.iter().map(|&x| gaussian(x, start)).collect();
    let (steps, dt) = (20, 0.5);
    for _ in 0..steps {
        let lattice = Lattice {
            values: &q,
            dims: grid.cells,
            offset: [0.5; 3],
        };
        q = maccormack(&grid, lattice, &velocity, dt);
    }
    let t = steps as f32 * dt;
    let end: [f32; 3] = std::array::from_fn(|a| start[a] + wind[a] * t);
    let mass: f32 = q.iter().sum();
    let centroid: [f32; 3] =
        std::array::from_fn(|a| q.iter().zip(&centres).map(|(v, x)| v * x[a]).sum::<f32>() / mass);
    let shift = (0..3)
        .map(|a| (centroid[a] - end[a]).powi(2))
        .sum::<f32>()
        .sqrt();
    let error = q
        .iter()
        .zip(&centres)
        .fold(0.0f32, |m, (v, &x)| m.max((v - gaussian(x, end)).abs()));
    println!(
        "a Gaussian of σ = 3 cells carried 7 cells: centroid off by {shift:.4} cells, largest error {:.2} % of its peak",
        100.0 * error
    );
    assert!(shift <= 0.05, "centroid off by {shift} cells");
    assert!(error <= 0.1, "pattern off by {error}");
}

#[test]
fn the_same_inputs_give_the_same_bytes() {
    let bytes = |faces| {
        let (mut flow, u_p) = stirred(faces);
        let temperature: Vec<f32> = (0..flow.grid.cell_count())
            .map(|c| (c % 7) as f32)
            .collect();
        flow.step(0.02, &u_p, Some(&temperature), &[]);
        flow.u_g
            .u
            .iter()
            .flatten()
            .map(|v| v.to_bits())
            .collect::<Vec<_>>()
    };
    for faces in FACES {
        assert_eq!(bytes(faces), bytes(faces));
    }
}
