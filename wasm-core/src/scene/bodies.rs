//! The solid objects of a scene's `render.objects` (docs/FORMATS.md, solid objects) as shapes:
//! each a closed region of space with a signed distance d(x) (m, negative inside) and an
//! outward normal n(x) = ∇d:
//!
//! - a sphere (centre c, radius a): d = |x − c| − a;
//! - a plane (point p, normal n̂): the half-space behind it, d = (x − p)·n̂;
//! - a cylinder (base b, axis â, radius R, height h): closed by its two caps; d is the distance
//!   to the nearest of side, caps and rims outside, minus the distance to the nearest face inside.
//!
//! Geometry only: how the wind goes round them is [`crate::wind`]'s.

use crate::scene::blob_list::Object;
use glam::Vec3A;

/// The shape of one solid, normalised (unit directions), in world metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Body {
    Sphere {
        center: Vec3A,
        radius: f32,
    },
    /// The half-space behind the plane through `point` with outward unit `normal`.
    Plane {
        point: Vec3A,
        normal: Vec3A,
    },
    /// A capped cylinder from `base` along the unit `axis` for `height`.
    Cylinder {
        base: Vec3A,
        axis: Vec3A,
        radius: f32,
        height: f32,
    },
}

/// A unit vector perpendicular to the unit `a`.
pub fn perpendicular(a: Vec3A) -> Vec3A {
    let other = if a.x.abs() < 0.9 { Vec3A::X } else { Vec3A::Y };
    a.cross(other).normalize()
}

impl Body {
    /// The body of a solid object, or none for an object that is not solid.
    pub fn of(object: &Object) -> Option<Body> {
        let v = Vec3A::from_array;
        match *object {
            Object::Sphere {
                center,
                radius,
                solid: true,
                ..
            } => Some(Body::Sphere {
                center: v(center),
                radius,
            }),
            Object::Plane {
                point,
                normal,
                solid: true,
                ..
            } => Some(Body::Plane {
                point: v(point),
                normal: v(normal).normalize(),
            }),
            Object::Cylinder {
                base,
                axis,
                radius,
                height,
                solid: true,
                ..
            } => Some(Body::Cylinder {
                base: v(base),
                axis: v(axis).normalize(),
                radius,
                height,
            }),
            _ => None,
        }
    }

    /// The signed distance d (m, negative inside) from `x` and the outward normal ∇d there.
    #[inline]
    pub fn distance(&self, x: Vec3A) -> (f32, Vec3A) {
        match *self {
            Body::Sphere { center, radius } => {
                let r = x - center;
                let len = r.length();
                let n = if len > 1e-12 { r / len } else { Vec3A::Y };
                (len - radius, n)
            }
            Body::Plane { point, normal } => ((x - point).dot(normal), normal),
            Body::Cylinder {
                base,
                axis,
                radius,
                height,
            } => {
                let r = x - base;
                let s = r.dot(axis);
                let radial = r - axis * s;
                let rho = radial.length();
                let out = if rho > 1e-12 {
                    radial / rho
                } else {
                    perpendicular(axis)
                };
                let dr = rho - radius;
                // Beyond the top cap (positive) or the bottom one, along the axis.
                let (ds, cap) = if s > 0.5 * height {
                    (s - height, axis)
                } else {
                    (-s, -axis)
                };
                match (dr > 0.0, ds > 0.0) {
                    (true, true) => {
                        let d = (dr * dr + ds * ds).sqrt();
                        (d, (out * dr + cap * ds) / d)
                    }
                    (true, false) => (dr, out),
                    (false, true) => (ds, cap),
                    (false, false) if dr > ds => (dr, out),
                    (false, false) => (ds, cap),
                }
            }
        }
    }

    /// The signed distance and normal of the solid with its edges rounded by `edge` (m): a
    /// cylinder's two rims become quarter-round tori of that radius (the solid shrinks by the
    /// sliver outside them); other bodies have no edges. The wind goes round this shape, whose
    /// normal is continuous outside and, within `edge` of the surface, inside
    /// (docs/CONVENTIONS.md, solid objects).
    #[inline]
    pub fn rounded_distance(&self, x: Vec3A, edge: f32) -> (f32, Vec3A) {
        let Body::Cylinder {
            base,
            axis,
            radius,
            height,
        } = *self
        else {
            return self.distance(x);
        };
        if edge <= 0.0 {
            return self.distance(x);
        }
        let r = x - base;
        let s = r.dot(axis);
        let radial = r - axis * s;
        let rho = radial.length();
        let out = if rho > 1e-12 {
            radial / rho
        } else {
            perpendicular(axis)
        };
        let half = 0.5 * height;
        let cap = if s > half { axis } else { -axis };
        let edge = edge.min(radius).min(half);
        // The distance to the shrunken cylinder, less the rounding.
        let qx = rho - (radius - edge);
        let qy = (s - half).abs() - (half - edge);
        if qx > 0.0 && qy > 0.0 {
            let q = (qx * qx + qy * qy).sqrt();
            (q - edge, (out * qx + cap * qy) / q)
        } else if qx > qy {
            (qx - edge, out)
        } else {
            (qy - edge, cap)
        }
    }

