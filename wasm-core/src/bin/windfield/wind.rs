//! `windfield wind`: the scene's whole wind u = u_l + u_s (m/s, world axes; what the solids
//! make of it included, carried eddies traced back, the flow's u_g inside its box) at one time,
//! or at each frame of a series, at given points or over a box of cells, for other programs
//! (docs/FORMATS.md, the command line).
//!
//! Without a flow the wind at T is a function of T alone: it is sampled at once, nothing is
//! simulated. With an enabled flow u_g is the state of a solver stepped under the gas's heat,
//! so the scene is simulated to T (whole steps of `simulation.dt`, under the step budget) and
//! the simulation's wind sampled then; a series (`--frames A..B --fps F`) is one simulation,
//! sampled at each frame's time k/F as it passes it, so frame k is what `--seconds k/F`
//! writes.

use super::atomic::write_atomically;
use super::failure::Failure;
use super::frames::{check_fps, FrameRange};
use super::input::{read_scene, read_text};
use super::moment::check_seconds;
use super::summary::{grouped, wall};
use clap::Args;
use glam::Vec3;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;
use windfield::export::vector_grid::VectorGrid;
use windfield::field::{npy, TurbulentField};
use windfield::scene::limits::MAX_COORD;
use windfield::wind::Wind;
use windfield::{Scene, Simulation};

/// Most points one run samples (as many as a field's lattice may hold).
pub const MAX_POINTS: usize = 1 << 24;
/// Most steps of `simulation.dt` the carried coordinates are traced back in; longer phases
/// are traced in this many equal steps.
pub const MAX_TRACE_STEPS: f64 = 10_000.0;

#[derive(Args)]
pub struct WindArgs {
    /// Scene file (JSON, format version 1).
    scene: PathBuf,
    /// The time (s), 0 or more (with a flow, at most 1,000,000 steps of simulation.dt).
    #[arg(long, allow_hyphen_values = true)]
    seconds: Option<f64>,
    /// A series instead of one time: frames k in the half-open range A..B at t = k/fps,
    /// written as one JSON array of frames, each an array of [u, v, w].
    #[arg(long, value_name = "A..B", allow_hyphen_values = true)]
    frames: Option<String>,
    /// With --frames: frames per second.
    #[arg(long, requires = "frames", allow_hyphen_values = true)]
    fps: Option<f64>,
    /// A JSON array of points [x, y, z] (m); the output (.json) is an array of [u, v, w]
    /// (m/s) in the same order.
    #[arg(long, required_unless_present = "bounds", conflicts_with_all = ["bounds", "cells"])]
    points: Option<PathBuf>,
    /// A box X0,Y0,Z0,X1,Y1,Z1 (m): the wind at the centres of its NX × NY × NZ cells (--n),
    /// x fastest, written as .npy (float32, shape (NZ, NY, NX, 3)), .vdb (a Vec3SGrid `wind`) or .json.
    #[arg(
        long = "box",
        id = "bounds",
        value_name = "X0,Y0,Z0,X1,Y1,Z1",
        requires = "cells",
        allow_hyphen_values = true
    )]
    bounds: Option<String>,
    /// The box's cells NX,NY,NZ (each at least 1, at most 2^24 in all).
    #[arg(
        long = "n",
        id = "cells",
        value_name = "NX,NY,NZ",
        requires = "bounds",
        allow_hyphen_values = true
    )]
    cells: Option<String>,
    /// Output file: .json, or for a box at one time .npy or .vdb too.
    #[arg(long)]
    out: PathBuf,
}

/// What the output's extension says to write.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Format {
    Json,
    Npy,
    Vdb,
}

/// The output format of `path` (`points` or a `series`: only JSON), or a refusal naming
/// `--out`.
fn format_of(path: &Path, points: bool, series: bool) -> Result<Format, Failure> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "json" => Ok(Format::Json),
        "npy" | "vdb" if series => Err(Failure::Input(
            "--out: a series (--frames) is written as .json (an array of frames, each an array of [u, v, w])".into(),
        )),
        "npy" if !points => Ok(Format::Npy),
        "npy" => Err(Failure::Input(
            "--out: the wind at --points is written as .json (an array of [u, v, w])".into(),
        )),
        "vdb" if !points => Ok(Format::Vdb),
        "vdb" => Err(Failure::Input(
            "--out: the wind at --points is written as .json (an array of [u, v, w])".into(),
        )),
        "" => Err(Failure::Input(format!(
            "--out: name the file {}, the format of the wind (got {:?})",
            if points { ".json" } else { ".json, .npy or .vdb" },
            path.display().to_string()
        ))),
        // In the words of every command's refusal of a format it does not write.
        e => Err(Failure::Input(if points {
            format!("--out: windfield writes the wind at --points as JSON, not .{e} (name the file .json)")
        } else {
            format!("--out: windfield writes the wind as JSON, NumPy or OpenVDB, not .{e} (name the file .json, .npy or .vdb)")
        })),
    }
}

