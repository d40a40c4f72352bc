//! `windfield flow SCENE --seconds T --out FILE` (docs/FORMATS.md, the flow's exports): the
//! scene run to T (whole steps of `simulation.dt`, under the step budget and the flow's
//! cell-step budget) and its flow's grid written as it stands then: u_g (m/s) at the centres
//! of the cells and the gas's temperature excess T (K) on them, as NumPy, OpenVDB or JSON by
//! the extension of FILE. A scene without an enabled `flow` is refused.
//!
//! The cells are cubes of edge h from the box's lower corner (the scene's cube rule): cell
//! (i, j, k) is centred at (x0, y0, z0) + (i + ½, j + ½, k + ½)·h.

use super::atomic::write_atomically;
use super::failure::Failure;
use super::input::read_scene;
use super::moment::{check_seconds, simulated};
use super::summary::wall;
use clap::Args;
use serde::Serialize;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;
use windfield::export::vdb::{self, AnyGrid, Grid, GridClass, Leaves, Meta, MetaMap, Transform};
use windfield::field::npy;
use windfield::wind::flow::FlowGrid;
use windfield::ParamError;

#[derive(Args)]
pub struct FlowArgs {
    /// Scene file (JSON, format version 1) with an enabled "flow".
    scene: PathBuf,
    /// The time (s), 0 or more (rounded to whole steps of simulation.dt, at most 1,000,000 of
    /// them and 1e10 cell-steps of the flow).
    #[arg(long, allow_hyphen_values = true)]
    seconds: f64,
    /// Output file: .npy (float32, shape (nz, ny, nx, 4): u, v, w in m/s, then T in K), .vdb
    /// (a Vec3SGrid `velocity` and a FloatGrid `temperature`) or .json.
    #[arg(long)]
    out: PathBuf,
}

/// What the output's extension says to write.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Format {
    Npy,
    Vdb,
    Json,
}

/// The format `out` names, or a refusal naming `--out` in the words of every command's.
fn format_of(out: &Path) -> Result<Format, Failure> {
    let ext = out
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("npy") => Ok(Format::Npy),
        Some("vdb") => Ok(Format::Vdb),
        Some("json") => Ok(Format::Json),
        Some(e) => Err(Failure::Input(format!(
            "--out: windfield writes the flow's grid as NumPy, OpenVDB or JSON, not .{e} (name the file .npy, .vdb or .json)"
        ))),
        None => Err(Failure::Input(format!(
            "--out: name the file .npy, .vdb or .json, the format of the flow's grid (got {:?})",
            out.display().to_string()
        ))),
    }
}

/// The grid's values as the `.npy` holds them: per cell, x fastest, u, v, w (m/s) then T (K).
fn interleaved(grid: &FlowGrid) -> Vec<f32> {
    grid.temperature
        .iter()
        .zip(grid.velocity.chunks_exact(3))
        .flat_map(|(&t, u)| [u[0], u[1], u[2], t])
        .collect()
}

/// The cubes' edge h (m) of `grid`: the mean of the box's sides per cell.
fn edge(grid: &FlowGrid) -> f64 {
    (0..3)
        .map(|a| (grid.bounds[a + 3] - grid.bounds[a]) / grid.cells[a] as f64)
        .sum::<f64>()
        / 3.0
}

