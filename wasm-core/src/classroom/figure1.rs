//! The paper's Figure 1 as a demo: a square of density evolving under the advection-diffusion
//! equation (Eq. 12) in a 2-D wind, solved on a grid, beside the blob model (Eqs. 13–16) of the
//! same setup.
//!
//! Domain: a periodic square of side `length` (m) on n×n cells. The wind comes from a stream
//! function ψ at cell corners, u = ∂ψ/∂y, v = −∂ψ/∂x, differenced onto cell faces, so the
//! discrete wind is exactly divergence-free; ψ is a uniform wind's plus a turbulent part taken
//! from one component of a 32⁴ Kolmogorov field (a z = 0 slice, moving in time).
//!
//! Grid: ∂ρ/∂t + ∇·(uρ) = (κ/2)∇²ρ − αρ (κ is twice the diffusivity, as in Eq. 15), donor-cell
//! upwind fluxes and the five-point Laplacian, explicit. Each update keeps every new value a
//! non-negative combination of old ones (so no new extrema and no negative density) when
//! `c + 4d ≤ 1`, c = Δt(|u| + |v|)_max/Δx and d = (κ/2)Δt/Δx²: the documented stability limit.
//! [`Figure1::step`] sub-steps to stay within it. Fluxes cancel in pairs, so without
//! dissipation the total mass is conserved to rounding.
//!
//! Blobs: the square is a grid of Gaussian blobs advected by RK2 through the same face
//! velocities (bilinearly interpolated), σ² = σ0² + κt, m = m0 e^(−αt); their density is
//! splatted onto the grid for display.

use crate::check;
use crate::error::ParamError;
use crate::field::{FieldParams, TurbulentField};
use serde::Deserialize;

/// The longest time one call of [`Figure1::step`] advances, s (the page steps a frame at a time).
pub const MAX_STEP_SECONDS: f64 = 60.0;

/// Setup of the demo.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Figure1Params {
    /// Cells per side.
    pub n: usize,
    /// Side of the periodic domain (m).
    pub length: f64,
    /// Square of density: centre (m) and side (m).
    pub square_center: [f64; 2],
    pub square_size: f64,
    /// κ (m²/s) and α (1/s) of Eq. 12 (κ as in Eq. 15).
    pub diffusion: f64,
    pub dissipation: f64,
    /// Mean wind (m/s).
    pub uniform: [f64; 2],
    /// Peak speed scale of the turbulent part (m/s); 0 for none.
    pub turbulence: f64,
    /// Seconds per temporal period of the turbulence.
    pub time_period: f64,
    pub seed: u64,
    /// Blobs per side of the square.
    pub blobs_per_side: usize,
}

impl Default for Figure1Params {
    fn default() -> Self {
        Self {
            n: 128,
            length: 1.0,
            square_center: [0.35, 0.5],
            square_size: 0.25,
            diffusion: 2e-4,
            dissipation: 0.0,
            uniform: [0.05, 0.0],
            turbulence: 0.15,
            time_period: 8.0,
            seed: 1,
            blobs_per_side: 24,
        }
    }
}

impl Figure1Params {
    pub fn validate(&self) -> Result<(), ParamError> {
        let err = |p: &str, m: &str| Err(ParamError::new(p, m));
        if !(8..=512).contains(&self.n) {
            return err("n", "must be between 8 and 512");
        }
        let pos = |p: &str, v: f64| -> Result<(), ParamError> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                err(p, "must be a positive number")
            }
        };
        pos("length", self.length)?;
        pos("square_size", self.square_size)?;
        pos("time_period", self.time_period)?;
        for (p, v) in [
            ("diffusion", self.diffusion),
            ("dissipation", self.dissipation),
            ("turbulence", self.turbulence),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return err(p, "must be a non-negative number");
            }
        }
        if !self
            .uniform
            .iter()
            .chain(&self.square_center)
            .all(|v| v.is_finite())
        {
            return err("uniform", "must be finite numbers");
        }
        if !(1..=256).contains(&self.blobs_per_side) {
            return err("blobs_per_side", "must be between 1 and 256");
        }
        Ok(())
    }
}

/// One 2-D blob.
#[derive(Debug, Clone, Copy)]
struct Blob2 {
    x: f64,
    y: f64,
}

/// The demo's state: grid density and blobs at `time`.
pub struct Figure1 {
    pub params: Figure1Params,
    /// Density per cell, row-major (y rows of x).
    pub rho: Vec<f64>,
    blobs: Vec<Blob2>,
    sigma0: f64,
    mass0: f64,
    pub time: f64,
    field: Option<TurbulentField>,
    /// Face velocities at the current time: u on x-faces (left face of cell i), v on y-faces.
    u: Vec<f64>,
    v: Vec<f64>,
}

