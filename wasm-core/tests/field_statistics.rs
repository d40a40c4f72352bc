//! The synthesised field against the paper's formulas (docs/FORMATS.md, statistics), fixed seeds throughout.

use rustfft::num_complex::Complex64;
use windfield::field::lattice::wave_number;
use windfield::field::spectrum::{SpectrumLaw, SpectrumParams};
use windfield::field::statistics::{analyse, FieldStats};
use windfield::field::{hermitian_spectrum, FieldParams, TurbulentField};

fn params(size: [usize; 4], spectrum: SpectrumParams, seed: u64) -> FieldParams {
    FieldParams {
        size,
        spectrum,
        seed,
    }
}

fn stats_for(p: &FieldParams) -> FieldStats {
    let f = TurbulentField::generate(p).unwrap();
    analyse(&f, &p.spectrum)
}

/// Every output value against Σ û exp(+i(k·x + ωt)) in f64, where û is the spectrum the
/// synthesis filters; returns the largest error and the largest value.
fn naive_inverse_dft_error(p: &FieldParams) -> (f64, f64) {
    let spectrum = hermitian_spectrum(p).unwrap();
    let field = TurbulentField::generate(p).unwrap();
    let [nx, ny, nz, nt] = p.size;
    let n = nx * ny * nz * nt;
    let coords = |i: usize| [i % nx, i / nx % ny, i / (nx * ny) % nz, i / (nx * ny * nz)];
    let mut max_err = 0.0f64;
    let mut max_val = 0.0f64;
    for xi in 0..n {
        let x = coords(xi);
        for (c, sc) in spectrum.iter().enumerate() {
            let mut sum = Complex64::new(0.0, 0.0);
            for (ki, u) in sc.iter().enumerate() {
                if u.norm_sqr() == 0.0 {
                    continue;
                }
                let k = coords(ki);
                let phase: f64 = (0..4)
                    .map(|a| {
                        let na = p.size[a];
                        std::f64::consts::TAU * wave_number(k[a], na) as f64 * x[a] as f64
                            / na as f64
                    })
                    .sum();
                sum += u * Complex64::from_polar(1.0, phase);
            }
            // Hermitian spectrum: the naive sum is real.
            assert!(sum.im.abs() < 1e-12, "imaginary part {}", sum.im);
            let got = field.data[3 * xi + c] as f64;
            max_err = max_err.max((got - sum.re).abs());
            max_val = max_val.max(sum.re.abs());
        }
    }
    (max_err, max_val)
}

#[test]
fn synthesis_equals_naive_inverse_dft_of_its_spectrum() {
    // Tiny anisotropic lattices, powers of two and not (each extent even, 2 mod 4 included).
    for size in [[8, 4, 8, 4], [6, 10, 4, 8], [10, 6, 6, 12], [4, 4, 14, 6]] {
        let p = params(
            size,
            SpectrumParams {
                k_inertial: 1.0,
                ..Default::default()
            },
            7,
        );
        let (max_err, max_val) = naive_inverse_dft_error(&p);
        assert!(max_val > 0.1, "{size:?}: field should not be empty");
        assert!(
            max_err < 1e-5 * max_val,
            "{size:?}: max error {max_err} of {max_val}"
        );
    }
}

#[test]
fn spectrum_is_hermitian_and_zero_on_nyquist_planes_and_k0() {
    for size in [[8, 8, 8, 8], [6, 10, 4, 8]] {
        let p = params(
            size,
            SpectrumParams {
                k_inertial: 1.0,
                ..Default::default()
            },
            3,
        );
        let s = hermitian_spectrum(&p).unwrap();
        let [nx, ny, nz, nt] = size;
        let index = |x: usize, y: usize, z: usize, t: usize| ((t * nz + z) * ny + y) * nx + x;
        let neg = |i: usize, n: usize| (n - i) % n;
        for t in 0..nt {
            for z in 0..nz {
                for y in 0..ny {
                    for x in 0..nx {
                        let i = index(x, y, z, t);
                        let j = index(neg(x, nx), neg(y, ny), neg(z, nz), neg(t, nt));
                        let nyquist = x == nx / 2 || y == ny / 2 || z == nz / 2 || t == nt / 2;
                        for c in s.iter() {
                            assert!((c[i] - c[j].conj()).norm() < 1e-15);
                            if nyquist || (x == 0 && y == 0 && z == 0) {
                                assert_eq!(c[i].norm(), 0.0);
                            }
                        }
                        // Divergence-free mode by mode: k·û = 0.
                        let k = [wave_number(x, nx), wave_number(y, ny), wave_number(z, nz)];
                        let div: Complex64 = (0..3).map(|c| s[c][i] * k[c] as f64).sum();
                        let size: f64 = (0..3).map(|c| s[c][i].norm()).sum();
                        assert!(div.norm() <= 1e-6 * size * 8.0, "k·û at {k:?}");
                    }
                }
            }
        }
    }
}

