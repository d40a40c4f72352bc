//! The reference renderer's march (paper §5, Appendix B): a blob list prepared once (blobs
//! resolved, hierarchy built, lights prepared), then each primary ray cut into intervals at the
//! chords of the truncated blobs it meets, stepped, and composited front to back with the
//! light it scatters (Eqs. 24–28). See the module [`super`] for the model.

use super::bvh::Bvh;
use super::gaussian::{Chord, RenderBlob};
use super::geometry::{nearest_hit, occluded, CameraRays};
use super::image::LinearImage;
use crate::error::ParamError;
use crate::scene::blob_list::{BlobList, Light, Object, Phase};
use glam::Vec3;

/// Quality and method switches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    /// Traverse the hierarchy (true) or test every blob (the brute-force baseline).
    pub use_tree: bool,
    /// Longest step along a ray, as a fraction of the smallest active σ.
    pub step_fraction: f32,
}

/// The longest step along a ray as a fraction of the smallest σ active on it, by default (the
/// exact GPU march steps the same way).
pub const STEP_FRACTION: f32 = 0.5;

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            use_tree: true,
            step_fraction: STEP_FRACTION,
        }
    }
}

/// Rays whose transmittance falls below this stop early.
const OPAQUE: f32 = 1e-5;
/// Radiance below this (linear, ~1/30 of an 8-bit sRGB step near black) is not computed.
const NEGLIGIBLE: f32 = 1e-5;
/// Shadow rays stop once their optical depth exceeds this (transmittance < 1e-7).
const SHADOW_DEPTH: f32 = 16.0;

#[derive(Debug, Clone, Copy)]
enum PreparedLight {
    Point {
        position: Vec3,
        color: Vec3,
    },
    /// Unit vector towards the light.
    Directional {
        to_light: Vec3,
        color: Vec3,
    },
}

/// A blob list prepared for rendering: blobs resolved, hierarchy built.
pub struct Renderer {
    blobs: Vec<RenderBlob>,
    bvh: Bvh,
    rays: CameraRays,
    kappa: Vec3,
    phase: Phase,
    lights: Vec<PreparedLight>,
    shadows: bool,
    background: Vec3,
    /// The background is transparent: the image carries its coverage as alpha.
    transparent: bool,
    objects: Vec<Object>,
    /// Σ_k max colour_k × max phase: a bound on L(x).
    scatter_bound: f32,
    pub width: u32,
    pub height: u32,
    options: RenderOptions,
}

impl Renderer {
    /// Validates `list` and prepares it; `size` overrides the image size.
    pub fn new(
        list: &BlobList,
        size: Option<(u32, u32)>,
        options: RenderOptions,
    ) -> Result<Self, ParamError> {
        let mut list = list.clone();
        if let Some((w, h)) = size {
            list.image.width = w;
            list.image.height = h;
        }
        list.validate()?;
        let medium_albedo = Vec3::from_array(list.medium.albedo);
        let blobs: Vec<RenderBlob> = list
            .blobs
            .iter()
            .filter(|b| b.mass > 0.0)
            .map(|b| RenderBlob::of(b, medium_albedo))
            .collect();
        let bvh = if options.use_tree {
            Bvh::build(&blobs)
        } else {
            Bvh::default()
        };
        let lights = list
            .lights
            .iter()
            .map(|l| match l {
                Light::Point { position, color } => PreparedLight::Point {
                    position: Vec3::from_array(*position),
                    color: Vec3::from_array(*color),
                },
                Light::Directional { direction, color } => PreparedLight::Directional {
                    to_light: -Vec3::from_array(*direction).normalize(),
                    color: Vec3::from_array(*color),
                },
            })
            .collect();
        let peak_phase = match list.medium.phase {
            Phase::Isotropic {} => 1.0,
            Phase::HenyeyGreenstein { g } => phase(list.medium.phase, g.signum()),
        };
        let scatter_bound = list
            .lights
            .iter()
            .map(|l| match l {
                Light::Point { color, .. } | Light::Directional { color, .. } => {
                    color.iter().cloned().fold(0.0f32, f32::max)
                }
            })
            .sum::<f32>()
            * peak_phase;
        Ok(Self {
            scatter_bound,
            blobs,
            bvh,
            rays: CameraRays::new(&list.camera, list.image.width, list.image.height),
            kappa: Vec3::from_array(list.medium.extinction.rgb()),
            phase: list.medium.phase,
            lights,
            shadows: list.shadows,
            background: Vec3::from_array(list.background.radiance()),
            transparent: list.background.is_transparent(),
            objects: list.objects.clone(),
            width: list.image.width,
            height: list.image.height,
            options,
        })
    }

