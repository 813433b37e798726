//! How wide a pixel is where a path meets a surface, for filtering textures.

use glam::Vec3;

/// A pixel's footprint at a point, as pbrt-v4 approximates it for every vertex of a path
/// (`Camera::Approximate_dp_dxy`): the width a camera ray's pixel cone would have there,
/// halved, since the pixel filter averages the samples too (pbrt-v4 narrows it by
/// max(1/8, 1/sqrt(spp)); a fixed factor keeps an image independent of how its samples
/// are split between passes and machines, and 1/2 is pbrt-v4's at 4 spp).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Footprint {
    /// The camera's position (perspective) or None (orthographic: the width is constant).
    pub origin: Option<Vec3>,
    /// Width per unit of distance from the camera (perspective), or the width itself.
    pub width: f32,
}

impl Footprint {
    /// For `camera` rendering `height` rows, seeing a vertical field of view `yfov` where
    /// its lens system sets it instead of its projection.
    pub(crate) fn new(
        camera: &prism_scene::camera::Camera,
        yfov: Option<f32>,
        height: u32,
    ) -> Self {
        let narrowing = 0.5;
        let rows = height.max(1) as f32;
        match camera.projection {
            prism_scene::camera::Projection::Perspective { yfov: own } => Self {
                origin: Some(camera.to_world.transform_point3(Vec3::ZERO)),
                width: 2.0 * (0.5 * yfov.unwrap_or(own)).tan() / rows * narrowing,
            },
            prism_scene::camera::Projection::Orthographic { ymag, .. } => Self {
                origin: None,
                width: 2.0 * ymag / rows * narrowing,
            },
        }
    }

    /// The footprint's width at `p`.
    pub(crate) fn at(&self, p: Vec3) -> f32 {
        match self.origin {
            Some(o) => self.width * (p - o).length(),
            None => self.width,
        }
    }
}
