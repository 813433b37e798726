//! A texture a spot light projects: Mitsuba 3's `spot` with a `texture`
//! (src/emitters/spot.cpp), whose intensity in a direction is multiplied by the texture
//! where the direction pierces the image plane at distance 1 along the axis, the cone of
//! the cutoff angle filling [0, 1]^2: uv = 1/2 + 1/2 (x, y) / (z tan(cutoff)) in the
//! light's frame (`direction_to_uv`).

use glam::{Mat3, Vec2, Vec3};
use prism_spectrum::{SampledSpectrum, SampledWavelengths};

use crate::textures::SceneSpectrum;

/// A spot light's projected texture.
#[derive(Debug, Clone)]
pub struct SpotTexture {
    /// World directions to the light's frame (its axis +z).
    to_local: Mat3,
    /// tan of the cutoff angle.
    uv_factor: f32,
    texture: SceneSpectrum,
}

impl SpotTexture {
    /// `texture` projected by a light whose frame is `to_world` (the linear part of its
    /// transform: +z the axis) with cutoff angle `cutoff` (radians). Errors for a frame
    /// that cannot be inverted or a cutoff whose tangent is not positive and finite.
    pub fn new(to_world: Mat3, cutoff: f32, texture: SceneSpectrum) -> Result<Self, String> {
        let to_local = to_world.inverse();
        let uv_factor = cutoff.tan();
        if !(to_local.is_finite() && uv_factor.is_finite() && uv_factor > 0.0) {
            return Err(format!(
                "a projected texture needs an invertible frame and a cutoff angle in (0, 90) \
                 degrees, not {}",
                cutoff.to_degrees()
            ));
        }
        Ok(Self {
            to_local,
            uv_factor,
            texture,
        })
    }

    /// The texture's coordinates in unit world direction `w` from the light.
    pub fn uv(&self, w: Vec3) -> Vec2 {
        let l = self.to_local * w;
        let scale = 0.5 / (l.z * self.uv_factor);
        Vec2::new(0.5 + l.x * scale, 0.5 + l.y * scale)
    }

    /// The factor on the light's intensity in unit world direction `w` from the light (0
    /// where it has no coordinates).
    pub fn at<const N: usize>(
        &self,
        w: Vec3,
        wavelengths: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let uv = self.uv(w);
        if uv.is_finite() {
            self.texture.at_uv(uv, wavelengths)
        } else {
            SampledSpectrum::splat(0.0)
        }
    }
}
