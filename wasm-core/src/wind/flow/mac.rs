//! A velocity on the MAC grid (m/s): each component's normal value on its faces
//! ([`super::grid`]), sampled anywhere by trilinear interpolation of each component on its
//! own lattice, with its discrete divergence and kinetic energy.

use super::grid::Grid;
use super::sample::{Axis, Lanes, Layout};
use glam::Vec4;

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

    /// Sets every face to its normal component of the uniform velocity `v` (m/s): what
    /// [`MacField::from_fn`] gives for a constant `f`, without a call per face.
    pub fn fill(&mut self, v: [f32; 3]) {
        for (comp, &va) in self.u.iter_mut().zip(&v) {
            comp.fill(va);
        }
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

    /// Sets each face to the sum of two fields' (all three on one grid).
    pub fn set_sum(&mut self, a: &Self, b: &Self) {
        for ((out, x), y) in self.u.iter_mut().zip(&a.u).zip(&b.u) {
            out.clear();
            out.extend(x.iter().zip(y).map(|(x, y)| x + y));
        }
    }

    /// The velocity at `x` (m), m/s: each component interpolated trilinearly on its faces
    /// (clamped to the box: outside it, the nearest faces' values).
    pub fn at(&self, grid: &Grid, x: [f32; 3]) -> [f32; 3] {
        FaceSampler::new(grid).at(self, x)
    }

    /// The velocity at each cell's centre (m/s, laid out as [`Grid::cell`]): each component the
    /// mean of the cell's two faces across its axis.
    pub fn cell_means(&self, grid: &Grid) -> Vec<[f32; 3]> {
        let n = grid.cells;
        let mut out = Vec::with_capacity(grid.cell_count());
        for k in 0..n[2] {
            for j in 0..n[1] {
                for i in 0..n[0] {
                    out.push(std::array::from_fn(|a| {
                        let mut up = [i, j, k];
                        up[a] += 1;
                        let f = &self.u[a];
                        0.5 * (f[grid.face(a, i, j, k)] + f[grid.face(a, up[0], up[1], up[2])])
                    }));
                }
            }
        }
        out
    }

    /// The largest |component| on any face, m/s.
    pub fn max_abs(&self) -> f32 {
        self.u.iter().flatten().fold(0.0f32, |m, &v| m.max(v.abs()))
    }

    /// The discrete divergence of each cell, 1/s: the net outward flux through its six faces
    /// over its volume.
    pub fn divergence(&self, grid: &Grid) -> Vec<f32> {
        let mut out = Vec::new();
        self.divergence_into(grid, &mut out);
        out
    }

    /// [`MacField::divergence`] into `out` (resized to the cells).
    pub fn divergence_into(&self, grid: &Grid, out: &mut Vec<f32>) {
        let n = grid.cells;
        out.clear();
        out.reserve(grid.cell_count());
        let h = grid.h;
        let [ux, uy, uz] = &self.u;
        // Rows of faces: x-faces have n0 + 1 per row, y-faces n1 + 1 rows per plane.
        let (rx, py) = (n[0] + 1, n[0] * (n[1] + 1));
        let pz = n[0] * n[1];
        for k in 0..n[2] {
            for j in 0..n[1] {
                let fx = &ux[rx * (j + n[1] * k)..][..rx];
                let y0 = &uy[n[0] * j + py * k..][..2 * n[0]];
                let z0 = &uz[n[0] * j + pz * k..];
                let z1 = &uz[n[0] * j + pz * (k + 1)..];
                for i in 0..n[0] {
                    let d = (fx[i + 1] - fx[i]) + (y0[n[0] + i] - y0[i]) + (z1[i] - z0[i]);
                    out.push(d / h);
                }
            }
        }
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
        let t = |a: usize| (x[a] - self.origin[a]) * self.inv_h;
        let (tx, ty, tz) = (t(0), t(1), t(2));
        let (wx, wy, wz) = (
            self.walls[0].locate(tx),
            self.walls[1].locate(ty),
            self.walls[2].locate(tz),
        );
        let (cx, cy, cz) = (
            self.centres[0].locate(tx),
            self.centres[1].locate(ty),
            self.centres[2].locate(tz),
        );
        [
            self.layouts[0].sample(&field.u[0], [wx, cy, cz]),
            self.layouts[1].sample(&field.u[1], [cx, wy, cz]),
            self.layouts[2].sample(&field.u[2], [cx, cy, wz]),
        ]
    }
}