/// `text` as `count` comma-separated numbers, each checked by `ok`, for `flag`.
fn numbers<T: std::str::FromStr>(
    flag: &str,
    text: &str,
    count: usize,
    what: &str,
) -> Result<Vec<T>, Failure> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let bad = || Failure::Input(format!("{flag}: expected {what} (got {text:?})"));
    if parts.len() != count {
        return Err(bad());
    }
    parts
        .iter()
        .map(|p| p.parse::<T>().map_err(|_| bad()))
        .collect()
}

/// The cell centres of the box `bounds` with `cells`, x fastest, then y, then z.
/// A box of cells: their counts, the box's lower and upper corners (m), and the cell centres,
/// x fastest.
struct CellBox {
    n: [usize; 3],
    lo: [f64; 3],
    hi: [f64; 3],
}

fn box_points(bounds: &str, cells: &str) -> Result<(CellBox, Vec<Vec3>), Failure> {
    let b: Vec<f64> = numbers("--box", bounds, 6, "X0,Y0,Z0,X1,Y1,Z1: six numbers")?;
    if let Some(v) = b.iter().find(|v| !(v.is_finite() && v.abs() <= MAX_COORD)) {
        return Err(Failure::Input(format!(
            "--box: every coordinate must be a finite number within ±{MAX_COORD} m (got {v})"
        )));
    }
    for a in 0..3 {
        if b[a + 3] <= b[a] {
            return Err(Failure::Input(format!(
                "--box: the upper corner must lie above the lower one on every axis (got {} ≤ {} on {})",
                b[a + 3],
                b[a],
                ["x", "y", "z"][a]
            )));
        }
    }
    let n: Vec<i64> = numbers("--n", cells, 3, "NX,NY,NZ: three whole numbers")?;
    if n.iter().any(|&v| v < 1) {
        return Err(Failure::Input(format!(
            "--n: each count must be at least 1 (got {cells})"
        )));
    }
    let total = n.iter().map(|&v| v as u128).product::<u128>();
    if total > MAX_POINTS as u128 {
        return Err(Failure::Input(format!(
            "--n: at most {MAX_POINTS} cells in all (got {total})"
        )));
    }
    let n = [n[0] as usize, n[1] as usize, n[2] as usize];
    let mut points = Vec::with_capacity(total as usize);
    let centre = |a: usize, i: usize| b[a] + (i as f64 + 0.5) * (b[a + 3] - b[a]) / n[a] as f64;
    for z in 0..n[2] {
        for y in 0..n[1] {
            for x in 0..n[0] {
                points.push(Vec3::new(
                    centre(0, x) as f32,
                    centre(1, y) as f32,
                    centre(2, z) as f32,
                ));
            }
        }
    }
    let cells = CellBox {
        n,
        lo: [b[0], b[1], b[2]],
        hi: [b[3], b[4], b[5]],
    };
    Ok((cells, points))
}

/// The points of a JSON file: an array of [x, y, z] (m).
fn read_points(path: &Path) -> Result<Vec<Vec3>, Failure> {
    let text = read_text(path)?;
    let list: Vec<[f64; 3]> = serde_json::from_str(&text).map_err(|e| {
        Failure::Input(format!(
            "{}: {}",
            path.display(),
            points_refusal(&text)
                .unwrap_or_else(|| format!("expected a JSON array of points [x, y, z]: {e}"))
        ))
    })?;
    if list.len() > MAX_POINTS {
        return Err(Failure::Input(format!(
            "{}: at most {MAX_POINTS} points (got {})",
            path.display(),
            list.len()
        )));
    }
    list.iter()
        .enumerate()
        .map(|(i, p)| {
            for (c, v) in p.iter().enumerate() {
                if !(v.is_finite() && v.abs() <= MAX_COORD) {
                    return Err(Failure::Input(format!(
                        "{}: [{i}][{c}]: must be a finite number within ±{MAX_COORD} m (got {v})",
                        path.display()
                    )));
                }
            }
            Ok(Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32))
        })
        .collect()
}

