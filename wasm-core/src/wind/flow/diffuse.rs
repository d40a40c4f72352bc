//! Viscosity, the ν∇²u_g term of the paper's Eq. 1 (ν in m²/s): explicit (forward Euler) steps
//! of the seven-point Laplacian on each component's faces, as many substeps as keep
//! ν·dt_sub/h² ≤ 1/8 (forward Euler in 3-D is stable up to 1/6). At air's ν = 1.5e-5 m²/s and
//! a 5 cm cell one substep holds for 20 s, so a step costs 7 samples and one update per face;
//! a large ν costs proportionally more substeps.
//!
//! The conditions hold on the whole wind u = u_p + u_g (u_p the primitives' wind, whose own
//! Laplacian is not added: it is given). A free face's neighbours in the stencil are:
//!
//! - beyond the box's faces and along the lattice's ends, the sample itself (zero normal
//!   derivative: free slip along closed walls, free outflow through open ones);
//! - across its own axis, a fixed face (a solid's or a closed wall's): the normal velocity v·n
//!   that face carries;
//! - along the other two axes, a face of a solid cell, a ghost value across the surface
//!   halfway between them: 2v − u for a no-slip solid (so u = v on the surface), u for a
//!   slipping one (no shear).
//!
//! Fixed faces are left as they are (the projection's step sets them). The stencil's error is
//! of order h² in the fluid (a wave of k loses (4/h²)·sin²(kh/2) in place of k²) and of order h
//! at a staircase surface.

use super::boundary::{FaceKind as Face, FaceKinds};
use super::grid::Grid;
use super::mac::MacField;
use crate::scene::limits::FLOW_VISCOSITY_STEP;

/// The largest ν·dt/h² of one substep (the scene's budget counts the same substeps).
const STABLE: f32 = FLOW_VISCOSITY_STEP as f32;

/// `u` (u_g, m/s) after ν∇²(u_p + u_g) has acted for `dt` (s) at viscosity `nu` (m²/s), `u_p`
/// the primitives' wind on the faces (m/s).
pub fn diffuse(grid: &Grid, kinds: &FaceKinds, u_p: &MacField, u: &mut MacField, nu: f32, dt: f32) {
    if nu <= 0.0 || dt <= 0.0 {
        return;
    }
    let r = nu * dt / (grid.h * grid.h);
    let substeps = (r / STABLE).ceil().max(1.0) as usize;
    let r = r / substeps as f32;
    for a in 0..3 {
        let d = grid.face_dims(a);
        let kind = &kinds.kind[a];
        let interior = &kinds.interior[a];
        let up = &u_p.u[a];
        let stride = [1, d[0], d[0] * d[1]];
        for _ in 0..substeps {
            let old = u.u[a].clone();
            let new = &mut u.u[a];
            // The steps to a face's neighbours below and above along an axis, 0 beyond the
            // lattice's ends (where the stencil reads the face itself).
            let steps = |i: usize, b: usize| {
                let st = stride[b];
                [
                    if i > 0 { st } else { 0 },
                    if i + 1 < d[b] { st } else { 0 },
                ]
            };
            for k in 0..d[2] {
                let dz = steps(k, 2);
                for j in 0..d[1] {
                    let dy = steps(j, 1);
                    let row = d[0] * (j + d[1] * k);
                    let n = d[0];
                    if n > 2 {
                        // The row's faces between its ends where the stencil reads free faces
                        // only: the same sum over slices, two selects and no branch.
                        let at = |o: usize| &old[o..][..n];
                        let (centre, ys, zs) = (
                            at(row),
                            [at(row - dy[0]), at(row + dy[1])],
                            [at(row - dz[0]), at(row + dz[1])],
                        );
                        let cells = (new[row + 1..row + n - 1].iter_mut())
                            .zip(&interior[row + 1..row + n - 1])
                            .zip(centre.iter().zip(&centre[1..]).zip(&centre[2..]))
                            .zip(ys[0][1..].iter().zip(&ys[1][1..]))
                            .zip(zs[0][1..].iter().zip(&zs[1][1..]));
                        for ((((out, &inside), ((&xm, &o), &xp)), (&ym, &yp)), (&zm, &zp)) in cells
                        {
                            let lap = 0.0
                                + (xm + xp - 2.0 * o)
                                + (ym + yp - 2.0 * o)
                                + (zm + zp - 2.0 * o);
                            let v = o + r * lap;
                            *out = if inside { v } else { *out };
                        }
                    }
                    for i in 0..d[0] {
                        let s = row + i;
                        if interior[s] && i > 0 && i + 1 < n {
                            continue;
                        }
                        if kind[s] != Face::Free {
                            continue;
                        }
                        let idx = [i, j, k];
                        // The neighbour `m` across axis `b`'s value of u_g.
                        let neighbour = |m: usize, b: usize| match kind[m] {
                            Face::Free => old[m],
                            Face::Fixed { v, .. } if b == a => v - up[m],
                            Face::Fixed { v, holds: true } => 2.0 * v - up[s] - old[s] - up[m],
                            Face::Fixed { holds: false, .. } => old[s],
                        };
                        let mut lap = 0.0;
                        for b in 0..3 {
                            let below = if idx[b] > 0 {
                                neighbour(s - stride[b], b)
                            } else {
                                old[s]
                            };
                            let above = if idx[b] + 1 < d[b] {
                                neighbour(s + stride[b], b)
                            } else {
                                old[s]
                            };
                            lap += below + above - 2.0 * old[s];
                        }
                        new[s] = old[s] + r * lap;
                    }
                }
            }
        }
    }
}
