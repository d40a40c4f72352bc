//! Four-wide loads from flat `f32` arrays: one unaligned 128-bit load (WASM's SIMD, SSE2),
//! plain element reads elsewhere. The hot loops (field sampling, advection) read xyz triples
//! this way.

use glam::{Vec3A, Vec4};

/// The four floats `w[i..i + 4]` as one vector. The caller guarantees `i + 4 <= w.len()`
/// (checked in debug builds).
#[inline(always)]
pub fn load4(w: &[f32], i: usize) -> Vec4 {
    debug_assert!(i + 4 <= w.len());
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    {
        // SAFETY: the caller guarantees four floats from i; wasm loads may be unaligned.
        Vec4::from(unsafe { core::arch::wasm32::v128_load(w.as_ptr().add(i).cast()) })
    }
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    {
        let four: &[f32; 4] = w[i..i + 4].try_into().expect("four floats");
        // SAFETY: `four` holds four floats; SSE2 is enabled (the cfg) and the load is unaligned.
        Vec4::from(unsafe { core::arch::x86_64::_mm_loadu_ps(four.as_ptr()) })
    }
    #[cfg(not(any(
        all(target_arch = "wasm32", target_feature = "simd128"),
        all(target_arch = "x86_64", target_feature = "sse2")
    )))]
    {
        Vec4::from_slice(&w[i..i + 4])
    }
}

/// The two pairs `w[i..i + 2]` and `w[j..j + 2]` as one vector (lanes `w[i]`, `w[i + 1]`,
/// `w[j]`, `w[j + 1]`): two 64-bit loads.
///
/// # Safety
/// `i + 2 <= w.len()` and `j + 2 <= w.len()` (checked in debug builds only).
#[inline(always)]
pub unsafe fn load2x2(w: &[f32], i: usize, j: usize) -> Vec4 {
    debug_assert!(i + 2 <= w.len() && j + 2 <= w.len());
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    {
        use core::arch::wasm32::*;
        let p = w.as_ptr();
        // SAFETY: the caller guarantees two floats from i and from j; wasm's 64-bit loads
        // may be unaligned.
        unsafe {
            let low = v128_load64_zero(p.add(i).cast());
            Vec4::from(v128_load64_lane::<1>(low, p.add(j).cast()))
        }
    }
    #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
    {
        // SAFETY: the caller guarantees two floats from i and from j; the reads are unaligned.
        let pair = |k: usize| unsafe { w.as_ptr().add(k).cast::<[f32; 2]>().read_unaligned() };
        let ([a, b], [c, d]) = (pair(i), pair(j));
        Vec4::new(a, b, c, d)
    }
}

/// The even and the odd lanes of `a` then `b`: (a₀, a₂, b₀, b₂) and (a₁, a₃, b₁, b₃), one
/// shuffle each (WASM's SIMD, SSE2).
#[inline(always)]
pub fn evens_odds(a: Vec4, b: Vec4) -> (Vec4, Vec4) {
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    {
        use core::arch::wasm32::*;
        let (a, b) = (a.into(), b.into());
        (
            Vec4::from(i32x4_shuffle::<0, 2, 4, 6>(a, b)),
            Vec4::from(i32x4_shuffle::<1, 3, 5, 7>(a, b)),
        )
    }
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    {
        use core::arch::x86_64::*;
        let (a, b) = (a.into(), b.into());
        // SAFETY: SSE2 is enabled for this target (checked by the cfg).
        unsafe {
            (
                Vec4::from(_mm_shuffle_ps::<0b10_00_10_00>(a, b)),
                Vec4::from(_mm_shuffle_ps::<0b11_01_11_01>(a, b)),
            )
        }
    }
    #[cfg(not(any(
        all(target_arch = "wasm32", target_feature = "simd128"),
        all(target_arch = "x86_64", target_feature = "sse2")
    )))]
    {
        (Vec4::new(a.x, a.z, b.x, b.z), Vec4::new(a.y, a.w, b.y, b.w))
    }
}

/// Per lane the lesser and the greater of `a` and `b` by one comparison each,
/// `if b < a { b } else { a }` and `if b > a { b } else { a }` (`a` where they are equal;
/// not for NaN lanes): WASM's pseudo-minimum and pseudo-maximum, one instruction each there.
#[inline(always)]
pub fn lesser_greater4(a: Vec4, b: Vec4) -> (Vec4, Vec4) {
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    {
        use core::arch::wasm32::*;
        let (a, b) = (a.into(), b.into());
        (Vec4::from(f32x4_pmin(a, b)), Vec4::from(f32x4_pmax(a, b)))
    }
    #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
    {
        (
            Vec4::select(b.cmplt(a), b, a),
            Vec4::select(b.cmpgt(a), b, a),
        )
    }
}

