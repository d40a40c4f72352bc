//! The frame the browser's views draw from: every blob packed into eight 32-bit words, sorted
//! into classes of σ, with the bounds of the gas. One whole buffer crosses from the engine
//! worker to the page per frame (docs/ARCHITECTURE.md); the page uploads it to the GPU unchanged.
//!
//! Words per blob ([`WORDS_PER_BLOB`]), little-endian as typed arrays see them:
//!
//! | word | content |
//! |---|---|
//! | 0–2 | centre x, y, z (f32 bits, m) |
//! | 3 | σ (f32 bits, m) |
//! | 4 | mass m (f32 bits; ρ integrates to it, Eq. 13) |
//! | 5 | albedo Ω r, g (two IEEE half floats, r in the low 16 bits: GLSL `unpackHalf2x16`) |
//! | 6 | albedo Ω b, emitted source (1 − Ω) Q r (halves) |
//! | 7 | emitted source (1 − Ω) Q g, b (halves) |
//!
//! A blob without an albedo of its own carries the medium's; the source term of the rendering model (docs/FORMATS.md) is
//! ρ [Ω L + (1 − Ω) Q], so the packed (1 − Ω) Q is what a view adds to Ω L. Blobs without mass
//! are left out.
//!
//! Classes: class k holds the blobs with σ in [σ_k, σ_{k+1}), σ_k = √2^(k − [`CLASS_BIAS`]) m (the
//! first and last classes are open below and above), so that each pass of the real-time view
//! draws only the blobs it needs (`frame::volume`: the particle mesh deposits a blob of class
//! k into mesh classes k and k + 1). The classes are fixed in metres, not relative to the frame,
//! so a blob keeps its class from frame to frame.
//!
//! Within a class the blobs are ordered by [`order_key`]: σ² to its binary exponent and the top
//! [`SUBCLASS_BITS`] bits of its mantissa (a counting sort, [`SUBCLASSES`] steps a class), so
//! that a view can cut a class at a width (the direct splat's limit) by a binary search over the
//! words and draw only the part that needs it.

use crate::gas::blobs::Blobs;
use crate::gas::simulation::Simulation;
use crate::render::RenderBlob;
use crate::scene::blob_list::BlobList;
use glam::Vec3;
use half::f16;

/// 32-bit words per packed blob (two RGBA32UI texels of the page's blob texture).
pub const WORDS_PER_BLOB: usize = 8;
/// Blobs per row of the page's blob texture; the exact march's index and shadow textures use
/// rows of as many texels.
pub const BLOBS_PER_ROW: usize = 1024;
/// The words are padded with zeros to a multiple of this many blobs: whole rows of the page's
/// blob texture, eight at a time, so that the texture changes size only now and then.
pub const PACK_ALIGN: usize = 8 * BLOBS_PER_ROW;
/// Floats of [`PackedFrame::info`] before its classes.
pub const INFO_HEADER: usize = 10;
/// Floats of [`PackedFrame::info`] per σ class.
pub const INFO_PER_CLASS: usize = 4;
/// Number of σ classes (a factor √2 apart).
pub const SIGMA_CLASSES: usize = 64;
/// Class k starts at σ = √2^(k − CLASS_BIAS) m: classes 0 to 63 span 60 nm to 181 m.
pub const CLASS_BIAS: i32 = 48;
/// The gas bounds enclose every blob's centre ± this many σ: the real-time view's splat
/// footprint (its weights are renormalised over it, so no mass is lost).
pub const FOOTPRINT: f32 = 3.0;

/// Bits of σ²'s mantissa that order the blobs within a class ([`order_key`]).
pub const SUBCLASS_BITS: u32 = 4;
/// Steps of σ within a class: σ² from σ_k² (1 + j / SUBCLASSES) to σ_k² (1 + (j + 1) / SUBCLASSES).
pub const SUBCLASSES: usize = 1 << SUBCLASS_BITS;

/// σ_k = √2^(k − CLASS_BIAS), the lower bound of class k (m).
pub fn class_sigma(k: usize) -> f32 {
    2f32.powf((k as i32 - CLASS_BIAS) as f32 / 2.0)
}

/// The class of σ (m): ⌊log2 σ²⌋ + CLASS_BIAS, the binary exponent of σ², clamped to the classes.
pub fn class_of(sigma: f32) -> usize {
    let exponent = ((sigma * sigma).to_bits() >> 23) as i32 - 127;
    (exponent + CLASS_BIAS).clamp(0, SIGMA_CLASSES as i32 - 1) as usize
}

