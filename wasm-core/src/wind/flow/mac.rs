//! A velocity on the MAC grid (m/s): each component's normal value on its faces
//! ([`super::grid`]), sampled anywhere by trilinear interpolation of each component on its
//! own lattice, with its discrete divergence and kinetic energy.

use super::grid::Grid;
use super::sample::{blend, Axis, Layout};

/// Face velocities, m/s: `u[a]` holds component a on the faces across axis a.
#[derive(Debug, Clone, PartialEq)]
pub struct MacField {
    /// The three components, each laid out as [`Grid::face`].
    pub u: [Vec<f32>; 3],
}

impl MacField {
    /// Zero on every face of `grid`.
    pub fn zeros(grid: &Grid) -> Self {
        Self {
            u: std::array::from_fn(|a| vec![0.0; grid.face_count(a)]),
        }
    }

    /// The field `f(x)` (m/s at x in m) sampled on the faces: each face keeps its normal
    /// component. This is how a given wind (the primitives' u_p) enters the solver.
    pub fn from_fn(grid: &Grid, f: impl Fn([f32; 3]) -> [f32; 3]) -> Self {
        let mut out = Self::zeros(grid);
        for (a, comp) in out.u.iter_mut().enumerate() {
            let d = grid.face_dims(a);
            for k in 0..d[2] {
                for j in 0..d[1] {
                    for i in 0..d[0] {
                        comp[grid.face(a, i, j, k)] = f(grid.face_position(a, i, j, k))[a];
                    }
                }
            }
        }
        out
    }

    /// The face-wise sum of two fields on one grid.
    pub fn plus(&self, other: &Self) -> Self {
        Self {
            u: std::array::from_fn(|a| {
                self.u[a]
                    .iter()
                    .zip(&other.u[a])
                    .map(|(x, y)| x + y)
                    .collect()
            }),
        }
    }

    /// The velocity at `x` (m), m/s: each component interpolated trilinearly on its faces
    /// (clamped to the box: outside it, the nearest faces' values).
    pub fn at(&self, grid: &Grid, x: [f32; 3]) -> [f32; 3] {
        FaceSampler::new(grid).at(self, x)
    }

    /// The largest |component| on any face, m/s.
    pub fn max_abs(&self) -> f32 {
        self.u.iter().flatten().fold(0.0f32, |m, &v| m.max(v.abs()))
    }

    /// The discrete divergence of each cell, 1/s: the net outward flux through its six faces
    /// over its volume.
    pub fn divergence(&self, grid: &Grid) -> Vec<f32> {
        let n = grid.cells;
        let mut out = vec![0.0; grid.cell_count()];
        for k in 0..n[2] {
            for j in 0..n[1] {
                for i in 0..n[0] {
                    let mut d = 0.0;
                    for a in 0..3 {
                        let mut up = [i, j, k];
                        up[a] += 1;
                        d += self.u[a][grid.face(a, up[0], up[1], up[2])]
                            - self.u[a][grid.face(a, i, j, k)];
                    }
                    out[grid.cell(i, j, k)] = d / grid.h;
                }
            }
        }
        out
    }

    /// The kinetic energy per unit density, ½ Σ u² h³ over every face of every component
    /// (m⁵/s², summed in f64).
    pub fn kinetic_energy(&self, grid: &Grid) -> f64 {
        let v = f64::from(grid.h).powi(3);
        0.5 * v
            * self
                .u
                .iter()
                .flatten()
                .map(|&x| f64::from(x) * f64::from(x))
                .sum::<f64>()
    }
}

/// Trilinear interpolation of a [`MacField`] made ready for many points: along each axis a
/// component's faces lie either on the cells' walls (its own axis: 0 cells from the origin,
/// one more than the cells) or at their centres (the other two: 1/2 cell), so a point is
/// located once on each of the two per axis and the three components share them.
#[derive(Debug, Clone, Copy)]
pub struct FaceSampler {
    origin: [f32; 3],
    inv_h: f32,
    /// Each axis's faces across it (offset 0, cells + 1 samples).
    walls: [Axis; 3],
    /// Each axis's faces along it (offset 1/2, cells samples).
    centres: [Axis; 3],
    /// Each component's layout.
    layouts: [Layout; 3],
}

impl FaceSampler {
    /// The sampler of the faces of `grid`.
    pub fn new(grid: &Grid) -> Self {
        Self {
            origin: grid.origin,
            inv_h: 1.0 / grid.h,
            walls: std::array::from_fn(|a| Axis::new(grid.cells[a] + 1, 0.0)),
            centres: std::array::from_fn(|a| Axis::new(grid.cells[a], 0.5)),
            layouts: std::array::from_fn(|a| Layout::new(grid.face_dims(a))),
        }
    }

    /// The velocity of `field` at `x` (m), m/s ([`MacField::at`]).
    #[inline(always)]
    pub fn at(&self, field: &MacField, x: [f32; 3]) -> [f32; 3] {
        let mut wall = [(0, 0.0); 3];
        let mut centre = [(0, 0.0); 3];
        for a in 0..3 {
            let t = (x[a] - self.origin[a]) * self.inv_h;
            wall[a] = self.walls[a].locate(t);
            centre[a] = self.centres[a].locate(t);
        }
        std::array::from_fn(|c| {
            let at = |a: usize| if a == c { wall[a] } else { centre[a] };
            let (b0, f0) = at(0);
            let (b1, f1) = at(1);
            let (b2, f2) = at(2);
            let corners = self.layouts[c].corners(&field.u[c], [b0, b1, b2]);
            blend(&corners, [f0, f1, f2])
        })
    }
}
