//! The real-time view's volumes (docs/ARCHITECTURE.md), computed here exactly as the browser's shaders
//! compute them (`web/src/views/volume/`), so that tests can hold the GPU to this twin and this
//! twin to the reference renderer.
//!
//! **Density.** The gas's bounds are covered by cubic voxels of side h. Each voxel stores ρ
//! (Eq. 13), ρΩ and ρ(1 − Ω)Q (the two parts of the rendering model's density-weighted source, docs/FORMATS.md), built two
//! ways so that the cost does not grow with the blob count faster than a few voxels a blob:
//!
//! - A blob narrower than [`DIRECT_LIMIT`] voxels is *splatted directly*: its share of voxel
//!   (i, j, k) is a product of three 1-D averages over the voxel, Φ(x_{i+1}) − Φ(x_i) with
//!   Φ(x) = ½ erf((x − c)/(σ√2)), over the voxels within [`FOOTPRINT`] σ of its centre
//!   (at most four a side), renormalised over them.
//! - A wider blob goes through a *particle mesh*: its mass is deposited on the eight voxels
//!   around its centre with trilinear weights (cloud in cell: mass and centre of mass exact),
//!   split between the mesh classes k and k + 1 of its σ class (σ_k = √2^(k − 48) m, see
//!   `frame::packed`) with weights that keep its column through the centre, m/(2πσ²):
//!   w/σ_k² + (1 − w)/σ_{k+1}² = 1/σ², i.e. w = 2σ_k²/σ² − 1. (Keeping the variance instead
//!   puts up to 23 % too much density at the centre of a blob halfway between two classes;
//!   keeping the column errs by at most 4 % in peak density and 4 % in width.) Each class's
//!   mesh is then blurred along x, y and z by a normalised kernel whose variance is
//!   σ_k² − h²/6, the cloud-in-cell tent's h²/6 making up the rest ([`blur_kernel`]). The work
//!   is eight voxels a blob plus a few passes over the grid per class.
//!
//! Either way a blob inside the grid deposits its mass and mean: Σ ρ h³ = Σ m up to the tails
//! the blur carries past the grid's faces, which lie at least [`FOOTPRINT`] σ beyond every
//! centre.
//!
//! **Sampling.** Between voxel centres the volumes are interpolated trilinearly; beyond the
//! outermost centres they are held (clamp to edge).
//!
//! **Light.** The light volume computed from this one is [`super::light_volume`].

use crate::error::ParamError;
use crate::frame::packed::{class_sigma, PackedFrame, FOOTPRINT};
use crate::render::{erf, RenderBlob};
use glam::Vec3;
use std::collections::BTreeMap;

/// Most voxels along any axis of a grid the core is asked to fill ([`VoxelGrid::new`]).
pub const MAX_GRID_SIDE: u32 = 512;

/// Most voxels of such a grid in all (256³): its eight channels of f32 are then 512 MiB, one
/// buffer a 32-bit build (WebAssembly, at most 2³¹ − 1 bytes in one) can hold.
pub const MAX_GRID_VOXELS: u64 = 1 << 24;

/// Cubic voxels of side `h` (m) from the corner `lo`, `dims` per axis (x fastest in storage).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VoxelGrid {
    pub lo: Vec3,
    pub h: f32,
    pub dims: [usize; 3],
}

impl VoxelGrid {
    /// The grid of `dims` voxels of side `h` (m) from the corner `lo` (m), checked: `lo` finite,
    /// `h` positive and finite, each of `dims` from 1 to [`MAX_GRID_SIDE`], at most
    /// [`MAX_GRID_VOXELS`] in all.
    pub fn new(lo: [f32; 3], h: f32, dims: [u32; 3]) -> Result<Self, ParamError> {
        let sides = 1..=MAX_GRID_SIDE;
        let voxels: u64 = dims.iter().map(|&n| u64::from(n)).product();
        if lo.iter().all(|v| v.is_finite())
            && h.is_finite()
            && h > 0.0
            && dims.iter().all(|n| sides.contains(n))
            && voxels <= MAX_GRID_VOXELS
        {
            return Ok(Self {
                lo: Vec3::from_array(lo),
                h,
                dims: dims.map(|n| n as usize),
            });
        }
        Err(ParamError::new(
            "voxel grid",
            format!(
                "lo must be 3 finite numbers, h positive, dims 3 counts from 1 to {MAX_GRID_SIDE} of at most {MAX_GRID_VOXELS} voxels in all"
            ),
        ))
    }