/// Where a blob of σ (m) goes in the packed order: its class × [`SUBCLASSES`] plus the top
/// [`SUBCLASS_BITS`] bits of σ²'s mantissa. Within classes 1 to 62 it grows with σ; in the
/// first and last classes (open below and above) it only groups.
pub fn order_key(sigma: f32) -> usize {
    let sub = ((sigma * sigma).to_bits() >> (23 - SUBCLASS_BITS)) as usize & (SUBCLASSES - 1);
    class_of(sigma) * SUBCLASSES + sub
}

/// One σ class of a packed frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SigmaClass {
    /// Its number k: σ in [σ_k, σ_{k+1}).
    pub index: usize,
    /// First blob of the class (in blobs, not words).
    pub offset: usize,
    pub count: usize,
    /// Widest σ in the class (m).
    pub sigma_max: f32,
}

/// A packed frame: the words and what the page needs to draw them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PackedFrame {
    /// [`WORDS_PER_BLOB`] words per blob, class after class, then zeros up to a multiple of
    /// [`PACK_ALIGN`] blobs.
    pub words: Vec<u32>,
    /// Blobs packed.
    pub count: usize,
    /// Bounds of every centre ± [`FOOTPRINT`] σ (m); None without blobs.
    pub bounds: Option<(Vec3, Vec3)>,
    /// Whether any blob has an emitted source (1 − Ω) Q ≠ 0.
    pub emissive: bool,
    /// Narrowest σ (m); 0 without blobs.
    pub sigma_min: f32,
    /// Non-empty classes, narrowest first.
    pub classes: Vec<SigmaClass>,
}

/// What packing reads of the blobs: centre, σ and mass first (classes and bounds), then the
/// whole blob of each one kept (its words).
trait PackSource {
    fn len(&self) -> usize;
    /// Centre (m), σ (m) and mass of blob `i`.
    fn extent(&self, i: usize) -> (Vec3, f32, f32);
    /// Albedo (resolved) and emission Q of blob `i`.
    fn colours(&self, i: usize) -> (Vec3, Vec3);
}

/// Blobs given one [`RenderBlob`] at a time.
struct Each<F>(usize, F);

impl<F: Fn(usize) -> RenderBlob> PackSource for Each<F> {
    fn len(&self) -> usize {
        self.0
    }

    #[inline(always)]
    fn extent(&self, i: usize) -> (Vec3, f32, f32) {
        let b = (self.1)(i);
        (b.center, b.sigma, b.mass)
    }

    #[inline(always)]
    fn colours(&self, i: usize) -> (Vec3, Vec3) {
        let b = (self.1)(i);
        (b.albedo, b.emission)
    }
}

/// The gas's blobs, a blob without an albedo of its own taking the medium's.
struct GasBlobs<'a> {
    blobs: &'a Blobs,
    medium: Vec3,
}

impl PackSource for GasBlobs<'_> {
    fn len(&self) -> usize {
        self.blobs.len()
    }

    #[inline(always)]
    fn extent(&self, i: usize) -> (Vec3, f32, f32) {
        let b = self.blobs;
        (b.center(i), b.sigma[i], b.mass[i])
    }

    #[inline(always)]
    fn colours(&self, i: usize) -> (Vec3, Vec3) {
        let b = self.blobs;
        let albedo = b.albedo_of(i).map_or(self.medium, Vec3::from_array);
        (albedo, Vec3::from_slice(&b.emission[3 * i..3 * i + 3]))
    }
}

/// The two halves of `a` (low 16 bits) and `b` (high) in one word.
fn halves(a: f32, b: f32) -> u32 {
    u32::from(f16::from_f32(a).to_bits()) | (u32::from(f16::from_f32(b).to_bits()) << 16)
}

impl PackedFrame {
    /// Packs the blobs that `blob(i)` gives for i in 0..n (albedo already resolved: the
    /// blob's own or the medium's), dropping those without mass.
    pub fn pack(n: usize, blob: impl Fn(usize) -> RenderBlob) -> Self {
        Self::pack_source(&Each(n, blob))
    }

    /// The gas's blobs packed, a blob without an albedo of its own taking `medium`'s: the
    /// same words as [`Self::pack`] of their [`RenderBlob`]s.
    pub fn of_blobs(blobs: &Blobs, medium: Vec3) -> Self {
        Self::pack_source(&GasBlobs { blobs, medium })
    }

