//! The animation system of paper §6: a scene's field, wind and gas advanced in fixed steps,
//! and the blob list (docs/FORMATS.md) a renderer takes.

use crate::check;
use crate::error::ParamError;
use crate::field::TurbulentField;
use crate::gas::blob_gas::Gas;
use crate::gas::blobs::{Blob, Blobs};
use crate::gas::slots::SlotTable;
use crate::scene::blob_list::{BlobList, BlobRecord, Object, RenderSettings};
use crate::scene::limits::{MAX_BLOBS_LIMIT, MAX_COORD, MAX_MASS0, MAX_SIGMA0};
use crate::scene::scene_format::{Primitive, Scene};
use crate::scene::shapes::Shape;
use crate::wind::flow::{FlowGrid, Projection, SceneFlow, Stir};
use crate::wind::wall_set::WallSet;
use crate::wind::wind_slice::SlicePlane;
use crate::wind::{Wind, WindFrame};
use glam::Vec3;
use std::borrow::Cow;
use std::sync::Arc;

/// Widest reach (m) of a stir ([`Simulation::stir_at`]'s radius, greater than 0).
pub const MAX_STIR_RADIUS: f32 = 1e3;
/// Fastest wind (m/s) a stir may give, along each axis.
pub const MAX_STIR_VELOCITY: f32 = 1e3;

#[derive(Debug, Clone)]
pub struct Simulation {
    pub scene: Scene,
    pub wind: Wind,
    /// Emitted blobs and the shapes played forwards.
    pub gas: Gas,
    /// Shapes played in reverse, one run each: `snapshots[k]` is the run after k steps.
    pub(super) reversed: Vec<Vec<Blobs>>,
    field: Option<Arc<TurbulentField>>,
    steps: u64,
    /// The clock: time = time_origin + (steps − steps_at_origin)·dt, both 0 from the start; an
    /// edit of `simulation.dt` moves them to the edit's time.
    time_origin: f64,
    steps_at_origin: u64,
    frames: [WindFrame; 2],
    /// While the GPU advects the centres: where each blob lives there ([`SlotTable`]).
    pub(super) slots: Option<SlotTable>,
    /// The solids whose grid the GPU was last handed ([`Simulation::solid_grid_for_gpu`], in [`crate::gas::gpu_handoff`]).
    pub(super) gpu_walls: Option<Arc<WallSet>>,
    /// The physical large scales (paper §7), when the scene has an enabled `flow`.
    pub(super) flow: Option<SceneFlow>,
    /// Each blob's heat at the last flow step (K·m³), scratch.
    heat: Vec<f32>,
    /// The last flow step's projection.
    projection: Option<Projection>,
}

/// What an edit did to the running simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Edit {
    /// The blobs and the time were kept.
    Kept,
    /// The scene restarted at t = 0: its initial blob sets (`shapes`) changed, or the time step
    /// of a scene that plays a shape in reverse.
    Restarted,
}

/// The blobs of shape `index`, born at time 0.
fn shape_blobs(shape: &Shape, seed: u64, index: usize) -> impl Iterator<Item = Blob> + '_ {
    shape.centres(seed, index).into_iter().map(move |c| {
        Blob::new(c, shape.sigma0, shape.mass0, 0.0).coloured(shape.albedo, shape.emission)
    })
}

impl Simulation {
    /// Validates `scene` (the one walk, [`Scene::validate`]) and synthesises its field (skipped
    /// when the amplitude is 0).
    pub fn new(scene: Scene) -> Result<Self, ParamError> {
        scene.validate()?;
        let field = if scene.field.amplitude > 0.0 {
            let params = scene.field_params();
            Some(Arc::new(if scene.needs_potential() {
                TurbulentField::generate_with_potential(&params)?
            } else {
                TurbulentField::generate(&params)?
            }))
        } else {
            None
        };
        Ok(Self::start(scene, field))
    }

    /// Validates `scene` and runs it on an already synthesised field, which must have the
    /// scene's field parameters, and its vector potential when the scene has solid objects
    /// (a scene of amplitude 0 leaves it unused).
    pub fn with_field(
        scene: Scene,
        field: Option<Arc<TurbulentField>>,
    ) -> Result<Self, ParamError> {
        scene.validate()?;
        let field = in_use(&scene, field);
        check_field(&scene, field.as_deref())?;
        Ok(Self::start(scene, field))
    }