    pub fn len(&self) -> usize {
        self.dims[0] * self.dims[1] * self.dims[2]
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The far corner of the box.
    pub fn hi(&self) -> Vec3 {
        self.lo
            + self.h
                * Vec3::new(
                    self.dims[0] as f32,
                    self.dims[1] as f32,
                    self.dims[2] as f32,
                )
    }

    /// Storage index of voxel (i, j, k).
    pub fn index(&self, i: usize, j: usize, k: usize) -> usize {
        (k * self.dims[1] + j) * self.dims[0] + i
    }

    /// Centre of voxel (i, j, k) (m).
    pub fn centre(&self, i: usize, j: usize, k: usize) -> Vec3 {
        self.lo + self.h * (Vec3::new(i as f32, j as f32, k as f32) + 0.5)
    }

    /// The light volume's grid: voxels twice as wide from the same corner, ⌈n/2⌉ per axis.
    pub fn halved(&self) -> VoxelGrid {
        VoxelGrid {
            lo: self.lo,
            h: 2.0 * self.h,
            dims: self.dims.map(|n| n.div_ceil(2)),
        }
    }

    /// Trilinear weights at `p` (trilinear sampling's, and the cloud in cell's): the lower voxel
    /// index and the fraction towards the next, per axis, clamped to the outermost centres.
    pub fn cell(&self, p: Vec3) -> ([usize; 3], [f32; 3]) {
        let g = (p - self.lo) / self.h - 0.5;
        let mut i0 = [0usize; 3];
        let mut f = [0.0f32; 3];
        for a in 0..3 {
            let n = self.dims[a];
            let x = g[a].clamp(0.0, (n - 1) as f32);
            let base = (x.floor() as usize).min(n.saturating_sub(2));
            i0[a] = base;
            f[a] = x - base as f32;
        }
        (i0, f)
    }

    /// Trilinear interpolation of channel `c` of `data` (`stride` floats per voxel) at `p`.
    pub fn sample(&self, data: &[f32], stride: usize, c: usize, p: Vec3) -> f32 {
        let (i0, f) = self.cell(p);
        let step = |a: usize| usize::from(self.dims[a] > 1);
        let mut v = 0.0;
        for corner in 0..8 {
            let o = [corner & 1, (corner >> 1) & 1, (corner >> 2) & 1];
            let w = (0..3)
                .map(|a| if o[a] == 1 { f[a] } else { 1.0 - f[a] })
                .product::<f32>();
            if w == 0.0 {
                continue;
            }
            let idx = self.index(
                i0[0] + o[0] * step(0),
                i0[1] + o[1] * step(1),
                i0[2] + o[2] * step(2),
            );
            v += w * data[stride * idx + c];
        }
        v
    }
}

/// The density volume: per voxel [ρ, ρΩ_r, ρΩ_g, ρΩ_b] and [ρ(1−Ω)Q_r, _g, _b, 0] (voxel
/// averages; ρ in mass per m³).
#[derive(Debug, Clone)]
pub struct DensityVolume {
    pub grid: VoxelGrid,
    pub density: Vec<f32>,
    pub source: Vec<f32>,
}

/// Blobs narrower than this many voxels (σ < `DIRECT_LIMIT` · h) are splatted directly.
pub const DIRECT_LIMIT: f32 = 0.5;
/// Longest blur kernel, in voxels either side of the centre.
pub const MAX_BLUR_RADIUS: usize = 32;
/// A blur narrower than this many voxels (its standard deviation) is three taps.
pub const BLUR_NARROW: f32 = 0.8;
/// A wider blur samples its Gaussian out to this many of its standard deviations.
pub const BLUR_REACH: f32 = 3.0;

/// Voxels within the footprint of a Gaussian (centre c, σ) along one axis of `n` voxels of side
/// `h` from `lo`, and its average over each, summing to 1: (first voxel, weights). Empty if the
/// footprint misses the axis.
pub fn axis_weights(c: f32, sigma: f32, lo: f32, h: f32, n: usize) -> (usize, Vec<f32>) {
    let top = n as i64 - 1;
    let first = (((c - FOOTPRINT * sigma - lo) / h).floor() as i64).clamp(0, top);
    let last = (((c + FOOTPRINT * sigma - lo) / h).floor() as i64).clamp(0, top);
    let inv = std::f32::consts::FRAC_1_SQRT_2 / sigma;
    let phi = |i: i64| 0.5 * erf((lo + i as f32 * h - c) * inv);
    let total = phi(last + 1) - phi(first);
    if total <= 1e-12 {
        return (first as usize, Vec::new());
    }
    let weights = (first..=last)
        .map(|i| (phi(i + 1) - phi(i)) / total)
        .collect();
    (first as usize, weights)
}

/// The blur that takes a cloud-in-cell deposit on voxels of side `h` to a Gaussian of `sigma`:
/// normalised taps at offsets −R..=R whose variance is σ² − h²/6 (none below zero). Below
/// [`BLUR_NARROW`] h three taps [a, 1 − 2a, a] with a = variance / (2h²); above, the Gaussian
/// sampled at the voxels within [`BLUR_REACH`] of its σ (at most [`MAX_BLUR_RADIUS`]).
pub fn blur_kernel(sigma: f32, h: f32) -> Vec<f32> {
    let variance = (sigma * sigma - h * h / 6.0).max(0.0);
    let width = variance.sqrt();
    if width < BLUR_NARROW * h {
        let a = variance / (2.0 * h * h);
        return vec![a, 1.0 - 2.0 * a, a];
    }
    let r = ((BLUR_REACH * width / h).ceil() as usize).min(MAX_BLUR_RADIUS) as i64;
    let taps: Vec<f32> = (-r..=r)
        .map(|t| {
            let x = t as f32 * h / width;
            (-0.5 * x * x).exp()
        })
        .collect();
    let total: f32 = taps.iter().sum();
    taps.iter().map(|w| w / total).collect()
}

/// Eight floats a voxel: [ρ, ρΩ_rgb] then [ρ(1−Ω)Q_rgb, 0].
const CHANNELS: usize = 8;

fn add_blob(out: &mut [f32], idx: usize, rho: f32, b: &RenderBlob) {
    let v = &mut out[CHANNELS * idx..CHANNELS * idx + CHANNELS];
    v[0] += rho;
    v[1] += rho * b.albedo.x;
    v[2] += rho * b.albedo.y;
    v[3] += rho * b.albedo.z;
    v[4] += rho * b.emission.x;
    v[5] += rho * b.emission.y;
    v[6] += rho * b.emission.z;
}

/// Blurs `mesh` (CHANNELS floats a voxel) along `axis` with `kernel` (zero beyond the grid).
fn blur_axis(grid: &VoxelGrid, mesh: &[f32], axis: usize, kernel: &[f32]) -> Vec<f32> {
    let r = (kernel.len() / 2) as i64;
    let n = grid.dims[axis] as i64;
    let stride = match axis {
        0 => 1,
        1 => grid.dims[0],
        _ => grid.dims[0] * grid.dims[1],
    };
    let mut out = vec![0.0f32; mesh.len()];
    for k in 0..grid.dims[2] {
        for j in 0..grid.dims[1] {
            for i in 0..grid.dims[0] {
                let idx = grid.index(i, j, k);
                let at = [i, j, k][axis] as i64;
                let o = &mut out[CHANNELS * idx..CHANNELS * idx + CHANNELS];
                for (t, w) in kernel.iter().enumerate() {
                    let from = at + t as i64 - r;
                    if from < 0 || from >= n {
                        continue;
                    }
                    let src = (idx as i64 + (from - at) * stride as i64) as usize;
                    for (c, v) in o.iter_mut().enumerate() {
                        *v += w * mesh[CHANNELS * src + c];
                    }
                }
            }
        }
    }
    out
}

/// Builds the density volume of `frame` on `grid` (see the module's comment). Colours as packed:
/// albedo Ω and the emitted source (1 − Ω)Q.
pub fn splat(frame: &PackedFrame, grid: &VoxelGrid) -> DensityVolume {
    let mut total = vec![0.0f32; CHANNELS * grid.len()];
    let mut meshes: BTreeMap<usize, Vec<f32>> = BTreeMap::new();
    let inv_volume = 1.0 / (grid.h * grid.h * grid.h);
    for class in &frame.classes {
        let k = class.index;
        let (s0, s1) = (class_sigma(k), class_sigma(k + 1));
        for i in class.offset..class.offset + class.count {
            let b = frame.blob(i);
            if b.sigma < DIRECT_LIMIT * grid.h {
                let w: Vec<(usize, Vec<f32>)> = (0..3)
                    .map(|a| axis_weights(b.center[a], b.sigma, grid.lo[a], grid.h, grid.dims[a]))
                    .collect();
                let scale = b.mass * inv_volume;
                for (dk, wz) in w[2].1.iter().enumerate() {
                    for (dj, wy) in w[1].1.iter().enumerate() {
                        for (di, wx) in w[0].1.iter().enumerate() {
                            let idx = grid.index(w[0].0 + di, w[1].0 + dj, w[2].0 + dk);
                            add_blob(&mut total, idx, scale * wx * wy * wz, &b);
                        }
                    }
                }
                continue;
            }
            let lower = (2.0 * s0 * s0 / (b.sigma * b.sigma) - 1.0).clamp(0.0, 1.0);
            debug_assert!((s1 * s1 - 2.0 * s0 * s0).abs() < 1e-6 * s1 * s1);
            let (i0, f) = grid.cell(b.center);
            for (mesh_class, share) in [(k, lower), (k + 1, 1.0 - lower)] {
                if share <= 0.0 {
                    continue;
                }
                let mesh = meshes
                    .entry(mesh_class)
                    .or_insert_with(|| vec![0.0; CHANNELS * grid.len()]);
                for corner in 0..8 {
                    let o = [corner & 1, (corner >> 1) & 1, (corner >> 2) & 1];
                    let w: f32 = (0..3)
                        .map(|a| if o[a] == 1 { f[a] } else { 1.0 - f[a] })
                        .product();
                    if w == 0.0 {
                        continue;
                    }
                    let step = |a: usize| usize::from(grid.dims[a] > 1);
                    let idx = grid.index(
                        i0[0] + o[0] * step(0),
                        i0[1] + o[1] * step(1),
                        i0[2] + o[2] * step(2),
                    );
                    add_blob(mesh, idx, share * w * b.mass * inv_volume, &b);
                }
            }
        }
    }
    for (mesh_class, mesh) in meshes {
        let kernel = blur_kernel(class_sigma(mesh_class), grid.h);
        let mut m = mesh;
        for axis in 0..3 {
            m = blur_axis(grid, &m, axis, &kernel);
        }
        for (t, v) in total.iter_mut().zip(m) {
            *t += v;
        }
    }
    let mut density = Vec::with_capacity(4 * grid.len());
    let mut source = Vec::with_capacity(4 * grid.len());
    for v in total.chunks_exact(CHANNELS) {
        density.extend_from_slice(&v[..4]);
        source.extend_from_slice(&v[4..]);
    }
    DensityVolume {
        grid: *grid,
        density,
        source,
    }
}

impl DensityVolume {
    /// ρ at `p` (trilinear).
    pub fn rho(&self, p: Vec3) -> f32 {
        self.grid.sample(&self.density, 4, 0, p)
    }