    /// Two passes over the blobs (classes and bounds from centre, σ and mass; then the words),
    /// no allocation but the output.
    fn pack_source(source: &impl PackSource) -> Self {
        let kept = |sigma: f32, mass: f32| mass > 0.0 && sigma > 0.0;
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        let mut sigma_min = f32::INFINITY;
        let mut counts = [0usize; SIGMA_CLASSES * SUBCLASSES];
        let mut widest = [0.0f32; SIGMA_CLASSES];
        for i in 0..source.len() {
            let (center, sigma, mass) = source.extent(i);
            if !kept(sigma, mass) {
                continue;
            }
            let key = order_key(sigma);
            counts[key] += 1;
            let k = key / SUBCLASSES;
            widest[k] = widest[k].max(sigma);
            sigma_min = sigma_min.min(sigma);
            let r = Vec3::splat(FOOTPRINT * sigma);
            lo = lo.min(center - r);
            hi = hi.max(center + r);
        }
        let count: usize = counts.iter().sum();
        if count == 0 {
            return Self::default();
        }
        let (classes, mut next) = Self::classes(&counts, &widest);
        let mut words = vec![0u32; WORDS_PER_BLOB * count.next_multiple_of(PACK_ALIGN)];
        let mut emissive = false;
        // Neighbouring blobs mostly share an emitter's colours: convert each change once.
        let mut colour = (Vec3::NAN, Vec3::NAN, [0u32; 3]);
        for i in 0..source.len() {
            let (center, sigma, mass) = source.extent(i);
            if !kept(sigma, mass) {
                continue;
            }
            let k = order_key(sigma);
            let w = &mut words[WORDS_PER_BLOB * next[k]..WORDS_PER_BLOB * (next[k] + 1)];
            next[k] += 1;
            let (albedo, emission) = source.colours(i);
            if albedo != colour.0 || emission != colour.1 {
                let q = (Vec3::ONE - albedo) * emission;
                emissive |= q != Vec3::ZERO;
                let packed = [
                    halves(albedo.x, albedo.y),
                    halves(albedo.z, q.x),
                    halves(q.y, q.z),
                ];
                colour = (albedo, emission, packed);
            }
            w[0] = center.x.to_bits();
            w[1] = center.y.to_bits();
            w[2] = center.z.to_bits();
            w[3] = sigma.to_bits();
            w[4] = mass.to_bits();
            w[5..8].copy_from_slice(&colour.2);
        }
        Self {
            words,
            count,
            bounds: Some((lo, hi)),
            emissive,
            sigma_min,
            classes,
        }
    }

    /// The non-empty classes of the blob counts per [`order_key`] and widest σ per class, and
    /// each key's first blob.
    fn classes(
        counts: &[usize; SIGMA_CLASSES * SUBCLASSES],
        widest: &[f32; SIGMA_CLASSES],
    ) -> (Vec<SigmaClass>, [usize; SIGMA_CLASSES * SUBCLASSES]) {
        let mut first = [0usize; SIGMA_CLASSES * SUBCLASSES];
        let mut classes = Vec::new();
        let mut offset = 0;
        for (k, &sigma_max) in widest.iter().enumerate() {
            let keys = k * SUBCLASSES..(k + 1) * SUBCLASSES;
            let count: usize = counts[keys.clone()].iter().sum();
            if count > 0 {
                classes.push(SigmaClass {
                    index: k,
                    offset,
                    count,
                    sigma_max,
                });
            }
            for key in keys {
                first[key] = offset;
                offset += counts[key];
            }
        }
        (classes, first)
    }

    /// The simulation's blobs now, a blob without an albedo of its own taking the medium's.
    pub fn of_simulation(sim: &Simulation) -> Self {
        let medium = Vec3::from_array(sim.scene.render.medium.albedo);
        Self::of_blobs(&sim.blobs(), medium)
    }

    /// A blob list's blobs packed (colours resolved against its medium's albedo).
    pub fn of_list(list: &BlobList) -> Self {
        let medium = Vec3::from_array(list.medium.albedo);
        Self::pack(list.blobs.len(), |i| RenderBlob::of(&list.blobs[i], medium))
    }

    /// The frame's description as floats: [`INFO_HEADER`] floats `[count, lo.xyz, hi.xyz,
    /// emissive (0/1), σ_min, classes]`, then [`INFO_PER_CLASS`] floats `[index, offset, count,
    /// σ_max]` per class (bounds 0 without blobs).
    pub fn info(&self) -> Vec<f32> {
        let (lo, hi) = self.bounds.unwrap_or((Vec3::ZERO, Vec3::ZERO));
        let mut out = vec![
            self.count as f32,
            lo.x,
            lo.y,
            lo.z,
            hi.x,
            hi.y,
            hi.z,
            f32::from(u8::from(self.emissive)),
            self.sigma_min,
            self.classes.len() as f32,
        ];
        for c in &self.classes {
            out.extend_from_slice(&[c.index as f32, c.offset as f32, c.count as f32, c.sigma_max]);
        }
        out
    }

