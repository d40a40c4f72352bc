//! The real-time view's light volume (docs/ARCHITECTURE.md), computed here exactly as the browser's
//! light pass computes it (`web/src/views/volume/light-pass.js`), from the density volume of
//! [`super::volume`].
//!
//! **Light.** For each light, the optical column ∫ρ ds from a point towards the light (S_k of
//! Eq. 25 is exp(−κ_t ∫ρ ds)) is stored on a grid of half the resolution (voxels of side 2h
//! from the same corner). From each of its voxel centres the column is a midpoint sum along
//! the direction to the light, over the part of the path inside the density grid's box (no gas
//! lies outside) and short of a point light, in n = ⌈length / (step·h)⌉ equal steps.
//!
//! **Objects.** The columns are the gas's alone and run through opaque objects: S_k's object
//! factor (zero where an object blocks the light) is the exact ray test
//! [`crate::render::occluded`], made per sample by the march and per fragment by the objects'
//! material (`web/src/views/shaders/occluders.js`), not stored here. The objects read these
//! columns at their own surfaces, where a column made infinite by the object behind the
//! surface (a floor, under every voxel below it) would darken the lit surface itself.

use crate::error::ParamError;
use crate::frame::packed::PackedFrame;
use crate::frame::volume::{splat, DensityVolume, VoxelGrid};
use crate::render::occluded;
use crate::scene::blob_list::{Light, Object};
use glam::Vec3;

/// Most lights the GPU views draw: a light volume holds one per channel. (A scene may have more,
/// [`crate::scene::limits::MAX_LIGHTS`]; the CPU reference still draws them all.)
pub const VIEW_LIGHTS: usize = 4;

/// Where a light is, seen from the gas.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Towards {
    /// A point light at this position (m).
    Point(Vec3),
    /// A directional light: the unit vector towards it.
    Direction(Vec3),
}

impl Towards {
    /// Where a blob list's light is (a directional light travels along `direction`).
    pub fn of(light: &Light) -> Self {
        match light {
            Light::Point { position, .. } => Towards::Point(Vec3::from_array(*position)),
            Light::Directional { direction, .. } => {
                Towards::Direction(-Vec3::from_array(*direction).normalize())
            }
        }
    }

    /// Unit direction from `x` towards the light and the distance to it (∞ if directional).
    pub fn from(self, x: Vec3) -> (Vec3, f32) {
        match self {
            Towards::Point(p) => {
                let d = p - x;
                let len = d.length();
                (d.normalize_or_zero(), len)
            }
            Towards::Direction(d) => (d, f32::INFINITY),
        }
    }
}

/// Distance from `x` (inside the box [lo, hi]) along unit `d` to the box's boundary.
pub fn exit_distance(x: Vec3, d: Vec3, lo: Vec3, hi: Vec3) -> f32 {
    (0..3)
        .map(|a| {
            if d[a] > 0.0 {
                (hi[a] - x[a]) / d[a]
            } else if d[a] < 0.0 {
                (lo[a] - x[a]) / d[a]
            } else {
                f32::INFINITY
            }
        })
        .fold(f32::INFINITY, f32::min)
        .max(0.0)
}

/// The column ∫ρ ds from `x` towards `light` through `volume`, in midpoint steps of at most
/// `step × h` (see the module's comment).
pub fn column(volume: &DensityVolume, light: Towards, x: Vec3, step: f32) -> f32 {
    let (d, to_light) = light.from(x);
    if d == Vec3::ZERO {
        return 0.0;
    }
    let grid = &volume.grid;
    let length = exit_distance(x, d, grid.lo, grid.hi()).min(to_light);
    if length <= 0.0 {
        return 0.0;
    }
    let n = (length / (step * grid.h)).ceil().max(1.0);
    midpoint_column(volume, x, d, length, n as u32)
}

/// ∫ρ ds over x + s·d, 0 ≤ s ≤ `length`, through `volume` as a midpoint sum of `n` equal steps.
fn midpoint_column(volume: &DensityVolume, x: Vec3, d: Vec3, length: f32, n: u32) -> f32 {
    let ds = length / n as f32;
    (0..n)
        .map(|k| volume.rho(x + d * ((k as f32 + 0.5) * ds)))
        .sum::<f32>()
        * ds
}

/// The light volume: [`column()`] towards each of up to [`VIEW_LIGHTS`] lights (one per channel,
/// unused channels 0) at the centres of [`VoxelGrid::halved`].
pub fn light_columns(
    volume: &DensityVolume,
    lights: &[Towards],
    step: f32,
) -> (VoxelGrid, Vec<f32>) {
    let grid = volume.grid.halved();
    let mut out = vec![0.0f32; VIEW_LIGHTS * grid.len()];
    for k in 0..grid.dims[2] {
        for j in 0..grid.dims[1] {
            for i in 0..grid.dims[0] {
                let x = grid.centre(i, j, k);
                let idx = grid.index(i, j, k);
                for (l, light) in lights.iter().take(VIEW_LIGHTS).enumerate() {
                    out[VIEW_LIGHTS * idx + l] = column(volume, *light, x, step);
                }
            }
        }
    }
    (grid, out)
}

/// How far towards a light the real-time march sums the column itself, through the density
/// volume, before it reads the light volume: in voxels of the density grid (two voxels of the
/// light grid). The light volume holds columns at centres 2h apart; in dense, fine gas a column
/// grows from nothing to several optical depths within one blob, and trilinear interpolation
/// across that jump lends the lit skin of the gas the column of its inside. Read past the near
/// part, the light volume is interpolated where the path has left that skin.
pub const NEAR_COLUMN_VOXELS: f32 = 4.0;
/// Midpoint steps of the near part of the column (one density voxel each).
pub const NEAR_COLUMN_STEPS: u32 = 4;

