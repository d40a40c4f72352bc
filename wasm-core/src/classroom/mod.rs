//! The classroom's demos: the paper's figures and flows computed beside the core's own answer.
//!
//! - [`figure1`]: the paper's Figure 1, a grid solution of the advection-diffusion equation
//!   (Eq. 12) beside the blob model (Eqs. 13–16) of the same setup.
//! - [`sphere_flow`]: streamlines of the core's wind past a solid sphere beside the potential
//!   flow's.

pub mod figure1;
pub mod sphere_flow;