/// Why a points file that does not read as an array of [x, y, z] is refused, naming the point:
/// read again as lists of numbers of any length, the first that is not three, or the path of
/// what is not a number (None where the text is not such lists at all: the JSON error tells).
fn points_refusal(text: &str) -> Option<String> {
    let read: Result<Vec<Vec<f64>>, _> =
        serde_path_to_error::deserialize(&mut serde_json::Deserializer::from_str(text));
    match read {
        Ok(lists) => lists
            .iter()
            .enumerate()
            .find(|(_, p)| p.len() != 3)
            .map(|(i, p)| {
                format!(
                    "[{i}]: must be a point [x, y, z] of 3 numbers (got {} item{})",
                    p.len(),
                    if p.len() == 1 { "" } else { "s" }
                )
            }),
        Err(e) if e.path().iter().next().is_some() => Some(format!("{}: {}", e.path(), e.inner())),
        Err(_) => None,
    }
}

/// The wind of `scene` (its field synthesised, with the vector potential when it has solids).
fn wind_of(scene: &Scene, bad: impl Fn(windfield::ParamError) -> Failure) -> Result<Wind, Failure> {
    let field = if scene.field.amplitude > 0.0 {
        let params = scene.field_params();
        let field = if scene.needs_potential() {
            TurbulentField::generate_with_potential(&params)
        } else {
            TurbulentField::generate(&params)
        };
        Some(Arc::new(field.map_err(&bad)?))
    } else {
        None
    };
    Ok(Wind::new(scene, field))
}

/// Writes the velocities `u` as JSON: an array of [u, v, w].
fn write_json(path: &Path, u: &[Vec3]) -> Result<(), Failure> {
    let rows: Vec<[f32; 3]> = u.iter().map(|v| v.to_array()).collect();
    let text = serde_json::to_string(&rows).expect("numbers serialise");
    write_atomically(path, |w| w.write_all(text.as_bytes()))
}

/// Writes a box's samples in the format its extension names; `.vdb` is a Vec3SGrid named
/// `wind` in world metres, voxel (i, j, k) at the cell centre of the same index.
fn write_box(
    path: &Path,
    format: Format,
    cells: &CellBox,
    seconds: f64,
    u: &[Vec3],
) -> Result<(), Failure> {
    let n = cells.n;
    match format {
        Format::Vdb => {
            let (first, cell) = VectorGrid::cells_of_box(cells.lo, cells.hi, n);
            let grid = VectorGrid {
                dims: n,
                first,
                cell,
                values: u.iter().map(|v| v.to_array()).collect(),
                time: seconds,
                periodic: false,
                source: "the whole wind of a scene (Eq. 3)".into(),
            };
            let bytes = grid.to_vdb();
            write_atomically(path, |w| w.write_all(&bytes))
        }
        Format::Json => write_json(path, u),
        Format::Npy => {
            let data: Vec<f32> = u.iter().flat_map(|v| v.to_array()).collect();
            write_atomically(path, |w| npy::write_f32(w, &[n[2], n[1], n[0], 3], &data))
        }
    }
}

/// When the wind is sampled: once, or at each frame of a series.
enum Moments {
    /// `--seconds T`.
    Once(f64),
    /// `--frames A..B --fps F`: frame k at t = k/F.
    Frames(FrameRange, f64),
}

impl Moments {
    /// `--seconds`, or `--frames` with `--fps`, checked; not both.
    fn parse(args: &WindArgs) -> Result<Self, Failure> {
        match (args.seconds, &args.frames) {
            (Some(_), Some(_)) => Err(Failure::Input(
                "--frames: a series samples the times of its frames, --seconds one time: give one of them, not both".into(),
            )),
            (Some(t), None) => {
                check_seconds(t)?;
                Ok(Self::Once(t))
            }
            (None, Some(frames)) => {
                let range = FrameRange::parse(frames).map_err(Failure::Input)?;
                let fps = args.fps.ok_or_else(|| {
                    Failure::Input(
                        "--fps: required with --frames (frames per second of the series)".into(),
                    )
                })?;
                Ok(Self::Frames(range, check_fps(fps).map_err(Failure::Input)?))
            }
            (None, None) => Err(Failure::Input(
                "give --seconds T, or --frames A..B with --fps F".into(),
            )),
        }
    }

    /// The times (s), in increasing order.
    fn times(&self) -> Vec<f64> {
        match *self {
            Self::Once(t) => vec![t],
            Self::Frames(range, fps) => (range.start..range.end).map(|k| k as f64 / fps).collect(),
        }
    }

