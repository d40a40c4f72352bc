//! Four-wide loads from flat `f32` arrays: one unaligned 128-bit load in WASM with SIMD, plain
//! element reads elsewhere. The hot loops (field sampling, advection) read xyz triples this way.

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
    #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
    {
        Vec4::from_slice(&w[i..i + 4])
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
