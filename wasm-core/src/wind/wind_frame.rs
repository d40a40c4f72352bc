//! The wind frozen at one time t: the small-scale field's slice (and, with solids, its vector
//! potential's), the primitives frozen with their mirror images in the solid planes, the solids
//! with their doublets, and the carried phases' blend. u(x) = u_l(x) + u_s(x) (paper Eq. 3),
//! turned along the solids within their layer (docs/CONVENTIONS.md, solid objects).

use crate::scene::bodies::Body;
use crate::wind::carried::Blend;
use crate::wind::doublets::Part;
use crate::wind::field_slice::FieldSlice;
use crate::wind::flow::FrozenFlow;
use crate::wind::frozen::{FrozenPrimitive, NOT_AN_IMAGE};
use crate::wind::solids::{Around, Nearest};
use crate::wind::wall_set::WallSet;
use crate::wind::walls::{project, ramp, Stencil};
use glam::{Vec3, Vec3A};
use std::sync::Arc;

/// The wind frozen at one time.
#[derive(Debug, Clone, Default)]
pub struct WindFrame {
    pub time: f64,
    /// Sum of the uniform winds without decay (m/s).
    pub(crate) constant: Vec3A,
    pub(crate) has_slice: bool,
    pub(crate) slice: FieldSlice,
    /// The scene's primitives (their first `originals`), then their mirror images in the
    /// solid planes; `images[i]` is the range of primitive i's images.
    pub(crate) primitives: Vec<FrozenPrimitive>,
    pub(crate) originals: usize,
    pub(crate) images: Vec<(u32, u32)>,
    /// The field's vector potential at this time (with solids whose field has it).
    pub(crate) has_psi: bool,
    pub(crate) psi: FieldSlice,
    pub(crate) walls: Option<Arc<WallSet>>,
    /// The carried phases' blend at this time.
    pub(crate) blend: Option<Blend>,
    /// The flow's u_g (paper §7), added to the large scales in its box.
    pub(crate) flow: Option<Arc<FrozenFlow>>,
}

impl WindFrame {
    /// u(x) = u_s(x) + Σ primitives (m/s).
    #[inline]
    pub fn velocity(&self, x: Vec3) -> Vec3 {
        self.velocity_a(x.into()).into()
    }

    /// Whether the wind is the plain sum (no solids, nothing carried): the fast path.
    #[inline]
    pub fn is_plain(&self) -> bool {
        self.walls.is_none() && self.blend.is_none()
    }

    /// [`Self::velocity`] in four-wide vectors, for the per-blob loop. Carried coordinates are
    /// taken as just reset (offsets zero).
    #[inline]
    pub fn velocity_a(&self, x: Vec3A) -> Vec3A {
        if !self.is_plain() {
            let (l, s) = self.parts(x, [Vec3A::ZERO; 2]);
            return l + s;
        }
        let mut u = self.constant;
        if self.has_slice {
            u += self.slice.sample(x);
        }
        if let Some(f) = &self.flow {
            u += f.velocity(x);
        }
        FrozenPrimitive::add_winds(&self.primitives, u, x)
    }

    /// u_p, the scene's primitives alone at `x` (no solids, no mirror images, no flow), m/s:
    /// the wind the flow's solver is given.
    #[inline]
    pub fn primitive_wind(&self, x: Vec3A) -> Vec3A {
        FrozenPrimitive::add_winds(&self.primitives[..self.originals], self.constant, x)
    }

    /// u_p where it is the same everywhere (the scene's primitives all uniform winds without
    /// decay): [`Self::primitive_wind`] at any point, m/s.
    pub fn uniform_primitive_wind(&self) -> Option<Vec3A> {
        (self.originals == 0).then_some(self.constant)
    }

