//! Pinhole camera rays and the opaque objects that stand in for the paper's conventional ray
//! tracer C_N (the rendering model of docs/FORMATS.md).

use crate::scene::blob_list::{Camera, Object};
use glam::Vec3;

/// Camera basis for primary rays through pixel centres (row 0 at the top).
#[derive(Debug, Clone, Copy)]
pub struct CameraRays {
    origin: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    /// tan(fov_y / 2).
    half_height: f32,
    width: u32,
    height: u32,
}

impl CameraRays {
    pub fn new(camera: &Camera, width: u32, height: u32) -> Self {
        let origin = Vec3::from_array(camera.position);
        let forward = (Vec3::from_array(camera.target) - origin).normalize();
        let right = forward.cross(Vec3::from_array(camera.up)).normalize();
        let up = right.cross(forward);
        Self {
            origin,
            forward,
            right,
            up,
            half_height: libm::tanf(camera.fov_y_deg.to_radians() * 0.5),
            width,
            height,
        }
    }

    pub fn origin(&self) -> Vec3 {
        self.origin
    }

    /// Unit direction through the centre of pixel (i, j).
    #[inline]
    pub fn direction(&self, i: u32, j: u32) -> Vec3 {
        let aspect = self.width as f32 / self.height as f32;
        let x = ((i as f32 + 0.5) / self.width as f32 * 2.0 - 1.0) * self.half_height * aspect;
        let y = (1.0 - (j as f32 + 0.5) / self.height as f32 * 2.0) * self.half_height;
        (self.forward + self.right * x + self.up * y).normalize()
    }
}

/// The nearest opaque hit: distance, unit normal facing the ray, colour.
#[derive(Debug, Clone, Copy)]
pub struct Hit {
    pub s: f32,
    pub normal: Vec3,
    pub color: Vec3,
}

const EPS: f32 = 1e-4;

/// Nearest hit of the ray with any object, beyond a small epsilon.
pub fn nearest_hit(objects: &[Object], origin: Vec3, dir: Vec3) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for o in objects {
        if let Some(h) = intersect(o, origin, dir) {
            if h.s > EPS && best.is_none_or(|b| h.s < b.s) {
                best = Some(h);
            }
        }
    }
    best.map(|mut h| {
        if h.normal.dot(dir) > 0.0 {
            h.normal = -h.normal;
        }
        h
    })
}

fn intersect(o: &Object, origin: Vec3, dir: Vec3) -> Option<Hit> {
    match o {
        Object::Sphere {
            center,
            radius,
            color,
            ..
        } => {
            let c = Vec3::from_array(*center);
            let oc = origin - c;
            let b = oc.dot(dir);
            let q = oc.length_squared() - radius * radius;
            let disc = b * b - q;
            if disc < 0.0 {
                return None;
            }
            let root = disc.sqrt();
            let s = if -b - root > EPS {
                -b - root
            } else {
                -b + root
            };
            (s > EPS).then(|| Hit {
                s,
                normal: (origin + dir * s - c) / *radius,
                color: Vec3::from_array(*color),
            })
        }
        Object::Plane {
            point,
            normal,
            color,
            ..
        } => {
            let n = Vec3::from_array(*normal).normalize();
            let denom = dir.dot(n);
            if denom.abs() < 1e-9 {
                return None;
            }
            let s = (Vec3::from_array(*point) - origin).dot(n) / denom;
            (s > EPS).then(|| Hit {
                s,
                normal: n,
                color: Vec3::from_array(*color),
            })
        }
        Object::Cylinder {
            base,
            axis,
            radius,
            height,
            color,
            ..
        } => cylinder(
            Vec3::from_array(*base),
            Vec3::from_array(*axis).normalize(),
            *radius,
            *height,
            origin,
            dir,
        )
        .map(|(s, normal)| Hit {
            s,
            normal,
            color: Vec3::from_array(*color),
        }),
    }
}

/// Whether the segment from `origin` along unit `dir` over (0, `s_max`) meets an opaque object
/// (`s_max` is the distance to a point light, or ∞): the object factor of S_k in Eq. 25, the
/// shadow of an object on the gas and on other objects. A ray counts as blocked where it enters
/// a sphere or a closed cylinder, or crosses a plane (planes are two-sided), beyond a small
/// epsilon; a ray that starts inside a sphere or cylinder is not blocked by it (only gas hidden
/// in a solid starts there, and a convex object's own lit surface never shadows itself, so
/// self-shadowing is n·l alone). An any-hit test: it stops at the first object met.
pub fn occluded(objects: &[Object], origin: Vec3, dir: Vec3, s_max: f32) -> bool {
    objects.iter().any(|o| enters(o, origin, dir, s_max))
}