/// The light volume's column (channel `k` of `columns` on `light_grid`) towards `light` from
/// `x`, as the march and the objects' material read it (`volumeColumn` in
/// `web/src/views/shaders/volume-shadow.js`): interpolated at `x` inside the density grid's box
/// `box_grid`; outside it, where the path to the light enters the box (no gas lies outside), or
/// 0 if it never does.
pub fn stored_column(
    box_grid: &VoxelGrid,
    light_grid: &VoxelGrid,
    columns: &[f32],
    k: usize,
    light: Towards,
    x: Vec3,
) -> f32 {
    let (lo, hi) = (box_grid.lo, box_grid.hi());
    let mut p = x;
    if x.cmplt(lo).any() || x.cmpgt(hi).any() {
        let (d, to_light) = light.from(x);
        let Some(enter) = box_span(x, d, to_light, lo, hi) else {
            return 0.0;
        };
        p = x + d * enter;
    }
    light_grid.sample(columns, VIEW_LIGHTS, k, p)
}

/// Where the ray x + s·d, 0 ≤ s ≤ `s_max`, enters the box [lo, hi] (slab test), or None if it
/// misses.
fn box_span(x: Vec3, d: Vec3, s_max: f32, lo: Vec3, hi: Vec3) -> Option<f32> {
    let inv = d.recip();
    let (a, b) = ((lo - x) * inv, (hi - x) * inv);
    let (t_min, t_max) = (a.min(b), a.max(b));
    let near = t_min.max_element().max(0.0);
    let far = t_max.min_element().min(s_max);
    (near <= far).then_some(near)
}

/// The column ∫ρ ds from `x` towards `light` as the real-time march takes it (`shadowColumn` in
/// `march-glsl.js`): the first [`NEAR_COLUMN_VOXELS`]·h (short of a point light) as a midpoint
/// sum of [`NEAR_COLUMN_STEPS`] samples of `volume`, the rest from the light volume
/// ([`stored_column`]) at the near part's end.
pub fn march_column(
    volume: &DensityVolume,
    light_grid: &VoxelGrid,
    columns: &[f32],
    k: usize,
    light: Towards,
    x: Vec3,
) -> f32 {
    let (d, to_light) = light.from(x);
    let reach = (NEAR_COLUMN_VOXELS * volume.grid.h).min(to_light);
    let near = midpoint_column(volume, x, d, reach, NEAR_COLUMN_STEPS);
    let far = if reach < to_light {
        stored_column(&volume.grid, light_grid, columns, k, light, x + d * reach)
    } else {
        0.0
    };
    near + far
}

/// S_k at `x` inside the gas as the real-time march takes it (Eq. 25, `march-glsl.js`): zero
/// where an object of `objects` lies between `x` and the light ([`occluded`]), else
/// exp(−κ_t × [`march_column`]).
pub fn transmittance(
    volume: &DensityVolume,
    (light_grid, columns): (&VoxelGrid, &[f32]),
    k: usize,
    light: Towards,
    objects: &[Object],
    kappa: Vec3,
    x: Vec3,
) -> Vec3 {
    let (d, to_light) = light.from(x);
    if occluded(objects, x, d, to_light) {
        return Vec3::ZERO;
    }
    (-kappa * march_column(volume, light_grid, columns, k, light, x)).exp()
}

/// The light volume of `frame` on `grid`: [`light_columns`] towards the first [`VIEW_LIGHTS`]
/// of `lights` in steps of `step × h` (`step` must be positive), [`VIEW_LIGHTS`] floats a voxel
/// of [`VoxelGrid::halved`].
pub fn light_twin(
    frame: &PackedFrame,
    grid: &VoxelGrid,
    lights: &[Light],
    step: f32,
) -> Result<Vec<f32>, ParamError> {
    if !(step.is_finite() && step > 0.0) {
        return Err(ParamError::new("light volume", "step must be positive"));
    }
    let towards: Vec<Towards> = lights.iter().map(Towards::of).collect();
    Ok(light_columns(&splat(frame, grid), &towards, step).1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_column_of_a_uniform_slab_is_its_density_times_the_path() {
        // One wide layer of density ρ0 fills the box; a directional light straight up.
        let g = VoxelGrid {
            lo: Vec3::ZERO,
            h: 0.1,
            dims: [4, 10, 4],
        };
        let v = DensityVolume {
            grid: g,
            density: [1.5, 0.0, 0.0, 0.0].repeat(g.len()),
            source: vec![0.0; 4 * g.len()],
        };
        let x = Vec3::new(0.2, 0.25, 0.2);
        let up = column(&v, Towards::Direction(Vec3::Y), x, 1.0);
        assert!((up - 1.5 * 0.75).abs() < 1e-5, "{up}");
        // A point light inside the box: only the path up to it.
        let near = column(&v, Towards::Point(Vec3::new(0.2, 0.65, 0.2)), x, 1.0);
        assert!((near - 1.5 * 0.4).abs() < 1e-5, "{near}");
        let (lg, cols) = light_columns(&v, &[Towards::Direction(Vec3::Y)], 1.0);
        assert_eq!(lg.dims, [2, 5, 2]);
        // The lowest light voxel's centre is 0.1 m up: 0.9 m of gas above it.
        assert!((cols[0] - 1.5 * 0.9).abs() < 1e-5, "{}", cols[0]);
        assert_eq!(cols[1], 0.0);
    }
}
