//! Solid objects (docs/FORMATS.md, solid objects): the scene's objects marked `solid`, as the
//! wind and the gas meet them. Each is a closed region of space with a signed distance d(x) (m,
//! negative inside) and an outward normal n(x) = ∇d:
//!
//! - a sphere (centre c, radius a): d = |x − c| − a;
//! - a plane (point p, normal n̂): the half-space behind it, d = (x − p)·n̂;
//! - a cylinder (base b, axis â, radius R, height h): closed by its two caps; d is the distance
//!   to the nearest of side, caps and rims outside, minus the distance to the nearest face inside.
//!
//! [`Solids`] finds the solid nearest to a point within a reach (a uniform grid over the finite
//! solids, so a point costs a cell lookup and the few solids whose reach covers the cell; planes,
//! which reach everywhere, are always tested) and puts points that ended inside a solid back on
//! its surface, just outside.

use crate::gas::blob_list::Object;
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
    fn bounds(&self, reach: f32) -> Option<(Vec3A, Vec3A)> {
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

/// The nearest solid to a point: its index, the signed distance d (m) and the normal there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Nearest {
    pub index: usize,
    pub distance: f32,
    pub normal: Vec3A,
}

/// Most cells of the grid over the finite solids.
const MAX_CELLS: usize = 1 << 18;

/// The scene's solids, with a uniform grid over the finite ones.
#[derive(Debug, Clone, Default)]
pub struct Solids {
    pub bodies: Vec<Body>,
    /// The rounding of each solid's edges the wind sees ([`Body::rounded_distance`]).
    pub edges: Vec<f32>,
    /// Indices of the planes, tested at every point.
    planes: Vec<usize>,
    /// The grid: its lower corner, cells per metre and cell counts; `cells[c]` is the range of
    /// `members` listing the finite solids whose reach covers cell c.
    lo: Vec3A,
    inv_cell: Vec3A,
    dims: [usize; 3],
    cells: Vec<(u32, u32)>,
    members: Vec<u32>,
}

impl Solids {
    /// The solid objects of `objects`, each reaching `reach[i]` metres around it (the layer
    /// over it, and whatever else of the wind it shapes): beyond that it is never reported.
    pub fn new(bodies: Vec<Body>, reach: &[f32]) -> Self {
        let edges = vec![0.0; bodies.len()];
        Self::with_edges(bodies, edges, reach)
    }