/// Whether the segment (see [`occluded`]) enters `o`.
fn enters(o: &Object, origin: Vec3, dir: Vec3, s_max: f32) -> bool {
    let ahead = |s: f32| s > EPS && s < s_max;
    match o {
        Object::Sphere { center, radius, .. } => {
            let oc = origin - Vec3::from_array(*center);
            let q = oc.length_squared() - radius * radius;
            let b = oc.dot(dir);
            let disc = b * b - q;
            // Outside (q > 0), and the near root ahead.
            q > 0.0 && disc >= 0.0 && ahead(-b - disc.sqrt())
        }
        Object::Plane { point, normal, .. } => {
            let n = Vec3::from_array(*normal).normalize();
            let denom = dir.dot(n);
            denom.abs() >= 1e-9 && ahead((Vec3::from_array(*point) - origin).dot(n) / denom)
        }
        Object::Cylinder {
            base,
            axis,
            radius,
            height,
            ..
        } => {
            let a = Vec3::from_array(*axis).normalize();
            let oc = origin - Vec3::from_array(*base);
            // The ray's parameters inside the slab 0 ≤ along ≤ h, then inside the infinite
            // cylinder; it enters where the later of the two entries comes first.
            let (da, oa) = (dir.dot(a), oc.dot(a));
            let (mut t0, mut t1) = if da.abs() > 1e-9 {
                let (ta, tb) = (-oa / da, (height - oa) / da);
                (ta.min(tb), ta.max(tb))
            } else if (0.0..=*height).contains(&oa) {
                (f32::NEG_INFINITY, f32::INFINITY)
            } else {
                return false;
            };
            let dp = dir - a * da;
            let op = oc - a * oa;
            let qa = dp.length_squared();
            let qb = dp.dot(op);
            let qc = op.length_squared() - radius * radius;
            if qa > 1e-12 {
                let disc = qb * qb - qa * qc;
                if disc < 0.0 {
                    return false;
                }
                let root = disc.sqrt();
                t0 = t0.max((-qb - root) / qa);
                t1 = t1.min((-qb + root) / qa);
            } else if qc > 0.0 {
                return false;
            }
            t0 < t1 && ahead(t0)
        }
    }
}