    /// The simulation of a validated `scene` at t = 0 on `field` (its own): its gas with the
    /// forward shapes born, the reversed shapes run.
    fn start(scene: Scene, field: Option<Arc<TurbulentField>>) -> Self {
        let wind = Wind::new(&scene, field.clone());
        let mut gas = Gas::new(scene.gas.clone(), &scene.emitters, scene.seed);
        let flow = scene.active_flow().map(|f| SceneFlow::new(f, &scene));
        gas.cooling = scene.active_flow().map_or(0.0, |f| f.cooling);
        let mut reversed = Vec::new();
        for (i, shape) in scene.shapes.iter().enumerate() {
            match shape.reverse_from {
                None => shape_blobs(shape, scene.seed, i)
                    .for_each(|b| gas.blobs.push(&b, b.sigma0, b.mass0)),
                Some(t) => reversed.push(Self::run_shape(&scene, &wind, shape, i, t)),
            }
        }
        Self {
            scene,
            wind,
            gas,
            reversed,
            field,
            steps: 0,
            time_origin: 0.0,
            steps_at_origin: 0,
            frames: Default::default(),
            slots: None,
            gpu_walls: None,
            flow,
            heat: Vec::new(),
            projection: None,
        }
    }

    /// Applies an edited `scene` to the running simulation (paper §6: wind fields superposed
    /// interactively while the gas moves): wind primitives, emitters, gas constants, the
    /// medium, lights, objects and the time step take effect from now, and every blob keeps its
    /// place, σ and mass, the time goes on. `field` is the small-scale field to use from now:
    /// the scene's own, or while a new one is synthesised the one in use (its world mapping is
    /// the scene's); [`Self::set_field`] swaps it in when ready. A change to `shapes` (or to
    /// `simulation.dt` while a shape plays in reverse) restarts the scene instead.
    pub fn edit(
        &mut self,
        scene: Scene,
        field: Option<Arc<TurbulentField>>,
    ) -> Result<Edit, ParamError> {
        scene.validate()?;
        let field = in_use(&scene, field);
        let retimed = scene.simulation.dt != self.scene.simulation.dt;
        if scene.shapes != self.scene.shapes || (retimed && !self.reversed.is_empty()) {
            // An interim field (other parameters) waits for `set_field`.
            let field = field.filter(|f| f.params == scene.field_params());
            *self = Self::start(scene, field);
            return Ok(Edit::Restarted);
        }
        let t = self.time();
        if retimed {
            self.time_origin = t;
            self.steps_at_origin = self.steps;
        }
        self.gas
            .edit(scene.gas.clone(), &scene.emitters, scene.seed, t);
        let transient = self.wind.transient().cloned();
        self.wind = Wind::new(&scene, field.clone());
        self.wind.set_transient(transient);
        self.field = field;
        self.edit_flow(&scene);
        self.wind
            .set_flow(self.flow.as_ref().map(SceneFlow::frozen));
        self.scene = scene;
        Ok(Edit::Kept)
    }

    /// The flow after an edit to `scene`: kept (u_g and all) with its new constants while its
    /// box, cells, faces and solid objects' shapes stay (an object's colour, its model or a
    /// non-solid object may change); else started again at rest; gone without an enabled
    /// `flow`.
    fn edit_flow(&mut self, scene: &Scene) {
        let stir = self.flow.as_ref().and_then(|f| f.stir);
        let solids = |s: &Scene| -> Vec<_> {
            s.render
                .objects
                .iter()
                .filter_map(|o| o.solid_shape())
                .collect()
        };
        self.flow = match (self.flow.take(), scene.active_flow()) {
            (Some(mut old), Some(new))
                if old.same_grid(new) && solids(scene) == solids(&self.scene) =>
            {
                old.retune(new);
                Some(old)
            }
            (_, Some(new)) => Some(SceneFlow::new(new, scene)),
            (_, None) => None,
        };
        if let Some(f) = &mut self.flow {
            f.stir = stir;
        }
        // While the GPU holds the gas, it advances the newborns through its flow.
        self.gas.newborns_elsewhere = self.slots.is_some() && self.flow.is_some();
        self.gas.cooling = scene.active_flow().map_or(0.0, |f| f.cooling);
    }

