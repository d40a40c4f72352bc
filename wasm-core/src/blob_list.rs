//! The blob list (DESIGN §4): what a renderer takes, from the CLI and the browser alike.
//! Camera, image, medium, lights, shadows, background and opaque objects, then the blobs.
//! Units: metres; colours linear RGB; extinction κ_t in m² per unit mass.

use crate::check;
use crate::error::ParamError;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Largest accepted coordinate magnitude (m).
pub const MAX_COORD: f64 = 1.0e6;
/// Largest image side in pixels.
pub const MAX_IMAGE_SIDE: u32 = 8192;

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
    pub width: u32,
    #[schemars(range(min = 1, max = MAX_IMAGE_SIDE))]
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
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Phase {
    #[default]
    Isotropic,
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
            phase: Phase::Isotropic,
        }
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
    },
    Plane {
        #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
        point: [f32; 3],
        #[schemars(inner(range(min = -1e6, max = 1e6)))]
        normal: [f32; 3],
        #[schemars(inner(range(min = 0, max = 1)))]
        color: [f32; 3],
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
    },
}

/// Meshes the browser may draw in place of a cylinder stand-in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Model {
    Mug,
    Teapot,
}

/// Everything of a blob list except the blobs; the `render` section of a scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct RenderSettings {
    pub camera: Camera,
    pub image: Image,
    pub medium: Medium,
    pub lights: Vec<Light>,
    pub shadows: bool,
    #[schemars(inner(range(min = 0, max = 1e6)))]
    pub background: [f32; 3],
    pub objects: Vec<Object>,
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
            background: [0.05, 0.06, 0.08],
            objects: Vec::new(),
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

/// The render input of DESIGN §4: the fields of [`RenderSettings`] plus the blobs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BlobList {
    pub camera: Camera,
    pub image: Image,
    pub medium: Medium,
    pub lights: Vec<Light>,
    pub shadows: bool,
    pub background: [f32; 3],
    pub objects: Vec<Object>,
    pub blobs: Vec<BlobRecord>,
}

