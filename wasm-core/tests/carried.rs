//! Turbulence carried by the large scales (paper §7; docs/CONVENTIONS.md): in a uniform wind
//! of 1 m/s a tracer moving with the wind sees the small-scale wind stay correlated as long as
//! the field's own temporal correlation says, where without carrying it decorrelates in the
//! time the wind takes to cross an eddy; the carried field keeps the field's energy and its
//! spectrum along the flow; a blob's own carried offsets follow the same coordinates.

use glam::{Vec3, Vec3A};
use serde_json::json;
use windfield::field::lattice::wave_number;
use windfield::field::spectrum::SpectrumParams;
use windfield::wind::Wind;
use windfield::{Scene, Simulation};

const L: f64 = 4.0;
const T: f64 = 32.0;
const N: usize = 32;
const SIGMA: f64 = 0.25;
const K_INERTIAL: f64 = 2.0;
const U: f64 = 1.0;

fn scene(carried: bool, carry_time: f64) -> Scene {
    Scene::from_value(json!({
        "version": 1, "seed": 11,
        "field": {"size": [N, N, N, N], "period": [L, L, L], "time_period": T,
                  "spectrum": {"k_inertial": K_INERTIAL, "sigma": SIGMA},
                  "carried": carried, "carry_time": carry_time},
        "wind": [{"type": "uniform", "velocity": [U, 0, 0]}]
    }))
    .unwrap()
}

/// The lattice's modes with what each contributes to the small-scale wind's correlation:
/// k_x, E(|k|)/(4π|k|²) (up to the 4π) and G_k(ω) over the lattice's ω (docs/FORMATS.md).
struct Modes {
    modes: Vec<(f64, f64, Vec<f64>)>,
    omegas: Vec<f64>,
}

impl Modes {
    fn new() -> Self {
        let spectrum = SpectrumParams {
            k_inertial: K_INERTIAL,
            sigma: SIGMA,
            ..Default::default()
        };
        let omegas: Vec<f64> = (0..N)
            .filter(|&t| t != N / 2)
            .map(|t| wave_number(t, N) as f64)
            .collect();
        let mut modes = Vec::new();
        for x in 0..N {
            for y in 0..N {
                for z in 0..N {
                    if [x, y, z].contains(&(N / 2)) {
                        continue;
                    }
                    let k = [x, y, z].map(|i| wave_number(i, N) as f64);
                    let kk = (k[0] * k[0] + k[1] * k[1] + k[2] * k[2]).sqrt();
                    if kk == 0.0 || spectrum.energy_spectrum(kk) == 0.0 {
                        continue;
                    }
                    let e = spectrum.energy_spectrum(kk) / (kk * kk);
                    modes.push((k[0], e, spectrum.temporal_spread(kk, &omegas)));
                }
            }
        }
        Self { modes, omegas }
    }

    /// The correlation of the wind seen at x + (vτ, 0, 0) and time t + τ with that at (x, t):
    /// Σ over the modes of E/(4π|k|²) G_k(ω) cos(k_x·2πvτ/L + ω·2πτ/T), over their sum.
    fn correlation(&self, tau: f64, v: f64) -> f64 {
        let (mut num, mut den) = (0.0, 0.0);
        let w = std::f64::consts::TAU * tau / T;
        let temporal: Vec<f64> = self.omegas.iter().map(|o| (o * w).cos()).collect();
        for (kx, e, g) in &self.modes {
            let t: f64 = g.iter().zip(&temporal).map(|(g, c)| g * c).sum();
            num += e * (kx * std::f64::consts::TAU * v * tau / L).cos() * t;
            den += e;
        }
        num / den
    }
}

/// The lag (s) at which `r` first falls to ½, interpolated linearly between samples `dt` apart.
fn half_time(r: &[f64], dt: f64) -> f64 {
    for j in 1..r.len() {
        if r[j] <= 0.5 {
            return dt * ((j - 1) as f64 + (r[j - 1] - 0.5) / (r[j - 1] - r[j]));
        }
    }
    panic!("never fell to ½: {r:?}");
}

/// The small-scale wind (m/s) at `points` and time `t`, carried coordinates traced back through
/// the (uniform) large-scale wind.
fn small_scale(wind: &Wind, points: &[Vec3], t: f64) -> Vec<Vec3A> {
    let frame = wind.frame(t);
    let offsets = wind.carried_offsets(points, t, 1e6);
    points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let o = offsets.as_ref().map_or([Vec3A::ZERO; 2], |o| o[i]);
            frame.parts((*p).into(), o).1
        })
        .collect()
}