impl Figure1 {
    pub fn new(params: Figure1Params) -> Result<Self, ParamError> {
        params.validate()?;
        let n = params.n;
        let dx = params.length / n as f64;
        let [cx, cy] = params.square_center;
        let h = params.square_size / 2.0;
        let mut rho = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                let (x, y) = ((i as f64 + 0.5) * dx, (j as f64 + 0.5) * dx);
                if (x - cx).abs() < h && (y - cy).abs() < h {
                    rho[j * n + i] = 1.0;
                }
            }
        }
        // Blobs on a regular grid over the square; σ0 of 0.6 spacings makes their sum nearly
        // flat inside. Mass of each: the square's mass shared equally.
        let b = params.blobs_per_side;
        let spacing = params.square_size / b as f64;
        let blobs = (0..b * b)
            .map(|k| Blob2 {
                x: cx - h + ((k % b) as f64 + 0.5) * spacing,
                y: cy - h + ((k / b) as f64 + 0.5) * spacing,
            })
            .collect();
        let mass: f64 = rho.iter().sum::<f64>() * dx * dx;
        let field = if params.turbulence > 0.0 {
            Some(TurbulentField::generate(&FieldParams {
                seed: params.seed,
                ..FieldParams::default()
            })?)
        } else {
            None
        };
        let mut demo = Self {
            rho,
            blobs,
            sigma0: 0.6 * spacing,
            mass0: mass / (b * b) as f64,
            time: 0.0,
            field,
            u: vec![0.0; n * n],
            v: vec![0.0; n * n],
            params,
        };
        demo.update_wind();
        Ok(demo)
    }

    fn dx(&self) -> f64 {
        self.params.length / self.params.n as f64
    }

    /// The turbulent part of ψ at corner (i, j) (lower-left corner of cell (i, j)), periodic
    /// (m²/s).
    fn psi(&self, i: usize, j: usize) -> f64 {
        let p = &self.params;
        let n = p.n;
        let mut psi = 0.0;
        if let Some(f) = &self.field {
            let [fx, fy, _, ft] = f.lattice.size;
            let q = [
                (i % n) as f64 * fx as f64 / n as f64,
                (j % n) as f64 * fy as f64 / n as f64,
                0.0,
                self.time / p.time_period * ft as f64,
            ];
            // The field's w component as a stream function: its rms is about 0.45 in field
            // units and its length scale length/(2π): ψ ≈ speed × length/(2π).
            let w = f.sample_lattice(q)[2] as f64;
            psi += p.turbulence * w * p.length / (2.0 * std::f64::consts::PI);
        }
        psi
    }

    /// Face velocities from ψ at the current time (exactly divergence-free per cell). The
    /// uniform part enters directly (ψ of a uniform wind is not periodic).
    fn update_wind(&mut self) {
        let n = self.params.n;
        let dx = self.dx();
        let [u0, v0] = self.params.uniform;
        let mut corner = vec![0.0; n * n];
        if self.field.is_some() {
            for j in 0..n {
                for i in 0..n {
                    corner[j * n + i] = self.psi(i, j);
                }
            }
        }
        let c = |i: usize, j: usize| corner[(j % n) * n + i % n];
        for j in 0..n {
            for i in 0..n {
                // Left face of cell (i, j) spans corners (i, j)..(i, j+1): u = ∂ψ/∂y.
                self.u[j * n + i] = u0 + (c(i, j + 1) - c(i, j)) / dx;
                // Bottom face spans corners (i, j)..(i+1, j): v = −∂ψ/∂x.
                self.v[j * n + i] = v0 - (c(i + 1, j) - c(i, j)) / dx;
            }
        }
    }

    /// Largest stable step (s): c + 4d = 1 (see the module docs).
    pub fn stable_dt(&self) -> f64 {
        let dx = self.dx();
        let n = self.params.n;
        let speed = (0..n * n)
            .map(|k| {
                let (i, j) = (k % n, k / n);
                let uo = self.u[j * n + (i + 1) % n].max(0.0) - self.u[k].min(0.0);
                let vo = self.v[((j + 1) % n) * n + i].max(0.0) - self.v[k].min(0.0);
                uo + vo
            })
            .fold(0.0, f64::max);
        let d_rate = 4.0 * 0.5 * self.params.diffusion / (dx * dx);
        1.0 / (speed / dx + d_rate).max(1e-12)
    }

    /// One explicit update of the grid by `dt` (must satisfy `dt ≤ stable_dt()`).
    pub fn grid_substep(&mut self, dt: f64) {
        let n = self.params.n;
        let dx = self.dx();
        let d = 0.5 * self.params.diffusion * dt / (dx * dx);
        let r = &self.rho;
        let at = |i: usize, j: usize| r[(j % n) * n + i % n];
        let mut next = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                let k = j * n + i;
                let (ip, jp) = ((i + 1) % n, (j + 1) % n);
                let (im, jm) = ((i + n - 1) % n, (j + n - 1) % n);
                // Donor-cell fluxes through the four faces (outward positive).
                let flux = |vel: f64, inside: f64, outside: f64| {
                    if vel > 0.0 {
                        vel * inside
                    } else {
                        vel * outside
                    }
                };
                let right = flux(self.u[j * n + ip], at(i, j), at(ip, j));
                let left = flux(self.u[k], at(im, j), at(i, j));
                let top = flux(self.v[jp * n + i], at(i, j), at(i, jp));
                let bottom = flux(self.v[k], at(i, jm), at(i, j));
                let lap = at(ip, j) + at(im, j) + at(i, jp) + at(i, jm) - 4.0 * at(i, j);
                next[k] = at(i, j) - dt / dx * (right - left + top - bottom) + d * lap;
            }
        }
        let decay = (-self.params.dissipation * dt).exp();
        next.iter_mut().for_each(|v| *v *= decay);
        self.rho = next;
    }

    /// Face velocity bilinearly interpolated at (x, y) (m/s).
    fn velocity(&self, x: f64, y: f64) -> (f64, f64) {
        let n = self.params.n;
        let dx = self.dx();
        let sample = |field: &[f64], ox: f64, oy: f64| {
            let (gx, gy) = (x / dx - ox, y / dx - oy);
            let (fx, fy) = (gx.floor(), gy.floor());
            let (tx, ty) = (gx - fx, gy - fy);
            let i0 = (fx as i64).rem_euclid(n as i64) as usize;
            let j0 = (fy as i64).rem_euclid(n as i64) as usize;
            let (i1, j1) = ((i0 + 1) % n, (j0 + 1) % n);
            let f = |i: usize, j: usize| field[j * n + i];
            (f(i0, j0) * (1.0 - tx) + f(i1, j0) * tx) * (1.0 - ty)
                + (f(i0, j1) * (1.0 - tx) + f(i1, j1) * tx) * ty
        };
        // u lives on left faces (x = i·dx, y = (j + ½)dx); v on bottom faces.
        (sample(&self.u, 0.0, 0.5), sample(&self.v, 0.5, 0.0))
    }

    /// Advances both models by `seconds` (0 to [`MAX_STEP_SECONDS`]): the grid in stable
    /// sub-steps, the blobs by RK2. Any other time is refused, naming `seconds`.
    pub fn step(&mut self, seconds: f64) -> Result<(), ParamError> {
        check::range("seconds", seconds, 0.0, MAX_STEP_SECONDS)?;
        let mut left = seconds;
        while left > 1e-12 {
            let dt = left.min(self.stable_dt());
            self.grid_substep(dt);
            // Blobs: RK2 midpoint in the wind of this sub-step.
            let moved: Vec<Blob2> = self
                .blobs
                .iter()
                .map(|b| {
                    let (u1, v1) = self.velocity(b.x, b.y);
                    let (u2, v2) = self.velocity(b.x + 0.5 * dt * u1, b.y + 0.5 * dt * v1);
                    Blob2 {
                        x: b.x + dt * u2,
                        y: b.y + dt * v2,
                    }
                })
                .collect();
            self.blobs = moved;
            self.time += dt;
            left -= dt;
            if self.field.is_some() {
                self.update_wind();
            }
        }
        Ok(())
    }

    /// σ (m) and mass of every blob now (Eqs. 15–16).
    pub fn blob_sigma_mass(&self) -> (f64, f64) {
        let p = &self.params;
        (
            (self.sigma0 * self.sigma0 + p.diffusion * self.time).sqrt(),
            self.mass0 * (-p.dissipation * self.time).exp(),
        )
    }

    /// The blobs' density averaged over each grid cell (exact cell integrals via erf,
    /// periodic images included), row-major like `rho`.
    pub fn blob_density(&self) -> Vec<f64> {
        let n = self.params.n;
        let dx = self.dx();
        let l = self.params.length;
        let (sigma, mass) = self.blob_sigma_mass();
        let reach = (5.0 * sigma / dx).ceil() as i64 + 1;
        let mut out = vec![0.0; n * n];
        let cdf = |a: f64| 0.5 * (1.0 + libm::erf(a / (sigma * std::f64::consts::SQRT_2)));
        for b in &self.blobs {
            let (bx, by) = (b.x.rem_euclid(l), b.y.rem_euclid(l));
            let (ci, cj) = ((bx / dx).floor() as i64, (by / dx).floor() as i64);
            // Per-axis cell weights, then their outer product.
            let weights = |c: i64, centre: f64| -> Vec<(usize, f64)> {
                (c - reach..=c + reach)
                    .map(|i| {
                        let (a, z) = (i as f64 * dx - centre, (i + 1) as f64 * dx - centre);
                        ((i.rem_euclid(n as i64)) as usize, cdf(z) - cdf(a))
                    })
                    .collect()
            };
            let (wx, wy) = (weights(ci, bx), weights(cj, by));
            for &(j, fy) in &wy {
                for &(i, fx) in &wx {
                    out[j * n + i] += mass * fx * fy / (dx * dx);
                }
            }
        }
        out
    }

    /// Total mass of the grid (density × cell area).
    pub fn grid_mass(&self) -> f64 {
        self.rho.iter().sum::<f64>() * self.dx() * self.dx()
    }

    /// Total mass of the blobs.
    pub fn blob_mass(&self) -> f64 {
        self.blob_sigma_mass().1 * self.blobs.len() as f64
    }
}