impl RenderSettings {
    /// Checks every value; errors are named `{path}.camera.fov_y_deg` and so on
    /// (`camera.fov_y_deg` when `path` is empty).
    pub fn validate(&self, path: &str) -> Result<(), ParamError> {
        let p = |s: &str| {
            if path.is_empty() {
                s.to_string()
            } else {
                format!("{path}.{s}")
            }
        };
        let c = &self.camera;
        check::vector(&p("camera.position"), c.position, MAX_COORD)?;
        check::vector(&p("camera.target"), c.target, MAX_COORD)?;
        check::direction(&p("camera.up"), c.up)?;
        check::range(&p("camera.fov_y_deg"), c.fov_y_deg as f64, 0.1, 179.0)?;
        let view: Vec<f32> = (0..3).map(|i| c.target[i] - c.position[i]).collect();
        let len2: f32 = view.iter().map(|v| v * v).sum();
        if len2 < 1e-12 {
            return Err(ParamError::new(
                p("camera.target"),
                "must differ from camera.position",
            ));
        }
        let cross = [
            view[1] * c.up[2] - view[2] * c.up[1],
            view[2] * c.up[0] - view[0] * c.up[2],
            view[0] * c.up[1] - view[1] * c.up[0],
        ];
        let up2: f32 = c.up.iter().map(|v| v * v).sum();
        if cross.iter().map(|v| v * v).sum::<f32>() < 1e-10 * len2 * up2 {
            return Err(ParamError::new(
                p("camera.up"),
                "must not be parallel to the view direction",
            ));
        }
        for (name, v) in [
            ("image.width", self.image.width),
            ("image.height", self.image.height),
        ] {
            if v == 0 || v > MAX_IMAGE_SIDE {
                return Err(ParamError::new(
                    p(name),
                    format!("must be an integer between 1 and {MAX_IMAGE_SIDE} (got {v})"),
                ));
            }
        }
        for (i, k) in self.medium.extinction.rgb().iter().enumerate() {
            check::range(
                &format!("{}[{i}]", p("medium.extinction")),
                *k as f64,
                0.0,
                1e6,
            )?;
        }
        check::colour(&p("medium.albedo"), self.medium.albedo, 1.0)?;
        if let Phase::HenyeyGreenstein { g } = self.medium.phase {
            if !(g.is_finite() && g > -1.0 && g < 1.0) {
                return Err(ParamError::new(
                    p("medium.phase.g"),
                    format!("must be strictly between -1 and 1 (got {g})"),
                ));
            }
        }
        for (i, light) in self.lights.iter().enumerate() {
            let lp = p(&format!("lights[{i}]"));
            match light {
                Light::Point { position, color } => {
                    check::vector(&format!("{lp}.position"), *position, MAX_COORD)?;
                    check::colour(&format!("{lp}.color"), *color, 1e6)?;
                }
                Light::Directional { direction, color } => {
                    check::direction(&format!("{lp}.direction"), *direction)?;
                    check::colour(&format!("{lp}.color"), *color, 1e6)?;
                }
            }
        }
        check::colour(&p("background"), self.background, 1e6)?;
        for (i, object) in self.objects.iter().enumerate() {
            let op = p(&format!("objects[{i}]"));
            match object {
                Object::Sphere {
                    center,
                    radius,
                    color,
                } => {
                    check::vector(&format!("{op}.center"), *center, MAX_COORD)?;
                    check::positive(&format!("{op}.radius"), *radius as f64, MAX_COORD)?;
                    check::colour(&format!("{op}.color"), *color, 1.0)?;
                }
                Object::Plane {
                    point,
                    normal,
                    color,
                } => {
                    check::vector(&format!("{op}.point"), *point, MAX_COORD)?;
                    check::direction(&format!("{op}.normal"), *normal)?;
                    check::colour(&format!("{op}.color"), *color, 1.0)?;
                }
                Object::Cylinder {
                    base,
                    axis,
                    radius,
                    height,
                    color,
                    ..
                } => {
                    check::vector(&format!("{op}.base"), *base, MAX_COORD)?;
                    check::direction(&format!("{op}.axis"), *axis)?;
                    check::positive(&format!("{op}.radius"), *radius as f64, MAX_COORD)?;
                    check::positive(&format!("{op}.height"), *height as f64, MAX_COORD)?;
                    check::colour(&format!("{op}.color"), *color, 1.0)?;
                }
            }
        }
        Ok(())
    }
}

impl Default for BlobList {
    /// The default render settings and no blobs.
    fn default() -> Self {
        Self::new(RenderSettings::default(), Vec::new())
    }
}

impl BlobList {
    /// A blob list of `settings` and `blobs`.
    pub fn new(settings: RenderSettings, blobs: Vec<BlobRecord>) -> Self {
        let RenderSettings {
            camera,
            image,
            medium,
            lights,
            shadows,
            background,
            objects,
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
        }
    }

    /// Parses and validates a blob list from a JSON value; errors name the JSON path.
    pub fn from_value(value: serde_json::Value) -> Result<Self, ParamError> {
        let list: BlobList = serde_path_to_error::deserialize(value).map_err(|e| {
            let path = e.path().to_string();
            let path = if path == "." {
                "blob_list".to_string()
            } else {
                path
            };
            ParamError::new(path, e.inner().to_string())
        })?;
        list.validate()?;
        Ok(list)
    }

    /// Checks the settings and every blob; paths are those of the blob list's JSON.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.settings().validate("")?;
        for (i, b) in self.blobs.iter().enumerate() {
            let bp = format!("blobs[{i}]");
            check::vector(&format!("{bp}.center"), b.center, MAX_COORD)?;
            check::positive(&format!("{bp}.sigma"), b.sigma as f64, MAX_COORD)?;
            check::range(&format!("{bp}.mass"), b.mass as f64, 0.0, 1e12)?;
            if let Some(a) = b.albedo {
                check::colour(&format!("{bp}.albedo"), a, 1.0)?;
            }
            if let Some(q) = b.emission {
                check::colour(&format!("{bp}.emission"), q, 1e6)?;
            }
        }
        Ok(())
    }
}
