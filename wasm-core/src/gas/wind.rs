//! The wind u = u_l + u_s (paper Eq. 3): large-scale primitives superposed on the small-scale
//! field, in world units (m, s, m/s), turned along the scene's solid objects.
//!
//! World mapping (docs/FORMATS.md, the field): one spatial period of the field spans `period` metres per axis and
//! one temporal period `time_period` seconds, so the lattice coordinate of x is x·n/L and world
//! velocity is `amplitude · u_field · L / time_period` per axis. The field's vector potential ψ
//! (u = ∇ × ψ in field coordinates) maps to world units by `amplitude · Lx Ly Lz / (2π T L_k)`
//! for its component k, so that the world wind is the world curl of the world ψ.
//!
//! A [`WindFrame`] freezes the wind at one time: repulsor paths are evaluated once and the two
//! field time slices bracketing t are blended into one 3-D slice, so sampling a blob costs one
//! trilinear lookup (equal to the quadrilinear sample, since both are linear in t). With solid
//! objects ([`crate::gas::walls`]) the frame also holds the potential's slice, the mirror
//! images and the doublets; with carried turbulence ([`crate::gas::carried`]) the blend of the
//! two phases.

use crate::field::TurbulentField;
use crate::gas::carried::{Blend, Phases};
use crate::gas::doublets::{Doublets, Part};
use crate::gas::frozen::{freeze, Frozen, FrozenPrimitive, NOT_AN_IMAGE};
use crate::gas::scene::{Primitive, Scene};
use crate::gas::solids::{Around, Body, Nearest, Solids};
use crate::gas::spline::Path;
use crate::gas::walls::{project, ramp, Doublet, Stencil};
use crate::lanes::{ints3, load4};
use glam::{Vec3, Vec3A, Vec4};
use std::f32::consts::TAU;
use std::sync::Arc;

pub use crate::gas::frozen::repulsor_velocity;
pub use crate::gas::wind_table::{
    REPULSOR_KIND, SOURCE_KIND, UNIFORM_KIND, VORTEX_KIND, WIND_TABLE_HEADER, WIND_TABLE_PRIMITIVE,
    WIND_TABLE_SOLID,
};

fn v3(a: [f32; 3]) -> Vec3 {
    Vec3::from_array(a)
}

