//! The animation system of paper §6: a scene's field, wind and gas advanced in fixed steps,
//! and the blob list (DESIGN §4) a renderer takes.

use crate::blob_list::{BlobList, BlobRecord, Object};
use crate::error::ParamError;
use crate::field::TurbulentField;
use crate::gas::Gas;
use crate::scene::Scene;
use crate::wind::{Wind, WindFrame};
use std::sync::Arc;

#[derive(Debug, Clone)]
pub struct Simulation {
    pub scene: Scene,
    pub wind: Wind,
    pub gas: Gas,
    field: Option<Arc<TurbulentField>>,
    steps: u64,
    frames: [WindFrame; 2],
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
        let gas = Gas::new(scene.gas.clone(), &scene.emitters, scene.seed);
        Ok(Self {
            scene,
            wind,
            gas,
            field,
            steps: 0,
            frames: Default::default(),
        })
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
        (seconds / self.scene.simulation.dt).round().max(0.0) as u64
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

    /// The blob list of the current state: the scene's render settings, visible repulsor
    /// spheres added to the objects, and every blob with its age, σ0 and m0.
    pub fn blob_list(&self) -> BlobList {
        let mut settings = self.scene.render.clone();
        let t = self.time();
        for (center, radius, color) in self.wind.visible_spheres(t) {
            settings.objects.push(Object::Sphere {
                center: center.to_array(),
                radius,
                color,
            });
        }
        let b = &self.gas.blobs;
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