/// The correlation seen by tracers moving with the wind, at lags 0, dt, 2dt, …, averaged over
/// 400 tracers starting on lattice points (so that, with lags of whole cells crossed, the
/// samples are the lattice's own) and at starts spread over `spread` seconds; and the
/// small-scale wind's energy ½⟨|u|²⟩ at the starts.
fn tracer_correlation(wind: &Wind, lags: usize, dt: f64, spread: f64) -> (Vec<f64>, f64) {
    let starts = 8;
    let cell = L / N as f64;
    let mut num = vec![0.0f64; lags];
    let mut energy = 0.0f64;
    let mut count = 0;
    for s in 0..starts {
        let t0 = 3.0 + spread * s as f64 / starts as f64;
        let x0: Vec<Vec3> = (0..50)
            .map(|i| {
                let f = |k: f64| {
                    (((((s * 50 + i) as f64) + 0.5) * k).fract() * N as f64).floor() * cell
                };
                Vec3::new(
                    f(0.7548777) as f32,
                    f(0.5698403) as f32,
                    f(0.4301597) as f32,
                )
            })
            .collect();
        let first = small_scale(wind, &x0, t0);
        for (j, n) in num.iter_mut().enumerate() {
            let tau = j as f64 * dt;
            let moved: Vec<Vec3> = x0.iter().map(|p| *p + Vec3::X * (U * tau) as f32).collect();
            let later = small_scale(wind, &moved, t0 + tau);
            *n += first
                .iter()
                .zip(&later)
                .map(|(a, b)| a.dot(*b) as f64)
                .sum::<f64>();
        }
        energy += first.iter().map(|a| a.length_squared() as f64).sum::<f64>();
        count += first.len();
    }
    (
        num.iter().map(|n| n / num[0]).collect(),
        0.5 * energy / count as f64,
    )
}

/// The small scales carried by a uniform wind decorrelate along the wind's path as the field
/// does in time (τ½, the lag at which the correlation falls to ½, within 20 % of the field's
/// own), where left in place they decorrelate as the wind crosses an eddy, ℓ/U (τ½ within 20 %
/// of the spectrum's for a point moving through a frozen-in-time field at U): both times are
/// printed, and their ratio is large.
#[test]
fn carried_eddies_ride_with_the_wind_and_left_in_place_they_pass_by() {
    let modes = Modes::new();
    // Lags of a quarter second for the carried tracer, of a cell crossed (L/N/U) in place;
    // the spectrum's correlation on the same lags, half-times interpolated alike.
    let (dt_carried, dt_plain) = (0.25, L / N as f64 / U);
    let field_own: Vec<f64> = (0..60)
        .map(|j| modes.correlation(j as f64 * dt_carried, 0.0))
        .collect();
    let passing: Vec<f64> = (0..12)
        .map(|j| modes.correlation(j as f64 * dt_plain, U))
        .collect();
    let (tau_field, tau_pass) = (
        half_time(&field_own, dt_carried),
        half_time(&passing, dt_plain),
    );
    assert!(tau_field > 10.0 * tau_pass, "{tau_field} s vs {tau_pass} s");
    // Phases reset ten times more slowly than the field decorrelates, so a tracer's phase
    // mostly stays the same over τ½ (docs/CONVENTIONS.md: carried turbulence).
    let carry = 10.0 * tau_field;
    let carried = Simulation::new(scene(true, carry)).unwrap();
    let plain = Simulation::new(scene(false, carry)).unwrap();
    let (r_carried, e_carried) = tracer_correlation(&carried.wind, 40, dt_carried, carry);
    let (r_plain, e_plain) = tracer_correlation(&plain.wind, 12, dt_plain, carry);
    let (t_carried, t_plain) = (
        half_time(&r_carried, dt_carried),
        half_time(&r_plain, dt_plain),
    );
    eprintln!(
        "τ½: the field's own {tau_field:.3} s, a tracer in the carried field {t_carried:.3} s; \
         passing through the field, ℓ/U {tau_pass:.3} s, a tracer in the field in place \
         {t_plain:.3} s; ratio {:.1}",
        t_carried / t_plain
    );
    assert!(
        (t_carried / tau_field - 1.0).abs() < 0.2,
        "carried {t_carried} s vs {tau_field} s"
    );
    assert!(
        (t_plain / tau_pass - 1.0).abs() < 0.2,
        "in place {t_plain} s vs {tau_pass} s"
    );
    assert!(t_carried > 8.0 * t_plain);
    // The carried field's energy is the field's (the blend's factor 1/√(w² + (1 − w)²)).
    assert!(
        (e_carried / e_plain - 1.0).abs() < 0.05,
        "energy {e_carried} vs {e_plain}"
    );
}