    /// Whether `x` lies surely farther than `d` (m, d ≥ 0) from the sphere (by a margin over
    /// the rounding of its distance, and without its root); false for other bodies.
    #[inline]
    pub fn surely_beyond(&self, x: Vec3A, d: f32) -> bool {
        match *self {
            Body::Sphere { center, radius } => {
                let r = radius + d;
                (x - center).length_squared() > r * r * (1.0 + 1e-5)
            }
            _ => false,
        }
    }

    /// A point the solid is gathered about (the sphere's centre, the middle of the cylinder's
    /// axis; a plane's `point`).
    pub fn centre(&self) -> Vec3A {
        match *self {
            Body::Sphere { center, .. } => center,
            Body::Plane { point, .. } => point,
            Body::Cylinder {
                base, axis, height, ..
            } => base + axis * (0.5 * height),
        }
    }

    /// Its smallest extent (m): the scale its surface bends over (infinite for a plane).
    pub fn size(&self) -> f32 {
        match *self {
            Body::Sphere { radius, .. } => radius,
            Body::Plane { .. } => f32::INFINITY,
            Body::Cylinder { radius, height, .. } => radius.min(0.5 * height),
        }
    }

    /// The axis-aligned box around the solid grown by `reach` (m); none for a plane.
    pub(crate) fn bounds(&self, reach: f32) -> Option<(Vec3A, Vec3A)> {
        match *self {
            Body::Sphere { center, radius } => {
                let r = Vec3A::splat(radius + reach);
                Some((center - r, center + r))
            }
            Body::Plane { .. } => None,
            Body::Cylinder {
                base,
                axis,
                radius,
                height,
            } => {
                let top = base + axis * height;
                // The disc of radius R about a unit axis a reaches R·√(1 − a_i²) along axis i.
                let e = (Vec3A::ONE - axis * axis).max(Vec3A::ZERO);
                let disc = Vec3A::new(e.x.sqrt(), e.y.sqrt(), e.z.sqrt()) * radius;
                let grow = disc + Vec3A::splat(reach);
                Some((base.min(top) - grow, base.max(top) + grow))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances_and_normals_of_each_body() {
        let sphere = Body::Sphere {
            center: Vec3A::new(1.0, 0.0, 0.0),
            radius: 0.5,
        };
        let (d, n) = sphere.distance(Vec3A::new(1.0, 2.0, 0.0));
        assert!((d - 1.5).abs() < 1e-6 && (n - Vec3A::Y).length() < 1e-6);
        let plane = Body::Plane {
            point: Vec3A::new(0.0, 1.0, 0.0),
            normal: Vec3A::NEG_Y,
        };
        assert_eq!(plane.distance(Vec3A::new(3.0, 0.25, 1.0)).0, 0.75);
        assert_eq!(plane.distance(Vec3A::new(3.0, 2.0, 1.0)).0, -1.0);
        let cyl = Body::Cylinder {
            base: Vec3A::ZERO,
            axis: Vec3A::Y,
            radius: 1.0,
            height: 2.0,
        };
        let at = |x, y, z| cyl.distance(Vec3A::new(x, y, z));
        // Side, top cap, rim, inside (nearest face: the side, then the bottom cap).
        assert_eq!(at(3.0, 1.0, 0.0), (2.0, Vec3A::X));
        assert_eq!(at(0.2, 2.5, 0.0), (0.5, Vec3A::Y));
        let (d, n) = at(4.0, 6.0, 0.0);
        assert!((d - 5.0).abs() < 1e-6 && (n - Vec3A::new(0.6, 0.8, 0.0)).length() < 1e-6);
        let (d, n) = at(0.0, 1.0, 0.9);
        assert!((d + 0.1).abs() < 1e-6 && n == Vec3A::Z, "{d} {n}");
        assert_eq!(at(0.0, 0.05, 0.0).0, -0.05);
        assert_eq!(at(0.0, 0.05, 0.0).1, Vec3A::NEG_Y);
    }
}
