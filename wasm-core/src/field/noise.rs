//! The white noise of the synthesis (paper §3.3, Appendix A Eq. 17): independent standard
//! normal deviates, taken in pairs as the real and imaginary parts of complex Gaussians.
//!
//! Every spatial column of the spectrum (one wave vector k, every ω) draws from its own stream,
//! a xoshiro256++ generator seeded from the field's seed and k. A column's noise therefore does
//! not depend on the order in which columns are visited, nor on any other column, so a
//! synthesis may visit them in whatever order its memory layout prefers and still give the same
//! bytes for the same seed.
//!
//! Normal deviates come from Marsaglia and Tsang's ziggurat (256 layers) on 32 random bits
//! each (8 pick the layer, 24 the signed abscissa), two per 64-bit draw, in single precision;
//! 99.3 % of them cost one table lookup, one multiplication and one comparison.

/// Layers of the ziggurat (a power of two: the layer is the low bits of a draw).
const LAYERS: usize = 256;
/// Bits that pick the layer.
const LAYER_BITS: u32 = LAYERS.trailing_zeros();
/// Right edge of the base layer (Marsaglia and Tsang, 256 layers).
const R: f64 = 3.654_152_885_361_009;
/// Area of every layer under exp(−x²/2).
const V: f64 = 4.928_673_233_99e-3;
/// Scale of the signed abscissa j, the draw's other 24 bits: |j| ≤ 2^23.
const SCALE: f64 = (1u32 << (31 - LAYER_BITS)) as f64;

/// SplitMix64's finaliser: a bijection of u64 that mixes every input bit into every output bit.
#[inline]
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// xoshiro256++ (Blackman and Vigna), seeded as rand_xoshiro's `seed_from_u64` (four SplitMix64
/// outputs): the same sequence, written out as a `Copy` value that the rare slow cases take and
/// give back, so that the state stays in registers in the hot loop.
#[derive(Debug, Clone, Copy)]
struct Xoshiro256([u64; 4]);

impl Xoshiro256 {
    fn seed_from_u64(mut x: u64) -> Self {
        Self([(); 4].map(|_| {
            x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
            mix64(x)
        }))
    }

    #[inline(always)]
    fn next_u64(&mut self) -> u64 {
        let s = &mut self.0;
        let result = s[0].wrapping_add(s[3]).rotate_left(23).wrapping_add(s[0]);
        let t = s[1] << 17;
        s[2] ^= s[0];
        s[3] ^= s[1];
        s[1] ^= s[2];
        s[0] ^= s[3];
        s[2] ^= t;
        s[3] = s[3].rotate_left(45);
        result
    }

    /// A uniform deviate in (0, 1).
    fn uniform(&mut self) -> f32 {
        (((self.next_u64() >> 40) as f32) + 0.5) * (1.0 / (1u32 << 24) as f32)
    }
}

/// A layer's rectangle: |j| < `bound` means x = j·`width` lies inside the density. The two
/// sit side by side, so one 8-byte load fetches both.
#[derive(Debug, Clone, Copy, Default)]
#[repr(C)]
struct Rectangle {
    /// Acceptance bound on |j|.
    bound: u32,
    /// Abscissa per unit of j.
    width: f32,
}

/// The ziggurat's tables for the standard normal density, unnormalised f(x) = exp(−x²/2).
#[derive(Debug, Clone)]
pub struct Ziggurat {
    /// Per layer, its rectangle.
    rect: [Rectangle; LAYERS],
    /// f at the layer's right edge.
    f: [f32; LAYERS],
}

impl Default for Ziggurat {
    fn default() -> Self {
        Self::new()
    }
}

