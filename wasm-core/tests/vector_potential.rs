//! The field's vector potential ψ (synthesised beside u for scenes with solid objects): mode by
//! mode i k × ψ̂ = û and k·ψ̂ = 0 from the same noise; the synthesised lattice equals a naive
//! inverse DFT of ψ̂; u itself is the same bytes with or without ψ; a scene with solids gets
//! it, one without does not.

use rustfft::num_complex::Complex64;
use serde_json::json;
use windfield::field::lattice::wave_number;
use windfield::field::spectrum::SpectrumParams;
use windfield::field::{
    hermitian_potential_spectrum, hermitian_spectrum, FieldParams, TurbulentField,
};
use windfield::{Scene, Simulation};

fn params(size: [usize; 4], seed: u64) -> FieldParams {
    FieldParams {
        size,
        spectrum: SpectrumParams {
            k_inertial: 1.0,
            ..Default::default()
        },
        seed,
    }
}

#[test]
fn the_curl_of_the_potential_is_the_velocity_mode_by_mode() {
    for size in [[8, 8, 8, 8], [6, 10, 4, 8]] {
        let p = params(size, 3);
        let u = hermitian_spectrum(&p).unwrap();
        let psi = hermitian_potential_spectrum(&p).unwrap();
        let [nx, ny, nz, nt] = size;
        let mut largest = 0.0f64;
        for t in 0..nt {
            for z in 0..nz {
                for y in 0..ny {
                    for x in 0..nx {
                        let i = ((t * nz + z) * ny + y) * nx + x;
                        let k = [wave_number(x, nx), wave_number(y, ny), wave_number(z, nz)]
                            .map(|v| v as f64);
                        let s = [psi[0][i], psi[1][i], psi[2][i]];
                        let i_unit = Complex64::new(0.0, 1.0);
                        let curl = [
                            i_unit * (s[2] * k[1] - s[1] * k[2]),
                            i_unit * (s[0] * k[2] - s[2] * k[0]),
                            i_unit * (s[1] * k[0] - s[0] * k[1]),
                        ];
                        let scale: f64 = (0..3).map(|c| u[c][i].norm()).sum::<f64>() + 1e-30;
                        largest = largest.max(scale);
                        for c in 0..3 {
                            assert!(
                                (curl[c] - u[c][i]).norm() <= 1e-6 * scale,
                                "{size:?} k {k:?} component {c}"
                            );
                        }
                        let div: Complex64 = (0..3).map(|c| s[c] * k[c]).sum();
                        assert!(div.norm() <= 1e-6 * scale, "k·ψ̂ at {k:?}");
                    }
                }
            }
        }
        assert!(largest > 0.0);
    }
}

#[test]
fn the_synthesised_potential_is_the_inverse_dft_of_its_spectrum_and_u_is_unchanged() {
    for size in [[8, 4, 8, 4], [6, 10, 4, 8]] {
        let p = params(size, 7);
        let with = TurbulentField::generate_with_potential(&p).unwrap();
        let without = TurbulentField::generate(&p).unwrap();
        assert_eq!(
            with.data, without.data,
            "u is the same bytes with ψ beside it"
        );
        assert!(without.potential.is_none());
        let psi = with.potential.as_ref().unwrap();
        let spectrum = hermitian_potential_spectrum(&p).unwrap();
        let [nx, ny, nz, nt] = size;
        let n = nx * ny * nz * nt;
        let coords = |i: usize| [i % nx, i / nx % ny, i / (nx * ny) % nz, i / (nx * ny * nz)];
        let (mut max_err, mut max_val) = (0.0f64, 0.0f64);
        for xi in 0..n {
            let x = coords(xi);
            for (c, sc) in spectrum.iter().enumerate() {
                let mut sum = Complex64::new(0.0, 0.0);
                for (ki, v) in sc.iter().enumerate() {
                    if v.norm_sqr() == 0.0 {
                        continue;
                    }
                    let k = coords(ki);
                    let phase: f64 = (0..4)
                        .map(|a| {
                            std::f64::consts::TAU * wave_number(k[a], size[a]) as f64 * x[a] as f64
                                / size[a] as f64
                        })
                        .sum();
                    sum += v * Complex64::from_polar(1.0, phase);
                }
                assert!(sum.im.abs() < 1e-12);
                max_err = max_err.max((psi[3 * xi + c] as f64 - sum.re).abs());
                max_val = max_val.max(sum.re.abs());
            }
        }
        assert!(
            max_val > 0.01 && max_err < 1e-5 * max_val,
            "{size:?}: {max_err} of {max_val}"
        );
    }
}

#[test]
fn only_a_scene_with_solids_synthesises_the_potential() {
    let scene = |solid: bool| {
        Scene::from_value(json!({
            "version": 1,
            "field": {"size": [8, 8, 8, 8], "spectrum": {"k_inertial": 2}},
            "render": {"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 0.3,
                                    "color": [1, 1, 1], "solid": solid}]}
        }))
        .unwrap()
    };
    assert!(Simulation::new(scene(true))
        .unwrap()
        .field()
        .unwrap()
        .potential
        .is_some());
    assert!(Simulation::new(scene(false))
        .unwrap()
        .field()
        .unwrap()
        .potential
        .is_none());
    // A field without ψ is refused for a scene with solids.
    let plain = TurbulentField::generate(&scene(true).field_params()).unwrap();
    let e = Simulation::with_field(scene(true), Some(std::sync::Arc::new(plain))).unwrap_err();
    assert_eq!(e.path, "field");
}
