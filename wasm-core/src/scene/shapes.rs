//! Initial blob sets (paper §6, "3-D morphing") as a scene writes them: point sets sampled
//! from simple solids, each point the centre of a blob born at time 0, optionally played in
//! reverse (the morph of one shape into another). The sampling is [`crate::gas`]'s.

use crate::scene::limits::{
    MAX_ALBEDO, MAX_COORD, MAX_EMISSION, MAX_MASS0, MAX_SHAPE_BLOBS, MAX_SIGMA0,
};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The solid a set's points are drawn from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Solid {
    /// A ball of `radius`.
    Sphere,
    /// A ring of major radius `radius` and tube radius `thickness`, about `axis`.
    Torus,
    /// A trefoil knot of scale `radius` and tube radius `thickness`, about `axis`.
    Trefoil,
    /// A cube of half-side `radius`.
    Cube,
    /// The listed `points`, offset by `center`.
    Points,
}

/// One initial blob set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Shape {
    pub shape: Solid,
    #[schemars(inner(range(min = -MAX_COORD, max = MAX_COORD)))]
    pub center: [f32; 3],
    /// Axis of the torus and the trefoil (need not be unit length).
    #[schemars(inner(range(min = -1e6, max = 1e6)))]
    pub axis: [f32; 3],
    /// Size (m): ball radius, torus major radius, trefoil scale, cube half-side.
    #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
    pub radius: f32,
    /// Tube radius of the torus and the trefoil (m).
    #[schemars(range(max = MAX_COORD), extend("exclusiveMinimum" = 0))]
    pub thickness: f32,
    /// Number of blobs (ignored for `points`).
    #[schemars(range(min = 1, max = MAX_SHAPE_BLOBS))]
    #[serde(deserialize_with = "crate::whole::number")]
    pub count: usize,
    /// Blob centres relative to `center`, for `points`.
    #[schemars(length(max = MAX_SHAPE_BLOBS), inner(inner(range(min = -MAX_COORD, max = MAX_COORD))))]
    pub points: Vec<[f32; 3]>,
    /// σ0 (m) and m0 of every blob.
    #[schemars(range(max = MAX_SIGMA0), extend("exclusiveMinimum" = 0))]
    pub sigma0: f32,
    #[schemars(range(max = MAX_MASS0), extend("exclusiveMinimum" = 0))]
    pub mass0: f32,
    /// Albedo colour; none uses the medium's. Zero lights the set by its emission alone.
    #[schemars(inner(range(min = 0, max = MAX_ALBEDO)))]
    pub albedo: Option<[f32; 3]>,
    /// Self-emission colour Q.
    #[schemars(inner(range(min = 0, max = MAX_EMISSION)))]
    pub emission: Option<[f32; 3]>,
    /// Play this set backwards from this time (s): at time t it shows its forward state at
    /// max(reverse_from − t, 0).
    #[schemars(range(max = 1e4), extend("exclusiveMinimum" = 0))]
    pub reverse_from: Option<f64>,
}

impl Default for Shape {
    fn default() -> Self {
        Self {
            shape: Solid::Sphere,
            center: [0.0; 3],
            axis: [0.0, 1.0, 0.0],
            radius: 0.5,
            thickness: 0.15,
            count: 500,
            points: Vec::new(),
            sigma0: 0.04,
            mass0: 0.01,
            albedo: None,
            emission: None,
            reverse_from: None,
        }
    }
}

impl Shape {
    /// Number of blobs the set makes.
    pub fn blob_count(&self) -> usize {
        match self.shape {
            Solid::Points => self.points.len(),
            _ => self.count,
        }
    }
}
