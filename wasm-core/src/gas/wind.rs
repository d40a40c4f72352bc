//! The wind u = u_l + u_s (paper Eq. 3): large-scale primitives superposed on the small-scale
//! field, in world units (m, s, m/s).
//!
//! World mapping (docs/FORMATS.md, the field): one spatial period of the field spans `period` metres per axis and
//! one temporal period `time_period` seconds, so the lattice coordinate of x is x·n/L and world
//! velocity is `amplitude · u_field · L / time_period` per axis.
//!
//! A [`WindFrame`] freezes the wind at one time: repulsor paths are evaluated once and the two
//! field time slices bracketing t are blended into one 3-D slice, so sampling a blob costs one
//! trilinear lookup (equal to the quadrilinear sample, since both are linear in t).

use crate::field::TurbulentField;
use crate::gas::scene::{Primitive, Scene};
use crate::gas::spline::Path;
use crate::lanes::load4;
use glam::{Vec3, Vec3A, Vec4};
use std::f32::consts::PI;
use std::sync::Arc;

fn v3(a: [f32; 3]) -> Vec3 {
    Vec3::from_array(a)
}

fn v3a(a: [f32; 3]) -> Vec3A {
    Vec3A::from_array(a)
}

/// The small-scale field with its world mapping.
#[derive(Debug, Clone)]
pub struct SmallScale {
    field: Arc<TurbulentField>,
    /// Lattice points per metre along x, y, z.
    cells_per_metre: Vec3,
    /// World velocity per unit field velocity, per axis (m/s).
    velocity_scale: Vec3,
    /// Lattice time steps per second.
    steps_per_second: f64,
    /// Mean wind that carries the eddies (zero unless `carried_by_wind`).
    carry: Vec3,
}

impl SmallScale {
    pub fn new(field: Arc<TurbulentField>, scene: &Scene) -> Self {
        let [nx, ny, nz, nt] = field.lattice.size;
        let fs = &scene.field;
        let l = Vec3::new(
            fs.period[0] as f32,
            fs.period[1] as f32,
            fs.period[2] as f32,
        );
        let carry = if fs.carried_by_wind {
            scene
                .wind
                .iter()
                .filter_map(|w| match w {
                    Primitive::Uniform {
                        velocity,
                        enabled: true,
                        ..
                    } => Some(v3(*velocity)),
                    _ => None,
                })
                .sum()
        } else {
            Vec3::ZERO
        };
        Self {
            cells_per_metre: Vec3::new(nx as f32, ny as f32, nz as f32) / l,
            velocity_scale: l * (fs.amplitude / fs.time_period) as f32,
            steps_per_second: nt as f64 / fs.time_period,
            carry,
            field,
        }
    }

    /// Reference sample: quadrilinear in the 4-D lattice, in world units.
    pub fn velocity(&self, x: Vec3, t: f64) -> Vec3 {
        let q = (x - self.carry * t as f32) * self.cells_per_metre;
        let u = self.field.sample_lattice([
            q.x as f64,
            q.y as f64,
            q.z as f64,
            t * self.steps_per_second,
        ]);
        Vec3::from_array(u) * self.velocity_scale
    }

    /// The field at time `t` as one 3-D slice (world velocities), written into `slice`.
    pub fn slice_into(&self, t: f64, slice: &mut FieldSlice) {
        let [nx, ny, nz, nt] = self.field.lattice.size;
        let per = nx * ny * nz * 3;
        let tl = t * self.steps_per_second;
        let fl = tl.floor();
        let f = (tl - fl) as f32;
        let i0 = (fl as i64).rem_euclid(nt as i64) as usize;
        let i1 = (i0 + 1) % nt;
        let a = &self.field.data[i0 * per..(i0 + 1) * per];
        let b = &self.field.data[i1 * per..(i1 + 1) * per];
        let scale = self.velocity_scale.to_array();
        let (sx, sy, sz) = (nx + 1, ny + 1, nz + 1);
        // One float of padding: the last row's four-wide load reads one past its end.
        slice.data.resize(3 * sx * sy * sz + 1, 0.0);
        for z in 0..sz {
            for y in 0..sy {
                let src = 3 * (((z % nz) * ny + y % ny) * nx);
                let dst = 3 * ((z * sy + y) * sx);
                let (ra, rb) = (&a[src..src + 3 * nx], &b[src..src + 3 * nx]);
                let out = &mut slice.data[dst..dst + 3 * sx];
                for ((o, a), b) in out
                    .chunks_exact_mut(3)
                    .zip(ra.chunks_exact(3))
                    .zip(rb.chunks_exact(3))
                {
                    for k in 0..3 {
                        o[k] = (a[k] + f * (b[k] - a[k])) * scale[k];
                    }
                }
                out.copy_within(0..3, 3 * nx);
            }
        }
        slice.size = [nx, ny, nz];
        slice.extent = Vec3A::new(nx as f32, ny as f32, nz as f32);
        slice.inv_extent = slice.extent.recip();
        slice.cells_per_metre = self.cells_per_metre.into();
        slice.offset = (self.carry * t as f32).into();
        slice.time_slices = (i0 as u32, i1 as u32, f);
        slice.velocity_scale = self.velocity_scale.into();
    }
}

