//! The doublets of the solids whose wind reaches a point ([`crate::wind::walls::Doublet`]),
//! summed there: the spheres four at a time, a sphere a lane of four-wide vectors, the others
//! one by one. A point among many spheres lies in the zones of several; their sum is most of
//! the cost of a wind among them.

use crate::lanes::sqrt4;
use crate::wind::solids::Around;
use crate::wind::walls::{Doublet, SPHERE_ZONE};
use glam::{Mat4, Vec3A, Vec4};

/// The scene's doublets (none for a solid without one), each sphere's centre and radius as one
/// vector (x, y, z, a), and the uniform wind U they are the potential flow in.
#[derive(Debug, Clone, Default)]
pub struct Doublets {
    doublets: Vec<Option<Doublet>>,
    spheres: Vec<Vec4>,
    wind: Vec3A,
}

/// What a sum gives: the vector potential ψ (m²/s) or the wind u = ∇ × ψ (m/s).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    Potential,
    Wind,
}

impl Doublets {
    /// `doublets[i]`, solid i's doublet in the uniform wind `wind` (m/s), if it has one.
    pub fn new(doublets: Vec<Option<Doublet>>, wind: Vec3A) -> Self {
        let spheres = doublets
            .iter()
            .map(|d| match *d {
                Some(Doublet::Sphere { centre, radius, .. }) => centre.extend(radius),
                _ => Vec4::ZERO,
            })
            .collect();
        Self {
            doublets,
            spheres,
            wind,
        }
    }

    /// Solid `i`'s doublet, if it has one.
    #[inline]
    pub fn get(&self, i: usize) -> Option<&Doublet> {
        self.doublets[i].as_ref()
    }

    /// Σ over the solids of `around` but `skip` of their doublets' ψ or u at `x`.
    #[inline(always)]
    pub fn sum(&self, part: Part, x: Vec3A, around: &Around, skip: usize) -> Vec3A {
        let mut sum = Vec3A::ZERO;
        if around.spheres.is_empty() && around.others.is_empty() {
            return sum;
        }
        let mut lanes = [Vec4::ZERO; 3];
        let mut quad = [Vec4::ZERO; 4];
        let mut k = 0;
        for &j in around.spheres {
            if j as usize != skip {
                quad[k] = self.spheres[j as usize];
                k += 1;
                if k == 4 {
                    self.add_spheres(part, &mut lanes, &quad, 4, x);
                    k = 0;
                }
            }
        }
        if k > 0 {
            self.add_spheres(part, &mut lanes, &quad, k, x);
        }
        if !around.spheres.is_empty() {
            let [a, b, c] = lanes;
            sum = Vec3A::new(a.element_sum(), b.element_sum(), c.element_sum());
        }
        for &j in around.others {
            if let (true, Some(d)) = (j as usize != skip, &self.doublets[j as usize]) {
                sum += match part {
                    Part::Wind => d.at(x).1,
                    Part::Potential => d.potential(x),
                };
            }
        }
        sum
    }