#[test]
fn kolmogorov_slope_over_the_inertial_range_averaged_over_seeds() {
    let mut slopes = Vec::new();
    for seed in 1..=4 {
        let st = stats_for(&params([32; 4], SpectrumParams::default(), seed));
        slopes.push(st.slope.unwrap());
    }
    let mean = slopes.iter().sum::<f64>() / slopes.len() as f64;
    assert!(
        (mean + 5.0 / 3.0).abs() < 0.1,
        "mean slope {mean} ({slopes:?})"
    );
}

/// The statistics of docs/FORMATS.md on a lattice whose extents are not powers of two (48 = 2⁴·3),
/// averaged over seeds: slope, energy, divergence, components, mean and temporal spread.
#[test]
fn statistics_on_a_48x48x48x16_lattice_averaged_over_seeds() {
    let seeds = 1..=4u64;
    let reports: Vec<FieldStats> = seeds
        .map(|seed| stats_for(&params([48, 48, 48, 16], SpectrumParams::default(), seed)))
        .collect();
    let count = reports.len() as f64;
    let mean_of = |f: &dyn Fn(&FieldStats) -> f64| reports.iter().map(f).sum::<f64>() / count;
    let slope = mean_of(&|st| st.slope.unwrap());
    assert!((slope + 5.0 / 3.0).abs() < 0.1, "mean slope {slope}");
    assert_eq!(reports[0].fit_range, [5, 23]);
    let energy = mean_of(&|st| st.energy_ratio);
    assert!((energy - 1.0).abs() < 0.05, "mean energy ratio {energy}");
    let mut components = [0.0; 3];
    for st in &reports {
        assert!(
            st.divergence_ratio < 1e-10,
            "divergence {}",
            st.divergence_ratio
        );
        for (total, e) in components.iter_mut().zip(st.component_energy) {
            *total += e;
        }
        for m in st.mean {
            assert!(m.abs() < 1e-6 * st.rms_speed, "mean {:?}", st.mean);
        }
    }
    let average = components.iter().sum::<f64>() / 3.0;
    for c in components {
        assert!(
            (c / average - 1.0).abs() < 0.05,
            "components {components:?}"
        );
    }
    // nt = 16 cuts the Gaussian of std kσ at the Nyquist ω: the measured spread follows the
    // lattice-normalised G_k, shell by shell.
    for shell in 5..=20 {
        let measured = mean_of(&|st| {
            st.shells
                .iter()
                .find(|s| s.k == shell)
                .unwrap()
                .temporal_spread
        });
        let expected = reports[0]
            .shells
            .iter()
            .find(|s| s.k == shell)
            .unwrap()
            .temporal_spread_expected;
        assert!(
            (measured / expected - 1.0).abs() < 0.1,
            "shell {shell}: spread {measured} vs {expected}"
        );
    }
}

#[test]
fn paper_literal_law_has_its_own_slope() {
    let sp = SpectrumParams {
        law: SpectrumLaw::PaperLiteral,
        ..Default::default()
    };
    let st = stats_for(&params([32; 4], sp, 2));
    assert!(
        (st.slope.unwrap() + 2.5).abs() < 0.1,
        "slope {:?}",
        st.slope
    );
}

