//! The flow (the paper's Eqs. 1–2 on a coarse grid) behind a bluff body: a uniform wind U past a
//! solid cylinder of diameter D, its axis across the wind, leaves a von Kármán vortex street,
//! and the cross-wind velocity two diameters behind it oscillates at the shedding frequency f,
//! a Strouhal number St = fD/U of about 0.2 from Re = UD/ν ≈ 300 to 10⁵ (Roshko 1954, "On the
//! development of turbulent wakes from vortex streets", NACA Report 1191; Williamson 1996,
//! "Vortex dynamics in the cylinder wake", Annu. Rev. Fluid Mech. 28), 0.15–0.25 asked here.
//!
//! The box (cells of h = 5 cm): 10 D along the wind, 6 D across it, 3 cells along the
//! cylinder's axis. The two layers at the ends of the axis are slipping solids at rest (planes
//! of symmetry, so the one layer of air between them is a two-dimensional flow), or the box is
//! that one layer with its faces across the axis closed (walls the air slips along, as a
//! scene's `flow.faces` `{"z": "closed"}` says); the wind enters either as a first layer of
//! solid cells moving at U or through the box's open face, and the box's other faces are open. The cylinder is no-slip, 8 cells across, at Re = 5,000;
//! the advection's own viscosity (about 0.06 h·U, `flow.rs`) brings the effective Re nearer 130.

use windfield::wind::flow::{Faces, Flow, Grid, MacField};

/// The cells' edge, m.
const H: f32 = 0.05;
/// The wind, m/s.
const WIND: f32 = 1.0;
/// The cylinder's diameter, 8 cells, m.
const DIAMETER: f32 = 8.0 * H;
/// The Reynolds number UD/ν.
const REYNOLDS: f32 = 5000.0;

/// The amplitude of the Hann-windowed discrete Fourier transform of the mean-removed `signal`
/// (sampled every `dt` s) at the Strouhal number `st` (frequency st·U/D), in the signal's units.
fn amplitude(signal: &[f32], dt: f32, st: f32) -> f64 {
    let n = signal.len();
    let mean = signal.iter().map(|&v| f64::from(v)).sum::<f64>() / n as f64;
    let omega = 2.0 * std::f64::consts::PI * f64::from(st * WIND / DIAMETER * dt);
    let (mut c, mut s, mut weight) = (0.0, 0.0, 0.0);
    for (m, &v) in signal.iter().enumerate() {
        let hann = 0.5 - 0.5 * (2.0 * std::f64::consts::PI * m as f64 / (n - 1) as f64).cos();
        let x = hann * (f64::from(v) - mean);
        c += x * (omega * m as f64).cos();
        s += x * (omega * m as f64).sin();
        weight += hann;
    }
    2.0 * (c * c + s * s).sqrt() / weight
}

/// The Strouhal number of the signal's upward crossings of its mean: their count less one over
/// the time between the first and the last (each crossing's time interpolated linearly).
fn crossing_strouhal(signal: &[f32], dt: f32) -> f32 {
    let mean = signal.iter().sum::<f32>() / signal.len() as f32;
    let times: Vec<f32> = signal
        .windows(2)
        .enumerate()
        .filter(|(_, w)| w[0] < mean && w[1] >= mean)
        .map(|(m, w)| (m as f32 + (mean - w[0]) / (w[1] - w[0])) * dt)
        .collect();
    match times.as_slice() {
        [first, .., last] => (times.len() - 1) as f32 / (last - first) * DIAMETER / WIND,
        _ => 0.0,
    }
}

/// What holds the air at the ends of the cylinder's axis.
#[derive(Clone, Copy, PartialEq)]
enum Ends {
    /// Two layers of slipping solid cells inside an open box.
    SlippingPlates,
    /// The box's own faces across the axis, closed.
    ClosedFaces,
}

