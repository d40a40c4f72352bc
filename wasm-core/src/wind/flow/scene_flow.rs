//! A scene's flow (docs/FORMATS.md, the flow): the solver ([`Flow`]) set up from the scene's
//! `flow`, its solid objects and its repulsors, and stepped under the scene's primitives with
//! the gas's heat and the pointer's stirs.
//!
//! Each step: u_p is the enabled primitives' wind (no solids: the flow itself goes round
//! them) sampled on the faces at the step's start; the solid objects' cells are fixed, each
//! repulsor's sphere is a solid moving along its path at the path's velocity; T is the
//! blobs' heat on the cells ([`super::heat`]); a stir pushes the flow towards its velocity
//! ([`Stir`]). The result is frozen for the blobs ([`FrozenFlow`]).

use super::boundary::{Faces, Solids};
use super::forces::Splat;
use super::frozen_flow::FrozenFlow;
use super::grid::Grid;
use super::heat::deposit;
use super::mac::MacField;
use super::project::Projection;
use super::step::Flow;
use crate::error::ParamError;
use crate::scene::bodies::Body;
use crate::scene::flow_settings::FlowSettings;
use crate::scene::scene_format::Scene;
use crate::wind::Wind;
use glam::Vec3A;
use std::sync::Arc;

/// How long a stir takes to bring the flow at its centre to its velocity (s).
pub const STIR_TIME: f32 = 0.05;
/// A stir's width in cells, fewest and most.
pub const STIR_CELLS: [f32; 2] = [1.5, 4.0];

/// A stir of the flow: the pointer's `velocity` (m/s) at `centre` (m) over a width `radius`
/// (m, clamped to [`STIR_CELLS`] cells), acting as the force (velocity − u)/[`STIR_TIME`] on
/// the flow, u the wind at the centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stir {
    pub centre: [f32; 3],
    pub velocity: [f32; 3],
    pub radius: f32,
}

/// The flow's grid at one time, as `windfield flow` and `exportFlow()` write it
/// (docs/FORMATS.md, the flow's exports).
#[derive(Debug, Clone, PartialEq)]
pub struct FlowGrid {
    /// The box `[x0, y0, z0, x1, y1, z1]`, m.
    pub bounds: [f64; 6],
    /// Cells along x, y, z.
    pub cells: [usize; 3],
    /// Its time, s.
    pub time: f64,
    /// u_g at each cell's centre, m/s: (nz, ny, nx, 3), x fastest.
    pub velocity: Vec<f32>,
    /// T at each cell, K: (nz, ny, nx).
    pub temperature: Vec<f32>,
}

/// The flow of a scene, at rest from its start.
#[derive(Debug, Clone)]
pub struct SceneFlow {
    pub settings: FlowSettings,
    pub flow: Flow,
    /// The solid objects' cells (the repulsors' spheres join them each step).
    fixed: Solids,
    /// T on the cells of the last step, K.
    temperature: Vec<f32>,
    /// The stir acting from the next step, if any.
    pub stir: Option<Stir>,
    frozen: Arc<FrozenFlow>,
    u_p: MacField,
    time: f64,
}

impl SceneFlow {
    /// The flow of `scene`'s `settings`, at rest.
    pub fn new(settings: &FlowSettings, scene: &Scene) -> Self {
        let h = settings.h() as f32;
        let origin = std::array::from_fn(|a| settings.bounds[a] as f32);
        let grid = Grid::new(origin, settings.cells, h);
        let faces = Faces {
            closed: settings.faces.closed(),
        };
        let mut flow = Flow::new(grid.clone(), faces);
        flow.eddies = true;
        let mut fixed = Solids::none(&grid);
        for body in scene.render.objects.iter().filter(|o| o.solid()) {
            if let Some(b) = Body::of(body) {
                fixed.add(&grid, [0.0; 3], |x| {
                    b.distance(Vec3A::from_array(x)).0 < 0.0
                });
            }
        }
        flow.solids = fixed.clone();
        let mut out = Self {
            settings: settings.clone(),
            frozen: Arc::new(FrozenFlow::new(&grid, MacField::zeros(&grid))),
            u_p: MacField::zeros(&grid),
            temperature: vec![0.0; grid.cell_count()],
            stir: None,
            fixed,
            flow,
            time: 0.0,
        };
        out.retune(settings);
        out
    }

    /// Takes the constants of `settings` (same box, cells and faces) from the next step.
    pub fn retune(&mut self, settings: &FlowSettings) {
        self.settings = settings.clone();
        self.flow.viscosity = settings.viscosity as f32;
        self.flow.buoyancy = settings.buoyancy as f32;
        self.flow.gravity = settings.gravity.map(|g| g as f32);
    }

    /// Whether `other` keeps this flow's grid and faces (an edit that keeps u_g).
    pub fn same_grid(&self, other: &FlowSettings) -> bool {
        self.settings.bounds == other.bounds
            && self.settings.cells == other.cells
            && self.settings.faces.closed() == other.faces.closed()
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.flow.grid
    }