/// One time slice of the small-scale field, in world velocities, periodic in x, y, z.
/// Stored `[z][y][x][component]` with one extra point per axis (a copy of index 0), so the
/// two x-neighbours of a row are six contiguous floats and no index wraps while sampling.
#[derive(Debug, Clone, Default)]
pub struct FieldSlice {
    size: [usize; 3],
    /// The extents as floats, and their reciprocals (for the periodic wrap).
    extent: Vec3A,
    inv_extent: Vec3A,
    data: Vec<f32>,
    cells_per_metre: Vec3A,
    offset: Vec3A,
    /// The lattice's two bracketing time slices and the blend between them: the slice is
    /// `(1 − f)·u[i0] + f·u[i1]`, times `velocity_scale` (for the GPU's own sampling).
    time_slices: (u32, u32, f32),
    velocity_scale: Vec3A,
}

impl FieldSlice {
    /// Trilinear, periodic sample at world position `x` (m/s).
    ///
    /// Four-wide: a lattice row `[u0 v0 w0 u1 v1 w1]` is read as two overlapping vectors
    /// `[u0 v0 w0 u1]` and `[u1 v1 w1 u2]`, so one vector lerp interpolates all three
    /// components along x (the fourth lane is ignored).
    #[inline]
    pub fn sample(&self, x: Vec3A) -> Vec3A {
        let q = (x - self.offset) * self.cells_per_metre;
        let fl = q.floor();
        let t = q - fl;
        let [nx, ny] = [self.size[0], self.size[1]];
        // The periodic wrap of the integer cell fl into 0..n, exact in f32 while |q| < 2^24: the
        // quotient may round to a neighbouring integer, which the two selects put right.
        let n = self.extent;
        let mut cell = fl - n * (fl * self.inv_extent).floor();
        cell = Vec3A::select(cell.cmpge(n), cell - n, cell);
        cell = Vec3A::select(cell.cmplt(Vec3A::ZERO), cell + n, cell);
        let cell = cell.max(Vec3A::ZERO).min(n - 1.0);
        let (x0, y0, z0) = (cell.x as usize, cell.y as usize, cell.z as usize);
        let (sx, sy) = (nx + 1, ny + 1);
        let base = 3 * ((z0 * sy + y0) * sx + x0);
        let (dy, dz) = (3 * sx, 3 * sx * sy);
        // The farthest of the eight corners' reads ends at base + dz + dy + 7.
        let Some(w) = self.data.get(base..base + dz + dy + 7) else {
            return Vec3A::ZERO;
        };
        let tx = Vec4::splat(t.x);
        // Every read below starts at most dz + dy + 3 and spans four floats: inside `w`.
        let along_x = |i: usize| -> Vec4 {
            let a = load4(w, i);
            a + (load4(w, i + 3) - a) * tx
        };
        let e00 = along_x(0);
        let e10 = along_x(dy);
        let e01 = along_x(dz);
        let e11 = along_x(dz + dy);
        let (ty, tz) = (t.y, t.z);
        let lo = e00 + (e10 - e00) * ty;
        let hi = e01 + (e11 - e01) * ty;
        Vec3A::from_vec4(lo + (hi - lo) * tz)
    }
}