/// The small-scale field with its world mapping.
#[derive(Debug, Clone)]
pub struct SmallScale {
    field: Arc<TurbulentField>,
    /// Lattice points per metre along x, y, z.
    cells_per_metre: Vec3,
    /// World velocity per unit field velocity, per axis (m/s).
    velocity_scale: Vec3,
    /// World potential per unit field potential, per component (m²/s).
    potential_scale: Vec3,
    /// Lattice time steps per second.
    steps_per_second: f64,
    /// Mean wind that carries the eddies (zero unless `carried_by_wind` without `carried`).
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
        let carry = if fs.carried_by_wind && !fs.carried {
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
        let scale = (fs.amplitude / fs.time_period) as f32;
        let volume = l.x * l.y * l.z;
        Self {
            cells_per_metre: Vec3::new(nx as f32, ny as f32, nz as f32) / l,
            velocity_scale: l * scale,
            potential_scale: Vec3::splat(volume * scale / TAU) / l,
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

    /// Whether the field has its vector potential.
    pub fn has_potential(&self) -> bool {
        self.field.potential.is_some()
    }

    /// The smallest lattice spacing (m): the smallest eddy.
    pub fn spacing(&self) -> f32 {
        1.0 / self.cells_per_metre.max_element()
    }

    /// The field at time `t` as one 3-D slice (world velocities), written into `slice`.
    pub fn slice_into(&self, t: f64, slice: &mut FieldSlice) {
        self.slice_of(&self.field.data, self.velocity_scale, t, slice);
    }

    /// The vector potential at time `t` as one 3-D slice (world units, m²/s), if the field
    /// has it.
    pub fn potential_slice_into(&self, t: f64, slice: &mut FieldSlice) -> bool {
        match &self.field.potential {
            Some(psi) => {
                self.slice_of(psi, self.potential_scale, t, slice);
                true
            }
            None => false,
        }
    }

    fn slice_of(&self, data: &[f32], scale: Vec3, t: f64, slice: &mut FieldSlice) {
        let [nx, ny, nz, nt] = self.field.lattice.size;
        let per = nx * ny * nz * 3;
        let tl = t * self.steps_per_second;
        let fl = tl.floor();
        let f = (tl - fl) as f32;
        let i0 = (fl as i64).rem_euclid(nt as i64) as usize;
        let i1 = (i0 + 1) % nt;
        let a = &data[i0 * per..(i0 + 1) * per];
        let b = &data[i1 * per..(i1 + 1) * per];
        let scale = scale.to_array();
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
        slice.wrap_mask = [nx, ny, nz]
            .iter()
            .all(|n| n.is_power_of_two())
            .then(|| [nx, ny, nz].map(|n| n as i32 - 1));
        slice.extent = Vec3A::new(nx as f32, ny as f32, nz as f32);
        slice.inv_extent = slice.extent.recip();
        slice.cells_per_metre = self.cells_per_metre.into();
        slice.offset = (self.carry * t as f32).into();
        slice.time_slices = (i0 as u32, i1 as u32, f);
        slice.velocity_scale = scale.into();
    }
}

/// One time slice of the small-scale field, in world velocities, periodic in x, y, z.
/// Stored `[z][y][x][component]` with one extra point per axis (a copy of index 0), so the
/// two x-neighbours of a row are six contiguous floats and no index wraps while sampling.
#[derive(Debug, Clone, Default)]
pub struct FieldSlice {
    size: [usize; 3],
    /// `size − 1` along each axis where all three are powers of two (a periodic wrap is then
    /// a mask), else none.
    wrap_mask: Option<[i32; 3]>,
    /// The extents as floats, and their reciprocals (for the periodic wrap).
    extent: Vec3A,
    inv_extent: Vec3A,
    data: Vec<f32>,
    pub(crate) cells_per_metre: Vec3A,
    pub(crate) offset: Vec3A,
    /// The lattice's two bracketing time slices and the blend between them: the slice is
    /// `(1 − f)·u[i0] + f·u[i1]`, times `velocity_scale` (for the GPU's own sampling).
    pub(crate) time_slices: (u32, u32, f32),
    pub(crate) velocity_scale: Vec3A,
}

impl FieldSlice {
    /// [`Self::sample`] at each of `xs`: where all lie in one lattice cell (a stencil of small
    /// steps), the cell's corners are read once and each point interpolates them as
    /// [`Self::sample`] does; else each point is sampled alone.
    #[inline]
    pub fn sample_each<const N: usize>(&self, xs: &[Vec3A; N]) -> [Vec3A; N] {
        let q: [Vec3A; N] = std::array::from_fn(|k| (xs[k] - self.offset) * self.cells_per_metre);
        let Some(fl) = q.first().map(|q| q.floor()) else {
            return [Vec3A::ZERO; N];
        };
        if q.iter().any(|q| q.floor() != fl) {
            return std::array::from_fn(|k| self.sample(xs[k]));
        }
        let Some((w, dy, dz)) = self.corners(fl) else {
            return [Vec3A::ZERO; N];
        };
        std::array::from_fn(|k| Self::interpolate(w, dy, dz, q[k] - fl))
    }

    /// Trilinear, periodic sample at world position `x` (m/s).
    ///
    /// Four-wide: a lattice row `[u0 v0 w0 u1 v1 w1]` is read as two overlapping vectors
    /// `[u0 v0 w0 u1]` and `[u1 v1 w1 u2]`, so one vector lerp interpolates all three
    /// components along x (the fourth lane is ignored).
    #[inline]
    pub fn sample(&self, x: Vec3A) -> Vec3A {
        let q = (x - self.offset) * self.cells_per_metre;
        let fl = q.floor();
        match self.corners(fl) {
            Some((w, dy, dz)) => Self::interpolate(w, dy, dz, q - fl),
            None => Vec3A::ZERO,
        }
    }

    /// The data from the lattice cell `fl` (integer coordinates, wrapped periodically) on, and
    /// the strides to its corners along y and z; none if it would reach past the data.
    #[inline(always)]
    fn corners(&self, fl: Vec3A) -> Option<(&[f32], usize, usize)> {
        let [nx, ny] = [self.size[0], self.size[1]];
        let [x0, y0, z0] = match self.wrap_mask {
            // Two's complement: i & (n − 1) is i mod n, negative i too.
            Some(mask) => {
                let i = ints3(fl.clamp(Vec3A::splat(-2.0e9), Vec3A::splat(2.0e9)));
                [0, 1, 2].map(|k| (i[k] & mask[k]) as usize)
            }
            None => {
                // The periodic wrap of the integer cell fl into 0..n, exact in f32 while
                // |q| < 2^24: the quotient may round to a neighbouring integer, which the two
                // selects put right.
                let n = self.extent;
                let mut cell = fl - n * (fl * self.inv_extent).floor();
                cell = Vec3A::select(cell.cmpge(n), cell - n, cell);
                cell = Vec3A::select(cell.cmplt(Vec3A::ZERO), cell + n, cell);
                let cell = cell.max(Vec3A::ZERO).min(n - 1.0);
                ints3(cell).map(|i| i as usize)
            }
        };
        let (sx, sy) = (nx + 1, ny + 1);
        let base = 3 * ((z0 * sy + y0) * sx + x0);
        let (dy, dz) = (3 * sx, 3 * sx * sy);
        // The farthest of the eight corners' reads ends at base + dz + dy + 7.
        let w = self.data.get(base..base + dz + dy + 7)?;
        Some((w, dy, dz))
    }

    /// The trilinear interpolation at `t` (in [0, 1]³) of the cell whose data start `w`.
    #[inline(always)]
    fn interpolate(w: &[f32], dy: usize, dz: usize, t: Vec3A) -> Vec3A {
        let tx = Vec4::splat(t.x);
        // Every read below starts at most dz + dy + 3 and spans four floats: inside `w`.
        let along_x = |i: usize| -> Vec4 {
            // One bounds check for the row's two overlapping reads.
            let row = &w[i..i + 7];
            let a = load4(row, 0);
            a + (load4(row, 3) - a) * tx
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

/// The scene's solid objects as the wind meets them: the bodies with their grid, the layer's
/// width d₀, each body's difference step h for the ramped curl, and each body's doublet in the
/// uniform wind U (the sum of the uniform winds without decay).
#[derive(Debug, Clone)]
pub struct WallSet {
    pub solids: Solids,
    pub width: f32,
    pub steps: Vec<f32>,
    pub uniform: Vec3A,
    pub doublets: Doublets,
}

/// Of a difference step for the ramped curl: this fraction of the smallest of the layer's
/// width, the field's lattice spacing and the solid's size, the scales the potential varies
/// over.
pub const CURL_STEP_FRACTION: f32 = 1.0 / 64.0;

/// The rounding of a cylinder's rims the wind sees, in difference steps.
pub const EDGE_STEPS: f32 = 3.0;

impl WallSet {
    fn new(scene: &Scene, spacing: f32) -> Option<Self> {
        let bodies: Vec<Body> = scene.render.objects.iter().filter_map(Body::of).collect();
        if bodies.is_empty() {
            return None;
        }
        let width = scene.field.boundary_width as f32;
        let uniform: Vec3A = scene
            .wind
            .iter()
            .filter_map(|w| match w {
                Primitive::Uniform {
                    velocity,
                    decay: None,
                    enabled: true,
                    ..
                } => Some(Vec3A::from_array(*velocity)),
                _ => None,
            })
            .sum();
        let doublets: Vec<Option<Doublet>> =
            bodies.iter().map(|b| Doublet::of(b, uniform)).collect();
        let steps: Vec<f32> = bodies
            .iter()
            .map(|b| CURL_STEP_FRACTION * width.min(spacing).min(b.size()))
            .collect();
        // A doublet reaches the stencils of the ramped curl about points it reaches, a step
        // farther.
        let step = steps.iter().copied().fold(0.0, f32::max);
        let reach: Vec<Option<f32>> = bodies
            .iter()
            .zip(&doublets)
            .map(|(b, d)| d.map(|_| Doublet::reach(b) + step))
            .collect();
        // A cylinder's rims rounded by three difference steps: no stencil about a point
        // outside (or less than a step inside) reaches across the jump of the normal inside.
        let edges = bodies
            .iter()
            .zip(&steps)
            .map(|(b, h)| match b {
                Body::Cylinder { .. } => EDGE_STEPS * h,
                _ => 0.0,
            })
            .collect();
        Some(Self {
            solids: Solids::with_edges(bodies, edges, width, &reach),
            width,
            steps,
            uniform,
            doublets: Doublets::new(doublets, uniform),
        })
    }

    /// The gap (m) a blob put back on a surface keeps from it.
    pub fn gap(&self) -> f32 {
        1e-4 * self.width
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
    walls: Option<Arc<WallSet>>,
    phases: Option<Phases>,
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
        let spacing = small.as_ref().map_or(f32::INFINITY, SmallScale::spacing);
        let walls = WallSet::new(scene, spacing).map(Arc::new);
        let phases = (scene.field.carried && small.is_some()).then(|| {
            let p = scene.field.period;
            Phases {
                period: scene.field.carry_period(),
                shift: Vec3A::new(p[0] as f32, p[1] as f32, p[2] as f32) * 0.5,
            }
        });
        Self {
            small,
            large,
            transient: None,
            walls,
            phases,
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

    /// The solid objects the wind goes round, if any.
    pub fn walls(&self) -> Option<&WallSet> {
        self.walls.as_deref()
    }

    /// [`Self::walls`], shared: the same solids as long as the wind is not built anew.
    pub fn shared_walls(&self) -> Option<Arc<WallSet>> {
        self.walls.clone()
    }

    /// The same wind with every solid visited at every point (no grid): what the grid must
    /// give, for checks of it.
    pub fn every_solid_visited(&self) -> Self {
        let walls = self.walls.as_ref().map(|w| {
            Arc::new(WallSet {
                solids: w.solids.every_solid_visited(),
                ..WallSet::clone(w)
            })
        });
        Self {
            walls,
            ..self.clone()
        }
    }

    /// The carried phases, if the small-scale field is carried by the large scales.
    pub fn phases(&self) -> Option<&Phases> {
        self.phases.as_ref()
    }

    /// Freezes the wind at time `t` into `frame` (reusing its allocations). Uniform winds
    /// without decay fold into one constant.
    pub fn frame_into(&self, t: f64, frame: &mut WindFrame) {
        self.freeze_into(t, frame, true);
    }

    /// The large-scale wind alone at time `t` (no field slices): what carries the eddies.
    pub fn large_frame(&self, t: f64) -> WindFrame {
        let mut f = WindFrame::default();
        self.freeze_into(t, &mut f, false);
        f
    }

    fn freeze_into(&self, t: f64, frame: &mut WindFrame, with_field: bool) {
        frame.time = t;
        frame.has_slice = false;
        frame.has_psi = false;
        if let (Some(s), true) = (&self.small, with_field) {
            s.slice_into(t, &mut frame.slice);
            frame.has_slice = true;
            if self.walls.is_some() {
                frame.has_psi = s.potential_slice_into(t, &mut frame.psi);
            }
        }
        frame.constant = Vec3A::ZERO;
        frame.primitives.clear();
        frame.images.clear();
        for l in self.acting() {
            let p = freeze(
                &l.primitive,
                l.path.as_ref(),
                t,
                frame.primitives.len() as u32,
            );
            match p.kind {
                Frozen::Uniform { velocity } if p.inv_decay == 0.0 => frame.constant += velocity,
                _ => frame.primitives.push(p),
            }
        }
        frame.originals = frame.primitives.len();
        if let Some(w) = &self.walls {
            // Mirror images in the solid planes, after the primitives, each original's together.
            for i in 0..frame.originals {
                let first = frame.primitives.len();
                for (j, body) in w.solids.bodies.iter().enumerate() {
                    if let Body::Plane { point, normal } = *body {
                        if let Some(image) = frame.primitives[i].mirrored(j as u32, point, normal) {
                            frame.primitives.push(image);
                        }
                    }
                }
                frame
                    .images
                    .push((first as u32, frame.primitives.len() as u32));
            }
        }
        frame.walls = self.walls.clone();
        frame.blend = self.phases.map(|p| p.blend(t));
    }

    /// A new frame at time `t`.
    pub fn frame(&self, t: f64) -> WindFrame {
        let mut f = WindFrame::default();
        self.frame_into(t, &mut f);
        f
    }

    /// Reference evaluation (quadrilinear field sample), for tests and probes. With solid
    /// objects or carried turbulence it is the frame's wind (and the carried coordinates traced
    /// back through the large-scale wind in steps of at most `1/60` s).
    pub fn velocity(&self, x: Vec3, t: f64) -> Vec3 {
        if self.walls.is_some() || self.phases.is_some() {
            return self.sample(&[x], t, 1.0 / 60.0)[0];
        }
        let small = self.small.as_ref().map_or(Vec3::ZERO, |s| s.velocity(x, t));
        small
            + self
                .acting()
                .map(|l| Vec3::from(freeze(&l.primitive, l.path.as_ref(), t, 0).velocity(x.into())))
                .sum::<Vec3>()
    }

    /// The whole wind (m/s) at `points` at time `t`: the frame's wind, with carried
    /// coordinates traced back through the large-scale wind to each phase's reset in RK2 steps
    /// of at most `dt` (s).
    pub fn sample(&self, points: &[Vec3], t: f64, dt: f64) -> Vec<Vec3> {
        let frame = self.frame(t);
        let offsets = self.carried_offsets(points, t, dt);
        points
            .iter()
            .enumerate()
            .map(|(i, x)| {
                let o = offsets.as_ref().map_or([Vec3A::ZERO; 2], |o| o[i]);
                let (l, s) = frame.parts(Vec3A::from(*x), o);
                Vec3::from(l + s)
            })
            .collect()
    }

    /// The carried offsets X − x of `points` at time `t` (none unless the field is carried):
    /// for each phase, x traced back through the large-scale wind to the phase's reset, by
    /// the midpoint rule in equal steps of at most `dt` (s).
    pub fn carried_offsets(&self, points: &[Vec3], t: f64, dt: f64) -> Option<Vec<[Vec3A; 2]>> {
        let phases = self.phases?;
        let mut out = vec![[Vec3A::ZERO; 2]; points.len()];
        for (k, age) in phases.ages(t).into_iter().enumerate() {
            let steps = (age / dt).ceil().max(0.0) as usize;
            if steps == 0 {
                continue;
            }
            let h = age / steps as f64;
            let mut x: Vec<Vec3A> = points.iter().map(|&p| p.into()).collect();
            for s in 0..steps {
                let t1 = t - s as f64 * h;
                let (f1, fm) = (self.large_frame(t1), self.large_frame(t1 - 0.5 * h));
                for p in &mut x {
                    let xm = *p - f1.parts(*p, [Vec3A::ZERO; 2]).0 * (0.5 * h as f32);
                    *p -= fm.parts(xm, [Vec3A::ZERO; 2]).0 * h as f32;
                }
            }
            for (o, (p, x0)) in out.iter_mut().zip(x.iter().zip(points)) {
                o[k] = *p - Vec3A::from(*x0);
            }
        }
        Some(out)
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
        FrozenPrimitive::add_winds(&self.primitives, u, x)
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
            let u = FrozenPrimitive::add_winds(&self.primitives, self.constant, x);
            return (u, small(self), f32::INFINITY);
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
