//! `windfield volume` (docs/FORMATS.md, OpenVDB volumes): the gas's density (and emission) as
//! an OpenVDB volume, made by the core's `export` module (the browser's worker calls the same
//! code); with `--frames`, one volume a frame ([`super::sequence`]).

use super::atomic::write_atomically;
use super::failure::Failure;
use super::formats::VOLUMES;
use super::input::{read_input, Input};
use super::moment::{blob_list_at, check_seconds};
use super::sequence::{Frame, Sequence, SequenceArgs, SequenceWords};
use super::summary::{grouped, wall};
use clap::Args;
use std::path::PathBuf;
use std::time::Instant;
use windfield::export::volume::{GasVolume, VolumeBuild};
use windfield::ParamError;

#[derive(Args)]
pub struct VolumeArgs {
    /// A scene (JSON with "version") or a blob list.
    input: PathBuf,
    /// Voxel side H in metres: voxel (i, j, k) is centred at (i, j, k)·H.
    #[arg(long, allow_hyphen_values = true)]
    voxel: f64,
    /// Output .vdb; with --frames, a pattern with one %0Nd for the frame number.
    #[arg(long)]
    out: PathBuf,
    #[command(flatten)]
    sequence: SequenceArgs<Volume>,
    /// For a blob list: the moment it shows (s), recorded in the grids' metadata (a scene's
    /// volume records the time it was simulated to).
    #[arg(long, conflicts_with_all = ["seconds", "frames"], allow_hyphen_values = true)]
    time: Option<f64>,
}

/// `volume`'s words for the sequence flags.
pub struct Volume;

impl SequenceWords for Volume {
    const SECONDS: &'static str = "For a scene: seconds to simulate, 0 or more, at most \
        1,000,000 steps of simulation.dt (default: the scene's render.time)";
    const FRAMES: &'static str =
        "For a scene: a sequence, frames k in the half-open range A..B at t = k/fps";
    const FPS: &'static str = "With --frames: frames per second";
    const SHARD: &'static str =
        "With --frames: write only the frames with k mod N = I (I/N, 0 ≤ I < N)";
    const FORCE: &'static str =
        "With --frames: write complete frames again, and over another run's";
}

fn input(e: ParamError) -> Failure {
    Failure::Input(e.to_string())
}

pub fn run(args: VolumeArgs) -> Result<(), Failure> {
    let start = Instant::now();
    if !(args.voxel.is_finite() && args.voxel > 0.0) {
        return Err(Failure::Input(format!(
            "--voxel: must be a voxel side in metres, greater than 0 (got {})",
            args.voxel
        )));
    }
    if let Some(frames) = &args.sequence.frames {
        let voxel = args.voxel;
        let job = Sequence::parse(frames, &args.sequence, &args.out, Frame::Volume { voxel })?;
        let given = read_input(&args.input)?;
        VOLUMES.check(&args.out)?;
        return match given {
            Input::Scene(scene) => job.run(*scene, &args.input, start),
            Input::List(_) => Err(Failure::Input(format!(
                "--frames: needs a scene to simulate; {} is a blob list",
                args.input.display()
            ))),
        };
    }
    if let Some(seconds) = args.sequence.seconds {
        check_seconds(seconds)?;
    }
    let path = &args.input;
    let given = read_input(path)?;
    VOLUMES.check(&args.out)?;
    let (list, time) = blob_list_at(
        given,
        path,
        args.sequence.seconds,
        args.time,
        "volume",
        false,
    )?;
    let build = VolumeBuild::new(&list, args.voxel, "--voxel").map_err(input)?;
    let volume: GasVolume = build.finish();
    let bytes = volume.to_vdb(time);
    write_atomically(&args.out, |w| std::io::Write::write_all(w, &bytes))?;
    let when = match time {
        Some(t) => format!("at t = {t:.2} s"),
        None => format!("from {}", path.display()),
    };
    eprintln!(
        "wrote {}: density{} of {} blobs {when}, {} active voxels of {} m, mass on the grid {:.6} of {:.6} ({} bytes), {}",
        args.out.display(),
        if volume.emission.is_some() { " and emission" } else { "" },
        grouped(list.blobs.len()),
        grouped(volume.active_voxels() as usize),
        args.voxel,
        volume.grid_mass(),
        volume.mass,
        grouped(bytes.len()),
        wall(start)
    );
    let lost = (volume.grid_mass() / volume.mass - 1.0).abs();
    if volume.mass > 0.0 && lost > 0.01 {
        eprintln!(
            "note: the grid holds {:.1} % {} mass than the blobs: voxels of {} m are too coarse for the narrowest blobs; a smaller --voxel samples them faithfully",
            100.0 * lost,
            if volume.grid_mass() < volume.mass { "less" } else { "more" },
            args.voxel
        );
    }
    Ok(())
}
