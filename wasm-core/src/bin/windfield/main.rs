//! `windfield`: the command-line face of the core.
//!
//! ```text
//! windfield generate --size 32 --epsilon 1 --k-inertial 4 --sigma 1 --seed 1 --out field.npy
//! windfield stats field.npy --json
//! windfield render scene.json --frames 0..240 --fps 24 --out frames/f%04d.png --shard 0/4
//! windfield wind scene.json --seconds 2 --box -1,0,-1,1,2,1 --n 32,64,32 --out wind.npy
//! windfield wind plume.json --frames 0..48 --fps 24 --points probes.json --out wind.json
//! windfield flow plume.json --seconds 2 --out flow.npy
//! windfield schema > ../public/scene.schema.json
//! windfield contract > ../web/src/generated/contract.js
//! ```
//!
//! Every command checks its flags and its input before it starts work; a refusal names the
//! flag or the JSON path and what is allowed (exit status 2; a failed read or write, a folder
//! given as an input file included, 1), and begins `windfield: error:`, the argument parser's
//! too (`messages`). An `--out` whose extension names a format the command does not write is
//! refused before the work starts (`formats`). On success `simulate` and `render` end with one
//! line on stderr: what was written, the blobs, the simulated time and the wall time (`wrote
//! still.png (640×480): 41,203 blobs at t = 3.00 s, 2.4 s`). Numeric flags take negative
//! numbers as values (`--seconds -1`), so that the range check, not the argument parser,
//! answers them.
//!
//! This file holds the grammar of the subcommands and hands each to its own file; what they
//! share: `failure` (exit statuses), `atomic` (every write), `input` (scenes and blob lists),
//! `moment` (`--seconds` and `--time`), `formats` (what `--out` names), `spectrum` (the field's
//! flags), `sequence` with `frames` and `claim` (`--frames` and its manifest), `summary` (the
//! last line) and `messages` (the argument parser's refusals).

mod atomic;
mod claim;
mod contract;
mod failure;
mod flipbook;
mod flow;
mod formats;
mod frames;
mod generate;
mod input;
mod messages;
mod moment;
mod render;
mod schema;
mod sequence;
mod simulate;
mod spectrum;
mod stats;
mod summary;
mod volume;
mod wind;

use clap::{Parser, Subcommand};
use failure::Failure;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "windfield",
    version,
    about = "Turbulent wind fields for gaseous phenomena (Stam & Fiume 1993)"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Synthesise a small-scale turbulence field and write it as float32 .npy,
    /// shape (nt, nz, ny, nx, 3), C order, velocity in lattice units.
    Generate(generate::GenerateArgs),
    /// Measure a field's statistics against the spectrum it should follow.
    Stats(stats::StatsArgs),
    /// Simulate a scene and write the blob list (camera, lights, medium and blobs).
    Simulate(simulate::SimulateArgs),
    /// Render a still with the CPU reference renderer: a blob list, or a scene simulated first.
    /// An --out ending in .exr writes OpenEXR (half-float linear RGBA).
    Render(render::RenderArgs),
    /// Sample the scene's whole wind (m/s), its flow included, at one time or at the frames of
    /// a series, at points or over a box of cells.
    Wind(wind::WindArgs),
    /// Render a scene's frames into one sprite sheet (PNG or EXR, with alpha) and its JSON.
    Flipbook(flipbook::FlipbookArgs),
    /// Write the gas's density (and emission) as an OpenVDB volume.
    Volume(volume::VolumeArgs),
    /// Run a scene with a flow and write the flow's grid (u_g in m/s at the cells' centres and
    /// the temperature excess in K) as .npy, .vdb or .json.
    Flow(flow::FlowArgs),
    /// Print the JSON Schema of the scene format.
    Schema,
    /// Print the JavaScript module of the constants the core shares with the page's code
    /// (web/src/generated/contract.js).
    Contract,
}

fn main() -> ExitCode {
    let cli = match messages::parse_args::<Cli>() {
        Ok(cli) => cli,
        Err(code) => return code,
    };
    let result = match cli.command {
        Command::Generate(a) => generate::run(a),
        Command::Stats(a) => stats::run(a),
        Command::Simulate(a) => simulate::run(a),
        Command::Render(a) => render::run(a),
        Command::Wind(a) => wind::run(a),
        Command::Flipbook(a) => flipbook::run(a),
        Command::Volume(a) => volume::run(a),
        Command::Flow(a) => flow::run(a),
        Command::Schema => schema::run(),
        Command::Contract => contract::run(),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Input(m)) => {
            eprintln!("windfield: error: {m}");
            ExitCode::from(2)
        }
        Err(Failure::Io(m)) => {
            eprintln!("windfield: error: {m}");
            ExitCode::from(1)
        }
    }
}
