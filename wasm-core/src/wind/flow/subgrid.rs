//! The statistical model of the small scales the paper's §7 names for Large Eddy Simulation:
//! Smagorinsky's (1963) eddy viscosity, the momentum the unresolved eddies carry across the
//! grid's cells, ν_t = (C_s h)² |S̄| with |S̄| = √(2 S̄_ij S̄_ij) the resolved strain rate (1/s)
//! and C_s = 0.17 (Lilly 1967), acting as a viscosity on u_g beside air's ν.
//!
//! The strain is taken from u_g's central differences at the cells' centres (u_g's face values
//! averaged to them; one-sided at the box's faces). Each free face then takes
//! dt·ν_f/h²·Σ(u_n − u_f) over its six neighbours, ν_f the mean of its two cells' ν_t (a box
//! face its one cell's); a neighbour beyond the box or on a fixed face adds nothing (no eddy
//! flux through walls). ν_t is capped at h²/(8 dt), the explicit step's stable bound, so one
//! pass always holds: where the cap binds the model mixes less than it asks.

use super::boundary::{FaceKind, FaceKinds};
use super::grid::Grid;
use super::mac::MacField;

/// Smagorinsky's constant C_s.
pub const SMAGORINSKY: f32 = 0.17;

/// ν_t (m²/s) on every cell of `grid` from u_g (m/s) `u`, capped at h²/(8 dt).
pub fn eddy_viscosity(grid: &Grid, u: &MacField, dt: f32, out: &mut Vec<f32>) {
    let n = grid.cells;
    let h = grid.h;
    let count = grid.cell_count();
    let centred = u.cell_means(grid);
    let cap = h * h / (8.0 * dt.max(f32::MIN_POSITIVE));
    let scale = (SMAGORINSKY * h).powi(2);
    out.clear();
    out.resize(count, 0.0);
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                let idx = [i, j, k];
                // g[a][b] = ∂u_a/∂x_b.
                let mut g = [[0.0f32; 3]; 3];
                for b in 0..3 {
                    let (mut lo, mut hi) = (idx, idx);
                    lo[b] = idx[b].saturating_sub(1);
                    hi[b] = (idx[b] + 1).min(n[b] - 1);
                    let span = (hi[b] - lo[b]) as f32 * h;
                    if span == 0.0 {
                        continue;
                    }
                    let ul = centred[grid.cell(lo[0], lo[1], lo[2])];
                    let uh = centred[grid.cell(hi[0], hi[1], hi[2])];
                    for a in 0..3 {
                        g[a][b] = (uh[a] - ul[a]) / span;
                    }
                }
                let mut ss = 0.0;
                for (a, row) in g.iter().enumerate() {
                    for (b, &gab) in row.iter().enumerate() {
                        let s = 0.5 * (gab + g[b][a]);
                        ss += s * s;
                    }
                }
                out[grid.cell(i, j, k)] = (scale * (2.0 * ss).sqrt()).min(cap);
            }
        }
    }
}

/// `u` (u_g, m/s) after the eddy viscosity `nu_t` (m²/s per cell) has acted for `dt` (s).
pub fn diffuse_eddies(grid: &Grid, kinds: &FaceKinds, u: &mut MacField, nu_t: &[f32], dt: f32) {
    let n = grid.cells;
    let inv_h2 = 1.0 / (grid.h * grid.h);
    for a in 0..3 {
        let d = grid.face_dims(a);
        let old = u.u[a].clone();
        let kind = &kinds.kind[a];
        let free = |f: usize| kind[f] == FaceKind::Free;
        let stride = [1, d[0], d[0] * d[1]];
        for k in 0..d[2] {
            for j in 0..d[1] {
                for i in 0..d[0] {
                    let f = grid.face(a, i, j, k);
                    if !free(f) {
                        continue;
                    }
                    let idx = [i, j, k];
                    let cell = |s: usize| {
                        let mut c = idx;
                        c[a] = s.min(n[a] - 1);
                        grid.cell(c[0], c[1], c[2])
                    };
                    let nu = if idx[a] == 0 {
                        nu_t[cell(0)]
                    } else {
                        0.5 * (nu_t[cell(idx[a] - 1)] + nu_t[cell(idx[a])])
                    };
                    if nu == 0.0 {
                        continue;
                    }
                    let mut sum = 0.0;
                    for b in 0..3 {
                        if idx[b] > 0 && free(f - stride[b]) {
                            sum += old[f - stride[b]] - old[f];
                        }
                        if idx[b] + 1 < d[b] && free(f + stride[b]) {
                            sum += old[f + stride[b]] - old[f];
                        }
                    }
                    u.u[a][f] = old[f] + dt * nu * inv_h2 * sum;
                }
            }
        }
    }
}
