//! The wind along solid objects (docs/CONVENTIONS.md, solid objects): within the layer of
//! width d₀ (`field.boundary_width`) over a solid the wind has no component through the
//! surface, and stays divergence-free wherever a divergence-free construction exists.
//!
//! - The ramp (Bridson, Hourihan and Nordenstam, "Curl-Noise for Procedural Fluid Flow",
//!   SIGGRAPH 2007): a wind u = ∇ × ψ becomes u = ∇ × (α ψ + (1 − α) n (n·ψ)), α = r(d/d₀),
//!   r(s) = (15s − 10s³ + 3s⁵)/8 on [−1, 1] (odd, ±1 beyond), d and n the signed distance to
//!   and outward normal of the nearest solid. At d = 0 only the normal part of ψ is left, whose
//!   curl is tangential: no flux through the surface; a curl has no divergence. The curl is
//!   taken by central differences of the potential with step h ([`Stencil`]), whose
//!   divergence by the same differences is zero exactly (the differences commute).
//! - Closed forms where they exist ([`Doublet`]): a uniform wind past a sphere is the
//!   potential flow around it, past a cylinder the two-dimensional potential flow of its
//!   cross-flow; a localised primitive in front of a plane gets its mirror image
//!   ([`crate::wind::frozen::FrozenPrimitive::mirrored`]).
//! - What has neither (a source, a repulsor, anything with decay, a uniform wind into a plane,
//!   or along a cylinder's axis at its caps) is projected: u − (1 − α)(u·n) n; a plane keeps
//!   what blows away from it: u − (1 − α) min(u·n, 0) n. (A uniform wind into an infinite
//!   plane has no bounded divergence-free deflection: its flux through every square metre
//!   would have to leave along the plane, ever faster with the distance. It stops in the
//!   layer, and the gas it carries gathers there.)

use crate::scene::bodies::Body;
use glam::Vec3A;

/// The ramp r(s) = (15s − 10s³ + 3s⁵)/8 for s in [−1, 1] and ±1 beyond: 0 at the surface,
/// slope 15/8 there, 1 with vanishing first and second derivatives at s = 1. Odd, so the
/// potential it builds is smooth through the surface.
#[inline]
pub fn ramp(s: f32) -> f32 {
    let s = s.clamp(-1.0, 1.0);
    let s2 = s * s;
    s * (15.0 + s2 * (-10.0 + 3.0 * s2)) * 0.125
}

/// A taper w(s) = 1 − (10s³ − 15s⁴ + 6s⁵) on [0, 1] (1 before, 0 after) and dw/ds: smooth to
/// the second derivative at both ends.
#[inline]
fn taper(s: f32) -> (f32, f32) {
    if s <= 0.0 {
        return (1.0, 0.0);
    }
    if s >= 1.0 {
        return (0.0, 0.0);
    }
    let s2 = s * s;
    let w = 1.0 - s2 * s * (10.0 + s * (-15.0 + 6.0 * s));
    let dw = -30.0 * s2 * (1.0 - s) * (1.0 - s);
    (w, dw)
}

/// Where a sphere's doublet is exact (within this many radii of its centre) and where it has
/// faded to nothing (a smooth taper of its vector potential between, so the wind stays
/// divergence-free): at 4 radii the doublet is (1/4)³/2 = 0.8 % of the wind.
pub const SPHERE_ZONE: [f32; 2] = [SPHERE_ZONE_INNER, SPHERE_ZONE_OUTER];
/// [`SPHERE_ZONE`]'s two radii, in the sphere's radii.
pub const SPHERE_ZONE_INNER: f32 = 4.0;
pub const SPHERE_ZONE_OUTER: f32 = 8.0;
/// The same for a cylinder's two-dimensional doublet (it falls as R²/ρ²: 2.8 % at 6 radii).
/// Beyond the caps it fades over one radius.
pub const CYLINDER_ZONE: [f32; 2] = [CYLINDER_ZONE_INNER, CYLINDER_ZONE_OUTER];
/// [`CYLINDER_ZONE`]'s two distances from the axis, in the cylinder's radii.
pub const CYLINDER_ZONE_INNER: f32 = 6.0;
pub const CYLINDER_ZONE_OUTER: f32 = 12.0;

