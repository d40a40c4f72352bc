//! The body forces of the paper's Eq. 1 (per unit mass, m/s²): the Boussinesq buoyancy
//! b = −β T g of the gas's heat (β in 1/K, T the temperature excess in K on the cells' centres,
//! g in m/s²), averaged onto each face from its two cells; and a force splat, a Gaussian of
//! force a few cells wide (a stir's push). Each adds dt times the force to the face velocities:
//! one or two reads and a multiply-add per face.

use super::grid::Grid;
use super::mac::MacField;

/// A force splat: `force` (m/s²) at `centre` (m), falling off as exp(−|x − centre|²/radius²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Splat {
    /// Its centre, m.
    pub centre: [f32; 3],
    /// Its width, m.
    pub radius: f32,
    /// The force per unit mass at its centre, m/s².
    pub force: [f32; 3],
}

/// Adds dt·b, b = −β T g, to `u` (m/s): `temperature` the excess over the ambient air (K) on
/// the cells, `beta` in 1/K, `gravity` in m/s², `dt` in s. A box face takes its one cell's T.
pub fn add_buoyancy(
    grid: &Grid,
    u: &mut MacField,
    temperature: &[f32],
    beta: f32,
    gravity: [f32; 3],
    dt: f32,
) {
    assert_eq!(
        temperature.len(),
        grid.cell_count(),
        "a temperature per cell"
    );
    let n = grid.cells;
    for (a, comp) in u.u.iter_mut().enumerate() {
        let g = gravity[a];
        if g == 0.0 {
            continue;
        }
        let d = grid.face_dims(a);
        for k in 0..d[2] {
            for j in 0..d[1] {
                for i in 0..d[0] {
                    let idx = [i, j, k];
                    let at = |m: usize| {
                        let mut c = idx;
                        c[a] = m;
                        temperature[grid.cell(c[0], c[1], c[2])]
                    };
                    let s = idx[a];
                    let t = if s == 0 {
                        at(0)
                    } else if s == n[a] {
                        at(n[a] - 1)
                    } else {
                        0.5 * (at(s - 1) + at(s))
                    };
                    comp[grid.face(a, i, j, k)] -= dt * beta * t * g;
                }
            }
        }
    }
}

/// Adds dt times the splat's force to `u` (m/s) on the faces within four widths of its centre.
pub fn add_splat(grid: &Grid, u: &mut MacField, splat: &Splat, dt: f32) {
    let r2 = splat.radius * splat.radius;
    let reach = 4.0 * splat.radius;
    for (a, comp) in u.u.iter_mut().enumerate() {
        if splat.force[a] == 0.0 {
            continue;
        }
        let d = grid.face_dims(a);
        let o = Grid::offset(a);
        let range: [(usize, usize); 3] = std::array::from_fn(|b| {
            let lo = (splat.centre[b] - reach - grid.origin[b]) / grid.h - o[b];
            let hi = (splat.centre[b] + reach - grid.origin[b]) / grid.h - o[b];
            let lo = lo.ceil().max(0.0) as usize;
            let hi = (hi.floor().max(-1.0) + 1.0) as usize;
            (lo.min(d[b]), hi.min(d[b]))
        });
        for k in range[2].0..range[2].1 {
            for j in range[1].0..range[1].1 {
                for i in range[0].0..range[0].1 {
                    let x = grid.face_position(a, i, j, k);
                    let q: f32 = (0..3).map(|b| (x[b] - splat.centre[b]).powi(2)).sum();
                    comp[grid.face(a, i, j, k)] += dt * splat.force[a] * (-q / r2).exp();
                }
            }
        }
    }
}