/// The least-squares slope of ln E(k) against ln k over k = 2..10 of the small-scale wind
/// sampled along the flow (256 lines along x, 64 points a period) at the times `ts`.
fn slope_along_the_flow(wind: &Wind, ts: &[f64]) -> f64 {
    let m = 64;
    let mut power = vec![0.0f64; m / 2];
    for &t in ts {
        for line in 0..256 {
            let (y, z) = (
                (line % 16) as f64 * L / 16.0 + 0.1,
                (line / 16) as f64 * L / 16.0 + 0.2,
            );
            let points: Vec<Vec3> = (0..m)
                .map(|j| Vec3::new((j as f64 * L / m as f64) as f32, y as f32, z as f32))
                .collect();
            let u = small_scale(wind, &points, t);
            for (k, p) in power.iter_mut().enumerate().skip(1) {
                for c in 0..3 {
                    let (mut re, mut im) = (0.0f64, 0.0f64);
                    for (j, v) in u.iter().enumerate() {
                        let phase = std::f64::consts::TAU * (k * j) as f64 / m as f64;
                        re += v[c] as f64 * phase.cos();
                        im -= v[c] as f64 * phase.sin();
                    }
                    *p += re * re + im * im;
                }
            }
        }
    }
    let ks: Vec<(f64, f64)> = (2..=10).map(|k| ((k as f64).ln(), power[k].ln())).collect();
    let n = ks.len() as f64;
    let (mx, my) = (
        ks.iter().map(|a| a.0).sum::<f64>() / n,
        ks.iter().map(|a| a.1).sum::<f64>() / n,
    );
    ks.iter().map(|a| (a.0 - mx) * (a.1 - my)).sum::<f64>()
        / ks.iter().map(|a| (a.0 - mx).powi(2)).sum::<f64>()
}

/// The carried field sampled along the flow (a blend of two translated copies of the field)
/// has the slope the field has there, within the statistics' tolerance of 0.1, over a whole
/// cycle of the phases.
#[test]
fn the_carried_field_keeps_its_spectrum_along_the_flow() {
    let carried = Simulation::new(scene(true, 4.0)).unwrap();
    let plain = Simulation::new(scene(false, 4.0)).unwrap();
    let ts = [5.0, 6.0, 7.0, 8.0];
    let (a, b) = (
        slope_along_the_flow(&carried.wind, &ts),
        slope_along_the_flow(&plain.wind, &ts),
    );
    eprintln!("slope along the flow: carried {a}, in place {b}");
    assert!((a - b).abs() < 0.1, "slope {a} carried, {b} in place");
}

/// A blob the large-scale wind alone moves keeps the carried coordinates the wind traces back
/// (its offsets stay −U·τ of each phase), across resets.
#[test]
fn a_blob_moving_with_the_wind_keeps_its_carried_coordinates() {
    let mut s = scene(true, 0.5);
    s.field.amplitude = 0.0;
    s.field.carried = true;
    // Without a small-scale field nothing is carried: give it one too faint to move a blob.
    s.field.amplitude = 1e-9;
    s.emitters = serde_json::from_value(json!([{"center": [0, 0, 0], "rate": 50}])).unwrap();
    let mut sim = Simulation::new(s).unwrap();
    for _ in 0..120 {
        sim.step();
        let t = sim.time();
        let phases = sim.wind.phases().copied().unwrap();
        let ages = phases.ages(t);
        let b = &sim.gas.blobs;
        assert!(b.carries());
        for i in 0..b.len() {
            for (k, age) in ages.iter().enumerate() {
                let o = Vec3::from_slice(&b.carried[6 * i + 3 * k..6 * i + 3 * k + 3]);
                let want = Vec3::X * -(U * age) as f32;
                assert!(
                    (o - want).length() < 1e-4,
                    "t {t}, blob {i}, phase {k}: {o} vs {want}"
                );
            }
        }
    }
}
