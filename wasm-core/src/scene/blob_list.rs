//! The blob list (docs/FORMATS.md): what a renderer takes, from the CLI and the browser alike.
//! Camera, image, medium, lights, shadows, background and opaque objects, then the blobs.
//! Units: metres; colours linear RGB; extinction κ_t in m² per unit mass.
//!
//! A scene's `render` section is a [`RenderSettings`], the list without its blobs. Reading a
//! list from JSON is [`super::read`]; its checks are [`super::validate`].

use crate::scene::limits::{
    MAX_COORD, MAX_IMAGE_SIDE, MAX_LIGHTS, MAX_LIST_BLOBS, MAX_OBJECTS, MAX_SECONDS,
};
use schemars::JsonSchema;
use serde::de::{Error as _, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize};

/// The moment (s) a still or a poster shows when neither the scene nor the caller names one.
pub const DEFAULT_RENDER_TIME: f64 = 3.0;

/// Pinhole camera; `fov_y_deg` is the full vertical angle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Camera {
    #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
    pub position: [f32; 3],
    #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
    pub target: [f32; 3],
    #[schemars(inner(range(min = -1e6, max = 1e6)))]
    pub up: [f32; 3],
    #[schemars(range(min = 0.1, max = 179))]
    pub fov_y_deg: f32,
}

impl Default for Camera {
    fn default() -> Self {
        Self {
            position: [0.0, 1.0, 4.0],
            target: [0.0, 1.0, 0.0],
            up: [0.0, 1.0, 0.0],
            fov_y_deg: 40.0,
        }
    }
}

/// Output encoding: `srgb` applies the sRGB transfer curve before quantising, `linear` does not.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(rename_all = "lowercase")]
pub enum Encoding {
    #[default]
    Srgb,
    Linear,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Image {
    #[schemars(range(min = 1, max = MAX_IMAGE_SIDE))]
    #[serde(deserialize_with = "crate::whole::number")]
    pub width: u32,
    #[schemars(range(min = 1, max = MAX_IMAGE_SIDE))]
    #[serde(deserialize_with = "crate::whole::number")]
    pub height: u32,
    pub encoding: Encoding,
}

impl Default for Image {
    fn default() -> Self {
        Self {
            width: 640,
            height: 480,
            encoding: Encoding::Srgb,
        }
    }
}

/// Extinction coefficient κ_t: one number for all channels, or per RGB channel.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum Extinction {
    Grey(#[schemars(range(min = 0, max = 1e6))] f32),
    Rgb(#[schemars(inner(range(min = 0, max = 1e6)))] [f32; 3]),
}

impl Extinction {
    pub fn rgb(self) -> [f32; 3] {
        match self {
            Self::Grey(v) => [v; 3],
            Self::Rgb(v) => v,
        }
    }
}

/// Phase function p(cos θ), normalised so that isotropic scattering is p ≡ 1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Phase {
    // p ≡ 1. A variant with no keys rather than a unit one, so that a key given with it
    // (`{"type": "isotropic", "g": 0.5}`) is refused as unknown, as in every other element.
    Isotropic {},
    /// p = (1 − g²) / (1 + g² − 2g cos θ)^{3/2}, g in (−1, 1).
    HenyeyGreenstein {
        #[schemars(extend("exclusiveMinimum" = -1, "exclusiveMaximum" = 1))]
        g: f32,
    },
}

/// The participating medium's optical constants (paper Appendix B).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Medium {
    pub extinction: Extinction,
    /// Albedo Ω per channel, in [0, 1]; a blob's own albedo overrides it.
    #[schemars(inner(range(min = 0, max = 1)))]
    pub albedo: [f32; 3],
    pub phase: Phase,
}

impl Default for Medium {
    fn default() -> Self {
        Self {
            extinction: Extinction::Grey(1.0),
            albedo: [0.9, 0.9, 0.9],
            phase: Phase::Isotropic {},
        }
    }
}

impl Default for Phase {
    fn default() -> Self {
        Self::Isotropic {}
    }
}

/// A light source. Point lights have no distance falloff. A directional light's `direction`
/// is the direction its light travels (from the light into the scene).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Light {
    Point {
        #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
        position: [f32; 3],
        #[schemars(inner(range(min = 0, max = 1e6)))]
        color: [f32; 3],
    },
    Directional {
        #[schemars(inner(range(min = -1e6, max = 1e6)))]
        direction: [f32; 3],
        #[schemars(inner(range(min = 0, max = 1e6)))]
        color: [f32; 3],
    },
}

