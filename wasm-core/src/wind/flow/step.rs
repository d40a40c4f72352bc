//! One step of the flow, the paper's Eqs. 1–2 for the grid's velocity u_g (m/s):
//!
//!   ∂u_g/∂t + (u_p + u_g)·∇u_g = −∇p/ρ + ν∇²u_g + b + f,   ∇·u_g = 0,
//!
//! u_p the primitives' wind (given, sampled on the faces), split into Stam's (1999) fractional
//! steps: advect u_g by u_p + u_g ([`super::advect`]), diffuse it ([`super::diffuse`]), add the
//! forces ([`super::forces`]), set the fixed faces so that (u_p + u_g)·n is the solid's v·n
//! (0 on closed walls, [`super::boundary`]) and project ([`super::project`]). Each split loses
//! its own share (the advection's numerical viscosity, the splitting's first-order error in
//! dt); nothing in it limits dt for stability, but an accurate step keeps |u|·dt within a
//! cell or two. No threads and no hashing: the same inputs give the same bytes.

use super::advect::{advect_velocity_into, Advection};
use super::boundary::{FaceKinds, Faces, Solids};
use super::diffuse::diffuse;
use super::forces::{add_buoyancy, add_splat, Splat};
use super::grid::Grid;
use super::mac::{Centred, MacField};
use super::project::{Projection, Projector};
use super::subgrid::{diffuse_eddies, eddy_viscosity};
use crate::scene::flow_settings;

/// Air's kinematic viscosity, m²/s (the scene's default, `flow.viscosity`).
pub const AIR_VISCOSITY: f32 = flow_settings::AIR_VISCOSITY as f32;
/// An ideal gas's expansion coefficient at room temperature, 1/K.
pub const AIR_EXPANSION: f32 = flow_settings::AIR_EXPANSION as f32;
/// The projection's relative residual by default.
pub const TOLERANCE: f64 = 1e-5;

/// The flow on its grid: the laws' constants, the solids, the faces and u_g.
#[derive(Debug, Clone)]
pub struct Flow {
    /// The MAC grid.
    pub grid: Grid,
    /// Its solid cells.
    pub solids: Solids,
    /// The box's faces.
    pub faces: Faces,
    /// ν, m²/s.
    pub viscosity: f32,
    /// β, 1/K.
    pub buoyancy: f32,
    /// g, m/s².
    pub gravity: [f32; 3],
    /// The projection's relative residual.
    pub tolerance: f64,
    /// The most CG iterations of one projection.
    pub max_iterations: usize,
    /// The grid's velocity u_g, m/s.
    pub u_g: MacField,
    /// The last projection's potential φ = p·dt/ρ, m²/s, per cell.
    pub phi: Vec<f64>,
    /// What a step keeps for the next one: its fields' storage and the projection's system.
    scratch: Scratch,
    /// Whether Smagorinsky's eddy viscosity acts beside ν ([`super::subgrid`]).
    pub eddies: bool,
    /// ν_t of the last step, m²/s per cell (empty without eddies).
    pub eddy_viscosity: Vec<f32>,
}

/// The storage a step reuses: the carrier u_p + u_g at the cells' centres, the advected u_g,
/// the advection's and the projection's own.
#[derive(Debug, Clone, Default)]
struct Scratch {
    /// The faces' kinds for the solids and faces they were worked out for.
    kinds: Option<(Solids, Faces, FaceKinds)>,
    carrier: Option<Centred>,
    advected: Option<MacField>,
    advection: Advection,
    projector: Projector,
    /// The potential φ of the projection before the last (m²/s per cell; empty before the
    /// second step), for the first guess's extrapolation.
    phi_before: Vec<f64>,
}

impl Flow {
    /// A flow at rest on `grid` with no solids, air's ν and β and Earth's g.
    pub fn new(grid: Grid, faces: Faces) -> Self {
        let iterations = 20 * grid.cells.iter().copied().max().unwrap_or(1) + 100;
        Self {
            solids: Solids::none(&grid),
            u_g: MacField::zeros(&grid),
            phi: Vec::new(),
            faces,
            viscosity: AIR_VISCOSITY,
            buoyancy: AIR_EXPANSION,
            gravity: flow_settings::EARTH_GRAVITY.map(|g| g as f32),
            tolerance: TOLERANCE,
            max_iterations: iterations,
            scratch: Scratch::default(),
            eddies: false,
            eddy_viscosity: Vec::new(),
            grid,
        }
    }

