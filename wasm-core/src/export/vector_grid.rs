//! The wind as a vector grid for game engines and other tools: velocities (m/s, world axes) at
//! the centres of a regular box of cells, written as an OpenVDB Vec3SGrid `wind` or as a raw
//! 3-D texture with a JSON description beside it.
//!
//! **Raw texture** (`.rgb32f`): no header; NX·NY·NZ texels of three little-endian float32
//! (R, G, B = u, v, w in m/s), x fastest, then y, then z, 12 bytes a texel. The JSON beside it
//! (the file's name with `.json` added) gives the size, the box, the cell, the first texel's
//! centre, the units and the time ([`VectorGrid::description`]).
//!
//! **VDB**: every cell an active voxel; voxel (i, j, k) is cell (i, j, k), centred at
//! `first + (i, j, k) ⊙ cell` m (a ScaleMap, or a ScaleTranslateMap when the first centre is
//! not the origin, uniform when the cells are cubes), values in m/s, vector type
//! "contravariant relative" (a velocity), `is_local_space` false.
//!
//! Two sources: the small-scale field alone at one time ([`VectorGrid::field_slice`], for
//! `windfield generate`), and the whole wind of a running scene over a box
//! ([`VectorGrid::scene_wind`], for `windfield wind --box`).

use super::vdb::{self, AnyGrid, Grid, GridClass, Leaves, Meta, MetaMap, Transform};
use crate::check;
use crate::error::ParamError;
use crate::field::TurbulentField;
use crate::gas::Simulation;
use crate::scene::limits::{MAX_SECONDS, WORLD_MAPPING};
use glam::Vec3;
use serde::Serialize;

/// Most cells one grid may hold (2^28).
pub const MAX_CELLS: u64 = 1 << 28;

/// The two files a grid is written as: an OpenVDB Vec3SGrid or a raw RGB32F texture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GridFormat {
    Vdb,
    Rgb32f,
}

impl GridFormat {
    /// `vdb` or `rgb32f`, as the browser API names them; refused at `what`.
    pub fn parse(name: &str, what: &str) -> Result<Self, ParamError> {
        match name {
            "vdb" => Ok(Self::Vdb),
            "rgb32f" => Ok(Self::Rgb32f),
            _ => Err(ParamError::new(
                what,
                format!("must be 'vdb' or 'rgb32f' (got {name:?})"),
            )),
        }
    }
}

/// The world mapping of one time slice of a field ([`VectorGrid::field_slice`]'s arguments):
/// `period` L (m, three), `time_period` T (s), `amplitude` A and the time `t` (s), each checked
/// against the ranges a scene's `field` has ([`WORLD_MAPPING`]) and `t` from 0 to
/// [`MAX_SECONDS`]; refusals name the argument (`period[1]`, `time_period`, `amplitude`, `t`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliceMapping {
    pub period: [f64; 3],
    pub time_period: f64,
    pub amplitude: f64,
    pub t: f64,
}

impl SliceMapping {
    pub fn new(
        period: &[f64],
        time_period: f64,
        amplitude: f64,
        t: f64,
    ) -> Result<Self, ParamError> {
        let period: [f64; 3] = period.try_into().map_err(|_| {
            ParamError::new(
                "period",
                format!("must be three lengths in metres (got {})", period.len()),
            )
        })?;
        let [lo, hi] = WORLD_MAPPING.period;
        for (i, &l) in period.iter().enumerate() {
            check::range(&format!("period[{i}]"), l, lo, hi)?;
        }
        let [lo, hi] = WORLD_MAPPING.time_period;
        check::range("time_period", time_period, lo, hi)?;
        let [lo, hi] = WORLD_MAPPING.amplitude;
        check::range("amplitude", amplitude, lo, hi)?;
        check::range("t", t, 0.0, MAX_SECONDS)?;
        Ok(Self {
            period,
            time_period,
            amplitude,
            t,
        })
    }
}

/// Velocities on a regular box of cells.
#[derive(Debug, Clone, PartialEq)]
pub struct VectorGrid {
    /// Cells along x, y, z.
    pub dims: [usize; 3],
    /// The centre of cell (0, 0, 0) (m).
    pub first: [f64; 3],
    /// The cell's sides (m).
    pub cell: [f64; 3],
    /// Velocities (m/s), x fastest.
    pub values: Vec<[f32; 3]>,
    /// The moment sampled (s).
    pub time: f64,
    /// Whether the grid is one period of a periodic field (it tiles without seams).
    pub periodic: bool,
    /// What was sampled, in words.
    pub source: String,
}

