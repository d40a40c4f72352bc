//! The pressure projection, −∇p/ρ of the paper's Eq. 1 and ∇·u_g = 0 of its Eq. 2 (Stam 1999,
//! "Stable Fluids"; on the MAC grid with solid cells as in Bridson's fluid notes, §4–5): the
//! potential φ = p·dt/ρ (m²/s) of each fluid cell solves the cells' Poisson equation
//!
//!   Σ_f (φ_i − φ_j) = −h² (∇·u_g)_i,
//!
//! the sum over the cell's free faces f (j the neighbour across f, φ_j = 0 beyond an open face
//! of the box; a fixed face, of a solid or a closed wall, drops out: its flux is given), and the
//! free faces lose ∇φ = (φ_j − φ_i)/h. The system is solved by conjugate gradients
//! preconditioned with the modified incomplete Cholesky factorisation MIC(0) (τ = 0.97, as in
//! Bridson's notes) to a relative residual max|r| ≤ tolerance · max|b| (1e-5 by default: the
//! divergence left is then below 1e-4 of max|u|/h). The velocities are f32; φ, the residual
//! and every CG vector are f64, and so are the dot products (summed in cell order: the same
//! inputs give the same bytes).
//!
//! With no open face the system is singular (φ up to a constant): the mean of b over the fluid
//! cells is taken out first, which makes it solvable when the fluid is one connected region
//! (the given fluxes' imbalance, if any, is spread evenly over it).
//!
//! Cost per cell: building the system and the preconditioner (a few reads per face) only when
//! the solid cells or the box's faces changed ([`Projector`] keeps them), the divergence and
//! the gradient's subtraction once per projection, then per iteration one 7-point product
//! (branch-free: the links are stored as 1s and 0s; two lanes wide) and its dot product, the vector updates
//! fused with the preconditioner's forward sweep, and its backward sweep with the next dot
//! product, about 40 flops; MIC(0) keeps the iterations near O(n^(1/2)) of a side of n cells
//! (tens to a hundred or so at 32³–80³ from rest; a first guess extrapolated from the last two
//! steps' φ, as the flow's step gives it, takes a wind past a sphere's to about 10
//! at 32³ and 12 at 64³, where the last step's φ alone took 13 and 24).

use super::boundary::{fixed_normal, Faces, Solids};
use super::grid::Grid;
use super::mac::MacField;

/// MIC(0)'s modification: how much of the dropped fill goes back onto the diagonal.
const TAU: f64 = 0.97;
/// MIC(0)'s safety: a pivot below this fraction of its diagonal falls back to the diagonal.
const SIGMA: f64 = 0.25;

/// How a projection went.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Projection {
    /// CG iterations taken.
    pub iterations: usize,
    /// The relative residual reached, max|r| / max|b| (0 when there was nothing to project).
    pub residual: f64,
}

/// The Poisson system of the fluid cells.
#[derive(Debug, Clone, Default)]
struct System {
    /// Free faces of each cell (0 for a solid cell or a fluid cell with none).
    diag: Vec<f64>,
    /// Which faces of each cell join it to a fluid neighbour (the matrix's entry there is −1):
    /// bit a for the next cell along axis a, bit 3 + a for the previous one.
    links: Vec<u8>,
    /// The strides of the cells along x, y and z.
    stride: [usize; 3],
    /// Whether any fluid cell has an open face of the box (the system is then definite).
    definite: bool,
    /// The links to the next cell along x, y and z as 1 or 0, padded as [`Vectors`] are, so
    /// that A·s is seven multiply-adds a cell with no branch.
    next: [Vec<f64>; 3],
    /// MIC(0)'s forward sweep per cell: its inverse pivot e and e times the previous cells'
    /// along x, y and z (0 where not linked).
    lower: Vec<[f32; 4]>,
    /// MIC(0)'s backward sweep per cell: e and e² where linked to the next cell along x, y, z.
    upper: Vec<[f32; 4]>,
}

/// The bit of [`System::links`] for the next cell along `a`.
const fn plus(a: usize) -> u8 {
    1 << a
}

/// The bit of [`System::links`] for the previous cell along `a`.
const fn minus(a: usize) -> u8 {
    8 << a
}