impl Ziggurat {
    pub fn new() -> Self {
        let density = |x: f64| (-0.5 * x * x).exp();
        let mut k = [0u32; LAYERS];
        let mut w = [0f32; LAYERS];
        let mut f = [0f32; LAYERS];
        // The base layer: the tail beyond R plus the rectangle [0, R], width q = V / f(R).
        let q = V / density(R);
        k[0] = (R / q * SCALE) as u32;
        k[1] = 0;
        w[0] = (q / SCALE) as f32;
        w[LAYERS - 1] = (R / SCALE) as f32;
        f[0] = 1.0;
        f[LAYERS - 1] = density(R) as f32;
        let (mut d, mut t) = (R, R);
        for i in (1..LAYERS - 1).rev() {
            d = (-2.0 * (V / d + density(d)).ln()).sqrt();
            k[i + 1] = (d / t * SCALE) as u32;
            t = d;
            f[i] = density(d) as f32;
            w[i] = (d / SCALE) as f32;
        }
        let rect = std::array::from_fn(|i| Rectangle {
            bound: k[i],
            width: w[i],
        });
        Self { rect, f }
    }
}

/// The noise stream of one spectral column.
pub struct ColumnNoise<'a> {
    rng: Xoshiro256,
    ziggurat: &'a Ziggurat,
}

impl<'a> ColumnNoise<'a> {
    /// The stream of the column with wave vector `k` (integer wave numbers, each within
    /// ±2^20) under `seed`. Distinct columns of one seed get distinct generator states.
    pub fn new(seed: u64, k: [i64; 3], ziggurat: &'a Ziggurat) -> Self {
        let bias = 1 << 20;
        let key = k
            .iter()
            .fold(0u64, |acc, &ki| (acc << 21) | (ki + bias) as u64);
        Self {
            rng: Xoshiro256::seed_from_u64(mix64(mix64(seed) ^ key)),
            ziggurat,
        }
    }

    /// The stream's next deviates, four per entry of `out` (two [`Self::normal_pair`]s).
    #[inline(never)]
    pub fn fill(&mut self, out: &mut [[f32; 4]]) {
        for g in out {
            let [g0, g1] = self.normal_pair();
            let [g2, g3] = self.normal_pair();
            *g = [g0, g1, g2, g3];
        }
    }

    /// [`Self::fill`] for two streams at once, `a` into `out_a` and `b` into `out_b` (of equal
    /// lengths): the same deviates, with the generators side by side in SIMD lanes where the
    /// build has them.
    #[inline(never)]
    pub fn fill_two(
        a: &mut ColumnNoise,
        b: &mut ColumnNoise,
        out_a: &mut [[f32; 4]],
        out_b: &mut [[f32; 4]],
    ) {
        assert_eq!(out_a.len(), out_b.len(), "one entry of each per ω");
        #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
        simd::fill_two(a, b, out_a, out_b);
        #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
        {
            a.fill(out_a);
            b.fill(out_b);
        }
    }

    /// Two standard normal deviates from one 64-bit draw (more in the rare slow cases).
    #[inline]
    pub fn normal_pair(&mut self) -> [f32; 2] {
        let bits = self.rng.next_u64();
        let (lo, hi) = (bits as u32, (bits >> 32) as u32);
        let z = self.ziggurat;
        let mask = LAYERS as u32 - 1;
        let (i, k) = ((lo & mask) as usize, (hi & mask) as usize);
        let (j, l) = ((lo as i32) >> LAYER_BITS, (hi as i32) >> LAYER_BITS);
        let (ri, rk) = (z.rect[i], z.rect[k]);
        if (j.unsigned_abs() < ri.bound) & (l.unsigned_abs() < rk.bound) {
            return [j as f32 * ri.width, l as f32 * rk.width];
        }
        let (rng, a) = slow(self.rng, lo, z);
        let (rng, b) = slow(rng, hi, z);
        self.rng = rng;
        [a, b]
    }
}

