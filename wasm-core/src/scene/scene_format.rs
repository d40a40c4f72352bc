//! The scene format, version 1 (docs/FORMATS.md): seed, field settings with the world mapping, wind
//! primitives, emitters, gas constants, simulation and render settings.
//!
//! This module holds the format's types, their defaults and its JSON Schema. Reading is
//! strict ([`super::validate`]: `Scene::from_json` and the one validation walk): unknown keys,
//! wrong types, non-finite or out-of-range numbers, and sizes over the memory guards
//! ([`super::limits`]) are errors that name the JSON path (`field.size[1]: must be an even
//! number between 4 and 256`). Every section and most keys have defaults; `version` is required.

use crate::error::ParamError;
use crate::field::lattice::{DEFAULT_EXTENT, MAX_EXTENT, MIN_EXTENT};
use crate::field::spectrum::SpectrumParams;
use crate::field::turbulent_field::DEFAULT_SEED;
use crate::field::{FieldParams, MAX_SEED};
use crate::scene::blob_list::RenderSettings;
use crate::scene::flow_settings::FlowSettings;
use crate::scene::limits::{
    MAX_ALBEDO, MAX_BLOBS_LIMIT, MAX_COORD, MAX_EMISSION, MAX_EMITTERS, MAX_FLOW_CELL_STEPS,
    MAX_MASS0, MAX_PATH_KEYS, MAX_PRIMITIVES, MAX_SHAPES, MAX_SIGMA0, MAX_STEPS, TEMPERATURE,
    WORLD_MAPPING,
};
use crate::scene::shapes::Shape;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The scene format version this build writes. Older versions are migrated on load.
pub const SCENE_VERSION: u32 = 1;

fn default_seed() -> u64 {
    DEFAULT_SEED
}
fn yes() -> bool {
    true
}

/// A complete scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Scene format version (currently 1).
    #[schemars(extend("const" = SCENE_VERSION))]
    #[serde(deserialize_with = "crate::whole::number")]
    pub version: u32,
    /// Seeds the field's white noise, the emitters and the splitting.
    #[serde(default = "default_seed", deserialize_with = "crate::whole::number")]
    #[schemars(range(max = MAX_SEED))]
    pub seed: u64,
    #[serde(default)]
    pub field: FieldSettings,
    /// Large-scale wind primitives, superposed on the small-scale field (paper Eq. 3).
    #[serde(default)]
    #[schemars(length(max = MAX_PRIMITIVES))]
    pub wind: Vec<Primitive>,
    #[serde(default)]
    #[schemars(length(max = MAX_EMITTERS))]
    pub emitters: Vec<Emitter>,
    /// Initial blob sets born at time 0, optionally played in reverse (the morph of §6).
    #[serde(default)]
    #[schemars(length(max = MAX_SHAPES))]
    pub shapes: Vec<Shape>,
    #[serde(default)]
    pub gas: GasSettings,
    #[serde(default)]
    pub simulation: SimulationSettings,
    #[serde(default)]
    pub render: RenderSettings,
    /// The physical large scales (paper §7): u_g solved on a coarse grid over a box; none
    /// keeps the wind kinematic.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flow: Option<FlowSettings>,
}

impl Default for Scene {
    fn default() -> Self {
        Self {
            version: SCENE_VERSION,
            seed: DEFAULT_SEED,
            field: FieldSettings::default(),
            wind: Vec::new(),
            emitters: Vec::new(),
            shapes: Vec::new(),
            gas: GasSettings::default(),
            simulation: SimulationSettings::default(),
            render: RenderSettings::default(),
            flow: None,
        }
    }
}

/// The JSON Schema of `field.size`: four even integers from 4 to 256 (the product's bound, 2^24
/// points, is beyond JSON Schema and stated in the description).
fn lattice_size_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
    schemars::json_schema!({
        "type": "array",
        "items": {
            "type": "integer",
            "minimum": MIN_EXTENT,
            "maximum": MAX_EXTENT,
            "multipleOf": 2
        },
        "minItems": 4,
        "maxItems": 4
    })
}

