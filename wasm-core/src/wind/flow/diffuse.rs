//! Viscosity, the ν∇²u_g term of the paper's Eq. 1 (ν in m²/s): explicit (forward Euler) steps
//! of the seven-point Laplacian on each component's faces, as many substeps as keep
//! ν·dt_sub/h² ≤ 1/8 (forward Euler in 3-D is stable up to 1/6). At air's ν = 1.5e-5 m²/s and
//! a 5 cm cell one substep holds for 20 s, so a step costs 7 samples and one update per face;
//! a large ν costs proportionally more substeps.
//!
//! Beyond the box's faces and along the lattice's ends the neighbour is the sample itself (zero
//! normal derivative: free slip along closed walls, free outflow through open ones). Fixed faces
//! (solids and walls) are left as they are and enter their neighbours' Laplacian as the wall's
//! value. The stencil's error is of order h² (a wave of k loses
//! (4/h²)·sin²(kh/2) in place of k²).

use super::boundary::{fixed_normal, Faces, Solids};
use super::grid::Grid;
use super::mac::MacField;

/// The largest ν·dt/h² of one substep.
const STABLE: f32 = 0.125;

/// `u` after ν∇²u has acted for `dt` (s) at viscosity `nu` (m²/s).
pub fn diffuse(grid: &Grid, solids: &Solids, faces: Faces, u: &mut MacField, nu: f32, dt: f32) {
    if nu <= 0.0 || dt <= 0.0 {
        return;
    }
    let r = nu * dt / (grid.h * grid.h);
    let substeps = (r / STABLE).ceil().max(1.0) as usize;
    let r = r / substeps as f32;
    for a in 0..3 {
        let d = grid.face_dims(a);
        let mut free = vec![false; u.u[a].len()];
        for k in 0..d[2] {
            for j in 0..d[1] {
                for i in 0..d[0] {
                    free[grid.face(a, i, j, k)] =
                        fixed_normal(grid, solids, faces, a, [i, j, k]).is_none();
                }
            }
        }
        let stride = [1, d[0], d[0] * d[1]];
        for _ in 0..substeps {
            let old = u.u[a].clone();
            for k in 0..d[2] {
                for j in 0..d[1] {
                    for i in 0..d[0] {
                        let s = grid.face(a, i, j, k);
                        if !free[s] {
                            continue;
                        }
                        let idx = [i, j, k];
                        let mut lap = 0.0;
                        for b in 0..3 {
                            let below = if idx[b] > 0 {
                                old[s - stride[b]]
                            } else {
                                old[s]
                            };
                            let above = if idx[b] + 1 < d[b] {
                                old[s + stride[b]]
                            } else {
                                old[s]
                            };
                            lap += below + above - 2.0 * old[s];
                        }
                        u.u[a][s] = old[s] + r * lap;
                    }
                }
            }
        }
    }
}