/// A standard normal deviate from 32 random bits, drawing more from `rng` where they fall
/// outside the ziggurat's rectangles: the tail beyond R (layer 0) or a wedge. The generator
/// goes in and out by value, so that the caller's stays in registers.
#[cold]
#[inline(never)]
fn slow(mut rng: Xoshiro256, mut bits: u32, z: &Ziggurat) -> (Xoshiro256, f32) {
    loop {
        let i = (bits & (LAYERS as u32 - 1)) as usize;
        let j = (bits as i32) >> LAYER_BITS;
        let x = j as f32 * z.rect[i].width;
        if j.unsigned_abs() < z.rect[i].bound {
            return (rng, x);
        }
        if i == 0 {
            // Marsaglia's tail: x = −ln(U₁)/R until −2 ln(U₂) > x².
            let r = R as f32;
            loop {
                let x = -rng.uniform().ln() / r;
                let y = -rng.uniform().ln();
                if y + y >= x * x {
                    return (rng, if j > 0 { r + x } else { -r - x });
                }
            }
        }
        if z.f[i] + rng.uniform() * (z.f[i - 1] - z.f[i]) < (-0.5 * x * x).exp() {
            return (rng, x);
        }
        bits = rng.next_u64() as u32;
    }
}

/// Two xoshiro256++ generators in the two 64-bit lanes of WASM's 128-bit vectors, and the
/// ziggurat's common case for the four deviates of their two draws in 32-bit lanes.
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
mod simd {
    use super::{ColumnNoise, Xoshiro256, LAYERS, LAYER_BITS};
    use core::arch::wasm32::*;

    /// `x` rotated left by `R` bits in each 64-bit lane.
    #[inline(always)]
    fn rotl<const R: u32>(x: v128) -> v128 {
        v128_or(i64x2_shl(x, R), u64x2_shr(x, 64 - R))
    }

    /// xoshiro256++'s step ([`Xoshiro256::next_u64`]) in both lanes.
    #[inline(always)]
    fn next(s: &mut [v128; 4]) -> v128 {
        let result = i64x2_add(rotl::<23>(i64x2_add(s[0], s[3])), s[0]);
        let t = i64x2_shl(s[1], 17);
        s[2] = v128_xor(s[2], s[0]);
        s[3] = v128_xor(s[3], s[1]);
        s[1] = v128_xor(s[1], s[2]);
        s[0] = v128_xor(s[0], s[3]);
        s[2] = v128_xor(s[2], t);
        s[3] = rotl::<45>(s[3]);
        result
    }

    /// The deviates of four 32-bit draws (lanes) as [`ColumnNoise::normal_pair`]'s fast path
    /// computes them, and whether each fell inside its layer's rectangle (all bits of a lane).
    #[inline(always)]
    fn rectangles(bits: v128, rect: *const u64) -> (v128, v128) {
        let layer = v128_and(bits, u32x4_splat(LAYERS as u32 - 1));
        let j = i32x4_shr(bits, LAYER_BITS);
        // SAFETY: every layer index is below LAYERS, the length of the table behind `rect`.
        let (lo, hi) = unsafe {
            let at = |lane: u32| rect.add(lane as usize);
            let lo = v128_load64_lane::<1>(
                v128_load64_zero(at(u32x4_extract_lane::<0>(layer))),
                at(u32x4_extract_lane::<1>(layer)),
            );
            let hi = v128_load64_lane::<1>(
                v128_load64_zero(at(u32x4_extract_lane::<2>(layer))),
                at(u32x4_extract_lane::<3>(layer)),
            );
            (lo, hi)
        };
        let bound = i32x4_shuffle::<0, 2, 4, 6>(lo, hi);
        let width = i32x4_shuffle::<1, 3, 5, 7>(lo, hi);
        let inside = u32x4_lt(i32x4_abs(j), bound);
        (f32x4_mul(f32x4_convert_i32x4(j), width), inside)
    }