/// An opaque, Lambert-shaded object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Object {
    Sphere {
        #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
        center: [f32; 3],
        #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
        radius: f32,
        #[schemars(inner(range(min = 0, max = 1)))]
        color: [f32; 3],
        /// A solid sphere deflects the wind and the gas; absent means not solid.
        #[serde(default, skip_serializing_if = "is_false")]
        solid: bool,
    },
    Plane {
        #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
        point: [f32; 3],
        #[schemars(inner(range(min = -1e6, max = 1e6)))]
        normal: [f32; 3],
        #[schemars(inner(range(min = 0, max = 1)))]
        color: [f32; 3],
        /// A solid plane bounds the half-space behind it (opposite its normal), which deflects
        /// the wind and the gas; absent means not solid.
        #[serde(default, skip_serializing_if = "is_false")]
        solid: bool,
    },
    Cylinder {
        #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
        base: [f32; 3],
        #[schemars(inner(range(min = -1e6, max = 1e6)))]
        axis: [f32; 3],
        #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
        radius: f32,
        #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
        height: f32,
        #[schemars(inner(range(min = 0, max = 1)))]
        color: [f32; 3],
        /// A richer mesh the browser draws in the cylinder's place (the still keeps the
        /// cylinder as its stand-in).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        model: Option<Model>,
        /// A solid cylinder (closed by its caps; a model keeps the cylinder as its solid)
        /// deflects the wind and the gas; absent means not solid.
        #[serde(default, skip_serializing_if = "is_false")]
        solid: bool,
    },
}

fn is_false(b: &bool) -> bool {
    !*b
}

impl Object {
    /// Whether the object deflects the wind and the gas.
    pub fn solid(&self) -> bool {
        match self {
            Self::Sphere { solid, .. }
            | Self::Plane { solid, .. }
            | Self::Cylinder { solid, .. } => *solid,
        }
    }

    /// A solid object's shape and place alone: the object with what only the renderers read
    /// (its colour, a cylinder's model) cleared; None for an object that is not solid. Two
    /// lists of objects with the same solid shapes deflect the wind alike.
    pub fn solid_shape(&self) -> Option<Self> {
        if !self.solid() {
            return None;
        }
        let mut shape = self.clone();
        match &mut shape {
            Self::Sphere { color, .. } | Self::Plane { color, .. } => *color = [0.0; 3],
            Self::Cylinder { color, model, .. } => {
                *color = [0.0; 3];
                *model = None;
            }
        }
        Some(shape)
    }
}

/// Meshes the browser may draw in place of a cylinder stand-in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Model {
    Mug,
    Teapot,
}

/// What a ray that meets neither gas nor object ends in: a colour (linear radiance per channel,
/// `[r, g, b]`), or `"transparent"`: nothing, and the image gets an alpha channel, α = 1 − T(∞)
/// over the gas (T the ray's transmittance, its channels' mean where the extinction is
/// coloured) and 1 on opaque objects (docs/FORMATS.md, the image).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Background {
    Colour([f32; 3]),
    Transparent,
}

/// The keyword of a transparent background.
pub const TRANSPARENT: &str = "transparent";

impl Background {
    /// The radiance a ray picks up past the gas: the colour, or none when transparent.
    pub fn radiance(self) -> [f32; 3] {
        match self {
            Self::Colour(c) => c,
            Self::Transparent => [0.0; 3],
        }
    }

    pub fn is_transparent(self) -> bool {
        self == Self::Transparent
    }
}

impl Default for Background {
    fn default() -> Self {
        Self::Colour([0.05, 0.06, 0.08])
    }
}

impl Serialize for Background {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Self::Colour(c) => c.serialize(s),
            Self::Transparent => s.serialize_str(TRANSPARENT),
        }
    }
}

impl<'de> Deserialize<'de> for Background {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Either;
        impl<'de> Visitor<'de> for Either {
            type Value = Background;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                write!(f, "[r, g, b] (linear radiance) or \"{TRANSPARENT}\"")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Background, E> {
                if v == TRANSPARENT {
                    Ok(Background::Transparent)
                } else {
                    Err(E::custom(format!(
                        "must be [r, g, b] (linear radiance) or \"{TRANSPARENT}\" (got \"{v}\")"
                    )))
                }
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Background, A::Error> {
                let rgb =
                    <[f32; 3]>::deserialize(serde::de::value::SeqAccessDeserializer::new(seq))?;
                Ok(Background::Colour(rgb))
            }
        }
        d.deserialize_any(Either)
    }
}