/// The small-scale field and its world mapping.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct FieldSettings {
    /// Lattice `[nx, ny, nz, nt]`, each an even number in 4..=256, at most 2^24 points in all.
    #[schemars(schema_with = "lattice_size_schema")]
    #[serde(deserialize_with = "crate::whole::list")]
    pub size: [usize; 4],
    pub spectrum: SpectrumParams,
    /// World metres per spatial period along x, y, z (the paper's grid spacing control).
    #[schemars(inner(range(min = WORLD_MAPPING.period[0], max = WORLD_MAPPING.period[1])))]
    pub period: [f64; 3],
    /// Seconds per temporal period.
    #[schemars(range(min = WORLD_MAPPING.time_period[0], max = WORLD_MAPPING.time_period[1]))]
    pub time_period: f64,
    /// Scale of the small-scale velocity; 0 turns the turbulence off.
    #[schemars(range(min = 0, max = WORLD_MAPPING.amplitude[1]))]
    pub amplitude: f64,
    /// Sample the field at x − U·t, U the sum of the uniform winds: the whole field translated
    /// by the mean wind (the simplest form of the paper's remedy for its independence
    /// assumption, §7). `carried` is the general form and supersedes it when both are set.
    pub carried_by_wind: bool,
    /// Width d₀ (m) of the layer over every solid object in which the wind is turned along
    /// the surface (the ramp α = r(d/d₀)); in (0, min(period)/2].
    #[schemars(range(max = 5e3), extend("exclusiveMinimum" = 0))]
    pub boundary_width: f64,
    /// Sample the field at coordinates advected by the large-scale wind (deflected by the
    /// solids): eddies ride with the flow (paper §7), in two phases cross-faded as Neyret's
    /// advected textures.
    pub carried: bool,
    /// Seconds between the resets of each phase of the carried coordinates; none means
    /// `time_period` / 8.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schemars(range(max = 1e6), extend("exclusiveMinimum" = 0))]
    pub carry_time: Option<f64>,
}

impl FieldSettings {
    /// Seconds between the resets of each carried phase: `carry_time`, else `time_period` / 8.
    pub fn carry_period(&self) -> f64 {
        self.carry_time.unwrap_or(self.time_period / 8.0)
    }
}

/// The default width of the layer over solid objects (m).
pub const DEFAULT_BOUNDARY_WIDTH: f64 = 0.1;

impl Default for FieldSettings {
    fn default() -> Self {
        Self {
            size: [DEFAULT_EXTENT; 4],
            spectrum: SpectrumParams::default(),
            period: [4.0; 3],
            time_period: 8.0,
            amplitude: 1.0,
            carried_by_wind: false,
            boundary_width: DEFAULT_BOUNDARY_WIDTH,
            carried: false,
            carry_time: None,
        }
    }
}

/// A large-scale wind primitive. Any primitive may carry `decay` L (m): its velocity is
/// multiplied by exp(−distance/L), distance from its `position` (for a repulsor, from the
/// sphere's centre). `enabled: false` keeps it in the scene without effect.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Primitive {
    /// Directional wind of constant `velocity` (m/s).
    Uniform {
        #[schemars(inner(range(min = -1e4, max = 1e4)))]
        velocity: [f32; 3],
        /// Where the decay is measured from (m); only used with `decay`.
        #[serde(default)]
        #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
        position: [f32; 3],
        #[serde(default)]
        #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
        decay: Option<f32>,
        #[serde(default = "yes")]
        enabled: bool,
    },
    /// Spherical source (strength > 0) or sink (< 0): volume flux `strength` (m³/s),
    /// u = s/(4π) · r / (|r|² + a²)^{3/2}, regularised within the core radius a = `radius`.
    Source {
        #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
        position: [f32; 3],
        #[schemars(range(min = -1e6, max = 1e6))]
        strength: f32,
        #[serde(default = "default_core")]
        #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
        radius: f32,
        #[serde(default)]
        #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
        decay: Option<f32>,
        #[serde(default = "yes")]
        enabled: bool,
    },
    /// Vortex line through `position` along `axis` with circulation `strength` Γ (m²/s) and
    /// core radius a: azimuthal speed Γ ρ / (2π (ρ² + a²)) at distance ρ from the axis.
    Vortex {
        #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
        position: [f32; 3],
        #[schemars(inner(range(min = -1e6, max = 1e6)))]
        axis: [f32; 3],
        #[schemars(range(min = -1e6, max = 1e6))]
        strength: f32,
        #[serde(default = "default_core")]
        #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
        radius: f32,
        #[serde(default)]
        #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
        decay: Option<f32>,
        #[serde(default = "yes")]
        enabled: bool,
    },
    /// A sphere of `radius` whose centre follows a smooth spline through the keys
    /// `[t, x, y, z]` of `path`; it pushes gas aside with the potential flow of a moving sphere
    /// plus a radial repulsion of speed `strength` (m/s) at its surface, falling off as 1/r².
    Repulsor {
        #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
        radius: f32,
        #[schemars(range(min = 0, max = 1e4))]
        strength: f32,
        #[schemars(
            length(min = 1, max = MAX_PATH_KEYS),
            inner(inner(range(min = -MAX_COORD, max = MAX_COORD)))
        )]
        path: Vec<[f64; 4]>,
        /// Colour of the sphere in renders; none keeps it invisible.
        #[serde(default)]
        #[schemars(inner(range(min = 0, max = 1)))]
        color: Option<[f32; 3]>,
        #[serde(default)]
        #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
        decay: Option<f32>,
        #[serde(default = "yes")]
        enabled: bool,
    },
}

