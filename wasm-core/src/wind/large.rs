//! A large-scale wind primitive (paper Eq. 3's u_l) as the wind keeps it: a repulsor's path
//! resolved once.

use crate::scene::scene_format::Primitive;
use crate::wind::spline::Path;

/// A primitive with its path resolved.
#[derive(Debug, Clone)]
pub(super) struct Large {
    pub(super) primitive: Primitive,
    pub(super) path: Option<Path>,
}

impl Large {
    pub(super) fn new(primitive: Primitive) -> Self {
        let path = match &primitive {
            Primitive::Repulsor { path, .. } => Some(Path::new(path)),
            _ => None,
        };
        Self { primitive, path }
    }
}