/// A velocity at the cells' centres, m/s, for the advection's traces: each component the mean
/// of its two faces across the cell, and between the centres trilinear interpolation of the
/// three components at once (one lattice: a point is located once, and its eight corners
/// blend four lanes wide), clamped to the box like [`MacField::at`]. Against that sample it
/// loses a quarter of each component's second difference along its own axis (the two means),
/// an error of order h² where the velocity is smooth.
#[derive(Debug, Clone)]
pub struct Centred {
    /// The velocity of each cell, laid out as [`Grid::cell`] (the fourth lane 0).
    values: Vec<Vec4>,
    origin: Vec4,
    inv_h: f32,
    cells: [usize; 3],
    lanes: Lanes,
}

impl Centred {
    /// At rest on `grid`.
    pub fn new(grid: &Grid) -> Self {
        let o = grid.origin;
        Self {
            values: vec![Vec4::ZERO; grid.cell_count()],
            origin: Vec4::new(o[0], o[1], o[2], 0.0),
            inv_h: 1.0 / grid.h,
            cells: grid.cells,
            lanes: Lanes::new(grid.cells, [0.5; 3]),
        }
    }

    /// The cells' velocity of the face-wise sum `p + q` of two fields on `grid`.
    pub fn set_sum(&mut self, grid: &Grid, p: &MacField, q: &MacField) {
        let n = grid.cells;
        let face = |a: usize, f: usize| p.u[a][f] + q.u[a][f];
        let (rx, py, pz) = (n[0] + 1, n[0] * (n[1] + 1), n[0] * n[1]);
        let mut c = 0;
        for k in 0..n[2] {
            for j in 0..n[1] {
                let x0 = rx * (j + n[1] * k);
                let y0 = n[0] * j + py * k;
                let z0 = n[0] * j + pz * k;
                for i in 0..n[0] {
                    self.values[c] = Vec4::new(
                        0.5 * (face(0, x0 + i) + face(0, x0 + i + 1)),
                        0.5 * (face(1, y0 + i) + face(1, y0 + i + n[0])),
                        0.5 * (face(2, z0 + i) + face(2, z0 + i + pz)),
                        0.0,
                    );
                    c += 1;
                }
            }
        }
    }

    /// The velocity at `t`, in cells from the grid's origin, m/s (the fourth lane 0).
    #[inline(always)]
    pub fn at_cells(&self, t: Vec4) -> Vec4 {
        self.lanes.value4(&self.values, t)
    }

    /// The velocity at `x` (m), m/s.
    pub fn at(&self, x: [f32; 3]) -> [f32; 3] {
        let t = (Vec4::new(x[0], x[1], x[2], 0.0) - self.origin) * self.inv_h;
        self.at_cells(t).truncate().to_array()
    }

    /// The velocity at face `idx` of component `axis`, m/s ([`Centred::at`] there: the mean of
    /// the two cells either side, the one cell at the box's faces).
    #[inline(always)]
    pub fn at_face(&self, axis: usize, idx: [usize; 3]) -> Vec4 {
        let n = self.cells;
        let stride = [1, n[0], n[0] * n[1]][axis];
        let mut c = idx;
        c[axis] = c[axis].min(n[axis] - 1);
        let above = c[0] + n[0] * (c[1] + n[1] * c[2]);
        let below = above - stride * usize::from(idx[axis] > 0 && idx[axis] < n[axis]);
        (self.values[below] + self.values[above]) * 0.5
    }
}