/// The potential flow a uniform wind U makes past one solid, less U: a closed form exact on
/// the solid's surface, faded out far from it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Doublet {
    /// A sphere (centre c, radius a): ψ = −(a³/2) U × r / r³ outside, −½ U × r inside (where
    /// U plus the doublet's wind is zero), so u = U − (a³/2)(3(U·r̂)r̂ − U)/r³: 1.5 U at the
    /// equator, 0 at the stagnation points.
    Sphere {
        centre: Vec3A,
        radius: f32,
        wind: Vec3A,
        /// a³/2 (m³) and 1/((ρ₂ − ρ₁) a), the taper's ρ₁ and ρ₂ in radii ([`SPHERE_ZONE`]).
        half_cube: f32,
        inv_span: f32,
    },
    /// A cylinder (base b, unit axis â, radius R, height h) in the cross-flow U⊥ = U −
    /// (U·â)â: the stream function Ψ = −R² (m·ρ)/ρ² outside (m = â × U), a smooth polynomial
    /// continuation within ρ < R, ψ = Ψ â times the tapers, so u = U⊥ − R²(2(U⊥·ρ̂)ρ̂ −
    /// U⊥)/ρ² along the side (2 U⊥ at its flanks), along the caps too (it has no axial part),
    /// faded over one radius beyond them (where the cross-flow over a cap's middle is
    /// stopped, a wake).
    Cylinder {
        base: Vec3A,
        axis: Vec3A,
        radius: f32,
        height: f32,
        m: Vec3A,
    },
}

impl Doublet {
    /// The doublet of `body` in the uniform wind `wind` (m/s), if it has one (a plane has
    /// none; a cylinder in a wind along its axis neither).
    pub fn of(body: &Body, wind: Vec3A) -> Option<Self> {
        match *body {
            Body::Sphere { center, radius } if wind != Vec3A::ZERO => Some(Doublet::Sphere {
                centre: center,
                radius,
                wind,
                half_cube: 0.5 * radius * radius * radius,
                inv_span: 1.0 / ((SPHERE_ZONE[1] - SPHERE_ZONE[0]) * radius),
            }),
            Body::Cylinder {
                base,
                axis,
                radius,
                height,
            } => {
                let m = axis.cross(wind);
                (m.length_squared() > 0.0).then_some(Doublet::Cylinder {
                    base,
                    axis,
                    radius,
                    height,
                    m,
                })
            }
            _ => None,
        }
    }

    /// How far from `body`'s surface (m) its doublet reaches: to [`SPHERE_ZONE`]'s outer
    /// radius from a sphere's centre, to [`CYLINDER_ZONE`]'s from a cylinder's axis and one
    /// radius beyond its caps (0 for a plane, which has none).
    pub fn reach(body: &Body) -> f32 {
        match *body {
            Body::Sphere { radius, .. } => (SPHERE_ZONE[1] - 1.0) * radius,
            Body::Cylinder { radius, .. } => (CYLINDER_ZONE[1] - 1.0).hypot(1.0) * radius,
            Body::Plane { .. } => 0.0,
        }
    }

    /// The vector potential ψ (m²/s) with the tapers, and its curl, the doublet's wind
    /// (m/s), at `x`.
    #[inline]
    pub fn at(&self, x: Vec3A) -> (Vec3A, Vec3A) {
        self.evaluate::<true>(x)
    }

    /// The vector potential ψ (m²/s) alone at `x`, as [`Self::at`] gives it.
    #[inline]
    pub fn potential(&self, x: Vec3A) -> Vec3A {
        self.evaluate::<false>(x).0
    }

