//! The wind frozen at one time as the page's GPU stepper reads it: one row of floats a frame
//! ([`crate::wind::WindFrame::write_gpu_table`]), written by the core and read by the step
//! shader (`web/src/stepper/wind-glsl.js`, which computes the core's wind from it:
//! `wasm-core/tests/gpu_steps.rs` holds the same arithmetic, in Rust, to the core's wind).

use crate::scene::bodies::Body;
use crate::wind::frozen::{Frozen, NOT_AN_IMAGE};
use crate::wind::walls::Doublet;
use crate::wind::WindFrame;
use glam::Vec3A;

/// Floats of a wind table's header ([`WindFrame::write_gpu_table`]).
pub const WIND_TABLE_HEADER: usize = 32;
/// Floats per frozen primitive in a wind table.
pub const WIND_TABLE_PRIMITIVE: usize = 16;
/// Floats per solid object in a wind table.
pub const WIND_TABLE_SOLID: usize = 16;
/// A frozen primitive's kind in a wind table.
pub const UNIFORM_KIND: f32 = 0.0;
pub const SOURCE_KIND: f32 = 1.0;
pub const VORTEX_KIND: f32 = 2.0;
pub const REPULSOR_KIND: f32 = 3.0;
/// A solid's kind in a wind table.
pub const SPHERE_SOLID_KIND: f32 = 0.0;
pub const PLANE_SOLID_KIND: f32 = 1.0;
pub const CYLINDER_SOLID_KIND: f32 = 2.0;
/// Where the carried phases' resets go in a table's header (floats 30 and 31): the age τ (s)
/// each phase has at the step's end when it reset during the step, else this.
pub const NO_RESET: f32 = -1.0;
/// The index of the header's float for phase a's reset (phase b's follows).
pub const RESET_AT: usize = 30;

