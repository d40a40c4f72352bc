//! The CPU reference renderer: the single-scattering model of paper §5 and Appendix B, with
//! shadows and a bounding-volume hierarchy, producing exactly the image a blob list stands for
//! (Appendix B's Eqs. 22–28, the rendering model of docs/FORMATS.md) in the limit of fine
//! steps.
//!
//! A primary ray is cut into intervals at the entry and exit points of the truncated blobs it
//! meets (Figure 2). Each interval is subdivided into steps no longer than
//! `step_fraction × min σ` of the blobs active on it; on each step the optical depth is the exact
//! sum of the blobs' Gaussian line integrals (Eq. 28, via erf), the source C is the
//! density-weighted mean of Ω L + (1 − Ω) Q over the step (Eq. 24), and compositing is front to
//! back (Eq. 27). L sums the lights with the phase function and the shadow transmittance S_k
//! (Eq. 25), itself an exact sum of line integrals through the same hierarchy, and zero where an
//! opaque object lies between the point and the light. Opaque objects end the ray with Lambert
//! shading shadowed by the gas and by the other objects; other rays end in the background.
//!
//! Its transcendental functions are `libm`'s (glam's `libm` feature for its vectors), the same
//! code the WebAssembly build runs, so a blob list renders to the same bytes natively and in
//! the browser (the platform's own `expf` and `powf` differ in the last bit now and then).
//!
//! Its input is the blob list of [`crate::scene::blob_list`]; it knows nothing of scenes, of the
//! gas's state or of the browser. The browser's GPU views have their own frame format
//! ([`crate::frame`]), held against this renderer by tests.
//!
//! - `gaussian`: one blob's density, its chord along a ray and the exact line integral (erf).
//! - `bvh`: the bounding-volume hierarchy over the truncated blobs.
//! - `geometry`: camera rays, the opaque objects and the shadow rays' any-hit test.
//! - [`image`]: linear images, sRGB encoding, PNG, PSNR.
//! - `renderer`: the [`Renderer`] itself, a ray's march and its light.
//! - [`banded`]: a still rendered a band of rows at a time (for progress reports).

pub mod banded;
mod bvh;
mod gaussian;
mod geometry;
pub mod image;
mod renderer;

pub use banded::BandedRender;
pub use bvh::Bvh;
pub use gaussian::{erf, Chord, RenderBlob, TRUNCATION};
pub use geometry::{occluded, CameraRays};
pub use image::{decode_png, encode_png, encode_png_rgba, psnr, LinearImage};
pub use renderer::{phase, RenderOptions, Renderer, STEP_FRACTION};
