//! Trilinear interpolation on one lattice of samples (a velocity component's faces or the cells'
//! centres), clamped to the lattice: beyond the outermost samples the value is the nearest
//! one's, a zero normal derivative at the box's faces. 8 samples and 7 lerps per call.

use crate::lanes::{evens_odds, lesser_greater4, load2x2};
use glam::{IVec4, Vec4, Vec4Swizzles};

/// Where a point falls along one axis of a lattice of samples.
#[derive(Debug, Clone, Copy)]
pub struct Axis {
    /// Where the samples lie, in cells from the origin.
    offset: f32,
    /// The last sample's coordinate, in cells from the first.
    top: f32,
    /// The last lower corner a point can take.
    last: usize,
    /// Whether the axis holds a single sample (its fraction is then 0).
    single: bool,
}

impl Axis {
    /// An axis of `samples` samples at `offset` cells from the origin.
    pub fn new(samples: usize, offset: f32) -> Self {
        Self {
            offset,
            top: (samples - 1) as f32,
            last: samples.saturating_sub(2),
            single: samples <= 1,
        }
    }

    /// The lower sample and the fraction within its cell of the point `t` cells from the
    /// origin, clamped to the samples.
    #[inline(always)]
    pub fn locate(&self, t: f32) -> (usize, f32) {
        let p = (t - self.offset).clamp(0.0, self.top);
        // p ≥ 0, so truncation is the floor (without a call to libm's floorf).
        let i = (p as usize).min(self.last);
        (i, if self.single { 0.0 } else { p - i as f32 })
    }
}

/// Where a point falls on a lattice of samples, the three axes at once in four lanes (the
/// fourth unused): [`Axis::locate`] for a point given in cells from the grid's origin.
#[derive(Debug, Clone, Copy)]
pub struct Lanes {
    /// Where the samples lie, in cells from the origin.
    offset: Vec4,
    /// The last sample's coordinate along each axis, in cells from the first (0 along an
    /// axis of one sample, whose fraction is then 0).
    top: Vec4,
    /// The last lower corner along each axis.
    last: IVec4,
    layout: Layout,
}

impl Lanes {
    /// The lattice of `dims` samples at `offset` cells from the origin.
    pub fn new(dims: [usize; 3], offset: [f32; 3]) -> Self {
        let top = |a: usize| (dims[a] - 1) as f32;
        let last = |a: usize| dims[a].saturating_sub(2) as i32;
        Self {
            offset: Vec4::new(offset[0], offset[1], offset[2], 0.0),
            top: Vec4::new(top(0), top(1), top(2), 0.0),
            last: IVec4::new(last(0), last(1), last(2), 0),
            layout: Layout::new(dims),
        }
    }

    /// The index of the lower corner of the point `t` (in cells from the origin) and its
    /// fractions along x, y and z, clamped to the samples.
    #[inline(always)]
    pub fn locate(&self, t: Vec4) -> (usize, Vec4) {
        let p = (t - self.offset).max(Vec4::ZERO).min(self.top);
        // p ≥ 0, so truncation is the floor.
        let i = p.as_ivec4().min(self.last);
        let [x, y, z, _] = i.to_array().map(|v| v as usize);
        (self.layout.index([x, y, z]), p - i.as_vec4())
    }

    /// The eight values around `t` (cells from the origin) and the fractions within their cell.
    #[inline(always)]
    pub fn corners<T: Copy>(&self, values: &[T], t: Vec4) -> ([T; 8], Vec4) {
        let (i0, f) = self.locate(t);
        (self.layout.corners_from(values, i0), f)
    }

    /// The eight values around `t` (cells from the origin) as their x-pairs' first and
    /// second samples ([`Layout::pairs_from`]) and the fractions within their cell.
    #[inline(always)]
    fn pairs(&self, values: &[f32], t: Vec4) -> (Vec4, Vec4, Vec4) {
        let (i0, f) = self.locate(t);
        let (first, second) = self.layout.pairs_from(values, i0);
        (first, second, f)
    }

    /// The value of `values` at `t` (cells from the origin): [`blend`] four lanes wide, the
    /// same bits.
    #[inline(always)]
    pub fn value(&self, values: &[f32], t: Vec4) -> f32 {
        let (first, second, f) = self.pairs(values, t);
        blend_pairs(first, second, f)
    }

