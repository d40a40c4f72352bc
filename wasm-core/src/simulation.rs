//! The animation system of paper §6: a scene's field, wind and gas advanced in fixed steps,
//! and the blob list (DESIGN §4) a renderer takes.

use crate::blob_list::{BlobList, BlobRecord, Object, RenderSettings};
use crate::error::ParamError;
use crate::field::TurbulentField;
use crate::gas::{Blob, Blobs, Gas};
use crate::scene::Scene;
use crate::shapes::Shape;
use crate::wind::{Wind, WindFrame};
use std::borrow::Cow;
use std::sync::Arc;

#[derive(Debug, Clone)]
pub struct Simulation {
    pub scene: Scene,
    pub wind: Wind,
    /// Emitted blobs and the shapes played forwards.
    pub gas: Gas,
    /// Shapes played in reverse, one run each: `snapshots[k]` is the run after k steps.
    reversed: Vec<Vec<Blobs>>,
    field: Option<Arc<TurbulentField>>,
    steps: u64,
    frames: [WindFrame; 2],
}

/// The blobs of shape `index`, born at time 0.
fn shape_blobs(shape: &Shape, seed: u64, index: usize) -> impl Iterator<Item = Blob> + '_ {
    shape.centres(seed, index).into_iter().map(move |c| {
        Blob::new(c, shape.sigma0, shape.mass0, 0.0).coloured(shape.albedo, shape.emission)
    })
}

impl Simulation {
    /// Validates `scene` and synthesises its field (skipped when the amplitude is 0).
    pub fn new(scene: Scene) -> Result<Self, ParamError> {
        scene.validate()?;
        let field = if scene.field.amplitude > 0.0 {
            Some(Arc::new(TurbulentField::generate(&scene.field_params())?))
        } else {
            None
        };
        Self::with_field(scene, field)
    }

    /// Uses an already synthesised field, which must match the scene's field parameters.
    pub fn with_field(
        scene: Scene,
        field: Option<Arc<TurbulentField>>,
    ) -> Result<Self, ParamError> {
        scene.validate()?;
        if let Some(f) = &field {
            if f.params != scene.field_params() {
                return Err(ParamError::new(
                    "field",
                    "the given field was made with other parameters",
                ));
            }
        }
        let wind = Wind::new(&scene, field.clone());
        let mut gas = Gas::new(scene.gas.clone(), &scene.emitters, scene.seed);
        let mut reversed = Vec::new();
        for (i, shape) in scene.shapes.iter().enumerate() {
            match shape.reverse_from {
                None => shape_blobs(shape, scene.seed, i)
                    .for_each(|b| gas.blobs.push(&b, b.sigma0, b.mass0)),
                Some(t) => reversed.push(Self::run_shape(&scene, &wind, shape, i, t)),
            }
        }
        Ok(Self {
            scene,
            wind,
            gas,
            reversed,
            field,
            steps: 0,
            frames: Default::default(),
        })
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
        self.steps as f64 * self.scene.simulation.dt
    }

    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Steps that make up `seconds` (rounded to the nearest whole step).
    pub fn steps_for(&self, seconds: f64) -> u64 {
        self.scene.simulation.steps_for(seconds)
    }

    /// Steps that make up `seconds`, refused (naming `simulation.dt` and the time) over
    /// `scene::MAX_STEPS`.
    pub fn budgeted_steps(&self, seconds: f64) -> Result<u64, ParamError> {
        self.scene.simulation.budgeted_steps(seconds)
    }

    /// One fixed step.
    pub fn step(&mut self) {
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