impl WindFrame {
    /// The wind frozen at this frame's time as the GPU stepper reads it, appended to `out`:
    ///
    /// - header ([`WIND_TABLE_HEADER`] floats, eight vec4): `[has_field, i0, i1, f]` (the
    ///   small-scale field's two lattice time slices and their blend), `[offset xyz (m), 0]`
    ///   (the eddies' shift by `carried_by_wind`), `[lattice cells per metre xyz, 0]`,
    ///   `[velocity scale xyz (m/s per lattice unit), 0]`, `[constant wind xyz (m/s),
    ///   primitive count]`, `[solid count, layer width d₀ (m), has potential, carried]`,
    ///   `[potential scale xyz (m²/s per lattice unit), the solids' slack (m): the
    ///   largest rounding of an edge, for the clearance]`, `[carried weight of phase a,
    ///   of phase b, reset age of a, of b]` (reset ages [`NO_RESET`] unless the step that
    ///   ends with this table resets a phase; [`crate::frame::gpu_steps`] sets them), then
    ///   nothing more (the shift of phase b, half the field's period, is
    ///   `0.5 · lattice size / cells per metre`);
    /// - per primitive ([`WIND_TABLE_PRIMITIVE`] floats, four vec4):
    ///   `[kind, 1/decay (1/m; 0: none), a, b]`, `[decay origin xyz (m), plane]`, `[p xyz,
    ///   first image]`, `[q xyz, images]`, where uniform: p = velocity; source: p = position,
    ///   a = s/(4π), b = core²; vortex: p = position, q = unit axis, a = Γ/(2π), b = core²;
    ///   repulsor: p = centre, q = velocity, a = radius, b = strength. A scene's primitive
    ///   has plane −1 and its mirror images at `first image` (count `images`; −1 and 0 for
    ///   none); an image has the index of its solid plane and −1, 0;
    /// - per solid ([`WIND_TABLE_SOLID`] floats, four vec4): `[kind, difference step h (m),
    ///   doublet (0 none, 1 sphere, 2 cylinder), 0]`, `[centre, point or base xyz (m),
    ///   radius]`, `[plane normal or cylinder axis xyz, height]`, `[the doublet's wind (a
    ///   sphere's U) or â × U (a cylinder's), 0]`.
    pub fn write_gpu_table(&self, out: &mut Vec<f32>) {
        let s = &self.slice;
        let (i0, i1, f) = s.time_slices;
        let v = |v: Vec3A, w: f32| [v.x, v.y, v.z, w];
        out.extend_from_slice(&[
            if self.has_slice { 1.0 } else { 0.0 },
            i0 as f32,
            i1 as f32,
            f,
        ]);
        out.extend_from_slice(&v(s.offset, 0.0));
        out.extend_from_slice(&v(s.cells_per_metre, 0.0));
        out.extend_from_slice(&v(s.velocity_scale, 0.0));
        out.extend_from_slice(&v(self.constant, self.primitives.len() as f32));
        let solids = self.walls.as_ref().map_or(0, |w| w.solids.len());
        out.extend_from_slice(&[
            solids as f32,
            self.walls.as_ref().map_or(0.0, |w| w.width),
            if self.has_psi { 1.0 } else { 0.0 },
            if self.blend.is_some() { 1.0 } else { 0.0 },
        ]);
        out.extend_from_slice(&v(
            self.psi.velocity_scale,
            self.walls.as_ref().map_or(0.0, |w| w.solids.slack()),
        ));
        let [wa, wb] = self.blend.map_or([0.0; 2], |b| b.weights);
        out.extend_from_slice(&[wa, wb, NO_RESET, NO_RESET]);
        for (i, p) in self.primitives.iter().enumerate() {
            let (kind, a, b, pos, q) = match p.kind {
                Frozen::Uniform { velocity } => (UNIFORM_KIND, 0.0, 0.0, velocity, Vec3A::ZERO),
                Frozen::Source { position, k, a2 } => (SOURCE_KIND, k, a2, position, Vec3A::ZERO),
                Frozen::Vortex {
                    position,
                    axis,
                    g,
                    a2,
                } => (VORTEX_KIND, g, a2, position, axis),
                Frozen::Repulsor {
                    center,
                    velocity,
                    radius,
                    strength,
                } => (REPULSOR_KIND, radius, strength, center, velocity),
            };
            let (plane, first, count) = if p.image_of == NOT_AN_IMAGE {
                match self.images.get(i) {
                    Some(&(a, b)) if b > a => (-1.0, a as f32, (b - a) as f32),
                    _ => (-1.0, -1.0, 0.0),
                }
            } else {
                (p.image_of as f32, -1.0, 0.0)
            };
            out.extend_from_slice(&[kind, p.inv_decay, a, b]);
            out.extend_from_slice(&v(p.origin, plane));
            out.extend_from_slice(&v(pos, first));
            out.extend_from_slice(&v(q, count));
        }
        if let Some(w) = &self.walls {
            for (j, body) in w.solids.bodies.iter().enumerate() {
                let (kind, a, r, b, h) = match *body {
                    Body::Sphere { center, radius } => {
                        (SPHERE_SOLID_KIND, center, radius, Vec3A::ZERO, 0.0)
                    }
                    Body::Plane { point, normal } => (PLANE_SOLID_KIND, point, 0.0, normal, 0.0),
                    Body::Cylinder {
                        base,
                        axis,
                        radius,
                        height,
                    } => (CYLINDER_SOLID_KIND, base, radius, axis, height),
                };
                let (doublet, d) = match w.doublets.get(j) {
                    Some(&Doublet::Sphere { wind, .. }) => (1.0, wind),
                    Some(&Doublet::Cylinder { m, .. }) => (2.0, m),
                    None => (0.0, Vec3A::ZERO),
                };
                out.extend_from_slice(&[kind, w.steps[j], doublet, 0.0]);
                out.extend_from_slice(&v(a, r));
                out.extend_from_slice(&v(b, h));
                out.extend_from_slice(&v(d, 0.0));
            }
        }
    }
}