impl Primitive {
    /// Whether the primitive acts on the wind.
    pub fn enabled(&self) -> bool {
        match self {
            Self::Uniform { enabled, .. }
            | Self::Source { enabled, .. }
            | Self::Vortex { enabled, .. }
            | Self::Repulsor { enabled, .. } => *enabled,
        }
    }
}

fn default_core() -> f32 {
    0.1
}

/// Where blobs are born.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(rename_all = "lowercase")]
pub enum EmitterShape {
    #[default]
    Point,
    /// Uniform on a disk of `radius` about `center`, perpendicular to `normal`.
    Disk,
    /// Uniform in a ball of `radius`.
    Sphere,
    /// Uniform in an axis-aligned box of full extents `size`.
    Box,
}

/// A blob emitter (paper §6: region of birth, birth rate, σ0 and m0 of each blob).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Emitter {
    pub shape: EmitterShape,
    #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
    pub center: [f32; 3],
    #[schemars(inner(range(min = -1e6, max = 1e6)))]
    pub normal: [f32; 3],
    #[schemars(range(min = 0, max = MAX_COORD))]
    pub radius: f32,
    #[schemars(inner(range(min = 0, max = MAX_COORD)))]
    pub size: [f32; 3],
    /// Birth rate in blobs per second; births are evenly spaced in time.
    #[schemars(range(min = 0, max = 1e6))]
    pub rate: f64,
    /// Initial standard deviation σ0 (m).
    #[schemars(range(max = MAX_SIGMA0), extend("exclusiveMinimum" = 0))]
    pub sigma0: f32,
    /// Initial mass m0.
    #[schemars(range(max = MAX_MASS0), extend("exclusiveMinimum" = 0))]
    pub mass0: f32,
    /// Albedo colour; none uses the medium's.
    #[schemars(inner(range(min = 0, max = MAX_ALBEDO)))]
    pub albedo: Option<[f32; 3]>,
    /// Self-emission colour Q; none is no emission.
    #[schemars(inner(range(min = 0, max = MAX_EMISSION)))]
    pub emission: Option<[f32; 3]>,
    /// Initial velocity of a blob relative to the wind (m/s); it relaxes to zero as
    /// exp(−age/`velocity_time`).
    #[schemars(inner(range(min = -1e4, max = 1e4)))]
    pub velocity: [f32; 3],
    /// Relaxation time of the initial velocity (s).
    #[schemars(range(max = 1e6), extend("exclusiveMinimum" = 0))]
    pub velocity_time: f32,
    pub enabled: bool,
    /// A moving source: keys `[t, x, y, z]` (s, m) the region's centre follows (the smooth
    /// spline of a repulsor's path), in place of `center`; empty keeps it at `center`.
    #[schemars(length(max = MAX_PATH_KEYS), inner(inner(range(min = -MAX_COORD, max = MAX_COORD))))]
    pub path: Vec<[f64; 4]>,
    /// Temperature excess (K over the ambient air) of each blob at birth: its heat
    /// h0 = temperature·(2π)^{3/2}·σ0³ drives the flow's buoyancy (read only with a `flow`).
    #[schemars(range(min = TEMPERATURE[0], max = TEMPERATURE[1]))]
    pub temperature: f64,
}