impl System {
    fn new(grid: &Grid, solids: &Solids, faces: Faces) -> Self {
        let n = grid.cells;
        let cells = grid.cell_count();
        let stride = [1, n[0], n[0] * n[1]];
        let mut diag = vec![0.0; cells];
        let mut links = vec![0u8; cells];
        let mut definite = false;
        for k in 0..n[2] {
            for j in 0..n[1] {
                for i in 0..n[0] {
                    let c = grid.cell(i, j, k);
                    if solids.solid[c] {
                        continue;
                    }
                    let idx = [i, j, k];
                    for a in 0..3 {
                        for side in 0..2 {
                            let mut f = idx;
                            f[a] += side;
                            if fixed_normal(grid, solids, faces, a, f).is_some() {
                                continue;
                            }
                            diag[c] += 1.0;
                            let inside = f[a] > 0 && f[a] < n[a];
                            if !inside {
                                definite = true;
                            } else if side == 1 {
                                links[c] |= plus(a);
                                links[c + stride[a]] |= minus(a);
                            }
                        }
                    }
                }
            }
        }
        let pad = stride[2];
        let next = std::array::from_fn(|a| {
            let mut m = vec![0.0; cells + 2 * pad];
            for (c, &l) in links.iter().enumerate() {
                if l & plus(a) != 0 {
                    m[pad + c] = 1.0;
                }
            }
            m
        });
        let mut system = Self {
            diag,
            links,
            stride,
            definite,
            next,
            lower: Vec::new(),
            upper: Vec::new(),
        };
        system.factorise();
        system
    }

    /// The padding before and after the cells of a [`Vectors`] vector: one plane of cells,
    /// so that every neighbour's index is in range.
    fn pad(&self) -> usize {
        self.stride[2]
    }

    /// MIC(0)'s inverse pivots (Bridson's notes, fig. 4.2), in cell order, and the two sweeps'
    /// coefficients from them.
    fn factorise(&mut self) {
        let cells = self.diag.len();
        let mut e = vec![0.0f64; cells];
        for c in 0..cells {
            let d = self.diag[c];
            if d == 0.0 {
                continue;
            }
            let mut pivot = d;
            for a in 0..3 {
                if self.links[c] & minus(a) == 0 {
                    continue;
                }
                let below = c - self.stride[a];
                let p = e[below];
                let others = (self.links[below] & 7 & !plus(a)).count_ones() as f64;
                pivot -= (1.0 + TAU * others) * p * p;
            }
            if pivot < SIGMA * d {
                pivot = d;
            }
            e[c] = 1.0 / pivot.sqrt();
        }
        self.lower = (0..cells)
            .map(|c| {
                let l = self.links[c];
                let mut w = [e[c] as f32, 0.0, 0.0, 0.0];
                for a in 0..3 {
                    if l & minus(a) != 0 {
                        w[1 + a] = (e[c] * e[c - self.stride[a]]) as f32;
                    }
                }
                w
            })
            .collect();
        self.upper = (0..cells)
            .map(|c| {
                let l = self.links[c];
                let mut w = [e[c] as f32, 0.0, 0.0, 0.0];
                for a in 0..3 {
                    if l & plus(a) != 0 {
                        w[1 + a] = (e[c] * e[c]) as f32;
                    }
                }
                w
            })
            .collect();
    }

    /// A·s into `out` (padded vectors both), and s·A·s.
    fn apply(&self, s: &[f64], out: &mut [f64]) -> f64 {
        let [_, sy, sz] = self.stride;
        let pad = self.pad();
        let cells = self.diag.len();
        let [nx, ny, nz] = &self.next;
        // The product alone first (no sum through it, so that it runs two lanes wide), then
        // the dot product in two sums, of the even cells and of the odd ones.
        let centre = &s[pad..pad + cells];
        let terms = (out[pad..pad + cells].iter_mut())
            .zip(&self.diag)
            .zip(centre)
            .zip(s[pad + 1..].iter().zip(&s[pad - 1..]))
            .zip(s[pad + sy..].iter().zip(&s[pad - sy..]))
            .zip(s[pad + sz..].iter().zip(&s[pad - sz..]))
            .zip(nx[pad..].iter().zip(&nx[pad - 1..]))
            .zip(ny[pad..].iter().zip(&ny[pad - sy..]))
            .zip(nz[pad..].iter().zip(&nz[pad - sz..]));
        for (
            (((((((o, &d), &c), (&xp, &xm)), (&yp, &ym)), (&zp, &zm)), (&mxp, &mxm)), (&myp, &mym)),
            (&mzp, &mzm),
        ) in terms
        {
            *o = d * c - mxp * xp - mxm * xm - myp * yp - mym * ym - mzp * zp - mzm * zm;
        }
        let (mut even, mut odd) = (0.0, 0.0);
        let pairs = centre
            .chunks_exact(2)
            .zip(out[pad..pad + cells].chunks_exact(2));
        for (sc, v) in pairs {
            even += sc[0] * v[0];
            odd += sc[1] * v[1];
        }
        if cells % 2 == 1 {
            even += centre[cells - 1] * out[pad + cells - 1];
        }
        even + odd
    }