/// The OpenVDB file: a Vec3SGrid `velocity` (m/s, vector type "contravariant relative") and a
/// FloatGrid `temperature` (K), every cell an active voxel, voxel (i, j, k) the cell (i, j, k)
/// under a uniform transform of voxel size h translated to the centre of cell (0, 0, 0).
fn to_vdb(grid: &FlowGrid) -> Vec<u8> {
    let h = edge(grid);
    let transform = Transform {
        scale: [h; 3],
        translation: std::array::from_fn(|a| grid.bounds[a] + 0.5 * h),
    };
    let [nx, ny, _] = grid.cells;
    let index = |n: usize| {
        let (i, j, k) = (n % nx, (n / nx) % ny, n / (nx * ny));
        (i as i32, j as i32, k as i32)
    };
    let mut velocity: Leaves<[f32; 3]> = Leaves::new();
    for (n, u) in grid.velocity.chunks_exact(3).enumerate() {
        let (i, j, k) = index(n);
        let leaf = velocity.entry(vdb::leaf_origin(i, j, k)).or_default();
        let o = vdb::leaf_offset(i, j, k);
        leaf.values[o] = [u[0], u[1], u[2]];
        leaf.set_active(o, true);
    }
    let mut temperature: Leaves<f32> = Leaves::new();
    for (n, &t) in grid.temperature.iter().enumerate() {
        let (i, j, k) = index(n);
        let leaf = temperature.entry(vdb::leaf_origin(i, j, k)).or_default();
        let o = vdb::leaf_offset(i, j, k);
        leaf.values[o] = t;
        leaf.set_active(o, true);
    }
    let meta = |units: &str, what: &str| {
        let mut m = MetaMap::new();
        m.insert("creator".into(), Meta::String(windfield::export::creator()));
        m.insert("windfield_time".into(), Meta::Double(grid.time));
        m.insert("windfield_units".into(), Meta::String(units.into()));
        m.insert("windfield_source".into(), Meta::String(what.into()));
        m
    };
    let grids = [
        AnyGrid::Vec3(Grid {
            name: "velocity",
            class: GridClass::Unknown,
            vector_type: Some("contravariant relative"),
            transform,
            leaves: &velocity,
            metadata: meta("m/s", "the flow's u_g at the cells' centres"),
        }),
        AnyGrid::Float(Grid {
            name: "temperature",
            class: GridClass::Unknown,
            vector_type: None,
            transform,
            leaves: &temperature,
            metadata: meta("K", "the gas's temperature excess over the ambient air"),
        }),
    ];
    let mut file_meta = MetaMap::new();
    file_meta.insert("creator".into(), Meta::String(windfield::export::creator()));
    vdb::write(&grids, &file_meta)
}

/// The JSON file: the box, the cells, the time, u_g as one [u, v, w] a cell and T as one
/// number a cell, both in the `.npy`'s order (x fastest, then y, then z).
#[derive(Serialize)]
struct FlowJson<'a> {
    #[serde(rename = "box")]
    bounds: [f64; 6],
    cells: [usize; 3],
    time: f64,
    velocity: Vec<[f32; 3]>,
    temperature: &'a [f32],
}

fn to_json(grid: &FlowGrid) -> Vec<u8> {
    let json = FlowJson {
        bounds: grid.bounds,
        cells: grid.cells,
        time: grid.time,
        velocity: grid
            .velocity
            .chunks_exact(3)
            .map(|u| [u[0], u[1], u[2]])
            .collect(),
        temperature: &grid.temperature,
    };
    serde_json::to_vec(&json).expect("numbers serialise")
}

pub fn run(args: FlowArgs) -> Result<(), Failure> {
    let start = Instant::now();
    check_seconds(args.seconds)?;
    let scene = read_scene(&args.scene)?;
    let format = format_of(&args.out)?;
    let file = args.scene.display().to_string();
    match &scene.flow {
        None => {
            return Err(Failure::Input(format!(
                "{file}: flow: the scene has no flow to write (give it one: \"flow\": {{\"box\": [x0, y0, z0, x1, y1, z1], \"cells\": [nx, ny, nz]}})"
            )))
        }
        Some(f) if !f.enabled => {
            return Err(Failure::Input(format!(
                "{file}: flow.enabled: the scene's flow is disabled, so there is no grid to write (set flow.enabled to true)"
            )))
        }
        Some(_) => {}
    }
    let bad = |e: ParamError| Failure::Input(format!("{file}: {e}"));
    // The budgets are the scene's to tell before the solver's memory is taken.
    scene.budgeted_steps(args.seconds).map_err(bad)?;
    let sim = simulated(scene, args.seconds, bad)?;
    let grid = sim.flow_grid().expect("an enabled flow is stepped");
    let [nx, ny, nz] = grid.cells;
    let bytes = match format {
        Format::Npy => {
            let mut bytes = Vec::new();
            npy::write_f32(&mut bytes, &[nz, ny, nx, 4], &interleaved(&grid))
                .expect("writing to memory");
            bytes
        }
        Format::Vdb => to_vdb(&grid),
        Format::Json => to_json(&grid),
    };
    write_atomically(&args.out, |w| w.write_all(&bytes))?;
    let fastest = grid
        .velocity
        .chunks_exact(3)
        .map(|u| (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt())
        .fold(0.0, f32::max);
    let hottest = grid.temperature.iter().copied().fold(0.0, f32::max);
    eprintln!(
        "wrote {}: the flow's {nx}×{ny}×{nz} cells at t = {:.2} s ({} steps; fastest u_g {fastest:.3} m/s, hottest {hottest:.2} K), {}",
        args.out.display(),
        grid.time,
        sim.steps(),
        wall(start)
    );
    Ok(())
}