    /// [`Self::new`] with the wind seeing each solid's edges rounded by `edges[i]` (m).
    pub fn with_edges(bodies: Vec<Body>, edges: Vec<f32>, reach: &[f32]) -> Self {
        let planes = (0..bodies.len())
            .filter(|&i| matches!(bodies[i], Body::Plane { .. }))
            .collect();
        let boxes: Vec<(usize, (Vec3A, Vec3A))> = bodies
            .iter()
            .enumerate()
            .filter_map(|(i, b)| b.bounds(reach[i]).map(|bx| (i, bx)))
            .collect();
        let mut solids = Self {
            bodies,
            edges,
            planes,
            ..Self::default()
        };
        if boxes.is_empty() {
            return solids;
        }
        let (mut lo, mut hi) = (Vec3A::splat(f32::INFINITY), Vec3A::splat(f32::NEG_INFINITY));
        let mut volume = 0.0f64;
        for (_, (a, b)) in &boxes {
            lo = lo.min(*a);
            hi = hi.max(*b);
            let e = (*b - *a).max(Vec3A::splat(1e-6));
            volume += (e.x as f64) * (e.y as f64) * (e.z as f64);
        }
        // Cells about the size of the mean box, four per box, within MAX_CELLS.
        let extent = (hi - lo).max(Vec3A::splat(1e-6));
        let total = (extent.x as f64) * (extent.y as f64) * (extent.z as f64);
        let wanted =
            (4.0 * boxes.len() as f64 * total / volume.max(1e-30)).clamp(1.0, MAX_CELLS as f64);
        let cell = (total / wanted).cbrt() as f32;
        let dims =
            [extent.x, extent.y, extent.z].map(|e| ((e / cell).ceil() as usize).clamp(1, 64));
        let inv_cell = Vec3A::new(
            dims[0] as f32 / extent.x,
            dims[1] as f32 / extent.y,
            dims[2] as f32 / extent.z,
        );
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); dims[0] * dims[1] * dims[2]];
        let clamp_cell = |p: Vec3A| {
            let q = (p - lo) * inv_cell;
            [q.x, q.y, q.z]
                .iter()
                .zip(dims)
                .map(|(&v, n)| (v.floor().max(0.0) as usize).min(n - 1))
                .collect::<Vec<_>>()
        };
        for (i, (a, b)) in &boxes {
            let (c0, c1) = (clamp_cell(*a), clamp_cell(*b));
            for z in c0[2]..=c1[2] {
                for y in c0[1]..=c1[1] {
                    for x in c0[0]..=c1[0] {
                        lists[(z * dims[1] + y) * dims[0] + x].push(*i as u32);
                    }
                }
            }
        }
        for list in lists {
            let start = solids.members.len() as u32;
            solids.members.extend(list);
            solids.cells.push((start, solids.members.len() as u32));
        }
        solids.lo = lo;
        solids.inv_cell = inv_cell;
        solids.dims = dims;
        solids
    }

    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    pub fn len(&self) -> usize {
        self.bodies.len()
    }

    /// The finite solids whose reach may cover `x` (the grid cell's list), then the planes.
    #[inline]
    pub fn candidates(&self, x: Vec3A) -> impl Iterator<Item = usize> + '_ {
        let q = (x - self.lo) * self.inv_cell;
        let inside = !self.cells.is_empty()
            && q.cmpge(Vec3A::ZERO).all()
            && q.x < self.dims[0] as f32
            && q.y < self.dims[1] as f32
            && q.z < self.dims[2] as f32;
        let cell: &[u32] = if inside {
            let (cx, cy, cz) = (q.x as usize, q.y as usize, q.z as usize);
            let (a, b) = self.cells[(cz * self.dims[1] + cy) * self.dims[0] + cx];
            &self.members[a as usize..b as usize]
        } else {
            &[]
        };
        cell.iter()
            .map(|&i| i as usize)
            .chain(self.planes.iter().copied())
    }

    /// The solid with the smallest signed distance from `x` (edges rounded as the wind sees
    /// them) among those closer than `reach` (m), or none.
    #[inline]
    pub fn nearest(&self, x: Vec3A, reach: f32) -> Option<Nearest> {
        let mut best: Option<Nearest> = None;
        for i in self.candidates(x) {
            let (d, n) = self.bodies[i].rounded_distance(x, self.edges[i]);
            if d < reach && best.is_none_or(|b| d < b.distance) {
                best = Some(Nearest {
                    index: i,
                    distance: d,
                    normal: n,
                });
            }
        }
        best
    }

    /// Whether `x` lies inside a solid (d < 0).
    pub fn inside(&self, x: Vec3A) -> Option<usize> {
        self.candidates(x)
            .find(|&i| self.bodies[i].distance(x).0 < 0.0)
    }

    /// `x` put back on the surface, `gap` metres outside, if it lies inside a solid; else `x`.
    /// A point pushed out of one solid into another is pushed again (at most four times, for
    /// solids that overlap). Where overlapping solids send it back and forth (a mug's base
    /// sunk in the floor), it leaves them all by the shortest of seven ways: along the last
    /// normal or an axis, in steps growing by a quarter from `gap`.
    #[inline]
    pub fn push_out(&self, mut x: Vec3A, gap: f32) -> Vec3A {
        let start = x;
        let mut normal = Vec3A::Y;
        for _ in 0..4 {
            let Some(i) = self.inside(x) else {
                return x;
            };
            let (d, n) = self.bodies[i].distance(x);
            // The gap grows with the coordinates' size so the step survives rounding.
            let g = gap + 4.0 * f32::EPSILON * x.abs().max_element();
            x += n * (g - d);
            normal = n;
        }
        if self.inside(x).is_none() {
            return x;
        }
        let ways = [
            normal,
            Vec3A::X,
            Vec3A::NEG_X,
            Vec3A::Y,
            Vec3A::NEG_Y,
            Vec3A::Z,
            Vec3A::NEG_Z,
        ];
        let mut t = gap.max(1e-4);
        while t < 1e3 {
            if let Some(y) = ways
                .iter()
                .map(|&w| start + w * t)
                .find(|&y| self.inside(y).is_none())
            {
                return y;
            }
            t *= 1.25;
        }
        x
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

    #[test]
    fn the_grid_finds_what_a_search_of_every_solid_finds() {
        let mut bodies = Vec::new();
        for i in 0..60 {
            let f = |k: f32| ((i as f32 + 0.5) * k).fract() * 6.0 - 3.0;
            let c = Vec3A::new(f(0.7548777), f(0.5698403), f(0.4301597));
            bodies.push(if i % 2 == 0 {
                Body::Sphere {
                    center: c,
                    radius: 0.05 + 0.002 * i as f32,
                }
            } else {
                Body::Cylinder {
                    base: c,
                    axis: Vec3A::new(0.3, 1.0, -0.2).normalize(),
                    radius: 0.08,
                    height: 0.3,
                }
            });
        }
        bodies.push(Body::Plane {
            point: Vec3A::new(0.0, -3.5, 0.0),
            normal: Vec3A::Y,
        });
        let reach = 0.25;
        let solids = Solids::new(bodies.clone(), &vec![reach; bodies.len()]);
        for i in 0..20_000 {
            let f = |k: f32| ((i as f32 + 0.5) * k).fract() * 8.0 - 4.0;
            let x = Vec3A::new(f(0.1234567), f(0.7654321), f(0.3141592));
            let brute = (0..bodies.len())
                .map(|j| (j, bodies[j].distance(x).0))
                .filter(|&(_, d)| d < reach)
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(j, _)| j);
            assert_eq!(solids.nearest(x, reach).map(|n| n.index), brute, "at {x}");
        }
    }

    #[test]
    fn points_inside_are_put_just_outside() {
        let solids = Solids::new(
            vec![
                Body::Cylinder {
                    base: Vec3A::ZERO,
                    axis: Vec3A::Y,
                    radius: 0.4,
                    height: 0.9,
                },
                Body::Plane {
                    point: Vec3A::ZERO,
                    normal: Vec3A::Y,
                },
            ],
            &[0.1, 0.1],
        );
        for x in [
            Vec3A::new(0.1, 0.85, 0.0),
            Vec3A::new(0.39, 0.5, 0.01),
            Vec3A::new(1.0, -0.2, 0.0),
            Vec3A::new(0.3, 0.01, 0.0),
        ] {
            let y = solids.push_out(x, 1e-5);
            assert!(solids.inside(y).is_none(), "{x} → {y}");
            assert!((y - x).length() < 0.2 + 1e-3, "{x} → {y}");
        }
    }
}