#[test]
fn energy_matches_the_lattice_sum_of_the_law() {
    for (size, sp) in [
        ([32; 4], SpectrumParams::default()),
        (
            [16, 32, 16, 8],
            SpectrumParams {
                epsilon: 3.0,
                k_inertial: 2.0,
                sigma: 0.5,
                ..Default::default()
            },
        ),
        (
            [32, 32, 32, 16],
            SpectrumParams {
                sigma: 0.0,
                ..Default::default()
            },
        ),
    ] {
        let st = stats_for(&params(size, sp, 11));
        // Independent recomputation of Σ E(|k|)/(4π|k|²) over non-Nyquist spatial modes.
        let mut expected = 0.0;
        for z in 0..size[2] {
            for y in 0..size[1] {
                for x in 0..size[0] {
                    if x == size[0] / 2 || y == size[1] / 2 || z == size[2] / 2 {
                        continue;
                    }
                    let k2 = [(x, size[0]), (y, size[1]), (z, size[2])]
                        .iter()
                        .map(|&(i, n)| (wave_number(i, n) as f64).powi(2))
                        .sum::<f64>();
                    if k2 > 0.0 {
                        expected +=
                            sp.energy_spectrum(k2.sqrt()) / (4.0 * std::f64::consts::PI * k2);
                    }
                }
            }
        }
        assert!((st.energy_expected / expected - 1.0).abs() < 1e-12);
        assert!(
            (st.energy_ratio - 1.0).abs() < 0.05,
            "{size:?}: ratio {}",
            st.energy_ratio
        );
    }
}

#[test]
fn divergence_free_to_float_rounding() {
    let st = stats_for(&params([32, 16, 32, 8], SpectrumParams::default(), 5));
    assert!(st.divergence_ratio < 1e-10, "ratio {}", st.divergence_ratio);
}

#[test]
fn components_carry_equal_energy_and_zero_mean() {
    let mut comp = [0.0; 3];
    for seed in 1..=3 {
        let st = stats_for(&params([32; 4], SpectrumParams::default(), seed));
        for (total, e) in comp.iter_mut().zip(st.component_energy) {
            *total += e;
        }
        for m in st.mean {
            assert!(m.abs() < 1e-6 * st.rms_speed, "mean {:?}", st.mean);
        }
    }
    let avg = comp.iter().sum::<f64>() / 3.0;
    for c in comp {
        assert!((c / avg - 1.0).abs() < 0.05, "component energies {comp:?}");
    }
}

#[test]
fn temporal_spread_per_shell_follows_k_sigma() {
    // nt = 64 keeps the Gaussian of std kσ well inside the lattice's ω range.
    let sp = SpectrumParams {
        sigma: 0.5,
        ..Default::default()
    };
    let st = stats_for(&params([32, 32, 32, 64], sp, 9));
    let mut checked = 0;
    for sh in st.shells.iter().filter(|s| s.k >= 5 && s.k <= 15) {
        let nominal = sh.mean_k * sp.sigma;
        assert!(
            (sh.temporal_spread / nominal - 1.0).abs() < 0.15,
            "shell {}: spread {} vs kσ {}",
            sh.k,
            sh.temporal_spread,
            nominal
        );
        checked += 1;
    }
    assert_eq!(checked, 11);
    // With σ = 1 on nt = 32 the Gaussian is cut at the Nyquist ω: the measurement follows
    // the lattice-normalised G_k in every shell.
    let st = stats_for(&params([32; 4], SpectrumParams::default(), 9));
    for sh in st.shells.iter().filter(|s| s.k >= 5 && s.k <= 15) {
        assert!(
            (sh.temporal_spread / sh.temporal_spread_expected - 1.0).abs() < 0.15,
            "shell {}: {} vs {}",
            sh.k,
            sh.temporal_spread,
            sh.temporal_spread_expected
        );
    }
}

#[test]
fn same_seed_same_bytes_other_seed_other_field() {
    let p = params([16, 16, 16, 8], SpectrumParams::default(), 42);
    let a = TurbulentField::generate(&p).unwrap();
    let b = TurbulentField::generate(&p).unwrap();
    assert_eq!(
        a.data.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
        b.data.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
    );
    let c = TurbulentField::generate(&FieldParams { seed: 43, ..p }).unwrap();
    assert_ne!(a.data, c.data);
}

#[test]
fn spectrum_parameters_filter_the_same_noise() {
    // A seed fixes the white noise: ε only rescales, it never re-draws.
    let p = params(
        [16; 4],
        SpectrumParams {
            k_inertial: 2.0,
            ..Default::default()
        },
        5,
    );
    let a = TurbulentField::generate(&p).unwrap();
    let q = FieldParams {
        spectrum: SpectrumParams {
            epsilon: 8.0,
            ..p.spectrum
        },
        ..p
    };
    let b = TurbulentField::generate(&q).unwrap();
    // E scales by ε^(2/3) = 4, so amplitudes by 2.
    for (x, y) in a.data.iter().zip(&b.data) {
        assert!((2.0 * x - y).abs() <= 1e-5 * (1.0 + y.abs()));
    }
}

