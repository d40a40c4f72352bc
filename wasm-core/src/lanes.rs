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