/// The street behind the cylinder, the wind entering through a solid layer moving at U
/// (`moving_inflow`) or through the box's open face, the axis's `ends` held as they say: its
/// measures 2 D behind, printed under `case` and held to a regular street at St 0.15–0.25.
fn sheds_a_regular_street(case: &str, moving_inflow: bool, ends: Ends) {
    let plates = ends == Ends::SlippingPlates;
    let cells = [80, 48, if plates { 3 } else { 1 }];
    let grid = Grid::new([0.0; 3], cells, H);
    let width = cells[1] as f32 * H;
    let depth = cells[2] as f32 * H;
    let centre = [3.0 * DIAMETER, 0.5 * width];
    let radius = 0.5 * DIAMETER;
    let faces = Faces {
        closed: [false, false, !plates],
    };
    let mut flow = Flow::new(grid.clone(), faces);
    flow.viscosity = WIND * DIAMETER / REYNOLDS;
    flow.solids.add(&grid, [0.0; 3], |x| {
        (x[0] - centre[0]).powi(2) + (x[1] - centre[1]).powi(2) < radius * radius
    });
    if moving_inflow {
        flow.solids.add(&grid, [WIND, 0.0, 0.0], |x| x[0] < H);
    }
    if plates {
        flow.solids
            .add_slipping(&grid, [0.0; 3], |x| x[2] < H || x[2] > depth - H);
    }
    let u_p = MacField::from_fn(&grid, |_| [WIND, 0.0, 0.0]);
    // The symmetry broken once: a cross-wind push of 0.05 U over a diameter of the near wake.
    flow.u_g = MacField::from_fn(&grid, |x| {
        let behind = x[0] > centre[0] && x[0] < centre[0] + DIAMETER;
        let near = (x[1] - centre[1]).abs() < DIAMETER;
        [0.0, if behind && near { 0.05 * WIND } else { 0.0 }, 0.0]
    });
    let probe = [centre[0] + 2.0 * DIAMETER, centre[1], 0.5 * depth];

    // A CFL number of 0.5 at U; 60 D/U in all, the street grown by 25 D/U, 35 D/U measured
    // (about 7 periods).
    let dt = 0.5 * H / WIND;
    let time = |d_over_u: f32| (d_over_u * DIAMETER / WIND / dt).round() as usize;
    let mut cross_wind = Vec::new();
    for n in 1..=time(60.0) {
        flow.step(dt, &u_p, None, &[]);
        if n > time(25.0) {
            cross_wind.push(flow.velocity_at(&u_p, probe)[1]);
        }
    }

    let spectrum: Vec<(f32, f64)> = (20..=600)
        .map(|k| k as f32 * 0.001)
        .map(|st| (st, amplitude(&cross_wind, dt, st)))
        .collect();
    let (strouhal, peak) =
        spectrum
            .iter()
            .copied()
            .fold((0.0, 0.0), |best, s| if s.1 > best.1 { s } else { best });
    // The next strongest line away from the peak (beyond a quarter of its frequency).
    let rival = spectrum
        .iter()
        .filter(|(st, _)| (st - strouhal).abs() > 0.25 * strouhal)
        .fold(0.0f64, |m, s| m.max(s.1));
    let crossings = crossing_strouhal(&cross_wind, dt);
    let mean = cross_wind.iter().sum::<f32>() / cross_wind.len() as f32;
    let rms = (cross_wind.iter().map(|v| (v - mean).powi(2)).sum::<f32>()
        / cross_wind.len() as f32)
        .sqrt();
    println!(
        "{case}: cylinder of {} cells at Re {REYNOLDS}, 2 D behind it: St = {strouhal:.3} (spectral peak), {crossings:.3} (mean crossings); cross-wind amplitude {:.2} U at the peak, rms {:.2} U; the next line {:.2} of the peak",
        DIAMETER / H,
        peak / f64::from(WIND),
        rms / WIND,
        rival / peak,
    );
    assert!(rms >= 0.2 * WIND, "no wake oscillation: rms v {rms} m/s");
    assert!(
        peak >= 0.2 * f64::from(WIND),
        "no shedding line: {peak} m/s"
    );
    assert!(
        rival <= 0.25 * peak,
        "no dominant line: {rival} m/s beside {peak} m/s"
    );
    assert!(
        (0.15..=0.25).contains(&strouhal),
        "Strouhal number {strouhal} (spectral peak)"
    );
    assert!(
        (crossings - strouhal).abs() <= 0.02,
        "Strouhal number {crossings} (mean crossings) against {strouhal} (spectral peak)"
    );
}

#[test]
fn a_wind_past_a_cylinder_sheds_vortices_at_a_strouhal_number_near_0_2() {
    sheds_a_regular_street("inflow a layer moving at U", true, Ends::SlippingPlates);
}

/// The wind as a scene's flow takes it: u_p through the open faces, nothing moving at the
/// inflow.
#[test]
fn a_wind_through_an_open_face_sheds_as_well() {
    sheds_a_regular_street("inflow through the open face", false, Ends::SlippingPlates);
}

/// The same between the box's own closed faces across the axis, the others open: the ends a
/// scene's `flow.faces` gives a post (its cylinder-wake preset's).
#[test]
fn a_wind_between_closed_faces_sheds_as_well() {
    sheds_a_regular_street("between closed faces", false, Ends::ClosedFaces);
}