    /// The small-scale field's slice sampled at `x`, with the carried coordinates' offsets
    /// `o` (ignored unless carried).
    #[inline(always)]
    fn blended(&self, slice: &FieldSlice, x: Vec3A, o: [Vec3A; 2]) -> Vec3A {
        match self.blend {
            None => slice.sample(x),
            Some(b) => {
                let [wa, wb] = b.weights;
                let mut u = Vec3A::ZERO;
                if wa != 0.0 {
                    u += slice.sample(x + o[0]) * wa;
                }
                if wb != 0.0 {
                    u += slice.sample(x + o[1] + b.shift) * wb;
                }
                u
            }
        }
    }

    /// [`Self::blended`] at each of `xs` (a stencil), each phase's points sampled together
    /// ([`FieldSlice::sample_each`]): the same values, a lattice cell's lookup shared.
    #[inline(always)]
    fn blended_each<const N: usize>(
        &self,
        slice: &FieldSlice,
        xs: &[Vec3A; N],
        o: [Vec3A; 2],
    ) -> [Vec3A; N] {
        let Some(b) = self.blend else {
            return slice.sample_each(xs);
        };
        let [wa, wb] = b.weights;
        let mut u = [Vec3A::ZERO; N];
        for (k, weight) in [wa, wb].into_iter().enumerate() {
            if weight != 0.0 {
                // The second phase's points as [`Self::blended`] forms them: (x + o) + shift.
                let at = |x: Vec3A| if k == 0 { x + o[0] } else { x + o[1] + b.shift };
                let phase = slice.sample_each(&xs.map(at));
                for (u, p) in u.iter_mut().zip(phase) {
                    *u += p * weight;
                }
            }
        }
        u
    }

    /// The wind at `x` in its two parts, the large-scale wind u_l (the primitives and what the
    /// solids make of them) and the small-scale u_s, with the carried offsets `o` (m) of the
    /// two phases (ignored unless the field is carried).
    #[inline]
    pub fn parts(&self, x: Vec3A, o: [Vec3A; 2]) -> (Vec3A, Vec3A) {
        let (large, small, _) = self.parts_and_clearance(x, o);
        (large, small)
    }

    /// [`Self::parts`], and how far `x` surely lies from every solid (m,
    /// [`Solids::clearance`]; infinite without solids).
    #[inline]
    pub fn parts_and_clearance(&self, x: Vec3A, o: [Vec3A; 2]) -> (Vec3A, Vec3A, f32) {
        let small = |f: &Self| {
            if f.has_slice {
                f.blended(&f.slice, x, o)
            } else {
                Vec3A::ZERO
            }
        };
        let Some(w) = &self.walls else {
            let mut u = FrozenPrimitive::add_winds(&self.primitives, self.constant, x);
            if let Some(f) = &self.flow {
                u += f.velocity(x);
            }
            return (u, small(self), f32::INFINITY);
        };
        let (large, small, clear) = self.around_solids(w, x, o);
        match &self.flow {
            None => (large, small, clear),
            Some(f) => {
                // Within the flow's box u_p + u_g replaces the solids' closed forms for the
                // large scales; across its fade layer the two blend.
                let (weight, u_g) = f.weighted(x);
                if weight == 0.0 {
                    return (large, small, clear);
                }
                let solved = self.primitive_wind(x) + u_g;
                (large + (solved - large) * weight, small, clear)
            }
        }
    }

    /// [`Self::parts_and_clearance`] of the wind that goes round the solids `w` by their closed
    /// forms and the ramped curl (no flow).
    #[inline]
    fn around_solids(&self, w: &WallSet, x: Vec3A, o: [Vec3A; 2]) -> (Vec3A, Vec3A, f32) {
        let small = |f: &Self| {
            if f.has_slice {
                f.blended(&f.slice, x, o)
            } else {
                Vec3A::ZERO
            }
        };
        let around = w.solids.around(x);
        if let Some(near) = w.solids.nearest_among(around.layers, x) {
            let clear = w.solids.clearance(Some(near.distance), x);
            let (large, small) = self.near_solid(w, x, near, around, o);
            return (large, small, clear);
        }
        let u = self.constant + w.doublets.sum(Part::Wind, x, &around, usize::MAX);
        (
            FrozenPrimitive::add_winds(&self.primitives, u, x),
            small(self),
            w.solids.clearance(None, x),
        )
    }

