//! The seeded generators of the gas: every emitter, every initial blob set and the splitting
//! draw from a Xoshiro256++ generator of their own, seeded by the scene's seed mixed with a
//! stream tag, so that adding one leaves the others' draws unchanged.

use rand_xoshiro::rand_core::Rng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// Mixes a seed with a stream tag (SplitMix64 finaliser), for independent generators.
pub fn stream_seed(seed: u64, tag: u64) -> u64 {
    let mut z = seed ^ tag.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Uniform in [0, 1): the top 24 bits of a draw, exact in single precision.
pub fn uniform(rng: &mut Xoshiro256PlusPlus) -> f32 {
    (rng.next_u32() >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}
