//! The scene's `flow` (docs/FORMATS.md, the flow): a coarse grid over a box on which the large
//! scales are solved by the paper's Eqs. 1–2 (§7, "a physical model for the large scales"),
//! its constants and its faces. The types, their defaults and the grid they describe; the
//! checks are [`super::validate`]'s, the bounds [`super::limits`]'.

use crate::scene::limits::{FLOW_CELLS, FLOW_VISCOSITY_STEP, MAX_COORD};
use schemars::JsonSchema;
use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer, Serialize};

/// Air's kinematic viscosity ν, m²/s.
pub const AIR_VISCOSITY: f64 = 1.5e-5;
/// An ideal gas's expansion coefficient β at room temperature (293.15 K), 1/K.
pub const AIR_EXPANSION: f64 = 1.0 / 293.15;
/// Earth's gravity, m/s².
pub const EARTH_GRAVITY: [f64; 3] = [0.0, -9.81, 0.0];
/// How fast the gas's heat is lost by default, 1/s.
pub const DEFAULT_COOLING: f64 = 0.5;

/// What a face of the box does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(rename_all = "lowercase")]
pub enum Face {
    /// Air enters and leaves: the pressure beyond the face is 0, u_g's normal derivative 0.
    #[default]
    Open,
    /// A solid wall: no air crosses it ((u_p + u_g)·n = 0); the air slips along it.
    Closed,
}

/// What the two faces across each axis do.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(deny_unknown_fields)]
pub struct AxisFaces {
    /// The faces across x (at x0 and x1).
    #[serde(default)]
    pub x: Face,
    /// The faces across y (at y0 and y1).
    #[serde(default)]
    pub y: Face,
    /// The faces across z (at z0 and z1).
    #[serde(default)]
    pub z: Face,
}

/// What the box's six faces do: all alike (`"open"` or `"closed"`), or the two across each
/// axis as that axis says (`{"x": …, "y": …, "z": …}`, an axis not named open).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, JsonSchema)]
#[serde(untagged)]
pub enum FlowFaces {
    /// The six faces alike.
    All(Face),
    /// The two faces across each axis as that axis says.
    PerAxis(AxisFaces),
}

// Read by its JSON type (a string, or an object) rather than as serde's untagged enum, so that a
// refusal within the object names its key (`flow.faces.w`, `flow.faces.y`).
impl<'de> Deserialize<'de> for FlowFaces {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Either;
        impl<'de> Visitor<'de> for Either {
            type Value = FlowFaces;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(r#""open", "closed" or an object {"x", "y", "z"} of those"#)
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<FlowFaces, E> {
                Face::deserialize(de::value::StrDeserializer::new(v)).map(FlowFaces::All)
            }
            fn visit_map<A: de::MapAccess<'de>>(self, map: A) -> Result<FlowFaces, A::Error> {
                AxisFaces::deserialize(de::value::MapAccessDeserializer::new(map))
                    .map(FlowFaces::PerAxis)
            }
        }
        d.deserialize_any(Either)
    }
}

impl Default for FlowFaces {
    fn default() -> Self {
        Self::All(Face::Open)
    }
}

impl FlowFaces {
    /// Whether the faces across x, y and z are closed.
    pub fn closed(self) -> [bool; 3] {
        let face = match self {
            Self::All(f) => [f; 3],
            Self::PerAxis(a) => [a.x, a.y, a.z],
        };
        face.map(|f| f == Face::Closed)
    }
}

/// The flow: u_g on `cells` cubes over `box`, under the primitives and the small scales.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FlowSettings {
    /// The box `[x0, y0, z0, x1, y1, z1]` (m), x0 < x1, y0 < y1, z0 < z1.
    #[serde(rename = "box")]
    #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
    pub bounds: [f64; 6],
    /// Cells along x, y and z, each 8 to 256, at most 2^21 in all; the box's sides divided by
    /// them agree within 1 % (the cells are cubes).
    #[serde(deserialize_with = "crate::whole::list")]
    #[schemars(inner(range(min = FLOW_CELLS[0], max = FLOW_CELLS[1])))]
    pub cells: [usize; 3],
    /// ν, the kinematic viscosity (m²/s).
    #[serde(default = "air_viscosity")]
    #[schemars(range(min = 0, max = 10))]
    pub viscosity: f64,
    /// β, the expansion coefficient of the Boussinesq buoyancy b = −β T g (1/K).
    #[serde(default = "air_expansion")]
    #[schemars(range(min = 0, max = 1))]
    pub buoyancy: f64,
    /// g (m/s²).
    #[serde(default = "earth_gravity")]
    #[schemars(inner(range(min = -1e3, max = 1e3)))]
    pub gravity: [f64; 3],
    /// c, the rate at which the gas's heat is lost: h = h0·exp(−c·age) (1/s).
    #[serde(default = "default_cooling")]
    #[schemars(range(min = 0, max = 1e3))]
    pub cooling: f64,
    #[serde(default)]
    pub faces: FlowFaces,
    /// `false` keeps the flow in the scene without effect.
    #[serde(default = "yes")]
    pub enabled: bool,
}

fn air_viscosity() -> f64 {
    AIR_VISCOSITY
}
fn air_expansion() -> f64 {
    AIR_EXPANSION
}
fn earth_gravity() -> [f64; 3] {
    EARTH_GRAVITY
}
fn default_cooling() -> f64 {
    DEFAULT_COOLING
}
fn yes() -> bool {
    true
}

impl FlowSettings {
    /// A flow over `bounds` on `cells` with air's constants, open faces.
    pub fn new(bounds: [f64; 6], cells: [usize; 3]) -> Self {
        Self {
            bounds,
            cells,
            viscosity: AIR_VISCOSITY,
            buoyancy: AIR_EXPANSION,
            gravity: EARTH_GRAVITY,
            cooling: DEFAULT_COOLING,
            faces: FlowFaces::default(),
            enabled: true,
        }
    }

    /// The box's side along each axis (m).
    pub fn sides(&self) -> [f64; 3] {
        std::array::from_fn(|a| self.bounds[a + 3] - self.bounds[a])
    }

    /// Each axis's side per cell (m).
    pub fn spacings(&self) -> [f64; 3] {
        let s = self.sides();
        std::array::from_fn(|a| s[a] / self.cells[a] as f64)
    }

    /// The cubes' edge h (m): the mean of [`Self::spacings`] (within 1 % of each).
    pub fn h(&self) -> f64 {
        self.spacings().iter().sum::<f64>() / 3.0
    }

    /// The number of cells.
    pub fn cell_count(&self) -> u64 {
        self.cells.iter().map(|&n| n as u64).product()
    }

    /// Substeps of the explicit viscosity a step of `dt` (s) takes: ν·dt/h² per substep at
    /// most [`FLOW_VISCOSITY_STEP`].
    pub fn viscosity_substeps(&self, dt: f64) -> f64 {
        let h = self.h();
        (self.viscosity * dt / (h * h) / FLOW_VISCOSITY_STEP)
            .ceil()
            .max(1.0)
    }
}