    /// Swaps in the small-scale field (synthesised for the scene's field settings after an
    /// edit); blobs and time are kept.
    pub fn set_field(&mut self, field: Option<Arc<TurbulentField>>) -> Result<(), ParamError> {
        let field = in_use(&self.scene, field);
        check_field(&self.scene, field.as_deref())?;
        let transient = self.wind.transient().cloned();
        let flow = self.wind.flow().cloned();
        self.wind = Wind::new(&self.scene, field.clone());
        self.wind.set_transient(transient);
        self.wind.set_flow(flow);
        self.field = field;
        Ok(())
    }

    /// Stirs the gas: a transient wind primitive (outside the scene) that acts from the next
    /// step until replaced; `None` stops it.
    pub fn stir(&mut self, primitive: Option<Primitive>) {
        self.wind.set_transient(primitive);
    }

    /// Stirs the gas from the next step on with a wind of `velocity` (m/s) at `position` (m),
    /// falling off as exp(−distance/`radius`) (a uniform primitive with decay, paper Eq. 3's
    /// u_l), until the next stir; `radius` 0 stops it. Refused unless `radius` is 0 or greater
    /// than 0 and at most [`MAX_STIR_RADIUS`] m, the velocity's components at most
    /// [`MAX_STIR_VELOCITY`] m/s and the position's [`MAX_COORD`] m.
    pub fn stir_at(
        &mut self,
        position: [f32; 3],
        velocity: [f32; 3],
        radius: f32,
    ) -> Result<(), ParamError> {
        if radius == 0.0 {
            self.stir(None);
            if let Some(f) = &mut self.flow {
                f.stir = None;
            }
            return Ok(());
        }
        let vector = |a: [f32; 3], name: &str, limit: f32| {
            if a.iter().all(|c| c.is_finite() && c.abs() <= limit) {
                Ok(a)
            } else {
                Err(ParamError::new(
                    "stir",
                    format!("{name} must be 3 finite numbers of at most {limit}"),
                ))
            }
        };
        if !(radius.is_finite() && radius > 0.0 && radius <= MAX_STIR_RADIUS) {
            return Err(ParamError::new(
                "stir",
                format!("radius must be between 0 and {MAX_STIR_RADIUS} m"),
            ));
        }
        let velocity = vector(velocity, "velocity", MAX_STIR_VELOCITY)?;
        let position = vector(position, "position", MAX_COORD as f32)?;
        if let Some(f) = &mut self.flow {
            // Where the scene has a flow, the stir pushes momentum into it (docs/FORMATS.md,
            // the flow's stirring); the air keeps turning after the pointer stops.
            f.stir = Some(Stir {
                centre: position,
                velocity,
                radius,
            });
            return Ok(());
        }
        self.stir(Some(Primitive::Uniform {
            velocity,
            position,
            decay: Some(radius),
            enabled: true,
        }));
        Ok(())
    }

    /// Adds blobs born now at `positions` (m, xyz interleaved) with σ0 (m) and m0, the medium's
    /// albedo and no emission; refused unless the positions come in triples within the world
    /// (±[`MAX_COORD`] m), σ0 and m0 are an emitter's (in (0, [`MAX_SIGMA0`]] m and (0,
    /// [`MAX_MASS0`]]), and the blobs then number at most [`MAX_BLOBS_LIMIT`].
    pub fn add_blobs(
        &mut self,
        positions: &[f32],
        sigma0: f32,
        mass0: f32,
    ) -> Result<(), ParamError> {
        if positions.len() % 3 != 0 {
            return Err(ParamError::new(
                "add blobs",
                "positions must be xyz triples",
            ));
        }
        check::positive("add blobs: sigma0", sigma0, MAX_SIGMA0)?;
        check::positive("add blobs: mass0", mass0, MAX_MASS0)?;
        for (i, p) in positions.chunks_exact(3).enumerate() {
            check::vector(
                &format!("add blobs: positions[{i}]"),
                [p[0], p[1], p[2]],
                MAX_COORD,
            )?;
        }
        let n = positions.len() / 3;
        check::length(
            "add blobs",
            self.gas.blobs.len() + n,
            MAX_BLOBS_LIMIT,
            "blobs in all",
        )?;
        let birth = self.time();
        for p in positions.chunks_exact(3) {
            let blob = Blob::new(Vec3::from_slice(p), sigma0, mass0, birth);
            self.gas.blobs.push(&blob, sigma0, mass0);
        }
        Ok(())
    }