#[test]
fn interpolation_is_exact_at_nodes_and_continuous_across_seams() {
    let p = params(
        [8, 16, 8, 4],
        SpectrumParams {
            k_inertial: 1.0,
            ..Default::default()
        },
        2,
    );
    let f = TurbulentField::generate(&p).unwrap();
    for &(x, y, z, t) in &[(0, 0, 0, 0), (7, 15, 7, 3), (3, 9, 1, 2)] {
        let s = f.sample_lattice([x as f64, y as f64, z as f64, t as f64]);
        assert_eq!(s, f.at(x, y, z, t));
        // One period away is the same point.
        let w = f.sample_lattice([
            x as f64 + 8.0,
            y as f64 - 16.0,
            z as f64 + 16.0,
            t as f64 - 4.0,
        ]);
        for c in 0..3 {
            assert!((w[c] - s[c]).abs() < 1e-6);
        }
    }
    // Approaching the seam x → 8 from below meets the value at x = 0.
    let near = f.sample_lattice([8.0 - 1e-7, 4.0, 2.0, 1.0]);
    let at0 = f.at(0, 4, 2, 1);
    for c in 0..3 {
        assert!((near[c] - at0[c]).abs() < 1e-5);
    }
    // Midway between nodes along t is the mean of the two (linear in each axis).
    let mid = f.sample_lattice([2.0, 3.0, 4.0, 3.5]);
    let (a, b) = (f.at(2, 3, 4, 3), f.at(2, 3, 4, 0));
    for c in 0..3 {
        assert!((mid[c] - 0.5 * (a[c] + b[c])).abs() < 1e-6);
    }
    // Field coordinates (radians): 2π is one period.
    let r = f.sample(std::f64::consts::TAU * 3.0 / 8.0, 0.0, 0.0, 0.0);
    assert_eq!(r, f.at(3, 0, 0, 0));
}