impl Default for Emitter {
    fn default() -> Self {
        Self {
            shape: EmitterShape::Point,
            center: [0.0; 3],
            normal: [0.0, 1.0, 0.0],
            radius: 0.1,
            size: [0.2; 3],
            rate: 30.0,
            sigma0: 0.05,
            mass0: 1.0,
            albedo: None,
            emission: None,
            velocity: [0.0; 3],
            velocity_time: 1.0,
            enabled: true,
            path: Vec::new(),
            temperature: 0.0,
        }
    }
}

/// Gas constants (paper Eqs. 12, 15, 16).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct GasSettings {
    /// κ (m²/s): σ² = σ0² + κ·age.
    #[schemars(range(min = 0, max = 1e3))]
    pub diffusion: f64,
    /// α (1/s): m = m0·exp(−α·age).
    #[schemars(range(min = 0, max = 1e3))]
    pub dissipation: f64,
    /// Blobs whose σ would exceed this (m) are split into smaller ones; none never splits.
    #[schemars(range(max = 1e4), extend("exclusiveMinimum" = 0))]
    pub split_sigma: Option<f64>,
    /// Most live blobs; the oldest are removed first beyond it (at most 1,000,000).
    #[schemars(range(min = 1, max = MAX_BLOBS_LIMIT))]
    #[serde(deserialize_with = "crate::whole::number")]
    pub max_blobs: usize,
    /// Blobs lighter than this are removed.
    #[schemars(range(min = 0, max = 1e12))]
    pub min_mass: f64,
}

impl Default for GasSettings {
    fn default() -> Self {
        Self {
            diffusion: 0.01,
            dissipation: 0.1,
            split_sigma: None,
            max_blobs: 20_000,
            min_mass: 1e-4,
        }
    }
}

/// Time integration of blob centres (Eq. 14).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(rename_all = "lowercase")]
pub enum Integrator {
    /// Second-order midpoint rule.
    #[default]
    Rk2,
    /// First-order forward Euler.
    Euler,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SimulationSettings {
    /// Fixed time step (s).
    #[schemars(range(max = 1), extend("exclusiveMinimum" = 0))]
    pub dt: f64,
    pub integrator: Integrator,
}

impl SimulationSettings {
    /// Fixed steps that make up `seconds` (rounded to the nearest whole step).
    pub fn steps_for(&self, seconds: f64) -> u64 {
        (seconds / self.dt).round().max(0.0) as u64
    }

    /// The steps of a run of `seconds` (round(T/dt)), or an error naming `simulation.dt` and the
    /// time when they would exceed [`MAX_STEPS`].
    pub fn budgeted_steps(&self, seconds: f64) -> Result<u64, ParamError> {
        let steps = (seconds / self.dt).round();
        if seconds.is_finite() && steps <= MAX_STEPS as f64 {
            return Ok(steps.max(0.0) as u64);
        }
        Err(ParamError::new(
            "simulation.dt",
            format!(
                "{} s of simulated time at dt = {:?} s is {} steps, over the limit of {MAX_STEPS}: raise simulation.dt or simulate less time",
                crate::error::number(seconds),
                self.dt,
                crate::error::number(steps)
            ),
        ))
    }
}

impl Default for SimulationSettings {
    fn default() -> Self {
        Self {
            dt: 1.0 / 60.0,
            integrator: Integrator::Rk2,
        }
    }
}

impl Scene {
    /// The field parameters for synthesis (lattice, spectrum, the scene's seed).
    pub fn field_params(&self) -> FieldParams {
        FieldParams {
            size: self.field.size,
            spectrum: self.field.spectrum,
            seed: self.seed,
        }
    }

    /// Whether any object of `render.objects` is solid (the wind and the gas go round it).
    pub fn has_solids(&self) -> bool {
        self.render.objects.iter().any(|o| o.solid())
    }

    /// Whether the scene's small-scale field needs its vector potential ψ beside it: it has a
    /// field (amplitude > 0) and solid objects the field must go round.
    pub fn needs_potential(&self) -> bool {
        self.field.amplitude > 0.0 && self.has_solids()
    }