    pub(super) fn fill_two(
        a: &mut ColumnNoise,
        b: &mut ColumnNoise,
        out_a: &mut [[f32; 4]],
        out_b: &mut [[f32; 4]],
    ) {
        let rect = a.ziggurat.rect.as_ptr() as *const u64;
        let (ra, rb) = (a.rng.0, b.rng.0);
        let mut s: [v128; 4] = std::array::from_fn(|i| u64x2(ra[i], rb[i]));
        for (ga, gb) in out_a.iter_mut().zip(out_b.iter_mut()) {
            let before = s;
            // Lanes [a's g₀, g₁, b's g₀, g₁], then [a's g₂, g₃, b's g₂, g₃].
            let (first, inside_first) = rectangles(next(&mut s), rect);
            let (second, inside_second) = rectangles(next(&mut s), rect);
            let va = i32x4_shuffle::<0, 1, 4, 5>(first, second);
            let vb = i32x4_shuffle::<2, 3, 6, 7>(first, second);
            // SAFETY: each entry is 16 bytes; WASM stores may be unaligned.
            unsafe {
                v128_store(ga.as_mut_ptr() as *mut v128, va);
                v128_store(gb.as_mut_ptr() as *mut v128, vb);
            }
            let inside = u32x4_bitmask(v128_and(inside_first, inside_second));
            if inside == 0b1111 {
                continue;
            }
            // A draw outside the rectangles: this ω again from where it began, for that
            // stream alone, as `normal_pair` draws it.
            let mut redo = |column: &mut ColumnNoise, lane: usize, g: &mut [f32; 4]| {
                column.rng = Xoshiro256([0, 1, 2, 3].map(|i| lane_of(before[i], lane)));
                column.fill(std::slice::from_mut(g));
                for (i, v) in s.iter_mut().enumerate() {
                    *v = with_lane(*v, lane, column.rng.0[i]);
                }
            };
            if inside & 0b0011 != 0b0011 {
                redo(a, 0, ga);
            }
            if inside & 0b1100 != 0b1100 {
                redo(b, 1, gb);
            }
        }
        a.rng = Xoshiro256([0, 1, 2, 3].map(|i| lane_of(s[i], 0)));
        b.rng = Xoshiro256([0, 1, 2, 3].map(|i| lane_of(s[i], 1)));
    }

    /// 64-bit lane `i` of `v`.
    #[inline(always)]
    fn lane_of(v: v128, i: usize) -> u64 {
        if i == 0 {
            u64x2_extract_lane::<0>(v)
        } else {
            u64x2_extract_lane::<1>(v)
        }
    }

