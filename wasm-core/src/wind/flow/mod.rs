//! The flow: a physical model for the large scales (the paper's §7, "a physical model for the
//! large scales … on a coarse grid"), the grid's velocity u_g (m/s) solved by the paper's
//! Eqs. 1–2 under the primitives' wind u_p:
//!
//!   ∂u_g/∂t + (u_p + u_g)·∇u_g = −∇p/ρ + ν∇²u_g + b + f,   ∇·u_g = 0,
//!
//! with (u_p + u_g)·n = v·n on the faces of solid cells, p = 0 beyond open faces of the box and
//! (u_p + u_g)·n = 0 on closed ones. Stam's (1999) "Stable Fluids" splitting on a MAC grid
//! (Bridson's fluid notes), MacCormack advection (Selle et al. 2008), explicit viscosity and a
//! MIC(0)-preconditioned conjugate-gradient projection.
//!
//! - [`grid`]: the MAC grid's cells, spacing and faces; [`sample`]: trilinear interpolation on
//!   one lattice of it; [`mac`]: a velocity on its faces, its divergence and energy.
//! - [`boundary`]: the solid cells and the box's open or closed faces.
//! - [`advect`]: semi-Lagrangian advection with MacCormack's clamped correction.
//! - [`diffuse`]: ν∇²u_g; [`forces`]: the buoyancy b = −β T g and force splats.
//! - [`project`]: the pressure projection.
//! - [`step`]: one step of them all ([`Flow`]); [`subgrid`]: Smagorinsky's eddy viscosity, the
//!   statistical model of the small scales LES adds (on in every scene's flow, off in a bare
//!   [`Flow`] unless asked for).
//! - [`heat`]: the gas's heat on the cells; [`scene_flow`]: a scene's flow stepped under its
//!   primitives, solids and stirs; [`frozen_flow`]: u_g as the blobs read it, faded beyond
//!   the box.
//!
//! A step costs, per cell, the advection's three faces (each two four-lane and two scalar
//! trilinear blends), a diffusion substep, the boundary's faces set and a projection of 15
//! warm-started CG iterations at 32³ (26 at 64³) in a steady flow, each about 40 flops: about
//! 0.25 µs a cell natively and 0.35 µs in WebAssembly on a shared two-core machine
//! (`npm run bench`: `flow_step_32_native_ms`, `flow_step_32_wasm_ms`; docs/BENCHMARKS.md).

pub mod advect;
pub mod boundary;
pub mod diffuse;
pub mod forces;
pub mod frozen_flow;
pub mod grid;
pub mod heat;
pub mod mac;
pub mod project;
pub mod sample;
pub mod scene_flow;
pub mod step;
pub mod subgrid;

pub use boundary::{Faces, Solids};
pub use forces::Splat;
pub use frozen_flow::FrozenFlow;
pub use grid::Grid;
pub use mac::MacField;
pub use project::Projection;
pub use scene_flow::{FlowGrid, SceneFlow, Stir};
pub use step::Flow;
