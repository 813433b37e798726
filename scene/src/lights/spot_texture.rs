//! A texture a spot light projects: Mitsuba 3's `spot` with a `texture`
//! (src/emitters/spot.cpp), whose intensity in a direction is multiplied by the texture
//! where the direction pierces the image plane at distance 1 along the axis, the cone of
//! the cutoff angle filling [0, 1]^2: uv = 1/2 + 1/2 (x, y) / (z tan(cutoff)) in the
//! light's frame (`direction_to_uv`).
//!
//! The same projection through a rectangular frustum is Mitsuba 3's `projector`
//! (src/emitters/projector.cpp): its image lies on the plane z = 1 where the perspective
//! camera's film would (`perspective_projection` in include/mitsuba/render/sensor.h),
//! uv = 1/2 - 1/2 (x / tan_x, y / tan_y) / z with tan_x, tan_y the tangents of the half
//! fields of view, and no light leaves outside [0, 1]^2 or behind the light.

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
    /// A projector's frustum: the tangents of its half fields of view along x and y
    /// (None: a spot's cone).
    frustum: Option<Vec2>,
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
            frustum: None,
            texture,
        })
    }

    /// `texture` projected by Mitsuba's `projector` whose frame is `to_world` (+z the
    /// axis) through a frustum whose half fields of view have tangents `tan_half` (x, y).
    /// Errors for a frame that cannot be inverted or tangents not positive and finite.
    pub fn frustum(to_world: Mat3, tan_half: Vec2, texture: SceneSpectrum) -> Result<Self, String> {
        let to_local = to_world.inverse();
        if !(to_local.is_finite() && tan_half.is_finite() && tan_half.min_element() > 0.0) {
            return Err(format!(
                "a projector needs an invertible frame and a field of view in (0, 180) \
                 degrees, not tangents {tan_half}"
            ));
        }
        Ok(Self {
            to_local,
            uv_factor: tan_half.length(),
            frustum: Some(tan_half),
            texture,
        })
    }

    /// tan of the angle from the axis that holds every direction the texture lights: a
    /// spot's cutoff, a projector's frustum corner.
    pub fn tan_extent(&self) -> f32 {
        self.uv_factor
    }

    /// The texture's coordinates in unit world direction `w` from the light.
    pub fn uv(&self, w: Vec3) -> Vec2 {
        let l = self.to_local * w;
        if let Some(tan_half) = self.frustum {
            return Vec2::splat(0.5) - Vec2::new(l.x, l.y) / (2.0 * l.z * tan_half);
        }
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
        let inside = self.frustum.is_none()
            || ((self.to_local * w).z > 0.0
                && uv.cmpge(Vec2::ZERO).all()
                && uv.cmple(Vec2::ONE).all());
        if uv.is_finite() && inside {
            self.texture.at_uv(uv, wavelengths)
        } else {
            SampledSpectrum::splat(0.0)
        }
    }
}