    /// z = M⁻¹ r by MIC(0)'s two triangular sweeps (padded vectors; `q` is scratch), and r·z.
    fn precondition(&self, r: &[f64], q: &mut [f64], z: &mut [f64]) -> f64 {
        let (nx, pad) = (self.stride[1], self.pad());
        let mut last = 0.0;
        for (row, w) in self.lower.chunks_exact(nx).enumerate() {
            let p0 = pad + row * nx;
            last = self.lower_row(w, &r[p0..p0 + nx], q, p0, last);
        }
        self.upper_sweep(r, q, z)
    }

    /// φ += α s and r −= α A s (`a_s` holding A s; padded vectors but φ) and MIC(0)'s forward
    /// sweep of the new r into `q`, a row at a time; returns max|r|.
    fn update_and_sweep(
        &self,
        alpha: f64,
        phi: &mut [f64],
        s: &[f64],
        a_s: &[f64],
        r: &mut [f64],
        q: &mut [f64],
    ) -> f64 {
        let (nx, pad) = (self.stride[1], self.pad());
        let mut worst = 0.0f64;
        let mut last = 0.0;
        let rows = self.lower.chunks_exact(nx).zip(phi.chunks_exact_mut(nx));
        for (row, (w, phi)) in rows.enumerate() {
            let p0 = pad + row * nx;
            let r = &mut r[p0..p0 + nx];
            let cells =
                (phi.iter_mut().zip(&s[p0..p0 + nx])).zip(r.iter_mut().zip(&a_s[p0..p0 + nx]));
            for ((p, &sc), (rc, &ac)) in cells {
                *p += alpha * sc;
                *rc -= alpha * ac;
                if rc.abs() > worst {
                    worst = rc.abs();
                }
            }
            last = self.lower_row(w, r, q, p0, last);
        }
        worst
    }

    /// MIC(0)'s forward sweep over the row of cells from padded index `p0` (`w` their
    /// coefficients, `r` their r): q_c = e_c (r_c + Σ e_b q_b) over the linked cells b before
    /// c, `last` the previous cell's q carried in a register (the sweep's one serial
    /// dependence), two cells at a time: the second's q from the same `last` as the first's
    /// (q_b = t_b + u_b t_a + u_b u_a last), one multiply-add of serial dependence for two
    /// cells. Returns the row's last q.
    #[inline(always)]
    fn lower_row(&self, w: &[[f32; 4]], r: &[f64], q: &mut [f64], p0: usize, last: f64) -> f64 {
        let (nx, sz) = (self.stride[1], self.stride[2]);
        let (done, rest) = q.split_at_mut(p0);
        let (below_y, below_z) = (&done[p0 - nx..][..nx], &done[p0 - sz..][..nx]);
        let (out, w, r) = (&mut rest[..nx], &w[..nx], &r[..nx]);
        let t = |i: usize| {
            let w = w[i];
            f64::from(w[0]) * r[i] + f64::from(w[2]) * below_y[i] + f64::from(w[3]) * below_z[i]
        };
        let mut last = last;
        let mut i = 0;
        while i + 2 <= nx {
            let (a, b) = (i, i + 1);
            let (ta, tb) = (t(a), t(b));
            let (ua, ub) = (f64::from(w[a][1]), f64::from(w[b][1]));
            out[a] = ta + ua * last;
            last = (tb + ub * ta) + (ub * ua) * last;
            out[b] = last;
            i += 2;
        }
        if i < nx {
            last = t(i) + f64::from(w[i][1]) * last;
            out[i] = last;
        }
        last
    }

