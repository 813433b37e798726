//! `KHR_materials_anisotropy` as a material describes it.

use std::sync::Arc;

use glam::{Vec2, Vec3};

use crate::textures::{RgbTexture, TexCoords};

use super::SurfaceFrame;

/// The base's anisotropy: strength and direction in the tangent frame.
#[derive(Debug, Clone)]
pub struct AnisotropyDesc {
    /// `anisotropyStrength`, in [0, 1].
    pub strength: f32,
    /// `anisotropyRotation`, radians counter-clockwise from the tangent.
    pub rotation: f32,
    /// `anisotropyTexture` (linear): red and green the direction in the tangent frame
    /// encoded as (d + 1) / 2, blue multiplying the strength.
    pub texture: Option<Arc<RgbTexture>>,
}

impl AnisotropyDesc {
    /// The strength and the direction in the local frame's xy plane at texture
    /// coordinates `at`; None without a usable tangent (the surface is then isotropic:
    /// the extension has no direction without one).
    pub fn at(&self, at: &TexCoords, frame: &SurfaceFrame) -> Option<(f32, Vec2)> {
        let (direction, strength) = match &self.texture {
            Some(t) => {
                let [r, g, b] = t.sample_at(at);
                (Vec2::new(2.0 * r - 1.0, 2.0 * g - 1.0), self.strength * b)
            }
            None => (Vec2::X, self.strength),
        };
        let direction = Vec2::from_angle(self.rotation).rotate(direction);
        let (t, b) = frame.tangents()?;
        let world: Vec3 = direction.x * t + direction.y * b;
        let local = frame.frame.to_local(world);
        Some((strength, Vec2::new(local.x, local.y).try_normalize()?))
    }

    /// Whether a texture varies it.
    pub fn textured(&self) -> bool {
        self.texture.is_some()
    }
}