/// The JSON beside a raw texture.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TextureDescription {
    /// `windfield-vector-texture/1`.
    pub format: &'static str,
    /// The raw file's layout, in words.
    pub layout: &'static str,
    /// Texels along x, y, z.
    pub size: [usize; 3],
    /// The box the texels tile (m): the outer faces of the outermost cells.
    #[serde(rename = "box")]
    pub bounds: BoxBounds,
    /// A texel's sides (m).
    pub cell: [f64; 3],
    /// The centre of texel (0, 0, 0) (m); texel (i, j, k) is centred at first + (i, j, k) ⊙ cell.
    pub first_center: [f64; 3],
    pub units: Units,
    /// The moment sampled (s).
    pub time: f64,
    /// The grid is one period of the field: it tiles (wrap sampling) without seams.
    pub periodic: bool,
    /// The largest speed (m/s).
    pub max_speed: f32,
    pub source: String,
    pub windfield: &'static str,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BoxBounds {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Units {
    pub position: &'static str,
    pub value: &'static str,
}

/// The box's cell count, checked: each side at least one, at most [`MAX_CELLS`] in all.
fn check_dims(dims: [usize; 3], what: &str) -> Result<(), ParamError> {
    let total = dims
        .iter()
        .map(|&n| n as u64)
        .try_fold(1u64, u64::checked_mul);
    match total {
        Some(t) if dims.iter().all(|&n| n >= 1) && t <= MAX_CELLS => Ok(()),
        _ => Err(ParamError::new(
            what,
            format!(
                "must be at least one cell a side and at most 2^28 ({MAX_CELLS}) cells in all (got {}×{}×{})",
                dims[0], dims[1], dims[2]
            ),
        )),
    }
}