    /// Σ ρ h³: the mass the volume holds.
    pub fn mass(&self) -> f64 {
        let cell = f64::from(self.grid.h).powi(3);
        self.density
            .chunks_exact(4)
            .map(|d| f64::from(d[0]))
            .sum::<f64>()
            * cell
    }
}

/// The density volume of `frame` on `grid` as the browser's GPU twin reads it: [`splat`]'s
/// `density` (four floats a voxel) then its `source` (four floats a voxel), x fastest.
pub fn density_twin(frame: &PackedFrame, grid: &VoxelGrid) -> Vec<f32> {
    let v = splat(frame, grid);
    [v.density, v.source].concat()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_xoshiro::rand_core::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    fn uniform(rng: &mut Xoshiro256PlusPlus) -> f32 {
        (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32
    }

    #[test]
    fn a_grid_is_bounded_by_its_sides_and_by_its_voxels_in_all() {
        assert!(VoxelGrid::new([0.0; 3], 0.1, [512, 512, 64]).is_ok());
        assert!(VoxelGrid::new([0.0; 3], 0.1, [256, 256, 256]).is_ok());
        for dims in [[512, 512, 65], [512, 512, 512], [513, 1, 1], [0, 4, 4]] {
            let e = VoxelGrid::new([0.0; 3], 0.1, dims).unwrap_err();
            assert!(
                e.message.contains("at most 16777216 voxels"),
                "{dims:?}: {}",
                e.message
            );
        }
    }

    fn grid() -> VoxelGrid {
        VoxelGrid {
            lo: Vec3::new(-0.5, 0.0, -0.25),
            h: 0.02,
            dims: [50, 60, 25],
        }
    }

    fn blob(center: Vec3, sigma: f32, mass: f32) -> RenderBlob {
        RenderBlob {
            center,
            sigma,
            mass,
            albedo: Vec3::new(0.9, 0.5, 0.1),
            emission: Vec3::new(0.0, 0.2, 0.0),
        }
    }

    #[test]
    fn every_blob_inside_the_grid_deposits_its_mass() {
        let g = grid();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        let mut total = 0.0f64;
        let blobs: Vec<RenderBlob> = (0..3000)
            .map(|_| {
                // σ from 0.05 h to 4 h, centres at least 3σ inside the box.
                let sigma = g.h * (0.05 + 3.95 * uniform(&mut rng));
                let margin = Vec3::splat(FOOTPRINT * sigma);
                let span = g.hi() - g.lo - 2.0 * margin;
                let u = Vec3::new(uniform(&mut rng), uniform(&mut rng), uniform(&mut rng));
                let m = 0.5 + uniform(&mut rng);
                total += f64::from(m);
                blob(g.lo + margin + u * span, sigma, m)
            })
            .collect();
        let v = splat(&PackedFrame::pack(blobs.len(), |i| blobs[i]), &g);
        assert!(
            (v.mass() / total - 1.0).abs() < 1e-3,
            "{} vs {total}",
            v.mass()
        );
        // The colour channels carry the same density times the blob's colour (packed in half
        // precision).
        let sum =
            |data: &[f32], c: usize| data.chunks_exact(4).map(|d| f64::from(d[c])).sum::<f64>();
        let rho = sum(&v.density, 0);
        assert!((sum(&v.density, 1) / rho - 0.9).abs() < 1e-3);
        assert!((sum(&v.density, 3) / rho - 0.1).abs() < 1e-3);
        // (1 − Ω) Q = 0.5 × 0.2 in green.
        assert!((sum(&v.source, 1) / rho - 0.1).abs() < 1e-3);
        assert_eq!(sum(&v.source, 0), 0.0);
    }

    /// A blob's density in the volume against its own at voxel centres near its middle.
    fn worst_density_error(sigma: f32) -> f32 {
        let g = grid();
        let c = g.centre(25, 30, 12);
        let b = blob(c, sigma, 1.0);
        let v = splat(&PackedFrame::pack(1, |_| b), &g);
        [(25, 30, 12), (27, 30, 12), (25, 34, 14), (20, 26, 9)]
            .iter()
            .map(|&(i, j, k)| {
                let p = g.centre(i, j, k);
                let got = v.density[4 * g.index(i, j, k)];
                assert!((v.rho(p) - got).abs() < 1e-5 * got);
                (got / b.density(p) - 1.0).abs()
            })
            .fold(0.0, f32::max)
    }

    #[test]
    fn a_wide_blob_gives_its_density_through_the_particle_mesh() {
        // At a class's σ (√2^k m, here 0.0884 m ≈ 4.4 voxels): the cloud in cell and the
        // variance-matched blur alone, within 3 %.
        let at_class = worst_density_error(2f32.powf(-3.5));
        assert!(at_class < 0.03, "{at_class}");
        // Between two classes (0.08 m): the two classes' mixture adds up to 4 % at the centre
        // (6.3 % with the kernel's own).
        let between = worst_density_error(0.08);
        assert!(between < 0.08, "{between}");
    }

    #[test]
    fn a_narrow_blob_stays_in_its_voxel() {
        let g = grid();
        let c = g.centre(10, 10, 10);
        let v = splat(&PackedFrame::pack(1, |_| blob(c, 0.01 * g.h, 2.0)), &g);
        let at = v.density[4 * g.index(10, 10, 10)];
        assert!((f64::from(at) * f64::from(g.h).powi(3) / 2.0 - 1.0).abs() < 1e-6);
        assert_eq!(v.density.iter().filter(|&&d| d != 0.0).count(), 4);
    }

    #[test]
    fn sampling_is_exact_at_centres_and_held_beyond_them() {
        let g = VoxelGrid {
            lo: Vec3::ZERO,
            h: 1.0,
            dims: [2, 1, 3],
        };
        let data: Vec<f32> = (0..6).map(|v| v as f32).collect();
        assert_eq!(g.sample(&data, 1, 0, g.centre(1, 0, 2)), 5.0);
        assert_eq!(g.sample(&data, 1, 0, Vec3::new(1.0, 0.5, 0.5)), 0.5);
        assert_eq!(g.sample(&data, 1, 0, Vec3::new(-3.0, 9.0, 1.5)), 2.0);
        assert_eq!(g.sample(&data, 1, 0, Vec3::new(1.0, 0.5, 2.0)), 3.5);
    }
}