    /// [`Lanes::value`] with the least and greatest of the eight samples it blends
    /// ([`bounds`] four lanes wide, the same bits).
    #[inline(always)]
    pub fn value_bounds(&self, values: &[f32], t: Vec4) -> (f32, f32, f32) {
        let (first, second, f) = self.pairs(values, t);
        let (lo, hi) = bounds_pairs(first, second);
        (blend_pairs(first, second, f), lo, hi)
    }

    /// The four-lane value of `values` at `t` (cells from the origin).
    #[inline(always)]
    pub fn value4(&self, values: &[Vec4], t: Vec4) -> Vec4 {
        let (c, f) = self.corners(values, t);
        let lerp = |p: Vec4, q: Vec4, t: f32| p + (q - p) * t;
        let y0 = lerp(lerp(c[0], c[1], f.x), lerp(c[2], c[3], f.x), f.y);
        let y1 = lerp(lerp(c[4], c[5], f.x), lerp(c[6], c[7], f.x), f.y);
        lerp(y0, y1, f.z)
    }
}

/// How a lattice's samples are laid out in memory: the index of a lower corner and the steps
/// to its seven other corners (0 along an axis of one sample).
#[derive(Debug, Clone, Copy)]
pub struct Layout {
    /// Samples along x, and along x and y together.
    row: [usize; 2],
    /// The steps to the next corner along x, y and z.
    step: [usize; 3],
    /// The step to the far corner, their sum.
    span: usize,
}

impl Layout {
    /// The layout of `dims` samples, x fastest.
    pub fn new(dims: [usize; 3]) -> Self {
        let step = |a: usize| usize::from(dims[a] > 1);
        let step = [step(0), dims[0] * step(1), dims[0] * dims[1] * step(2)];
        let span = (step[0].checked_add(step[1]))
            .and_then(|s| s.checked_add(step[2]))
            .expect("a lattice's steps add up within usize");
        Self {
            row: [dims[0], dims[0] * dims[1]],
            step,
            span,
        }
    }

    /// The eight values around lower corner `b`.
    #[inline(always)]
    pub fn corners<T: Copy>(&self, values: &[T], b: [usize; 3]) -> [T; 8] {
        self.corners_from(values, self.index(b))
    }

    /// The index of sample `b`.
    #[inline(always)]
    pub fn index(&self, b: [usize; 3]) -> usize {
        b[0] + self.row[0] * b[1] + self.row[1] * b[2]
    }

    /// The eight values around the lower corner of index `i0`.
    #[inline(always)]
    pub fn corners_from<T: Copy>(&self, values: &[T], i0: usize) -> [T; 8] {
        let [sx, sy, sz] = self.step;
        let v = &values[i0..][..=self.span];
        // SAFETY: each corner's offset is a sum of some of the steps, at most their sum
        // `span` (which [`Layout::new`] checked does not wrap), the last index of `v`. One
        // check where there were eight: these reads are most of a trace, and the traces most
        // of the flow's step.
        let at = |o: usize| unsafe { *v.get_unchecked(o) };
        [
            at(0),
            at(sx),
            at(sy),
            at(sx + sy),
            at(sz),
            at(sx + sz),
            at(sy + sz),
            at(self.span),
        ]
    }
}

impl Layout {
    /// The eight values around the lower corner of index `i0` as the first and the second
    /// samples of their four x-pairs: (c₀, c₂, c₄, c₆) and (c₁, c₃, c₅, c₇) in
    /// [`Layout::corners_from`]'s order. Where the samples along x are adjacent, each x-pair
    /// is one 64-bit load.
    #[inline(always)]
    pub fn pairs_from(&self, values: &[f32], i0: usize) -> (Vec4, Vec4) {
        let [sx, sy, sz] = self.step;
        let v = &values[i0..][..=self.span];
        let (near, far) = if sx == 1 {
            // SAFETY: with sx = 1 the pairs start at 0 and sy, and at sz and sy + sz =
            // span − 1, so each ends at or before span, the last index of `v`.
            unsafe { (load2x2(v, 0, sy), load2x2(v, sz, sy + sz)) }
        } else {
            let c = self.corners_from(values, i0);
            (
                Vec4::new(c[0], c[1], c[2], c[3]),
                Vec4::new(c[4], c[5], c[6], c[7]),
            )
        };
        evens_odds(near, far)
    }

