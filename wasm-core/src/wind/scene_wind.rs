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
//! objects ([`crate::wind::walls`]) the frame also holds the potential's slice, the mirror
//! images and the doublets; with carried turbulence ([`crate::wind::carried`]) the blend of the
//! two phases.

use crate::field::TurbulentField;
use crate::scene::bodies::Body;
use crate::scene::scene_format::{Primitive, Scene};
use crate::wind::carried::Phases;
use crate::wind::flow::FrozenFlow;
use crate::wind::frozen::{freeze, Frozen};
use crate::wind::large::Large;
use crate::wind::small_scale::SmallScale;
use crate::wind::wall_set::WallSet;
use crate::wind::wind_frame::WindFrame;
use glam::{Vec3, Vec3A};
use std::sync::Arc;

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
    /// The flow's u_g for the coming step (paper §7's physical large scales), if the scene
    /// has a flow ([`crate::wind::flow::SceneFlow`] sets it).
    flow: Option<Arc<FrozenFlow>>,
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
            flow: None,
        }
    }

    /// Sets (or with `None` removes) the flow's u_g, added to the large scales inside its box
    /// from the next frame.
    pub fn set_flow(&mut self, flow: Option<Arc<FrozenFlow>>) {
        self.flow = flow;
    }

    /// The flow's u_g, if set.
    pub fn flow(&self) -> Option<&Arc<FrozenFlow>> {
        self.flow.as_ref()
    }

    /// Each acting repulsor's sphere at time `t`: centre (m), radius (m) and velocity (m/s).
    pub fn repulsor_spheres(&self, t: f64) -> Vec<(Vec3, f32, Vec3)> {
        self.acting()
            .filter_map(|l| match (&l.primitive, &l.path) {
                (Primitive::Repulsor { radius, .. }, Some(path)) => {
                    let (x, v) = path.at(t);
                    Some((x.as_vec3(), *radius, v.as_vec3()))
                }
                _ => None,
            })
            .collect()
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
        frame.flow = self.flow.clone();
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