    /// The enabled flow, if any.
    pub fn active_flow(&self) -> Option<&FlowSettings> {
        self.flow.as_ref().filter(|f| f.enabled)
    }

    /// The steps of a run of `seconds` ([`SimulationSettings::budgeted_steps`]), refused too
    /// (naming `flow.cells`) when the enabled flow's cells × steps exceed
    /// [`MAX_FLOW_CELL_STEPS`].
    pub fn budgeted_steps(&self, seconds: f64) -> Result<u64, ParamError> {
        let steps = self.simulation.budgeted_steps(seconds)?;
        if let Some(f) = self.active_flow() {
            let work = f.cell_count() as f64 * steps as f64;
            if work > MAX_FLOW_CELL_STEPS {
                return Err(ParamError::new(
                    "flow.cells",
                    format!(
                        "{} cells × {steps} steps ({} s at dt = {:?} s) is {work:.3e} cell-steps, \
                         over the limit of {MAX_FLOW_CELL_STEPS:.0e}: fewer cells, a larger \
                         simulation.dt or less time",
                        f.cell_count(),
                        crate::error::number(seconds),
                        self.simulation.dt
                    ),
                ));
            }
        }
        Ok(steps)
    }

    /// Serialises to pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("scenes serialise")
    }
}

/// The JSON Schema of the scene format (draft 2020-12), as shipped in `public/scene.schema.json`.
pub fn json_schema() -> String {
    let mut schema = serde_json::to_value(schemars::schema_for!(Scene)).expect("schema serialises");
    if let Some(obj) = schema.as_object_mut() {
        obj.insert(
            "$id".into(),
            "https://windfield.dev/scene.schema.json".into(),
        );
        obj.insert("title".into(), "windfield scene, version 1".into());
        obj.insert(
            "description".into(),
            "Every per-value range the parser enforces is stated here. Rules over several \
             values are not: a direction (axis, normal, up) must have non-zero length; the \
             camera's target must differ from its position and its up must not be parallel to \
             the view; a repulsor's key times must increase; field.size holds at most 2^24 \
             points; the enabled emitters make at most 100,000 births a step (the sum of \
             rate × simulation.dt); all shapes together make at most 1,000,000 blobs; a \
             reversed shape's run (reverse_from / simulation.dt) and render.time / \
             simulation.dt are at most 1,000,000 steps each; all reversed shapes keep at most \
             100,000 steps and 2e6 blobs over them (blobs × (steps + 1), a gas that splits \
             counting max(count, gas.max_blobs) a step); field.boundary_width is at most half \
             the shortest field.period; no emitter's center (or path key) lies inside a solid \
             object; a flow's box has each upper corner above its lower, at most 2^21 cells, \
             sides per cell that agree within 1 % (the cells are cubes), at most 1e10 cells × \
             steps of render.time / simulation.dt, and at most 64 viscosity substeps a step \
             (ν·simulation.dt/h² at most 1/8 each)."
                .into(),
        );
    }
    single_precision_written_short(&mut schema);
    serde_json::to_string_pretty(&schema).expect("schema serialises") + "\n"
}

/// Writes each number of `v` that is a single-precision value widened to double (a default
/// of an f32 key: 0.10000000149011612) as the single-precision number's own shortest digits
/// (0.1), which read back as the same f32. A double-precision number is kept: one that is
/// not exactly a single-precision value, or whose digits are as short either way.
fn single_precision_written_short(v: &mut serde_json::Value) {
    match v {
        serde_json::Value::Number(n) => {
            let Some(x) = n.as_f64().filter(|_| n.is_f64()) else {
                return;
            };
            let single = x as f32;
            if f64::from(single) != x {
                return;
            }
            let short: f64 = single.to_string().parse().unwrap_or(x);
            if short != x {
                if let Some(s) = serde_json::Number::from_f64(short) {
                    *n = s;
                }
            }
        }
        serde_json::Value::Array(items) => {
            items.iter_mut().for_each(single_precision_written_short)
        }
        serde_json::Value::Object(map) => map.values_mut().for_each(single_precision_written_short),
        _ => {}
    }
}