    /// ψ and, when `CURL`, its curl (zero otherwise) at `x`: [`Self::at`].
    #[inline(always)]
    fn evaluate<const CURL: bool>(&self, x: Vec3A) -> (Vec3A, Vec3A) {
        match *self {
            Doublet::Sphere {
                centre,
                radius,
                wind,
                half_cube,
                inv_span,
            } => sphere_doublet(centre, radius, wind, half_cube, inv_span, x),
            Doublet::Cylinder {
                base,
                axis,
                radius,
                height,
                m,
            } => {
                let r = x - base;
                // Beyond the ball around the zone (its middle, to the rims of its ends): nothing.
                let half = 0.5 * height;
                let (along, across) = (half + radius, CYLINDER_ZONE[1] * radius);
                let bound = (along * along + across * across) * (1.0 + 1e-4);
                if (r - axis * half).length_squared() > bound {
                    return (Vec3A::ZERO, Vec3A::ZERO);
                }
                let s = r.dot(axis);
                let beyond = if s > height { s - height } else { -s };
                let (w_axial, _) = taper(beyond / radius);
                if w_axial == 0.0 {
                    return (Vec3A::ZERO, Vec3A::ZERO);
                }
                let rv = r - axis * s;
                let rho = rv.length();
                let span = (CYLINDER_ZONE[1] - CYLINDER_ZONE[0]) * radius;
                let (w_radial, dw) = taper((rho - CYLINDER_ZONE[0] * radius) / span);
                if w_radial == 0.0 {
                    return (Vec3A::ZERO, Vec3A::ZERO);
                }
                let r2 = radius * radius;
                let md = m.dot(rv);
                let (stream, grad) = if rho >= radius {
                    let inv2 = 1.0 / (rho * rho);
                    (-r2 * md * inv2, (m - rv * (2.0 * md * inv2)) * (-r2 * inv2))
                } else {
                    // Inside (and beyond the caps, within the radius): Ψ = −(m·ρ) P(ρ²/R²),
                    // P = 1 + 3s − 5s² + 2s³, equal to the outside's value and first two
                    // radial derivatives at ρ = R, so the wind beyond the caps has no sheet.
                    let s = rho * rho / r2;
                    let p = 1.0 + s * (3.0 + s * (-5.0 + 2.0 * s));
                    let dp = 3.0 + s * (-10.0 + 6.0 * s);
                    (-md * p, -(m * p + rv * (md * dp * 2.0 / r2)))
                };
                // ψ = w_a w_r Ψ â; ∇ × ψ = w_a (w_r ∇Ψ + Ψ w_r' ρ̂) × â (∇w_a is along â).
                let psi = axis * (stream * w_radial * w_axial);
                if !CURL {
                    return (psi, Vec3A::ZERO);
                }
                let mut g = grad * w_radial;
                if dw != 0.0 {
                    g += rv * (stream * dw / (span * rho));
                }
                (psi, g.cross(axis) * w_axial)
            }
        }
    }
}

/// [`Doublet::Sphere`] at `x`: its zones by a clamp and its two sides by selects, with no
/// branch, so that the doublets of many spheres summed at a point overlap in the processor;
/// one root and one division. Where the taper is 1 the extra terms are zeros; where it is 0,
/// every term is.
#[inline(always)]
fn sphere_doublet(
    centre: Vec3A,
    radius: f32,
    wind: Vec3A,
    half_cube: f32,
    inv_span: f32,
    x: Vec3A,
) -> (Vec3A, Vec3A) {
    let r = x - centre;
    let rho = r.length();
    let inv = 1.0 / rho.max(radius);
    // taper(s) on [0, 1], which is 1 and 0 at the ends.
    let s = ((rho - SPHERE_ZONE[0] * radius) * inv_span).clamp(0.0, 1.0);
    let s2 = s * s;
    let w = 1.0 - s2 * s * (10.0 + s * (-15.0 + 6.0 * s));
    let dw = -30.0 * s2 * (1.0 - s) * (1.0 - s);
    // Outside (ρ ≥ a): ψ = −(a³/2ρ³) U × r, u = −(a³/2ρ³)(3(U·r̂)r̂ − U); inside: ψ = −½ U × r
    // and u = −U.
    let outside = rho >= radius;
    let q3 = if outside {
        half_cube * inv * inv * inv
    } else {
        0.5
    };
    let psi = wind.cross(r) * (-q3);
    let u = Vec3A::select(
        Vec3A::splat(rho).cmpge(Vec3A::splat(radius)),
        (r * (3.0 * wind.dot(r) * inv * inv) - wind) * (-q3),
        -wind,
    );
    // ∇ × (w ψ) = w ∇ × ψ + ∇w × ψ, ∇w = w'(ρ) r̂ (w' per metre; zero where ρ < ρ₁ a).
    let grad = r * (dw * inv_span * inv);
    (psi * w, u * w + grad.cross(psi))
}

/// The projection of a wind without a vector potential in the layer: u − (1 − α)(u·n) n, or
/// for a surface that keeps what blows away from it (`keep_outflow`), u − (1 − α) min(u·n, 0) n.
#[inline]
pub fn project(u: Vec3A, normal: Vec3A, alpha: f32, keep_outflow: bool) -> Vec3A {
    let un = u.dot(normal);
    let un = if keep_outflow { un.min(0.0) } else { un };
    u - normal * ((1.0 - alpha) * un)
}

/// The six points of a central-difference curl about x (±h along x, y, z) with the ramp and
/// the normal of one solid at each.
#[derive(Debug, Clone, Copy)]
pub struct Stencil {
    pub points: [Vec3A; 6],
    alpha: [f32; 6],
    normal: [Vec3A; 6],
    /// 1/(x₊ − x₋) along each axis, from the points as rounded.
    inv_span: Vec3A,
}