    /// The trilinear sample of `values` at the lower corners and fractions `at` along x, y, z.
    #[inline(always)]
    pub fn sample(&self, values: &[f32], at: [(usize, f32); 3]) -> f32 {
        let c = self.corners(values, [at[0].0, at[1].0, at[2].0]);
        blend(&c, [at[0].1, at[1].1, at[2].1])
    }
}

/// Trilinear blending of the eight corners `c` at fractions `f`.
#[inline(always)]
pub fn blend(c: &[f32; 8], f: [f32; 3]) -> f32 {
    let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
    let y0 = lerp(lerp(c[0], c[1], f[0]), lerp(c[2], c[3], f[0]), f[1]);
    let y1 = lerp(lerp(c[4], c[5], f[0]), lerp(c[6], c[7], f[0]), f[1]);
    lerp(y0, y1, f[2])
}

/// The least and greatest of eight values.
#[inline(always)]
pub fn bounds(c: &[f32; 8]) -> (f32, f32) {
    // Comparisons, not f32::min and max: their NaN rule costs a call to libm's fminf and
    // fmaxf in WebAssembly (the samples are never NaN).
    let min = |a: f32, b: f32| if b < a { b } else { a };
    let max = |a: f32, b: f32| if b > a { b } else { a };
    let lo = min(
        min(min(c[0], c[1]), min(c[2], c[3])),
        min(min(c[4], c[5]), min(c[6], c[7])),
    );
    let hi = max(
        max(max(c[0], c[1]), max(c[2], c[3])),
        max(max(c[4], c[5]), max(c[6], c[7])),
    );
    (lo, hi)
}

/// [`blend`] of the eight corners given as their x-pairs' first and second samples
/// ([`Layout::pairs_from`]) at fractions `f` (x, y, z): the four lerps along x in one, then
/// the two along y, then the one along z, each lane the same operations, so the same bits.
#[inline(always)]
pub fn blend_pairs(first: Vec4, second: Vec4, f: Vec4) -> f32 {
    let x = first + (second - first) * f.xxxx();
    let y = x + (x.yyww() - x) * f.yyyy();
    y.x + (y.z - y.x) * f.z
}

/// [`bounds`] of the eight corners given as their x-pairs' first and second samples
/// ([`Layout::pairs_from`]): the same comparisons in the same order, four lanes wide.
#[inline(always)]
pub fn bounds_pairs(first: Vec4, second: Vec4) -> (f32, f32) {
    // The comparisons of `bounds` (the samples are never NaN).
    let (lo, hi) = lesser_greater4(first, second);
    let (lo, hi) = (
        lesser_greater4(lo, lo.yyww()).0,
        lesser_greater4(hi, hi.yyww()).1,
    );
    (
        if lo.z < lo.x { lo.z } else { lo.x },
        if hi.z > hi.x { hi.z } else { hi.x },
    )
}

/// One lattice of samples made ready for many interpolations: `dims` samples at `offset` cells
/// from `origin` (m) on a grid of spacing `h` (m).
#[derive(Debug, Clone, Copy)]
pub struct Sampler {
    origin: [f32; 3],
    inv_h: f32,
    axes: [Axis; 3],
    layout: Layout,
}

impl Sampler {
    /// The sampler of `dims` samples at `offset` cells from `origin` (m), spacing `h` (m).
    pub fn new(origin: [f32; 3], h: f32, dims: [usize; 3], offset: [f32; 3]) -> Self {
        Self {
            origin,
            inv_h: 1.0 / h,
            axes: std::array::from_fn(|a| Axis::new(dims[a], offset[a])),
            layout: Layout::new(dims),
        }
    }

    /// The eight corner values around `x` (m) and the fractions within their cell.
    #[inline(always)]
    fn corners(&self, values: &[f32], x: [f32; 3]) -> ([f32; 8], [f32; 3]) {
        let mut b = [0; 3];
        let mut f = [0.0; 3];
        for a in 0..3 {
            (b[a], f[a]) = self.axes[a].locate((x[a] - self.origin[a]) * self.inv_h);
        }
        (self.layout.corners(values, b), f)
    }