impl JsonSchema for Background {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Background".into()
    }

    fn inline_schema() -> bool {
        true
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({
            "description": "Linear radiance [r, g, b] behind the gas, or \"transparent\": an alpha channel instead (alpha = 1 - T(inf) over the gas, 1 on objects).",
            "anyOf": [
                {
                    "type": "array",
                    "items": { "type": "number", "format": "float", "minimum": 0, "maximum": 1e6 },
                    "minItems": 3,
                    "maxItems": 3
                },
                { "const": TRANSPARENT }
            ]
        })
    }
}

/// The `render` section of a scene: everything of a blob list except the blobs, and the
/// scene's `time`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct RenderSettings {
    pub camera: Camera,
    pub image: Image,
    pub medium: Medium,
    #[schemars(length(max = MAX_LIGHTS))]
    pub lights: Vec<Light>,
    pub shadows: bool,
    pub background: Background,
    #[schemars(length(max = MAX_OBJECTS))]
    pub objects: Vec<Object>,
    /// The moment (s) a still or a poster shows when none is given (`windfield render`
    /// without `--seconds`, the element's `poster-time`); none is 3 s. A scene's only: a blob
    /// list is one moment already and has no `time`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0, max = MAX_SECONDS), extend("default" = DEFAULT_RENDER_TIME))]
    pub time: Option<f64>,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            camera: Camera::default(),
            image: Image::default(),
            medium: Medium::default(),
            lights: vec![Light::Directional {
                direction: [-0.4, -1.0, -0.3],
                color: [1.0, 1.0, 1.0],
            }],
            shadows: true,
            background: Background::default(),
            objects: Vec::new(),
            time: None,
        }
    }
}

/// One Gaussian blob (paper Eqs. 13, 15): density m / ((2π)^{3/2} σ³) · exp(−|x − c|²/(2σ²)).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BlobRecord {
    pub center: [f32; 3],
    pub sigma: f32,
    pub mass: f32,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub albedo: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emission: Option<[f32; 3]>,
    /// Seconds since this blob was born (emitted, or split from its parent).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub age: Option<f64>,
    /// σ at birth: σ² = σ0² + κ·age.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma0: Option<f32>,
    /// Mass at birth: m = m0·exp(−α·age).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass0: Option<f32>,
}

/// The render input (the blob list of docs/FORMATS.md): the fields of [`RenderSettings`] plus the blobs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BlobList {
    pub camera: Camera,
    pub image: Image,
    pub medium: Medium,
    pub lights: Vec<Light>,
    pub shadows: bool,
    pub background: Background,
    pub objects: Vec<Object>,
    /// At most [`MAX_LIST_BLOBS`]: a longer list is refused as it is read, before it is held.
    #[serde(deserialize_with = "bounded_blobs")]
    pub blobs: Vec<BlobRecord>,
}

/// Reads the `blobs` array, refusing it at its [`MAX_LIST_BLOBS`]` + 1`th blob.
fn bounded_blobs<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<BlobRecord>, D::Error> {
    struct Bounded;
    impl<'de> Visitor<'de> for Bounded {
        type Value = Vec<BlobRecord>;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            write!(f, "a list of at most {MAX_LIST_BLOBS} blobs")
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
            let mut blobs = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(4096));
            while let Some(blob) = seq.next_element()? {
                if blobs.len() == MAX_LIST_BLOBS {
                    return Err(A::Error::custom(format!(
                        "must hold at most {MAX_LIST_BLOBS} blobs (got more)"
                    )));
                }
                blobs.push(blob);
            }
            Ok(blobs)
        }
    }
    d.deserialize_seq(Bounded)
}

impl RenderSettings {
    /// The moment (s) a still of the scene shows when none is given: `time`, else 3 s.
    pub fn still_time(&self) -> f64 {
        self.time.unwrap_or(DEFAULT_RENDER_TIME)
    }
}

impl Default for BlobList {
    /// The default render settings and no blobs.
    fn default() -> Self {
        Self::new(RenderSettings::default(), Vec::new())
    }
}

impl BlobList {
    /// A blob list of `settings` (a scene's `time` is left out: the list is one moment) and
    /// `blobs`.
    pub fn new(settings: RenderSettings, blobs: Vec<BlobRecord>) -> Self {
        let RenderSettings {
            camera,
            image,
            medium,
            lights,
            shadows,
            background,
            objects,
            time: _,
        } = settings;
        Self {
            camera,
            image,
            medium,
            lights,
            shadows,
            background,
            objects,
            blobs,
        }
    }

    /// The settings part (everything but the blobs).
    pub fn settings(&self) -> RenderSettings {
        RenderSettings {
            camera: self.camera.clone(),
            image: self.image.clone(),
            medium: self.medium.clone(),
            lights: self.lights.clone(),
            shadows: self.shadows,
            background: self.background,
            objects: self.objects.clone(),
            time: None,
        }
    }
}