/// The lanes of `v` (each less than 2^31 in size) truncated toward zero to integers: one
/// conversion of the three lanes (SSE2), else lane by lane (one instruction each in WASM).
/// Where the lanes are known to be in range this spares the checks of `as usize`.
#[inline(always)]
pub fn ints3(v: Vec3A) -> [i32; 3] {
    debug_assert!(v.abs().cmplt(Vec3A::splat(2_147_483_648.0)).all());
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    {
        use core::arch::x86_64::*;
        // SAFETY: SSE2 is enabled (the cfg); a __m128i is four i32 lanes.
        let i: [i32; 4] = unsafe { core::mem::transmute(_mm_cvttps_epi32(v.into())) };
        [i[0], i[1], i[2]]
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
    {
        [v.x as i32, v.y as i32, v.z as i32]
    }
}

/// The triple `w[i..i + 3]` as a vector; four-wide where a fourth float follows.
#[inline(always)]
pub fn load3(w: &[f32], i: usize) -> Vec3A {
    if i + 4 <= w.len() {
        Vec3A::from_vec4(load4(w, i))
    } else {
        Vec3A::from_slice(&w[i..i + 3])
    }
}

/// Interleaves three sequences into triples: `out[3i + c] = [a, b, c][c][i]` (the field's
/// `[x][c]` rows from its components), four triples per three 128-bit stores in WASM.
#[inline]
pub fn interleave3(a: &[f32], b: &[f32], c: &[f32], out: &mut [f32]) {
    let n = a.len();
    assert!(
        b.len() == n && c.len() == n && out.len() == 3 * n,
        "three sequences of n"
    );
    #[allow(unused_mut)]
    let mut done = 0;
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    {
        use core::arch::wasm32::*;
        while done + 4 <= n {
            // SAFETY: lanes done..done + 4 of a, b, c and 3·done..3·done + 12 of out are in
            // bounds (checked above and by the loop condition); WASM accesses may be unaligned.
            unsafe {
                let at = |s: &[f32]| v128_load(s.as_ptr().add(done).cast());
                let (a, b, c) = (at(a), at(b), at(c));
                let ab01 = i32x4_shuffle::<0, 4, 1, 5>(a, b);
                let ab23 = i32x4_shuffle::<2, 6, 3, 7>(a, b);
                let o = out.as_mut_ptr().add(3 * done);
                v128_store(o.cast(), i32x4_shuffle::<0, 1, 4, 2>(ab01, c));
                let bc1 = i32x4_shuffle::<3, 5, 3, 5>(ab01, c);
                v128_store(o.add(4).cast(), i32x4_shuffle::<0, 1, 4, 5>(bc1, ab23));
                v128_store(o.add(8).cast(), i32x4_shuffle::<6, 2, 3, 7>(ab23, c));
            }
            done += 4;
        }
    }
    let triples = out[3 * done..].chunks_exact_mut(3);
    for (((o, a), b), c) in triples.zip(&a[done..]).zip(&b[done..]).zip(&c[done..]) {
        o.copy_from_slice(&[*a, *b, *c]);
    }
}

/// The square roots of four lanes by one instruction where there is one (SSE2, WASM's SIMD),
/// else lane by lane. glam's `Vec4::sqrt` takes four roots from libm, a routine rather than an
/// instruction in WASM; every one of them is correctly rounded, so the bits are the same.
#[inline(always)]
pub fn sqrt4(v: Vec4) -> Vec4 {
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    {
        Vec4::from(core::arch::wasm32::f32x4_sqrt(v.into()))
    }
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    {
        // SAFETY: SSE2 is enabled for this target (checked by the cfg).
        Vec4::from(unsafe { core::arch::x86_64::_mm_sqrt_ps(v.into()) })
    }
    #[cfg(not(any(
        all(target_arch = "wasm32", target_feature = "simd128"),
        all(target_arch = "x86_64", target_feature = "sse2")
    )))]
    {
        Vec4::new(v.x.sqrt(), v.y.sqrt(), v.z.sqrt(), v.w.sqrt())
    }
}

/// Whether [`exp4`] takes its four exponentials together (else one by one, as four calls).
pub const EXP4_IS_VECTOR: bool = cfg!(all(target_arch = "wasm32", target_feature = "simd128"));

/// e^x in four lanes, each exactly what `f32::exp` gives on this target. In WASM with SIMD,
/// a four-wide form of the `expf` that `f32::exp` calls there (FreeBSD's, through Rust's libm):
/// the same reduction x = k ln 2 + r, the same rational approximation of e^r and the same
/// scaling by 2^k, operation for operation; lanes outside its plain range (|x| ≤ 2^−14, and
/// −103.97 < x ≤ −80 or x ≥ 80, where `expf` treats subnormals, overflow and NaN apart) take
/// `f32::exp` itself. Elsewhere, `f32::exp` per lane.
#[inline]
pub fn exp4(x: [f32; 4]) -> [f32; 4] {
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    {
        if let Some(y) = simd::exp4(x) {
            return y;
        }
    }
    x.map(f32::exp)
}

