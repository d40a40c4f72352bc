//! The integration tests as one test binary: each file of this folder is a module of it. One
//! binary links once, and the harness runs the tests of every file side by side (the long
//! golden stills beside the short checks). Run one file's tests by its module's name:
//! `cargo test --release --test integration render_golden::`.

mod architecture;
mod at_scale;
mod carried;
mod cli;
mod contract;
mod exports;
mod field_statistics;
mod figure1;
mod flow;
mod flow_cli;
mod flow_scene;
mod flow_shedding;
mod fuzz_inputs;
mod gas_physics;
mod gpu_steps;
mod live_edit;
mod render_golden;
mod render_lod;
mod render_reference;
mod render_volume;
mod scene_format;
mod shapes;
mod solids;
mod support;
mod vector_potential;
mod wind_command;