    /// The time of the last step's end (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// u_g frozen after the last step.
    pub fn frozen(&self) -> Arc<FrozenFlow> {
        self.frozen.clone()
    }

    /// One step from `t` to `t + dt` (s) under `wind`'s primitives, with blobs of centres
    /// `centres` (m), widths `sigma` (m) and heats `heat` (K·m³).
    pub fn step(
        &mut self,
        wind: &Wind,
        t: f64,
        dt: f64,
        centres: &[f32],
        sigma: &[f32],
        heat: &[f32],
    ) -> Projection {
        let frame = wind.large_frame(t);
        let grid = self.flow.grid.clone();
        match frame.uniform_primitive_wind() {
            // A uniform u_p (uniform winds alone) fills the faces it has.
            Some(v) => self.u_p.fill(v.to_array()),
            None => {
                self.u_p = MacField::from_fn(&grid, |x| {
                    frame.primitive_wind(Vec3A::from_array(x)).to_array()
                })
            }
        }
        let spheres = wind.repulsor_spheres(t);
        if !spheres.is_empty() {
            let mut solids = self.fixed.clone();
            for (centre, radius, velocity) in spheres {
                solids.add_sphere(&grid, centre.to_array(), radius, velocity.to_array());
            }
            if solids != self.flow.solids {
                self.flow.solids = solids;
            }
        } else if self.flow.solids != self.fixed {
            // The repulsors an edit removed leave no solid cells behind.
            self.flow.solids = self.fixed.clone();
        }
        let heated = heat.iter().any(|&q| q != 0.0);
        if heated {
            deposit(&grid, centres, sigma, heat, &mut self.temperature);
        } else {
            self.temperature.iter_mut().for_each(|v| *v = 0.0);
        }
        let splats: Vec<Splat> = self
            .stir
            .iter()
            .map(|s| {
                let [lo, hi] = STIR_CELLS;
                let radius = s.radius.clamp(lo * grid.h, hi * grid.h);
                let u = self.flow.velocity_at(&self.u_p, s.centre);
                Splat {
                    centre: s.centre,
                    radius,
                    force: std::array::from_fn(|a| (s.velocity[a] - u[a]) / STIR_TIME),
                }
            })
            .collect();
        let report = self.flow.step(
            dt as f32,
            &self.u_p,
            heated.then_some(&self.temperature[..]),
            &splats,
        );
        self.frozen = Arc::new(FrozenFlow::new(&grid, self.flow.u_g.clone()));
        self.time = t + dt;
        report
    }

    /// Takes `u_g` (m/s on each component's faces, laid out as [`Grid::face`]) as the flow's
    /// own at time `t` (s): a flow stepped elsewhere (the page's GPU) handed back. Refused,
    /// naming the component, where a component's length is not its faces' count or a value is
    /// not finite; φ starts again from 0.
    pub fn take_u_g(&mut self, u_g: [&[f32]; 3], t: f64) -> Result<(), ParamError> {
        let grid = &self.flow.grid;
        for (a, u) in u_g.iter().enumerate() {
            let faces = grid.face_count(a);
            if u.len() != faces {
                return Err(ParamError::new(
                    ["u", "v", "w"][a],
                    format!(
                        "must hold the flow's {faces} faces across {} (got {})",
                        ["x", "y", "z"][a],
                        u.len()
                    ),
                ));
            }
            if let Some(bad) = u.iter().find(|v| !v.is_finite()) {
                return Err(ParamError::new(
                    ["u", "v", "w"][a],
                    format!("must be finite velocities (got {bad})"),
                ));
            }
        }
        self.flow.u_g = MacField {
            u: u_g.map(<[f32]>::to_vec),
        };
        self.flow.phi.clear();
        self.frozen = Arc::new(FrozenFlow::new(grid, self.flow.u_g.clone()));
        self.time = t;
        Ok(())
    }

    /// u_g on each component's faces (m/s, laid out as [`Grid::face`]).
    pub fn faces(&self) -> &[Vec<f32>; 3] {
        &self.flow.u_g.u
    }

    /// The grid as the exports write it ([`FlowGrid`]) at the time of the last step, its T
    /// (K) laid on the cells from the blobs as they are then: `centres` (m, xyz interleaved),
    /// `sigma` (m) and `heat` (K·m³, each blob's h at that time). A step lays T from the blobs
    /// at its start, before they move and the newborns come; the export's T is the grid's at
    /// its own time.
    pub fn export(&self, centres: &[f32], sigma: &[f32], heat: &[f32]) -> FlowGrid {
        let mut temperature = Vec::new();
        deposit(&self.flow.grid, centres, sigma, heat, &mut temperature);
        FlowGrid {
            bounds: self.settings.bounds,
            cells: self.settings.cells,
            time: self.time,
            velocity: self.cell_velocity(),
            temperature,
        }
    }

    /// u_g at the cells' centres (m/s, xyz interleaved, x fastest, then y, then z): each
    /// component the mean of its cell's two faces.
    pub fn cell_velocity(&self) -> Vec<f32> {
        self.flow
            .u_g
            .cell_means(&self.flow.grid)
            .into_iter()
            .flatten()
            .collect()
    }
}
