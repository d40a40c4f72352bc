//! One time slice of the small-scale field: the two lattice time slices bracketing t blended
//! into one 3-D slice, so a sample costs one trilinear lookup (equal to the quadrilinear sample
//! of the 4-D lattice, since both are linear in t).

use crate::lanes::{ints3, load4};
use glam::{Vec3A, Vec4};

/// One time slice of the small-scale field, in world velocities, periodic in x, y, z.
/// Stored `[z][y][x][component]` with one extra point per axis (a copy of index 0), so the
/// two x-neighbours of a row are six contiguous floats and no index wraps while sampling.
#[derive(Debug, Clone, Default)]
pub struct FieldSlice {
    pub(super) size: [usize; 3],
    /// `size − 1` along each axis where all three are powers of two (a periodic wrap is then
    /// a mask), else none.
    pub(super) wrap_mask: Option<[i32; 3]>,
    /// The extents as floats, and their reciprocals (for the periodic wrap).
    pub(super) extent: Vec3A,
    pub(super) inv_extent: Vec3A,
    pub(super) data: Vec<f32>,
    pub(crate) cells_per_metre: Vec3A,
    pub(crate) offset: Vec3A,
    /// The lattice's two bracketing time slices and the blend between them: the slice is
    /// `(1 − f)·u[i0] + f·u[i1]`, times `velocity_scale` (for the GPU's own sampling).
    pub(crate) time_slices: (u32, u32, f32),
    pub(crate) velocity_scale: Vec3A,
}

impl FieldSlice {
    /// [`Self::sample`] at each of `xs`: where all lie in one lattice cell (a stencil of small
    /// steps), the cell's corners are read once and each point interpolates them as
    /// [`Self::sample`] does; else each point is sampled alone.
    #[inline]
    pub fn sample_each<const N: usize>(&self, xs: &[Vec3A; N]) -> [Vec3A; N] {
        let q: [Vec3A; N] = std::array::from_fn(|k| (xs[k] - self.offset) * self.cells_per_metre);
        let Some(fl) = q.first().map(|q| q.floor()) else {
            return [Vec3A::ZERO; N];
        };
        if q.iter().any(|q| q.floor() != fl) {
            return std::array::from_fn(|k| self.sample(xs[k]));
        }
        let Some((w, dy, dz)) = self.corners(fl) else {
            return [Vec3A::ZERO; N];
        };
        std::array::from_fn(|k| Self::interpolate(w, dy, dz, q[k] - fl))
    }

    /// Trilinear, periodic sample at world position `x` (m/s).
    ///
    /// Four-wide: a lattice row `[u0 v0 w0 u1 v1 w1]` is read as two overlapping vectors
    /// `[u0 v0 w0 u1]` and `[u1 v1 w1 u2]`, so one vector lerp interpolates all three
    /// components along x (the fourth lane is ignored).
    #[inline]
    pub fn sample(&self, x: Vec3A) -> Vec3A {
        let q = (x - self.offset) * self.cells_per_metre;
        let fl = q.floor();
        match self.corners(fl) {
            Some((w, dy, dz)) => Self::interpolate(w, dy, dz, q - fl),
            None => Vec3A::ZERO,
        }
    }

    /// The data from the lattice cell `fl` (integer coordinates, wrapped periodically) on, and
    /// the strides to its corners along y and z; none if it would reach past the data.
    #[inline(always)]
    fn corners(&self, fl: Vec3A) -> Option<(&[f32], usize, usize)> {
        let [nx, ny] = [self.size[0], self.size[1]];
        let [x0, y0, z0] = match self.wrap_mask {
            // Two's complement: i & (n − 1) is i mod n, negative i too.
            Some(mask) => {
                let i = ints3(fl.clamp(Vec3A::splat(-2.0e9), Vec3A::splat(2.0e9)));
                [0, 1, 2].map(|k| (i[k] & mask[k]) as usize)
            }
            None => {
                // The periodic wrap of the integer cell fl into 0..n, exact in f32 while
                // |q| < 2^24: the quotient may round to a neighbouring integer, which the two
                // selects put right.
                let n = self.extent;
                let mut cell = fl - n * (fl * self.inv_extent).floor();
                cell = Vec3A::select(cell.cmpge(n), cell - n, cell);
                cell = Vec3A::select(cell.cmplt(Vec3A::ZERO), cell + n, cell);
                let cell = cell.max(Vec3A::ZERO).min(n - 1.0);
                ints3(cell).map(|i| i as usize)
            }
        };
        let (sx, sy) = (nx + 1, ny + 1);
        let base = 3 * ((z0 * sy + y0) * sx + x0);
        let (dy, dz) = (3 * sx, 3 * sx * sy);
        // The farthest of the eight corners' reads ends at base + dz + dy + 7.
        let w = self.data.get(base..base + dz + dy + 7)?;
        Some((w, dy, dz))
    }

    /// The trilinear interpolation at `t` (in [0, 1]³) of the cell whose data start `w`.
    #[inline(always)]
    fn interpolate(w: &[f32], dy: usize, dz: usize, t: Vec3A) -> Vec3A {
        let tx = Vec4::splat(t.x);
        // Every read below starts at most dz + dy + 3 and spans four floats: inside `w`.
        let along_x = |i: usize| -> Vec4 {
            // One bounds check for the row's two overlapping reads.
            let row = &w[i..i + 7];
            let a = load4(row, 0);
            a + (load4(row, 3) - a) * tx
        };
        let e00 = along_x(0);
        let e10 = along_x(dy);
        let e01 = along_x(dz);
        let e11 = along_x(dz + dy);
        let (ty, tz) = (t.y, t.z);
        let lo = e00 + (e10 - e00) * ty;
        let hi = e01 + (e11 - e01) * ty;
        Vec3A::from_vec4(lo + (hi - lo) * tz)
    }
}