impl Stencil {
    /// The stencil of step `h` (m) about `x` for `body` with its edges rounded by `edge`,
    /// whose layer is `1/inv_width` thick.
    #[inline]
    pub fn new(body: &Body, edge: f32, x: Vec3A, h: f32, inv_width: f32) -> Self {
        let axes = [Vec3A::X, Vec3A::Y, Vec3A::Z];
        let mut points = [x; 6];
        let mut alpha = [0.0; 6];
        let mut normal = [Vec3A::ZERO; 6];
        for (k, p) in points.iter_mut().enumerate() {
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            *p = x + axes[k / 2] * (sign * h);
            let (d, n) = body.rounded_distance(*p, edge);
            alpha[k] = ramp(d * inv_width);
            normal[k] = n;
        }
        let span = Vec3A::new(
            points[0].x - points[1].x,
            points[2].y - points[3].y,
            points[4].z - points[5].z,
        );
        Self {
            points,
            alpha,
            normal,
            inv_span: span.recip(),
        }
    }

    /// ∇ × (α ψ + (1 − α) n (n·ψ)) by central differences, from ψ at the six points.
    #[inline]
    pub fn ramped_curl(&self, psi: &[Vec3A; 6]) -> Vec3A {
        let a: [Vec3A; 6] = std::array::from_fn(|k| {
            let (al, n) = (self.alpha[k], self.normal[k]);
            psi[k] * al + n * ((1.0 - al) * n.dot(psi[k]))
        });
        // a[2i] at +h along axis i, a[2i + 1] at −h.
        let d = |axis: usize| (a[2 * axis] - a[2 * axis + 1]) * self.inv_span[axis];
        let (dx, dy, dz) = (d(0), d(1), d(2));
        Vec3A::new(dy.z - dz.y, dz.x - dx.z, dx.y - dy.x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ramp_and_the_taper_meet_their_ends_smoothly() {
        assert_eq!(ramp(0.0), 0.0);
        assert!((ramp(1.0) - 1.0).abs() < 1e-7 && ramp(2.0) == 1.0 && ramp(-3.0) == -1.0);
        let slope = |f: &dyn Fn(f32) -> f32, s: f32| (f(s + 1e-3) - f(s - 1e-3)) / 2e-3;
        assert!((slope(&ramp, 0.0) - 15.0 / 8.0).abs() < 1e-3);
        assert!(slope(&ramp, 0.999).abs() < 1e-3);
        let w = |s| taper(s).0;
        assert!(slope(&w, 0.001).abs() < 1e-3 && slope(&w, 0.999).abs() < 1e-3);
        assert!((slope(&w, 0.4) - taper(0.4).1).abs() < 1e-3);
    }

    /// The doublets' winds are the curls of their potentials (by differences), inside, outside
    /// and in the tapers.
    #[test]
    fn each_doublet_is_the_curl_of_its_potential() {
        let wind = Vec3A::new(0.7, 0.2, -0.4);
        let doublets = [
            Doublet::of(
                &Body::Sphere {
                    center: Vec3A::new(0.1, 0.2, 0.3),
                    radius: 0.5,
                },
                wind,
            )
            .unwrap(),
            Doublet::of(
                &Body::Cylinder {
                    base: Vec3A::ZERO,
                    axis: Vec3A::new(0.0, 1.0, 0.2).normalize(),
                    radius: 0.3,
                    height: 1.0,
                },
                wind,
            )
            .unwrap(),
        ];
        let h = 1e-3;
        for d in doublets {
            for i in 0..400 {
                let f = |k: f32| ((i as f32 + 0.5) * k).fract() * 8.0 - 4.0;
                let x = Vec3A::new(f(0.7548777), f(0.5698403), f(0.4301597));
                let psi = |p: Vec3A| d.at(p).0;
                let g = |axis: Vec3A| (psi(x + axis * h) - psi(x - axis * h)) / (2.0 * h);
                let (gx, gy, gz) = (g(Vec3A::X), g(Vec3A::Y), g(Vec3A::Z));
                let curl = Vec3A::new(gy.z - gz.y, gz.x - gx.z, gx.y - gy.x);
                let u = d.at(x).1;
                // Skip the surfaces where ψ has a kink (the doublet's own boundary).
                let (dist, _) = match d {
                    Doublet::Sphere { centre, radius, .. } => Body::Sphere {
                        center: centre,
                        radius,
                    }
                    .distance(x),
                    Doublet::Cylinder {
                        base,
                        axis,
                        radius,
                        height,
                        ..
                    } => Body::Cylinder {
                        base,
                        axis,
                        radius,
                        height,
                    }
                    .distance(x),
                };
                if dist.abs() < 0.01 {
                    continue;
                }
                assert!(
                    (curl - u).length() < 2e-3 * (1.0 + u.length()),
                    "{x}: {curl} vs {u}"
                );
            }
        }
    }
}