#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
mod simd {
    use core::arch::wasm32::*;

    // The constants as bit patterns (a v128 holds four of either): ln 2 in two parts, 1/ln 2,
    // and the two coefficients of the approximation.
    const LN2_HI: u32 = 0x3f31_7200;
    const LN2_LO: u32 = 0x35bf_be8e;
    const INV_LN2: u32 = 0x3fb8_aa3b;
    const P1: u32 = 0x3e2a_aa8f;
    const P2: u32 = 0xbb35_5215;

    fn splat_u(v: u32) -> v128 {
        u32x4_splat(v)
    }

    /// The vector path of [`super::exp4`]; None when a lane needs `expf`'s special cases.
    #[inline]
    pub fn exp4(x: [f32; 4]) -> Option<[f32; 4]> {
        let v = f32x4(x[0], x[1], x[2], x[3]);
        // |x| as bits, and all ones in the negative lanes.
        let hx = v128_and(v, splat_u(0x7fff_ffff));
        let negative = i32x4_shr(v, 31);
        let plain = v128_and(
            u32x4_gt(hx, splat_u(0x3900_0000)),
            u32x4_lt(hx, splat_u(0x42a0_0000)),
        );
        // x ≤ −103.972084 (−∞ included): exactly 0.
        let zero = v128_and(
            negative,
            v128_and(
                u32x4_ge(hx, splat_u(0x42cf_f1b5)),
                u32x4_le(hx, splat_u(0x7f80_0000)),
            ),
        );
        if !u32x4_all_true(v128_or(plain, zero)) {
            return None;
        }
        // k: round(x / ln 2) above 1.5 ln 2, ±1 above 0.5 ln 2, else 0.
        let half = v128_bitselect(f32x4_splat(-0.5), f32x4_splat(0.5), negative);
        let k_far = i32x4_trunc_sat_f32x4(f32x4_add(f32x4_mul(splat_u(INV_LN2), v), half));
        let k_near = i32x4_add(i32x4_splat(1), i32x4_shl(negative, 1));
        let k = v128_bitselect(
            k_far,
            v128_and(k_near, u32x4_gt(hx, splat_u(0x3eb1_7218))),
            u32x4_gt(hx, splat_u(0x3f85_1592)),
        );
        let kf = f32x4_convert_i32x4(k);
        let hi = f32x4_sub(v, f32x4_mul(kf, splat_u(LN2_HI)));
        let lo = f32x4_mul(kf, splat_u(LN2_LO));
        let r = f32x4_sub(hi, lo);
        let rr = f32x4_mul(r, r);
        let p = f32x4_add(splat_u(P1), f32x4_mul(rr, splat_u(P2)));
        let c = f32x4_sub(r, f32x4_mul(rr, p));
        let q = f32x4_div(f32x4_mul(r, c), f32x4_sub(f32x4_splat(2.0), c));
        let y = f32x4_add(f32x4_splat(1.0), f32x4_add(f32x4_sub(q, lo), hi));
        // y · 2^k, exact for the k of the plain range.
        let scale = i32x4_shl(i32x4_add(k, i32x4_splat(0x7f)), 23);
        let out = v128_andnot(f32x4_mul(y, scale), zero);
        Some([
            f32x4_extract_lane::<0>(out),
            f32x4_extract_lane::<1>(out),
            f32x4_extract_lane::<2>(out),
            f32x4_extract_lane::<3>(out),
        ])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exp4_is_exp_in_every_lane() {
        let special = [
            0.0, -0.0, 1e-5, -1e-5, 0.3, -0.3, 1.0, -1.0, 79.9, -79.9, -80.0, -90.0,
        ];
        let more = [
            -104.0,
            -1e9,
            88.8,
            f32::NEG_INFINITY,
            f32::INFINITY,
            0.5,
            -3.0,
            -20.0,
        ];
        let sweep = (0..4000).map(|i| (i as f32 - 2000.0) * 0.0537);
        let all: Vec<f32> = special.into_iter().chain(more).chain(sweep).collect();
        for x in all.chunks_exact(4) {
            let x = [x[0], x[1], x[2], x[3]];
            assert_eq!(
                exp4(x).map(f32::to_bits),
                x.map(|v| v.exp().to_bits()),
                "{x:?}"
            );
        }
        assert!(exp4([f32::NAN; 4]).iter().all(|v| v.is_nan()));
    }
}