    /// The value of `values` at `x` (m).
    #[inline(always)]
    pub fn value(&self, values: &[f32], x: [f32; 3]) -> f32 {
        let (c, f) = self.corners(values, x);
        blend(&c, f)
    }

    /// [`Sampler::value`] with the least and greatest of the eight samples it blends.
    #[inline(always)]
    pub fn value_bounds(&self, values: &[f32], x: [f32; 3]) -> (f32, f32, f32) {
        let (c, f) = self.corners(values, x);
        let (lo, hi) = bounds(&c);
        (blend(&c, f), lo, hi)
    }
}

/// The value at world point `x` (m) of `values`, laid out on `dims` samples at `offset` cells
/// from `origin` on a grid of spacing `h`.
pub fn trilinear(
    values: &[f32],
    origin: [f32; 3],
    h: f32,
    dims: [usize; 3],
    offset: [f32; 3],
    x: [f32; 3],
) -> f32 {
    Sampler::new(origin, h, dims, offset).value(values, x)
}

/// [`trilinear`] with the least and greatest of the eight samples it blends (the bounds
/// MacCormack's correction is clamped to).
pub fn trilinear_bounds(
    values: &[f32],
    origin: [f32; 3],
    h: f32,
    dims: [usize; 3],
    offset: [f32; 3],
    x: [f32; 3],
) -> (f32, f32, f32) {
    Sampler::new(origin, h, dims, offset).value_bounds(values, x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_linear_function_is_reproduced_and_clamped_outside() {
        let dims = [4, 3, 5];
        let f = |x: [f32; 3]| 1.0 + 2.0 * x[0] - 0.5 * x[1] + 0.25 * x[2];
        let mut v = vec![0.0; 60];
        for k in 0..5 {
            for j in 0..3 {
                for i in 0..4 {
                    v[i + 4 * (j + 3 * k)] =
                        f([i as f32 * 0.5, (j as f32 + 0.5) * 0.5, k as f32 * 0.5]);
                }
            }
        }
        let off = [0.0, 0.5, 0.0];
        let x = [0.7, 0.6, 1.3];
        assert!((trilinear(&v, [0.0; 3], 0.5, dims, off, x) - f(x)).abs() < 1e-5);
        let far = trilinear(&v, [0.0; 3], 0.5, dims, off, [-3.0, 0.6, 1.3]);
        assert!((far - f([0.0, 0.6, 1.3])).abs() < 1e-5);
    }

    #[test]
    fn the_four_lane_blend_and_bounds_are_the_scalar_bits() {
        // Lattices with and without a second sample along x (whose x-pairs are not adjacent),
        // values with repeats and both zeros, points inside and beyond the samples.
        let mut seed = 12345u32;
        let mut next = move || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / (1u32 << 24) as f32
        };
        for dims in [[5, 4, 3], [1, 4, 3], [6, 1, 2], [3, 3, 1]] {
            let n = dims[0] * dims[1] * dims[2];
            let values: Vec<f32> = (0..n)
                .map(|i| match i % 5 {
                    0 => 0.0,
                    1 => -0.0,
                    _ => (next() - 0.5) * 8.0,
                })
                .collect();
            let lanes = Lanes::new(dims, [0.5, 0.0, 0.5]);
            for _ in 0..500 {
                let t = Vec4::new(
                    next() * 8.0 - 1.5,
                    next() * 6.0 - 1.0,
                    next() * 5.0 - 1.0,
                    0.0,
                );
                let (c, f) = lanes.corners(&values, t);
                let (v, lo, hi) = lanes.value_bounds(&values, t);
                let (lo0, hi0) = bounds(&c);
                assert_eq!(v.to_bits(), blend(&c, [f.x, f.y, f.z]).to_bits());
                assert_eq!(lanes.value(&values, t).to_bits(), v.to_bits());
                assert_eq!((lo.to_bits(), hi.to_bits()), (lo0.to_bits(), hi0.to_bits()));
            }
        }
    }
}
