//! `windfield simulate`: runs a scene for whole steps of `simulation.dt` and writes the blob
//! list a renderer takes (docs/FORMATS.md, the blob list), every blob with its `age`, `sigma0`
//! and `mass0`; the same scene gives the same bytes.

use super::atomic::write_atomically;
use super::failure::Failure;
use super::formats::BLOB_LISTS;
use super::input::read_scene;
use super::moment::{check_seconds, simulated};
use super::summary::{grouped, wall};
use clap::Args;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Args)]
pub struct SimulateArgs {
    /// Scene file (JSON, format version 1).
    scene: PathBuf,
    /// Simulated time in seconds, 0 or more (rounded to whole steps of simulation.dt, at most
    /// 1,000,000 of them).
    #[arg(long, allow_hyphen_values = true)]
    seconds: f64,
    /// Output blob list (JSON).
    #[arg(long)]
    out: PathBuf,
}

pub fn run(args: SimulateArgs) -> Result<(), Failure> {
    let start = Instant::now();
    check_seconds(args.seconds)?;
    let scene = read_scene(&args.scene)?;
    BLOB_LISTS.check(&args.out)?;
    let sim = simulated(scene, args.seconds, |e| Failure::Input(e.to_string()))?;
    let list = sim.blob_list();
    let text = serde_json::to_string(&list).expect("blob lists serialise");
    write_atomically(&args.out, |w| std::io::Write::write_all(w, text.as_bytes()))?;
    let c = sim.gas.counts;
    eprintln!(
        "wrote {}: {} blobs at t = {:.2} s ({} steps; {} emitted, {} split, {} dissipated, {} capped), {}",
        args.out.display(),
        grouped(list.blobs.len()),
        sim.time(),
        sim.steps(),
        grouped(c.emitted as usize),
        grouped(c.split as usize),
        grouped(c.dissipated as usize),
        grouped(c.capped as usize),
        wall(start)
    );
    Ok(())
}
