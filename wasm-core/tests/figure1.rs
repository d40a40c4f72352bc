//! The Figure 1 demo: the grid solver of Eq. 12 conserves mass without dissipation, stays
//! non-negative and bounded at its documented stability limit, matches the closed form of a
//! diffusing, drifting square, and agrees with the blob model of the same setup.

use windfield::classroom::figure1::{Figure1, Figure1Params};

fn demo(p: Figure1Params) -> Figure1 {
    Figure1::new(p).unwrap()
}

#[test]
fn mass_is_conserved_without_dissipation() {
    let mut d = demo(Figure1Params {
        n: 64,
        ..Default::default()
    });
    let m0 = d.grid_mass();
    d.step(2.0).unwrap();
    assert!(
        ((d.grid_mass() - m0) / m0).abs() < 1e-12,
        "{} vs {m0}",
        d.grid_mass()
    );
    assert!(((d.blob_mass() - m0) / m0).abs() < 1e-12);
    // And with dissipation both follow exp(−αt).
    let mut d = demo(Figure1Params {
        n: 64,
        dissipation: 0.3,
        ..Default::default()
    });
    d.step(1.5).unwrap();
    let want = m0 * (-0.45f64).exp();
    assert!(((d.grid_mass() - want) / want).abs() < 1e-9);
    assert!(((d.blob_mass() - want) / want).abs() < 1e-12);
}

#[test]
fn at_the_stability_limit_the_grid_stays_non_negative_and_bounded() {
    for (turbulence, diffusion) in [(0.6, 0.0), (0.0, 5e-3), (0.4, 1e-3)] {
        let mut d = demo(Figure1Params {
            n: 48,
            turbulence,
            diffusion,
            ..Default::default()
        });
        for _ in 0..300 {
            let dt = d.stable_dt();
            d.grid_substep(dt);
            let (lo, hi) = d
                .rho
                .iter()
                .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
            assert!(lo >= -1e-12, "negative density {lo}");
            assert!(hi <= 1.0 + 1e-9, "new maximum {hi}");
        }
    }
}

/// A square of side a diffusing in a uniform wind: per axis, the box convolved with a
/// Gaussian of variance (κ/2)·2t = κt, shifted by the wind.
#[test]
fn a_drifting_diffusing_square_matches_the_closed_form_and_the_blobs() {
    let p = Figure1Params {
        n: 128,
        turbulence: 0.0,
        uniform: [0.0, 0.0],
        diffusion: 4e-4,
        square_center: [0.5, 0.5],
        square_size: 0.3,
        blobs_per_side: 48,
        ..Default::default()
    };
    let mut d = demo(p.clone());
    let t = 10.0;
    d.step(t).unwrap();
    let n = p.n;
    let dx = p.length / n as f64;
    let var = p.diffusion * t;
    let edge = |x: f64| {
        let s = (2.0 * var).sqrt();
        let h = p.square_size / 2.0;
        0.5 * (libm::erf((x - 0.5 + h) / s) - libm::erf((x - 0.5 - h) / s))
    };
    let blobs = d.blob_density();
    let (mut err_grid, mut err_blobs) = (0.0f64, 0.0f64);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = ((i as f64 + 0.5) * dx, (j as f64 + 0.5) * dx);
            let exact = edge(x) * edge(y);
            err_grid = err_grid.max((d.rho[j * n + i] - exact).abs());
            err_blobs = err_blobs.max((blobs[j * n + i] - exact).abs());
        }
    }
    assert!(err_grid < 0.02, "grid error {err_grid}");
    assert!(err_blobs < 0.08, "blob error {err_blobs}");
}

/// Circular-mean centroid of an n×n periodic density, in units of the domain.
fn centroid(rho: &[f64], n: usize) -> [f64; 2] {
    let mut acc = [(0.0f64, 0.0f64); 2];
    for (k, &r) in rho.iter().enumerate() {
        for (a, c) in acc.iter_mut().zip([k % n, k / n]) {
            let phase = std::f64::consts::TAU * (c as f64 + 0.5) / n as f64;
            a.0 += r * phase.cos();
            a.1 += r * phase.sin();
        }
    }
    acc.map(|(c, s)| s.atan2(c).rem_euclid(std::f64::consts::TAU) / std::f64::consts::TAU)
}

/// In turbulence the two models carry the square to the same place (centroids within a sixth of
/// its side, on coarse and fine grids alike) with strongly correlated densities. They are not
/// equal: the upwind scheme adds numerical diffusion, and the blobs start from a smoothed square.
#[test]
fn in_turbulence_the_grid_and_the_blobs_agree() {
    let gap_at = |n: usize| {
        let mut d = demo(Figure1Params {
            n,
            ..Default::default()
        });
        d.step(3.0).unwrap();
        let blobs = d.blob_density();
        let (g, b) = (centroid(&d.rho, n), centroid(&blobs, n));
        let gap = (0..2)
            .map(|a| {
                let e = (g[a] - b[a]).abs();
                e.min(1.0 - e)
            })
            .fold(0.0, f64::max);
        let dot: f64 = d.rho.iter().zip(&blobs).map(|(x, y)| x * y).sum();
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        (gap, dot / (norm(&d.rho) * norm(&blobs)))
    };
    for n in [64, 96, 192] {
        let (gap, correlation) = gap_at(n);
        assert!(gap < 0.25 / 6.0, "n = {n}: centroid gap {gap}");
        assert!(correlation > 0.8, "n = {n}: correlation {correlation}");
    }
}

#[test]
fn bad_setups_are_rejected() {
    for (p, path) in [
        (
            Figure1Params {
                n: 4,
                ..Default::default()
            },
            "n",
        ),
        (
            Figure1Params {
                length: 0.0,
                ..Default::default()
            },
            "length",
        ),
        (
            Figure1Params {
                diffusion: -1.0,
                ..Default::default()
            },
            "diffusion",
        ),
        (
            Figure1Params {
                dissipation: f64::NAN,
                ..Default::default()
            },
            "dissipation",
        ),
        (
            Figure1Params {
                blobs_per_side: 0,
                ..Default::default()
            },
            "blobs_per_side",
        ),
    ] {
        let err = Figure1::new(p).err().unwrap().to_string();
        assert!(err.starts_with(path), "{err}");
    }
}

/// A step of no finite length (∞ would sub-step for ever), a negative one or one past the
/// bound is refused by name and leaves the demo as it was.
#[test]
fn a_step_of_no_finite_length_is_refused() {
    let mut d = demo(Figure1Params {
        n: 32,
        ..Default::default()
    });
    for bad in [f64::INFINITY, f64::NAN, -1.0, 61.0] {
        let e = d.step(bad).unwrap_err();
        assert_eq!(e.path, "seconds");
        assert!(
            e.message
                .starts_with("must be a finite number between 0 and 60 (got "),
            "{}",
            e.message
        );
    }
    assert_eq!(d.time, 0.0);
    d.step(0.1).unwrap();
    assert!(d.time > 0.0);
}