    /// Adds the doublets of the first `live` spheres of `quad` ((x, y, z, a) each) at `x`,
    /// lane by lane, to `lanes` (x, y and z components). [`Doublet::at`] for spheres, four-wide.
    #[inline(always)]
    fn add_spheres(
        &self,
        part: Part,
        lanes: &mut [Vec4; 3],
        quad: &[Vec4; 4],
        live: usize,
        x: Vec3A,
    ) {
        let m = Mat4::from_cols(quad[0], quad[1], quad[2], quad[3]).transpose();
        let a = m.w_axis;
        // Dead lanes copy the first sphere and are dropped at the end.
        let live = Vec4::new(0.0, 1.0, 2.0, 3.0).cmplt(Vec4::splat(live as f32));
        let r = [
            Vec4::splat(x.x) - m.x_axis,
            Vec4::splat(x.y) - m.y_axis,
            Vec4::splat(x.z) - m.z_axis,
        ];
        let rho = sqrt4(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
        let inv = Vec4::ONE / rho.max(a);
        let inv_span = Vec4::ONE / (a * (SPHERE_ZONE[1] - SPHERE_ZONE[0]));
        // The taper w(s) and dw/ds on [0, 1], which are 1 and 0 at the ends.
        let s = ((rho - a * SPHERE_ZONE[0]) * inv_span).clamp(Vec4::ZERO, Vec4::ONE);
        let s2 = s * s;
        let w = Vec4::ONE - s2 * s * (10.0 + s * (-15.0 + 6.0 * s));
        // Outside (ρ ≥ a): ψ = −(a³/2ρ³) U × r, u = −(a³/2ρ³)(3(U·r)r/ρ² − U); inside:
        // ψ = −½ U × r, u = −U.
        let outside = rho.cmpge(a);
        let q = Vec4::select(outside, 0.5 * a * a * a * inv * inv * inv, Vec4::splat(0.5));
        let u = [
            Vec4::splat(self.wind.x),
            Vec4::splat(self.wind.y),
            Vec4::splat(self.wind.z),
        ];
        let psi = [
            (u[1] * r[2] - u[2] * r[1]) * -q,
            (u[2] * r[0] - u[0] * r[2]) * -q,
            (u[0] * r[1] - u[1] * r[0]) * -q,
        ];
        let out = if part == Part::Potential {
            psi.map(|p| p * w)
        } else {
            let k = 3.0 * (u[0] * r[0] + u[1] * r[1] + u[2] * r[2]) * inv * inv;
            let v: [Vec4; 3] =
                std::array::from_fn(|i| Vec4::select(outside, (k * r[i] - u[i]) * -q, -u[i]));
            // ∇ × (w ψ) = w ∇ × ψ + ∇w × ψ, ∇w = w'(ρ) r/ρ (w' per metre).
            let dw = -30.0 * s2 * (Vec4::ONE - s) * (Vec4::ONE - s);
            let g = dw * inv_span * inv;
            let grad = [g * r[0], g * r[1], g * r[2]];
            [
                w * v[0] + (grad[1] * psi[2] - grad[2] * psi[1]),
                w * v[1] + (grad[2] * psi[0] - grad[0] * psi[2]),
                w * v[2] + (grad[0] * psi[1] - grad[1] * psi[0]),
            ]
        };
        for (l, o) in lanes.iter_mut().zip(out) {
            *l += Vec4::select(live, o, Vec4::ZERO);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::bodies::Body;

    /// Spheres four at a time (with the dead lanes of a last, partial four) and a cylinder
    /// one by one give the sum of [`Doublet::at`] over the list, inside, outside and in the
    /// tapers.
    #[test]
    fn the_sum_is_the_sum_of_each_doublet() {
        let wind = Vec3A::new(0.4, 1.1, -0.3);
        let mut bodies: Vec<Body> = (0..11)
            .map(|i| {
                let f = |k: f32| ((i as f32 + 0.5) * k).fract() * 2.0 - 1.0;
                Body::Sphere {
                    center: Vec3A::new(f(0.7548777), f(0.5698403), f(0.4301597)),
                    radius: 0.05 + 0.01 * i as f32,
                }
            })
            .collect();
        bodies.insert(
            5,
            Body::Cylinder {
                base: Vec3A::new(0.1, -0.5, 0.2),
                axis: Vec3A::new(0.2, 1.0, 0.1).normalize(),
                radius: 0.1,
                height: 0.8,
            },
        );
        let each: Vec<Option<Doublet>> = bodies.iter().map(|b| Doublet::of(b, wind)).collect();
        let set = Doublets::new(each.clone(), wind);
        let (spheres, others): (Vec<u32>, Vec<u32>) = (0..bodies.len() as u32)
            .partition(|&j| matches!(bodies[j as usize], Body::Sphere { .. }));
        let around = Around {
            layers: &[],
            spheres: &spheres,
            others: &others,
        };
        for i in 0..2000 {
            let f = |k: f32| ((i as f32 + 0.5) * k).fract() * 3.0 - 1.5;
            let x = Vec3A::new(f(0.1234567), f(0.7654321), f(0.3141592));
            for (part, skip) in [(Part::Wind, usize::MAX), (Part::Potential, 3)] {
                let one_by_one: Vec3A = (0..bodies.len())
                    .filter(|&j| j != skip)
                    .filter_map(|j| each[j].map(|d| d.at(x)))
                    .map(|(psi, u)| if part == Part::Wind { u } else { psi })
                    .sum();
                let sum = set.sum(part, x, &around, skip);
                let tol = 1e-5 * (1.0 + one_by_one.length());
                assert!(
                    (sum - one_by_one).length() < tol,
                    "{x}: {sum} vs {one_by_one}"
                );
            }
        }
    }
}
