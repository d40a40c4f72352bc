//! Trilinear interpolation on one lattice of samples (a velocity component's faces or the cells'
//! centres), clamped to the lattice: beyond the outermost samples the value is the nearest
//! one's, a zero normal derivative at the box's faces. 8 samples and 7 lerps per call.

/// The lattice coordinates of world point `x` (m) for samples at `offset` cells
/// ([`crate::wind::flow::grid::Grid::offset`]), clamped to `dims`: the cell of the lower
/// corner and the fractions within it.
fn locate(
    origin: [f32; 3],
    h: f32,
    dims: [usize; 3],
    offset: [f32; 3],
    x: [f32; 3],
) -> ([usize; 3], [f32; 3]) {
    let mut base = [0; 3];
    let mut frac = [0.0; 3];
    let inv_h = 1.0 / h;
    for a in 0..3 {
        let top = (dims[a] - 1) as f32;
        let p = ((x[a] - origin[a]) * inv_h - offset[a]).clamp(0.0, top);
        // p ≥ 0, so truncation is the floor (without a call to libm's floorf).
        let i = (p as usize).min(dims[a].saturating_sub(2));
        base[a] = i;
        frac[a] = if dims[a] > 1 { p - i as f32 } else { 0.0 };
    }
    (base, frac)
}

/// The eight corner values around `x` and the fractions within their cell.
fn corners(
    values: &[f32],
    origin: [f32; 3],
    h: f32,
    dims: [usize; 3],
    offset: [f32; 3],
    x: [f32; 3],
) -> ([f32; 8], [f32; 3]) {
    let (b, f) = locate(origin, h, dims, offset, x);
    let step = |a: usize| usize::from(dims[a] > 1);
    let (sx, sy, sz) = (step(0), dims[0] * step(1), dims[0] * dims[1] * step(2));
    let i0 = b[0] + dims[0] * (b[1] + dims[1] * b[2]);
    let c = [
        values[i0],
        values[i0 + sx],
        values[i0 + sy],
        values[i0 + sx + sy],
        values[i0 + sz],
        values[i0 + sx + sz],
        values[i0 + sy + sz],
        values[i0 + sx + sy + sz],
    ];
    (c, f)
}

fn blend(c: &[f32; 8], f: [f32; 3]) -> f32 {
    let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
    let y0 = lerp(lerp(c[0], c[1], f[0]), lerp(c[2], c[3], f[0]), f[1]);
    let y1 = lerp(lerp(c[4], c[5], f[0]), lerp(c[6], c[7], f[0]), f[1]);
    lerp(y0, y1, f[2])
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
    let (c, f) = corners(values, origin, h, dims, offset, x);
    blend(&c, f)
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
    let (c, f) = corners(values, origin, h, dims, offset, x);
    let lo = c.iter().copied().fold(f32::INFINITY, f32::min);
    let hi = c.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    (blend(&c, f), lo, hi)
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
}