    /// One step of `dt` (s) with the primitives' wind `u_p` on the faces (m/s), the
    /// temperature excess on the cells (K; `None`: no heat) and the force splats.
    pub fn step(
        &mut self,
        dt: f32,
        u_p: &MacField,
        temperature: Option<&[f32]>,
        splats: &[Splat],
    ) -> Projection {
        let g = &self.grid;
        let scratch = &mut self.scratch;
        let stale =
            !matches!(&scratch.kinds, Some((s, f, _)) if *s == self.solids && *f == self.faces);
        if stale {
            let kinds = FaceKinds::new(g, &self.solids, self.faces);
            scratch.kinds = Some((self.solids.clone(), self.faces, kinds));
        }
        let Some((_, _, kinds)) = &scratch.kinds else {
            unreachable!("the faces' kinds were just worked out")
        };
        let carrier = scratch.carrier.get_or_insert_with(|| Centred::new(g));
        carrier.set_sum(g, u_p, &self.u_g);
        let u = scratch.advected.get_or_insert_with(|| MacField::zeros(g));
        let faces = self.faces;
        advect_velocity_into(g, &self.u_g, carrier, dt, faces, &mut scratch.advection, u);
        diffuse(g, kinds, u_p, u, self.viscosity, dt);
        if self.eddies {
            eddy_viscosity(g, &self.u_g, dt, &mut self.eddy_viscosity);
            diffuse_eddies(g, kinds, u, &self.eddy_viscosity, dt);
        }
        if let Some(t) = temperature {
            add_buoyancy(g, u, t, self.buoyancy, self.gravity, dt);
        }
        for s in splats {
            add_splat(g, u, s, dt);
        }
        kinds.impose(u_p, u);
        first_guess(&mut self.phi, &mut scratch.phi_before);
        let report = scratch.projector.project(
            g,
            &self.solids,
            self.faces,
            u,
            self.tolerance,
            self.max_iterations,
            &mut self.phi,
        );
        if report.iterations == 0 && report.residual == 0.0 {
            // Nothing was projected and φ was reset to 0: start the extrapolation again.
            scratch.phi_before.clear();
        }
        std::mem::swap(&mut self.u_g, u);
        report
    }

    /// The wind u_p + u_g at `x` (m), m/s, u_p given on the faces.
    pub fn velocity_at(&self, u_p: &MacField, x: [f32; 3]) -> [f32; 3] {
        let p = u_p.at(&self.grid, x);
        let q = self.u_g.at(&self.grid, x);
        std::array::from_fn(|a| p[a] + q[a])
    }
}

/// The projection's first guess: φ extrapolated linearly from the last two projections,
/// 2φ_n − φ_{n−1} (φ_n alone while there is no φ_{n−1}, or when φ was reset); `before` is left
/// holding φ_n. A flow that changes smoothly from step to step changes its pressure smoothly
/// too, and the guess starts CG nearer the answer than φ_n does: about a quarter fewer
/// iterations at 32³ and half at 64³ for a wind past a sphere (docs/BENCHMARKS.md). The answer
/// is the same to the projection's tolerance, which CG reaches from any guess.
fn first_guess(phi: &mut [f64], before: &mut Vec<f64>) {
    if before.len() == phi.len() {
        for (p, b) in phi.iter_mut().zip(before.iter_mut()) {
            let now = *p;
            *p = 2.0 * now - *b;
            *b = now;
        }
    } else {
        before.clear();
        before.extend_from_slice(phi);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_guess_extrapolates_the_last_two_potentials() {
        let mut before = Vec::new();
        let mut phi = vec![1.0, 2.0];
        first_guess(&mut phi, &mut before);
        assert_eq!(
            (phi.as_slice(), before.as_slice()),
            ([1.0, 2.0].as_slice(), [1.0, 2.0].as_slice())
        );
        phi = vec![2.0, 1.5];
        first_guess(&mut phi, &mut before);
        assert_eq!(
            (phi.as_slice(), before.as_slice()),
            ([3.0, 1.0].as_slice(), [2.0, 1.5].as_slice())
        );
    }

    /// A wind past a sphere: steps with the extrapolated guess take fewer CG iterations than
    /// steps that start from the last φ (the history cleared before each), and end as close to
    /// divergence-free.
    #[test]
    fn a_steady_wind_projects_in_fewer_iterations_from_the_extrapolated_guess() {
        let run = |extrapolate: bool| {
            let n = 16;
            let grid = Grid::new([0.0; 3], [n; 3], 1.6 / n as f32);
            let mut flow = Flow::new(grid.clone(), Faces::OPEN);
            flow.solids.add_sphere(&grid, [0.8; 3], 0.3, [0.0; 3]);
            let u_p = MacField::from_fn(&grid, |_| [1.0, 0.0, 0.0]);
            let mut iterations = 0;
            for step in 0..60 {
                if !extrapolate {
                    flow.scratch.phi_before.clear();
                }
                let report = flow.step(0.02, &u_p, None, &[]);
                assert!(report.residual <= flow.tolerance, "step {step}: {report:?}");
                if step >= 30 {
                    iterations += report.iterations;
                }
            }
            iterations
        };
        let (last, extrapolated) = (run(false), run(true));
        assert!(
            extrapolated * 10 < last * 9,
            "{extrapolated} iterations extrapolated, {last} from the last φ"
        );
    }
}