impl VectorGrid {
    /// The small-scale field u_s at time `t` (s) on its own lattice: one cell a lattice point,
    /// cell (i, j, k) centred at (i·Lx/nx, j·Ly/ny, k·Lz/nz) with `period` L (m), the velocity
    /// A·(L/T) ⊙ ũ(i, j, k, t·nt/T) (m/s) for `amplitude` A and `time_period` T (s): the
    /// world mapping of docs/FORMATS.md, exact at the lattice points in space and linear in time
    /// between lattice times. One period in each axis: the grid tiles.
    pub fn field_slice(
        field: &TurbulentField,
        period: [f64; 3],
        time_period: f64,
        amplitude: f64,
        t: f64,
    ) -> Self {
        let [nx, ny, nz, nt] = field.lattice.size;
        let scale = Vec3::new(period[0] as f32, period[1] as f32, period[2] as f32)
            * (amplitude / time_period) as f32;
        let q_t = t * nt as f64 / time_period;
        let mut values = Vec::with_capacity(nx * ny * nz);
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let u = field.sample_lattice([i as f64, j as f64, k as f64, q_t]);
                    values.push((Vec3::from_array(u) * scale).to_array());
                }
            }
        }
        Self {
            dims: [nx, ny, nz],
            first: [0.0; 3],
            cell: [
                period[0] / nx as f64,
                period[1] / ny as f64,
                period[2] / nz as f64,
            ],
            values,
            time: t,
            periodic: true,
            source: format!(
                "the small-scale field (seed {}, lattice {nx}x{ny}x{nz}x{nt}), period {:?} m, time period {time_period} s, amplitude {amplitude}",
                field.params.seed, period
            ),
        }
    }

    /// The whole wind u = u_l + u_s (Eq. 3) of `sim` at its current time over the box from `lo`
    /// to `hi` (m), sampled at the centres of `dims` cells (the reference evaluation,
    /// quadrilinear in the field). Refused, naming `what`, for an empty or inverted box or more
    /// than [`MAX_CELLS`] cells.
    pub fn scene_wind(
        sim: &Simulation,
        lo: [f64; 3],
        hi: [f64; 3],
        dims: [usize; 3],
        what: &str,
    ) -> Result<Self, ParamError> {
        check_dims(dims, what)?;
        if (0..3).any(|a| !(lo[a].is_finite() && hi[a].is_finite() && hi[a] > lo[a])) {
            return Err(ParamError::new(
                what,
                "the box must be X0,Y0,Z0,X1,Y1,Z1 with each upper corner above the lower",
            ));
        }
        let (first, cell) = Self::cells_of_box(lo, hi, dims);
        let t = sim.time();
        let mut values = Vec::with_capacity(dims.iter().product());
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    let p = [i, j, k]
                        .iter()
                        .enumerate()
                        .map(|(a, &n)| (first[a] + n as f64 * cell[a]) as f32)
                        .collect::<Vec<_>>();
                    let x = Vec3::new(p[0], p[1], p[2]);
                    values.push(sim.wind.velocity(x, t).to_array());
                }
            }
        }
        Ok(Self {
            dims,
            first,
            cell,
            values,
            time: t,
            periodic: false,
            source: "the whole wind of a scene (Eq. 3)".into(),
        })
    }

    /// The first cell's centre and the cells' sides (m) of `dims` cells filling the box from
    /// `lo` to `hi` (m).
    pub fn cells_of_box(lo: [f64; 3], hi: [f64; 3], dims: [usize; 3]) -> ([f64; 3], [f64; 3]) {
        let cell = [0, 1, 2].map(|a| (hi[a] - lo[a]) / dims[a] as f64);
        ([0, 1, 2].map(|a| lo[a] + 0.5 * cell[a]), cell)
    }

    /// The grid's file in `format`: [`Self::to_vdb`] or [`Self::to_rgb32f`].
    pub fn to_file(&self, format: GridFormat) -> Vec<u8> {
        match format {
            GridFormat::Vdb => self.to_vdb(),
            GridFormat::Rgb32f => self.to_rgb32f(),
        }
    }

    /// The raw texture: little-endian RGB32F, x fastest (see the module's comment).
    pub fn to_rgb32f(&self) -> Vec<u8> {
        self.values
            .iter()
            .flat_map(|v| v.iter().flat_map(|c| c.to_le_bytes()))
            .collect()
    }

    /// The JSON description written beside the raw texture.
    pub fn description(&self) -> TextureDescription {
        let lo = [0, 1, 2].map(|a| self.first[a] - 0.5 * self.cell[a]);
        let hi = [0, 1, 2].map(|a| lo[a] + self.dims[a] as f64 * self.cell[a]);
        TextureDescription {
            format: "windfield-vector-texture/1",
            layout: "RGB32F: 3 little-endian float32 a texel (u, v, w in m/s), x fastest, then y, then z; no header",
            size: self.dims,
            bounds: BoxBounds { min: lo, max: hi },
            cell: self.cell,
            first_center: self.first,
            units: Units {
                position: "m",
                value: "m/s",
            },
            time: self.time,
            periodic: self.periodic,
            max_speed: self
                .values
                .iter()
                .map(|v| Vec3::from_array(*v).length())
                .fold(0.0, f32::max),
            source: self.source.clone(),
            windfield: env!("CARGO_PKG_VERSION"),
        }
    }

    /// The VDB file: a Vec3SGrid `wind` (see the module's comment).
    pub fn to_vdb(&self) -> Vec<u8> {
        let mut leaves: Leaves<[f32; 3]> = Leaves::new();
        let [nx, ny, _] = self.dims;
        for (n, v) in self.values.iter().enumerate() {
            let (i, j, k) = (
                (n % nx) as i32,
                ((n / nx) % ny) as i32,
                (n / (nx * ny)) as i32,
            );
            let leaf = leaves.entry(vdb::leaf_origin(i, j, k)).or_default();
            let o = vdb::leaf_offset(i, j, k);
            leaf.values[o] = *v;
            leaf.set_active(o, true);
        }
        let mut meta = MetaMap::new();
        meta.insert("creator".into(), Meta::String(super::creator()));
        meta.insert("windfield_time".into(), Meta::Double(self.time));
        meta.insert("windfield_units".into(), Meta::String("m/s".into()));
        meta.insert("windfield_source".into(), Meta::String(self.source.clone()));
        let grid = Grid {
            name: "wind",
            class: GridClass::Unknown,
            vector_type: Some("contravariant relative"),
            transform: Transform {
                scale: self.cell,
                translation: self.first,
            },
            leaves: &leaves,
            metadata: meta,
        };
        let mut file_meta = MetaMap::new();
        file_meta.insert("creator".into(), Meta::String(super::creator()));
        vdb::write(&[AnyGrid::Vec3(grid)], &file_meta)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_slice_mapping_is_refused_by_its_argument_in_the_scene_ranges() {
        let ok = SliceMapping::new(&[2.0, 2.0, 2.0], 8.0, 1.0, 1e6).expect("in range");
        assert_eq!(ok.period, [2.0; 3]);
        let refused = |p: &[f64], tp: f64, a: f64, t: f64| {
            SliceMapping::new(p, tp, a, t)
                .expect_err("out of range")
                .to_string()
        };
        assert_eq!(
            refused(&[2.0, 2.0], 8.0, 1.0, 0.0),
            "period: must be three lengths in metres (got 2)"
        );
        assert_eq!(
            refused(&[2.0, 0.0, 2.0], 8.0, 1.0, 0.0),
            "period[1]: must be a finite number between 0.001 and 10000 (got 0)"
        );
        assert!(refused(&[2.0; 3], 0.0, 1.0, 0.0).starts_with("time_period: "));
        assert!(refused(&[2.0; 3], 8.0, -1.0, 0.0).starts_with("amplitude: "));
        assert!(refused(&[2.0; 3], 8.0, 1.0, f64::NAN).starts_with("t: "));
        assert!(refused(&[2.0; 3], 8.0, 1.0, 2e6).starts_with("t: "));
    }

    #[test]
    fn a_grid_format_is_vdb_or_rgb32f() {
        assert_eq!(GridFormat::parse("vdb", "format"), Ok(GridFormat::Vdb));
        assert_eq!(
            GridFormat::parse("rgb32f", "format"),
            Ok(GridFormat::Rgb32f)
        );
        assert_eq!(
            GridFormat::parse("npy", "format")
                .expect_err("refused")
                .to_string(),
            "format: must be 'vdb' or 'rgb32f' (got \"npy\")"
        );
    }
}