    /// Renders the whole image (rows in parallel where the `parallel` feature is on); with a
    /// transparent background it carries its coverage as alpha.
    pub fn render(&self) -> LinearImage {
        let pixels = (self.width * self.height) as usize;
        let mut data = vec![0.0f32; 3 * pixels];
        let mut alpha = vec![0.0f32; pixels];
        let (row_len, w) = (3 * self.width as usize, self.width as usize);
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            data.par_chunks_mut(row_len)
                .zip(alpha.par_chunks_mut(w))
                .enumerate()
                .for_each(|(j, (row, a))| self.render_row(j as u32, row, a));
        }
        #[cfg(not(feature = "parallel"))]
        for (j, (row, a)) in data
            .chunks_mut(row_len)
            .zip(alpha.chunks_mut(w))
            .enumerate()
        {
            self.render_row(j as u32, row, a);
        }
        LinearImage {
            width: self.width,
            height: self.height,
            data,
            alpha: self.transparent.then_some(alpha),
        }
    }

    /// Renders row `j` into `row` (3 × width floats) and its coverage into `alpha` (width
    /// floats).
    pub fn render_row(&self, j: u32, row: &mut [f32], alpha: &mut [f32]) {
        for i in 0..self.width {
            let (c, a) = self.radiance_alpha(self.rays.origin(), self.rays.direction(i, j));
            row[3 * i as usize..3 * i as usize + 3].copy_from_slice(&c.to_array());
            alpha[i as usize] = a;
        }
    }

    /// Whether the background is transparent (the image carries alpha).
    pub fn transparent(&self) -> bool {
        self.transparent
    }

    /// Blobs the ray may touch: through the hierarchy, or all of them. `visit` returns false
    /// to stop early.
    #[inline]
    fn candidates(
        &self,
        origin: Vec3,
        dir: Vec3,
        s_max: f32,
        mut visit: impl FnMut(usize) -> bool,
    ) {
        if self.options.use_tree {
            self.bvh.for_each_candidate(origin, dir, s_max, visit);
        } else {
            for j in 0..self.blobs.len() {
                if !visit(j) {
                    return;
                }
            }
        }
    }

    /// ∫ρ ds from `origin` along `dir` over [0, s_max]; stops adding once the column is
    /// opaque (transmittance below e^−[`SHADOW_DEPTH`] in every channel).
    fn column(&self, origin: Vec3, dir: Vec3, s_max: f32) -> f32 {
        let mut sum = 0.0;
        let limit = SHADOW_DEPTH / self.kappa.min_element().max(1e-12);
        self.candidates(origin, dir, s_max, |j| {
            if let Some(c) = self.blobs[j].chord(origin, dir) {
                sum += c.integral_clipped(0.0, s_max);
            }
            sum < limit
        });
        sum
    }

    /// The column ∫ρ ds from `x` towards light `k` (to the light, or to infinity): the gas's
    /// share of S_k; objects on the way are [`Self::light_blocked`]'s.
    pub fn column_to_light(&self, x: Vec3, k: usize) -> f32 {
        let (to_light, s_max) = self.towards(x, k);
        self.column(x, to_light, s_max)
    }

    /// The unit vector from `x` towards light `k` and the distance to it (∞ if directional).
    fn towards(&self, x: Vec3, k: usize) -> (Vec3, f32) {
        match self.lights[k] {
            PreparedLight::Point { position, .. } => {
                let d = position - x;
                (d.normalize_or_zero(), d.length())
            }
            PreparedLight::Directional { to_light, .. } => (to_light, f32::INFINITY),
        }
    }

    /// Whether an opaque object lies between `x` and light `k` (then S_k = 0 whatever the
    /// gas; [`occluded`]).
    pub fn light_blocked(&self, x: Vec3, k: usize) -> bool {
        let (to_light, s_max) = self.towards(x, k);
        occluded(&self.objects, x, to_light, s_max)
    }

    /// Number of lights.
    pub fn light_count(&self) -> usize {
        self.lights.len()
    }

    /// Axis-aligned bounds of the truncated blobs, if any.
    pub fn gas_bounds(&self) -> Option<(Vec3, Vec3)> {
        self.blobs.iter().fold(None, |acc, b| {
            let r = Vec3::splat(b.radius());
            let (lo, hi) = (b.center - r, b.center + r);
            Some(acc.map_or((lo, hi), |(a, c): (Vec3, Vec3)| (a.min(lo), c.max(hi))))
        })
    }

    /// Σ_k p(D·l_k) S_k(x) L_k (Eq. 25), S_k zero where an object blocks the light; with
    /// `lambert`, max(0, n·l_k) replaces the phase.
    fn in_scattered(&self, x: Vec3, dir: Vec3, lambert: Option<Vec3>) -> Vec3 {
        let mut total = Vec3::ZERO;
        for light in &self.lights {
            let (to_light, s_max, color) = match *light {
                PreparedLight::Point { position, color } => {
                    let d = position - x;
                    let len = d.length();
                    if len < 1e-9 {
                        continue;
                    }
                    (d / len, len, color)
                }
                PreparedLight::Directional { to_light, color } => (to_light, f32::INFINITY, color),
            };
            let weight = match lambert {
                Some(n) => n.dot(to_light).max(0.0),
                None => phase(self.phase, dir.dot(to_light)),
            };
            if weight == 0.0 {
                continue;
            }
            let s = if self.shadows {
                // An opaque object on the way: S_k = 0, and no column to integrate.
                if occluded(&self.objects, x, to_light, s_max) {
                    continue;
                }
                (-self.kappa * self.column(x, to_light, s_max)).exp()
            } else {
                Vec3::ONE
            };
            total += color * s * weight;
        }
        total
    }

    /// Radiance arriving at `origin` from direction `dir`.
    pub fn radiance(&self, origin: Vec3, dir: Vec3) -> Vec3 {
        self.radiance_alpha(origin, dir).0
    }

    /// Radiance arriving at `origin` from direction `dir`, and its coverage α: 1 where the ray
    /// ends on an opaque object or in opaque gas, else 1 − T(∞) (the mean over the channels of
    /// the transmittance past the gas). With a transparent background the radiance is the
    /// premultiplied colour over nothing; with a colour it includes T(∞) · background.
    pub fn radiance_alpha(&self, origin: Vec3, dir: Vec3) -> (Vec3, f32) {
        let hit = nearest_hit(&self.objects, origin, dir);
        let s_end = hit.map_or(f32::INFINITY, |h| h.s);
        let mut chords: Vec<(Chord, usize)> = Vec::new();
        self.candidates(origin, dir, s_end, |j| {
            if let Some(mut c) = self.blobs[j].chord(origin, dir) {
                c.s_in = c.s_in.max(0.0);
                c.s_out = c.s_out.min(s_end);
                if c.s_out > c.s_in {
                    chords.push((c, j));
                }
            }
            true
        });
        chords.sort_unstable_by(|a, b| a.0.s_in.total_cmp(&b.0.s_in).then(a.1.cmp(&b.1)));
        let mut radiance = Vec3::ZERO;
        let mut transmittance = Vec3::ONE;
        if self.march(origin, dir, &chords, &mut radiance, &mut transmittance) {
            return (radiance, 1.0);
        }
        match hit {
            Some(h) => {
                let p = origin + dir * h.s + h.normal * 1e-4;
                radiance += transmittance * h.color * self.in_scattered(p, dir, Some(h.normal));
                (radiance, 1.0)
            }
            None => {
                radiance += transmittance * self.background;
                (radiance, 1.0 - transmittance.element_sum() / 3.0)
            }
        }
    }

    /// Composites the chords (sorted by entry) front to back (Eqs. 26–27). Steps are at most
    /// `step_fraction × min σ` of the blobs active at the step's start; every chord's exact
    /// integral over each step is used, so entries and exits need no steps of their own, and
    /// gaps between blobs are jumped. Returns true if the ray became opaque.
    fn march(
        &self,
        origin: Vec3,
        dir: Vec3,
        chords: &[(Chord, usize)],
        radiance: &mut Vec3,
        transmittance: &mut Vec3,
    ) -> bool {
        let mut active: Vec<usize> = Vec::new();
        let mut erf_at: Vec<f32> = vec![0.0; chords.len()];
        let mut next = 0;
        let mut s = 0.0f32;
        while next < chords.len() || !active.is_empty() {
            if active.is_empty() {
                s = s.max(chords[next].0.s_in);
            }
            while next < chords.len() && chords[next].0.s_in <= s {
                let c = &chords[next].0;
                erf_at[next] = c.erf_at(s);
                active.push(next);
                next += 1;
            }
            let min_sigma = active
                .iter()
                .map(|&k| self.blobs[chords[k].1].sigma)
                .fold(f32::INFINITY, f32::min);
            let s1 = s + (min_sigma * self.options.step_fraction).max(1e-6);
            // Blobs entering inside the step contribute from their entry on.
            while next < chords.len() && chords[next].0.s_in < s1 {
                let c = &chords[next].0;
                erf_at[next] = c.erf_at(c.s_in);
                active.push(next);
                next += 1;
            }
            let mut w_sum = 0.0f32;
            let mut albedo = Vec3::ZERO;
            let mut emitted = Vec3::ZERO;
            // Where the step's gas ends: its light is sought within the gas, never past the
            // object that ends the ray (whose shadow would fall on the point).
            let mut reach = s;
            active.retain(|&k| {
                let (c, j) = &chords[k];
                let end = s1.min(c.s_out);
                reach = reach.max(end);
                let e1 = c.erf_at(end);
                let w = (c.peak * (e1 - erf_at[k])).max(0.0);
                erf_at[k] = e1;
                let blob = &self.blobs[*j];
                w_sum += w;
                albedo += blob.albedo * w;
                emitted += (Vec3::ONE - blob.albedo) * blob.emission * w;
                c.s_out > s1
            });
            if w_sum > 0.0 {
                let tau = self.kappa * w_sum;
                let albedo = albedo / w_sum;
                let mut source = emitted / w_sum;
                let absorbed = Vec3::ONE - (-tau).exp();
                // In-scattering only where it can show: its largest possible contribution
                // (full light, peak phase, no shadow) above NEGLIGIBLE.
                let bound = (*transmittance * absorbed * albedo).max_element() * self.scatter_bound;
                if bound > NEGLIGIBLE {
                    let x = origin + dir * (0.5 * (s + reach));
                    source += albedo * self.in_scattered(x, dir, None);
                }
                *radiance += *transmittance * absorbed * source;
                *transmittance *= Vec3::ONE - absorbed;
                if transmittance.max_element() < OPAQUE {
                    return true;
                }
            }
            s = s1;
        }
        false
    }
}

/// The phase function at cos θ = D·l (isotropic p ≡ 1; Henyey-Greenstein).
pub fn phase(p: Phase, cos_theta: f32) -> f32 {
    match p {
        Phase::Isotropic {} => 1.0,
        Phase::HenyeyGreenstein { g } => {
            (1.0 - g * g) / libm::powf(1.0 + g * g - 2.0 * g * cos_theta, 1.5)
        }
    }
}