    /// `v` with 64-bit lane `i` replaced by `x`.
    #[inline(always)]
    fn with_lane(v: v128, i: usize, x: u64) -> v128 {
        if i == 0 {
            u64x2_replace_lane::<0>(v, x)
        } else {
            u64x2_replace_lane::<1>(v, x)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn draw(seed: u64, k: [i64; 3], pairs: usize) -> Vec<f32> {
        let z = Ziggurat::new();
        let mut n = ColumnNoise::new(seed, k, &z);
        (0..pairs).flat_map(|_| n.normal_pair()).collect()
    }

    #[test]
    fn the_generator_is_rand_xoshiros_xoshiro256plusplus() {
        use rand_xoshiro::rand_core::{Rng, SeedableRng};
        for seed in [0, 1, 0x1234_5678_9abc_def0] {
            let mut ours = Xoshiro256::seed_from_u64(seed);
            let mut theirs = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed);
            for _ in 0..100 {
                assert_eq!(ours.next_u64(), theirs.next_u64());
            }
        }
    }

    #[test]
    fn streams_are_reproducible_and_distinct() {
        assert_eq!(draw(1, [3, -2, 0], 4), draw(1, [3, -2, 0], 4));
        assert_ne!(draw(1, [3, -2, 0], 4), draw(1, [3, 2, 0], 4));
        assert_ne!(draw(1, [3, -2, 0], 4), draw(2, [3, -2, 0], 4));
        assert_ne!(draw(1, [0, 0, 1], 4), draw(1, [0, 1, 0], 4));
    }

    #[test]
    fn the_ziggurat_tables_tile_the_density() {
        let z = Ziggurat::new();
        // The top layer, from x = 0 to x₁ under f = 1, closes the recurrence with area V.
        let x1 = z.rect[1].width as f64 * SCALE;
        assert!(
            (x1 * (1.0 - (-0.5 * x1 * x1).exp()) - V).abs() < 1e-6,
            "x₁ {x1}"
        );
        for i in 1..LAYERS - 1 {
            assert!(
                z.rect[i].width < z.rect[i + 1].width && z.f[i] > z.f[i + 1],
                "layer {i}"
            );
        }
    }

    /// 4·10⁶ deviates against the moments, the tail masses and the histogram of N(0, 1), and
    /// the two of a pair against independence.
    #[test]
    fn deviates_are_standard_normal_and_pairs_independent() {
        let x = draw(11, [1, 2, 3], 2_000_000);
        let m = x.len() as f64;
        let se = 1.0 / m.sqrt();
        let moment = |p: i32| x.iter().map(|&v| (v as f64).powi(p)).sum::<f64>() / m;
        // Standard errors: mean 1, variance √2, skewness √15, kurtosis √96; 5σ bounds.
        assert!(moment(1).abs() < 5.0 * se, "mean {}", moment(1));
        assert!(
            (moment(2) - 1.0).abs() < 5.0 * 2f64.sqrt() * se,
            "var {}",
            moment(2)
        );
        assert!(
            moment(3).abs() < 5.0 * 15f64.sqrt() * se,
            "third {}",
            moment(3)
        );
        assert!(
            (moment(4) - 3.0).abs() < 5.0 * 96f64.sqrt() * se,
            "fourth {}",
            moment(4)
        );
        // P(|X| > a) = erfc(a/√2).
        let tails = [
            (1.0, 0.317_310_5),
            (2.0, 0.045_500_26),
            (3.0, 0.002_699_796),
            (3.5, 4.652_582e-4),
            (4.0, 6.334_248e-5),
        ];
        for (a, p) in tails {
            let got = x.iter().filter(|v| v.abs() > a).count() as f64 / m;
            let sd = (p * (1.0 - p) / m).sqrt();
            assert!((got - p).abs() < 5.0 * sd, "tail beyond {a}: {got} vs {p}");
        }
        // Histogram in 40 bins of equal probability (edges: Φ inverted by bisection).
        let cdf = |z: f64| 0.5 * libm::erfc(-z / std::f64::consts::SQRT_2);
        let edges: Vec<f64> = (1..40)
            .map(|i| {
                let (mut lo, mut hi) = (-10.0, 10.0);
                for _ in 0..80 {
                    let mid = 0.5 * (lo + hi);
                    if cdf(mid) < i as f64 / 40.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                lo
            })
            .collect();
        let mut bins = [0usize; 40];
        for &v in &x {
            bins[edges.partition_point(|&e| e < v as f64)] += 1;
        }
        let expected = m / 40.0;
        let chi2: f64 = bins
            .iter()
            .map(|&b| (b as f64 - expected).powi(2) / expected)
            .sum();
        // 39 degrees of freedom: the 99.99th percentile is about 80.
        assert!(chi2 < 80.0, "chi² {chi2} over {bins:?}");
        // Pairs: uncorrelated, and uncorrelated in square (independent, not just orthogonal).
        let (mut c1, mut c2) = (0.0, 0.0);
        for p in x.chunks_exact(2) {
            let (a, b) = (p[0] as f64, p[1] as f64);
            c1 += a * b;
            c2 += a * a * b * b;
        }
        let h = m / 2.0;
        assert!((c1 / h).abs() < 5.0 / h.sqrt(), "E[ab] {}", c1 / h);
        assert!(
            (c2 / h - 1.0).abs() < 5.0 * 8f64.sqrt() / h.sqrt(),
            "E[a²b²] {}",
            c2 / h
        );
    }
}
