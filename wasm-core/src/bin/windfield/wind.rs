//! `windfield wind`: the scene's whole wind u = u_l + u_s (m/s, world axes; what the solids
//! make of it included, carried eddies traced back) at one time, at given points or over a box
//! of cells, for other programs (docs/FORMATS.md, the command line).

use super::atomic::write_atomically;
use super::failure::Failure;
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
use windfield::Scene;

/// Most points one run samples (as many as a field's lattice may hold).
pub const MAX_POINTS: usize = 1 << 24;
/// Most steps of `simulation.dt` the carried coordinates are traced back in; longer phases
/// are traced in this many equal steps.
pub const MAX_TRACE_STEPS: f64 = 10_000.0;

#[derive(Args)]
pub struct WindArgs {
    /// Scene file (JSON, format version 1).
    scene: PathBuf,
    /// The time (s), 0 or more (at most 1,000,000 steps of simulation.dt).
    #[arg(long, allow_hyphen_values = true)]
    seconds: f64,
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
    /// Output file: .json, or for a box .npy or .vdb too.
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

/// The output format of `path` (`points`: only JSON), or a refusal naming `--out`.
fn format_of(path: &Path, points: bool) -> Result<Format, Failure> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "json" => Ok(Format::Json),
        "npy" if !points => Ok(Format::Npy),
        "npy" => Err(Failure::Input(
            "--out: the wind at --points is written as .json (an array of [u, v, w])".into(),
        )),
        "vdb" if !points => Ok(Format::Vdb),
        "vdb" => Err(Failure::Input(
            "--out: the wind at --points is written as .json (an array of [u, v, w])".into(),
        )),
        _ => Err(Failure::Input(format!(
            "--out: must end in .json{} (got {:?})",
            if points { "" } else { ", .npy or .vdb" },
            path.display().to_string()
        ))),
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
            "{}: expected a JSON array of points [x, y, z]: {e}",
            path.display()
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

pub fn run(args: WindArgs) -> Result<(), Failure> {
    let start = Instant::now();
    check_seconds(args.seconds)?;
    let format = format_of(&args.out, args.points.is_some())?;
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
    let file = args.scene.display().to_string();
    let wind = wind_of(&scene, |e| Failure::Input(format!("{file}: {e}")))?;
    // Carried coordinates are traced back in steps of the scene's dt (at most 10,000 a phase).
    let trace = scene
        .simulation
        .dt
        .max(scene.field.carry_period() / MAX_TRACE_STEPS);
    let u = wind.sample(&points, args.seconds, trace);
    match &cells {
        Some(cells) => write_box(&args.out, format, cells, args.seconds, &u)?,
        None => write_json(&args.out, &u)?,
    }
    let what = match &cells {
        Some(CellBox { n: [x, y, z], .. }) => format!("{x}×{y}×{z} cells"),
        None => format!("{} points", grouped(points.len())),
    };
    eprintln!(
        "wrote {}: the wind at {what} at t = {:.2} s, {}",
        args.out.display(),
        args.seconds,
        wall(start)
    );
    Ok(())
}
