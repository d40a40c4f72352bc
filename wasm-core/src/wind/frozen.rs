//! The large-scale wind primitives (paper Eq. 3's u_l) frozen at one time: repulsors placed on
//! their paths, constants folded, in world units (m, s, m/s). A frozen primitive also knows
//! whether it is a mirror image in a solid plane ([`FrozenPrimitive::mirrored`],
//! docs/CONVENTIONS.md, solid objects).

use crate::lanes::{exp4, EXP4_IS_VECTOR};
use crate::scene::scene_format::Primitive;
use crate::wind::spline::Path;
use glam::Vec3A;
use std::f32::consts::PI;

/// Marks a frozen primitive that is no mirror image ([`FrozenPrimitive::image_of`]).
pub const NOT_AN_IMAGE: u32 = u32::MAX;

/// A primitive frozen at one time, with its constants folded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Frozen {
    Uniform {
        velocity: Vec3A,
    },
    /// k = s/(4π), a² the squared core radius.
    Source {
        position: Vec3A,
        k: f32,
        a2: f32,
    },
    /// g = Γ/(2π).
    Vortex {
        position: Vec3A,
        axis: Vec3A,
        g: f32,
        a2: f32,
    },
    Repulsor {
        center: Vec3A,
        velocity: Vec3A,
        radius: f32,
        strength: f32,
    },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrozenPrimitive {
    pub kind: Frozen,
    /// Where decay is measured from, and 1/L (0 for no decay).
    pub origin: Vec3A,
    pub inv_decay: f32,
    /// The index of the solid plane this is the mirror image in ([`NOT_AN_IMAGE`] for a
    /// primitive of the scene), and the index (in the frame's list) of the primitive it
    /// mirrors (its own index for a primitive of the scene).
    pub image_of: u32,
    pub parent: u32,
}

impl FrozenPrimitive {
    #[inline]
    pub fn velocity(&self, x: Vec3A) -> Vec3A {
        let u = self.undecayed(x);
        if self.inv_decay > 0.0 {
            u * self.decay_exponent(x).exp()
        } else {
            u
        }
    }

    /// `u` plus the winds of `primitives` at `x` (m/s), added in order: [`Self::velocity`]
    /// each. Where the exponential has a four-wide form (WASM's SIMD) the decays' are taken
    /// four at a time ([`exp4`], each lane what `f32::exp` gives), so the same bits.
    #[inline]
    pub fn add_winds(primitives: &[Self], mut u: Vec3A, x: Vec3A) -> Vec3A {
        if !EXP4_IS_VECTOR {
            for p in primitives {
                u += p.velocity(x);
            }
            return u;
        }
        Self::add_winds_four(primitives, u, x)
    }

    /// [`Self::add_winds`] with the exponentials four at a time.
    #[inline(always)]
    fn add_winds_four(primitives: &[Self], mut u: Vec3A, x: Vec3A) -> Vec3A {
        for four in primitives.chunks(4) {
            // Lanes without decay take a harmless exponent and ignore its exponential.
            let mut exponent = [-1.0f32; 4];
            for (e, p) in exponent.iter_mut().zip(four) {
                if p.inv_decay > 0.0 {
                    *e = p.decay_exponent(x);
                }
            }
            let decay = exp4(exponent);
            for (p, d) in four.iter().zip(decay) {
                let w = p.undecayed(x);
                u += if p.inv_decay > 0.0 { w * d } else { w };
            }
        }
        u
    }

    /// The exponent of the decay factor exp(−|x − origin| / L).
    #[inline(always)]
    fn decay_exponent(&self, x: Vec3A) -> f32 {
        -(x - self.origin).length() * self.inv_decay
    }

    /// The wind at `x` before the decay (m/s).
    #[inline(always)]
    fn undecayed(&self, x: Vec3A) -> Vec3A {
        match self.kind {
            Frozen::Uniform { velocity } => velocity,
            Frozen::Source { position, k, a2 } => {
                let r = x - position;
                let d2 = r.length_squared() + a2;
                r * (k / (d2 * d2.sqrt()))
            }
            Frozen::Vortex {
                position,
                axis,
                g,
                a2,
            } => {
                // â × (x − p) is the distance from the axis turned a quarter round it, so
                // its length is that distance: u = g (â × r) / (|â × r|² + a²).
                let c = axis.cross(x - position);
                c * (g / (c.length_squared() + a2))
            }
            Frozen::Repulsor {
                center,
                velocity,
                radius,
                strength,
            } => repulsor_velocity(x - center, velocity, radius, strength),
        }
    }

