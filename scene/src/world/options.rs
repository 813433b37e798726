//! Choices made when turning a loaded file into a scene.

use crate::geometry::BvhQuality;
use crate::lights::Environment;

/// Choices made when turning a loaded file into a scene: start from the default and set
/// what you need (`#[non_exhaustive]`: options can be added without breaking callers).
#[derive(Debug, Clone, Default)]
#[non_exhaustive]
pub struct SceneOptions {
    /// The camera by name (default: the first, else one framing the scene).
    pub camera: Option<String>,
    /// An environment replacing the file's own (`PRISM_spectral` on the root), if any.
    pub environment: Option<Environment>,
    /// BVH build effort.
    pub quality: BvhQuality,
}

impl SceneOptions {
    /// With [`SceneOptions::camera`] set.
    pub fn camera(mut self, camera: Option<String>) -> Self {
        self.camera = camera;
        self
    }

    /// With [`SceneOptions::environment`] set.
    pub fn environment(mut self, environment: Option<Environment>) -> Self {
        self.environment = environment;
        self
    }

    /// With [`SceneOptions::quality`] set.
    pub fn quality(mut self, quality: BvhQuality) -> Self {
        self.quality = quality;
        self
    }
}