    /// The wind within the layer of the solid `near` (docs/CONVENTIONS.md, solid objects).
    /// `around`: the lists of `x`'s grid cell.
    fn near_solid(
        &self,
        w: &WallSet,
        x: Vec3A,
        near: Nearest,
        around: Around,
        o: [Vec3A; 2],
    ) -> (Vec3A, Vec3A) {
        let n_index = near.index;
        let body = w.solids.bodies[n_index];
        let n = near.normal;
        let alpha = ramp(near.distance / w.width);
        let plane = matches!(body, Body::Plane { .. });
        // The uniform wind: exact past a sphere and along a cylinder's side (its cross-flow by
        // the doublet); a cylinder's caps stop its axial part, a plane what blows into it (and
        // keeps what blows away).
        let u0 = self.constant;
        let mut large = match body {
            Body::Sphere { .. } => u0,
            Body::Cylinder { axis, .. } => {
                let along = axis * u0.dot(axis);
                (u0 - along) + project(along, n, alpha, false)
            }
            Body::Plane { .. } => project(u0, n, alpha, true),
        };
        if let Some(d) = w.doublets.get(n_index) {
            large += d.at(x).1;
        }
        let gauge = |p: &FrozenPrimitive| match body {
            Body::Plane { point, normal } => {
                let q = p.place();
                q - normal * (q - point).dot(normal)
            }
            _ => body.centre(),
        };
        // Deeper inside than a step (a midpoint of a step into the solid), the ramped curl is
        // the one a step deep, about `xs`: the normal there is continuous.
        let h = w.steps[n_index];
        let (xs, around) = if near.distance < -h {
            let xs = x + n * (-h - near.distance);
            (xs, w.solids.around(xs))
        } else {
            (x, around)
        };
        // Other solids' doublets (those reaching the stencil about xs) and vortices go round
        // this one by the ramped curl.
        let others = around.any_but(n_index);
        let mut vortices = false;
        for (i, p) in self.primitives.iter().enumerate() {
            let exact = plane
                && (p.image_of == n_index as u32
                    || (p.image_of == NOT_AN_IMAGE && self.has_image_in(i, n_index as u32)));
            if exact {
                large += p.velocity(x);
            } else if p.has_potential() {
                vortices = true;
            } else {
                large += project(p.velocity(x), n, alpha, plane);
            }
        }
        let need_stencil = others || vortices || self.has_psi;
        if !need_stencil {
            let small = if self.has_slice {
                project(self.blended(&self.slice, x, o), n, alpha, false)
            } else {
                Vec3A::ZERO
            };
            return (large, small);
        }
        let stencil = Stencil::new(&body, w.solids.edges[n_index], xs, h, 1.0 / w.width);
        if others || vortices {
            let psi: [Vec3A; 6] = std::array::from_fn(|k| {
                let y = stencil.points[k];
                let mut psi = w.doublets.sum(Part::Potential, y, &around, n_index);
                for (i, p) in self.primitives.iter().enumerate() {
                    let exact = plane
                        && (p.image_of == n_index as u32
                            || (p.image_of == NOT_AN_IMAGE
                                && self.has_image_in(i, n_index as u32)));
                    if !exact && p.has_potential() {
                        psi += p.vortex_potential(y, gauge(p));
                    }
                }
                psi
            });
            large += stencil.ramped_curl(&psi);
        }
        let small = if self.has_psi {
            let psi = self.blended_each(&self.psi, &stencil.points, o);
            stencil.ramped_curl(&psi)
        } else if self.has_slice {
            // The field's potential is still being synthesised: project meanwhile.
            project(self.blended(&self.slice, xs, o), n, alpha, false)
        } else {
            Vec3A::ZERO
        };
        (large, small)
    }