    /// Whether the primitive is a vortex without decay: the one localised primitive with a
    /// vector potential in closed form ([`Self::vortex_potential`]), turned along solids other
    /// than planes it is mirrored in by the ramped curl.
    pub fn has_potential(&self) -> bool {
        matches!(self.kind, Frozen::Vortex { .. }) && self.inv_decay == 0.0
    }

    /// The vortex's vector potential ψ = −(g/2) ln((ρ² + a²)/(ρ₀² + a²)) â, ρ the distance
    /// of `x` from the axis and ρ₀ that of `gauge` (ψ vanishes there): ∇ × ψ is the vortex's
    /// wind for any gauge point. Zero for other primitives.
    #[inline]
    pub fn vortex_potential(&self, x: Vec3A, gauge: Vec3A) -> Vec3A {
        match self.kind {
            Frozen::Vortex {
                position,
                axis,
                g,
                a2,
            } => {
                let rho2 = axis.cross(x - position).length_squared();
                let rho02 = axis.cross(gauge - position).length_squared();
                axis * (-0.5 * g * ((rho2 + a2) / (rho02 + a2)).ln())
            }
            _ => Vec3A::ZERO,
        }
    }

    /// Where the primitive sits (a source's or vortex's position, a repulsor's centre, a
    /// uniform wind's decay origin).
    pub fn place(&self) -> Vec3A {
        match self.kind {
            Frozen::Uniform { .. } => self.origin,
            Frozen::Source { position, .. } | Frozen::Vortex { position, .. } => position,
            Frozen::Repulsor { center, .. } => center,
        }
    }

    /// Its mirror image in the solid plane `plane` (index) through `point` with outward unit
    /// `normal`, or none where the plane takes no image of it: the image's wind at x is
    /// M u(M x), M the reflection, so the two together have no component through the plane.
    ///
    /// A localised primitive (a uniform wind with decay, a source or sink, a vortex, a
    /// repulsor) gets one when it sits outside the solid (in front of the plane), and:
    /// a uniform wind with decay only when it blows into the plane (a plane never cancels a
    /// wind away from it); a vortex only when its axis is parallel to the plane (a vortex line
    /// through the plane ends on it, where its wind is already nearly along the plane).
    pub fn mirrored(&self, plane: u32, point: Vec3A, normal: Vec3A) -> Option<Self> {
        let reflect_point = |p: Vec3A| p - normal * (2.0 * (p - point).dot(normal));
        let reflect = |v: Vec3A| v - normal * (2.0 * v.dot(normal));
        if (self.place() - point).dot(normal) <= 0.0 {
            return None;
        }
        let kind = match self.kind {
            Frozen::Uniform { velocity } => {
                if self.inv_decay == 0.0 || velocity.dot(normal) >= 0.0 {
                    return None;
                }
                Frozen::Uniform {
                    velocity: reflect(velocity),
                }
            }
            Frozen::Source { position, k, a2 } => Frozen::Source {
                position: reflect_point(position),
                k,
                a2,
            },
            Frozen::Vortex {
                position,
                axis,
                g,
                a2,
            } => {
                if axis.dot(normal).abs() > 1e-3 {
                    return None;
                }
                // An axis is a pseudovector: its image turns the other way, −M â.
                Frozen::Vortex {
                    position: reflect_point(position),
                    axis: -reflect(axis),
                    g,
                    a2,
                }
            }
            Frozen::Repulsor {
                center,
                velocity,
                radius,
                strength,
            } => Frozen::Repulsor {
                center: reflect_point(center),
                velocity: reflect(velocity),
                radius,
                strength,
            },
        };
        Some(Self {
            kind,
            origin: reflect_point(self.origin),
            inv_decay: self.inv_decay,
            image_of: plane,
            parent: self.parent,
        })
    }
}

/// Flow around a sphere of `radius` moving at `v`, at offset `r` from its centre: the potential
/// flow of a moving sphere (a dipole; normal velocity v·n at the surface) plus a radial push of
/// speed `s` at the surface, falling as 1/r². Inside, the sphere carries and expels gas.
#[inline]
pub fn repulsor_velocity(r: Vec3A, v: Vec3A, radius: f32, s: f32) -> Vec3A {
    let d = r.length();
    let n = if d > 1e-6 { r / d } else { Vec3A::Y };
    if d < radius {
        return v + n * s;
    }
    let q = radius / d;
    (n * (3.0 * v.dot(n)) - v) * (0.5 * q * q * q) + n * (s * q * q)
}