    /// Blob `i` as packed (colours rounded to half precision).
    pub fn blob(&self, i: usize) -> RenderBlob {
        let w = &self.words[WORDS_PER_BLOB * i..WORDS_PER_BLOB * (i + 1)];
        let lo = |x: u32| f16::from_bits(x as u16).to_f32();
        let hi = |x: u32| f16::from_bits((x >> 16) as u16).to_f32();
        RenderBlob {
            center: Vec3::new(
                f32::from_bits(w[0]),
                f32::from_bits(w[1]),
                f32::from_bits(w[2]),
            ),
            sigma: f32::from_bits(w[3]),
            mass: f32::from_bits(w[4]),
            albedo: Vec3::new(lo(w[5]), hi(w[5]), lo(w[6])),
            // The emitted source (1 − Ω) Q, not Q: see the module's comment.
            emission: Vec3::new(hi(w[6]), lo(w[7]), hi(w[7])),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gas::blobs::Blob;

    fn blob(x: f32, sigma: f32, mass: f32) -> RenderBlob {
        RenderBlob {
            center: Vec3::new(x, 2.0 * x, -x),
            sigma,
            mass,
            albedo: Vec3::new(0.25, 0.5, 0.75),
            emission: Vec3::new(2.0, 0.0, 4.0),
        }
    }

    #[test]
    fn packs_every_massive_blob_into_its_sigma_class() {
        let blobs = [
            blob(0.0, 0.01, 1.0),
            blob(1.0, 0.05, 2.0),
            blob(2.0, 0.015, 3.0),
            blob(3.0, 0.02, 0.0), // no mass: left out
            blob(4.0, 0.019, 4.0),
        ];
        let f = PackedFrame::pack(blobs.len(), |i| blobs[i]);
        assert_eq!(f.count, 4);
        assert_eq!(f.words.len(), PACK_ALIGN * WORDS_PER_BLOB);
        assert!(f.words[4 * WORDS_PER_BLOB..].iter().all(|&w| w == 0));
        // σ² = 1e-4 (2^-13.3: class 34), 2.25e-4 and 3.6e-4 (2^-12.2, 2^-11.4: class 35 and 36),
        // 2.5e-3 (2^-8.6: class 39).
        let shape: Vec<(usize, usize, usize, f32)> = f
            .classes
            .iter()
            .map(|c| (c.index, c.offset, c.count, c.sigma_max))
            .collect();
        assert_eq!(
            shape,
            vec![
                (34, 0, 1, 0.01),
                (35, 1, 1, 0.015),
                (36, 2, 1, 0.019),
                (39, 3, 1, 0.05)
            ]
        );
        let masses: Vec<f32> = (0..4).map(|i| f.blob(i).mass).collect();
        assert_eq!(masses, vec![1.0, 3.0, 4.0, 2.0]);
        let b = f.blob(3);
        assert_eq!(b.center, Vec3::new(1.0, 2.0, -1.0));
        assert_eq!(b.sigma, 0.05);
        assert_eq!(b.albedo, Vec3::new(0.25, 0.5, 0.75));
        // (1 − Ω) Q, exact in half precision here.
        assert_eq!(b.emission, Vec3::new(1.5, 0.0, 1.0));
        assert!(f.emissive);
    }

    #[test]
    fn the_gas_packs_as_its_render_blobs_do() {
        let mut blobs = Blobs::default();
        for i in 0..300 {
            let x = i as f32 * 0.01;
            let own = (i % 3 == 0).then_some([0.2, 0.4, 0.6]);
            let glow = (i % 5 == 0).then_some([1.0, 0.5, 0.0]);
            let b = Blob::new(Vec3::new(x, 1.0 - x, 0.5 * x), 0.01, 1.0, 0.0).coloured(own, glow);
            let mass = if i % 7 == 0 { 0.0 } else { 1.0 + x };
            blobs.push(&b, 0.001 * (1.0 + (i % 40) as f32), mass);
        }
        let medium = Vec3::new(0.9, 0.8, 0.7);
        let each = PackedFrame::pack(blobs.len(), |i| RenderBlob {
            center: blobs.center(i),
            sigma: blobs.sigma[i],
            mass: blobs.mass[i],
            albedo: blobs.albedo_of(i).map_or(medium, Vec3::from_array),
            emission: Vec3::from_slice(&blobs.emission[3 * i..3 * i + 3]),
        });
        let gas = PackedFrame::of_blobs(&blobs, medium);
        assert!(gas.classes.len() > 3 && gas.emissive);
        assert_eq!(gas.count, 300 - 43);
        assert_eq!(gas, each);
    }

    #[test]
    fn bounds_hold_every_footprint_and_info_describes_the_frame() {
        let blobs = [blob(0.0, 0.1, 1.0), blob(1.0, 0.2, 1.0)];
        let f = PackedFrame::pack(2, |i| blobs[i]);
        let (lo, hi) = f.bounds.unwrap();
        assert!(lo.abs_diff_eq(Vec3::new(-0.3, -0.3, -1.6), 1e-6), "{lo}");
        assert!(hi.abs_diff_eq(Vec3::new(1.6, 2.6, 0.3), 1e-6), "{hi}");
        let info = f.info();
        assert_eq!(info[0], 2.0);
        assert_eq!(&info[1..7], &[lo.x, lo.y, lo.z, hi.x, hi.y, hi.z]);
        assert_eq!(info[7], 1.0);
        assert_eq!(info[8], 0.1);
        // σ = 0.1: σ² = 2^-6.6, class 41; σ = 0.2: 2^-4.6, class 43.
        assert_eq!(info[9], 2.0);
        assert_eq!(&info[10..], &[41.0, 0.0, 1.0, 0.1, 43.0, 1.0, 1.0, 0.2]);
    }

    #[test]
    fn a_class_is_ordered_by_width_so_a_view_can_cut_it() {
        // Widths spread over classes 33 to 35, in no order: within each class the packed σ come
        // in order of their key, and the key never falls as σ grows.
        let blobs: Vec<RenderBlob> = (0..500)
            .map(|i| {
                blob(
                    i as f32,
                    0.005 * (1.0 + ((i * 7919) % 500) as f32 / 250.0),
                    1.0,
                )
            })
            .collect();
        let f = PackedFrame::pack(blobs.len(), |i| blobs[i]);
        assert_eq!(f.count, 500);
        for c in &f.classes {
            let keys: Vec<usize> = (c.offset..c.offset + c.count)
                .map(|i| order_key(f.blob(i).sigma))
                .collect();
            assert!(keys.windows(2).all(|w| w[0] <= w[1]), "class {}", c.index);
            assert!(keys.iter().all(|&k| k / SUBCLASSES == c.index));
        }
        let mut sigmas: Vec<f32> = blobs.iter().map(|b| b.sigma).collect();
        sigmas.sort_by(f32::total_cmp);
        assert!(sigmas
            .windows(2)
            .all(|w| order_key(w[0]) <= order_key(w[1])));
        // Sixteen steps a class: σ² = σ_k² (1 + j/16) starts step j.
        let k = 40;
        for j in 0..SUBCLASSES {
            let sigma = (class_sigma(k).powi(2) * (1.0 + j as f32 / 16.0)).sqrt() * (1.0 + 1e-6);
            assert_eq!(order_key(sigma), k * SUBCLASSES + j);
        }
    }

    #[test]
    fn an_empty_frame_has_no_bounds() {
        let f = PackedFrame::pack(0, |_| unreachable!());
        assert_eq!(f.count, 0);
        assert!(f.bounds.is_none());
        assert_eq!(f.info(), vec![0.0; 10]);
    }

    #[test]
    fn the_widest_blobs_share_the_last_class() {
        // σ = 2^k m for k = −28 … 9: factors of 2 are two classes apart; the narrowest share the
        // first class and the widest the last.
        let blobs: Vec<RenderBlob> = (-28..10)
            .map(|k| blob(k as f32, 2f32.powi(k), 1.0))
            .collect();
        let f = PackedFrame::pack(blobs.len(), |i| blobs[i]);
        let first = f.classes[0];
        assert_eq!((first.index, first.count), (0, 5));
        assert_eq!(first.sigma_max, 2f32.powi(-24));
        let last = f.classes.last().unwrap();
        assert_eq!((last.index, last.count), (SIGMA_CLASSES - 1, 2));
        assert_eq!(f.classes.len(), 2 + 31);
        for (k, c) in f
            .classes
            .iter()
            .enumerate()
            .skip(1)
            .take(f.classes.len() - 2)
        {
            assert_eq!(c.index, 2 * (k - 1) + 2, "{c:?}");
            assert_eq!(class_sigma(c.index), c.sigma_max);
        }
    }
}