#[test]
fn every_even_extent_from_4_to_256_is_accepted() {
    let spectrum = SpectrumParams {
        k_inertial: 1.0,
        ..Default::default()
    };
    for n in (4..=256).step_by(2) {
        assert!(
            FieldParams {
                size: [n, 4, 4, 4],
                spectrum,
                ..FieldParams::default()
            }
            .validate()
            .is_ok(),
            "{n}"
        );
    }
    for n in (5..=255).step_by(2).chain([0, 2, 258, 512]) {
        let e = FieldParams {
            size: [4, 4, 4, n],
            ..FieldParams::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(e.path, "field.size[3]");
        assert_eq!(
            e.message,
            format!("must be an even number between 4 and 256 (got {n} for nt)")
        );
    }
}

/// The paper's k_inertial = 4 on lattices too small for a whole shell of it: an 8-lattice keeps
/// the modes near its corners (|k| up to √27), and only those; a 4-lattice has none that reach
/// 4, so its field is calm.
#[test]
fn the_papers_k_inertial_on_the_smallest_lattices() {
    let p = params([8, 8, 8, 8], SpectrumParams::default(), 3);
    assert!((p.validate().unwrap().max_wave_number() - 27f64.sqrt()).abs() < 1e-12);
    let spectrum = hermitian_spectrum(&p).unwrap();
    let [nx, ny, nz, nt] = p.size;
    let mut carrying = 0;
    for (i, _) in spectrum[0].iter().enumerate() {
        let k = [i % nx, i / nx % ny, i / (nx * ny) % nz];
        let k2: i64 = (0..3).map(|a| wave_number(k[a], p.size[a]).pow(2)).sum();
        let energy: f64 = spectrum.iter().map(|c| c[i].norm_sqr()).sum();
        if energy > 0.0 {
            assert!(k2 >= 16, "mode {k:?} below k_inertial carries {energy}");
            carrying += 1;
        }
    }
    assert!(
        carrying > 0 && carrying < nx * ny * nz * nt / 4,
        "{carrying} modes carry energy"
    );
    let f = TurbulentField::generate(&p).unwrap();
    assert!(
        f.data.iter().any(|&v| v != 0.0),
        "the 8-lattice's field has energy"
    );
    let calm = params([4, 4, 4, 4], SpectrumParams::default(), 3);
    assert!(!calm.spectrum.has_energy_on(&calm.validate().unwrap()));
    let f = TurbulentField::generate(&calm).unwrap();
    assert!(
        f.data.iter().all(|&v| v == 0.0),
        "no mode of a 4-lattice reaches k = 4"
    );
}

#[test]
fn every_bad_parameter_is_rejected_with_its_name() {
    let good = FieldParams::default();
    let cases: Vec<(FieldParams, &str, &str)> = vec![
        (
            FieldParams {
                size: [32, 33, 32, 32],
                ..good
            },
            "field.size[1]",
            "must be an even number between 4 and 256 (got 33 for ny)",
        ),
        (
            FieldParams {
                size: [2, 32, 32, 32],
                ..good
            },
            "field.size[0]",
            "must be an even number between 4 and 256 (got 2 for nx)",
        ),
        (
            FieldParams {
                size: [32, 32, 258, 4],
                ..good
            },
            "field.size[2]",
            "must be an even number between 4 and 256 (got 258 for nz)",
        ),
        (
            FieldParams {
                size: [32, 32, 32, 0],
                ..good
            },
            "field.size[3]",
            "(got 0 for nt)",
        ),
        (
            FieldParams {
                size: [24, 24, 5, 24],
                ..good
            },
            "field.size[2]",
            "(got 5 for nz)",
        ),
        (
            FieldParams {
                size: [64, 64, 64, 66],
                ..good
            },
            "field.size",
            "nx*ny*nz*nt must be at most 16777216 lattice points (64^4) to stay within memory (got 17301504)",
        ),
        (
            FieldParams {
                size: [256, 256, 256, 4],
                ..good
            },
            "field.size",
            "at most 16777216",
        ),
        (
            FieldParams {
                spectrum: SpectrumParams {
                    epsilon: 0.0,
                    ..good.spectrum
                },
                ..good
            },
            "field.spectrum.epsilon",
            "greater than 0",
        ),
        (
            FieldParams {
                spectrum: SpectrumParams {
                    epsilon: f64::INFINITY,
                    ..good.spectrum
                },
                ..good
            },
            "field.spectrum.epsilon",
            "finite",
        ),
        (
            FieldParams {
                spectrum: SpectrumParams {
                    k_inertial: -1.0,
                    ..good.spectrum
                },
                ..good
            },
            "field.spectrum.k_inertial",
            "greater than 0",
        ),
        (
            FieldParams {
                spectrum: SpectrumParams {
                    k_inertial: 300.0,
                    ..good.spectrum
                },
                ..good
            },
            "field.spectrum.k_inertial",
            "at most 256",
        ),
        (
            FieldParams {
                spectrum: SpectrumParams {
                    sigma: -0.1,
                    ..good.spectrum
                },
                ..good
            },
            "field.spectrum.sigma",
            "between 0 and 100",
        ),
        (
            FieldParams {
                spectrum: SpectrumParams {
                    sigma: f64::NAN,
                    ..good.spectrum
                },
                ..good
            },
            "field.spectrum.sigma",
            "finite",
        ),
        (
            FieldParams {
                seed: (1 << 53) + 1,
                ..good
            },
            "seed",
            "between 0 and",
        ),
    ];
    for (p, path, text) in cases {
        let e = TurbulentField::generate(&p).unwrap_err();
        assert_eq!(e.path, path, "{e}");
        assert!(e.message.contains(text), "{e}");
    }
}

/// A slice of the field (the explorer's and the classroom's plane) samples the lattice
/// quadrilinearly, exactly at the lattice's points, and a side over the bound is refused by
/// its name before any buffer is made (a 32-bit build could not hold 65536 × 32768 of them).
#[test]
fn a_slice_is_the_field_at_its_points_and_its_size_is_bounded() {
    let p = params([8, 8, 4, 4], SpectrumParams::default(), 5);
    let f = TurbulentField::generate(&p).unwrap();
    let s = f.slice_xy(1.0, 2.0, 8, 4).unwrap();
    assert_eq!(s.len(), 3 * 8 * 4);
    for j in 0..4 {
        for i in 0..8 {
            let at = f.sample_lattice([i as f64, 2.0 * j as f64, 1.0, 2.0]);
            assert_eq!(&s[3 * (8 * j + i)..3 * (8 * j + i) + 3], &at[..]);
        }
    }
    let e = f.slice_xy(0.0, 0.0, 65536, 32768).unwrap_err();
    assert_eq!(e.path, "width");
    assert_eq!(
        e.message,
        "must be an integer between 0 and 4096 (got 65536)"
    );
    assert_eq!(f.slice_xy(0.0, 0.0, 16, 4097).unwrap_err().path, "height");
}