    /// Whether the scene's primitive `i` has a mirror image in the solid `plane`.
    #[inline]
    fn has_image_in(&self, i: usize, plane: u32) -> bool {
        let Some(&(a, b)) = self.images.get(i) else {
            return false;
        };
        self.primitives[a as usize..b as usize]
            .iter()
            .any(|p| p.image_of == plane)
    }

    /// The solids the frame's wind goes round, if any.
    pub fn walls(&self) -> Option<&WallSet> {
        self.walls.as_deref()
    }

    /// The difference step (m) of the ramped curl near solid `index`, for checks of it.
    pub fn curl_step(&self, index: usize) -> Option<f32> {
        self.walls.as_ref().map(|w| w.steps[index])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::TurbulentField;
    use crate::lanes::ints3;
    use crate::scene::Scene;
    use crate::wind::Wind;

    /// A carried field over a solid floor, both phases weighing in at `t`.
    fn carried_frame(t: f64) -> WindFrame {
        let scene = Scene::from_json(
            r#"{"version": 1, "seed": 5,
                "field": {"size": [8, 8, 8, 8], "period": [1, 1, 1], "time_period": 4,
                          "spectrum": {"k_inertial": 2}, "carried": true, "carry_time": 0.5},
                "wind": [{"type": "uniform", "velocity": [0.3, 0.5, 0]}],
                "render": {"objects": [{"type": "plane", "point": [0, 0, 0],
                                        "normal": [0, 1, 0], "color": [0.5, 0.5, 0.5],
                                        "solid": true}]}}"#,
        )
        .expect("valid");
        let field = TurbulentField::generate_with_potential(&scene.field_params()).expect("valid");
        Wind::new(&scene, Some(Arc::new(field))).frame(t)
    }

    /// The stencil's carried ψ, each phase's six points sampled together, is bit for bit each
    /// point's own blend: in one lattice cell (the shared lookup) and across cells.
    #[test]
    fn a_stencils_blend_is_each_points_blend() {
        let frame = carried_frame(0.6);
        let b = frame.blend.expect("carried");
        assert!(b.weights.iter().all(|&w| w > 0.05), "{:?}", b.weights);
        assert!(frame.has_psi);
        let o = [
            Vec3A::new(0.031, -0.017, 0.052),
            Vec3A::new(-0.21, 0.08, 0.33),
        ];
        for (x, h) in [
            (Vec3A::new(0.31, 0.02, -0.27), 1e-3),
            (Vec3A::new(0.5, 0.05, 0.5), 0.1),
        ] {
            let axes = [Vec3A::X, Vec3A::Y, Vec3A::Z];
            let points: [Vec3A; 6] =
                std::array::from_fn(|k| x + axes[k / 2] * if k % 2 == 0 { h } else { -h });
            let together = frame.blended_each(&frame.psi, &points, o);
            for (p, u) in points.iter().zip(together) {
                let alone = frame.blended(&frame.psi, *p, o);
                assert_eq!(u.to_array(), alone.to_array(), "at {p}");
                assert!(alone.length() > 0.0);
            }
        }
    }

    /// A lattice of powers of two wraps its cells by a mask: the same cells, so the same
    /// samples bit for bit, as the general wrap, at points far either side of the period.
    #[test]
    fn the_masked_wrap_is_the_general_wrap() {
        let frame = carried_frame(0.6);
        let masked = &frame.slice;
        assert!(masked.wrap_mask.is_some());
        let general = FieldSlice {
            wrap_mask: None,
            ..masked.clone()
        };
        let mut seen = std::collections::HashSet::new();
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
        };
        for i in 0..6000 {
            let scale = [0.3, 4.0, 1000.0][i % 3];
            let x = Vec3A::new(next(), next(), next()) * scale;
            let q = ((x - masked.offset) * masked.cells_per_metre).floor();
            seen.insert(ints3(q).map(|i| i.rem_euclid(8)));
            assert_eq!(
                masked.sample(x).to_array(),
                general.sample(x).to_array(),
                "at {x}"
            );
        }
        // Every cell of the 8³ lattice was visited, from negative and positive coordinates.
        assert_eq!(seen.len(), 512);
    }
}