/// A primitive frozen at one time, with its constants folded.
#[derive(Debug, Clone, Copy)]
enum Frozen {
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

#[derive(Debug, Clone, Copy)]
struct FrozenPrimitive {
    kind: Frozen,
    /// Where decay is measured from, and 1/L (0 for no decay).
    origin: Vec3A,
    inv_decay: f32,
}

impl FrozenPrimitive {
    #[inline]
    fn velocity(&self, x: Vec3A) -> Vec3A {
        let u = match self.kind {
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
        };
        if self.inv_decay > 0.0 {
            u * (-(x - self.origin).length() * self.inv_decay).exp()
        } else {
            u
        }
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

/// A primitive with its path resolved.
#[derive(Debug, Clone)]
struct Large {
    primitive: Primitive,
    path: Option<Path>,
}

impl Large {
    fn new(primitive: Primitive) -> Self {
        let path = match &primitive {
            Primitive::Repulsor { path, .. } => Some(Path::new(path)),
            _ => None,
        };
        Self { primitive, path }
    }
}

/// The whole wind of a scene.
#[derive(Debug, Clone)]
pub struct Wind {
    small: Option<SmallScale>,
    large: Vec<Large>,
    /// A primitive outside the scene that acts until it is replaced or removed (the pointer
    /// stirring the gas in the playground).
    transient: Option<Large>,
}

impl Wind {
    /// The wind of `scene`; `field` is its small-scale field (none when the amplitude is 0).
    pub fn new(scene: &Scene, field: Option<Arc<TurbulentField>>) -> Self {
        let small = field
            .filter(|_| scene.field.amplitude > 0.0)
            .map(|f| SmallScale::new(f, scene));
        let large = scene
            .wind
            .iter()
            .filter(|w| w.enabled())
            .map(|w| Large::new(w.clone()))
            .collect();
        Self {
            small,
            large,
            transient: None,
        }
    }

    /// Sets (or with `None` removes) the transient primitive, which acts beside the scene's
    /// until replaced. A repulsor needs its path; any other kind acts as it stands.
    pub fn set_transient(&mut self, primitive: Option<Primitive>) {
        self.transient = primitive.map(Large::new);
    }

    /// The transient primitive, if any.
    pub fn transient(&self) -> Option<&Primitive> {
        self.transient.as_ref().map(|l| &l.primitive)
    }

    /// The scene's enabled primitives and the transient one.
    fn acting(&self) -> impl Iterator<Item = &Large> {
        self.large.iter().chain(self.transient.iter())
    }

    pub fn small_scale(&self) -> Option<&SmallScale> {
        self.small.as_ref()
    }

    /// Freezes the wind at time `t` into `frame` (reusing its allocations). Uniform winds
    /// without decay fold into one constant.
    pub fn frame_into(&self, t: f64, frame: &mut WindFrame) {
        frame.time = t;
        frame.has_slice = false;
        if let Some(s) = &self.small {
            s.slice_into(t, &mut frame.slice);
            frame.has_slice = true;
        }
        frame.constant = Vec3A::ZERO;
        frame.primitives.clear();
        for p in self.acting().map(|l| freeze(l, t)) {
            match p.kind {
                Frozen::Uniform { velocity } if p.inv_decay == 0.0 => frame.constant += velocity,
                _ => frame.primitives.push(p),
            }
        }
    }

    /// A new frame at time `t`.
    pub fn frame(&self, t: f64) -> WindFrame {
        let mut f = WindFrame::default();
        self.frame_into(t, &mut f);
        f
    }

    /// Reference evaluation without a frame (quadrilinear field sample), for tests and probes.
    pub fn velocity(&self, x: Vec3, t: f64) -> Vec3 {
        let small = self.small.as_ref().map_or(Vec3::ZERO, |s| s.velocity(x, t));
        small
            + self
                .acting()
                .map(|l| Vec3::from(freeze(l, t).velocity(x.into())))
                .sum::<Vec3>()
    }

    /// Centres, radii and colours of the visible repulsor spheres at time `t`.
    pub fn visible_spheres(&self, t: f64) -> Vec<(Vec3, f32, [f32; 3])> {
        self.large
            .iter()
            .filter_map(|l| match (&l.primitive, &l.path) {
                (
                    Primitive::Repulsor {
                        radius,
                        color: Some(c),
                        ..
                    },
                    Some(path),
                ) => Some((path.at(t).0.as_vec3(), *radius, *c)),
                _ => None,
            })
            .collect()
    }
}

fn freeze(l: &Large, t: f64) -> FrozenPrimitive {
    let inv = |d: &Option<f32>| d.map_or(0.0, |l| 1.0 / l);
    match &l.primitive {
        Primitive::Uniform {
            velocity,
            position,
            decay,
            ..
        } => FrozenPrimitive {
            kind: Frozen::Uniform {
                velocity: v3a(*velocity),
            },
            origin: v3a(*position),
            inv_decay: inv(decay),
        },
        Primitive::Source {
            position,
            strength,
            radius,
            decay,
            ..
        } => FrozenPrimitive {
            kind: Frozen::Source {
                position: v3a(*position),
                k: strength / (4.0 * PI),
                a2: radius * radius,
            },
            origin: v3a(*position),
            inv_decay: inv(decay),
        },
        Primitive::Vortex {
            position,
            axis,
            strength,
            radius,
            decay,
            ..
        } => FrozenPrimitive {
            kind: Frozen::Vortex {
                position: v3a(*position),
                axis: v3a(*axis).normalize(),
                g: strength / (2.0 * PI),
                a2: radius * radius,
            },
            origin: v3a(*position),
            inv_decay: inv(decay),
        },
        Primitive::Repulsor {
            radius,
            strength,
            decay,
            ..
        } => {
            let (c, v) = l.path.as_ref().expect("repulsors have paths").at(t);
            FrozenPrimitive {
                kind: Frozen::Repulsor {
                    center: c.as_vec3a(),
                    velocity: v.as_vec3a(),
                    radius: *radius,
                    strength: *strength,
                },
                origin: c.as_vec3a(),
                inv_decay: inv(decay),
            }
        }
    }
}

/// The wind frozen at one time.
#[derive(Debug, Clone, Default)]
pub struct WindFrame {
    pub time: f64,
    /// Sum of the uniform winds without decay (m/s).
    constant: Vec3A,
    has_slice: bool,
    slice: FieldSlice,
    primitives: Vec<FrozenPrimitive>,
}

/// Floats of a wind table's header ([`WindFrame::write_gpu_table`]).
pub const WIND_TABLE_HEADER: usize = 20;
/// Floats per frozen primitive in a wind table.
pub const WIND_TABLE_PRIMITIVE: usize = 16;
/// A frozen primitive's kind in a wind table.
pub const UNIFORM_KIND: f32 = 0.0;
pub const SOURCE_KIND: f32 = 1.0;
pub const VORTEX_KIND: f32 = 2.0;
pub const REPULSOR_KIND: f32 = 3.0;

impl WindFrame {
    /// The wind frozen at this frame's time as the GPU stepper reads it, appended to `out`:
    ///
    /// - header ([`WIND_TABLE_HEADER`] floats): `[has_field, i0, i1, f]` (the small-scale
    ///   field's two lattice time slices and their blend), `[offset xyz (m), 0]` (the carried
    ///   eddies' shift), `[lattice cells per metre xyz, 0]`, `[velocity scale xyz (m/s per
    ///   lattice unit), 0]`, `[constant wind xyz (m/s), primitive count]`;
    /// - per primitive ([`WIND_TABLE_PRIMITIVE`] floats, four vec4):
    ///   `[kind, 1/decay (1/m; 0: none), a, b]`, `[decay origin xyz (m), 0]`, `[p xyz, 0]`,
    ///   `[q xyz, 0]`, where uniform: p = velocity; source: p = position, a = s/(4π),
    ///   b = core²; vortex: p = position, q = unit axis, a = Γ/(2π), b = core²; repulsor:
    ///   p = centre, q = velocity, a = radius, b = strength.
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
        for p in &self.primitives {
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
            out.extend_from_slice(&[kind, p.inv_decay, a, b]);
            out.extend_from_slice(&v(p.origin, 0.0));
            out.extend_from_slice(&v(pos, 0.0));
            out.extend_from_slice(&v(q, 0.0));
        }
    }

    /// u(x) = u_s(x) + Σ primitives (m/s).
    #[inline]
    pub fn velocity(&self, x: Vec3) -> Vec3 {
        self.velocity_a(x.into()).into()
    }

    /// [`Self::velocity`] in four-wide vectors, for the per-blob loop.
    #[inline]
    pub fn velocity_a(&self, x: Vec3A) -> Vec3A {
        let mut u = self.constant;
        if self.has_slice {
            u += self.slice.sample(x);
        }
        for p in &self.primitives {
            u += p.velocity(x);
        }
        u
    }
}