    /// MIC(0)'s backward sweep, z_c = e_c (q_c + e_c Σ z_a) over the linked cells a after c, a
    /// row at a time from the last; returns r·z.
    fn upper_sweep(&self, r: &[f64], q: &[f64], z: &mut [f64]) -> f64 {
        let (nx, sz, pad) = (self.stride[1], self.stride[2], self.pad());
        let mut last = 0.0;
        let mut rz = [0.0; 2];
        for (row, w) in self.upper.chunks_exact(nx).enumerate().rev() {
            let p0 = pad + row * nx;
            let (head, above) = z.split_at_mut(p0 + nx);
            let (above_y, above_z) = (&above[..nx], &above[sz - nx..][..nx]);
            let out = &mut head[p0..];
            let (q, r) = (&q[p0..p0 + nx], &r[p0..p0 + nx]);
            let t = |i: usize| {
                let w = w[i];
                f64::from(w[0]) * q[i] + f64::from(w[2]) * above_y[i] + f64::from(w[3]) * above_z[i]
            };
            // Two cells at a time, as in the forward sweep ([`System::lower_row`]).
            let mut i = nx;
            while i >= 2 {
                let (a, b) = (i - 1, i - 2);
                let (ta, tb) = (t(a), t(b));
                let (ua, ub) = (f64::from(w[a][1]), f64::from(w[b][1]));
                let za = ta + ua * last;
                let zb = (tb + ub * ta) + (ub * ua) * last;
                out[a] = za;
                out[b] = zb;
                rz[0] += r[a] * za;
                rz[1] += r[b] * zb;
                last = zb;
                i -= 2;
            }
            if i == 1 {
                last = t(0) + f64::from(w[0][1]) * last;
                out[0] = last;
                rz[0] += r[0] * last;
            }
        }
        rz[0] + rz[1]
    }
}

/// The conjugate gradients' vectors, each padded with one plane of zero cells before and
/// after ([`System::pad`]).
#[derive(Debug, Clone, Default)]
struct Vectors {
    r: Vec<f64>,
    z: Vec<f64>,
    q: Vec<f64>,
    s: Vec<f64>,
    a_s: Vec<f64>,
}

/// The projection made ready for many steps: the system and its preconditioner, kept while
/// the solids and the box's faces stay as they are, and the vectors, kept between steps.
#[derive(Debug, Clone, Default)]
pub struct Projector {
    /// The solid cells, faces and grid the system was built for.
    built_for: Option<(Vec<bool>, Faces, [usize; 3])>,
    system: System,
    vectors: Vectors,
    divergence: Vec<f32>,
}

impl Projector {
    /// [`project`], the system and the preconditioner built again only when the solid cells,
    /// the faces or the grid changed since the last call.
    #[allow(clippy::too_many_arguments)]
    pub fn project(
        &mut self,
        grid: &Grid,
        solids: &Solids,
        faces: Faces,
        u_g: &mut MacField,
        tolerance: f64,
        max_iterations: usize,
        phi: &mut Vec<f64>,
    ) -> Projection {
        let current = matches!(&self.built_for,
            Some((solid, f, n)) if *f == faces && *n == grid.cells && *solid == solids.solid);
        if !current {
            self.system = System::new(grid, solids, faces);
            self.built_for = Some((solids.solid.clone(), faces, grid.cells));
            let len = grid.cell_count() + 2 * self.system.pad();
            self.vectors = Vectors {
                r: vec![0.0; len],
                z: vec![0.0; len],
                q: vec![0.0; len],
                s: vec![0.0; len],
                a_s: vec![0.0; len],
            };
        }
        let system = &self.system;
        let Vectors { r, z, q, s, a_s } = &mut self.vectors;
        let cells = grid.cell_count();
        let pad = system.pad();
        let inside = pad..pad + cells;
        let h2 = f64::from(grid.h) * f64::from(grid.h);
        u_g.divergence_into(grid, &mut self.divergence);
        let b = &mut r[inside.clone()];
        for ((bc, &d), &div) in b.iter_mut().zip(&system.diag).zip(&self.divergence) {
            *bc = if d > 0.0 { -h2 * f64::from(div) } else { 0.0 };
        }
        if !system.definite {
            let fluid = system.diag.iter().filter(|&&d| d > 0.0).count();
            if fluid > 0 {
                let mean = b.iter().sum::<f64>() / fluid as f64;
                for (bc, &d) in b.iter_mut().zip(&system.diag) {
                    if d > 0.0 {
                        *bc -= mean;
                    }
                }
            }
        }
        let scale = max_abs(b);
        if phi.len() != cells || scale == 0.0 {
            phi.clear();
            phi.resize(cells, 0.0);
        }
        let mut report = Projection::default();
        if scale > 0.0 {
            // φ on entry is the first guess: r = b − A·φ.
            for (p, &d) in phi.iter_mut().zip(&system.diag) {
                if d == 0.0 {
                    *p = 0.0;
                }
            }
            s[inside.clone()].copy_from_slice(phi);
            system.apply(s, a_s);
            let mut worst = 0.0f64;
            for (rc, &ac) in r[inside.clone()].iter_mut().zip(&a_s[inside.clone()]) {
                *rc -= ac;
                worst = worst.max(rc.abs());
            }
            report.residual = worst / scale;
            if report.residual > tolerance {
                let mut sigma = system.precondition(r, q, z);
                s.copy_from_slice(z);
                while report.iterations < max_iterations {
                    report.iterations += 1;
                    let alpha = sigma / system.apply(s, a_s);
                    // φ += α s and r −= α A s, and MIC(0)'s forward sweep of the new r.
                    let worst = system.update_and_sweep(alpha, phi, s, a_s, r, q);
                    report.residual = worst / scale;
                    if report.residual <= tolerance {
                        break;
                    }
                    let next = system.upper_sweep(r, q, z);
                    let beta = next / sigma;
                    sigma = next;
                    for (sc, &zc) in s[inside.clone()].iter_mut().zip(&z[inside.clone()]) {
                        *sc = zc + beta * *sc;
                    }
                }
            }
        }
        subtract_gradient(grid, system, faces, u_g, phi);
        report
    }
}