/// A closed cylinder (side and both caps).
fn cylinder(base: Vec3, a: Vec3, r: f32, h: f32, origin: Vec3, dir: Vec3) -> Option<(f32, Vec3)> {
    let mut best: Option<(f32, Vec3)> = None;
    let mut take = |s: f32, n: Vec3| {
        if s > EPS && best.is_none_or(|(b, _)| s < b) {
            best = Some((s, n));
        }
    };
    let oc = origin - base;
    let dp = dir - a * dir.dot(a);
    let op = oc - a * oc.dot(a);
    let qa = dp.length_squared();
    if qa > 1e-12 {
        let qb = 2.0 * dp.dot(op);
        let qc = op.length_squared() - r * r;
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let root = disc.sqrt();
            for s in [(-qb - root) / (2.0 * qa), (-qb + root) / (2.0 * qa)] {
                let p = oc + dir * s;
                let along = p.dot(a);
                if (0.0..=h).contains(&along) {
                    take(s, (p - a * along) / r);
                }
            }
        }
    }
    let da = dir.dot(a);
    if da.abs() > 1e-9 {
        for (offset, n) in [(0.0, -a), (h, a)] {
            let s = (offset - oc.dot(a)) / da;
            let p = oc + dir * s;
            if (p - a * p.dot(a)).length_squared() <= r * r {
                take(s, n);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_pixel_looks_at_the_target_and_rows_go_down() {
        let cam = Camera {
            position: [0.0, 0.0, 5.0],
            target: [0.0, 0.0, 0.0],
            up: [0.0, 1.0, 0.0],
            fov_y_deg: 90.0,
        };
        let rays = CameraRays::new(&cam, 3, 3);
        assert!((rays.direction(1, 1) - Vec3::NEG_Z).length() < 1e-6);
        assert!(rays.direction(1, 0).y > 0.0 && rays.direction(1, 2).y < 0.0);
        assert!(rays.direction(0, 1).x < 0.0);
        // fov_y is the full angle: the top row's centre is (2/3)·45° off axis... within the frustum.
        let top = rays.direction(1, 0);
        let angle = top.y.atan2(-top.z).to_degrees();
        assert!((angle - (2.0f32 / 3.0).atan().to_degrees()).abs() < 1e-3);
    }

    #[test]
    fn objects_are_hit_where_expected() {
        let o = Vec3::new(0.0, 0.5, 5.0);
        let d = Vec3::NEG_Z;
        let sphere = Object::Sphere {
            center: [0.0, 0.5, 0.0],
            radius: 1.0,
            color: [1.0; 3],
            solid: false,
        };
        assert!((nearest_hit(&[sphere], o, d).unwrap().s - 4.0).abs() < 1e-5);
        let plane = Object::Plane {
            point: [0.0, 0.0, -2.0],
            normal: [0.0, 0.0, 1.0],
            color: [1.0; 3],
            solid: false,
        };
        assert!((nearest_hit(&[plane], o, d).unwrap().s - 7.0).abs() < 1e-5);
        let cyl = Object::Cylinder {
            base: [0.0, 0.0, 0.0],
            axis: [0.0, 1.0, 0.0],
            radius: 0.5,
            height: 1.0,
            color: [1.0; 3],
            model: None,
            solid: false,
        };
        let h = nearest_hit(std::slice::from_ref(&cyl), o, d).unwrap();
        assert!((h.s - 4.5).abs() < 1e-5 && (h.normal - Vec3::Z).length() < 1e-5);
        let top = nearest_hit(&[cyl], Vec3::new(0.1, 3.0, 0.0), Vec3::NEG_Y).unwrap();
        assert!((top.s - 2.0).abs() < 1e-5 && (top.normal - Vec3::Y).length() < 1e-5);
    }

    #[test]
    fn shadow_rays_are_blocked_where_they_enter_an_object_before_the_light() {
        let inf = f32::INFINITY;
        let sphere = [Object::Sphere {
            center: [0.0, 1.0, 0.0],
            radius: 0.5,
            color: [1.0; 3],
            solid: false,
        }];
        let below = Vec3::new(0.0, -1.0, 0.0);
        assert!(occluded(&sphere, below, Vec3::Y, inf));
        // A point light short of the sphere, a ray that passes beside it or leaves it.
        assert!(!occluded(&sphere, below, Vec3::Y, 1.4));
        assert!(occluded(&sphere, below, Vec3::Y, 1.6));
        assert!(!occluded(&sphere, Vec3::new(0.6, -1.0, 0.0), Vec3::Y, inf));
        assert!(!occluded(&sphere, below, Vec3::NEG_Y, inf));
        // From inside (gas hidden in the solid) or from its own lit surface: not blocked.
        assert!(!occluded(&sphere, Vec3::new(0.0, 1.2, 0.0), Vec3::Y, inf));
        let top = Vec3::new(0.0, 1.5001, 0.0);
        assert!(!occluded(&sphere, top, Vec3::Y, inf));
        // A two-sided plane blocks every crossing, from either side, short of the light.
        let plane = [Object::Plane {
            point: [0.0, 0.0, 0.0],
            normal: [0.0, 1.0, 0.0],
            color: [1.0; 3],
            solid: false,
        }];
        let up = Vec3::new(0.3, 0.8, 0.0).normalize();
        assert!(occluded(&plane, Vec3::new(0.0, -0.5, 0.0), up, inf));
        assert!(occluded(&plane, Vec3::new(0.0, 0.5, 0.0), -up, inf));
        assert!(!occluded(&plane, Vec3::new(0.0, 0.5, 0.0), up, inf));
        assert!(!occluded(&plane, Vec3::new(0.0, -0.5, 0.0), up, 0.5));
        assert!(!occluded(&plane, Vec3::new(0.0, 0.5, 0.0), Vec3::X, inf));
        // A closed cylinder: through its side, through a cap, along its axis, from inside.
        let cyl = [Object::Cylinder {
            base: [0.0, 0.0, 0.0],
            axis: [0.0, 1.0, 0.0],
            radius: 0.5,
            height: 1.0,
            color: [1.0; 3],
            model: None,
            solid: false,
        }];
        assert!(occluded(&cyl, Vec3::new(-2.0, 0.5, 0.0), Vec3::X, inf));
        assert!(!occluded(&cyl, Vec3::new(-2.0, 1.1, 0.0), Vec3::X, inf));
        assert!(!occluded(&cyl, Vec3::new(-2.0, 0.5, 0.0), Vec3::X, 1.4));
        assert!(occluded(&cyl, Vec3::new(0.2, 2.0, 0.0), Vec3::NEG_Y, inf));
        assert!(!occluded(&cyl, Vec3::new(0.6, 2.0, 0.0), Vec3::NEG_Y, inf));
        let slant = Vec3::new(1.0, 1.0, 0.0).normalize();
        assert!(occluded(&cyl, Vec3::new(-0.3, -0.6, 0.0), slant, inf));
        assert!(!occluded(&cyl, Vec3::new(-2.4, -0.6, 0.0), slant, inf));
        assert!(occluded(&cyl, Vec3::new(-1.4, -0.6, 0.0), slant, inf));
        assert!(!occluded(&cyl, Vec3::new(0.0, 0.5, 0.0), Vec3::X, inf));
        assert!(!occluded(&cyl, Vec3::new(0.0, 0.5, 0.0), Vec3::Y, inf));
    }
}