    /// The whole wind u = u_l + u_s (Eq. 3) now on `plane` (see [`SlicePlane::sample`]).
    pub fn wind_slice(&self, plane: &SlicePlane) -> Vec<f32> {
        plane.sample(&self.wind.frame(self.time()))
    }

    /// Runs shape `index` alone forwards for `seconds`, keeping every step.
    fn run_shape(
        scene: &Scene,
        wind: &Wind,
        shape: &Shape,
        index: usize,
        seconds: f64,
    ) -> Vec<Blobs> {
        let dt = scene.simulation.dt;
        let steps = scene.simulation.steps_for(seconds);
        let mut gas = Gas::new(scene.gas.clone(), &[], scene.seed);
        shape_blobs(shape, scene.seed, index).for_each(|b| gas.blobs.push(&b, b.sigma0, b.mass0));
        let mut frames: [WindFrame; 2] = Default::default();
        let mut snapshots = vec![gas.blobs.clone()];
        for k in 0..steps {
            gas.step(
                wind,
                k as f64 * dt,
                dt,
                scene.simulation.integrator,
                &mut frames,
            );
            snapshots.push(gas.blobs.clone());
        }
        snapshots
    }

    /// Every visible blob: the gas, then each reversed shape at its mirrored step (ages are
    /// those within the shape's own run).
    pub fn blobs(&self) -> Cow<'_, Blobs> {
        if self.reversed.is_empty() {
            return Cow::Borrowed(&self.gas.blobs);
        }
        let mut all = self.gas.blobs.clone();
        let dt = self.scene.simulation.dt;
        for run in &self.reversed {
            let k = (run.len() as u64 - 1).saturating_sub(self.steps) as usize;
            all.append_shifted(&run[k], self.time() - k as f64 * dt);
        }
        Cow::Owned(all)
    }

    /// The small-scale field, if the scene has one.
    pub fn field(&self) -> Option<&Arc<TurbulentField>> {
        self.field.as_ref()
    }

    /// Simulated time (s): steps × dt.
    pub fn time(&self) -> f64 {
        self.time_origin + (self.steps - self.steps_at_origin) as f64 * self.scene.simulation.dt
    }

    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Steps that make up `seconds` (rounded to the nearest whole step).
    pub fn steps_for(&self, seconds: f64) -> u64 {
        self.scene.simulation.steps_for(seconds)
    }

    /// Steps that make up `seconds`, refused (naming `simulation.dt` and the time) over
    /// [`crate::scene::limits::MAX_STEPS`].
    pub fn budgeted_steps(&self, seconds: f64) -> Result<u64, ParamError> {
        self.scene.budgeted_steps(seconds)
    }

    /// A run of `steps` fixed steps, refused unless it is a whole number, 0 or more (path
    /// `steps`), and over the step budget ([`Self::budgeted_steps`]).
    pub fn check_steps(&self, steps: f64) -> Result<u64, ParamError> {
        if !(steps.is_finite() && steps >= 0.0 && steps.fract() == 0.0) {
            return Err(ParamError::new(
                "steps",
                format!("must be a whole number, 0 or more (got {steps})"),
            ));
        }
        self.budgeted_steps(steps * self.scene.simulation.dt)
    }

    /// One fixed step: the flow's (if any, [`Self::step_flow`]; not while the GPU holds the
    /// centres, and with them the flow), then the gas's ([`Self::step_gas`]).
    pub fn step(&mut self) {
        if !self.centres_on_gpu() {
            self.step_flow();
        }
        self.step_gas();
    }

    /// The flow's part of a step (nothing without a flow): u_g from now to a step on under
    /// the primitives, the solids, the blobs' heat and the stir, frozen for the gas's part.
    pub fn step_flow(&mut self) {
        let t = self.time();
        let dt = self.scene.simulation.dt;
        let Some(flow) = &mut self.flow else {
            return;
        };
        self.gas.heat_into(t, &mut self.heat);
        let b = &self.gas.blobs;
        self.projection = Some(flow.step(&self.wind, t, dt, &b.position, &b.sigma, &self.heat));
        self.wind.set_flow(Some(flow.frozen()));
    }

    /// The gas's part of a step: the blobs advected through the wind (the flow's u_g of the
    /// last [`Self::step_flow`] included), emitted, diffused, dissipated, split.
    pub fn step_gas(&mut self) {
        let t = self.time();
        let dt = self.scene.simulation.dt;
        self.gas.step(
            &self.wind,
            t,
            dt,
            self.scene.simulation.integrator,
            &mut self.frames,
        );
        self.steps += 1;
    }

    /// The scene's flow, if it has an enabled one.
    pub fn flow(&self) -> Option<&SceneFlow> {
        self.flow.as_ref()
    }

    /// The flow's grid now (u_g and T on its cells), if the scene has a flow: u_g at rest
    /// before the first step, T from the blobs and their heat now.
    pub fn flow_grid(&self) -> Option<FlowGrid> {
        let flow = self.flow.as_ref()?;
        let t = self.time();
        let mut heat = Vec::new();
        self.gas.heat_into(t, &mut heat);
        let b = &self.gas.blobs;
        Some(FlowGrid {
            time: t,
            ..flow.export(&b.position, &b.sigma, &heat)
        })
    }

    /// The last flow step's projection (iterations and residual), if any.
    pub fn projection(&self) -> Option<Projection> {
        self.projection
    }

    /// The wind of the last step frozen at its start and at its middle (the RK2 midpoint;
    /// with Euler only the first is current).
    pub fn wind_frames(&self) -> &[WindFrame; 2] {
        &self.frames
    }

    /// `n` fixed steps.
    pub fn run(&mut self, n: u64) {
        for _ in 0..n {
            self.step();
        }
    }

    /// The scene's render settings at the current time: visible repulsor spheres join the
    /// objects.
    pub fn render_settings(&self) -> RenderSettings {
        let mut settings = self.scene.render.clone();
        for (center, radius, color) in self.wind.visible_spheres(self.time()) {
            settings.objects.push(Object::Sphere {
                center: center.to_array(),
                radius,
                color,
                solid: false,
            });
        }
        settings
    }

    /// The blob list of the current state: the scene's render settings, visible repulsor
    /// spheres added to the objects, and every blob with its age, σ0 and m0.
    pub fn blob_list(&self) -> BlobList {
        let settings = self.render_settings();
        let t = self.time();
        let b = self.blobs();
        let blobs = (0..b.len())
            .map(|i| {
                let e = [
                    b.emission[3 * i],
                    b.emission[3 * i + 1],
                    b.emission[3 * i + 2],
                ];
                BlobRecord {
                    center: b.center(i).to_array(),
                    sigma: b.sigma[i],
                    mass: b.mass[i],
                    albedo: b.albedo_of(i),
                    emission: (e != [0.0; 3]).then_some(e),
                    age: Some(t - b.birth[i]),
                    sigma0: Some(b.sigma0[i]),
                    mass0: Some(b.mass0[i]),
                }
            })
            .collect();
        BlobList::new(settings, blobs)
    }
}

/// Ok unless `field` was synthesised for other field parameters than `scene`'s, or without
/// the vector potential a scene with solid objects needs.
fn check_field(scene: &Scene, field: Option<&TurbulentField>) -> Result<(), ParamError> {
    match field {
        Some(f) if f.params != scene.field_params() => Err(ParamError::new(
            "field",
            "the given field was made with other parameters",
        )),
        Some(f) if scene.needs_potential() && f.potential.is_none() => Err(ParamError::new(
            "field",
            "a scene with solid objects needs the field's vector potential (synthesise it \
             with the field)",
        )),
        _ => Ok(()),
    }
}

/// `field` if `scene` uses a small-scale field (amplitude > 0), else none.
fn in_use(scene: &Scene, field: Option<Arc<TurbulentField>>) -> Option<Arc<TurbulentField>> {
    field.filter(|_| scene.field.amplitude > 0.0)
}