fn max_abs(a: &[f64]) -> f64 {
    a.iter()
        .fold(0.0f64, |m, &v| if v.abs() > m { v.abs() } else { m })
}

/// Makes `u_g` (m/s) divergence-free on the fluid cells, its fixed faces as they are (set them
/// first, [`super::boundary::impose`]), to `tolerance` in at most `max_iterations` CG
/// iterations. Returns how it went; the potential φ (m²/s) is left in `phi`, and a `phi` of
/// the grid's cells on entry (the last step's, or a guess from it) is the first guess. A [`Projector`] keeps the
/// system and its vectors from one call to the next.
pub fn project(
    grid: &Grid,
    solids: &Solids,
    faces: Faces,
    u_g: &mut MacField,
    tolerance: f64,
    max_iterations: usize,
    phi: &mut Vec<f64>,
) -> Projection {
    Projector::default().project(grid, solids, faces, u_g, tolerance, max_iterations, phi)
}

/// The free faces of `u_g` lose ∇φ: a face inside the box is free where it joins two fluid
/// cells, one on the box's faces where its cell is fluid and the face is open.
fn subtract_gradient(grid: &Grid, system: &System, faces: Faces, u_g: &mut MacField, phi: &[f64]) {
    let n = grid.cells;
    let inv_h = 1.0 / f64::from(grid.h);
    for a in 0..3 {
        let d = grid.face_dims(a);
        let st = system.stride[a];
        for k in 0..d[2] {
            for j in 0..d[1] {
                for i in 0..d[0] {
                    let idx = [i, j, k];
                    let s = idx[a];
                    let mut c = idx;
                    c[a] = s.min(n[a] - 1);
                    let cell = grid.cell(c[0], c[1], c[2]);
                    let open = faces.open(a) && system.diag[cell] > 0.0;
                    let (below, above) = if s == 0 {
                        if !open {
                            continue;
                        }
                        (0.0, phi[cell])
                    } else if s == n[a] {
                        if !open {
                            continue;
                        }
                        (phi[cell], 0.0)
                    } else {
                        if system.links[cell - st] & plus(a) == 0 {
                            continue;
                        }
                        (phi[cell - st], phi[cell])
                    };
                    let f = grid.face(a, i, j, k);
                    u_g.u[a][f] -= ((above - below) * inv_h) as f32;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_random_field_in_a_closed_box_is_projected_to_the_tolerance() {
        let grid = Grid::new([0.0; 3], [9, 7, 8], 0.2);
        let mut solids = Solids::none(&grid);
        solids.add_sphere(&grid, [0.9, 0.7, 0.8], 0.35, [0.0; 3]);
        let mut u = MacField::zeros(&grid);
        let mut seed = 1u32;
        for v in u.u.iter_mut().flatten() {
            seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
            *v = (seed >> 8) as f32 / (1u32 << 24) as f32 - 0.5;
        }
        let still = MacField::zeros(&grid);
        super::super::boundary::impose(&grid, &solids, Faces::CLOSED, &still, &mut u);
        let mut phi = Vec::new();
        let report = project(&grid, &solids, Faces::CLOSED, &mut u, 1e-6, 500, &mut phi);
        assert!(report.residual <= 1e-6, "{report:?}");
        let worst = u
            .divergence(&grid)
            .iter()
            .zip(&solids.solid)
            .filter(|(_, &s)| !s)
            .fold(0.0f32, |m, (&d, _)| m.max(d.abs()));
        assert!(worst * grid.h <= 1e-5, "divergence {worst}");
    }
}