fn v3a(a: [f32; 3]) -> Vec3A {
    Vec3A::from_array(a)
}

/// `primitive` frozen at time `t` (s); `path` is a repulsor's resolved path. Its index in the
/// frame's list is `index`.
pub fn freeze(primitive: &Primitive, path: Option<&Path>, t: f64, index: u32) -> FrozenPrimitive {
    let inv = |d: &Option<f32>| d.map_or(0.0, |l| 1.0 / l);
    let (kind, origin, inv_decay) = match primitive {
        Primitive::Uniform {
            velocity,
            position,
            decay,
            ..
        } => (
            Frozen::Uniform {
                velocity: v3a(*velocity),
            },
            v3a(*position),
            inv(decay),
        ),
        Primitive::Source {
            position,
            strength,
            radius,
            decay,
            ..
        } => (
            Frozen::Source {
                position: v3a(*position),
                k: strength / (4.0 * PI),
                a2: radius * radius,
            },
            v3a(*position),
            inv(decay),
        ),
        Primitive::Vortex {
            position,
            axis,
            strength,
            radius,
            decay,
            ..
        } => (
            Frozen::Vortex {
                position: v3a(*position),
                axis: v3a(*axis).normalize(),
                g: strength / (2.0 * PI),
                a2: radius * radius,
            },
            v3a(*position),
            inv(decay),
        ),
        Primitive::Repulsor {
            radius,
            strength,
            decay,
            ..
        } => {
            let (c, v) = path.expect("repulsors have paths").at(t);
            (
                Frozen::Repulsor {
                    center: c.as_vec3a(),
                    velocity: v.as_vec3a(),
                    radius: *radius,
                    strength: *strength,
                },
                c.as_vec3a(),
                inv(decay),
            )
        }
    };
    FrozenPrimitive {
        kind,
        origin,
        inv_decay,
        image_of: NOT_AN_IMAGE,
        parent: index,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Four at a time (a last, partial four; lanes without decay among them) the winds add up
    /// to the same bits as one by one.
    #[test]
    fn the_winds_four_at_a_time_are_the_winds_one_by_one() {
        let at = |x: f32, y: f32, z: f32| Vec3A::new(x, y, z);
        let kinds = [
            Frozen::Uniform {
                velocity: at(0.3, 1.2, -0.1),
            },
            Frozen::Source {
                position: at(0.5, 0.0, 0.2),
                k: 0.04,
                a2: 0.01,
            },
            Frozen::Vortex {
                position: at(-0.3, 0.4, 0.0),
                axis: at(0.0, 1.0, 0.0),
                g: 0.2,
                a2: 0.02,
            },
            Frozen::Repulsor {
                center: at(0.1, 0.6, -0.2),
                velocity: at(0.4, 0.0, 0.1),
                radius: 0.3,
                strength: 1.0,
            },
        ];
        let primitives: Vec<FrozenPrimitive> = (0..7)
            .map(|i| FrozenPrimitive {
                kind: kinds[i % 4],
                origin: at(0.1 * i as f32, 0.5, -0.05 * i as f32),
                inv_decay: [0.0, 1.7, 0.6][i % 3],
                image_of: NOT_AN_IMAGE,
                parent: i as u32,
            })
            .collect();
        for n in [1, 3, 4, 5, 7] {
            for i in 0..200 {
                let f = |k: f32| ((i as f32 + 0.5) * k).fract() * 3.0 - 1.5;
                let x = at(f(0.754_877_7), f(0.569_840_3), f(0.430_159_7));
                let u0 = at(0.01, -0.02, 0.03);
                let one_by_one = primitives[..n].iter().fold(u0, |u, p| u + p.velocity(x));
                let four = FrozenPrimitive::add_winds_four(&primitives[..n], u0, x);
                assert_eq!(four.to_array(), one_by_one.to_array(), "{n} at {x}");
                assert_eq!(
                    FrozenPrimitive::add_winds(&primitives[..n], u0, x).to_array(),
                    one_by_one.to_array()
                );
            }
        }
    }
}