    /// How many times.
    fn count(&self) -> u64 {
        match self {
            Self::Once(_) => 1,
            Self::Frames(range, _) => range.end - range.start,
        }
    }
}

/// The whole wind of `scene` (read from `file`) at `points` at each of `times` (s, in
/// increasing order): without a flow its wind sampled at each time; with one, one simulation
/// run through the times (refused over its budget for the last one), its wind sampled as it
/// passes each.
fn sample_at(
    scene: Scene,
    points: &[Vec3],
    times: &[f64],
    file: &str,
) -> Result<Vec<Vec<Vec3>>, Failure> {
    let bad = |e: windfield::ParamError| Failure::Input(format!("{file}: {e}"));
    // Carried coordinates are traced back in steps of the scene's dt (at most 10,000 a phase).
    let trace = scene
        .simulation
        .dt
        .max(scene.field.carry_period() / MAX_TRACE_STEPS);
    if scene.active_flow().is_none() {
        let wind = wind_of(&scene, bad)?;
        return Ok(times
            .iter()
            .map(|&t| wind.sample(points, t, trace))
            .collect());
    }
    // The budget holds for the last time, told before the solver's memory is taken.
    let last = times.last().copied().unwrap_or(0.0);
    scene.budgeted_steps(last).map_err(bad)?;
    let mut sim = Simulation::new(scene).map_err(bad)?;
    Ok(times
        .iter()
        .map(|&t| {
            sim.run(sim.steps_for(t) - sim.steps());
            sim.wind.sample(points, t, trace)
        })
        .collect())
}

/// Writes a series as JSON: an array of frames, each an array of [u, v, w], each frame the
/// bytes one time's JSON has.
fn write_series(path: &Path, frames: &[Vec<Vec3>]) -> Result<(), Failure> {
    let rows: Vec<Vec<[f32; 3]>> = frames
        .iter()
        .map(|u| u.iter().map(|v| v.to_array()).collect())
        .collect();
    let text = serde_json::to_string(&rows).expect("numbers serialise");
    write_atomically(path, |w| w.write_all(text.as_bytes()))
}

pub fn run(args: WindArgs) -> Result<(), Failure> {
    let start = Instant::now();
    let moments = Moments::parse(&args)?;
    let series = matches!(moments, Moments::Frames(..));
    let format = format_of(&args.out, args.points.is_some(), series)?;
    let scene = read_scene(&args.scene)?;
    let (cells, points) = match (&args.points, &args.bounds, &args.cells) {
        (Some(p), _, _) => (None, read_points(p)?),
        (None, Some(b), Some(n)) => {
            let (n, p) = box_points(b, n)?;
            (Some(n), p)
        }
        _ => {
            return Err(Failure::Input(
                "give --points FILE.json, or --box X0,Y0,Z0,X1,Y1,Z1 with --n NX,NY,NZ".into(),
            ))
        }
    };
    let samples = moments.count() as u128 * points.len() as u128;
    if samples > MAX_POINTS as u128 {
        return Err(Failure::Input(format!(
            "--frames: at most {MAX_POINTS} samples in all, frames × points (got {} × {})",
            moments.count(),
            points.len()
        )));
    }
    let file = args.scene.display().to_string();
    let flow = scene.active_flow().is_some();
    let times = moments.times();
    let frames = sample_at(scene, &points, &times, &file)?;
    match (&moments, &cells) {
        (Moments::Frames(..), _) => write_series(&args.out, &frames)?,
        (Moments::Once(t), Some(cells)) => write_box(&args.out, format, cells, *t, &frames[0])?,
        (Moments::Once(_), None) => write_json(&args.out, &frames[0])?,
    }
    let what = match &cells {
        Some(CellBox { n: [x, y, z], .. }) => format!("{x}×{y}×{z} cells"),
        None => format!("{} points", grouped(points.len())),
    };
    let when = match moments {
        // Any time is a moment of the wind: past a million seconds it is written as a number is
        // in a message (1e300), not in 300 digits.
        Moments::Once(t) if t.abs() >= 1e6 => format!("at t = {} s", windfield::error::number(t)),
        Moments::Once(t) => format!("at t = {t:.2} s"),
        Moments::Frames(range, fps) => format!(
            "in frames {}..{} at {fps} fps (t = {:.2} to {:.2} s)",
            range.start,
            range.end,
            times[0],
            times[times.len() - 1]
        ),
    };
    eprintln!(
        "wrote {}: the wind{} at {what} {when}, {}",
        args.out.display(),
        if flow { ", its flow simulated," } else { "" },
        wall(start)
    );
    Ok(())
}
