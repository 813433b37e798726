//! `KHR_materials_sheen` as a material describes it.

use std::sync::Arc;

use prism_spectrum::SampledWavelengths;

use crate::bsdf::Sheen;
use crate::textures::{RgbTexture, SceneSpectrum, TexCoords};

/// A sheen: its colour and roughness.
#[derive(Debug, Clone)]
pub struct SheenDesc {
    /// `sheenColorFactor` times `sheenColorTexture`, as a reflectance spectrum (or a
    /// `PRISM_spectral` measured one).
    pub color: SceneSpectrum,
    /// `sheenRoughnessFactor` (default 0).
    pub roughness: f32,
    /// `sheenRoughnessTexture`'s alpha channel times the factor, in every channel.
    pub roughness_texture: Option<Arc<RgbTexture>>,
}

impl SheenDesc {
    /// At texture coordinates `at`, for a path at `wavelengths`.
    pub fn at<const N: usize>(
        &self,
        at: &TexCoords,
        wavelengths: &SampledWavelengths<N>,
    ) -> Sheen<N> {
        let roughness = match &self.roughness_texture {
            Some(t) => t.sample_at(at)[0],
            None => self.roughness,
        };
        Sheen::new(self.color.at_uv(*at, wavelengths), roughness)
    }

    /// Whether a texture varies it.
    pub fn textured(&self) -> bool {
        self.roughness_texture.is_some() || matches!(self.color, SceneSpectrum::Texture(_))
    }
}
